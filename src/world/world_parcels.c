// bedlam — a world of parcels: the gas, its coupling and the parcel solver, one gas step per
// step (src/parcels/parcels.h has the scheme).
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "cfd/gas.h"
#include "couple/coupling.h"
#include "parcels/parcels.h"
#include "world/world.h"

bdl_result bdl_world_parcels_init(bdl_world *w, bdl_scene_error *err)
{
    bdl_result r = bdl_world_gas_init(w, err);
    if (r != BDL_OK)
        return r;
    w->parcels = calloc(1, sizeof *w->parcels);
    if (!w->parcels || bdl_parcels_init(w->parcels, &w->scene.parcels.def, w->gas) != BDL_OK) {
        snprintf(err->message, sizeof err->message, "%s: [parcels]: out of memory", w->scene.path);
        return BDL_ERR_NOMEM;
    }
    // No contacts: empty lists and no coordination, for what reads them (outputs, checkpoints).
    const long n = w->particles.capacity;
    w->coordination = calloc((size_t)(n > 0 ? n : 1), 1);
    w->coordination_capacity = n;
    if (!w->coordination || bdl_neighbor_none(&w->neighbor, n) != BDL_OK)
        return BDL_ERR_NOMEM;
    const bdl_gas_scene *gs = &w->scene.gas;
    w->dt = w->scene.dt > 0.0
                ? w->scene.dt
                : bdl_world_expected_gas_dt(w, fmax(gs->inlet_velocity, gs->jet_velocity));
    w->gas_fixed = 1;
    w->gas_every = w->gas_every_max = 1;
    w->gas_next = 0;
    w->budget.dt = w->dt;
    w->budget.steps = w->scene.end_time / w->dt;
    return bdl_budget_check_steps(w, w->dt, err);
}

double bdl_world_parcels_stable_dt(const bdl_world *w)
{
    const bdl_grid *g = &w->gas->grid;
    const bdl_gas_scene *gs = &w->scene.gas;
    const double u =
        fmax(gs->inlet_velocity, gs->jet_velocity) / (1.0 - w->scene.parcels.def.close_packing);
    double hmin = INFINITY;
    for (int a = 0; a < 3; ++a)
        if (g->n[a] > 1)
            hmin = fmin(hmin, g->h[a]);
    const double cfl = u > 0.0 && isfinite(hmin) ? 0.5 * hmin / u : INFINITY;
    return fmin(cfl, bdl_gas_stable_dt(w->gas));
}

void bdl_world_parcels_free(bdl_world *w)
{
    if (w->parcels)
        bdl_parcels_free(w->parcels);
    free(w->parcels);
    w->parcels = NULL;
}

bdl_result bdl_world_parcels_step(bdl_world *w)
{
    const bdl_parcels_step_def def = {.dt = w->dt,
                                      .first = w->gas_steps == 0,
                                      .gravity = bdl_world_gravity(w, w->time + 0.5 * w->dt)};
    const double gravity[3] = {def.gravity.x, def.gravity.y, def.gravity.z};
    bdl_gas_set_gravity(w->gas, gravity);
    if (w->scene.gas.sweep != BDL_SWEEP_NONE || w->gas_inflow_raised)
        bdl_gas_set_inflow(w->gas, bdl_world_inlet_velocity(w, w->time),
                           w->live.inlet_scale * w->scene.gas.jet_velocity);
    w->gas_inflow_raised = 0;
    w->coupling->parallel_min = w->parallel_min;
    bdl_parcels_report report;
    bdl_result r = bdl_parcels_step(w->parcels, w->coupling, w->gas, &w->particles, &def, &report);
    w->gas_seconds += report.gas_seconds;
    w->coupling_seconds += report.parcel_seconds;
    w->removed += report.removed;
    w->removed_mass += report.removed_mass;
    w->parcels_held += report.held;
    w->max_solids = report.max_solids;
    if (report.stable_dt > 0.0)
        w->gas_stable = report.stable_dt;
    if (r == BDL_ERR_UNSTABLE && report.stable_dt > 0.0)
        snprintf(w->failure, sizeof w->failure,
                 "parcel step at t = %.6g s (step %ld): the step %.3g s is above twice the gas's "
                 "stable limit %.3g s (CFL 1 or the viscous limit); set [run] dt to %.3g s or less",
                 w->time, w->step, w->dt, report.stable_dt, report.stable_dt);
    else if (r == BDL_ERR_UNSTABLE)
        snprintf(w->failure, sizeof w->failure,
                 "parcel step at t = %.6g s (step %ld) failed: the pressure solver did not "
                 "converge (residual %.3g after %d iterations) or a velocity is not finite; try a "
                 "smaller [run] dt",
                 w->time, w->step, w->gas->last_solve.residual, w->gas->last_solve.iterations);
    if (r != BDL_OK)
        return r;
    for (int a = 0; a < 3; ++a) {
        w->particle_drag[a] = report.particle_drag[a];
        w->gas_drag[a] = report.gas_drag[a];
    }
    w->gas_steps++;
    w->gas_next = w->step + 1;
    w->step++;
    w->time += w->dt;
    return BDL_OK;
}
