// A small pseudo-2D bed fluidized above minimum fluidization: the gas pressure drop carries the
// bed's weight, the gas volume balance holds to the solver's tolerance and the momentum the gas
// gives the particles is the momentum it loses.
#include <math.h>
#include <stdio.h>

#include "cfd/gas.h"
#include "check.h"
#include "scene_util.h"
#include "output/diagnostics.h"
#include "run/loop.h"

int main(void)
{
    bdl_world *w = bdl_test_world(
        "[run]\nend_time = 1\ndt_fraction = 0.05\ngravity = 0 0 -9.81\nseed = 3\n"
        "[domain]\nmin = 0 0 0\nmax = 0.04 0.006 0.12\n"
        "[contact]\nlaw = linear\n"
        "[species glass]\ndiameter = 0.002\ndensity = 2500\nstiffness = 1000\n"
        "restitution = 0.9\nfriction = 0.3\n"
        "[wall box]\ntype = box\nmin = 0 0 0\nmax = 0.04 0.006 0.12\n"
        "[create bed]\ntype = random\nspecies = glass\ncount = 700\nregion_min = 0 0 0\n"
        "region_max = 0.04 0.006 0.05\n"
        "[gas]\ncells = 8 1 24\nymin = slip\nymax = slip\nzmin = inlet\nzmax = outlet\n"
        "inlet_velocity = 1.6\nprobe_low = 0.0025\nprobe_high = 0.1175\n"
        "[coupling]\ndrag = gidaspow\n");
    CHECK(w != NULL && w->gas != NULL);
    if (!w)
        return bdl_test_summary("test_fluidized");
    double mass = 0.0;
    for (long i = 0; i < w->particles.count; ++i)
        mass += 1.0 / w->particles.inv_mass[i];
    const double weight = mass * 9.81 / (0.04 * 0.006); // per unit base area [Pa]
    double dp = 0.0, worst_volume = 0.0, worst_momentum = 0.0, worst_probe = 0.0;
    int samples = 0;
    long seen = -1;
    while (w->time < 0.4) {
        if (bdl_world_step(w) != BDL_OK) {
            CHECK_MSG(0, "step failed at t = %g", w->time);
            break;
        }
        if (w->time > 0.2 && w->gas_steps != seen) { // just after a gas step
            seen = w->gas_steps;
            bdl_diagnostics d;
            bdl_diagnostics_compute(w, 0.0, &d);
            dp += d.pressure_drop;
            worst_volume = fmax(worst_volume, d.gas_volume_imbalance);
            worst_momentum = fmax(worst_momentum, d.momentum_imbalance);
            // Probes at the centres of the lowest and highest cell layers read those layers.
            worst_probe = fmax(worst_probe, fabs(d.probe_pressure_drop - d.pressure_drop));
            ++samples;
        }
    }
    dp /= samples > 0 ? samples : 1;
    printf("bed weight per area %.1f Pa, mean pressure drop %.1f Pa (%.1f %%), gas volume "
           "imbalance <= %.1e, momentum imbalance <= %.1e, %ld gas steps\n",
           weight, dp, 100.0 * (dp / weight - 1.0), worst_volume, worst_momentum, w->gas_steps);
    // Fluidized: the drag carries the bed. The gas column's own weight (1.2 kg/m^3 over 12 cm,
    // 1.4 Pa) and wall friction make up the rest.
    CHECK_MSG(fabs(dp / weight - 1.0) < 0.1, "pressure drop %g vs bed weight %g", dp, weight);
    CHECK(worst_volume < 1e-8);
    CHECK(worst_momentum < 1e-12);
    CHECK_MSG(worst_probe < 1e-9 * weight, "probes off the layers by %g Pa", worst_probe);
    // The viewer's live parameter: a factor on the inlet velocity.
    CHECK(bdl_world_set_parameter(w, "gas.inlet_scale", 0.5) == 1);
    CHECK(w->gas->def.side[4].inflow == 0.8);
    bdl_world_destroy(w);
    return bdl_test_summary("test_fluidized");
}
