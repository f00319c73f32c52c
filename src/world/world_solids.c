// bedlam — a world with a solids phase on the gas grid: the gas and the phase, one step of both
// per step (src/solids/phase.h has the scheme); no particles.
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "cfd/gas.h"
#include "solids/kinetic.h"
#include "solids/phase.h"
#include "world/world.h"

/// The phase's definition with the restitution made effective by friction (Jenkins & Zhang).
static bdl_solids_def solids_def(const bdl_scene *s)
{
    bdl_solids_def d = s->solids.def;
    if (s->solids.friction > 0.0)
        d.restitution = bdl_jenkins_zhang_effective(d.restitution, s->solids.friction,
                                                    s->solids.tangential_restitution)
                            .e_eff;
    return d;
}

/// The cells whose centres lie below the bed height hold the scene's solids fraction.
static void fill_bed(bdl_world *w)
{
    bdl_solids *s = w->solids;
    const bdl_grid *gr = &s->grid;
    for (int k = 0; k < gr->n[2]; ++k)
        for (int j = 0; j < gr->n[1]; ++j)
            for (int i = 0; i < gr->n[0]; ++i)
                if ((k + 0.5) * gr->h[2] < w->scene.solids.bed_height)
                    s->eps[bdl_grid_index(gr, i, j, k)] = w->scene.solids.fraction;
    bdl_solids_share_voidage(s, w->gas);
}

bdl_result bdl_world_solids_init(bdl_world *w, bdl_scene_error *err)
{
    bdl_result r = bdl_world_gas_init(w, err);
    if (r != BDL_OK)
        return r;
    const bdl_solids_def def = solids_def(&w->scene);
    r = bdl_solids_create(&def, w->gas, &w->solids);
    if (r != BDL_OK) {
        snprintf(err->message, sizeof err->message, "%s: [solids]: %s", w->scene.path,
                 r == BDL_ERR_NOMEM ? "out of memory" : "a parameter out of range");
        return r == BDL_ERR_NOMEM ? BDL_ERR_NOMEM : BDL_ERR_SCENE;
    }
    fill_bed(w);
    // No particles: empty lists and no coordination, for what reads them (outputs, checkpoints).
    w->coordination = calloc(1, 1);
    w->coordination_capacity = 0;
    if (!w->coordination || bdl_neighbor_none(&w->neighbor, 0) != BDL_OK)
        return BDL_ERR_NOMEM;
    w->dt = w->scene.dt;
    w->gas_fixed = 1;
    w->gas_every = w->gas_every_max = 1;
    w->gas_next = 0;
    w->max_solids = w->solids->stats.eps_max = w->scene.solids.fraction;
    w->gas_stable = fmin(bdl_gas_stable_dt(w->gas), bdl_solids_stable_dt(w->solids));
    w->budget.dt = w->dt;
    w->budget.steps = w->scene.end_time / w->dt;
    return bdl_budget_check_steps(w, w->dt, err);
}

void bdl_world_solids_free(bdl_world *w)
{
    bdl_solids_destroy(w->solids);
    w->solids = NULL;
}

bdl_result bdl_world_solids_step(bdl_world *w)
{
    const bdl_vec3 g = bdl_world_gravity(w, w->time + 0.5 * w->dt);
    const double gravity[3] = {g.x, g.y, g.z};
    bdl_gas_set_gravity(w->gas, gravity);
    if (w->scene.gas.sweep != BDL_SWEEP_NONE || w->gas_inflow_raised)
        bdl_gas_set_inflow(w->gas, bdl_world_inlet_velocity(w, w->time),
                           w->live.inlet_scale * w->scene.gas.jet_velocity);
    w->gas_inflow_raised = 0;
    // The stable step of the state the step starts from (CFL 1/2 for gas and solids; the last
    // step's, or the start's): a step above twice it is not taken.
    if (w->dt > 2.0 * w->gas_stable) {
        bdl_world_gas_failure(w, "solids step", "[run] dt", w->dt, w->gas_stable);
        return BDL_ERR_UNSTABLE;
    }
    const bdl_result r = bdl_solids_step(w->solids, w->gas, w->dt);
    if (r != BDL_OK) {
        bdl_world_gas_failure(w, "solids step", "[run] dt", w->dt, 0.0);
        return r;
    }
    w->gas_stable = fmin(bdl_gas_stable_dt(w->gas), bdl_solids_stable_dt(w->solids));
    w->max_solids = w->solids->stats.eps_max;
    w->gas_steps++;
    w->gas_next = w->step + 1;
    w->step++;
    w->time += w->dt;
    return BDL_OK;
}

void bdl_world_solids_describe(const bdl_world *w, char *buf, size_t size)
{
    const bdl_solids_def *d = &w->solids->def;
    snprintf(buf, size,
             "solids phase (two-fluid model: %.4g mm, %.4g kg/m^3, restitution %.4g%s; drag %s; "
             "Syamlal's viscous regime, its energy balanced in each cell; Schaeffer's plastic "
             "regime from "
             "%.3g, A %.3g Pa, n %.3g, %.3g deg, viscosity at most %.3g Pa s; step %.3g s)",
             1e3 * d->diameter, d->density, d->restitution,
             w->scene.solids.friction > 0.0 ? " (Jenkins & Zhang's effective)" : "",
             bdl_drag_law_names[d->drag], d->eps_star, d->schaeffer_a, d->schaeffer_n,
             d->friction_angle, d->mu_max, w->dt);
}
