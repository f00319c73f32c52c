// bedlam run SCENE — a run headless: the progress line, signals and the output folder around
// run/run.h.
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "app/app.h"
#include "core/comm.h"
#include "render/context.h"
#include "run/run.h"

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
    "Ctrl-C stops cleanly: the diagnostics are flushed and a checkpoint is written. A run\n"
    "killed outright resumes from its last checkpoint with every output up to it. After an\n"
    "instability the state goes to checkpoint/failed.bdlckpt, beside the last good one.\n"
    "Exit codes: 0 done, 1 instability, a file that could not be written, or interrupted,\n"
    "2 bad scene or options.\n";

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
    if (r == BDL_OK && !o.quiet && bdl_comm_rank() == 0) // under MPI the first rank speaks
        fprintf(stderr, "done: t = %g s, %ld steps in %.2f s; outputs in %s\n", report.time,
                report.step, report.wall_seconds, out);
    return r;
}
