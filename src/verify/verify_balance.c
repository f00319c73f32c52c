// bedlam — the particle momentum balance of a slugging bed (bedlam verify bed_balance).
#include <math.h>

#include "cfd/gas.h"
#include "verify/verify.h"

/// The pseudo-2D slot of scenes/fluidized_bed.ini (800 beads of 3 mm, 8 x 1 x 33 cells of 7.5 mm,
/// air at 3.2 m/s), its floor at the inlet or `raised` cells above it.
static bdl_world *slot_bed(int raised)
{
    const double floor = raised * 0.25 / 33.0;
    return bdl_verify_world(
        "[run]\nend_time = 100\ndt_fraction = 0.05\ngravity = 0 0 -9.81\n"
        "[domain]\nmin = 0 0 0\nmax = 0.06 0.0045 0.25\n"
        "[contact]\nskin = 0.3\nlaw = linear\n"
        "[species glass]\ndiameter = 0.003\ndensity = 2500\nstiffness = 300\nrestitution = 0.9\n"
        "friction = 0.3\n"
        "[wall slot]\ntype = box\nmin = 0 0 %.17g\nmax = 0.06 0.0045 0.25\n"
        "[create bed]\ntype = lattice\nspecies = glass\ncount = 800\n"
        "region_min = 0.0001 0.0001 %.17g\nregion_max = 0.0599 0.0044 %.17g\n"
        "velocity_jitter = 0.05\n"
        "[gas]\ncells = 8 1 33\nxmin = wall\nxmax = wall\nymin = slip\nymax = slip\n"
        "zmin = inlet\nzmax = outlet\ninlet_velocity = 3.2\ntolerance = 1e-6\n"
        "[coupling]\ndrag = gidaspow\n",
        floor, floor + 0.0001, floor + 0.2);
}

/// Sum of the particles' vertical momentum [kg m/s].
static double momentum_z(const bdl_particles *p)
{
    double sum = 0.0;
    for (long i = 0; i < p->count; ++i)
        sum += p->vel[i].z / p->inv_mass[i];
    return sum;
}

/// Vertical force of the gas on the particles, drag and pressure, less their buoyancy in a gas at
/// rest (rho g V each) [N].
static double fluid_force_z(const bdl_particles *p, double rho, double grav)
{
    double sum = 0.0;
    for (long i = 0; i < p->count; ++i)
        sum += p->fluid_accel[i].z / p->inv_mass[i] - rho * grav * bdl_particle_volume(p, i);
    return sum;
}

/// The gas's momentum flux into the domain through the inlet less what leaves through the
/// outlet, per base area [Pa], as the inflow U enters the lowest layer at its interstitial speed
/// U/eps and leaves the clear top at U: rho U^2 (mean of 1/eps over the lowest layer - 1). For
/// this scene's inlet on the low z side only (side 4; the cells' voidage for the inlet faces').
static double inflow_momentum(const bdl_gas *gas)
{
    const bdl_grid *g = &gas->grid;
    double sum = 0.0;
    for (int j = 0; j < g->n[1]; ++j)
        for (int i = 0; i < g->n[0]; ++i)
            sum += 1.0 / gas->eps[bdl_grid_index(g, i, j, 0)];
    const double u = gas->def.side[4].inflow;
    return gas->def.density * u * u * (sum / (g->n[0] * g->n[1]) - 1.0);
}

/// Vertical force of the walls on the particles this step [N]: the contact forces summed over
/// all particles, in which every pair's action and reaction cancel (no background damping here).
static double wall_force_z(const bdl_particles *p)
{
    double sum = 0.0;
    for (long i = 0; i < p->count; ++i)
        sum += p->load[i].force.z;
    return sum;
}

bdl_result bdl_verify_bed_balance(int raised, double settle, double window, bdl_verify_balance *out)
{
    *out = (bdl_verify_balance){0};
    bdl_world *w = slot_bed(raised);
    if (!w || !w->gas) {
        if (w)
            bdl_world_destroy(w);
        return BDL_ERR_SCENE;
    }
    const bdl_grid *g = &w->gas->grid;
    const int n = g->n[2];
    const double area = g->n[0] * g->h[0] * g->n[1] * g->h[1], grav = 9.81;
    const double rho = w->gas->def.density, column = rho * grav * (n - 1) * g->h[2];
    bdl_result r = BDL_OK;
    while (r == BDL_OK && w->time < settle)
        r = bdl_world_step(w);
    const double m0 = momentum_z(&w->particles), t0 = w->time;
    double pressure = 0.0, wall = 0.0, fluid = 0.0, inflow = 0.0;
    long steps = 0;
    while (r == BDL_OK && w->time < settle + window) {
        r = bdl_world_step(w);
        pressure += bdl_grid_layer_mean(g, w->gas->p, 2, 0) -
                    bdl_grid_layer_mean(g, w->gas->p, 2, n - 1) - column;
        wall += wall_force_z(&w->particles);
        fluid += fluid_force_z(&w->particles, rho, grav);
        inflow += inflow_momentum(w->gas);
        ++steps;
    }
    const bdl_particles *p = &w->particles;
    for (long i = 0; i < p->count; ++i)
        out->weight += (1.0 / p->inv_mass[i] - rho * bdl_particle_volume(p, i)) * grav / area;
    if (r == BDL_OK && steps > 0 && p->count == 800) {
        out->pressure = pressure / (double)steps;
        out->wall = wall / (double)steps / area;
        out->momentum_rate = (momentum_z(p) - m0) / (w->time - t0) / area;
        out->residual = out->pressure - out->weight + out->wall - out->momentum_rate;
        out->fluid = fluid / (double)steps / area;
        out->gas_residual = out->pressure - out->fluid;
        out->inflow_momentum = inflow / (double)steps;
    } else if (r == BDL_OK) {
        r = BDL_ERR_UNSTABLE; // a bead left the slot: the balance does not cover it
    }
    out->steps = w->step;
    bdl_world_destroy(w);
    return r;
}
