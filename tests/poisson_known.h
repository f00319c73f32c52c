// A pressure equation of known discrete solution for the solver tests: coefficients spanning a
// factor of 20 between neighbouring faces, a smooth x chosen, f made from it, then solved from
// zero at tolerance 1e-12 by the solver given.
#ifndef BDL_TEST_POISSON_KNOWN_H
#define BDL_TEST_POISSON_KNOWN_H

#include <math.h>
#include <stdlib.h>

#include "cfd/poisson.h"
#include "check.h"

/// Solves the known problem on n cells with `solver`; returns max |x - exact| / max |exact| (the
/// means removed when `singular`), the solution (means likewise) into x_out in cell order x
/// fastest when it is not NULL, and the solver's statistics.
static double poisson_known_solution(const int n[3], const int periodic[3], const int dirichlet[6],
                                     int singular, bdl_pressure_solver solver, double *x_out,
                                     bdl_poisson_stats *st)
{
    const double lo[3] = {0, 0, 0}, hi[3] = {1.0, 0.7, 0.4};
    const double p_side[6] = {0.2, -0.1, 0, 0, 0.5, 1.5};
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
        for (long i = 0; i < g.size; ++i) // a factor of 20, as eps^2 dt / rho across a bed
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
    CHECK(bdl_poisson_solve(p, x, f, p_side, 1e-12, 500, st));
    for (int k = 0; k < n[2]; ++k)
        for (int j = 0; j < n[1]; ++j)
            for (int i = 0; i < n[0]; ++i)
                mean_x += x[bdl_grid_index(&g, i, j, k)] / cells;
    double err = 0.0, scale = 0.0;
    long m = 0;
    for (int k = 0; k < n[2]; ++k)
        for (int j = 0; j < n[1]; ++j)
            for (int i = 0; i < n[0]; ++i, ++m) {
                const long idx = bdl_grid_index(&g, i, j, k);
                const double xi = singular ? x[idx] - mean_x + mean_exact : x[idx];
                err = fmax(err, fabs(xi - exact[idx]));
                scale = fmax(scale, fabs(exact[idx]));
                if (x_out)
                    x_out[m] = xi;
            }
    bdl_poisson_destroy(p);
    for (int a = 0; a < 3; ++a)
        free(c[a]);
    free(x), free(f), free(exact), free(r);
    return err / scale;
}

#endif
