// bedlam run SCENE — and the option parsing shared by scene commands.
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

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

bdl_result bdl_parse_scene_opts(int argc, char **argv, const char *usage, bdl_scene_opts *opts)
{
    memset(opts, 0, sizeof *opts);
    opts->until = -1.0;
    for (int k = 1; k < argc; ++k) {
        const char *a = argv[k];
        const char *next = k + 1 < argc ? argv[k + 1] : NULL;
        if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
            fputs(usage, stdout);
            opts->help = 1;
            return BDL_OK;
        }
        int takes_value = strcmp(a, "--set") == 0 || strcmp(a, "--out") == 0 ||
                          strcmp(a, "--until") == 0 || strcmp(a, "--threads") == 0 ||
                          strcmp(a, "--resume") == 0 || strcmp(a, "--steps") == 0 ||
                          strcmp(a, "--gl") == 0 || strcmp(a, "--size") == 0 ||
                          strcmp(a, "--script") == 0;
        if (takes_value && !next) {
            fprintf(stderr, "error: %s needs a value\n\n%s", a, usage);
            return BDL_ERR_ARGS;
        }
        if (strcmp(a, "--set") == 0) {
            if (!strchr(next, '=') || opts->override_count >= 256) {
                fprintf(stderr, "error: --set %s: expected section.key=value\n", next);
                return BDL_ERR_ARGS;
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
                return BDL_ERR_ARGS;
            ++k;
        } else if (strcmp(a, "--steps") == 0) {
            double st;
            if (!parse_number(a, next, 1, &st) || st != (long)st) {
                fprintf(stderr, "error: --steps %s: expected a whole number >= 1\n", next);
                return BDL_ERR_ARGS;
            }
            opts->steps = (long)st;
            ++k;
        } else if (strcmp(a, "--threads") == 0) {
            double t;
            if (!parse_number(a, next, 1, &t) || t > 256 || t != (int)t) {
                fprintf(stderr, "error: --threads %s: expected a whole number from 1 to 256\n",
                        next);
                return BDL_ERR_ARGS;
            }
            opts->threads = (int)t;
            ++k;
        } else if (strcmp(a, "--gl") == 0) {
            bdl_gl_backend b;
            if (!bdl_gl_backend_parse(next, &b)) {
                fprintf(stderr, "error: --gl %s: expected auto, sdl, egl or osmesa\n", next);
                return BDL_ERR_ARGS;
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
                return BDL_ERR_ARGS;
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
            return BDL_ERR_ARGS;
        } else if (!opts->scene) {
            opts->scene = a;
        } else {
            fprintf(stderr, "error: unexpected argument '%s' (one scene only)\n\n%s", a, usage);
            return BDL_ERR_ARGS;
        }
    }
    if (!opts->scene) {
        fprintf(stderr, "error: no scene file given\n\n%s", usage);
        return BDL_ERR_ARGS;
    }
    return BDL_OK;
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

/// The progress line on stderr: rewritten in place on a terminal every [output]
/// progress_interval, a line every ten intervals otherwise.
typedef struct progress_line {
    int tty, printed;
    double last_time, last_wall;
    long last_step;
} progress_line;

static void format_hms(double s, char *out, size_t len)
{
    if (!isfinite(s) || s < 0) {
        snprintf(out, len, "--:--:--");
        return;
    }
    long t = (long)(s + 0.5);
    snprintf(out, len, "%02ld:%02ld:%02ld", t / 3600, (t / 60) % 60, t % 60);
}

/// The run's own errors beside its speed: the energy balance (energy now, less the energy at the
/// start and the work put in by walls, gas and insertion: zero for elastic contacts, the
/// dissipated energy otherwise) and, with a gas, the pressure drop against the bed's weight, the
/// worst cell's gas volume imbalance and the interphase momentum imbalance.
static void error_summary(const bdl_run_status *s, char *out, size_t len)
{
    out[0] = 0;
    if (!s->measured)
        return;
    int k = snprintf(out, len, "  energy balance %.2e J (work in %.2e J)", s->energy_balance,
                     s->energy_in);
    if (s->gas && k > 0 && (size_t)k < len)
        k += snprintf(out + k, len - (size_t)k, "  dp/weight %.3f  gas volume %.1e  momentum %.1e",
                      s->weight_ratio, s->gas_volume_imbalance, s->momentum_imbalance);
    if (s->particles_out > 0 && k > 0 && (size_t)k < len) // through gas outlets: counted
        snprintf(out + k, len - (size_t)k, "  out %ld", s->particles_out);
}

static void print_progress(void *user, const bdl_run_status *s)
{
    progress_line *p = user;
    if (s->finished) {
        if (p->tty && p->printed)
            fputc('\n', stderr);
        return;
    }
    if (!p->printed && p->last_wall == 0.0) {
        p->last_time = s->start_time;
        p->last_step = s->start_step;
    }
    const double dw = s->wall_seconds - p->last_wall;
    if (!p->tty && dw < 10.0 * s->progress_interval)
        return;
    double rate = dw > 0 ? (double)(s->step - p->last_step) * (double)s->particles / dw : 0.0;
    double speed = dw > 0 ? (s->time - p->last_time) / dw : 0.0;
    double eta = s->time > s->start_time
                     ? (s->end_time - s->time) * s->wall_seconds / (s->time - s->start_time)
                     : NAN;
    char elapsed[16], left[16], errors[192];
    format_hms(s->wall_seconds, elapsed, sizeof elapsed);
    format_hms(eta, left, sizeof left);
    error_summary(s, errors, sizeof errors);
    fprintf(stderr,
            "%st = %.4g / %.4g s  step %ld  %ld particles  %.3g particle-steps/s  %.3gx real time  "
            "elapsed %s  ETA %s%s%s",
            p->tty ? "\r" : "", s->time, s->end_time, s->step, s->particles, rate, speed, elapsed,
            left, errors, p->tty ? "\033[K" : "\n");
    fflush(stderr);
    p->printed = 1;
    p->last_time = s->time;
    p->last_step = s->step;
    p->last_wall = s->wall_seconds;
}

static volatile sig_atomic_t stop_requested = 0;

static void on_signal(int sig)
{
    (void)sig;
    stop_requested = 1;
}

/// The output folder: --out, the run folder a --resume names, or runs/<scene file's stem>.
static void output_folder(const bdl_scene_opts *o, char *out, size_t len)
{
    char ckpt[1200];
    if (o->out) {
        snprintf(out, len, "%s", o->out);
    } else if (o->resume && bdl_run_checkpoint_path(o->resume, ckpt, sizeof ckpt)) {
        snprintf(out, len, "%s", o->resume);
    } else {
        const char *base = strrchr(o->scene, '/');
        char stem[256];
        snprintf(stem, sizeof stem, "%s", base ? base + 1 : o->scene);
        char *dot = strrchr(stem, '.');
        if (dot)
            *dot = '\0';
        snprintf(out, len, "runs/%s", stem);
    }
}

bdl_result bdl_cmd_run(int argc, char **argv)
{
    bdl_scene_opts o;
    bdl_result r = bdl_parse_scene_opts(argc, argv, run_usage, &o);
    if (r != BDL_OK || o.help)
        return r;
    if (o.gl_backend == BDL_GL_SDL) {
        fprintf(stderr, "error: --gl sdl: frames of a run are drawn headless (egl or osmesa)\n");
        return BDL_ERR_ARGS;
    }
    char out[1024];
    output_folder(&o, out, sizeof out);
    progress_line line = {.tty = isatty(STDERR_FILENO)};
    bdl_run_def def = bdl_default_run_def();
    def.scene_path = o.scene;
    def.overrides = o.overrides;
    def.override_count = o.override_count;
    def.out_dir = out;
    def.until = o.until;
    def.max_steps = o.steps;
    def.threads = o.threads;
    def.resume = o.resume;
    def.gl_backend = o.gl_backend;
    def.stop = &stop_requested;
    def.progress = o.quiet ? NULL : print_progress;
    def.user = &line;
    // Ctrl-C and a polite kill stop the run after the current step, with a checkpoint.
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_signal;
    sigaction(SIGINT, &sa, NULL);
    sigaction(SIGTERM, &sa, NULL);
    bdl_run_report report = {0};
    r = bdl_run(&def, &report);
    signal(SIGINT, SIG_DFL);
    signal(SIGTERM, SIG_DFL);
    if (r == BDL_OK && !o.quiet)
        fprintf(stderr, "done: t = %g s, %ld steps in %.2f s; outputs in %s\n", report.time,
                report.step, report.wall_seconds, out);
    return r;
}
