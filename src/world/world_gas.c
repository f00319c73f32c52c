// bedlam — the gas in the world: built from [gas] and [coupling], advanced every gas_every
// particle steps; between gas steps each particle carries the gas's force as a constant
// acceleration (src/couple/coupling.h has the scheme).
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cfd/gas.h"
#include "core/log.h"
#include "core/timer.h"
#include "couple/coupling.h"
#include "world/world.h"

/// The longest automatic gas step [s].
#define BDL_GAS_DT_MAX 5e-4

/// Whole particle steps in a time span (a span that is a whole number of steps up to round-off
/// counts as that number).
static long steps_in(const bdl_world *w, double span)
{
    return (long)floor(span / w->dt * (1.0 + 1e-12));
}

bdl_result bdl_world_gas_init(bdl_world *w, bdl_scene_error *err)
{
    const bdl_scene *s = &w->scene;
    const bdl_gas_scene *gs = &s->gas;
    bdl_gas_def d = {0};
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
    d.tolerance = gs->tolerance;
    d.max_iterations = 200;
    if (bdl_gas_create(&d, &w->gas) != BDL_OK) {
        snprintf(err->message, sizeof err->message, "%s: [gas]: cannot allocate the gas grid",
                 s->path);
        return BDL_ERR_NOMEM;
    }
    w->coupling = calloc(1, sizeof *w->coupling);
    if (!w->coupling)
        return BDL_ERR_NOMEM;
    double hmax = fmax(fmax(w->gas->grid.h[0], w->gas->grid.h[1]), w->gas->grid.h[2]);
    bdl_coupling_def cd = {.drag = s->coupling.drag,
                           .drag_params = {s->coupling.syamlal_c, s->coupling.syamlal_d},
                           .kernel_width = s->coupling.kernel_width > 0.0 ? s->coupling.kernel_width
                                                                          : 1.5 * hmax,
                           .max_solids = s->coupling.max_solids};
    if (bdl_coupling_init(w->coupling, &cd, w->gas) != BDL_OK) {
        snprintf(err->message, sizeof err->message, "%s: [coupling]: out of memory", s->path);
        return BDL_ERR_NOMEM;
    }

    // The gas step: as given, or CFL 1/2 for the fastest gas to expect (the inflow through the
    // densest packing, plus a margin for bubbles) across the axes the gas can move along (more
    // than one cell), at most BDL_GAS_DT_MAX; after the first, CFL 1/2 for the gas as it is.
    double dt_gas = gs->dt;
    w->gas_fixed = dt_gas > 0.0;
    if (!w->gas_fixed) {
        double u = fmax(gs->inlet_velocity, gs->jet_velocity) / (1.0 - cd.max_solids) + 0.5;
        double hmin = INFINITY, hany = INFINITY;
        for (int a = 0; a < 3; ++a) {
            hany = fmin(hany, w->gas->grid.h[a]);
            if (w->gas->grid.n[a] > 1)
                hmin = fmin(hmin, w->gas->grid.h[a]);
        }
        if (isinf(hmin))
            hmin = hany;
        dt_gas = fmin(fmin(BDL_GAS_DT_MAX, 0.5 * hmin / u), bdl_gas_stable_dt(w->gas));
    }
    w->gas_every = steps_in(w, dt_gas);
    if (w->gas_every < 1)
        w->gas_every = 1;
    w->gas_every_max = w->gas_fixed ? w->gas_every : steps_in(w, BDL_GAS_DT_MAX);
    if (w->gas_every_max < 1)
        w->gas_every_max = 1;
    w->gas_next = 0;
    return BDL_OK;
}

void bdl_world_gas_free(bdl_world *w)
{
    if (w->coupling)
        bdl_coupling_free(w->coupling);
    free(w->coupling);
    bdl_gas_destroy(w->gas);
    free(w->gas_buffer);
    w->gas = NULL;
    w->coupling = NULL;
    w->gas_buffer = NULL;
}

/// Along a periodic gravity axis nothing holds the suspension up: a mean pressure gradient equal
/// to the mixture's weight, G = rho_mix g, acts on both phases instead (-eps G per unit volume on
/// the gas, -V G on each particle), as a container's base would; the box then neither falls nor
/// rises as a whole. Returns G (zero when the gravity axis has a boundary), and sets the gas's
/// body force.
static bdl_vec3 periodic_column(bdl_world *w, bdl_vec3 gravity)
{
    bdl_gas *gas = w->gas;
    const bdl_grid *g = &gas->grid;
    const int axis = bdl_v3_major_axis(gravity);
    if (!g->periodic[axis] || bdl_v3_comp(gravity, axis) == 0.0)
        return bdl_v3_zero();
    const double vc = g->h[0] * g->h[1] * g->h[2];
    double mass = 0.0, volume = vc * g->n[0] * g->n[1] * g->n[2];
    for (long i = 0; i < w->particles.count; ++i)
        mass += 1.0 / w->particles.inv_mass[i];
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

double bdl_world_inlet_velocity(const bdl_world *w, double t)
{
    const bdl_gas_scene *g = &w->scene.gas;
    double u = g->inlet_velocity;
    if (g->sweep != 0 && t >= g->sweep_start) {
        // Stages from inlet_velocity towards sweep_to (and back for up_down), sweep_step apart.
        const long stages = lround(fabs(g->sweep_to - u) / g->sweep_step);
        const double sign = g->sweep_to >= u ? 1.0 : -1.0;
        long k = (long)floor((t - g->sweep_start) / g->sweep_dwell + 1e-9);
        if (g->sweep == 3) // up_down: out and back, then hold at the start
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
    const bdl_particles *p = &w->particles;
    const double elapsed = (double)(w->step - (w->gas_next - w->gas_every)) * w->dt;
    // As gas steps book it: trapezoidal in the velocity, the gas's acceleration held.
    return elapsed *
           bdl_v3_dot(p->fluid_accel[i], bdl_v3_scale(bdl_v3_add(p->vel_mark[i], p->vel[i]), 0.5)) /
           p->inv_mass[i];
}

bdl_result bdl_world_gas_step(bdl_world *w)
{
    bdl_particles *p = &w->particles;
    const long n = p->count;
    const double t0 = bdl_wall_seconds();
    // The last gas step's length, then this one's: CFL 1/2 for the gas as the last step left it.
    const double dt_last = (double)w->gas_every * w->dt;
    if (!w->gas_fixed && w->gas_steps > 0) {
        const long every = steps_in(w, w->gas_stable);
        w->gas_every = every < 1 ? 1 : every > w->gas_every_max ? w->gas_every_max : every;
    }
    const double dt = (double)w->gas_every * w->dt;
    w->gas_next = w->step + w->gas_every;
    if (w->scene.gas.sweep != 0) { // the sweep's stage at the start of this gas step
        const double u = bdl_world_inlet_velocity(w, w->time);
        for (int s = 0; s < 6; ++s)
            w->gas->def.side[s].inflow = u;
    }
    const bdl_vec3 gravity = bdl_world_gravity(w, w->time + 0.5 * dt); // mid-step
    for (int a = 0; a < 3; ++a)
        w->gas->def.gravity[a] = bdl_v3_comp(gravity, a);
    if (n * 17 > w->gas_buffer_capacity) {
        long cap = n * 17 + n * 17 / 2 + 64;
        double *b = realloc(w->gas_buffer, (size_t)cap * sizeof(double));
        if (!b)
            return BDL_ERR_NOMEM;
        w->gas_buffer = b;
        w->gas_buffer_capacity = cap;
    }
    double *pos = w->gas_buffer, *vel = pos + 3 * n, *acc = vel + 3 * n, *rad = acc + 3 * n,
           *dens = rad + n;
    // Work of the gas's forces over the last gas step (trapezoidal in the velocity).
    if (w->gas_steps > 0) {
        double work = 0.0;
        for (long i = 0; i < n; ++i)
            work += bdl_v3_dot(p->fluid_accel[i],
                               bdl_v3_scale(bdl_v3_add(p->vel_mark[i], p->vel[i]), 0.5)) /
                    p->inv_mass[i];
        w->gas_work += work * dt_last;
    }
    for (long i = 0; i < n; ++i) {
        double volume = 4.0 / 3.0 * BDL_PI * p->radius[i] * p->radius[i] * p->radius[i];
        // The particle's acceleration other than the drag over the last gas step: contacts,
        // walls, gravity and the gas pressure (before the first, gravity less the buoyancy of a
        // fluid at rest).
        const double density = 1.0 / (p->inv_mass[i] * volume);
        bdl_vec3 other =
            w->gas_steps > 0
                ? bdl_v3_sub(bdl_v3_scale(bdl_v3_sub(p->vel[i], p->vel_mark[i]), 1.0 / dt_last),
                             p->drag_accel[i])
                : bdl_v3_scale(gravity, 1.0 - w->gas->def.density / density);
        for (int a = 0; a < 3; ++a) {
            pos[3 * i + a] = bdl_v3_comp(p->pos[i], a);
            vel[3 * i + a] = bdl_v3_comp(p->vel[i], a);
            acc[3 * i + a] = bdl_v3_comp(other, a);
        }
        rad[i] = p->radius[i];
        dens[i] = density;
    }
    bdl_coupling_particles cp = {n, pos, vel, acc, rad, dens};
    w->coupling->parallel_min = w->parallel_min; // one threshold for all particle loops
    if (bdl_coupling_locate(w->coupling, w->gas, n, pos) != BDL_OK)
        return BDL_ERR_NOMEM;
    bdl_coupling_voidage(w->coupling, w->gas, &cp);
    if (w->gas_steps == 0)
        memcpy(w->gas->eps_old, w->gas->eps, (size_t)w->gas->grid.size * sizeof(double));
    bdl_vec3 mean_gradient = periodic_column(w, gravity);
    bdl_coupling_drag_setup(w->coupling, w->gas, &cp, dt);
    const double t1 = bdl_wall_seconds();
    bdl_result r = bdl_gas_step(w->gas, dt);
    const double t2 = bdl_wall_seconds();
    w->gas_seconds += t2 - t1;
    if (r != BDL_OK) {
        bdl_error("gas step at t = %.6g s failed: the pressure solver did not converge (residual "
                  "%.3g after %d iterations) or a velocity is not finite; try a smaller [gas] dt",
                  w->time, w->gas->last_solve.residual, w->gas->last_solve.iterations);
        return BDL_ERR_UNSTABLE;
    }
    double stable = w->gas_stable = bdl_gas_stable_dt(w->gas);
    if (dt > 2.0 * stable) {
        bdl_error("gas step at t = %.6g s: the gas step %.3g s is above twice the stable limit "
                  "%.3g s (CFL 1 or the viscous limit); set [gas] dt to %.3g s or less",
                  w->time, dt, stable, stable);
        return BDL_ERR_UNSTABLE;
    }
    // Forces for the coming particle steps: drag, then pressure, 3 per particle each.
    double *drag_out = dens + n; // 6 per particle, in the buffer after the particle data
    bdl_coupling_forces(w->coupling, w->gas, &cp, dt, drag_out, drag_out + 3 * n);
    double total[3] = {0, 0, 0};
    for (long i = 0; i < n; ++i) {
        bdl_vec3 f = {drag_out[3 * i] + drag_out[3 * n + 3 * i],
                      drag_out[3 * i + 1] + drag_out[3 * n + 3 * i + 1],
                      drag_out[3 * i + 2] + drag_out[3 * n + 3 * i + 2]};
        for (int a = 0; a < 3; ++a)
            total[a] += drag_out[3 * i + a];
        p->fluid_accel[i] =
            bdl_v3_madd(bdl_v3_scale(f, p->inv_mass[i]), mean_gradient, -1.0 / dens[i]);
        p->drag_accel[i] = bdl_v3_scale(
            (bdl_vec3){drag_out[3 * i], drag_out[3 * i + 1], drag_out[3 * i + 2]}, p->inv_mass[i]);
        p->vel_mark[i] = p->vel[i];
    }
    memcpy(w->particle_drag, total, sizeof total);
    bdl_coupling_gas_drag(w->gas, w->gas_drag);
    w->gas_steps++;
    w->coupling_seconds += (t1 - t0) + (bdl_wall_seconds() - t2);
    return BDL_OK;
}

void bdl_world_gas_describe(const bdl_world *w, char *buf, size_t size)
{
    if (!w->gas) {
        snprintf(buf, size, "none (no [gas] section: no grid is allocated)");
        return;
    }
    const bdl_grid *g = &w->gas->grid;
    snprintf(buf, size,
             "%d x %d x %d cells of %.3g x %.3g x %.3g mm, %s convection; drag %s, kernel "
             "half-width %.3g mm; gas step %.3g s = %ld particle steps%s",
             g->n[0], g->n[1], g->n[2], 1e3 * g->h[0], 1e3 * g->h[1], 1e3 * g->h[2],
             bdl_convection_labels[w->gas->def.convection],
             bdl_drag_law_names[w->coupling->def.drag], 1e3 * w->coupling->width[0],
             (double)w->gas_every * w->dt, w->gas_every,
             w->gas_fixed ? " (fixed)" : " at first, then CFL 1/2 for the gas as it flows");
}
