// Hindered settling of a homogeneous suspension (Richardson & Zaki 1954): in a box periodic in
// every direction, the particles' velocity relative to the zero-volume-flux frame against the one
// the drag law implies, v = eps w with K(eps, w) w = eps (rho_p - rho) g, i.e. v / v_t = eps^n
// with n from the drag law (4.65 for Wen-Yu in creeping flow).
#include <math.h>
#include <stdio.h>

#include "cfd/gas.h"
#include "check.h"
#include "couple/drag.h"
#include "scene_util.h"

static const double d = 1e-4, rho_p = 2500.0, rho = 1000.0, mu = 1e-3, g = 9.81;

/// Slip w with K(eps, w) w = eps (rho_p - rho) g (Wen-Yu), by bisection.
static double implied_slip(double eps)
{
    double lo = 0.0, hi = 1.0, target = eps * (rho_p - rho) * g;
    for (int it = 0; it < 200; ++it) {
        double mid = 0.5 * (lo + hi);
        if (bdl_drag_per_volume(BDL_DRAG_WEN_YU, NULL, eps, d, mid, rho, mu) * mid < target)
            lo = mid;
        else
            hi = mid;
    }
    return 0.5 * (lo + hi);
}

static void suspension(double phi)
{
    const double side = 10 * d, height = 20 * d;
    long count = lrint(phi * side * side * height / (BDL_PI / 6.0 * d * d * d));
    bdl_world *w = bdl_test_world(
        "[run]\nend_time = 1\ndt_fraction = 0.05\ngravity = 0 0 -9.81\nseed = 11\n"
        "[domain]\nmin = 0 0 0\nmax = %g %g %g\nperiodic = x y z\n"
        "[contact]\nlaw = linear\n"
        "[species glass]\ndiameter = %g\ndensity = 2500\nstiffness = 0.01\nrestitution = 0.5\n"
        "friction = 0\n"
        "[create cloud]\ntype = random\nspecies = glass\ncount = %ld\nregion_min = 0 0 0\n"
        "region_max = %g %g %g\n"
        "[gas]\ndensity = 1000\nviscosity = 1e-3\ncells = 4 4 8\n"
        "[coupling]\ndrag = wen_yu\n",
        side, side, height, d, count, side, side, height);
    CHECK(w != NULL && w->gas != NULL);
    if (!w)
        return;
    const bdl_grid *gr = &w->gas->grid;
    double sum = 0.0;
    int samples = 0;
    while (w->time < 0.06) {
        if (bdl_world_step(w) != BDL_OK) {
            CHECK_MSG(0, "step failed at t = %g", w->time);
            break;
        }
        if (w->time < 0.03)
            continue;
        // Particle velocity relative to the volume flux of the mixture.
        double vp = 0.0, vol_p = 0.0, flux = 0.0;
        for (long i = 0; i < w->particles.count; ++i) {
            double v = BDL_PI / 6.0 * d * d * d;
            vp += v * w->particles.vel[i].z;
            vol_p += v;
        }
        for (int k = 0; k < gr->n[2]; ++k)
            for (int j = 0; j < gr->n[1]; ++j)
                for (int i = 0; i < gr->n[0]; ++i) {
                    long idx = bdl_grid_index(gr, i, j, k);
                    double eps = 0.5 * (w->gas->eps[idx] + w->gas->eps[idx - gr->stride[2]]);
                    flux += eps * w->gas->u[2][idx] * gr->h[0] * gr->h[1] * gr->h[2];
                }
        double volume = side * side * height;
        double j_mix = (vp + flux) / volume;
        sum += vp / vol_p - j_mix;
        ++samples;
    }
    double measured = -sum / samples, eps = 1.0 - phi;
    double expected = eps * implied_slip(eps), vt = implied_slip(1.0);
    double n = log(expected / vt) / log(eps);
    printf("phi %.2f: settling %.5g m/s, drag law %.5g m/s (%+.2f %%); v_t %.4g m/s, "
           "Re_t %.2f, n = %.2f\n",
           phi, measured, expected, 100.0 * (measured / expected - 1.0), vt, rho * vt * d / mu, n);
    CHECK_MSG(fabs(measured / expected - 1.0) < 0.05, "phi %g: %g vs %g", phi, measured, expected);
    bdl_world_destroy(w);
}

int main(void)
{
    suspension(0.1);
    suspension(0.2);
    suspension(0.3);
    return bdl_test_summary("test_settling");
}
