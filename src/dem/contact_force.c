// The contact-force pass, deterministic in parallel.
//
// Particles are split into one contiguous index range per thread. Each particle's force is
// summed in one canonical order whatever the thread count: the contributions of its pairs ordered
// by the pair's first particle i, and within i by list order. A pair (i, j) with j > i is
// evaluated once, when the loop over i reaches it: i keeps +F in a register, j receives -F at
// once (its own turn comes later). Pairs whose j lies in a later thread's range ("boundary
// pairs") are evaluated first, in a separate phase, and stored; the owner of j adds them before
// its own loop, which preserves the canonical order because every i of an earlier range is
// smaller than every i of its own. When the loop passes particle i, every pair involving i has
// been evaluated, so i's walls, damping and closing half kick are applied right there: one pass
// over the particles per step. No floating-point atomics, no thread-count-dependent sums: the
// state after N steps is bitwise the same for any thread count.
#include "dem/contact_force.h"
#include "core/memory.h"
#include "core/parallel.h"

#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>

#include "dem/contact_law.h"

#if defined(__GNUC__)
#define BDL_PREFETCH(address)    __builtin_prefetch(address)
#define BDL_PREFETCH_L2(address) __builtin_prefetch(address, 0, 2)
#else
#define BDL_PREFETCH(address)    ((void)(address))
#define BDL_PREFETCH_L2(address) ((void)(address))
#endif

typedef bdl_pair_result pair_result;

// Pairs are evaluated in batches, three loops per batch:
//   gather  (scalar): for each listed pair of a run of particles, the separation and the touching
//           test; every touching pair is appended (without a branch) to the batch, with the
//           state the contact law reads, as structure-of-arrays;
//   kernel  (vectorised): the contact law over the batch, no branches;
//   scatter (scalar): the results are added to both particles in the canonical order.
// The gather and scatter loops are short and have no unpredictable branch, and the kernel runs
// its square roots and divisions for several contacts at once instead of one latency-bound chain
// after the other. When every particle has the same species, radius and mass ("uniform", checked
// at each neighbour build) the gather skips those loads; the arithmetic, and so the result, is
// the same either way.

/// How many pairs ahead the gather prefetches the partner's state (into L2: far enough ahead to
/// cover a miss to memory in the large beds, without crowding L1 in the small ones).
#ifndef PREFETCH_AHEAD
#define PREFETCH_AHEAD 32 ///< pairs
#endif

/// How many particles (or pairs) ahead the force pass prefetches the arrays it reads in order:
/// it reads more of them at once than the hardware prefetcher follows (docs/performance.md).
#ifndef STREAM_AHEAD
#define STREAM_AHEAD 32
#endif

/// Listed pairs per batch. A particle with more pairs is evaluated in several batches.
#define BATCH 64

typedef struct bdl_pair_batch {
    // inputs (the spring u is updated in place)
    double dx[BATCH], dy[BATCH], dz[BATCH], d2[BATCH];
    double ri[BATCH], rj[BATCH], imi[BATCH], imj[BATCH]; // not filled when uniform
    double dvx[BATCH], dvy[BATCH], dvz[BATCH];
    double wix[BATCH], wiy[BATCH], wiz[BATCH], wjx[BATCH], wjy[BATCH], wjz[BATCH];
    double ux[BATCH], uy[BATCH], uz[BATCH], work[BATCH]; ///< work: Hertz-Mindlin springs
    // outputs
    double unx[BATCH], uny[BATCH], unz[BATCH], work_new[BATCH]; ///< the spring after this step
    double fx[BATCH], fy[BATCH], fz[BATCH];
    double tix[BATCH], tiy[BATCH], tiz[BATCH], tjx[BATCH], tjy[BATCH], tjz[BATCH];
    double fn[BATCH], reff[BATCH];
    int32_t k[BATCH], i[BATCH], j[BATCH], cp[BATCH];
    int32_t exceptional[BATCH]; ///< the trial evaluation left something out
    int32_t end[BATCH];         ///< per particle of the run: end of its slots (or a slot's entry)
} pair_batch;

/// What the gather reads, copied out of the structures so that the compiler keeps it in
/// registers (a store through uint8_t * may alias anything).
typedef struct gather_view {
    const bdl_vec3 *pos, *vel, *omega;
    const bdl_wrench *load;
    const double *radius, *inv_mass;
    const int32_t *species, *partner;
    uint8_t *touching;
    bdl_vec3 *history;
    double *spring_work;     ///< Hertz-Mindlin springs only
    bdl_exact_sum *released; ///< this thread's: what springs held when their contacts ended
    double len[3], half[3];  ///< per axis; a closed axis has len 0 and half infinite
    double shift, jump;      ///< Lees–Edwards: the image above's x offset and x velocity
    /// MPI ranks (nb->ghosted): a pair's released work is booked by the rank that owns its
    /// particle of the lower id (the others hold copies of the pair); NULL in one process.
    const uint32_t *id;
    long owned;
    int ns;
    double cut; ///< r_i + r_j when uniform
} gather_view;

static gather_view make_view(const bdl_particles *p, bdl_neighbor *nb, const bdl_force_def *def,
                             bdl_force_work *fw, int t)
{
    gather_view v;
    v.released = &fw->released[t];
    v.pos = p->pos;
    v.vel = p->vel;
    v.omega = p->omega;
    v.load = p->load;
    v.radius = p->radius;
    v.inv_mass = p->inv_mass;
    v.species = p->species;
    v.partner = nb->partner;
    v.touching = nb->touching;
    v.history = nb->history;
    v.spring_work = nb->spring_work;
    for (int a = 0; a < 3; ++a) {
        v.len[a] = nb->periodic[a] ? bdl_v3_comp(nb->length, a) : 0.0;
        v.half[a] = nb->periodic[a] ? 0.5 * v.len[a] : INFINITY;
    }
    v.shift = nb->shear_shift;
    v.jump = nb->shear_velocity;
    v.id = nb->ghosted ? p->id : NULL;
    v.owned = nb->owned;
    v.ns = def->species_count;
    v.cut = fw->radius + fw->radius;
    return v;
}

/// Minimum image along one axis, as bdl_neighbor_delta (the same result, as selects: on a closed
/// axis `half` is infinite).
static inline double wrap(double d, double len, double half)
{
    d = d > half ? d - len : d;
    return d < -half ? d + len : d;
}

/// The state of particle i that every pair of i reads.
typedef struct particle_i {
    int32_t i, species;
    bdl_vec3 x;
    double r, im;
} particle_i;

static inline particle_i load_i(const gather_view *v, long i)
{
    particle_i pi = {(int32_t)i, v->species[i], v->pos[i], v->radius[i], v->inv_mass[i]};
    return pi;
}

/// Writes the separation of pair k = (i, j) to slot m of the batch and returns 1 if the pair
/// overlaps (else the slot is left to be overwritten and 0 is returned). Updates the pair's
/// touching flag, and clears its history when a contact has ended.
static BDL_FORCE_INLINE int gather_pair(pair_batch *restrict b, int m, const gather_view *v,
                                        const particle_i *pi, int32_t k, int uniform)
{
    int32_t j = v->partner[k];
    bdl_vec3 xj = v->pos[j];
    double d_x = pi->x.x - xj.x, d_z = pi->x.z - xj.z;
    if (v->shift != 0.0) // Lees–Edwards: a partner across the z faces is met as its image
        d_x -= (double)((d_z > v->half[2]) - (d_z < -v->half[2])) * v->shift;
    d_x = wrap(d_x, v->len[0], v->half[0]);
    double d_y = wrap(pi->x.y - xj.y, v->len[1], v->half[1]);
    d_z = wrap(d_z, v->len[2], v->half[2]);
    double cut;
    if (uniform) {
        cut = v->cut;
    } else {
        double rj = v->radius[j];
        cut = pi->r + rj;
        b->ri[m] = pi->r;
        b->rj[m] = rj;
        b->imi[m] = pi->im;
        b->imj[m] = v->inv_mass[j];
        b->cp[m] = pi->species * v->ns + v->species[j];
    }
    double d2 = d_x * d_x + d_y * d_y + d_z * d_z;
    int touching = !(d2 >= cut * cut) & (d2 != 0.0);
    b->dx[m] = d_x;
    b->dy[m] = d_y;
    b->dz[m] = d_z;
    b->d2[m] = d2;
    b->k[m] = k;
    b->i[m] = pi->i;
    b->j[m] = j;
    uint8_t was = v->touching[k];
    v->touching[k] = (uint8_t)touching;
    if (v->history && (was & !touching)) { // the contact has ended
        v->history[k] = bdl_v3_zero();
        if (v->spring_work) { // what the spring still holds leaves the bodies
            const long lower = !v->id ? 0 : v->id[pi->i] < v->id[j] ? pi->i : j;
            if (lower < v->owned || !v->id)
                *v->released += bdl_exact_term(v->spring_work[k]);
            v->spring_work[k] = 0.0;
        }
    }
    return touching;
}

/// Second gather loop, over the overlapping pairs only: velocities, spins and springs.
static void gather_motion(pair_batch *restrict b, int m, const gather_view *v)
{
    const bdl_vec3 *vel = v->vel, *omega = v->omega;
    const bdl_vec3 *history = v->history;
    for (int q = 0; q < m; ++q) {
        int32_t i = b->i[q], j = b->j[q];
        bdl_vec3 vi = vel[i], vj = vel[j], wi = omega[i], wj = omega[j];
        b->dvx[q] = vi.x - vj.x;
        b->dvy[q] = vi.y - vj.y;
        b->dvz[q] = vi.z - vj.z;
        b->wix[q] = wi.x;
        b->wiy[q] = wi.y;
        b->wiz[q] = wi.z;
        b->wjx[q] = wj.x;
        b->wjy[q] = wj.y;
        b->wjz[q] = wj.z;
    }
    if (v->jump != 0.0) // Lees–Edwards: a partner across the z faces is met as its image
        for (int q = 0; q < m; ++q) {
            double d_z = v->pos[b->i[q]].z - v->pos[b->j[q]].z;
            b->dvx[q] -= (double)((d_z > v->half[2]) - (d_z < -v->half[2])) * v->jump;
        }
    if (history) {
        for (int q = 0; q < m; ++q) {
            bdl_vec3 u = history[b->k[q]];
            b->ux[q] = u.x;
            b->uy[q] = u.y;
            b->uz[q] = u.z;
        }
    }
    if (v->spring_work)
        for (int q = 0; q < m; ++q)
            b->work[q] = v->spring_work[b->k[q]];
}

/// Loop invariants of the contact law over a batch.
typedef struct kernel_consts {
    const bdl_contact_params *params; ///< pair table
    bdl_contact_params uniform;       ///< the one pair when uniform
    double r, m_eff, r_eff;           ///< when uniform: radius, m*, R*
    double dt;
} kernel_consts;

static kernel_consts make_consts(const bdl_force_def *def, const bdl_force_work *fw)
{
    kernel_consts kc;
    kc.params = def->pair_params;
    kc.uniform = def->pair_params[fw->species * def->species_count + fw->species];
    double r = fw->radius, im = fw->inv_mass;
    kc.r = r;
    kc.m_eff = 1.0 / (im + im);
    kc.r_eff = r * r / (r + r);
    kc.dt = def->dt;
    return kc;
}

/// The contact law for slot q of a batch: geometry from the gathered state, the law, the results
/// stored. Returns whether a trial evaluation left something out (see bdl_contact_eval_mode).
static BDL_FORCE_INLINE int eval_slot(pair_batch *restrict b, int q, const kernel_consts *kc,
                                      int hertz, int friction, int torques, int uniform, int trial)
{
    const bdl_contact_params *cp = uniform ? &kc->uniform : kc->params + b->cp[q];
    double ri = uniform ? kc->r : b->ri[q], rj = uniform ? kc->r : b->rj[q];
    // Lever arms run from each centre to the middle of the overlap, r - delta/2, so that the
    // two arms add up to the centre distance and a pair conserves angular momentum exactly.
    double dist = sqrt(b->d2[q]);
    double inv = 1.0 / dist;
    bdl_contact_geom g;
    g.n = bdl_v3(b->dx[q] * inv, b->dy[q] * inv, b->dz[q] * inv);
    g.overlap = ri + rj - dist;
    double arm_i = ri - 0.5 * g.overlap;
    double arm_j = rj - 0.5 * g.overlap;
    bdl_vec3 spin =
        bdl_v3(b->wix[q] * arm_i + b->wjx[q] * arm_j, b->wiy[q] * arm_i + b->wjy[q] * arm_j,
               b->wiz[q] * arm_i + b->wjz[q] * arm_j);
    bdl_vec3 sxn = bdl_v3_cross(spin, g.n);
    g.v_c = bdl_v3(b->dvx[q] - sxn.x, b->dvy[q] - sxn.y, b->dvz[q] - sxn.z);
    g.m_eff = uniform ? kc->m_eff : 1.0 / (b->imi[q] + b->imj[q]);
    g.r_eff = uniform ? kc->r_eff : ri * rj / (ri + rj);
    bdl_spring u = {friction ? bdl_v3(b->ux[q], b->uy[q], b->uz[q]) : bdl_v3_zero(),
                    hertz && friction ? b->work[q] : 0.0};
    bdl_contact_result c = bdl_contact_eval_mode(cp, hertz, friction, g, u, kc->dt, trial);
    b->fx[q] = c.force.x;
    b->fy[q] = c.force.y;
    b->fz[q] = c.force.z;
    if (friction) {
        b->unx[q] = c.spring.u.x;
        b->uny[q] = c.spring.u.y;
        b->unz[q] = c.spring.u.z;
    }
    if (hertz && friction)
        b->work_new[q] = c.spring.work;
    if (torques) {
        b->tix[q] = c.n_x_ft.x * -arm_i;
        b->tiy[q] = c.n_x_ft.y * -arm_i;
        b->tiz[q] = c.n_x_ft.z * -arm_i;
        b->tjx[q] = c.n_x_ft.x * -arm_j;
        b->tjy[q] = c.n_x_ft.y * -arm_j;
        b->tjz[q] = c.n_x_ft.z * -arm_j;
    }
    b->fn[q] = c.normal;
    b->reff[q] = g.r_eff;
    return c.exceptional;
}

/// The full contact law (with friction) for one slot that the trial evaluation flagged. Not
/// inlined, so that the loop calling it for the few flagged slots is not vectorised.
#if defined(__GNUC__)
__attribute__((noinline))
#endif
static void
eval_slot_full(pair_batch *b, int q, const kernel_consts *kc, int hertz, int uniform)
{
    // With friction there are torques.
    if (hertz)
        uniform ? eval_slot(b, q, kc, 1, 1, 1, 1, 0) : eval_slot(b, q, kc, 1, 1, 1, 0, 0);
    else
        uniform ? eval_slot(b, q, kc, 0, 1, 1, 1, 0) : eval_slot(b, q, kc, 0, 1, 1, 0, 0);
}

/// The contact law over slots [0, m) of a batch: a vectorised trial evaluation of all, then the
/// full law for the few it flagged (sliding contacts, fast-turning springs). `hertz`, `friction`,
/// `torques` and `uniform` are constants in each instantiation below, so the loop has no branches.
static BDL_FORCE_INLINE void kernel_loop(pair_batch *restrict b, int m, const bdl_force_def *def,
                                         const bdl_force_work *fw, int hertz, int friction,
                                         int torques, int uniform)
{
    const kernel_consts kc = make_consts(def, fw);
#if defined(_OPENMP)
#pragma omp simd
#endif
    for (int q = 0; q < m; ++q)
        b->exceptional[q] = eval_slot(b, q, &kc, hertz, friction, torques, uniform, 1);
    if (!friction)
        return;
    for (int q = 0; q < m; ++q)
        if (b->exceptional[q])
            eval_slot_full(b, q, &kc, hertz, uniform);
}

/// Evaluates slots [0, m) of a batch: the contact law, then rolling resistance.
BDL_SIMD_CLONES static void eval_batch(pair_batch *b, int m, const bdl_particles *p,
                                       const bdl_force_def *def, const bdl_force_work *fw,
                                       const gather_view *v)
{
    int torques = def->friction || def->rolling;
    gather_motion(b, m, v);
    // One instantiation per combination, so that each loop is free of branches.
    int u = fw->uniform;
    if (def->hertz && def->friction)
        u ? kernel_loop(b, m, def, fw, 1, 1, 1, 1) : kernel_loop(b, m, def, fw, 1, 1, 1, 0);
    else if (def->hertz && torques)
        u ? kernel_loop(b, m, def, fw, 1, 0, 1, 1) : kernel_loop(b, m, def, fw, 1, 0, 1, 0);
    else if (def->hertz)
        u ? kernel_loop(b, m, def, fw, 1, 0, 0, 1) : kernel_loop(b, m, def, fw, 1, 0, 0, 0);
    else if (def->friction)
        u ? kernel_loop(b, m, def, fw, 0, 1, 1, 1) : kernel_loop(b, m, def, fw, 0, 1, 1, 0);
    else if (torques)
        u ? kernel_loop(b, m, def, fw, 0, 0, 1, 1) : kernel_loop(b, m, def, fw, 0, 0, 1, 0);
    else
        u ? kernel_loop(b, m, def, fw, 0, 0, 0, 1) : kernel_loop(b, m, def, fw, 0, 0, 0, 0);
    if (!def->rolling)
        return;
    for (int q = 0; q < m; ++q) {
        int32_t i = b->i[q], j = b->j[q];
        const bdl_contact_params *cp =
            def->pair_params + p->species[i] * def->species_count + p->species[j];
        double inv_i = bdl_particle_inv_inertia(p, i) + bdl_particle_inv_inertia(p, j);
        bdl_vec3 roll = bdl_rolling_torque(cp, b->fn[q], b->reff[q],
                                           bdl_v3_sub(p->omega[i], p->omega[j]), inv_i, def->dt);
        b->tix[q] += roll.x;
        b->tiy[q] += roll.y;
        b->tiz[q] += roll.z;
        b->tjx[q] -= roll.x;
        b->tjy[q] -= roll.y;
        b->tjz[q] -= roll.z;
    }
}

static inline bdl_vec3 slot_force(const pair_batch *b, int q)
{
    return bdl_v3(b->fx[q], b->fy[q], b->fz[q]);
}
static inline bdl_vec3 slot_torque_i(const pair_batch *b, int q)
{
    return bdl_v3(b->tix[q], b->tiy[q], b->tiz[q]);
}
static inline bdl_vec3 slot_torque_j(const pair_batch *b, int q)
{
    return bdl_v3(b->tjx[q], b->tjy[q], b->tjz[q]);
}

/// Whether entry k of particle i's wall list (a triangle) touches and counts now.
static int triangle_counts(const bdl_particles *p, const bdl_neighbor *nb, const bdl_walls *walls,
                           long i, int32_t k)
{
    bdl_vec3 n;
    const int32_t k0 = nb->wall_start[i], prim = nb->wall_prim[k];
    return prim >= walls->prim_count &&
           bdl_wall_gap(walls, prim, p->pos[i], p->radius[i], &n) < 0.0 &&
           bdl_wall_tri_counted(walls, nb->wall_prim + k0, nb->wall_start[i + 1] - k0,
                                (int)(k - k0), p->pos[i], p->radius[i]);
}

#define CARRY_MAX 32

/// A sphere passing from one triangle of a mesh wall to the next keeps its tangential spring:
/// a triangle contact that starts this step takes over the spring (and the work it holds) of a
/// triangle contact of the same wall that ends this step, before the pass below updates either.
/// (Particles with more than CARRY_MAX wall entries start afresh, as at the join of two
/// primitive walls.)
static void carry_springs(const bdl_particles *p, bdl_neighbor *nb, const bdl_walls *walls, long i)
{
    const int32_t k0 = nb->wall_start[i], m = nb->wall_start[i + 1] - k0;
    if (walls->tri_count == 0 || m < 2 || m > CARRY_MAX)
        return;
    uint8_t now[CARRY_MAX];
    int starts = 0, ends = 0;
    for (int32_t k = 0; k < m; ++k) {
        now[k] = (uint8_t)triangle_counts(p, nb, walls, i, k0 + k);
        starts += now[k] && !nb->wall_touching[k0 + k];
        ends += !now[k] && nb->wall_touching[k0 + k] && nb->wall_prim[k0 + k] >= walls->prim_count;
    }
    for (int32_t k = 0; k < m && starts > 0 && ends > 0; ++k) {
        if (!now[k] || nb->wall_touching[k0 + k])
            continue;
        for (int32_t e = 0; e < m; ++e) {
            const int32_t a = k0 + k, b = k0 + e;
            if (now[e] || !nb->wall_touching[b] || nb->wall_prim[b] < walls->prim_count ||
                bdl_wall_of(walls, nb->wall_prim[b]) != bdl_wall_of(walls, nb->wall_prim[a]))
                continue;
            nb->wall_history[a] = nb->wall_history[b];
            nb->wall_history[b] = bdl_v3_zero();
            if (nb->wall_spring_work) { // moved, not released
                nb->wall_spring_work[a] = nb->wall_spring_work[b];
                nb->wall_spring_work[b] = 0.0;
            }
            nb->wall_touching[b] = 0;
            --ends;
            break;
        }
    }
}

/// Wall contacts of particle i, added to f and t.
static void wall_contacts(bdl_particles *p, bdl_neighbor *nb, const bdl_walls *walls,
                          const bdl_force_def *def, long i, bdl_vec3 *f, bdl_vec3 *t,
                          bdl_exact_sum *released)
{
    int ns = def->species_count;
    double r = p->radius[i];
    if (def->friction)
        carry_springs(p, nb, walls, i);
    for (int32_t k = nb->wall_start[i]; k < nb->wall_start[i + 1]; ++k) {
        int prim = nb->wall_prim[k];
        bdl_vec3 n;
        double gap = bdl_wall_gap(walls, prim, p->pos[i], r, &n);
        if (gap >= 0.0 || !bdl_wall_tri_counted(walls, nb->wall_prim + nb->wall_start[i],
                                                nb->wall_start[i + 1] - nb->wall_start[i],
                                                (int)(k - nb->wall_start[i]), p->pos[i], r)) {
            nb->wall_touching[k] = 0;
            nb->wall_force[k] = bdl_v3_zero();
            nb->wall_history[k] = bdl_v3_zero();
            if (nb->wall_spring_work) {            // what the spring still holds leaves the bodies
                if (!nb->ghosted || i < nb->owned) // a ghost's is booked by its owner
                    *released += bdl_exact_term(nb->wall_spring_work[k]);
                nb->wall_spring_work[k] = 0.0;
            }
            continue;
        }
        int wall = bdl_wall_of(walls, prim);
        double arm = r + 0.5 * gap;
        bdl_contact_geom g;
        g.n = n;
        g.overlap = -gap;
        g.v_c = bdl_v3_sub(bdl_v3_sub(p->vel[i], bdl_wall_velocity_at(
                                                     walls, wall, bdl_v3_madd(p->pos[i], n, -arm))),
                           bdl_v3_scale(bdl_v3_cross(p->omega[i], n), arm));
        g.m_eff = 1.0 / p->inv_mass[i];
        g.r_eff = bdl_wall_r_eff(walls, prim, r);
        const bdl_contact_params *cp = def->wall_params + wall * ns + p->species[i];
        bdl_spring u = {nb->wall_history[k], nb->wall_spring_work ? nb->wall_spring_work[k] : 0.0};
        bdl_contact_result res = def->hertz ? bdl_contact_eval(cp, 1, def->friction, g, u, def->dt)
                                            : bdl_contact_eval(cp, 0, def->friction, g, u, def->dt);
        if (def->friction)
            nb->wall_history[k] = res.spring.u;
        if (nb->wall_spring_work)
            nb->wall_spring_work[k] = res.spring.work;
        nb->wall_touching[k] = 1;
        nb->wall_force[k] = res.force;
        *f = bdl_v3_add(*f, res.force);
        *t = bdl_v3_madd(*t, res.n_x_ft, -arm);
        if (def->rolling)
            *t = bdl_v3_add(*t, bdl_rolling_torque(cp, res.normal, g.r_eff, p->omega[i],
                                                   bdl_particle_inv_inertia(p, i), def->dt));
    }
}

/// Whether every particle has the same species, radius and mass (then the gather need not load
/// them per pair).
static void check_uniform(bdl_force_work *fw, const bdl_particles *p)
{
    long n = p->count;
    fw->uniform = n > 0;
    if (n == 0)
        return;
    fw->species = p->species[0];
    fw->radius = p->radius[0];
    fw->inv_mass = p->inv_mass[0];
    int same = 1;
    for (long i = 0; i < n; ++i)
        same &= (p->species[i] == fw->species) & (p->radius[i] == fw->radius) &
                (p->inv_mass[i] == fw->inv_mass);
    fw->uniform = same;
}

/// Sets the thread ranges so that each holds an equal share of the work, not of the count: a
/// particle costs about as much as one of its pairs, and the free surface of a bed has fewer
/// pairs than its bottom. Cost up to i: i + start[i].
static void balance_ranges(bdl_force_work *fw, const bdl_neighbor *nb, long n, int threads)
{
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
}

/// Room for the boundary entries of the ranges just set, a batch per thread and the owner of every
/// listed pair.
static bdl_result reserve_work(bdl_force_work *fw, const bdl_neighbor *nb, long n, int threads)
{
    long count = 0;
    for (int t = 0; t + 1 < threads; ++t)
        for (long i = fw->range[t]; i < fw->range[t + 1]; ++i)
            for (int32_t k = nb->start[i]; k < nb->start[i + 1]; ++k)
                count += nb->partner[k] >= fw->range[t + 1];
    if (count > fw->capacity) {
        long cap = count + count / 4 + 64;
        if (!bdl_grow((void **)&fw->pair, cap, sizeof(int32_t)) ||
            !bdl_grow((void **)&fw->pair_i, cap, sizeof(int32_t)) ||
            !bdl_grow((void **)&fw->target, cap, sizeof(int32_t)) ||
            !bdl_grow((void **)&fw->result, cap, sizeof *fw->result))
            return BDL_ERR_NOMEM;
        fw->capacity = cap;
    }
    for (int t = 0; t < threads; ++t)
        if (!fw->batch[t] && !(fw->batch[t] = malloc(sizeof(pair_batch))))
            return BDL_ERR_NOMEM;
    long pairs = nb->start[n];
    if (pairs > fw->owner_capacity) {
        long cap = pairs + pairs / 16 + 64;
        if (!bdl_grow((void **)&fw->owner, cap, sizeof(int32_t)))
            return BDL_ERR_NOMEM;
        fw->owner_capacity = cap;
    }
    return BDL_OK;
}

/// The first particle of every pair, so that the gather runs over pairs in one flat loop.
static void list_owners(bdl_force_work *fw, const bdl_neighbor *nb, long n)
{
    for (long i = 0; i < n; ++i)
        for (int32_t k = nb->start[i]; k < nb->start[i + 1]; ++k)
            fw->owner[k] = (int32_t)i;
    fw->owner_count = (int32_t)nb->start[n];
}

/// The boundary pairs: per source thread the pairs (in list order) whose j lies in a later range,
/// then per target thread the indices of those entries that point into it, by source thread and
/// list order.
static void list_boundary(bdl_force_work *fw, const bdl_neighbor *nb, int threads)
{
    long m = 0;
    for (int t = 0; t < threads; ++t) {
        fw->out_start[t] = m;
        for (long i = fw->range[t]; i < fw->range[t + 1]; ++i)
            for (int32_t k = nb->start[i]; k < nb->start[i + 1]; ++k)
                if (nb->partner[k] >= fw->range[t + 1]) {
                    fw->pair_i[m] = (int32_t)i;
                    fw->pair[m++] = k;
                }
    }
    fw->out_start[threads] = m;
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
}

/// Splits the particles into one range per thread and lists the boundary pairs between them; also
/// checks whether the particles are uniform and allocates the per-thread batches. Nothing to do
/// while the lists, the particle count and the thread count stay the same.
bdl_result bdl_force_partition(bdl_force_work *fw, const bdl_neighbor *nb, const bdl_particles *p,
                               int threads)
{
    long n = p->count;
    if (fw->threads == threads && fw->version == nb->version && fw->count == n)
        return BDL_OK;
    if (threads > BDL_MAX_FORCE_THREADS)
        threads = BDL_MAX_FORCE_THREADS;
    fw->threads = 0; // until complete
    check_uniform(fw, p);
    balance_ranges(fw, nb, n, threads);
    bdl_result r = reserve_work(fw, nb, n, threads);
    if (r != BDL_OK)
        return r;
    list_owners(fw, nb, n);
    list_boundary(fw, nb, threads);
    fw->threads = threads;
    fw->version = nb->version;
    fw->count = n;
    return BDL_OK;
}

/// Adds -F and the torque of a pair to particle j (its second particle).
static inline void add_to_j(bdl_particles *p, uint8_t *coordination, int32_t j, bdl_vec3 force,
                            bdl_vec3 torque_j, int torques)
{
    p->load[j].force = bdl_v3_sub(p->load[j].force, force);
    if (torques)
        p->load[j].torque = bdl_v3_add(p->load[j].torque, torque_j);
    if (coordination[j] < 255)
        coordination[j]++;
}

/// Walls, background damping, storage and the closing half kick of particle i, once all its
/// pairs are in.
static inline void finish_particle(bdl_particles *p, bdl_neighbor *nb, const bdl_walls *walls,
                                   const bdl_force_def *def, long i, bdl_vec3 f, bdl_vec3 t,
                                   double kick, bdl_exact_sum *released)
{
    if (nb->wall_start[i] < nb->wall_start[i + 1])
        wall_contacts(p, nb, walls, def, i, &f, &t, released);
    const double b = def->background_damping[p->species[i]];
    if (b > 0.0)
        f = bdl_v3_madd(f, bdl_background_slip(def, p, i), -b / p->inv_mass[i]);
    p->load[i] = (bdl_wrench){f, t};
    if (kick > 0.0) {
        double im = p->inv_mass[i];
        bdl_vec3 g = p->fluid_accel ? bdl_v3_add(def->gravity, p->fluid_accel[i]) : def->gravity;
        p->vel[i] = bdl_v3_madd(bdl_v3_madd(p->vel[i], g, kick), f, kick * im);
        p->omega[i] = bdl_v3_madd(p->omega[i], t, kick * bdl_particle_inv_inertia(p, i));
    }
}

/// Prefetches the per-particle arrays the force pass reads in index order, for particle i (when
/// below hi).
static inline void prefetch_streams(const bdl_particles *p, const bdl_neighbor *nb,
                                    const uint8_t *coordination, long i, long hi)
{
    if (i >= hi)
        return;
    BDL_PREFETCH(&nb->start[i + 1]);
    BDL_PREFETCH(&nb->wall_start[i + 1]);
    BDL_PREFETCH(&p->species[i]);
    BDL_PREFETCH(&p->inv_mass[i]);
    BDL_PREFETCH(&p->radius[i]);
    BDL_PREFETCH(&coordination[i]);
}

/// Gathers pairs [k, k_end) of particle pi into the batch from slot m on, boundary pairs
/// excepted (the cursor *out skips them); returns the new slot count.
static BDL_FORCE_INLINE int gather_pairs(pair_batch *b, int m, const gather_view *v,
                                         const particle_i *pi, int32_t k, int32_t k_end,
                                         const int32_t *boundary, long *out, long out_end,
                                         int uniform)
{
    long o = *out;
    for (; k < k_end; ++k) {
        if (o < out_end && boundary[o] == k) {
            ++o;
            continue;
        }
        m += gather_pair(b, m, v, pi, k, uniform);
    }
    *out = o;
    return m;
}

/// Gathers pairs [k0, k1) of the particles from `first` on into the batch, boundary pairs
/// excepted (the cursor *out skips them); b->end[i - first] is set to the slot count after the
/// last pair of i. Returns the slot count.
static BDL_FORCE_INLINE int gather_run(pair_batch *b, const gather_view *v,
                                       const bdl_force_work *fw, long first, int32_t k0, int32_t k1,
                                       long *out, long out_end, int uniform)
{
    const int32_t *owner = fw->owner, *boundary = fw->pair, *partner = v->partner;
    int32_t k_last = fw->owner_count;
    long o = *out;
    int m = 0;
    for (int32_t k = k0; k < k1; ++k) {
        if (k + PREFETCH_AHEAD < k_last) {
            // The partner PREFETCH_AHEAD pairs on is read soon (its position by this loop, the
            // rest by the second gather loop and the scatter): ask for it now.
            int32_t jp = partner[k + PREFETCH_AHEAD];
            BDL_PREFETCH_L2(&v->pos[jp]);
            BDL_PREFETCH_L2(&v->vel[jp]);
            BDL_PREFETCH_L2(&v->omega[jp]);
            BDL_PREFETCH_L2(&v->load[jp]);
            BDL_PREFETCH_L2(&v->load[jp].torque.z); // a record may straddle two lines
            // The springs are read in list order, but only those of touching pairs and in a
            // later loop: the hardware does not see that stream coming.
            if (v->history && k + 3 * PREFETCH_AHEAD < k_last)
                BDL_PREFETCH(&v->history[k + 3 * PREFETCH_AHEAD]);
        }
        if (k + STREAM_AHEAD < k_last) {
            BDL_PREFETCH(&owner[k + STREAM_AHEAD]);
            BDL_PREFETCH(&v->touching[k + STREAM_AHEAD]);
        }
        int32_t i = owner[k];
        if (o < out_end && boundary[o] == k) {
            ++o;
            continue;
        }
        particle_i pi;
        pi.i = i;
        pi.x = v->pos[i];
        if (!uniform) {
            pi.species = v->species[i];
            pi.r = v->radius[i];
            pi.im = v->inv_mass[i];
        }
        m += gather_pair(b, m, v, &pi, k, uniform);
        b->end[i - first] = m;
    }
    *out = o;
    return m;
}

/// Evaluates the boundary pairs of thread t (pairs whose j lies in a later range) and stores
/// them for the owners of their j.
static void boundary_pairs(bdl_particles *p, bdl_neighbor *nb, const bdl_force_def *def,
                           bdl_force_work *fw, int t)
{
    pair_batch *b = fw->batch[t];
    gather_view v = make_view(p, nb, def, fw, t);
    long e = fw->out_start[t], end = fw->out_start[t + 1];
    while (e < end) {
        // Gather up to a batch of boundary pairs; slot m holds entry first + b->end[m].
        int m = 0;
        long first = e;
        for (; e < end && e - first < BATCH; ++e) {
            // These pairs lie scattered over the range: ask for the ones a few ahead.
            if (e + 4 < end) {
                BDL_PREFETCH(&v.pos[fw->pair_i[e + 4]]);
                BDL_PREFETCH(&v.pos[v.partner[fw->pair[e + 4]]]);
                BDL_PREFETCH(&v.vel[fw->pair_i[e + 4]]);
                BDL_PREFETCH(&v.omega[fw->pair_i[e + 4]]);
                if (v.history)
                    BDL_PREFETCH(&v.history[fw->pair[e + 4]]);
            }
            int32_t k = fw->pair[e];
            particle_i pi = load_i(&v, fw->pair_i[e]);
            b->end[m] = (int32_t)(e - first);
            fw->result[e].touching = 0;
            m += fw->uniform ? gather_pair(b, m, &v, &pi, k, 1) : gather_pair(b, m, &v, &pi, k, 0);
        }
        eval_batch(b, m, p, def, fw, &v);
        for (int q = 0; q < m; ++q) {
            pair_result *r = &fw->result[first + b->end[q]];
            r->touching = 1;
            r->force = slot_force(b, q);
            r->torque_i = slot_torque_i(b, q);
            r->torque_j = slot_torque_j(b, q);
            if (nb->history)
                nb->history[b->k[q]] = bdl_v3(b->unx[q], b->uny[q], b->unz[q]);
            if (nb->spring_work)
                nb->spring_work[b->k[q]] = b->work_new[q];
        }
    }
}

/// Running sums of the particle being accumulated.
typedef struct particle_sum {
    bdl_vec3 f, t;
    int contacts;
} particle_sum;

/// Adds slots [q, q_end) of one particle i and its boundary pairs listed before k_end to i (sum)
/// and to their j, in list order; returns q_end.
static BDL_FORCE_INLINE int accumulate(const pair_batch *b, int q, int q_end, int32_t k_end,
                                       bdl_particles *p, const gather_view *v,
                                       uint8_t *coordination, const bdl_force_work *fw, long *out,
                                       long out_end, int torques, particle_sum *sum)
{
    long o = *out;
    for (;;) {
        if (o < out_end && fw->pair[o] < k_end && (q == q_end || fw->pair[o] < b->k[q])) {
            const pair_result *r = &fw->result[o++];
            if (r->touching) {
                ++sum->contacts;
                sum->f = bdl_v3_add(sum->f, r->force);
                if (torques)
                    sum->t = bdl_v3_add(sum->t, r->torque_i);
            }
            continue;
        }
        if (q == q_end)
            break;
        bdl_vec3 force = slot_force(b, q);
        add_to_j(p, coordination, b->j[q], force, slot_torque_j(b, q), torques);
        if (v->history)
            v->history[b->k[q]] = bdl_v3(b->unx[q], b->uny[q], b->unz[q]);
        if (v->spring_work)
            v->spring_work[b->k[q]] = b->work_new[q];
        ++sum->contacts;
        sum->f = bdl_v3_add(sum->f, force);
        if (torques)
            sum->t = bdl_v3_add(sum->t, slot_torque_i(b, q));
        ++q;
    }
    *out = o;
    return q;
}

static inline particle_sum sum_start(const bdl_particles *p, const uint8_t *coordination, long i)
{
    particle_sum s = {p->load[i].force, p->load[i].torque, coordination[i]};
    return s;
}

/// What every step of one thread's share of the force pass works with.
typedef struct range_pass {
    bdl_particles *p;
    bdl_neighbor *nb;
    const bdl_walls *walls;
    const bdl_force_def *def;
    const bdl_force_work *fw;
    uint8_t *coordination;
    pair_batch *b;           ///< this thread's
    bdl_exact_sum *released; ///< this thread's (bdl_force_work)
    double kick;
    long hi;      ///< end of the range
    long out_end; ///< end of the range's boundary pairs
    int torques, uniform;
} range_pass;

static inline void sum_finish(const range_pass *r, long i, const particle_sum *s)
{
    r->coordination[i] = (uint8_t)(s->contacts < 255 ? s->contacts : 255);
    finish_particle(r->p, r->nb, r->walls, r->def, i, s->f, s->t, r->kick, r->released);
}

/// Starts the sums of range t: cleared, then the boundary pairs from earlier ranges, whose i are
/// smaller than all of ours.
static void open_range(const range_pass *r, int t)
{
    long lo = r->fw->range[t];
    if (!r->def->loads_cleared)
        for (long i = lo; i < r->hi; ++i)
            r->p->load[i] = (bdl_wrench){bdl_v3_zero(), bdl_v3_zero()};
    memset(r->coordination + lo, 0, (size_t)(r->hi - lo));
    const bdl_force_work *fw = r->fw;
    for (long c = fw->in_start[t]; c < fw->in_start[t + 1]; ++c) {
        const pair_result *res = &fw->result[fw->target[c]];
        if (res->touching)
            add_to_j(r->p, r->coordination, r->nb->partner[fw->pair[fw->target[c]]], res->force,
                     res->torque_j, r->torques);
    }
}

/// Particle i with more pairs than a batch holds: several batches for it alone. Takes and returns
/// the cursor of the range's boundary pairs.
static long crowded_particle(const range_pass *r, const gather_view *v, long i, long out)
{
    const int32_t *start = r->nb->start;
    pair_batch *b = r->b;
    particle_sum sum = sum_start(r->p, r->coordination, i);
    particle_i pi = load_i(v, i);
    for (int32_t k = start[i]; k < start[i + 1]; k += BATCH) {
        int32_t k_end = k + BATCH < start[i + 1] ? k + BATCH : start[i + 1];
        long out_first = out;
        int m = gather_pairs(b, 0, v, &pi, k, k_end, r->fw->pair, &out, r->out_end, r->uniform);
        eval_batch(b, m, r->p, r->def, r->fw, v);
        out = out_first;
        accumulate(b, 0, m, k_end, r->p, v, r->coordination, r->fw, &out, r->out_end, r->torques,
                   &sum);
    }
    sum_finish(r, i, &sum);
    return out;
}

/// The end of the run of particles from `first` whose pairs surely fit in one batch (at most a
/// batch of particles); marks each as having no slots yet and prefetches the streams ahead.
static BDL_FORCE_INLINE long run_end(const range_pass *r, long first)
{
    const int32_t *start = r->nb->start;
    int32_t k0 = start[first];
    long i = first;
    while (i < r->hi && i - first < BATCH && start[i + 1] - k0 <= BATCH) {
        prefetch_streams(r->p, r->nb, r->coordination, i + STREAM_AHEAD, r->hi);
        r->b->end[i++ - first] = -1;
    }
    return i;
}

/// Particles without pairs end where the one before them ends.
static inline void fill_ends(pair_batch *b, long count)
{
    int last = 0;
    for (long l = 0; l < count; ++l) {
        last = b->end[l] < 0 ? last : b->end[l];
        b->end[l] = last;
    }
}

/// Adds the evaluated pairs of particles [first, end) to both of their particles in the canonical
/// order, and finishes each particle.
static BDL_FORCE_INLINE void scatter_run(const range_pass *r, const gather_view *v, long first,
                                         long end, long *out)
{
    const int32_t *start = r->nb->start;
    int q = 0;
    for (long i = first; i < end; ++i) {
        particle_sum sum = sum_start(r->p, r->coordination, i);
        q = accumulate(r->b, q, r->b->end[i - first], start[i + 1], r->p, v, r->coordination, r->fw,
                       out, r->out_end, r->torques, &sum);
        sum_finish(r, i, &sum);
    }
}

/// A run of particles from `first`, gathered in one loop over their pairs (b->end[i - first] ends
/// the slots of particle i), evaluated and scattered; returns the end of the run.
static BDL_FORCE_INLINE long particle_run(const range_pass *r, const gather_view *v, long first,
                                          long *out)
{
    pair_batch *b = r->b;
    long out_first = *out;
    long end = run_end(r, first);
    int32_t k0 = r->nb->start[first], k1 = r->nb->start[end];
    int m = r->uniform ? gather_run(b, v, r->fw, first, k0, k1, out, r->out_end, 1)
                       : gather_run(b, v, r->fw, first, k0, k1, out, r->out_end, 0);
    fill_ends(b, end - first);
    eval_batch(b, m, r->p, r->def, r->fw, v);
    *out = out_first;
    scatter_run(r, v, first, end, out);
    return end;
}

/// Thread t's share of the force pass: its particles in index order, in runs that fill a batch.
static void force_range(bdl_particles *p, bdl_neighbor *nb, const bdl_walls *walls,
                        const bdl_force_def *def, bdl_force_work *fw, uint8_t *coordination,
                        double kick, int t)
{
    const range_pass r = {.p = p,
                          .nb = nb,
                          .walls = walls,
                          .def = def,
                          .fw = fw,
                          .coordination = coordination,
                          .b = fw->batch[t],
                          .released = &fw->released[t],
                          .kick = kick,
                          .hi = fw->range[t + 1],
                          .out_end = fw->out_start[t + 1],
                          .torques = def->friction || def->rolling,
                          .uniform = fw->uniform};
    gather_view v = make_view(p, nb, def, fw, t);
    open_range(&r, t);
    long out = fw->out_start[t];
    long i = fw->range[t];
    while (i < r.hi) {
        if (nb->start[i + 1] - nb->start[i] > BATCH)
            out = crowded_particle(&r, &v, i++, out);
        else
            i = particle_run(&r, &v, i, &out);
    }
}

bdl_result bdl_force_run(const bdl_force_pass *pass, bdl_particles *p, bdl_neighbor *nb,
                         const bdl_walls *walls, const bdl_force_def *def, bdl_force_work *fw,
                         uint8_t *coordination, double kick)
{
    int threads = p->count >= def->parallel_min ? omp_get_max_threads() : 1;
    bdl_result r = bdl_force_partition(fw, nb, p, threads);
    if (r != BDL_OK)
        return r;
    threads = fw->threads;
    for (int t = 0; t < threads; ++t)
        fw->released[t] = 0;
    if (threads == 1) {
        pass->range(p, nb, walls, def, fw, coordination, kick, 0);
    } else {
#pragma omp parallel num_threads(threads)
        {
            const int t = omp_get_thread_num();
            // Phase 1: this range's boundary pairs, stored for the owners of their j.
            pass->boundary(p, nb, def, fw, t);
#pragma omp barrier
            // Phase 2: everything else, in index order.
            pass->range(p, nb, walls, def, fw, coordination, kick, t);
        }
    }
    for (int t = 0; t < threads; ++t) // exact: the same on any thread count
        nb->spring_work_left += fw->released[t];
    return BDL_OK;
}

bdl_result bdl_dem_forces(bdl_particles *p, bdl_neighbor *nb, const bdl_walls *walls,
                          const bdl_force_def *def, bdl_force_work *fw, uint8_t *coordination,
                          double kick)
{
    static const bdl_force_pass spheres = {boundary_pairs, force_range};
    return bdl_force_run(&spheres, p, nb, walls, def, fw, coordination, kick);
}

void bdl_force_work_free(bdl_force_work *fw)
{
    free(fw->pair);
    free(fw->pair_i);
    free(fw->owner);
    free(fw->target);
    free(fw->result);
    for (int t = 0; t < BDL_MAX_FORCE_THREADS; ++t)
        free(fw->batch[t]);
    memset(fw, 0, sizeof *fw);
}

long bdl_force_work_bytes(const bdl_force_work *fw)
{
    long bytes = fw->capacity * (long)(3 * sizeof(int32_t) + sizeof *fw->result) +
                 fw->owner_capacity * (long)sizeof(int32_t);
    for (int t = 0; t < BDL_MAX_FORCE_THREADS; ++t)
        bytes += fw->batch[t] ? (long)sizeof(pair_batch) : 0;
    return bytes;
}
