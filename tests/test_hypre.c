// hypre's pressure solver (builds with -DBDL_WITH_MPI=ON) against bedlam's own: the same known
// discrete solutions on Dirichlet, Neumann (singular), periodic and one-cell-deep grids, to the
// solver tolerance; then the lid-driven cavity, a CFD-DEM fluidized bed and the two-fluid bed
// stepped with each, agreeing to what the tolerance leaves. Prints the iterations per solve of
// both (docs/parallel.md).
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cfd/gas.h"
#include "check.h"
#include "poisson_known.h"
#include "core/comm.h"
#include "scene/scene.h"
#include "world/world.h"

static void known_solutions(void)
{
    struct {
        const char *name;
        int n[3], periodic[3], dirichlet[6], singular;
    } cases[] = {
        {"outlet on top", {16, 12, 10}, {0, 0, 0}, {0, 0, 0, 0, 0, 1}, 0},
        {"closed box (singular)", {15, 9, 7}, {0, 0, 0}, {0}, 1},
        {"periodic x, z (odd); outlet", {15, 8, 9}, {1, 0, 1}, {0, 0, 0, 1, 0, 0}, 0},
        {"periodic everywhere (singular)", {12, 10, 8}, {1, 1, 1}, {0}, 1},
        {"one cell deep, periodic y", {15, 1, 45}, {0, 1, 0}, {0, 0, 0, 0, 1, 1}, 0},
    };
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; ++c) {
        const int *n = cases[c].n;
        const long cells = (long)n[0] * n[1] * n[2];
        double *xm = malloc((size_t)cells * sizeof *xm), *xh = malloc((size_t)cells * sizeof *xh);
        bdl_poisson_stats sm = {0}, sh = {0};
        const double em = poisson_known_solution(n, cases[c].periodic, cases[c].dirichlet,
                                                 cases[c].singular, BDL_PRESSURE_MGPCG, xm, &sm);
        const double eh = poisson_known_solution(n, cases[c].periodic, cases[c].dirichlet,
                                                 cases[c].singular, BDL_PRESSURE_HYPRE, xh, &sh);
        const int im = sm.iterations, ih = sh.iterations;
        double diff = 0.0;
        for (long i = 0; i < cells; ++i)
            diff = fmax(diff, fabs(xm[i] - xh[i]));
        printf("%-32s %2dx%2dx%2d: MG-PCG %3d iterations (error %.1e), hypre %3d (error %.1e), "
               "difference %.1e\n",
               cases[c].name, n[0], n[1], n[2], im, em, ih, eh, diff);
        CHECK_MSG(em < 1e-9 && eh < 1e-9, "%s: errors %g (MG-PCG), %g (hypre)", cases[c].name, em,
                  eh);
        free(xm);
        free(xh);
    }
}

/// The lid-driven cavity (Re 100, 32 x 32) stepped 400 times by each solver: the velocities agree
/// to the solver tolerance's order.
static void cavity(void)
{
    double *u[2] = {NULL, NULL};
    long size = 0, solves[2] = {0, 0}, iterations[2] = {0, 0};
    for (int s = 0; s < 2; ++s) {
        bdl_gas_def d = bdl_default_gas_def();
        d.n[0] = d.n[1] = 32, d.n[2] = 1;
        d.hi[0] = d.hi[1] = 1.0, d.hi[2] = 1.0 / 32;
        d.density = 1.0;
        d.viscosity = 0.01;
        d.side[3].wall_velocity[0] = 1.0;
        d.side[4].type = d.side[5].type = BDL_SIDE_PERIODIC;
        d.tolerance = 1e-10;
        d.pressure_solver = s ? BDL_PRESSURE_HYPRE : BDL_PRESSURE_MGPCG;
        bdl_gas *g = NULL;
        CHECK(bdl_gas_create(&d, &g) == BDL_OK);
        if (!g)
            return;
        for (int k = 0; k < 400; ++k) {
            CHECK(bdl_gas_step(g, 0.005) == BDL_OK);
            iterations[s] += g->last_solve.iterations;
            solves[s]++;
        }
        size = g->grid.size;
        u[s] = malloc((size_t)size * sizeof(double));
        memcpy(u[s], g->u[0], (size_t)size * sizeof(double));
        bdl_gas_destroy(g);
    }
    double diff = 0.0;
    for (long i = 0; i < size; ++i)
        diff = fmax(diff, fabs(u[0][i] - u[1][i]));
    printf("cavity 32x32, 400 steps: MG-PCG %.2f, hypre %.2f iterations per solve; largest "
           "difference in u %.1e (lid 1)\n",
           (double)iterations[0] / solves[0], (double)iterations[1] / solves[1], diff);
    CHECK_MSG(diff < 1e-7, "the cavity's u differs by %g", diff);
    free(u[0]);
    free(u[1]);
}

/// A scene stepped `steps` times with each solver: the largest difference of the particles'
/// positions (over the box's size) and of the solids fractions after the steps, and the
/// iterations per solve.
static void scene(const char *path, const char *extra, const char *extra2, int steps,
                  double tolerance)
{
    double diff_pos = 0.0, diff_eps = 0.0, its[2] = {0, 0};
    bdl_world *w[2] = {NULL, NULL};
    for (int s = 0; s < 2; ++s) {
        const char *over[4] = {"gas.tolerance=1e-11",
                               s ? "gas.pressure_solver=hypre" : "gas.pressure_solver=mgpcg", extra,
                               extra2};
        static bdl_scene sc;
        static bdl_scene_error err;
        CHECK(bdl_scene_load(path, over, extra ? 4 : 2, &sc, &err) == BDL_OK);
        CHECK(bdl_world_create(&sc, &w[s], &err) == BDL_OK);
        if (!w[s])
            return;
        long solves = 0;
        for (int k = 0; k < steps; ++k) {
            const long before = w[s]->gas_steps;
            CHECK(bdl_world_step(w[s]) == BDL_OK);
            if (w[s]->gas_steps != before)
                its[s] += w[s]->gas->last_solve.iterations, solves++;
        }
        its[s] /= (double)(solves > 0 ? solves : 1);
    }
    const bdl_particles *a = &w[0]->particles, *b = &w[1]->particles;
    CHECK(a->count == b->count);
    const double box = w[0]->scene.domain_max.z - w[0]->scene.domain_min.z;
    for (long i = 0; i < a->count && a->count == b->count; ++i)
        diff_pos = fmax(diff_pos, bdl_v3_len(bdl_v3_sub(a->pos[i], b->pos[i])) / box);
    if (w[0]->solids)
        for (long i = 0; i < w[0]->solids->grid.size; ++i)
            diff_eps = fmax(diff_eps, fabs(w[0]->solids->eps[i] - w[1]->solids->eps[i]));
    printf("%s, %d steps: MG-PCG %.2f, hypre %.2f iterations per solve; largest difference: "
           "positions %.1e of the box, solids fractions %.1e\n",
           path, steps, its[0], its[1], diff_pos, diff_eps);
    CHECK_MSG(diff_pos < tolerance && diff_eps < tolerance, "%s: differences %g, %g", path,
              diff_pos, diff_eps);
    bdl_world_destroy(w[0]);
    bdl_world_destroy(w[1]);
}

int main(int argc, char **argv)
{
    bdl_comm_init(&argc, &argv);
    known_solutions();
    cavity();
    // A relative residual of 1e-11 leaves differences near 1e-12 per step; 1e-8 is the bound
    // after the steps below (DEM contacts and the plastic regime amplify them only mildly).
    scene("../scenes/fluidized_bed.ini", NULL, NULL, 400, 1e-8);
    // The two-fluid bed at a fixed step: an adaptive one may take its steps back differently.
    scene("../scenes/tfm_goldschmidt_bed.ini", "solids.courant=0", "run.dt=2e-4", 500, 1e-8);
    const int code = bdl_test_summary("test_hypre");
    bdl_comm_finalize();
    return code;
}
