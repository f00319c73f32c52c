// bedlam — parcel collisions: the cell list and the soft-sphere force of model B (collisions.h).
#include "parcels/collisions.h"

#include <stdlib.h>
#include <string.h>

#include "core/memory.h"
#include "core/parallel.h"

double bdl_parcel_collision_damping(double restitution, double mass, double stiffness)
{
    if (!(restitution > 0.0) || !(mass > 0.0) || !(stiffness > 0.0))
        return 0.0;
    const double alpha = -log(fmin(restitution, 1.0)) / BDL_PI;
    return 2.0 * alpha * sqrt(mass * stiffness / (1.0 + alpha * alpha));
}

bdl_result bdl_parcel_collisions_init(bdl_parcel_collisions *c, const bdl_parcel_collision_law *law,
                                      const bdl_parcel_box *box)
{
    *c = (bdl_parcel_collisions){0};
    c->law = *law;
    c->box = *box;
    c->parallel_min = BDL_PARALLEL_MIN;
    return BDL_OK;
}

void bdl_parcel_collisions_free(bdl_parcel_collisions *c)
{
    free(c->sphere);
    free(c->cell);
    free(c->order);
    free(c->overlap);
    free(c->touching);
    free(c->touching_wall);
    free(c->start);
    *c = (bdl_parcel_collisions){0};
}

static bdl_result reserve(bdl_parcel_collisions *c, long parcels, long cells)
{
    if (parcels > c->capacity) {
        const long cap = parcels + parcels / 4 + 64;
        if (!bdl_grow((void **)&c->sphere, cap, sizeof(double)) ||
            !bdl_grow((void **)&c->cell, cap, sizeof(int32_t)) ||
            !bdl_grow((void **)&c->order, cap, sizeof(int32_t)) ||
            !bdl_grow((void **)&c->overlap, cap, sizeof(double)) ||
            !bdl_grow((void **)&c->touching, cap, sizeof(int32_t)) ||
            !bdl_grow((void **)&c->touching_wall, cap, sizeof(int32_t)))
            return BDL_ERR_NOMEM;
        c->capacity = cap;
    }
    if (cells + 1 > c->cell_capacity) {
        if (!bdl_grow((void **)&c->start, cells + 1, sizeof(long)))
            return BDL_ERR_NOMEM;
        c->cell_capacity = cells + 1;
    }
    return BDL_OK;
}

/// Cells per axis at least `reach` wide; no more cells in all than a few per parcel (wider cells
/// then: a search over more parcels, never a missed pair).
static void choose_cells(bdl_parcel_collisions *c, double reach, long parcels)
{
    const double cap = 4.0 * (double)parcels + 64.0;
    double width = reach > 0.0 ? reach : INFINITY, m[3];
    for (int tries = 0; tries < 400; ++tries, width *= 1.25) {
        for (int a = 0; a < 3; ++a) {
            const double extent = c->box.hi[a] - c->box.lo[a];
            m[a] = fmax(1.0, floor(extent / width));
        }
        if (m[0] * m[1] * m[2] <= cap)
            break;
    }
    for (int a = 0; a < 3; ++a) {
        c->n[a] = (int)fmin(m[a], 1 << 20);
        c->inv_cell[a] = c->n[a] / (c->box.hi[a] - c->box.lo[a]);
    }
}

/// The cell of position x.
static long cell_of(const bdl_parcel_collisions *c, bdl_vec3 x)
{
    long index = 0;
    for (int a = 2; a >= 0; --a) {
        const double f = (bdl_v3_comp(x, a) - c->box.lo[a]) * c->inv_cell[a];
        const int m = !(f > 0.0) ? 0 : f >= c->n[a] ? c->n[a] - 1 : (int)f;
        index = index * c->n[a] + m;
    }
    return index;
}

/// Every parcel's sphere and cell, and the parcels sorted by cell (by index within a cell).
static bdl_result bin(bdl_parcel_collisions *c, const bdl_particles *p, const uint8_t *skip)
{
    double r_max = 0.0;
    for (long i = 0; i < p->count; ++i) {
        c->sphere[i] = bdl_parcel_sphere_radius(p, i);
        if (!skip || !skip[i])
            r_max = fmax(r_max, c->sphere[i]);
    }
    choose_cells(c, (1.0 + c->law.range) * 2.0 * r_max, p->count);
    const long cells = (long)c->n[0] * c->n[1] * c->n[2];
    if (reserve(c, p->count, cells) != BDL_OK)
        return BDL_ERR_NOMEM;
    memset(c->start, 0, (size_t)(cells + 1) * sizeof(long));
    for (long i = 0; i < p->count; ++i) {
        c->cell[i] = skip && skip[i] ? -1 : (int32_t)cell_of(c, p->pos[i]);
        if (c->cell[i] >= 0)
            c->start[c->cell[i] + 1]++;
    }
    for (long k = 0; k < cells; ++k)
        c->start[k + 1] += c->start[k];
    for (long i = 0; i < p->count; ++i) // start[k] becomes the end of cell k
        if (c->cell[i] >= 0)
            c->order[c->start[c->cell[i]]++] = (int32_t)i;
    for (long k = cells; k > 0; --k)
        c->start[k] = c->start[k - 1];
    c->start[0] = 0;
    return BDL_OK;
}

/// The distinct cells at offsets -1, 0, +1 from cell m along an axis of n cells; their count.
static int axis_cells(int m, int n, int periodic, int out[3])
{
    int k = 0;
    for (int o = -1; o <= 1; ++o) {
        int q = m + o;
        if (periodic)
            q = (q + n) % n;
        else if (q < 0 || q >= n)
            continue;
        int seen = 0;
        for (int e = 0; e < k; ++e)
            seen |= out[e] == q;
        if (!seen)
            out[k++] = q;
    }
    return k;
}

/// k_c delta^m.
static inline double spring(const bdl_parcel_collision_law *law, double delta)
{
    const double m = law->exponent;
    const double power = m == 1.5 ? delta * sqrt(delta) : m == 1.0 ? delta : pow(delta, m);
    return law->stiffness * power;
}

/// x_i - x_j, through the nearest image along the periodic axes (an exact negative when i and j
/// trade places).
static inline bdl_vec3 separation(const bdl_parcel_box *box, bdl_vec3 xi, bdl_vec3 xj)
{
    bdl_vec3 d = bdl_v3_sub(xi, xj);
    for (int a = 0; a < 3; ++a) {
        if (!box->periodic[a])
            continue;
        const double L = box->hi[a] - box->lo[a], s = bdl_v3_comp(d, a);
        bdl_v3_set_comp(&d, a, s > 0.5 * L ? s - L : s < -0.5 * L ? s + L : s);
    }
    return d;
}

/// The force of parcel j on parcel i (eq. 17); zero beyond the range. Adds to *touching and
/// raises *overlap (delta / R_ei) when they touch.
static inline bdl_vec3 pair_force(const bdl_parcel_collisions *c, const bdl_particles *p,
                                  const bdl_vec3 *vel, long i, long j, int32_t *touching,
                                  double *overlap)
{
    const double ri = c->sphere[i], rj = c->sphere[j];
    const double reach = (1.0 + c->law.range) * (ri + rj);
    const bdl_vec3 d = separation(&c->box, p->pos[i], p->pos[j]);
    const double d2 = bdl_v3_len2(d);
    if (!(d2 < reach * reach) || d2 == 0.0) // coincident centres: no direction, no force
        return bdl_v3_zero();
    const double dist = sqrt(d2), delta = reach - dist;
    const bdl_vec3 n = bdl_v3_scale(d, 1.0 / dist);
    const double vn = bdl_v3_dot(bdl_v3_sub(vel[i], vel[j]), n);
    *touching += 1;
    *overlap = fmax(*overlap, delta / ri);
    return bdl_v3_scale(n, spring(&c->law, delta) - c->law.damping * vn);
}

/// The sides' force on parcel i (eq. 19, the overlap from the threshold: collisions.h).
static bdl_vec3 wall_force(const bdl_parcel_collisions *c, const bdl_particles *p,
                           const bdl_vec3 *vel, long i, int32_t *touching, double *overlap)
{
    const bdl_parcel_box *box = &c->box;
    const double r = c->sphere[i], reach = r + c->law.range * 2.0 * r;
    bdl_vec3 f = bdl_v3_zero();
    for (int a = 0; a < 3; ++a) {
        if (box->periodic[a])
            continue;
        const double x = bdl_v3_comp(p->pos[i], a), v = bdl_v3_comp(vel[i], a);
        double fa = 0.0;
        for (int side = 0; side < 2; ++side) {
            const double dw = side ? box->hi[a] - x : x - box->lo[a];
            if (!box->solid[2 * a + side] || !(dw < reach))
                continue;
            const double delta = reach - dw, vn = side ? -v : v; // vn = u . n, n inward
            const double push = spring(&c->law, delta) - c->law.damping * vn;
            fa += side ? -push : push;
            *touching += 1;
            *overlap = fmax(*overlap, delta / r);
        }
        bdl_v3_set_comp(&f, a, bdl_v3_comp(f, a) + fa);
    }
    return f;
}

/// F_cp on parcel i: its pairs, cell by cell in a fixed order, then the sides.
static bdl_vec3 force_on(bdl_parcel_collisions *c, const bdl_particles *p, const bdl_vec3 *vel,
                         long i)
{
    c->overlap[i] = 0.0;
    c->touching[i] = c->touching_wall[i] = 0;
    if (c->cell[i] < 0)
        return bdl_v3_zero();
    const long home = c->cell[i];
    const int m[3] = {(int)(home % c->n[0]), (int)(home / c->n[0] % c->n[1]),
                      (int)(home / ((long)c->n[0] * c->n[1]))};
    int around[3][3], count[3];
    for (int a = 0; a < 3; ++a)
        count[a] = axis_cells(m[a], c->n[a], c->box.periodic[a], around[a]);
    bdl_vec3 f = bdl_v3_zero();
    for (int z = 0; z < count[2]; ++z)
        for (int y = 0; y < count[1]; ++y)
            for (int x = 0; x < count[0]; ++x) {
                const long cell =
                    ((long)around[2][z] * c->n[1] + around[1][y]) * c->n[0] + around[0][x];
                for (long k = c->start[cell]; k < c->start[cell + 1]; ++k) {
                    const long j = c->order[k];
                    if (j != i)
                        f = bdl_v3_add(
                            f, pair_force(c, p, vel, i, j, &c->touching[i], &c->overlap[i]));
                }
            }
    return bdl_v3_add(f, wall_force(c, p, vel, i, &c->touching_wall[i], &c->overlap[i]));
}

bdl_result bdl_parcel_collisions_force(bdl_parcel_collisions *c, const bdl_particles *p,
                                       const bdl_vec3 *vel, const uint8_t *skip, bdl_vec3 *force,
                                       bdl_parcel_contacts *found)
{
    if (reserve(c, p->count, 0) != BDL_OK || bin(c, p, skip) != BDL_OK)
        return BDL_ERR_NOMEM;
    BDL_PARALLEL_FOR(p->count >= c->parallel_min,
                     for (long i = 0; i < p->count; ++i) force[i] = force_on(c, p, vel, i););
    if (found) {
        *found = (bdl_parcel_contacts){0};
        for (long i = 0; i < p->count; ++i) { // serial: counts and a maximum
            found->pairs += c->touching[i];
            found->walls += c->touching_wall[i];
            found->max_overlap = fmax(found->max_overlap, c->overlap[i]);
        }
        found->pairs /= 2;
    }
    return BDL_OK;
}
