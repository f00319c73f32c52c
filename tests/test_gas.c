// Gas solver verification: plane Poiseuille flow (second-order convergence under refinement),
// hydrostatic rest, plug flow from an inlet to an outlet, gas volume conservation while the
// voidage changes, a porous distributor plate sharing its flow among columns of unequal drag, and
// point-implicit convection: a square wave carried across a periodic box at Courant numbers
// up to 8, bounded and conserved, moving at U / (1 + c).
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "cfd/gas.h"
#include "core/vec3.h"
#include "check.h"
#include "verify/verify.h"

static double poiseuille_error(int ny)
{
    double cross = 1.0;
    double err = bdl_verify_poiseuille(ny, &cross, NULL);
    CHECK_MSG(cross < 1e-12, "cross-stream velocity %g of u_max", cross); // the flow stays parallel
    return err;
}

static void test_poiseuille(void)
{
    double e[3];
    int n[3] = {8, 16, 32};
    printf("plane Poiseuille: cells  max error / u_max  order\n");
    for (int k = 0; k < 3; ++k) {
        e[k] = poiseuille_error(n[k]);
        if (k == 0)
            printf("                  %5d  %.3e\n", n[k], e[k]);
        else
            printf("                  %5d  %.3e  %.2f\n", n[k], e[k], log2(e[k - 1] / e[k]));
    }
    CHECK(e[0] < 0.02);
    CHECK_MSG(log2(e[1] / e[2]) > 1.9 && log2(e[1] / e[2]) < 2.1, "order %g", log2(e[1] / e[2]));
}

/// A closed box under gravity: the gas stays at rest and the pressure is hydrostatic.
static void test_hydrostatic(void)
{
    bdl_gas_def d = bdl_default_gas_def();
    d.n[0] = 8, d.n[1] = 16, d.n[2] = 4;
    d.hi[0] = 0.1, d.hi[1] = 0.2, d.hi[2] = 0.05;
    d.gravity[1] = -9.81;
    for (int s = 0; s < 6; ++s)
        d.side[s].type = BDL_SIDE_WALL;
    d.tolerance = 1e-12;
    bdl_gas *g = NULL;
    CHECK(bdl_gas_create(&d, &g) == BDL_OK);
    for (int step = 0; step < 20; ++step)
        CHECK(bdl_gas_step(g, 1e-3) == BDL_OK);
    double umax = 0.0, grad_err = 0.0;
    for (int a = 0; a < 3; ++a)
        for (long i = 0; i < g->grid.size; ++i)
            umax = fmax(umax, fabs(g->u[a][i]));
    const double h = g->grid.h[1];
    for (int k = 0; k < 4; ++k)
        for (int j = 1; j < 16; ++j)
            for (int i = 0; i < 8; ++i) {
                double dp = g->p[bdl_grid_index(&g->grid, i, j, k)] -
                            g->p[bdl_grid_index(&g->grid, i, j - 1, k)];
                grad_err = fmax(grad_err, fabs(dp / h - d.density * d.gravity[1]));
            }
    CHECK_MSG(umax < 1e-10, "gas at rest moves at %g m/s", umax);
    CHECK_MSG(grad_err < 1e-8 * d.density * 9.81, "hydrostatic gradient off by %g", grad_err);
    bdl_gas_destroy(g);
}

/// Uniform inflow at the bottom, pressure outlet at the top, free-slip sides: plug flow with
/// interstitial velocity U / eps, here with a voidage that varies with height.
static void test_plug_flow(void)
{
    bdl_gas_def d = bdl_default_gas_def();
    d.n[0] = 6, d.n[1] = 12, d.n[2] = 1;
    d.hi[0] = 0.06, d.hi[1] = 0.12, d.hi[2] = 0.01;
    d.side[0].type = d.side[1].type = BDL_SIDE_SLIP;
    d.side[2].type = BDL_SIDE_INLET;
    d.side[2].inflow = 0.3;
    d.side[3].type = BDL_SIDE_OUTLET;
    d.side[4].type = d.side[5].type = BDL_SIDE_PERIODIC;
    d.tolerance = 1e-12;
    bdl_gas *g = NULL;
    CHECK(bdl_gas_create(&d, &g) == BDL_OK);
    for (int j = 0; j < 12; ++j)
        for (int i = 0; i < 6; ++i)
            g->eps[bdl_grid_index(&g->grid, i, j, 0)] =
                g->eps_old[bdl_grid_index(&g->grid, i, j, 0)] = j < 6 ? 0.45 : 1.0;
    for (int step = 0; step < 200; ++step)
        CHECK(bdl_gas_step(g, 1e-3) == BDL_OK);
    double worst = 0.0;
    for (int j = 1; j <= 12; ++j)
        for (int i = 0; i < 6; ++i) {
            long idx = bdl_grid_index(&g->grid, i, j, 0);
            double eps_face = 0.5 * (g->eps[idx] + g->eps[idx - g->grid.stride[1]]);
            worst = fmax(worst, fabs(eps_face * g->u[1][idx] - 0.3));
        }
    CHECK_MSG(worst < 1e-9, "superficial velocity off by %g m/s", worst);
    CHECK(g->mass_imbalance < 1e-9);
    bdl_gas_destroy(g);
}

/// The voidage changes every step (a sinusoidal wave of solids passing through a closed, periodic
/// box): the gas volume balance holds in every cell to the solver's tolerance.
static void test_volume_conservation(void)
{
    bdl_gas_def d = bdl_default_gas_def();
    d.n[0] = 16, d.n[1] = 16, d.n[2] = 2;
    d.hi[0] = 0.04, d.hi[1] = 0.04, d.hi[2] = 0.005;
    d.side[0].type = d.side[1].type = BDL_SIDE_PERIODIC;
    d.side[2].type = BDL_SIDE_WALL;
    d.side[3].type = BDL_SIDE_OUTLET;
    d.side[4].type = d.side[5].type = BDL_SIDE_PERIODIC;
    d.convection = BDL_CONVECTION_SUPERBEE;
    d.tolerance = 1e-10;
    bdl_gas *g = NULL;
    CHECK(bdl_gas_create(&d, &g) == BDL_OK);
    double worst = 0.0;
    const double dt = 1e-4;
    for (int step = 0; step <= 50; ++step) {
        double t = step * dt;
        for (int k = 0; k < 2; ++k)
            for (int j = 0; j < 16; ++j)
                for (int i = 0; i < 16; ++i)
                    g->eps[bdl_grid_index(&g->grid, i, j, k)] =
                        0.7 +
                        0.2 * sin(2.0 * BDL_PI * (i / 16.0 - 10.0 * t)) * cos(BDL_PI * j / 16.0);
        if (step == 0) { // start from the wave at t = 0
            memcpy(g->eps_old, g->eps, (size_t)g->grid.size * sizeof(double));
            continue;
        }
        CHECK(bdl_gas_step(g, dt) == BDL_OK);
        worst = fmax(worst, g->mass_imbalance);
    }
    printf("volume balance: worst cell |d eps/dt + div(eps u)| dt = %.2e\n", worst);
    CHECK_MSG(worst < 1e-9, "volume imbalance %g", worst);
    bdl_gas_destroy(g);
}

/// A porous distributor plate under four columns of different drag, kept apart by a drag across
/// them 10^9 times larger: each column's superficial velocity is P / (R + beta_i L) with
/// L the distance from its first cell's centre to the outlet, and the plenum pressure P makes
/// them average the set inflow U; with equal drag every column takes U. Also: the plate's flux
/// follows the pressure as it builds (the volume balance holds every step).
static void test_distributor(void)
{
    const double R = 150.0, U = 0.8, beta[4] = {1e3, 2e3, 4e3, 8e3};
    bdl_gas_def d = bdl_default_gas_def();
    d.n[0] = 4, d.n[1] = 1, d.n[2] = 10;
    d.hi[0] = 0.04, d.hi[1] = 0.01, d.hi[2] = 0.1;
    d.viscosity = 1e-12; // no shear between the columns
    d.side[0].type = d.side[1].type = d.side[2].type = d.side[3].type = BDL_SIDE_SLIP;
    d.side[4].type = BDL_SIDE_INLET;
    d.side[4].inflow = U;
    d.side[4].resistance = R;
    d.side[5].type = BDL_SIDE_OUTLET;
    d.tolerance = 1e-13;
    d.max_iterations = 1000;
    for (int uniform = 0; uniform < 2; ++uniform) {
        bdl_gas *g = NULL;
        CHECK(bdl_gas_create(&d, &g) == BDL_OK);
        for (long idx = 0; idx < g->grid.size; ++idx)
            g->beta[0][idx] = 1e13;
        for (int k = 0; k <= 10; ++k)
            for (int i = 0; i < 4; ++i)
                g->beta[2][bdl_grid_index(&g->grid, i, 0, k)] = uniform ? 3e3 : beta[i];
        double worst_balance = 0.0;
        for (int step = 0; step < 3000; ++step) {
            CHECK(bdl_gas_step(g, 1e-3) == BDL_OK);
            worst_balance = fmax(worst_balance, g->mass_imbalance);
        }
        const double L = 0.1 - 0.005;
        double sum_inv = 0.0, mean = 0.0, worst = 0.0;
        for (int i = 0; i < 4; ++i)
            sum_inv += 1.0 / (R + (uniform ? 3e3 : beta[i]) * L);
        const double P = 4.0 * U / sum_inv;
        for (int i = 0; i < 4; ++i) {
            const double u = g->u[2][bdl_grid_index(&g->grid, i, 0, 0)];
            const double want = P / (R + (uniform ? 3e3 : beta[i]) * L);
            mean += u / 4.0;
            worst = fmax(worst, fabs(u - want) / want);
            if (!uniform)
                printf("distributor: column %d  u %.6f m/s  analytic %.6f m/s\n", i, u, want);
        }
        printf("distributor (%s drag): plenum %.4f Pa (analytic %.4f), mean inflow %.9f m/s, "
               "worst column error %.2e, volume balance %.1e\n",
               uniform ? "equal" : "unequal", g->plenum[4], P, mean, worst, worst_balance);
        CHECK_MSG(worst < 1e-6, "column velocity off by %g of the analytic", worst);
        CHECK_MSG(fabs(mean - U) < 1e-9 * U, "mean inflow %.12g m/s, set %g", mean, U);
        CHECK_MSG(fabs(g->plenum[4] - P) < 1e-6 * P, "plenum %g Pa, analytic %g", g->plenum[4], P);
        CHECK(worst_balance < 1e-9);
        bdl_gas_destroy(g);
    }
    bdl_gas_def bad = d;
    bad.side[4].jet = 1;
    bdl_gas *g = NULL;
    CHECK(bdl_gas_create(&bad, &g) == BDL_ERR_ARGS); // a plate has no jet
    bad = d;
    bad.side[4].resistance = -1.0;
    CHECK(bdl_gas_create(&bad, &g) == BDL_ERR_ARGS);
}

/// A square wave of u_z(x) (0 and 1) carried along x by a uniform u_x = 1 m/s across a periodic
/// box of 32 cells for `steps` steps at Courant number `courant`; the worst excursion beyond
/// [0, 1], the change of sum(u_z), and the phase lag of the first Fourier mode behind the exact
/// solution's [rad] into *lag.
static double carried_wave(bdl_convection scheme, bdl_convection_step step, double courant,
                           int steps, double *drift, double *lag)
{
    bdl_gas_def d = bdl_default_gas_def();
    const int n = 32;
    d.n[0] = n, d.n[1] = 1, d.n[2] = 1;
    d.hi[0] = 0.32, d.hi[1] = 0.01, d.hi[2] = 0.01;
    for (int side = 0; side < 6; ++side)
        d.side[side].type = BDL_SIDE_PERIODIC;
    d.viscosity = 1e-15; // (must be positive) no diffusion to speak of
    d.convection = scheme;
    d.convection_step = step;
    bdl_gas *g = NULL;
    CHECK(bdl_gas_create(&d, &g) == BDL_OK);
    const bdl_grid *gr = &g->grid;
    double sum0 = 0.0;
    for (long idx = 0; idx < gr->size; ++idx)
        g->u[0][idx] = 1.0;
    for (int i = 0; i < n; ++i) {
        const long idx = bdl_grid_index(gr, i, 0, 0);
        g->u[2][idx] = g->u[2][idx + gr->stride[2]] = i >= 8 && i < 16 ? 1.0 : 0.0;
        sum0 += g->u[2][idx];
    }
    const double dt = courant * gr->h[0];
    for (int k = 0; k < steps; ++k)
        CHECK(bdl_gas_step(g, dt) == BDL_OK);
    double worst = 0.0, sum = 0.0, re = 0.0, im = 0.0;
    for (int i = 0; i < n; ++i) {
        const double v = g->u[2][bdl_grid_index(gr, i, 0, 0)], x = (i + 0.5) / n;
        worst = fmax(worst, fmax(-v, v - 1.0));
        sum += v;
        re += v * cos(2.0 * BDL_PI * x), im += v * sin(2.0 * BDL_PI * x);
    }
    // The wave's first mode starts at phase 2 pi 12/32 (its centre) and moves 2 pi U t / L.
    const double moved = 2.0 * BDL_PI * (12.0 / n + steps * dt * 1.0 / 0.32);
    *lag = remainder(moved - atan2(im, re), 2.0 * BDL_PI);
    *drift = fabs(sum - sum0);
    bdl_gas_destroy(g);
    return worst;
}

static void test_point_implicit_convection(void)
{
    double drift = 0.0, lag = 0.0;
    // Explicit, the wave grows out of its bounds at Courant number 2 (the test can fail).
    const double explicit_worst =
        carried_wave(BDL_CONVECTION_UPWIND, BDL_CONVECTION_EXPLICIT, 2.0, 16, &drift, &lag);
    CHECK_MSG(explicit_worst > 1.0, "explicit upwind at Courant 2 stays within %g", explicit_worst);
    const bdl_convection schemes[2] = {BDL_CONVECTION_UPWIND, BDL_CONVECTION_SUPERBEE};
    const double courants[3] = {0.25, 2.0, 8.0};
    for (int s = 0; s < 2; ++s)
        for (int c = 0; c < 3; ++c) {
            const int steps = (int)lround(16.0 / courants[c]); // half a period
            const double worst = carried_wave(schemes[s], BDL_CONVECTION_POINT_IMPLICIT,
                                              courants[c], steps, &drift, &lag);
            printf("point-implicit %s at Courant %g: %d steps, beyond [0, 1] by %.2e, sum "
                   "changed by %.2e, phase lag %.3f rad\n",
                   bdl_convection_labels[schemes[s]], courants[c], steps, worst, drift, lag);
            CHECK_MSG(worst < 1e-12, "out of bounds by %g", worst);
            CHECK_MSG(drift < 1e-11, "sum of u_z changed by %g", drift);
            // The scheme is the explicit step with its convection divided by 1 + c: the wave
            // moves at U / (1 + c), behind the exact one by pi c / (1 + c) after half a period
            // (the price of a step that is a weighted mean at any c; gas.h).
            const double expected = BDL_PI * courants[c] / (1.0 + courants[c]);
            CHECK_MSG(fabs(lag - expected) < 0.02, "phase lag %g rad, expected %g", lag, expected);
        }
}

int main(void)
{
    test_point_implicit_convection();
    test_distributor();
    test_hydrostatic();
    test_plug_flow();
    test_volume_conservation();
    test_poiseuille();
    return bdl_test_summary("test_gas");
}
