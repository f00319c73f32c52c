// bedlam — the gas in the world: built from [gas] and [coupling], advanced every gas_every
// particle steps; between gas steps each particle carries the gas's force as a constant
// acceleration (src/couple/coupling.h has the scheme).
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cfd/gas.h"
#include "core/comm.h"
#include "core/timer.h"
#include "couple/coupling.h"
#include "world/world.h"

/// The longest automatic gas step [s].
#define BDL_GAS_DT_MAX 5e-4

/// Whole particle steps in a time span (a span that is a whole number of steps up to round-off
/// counts as that number).
static long steps_in(const bdl_world *w, double span)
{
    const double steps = floor(span / w->dt * (1.0 + 1e-12));
    return !(steps > 0.0) ? 0 : steps < 1e15 ? (long)steps : (long)1e15; // defined for any span
}

/// The gas of the scene's [gas] section on the domain's grid, at rest.
static bdl_gas_def gas_def(bdl_world *w)
{
    const bdl_scene *s = &w->scene;
    const bdl_gas_scene *gs = &s->gas;
    bdl_gas_def d = bdl_default_gas_def();
    for (int a = 0; a < 3; ++a) {
        d.n[a] = (int)bdl_v3_comp(gs->cells, a);
        d.lo[a] = bdl_v3_comp(s->domain_min, a);
        d.hi[a] = bdl_v3_comp(s->domain_max, a);
        d.gravity[a] = bdl_v3_comp(s->gravity, a);
        for (int side = 0; side < 2; ++side) {
            bdl_gas_side *sd = &d.side[2 * a + side];
            sd->type = s->periodic[a] ? BDL_SIDE_PERIODIC : gs->side[2 * a + side];
            w->outflow[2 * a + side] = sd->type == BDL_SIDE_OUTLET;
            sd->inflow = gs->inlet_velocity;
            sd->pressure = gs->outlet_pressure;
            sd->resistance = sd->type == BDL_SIDE_INLET ? gs->distributor_resistance : 0.0;
            if (gs->jet_velocity > 0.0 && gs->has_jet_min && gs->has_jet_max) {
                sd->jet = 1;
                sd->jet_inflow = gs->jet_velocity;
                for (int b = 0; b < 3; ++b) {
                    sd->jet_lo[b] = bdl_v3_comp(gs->jet_min, b);
                    sd->jet_hi[b] = bdl_v3_comp(gs->jet_max, b);
                }
            }
        }
    }
    d.density = gs->density;
    d.viscosity = gs->viscosity;
    d.convection = gs->convection;
    d.convection_step = gs->convection_step;
    d.tolerance = gs->tolerance;
    d.pressure_solver = gs->pressure_solver;
    d.pressure_share = s->parcels.enabled || s->solids.enabled; // their elimination's hooks
    return d;
}

/// The [coupling] section on the gas's grid (a kernel width of 0 keeps the default).
static bdl_coupling_def coupling_def(const bdl_world *w)
{
    const bdl_coupling_scene *cs = &w->scene.coupling;
    bdl_coupling_def d = bdl_default_coupling_def(&w->gas->grid);
    d.drag = cs->drag;
    d.drag_params = (bdl_drag_params){cs->syamlal_c, cs->syamlal_d};
    if (cs->kernel_width > 0.0)
        d.kernel_width = cs->kernel_width;
    else if (w->scene.parcels.enabled) // the seed's trilinear kernel: a tent one cell wide
        d.kernel_width = 0.0;
    if (w->scene.parcels.enabled) // parcels deposit in chunks, in parallel
        d.chunk = BDL_COUPLING_CHUNK;
    d.max_solids = cs->max_solids;
    d.mean_drag = cs->drag_velocity;
    if (w->scene.solids.enabled) // the packing the gas's expected step flows through
        d.max_solids = w->scene.solids.def.eps_star;
    return d;
}

/// CFL 1/2 for the fastest gas to expect at a superficial inflow u (the larger of the inlet's and
/// the jet's): u through the densest packing, plus a margin for bubbles, across the axes the gas
/// can move along (more than one cell); at most BDL_GAS_DT_MAX and the gas's own stable step.
double bdl_world_expected_gas_dt(const bdl_world *w, double inflow)
{
    const bdl_grid *g = &w->gas->grid;
    const double u = inflow / (1.0 - w->coupling->def.max_solids) + 0.5;
    double hmin = INFINITY, hany = INFINITY;
    for (int a = 0; a < 3; ++a) {
        hany = fmin(hany, g->h[a]);
        if (g->n[a] > 1)
            hmin = fmin(hmin, g->h[a]);
    }
    if (isinf(hmin))
        hmin = hany;
    return fmin(fmin(BDL_GAS_DT_MAX, 0.5 * hmin / u), bdl_gas_stable_dt(w->gas));
}

double bdl_world_inflow_gas_dt(const bdl_world *w)
{
    const bdl_gas_scene *gs = &w->scene.gas;
    return bdl_world_expected_gas_dt(w, fmax(gs->inlet_velocity, gs->jet_velocity));
}

/// The first gas step: as given, or expected_gas_dt for the scene's inflow; after the first, CFL
/// 1/2 for the gas as it is.
static void schedule_gas(bdl_world *w)
{
    const bdl_gas_scene *gs = &w->scene.gas;
    double dt_gas = gs->dt;
    w->gas_fixed = dt_gas > 0.0;
    if (!w->gas_fixed)
        dt_gas = bdl_world_inflow_gas_dt(w);
    w->gas_every = steps_in(w, dt_gas);
    if (w->gas_every < 1)
        w->gas_every = 1;
    w->gas_every_max = w->gas_fixed ? w->gas_every : steps_in(w, BDL_GAS_DT_MAX);
    if (w->gas_every_max < 1)
        w->gas_every_max = 1;
    w->gas_next = 0;
}

bdl_result bdl_world_gas_init(bdl_world *w, bdl_scene_error *err)
{
    const bdl_gas_def gd = gas_def(w);
    if (bdl_gas_create(&gd, &w->gas) != BDL_OK) {
        snprintf(err->message, sizeof err->message, "%s: [gas]: cannot allocate the gas grid",
                 w->scene.path);
        return BDL_ERR_NOMEM;
    }
    w->coupling = calloc(1, sizeof *w->coupling);
    if (!w->coupling)
        return BDL_ERR_NOMEM;
    const bdl_coupling_def cd = coupling_def(w);
    if (bdl_coupling_init(w->coupling, &cd, w->gas) != BDL_OK) {
        snprintf(err->message, sizeof err->message, "%s: [coupling]: out of memory", w->scene.path);
        return BDL_ERR_NOMEM;
    }
    schedule_gas(w);
    return BDL_OK;
}

void bdl_world_gas_free(bdl_world *w)
{
    if (w->coupling)
        bdl_coupling_free(w->coupling);
    free(w->coupling);
    bdl_gas_destroy(w->gas);
    w->gas = NULL;
    w->coupling = NULL;
}

double bdl_world_inlet_velocity(const bdl_world *w, double t)
{
    const bdl_gas_scene *g = &w->scene.gas;
    double u = g->inlet_velocity;
    if (g->sweep != BDL_SWEEP_NONE && t >= g->sweep_start) {
        // Stages from inlet_velocity towards sweep_to (and back for up_down), sweep_step apart.
        const long stages = lround(fabs(g->sweep_to - u) / g->sweep_step);
        const double sign = g->sweep_to >= u ? 1.0 : -1.0;
        const double stage = floor((t - g->sweep_start) / g->sweep_dwell + 1e-9);
        long k = stage < 2.0 * stages + 1.0 ? (long)stage : 2 * stages + 1; // after the sweep
        if (g->sweep == BDL_SWEEP_UP_DOWN) // out and back, then hold at the start
            k = k <= stages ? k : k <= 2 * stages ? 2 * stages - k : 0;
        else if (k > stages)
            k = stages;
        u = k == stages ? g->sweep_to : u + sign * g->sweep_step * (double)k;
    }
    return w->live.inlet_scale * u;
}

double bdl_world_gas_work_pending(const bdl_world *w, long i)
{
    if (!w->gas || w->gas_steps == 0)
        return 0.0;
    return bdl_coupling_work(&w->particles, i,
                             (double)(w->step - (w->gas_next - w->gas_every)) * w->dt);
}

/// The inflow now (the larger of the inlet's and the jet's) if it rose since the last gas step
/// started `dt_last` ago — a sweep's next stage, or a live raise of the inlet scale — else 0: the
/// gas as the last step left it does not yet flow that fast, so its stable step would be too long.
static double raised_inflow(bdl_world *w, double dt_last)
{
    const double jet = w->live.inlet_scale * w->scene.gas.jet_velocity;
    const double now = fmax(bdl_world_inlet_velocity(w, w->time), jet);
    const double before = fmax(bdl_world_inlet_velocity(w, w->time - dt_last), jet);
    const int live = w->gas_inflow_raised;
    w->gas_inflow_raised = 0;
    return live || now > before ? now : 0.0;
}

void bdl_world_gas_failure(bdl_world *w, const char *what, const char *key, double dt,
                           double stable_dt)
{
    if (stable_dt > 0.0)
        snprintf(w->failure, sizeof w->failure,
                 "%s at t = %.6g s (step %ld): the %s %.3g s is above twice the stable limit %.3g "
                 "s (CFL 1 or the viscous limit); set %s to %.3g s or less",
                 what, w->time, w->step, what, dt, stable_dt, key, stable_dt);
    else
        snprintf(
            w->failure, sizeof w->failure,
            "%s at t = %.6g s (step %ld) failed: the pressure solver did not converge "
            "(residual %.3g after %d iterations) or a velocity is not finite; try a smaller %s",
            what, w->time, w->step, w->gas->last_solve.residual, w->gas->last_solve.iterations,
            key);
}

bdl_result bdl_world_gas_step(bdl_world *w)
{
    // The last gas step's length, then this one's: CFL 1/2 for the gas as the last step left it.
    const double dt_last = (double)w->gas_every * w->dt;
    // Before the first, the scheduled step (bounded anew if the inlet scale rose before it).
    const double raised = w->gas_fixed ? 0.0 : raised_inflow(w, w->gas_steps > 0 ? dt_last : 0.0);
    if (!w->gas_fixed && (w->gas_steps > 0 || raised > 0.0)) {
        const double stable = w->gas_steps > 0 ? w->gas_stable : dt_last;
        const long every =
            steps_in(w, raised > 0.0 ? fmin(stable, bdl_world_expected_gas_dt(w, raised)) : stable);
        w->gas_every = every < 1 ? 1 : every > w->gas_every_max ? w->gas_every_max : every;
    }
    const double dt = (double)w->gas_every * w->dt;
    w->gas_next = w->step + w->gas_every;
    if (w->scene.gas.sweep != BDL_SWEEP_NONE) // the sweep's stage at the start of this gas step
        bdl_gas_set_inflow(w->gas, bdl_world_inlet_velocity(w, w->time),
                           w->live.inlet_scale * w->scene.gas.jet_velocity);
    const bdl_coupling_step_def def = {.dt = dt,
                                       .dt_last = w->gas_steps > 0 ? dt_last : 0.0,
                                       .gravity = bdl_world_gravity(w, w->time + 0.5 * dt)};
    const double gravity[3] = {def.gravity.x, def.gravity.y, def.gravity.z};
    bdl_gas_set_gravity(w->gas, gravity);
    w->coupling->parallel_min = w->parallel_min; // one threshold for all particle loops
    bdl_coupling_report report;
    bdl_result r = bdl_coupling_step(w->coupling, w->gas, &w->particles, &def, &report);
    w->gas_seconds += report.gas_seconds;
    if (w->dist) // the gas is the same on every rank; its schedule must be too
        report.stable_dt = bdl_comm_min(report.stable_dt);
    if (report.stable_dt > 0.0)
        w->gas_stable = report.stable_dt;
    if (r == BDL_ERR_UNSTABLE)
        bdl_world_gas_failure(w, "gas step", "[gas] dt", dt, report.stable_dt);
    if (r != BDL_OK)
        return r;
    w->gas_work += report.work;
    memcpy(w->particle_drag, report.particle_drag, sizeof w->particle_drag);
    memcpy(w->gas_drag, report.gas_drag, sizeof w->gas_drag);
    w->gas_steps++;
    w->coupling_seconds += report.coupling_seconds;
    return BDL_OK;
}

void bdl_world_gas_describe(const bdl_world *w, char *buf, size_t size)
{
    if (!w->gas) {
        snprintf(buf, size, "none (no [gas] section: no grid is allocated)");
        return;
    }
    const bdl_grid *g = &w->gas->grid;
    char conv[64];
    snprintf(conv, sizeof conv, "%s%s", bdl_convection_labels[w->gas->def.convection],
             w->gas->def.convection_step == BDL_CONVECTION_POINT_IMPLICIT ? " point-implicit" : "");
    char plate[160] = "";
    int at = 0;
    if (w->scene.gas.distributor_resistance > 0.0)
        at = snprintf(plate, sizeof plate, "; inlets through a porous plate of %.4g Pa s/m",
                      w->scene.gas.distributor_resistance);
    if (w->gas->def.pressure_solver != BDL_PRESSURE_MGPCG && at >= 0 && at < (int)sizeof plate)
        snprintf(plate + at, sizeof plate - (size_t)at, "; pressure by %s",
                 bdl_pressure_solver_labels[w->gas->def.pressure_solver]);
    if (w->solids) {
        snprintf(buf, size,
                 "%d x %d x %d cells of %.3g x %.3g x %.3g mm, %s convection; one step with the "
                 "solids phase, %.3g s%s",
                 g->n[0], g->n[1], g->n[2], 1e3 * g->h[0], 1e3 * g->h[1], 1e3 * g->h[2], conv,
                 w->dt, plate);
        return;
    }
    if (w->parcels) {
        snprintf(buf, size,
                 "%d x %d x %d cells of %.3g x %.3g x %.3g mm, %s convection; drag %s, kernel "
                 "half-width %.3g mm; one gas step per step of the parcels, %.3g s%s",
                 g->n[0], g->n[1], g->n[2], 1e3 * g->h[0], 1e3 * g->h[1], 1e3 * g->h[2], conv,
                 bdl_drag_law_names[w->coupling->def.drag], 1e3 * w->coupling->width[0], w->dt,
                 plate);
        return;
    }
    snprintf(buf, size,
             "%d x %d x %d cells of %.3g x %.3g x %.3g mm, %s convection; drag %s, kernel "
             "half-width %.3g mm; gas step %.3g s = %ld particle steps%s%s",
             g->n[0], g->n[1], g->n[2], 1e3 * g->h[0], 1e3 * g->h[1], 1e3 * g->h[2], conv,
             bdl_drag_law_names[w->coupling->def.drag], 1e3 * w->coupling->width[0],
             (double)w->gas_every * w->dt, w->gas_every,
             w->gas_fixed ? " (fixed)" : " at first, then CFL 1/2 for the gas as it flows", plate);
}
