// bedlam — a world of parcels: the gas, its coupling and the parcel solver, one gas step per
// step (src/parcels/parcels.h has the scheme).
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "cfd/gas.h"
#include "couple/coupling.h"
#include "dem/species.h"
#include "parcels/parcels.h"
#include "world/world.h"

/// The solids volume of species s's parcels at diameter d [m^3].
static double parcel_volume_at(const bdl_species_def *s, double d)
{
    return bdl_species_volume(s, d) * bdl_species_parcel_count(s, d);
}

double bdl_world_parcel_mass_min(const bdl_world *w)
{
    double m = INFINITY;
    for (int k = 0; k < w->scene.species_count; ++k) {
        const bdl_species_def *s = &w->scene.species[k];
        if (bdl_species_is_parcel(s))
            m = fmin(m, s->density * parcel_volume_at(s, bdl_species_min_diameter(s)));
    }
    return m;
}

double bdl_world_parcels_collision_dt(const bdl_world *w)
{
    return bdl_parcels_collision_dt(&w->scene.parcels.def, bdl_world_parcel_mass_min(w));
}

void bdl_world_parcels_describe(const bdl_world *w, char *buf, size_t size)
{
    const bdl_parcels_def *d = &w->parcels->def;
    if (d->model == BDL_PARCEL_STRESS) {
        snprintf(buf, size,
                 "parcels (MP-PIC, model A stress P_s theta^beta / max(theta_cs - theta, floor): "
                 "P_s = %g Pa, beta = %g, theta_cs = %g, floor = %g; %d drift part(s) and at "
                 "most %d gas step(s) per step, wall restitution %g)",
                 d->stress_pressure, d->stress_exponent, d->close_packing, d->stress_floor,
                 d->substeps, d->gas_substeps, d->wall_restitution);
        return;
    }
    const bdl_parcel_collision_law *law = &w->parcels->collisions.law;
    snprintf(
        buf, size,
        "parcels (MP-PIC, model B collisions: k_c = %g N/m^%g, eta_c = %.4g kg/s%s, range %g of a "
        "parcel's diameter; %d part(s) and at most %d gas step(s) per step, dt below %.4g s; "
        "packing guard at %g)",
        law->stiffness, law->exponent, law->damping,
        d->collision_damping < 0.0 ? " from the restitution" : "", law->range, d->substeps,
        d->gas_substeps, bdl_world_parcels_collision_dt(w), d->close_packing);
}

/// Model B meets pairs through the nearest image only: a periodic axis must be at least twice
/// the longest reach (1 + range) 2 R_ep long.
static bdl_result check_periodic_reach(const bdl_world *w, bdl_scene_error *err)
{
    const bdl_scene *scene = &w->scene;
    if (scene->parcels.def.model != BDL_PARCEL_COLLISIONS)
        return BDL_OK;
    double r_max = 0.0;
    for (int k = 0; k < scene->species_count; ++k) {
        const bdl_species_def *s = &scene->species[k];
        r_max = fmax(r_max, cbrt(0.75 / BDL_PI * parcel_volume_at(s, bdl_species_max_diameter(s))));
    }
    const double reach = (1.0 + scene->parcels.def.collision_range) * 2.0 * r_max;
    static const char *const axes[3] = {"x", "y", "z"};
    for (int a = 0; a < 3; ++a) {
        const double L = bdl_v3_comp(scene->domain_max, a) - bdl_v3_comp(scene->domain_min, a);
        if (scene->periodic[a] && L < 2.0 * reach) {
            snprintf(err->message, sizeof err->message,
                     "%s: [domain] the periodic %s axis is %g m long; parcel collisions (model B) "
                     "need at least twice the longest reach (1 + collision_range) x 2 R_ep, "
                     "%g m",
                     scene->path, axes[a], L, 2.0 * reach);
            return BDL_ERR_SCENE;
        }
    }
    return BDL_OK;
}

bdl_result bdl_world_parcels_init(bdl_world *w, bdl_scene_error *err)
{
    bdl_result r = bdl_world_gas_init(w, err);
    if (r != BDL_OK)
        return r;
    r = check_periodic_reach(w, err);
    if (r != BDL_OK)
        return r;
    // eta_c resolved once, from the smallest parcel mass (eq. 18) unless given.
    bdl_parcels_def def = w->scene.parcels.def;
    def.collision_damping = bdl_parcels_collision_damping(&def, bdl_world_parcel_mass_min(w));
    w->parcels = calloc(1, sizeof *w->parcels);
    if (!w->parcels || bdl_parcels_init(w->parcels, &def, w->gas) != BDL_OK) {
        snprintf(err->message, sizeof err->message, "%s: [parcels]: out of memory", w->scene.path);
        return BDL_ERR_NOMEM;
    }
    // No contacts: empty lists and no coordination, for what reads them (outputs, checkpoints).
    const long n = w->particles.capacity;
    w->coordination = calloc((size_t)(n > 0 ? n : 1), 1);
    w->coordination_capacity = n;
    if (!w->coordination || bdl_neighbor_none(&w->neighbor, n) != BDL_OK ||
        bdl_neighbor_none(&w->neighbor, w->particles.count) != BDL_OK)
        return BDL_ERR_NOMEM;
    const double automatic =
        fmin(bdl_world_inflow_gas_dt(w), 0.5 * bdl_world_parcels_collision_dt(w));
    w->dt = w->scene.dt > 0.0 ? w->scene.dt : automatic;
    w->gas_fixed = 1;
    w->gas_every = w->gas_every_max = 1;
    w->gas_next = 0;
    w->budget.dt = w->dt;
    w->budget.steps = w->scene.end_time / w->dt;
    // The solids fraction of the initial parcels in the gas's cells, for what reads it before the
    // first step (the pictures' solids colour, check): the step deposits it anew.
    if (bdl_coupling_locate(w->coupling, w->gas, &w->particles) != BDL_OK)
        return BDL_ERR_NOMEM;
    bdl_coupling_voidage(w->coupling, w->gas, &w->particles);
    return bdl_budget_check_steps(w, w->dt, err);
}

/// Largest solids fraction 1 - eps over the gas's cells.
static double largest_solids(const bdl_gas *gas)
{
    const bdl_grid *g = &gas->grid;
    double top = 0.0;
    for (int k = 0; k < g->n[2]; ++k)
        for (int j = 0; j < g->n[1]; ++j)
            for (int i = 0; i < g->n[0]; ++i)
                top = fmax(top, 1.0 - gas->eps[bdl_grid_index(g, i, j, k)]);
    return top;
}

/// The gas cell holding x along each axis (clamped to the grid), as one index, x fastest.
static long cell_of(const bdl_grid *g, bdl_vec3 x)
{
    long idx = 0;
    for (int a = 2; a >= 0; --a) {
        int m = (int)floor((bdl_v3_comp(x, a) - g->origin[a]) / g->h[a]);
        m = m < 0 ? 0 : m >= g->n[a] ? g->n[a] - 1 : m;
        idx = idx * g->n[a] + m;
    }
    return idx;
}

bdl_result bdl_world_parcels_census(const bdl_world *w, bdl_parcels_census *out)
{
    *out = (bdl_parcels_census){0};
    const bdl_particles *p = &w->particles;
    const bdl_grid *g = &w->gas->grid;
    const long cells = (long)g->n[0] * g->n[1] * g->n[2];
    long *count = calloc((size_t)cells, sizeof *count);
    if (!count)
        return BDL_ERR_NOMEM;
    out->parcels = p->count;
    for (long i = 0; i < p->count; ++i) {
        out->real_particles += p->parcels ? p->parcel_count[i] : 1.0;
        count[cell_of(g, p->pos[i])]++;
    }
    for (long c = 0; c < cells; ++c) {
        if (count[c] == 0)
            continue;
        out->per_cell_min = out->filled_cells == 0 ? count[c] : fmin(out->per_cell_min, count[c]);
        out->per_cell_max = fmax(out->per_cell_max, count[c]);
        out->filled_cells++;
    }
    free(count);
    out->cells = cells;
    out->per_cell_mean = out->filled_cells > 0 ? (double)p->count / out->filled_cells : 0.0;
    out->max_solids = largest_solids(w->gas);
    return BDL_OK;
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
    // CFL 1/2 for the gas in each of its steps; and with gas sub-steps, CFL 1 for the parcels,
    // which move no faster than the gas that carries them.
    const int most = w->scene.parcels.def.gas_substeps > 1 ? w->scene.parcels.def.gas_substeps : 1;
    const double cfl = u > 0.0 && isfinite(hmin) ? 0.5 * hmin / u : INFINITY;
    return fmin(fmin(most * cfl, most > 1 ? 2.0 * cfl : INFINITY),
                most * bdl_gas_stable_dt(w->gas));
}

const char *bdl_world_parcels_stable_basis(const bdl_world *w)
{
    return w->scene.parcels.def.gas_substeps > 1
               ? "[parcels] gas_substeps times the gas's step, CFL 1/2 for the inflow through "
                 "close packing and its viscous limit, up to the parcels' CFL 1"
               : "CFL 1/2 for the inflow through close packing, and the gas's viscous limit";
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
    if (w->neighbor.count != w->particles.count) // the empty lists cover the parcels there are
        bdl_neighbor_none(&w->neighbor, w->particles.count);
    w->parcels_held += report.held;
    w->max_solids = report.max_solids;
    w->parcel_pairs = report.contacts.pairs;
    w->parcel_walls = report.contacts.walls;
    w->parcel_overlap = report.contacts.max_overlap;
    if (report.stable_dt > 0.0)
        w->gas_stable = report.stable_dt;
    if (r == BDL_ERR_UNSTABLE && report.failed_part)
        snprintf(w->failure, sizeof w->failure,
                 "parcel step at t = %.6g s (step %ld): a gas sub-step of %.3g s ended above twice "
                 "the gas's stable step %.3g s (CFL 1 or the viscous limit): the gas sped up more "
                 "than twofold within it; lower [run] dt or raise [parcels] gas_substeps",
                 w->time, w->step, report.failed_dt, report.stable_dt);
    else if (r == BDL_ERR_UNSTABLE)
        bdl_world_gas_failure(w, "parcel step", "[run] dt",
                              report.failed_dt > 0.0 ? report.failed_dt : w->dt, report.stable_dt);
    if (r != BDL_OK)
        return r;
    w->gas_work += report.gas_work;
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
