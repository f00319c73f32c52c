// Minimum fluidization velocity from a velocity sweep, as in the laboratory: fluidize a bed, lower
// the gas velocity step by step, and find where the packed-bed pressure drop (Ergun's a U + b U^2
// at low velocity) meets the bed's weight. (The narrow periodic column slugs when fluidized, so
// the pressure drop above U_mf fluctuates by tens of per cent; the packed branch does not.)
// Compared with Wen & Yu (1966), Re_mf = sqrt(33.7^2 + 0.0408 Ar) - 33.7, for the same beads.
#include <math.h>
#include <stdio.h>

#include "cfd/gas.h"
#include "check.h"
#include "scene_util.h"
#include "sim/diagnostics.h"
#include "sim/loop.h"

static double mean_pressure_drop(bdl_world *w, double duration)
{
    double sum = 0.0, end = w->time + duration, start = w->time + 0.5 * duration;
    int n = 0;
    long seen = -1;
    while (w->time < end) {
        if (bdl_world_step(w) != BDL_OK) {
            CHECK_MSG(0, "step failed at t = %g", w->time);
            return 0.0;
        }
        if (w->time > start && w->gas_steps != seen) { // just after a gas step
            seen = w->gas_steps;
            bdl_diagnostics d;
            bdl_diagnostics_compute(w, 0.0, &d);
            sum += d.pressure_drop;
            ++n;
        }
    }
    return n > 0 ? sum / n : 0.0;
}

/// One sweep through the velocities u[0..n-1]: the mean pressure drop at each; then Ergun's form
/// a U + b U^2 fitted (least squares) to the four points of the packed branch (the four lowest
/// velocities, where the bed is surely fixed), and U_mf where it reaches the bed's weight.
static double sweep(bdl_world *w, const char *name, const double *u, int n, double U0,
                    double target, double gas_column)
{
    double dp[16];
    printf("   %s sweep: U [m/s]   pressure drop / bed weight\n", name);
    for (int k = 0; k < n; ++k) {
        bdl_world_set_parameter(w, "gas.inlet_scale", u[k] / U0);
        dp[k] = mean_pressure_drop(w, 0.08) - gas_column;
        printf("      %.2f      %.3f\n", u[k], dp[k] / target);
    }
    int low[4], count = 0; // the four lowest velocities
    for (int pass = 0; pass < 4; ++pass) {
        int best = -1;
        for (int k = 0; k < n; ++k) {
            int used = 0;
            for (int m = 0; m < count; ++m)
                used |= low[m] == k;
            if (!used && (best < 0 || u[k] < u[best]))
                best = k;
        }
        low[count++] = best;
    }
    double s11 = 0, s12 = 0, s22 = 0, r1 = 0, r2 = 0;
    for (int m = 0; m < 4; ++m) {
        double x = u[low[m]], y = dp[low[m]];
        s11 += x * x, s12 += x * x * x, s22 += x * x * x * x;
        r1 += x * y, r2 += x * x * y;
    }
    double det = s11 * s22 - s12 * s12;
    double a = (r1 * s22 - r2 * s12) / det, b = (s11 * r2 - s12 * r1) / det;
    return b > 0.0 ? (-a + sqrt(a * a + 4.0 * b * target)) / (2.0 * b) : target / a;
}

int main(void)
{
    const double d = 0.002, rho = 1.2, rho_p = 2500.0, mu = 1.8e-5, U0 = 1.5;
    bdl_world *w = bdl_test_world(
        "[run]\nend_time = 10\ndt_fraction = 0.05\ngravity = 0 0 -9.81\nseed = 5\n"
        "[domain]\nmin = 0 0 0\nmax = 0.02 0.02 0.12\nperiodic = x y\n"
        "[contact]\nlaw = linear\n"
        "[species glass]\ndiameter = 0.002\ndensity = 2500\nstiffness = 1000\n"
        "restitution = 0.3\nfriction = 0.5\n"
        "[wall floor]\ntype = plane\npoint = 0 0 0\nnormal = 0 0 1\n"
        "[create bed]\ntype = random\nspecies = glass\ncount = 1400\nregion_min = 0 0 0\n"
        "region_max = 0.02 0.02 0.075\n"
        "[gas]\ncells = 5 5 30\nzmin = inlet\nzmax = outlet\ninlet_velocity = %g\n"
        "[coupling]\ndrag = gidaspow\n",
        U0);
    CHECK(w != NULL && w->gas != NULL);
    if (!w)
        return bdl_test_summary("test_umf");
    double mass = 0.0;
    for (long i = 0; i < w->particles.count; ++i)
        mass += 1.0 / w->particles.inv_mass[i];
    // The bed's weight per area, less buoyancy, plus the gas column's own weight.
    const double weight = mass * (1.0 - rho / rho_p) * 9.81 / (0.02 * 0.02) + rho * 9.81 * 0.12;
    const double gas_column = rho * 9.81 * 0.12;
    mean_pressure_drop(w, 0.25); // fluidize
    const double target = weight - gas_column;
    double ar = rho * (rho_p - rho) * 9.81 * d * d * d / (mu * mu);
    double wen_yu = (sqrt(33.7 * 33.7 + 0.0408 * ar) - 33.7) * mu / (rho * d);
    // Down from the fluidized bed, then back up through the packed bed it settled into.
    const double down[] = {1.4, 1.3, 1.2, 1.1, 1.0, 0.9, 0.8, 0.6, 0.4};
    const double up[] = {0.4, 0.6, 0.8, 0.9, 1.0, 1.1, 1.2, 1.3, 1.4};
    double umf_down = sweep(w, "decreasing", down, 9, U0, target, gas_column);
    double umf_up = sweep(w, "increasing", up, 9, U0, target, gas_column);
    printf("U_mf from the decreasing sweep %.3f m/s (%+.1f %%), from the increasing sweep %.3f m/s "
           "(%+.1f %%); Wen-Yu %.3f m/s\n",
           umf_down, 100.0 * (umf_down / wen_yu - 1.0), umf_up, 100.0 * (umf_up / wen_yu - 1.0),
           wen_yu);
    CHECK_MSG(fabs(umf_down / wen_yu - 1.0) < 0.1, "U_mf down %g vs Wen-Yu %g", umf_down, wen_yu);
    CHECK_MSG(fabs(umf_up / wen_yu - 1.0) < 0.1, "U_mf up %g vs Wen-Yu %g", umf_up, wen_yu);
    bdl_world_destroy(w);
    return bdl_test_summary("test_umf");
}
