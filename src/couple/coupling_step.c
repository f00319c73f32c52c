// bedlam — one gas step with its coupling (the four steps of coupling.h), on the particle store.
#include "couple/coupling.h"
#include "core/comm.h"

#include <string.h>

#include "core/timer.h"

/// Along a periodic gravity axis nothing holds the suspension up: a mean pressure gradient equal
/// to the mixture's weight, G = rho_mix g, acts on both phases instead (-eps G per unit volume on
/// the gas, -V G on each particle), as a container's base would; the box then neither falls nor
/// rises as a whole. Returns G (zero when the gravity axis has a boundary), and sets the gas's
/// body force.
static bdl_vec3 periodic_column(const bdl_coupling *c, bdl_gas *gas, const bdl_particles *p,
                                bdl_vec3 gravity)
{
    const bdl_grid *g = &gas->grid;
    const int axis = bdl_v3_major_axis(gravity);
    if (!g->periodic[axis] || bdl_v3_comp(gravity, axis) == 0.0)
        return bdl_v3_zero();
    const double vc = g->h[0] * g->h[1] * g->h[2];
    double mass = 0.0, volume = vc * g->n[0] * g->n[1] * g->n[2];
    for (long i = 0; i < p->count; ++i)
        mass += 1.0 / p->inv_mass[i];
    if (c->divided) // every rank's particles
        bdl_comm_sum(&mass, 1);
    for (int k = 0; k < g->n[2]; ++k)
        for (int j = 0; j < g->n[1]; ++j)
            for (int i = 0; i < g->n[0]; ++i)
                mass += gas->def.density * gas->eps[bdl_grid_index(g, i, j, k)] * vc;
    bdl_vec3 G = bdl_v3_scale(gravity, mass / volume);
    bdl_grid_wrap_cells(g, gas->eps);
    for (int a = 0; a < 3; ++a) {
        const long s = g->stride[a];
        const double ga = bdl_v3_comp(G, a);
        for (long idx = s; idx < g->size; ++idx)
            gas->source[a][idx] = -0.5 * (gas->eps[idx] + gas->eps[idx - s]) * ga;
    }
    return G;
}

/// Work of the gas's forces on particle i over `span` seconds of the current gas step:
/// trapezoidal in the velocity, the gas's acceleration held [J].
static double work_of(const bdl_particles *p, long i, double span)
{
    return span *
           bdl_v3_dot(p->fluid_accel[i], bdl_v3_scale(bdl_v3_add(p->vel_mark[i], p->vel[i]), 0.5)) /
           p->inv_mass[i];
}

double bdl_coupling_work(const bdl_particles *p, long i, double span)
{
    return work_of(p, i, span);
}

/// Each particle's acceleration other than the drag over the last gas step: contacts, walls,
/// gravity and the gas pressure (before the first gas step: gravity less the buoyancy of a gas at
/// rest). The drag set-up and the forces extrapolate the particle's velocity with it.
static void other_acceleration(bdl_coupling *c, const bdl_gas *gas, const bdl_particles *p,
                               const bdl_coupling_step_def *def)
{
    for (long i = 0; i < p->count; ++i) {
        const double volume = bdl_particle_solids_volume(p, i);
        const double density = 1.0 / (p->inv_mass[i] * volume);
        c->accel[i] = def->dt_last > 0.0
                          ? bdl_v3_sub(bdl_v3_scale(bdl_v3_sub(p->vel[i], p->vel_mark[i]),
                                                    1.0 / def->dt_last),
                                       p->drag_accel[i])
                          : bdl_v3_scale(def->gravity, 1.0 - gas->def.density / density);
    }
}

/// The forces of the step as the particles carry them until the next gas step: drag and pressure
/// force as accelerations (with the periodic column's mean gradient), the drag alone, and the
/// velocity they start from. Returns the total drag on the particles in `total`.
static void hand_over(const bdl_coupling *c, bdl_particles *p, bdl_vec3 mean_gradient,
                      double total[3])
{
    total[0] = total[1] = total[2] = 0.0;
    for (long i = 0; i < p->count; ++i) {
        const bdl_vec3 drag = c->drag[i], f = bdl_v3_add(drag, c->pressure[i]);
        total[0] += drag.x;
        total[1] += drag.y;
        total[2] += drag.z;
        const double volume = bdl_particle_solids_volume(p, i);
        const double density = 1.0 / (p->inv_mass[i] * volume);
        p->fluid_accel[i] =
            bdl_v3_madd(bdl_v3_scale(f, p->inv_mass[i]), mean_gradient, -1.0 / density);
        p->drag_accel[i] = bdl_v3_scale(drag, p->inv_mass[i]);
        p->vel_mark[i] = p->vel[i];
    }
}

bdl_result bdl_coupling_step(bdl_coupling *c, bdl_gas *gas, bdl_particles *p,
                             const bdl_coupling_step_def *def, bdl_coupling_report *out)
{
    const double t0 = bdl_wall_seconds(), dt = def->dt;
    *out = (bdl_coupling_report){0};
    if (def->dt_last > 0.0) // the last step's work, before its forces are replaced
        for (long i = 0; i < p->count; ++i)
            out->work += work_of(p, i, 1.0);
    out->work *= def->dt_last;
    if (bdl_coupling_locate(c, gas, p) != BDL_OK)
        return BDL_ERR_NOMEM;
    other_acceleration(c, gas, p, def);
    bdl_coupling_voidage(c, gas, p);
    if (def->dt_last == 0.0) // the first step: the voidage had no earlier value
        memcpy(gas->eps_old, gas->eps, (size_t)gas->grid.size * sizeof(double));
    const bdl_vec3 mean_gradient = periodic_column(c, gas, p, def->gravity);
    bdl_coupling_drag_setup(c, gas, p, c->accel, NULL, dt);
    const double t1 = bdl_wall_seconds();
    bdl_result r = bdl_gas_step(gas, dt);
    const double t2 = bdl_wall_seconds();
    out->gas_seconds = t2 - t1;
    out->stable_dt = r == BDL_OK ? bdl_gas_stable_dt(gas) : 0.0;
    if (r == BDL_OK && dt > 2.0 * out->stable_dt)
        r = BDL_ERR_UNSTABLE; // beyond CFL 1 or the viscous limit: the caller says which
    if (r != BDL_OK)
        return r;
    bdl_coupling_forces(c, gas, p, c->accel, dt, c->drag, c->pressure);
    hand_over(c, p, mean_gradient, out->particle_drag);
    bdl_coupling_gas_drag(gas, gas->u, out->gas_drag);
    out->coupling_seconds = (t1 - t0) + (bdl_wall_seconds() - t2);
    return BDL_OK;
}
