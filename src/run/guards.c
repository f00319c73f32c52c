#include "run/guards.h"

#include <math.h>
#include <stdio.h>

#include "dem/create.h"

bdl_result bdl_guards_check_dt(const bdl_world *w, char *message, size_t len, char *warning,
                               size_t warning_len)
{
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

void bdl_guards_init(bdl_guard_state *g, const bdl_diagnostics *d)
{
    g->energy0 = bdl_diagnostics_total_energy(d);
    g->active_max = d->kinetic_energy + d->rotational_energy + d->elastic_energy;
}

static const char *const axis_names[3] = {"x", "y", "z"};

static bdl_result check_finite(const bdl_world *w, char *message, size_t len)
{
    const bdl_particles *p = &w->particles;
    for (long i = 0; i < p->count; ++i) {
        if (bdl_v3_isfinite(p->pos[i]) && bdl_v3_isfinite(p->vel[i]) &&
            bdl_v3_isfinite(p->omega[i]))
            continue;
        snprintf(
            message, len,
            "particle %u has a non-finite position, velocity or spin at t = %.6g s (step %ld), "
            "last position (%g, %g, %g) m. Likely fix: a smaller dt (now %.3g of the contact time)",
            p->id[i], w->time, w->step, p->pos[i].x, p->pos[i].y, p->pos[i].z,
            w->contact_time_dt_ratio);
        return BDL_ERR_UNSTABLE;
    }
    return BDL_OK;
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

bdl_result bdl_guards_check(const bdl_world *w, bdl_guard_state *g, const bdl_diagnostics *d,
                            char *message, size_t len)
{
    bdl_result r = check_finite(w, message, len);
    if (r == BDL_OK)
        r = check_domain(w, message, len);
    if (r != BDL_OK)
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
    double active = d->kinetic_energy + d->rotational_energy + d->elastic_energy;
    if (active > g->active_max)
        g->active_max = active;
    double scale = g->active_max + fabs(w->wall_work) + fabs(w->inserted_energy) +
                   fabs(w->gas_work) + fabs(w->removed_energy);
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
