// The contact-force pass of scenes with rods, deterministic in parallel as the spheres' pass is
// (contact_force.c: thread ranges, boundary pairs evaluated first and added by their j's owner,
// every particle's sum in list order), but with each pair evaluated on its own: rods are not
// batched.
//
// Two rods touch where their shafts come closer than r_i + r_j (dem/capsule.h); the normal runs
// between the closest shaft points, from j's to i's, and the contact point lies in the middle of
// the overlap. The force acts there: the arms from each centre to it carry its torque, the normal
// force included (a rod's contact normal need not pass through its centre). A sphere is a rod
// without a shaft, and then this is exactly the spheres' geometry.
//
// A wall touches the stretch of a rod's shaft whose surface lies beyond it: with the depth taken
// linear between the two tips, the contact point is the depth-weighted middle of that stretch and
// the overlap is the largest depth. A rod lying flat touches at its middle, a tilted one at its
// lower tip, and the point moves continuously between the two as the rod tips over.
//
// The damping of each contact uses the mass the contact point shows along the normal,
// 1/m* = 1/m_i + (a_i x n).I_i^-1 (a_i x n) (+ the same for j), a the arm: an impact then ends
// with the configured restitution of the contact point's normal velocity, as a rigid-body
// collision does (for spheres, and for rods struck in line with their centre, this is the usual
// reduced mass).
// Rolling resistance (Wensrich & Katterfeld 2012, "Rolling friction as a technique for modelling
// particle shape in DEM", Powder Technology 217) uses the two arms' harmonic mean as the lever, the
// radius of a sphere.
#include "dem/rod_force.h"

#include <string.h>

#include "dem/capsule.h"
#include "dem/contact_law.h"
#include "dem/rigid.h"

typedef bdl_rod_contact rod_contact;

/// The closest points of the shafts of a listed pair: the separation d of the centres (j's image
/// nearest to i), the places l, m along the shafts and the squared distance.
typedef struct shaft_pair {
    bdl_vec3 d;
    double l, m, d2;
} shaft_pair;

static inline shaft_pair shafts_of(const bdl_particles *p, const bdl_neighbor *nb, long i, long j)
{
    shaft_pair s;
    s.d = bdl_neighbor_delta(nb, p->pos[i], p->pos[j]);
    s.d2 = bdl_shafts_closest(s.d, p->axis[i], p->half_length[i], p->axis[j], p->half_length[j],
                              &s.l, &s.m);
    return s;
}

/// The contact of the pair (i, j) from its closest points; 0 when they do not touch.
static inline int contact_from(const bdl_particles *p, long i, long j, const shaft_pair *s,
                               bdl_rod_contact *c)
{
    const double cut = p->radius[i] + p->radius[j];
    if (!(s->d2 < cut * cut) || s->d2 == 0.0)
        return 0;
    const bdl_vec3 ui = p->axis[i], uj = p->axis[j];
    const double dist = sqrt(s->d2);
    const bdl_vec3 w = bdl_v3_sub(bdl_v3_madd(s->d, ui, s->l), bdl_v3_scale(uj, s->m));
    c->n = bdl_v3_scale(w, 1.0 / dist);
    c->overlap = cut - dist;
    c->arm_i = bdl_v3_madd(bdl_v3_scale(ui, s->l), c->n, -(p->radius[i] - 0.5 * c->overlap));
    c->arm_j = bdl_v3_madd(bdl_v3_scale(uj, s->m), c->n, p->radius[j] - 0.5 * c->overlap);
    return 1;
}

int bdl_rod_contact_of(const bdl_particles *p, const bdl_neighbor *nb, long i, long j,
                       bdl_rod_contact *c)
{
    const shaft_pair s = shafts_of(p, nb, i, j);
    return contact_from(p, i, j, &s, c);
}

double bdl_rod_inv_mass_at(const bdl_particles *p, long i, bdl_vec3 arm, bdl_vec3 n)
{
    // (a x n).I^-1 (a x n) of an axisymmetric body: |w|^2 / I_t + (1/I_a - 1/I_t)(w . u)^2.
    const bdl_vec3 w = bdl_v3_cross(arm, n), inv = p->inv_inertia[i];
    const double c = bdl_v3_dot(w, p->axis[i]);
    return p->inv_mass[i] + inv.x * bdl_v3_len2(w) + (inv.z - inv.x) * c * c;
}

int bdl_rod_wall_contact_of(const bdl_particles *p, const bdl_walls *walls, long i, int prim,
                            bdl_rod_contact *c)
{
    const bdl_vec3 x = p->pos[i], e = bdl_particle_half_axis(p, i);
    const double r = p->radius[i];
    bdl_vec3 n0, n1;
    const double d0 = -bdl_wall_gap(walls, prim, bdl_v3_sub(x, e), r, &n0);
    const double d1 = -bdl_wall_gap(walls, prim, bdl_v3_add(x, e), r, &n1);
    if (!(d0 > 0.0) && !(d1 > 0.0))
        return 0;
    // The stretch [sa, sb] of the shaft beyond the wall and its depths at the ends.
    double sa = -1.0, sb = 1.0, da = d0, db = d1;
    if (!(d0 > 0.0))
        sa = -1.0 + 2.0 * d0 / (d0 - d1), da = 0.0;
    if (!(d1 > 0.0))
        sb = -1.0 + 2.0 * d0 / (d0 - d1), db = 0.0;
    const double s = sa + (sb - sa) * (da + 2.0 * db) / (3.0 * (da + db));
    c->overlap = d0 > d1 ? d0 : d1;
    bdl_vec3 n; // a plane's normal everywhere; a cylinder's radial at the contact point
    bdl_wall_gap(walls, prim, bdl_v3_madd(x, e, s), r, &n);
    c->n = bdl_v3_len2(n) > 0.0 ? n : d0 > d1 ? n0 : n1;
    c->arm_i = bdl_v3_madd(bdl_v3_scale(e, s), c->n, -(r - 0.5 * c->overlap));
    c->arm_j = bdl_v3_zero();
    return 1;
}

/// Rolling resistance between bodies a and b (torque on a; b takes minus it), the relative spin
/// limited as bdl_rolling_torque limits it, with the inverse inertias about the relative spin.
static bdl_vec3 rolling(const bdl_particles *p, long a, long b, const bdl_contact_params *cp,
                        double normal, double lever, double dt)
{
    const bdl_vec3 w_rel = b >= 0 ? bdl_v3_sub(p->omega[a], p->omega[b]) : p->omega[a];
    const double spin = bdl_v3_len(w_rel);
    if (!(spin > 0.0))
        return bdl_v3_zero();
    const bdl_vec3 e = bdl_v3_scale(w_rel, 1.0 / spin);
    double inv = bdl_particle_inv_inertia_along(p, a, e);
    if (b >= 0)
        inv += bdl_particle_inv_inertia_along(p, b, e);
    return bdl_rolling_torque(cp, normal, lever, w_rel, inv, dt);
}

/// The force on i and the torques of the touching pair (i, j): the contact law at the contact
/// point, the spring of the pair updated.
static void pair_force(const bdl_particles *p, const bdl_force_def *def, long i, long j,
                       const rod_contact *c, bdl_vec3 *spring, bdl_pair_result *out)
{
    const bdl_contact_params *cp =
        def->pair_params + p->species[i] * def->species_count + p->species[j];
    const double ri = p->radius[i], rj = p->radius[j];
    bdl_contact_geom g = {.n = c->n,
                          .overlap = c->overlap,
                          .m_eff = 1.0 / (bdl_rod_inv_mass_at(p, i, c->arm_i, c->n) +
                                          bdl_rod_inv_mass_at(p, j, c->arm_j, c->n)),
                          .r_eff = ri * rj / (ri + rj)};
    g.v_c = bdl_v3_sub(bdl_v3_add(p->vel[i], bdl_v3_cross(p->omega[i], c->arm_i)),
                       bdl_v3_add(p->vel[j], bdl_v3_cross(p->omega[j], c->arm_j)));
    const bdl_vec3 u = def->friction ? *spring : bdl_v3_zero();
    const bdl_contact_result res = bdl_contact_eval(cp, def->hertz, def->friction, g, u, def->dt);
    if (def->friction)
        *spring = res.spring;
    out->touching = 1;
    out->force = res.force;
    out->torque_i = bdl_v3_cross(c->arm_i, res.force);
    out->torque_j = bdl_v3_cross(c->arm_j, bdl_v3_neg(res.force));
    if (def->rolling) {
        const double li = bdl_v3_len(c->arm_i), lj = bdl_v3_len(c->arm_j);
        const bdl_vec3 roll = rolling(p, i, j, cp, res.normal, li * lj / (li + lj), def->dt);
        out->torque_i = bdl_v3_add(out->torque_i, roll);
        out->torque_j = bdl_v3_sub(out->torque_j, roll);
    }
}

/// Pair k = (i, partner[k]) with its closest points s: evaluated, its touching flag and history
/// kept up to date.
static bdl_pair_result evaluate_pair_at(bdl_particles *p, bdl_neighbor *nb,
                                        const bdl_force_def *def, long i, int32_t k,
                                        const shaft_pair *s)
{
    bdl_pair_result r = {.touching = 0};
    rod_contact c;
    const long j = nb->partner[k];
    if (contact_from(p, i, j, s, &c)) {
        bdl_vec3 none = bdl_v3_zero();
        pair_force(p, def, i, j, &c, nb->history ? &nb->history[k] : &none, &r);
    } else if (nb->history && nb->touching[k]) {
        nb->history[k] = bdl_v3_zero(); // the contact has ended
    }
    nb->touching[k] = (uint8_t)r.touching;
    return r;
}

static bdl_pair_result evaluate_pair(bdl_particles *p, bdl_neighbor *nb, const bdl_force_def *def,
                                     long i, int32_t k)
{
    const shaft_pair s = shafts_of(p, nb, i, nb->partner[k]);
    return evaluate_pair_at(p, nb, def, i, k, &s);
}

/// Wall contact k of particle i, added to f and t.
static void wall_contact(bdl_particles *p, bdl_neighbor *nb, const bdl_walls *walls,
                         const bdl_force_def *def, long i, int32_t k, bdl_vec3 *f, bdl_vec3 *t)
{
    const int prim = nb->wall_prim[k];
    rod_contact c;
    if (!bdl_rod_wall_contact_of(p, walls, i, prim, &c)) {
        nb->wall_touching[k] = 0;
        nb->wall_force[k] = bdl_v3_zero();
        nb->wall_history[k] = bdl_v3_zero();
        return;
    }
    const int wall = walls->prims[prim].wall;
    bdl_contact_geom g = {.n = c.n,
                          .overlap = c.overlap,
                          .m_eff = 1.0 / bdl_rod_inv_mass_at(p, i, c.arm_i, c.n),
                          .r_eff = bdl_wall_r_eff(walls, prim, p->radius[i])};
    g.v_c = bdl_v3_sub(bdl_v3_add(p->vel[i], bdl_v3_cross(p->omega[i], c.arm_i)),
                       walls->velocity[wall]);
    const bdl_contact_params *cp = def->wall_params + wall * def->species_count + p->species[i];
    const bdl_contact_result res =
        bdl_contact_eval(cp, def->hertz, def->friction, g, nb->wall_history[k], def->dt);
    if (def->friction)
        nb->wall_history[k] = res.spring;
    nb->wall_touching[k] = 1;
    nb->wall_force[k] = res.force;
    *f = bdl_v3_add(*f, res.force);
    *t = bdl_v3_add(*t, bdl_v3_cross(c.arm_i, res.force));
    if (def->rolling)
        *t = bdl_v3_add(*t, rolling(p, i, -1, cp, res.normal, bdl_v3_len(c.arm_i), def->dt));
}

/// Walls, background damping, storage and the closing half kick of particle i, once all its
/// pairs are in: v += h (F/m + g), L += h T, and the angular velocity of the new momentum.
static void finish_particle(bdl_particles *p, bdl_neighbor *nb, const bdl_walls *walls,
                            const bdl_force_def *def, long i, bdl_vec3 f, bdl_vec3 t, double kick)
{
    for (int32_t k = nb->wall_start[i]; k < nb->wall_start[i + 1]; ++k)
        wall_contact(p, nb, walls, def, i, k, &f, &t);
    const double b = def->background_damping[p->species[i]];
    if (b > 0.0)
        f = bdl_v3_madd(f, p->vel[i], -b / p->inv_mass[i]);
    p->load[i] = (bdl_wrench){f, t};
    if (kick > 0.0) {
        p->vel[i] =
            bdl_v3_madd(bdl_v3_madd(p->vel[i], def->gravity, kick), f, kick * p->inv_mass[i]);
        p->ang_mom[i] = bdl_v3_madd(p->ang_mom[i], t, kick);
        p->omega[i] = bdl_particle_omega(p, i, p->ang_mom[i]);
    }
}

/// Thread t's boundary pairs (j in a later range): evaluated and stored for j's owner.
static void boundary_pairs(bdl_particles *p, bdl_neighbor *nb, const bdl_force_def *def,
                           bdl_force_work *fw, int t)
{
    for (long e = fw->out_start[t]; e < fw->out_start[t + 1]; ++e)
        fw->result[e] = evaluate_pair(p, nb, def, fw->pair_i[e], fw->pair[e]);
}

/// Adds -F and the torque of a pair to its second particle j.
static void add_to_j(bdl_particles *p, uint8_t *coordination, long j, const bdl_pair_result *r)
{
    p->load[j].force = bdl_v3_sub(p->load[j].force, r->force);
    p->load[j].torque = bdl_v3_add(p->load[j].torque, r->torque_j);
    if (coordination[j] < 255)
        coordination[j]++;
}

/// Pairs whose closest points are found together (see force_range).
#define ROD_RUN 16

/// Thread t's share: loads cleared, the boundary pairs of earlier ranges added to their j, then
/// every particle in index order, its pairs in list order.
static void force_range(bdl_particles *p, bdl_neighbor *nb, const bdl_walls *walls,
                        const bdl_force_def *def, bdl_force_work *fw, uint8_t *coordination,
                        double kick, int t)
{
    const long lo = fw->range[t], hi = fw->range[t + 1], out_end = fw->out_start[t + 1];
    if (!def->loads_cleared)
        for (long i = lo; i < hi; ++i)
            p->load[i] = (bdl_wrench){bdl_v3_zero(), bdl_v3_zero()};
    memset(coordination + lo, 0, (size_t)(hi - lo));
    for (long c = fw->in_start[t]; c < fw->in_start[t + 1]; ++c) {
        const bdl_pair_result *r = &fw->result[fw->target[c]];
        if (r->touching)
            add_to_j(p, coordination, nb->partner[fw->pair[fw->target[c]]], r);
    }
    long o = fw->out_start[t];
    for (long i = lo; i < hi; ++i) {
        bdl_vec3 f = p->load[i].force, tq = p->load[i].torque;
        int contacts = coordination[i];
        // The closest points of a run of pairs first, then the forces: the runs' divisions and
        // square roots are independent of one another, and the processor overlaps them.
        for (int32_t k0 = nb->start[i]; k0 < nb->start[i + 1]; k0 += ROD_RUN) {
            const int32_t k1 = k0 + ROD_RUN < nb->start[i + 1] ? k0 + ROD_RUN : nb->start[i + 1];
            shaft_pair run[ROD_RUN];
            for (int32_t k = k0; k < k1; ++k)
                run[k - k0] = shafts_of(p, nb, i, nb->partner[k]);
            for (int32_t k = k0; k < k1; ++k) {
                const int boundary = o < out_end && fw->pair[o] == k;
                const bdl_pair_result r =
                    boundary ? fw->result[o++] : evaluate_pair_at(p, nb, def, i, k, &run[k - k0]);
                if (!r.touching)
                    continue;
                if (!boundary)
                    add_to_j(p, coordination, nb->partner[k], &r);
                ++contacts;
                f = bdl_v3_add(f, r.force);
                tq = bdl_v3_add(tq, r.torque_i);
            }
        }
        coordination[i] = (uint8_t)(contacts < 255 ? contacts : 255);
        finish_particle(p, nb, walls, def, i, f, tq, kick);
    }
}

bdl_result bdl_rod_forces(bdl_particles *p, bdl_neighbor *nb, const bdl_walls *walls,
                          const bdl_force_def *def, bdl_force_work *fw, uint8_t *coordination,
                          double kick)
{
    static const bdl_force_pass rods = {boundary_pairs, force_range};
    return bdl_force_run(&rods, p, nb, walls, def, fw, coordination, kick);
}
