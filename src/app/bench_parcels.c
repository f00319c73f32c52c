// bedlam bench parcels — how fast a bubbling bed of parcels (MP-PIC) runs: parcel updates per
// second, the real particles they stand for, and simulated seconds per wall second, on each
// thread count, for a scene of parcels (by default scenes/parcels_bubbling_bed.ini: 6.3 million
// real particles of 500 um sand in 31 500 parcels, fluidized at 1.8 m/s).
//
// The bed is warmed up once (on all threads: bubbling has begun) and saved as a checkpoint; every
// thread count then starts from it and times the same window of the same run, so each does the
// same work, and the states at the end must agree bit for bit (the sums go in fixed chunks in a
// fixed order: docs/architecture.md). Timings are reported, never asserted.
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "app/app.h"
#include "app/options.h"
#include "core/timer.h"
#include "output/checkpoint.h"
#include "world/world.h"

static const char usage[] =
    "usage: bedlam bench parcels [SCENE] [options]\n"
    "\n"
    "Times a scene of parcels (MP-PIC; default scenes/parcels_bubbling_bed.ini, a bubbling bed of\n"
    "6.3e6 real particles in 31 500 parcels) and reports parcel updates per second, the real\n"
    "particles they stand for, and simulated seconds per wall second (the ratio to real time),\n"
    "with the split between the gas and the parcels, for each thread count. The bed is warmed up\n"
    "once; every thread count times the same window from there (and must end in the same state).\n"
    "\n"
    "columns: parcel-upd/s (parcels x steps per wall second), particle-upd/s (the same in real\n"
    "particles), x real time (simulated per wall second), gas ms and parcels ms (wall time per\n"
    "step in the gas step and in the rest), held (parcels the packing guard held back per step)\n"
    "\n"
    "options:\n"
    "  --warmup T       simulated seconds run before timing (default 0.2: bubbling has begun)\n"
    "  --time T         simulated seconds timed (default 0.1)\n"
    "  --threads LIST   comma-separated thread counts (default 1,2)\n"
    "  --set SECTION.KEY=VALUE   override a scene key (as for run)\n";

typedef struct parcels_opts {
    const char *path;
    double warmup, time;
    int threads[16], thread_count;
    const char *overrides[64];
    int override_count;
} parcels_opts;

/// One timed window.
typedef struct window {
    double wall, sim, gas, parcels; ///< [s]
    long steps, count;              ///< steps taken, parcels at the end
    double real;                    ///< real particles at the end
    long held;                      ///< parcels the packing guard held back in the window
    uint64_t hash;                  ///< the state at the end
} window;

static const bdl_option parcels_options[] = {
    {"--warmup", BDL_OPTION_NUMBER, offsetof(parcels_opts, warmup)},
    {"--time", BDL_OPTION_NUMBER, offsetof(parcels_opts, time)},
};

/// The scene (an argument that is not an option), --threads LIST and --set.
static int take_other(void *opts, int argc, char **argv, int i)
{
    parcels_opts *o = opts;
    if (argv[i][0] != '-') {
        o->path = argv[i];
        return 1;
    }
    if (i + 1 < argc && strcmp(argv[i], "--threads") == 0) {
        char buf[128];
        snprintf(buf, sizeof buf, "%s", argv[i + 1]);
        o->thread_count = 0;
        for (char *t = strtok(buf, ","); t && o->thread_count < 16; t = strtok(NULL, ","))
            o->threads[o->thread_count++] = atoi(t);
        return 2;
    }
    if (i + 1 < argc && strcmp(argv[i], "--set") == 0 && o->override_count < 64) {
        o->overrides[o->override_count++] = argv[i + 1];
        return 2;
    }
    fprintf(stderr, "error: bench parcels: bad option '%s'\n\n%s", argv[i], usage);
    return 0;
}

static bdl_result parse(int argc, char **argv, parcels_opts *o, int *help)
{
    static const bdl_option_parser parser = {parcels_options, BDL_OPTION_COUNT(parcels_options),
                                             usage, 0, take_other};
    bdl_result r = bdl_option_parse(&parser, argc, argv, 1, o, help);
    if (r != BDL_OK || *help)
        return r;
    int bad = o->thread_count < 1;
    for (int t = 0; t < o->thread_count; ++t)
        bad |= o->threads[t] < 1;
    if (bad || !(o->warmup >= 0.0) || !(o->time > 0.0)) {
        fprintf(stderr, "error: bench parcels: --warmup >= 0, --time > 0, --threads >= 1\n");
        return BDL_ERR_ARGS;
    }
    return BDL_OK;
}

/// Steps until the simulated time reaches `until`; prints the failure.
static bdl_result run_until(bdl_world *w, double until)
{
    while (w->time < until - 0.5 * w->dt)
        if (bdl_world_step(w) != BDL_OK) {
            fprintf(stderr, "error: %s\n", w->failure);
            return BDL_ERR_UNSTABLE;
        }
    return BDL_OK;
}

static double real_particles(const bdl_world *w)
{
    double n = 0.0;
    for (long i = 0; i < w->particles.count; ++i)
        n += w->particles.parcel_count[i];
    return n;
}

/// Times `span` simulated seconds from the checkpoint at `start` on `threads` threads.
static bdl_result time_window(bdl_world *w, const char *start, int threads, double span,
                              window *out)
{
    char why[1024];
    if (bdl_checkpoint_load(w, start, NULL, why, sizeof why) != BDL_OK) {
        fprintf(stderr, "error: %s\n", why);
        return BDL_ERR_CHECKPOINT;
    }
    omp_set_num_threads(threads);
    w->gas_seconds = w->coupling_seconds = 0.0;
    const long step0 = w->step, held0 = w->parcels_held;
    const double t0 = bdl_wall_seconds(), sim0 = w->time;
    const bdl_result r = run_until(w, sim0 + span);
    *out = (window){.wall = bdl_wall_seconds() - t0,
                    .sim = w->time - sim0,
                    .gas = w->gas_seconds,
                    .parcels = w->coupling_seconds,
                    .steps = w->step - step0,
                    .count = w->particles.count,
                    .real = real_particles(w),
                    .held = w->parcels_held - held0,
                    .hash = bdl_world_hash(w)};
    return r;
}

static void report(const window *t, int threads, const window *first, int first_threads)
{
    const double updates = (double)t->count * (double)t->steps / t->wall;
    printf("%7d %14.4g %14.4g %12.4g %10.3f %10.3f %10.3g\n", threads, updates,
           updates * t->real / (double)t->count, t->sim / t->wall, 1e3 * t->gas / (double)t->steps,
           1e3 * (t->wall - t->gas) / (double)t->steps, (double)t->held / (double)t->steps);
    if (first != t)
        printf("  speed-up %d vs %d threads: %.2fx; the state after the window %s\n", threads,
               first_threads, first->wall / t->wall,
               t->hash == first->hash ? "is the same bit for bit" : "DIFFERS (not deterministic)");
}

/// Builds and warms up the bed, saves it at `start`, and prints what it is.
static bdl_result warm_up(const parcels_opts *o, const char *start, bdl_world **out)
{
    bdl_world *w = NULL;
    bdl_result r = bdl_load_world(o->path, o->overrides, o->override_count, &w);
    if (r != BDL_OK)
        return r;
    *out = w;
    if (!w->parcels) {
        fprintf(stderr,
                "error: %s has no parcels (a species with parcel_particles or "
                "parcel_volume)\n",
                o->path);
        return BDL_ERR_SCENE;
    }
    const double t0 = bdl_wall_seconds();
    omp_set_num_threads(omp_get_num_procs());
    if ((r = run_until(w, o->warmup)) != BDL_OK)
        return r;
    if (bdl_checkpoint_save(w, start) != BDL_OK) {
        fprintf(stderr, "error: cannot save the warmed-up bed to %s\n", start);
        return BDL_ERR_IO;
    }
    const bdl_grid *g = &w->gas->grid;
    printf("bedlam bench parcels: %s, %ld parcels standing for %.4g real particles, %d x %d x %d "
           "gas cells, dt %g s\n",
           o->path, w->particles.count, real_particles(w), g->n[0], g->n[1], g->n[2], w->dt);
    printf("warmed up to t = %g s in %.1f s wall; timing %g s of simulated time (%.0f steps) "
           "from there on each thread count\n",
           w->time, bdl_wall_seconds() - t0, o->time, o->time / w->dt);
    return BDL_OK;
}

bdl_result bdl_bench_parcels(int argc, char **argv)
{
    parcels_opts o = {.path = "scenes/parcels_bubbling_bed.ini",
                      .warmup = 0.2,
                      .time = 0.1,
                      .threads = {1, 2},
                      .thread_count = 2};
    int help;
    bdl_result r = parse(argc, argv, &o, &help);
    if (r != BDL_OK || help)
        return r;
    const char *tmp = getenv("TMPDIR");
    char start[1024];
    snprintf(start, sizeof start, "%s/bedlam-bench-parcels-%ld.bdlckpt",
             tmp && tmp[0] ? tmp : "/tmp", (long)getpid());
    bdl_world *w = NULL;
    if ((r = warm_up(&o, start, &w)) == BDL_OK) {
        printf("%7s %14s %14s %12s %10s %10s %10s\n", "threads", "parcel-upd/s", "particle-upd/s",
               "x real time", "gas ms", "parcels ms", "held");
        window first = {0}, now;
        for (int t = 0; t < o.thread_count && r == BDL_OK; ++t) {
            r = time_window(w, start, o.threads[t], o.time, t == 0 ? &first : &now);
            if (r == BDL_OK)
                report(t == 0 ? &first : &now, o.threads[t], &first, o.threads[0]);
        }
    }
    remove(start);
    bdl_world_destroy(w);
    return r;
}
