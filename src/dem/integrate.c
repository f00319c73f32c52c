// DEM forces and velocity Verlet.
//
// Deterministic parallel forces. Particles are split into one contiguous index range per thread.
// Each particle's force is summed in one canonical order whatever the thread count: the
// contributions of its pairs ordered by the pair's first particle i, and within i by list
// order. A pair (i, j) with j > i is evaluated once, when the loop over i reaches it: i keeps
// +F in a register, j receives -F at once (its own turn comes later). Pairs whose j lies in a
// later thread's range ("boundary pairs") are evaluated first, in a separate phase, and stored;
// the owner of j adds them before its own loop, which preserves the canonical order because
// every i of an earlier range is smaller than every i of its own. When the loop passes particle
// i, every pair involving i has been evaluated, so i's walls, damping and closing half kick are
// applied right there: one pass over the particles per step. No floating-point atomics, no
// thread-count-dependent sums: the state after N steps is bitwise the same for any thread count.
#include "dem/integrate.h"

#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>

#include "dem/contact_law.h"

#if defined(__GNUC__)
#define BDL_PREFETCH(address) __builtin_prefetch(address)
#else
#define BDL_PREFETCH(address) ((void)(address))
#endif

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
    bdl_vec3 spin =
        bdl_v3_add(bdl_v3_scale(p->omega[i], *arm_i), bdl_v3_scale(p->omega[j], *arm_j));
    g.v_c = bdl_v3_sub(bdl_v3_sub(p->vel[i], p->vel[j]), bdl_v3_cross(spin, g.n));
    g.m_eff = 1.0 / (p->inv_mass[i] + p->inv_mass[j]);
    g.r_eff = ri * rj / (ri + rj);
    return g;
}

typedef struct bdl_pair_result {
    bdl_vec3 force;    ///< on i [N]
    bdl_vec3 torque_i; ///< [N m]
    bdl_vec3 torque_j; ///< [N m]
    int touching;
} pair_result;

/// Evaluates pair k = (i, j); updates its history and touching flag.
static inline pair_result eval_pair(bdl_particles *p, bdl_neighbor *nb, const bdl_force_def *def,
                                    long i, int32_t k)
{
    pair_result res = {{0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}, 0};
    int32_t j = nb->partner[k];
    bdl_vec3 d = bdl_neighbor_delta(nb, p->pos[i], p->pos[j]);
    double cut = p->radius[i] + p->radius[j];
    double dist2 = bdl_v3_len2(d);
    if (dist2 >= cut * cut || dist2 == 0.0) {
        res.touching = 0;
        if (nb->touching[k]) {
            nb->touching[k] = 0;
            if (nb->history)
                nb->history[k] = bdl_v3_zero();
        }
        return res;
    }
    double arm_i, arm_j;
    bdl_contact_geom g = pair_geom(p, i, j, d, sqrt(dist2), &arm_i, &arm_j);
    const bdl_contact_params *cp =
        def->pair_params + p->species[i] * def->species_count + p->species[j];
    bdl_contact_result c =
        bdl_contact_eval(cp, def->hertz, &g, def->friction ? &nb->history[k] : NULL, def->dt);
    nb->touching[k] = 1;
    res.touching = 1;
    res.force = c.force;
    res.torque_i = bdl_v3_scale(c.n_x_ft, -arm_i);
    res.torque_j = bdl_v3_scale(c.n_x_ft, -arm_j);
    if (def->rolling) {
        double inv_i = bdl_particle_inv_inertia(p, i) + bdl_particle_inv_inertia(p, j);
        bdl_vec3 roll = bdl_rolling_torque(cp, c.normal, g.r_eff,
                                           bdl_v3_sub(p->omega[i], p->omega[j]), inv_i, def->dt);
        res.torque_i = bdl_v3_add(res.torque_i, roll);
        res.torque_j = bdl_v3_sub(res.torque_j, roll);
    }
    return res;
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
        bdl_contact_result res = bdl_contact_eval(
            cp, def->hertz, &g, def->friction ? &nb->wall_history[k] : NULL, def->dt);
        nb->wall_touching[k] = 1;
        nb->wall_force[k] = res.force;
        *f = bdl_v3_add(*f, res.force);
        *t = bdl_v3_madd(*t, res.n_x_ft, -arm);
        if (def->rolling)
            *t = bdl_v3_add(*t, bdl_rolling_torque(cp, res.normal, g.r_eff, p->omega[i],
                                                   bdl_particle_inv_inertia(p, i), def->dt));
    }
}

static int grow(void **ptr, long count, size_t elem)
{
    void *q = realloc(*ptr, (size_t)(count > 0 ? count : 1) * elem);
    if (!q)
        return 0;
    *ptr = q;
    return 1;
}

/// Splits the particles into one range per thread and lists the boundary pairs: per source
/// thread s the pairs (in list order) whose j lies in a later range, and per target thread the
/// indices of those entries that point into it, by source thread and list order.
static bdl_result partition(bdl_force_work *fw, const bdl_neighbor *nb, long n, int threads)
{
    if (fw->threads == threads && fw->version == nb->version && fw->count == n)
        return BDL_OK;
    if (threads > BDL_MAX_FORCE_THREADS)
        threads = BDL_MAX_FORCE_THREADS;
    fw->threads = threads;
    fw->version = nb->version;
    fw->count = n;
    // Balance the work, not the count: a particle costs about as much as one of its pairs, and
    // the free surface of a bed has fewer pairs than its bottom. Cost up to i: i + start[i].
    double total = (double)n + (double)nb->start[n];
    fw->range[0] = 0;
    for (int t = 1; t < threads; ++t) {
        double goal = total * t / threads;
        long lo = fw->range[t - 1], hi = n;
        while (lo < hi) {
            long mid = lo + (hi - lo) / 2;
            if ((double)mid + (double)nb->start[mid] < goal)
                lo = mid + 1;
            else
                hi = mid;
        }
        fw->range[t] = lo;
    }
    fw->range[threads] = n;
    long count = 0;
    for (int t = 0; t + 1 < threads; ++t)
        for (long i = fw->range[t]; i < fw->range[t + 1]; ++i)
            for (int32_t k = nb->start[i]; k < nb->start[i + 1]; ++k)
                count += nb->partner[k] >= fw->range[t + 1];
    if (count > fw->capacity) {
        long cap = count + count / 4 + 64;
        if (!grow((void **)&fw->pair, cap, sizeof(int32_t)) ||
            !grow((void **)&fw->target, cap, sizeof(int32_t)) ||
            !grow((void **)&fw->result, cap, sizeof *fw->result))
            return BDL_ERR_NOMEM;
        fw->capacity = cap;
    }
    long m = 0;
    for (int t = 0; t < threads; ++t) {
        fw->out_start[t] = m;
        for (long i = fw->range[t]; i < fw->range[t + 1]; ++i)
            for (int32_t k = nb->start[i]; k < nb->start[i + 1]; ++k)
                if (nb->partner[k] >= fw->range[t + 1])
                    fw->pair[m++] = k;
    }
    fw->out_start[threads] = m;
    // Incoming lists: entries sorted by target thread, then source thread, then list order.
    long c = 0;
    for (int u = 0; u < threads; ++u) {
        fw->in_start[u] = c;
        for (long e = 0; e < m; ++e) {
            long j = nb->partner[fw->pair[e]];
            if (j >= fw->range[u] && j < fw->range[u + 1])
                fw->target[c++] = (int32_t)e;
        }
    }
    fw->in_start[threads] = c;
    return BDL_OK;
}

/// Adds -F and the torque of a pair to particle j (its second particle).
static inline void add_to_j(bdl_particles *p, uint8_t *coordination, int32_t j,
                            const pair_result *r, int torques)
{
    p->force[j] = bdl_v3_sub(p->force[j], r->force);
    if (torques)
        p->torque[j] = bdl_v3_add(p->torque[j], r->torque_j);
    if (coordination[j] < 255)
        coordination[j]++;
}

/// Walls, background damping, storage and the closing half kick of particle i, once all its
/// pairs are in.
static inline void finish_particle(bdl_particles *p, bdl_neighbor *nb, const bdl_walls *walls,
                                   const bdl_force_def *def, long i, bdl_vec3 f, bdl_vec3 t,
                                   double kick)
{
    wall_contacts(p, nb, walls, def, i, &f, &t);
    double b = def->background_damping[p->species[i]];
    if (b > 0.0)
        f = bdl_v3_madd(f, p->vel[i], -b / p->inv_mass[i]);
    p->force[i] = f;
    p->torque[i] = t;
    if (kick > 0.0) {
        double im = p->inv_mass[i];
        p->vel[i] = bdl_v3_madd(bdl_v3_madd(p->vel[i], def->gravity, kick), f, kick * im);
        p->omega[i] = bdl_v3_madd(p->omega[i], t, kick * bdl_particle_inv_inertia(p, i));
    }
}

static void force_range(bdl_particles *p, bdl_neighbor *nb, const bdl_walls *walls,
                        const bdl_force_def *def, bdl_force_work *fw, uint8_t *coordination,
                        double kick, int t)
{
    long lo = fw->range[t], hi = fw->range[t + 1];
    int torques = def->friction || def->rolling;
    for (long i = lo; i < hi; ++i) {
        p->force[i] = bdl_v3_zero();
        p->torque[i] = bdl_v3_zero();
        coordination[i] = 0;
    }
    // Boundary pairs from earlier ranges first: their i are smaller than all of ours.
    for (long c = fw->in_start[t]; c < fw->in_start[t + 1]; ++c) {
        const pair_result *r = &fw->result[fw->target[c]];
        if (r->touching)
            add_to_j(p, coordination, nb->partner[fw->pair[fw->target[c]]], r, torques);
    }
    long out = fw->out_start[t], out_end = fw->out_start[t + 1];
    for (long i = lo; i < hi; ++i) {
        bdl_vec3 f = p->force[i], tq = p->torque[i];
        int contacts = coordination[i];
        if (i + 2 < hi) {
            // The partners of the particle after next are read soon: ask for them now.
            for (int32_t k = nb->start[i + 2]; k < nb->start[i + 3]; ++k) {
                BDL_PREFETCH(&p->pos[nb->partner[k]]);
                BDL_PREFETCH(&p->vel[nb->partner[k]]);
            }
        }
        for (int32_t k = nb->start[i]; k < nb->start[i + 1]; ++k) {
            pair_result r;
            if (out < out_end && fw->pair[out] == k)
                r = fw->result[out++];
            else {
                r = eval_pair(p, nb, def, i, k);
                if (r.touching)
                    add_to_j(p, coordination, nb->partner[k], &r, torques);
            }
            if (!r.touching)
                continue;
            ++contacts;
            f = bdl_v3_add(f, r.force);
            if (torques)
                tq = bdl_v3_add(tq, r.torque_i);
        }
        coordination[i] = (uint8_t)(contacts < 255 ? contacts : 255);
        finish_particle(p, nb, walls, def, i, f, tq, kick);
    }
}

bdl_result bdl_dem_forces(bdl_particles *p, bdl_neighbor *nb, const bdl_walls *walls,
                          const bdl_force_def *def, bdl_force_work *fw, uint8_t *coordination,
                          double kick)
{
    long n = p->count;
    int threads = n >= def->parallel_min ? omp_get_max_threads() : 1;
    bdl_result r = partition(fw, nb, n, threads);
    if (r != BDL_OK)
        return r;
    threads = fw->threads;
    if (threads == 1) {
        force_range(p, nb, walls, def, fw, coordination, kick, 0);
        return BDL_OK;
    }
#pragma omp parallel num_threads(threads)
    {
        int t = omp_get_thread_num();
        // Phase 1: this range's boundary pairs, stored for the owners of their j.
        long i = fw->range[t];
        for (long e = fw->out_start[t]; e < fw->out_start[t + 1]; ++e) {
            int32_t k = fw->pair[e];
            while (nb->start[i + 1] <= k)
                ++i;
            fw->result[e] = eval_pair(p, nb, def, i, k);
        }
#pragma omp barrier
        // Phase 2: everything else, in index order.
        force_range(p, nb, walls, def, fw, coordination, kick, t);
    }
    return BDL_OK;
}

void bdl_force_work_free(bdl_force_work *fw)
{
    free(fw->pair);
    free(fw->target);
    free(fw->result);
    memset(fw, 0, sizeof *fw);
}

long bdl_force_work_bytes(const bdl_force_work *fw)
{
    return fw->capacity * (long)(2 * sizeof(int32_t) + sizeof *fw->result);
}

double bdl_dem_kick_drift(bdl_particles *p, bdl_vec3 gravity, double h, double dt)
{
    long n = p->count;
    double max2 = 0.0;
#pragma omp parallel for schedule(static) reduction(max : max2) if (n >= BDL_PARALLEL_MIN)
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

double bdl_dem_elastic_energy(const bdl_particles *p, const bdl_neighbor *nb,
                              const bdl_walls *walls, const bdl_force_def *def)
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
