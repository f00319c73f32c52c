// bedlam run SCENE — and the option parsing shared by scene commands.
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app/app.h"
#include "render/context.h"
#include "run/run.h"

static int parse_number(const char *opt, const char *text, double lo, double *out)
{
    char *end;
    double v = strtod(text, &end);
    if (end == text || *end != '\0' || !(v >= lo)) {
        fprintf(stderr, "error: %s %s: expected a number >= %g\n", opt, text, lo);
        return 0;
    }
    *out = v;
    return 1;
}

int bdl_parse_scene_opts(int argc, char **argv, const char *usage, bdl_scene_opts *opts)
{
    memset(opts, 0, sizeof *opts);
    opts->until = -1.0;
    for (int k = 1; k < argc; ++k) {
        const char *a = argv[k];
        const char *next = k + 1 < argc ? argv[k + 1] : NULL;
        if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
            fputs(usage, stdout);
            return -1;
        }
        int takes_value = strcmp(a, "--set") == 0 || strcmp(a, "--out") == 0 ||
                          strcmp(a, "--until") == 0 || strcmp(a, "--threads") == 0 ||
                          strcmp(a, "--resume") == 0 || strcmp(a, "--steps") == 0 ||
                          strcmp(a, "--gl") == 0 || strcmp(a, "--size") == 0 ||
                          strcmp(a, "--script") == 0;
        if (takes_value && !next) {
            fprintf(stderr, "error: %s needs a value\n\n%s", a, usage);
            return 2;
        }
        if (strcmp(a, "--set") == 0) {
            if (!strchr(next, '=') || opts->override_count >= 256) {
                fprintf(stderr, "error: --set %s: expected section.key=value\n", next);
                return 2;
            }
            opts->overrides[opts->override_count++] = next;
            ++k;
        } else if (strcmp(a, "--out") == 0) {
            opts->out = next;
            ++k;
        } else if (strcmp(a, "--resume") == 0) {
            opts->resume = next;
            ++k;
        } else if (strcmp(a, "--until") == 0) {
            if (!parse_number(a, next, 1e-300, &opts->until))
                return 2;
            ++k;
        } else if (strcmp(a, "--steps") == 0) {
            double st;
            if (!parse_number(a, next, 1, &st) || st != (long)st) {
                fprintf(stderr, "error: --steps %s: expected a whole number >= 1\n", next);
                return 2;
            }
            opts->steps = (long)st;
            ++k;
        } else if (strcmp(a, "--threads") == 0) {
            double t;
            if (!parse_number(a, next, 1, &t) || t > 256 || t != (int)t) {
                fprintf(stderr, "error: --threads %s: expected a whole number from 1 to 256\n",
                        next);
                return 2;
            }
            opts->threads = (int)t;
            ++k;
        } else if (strcmp(a, "--gl") == 0) {
            bdl_gl_backend b;
            if (!bdl_gl_backend_parse(next, &b)) {
                fprintf(stderr, "error: --gl %s: expected auto, sdl, egl or osmesa\n", next);
                return 2;
            }
            opts->gl_backend = (int)b;
            ++k;
        } else if (strcmp(a, "--size") == 0) {
            int w = 0, h = 0;
            char tail;
            if (sscanf(next, "%dx%d%c", &w, &h, &tail) != 2 || w < 16 || h < 16 || w > 8192 ||
                h > 8192) {
                fprintf(stderr, "error: --size %s: expected WIDTHxHEIGHT, 16 to 8192 pixels\n",
                        next);
                return 2;
            }
            opts->width = w;
            opts->height = h;
            ++k;
        } else if (strcmp(a, "--script") == 0) {
            opts->script = next;
            ++k;
        } else if (strcmp(a, "--paused") == 0) {
            opts->paused = 1;
        } else if (strcmp(a, "--quiet") == 0 || strcmp(a, "-q") == 0) {
            opts->quiet = 1;
        } else if (a[0] == '-' && a[1] != '\0') {
            fprintf(stderr, "error: unknown option '%s'\n\n%s", a, usage);
            return 2;
        } else if (!opts->scene) {
            opts->scene = a;
        } else {
            fprintf(stderr, "error: unexpected argument '%s' (one scene only)\n\n%s", a, usage);
            return 2;
        }
    }
    if (!opts->scene) {
        fprintf(stderr, "error: no scene file given\n\n%s", usage);
        return 2;
    }
    return 0;
}

static const char run_usage[] =
    "usage: bedlam run SCENE [options]\n"
    "\n"
    "Runs SCENE headless to its [run] end_time and writes one output folder:\n"
    "  run.log, diagnostics.csv, particles.pvd + vtk/*.vtp, checkpoint/state.bdlckpt,\n"
    "  and frames/frame_NNNNNN.png when [output] frame_interval asks for frames\n"
    "\n"
    "options:\n"
    "  --set SECTION.KEY=VALUE   override a scene key (named sections: "
    "species.glass.density=2500)\n"
    "  --out DIR                 output folder (default runs/<scene name>)\n"
    "  --until T                 stop at simulated time T [s] instead of end_time\n"
    "  --steps N                 stop after N steps (smoke tests)\n"
    "  --threads N               solver threads (default: [run] threads, 0 = all cores)\n"
    "  --resume PATH             continue bit-for-bit from a checkpoint file or a run folder\n"
    "  --gl BACKEND              frames: auto (EGL, then OSMesa), egl or osmesa\n"
    "  --quiet                   no progress line\n"
    "\n"
    "Ctrl-C stops cleanly: the diagnostics are flushed and a checkpoint is written.\n"
    "Exit codes: 0 done, 1 instability or interrupted, 2 bad scene or options.\n";

int bdl_cmd_run(int argc, char **argv)
{
    bdl_scene_opts o;
    int rc = bdl_parse_scene_opts(argc, argv, run_usage, &o);
    if (rc != 0)
        return rc < 0 ? 0 : rc;
    bdl_run_def def = bdl_default_run_def();
    def.scene_path = o.scene;
    def.overrides = o.overrides;
    def.override_count = o.override_count;
    def.out_dir = o.out;
    def.until = o.until;
    def.max_steps = o.steps;
    def.threads = o.threads;
    def.resume = o.resume;
    def.progress = !o.quiet;
    def.gl_backend = o.gl_backend;
    if (o.gl_backend == BDL_GL_SDL) {
        fprintf(stderr, "error: --gl sdl: frames of a run are drawn headless (egl or osmesa)\n");
        return 2;
    }
    return bdl_run(&def);
}
