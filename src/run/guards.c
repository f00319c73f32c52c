#include "run/guards.h"

#include <math.h>
#include <stdio.h>

#include "cfd/gas.h"
#include "dem/create.h"

/// The step of a world of parcels against its stable step (twice it is refused: CFL 1), and with
/// collisions (model B) against Cundall & Strack's bound and the dashpot's (parcels.h).
static bdl_result check_parcel_dt(const bdl_world *w, char *message, size_t len)
{
    const double collision = bdl_world_parcels_collision_dt(w);
    if (!(w->dt < collision)) {
        const bdl_parcels_def *def = &w->scene.parcels.def;
        const double m = bdl_world_parcel_mass_min(w);
        const int k = def->substeps > 0 ? def->substeps : 1;
        snprintf(message, len,
                 "%s: [run] dt = %g s is too long for parcel collisions (model B): dt / substeps "
                 "must be below 2 sqrt(M / k_c) = %g s (Cundall & Strack, for the smallest parcel "
                 "mass M = %g kg and collision_stiffness k_c = %g) and below M / eta_c = %g s "
                 "(the dashpot, eta_c = %g kg/s); allowed: dt < %g s with substeps = %d. Likely "
                 "fix: lower dt, raise [parcels] substeps, or soften collision_stiffness",
                 w->scene.path, w->dt, 2.0 * sqrt(m / def->collision_stiffness), m,
                 def->collision_stiffness, m / bdl_parcels_collision_damping(def, m),
                 bdl_parcels_collision_damping(def, m), collision, k);
        return BDL_ERR_SCENE;
    }
    const double stable = bdl_world_parcels_stable_dt(w);
    if (w->dt > 2.0 * stable) {
        snprintf(message, len,
                 "%s: [run] dt = %g s is %.3g times the parcels' stable step %g s (%s); "
                 "allowed: at most twice it (dt <= %g s). Likely fix: lower dt%s",
                 w->scene.path, w->dt, w->dt / stable, stable, bdl_world_parcels_stable_basis(w),
                 2.0 * stable,
                 w->scene.parcels.def.gas_substeps > 1 ? "" : ", or raise [parcels] gas_substeps");
        return BDL_ERR_SCENE;
    }
    return BDL_OK;
}

/// The step of a world with a solids phase against the gas's expected stable step (CFL 1/2 for
/// the inflow through the densest packing, with a margin for bubbles): twice it is refused.
static bdl_result check_solids_dt(const bdl_world *w, char *message, size_t len)
{
    const double stable = bdl_world_inflow_gas_dt(w);
    if (w->dt > 2.0 * stable) {
        snprintf(message, len,
                 "%s: [run] dt = %g s is %.3g times the gas's expected stable step %g s (CFL 1/2 "
                 "for the inflow through the packed bed, plus 0.5 m/s for bubbles); allowed: at "
                 "most twice it (dt <= %g s). Likely fix: lower dt",
                 w->scene.path, w->dt, w->dt / stable, stable, 2.0 * stable);
        return BDL_ERR_SCENE;
    }
    return BDL_OK;
}

bdl_result bdl_guards_check_dt(const bdl_world *w, char *message, size_t len, char *warning,
                               size_t warning_len)
{
    if (w->parcels) {
        warning[0] = '\0';
        return check_parcel_dt(w, message, len);
    }
    if (w->solids) {
        warning[0] = '\0';
        return check_solids_dt(w, message, len);
    }
    char which[160];
    double v_ref = bdl_world_reference_speed(w);
    double tc = bdl_world_min_contact_time(w, v_ref, which, (int)sizeof which);
    double ratio = w->dt / tc;
    const bdl_guard_def *g = &w->scene.guards;
    warning[0] = '\0';
    if (ratio > g->dt_refuse) {
        snprintf(message, len,
                 "%s: [run] dt = %g s is %.3g of the contact time %g s of %s; allowed: at most "
                 "[guards] dt_refuse = %g of it (dt <= %g s). Likely fix: lower dt, or soften the "
                 "contacts (smaller youngs_modulus or stiffness)",
                 w->scene.path, w->dt, ratio, tc, which, g->dt_refuse, g->dt_refuse * tc);
        return BDL_ERR_SCENE;
    }
    if (ratio > g->dt_warn)
        snprintf(warning, warning_len,
                 "dt = %g s is %.3g of the contact time %g s of %s (above dt_warn = %g): contacts "
                 "are resolved by only %.0f steps; restitution and overlaps lose accuracy",
                 w->dt, ratio, tc, which, g->dt_warn, 1.0 / ratio);
    return BDL_OK;
}

void bdl_guards_init(bdl_guard_state *g, const bdl_world *w, const bdl_diagnostics *d)
{
    g->energy0 = bdl_diagnostics_total_energy(d);
    g->active_max = d->kinetic_energy + d->rotational_energy + d->elastic_energy;
    g->finite_step = w->step;
}

static const char *const axis_names[3] = {"x", "y", "z"};

/// One array of the state the finite check walks: `components` doubles per particle, `stride`
/// doubles apart.
typedef struct state_array {
    const char *name;
    const double *data; ///< NULL: not in this world
    int stride, components;
} state_array;

static const char *const vector_components[3] = {"x", "y", "z"};
static const char *const quat_components[4] = {"w", "x", "y", "z"};

/// The particles' arrays the next step starts from, in the order they are checked.
static int particle_arrays(const bdl_particles *p, state_array *a)
{
    int n = 0;
    a[n++] = (state_array){"position", &p->pos[0].x, 3, 3};
    a[n++] = (state_array){"velocity", &p->vel[0].x, 3, 3};
    a[n++] = (state_array){"spin", &p->omega[0].x, 3, 3};
    a[n++] = (state_array){"force", &p->load[0].force.x, 6, 3};
    a[n++] = (state_array){"torque", &p->load[0].torque.x, 6, 3};
    if (p->rods) {
        a[n++] = (state_array){"orientation", &p->orient[0].w, 4, 4};
        a[n++] = (state_array){"angular momentum", &p->ang_mom[0].x, 3, 3};
    }
    if (p->fluid)
        a[n++] = (state_array){"gas force", &p->fluid_accel[0].x, 3, 3};
    return n;
}

/// The first non-finite number of the particles' state, described; 0 when all are finite.
static int particles_finite(const bdl_world *w, char *what, size_t len)
{
    const bdl_particles *p = &w->particles;
    if (p->count == 0)
        return 1;
    state_array arrays[8];
    const int count = particle_arrays(p, arrays);
    for (long i = 0; i < p->count; ++i)
        for (int k = 0; k < count; ++k)
            for (int c = 0; c < arrays[k].components; ++c) {
                const double v = arrays[k].data[i * arrays[k].stride + c];
                if (isfinite(v))
                    continue;
                snprintf(what, len, "the %s of particle %u (%s component) is %g", arrays[k].name,
                         p->id[i],
                         (arrays[k].components == 4 ? quat_components : vector_components)[c], v);
                return 0;
            }
    return 1;
}

/// The first non-finite value of the gas's fields, described; 0 when all are finite.
static int gas_finite(const bdl_world *w, char *what, size_t len)
{
    const bdl_gas *g = w->gas;
    if (!g)
        return 1;
    const struct {
        const double *v;
        const char *name;
    } fields[] = {{g->u[0], "gas velocity x"},
                  {g->u[1], "gas velocity y"},
                  {g->u[2], "gas velocity z"},
                  {g->p, "gas pressure"},
                  {g->eps, "voidage"}};
    const bdl_grid *grid = &g->grid;
    for (int f = 0; f < 5; ++f)
        for (long m = 0; m < grid->size; ++m) {
            if (isfinite(fields[f].v[m]))
                continue;
            int ix[3]; // the padded index back to the cell (ghosts: outside 0..n-1)
            bdl_grid_position(grid, m, ix);
            snprintf(what, len, "the %s in cell (%d, %d, %d) is %g", fields[f].name, ix[0], ix[1],
                     ix[2], fields[f].v[m]);
            return 0;
        }
    return 1;
}

bdl_result bdl_guards_check_finite(const bdl_world *w, bdl_guard_state *g, char *message,
                                   size_t len)
{
    char what[320];
    if (particles_finite(w, what, sizeof what) && gas_finite(w, what, sizeof what)) {
        g->finite_step = w->step;
        return BDL_OK;
    }
    snprintf(message, len,
             "%s at t = %.6g s (step %ld); the state was finite at step %ld, the last check. "
             "Something grew without bound in between: see max_speed, max_overlap_ratio and the "
             "energies in diagnostics.csv up to here (dt is %.3g of the contact time)",
             what, w->time, w->step, g->finite_step, w->contact_time_dt_ratio);
    return BDL_ERR_UNSTABLE;
}

static bdl_result check_domain(const bdl_world *w, char *message, size_t len)
{
    const bdl_particles *p = &w->particles;
    const bdl_scene *s = &w->scene;
    for (long i = 0; i < p->count; ++i)
        for (int a = 0; a < 3; ++a) {
            if (s->periodic[a])
                continue;
            double x = bdl_v3_comp(p->pos[i], a);
            double lo = bdl_v3_comp(s->domain_min, a), hi = bdl_v3_comp(s->domain_max, a);
            if (x >= lo && x <= hi)
                continue;
            snprintf(
                message, len,
                "particle %u left the domain through the %s %s face at t = %.6g s (step %ld), "
                "position (%g, %g, %g) m, speed %g m/s. Likely fix: close the container with a "
                "wall on that side, enlarge [domain], or lower dt if particles tunnel through "
                "walls",
                p->id[i], axis_names[a], x < lo ? "min" : "max", w->time, w->step, p->pos[i].x,
                p->pos[i].y, p->pos[i].z, bdl_v3_len(p->vel[i]));
            return BDL_ERR_UNSTABLE;
        }
    return BDL_OK;
}

bdl_result bdl_guards_check_state(const bdl_world *w, bdl_guard_state *g, const bdl_diagnostics *d,
                                  char *message, size_t len)
{
    bdl_result r = bdl_guards_check_finite(w, g, message, len);
    if (r != BDL_OK)
        return r;
    if ((r = check_domain(w, message, len)) != BDL_OK)
        return r;
    const bdl_guard_def *gd = &w->scene.guards;
    if (d->max_overlap_ratio > gd->max_overlap) {
        snprintf(
            message, len,
            "an overlap reached %.3g of the smaller particle radius at t = %.6g s (step %ld); "
            "allowed: [guards] max_overlap = %g. Likely fix: stiffer contacts (the springs are "
            "too soft for the loads), or a smaller dt (now %.3g of the contact time)",
            d->max_overlap_ratio, w->time, w->step, gd->max_overlap, w->contact_time_dt_ratio);
        return BDL_ERR_UNSTABLE;
    }
    return BDL_OK;
}

bdl_result bdl_guards_check(const bdl_world *w, bdl_guard_state *g, const bdl_diagnostics *d,
                            char *message, size_t len)
{
    bdl_result r = bdl_guards_check_state(w, g, d, message, len);
    // A world of parcels books neither the gas's work on them nor the stress's (the parcel step
    // does not report it); Lees–Edwards boundaries do work on the particles that is not booked,
    // and a particle passing through a z face changes its x velocity by the images' speed: their
    // energy has sources the balance does not see. A solids phase books none of its energy.
    if (r != BDL_OK || w->parcels || w->solids || w->scene.shear_rate != 0.0)
        return r;
    const bdl_guard_def *gd = &w->scene.guards;
    double active = d->kinetic_energy + d->rotational_energy + d->elastic_energy;
    if (active > g->active_max)
        g->active_max = active;
    double scale = g->active_max + fabs(w->wall_work) + fabs(w->inserted_energy) +
                   fabs(w->gas_work) + fabs(w->removed_energy) + fabs(d->spring_work_left);
    double growth = d->energy_balance;
    if (growth > gd->energy_growth * scale && growth > 1e-12 * fabs(g->energy0)) {
        snprintf(
            message, len,
            "mechanical energy grew by %.3g J (%.3g of the active energy %.3g J) without a "
            "source at t = %.6g s (step %ld); allowed: [guards] energy_growth = %g. Likely fix: "
            "a smaller dt (now %.3g of the contact time)",
            growth, growth / scale, scale, w->time, w->step, gd->energy_growth,
            w->contact_time_dt_ratio);
        return BDL_ERR_UNSTABLE;
    }
    return BDL_OK;
}

bdl_result bdl_guards_check_row(const bdl_world *w, const char *file, const char *const *names,
                                const double *row, int count, int (*may_be_nan)(int), char *message,
                                size_t len)
{
    for (int c = 0; c < count; ++c) {
        if (isfinite(row[c]) || (isnan(row[c]) && may_be_nan && may_be_nan(c)))
            continue;
        char column[64];
        if (names)
            snprintf(column, sizeof column, "%s", names[c]);
        else
            snprintf(column, sizeof column, "column %d", c + 1);
        snprintf(message, len,
                 "%s: the %s of t = %.6g s (step %ld) would be %g, with every position, velocity, "
                 "spin, force and torque finite: a value overflowed (see max_speed in the rows "
                 "before; dt is %.3g of the contact time)",
                 file, column, w->time, w->step, row[c], w->contact_time_dt_ratio);
        return BDL_ERR_UNSTABLE;
    }
    return BDL_OK;
}
