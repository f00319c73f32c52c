// A floor vibrating at Gamma = 20 (40 Hz, amplitude 3.1 mm, peak speed 0.78 m/s): the contact
// time the step is chosen from is taken at the impact speed the wall can give, so the bed of 500
// spheres thrown about by it stays finite, its overlaps stay within the guard, and the energy
// balance (energy less the start and the work of the floor) does not grow.
#include <math.h>
#include <stdio.h>

#include "check.h"
#include "scene_util.h"
#include "output/diagnostics.h"

int main(void)
{
    bdl_world *w = bdl_test_world(
        "[run]\nend_time = 1\ndt_fraction = 0.05\ngravity = 0 0 -9.81\nseed = 5\n"
        "[domain]\nmin = 0 0 -0.01\nmax = 0.03 0.03 0.15\n"
        "[contact]\nlaw = hertz\n"
        "[species bead]\ndiameter = 0.002\ndensity = 2500\nyoungs_modulus = 1e8\n"
        "poisson_ratio = 0.25\nrestitution = 0.7\nfriction = 0.3\n"
        "[wall box]\ntype = box\nmin = 0 0 0\nmax = 0.03 0.03 0.14\nmotion = vibrate\n"
        "direction = 0 0 1\nfrequency = 40\ngamma = 20\n"
        "[create bed]\ntype = random\nspecies = bead\ncount = 500\nregion_min = 0 0 0.004\n"
        "region_max = 0.03 0.03 0.03\n");
    CHECK(w != NULL);
    if (!w)
        return bdl_test_summary("test_violent_shaking");
    bdl_diagnostics d;
    bdl_diagnostics_compute(w, 0.0, &d);
    const double e0 = bdl_diagnostics_total_energy(&d);
    double worst_overlap = 0.0, worst_balance = -INFINITY, top_speed = 0.0;
    int finite = 1;
    while (w->time < 0.25) { // ten periods
        if (bdl_world_step(w) != BDL_OK) {
            CHECK_MSG(0, "step failed at t = %g", w->time);
            break;
        }
        if (w->step % 100)
            continue;
        bdl_diagnostics_compute(w, e0, &d);
        finite = finite && isfinite(d.kinetic_energy) && isfinite(d.energy_balance);
        worst_overlap = fmax(worst_overlap, d.max_overlap_ratio);
        worst_balance = fmax(worst_balance, d.energy_balance);
        top_speed = fmax(top_speed, d.max_speed);
    }
    const double scale = fabs(e0) + fabs(w->wall_work);
    printf("Gamma 20: %ld steps to %.2f s (dt %.3g s), top speed %.2f m/s, largest overlap %.3g of "
           "the radius, work of the floor %.3g J, energy balance at most %.2e of %.3g J\n",
           w->step, w->time, w->dt, top_speed, worst_overlap, w->wall_work, worst_balance, scale);
    CHECK(finite);
    CHECK_MSG(worst_overlap < w->scene.guards.max_overlap, "overlap %g", worst_overlap);
    CHECK_MSG(worst_balance < 1e-3 * scale, "energy grew by %g J", worst_balance);
    bdl_world_destroy(w);
    return bdl_test_summary("test_violent_shaking");
}
