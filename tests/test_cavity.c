// Lid-driven cavity at Re = 100 against Ghia, Ghia & Shin (1982), J. Comput. Phys. 48,
// 387-411, table I (u on the vertical centreline) and table II (v on the horizontal one).
// Usage: test_cavity [cells per side, default 64] [scheme: central|vanleer|superbee]
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cfd/gas.h"
#include "check.h"

static const double ghia_y[] = {0.9766, 0.9688, 0.9609, 0.9531, 0.8516, 0.7344, 0.6172, 0.5000,
                                0.4531, 0.2813, 0.1719, 0.1016, 0.0703, 0.0625, 0.0547};
static const double ghia_u[] = {0.84123,  0.78871,  0.73722,  0.68717,  0.23151,
                                0.00332,  -0.13641, -0.20581, -0.21090, -0.15662,
                                -0.10150, -0.06434, -0.04775, -0.04192, -0.03717};
static const double ghia_x[] = {0.9688, 0.9609, 0.9531, 0.9453, 0.9063, 0.8594, 0.8047, 0.5000,
                                0.2344, 0.2266, 0.1563, 0.0938, 0.0781, 0.0703, 0.0625};
static const double ghia_v[] = {-0.05906, -0.07391, -0.08864, -0.10313, -0.16914,
                                -0.22445, -0.24533, 0.05454,  0.17527,  0.17507,
                                0.16077,  0.12317,  0.10890,  0.10091,  0.09233};

/// Linear interpolation of face values f(s) stored at s = (m + 0.5) h, m = 0..n-1, with the
/// wall values w0 at s = 0 and w1 at s = 1.
static double along(const double *f, int n, double s, double w0, double w1)
{
    double x = s * n - 0.5;
    if (x < 0.0)
        return w0 + (f[0] - w0) * (s * n) / 0.5;
    if (x > n - 1)
        return f[n - 1] + (w1 - f[n - 1]) * (x - (n - 1)) / 0.5;
    int m = (int)x;
    if (m > n - 2)
        m = n - 2;
    return f[m] + (f[m + 1] - f[m]) * (x - m);
}

int main(int argc, char **argv)
{
    const int n = argc > 1 ? atoi(argv[1]) : 64;
    bdl_convection scheme = BDL_CONVECTION_CENTRAL;
    if (argc > 2 && strcmp(argv[2], "vanleer") == 0)
        scheme = BDL_CONVECTION_VANLEER;
    if (argc > 2 && strcmp(argv[2], "superbee") == 0)
        scheme = BDL_CONVECTION_SUPERBEE;
    bdl_gas_def d = {0};
    d.n[0] = d.n[1] = n, d.n[2] = 1;
    d.hi[0] = d.hi[1] = 1.0, d.hi[2] = 1.0 / n;
    d.density = 1.0;
    d.viscosity = 0.01; // Re = U L / nu = 100
    for (int s = 0; s < 4; ++s)
        d.side[s].type = BDL_SIDE_WALL;
    d.side[3].wall_velocity[0] = 1.0; // the lid at y = 1
    d.side[4].type = d.side[5].type = BDL_SIDE_PERIODIC;
    d.convection = scheme;
    d.tolerance = 1e-10;
    bdl_gas *g = NULL;
    if (bdl_gas_create(&d, &g) != BDL_OK)
        return 1;
    const double dt = fmin(0.8 / (2.0 * d.viscosity * 2.0 * n * n), 0.4 / n);
    double change = INFINITY, t = 0.0;
    int steps = 0;
    while (change > 1e-6 && t < 200.0) {
        // Steady when no velocity changes faster than 1e-6 (lid velocities) per unit time.
        double *before = malloc((size_t)g->grid.size * sizeof(double));
        memcpy(before, g->u[0], (size_t)g->grid.size * sizeof(double));
        for (int k = 0; k < 50; ++k, ++steps)
            if (bdl_gas_step(g, dt) != BDL_OK) {
                fprintf(stderr, "step %d failed\n", steps);
                return 1;
            }
        t += 50 * dt;
        change = 0.0;
        for (int j = 0; j < n; ++j)
            for (int i = 0; i <= n; ++i) {
                long idx = bdl_grid_index(&g->grid, i, j, 0);
                change = fmax(change, fabs(g->u[0][idx] - before[idx]) / (50 * dt));
            }
        free(before);
    }
    // u on x = 0.5 (faces i = n/2), v on y = 0.5 (faces j = n/2).
    double *uc = malloc((size_t)n * sizeof(double)), *vc = malloc((size_t)n * sizeof(double));
    for (int m = 0; m < n; ++m) {
        uc[m] = g->u[0][bdl_grid_index(&g->grid, n / 2, m, 0)];
        vc[m] = g->u[1][bdl_grid_index(&g->grid, m, n / 2, 0)];
    }
    double worst_u = 0.0, worst_v = 0.0;
    printf("lid-driven cavity, Re = 100, %dx%d cells, steady at t = %.1f (%d steps)\n", n, n, t,
           steps);
    printf("   y      u        Ghia     |    x      v        Ghia\n");
    for (size_t k = 0; k < sizeof ghia_y / sizeof ghia_y[0]; ++k) {
        double u = along(uc, n, ghia_y[k], 0.0, 1.0), v = along(vc, n, ghia_x[k], 0.0, 0.0);
        worst_u = fmax(worst_u, fabs(u - ghia_u[k]));
        worst_v = fmax(worst_v, fabs(v - ghia_v[k]));
        printf("%.4f % .5f % .5f | %.4f % .5f % .5f\n", ghia_y[k], u, ghia_u[k], ghia_x[k], v,
               ghia_v[k]);
    }
    printf("largest difference: u %.4f, v %.4f (lid velocity 1)\n", worst_u, worst_v);
    CHECK_MSG(worst_u < 0.02, "u differs from Ghia by %g", worst_u);
    CHECK_MSG(worst_v < 0.02, "v differs from Ghia by %g", worst_v);
    free(uc);
    free(vc);
    bdl_gas_destroy(g);
    return bdl_test_summary("test_cavity");
}
