// The direct pressure solver (`[gas] pressure_solver = direct`, a banded Cholesky) on
// known discrete solutions: Dirichlet and Neumann (singular) sides, a grid one cell deep across a
// period, a column, a three-dimensional grid, beside bedlam's multigrid CG on the same matrix;
// then its band and the grids it refuses.
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "cfd/poisson.h"
#include "check.h"
#include "poisson_known.h"

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
        int singular = 1;
        for (int side = 0; side < 6; ++side)
            singular = singular && !(cases[t].dirichlet[side] && !cases[t].periodic[side / 2]);
        bdl_poisson_stats sd = {0}, sm = {0};
        const double e_direct =
            poisson_known_solution(cases[t].n, cases[t].periodic, cases[t].dirichlet, singular,
                                   BDL_PRESSURE_DIRECT, NULL, &sd);
        const double e_mg =
            poisson_known_solution(cases[t].n, cases[t].periodic, cases[t].dirichlet, singular,
                                   BDL_PRESSURE_MGPCG, NULL, &sm);
        const int it_direct = sd.iterations, it_mg = sm.iterations;
        const double res_direct = sd.residual;
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
