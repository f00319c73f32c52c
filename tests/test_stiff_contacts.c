// Very stiff contacts: glass (70 GPa) on 100 um spheres, whose contact lasts well under a
// microsecond. At the time-step limit (0.2 of the contact time, [guards] dt_refuse) a dense
// granular gas of 2000 spheres colliding at up to 1 m/s runs stably — velocities finite, energy
// not growing, overlaps bounded — and just above the limit the run is refused with a message
// that names the step and the limit.
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "scene_util.h"
#include "output/diagnostics.h"
#include "run/guards.h"

#define SCENE                                                                                      \
    "[run]\nend_time = 1\ndt = %.17g\ngravity = 0 0 -9.81\nseed = 3\n"                             \
    "[domain]\nmin = 0 0 0\nmax = 0.002 0.002 0.004\n"                                             \
    "[contact]\nlaw = hertz\n"                                                                     \
    "[species glass]\ndiameter = 1e-4\ndensity = 2500\nyoungs_modulus = 7e10\n"                    \
    "poisson_ratio = 0.22\nrestitution = 0.9\nfriction = 0.5\n"                                    \
    "[wall box]\ntype = box\nmin = 0 0 0\nmax = 0.002 0.002 0.004\n"                               \
    "[create bed]\ntype = random\nspecies = glass\ncount = 2000\nregion_min = 0 0 0\n"             \
    "region_max = 0.002 0.002 0.001\nvelocity_jitter = 1\n"

int main(void)
{
    // The contact time the guard uses, from a world at a safe step.
    bdl_world *probe = bdl_test_world(SCENE, 1e-9);
    CHECK(probe != NULL);
    if (!probe)
        return bdl_test_summary("test_stiff_contacts");
    const double tc = probe->contact_time;
    bdl_world_destroy(probe);
    printf("glass, 100 um: contact time %.3g s\n", tc);
    CHECK(tc > 0.0 && tc < 1e-6);

    // Just above the limit: refused, naming the step and the limit.
    char message[512], warning[512];
    bdl_world *above = bdl_test_world(SCENE, 0.21 * tc);
    CHECK(above && bdl_guards_check_dt(above, message, sizeof message, warning, sizeof warning) ==
                       BDL_ERR_SCENE);
    printf("dt = 0.21 t_c: %s\n", message);
    CHECK(strstr(message, "dt") != NULL && strstr(message, "0.2") != NULL);
    bdl_world_destroy(above);

    // At the limit: accepted (with a warning on accuracy) and stable.
    bdl_world *w = bdl_test_world(SCENE, 0.199 * tc);
    CHECK(w && bdl_guards_check_dt(w, message, sizeof message, warning, sizeof warning) == BDL_OK);
    if (!w)
        return bdl_test_summary("test_stiff_contacts");
    printf("dt = 0.199 t_c: accepted; warning: %s\n", warning[0] ? warning : "(none)");
    bdl_diagnostics d;
    bdl_diagnostics_compute(w, 0.0, &d);
    const double e0 = bdl_diagnostics_total_energy(&d);
    double worst_overlap = 0.0, worst_rise = 0.0, contacts = 0.0;
    int finite = 1;
    for (int step = 1; step <= 20000; ++step) {
        if (bdl_world_step(w) != BDL_OK) {
            CHECK_MSG(0, "step %d failed", step);
            break;
        }
        if (step % 200)
            continue;
        bdl_diagnostics_compute(w, e0, &d);
        finite = finite && isfinite(d.kinetic_energy) && isfinite(d.energy_balance);
        worst_overlap = fmax(worst_overlap, d.max_overlap_ratio);
        worst_rise = fmax(worst_rise, d.energy_balance);
        contacts += d.mean_coordination;
    }
    printf("20000 steps (%.3g s): mean coordination %.3f, largest overlap %.3g of the radius, "
           "energy balance at most %.2e of the starting energy (%.3g J dissipated)\n",
           w->time, contacts / 100.0, worst_overlap, worst_rise / fabs(e0), -d.energy_balance);
    // Contacts happened: overlaps seen and energy taken out by the restitution 0.9 damping.
    CHECK_MSG(worst_overlap > 0.0 && d.energy_balance < 0.0, "no contacts to test");
    CHECK(finite);
    CHECK_MSG(worst_overlap < 0.05, "overlap %g of the radius", worst_overlap);
    CHECK_MSG(worst_rise < 1e-3 * fabs(e0), "energy grew by %g of %g J", worst_rise, fabs(e0));
    bdl_world_destroy(w);
    return bdl_test_summary("test_stiff_contacts");
}
