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
    while (w->time < end) {
        if (bdl_world_step(w) != BDL_OK) {
            CHECK_MSG(0, "step failed at t = %g", w->time);
            return 0.0;
        }
        if (w->time > start && w->step % w->gas_every == 1) {
            bdl_diagnostics d;
            bdl_diagnostics_compute(w, 0.0, &d);
            sum += d.pressure_drop;
            ++n;
        }
    }
    return n > 0 ? sum / n : 0.0;
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
    const double sweep[] = {1.4, 1.3, 1.2, 1.1, 1.0, 0.9, 0.8, 0.6, 0.4};
    const int n = (int)(sizeof sweep / sizeof sweep[0]);
    double dp[16];
    printf("   U [m/s]   pressure drop / bed weight\n");
    for (int k = 0; k < n; ++k) {
        bdl_world_set_parameter(w, "gas.inlet_scale", sweep[k] / U0);
        dp[k] = mean_pressure_drop(w, 0.08);
        printf("   %.2f      %.3f\n", sweep[k], (dp[k] - gas_column) / (weight - gas_column));
    }
    // The packed branch: Ergun's form a U + b U^2 fitted (least squares) to the four lowest
    // velocities, where the bed is surely fixed; U_mf where it reaches the bed's weight.
    double s11 = 0, s12 = 0, s22 = 0, r1 = 0, r2 = 0;
    for (int k = n - 4; k < n; ++k) {
        double u = sweep[k], y = dp[k] - gas_column;
        s11 += u * u, s12 += u * u * u, s22 += u * u * u * u;
        r1 += u * y, r2 += u * u * y;
    }
    double det = s11 * s22 - s12 * s12;
    double a = (r1 * s22 - r2 * s12) / det, b = (s11 * r2 - s12 * r1) / det;
    double target = weight - gas_column;
    double umf = b > 0.0 ? (-a + sqrt(a * a + 4.0 * b * target)) / (2.0 * b) : target / a;
    double ar = rho * (rho_p - rho) * 9.81 * d * d * d / (mu * mu);
    double wen_yu = (sqrt(33.7 * 33.7 + 0.0408 * ar) - 33.7) * mu / (rho * d);
    printf("U_mf from the sweep %.3f m/s, Wen-Yu %.3f m/s (%+.1f %%)\n", umf, wen_yu,
           100.0 * (umf / wen_yu - 1.0));
    CHECK_MSG(fabs(umf / wen_yu - 1.0) < 0.1, "U_mf %g vs Wen-Yu %g", umf, wen_yu);
    bdl_world_destroy(w);
    return bdl_test_summary("test_umf");
}
