#include "dem/integrate.h"

#include <math.h>

#include "dem/contact_law.h"

// Lever arms run from each centre to the middle of the overlap, r - delta/2, so that the two arms
// add up to the centre distance and a pair conserves angular momentum exactly.
static inline bdl_contact_geom pair_geom(const bdl_particles *p, long i, long j, bdl_vec3 d,
                                         double dist, double *arm_i, double *arm_j)
{
    bdl_contact_geom g;
    double ri = p->radius[i], rj = p->radius[j];
    g.n = bdl_v3_scale(d, 1.0 / dist);
    g.overlap = ri + rj - dist;
    *arm_i = ri - 0.5 * g.overlap;
    *arm_j = rj - 0.5 * g.overlap;
    bdl_vec3 spin = bdl_v3_add(bdl_v3_scale(p->omega[i], *arm_i), bdl_v3_scale(p->omega[j], *arm_j));
    g.v_c = bdl_v3_sub(bdl_v3_sub(p->vel[i], p->vel[j]), bdl_v3_cross(spin, g.n));
    g.m_eff = 1.0 / (p->inv_mass[i] + p->inv_mass[j]);
    g.r_eff = ri * rj / (ri + rj);
    return g;
}

static void clear_pair(bdl_neighbor *nb, int32_t k)
{
    int32_t s = nb->jslot[k];
    nb->touching[k] = 0;
    nb->slot_touching[s] = 0;
    nb->force[s] = bdl_v3_zero();
    if (nb->history)
        nb->history[k] = bdl_v3_zero();
    if (nb->torque_j)
        nb->torque_j[s] = bdl_v3_zero();
}

void bdl_dem_pair_forces(bdl_particles *p, bdl_neighbor *nb, const bdl_force_def *def)
{
    long n = p->count;
    int ns = def->species_count;
#pragma omp parallel for schedule(static)
    for (long i = 0; i < n; ++i) {
        bdl_vec3 xi = p->pos[i];
        double ri = p->radius[i];
        const bdl_contact_params *row = def->pair_params + p->species[i] * ns;
        // Particle i's own pairs are summed here, in list order; the gather adds the pairs where
        // it is the second particle.
        bdl_vec3 fi = bdl_v3_zero(), ti = bdl_v3_zero();
        for (int32_t k = nb->start[i]; k < nb->start[i + 1]; ++k) {
            int32_t j = nb->partner[k];
            bdl_vec3 d = bdl_neighbor_delta(nb, xi, p->pos[j]);
            double cut = ri + p->radius[j];
            double dist2 = bdl_v3_len2(d);
            if (dist2 >= cut * cut || dist2 == 0.0) {
                if (nb->touching[k])
                    clear_pair(nb, k);
                continue;
            }
            double arm_i, arm_j;
            bdl_contact_geom g = pair_geom(p, i, j, d, sqrt(dist2), &arm_i, &arm_j);
            const bdl_contact_params *cp = row + p->species[j];
            bdl_contact_result res =
                bdl_contact_eval(cp, def->hertz, &g, def->friction ? &nb->history[k] : NULL, def->dt);
            int32_t slot = nb->jslot[k];
            nb->touching[k] = 1;
            nb->slot_touching[slot] = 1;
            nb->force[slot] = res.force;
            fi = bdl_v3_add(fi, res.force);
            if (!nb->torque_j)
                continue;
            bdl_vec3 tj = bdl_v3_scale(res.n_x_ft, -arm_j);
            bdl_vec3 tq = bdl_v3_scale(res.n_x_ft, -arm_i);
            if (def->rolling) {
                double inv_i = bdl_particle_inv_inertia(p, i) + bdl_particle_inv_inertia(p, j);
                bdl_vec3 roll = bdl_rolling_torque(cp, res.normal, g.r_eff,
                                                   bdl_v3_sub(p->omega[i], p->omega[j]), inv_i, def->dt);
                tj = bdl_v3_sub(tj, roll);
                tq = bdl_v3_add(tq, roll);
            }
            nb->torque_j[slot] = tj;
            ti = bdl_v3_add(ti, tq);
        }
        p->force[i] = fi;
        p->torque[i] = ti;
    }
}

/// Wall contacts of particle i, added to f and t.
static void wall_contacts(bdl_particles *p, bdl_neighbor *nb, const bdl_walls *walls,
                          const bdl_force_def *def, long i, bdl_vec3 *f, bdl_vec3 *t)
{
    int ns = def->species_count;
    double r = p->radius[i];
    for (int32_t k = nb->wall_start[i]; k < nb->wall_start[i + 1]; ++k) {
        int prim = nb->wall_prim[k];
        bdl_vec3 n;
        double gap = bdl_wall_gap(walls, prim, p->pos[i], r, &n);
        if (gap >= 0.0) {
            nb->wall_touching[k] = 0;
            nb->wall_force[k] = bdl_v3_zero();
            nb->wall_history[k] = bdl_v3_zero();
            continue;
        }
        int wall = walls->prims[prim].wall;
        double arm = r + 0.5 * gap;
        bdl_contact_geom g;
        g.n = n;
        g.overlap = -gap;
        g.v_c = bdl_v3_sub(bdl_v3_sub(p->vel[i], walls->velocity[wall]),
                           bdl_v3_scale(bdl_v3_cross(p->omega[i], n), arm));
        g.m_eff = 1.0 / p->inv_mass[i];
        g.r_eff = bdl_wall_r_eff(walls, prim, r);
        const bdl_contact_params *cp = def->wall_params + wall * ns + p->species[i];
        bdl_contact_result res =
            bdl_contact_eval(cp, def->hertz, &g, def->friction ? &nb->wall_history[k] : NULL, def->dt);
        nb->wall_touching[k] = 1;
        nb->wall_force[k] = res.force;
        *f = bdl_v3_add(*f, res.force);
        *t = bdl_v3_madd(*t, res.n_x_ft, -arm);
        if (def->rolling)
            *t = bdl_v3_add(*t, bdl_rolling_torque(cp, res.normal, g.r_eff, p->omega[i],
                                                   bdl_particle_inv_inertia(p, i), def->dt));
    }
}

void bdl_dem_gather(bdl_particles *p, bdl_neighbor *nb, const bdl_walls *walls,
                    const bdl_force_def *def, uint8_t *coordination, double kick)
{
    long n = p->count;
#pragma omp parallel for schedule(static)
    for (long i = 0; i < n; ++i) {
        // The pair pass left the sum over i's own pairs in force[i] and torque[i].
        bdl_vec3 f = p->force[i], t = p->torque[i];
        int contacts = 0;
        for (int32_t k = nb->start[i]; k < nb->start[i + 1]; ++k)
            contacts += nb->touching[k];
        for (int32_t m = nb->jstart[i]; m < nb->jstart[i + 1]; ++m) {
            if (!nb->slot_touching[m])
                continue;
            ++contacts;
            f = bdl_v3_sub(f, nb->force[m]);
            if (nb->torque_j)
                t = bdl_v3_add(t, nb->torque_j[m]);
        }
        wall_contacts(p, nb, walls, def, i, &f, &t);
        double b = def->background_damping[p->species[i]];
        if (b > 0.0)
            f = bdl_v3_madd(f, p->vel[i], -b / p->inv_mass[i]);
        p->force[i] = f;
        p->torque[i] = t;
        if (coordination)
            coordination[i] = (uint8_t)(contacts < 255 ? contacts : 255);
        if (kick > 0.0) {
            bdl_vec3 v = bdl_v3_madd(p->vel[i], def->gravity, kick);
            p->vel[i] = bdl_v3_madd(v, f, kick * p->inv_mass[i]);
            p->omega[i] = bdl_v3_madd(p->omega[i], t, kick * bdl_particle_inv_inertia(p, i));
        }
    }
}

double bdl_dem_kick_drift(bdl_particles *p, bdl_vec3 gravity, double h, double dt)
{
    long n = p->count;
    double max2 = 0.0;
#pragma omp parallel for schedule(static) reduction(max : max2)
    for (long i = 0; i < n; ++i) {
        double im = p->inv_mass[i];
        bdl_vec3 v = bdl_v3_madd(bdl_v3_madd(p->vel[i], gravity, h), p->force[i], h * im);
        p->vel[i] = v;
        p->omega[i] = bdl_v3_madd(p->omega[i], p->torque[i], h * bdl_particle_inv_inertia(p, i));
        bdl_vec3 x = bdl_v3_madd(p->pos[i], v, dt);
        p->pos[i] = x;
        double d2 = bdl_v3_len2(bdl_v3_sub(x, p->pos_at_build[i]));
        if (d2 > max2)
            max2 = d2;
    }
    return max2;
}

double bdl_dem_wall_power(const bdl_particles *p, const bdl_neighbor *nb, const bdl_walls *walls)
{
    int moving = 0;
    for (int w = 0; w < walls->wall_count; ++w)
        moving |= walls->motion[w] != BDL_MOTION_NONE;
    if (!moving)
        return 0.0;
    // Serial in list order: the result is the same for any thread count.
    double power = 0.0;
    long entries = nb->wall_start ? nb->wall_start[p->count] : 0;
    for (long k = 0; k < entries; ++k) {
        if (!nb->wall_touching[k])
            continue;
        int wall = walls->prims[nb->wall_prim[k]].wall;
        power += bdl_v3_dot(nb->wall_force[k], walls->velocity[wall]);
    }
    return power;
}

static double spring_energy(const bdl_contact_params *cp, int hertz, double overlap, double r_eff)
{
    if (hertz)
        return (8.0 / 15.0) * cp->e_star * sqrt(r_eff) * pow(overlap, 2.5);
    return 0.5 * cp->kn * overlap * overlap;
}

double bdl_dem_elastic_energy(const bdl_particles *p, const bdl_neighbor *nb, const bdl_walls *walls,
                              const bdl_force_def *def)
{
    double e = 0.0;
    int ns = def->species_count;
    for (long i = 0; i < p->count; ++i) {
        for (int32_t k = nb->start[i]; k < nb->start[i + 1]; ++k) {
            int32_t j = nb->partner[k];
            bdl_vec3 d = bdl_neighbor_delta(nb, p->pos[i], p->pos[j]);
            double cut = p->radius[i] + p->radius[j];
            double dist = bdl_v3_len(d);
            if (dist >= cut)
                continue;
            double r_eff = p->radius[i] * p->radius[j] / cut;
            e += spring_energy(def->pair_params + p->species[i] * ns + p->species[j], def->hertz,
                               cut - dist, r_eff);
        }
        for (int32_t k = nb->wall_start[i]; k < nb->wall_start[i + 1]; ++k) {
            bdl_vec3 n;
            int prim = nb->wall_prim[k];
            double gap = bdl_wall_gap(walls, prim, p->pos[i], p->radius[i], &n);
            if (gap >= 0.0)
                continue;
            int wall = walls->prims[prim].wall;
            e += spring_energy(def->wall_params + wall * ns + p->species[i], def->hertz, -gap,
                               bdl_wall_r_eff(walls, prim, p->radius[i]));
        }
    }
    return e;
}
