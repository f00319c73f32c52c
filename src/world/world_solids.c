// bedlam — a world with a solids phase on the gas grid: the gas and the phase, one step of both
// per step (src/solids/phase.h has the scheme); no particles.
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "cfd/gas.h"
#include "solids/kinetic.h"
#include "solids/phase.h"
#include "world/world.h"

/// The restitution made effective by friction (Jenkins & Zhang), or as it is without friction.
static double effective_restitution(double e, double friction, double beta0)
{
    return friction > 0.0 ? bdl_jenkins_zhang_effective(e, friction, beta0).e_eff : e;
}

/// The phases' definitions (the scene's [phase NAME] sections, or [solids] alone as one phase);
/// returns their count.
static int solids_defs(const bdl_scene *s, bdl_solids_def *defs)
{
    const bdl_solids_scene *so = &s->solids;
    if (so->phase_count == 0) {
        defs[0] = so->def;
        defs[0].restitution =
            effective_restitution(so->def.restitution, so->friction, so->tangential_restitution);
        return 1;
    }
    for (int m = 0; m < so->phase_count; ++m) {
        const bdl_phase_scene *ph = &so->phases[m];
        defs[m] = so->def;
        defs[m].diameter = ph->diameter;
        defs[m].density = ph->density;
        defs[m].restitution =
            effective_restitution(ph->restitution, ph->friction, ph->tangential_restitution);
    }
    return so->phase_count;
}

/// The cells whose centres lie below the bed height hold the scene's solids fraction of each
/// phase.
static void fill_bed(bdl_world *w)
{
    bdl_solids *s = w->solids;
    const bdl_grid *gr = &s->grid;
    const bdl_solids_scene *so = &w->scene.solids;
    for (int m = 0; m < s->count; ++m) {
        const bdl_phase_scene *ph = so->phase_count ? &so->phases[m] : NULL;
        const double fraction = ph ? ph->fraction : so->fraction;
        const double bottom = ph ? ph->bed_bottom : 0.0;
        const double top = ph && ph->bed_top > 0.0 ? ph->bed_top : so->bed_height;
        for (int k = 0; k < gr->n[2]; ++k)
            for (int j = 0; j < gr->n[1]; ++j)
                for (int i = 0; i < gr->n[0]; ++i) {
                    const double z = (k + 0.5) * gr->h[2];
                    if (z >= bottom && z < top)
                        s->phase[m].eps[bdl_grid_index(gr, i, j, k)] = fraction;
                }
    }
    bdl_solids_share_voidage(s, w->gas);
}

bdl_result bdl_world_solids_init(bdl_world *w, bdl_scene_error *err)
{
    bdl_result r = bdl_world_gas_init(w, err);
    if (r != BDL_OK)
        return r;
    bdl_solids_def defs[BDL_SOLIDS_PHASES];
    const int count = solids_defs(&w->scene, defs);
    r = bdl_solids_create_mixture(defs, count, w->gas, &w->solids);
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
    double filled = 0.0; // the bed's largest fraction
    for (long i = 0; i < w->solids->grid.size; ++i)
        filled = fmax(filled, w->solids->eps[i]);
    w->max_solids = w->solids->stats.eps_max = filled;
    w->gas_stable = fmin(bdl_gas_stable_dt(w->gas), bdl_solids_stable_dt(w->solids));
    const double courant = w->scene.solids.courant;
    if (courant > 0.0) { // an adaptive step starts from the gas's expected stable one
        w->gas_stable = fmin(w->gas_stable, bdl_world_inflow_gas_dt(w));
        w->dt = fmin(w->scene.dt, 2.0 * courant * w->gas_stable);
    }
    w->budget.dt = w->dt;
    w->budget.steps = w->scene.end_time / w->dt;
    return bdl_budget_check_steps(w, w->dt, err);
}

void bdl_world_solids_free(bdl_world *w)
{
    bdl_solids_destroy(w->solids);
    w->solids = NULL;
}

/// The adaptive step: the largest at most [run] dt that keeps the Courant number at most
/// [solids] courant (gas_stable is the step of Courant number 1/2), shortened to land on the
/// next row of diagnostics.csv, in two equal steps where one would leave a sliver. Not on the
/// end time: that is not in a checkpoint, and a run stopped early (--until) and resumed must
/// take the steps of one that was not.
static double adaptive_step(const bdl_world *w)
{
    double dt = fmin(w->scene.dt, 2.0 * w->scene.solids.courant * w->gas_stable);
    const double every = w->scene.output.diagnostics_interval;
    if (!(every > 0.0))
        return dt;
    const double next = every * (floor(w->time / every * (1.0 + 1e-12) + 1e-9) + 1.0);
    const double left = next - w->time;
    if (left > 1e-12 * fmax(next, 1.0)) {
        if (dt >= left)
            dt = left;
        else if (dt > 0.5 * left)
            dt = 0.5 * left;
    }
    return dt;
}

/// Sets the gravity (a vibrated container's at mid-step) and the inflow for a step of w->dt.
static void step_conditions(bdl_world *w)
{
    const bdl_vec3 g = bdl_world_gravity(w, w->time + 0.5 * w->dt);
    const double gravity[3] = {g.x, g.y, g.z};
    bdl_gas_set_gravity(w->gas, gravity);
    if (w->scene.gas.sweep != BDL_SWEEP_NONE || w->gas_inflow_raised)
        bdl_gas_set_inflow(w->gas, bdl_world_inlet_velocity(w, w->time),
                           w->live.inlet_scale * w->scene.gas.jet_velocity);
    w->gas_inflow_raised = 0;
}

/// Whether an adaptive step should be taken back: it failed, its plastic correction did not
/// settle, or the state it left asks for less than half of it.
static int retake(const bdl_world *w, bdl_result r, double stable)
{
    return r != BDL_OK || w->solids->stats.unsettled ||
           2.0 * w->scene.solids.courant * stable < 0.5 * w->dt;
}

bdl_result bdl_world_solids_step(bdl_world *w)
{
    const int adaptive = w->scene.solids.courant > 0.0;
    if (adaptive)
        w->dt = adaptive_step(w);
    // The stable step of the state the step starts from (CFL 1/2 for gas and solids; the last
    // step's, or the start's): a step above twice it is not taken.
    if (w->dt > 2.0 * w->gas_stable) {
        bdl_world_gas_failure(w, "solids step", "[run] dt", w->dt, w->gas_stable);
        return BDL_ERR_UNSTABLE;
    }
    if (adaptive && bdl_solids_keep(w->solids, w->gas) != BDL_OK)
        return BDL_ERR_NOMEM;
    bdl_result r;
    double stable;
    for (int attempt = 0;; ++attempt) {
        step_conditions(w);
        r = bdl_solids_step(w->solids, w->gas, w->dt);
        stable = fmin(bdl_gas_stable_dt(w->gas), bdl_solids_stable_dt(w->solids));
        // An adaptive step is retaken at most eight times, each time at most half as long.
        if (!adaptive || attempt == 8 || !retake(w, r, stable))
            break;
        bdl_solids_undo(w->solids, w->gas);
        const double shorter = 2.0 * w->scene.solids.courant * stable;
        w->dt = r == BDL_OK && shorter > 0.0 ? fmin(0.5 * w->dt, shorter) : 0.5 * w->dt;
        w->solids_retakes++;
    }
    if (r != BDL_OK) {
        bdl_world_gas_failure(w, "solids step", "[run] dt", w->dt, 0.0);
        return r;
    }
    w->gas_stable = stable;
    w->max_solids = w->solids->stats.eps_max;
    w->gas_steps++;
    w->gas_next = w->step + 1;
    w->step++;
    w->time += w->dt;
    return BDL_OK;
}

void bdl_world_solids_bed(const bdl_world *w, char *buf, size_t size)
{
    const bdl_solids_scene *so = &w->scene.solids;
    if (so->phase_count == 0) {
        snprintf(buf, size, "a bed %g m tall at a solids fraction of %g", so->bed_height,
                 so->fraction);
        return;
    }
    size_t at = (size_t)snprintf(buf, size, "phases:");
    for (int m = 0; m < so->phase_count && at < size; ++m) {
        const bdl_phase_scene *ph = &so->phases[m];
        at += (size_t)snprintf(buf + at, size - at, "%s %s at %g from %g to %g m", m ? "," : "",
                               ph->name, ph->fraction, ph->bed_bottom,
                               ph->bed_top > 0.0 ? ph->bed_top : so->bed_height);
    }
}

void bdl_world_solids_describe(const bdl_world *w, char *buf, size_t size)
{
    const bdl_solids *s = w->solids;
    const bdl_solids_def *d = &s->def;
    char phases[512] = "";
    size_t at = 0;
    for (int m = 0; m < s->count && at < sizeof phases; ++m) {
        const bdl_solids_def *p = &s->phase[m].def;
        const int rotation = s->count > 1 ? w->scene.solids.phases[m].friction > 0.0
                                          : w->scene.solids.friction > 0.0;
        at += (size_t)snprintf(phases + at, sizeof phases - at,
                               "%s%.4g mm, %.4g kg/m^3, "
                               "restitution %.4g%s",
                               m ? "; " : "", 1e3 * p->diameter, p->density, p->restitution,
                               rotation ? " (Jenkins & Zhang's effective)" : "");
    }
    char pressure[96] = "explicit";
    if (d->kinetic_pressure == BDL_KINETIC_PRESSURE_IMPLICIT && d->wave_weight > 0.0)
        snprintf(pressure, sizeof pressure,
                 "implicit (with the plastic correction; its waves weighted in the step by %.3g)",
                 d->wave_weight);
    else if (d->kinetic_pressure == BDL_KINETIC_PRESSURE_IMPLICIT)
        snprintf(pressure, sizeof pressure, "implicit (with the plastic correction)");
    char between[160] = "";
    if (s->count > 1)
        snprintf(between, sizeof between,
                 ", Syamlal's between phases (C_f %.3g) with Gera's hindrance %.3g s/m^2",
                 d->phase_friction, d->hindrance);
    snprintf(buf, size,
             "solids %s (%s model: %s; drag %s%s; Syamlal's viscous regime, its energy %s, its "
             "pressure %s; Schaeffer's plastic regime from %.3g, A %.3g Pa, n %.3g, %.3g deg, "
             "viscosity at most %.3g Pa s; walls %s, specularity %.3g; step %.3g s)",
             s->count > 1 ? "phases" : "phase", s->count > 1 ? "multi-fluid" : "two-fluid", phases,
             bdl_drag_law_names[d->drag], between,
             d->granular_energy == BDL_GRANULAR_ENERGY_TRANSPORT ? "by its transport equation"
                                                                 : "balanced in each cell",
             pressure, d->eps_star, d->schaeffer_a, d->schaeffer_n, d->friction_angle, d->mu_max,
             d->specularity > 0.0 ? "Johnson & Jackson's" : "free-slip", d->specularity, w->dt);
}
