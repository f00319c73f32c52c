// bedlam bench coupled — where the time of a CFD-DEM step goes: the gas, the coupling (voidage,
// drag set-up, forces), and the particles (everything else), per gas step, for a scene with [gas]
// (by default scenes/fluidized_bed.ini). Timings are reported, never asserted.
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app/app.h"
#include "app/options.h"
#include "cfd/gas.h"
#include "core/timer.h"
#include "world/world.h"

static const char usage[] =
    "usage: bedlam bench coupled [SCENE] [options]\n"
    "\n"
    "Times a CFD-DEM scene (default scenes/fluidized_bed.ini) and splits each gas step's wall "
    "time\n"
    "into the gas solver, the coupling (voidage, drag set-up, forces on the particles) and the\n"
    "particle steps in between. Each repetition runs the same window of the same run from the\n"
    "start; the fastest is reported, with the median of the wall times.\n"
    "\n"
    "options:\n"
    "  --warmup T    simulated seconds run before timing (default 0.5: the bed is fluidized)\n"
    "  --time T      simulated seconds timed (default 0.5)\n"
    "  --repeat R    repetitions (default 1)\n"
    "  --threads N   threads (default: all cores)\n";

/// One timed window.
typedef struct timing {
    double wall, sim, gas, coupling;
    long steps, gas_steps, particles;
    int iterations;
    double residual;
    int cells[3];
} timing;

/// Builds the world, runs the warm-up, times the window; what stopped it otherwise (printed).
static bdl_result time_window(const char *path, double warmup, double timed, timing *t)
{
    bdl_world *w = NULL;
    bdl_result code = bdl_load_world(path, NULL, 0, &w);
    if (code != BDL_OK)
        return code;
    if (!w->gas) {
        fprintf(stderr, "error: %s has no [gas] section\n", path);
        code = BDL_ERR_SCENE;
    }
    while (code == BDL_OK && w->time < warmup)
        if ((code = bdl_world_step(w)) != BDL_OK)
            fprintf(stderr, "error: the scene failed during the warm-up: %s\n", w->failure);
    if (code == BDL_OK) {
        w->gas_seconds = w->coupling_seconds = 0.0;
        long steps0 = w->step, gas0 = w->gas_steps;
        double t0 = bdl_wall_seconds(), sim0 = w->time;
        while (w->time < sim0 + timed)
            if (bdl_world_step(w) != BDL_OK) {
                fprintf(stderr, "error: %s\n", w->failure);
                break;
            }
        t->wall = bdl_wall_seconds() - t0;
        t->sim = w->time - sim0;
        t->steps = w->step - steps0;
        t->gas_steps = w->gas_steps - gas0;
        t->gas = w->gas_seconds;
        t->coupling = w->coupling_seconds;
        t->particles = w->particles.count;
        t->iterations = w->gas->last_solve.iterations;
        t->residual = w->gas->last_solve.residual;
        memcpy(t->cells, w->gas->grid.n, sizeof t->cells);
    }
    bdl_world_destroy(w);
    return code;
}

static int compare_wall(const void *a, const void *b)
{
    double x = ((const timing *)a)->wall, y = ((const timing *)b)->wall;
    return (x > y) - (x < y);
}

typedef struct coupled_opts {
    const char *path;
    double warmup, time;
    int threads, repeat;
} coupled_opts;

static const bdl_option coupled_options[] = {
    {"--warmup", BDL_OPTION_NUMBER, offsetof(coupled_opts, warmup)},
    {"--time", BDL_OPTION_NUMBER, offsetof(coupled_opts, time)},
    {"--repeat", BDL_OPTION_INT, offsetof(coupled_opts, repeat)},
    {"--threads", BDL_OPTION_INT, offsetof(coupled_opts, threads)},
};

/// The scene: any argument that is not an option.
static int take_scene(void *opts, int argc, char **argv, int i)
{
    (void)argc;
    if (argv[i][0] != '-') {
        ((coupled_opts *)opts)->path = argv[i];
        return 1;
    }
    fprintf(stderr, "error: bench coupled: bad option '%s'\n\n%s", argv[i], usage);
    return 0;
}

/// Reads the options into *o; *help when --help was printed.
static bdl_result parse_coupled(int argc, char **argv, coupled_opts *o, int *help)
{
    static const bdl_option_parser parser = {coupled_options, BDL_OPTION_COUNT(coupled_options),
                                             usage, 0, take_scene};
    bdl_result r = bdl_option_parse(&parser, argc, argv, 1, o, help);
    if (r != BDL_OK || *help)
        return r;
    if (!(o->warmup >= 0.0) || !(o->time > 0.0) || o->threads < 0 || o->repeat < 1 ||
        o->repeat > 100) {
        fprintf(stderr, "error: bench coupled: --warmup >= 0, --time > 0, --repeat 1..100, "
                        "--threads >= 0\n");
        return BDL_ERR_ARGS;
    }
    return BDL_OK;
}

static void report(const char *path, const timing *runs, int repeat)
{
    const timing *t = &runs[0];
    const double median = runs[repeat / 2].wall;
    const double dem = t->wall - t->gas - t->coupling;
    printf("bedlam bench coupled: %s, %ld particles, %d x %d x %d cells, %d threads\n", path,
           t->particles, t->cells[0], t->cells[1], t->cells[2], omp_get_max_threads());
    printf("timed %.3g s of simulated time: %ld particle steps, %ld gas steps (%.1f particle "
           "steps each), %.3g s wall = %.3g x real time, %.3g particle-steps/s",
           t->sim, t->steps, t->gas_steps, (double)t->steps / (double)t->gas_steps, t->wall,
           t->sim / t->wall, (double)t->steps * (double)t->particles / t->wall);
    if (repeat > 1)
        printf(" (fastest of %d; median %.3g s wall = %.3g x real time)", repeat, median,
               t->sim / median);
    printf("\nper gas step: gas %.3f ms (%.1f %%), coupling %.3f ms (%.1f %%), particles %.3f ms "
           "(%.1f %%); gas + coupling %.1f %% of the step\n",
           1e3 * t->gas / t->gas_steps, 100.0 * t->gas / t->wall, 1e3 * t->coupling / t->gas_steps,
           100.0 * t->coupling / t->wall, 1e3 * dem / t->gas_steps, 100.0 * dem / t->wall,
           100.0 * (t->gas + t->coupling) / t->wall);
    printf("pressure solver: %d iterations in the last gas step (relative residual %.2g)\n",
           t->iterations, t->residual);
}

bdl_result bdl_bench_coupled(int argc, char **argv)
{
    coupled_opts o = {"scenes/fluidized_bed.ini", 0.5, 0.5, 0, 1};
    int help;
    bdl_result code = parse_coupled(argc, argv, &o, &help);
    if (code != BDL_OK || help)
        return code;
    if (o.threads > 0)
        omp_set_num_threads(o.threads);
    timing runs[100];
    for (int r = 0; r < o.repeat; ++r)
        if ((code = time_window(o.path, o.warmup, o.time, &runs[r])) != BDL_OK)
            return code;
    qsort(runs, (size_t)o.repeat, sizeof runs[0], compare_wall);
    report(o.path, runs, o.repeat);
    return BDL_OK;
}
