// The pressure solver: recovers a known discrete solution with variable coefficients on
// Dirichlet, Neumann and periodic boxes; iteration counts that barely grow with the grid
// (the multigrid preconditioner at work); the same bits for one and two threads.
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cfd/poisson.h"
#include "check.h"

typedef struct problem {
    bdl_grid g;
    bdl_poisson *p;
    double *c[3], *x, *f, *exact, *r;
} problem;

static void setup(problem *pb, int nx, int ny, int nz, const int periodic[3],
                  const int dirichlet[6])
{
    const double lo[3] = {0, 0, 0}, hi[3] = {1.0, 0.7, 0.4};
    int n[3] = {nx, ny, nz};
    bdl_grid_init(&pb->g, n, lo, hi, periodic);
    pb->p = bdl_poisson_create(&pb->g, dirichlet);
    for (int a = 0; a < 3; ++a) {
        pb->c[a] = bdl_grid_alloc(&pb->g);
        // Coefficients varying by a factor of 20, as eps^2 dt / rho does across a bed.
        for (long i = 0; i < pb->g.size; ++i)
            pb->c[a][i] = 0.05 + 0.95 * (0.5 + 0.5 * sin(0.37 * (double)i + a));
    }
    bdl_poisson_set_coefficients(pb->p, pb->c);
    pb->x = bdl_grid_alloc(&pb->g);
    pb->f = bdl_grid_alloc(&pb->g);
    pb->exact = bdl_grid_alloc(&pb->g);
    pb->r = bdl_grid_alloc(&pb->g);
}

static void teardown(problem *pb)
{
    bdl_poisson_destroy(pb->p);
    for (int a = 0; a < 3; ++a)
        free(pb->c[a]);
    free(pb->x);
    free(pb->f);
    free(pb->exact);
    free(pb->r);
}

static double cell_mean(const problem *pb, const double *v)
{
    double s = 0.0;
    long count = 0;
    for (int k = 0; k < pb->g.n[2]; ++k)
        for (int j = 0; j < pb->g.n[1]; ++j)
            for (int i = 0; i < pb->g.n[0]; ++i, ++count)
                s += v[bdl_grid_index(&pb->g, i, j, k)];
    return s / (double)count;
}

/// f from a chosen discrete solution, then solve from zero: returns max |x - exact| relative
/// to max |exact| (after removing the means when the problem is singular), and the iterations.
static double recover(problem *pb, int singular, const double p_side[6], int *iterations)
{
    const bdl_grid *g = &pb->g;
    for (int k = 0; k < g->n[2]; ++k)
        for (int j = 0; j < g->n[1]; ++j)
            for (int i = 0; i < g->n[0]; ++i)
                pb->exact[bdl_grid_index(g, i, j, k)] =
                    cos(2.1 * i / g->n[0]) * sin(3.3 * j / g->n[1] + 0.2) + 0.3 * k / g->n[2];
    memset(pb->f, 0, (size_t)g->size * sizeof(double));
    // r = f - div(c grad exact) with f = 0, so f = -r makes `exact` the solution.
    bdl_poisson_residual(pb->p, pb->exact, pb->f, p_side, pb->r);
    for (long i = 0; i < g->size; ++i)
        pb->f[i] = -pb->r[i];
    memset(pb->x, 0, (size_t)g->size * sizeof(double));
    bdl_poisson_stats st;
    CHECK(bdl_poisson_solve(pb->p, pb->x, pb->f, p_side, 1e-12, 300, &st));
    *iterations = st.iterations;
    double shift = singular ? cell_mean(pb, pb->exact) - cell_mean(pb, pb->x) : 0.0;
    double err = 0.0, scale = 0.0;
    for (int k = 0; k < g->n[2]; ++k)
        for (int j = 0; j < g->n[1]; ++j)
            for (int i = 0; i < g->n[0]; ++i) {
                long idx = bdl_grid_index(g, i, j, k);
                err = fmax(err, fabs(pb->x[idx] + shift - pb->exact[idx]));
                scale = fmax(scale, fabs(pb->exact[idx]));
            }
    return err / scale;
}

int main(void)
{
    const double p_side[6] = {0, 0, 0, 0, 0, 1.5};
    struct {
        const char *name;
        int periodic[3], dirichlet[6], singular;
    } cases[] = {
        {"outlet on top", {0, 0, 0}, {0, 0, 0, 0, 0, 1}, 0},
        {"closed box (singular)", {0, 0, 0}, {0, 0, 0, 0, 0, 0}, 1},
        {"periodic x, z; outlet", {1, 0, 1}, {0, 0, 0, 1, 0, 0}, 0},
        {"periodic everywhere (singular)", {1, 1, 1}, {0}, 1},
    };
    // Odd counts coarsen too, the last coarse cell having a single child.
    int all_sizes[2][2][3] = {{{16, 16, 8}, {64, 64, 32}}, {{15, 9, 5}, {61, 35, 21}}};
    for (size_t run = 0; run < 2 * sizeof cases / sizeof cases[0]; ++run) {
        int its[2];
        size_t c = run / 2;
        int(*sizes)[3] = all_sizes[run % 2];
        for (int s = 0; s < 2; ++s) {
            problem pb;
            setup(&pb, sizes[s][0], sizes[s][1], sizes[s][2], cases[c].periodic,
                  cases[c].dirichlet);
            double err = recover(&pb, cases[c].singular, p_side, &its[s]);
            printf("%-32s %2dx%2dx%2d: %3d iterations, error %.1e\n", cases[c].name, sizes[s][0],
                   sizes[s][1], sizes[s][2], its[s], err);
            CHECK_MSG(err < 1e-9, "%s: error %g", cases[c].name, err);
            teardown(&pb);
        }
        // 64 times the cells, not even twice the iterations.
        CHECK_MSG(its[1] < 2 * its[0], "%s: %d then %d iterations", cases[c].name, its[0], its[1]);
    }

    // One and two threads give the same bits.
    double *x1 = NULL;
    for (int threads = 1; threads <= 2; ++threads) {
        omp_set_num_threads(threads);
        problem pb;
        const int periodic[3] = {1, 0, 0}, dirichlet[6] = {0, 0, 0, 1, 0, 0};
        setup(&pb, 32, 24, 16, periodic, dirichlet);
        int its;
        recover(&pb, 0, p_side, &its);
        if (threads == 1) {
            x1 = pb.x;
            pb.x = NULL;
        } else {
            CHECK(memcmp(x1, pb.x, (size_t)pb.g.size * sizeof(double)) == 0);
        }
        teardown(&pb);
    }
    free(x1);
    return bdl_test_summary("test_poisson");
}
