// bedlam bench coupled — where the time of a CFD-DEM step goes: the gas, the coupling (voidage,
// drag set-up, forces), and the particles (everything else), per gas step, for a scene with [gas]
// (by default scenes/fluidized_bed.ini). Timings are reported, never asserted.
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app/app.h"
#include "cfd/gas.h"
#include "core/timer.h"
#include "sim/world.h"

static const char usage[] =
    "usage: bedlam bench coupled [SCENE] [options]\n"
    "\n"
    "Times a CFD-DEM scene (default scenes/fluidized_bed.ini) and splits each gas step's wall "
    "time\n"
    "into the gas solver, the coupling (voidage, drag set-up, forces on the particles) and the\n"
    "particle steps in between.\n"
    "\n"
    "options:\n"
    "  --warmup T    simulated seconds run before timing (default 0.5: the bed is fluidized)\n"
    "  --time T      simulated seconds timed (default 0.5)\n"
    "  --threads N   threads (default: all cores)\n";

int bdl_bench_coupled(int argc, char **argv)
{
    const char *path = "scenes/fluidized_bed.ini";
    double warmup = 0.5, timed = 0.5;
    int threads = 0;
    for (int k = 1; k < argc; ++k) {
        const char *a = argv[k], *v = k + 1 < argc ? argv[k + 1] : NULL;
        if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
            fputs(usage, stdout);
            return 0;
        } else if (v && strcmp(a, "--warmup") == 0) {
            warmup = atof(v), ++k;
        } else if (v && strcmp(a, "--time") == 0) {
            timed = atof(v), ++k;
        } else if (v && strcmp(a, "--threads") == 0) {
            threads = atoi(v), ++k;
        } else if (a[0] != '-') {
            path = a;
        } else {
            fprintf(stderr, "error: bench coupled: bad option '%s'\n\n%s", a, usage);
            return 2;
        }
    }
    if (!(warmup >= 0.0) || !(timed > 0.0) || threads < 0) {
        fprintf(stderr, "error: bench coupled: --warmup >= 0, --time > 0, --threads >= 0\n");
        return 2;
    }
    if (threads > 0)
        omp_set_num_threads(threads);
    bdl_scene *scene = calloc(1, sizeof *scene);
    bdl_scene_error err;
    bdl_world *w = NULL;
    if (!scene || bdl_scene_load(path, NULL, 0, scene, &err) != BDL_OK ||
        bdl_world_create(scene, &w, &err) != BDL_OK) {
        fprintf(stderr, "error: %s\n", scene ? err.message : "out of memory");
        free(scene);
        return 2;
    }
    if (!w->gas) {
        fprintf(stderr, "error: %s has no [gas] section\n", path);
        bdl_world_destroy(w);
        free(scene);
        return 2;
    }
    while (w->time < warmup)
        if (bdl_world_step(w) != BDL_OK) {
            fprintf(stderr, "error: the scene failed during the warm-up at t = %g s\n", w->time);
            bdl_world_destroy(w);
            free(scene);
            return 1;
        }
    w->gas_seconds = w->coupling_seconds = 0.0;
    long steps0 = w->step, gas0 = w->gas_steps;
    double t0 = bdl_wall_seconds(), sim0 = w->time;
    while (w->time < sim0 + timed)
        if (bdl_world_step(w) != BDL_OK)
            break;
    double wall = bdl_wall_seconds() - t0, sim = w->time - sim0;
    long steps = w->step - steps0, gas_steps = w->gas_steps - gas0;
    double dem = wall - w->gas_seconds - w->coupling_seconds;
    const bdl_grid *g = &w->gas->grid;
    printf("bedlam bench coupled: %s, %ld particles, %d x %d x %d cells, %d threads\n", path,
           w->particles.count, g->n[0], g->n[1], g->n[2], omp_get_max_threads());
    printf("timed %.3g s of simulated time: %ld particle steps, %ld gas steps (%.1f particle "
           "steps each), %.3g s wall = %.3g x real time, %.3g particle-steps/s\n",
           sim, steps, gas_steps, (double)steps / (double)gas_steps, wall, sim / wall,
           (double)steps * (double)w->particles.count / wall);
    printf("per gas step: gas %.3f ms (%.1f %%), coupling %.3f ms (%.1f %%), particles %.3f ms "
           "(%.1f %%); gas + coupling %.1f %% of the step\n",
           1e3 * w->gas_seconds / gas_steps, 100.0 * w->gas_seconds / wall,
           1e3 * w->coupling_seconds / gas_steps, 100.0 * w->coupling_seconds / wall,
           1e3 * dem / gas_steps, 100.0 * dem / wall,
           100.0 * (w->gas_seconds + w->coupling_seconds) / wall);
    printf("pressure solver: %d iterations in the last gas step (relative residual %.2g)\n",
           w->gas->last_solve.iterations, w->gas->last_solve.residual);
    bdl_world_destroy(w);
    free(scene);
    return 0;
}
