// Polydispersity with a size ratio of 10: 1000 spheres of 1 mm and 20 of 10 mm fall together into
// a box and settle. The neighbour grid is sized by the large spheres, so each of its cells holds
// many small ones; the run must stay finite, keep overlaps within the guard, and only lose energy.
#include <math.h>
#include <stdio.h>

#include "check.h"
#include "scene_util.h"
#include "output/diagnostics.h"

int main(void)
{
    bdl_world *w = bdl_test_world(
        "[run]\nend_time = 1\ndt_fraction = 0.05\ngravity = 0 0 -9.81\nseed = 9\n"
        "[domain]\nmin = 0 0 0\nmax = 0.04 0.04 0.08\n"
        "[contact]\nlaw = hertz\n"
        "[species fine]\ndiameter = 0.001\ndensity = 2500\nyoungs_modulus = 2e9\n"
        "poisson_ratio = 0.25\nrestitution = 0.5\nfriction = 0.3\n"
        "[species coarse]\ndiameter = 0.01\ndensity = 2500\nyoungs_modulus = 2e9\n"
        "poisson_ratio = 0.25\nrestitution = 0.5\nfriction = 0.3\n"
        "[wall box]\ntype = box\nmin = 0 0 0\nmax = 0.04 0.04 0.08\n"
        "[create big]\ntype = random\nspecies = coarse\ncount = 20\nregion_min = 0 0 0.03\n"
        "region_max = 0.04 0.04 0.08\n"
        "[create small]\ntype = random\nspecies = fine\ncount = 1000\nregion_min = 0 0 0\n"
        "region_max = 0.04 0.04 0.08\n");
    CHECK(w != NULL);
    if (!w)
        return bdl_test_summary("test_size_ratio");
    bdl_diagnostics d;
    bdl_diagnostics_compute(w, 0.0, &d);
    const double e0 = bdl_diagnostics_total_energy(&d);
    double worst_overlap = 0.0, worst_rise = -INFINITY, last = 0.0;
    int finite = 1;
    while (w->time < 0.12) {
        if (bdl_world_step(w) != BDL_OK) {
            CHECK_MSG(0, "step failed at t = %g", w->time);
            break;
        }
        if (w->step % 200)
            continue;
        bdl_diagnostics_compute(w, e0, &d);
        finite = finite && isfinite(d.kinetic_energy) && isfinite(d.energy_balance);
        worst_overlap = fmax(worst_overlap, d.max_overlap_ratio);
        worst_rise = fmax(worst_rise, d.energy_balance - last);
        last = d.energy_balance;
    }
    printf("size ratio 10: %ld steps to %.2f s, largest overlap %.3g of the smaller radius, "
           "%.3g J dissipated, largest rise of the balance between samples %.2e of %.3g J\n",
           w->step, w->time, worst_overlap, -last, worst_rise, fabs(e0));
    CHECK(finite);
    CHECK_MSG(worst_overlap < w->scene.guards.max_overlap, "overlap %g", worst_overlap);
    CHECK_MSG(worst_rise < 1e-5 * fabs(e0), "energy grew by %g J", worst_rise);
    CHECK(last < 0.0);
    bdl_world_destroy(w);
    return bdl_test_summary("test_size_ratio");
}
