// The contact-force pass of scenes with rods, deterministic in parallel as the spheres' pass is
// (contact_force.c: thread ranges, boundary pairs evaluated first and added by their j's owner,
// every particle's sum in list order), and batched as the spheres' pass is (below, at the batch).
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

#include "core/parallel.h"
#include "dem/capsule.h"
#include "dem/contact_law.h"
#include "dem/rigid.h"

/// The contact of two touching shafts from their closest points: w the gap between the points
/// (i's minus j's), d2 = |w|^2, l and m the places along the unit axes u_i and u_j.
static BDL_FORCE_INLINE bdl_rod_contact contact_shape(bdl_vec3 w, double d2, bdl_vec3 ui, double l,
                                                      double ri, bdl_vec3 uj, double m, double rj)
{
    bdl_rod_contact c;
    const double dist = sqrt(d2);
    c.n = bdl_v3_scale(w, 1.0 / dist);
    c.overlap = ri + rj - dist;
    c.arm_i = bdl_v3_madd(bdl_v3_scale(ui, l), c.n, -(ri - 0.5 * c.overlap));
    c.arm_j = bdl_v3_madd(bdl_v3_scale(uj, m), c.n, rj - 0.5 * c.overlap);
    return c;
}

/// (a x n).I^-1 (a x n) + 1/m of an axisymmetric body of axis u, 1/m = im, 1/I transverse it and
/// axial ia: 1/m + |w|^2 / I_t + (1/I_a - 1/I_t)(w . u)^2, w = a x n.
static BDL_FORCE_INLINE double inv_mass_at(double im, double it, double ia, bdl_vec3 u,
                                           bdl_vec3 arm, bdl_vec3 n)
{
    const bdl_vec3 w = bdl_v3_cross(arm, n);
    const double c = bdl_v3_dot(w, u);
    return im + it * bdl_v3_len2(w) + (ia - it) * c * c;
}

int bdl_rod_contact_of(const bdl_particles *p, const bdl_neighbor *nb, long i, long j,
                       bdl_rod_contact *c)
{
    const bdl_vec3 d = bdl_neighbor_delta(nb, p->pos[i], p->pos[j]);
    const bdl_vec3 ui = p->axis[i], uj = p->axis[j];
    double l, m;
    const double d2 = bdl_shafts_closest(d, ui, p->half_length[i], uj, p->half_length[j], &l, &m);
    const double ri = p->radius[i], rj = p->radius[j];
    if (!(d2 < (ri + rj) * (ri + rj)) || d2 == 0.0)
        return 0;
    const bdl_vec3 w = bdl_v3_sub(bdl_v3_madd(d, ui, l), bdl_v3_scale(uj, m));
    *c = contact_shape(w, d2, ui, l, ri, uj, m, rj);
    return 1;
}

double bdl_rod_inv_mass_at(const bdl_particles *p, long i, bdl_vec3 arm, bdl_vec3 n)
{
    const bdl_vec3 inv = p->inv_inertia[i];
    return inv_mass_at(p->inv_mass[i], inv.x, inv.z, p->axis[i], arm, n);
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

/// Wall contact k of particle i, added to f and t.
static void wall_contact(bdl_particles *p, bdl_neighbor *nb, const bdl_walls *walls,
                         const bdl_force_def *def, long i, int32_t k, bdl_vec3 *f, bdl_vec3 *t,
                         bdl_exact_sum *released)
{
    const int prim = nb->wall_prim[k];
    bdl_rod_contact c;
    if (!bdl_rod_wall_contact_of(p, walls, i, prim, &c)) {
        nb->wall_touching[k] = 0;
        nb->wall_force[k] = bdl_v3_zero();
        nb->wall_history[k] = bdl_v3_zero();
        if (nb->wall_spring_work) { // what the spring still holds leaves the bodies
            *released += bdl_exact_term(nb->wall_spring_work[k]);
            nb->wall_spring_work[k] = 0.0;
        }
        return;
    }
    const int wall = bdl_wall_of(walls, prim);
    bdl_contact_geom g = {.n = c.n,
                          .overlap = c.overlap,
                          .m_eff = 1.0 / bdl_rod_inv_mass_at(p, i, c.arm_i, c.n),
                          .r_eff = bdl_wall_r_eff(walls, prim, p->radius[i])};
    g.v_c = bdl_v3_sub(bdl_v3_add(p->vel[i], bdl_v3_cross(p->omega[i], c.arm_i)),
                       bdl_wall_velocity_at(walls, wall, bdl_v3_add(p->pos[i], c.arm_i)));
    const bdl_contact_params *cp = def->wall_params + wall * def->species_count + p->species[i];
    const bdl_spring u = {nb->wall_history[k],
                          nb->wall_spring_work ? nb->wall_spring_work[k] : 0.0};
    const bdl_contact_result res = bdl_contact_eval(cp, def->hertz, def->friction, g, u, def->dt);
    if (def->friction)
        nb->wall_history[k] = res.spring.u;
    if (nb->wall_spring_work)
        nb->wall_spring_work[k] = res.spring.work;
    nb->wall_touching[k] = 1;
    nb->wall_force[k] = res.force;
    *f = bdl_v3_add(*f, res.force);
    *t = bdl_v3_add(*t, bdl_v3_cross(c.arm_i, res.force));
    if (def->rolling)
        *t = bdl_v3_add(*t, rolling(p, i, -1, cp, res.normal, bdl_v3_len(c.arm_i), def->dt));
}

/// Walls, background damping, storage and the closing half kick of particle i, once all its
/// pairs are in: v += h (F/m + g + a_gas), L += h T, and the angular velocity of the new momentum.
static void finish_particle(bdl_particles *p, bdl_neighbor *nb, const bdl_walls *walls,
                            const bdl_force_def *def, long i, bdl_vec3 f, bdl_vec3 t, double kick,
                            bdl_exact_sum *released)
{
    for (int32_t k = nb->wall_start[i]; k < nb->wall_start[i + 1]; ++k)
        wall_contact(p, nb, walls, def, i, k, &f, &t, released);
    const double b = def->background_damping[p->species[i]];
    if (b > 0.0)
        f = bdl_v3_madd(f, bdl_background_slip(def, p, i), -b / p->inv_mass[i]);
    p->load[i] = (bdl_wrench){f, t};
    if (kick > 0.0) {
        const bdl_vec3 g =
            p->fluid_accel ? bdl_v3_add(def->gravity, p->fluid_accel[i]) : def->gravity;
        p->vel[i] = bdl_v3_madd(bdl_v3_madd(p->vel[i], g, kick), f, kick * p->inv_mass[i]);
        p->ang_mom[i] = bdl_v3_madd(p->ang_mom[i], t, kick);
        p->omega[i] = bdl_particle_omega(p, i, p->ang_mom[i]);
    }
}

// Pairs are evaluated in batches of listed pairs, as the spheres' pass does (contact_force.c),
// in five loops per batch:
//   gather   (scalar): the separation of each listed pair, the axes, half lengths and radii;
//   closest  (vectorised): the closest points of the shafts and the touching test;
//   compact  (scalar): the touching pairs moved to the front, flags and ended springs updated,
//            velocities, spins, springs and inertias of the touching pairs gathered;
//   kernel   (vectorised): the contact geometry, the mass at the contact point, the contact law
//            and the torques; the few contacts the trial law flags evaluated again in full;
//   scatter  (scalar): the results added to both particles in the canonical order.
// Every pair is a slot of the batch, whether a run of particles' own pairs or a thread's boundary
// pairs, so a pair gives the same bits on any thread count. The loops compute both sides of their
// selects (the build says the unused side may be evaluated: no trap is enabled), and the geometry
// is that of bdl_rod_contact_of, which the other modules use.

/// Listed pairs per batch.
#define ROD_BATCH 64

typedef struct rod_batch {
    double wx[ROD_BATCH], wy[ROD_BATCH], wz[ROD_BATCH]; ///< separation, then closest-point gap
    double uix[ROD_BATCH], uiy[ROD_BATCH], uiz[ROD_BATCH], hi[ROD_BATCH];
    double ujx[ROD_BATCH], ujy[ROD_BATCH], ujz[ROD_BATCH], hj[ROD_BATCH];
    double ri[ROD_BATCH], rj[ROD_BATCH], l[ROD_BATCH], m[ROD_BATCH], d2[ROD_BATCH];
    double vix[ROD_BATCH], viy[ROD_BATCH], viz[ROD_BATCH];
    double vjx[ROD_BATCH], vjy[ROD_BATCH], vjz[ROD_BATCH];
    double wix[ROD_BATCH], wiy[ROD_BATCH], wiz[ROD_BATCH];
    double wjx[ROD_BATCH], wjy[ROD_BATCH], wjz[ROD_BATCH];
    double ux[ROD_BATCH], uy[ROD_BATCH], uz[ROD_BATCH];    ///< spring
    double unx[ROD_BATCH], uny[ROD_BATCH], unz[ROD_BATCH]; ///< spring after the step
    double work[ROD_BATCH], work_new[ROD_BATCH]; ///< Mindlin springs: work held, after the step
    double imi[ROD_BATCH], iti[ROD_BATCH], iai[ROD_BATCH]; ///< 1/m, 1/I transverse and axial
    double imj[ROD_BATCH], itj[ROD_BATCH], iaj[ROD_BATCH];
    double fx[ROD_BATCH], fy[ROD_BATCH], fz[ROD_BATCH];
    double tix[ROD_BATCH], tiy[ROD_BATCH], tiz[ROD_BATCH], tjx[ROD_BATCH], tjy[ROD_BATCH],
        tjz[ROD_BATCH];
    double fn[ROD_BATCH]; ///< normal force
    double aix[ROD_BATCH], aiy[ROD_BATCH], aiz[ROD_BATCH], ajx[ROD_BATCH], ajy[ROD_BATCH],
        ajz[ROD_BATCH]; ///< arms from the centres to the contact point
    int32_t touch[ROD_BATCH], exceptional[ROD_BATCH];
    int32_t k[ROD_BATCH], i[ROD_BATCH], j[ROD_BATCH], cp[ROD_BATCH];
    int32_t slot[ROD_BATCH]; ///< the gathered slot a touching pair came from
    int32_t end[ROD_BATCH];  ///< per particle of a run: the end of its touching slots
} rod_batch;

/// Gathers pair k = (i, j) into slot q: the separation, shafts and radii.
static inline void gather_shafts(rod_batch *restrict b, int q, const bdl_particles *p,
                                 const bdl_neighbor *nb, long i, int32_t k)
{
    const int32_t j = nb->partner[k];
    const bdl_vec3 d = bdl_neighbor_delta(nb, p->pos[i], p->pos[j]);
    const bdl_vec3 ui = p->axis[i], uj = p->axis[j];
    b->wx[q] = d.x, b->wy[q] = d.y, b->wz[q] = d.z;
    b->uix[q] = ui.x, b->uiy[q] = ui.y, b->uiz[q] = ui.z, b->hi[q] = p->half_length[i];
    b->ujx[q] = uj.x, b->ujy[q] = uj.y, b->ujz[q] = uj.z, b->hj[q] = p->half_length[j];
    b->ri[q] = p->radius[i], b->rj[q] = p->radius[j];
    b->k[q] = k, b->i[q] = (int32_t)i, b->j[q] = j;
}

static inline bdl_vec3 slot_v3(const double *x, const double *y, const double *z, int q)
{
    return bdl_v3(x[q], y[q], z[q]);
}

/// The closest points of slots [0, n): l, m, the gap w between them and the touching flag.
BDL_SIMD_CLONES static void closest_loop(rod_batch *restrict b, int n)
{
#if defined(_OPENMP)
#pragma omp simd
#endif
    for (int q = 0; q < n; ++q) {
        const bdl_vec3 d = slot_v3(b->wx, b->wy, b->wz, q);
        const bdl_vec3 ui = slot_v3(b->uix, b->uiy, b->uiz, q);
        const bdl_vec3 uj = slot_v3(b->ujx, b->ujy, b->ujz, q);
        double l, m;
        const double d2 = bdl_shafts_closest(d, ui, b->hi[q], uj, b->hj[q], &l, &m);
        const bdl_vec3 w = bdl_v3_sub(bdl_v3_madd(d, ui, l), bdl_v3_scale(uj, m));
        const double cut = b->ri[q] + b->rj[q];
        b->wx[q] = w.x, b->wy[q] = w.y, b->wz[q] = w.z;
        b->l[q] = l, b->m[q] = m, b->d2[q] = d2;
        b->touch[q] = (d2 < cut * cut) & (d2 != 0.0);
    }
}

/// Moves touching slot s to slot q <= s (the shafts' part of it).
static inline void move_slot(rod_batch *restrict b, int q, int s)
{
    b->wx[q] = b->wx[s], b->wy[q] = b->wy[s], b->wz[q] = b->wz[s];
    b->uix[q] = b->uix[s], b->uiy[q] = b->uiy[s], b->uiz[q] = b->uiz[s];
    b->ujx[q] = b->ujx[s], b->ujy[q] = b->ujy[s], b->ujz[q] = b->ujz[s];
    b->ri[q] = b->ri[s], b->rj[q] = b->rj[s], b->l[q] = b->l[s], b->m[q] = b->m[s];
    b->d2[q] = b->d2[s], b->k[q] = b->k[s], b->i[q] = b->i[s], b->j[q] = b->j[s];
    b->slot[q] = s;
}

/// Touching flags and ended springs of slots [0, n) brought up to date (what an ended Mindlin
/// spring held added to *released), the touching slots moved to the front (in order); returns
/// their count.
static int compact(rod_batch *restrict b, int n, bdl_neighbor *nb, bdl_exact_sum *released)
{
    int c = 0;
    for (int s = 0; s < n; ++s) {
        const int32_t k = b->k[s], touching = b->touch[s];
        if (nb->history && nb->touching[k] && !touching) { // the contact has ended
            nb->history[k] = bdl_v3_zero();
            if (nb->spring_work) { // what the spring still holds leaves the bodies
                *released += bdl_exact_term(nb->spring_work[k]);
                nb->spring_work[k] = 0.0;
            }
        }
        nb->touching[k] = (uint8_t)touching;
        move_slot(b, c, s);
        c += touching;
    }
    return c;
}

/// The motion, inertia and spring of the touching slots [0, c).
static void gather_motion(rod_batch *restrict b, int c, const bdl_particles *p,
                          const bdl_neighbor *nb, int species_count)
{
    for (int q = 0; q < c; ++q) {
        const int32_t i = b->i[q], j = b->j[q];
        const bdl_vec3 vi = p->vel[i], wi = p->omega[i], wj = p->omega[j];
        const bdl_vec3 vj =
            bdl_v3_add(p->vel[j], bdl_neighbor_image_velocity(nb, p->pos[i], p->pos[j]));
        const bdl_vec3 ii = p->inv_inertia[i], ij = p->inv_inertia[j];
        b->vix[q] = vi.x, b->viy[q] = vi.y, b->viz[q] = vi.z;
        b->vjx[q] = vj.x, b->vjy[q] = vj.y, b->vjz[q] = vj.z;
        b->wix[q] = wi.x, b->wiy[q] = wi.y, b->wiz[q] = wi.z;
        b->wjx[q] = wj.x, b->wjy[q] = wj.y, b->wjz[q] = wj.z;
        b->imi[q] = p->inv_mass[i], b->iti[q] = ii.x, b->iai[q] = ii.z;
        b->imj[q] = p->inv_mass[j], b->itj[q] = ij.x, b->iaj[q] = ij.z;
        b->cp[q] = p->species[i] * species_count + p->species[j];
        const bdl_vec3 u = nb->history ? nb->history[b->k[q]] : bdl_v3_zero();
        b->ux[q] = u.x, b->uy[q] = u.y, b->uz[q] = u.z;
        b->work[q] = nb->spring_work ? nb->spring_work[b->k[q]] : 0.0;
    }
}

/// The contact of touching slot q: geometry, the law, forces and torques stored. Returns whether
/// a trial evaluation left something out (see bdl_contact_eval_mode).
static BDL_FORCE_INLINE int rod_slot(rod_batch *restrict b, int q, const bdl_contact_params *table,
                                     int hertz, int friction, double dt, int trial)
{
    const bdl_contact_params *cp = table + b->cp[q];
    const double ri = b->ri[q], rj = b->rj[q], l = b->l[q], m = b->m[q];
    const bdl_vec3 ui = slot_v3(b->uix, b->uiy, b->uiz, q);
    const bdl_vec3 uj = slot_v3(b->ujx, b->ujy, b->ujz, q);
    const bdl_rod_contact c =
        contact_shape(slot_v3(b->wx, b->wy, b->wz, q), b->d2[q], ui, l, ri, uj, m, rj);
    bdl_contact_geom g = {.n = c.n,
                          .overlap = c.overlap,
                          .m_eff = 1.0 /
                                   (inv_mass_at(b->imi[q], b->iti[q], b->iai[q], ui, c.arm_i, c.n) +
                                    inv_mass_at(b->imj[q], b->itj[q], b->iaj[q], uj, c.arm_j, c.n)),
                          .r_eff = ri * rj / (ri + rj)};
    const bdl_vec3 wi = slot_v3(b->wix, b->wiy, b->wiz, q), wj = slot_v3(b->wjx, b->wjy, b->wjz, q);
    g.v_c = bdl_v3_sub(bdl_v3_add(slot_v3(b->vix, b->viy, b->viz, q), bdl_v3_cross(wi, c.arm_i)),
                       bdl_v3_add(slot_v3(b->vjx, b->vjy, b->vjz, q), bdl_v3_cross(wj, c.arm_j)));
    const bdl_spring u = {friction ? slot_v3(b->ux, b->uy, b->uz, q) : bdl_v3_zero(), b->work[q]};
    const bdl_contact_result res = bdl_contact_eval_mode(cp, hertz, friction, g, u, dt, trial);
    const bdl_vec3 ti = bdl_v3_cross(c.arm_i, res.force);
    const bdl_vec3 tj = bdl_v3_cross(c.arm_j, bdl_v3_neg(res.force));
    b->fx[q] = res.force.x, b->fy[q] = res.force.y, b->fz[q] = res.force.z;
    b->tix[q] = ti.x, b->tiy[q] = ti.y, b->tiz[q] = ti.z;
    b->tjx[q] = tj.x, b->tjy[q] = tj.y, b->tjz[q] = tj.z;
    if (friction)
        b->unx[q] = res.spring.u.x, b->uny[q] = res.spring.u.y, b->unz[q] = res.spring.u.z;
    b->work_new[q] = res.spring.work;
    b->fn[q] = res.normal;
    b->aix[q] = c.arm_i.x, b->aiy[q] = c.arm_i.y, b->aiz[q] = c.arm_i.z;
    b->ajx[q] = c.arm_j.x, b->ajy[q] = c.arm_j.y, b->ajz[q] = c.arm_j.z;
    return res.exceptional;
}

/// Slot q again with the full law. Not inlined, so that the loop calling it for the few flagged
/// slots is not vectorised.
__attribute__((noinline)) static void
rod_slot_full(rod_batch *b, int q, const bdl_contact_params *table, int hertz, double dt)
{
    hertz ? rod_slot(b, q, table, 1, 1, dt, 0) : rod_slot(b, q, table, 0, 1, dt, 0);
}

/// The contacts of slots [0, c): a vectorised trial evaluation, then the full law for the slots
/// it flagged. `hertz` and `friction` are constants in each instantiation.
static BDL_FORCE_INLINE void kernel_loop(rod_batch *restrict b, int c, const bdl_force_def *def,
                                         int hertz, int friction)
{
    const bdl_contact_params *table = def->pair_params;
    const double dt = def->dt;
#if defined(_OPENMP)
#pragma omp simd
#endif
    for (int q = 0; q < c; ++q)
        b->exceptional[q] = rod_slot(b, q, table, hertz, friction, dt, 1);
    if (!friction)
        return;
    for (int q = 0; q < c; ++q)
        if (b->exceptional[q])
            rod_slot_full(b, q, table, hertz, dt);
}

BDL_SIMD_CLONES static void kernel(rod_batch *b, int c, const bdl_force_def *def)
{
    if (def->hertz)
        def->friction ? kernel_loop(b, c, def, 1, 1) : kernel_loop(b, c, def, 1, 0);
    else
        def->friction ? kernel_loop(b, c, def, 0, 1) : kernel_loop(b, c, def, 0, 0);
}

/// Evaluates the n gathered slots of a batch: returns the count c of touching pairs, whose
/// results are in slots [0, c) (b->slot[q] the gathered slot of each).
static int evaluate_batch(rod_batch *b, int n, bdl_particles *p, bdl_neighbor *nb,
                          const bdl_force_def *def, bdl_exact_sum *released)
{
    closest_loop(b, n);
    const int c = compact(b, n, nb, released);
    gather_motion(b, c, p, nb, def->species_count);
    kernel(b, c, def);
    for (int q = 0; q < c; ++q) {
        if (nb->history)
            nb->history[b->k[q]] = def->friction ? slot_v3(b->unx, b->uny, b->unz, q)
                                                 : slot_v3(b->ux, b->uy, b->uz, q);
        if (nb->spring_work)
            nb->spring_work[b->k[q]] = b->work_new[q];
        if (def->rolling) {
            const int32_t i = b->i[q], j = b->j[q];
            const bdl_contact_params *cp = def->pair_params + b->cp[q];
            const double li = bdl_v3_len(slot_v3(b->aix, b->aiy, b->aiz, q));
            const double lj = bdl_v3_len(slot_v3(b->ajx, b->ajy, b->ajz, q));
            const bdl_vec3 roll = rolling(p, i, j, cp, b->fn[q], li * lj / (li + lj), def->dt);
            b->tix[q] += roll.x, b->tiy[q] += roll.y, b->tiz[q] += roll.z;
            b->tjx[q] -= roll.x, b->tjy[q] -= roll.y, b->tjz[q] -= roll.z;
        }
    }
    return c;
}

static inline bdl_pair_result slot_result(const rod_batch *b, int q)
{
    bdl_pair_result r = {.force = slot_v3(b->fx, b->fy, b->fz, q),
                         .torque_i = slot_v3(b->tix, b->tiy, b->tiz, q),
                         .torque_j = slot_v3(b->tjx, b->tjy, b->tjz, q),
                         .touching = 1};
    return r;
}

/// Thread t's boundary pairs (j in a later range): evaluated and stored for j's owner.
static void boundary_pairs(bdl_particles *p, bdl_neighbor *nb, const bdl_force_def *def,
                           bdl_force_work *fw, int t)
{
    rod_batch b;
    for (long first = fw->out_start[t]; first < fw->out_start[t + 1]; first += ROD_BATCH) {
        const long last =
            first + ROD_BATCH < fw->out_start[t + 1] ? first + ROD_BATCH : fw->out_start[t + 1];
        for (long e = first; e < last; ++e) {
            gather_shafts(&b, (int)(e - first), p, nb, fw->pair_i[e], fw->pair[e]);
            fw->result[e].touching = 0;
        }
        const int c = evaluate_batch(&b, (int)(last - first), p, nb, def, &fw->released[t]);
        for (int q = 0; q < c; ++q)
            fw->result[first + b.slot[q]] = slot_result(&b, q);
    }
}

/// Adds -F and the torque of a pair to its second particle j.
static void add_to_j(bdl_particles *p, uint8_t *coordination, long j, const bdl_pair_result *r)
{
    p->load[j].force = bdl_v3_sub(p->load[j].force, r->force);
    p->load[j].torque = bdl_v3_add(p->load[j].torque, r->torque_j);
    if (coordination[j] < 255)
        coordination[j]++;
}

/// Running sums of the particle being accumulated.
typedef struct rod_sum {
    bdl_vec3 f, t;
    int contacts;
} rod_sum;

static inline void sum_add(rod_sum *s, const bdl_pair_result *r)
{
    ++s->contacts;
    s->f = bdl_v3_add(s->f, r->force);
    s->t = bdl_v3_add(s->t, r->torque_i);
}

/// What one thread's share of the pass works with.
typedef struct rod_range {
    bdl_particles *p;
    bdl_neighbor *nb;
    const bdl_walls *walls;
    const bdl_force_def *def;
    const bdl_force_work *fw;
    uint8_t *coordination;
    bdl_exact_sum *released; ///< this thread's (bdl_force_work)
    double kick;
    long hi, out_end; ///< end of the range and of its boundary pairs
} rod_range;

/// Gathers the listed pairs [k0, k1) (of the particles their owners name) into b, the boundary
/// pairs left out (the cursor *out passes them), and evaluates them; b->end[i - first] is the end
/// of particle i's touching slots. Returns the count of touching slots.
static int run_pairs(const rod_range *r, rod_batch *b, long first, int32_t k0, int32_t k1, long out)
{
    const int32_t *owner = r->fw->owner, *boundary = r->fw->pair;
    int n = 0;
    for (int32_t k = k0; k < k1; ++k) {
        if (out < r->out_end && boundary[out] == k) {
            ++out;
            continue;
        }
        gather_shafts(b, n++, r->p, r->nb, owner[k], k);
    }
    const int c = evaluate_batch(b, n, r->p, r->nb, r->def, r->released);
    for (int q = 0; q < c; ++q)
        b->end[b->i[q] - first] = q + 1;
    return c;
}

/// Adds the touching slots from *q on of particle i and its boundary pairs listed before k_end
/// to i's sum and to their j, in list order.
static void accumulate(const rod_range *r, const rod_batch *b, int *q, int q_end, int32_t k_end,
                       long *out, rod_sum *sum)
{
    const bdl_force_work *fw = r->fw;
    for (;;) {
        if (*out < r->out_end && fw->pair[*out] < k_end &&
            (*q == q_end || fw->pair[*out] < b->k[*q])) {
            const bdl_pair_result *res = &fw->result[(*out)++];
            if (res->touching)
                sum_add(sum, res);
            continue;
        }
        if (*q == q_end)
            return;
        const bdl_pair_result res = slot_result(b, *q);
        add_to_j(r->p, r->coordination, b->j[*q], &res);
        sum_add(sum, &res);
        ++*q;
    }
}

static inline rod_sum sum_start(const rod_range *r, long i)
{
    rod_sum s = {r->p->load[i].force, r->p->load[i].torque, r->coordination[i]};
    return s;
}

static inline void sum_finish(const rod_range *r, long i, const rod_sum *s)
{
    r->coordination[i] = (uint8_t)(s->contacts < 255 ? s->contacts : 255);
    finish_particle(r->p, r->nb, r->walls, r->def, i, s->f, s->t, r->kick, r->released);
}

/// Particle i with more listed pairs than a batch holds: a batch at a time. Returns the cursor of
/// the boundary pairs after i's.
static long crowded_particle(const rod_range *r, rod_batch *b, long i, long out)
{
    rod_sum sum = sum_start(r, i);
    const int32_t *start = r->nb->start;
    for (int32_t k = start[i]; k < start[i + 1]; k += ROD_BATCH) {
        const int32_t k_end = k + ROD_BATCH < start[i + 1] ? k + ROD_BATCH : start[i + 1];
        int q = 0;
        const int c = run_pairs(r, b, i, k, k_end, out);
        accumulate(r, b, &q, c, k_end, &out, &sum);
    }
    sum_finish(r, i, &sum);
    return out;
}

/// The particles from `first` whose pairs fit in one batch, evaluated together; returns the end
/// of the run (and moves the cursor of the boundary pairs past it).
static long particle_run(const rod_range *r, rod_batch *b, long first, long *out)
{
    const int32_t *start = r->nb->start;
    long end = first;
    while (end < r->hi && end - first < ROD_BATCH && start[end + 1] - start[first] <= ROD_BATCH)
        b->end[end++ - first] = -1;
    run_pairs(r, b, first, start[first], start[end], *out);
    int q = 0, last = 0;
    for (long i = first; i < end; ++i) {
        last = b->end[i - first] < 0 ? last : b->end[i - first];
        rod_sum sum = sum_start(r, i);
        accumulate(r, b, &q, last, start[i + 1], out, &sum);
        sum_finish(r, i, &sum);
    }
    return end;
}

/// Thread t's share: loads cleared, the boundary pairs of earlier ranges added to their j, then
/// every particle in index order, its pairs in list order.
static void force_range(bdl_particles *p, bdl_neighbor *nb, const bdl_walls *walls,
                        const bdl_force_def *def, bdl_force_work *fw, uint8_t *coordination,
                        double kick, int t)
{
    const rod_range r = {p,
                         nb,
                         walls,
                         def,
                         fw,
                         coordination,
                         &fw->released[t],
                         kick,
                         fw->range[t + 1],
                         fw->out_start[t + 1]};
    const long lo = fw->range[t];
    if (!def->loads_cleared)
        for (long i = lo; i < r.hi; ++i)
            p->load[i] = (bdl_wrench){bdl_v3_zero(), bdl_v3_zero()};
    memset(coordination + lo, 0, (size_t)(r.hi - lo));
    for (long c = fw->in_start[t]; c < fw->in_start[t + 1]; ++c) {
        const bdl_pair_result *res = &fw->result[fw->target[c]];
        if (res->touching)
            add_to_j(p, coordination, nb->partner[fw->pair[fw->target[c]]], res);
    }
    rod_batch b;
    long out = fw->out_start[t];
    for (long i = lo; i < r.hi;) {
        if (nb->start[i + 1] - nb->start[i] > ROD_BATCH)
            out = crowded_particle(&r, &b, i++, out);
        else
            i = particle_run(&r, &b, i, &out);
    }
}

bdl_result bdl_rod_forces(bdl_particles *p, bdl_neighbor *nb, const bdl_walls *walls,
                          const bdl_force_def *def, bdl_force_work *fw, uint8_t *coordination,
                          double kick)
{
    static const bdl_force_pass rods = {boundary_pairs, force_range};
    return bdl_force_run(&rods, p, nb, walls, def, fw, coordination, kick);
}
