// Density ratios from 1 (liquid-solid) to 1e4 (gas-solid): a random suspension at 10 % solids in
// a closed box of fluid, settling under gravity. Neutrally buoyant particles must stay at rest
// (buoyancy, from the pressure gradient, balances gravity exactly); heavier ones settle; every
// ratio runs stably (finite, overlaps within the guard, no speed beyond the drag law's terminal
// velocity of a single particle).
#include <math.h>
#include <stdio.h>

#include "check.h"
#include "scene_util.h"
#include "output/diagnostics.h"

static void suspension(double rho_p, double rho, double mu)
{
    const double d = 2e-4;
    const double v_t = fabs(rho_p - rho) * d * d * 9.81 / (18.0 * mu); // Stokes, an upper bound
    bdl_world *w = bdl_test_world(
        "[run]\nend_time = 1\ndt_fraction = 0.05\ngravity = 0 0 -9.81\nseed = 2\n"
        "[domain]\nmin = 0 0 0\nmax = 0.004 0.004 0.008\n"
        "[contact]\nlaw = linear\n"
        "[species p]\ndiameter = %g\ndensity = %g\nstiffness = %g\nrestitution = 0.5\n"
        "friction = 0\n"
        "[wall box]\ntype = box\nmin = 0 0 0\nmax = 0.004 0.004 0.008\n"
        "[create cloud]\ntype = random\nspecies = p\nvolume_fraction = 0.1\nregion_min = 0 0 0\n"
        "region_max = 0.004 0.004 0.008\n"
        "[gas]\ndensity = %g\nviscosity = %g\ncells = 4 4 8\n"
        "[coupling]\ndrag = wen_yu\n",
        d, rho_p, rho_p / 100.0, rho, mu); // springs as stiff as the weight asks
    CHECK(w != NULL && w->gas != NULL);
    if (!w)
        return;
    double top = 0.0, overlap = 0.0;
    int finite = 1;
    for (int step = 0; step < 3000; ++step) {
        if (bdl_world_step(w) != BDL_OK) {
            CHECK_MSG(0, "ratio %g: step failed at t = %g", rho_p / rho, w->time);
            break;
        }
        if (step % 100)
            continue;
        bdl_diagnostics dg;
        bdl_diagnostics_compute(w, 0.0, &dg);
        finite = finite && isfinite(dg.kinetic_energy);
        top = fmax(top, dg.max_speed);
        overlap = fmax(overlap, dg.max_overlap_ratio);
    }
    printf("density ratio %8.3g: %ld particles, %.3g s, fastest particle %.3g m/s (Stokes terminal "
           "velocity %.3g m/s), largest overlap %.3g\n",
           rho_p / rho, w->particles.count, w->time, top, v_t, overlap);
    CHECK(finite);
    CHECK_MSG(overlap < w->scene.guards.max_overlap, "ratio %g: overlap %g", rho_p / rho, overlap);
    if (rho_p == rho)
        CHECK_MSG(top < 1e-9, "neutrally buoyant particles move at %g m/s", top);
    else
        CHECK_MSG(top > 0.0 && top < 1.5 * v_t, "ratio %g: top speed %g vs %g", rho_p / rho, top,
                  v_t);
    bdl_world_destroy(w);
}

int main(void)
{
    suspension(1000.0, 1000.0, 1e-3); // neutrally buoyant, in water
    suspension(2500.0, 1000.0, 1e-3); // glass in water
    suspension(2500.0, 1.2, 1.8e-5);  // glass in air: 2083
    suspension(12000.0, 1.2, 1.8e-5); // a heavy metal in air: 1e4
    return bdl_test_summary("test_density_ratio");
}
