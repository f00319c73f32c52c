// bedlam — parcels: drift, packing guard, interparticle stress or collisions, and the implicit
// exchange with the gas (parcels.h has the scheme).
#include "core/parallel.h"
#include "parcels/parcels.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/memory.h"
#include "core/timer.h"

BDL_CHOICE_WORDS(bdl_parcel_model, BDL_PARCEL_MODELS);

bdl_parcels_def bdl_default_parcels_def(void)
{
    return (bdl_parcels_def){.model = BDL_PARCEL_STRESS,
                             .stress_pressure = 100.0,
                             .stress_exponent = 3.0,
                             .close_packing = 0.6,
                             .stress_floor = 1e-3,
                             .substeps = 1,
                             .gas_substeps = 1,
                             .wall_restitution = 0.9,
                             .collision_stiffness = 800.0,
                             .collision_exponent = 1.5,
                             .collision_damping = -1.0,
                             .collision_restitution = 0.9,
                             .collision_range = 0.075};
}

double bdl_parcels_collision_damping(const bdl_parcels_def *def, double mass)
{
    if (def->collision_damping >= 0.0)
        return def->collision_damping;
    return bdl_parcel_collision_damping(def->collision_restitution, mass, def->collision_stiffness);
}

double bdl_parcels_collision_dt(const bdl_parcels_def *def, double mass)
{
    if (def->model != BDL_PARCEL_COLLISIONS || !(mass > 0.0))
        return INFINITY;
    const double eta = bdl_parcels_collision_damping(def, mass);
    const double spring =
        def->collision_stiffness > 0.0 ? 2.0 * sqrt(mass / def->collision_stiffness) : INFINITY;
    const double dashpot = eta > 0.0 ? mass / eta : INFINITY;
    return (def->substeps > 0 ? def->substeps : 1) * fmin(spring, dashpot);
}

/// The domain of the gas as the parcels meet it.
static bdl_parcel_box parcel_box(const bdl_gas *gas)
{
    const bdl_grid *g = &gas->grid;
    bdl_parcel_box box = {0};
    for (int a = 0; a < 3; ++a) {
        box.lo[a] = g->origin[a];
        box.hi[a] = g->origin[a] + g->n[a] * g->h[a];
        box.periodic[a] = g->periodic[a];
        for (int side = 2 * a; side < 2 * a + 2; ++side)
            box.solid[side] = !g->periodic[a] && gas->def.side[side].type != BDL_SIDE_OUTLET;
    }
    return box;
}

double bdl_parcels_stress(const bdl_parcels_def *def, double theta)
{
    if (!(theta > 0.0))
        return 0.0;
    const double gap = fmax(def->close_packing - theta, def->stress_floor);
    return def->stress_pressure * pow(theta, def->stress_exponent) / gap;
}

bdl_result bdl_parcels_init(bdl_parcels *pc, const bdl_parcels_def *def, const bdl_gas *gas)
{
    *pc = (bdl_parcels){0};
    pc->def = *def;
    pc->tau = bdl_grid_alloc(&gas->grid);
    pc->eps_begin = bdl_grid_alloc(&gas->grid);
    int ok = pc->tau != NULL && pc->eps_begin != NULL;
    for (int a = 0; a < 3; ++a)
        ok = ok && (pc->grad[a] = bdl_grid_alloc(&gas->grid));
    const bdl_parcel_collision_law law = {.stiffness = def->collision_stiffness,
                                          .exponent = def->collision_exponent,
                                          .damping = fmax(def->collision_damping, 0.0),
                                          .range = def->collision_range};
    const bdl_parcel_box box = parcel_box(gas);
    ok = ok && bdl_parcel_collisions_init(&pc->collisions, &law, &box) == BDL_OK;
    if (def->gas_substeps > 1) {
        ok = ok && (pc->eps_start = bdl_grid_alloc(&gas->grid)) &&
             (pc->eps_end = bdl_grid_alloc(&gas->grid));
        for (int a = 0; a < 3; ++a)
            ok = ok && (pc->u_mean[a] = bdl_grid_alloc(&gas->grid)) &&
                 (pc->grad_p_mean[a] = bdl_grid_alloc(&gas->grid));
    }
    if (!ok) {
        bdl_parcels_free(pc);
        return BDL_ERR_NOMEM;
    }
    return BDL_OK;
}

void bdl_parcels_free(bdl_parcels *pc)
{
    free(pc->start);
    free(pc->moved);
    free(pc->accel);
    free(pc->value);
    free(pc->perm);
    free(pc->scratch);
    free(pc->held);
    free(pc->tau);
    free(pc->eps_begin);
    for (int a = 0; a < 3; ++a) {
        free(pc->grad[a]);
        free(pc->u_mean[a]);
        free(pc->grad_p_mean[a]);
    }
    free(pc->eps_start);
    free(pc->eps_end);
    bdl_parcel_collisions_free(&pc->collisions);
    free(pc->sub_v);
    free(pc->push);
    *pc = (bdl_parcels){0};
}

static bdl_result reserve(bdl_parcels *pc, long n)
{
    if (n <= pc->capacity)
        return BDL_OK;
    const long cap = n + n / 4 + 64;
    if (!bdl_grow((void **)&pc->start, cap, sizeof(bdl_vec3)) ||
        !bdl_grow((void **)&pc->moved, cap, sizeof(bdl_vec3)) ||
        !bdl_grow((void **)&pc->accel, cap, sizeof(bdl_vec3)) ||
        !bdl_grow((void **)&pc->value, cap, sizeof(double)) ||
        !bdl_grow((void **)&pc->perm, cap, sizeof(int32_t)) ||
        !bdl_grow((void **)&pc->scratch, cap, sizeof(bdl_vec3)) ||
        !bdl_grow((void **)&pc->held, cap, 1) ||
        !bdl_grow((void **)&pc->sub_v, cap, sizeof(bdl_vec3)) ||
        !bdl_grow((void **)&pc->push, cap, sizeof(bdl_vec3)))
        return BDL_ERR_NOMEM;
    pc->capacity = cap;
    return BDL_OK;
}

double bdl_parcels_solids_volume(const bdl_particles *p)
{
    double sum = 0.0;
    for (long i = 0; i < p->count; ++i)
        sum += bdl_particle_solids_volume(p, i);
    return sum;
}

// ---------------------------------------------------------------------------------------------
// Drift.

/// Keeps coordinate a of parcel i inside the domain: wraps a periodic axis, reflects off a wall
/// or an inlet (the normal velocity reversed and scaled by the restitution); returns 1 when the
/// parcel is beyond an outlet.
static int keep_inside(const bdl_parcels *pc, const bdl_gas *gas, bdl_particles *p, long i, int a)
{
    const bdl_grid *g = &gas->grid;
    const double lo = g->origin[a], hi = lo + g->n[a] * g->h[a];
    double x = bdl_v3_comp(p->pos[i], a), v = bdl_v3_comp(p->vel[i], a);
    if (x >= lo && x <= hi)
        return 0;
    if (g->periodic[a]) {
        const double L = hi - lo;
        x = lo + fmod(fmod(x - lo, L) + L, L);
    } else {
        const int side = x < lo ? 2 * a : 2 * a + 1;
        if (gas->def.side[side].type == BDL_SIDE_OUTLET)
            return 1;
        const int below = x < lo;
        x = 2.0 * (below ? lo : hi) - x;
        x = fmin(fmax(x, lo), hi); // a parcel faster than a domain per part stops at the side
        if (below ? v < 0.0 : v > 0.0)
            v = -pc->def.wall_restitution * v;
    }
    bdl_v3_set_comp(&p->pos[i], a, x);
    bdl_v3_set_comp(&p->vel[i], a, v);
    return 0;
}

/// Model B: the collision acceleration a = F_cp / M at the parcels' positions now, with the
/// velocities w = v + h S of the step's parts so far, added to the sum S (pc->accel). The parcels
/// in `skip` (NULL: none) take no part.
static bdl_result collide(bdl_parcels *pc, bdl_particles *p, double h, const uint8_t *skip,
                          bdl_parcel_contacts *found)
{
    for (long i = 0; i < p->count; ++i)
        pc->sub_v[i] = bdl_v3_madd(p->vel[i], pc->accel[i], h);
    if (bdl_parcel_collisions_force(&pc->collisions, p, pc->sub_v, skip, pc->push, found) != BDL_OK)
        return BDL_ERR_NOMEM;
    for (long i = 0; i < p->count; ++i)
        pc->accel[i] = bdl_v3_madd(pc->accel[i], pc->push[i], p->inv_mass[i]);
    return BDL_OK;
}

/// How many of the first n flags are set.
static long count_marked(const uint8_t *flags, long n)
{
    long count = 0;
    for (long i = 0; i < n; ++i)
        count += flags[i];
    return count;
}

/// Moves every parcel by w dt in `substeps` parts h, meeting the sides within each (see
/// parcels.h: w = v, or for model B v + h S with the collisions evaluated between the parts);
/// the parcels beyond an outlet are marked in pc->held and move no more. Their count into
/// *leaving.
static bdl_result drift(bdl_parcels *pc, const bdl_gas *gas, bdl_particles *p, double dt,
                        long *leaving)
{
    const int parts = pc->def.substeps > 0 ? pc->def.substeps : 1;
    const int collisions = pc->def.model == BDL_PARCEL_COLLISIONS;
    const double h = dt / parts;
    if (p->count == 0) // no arrays yet (a null pointer may not go to memset, even for 0 bytes)
        return BDL_OK;
    memset(pc->held, 0, (size_t)p->count);
    memset(pc->moved, 0, (size_t)p->count * sizeof(bdl_vec3));
    if (collisions)
        memset(pc->accel, 0, (size_t)p->count * sizeof(bdl_vec3));
    for (int k = 0; k < parts; ++k) {
        BDL_PARALLEL_FOR(
            p->count >= pc->collisions.parallel_min, for (long i = 0; i < p->count; ++i) {
                if (pc->held[i])
                    continue;
                const bdl_vec3 w = collisions ? bdl_v3_madd(p->vel[i], pc->accel[i], h) : p->vel[i];
                p->pos[i] = bdl_v3_madd(p->pos[i], w, h);
                if (collisions)
                    pc->moved[i] = bdl_v3_madd(pc->moved[i], pc->accel[i], h / parts);
                int out = 0;
                for (int a = 0; a < 3; ++a)
                    out |= keep_inside(pc, gas, p, i, a);
                pc->held[i] = (uint8_t)out;
            });
        if (collisions && k + 1 < parts && collide(pc, p, h, pc->held, NULL) != BDL_OK)
            return BDL_ERR_NOMEM;
    }
    *leaving = count_marked(pc->held, p->count);
    return BDL_OK;
}

/// Removes the parcels marked in pc->held (beyond an outlet), keeping the others' order.
static void remove_marked(bdl_parcels *pc, bdl_particles *p, bdl_parcels_report *out)
{
    long kept = 0;
    for (long i = 0; i < p->count; ++i) {
        if (pc->held[i]) {
            out->removed++;
            out->removed_mass += 1.0 / p->inv_mass[i];
        } else {
            pc->perm[kept] = (int32_t)i;
            pc->start[kept] = pc->start[i];
            pc->moved[kept] = pc->moved[i];
            pc->accel[kept] = pc->accel[i];
            ++kept;
        }
    }
    for (long i = kept; i < p->count; ++i) // the leavers last: permute moves whole slots
        if (pc->held[i])
            pc->perm[kept++] = (int32_t)i;
    bdl_particles_permute(p, pc->perm, pc->scratch);
    p->count -= out->removed;
}

// ---------------------------------------------------------------------------------------------
// The packing guard.

/// Whether the cell at idx holds a solids fraction above close packing and above what it held
/// at the start of the step (beyond round-off: the parcels' order, and so the deposit's sums,
/// may have changed since).
static int overfull_cell(const bdl_parcels *pc, const bdl_gas *gas, long idx)
{
    return 1.0 - gas->eps[idx] > pc->def.close_packing &&
           gas->eps[idx] < pc->eps_begin[idx] - 1e-12;
}

/// Whether any cell of the gas grid is overfull (overfull_cell); the largest solids fraction of
/// a cell into *max_solids.
static int overfull(const bdl_parcels *pc, const bdl_gas *gas, double *max_solids)
{
    const bdl_grid *g = &gas->grid;
    int any = 0;
    double top = 0.0;
    for (int k = 0; k < g->n[2]; ++k)
        for (int j = 0; j < g->n[1]; ++j)
            for (int i = 0; i < g->n[0]; ++i) {
                const long idx = bdl_grid_index(g, i, j, k);
                top = fmax(top, 1.0 - gas->eps[idx]);
                any |= overfull_cell(pc, gas, idx);
            }
    *max_solids = top;
    return any;
}

/// The solids fraction of the parcels where they are now; while a cell is overfull (above close
/// packing and above its start), every parcel whose move added to such a cell returns to where
/// the step began, at rest (and with no collision acceleration of the step so far; its kernel
/// weights recomputed, the others' kept). An overfull cell then holds no more than at the start
/// (the parcels that stay moved gave it no more than before), so each round ends one; a
/// returned parcel may overfill another, which the next round mends: every round returns
/// parcels for good, so the rounds end.
static bdl_result place(bdl_parcels *pc, bdl_coupling *c, bdl_gas *gas, bdl_particles *p,
                        bdl_parcels_report *out)
{
    if (bdl_coupling_locate(c, gas, p) != BDL_OK)
        return BDL_ERR_NOMEM;
    for (;;) {
        bdl_coupling_voidage(c, gas, p);
        if (!overfull(pc, gas, &out->max_solids))
            return BDL_OK;
        // A cell field marking the overfull cells, read back through the kernels.
        double *mark = pc->tau;
        const bdl_grid *g = &gas->grid;
        for (long idx = 0; idx < g->size; ++idx)
            mark[idx] = overfull_cell(pc, gas, idx) ? 1.0 : 0.0;
        BDL_PARALLEL_FOR(
            p->count >= c->parallel_min, for (long i = 0; i < p->count; ++i) {
                const bdl_vec3 x = p->pos[i], x0 = pc->start[i];
                pc->held[i] = (x.x != x0.x || x.y != x0.y || x.z != x0.z) &&
                              bdl_coupling_touches(c, i, mark) &&
                              bdl_coupling_gains(c, gas, i, x0, mark);
                if (pc->held[i]) {
                    p->pos[i] = x0;
                    p->vel[i] = bdl_v3_zero();
                    pc->accel[i] = bdl_v3_zero();
                    pc->moved[i] = bdl_v3_zero();
                }
            });
        const long moved = count_marked(pc->held, p->count);
        out->held += moved;
        if (moved == 0) // only round-off above the start: go on
            return BDL_OK;
        if (bdl_coupling_relocate(c, gas, p, pc->held) != BDL_OK)
            return BDL_ERR_NOMEM;
    }
}

// ---------------------------------------------------------------------------------------------
// Stress.

/// tau in the cells, grad tau / theta on the momentum faces, and A_b = g + A_cp at each parcel.
static void stress(bdl_parcels *pc, const bdl_coupling *c, const bdl_gas *gas,
                   const bdl_particles *p, bdl_vec3 gravity)
{
    const bdl_grid *g = &gas->grid;
    for (long idx = 0; idx < g->size; ++idx)
        pc->tau[idx] = bdl_parcels_stress(&pc->def, 1.0 - gas->eps[idx]);
    for (int a = 0; a < 3; ++a) {
        const long s = g->stride[a];
        const double inv_h = 1.0 / g->h[a];
        double *grad = pc->grad[a];
        memset(grad, 0, (size_t)g->size * sizeof(double));
        // Interior faces only: the kernels reach no face on a wall, and across a periodic side
        // the ghost cells are the images.
        for (int k = 0; k < g->n[2] + (a == 2); ++k)
            for (int j = 0; j < g->n[1] + (a == 1); ++j)
                for (int i = 0; i < g->n[0] + (a == 0); ++i) {
                    const int m = a == 0 ? i : a == 1 ? j : k;
                    if (!g->periodic[a] && (m == 0 || m == g->n[a]))
                        continue;
                    const long idx = bdl_grid_index(g, i, j, k);
                    const double theta = 1.0 - 0.5 * (gas->eps[idx] + gas->eps[idx - s]);
                    grad[idx] = (pc->tau[idx] - pc->tau[idx - s]) * inv_h / fmax(theta, 1e-3);
                }
    }
    BDL_PARALLEL_FOR(
        p->count >= c->parallel_min, for (long i = 0; i < p->count; ++i) {
            const double density = 1.0 / (p->inv_mass[i] * bdl_particle_solids_volume(p, i));
            const bdl_vec3 gt = bdl_coupling_face_average(c, i, pc->grad);
            pc->accel[i] = bdl_v3_madd(gravity, gt, -1.0 / density);
        });
}

/// Model B: the last collision acceleration at the step's final positions, and A_b = g + A_cp
/// with A_cp the mean of the step's K evaluations.
static bdl_result collision_accel(bdl_parcels *pc, bdl_particles *p, bdl_vec3 gravity, double dt,
                                  bdl_parcels_report *out)
{
    const int parts = pc->def.substeps > 0 ? pc->def.substeps : 1;
    if (collide(pc, p, dt / parts, NULL, &out->contacts) != BDL_OK)
        return BDL_ERR_NOMEM;
    for (long i = 0; i < p->count; ++i)
        pc->accel[i] = bdl_v3_madd(gravity, pc->accel[i], 1.0 / parts);
    return BDL_OK;
}

// ---------------------------------------------------------------------------------------------
// The step.

/// v^{n+1} = v + a dt / m (u - v - dt A_b + dt grad p / rho_p) + dt (A_b - grad p / rho_p): the
/// implicit update written as the drag the gas gave plus the other forces; the move still to
/// come, dt (v^{n+1} - v - m), into pc->moved (m: what it held, the drift's velocity beyond v);
/// the total drag on the parcels into `drag`, and the work of the gas's forces (drag and
/// pressure) over the step, dt F . (v^n + v^{n+1}) / 2, into *work.
static void velocities(bdl_parcels *pc, const bdl_coupling *c, double *const gas_u[3],
                       double *const grad_p[3], bdl_particles *p, double dt, double drag[3],
                       double *work)
{
    BDL_PARALLEL_FOR(
        p->count >= c->parallel_min, for (long i = 0; i < p->count; ++i) {
            const double m_inv = p->inv_mass[i], volume = bdl_particle_solids_volume(p, i);
            const double density = 1.0 / (m_inv * volume);
            bdl_vec3 u, gp; // the gas velocity and pressure gradient at the parcel
            bdl_coupling_face_average2(c, i, gas_u, grad_p, &u, &gp);
            const bdl_vec3 other = bdl_v3_madd(pc->accel[i], gp, -1.0 / density);
            const bdl_vec3 slip = bdl_v3_sub(bdl_v3_sub(u, p->vel[i]), bdl_v3_scale(other, dt));
            const bdl_vec3 f = bdl_v3_scale(slip, c->factor[i]);
            const bdl_vec3 v0 = p->vel[i];
            p->vel[i] = bdl_v3_add(v0, bdl_v3_scale(bdl_v3_madd(other, f, m_inv), dt));
            pc->moved[i] = bdl_v3_scale(bdl_v3_sub(bdl_v3_sub(p->vel[i], v0), pc->moved[i]), dt);
            // The drag as the gas booked it, a (u - v - dt A_b); the rest of f, a dt grad p /
            // rho_p, is the share of the pressure force the gas's 1 - C_pr handed over.
            p->load[i].force = bdl_v3_madd(f, gp, -c->factor[i] * dt / density);
            const bdl_vec3 gas_force = bdl_v3_madd(f, gp, -volume);
            pc->value[i] = 0.5 * dt * bdl_v3_dot(gas_force, bdl_v3_add(v0, p->vel[i]));
        });
    drag[0] = drag[1] = drag[2] = 0.0;
    *work = 0.0;
    for (long i = 0; i < p->count; ++i) { // serial: a fixed summation order
        drag[0] += p->load[i].force.x;
        drag[1] += p->load[i].force.y;
        drag[2] += p->load[i].force.z;
        *work += pc->value[i];
    }
}

/// sum = (sum + w f) * scale over a padded grid field.
static void add_field(const bdl_grid *g, double *sum, const double *f, double w, double scale)
{
    for (long idx = 0; idx < g->size; ++idx)
        sum[idx] = (sum[idx] + w * f[idx]) * scale;
}

/// The gas over h, the solids fraction at the fraction `reach` of the way from the step's start
/// to its end (1: its end exactly).
static bdl_result gas_part(bdl_parcels *pc, bdl_gas *gas, double h, double reach)
{
    const bdl_grid *g = &gas->grid;
    if (reach < 1.0)
        for (long idx = 0; idx < g->size; ++idx)
            gas->eps[idx] = pc->eps_start[idx] + reach * (pc->eps_end[idx] - pc->eps_start[idx]);
    else
        memcpy(gas->eps, pc->eps_end, (size_t)g->size * sizeof(double));
    return bdl_gas_step(gas, h);
}

/// After a gas step of length h that converged: whether h passed the gas's CFL 1 (twice its
/// stable step); if so the step and the stable step at its end into *out.
static int past_cfl(const bdl_gas *gas, double h, bdl_parcels_report *out)
{
    const double stable = bdl_gas_stable_dt(gas);
    if (!(h > 2.0 * stable))
        return 0;
    out->failed_dt = h;
    out->stable_dt = stable;
    return 1;
}

/// Step 5: the gas over dt. With gas_substeps G > 1 and dt above the gas's stable step, in
/// parts: each time the rest of the step in equal parts no longer than the stable step at the
/// gas's velocities then (at most G parts in all, the last taking what is left), so that the
/// parts follow the gas as it speeds up. The fields the parcels' velocities read into u and
/// grad_p: the gas's own after one part, their means over the step after several. The stable
/// step (times G) and the parts taken into *out.
static bdl_result gas_steps(bdl_parcels *pc, bdl_gas *gas, double dt, double *u[3],
                            double *grad_p[3], bdl_parcels_report *out)
{
    const int most = pc->def.gas_substeps > 1 ? pc->def.gas_substeps : 1;
    const bdl_grid *g = &gas->grid;
    const size_t bytes = (size_t)g->size * sizeof(double);
    bdl_result r;
    if (most == 1 || !(dt > bdl_gas_stable_dt(gas))) {
        r = bdl_gas_step(gas, dt);
        out->gas_steps = 1;
        for (int a = 0; a < 3; ++a)
            u[a] = gas->u[a], grad_p[a] = gas->grad_p[a];
        // In one part the gas may have sped up past its CFL (from rest, say); that fails only
        // beyond what G parts could have taken, the next step sub-cycling at the new speed.
        if (r == BDL_OK && past_cfl(gas, dt / most, out)) {
            out->failed_dt = dt;
            out->failed_part = most > 1;
            return BDL_ERR_UNSTABLE;
        }
    } else {
        memcpy(pc->eps_start, gas->eps_old, bytes);
        memcpy(pc->eps_end, gas->eps, bytes);
        for (int a = 0; a < 3; ++a) {
            u[a] = pc->u_mean[a], grad_p[a] = pc->grad_p_mean[a];
            memset(u[a], 0, bytes);
            memset(grad_p[a], 0, bytes);
        }
        double done = 0.0;
        r = BDL_OK;
        while (r == BDL_OK && done < dt) {
            const double left = dt - done, stable = bdl_gas_stable_dt(gas);
            const int parts = (int)fmin(most - out->gas_steps, fmax(1.0, ceil(left / stable)));
            const double h = parts == 1 ? left : left / parts;
            done = parts == 1 ? dt : done + h;
            r = gas_part(pc, gas, h, done < dt ? done / dt : 1.0);
            out->gas_steps++;
            if (r == BDL_OK && past_cfl(gas, h, out)) {
                out->failed_part = 1;
                return BDL_ERR_UNSTABLE;
            }
            const double scale = done < dt ? 1.0 : 1.0 / dt;
            for (int a = 0; a < 3; ++a) {
                add_field(g, u[a], gas->u[a], h, scale);
                add_field(g, grad_p[a], gas->grad_p[a], h, scale);
            }
        }
    }
    out->stable_dt = r == BDL_OK ? most * bdl_gas_stable_dt(gas) : 0.0;
    return r;
}

/// Step 7: every parcel moves on by dt (v^{n+1} - v^n - m) (pc->moved), so that over the step it
/// moved by dt v^{n+1}, as the gas's pressure equation counted its volume flux; the sides met as
/// in the drift, the guard as after it, and the gas's voidage (new and old) the parcels' there.
static bdl_result settle(bdl_parcels *pc, bdl_coupling *c, bdl_gas *gas, bdl_particles *p,
                         bdl_parcels_report *out)
{
    BDL_PARALLEL_FOR(
        p->count >= c->parallel_min, for (long i = 0; i < p->count; ++i) {
            p->pos[i] = bdl_v3_add(p->pos[i], pc->moved[i]);
            int beyond = 0;
            for (int a = 0; a < 3; ++a)
                beyond |= keep_inside(pc, gas, p, i, a);
            pc->held[i] = (uint8_t)beyond;
        });
    if (count_marked(pc->held, p->count) > 0)
        remove_marked(pc, p, out);
    const bdl_result r = place(pc, c, gas, p, out);
    memcpy(gas->eps_old, gas->eps, (size_t)gas->grid.size * sizeof(double));
    return r;
}

bdl_result bdl_parcels_step(bdl_parcels *pc, bdl_coupling *c, bdl_gas *gas, bdl_particles *p,
                            const bdl_parcels_step_def *def, bdl_parcels_report *out)
{
    const double t0 = bdl_wall_seconds(), dt = def->dt;
    *out = (bdl_parcels_report){0};
    // The parcels in cell order first (now and then), for the kernels' locality.
    if (reserve(pc, p->count) != BDL_OK || bdl_coupling_sort(c, gas, p, NULL) != BDL_OK)
        return BDL_ERR_NOMEM;
    memcpy(pc->eps_begin, gas->eps, (size_t)gas->grid.size * sizeof(double));
    if (p->count > 0) // no arrays without parcels (memcpy takes no null pointer)
        memcpy(pc->start, p->pos, (size_t)p->count * sizeof(bdl_vec3));
    pc->collisions.parallel_min = c->parallel_min;
    long leaving = 0;
    bdl_result r = drift(pc, gas, p, dt, &leaving);
    if (r != BDL_OK)
        return r;
    if (leaving > 0)
        remove_marked(pc, p, out);
    r = place(pc, c, gas, p, out);
    if (r != BDL_OK)
        return r;
    if (def->first)
        memcpy(gas->eps_old, gas->eps, (size_t)gas->grid.size * sizeof(double));
    if (pc->def.model == BDL_PARCEL_COLLISIONS)
        r = collision_accel(pc, p, def->gravity, dt, out);
    else
        stress(pc, c, gas, p, def->gravity);
    if (r != BDL_OK)
        return r;
    // and the pressure share 1 - C_pr and the flux still to come:
    bdl_coupling_drag_setup(c, gas, p, pc->accel, pc->moved, dt);
    const double t1 = bdl_wall_seconds();
    double *u[3], *grad_p[3];
    r = gas_steps(pc, gas, dt, u, grad_p, out);
    const double t2 = bdl_wall_seconds();
    out->gas_seconds = t2 - t1;
    if (r != BDL_OK)
        return r;
    velocities(pc, c, u, grad_p, p, dt, out->particle_drag, &out->gas_work);
    bdl_coupling_gas_drag(gas, u, out->gas_drag);
    r = settle(pc, c, gas, p, out);
    if (r != BDL_OK)
        return r;
    out->parcel_seconds = (t1 - t0) + (bdl_wall_seconds() - t2);
    return BDL_OK;
}
