// The restitution limits over long runs: a bed of 500 spheres poured into a box and shaken by its
// floor (Gamma 2, 25 Hz) for 0.25 s, six periods, with e = 0.01 and with e = 1 (frictionless).
// Energy may only leave through the contacts: the energy balance (energy now, less the energy at
// the start and the work the floor did) must fall (e = 0.01) or stay at zero (e = 1) up to the
// time-integration error, and every velocity stays finite.
#include <math.h>
#include <stdio.h>

#include "check.h"
#include "scene_util.h"
#include "output/diagnostics.h"

static void shake(double e, double friction)
{
    bdl_world *w = bdl_test_world(
        "[run]\nend_time = 1\ndt_fraction = 0.05\ngravity = 0 0 -9.81\nseed = 7\n"
        "[domain]\nmin = 0 0 -0.01\nmax = 0.03 0.03 0.1\n"
        "[contact]\nlaw = hertz\n"
        "[species bead]\ndiameter = 0.002\ndensity = 2500\nyoungs_modulus = 1e7\n"
        "poisson_ratio = 0.25\nrestitution = %g\nfriction = %g\n"
        "[wall box]\ntype = box\nmin = 0 0 0\nmax = 0.03 0.03 0.09\nmotion = vibrate\n"
        "direction = 0 0 1\nfrequency = 25\ngamma = 2\n"
        "[create bed]\ntype = random\nspecies = bead\ncount = 500\nregion_min = 0 0 0\n"
        "region_max = 0.03 0.03 0.04\n",
        e, friction);
    CHECK(w != NULL);
    if (!w)
        return;
    bdl_diagnostics d;
    bdl_diagnostics_compute(w, 0.0, &d);
    const double e0 = bdl_diagnostics_total_energy(&d);
    double worst_rise = 0.0, last = 0.0, scale = fabs(e0);
    int finite = 1;
    for (long step = 1; w->time < 0.25; ++step) {
        if (bdl_world_step(w) != BDL_OK) {
            CHECK_MSG(0, "e = %g: step %ld failed", e, step);
            break;
        }
        if (step % 100)
            continue;
        bdl_diagnostics_compute(w, e0, &d);
        finite = finite && isfinite(d.energy_balance) && isfinite(d.kinetic_energy);
        scale = fmax(scale, fabs(w->wall_work));
        if (e < 1.0) // dissipative: the balance only ever falls
            worst_rise = fmax(worst_rise, d.energy_balance - last);
        else // elastic: it stays at zero
            worst_rise = fmax(worst_rise, fabs(d.energy_balance));
        last = d.energy_balance;
    }
    printf("e = %.2f: after %ld steps (%.3f s) the energy balance is %.3e J (work of the floor "
           "%.3e J); "
           "largest %s %.2e of the energy scale\n",
           e, w->step, w->time, last, w->wall_work, e < 1.0 ? "rise between samples" : "deviation",
           worst_rise / scale);
    CHECK(finite);
    // The time integration (of the contacts, and of the floor's work summed step by step) lets
    // the balance tick up between samples by about 1e-6 of the energy scale; growth, not that,
    // is what this catches.
    CHECK_MSG(worst_rise < (e < 1.0 ? 1e-5 : 2e-3) * scale, "e = %g: energy grew by %g of %g", e,
              worst_rise, scale);
    if (e < 1.0)
        CHECK_MSG(last < 0.0, "e = %g: nothing dissipated (%g J)", e, last);
    bdl_world_destroy(w);
}

int main(void)
{
    shake(0.01, 0.5);
    shake(1.0, 0.0);
    return bdl_test_summary("test_restitution_limits");
}
