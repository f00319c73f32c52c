// A 40 m/s jet through the floor of a narrow column entrains beads and carries them out through
// the pressure outlet at the top. Particles that cross an outlet face leave the run: they are
// removed and counted (diagnostics columns particles_out and mass_out), never lost silently and
// never mistaken for a particle escaping a closed container. Asserted: the run passes every guard
// (no NaN, overlaps and energy within bounds) with the stability checks on every 100 steps;
// beads do leave; particles in the column + particles out = particles at the start, and the mass
// likewise to round-off; the energy balance (with the energy carried out booked) stays within the
// guard's bound; the gas volume balance holds to the solver's tolerance.
#include <math.h>
#include <stdio.h>

#include "check.h"
#include "scene_util.h"
#include "output/diagnostics.h"
#include "run/guards.h"

int main(void)
{
    // 1 mm glass beads (U_mf about 0.6 m/s) in a slot 40 mm wide and 4 mm deep, 100 mm tall;
    // walls on the sides and the floor only, the top open to the gas outlet.
    bdl_world *w = bdl_test_world(
        "[run]\nend_time = 1\ndt_fraction = 0.05\ngravity = 0 0 -9.81\nseed = 4\n"
        "[domain]\nmin = 0 0 0\nmax = 0.04 0.004 0.1\n"
        "[contact]\nlaw = linear\nskin = 0.5\n"
        "[species glass]\ndiameter = 0.001\ndensity = 2500\nstiffness = 5000\nrestitution = 0.8\n"
        "friction = 0.3\n"
        "[wall left]\ntype = plane\npoint = 0 0 0\nnormal = 1 0 0\n"
        "[wall right]\ntype = plane\npoint = 0.04 0 0\nnormal = -1 0 0\n"
        "[wall front]\ntype = plane\npoint = 0 0 0\nnormal = 0 1 0\n"
        "[wall back]\ntype = plane\npoint = 0 0.004 0\nnormal = 0 -1 0\n"
        "[wall floor]\ntype = plane\npoint = 0 0 0\nnormal = 0 0 1\n"
        "[create bed]\ntype = lattice\nspecies = glass\ncount = 400\n"
        "region_min = 0.0001 0.0001 0.0001\nregion_max = 0.0399 0.0039 0.03\n"
        "[gas]\ncells = 10 1 25\nxmin = wall\nxmax = wall\nymin = slip\nymax = slip\n"
        "zmin = inlet\nzmax = outlet\ninlet_velocity = 0.3\njet_velocity = 40\n"
        "jet_min = 0.016 0 0\njet_max = 0.024 0.004 0\ntolerance = 1e-8\n"
        "[coupling]\ndrag = gidaspow\n");
    CHECK(w != NULL && w->gas != NULL);
    if (!w || !w->gas)
        return bdl_test_summary("test_jet_outflow");
    const long n0 = w->particles.count;
    double mass0 = 0.0;
    for (long i = 0; i < n0; ++i)
        mass0 += 1.0 / w->particles.inv_mass[i];
    bdl_diagnostics d;
    bdl_diagnostics_compute(w, 0.0, &d);
    bdl_guard_state guard;
    bdl_guards_init(&guard, w, &d);
    const double energy0 = bdl_diagnostics_total_energy(&d);
    char message[1024] = "";
    bdl_result r = BDL_OK;
    double worst_volume = 0.0, max_speed = 0.0, first_out = -1.0;
    while (w->time < 0.25 && r == BDL_OK) {
        r = bdl_world_step(w);
        if (r != BDL_OK || w->step % 100)
            continue;
        bdl_diagnostics_compute(w, energy0, &d);
        r = bdl_guards_check(w, &guard, &d, message, sizeof message);
        worst_volume = fmax(worst_volume, d.gas_volume_imbalance);
        max_speed = fmax(max_speed, d.max_speed);
        if (first_out < 0.0 && d.particles_out > 0)
            first_out = w->time;
    }
    CHECK_MSG(r == BDL_OK, "the run stopped at t = %g: %s", w->time, message);
    bdl_diagnostics_compute(w, energy0, &d);
    double mass = 0.0;
    for (long i = 0; i < w->particles.count; ++i)
        mass += 1.0 / w->particles.inv_mass[i];
    printf("40 m/s jet, %.2f s: %ld of %ld beads left through the outlet (first at %.3f s), "
           "%ld remain; mass in + out - start = %.1e of the start; fastest bead %.1f m/s; "
           "energy balance %.3g J (bound %.3g J); gas volume imbalance <= %.1e\n",
           w->time, d.particles_out, n0, first_out, w->particles.count,
           (mass + d.mass_out - mass0) / mass0, max_speed, d.energy_balance,
           w->scene.guards.energy_growth * (guard.active_max + fabs(w->wall_work) +
                                            fabs(w->gas_work) + fabs(w->removed_energy)),
           worst_volume);
    CHECK_MSG(d.particles_out >= 10, "only %ld beads left", d.particles_out);
    CHECK(w->particles.count + d.particles_out == n0);
    CHECK_MSG(fabs(mass + d.mass_out - mass0) <= 1e-12 * mass0, "mass %g + %g vs %g", mass,
              d.mass_out, mass0);
    CHECK(worst_volume < 1e-6);
    for (long i = 0; i < w->particles.count; ++i) // the rest are all inside the column
        CHECK(w->particles.pos[i].z <= 0.1 && w->particles.pos[i].z >= 0.0);
    bdl_world_destroy(w);
    return bdl_test_summary("test_jet_outflow");
}
