// The direct pressure solver (`[gas] pressure_solver = direct`, LAPACK's banded Cholesky) on
// known discrete solutions: Dirichlet and Neumann (singular) sides, a grid one cell deep across a
// period, a column, a three-dimensional grid, beside bedlam's multigrid CG on the same matrix;
// then its band and the grids it refuses.
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "cfd/poisson.h"
#include "check.h"

/// Solves div(c grad x) = f for f made from a known x by `solver`; returns max |x - exact| /
/// max |exact| (means removed when singular), the iterations and the reported residual.
static double recover(const int n[3], const int periodic[3], const int dirichlet[6],
                      bdl_pressure_solver solver, int *iterations, double *residual)
{
    const double lo[3] = {0, 0, 0}, hi[3] = {1.0, 0.7, 0.4};
    const double p_side[6] = {0.2, -0.1, 0, 0, 0.5, 1.5};
    int singular = 1;
    for (int s = 0; s < 6; ++s)
        singular = singular && !(dirichlet[s] && !periodic[s / 2]);
    bdl_grid g;
    bdl_grid_init(&g, n, lo, hi, periodic);
    bdl_poisson *p = bdl_poisson_create_solver(&g, dirichlet, solver);
    CHECK(p != NULL);
    if (!p)
        return INFINITY;
    double *c[3], *x = bdl_grid_alloc(&g), *f = bdl_grid_alloc(&g), *exact = bdl_grid_alloc(&g),
                  *r = bdl_grid_alloc(&g);
    for (int a = 0; a < 3; ++a) {
        c[a] = bdl_grid_alloc(&g);
        for (long i = 0; i < g.size; ++i) // coefficients spanning a factor of 20
            c[a][i] = 0.05 + 0.95 * (0.5 + 0.5 * sin(0.37 * (double)i + a));
    }
    bdl_poisson_set_coefficients(p, c);
    const double cells = (double)n[0] * n[1] * n[2];
    double mean_exact = 0.0, mean_x = 0.0;
    for (int k = 0; k < n[2]; ++k)
        for (int j = 0; j < n[1]; ++j)
            for (int i = 0; i < n[0]; ++i) {
                const long idx = bdl_grid_index(&g, i, j, k);
                exact[idx] = cos(2.1 * i / n[0]) * sin(3.3 * j / n[1] + 0.2) + 0.3 * k / n[2];
                mean_exact += exact[idx] / cells;
            }
    bdl_poisson_residual(p, exact, f, p_side, r); // f = 0 here: r = -div(c grad exact)
    for (long i = 0; i < g.size; ++i)
        f[i] = -r[i];
    bdl_poisson_stats st = {0};
    CHECK(bdl_poisson_solve(p, x, f, p_side, 1e-12, 500, &st));
    *iterations = st.iterations;
    *residual = st.residual;
    for (int k = 0; k < n[2]; ++k)
        for (int j = 0; j < n[1]; ++j)
            for (int i = 0; i < n[0]; ++i)
                mean_x += x[bdl_grid_index(&g, i, j, k)] / cells;
    double err = 0.0, scale = 0.0;
    for (int k = 0; k < n[2]; ++k)
        for (int j = 0; j < n[1]; ++j)
            for (int i = 0; i < n[0]; ++i) {
                const long idx = bdl_grid_index(&g, i, j, k);
                const double xi = singular ? x[idx] - mean_x + mean_exact : x[idx];
                err = fmax(err, fabs(xi - exact[idx]));
                scale = fmax(scale, fabs(exact[idx]));
            }
    for (int a = 0; a < 3; ++a)
        free(c[a]);
    free(x), free(f), free(exact), free(r);
    bdl_poisson_destroy(p);
    return err / scale;
}

static void test_known_solutions(void)
{
    static const struct {
        const char *name;
        int n[3], periodic[3], dirichlet[6];
    } cases[] = {
        {"Dirichlet on z, walls on x, one cell deep across a period (a 2-D bed)",
         {15, 1, 45},
         {0, 1, 0},
         {0, 0, 0, 0, 1, 1}},
        {"Neumann everywhere (singular)", {9, 1, 13}, {0, 1, 0}, {0, 0, 0, 0, 0, 0}},
        {"Dirichlet on x", {12, 1, 7}, {0, 1, 0}, {1, 1, 0, 0, 0, 0}},
        {"three dimensions, Dirichlet on z", {5, 4, 9}, {0, 0, 0}, {0, 0, 0, 0, 1, 1}},
        {"three dimensions, singular", {4, 3, 6}, {0, 0, 0}, {0, 0, 0, 0, 0, 0}},
        {"a column", {1, 1, 30}, {1, 1, 0}, {0, 0, 0, 0, 1, 0}},
    };
    for (size_t t = 0; t < sizeof cases / sizeof cases[0]; ++t) {
        int it_direct = 0, it_mg = 0;
        double res_direct = 0.0, res_mg = 0.0;
        const double e_direct = recover(cases[t].n, cases[t].periodic, cases[t].dirichlet,
                                        BDL_PRESSURE_DIRECT, &it_direct, &res_direct);
        const double e_mg = recover(cases[t].n, cases[t].periodic, cases[t].dirichlet,
                                    BDL_PRESSURE_MGPCG, &it_mg, &res_mg);
        printf("%s: direct error %.2e (%d solve%s, residual %.1e), multigrid CG %.2e (%d "
               "iterations)\n",
               cases[t].name, e_direct, it_direct, it_direct == 1 ? "" : "s", res_direct, e_mg,
               it_mg);
        CHECK_MSG(e_direct < 1e-10, "%s: %g", cases[t].name, e_direct);
        CHECK_MSG(it_direct >= 1 && it_direct <= 2, "%s: %d solves", cases[t].name, it_direct);
        CHECK_MSG(res_direct <= 1e-12, "%s: residual %g", cases[t].name, res_direct);
    }
}

/// The band (the cells of an x row, or of an x-y layer) and the grids it refuses.
static void test_band(void)
{
    const double lo[3] = {0, 0, 0}, hi[3] = {1, 1, 1};
    const int walls[3] = {0, 0, 0}, y_period[3] = {0, 1, 0}, x_period[3] = {1, 0, 0};
    static const int none[6] = {0};
    struct {
        int n[3];
        const int *periodic;
        int band;
    } cases[] = {
        {{15, 1, 45}, y_period, 15}, {{6, 5, 7}, walls, 30}, {{1, 1, 9}, walls, 1},
        {{8, 1, 1}, walls, 1},       {{1, 1, 1}, walls, 0},  {{4, 1, 8}, x_period, -1},
        {{1, 1, 8}, x_period, 1},
    };
    for (size_t t = 0; t < sizeof cases / sizeof cases[0]; ++t) {
        bdl_grid g;
        bdl_grid_init(&g, cases[t].n, lo, hi, cases[t].periodic);
        const int band = bdl_poisson_direct_band(cases[t].n, cases[t].periodic);
        CHECK_MSG(band == cases[t].band, "case %zu: band %d, expected %d", t, band, cases[t].band);
        bdl_poisson *p = bdl_poisson_create_solver(&g, none, BDL_PRESSURE_DIRECT);
        CHECK_MSG((p != NULL) == (band >= 0), "case %zu: created %d", t, p != NULL);
        bdl_poisson_destroy(p);
    }
    bdl_grid g; // a layer above the largest band
    const int n[3] = {40, 40, 3};
    bdl_grid_init(&g, n, lo, hi, walls);
    CHECK(bdl_poisson_direct_band(n, walls) > BDL_POISSON_DIRECT_BAND_MAX);
    CHECK(bdl_poisson_create_solver(&g, none, BDL_PRESSURE_DIRECT) == NULL);
    const int deep[3] = {30, 30, 1200}; // a band of 900 over 1.08e6 cells: 8.7e11 a step
    bdl_grid_init(&g, deep, lo, hi, walls);
    CHECK_CLOSE(bdl_poisson_direct_cost(deep, walls), 1.08e6 * 900.0 * 900.0, 1.0);
    CHECK(bdl_poisson_create_solver(&g, none, BDL_PRESSURE_DIRECT) == NULL);
}

int main(void)
{
    test_known_solutions();
    test_band();
    return bdl_test_summary("test_poisson_direct");
}
