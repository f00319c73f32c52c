#include "dem/neighbor.h"
#include "dem/capsule.h"
#include "core/memory.h"
#include "core/parallel.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static uint64_t spread_bits(uint64_t v)
{
    v &= 0x1fffff;
    v = (v | v << 32) & 0x1f00000000ffffULL;
    v = (v | v << 16) & 0x1f0000ff0000ffULL;
    v = (v | v << 8) & 0x100f00f00f00f00fULL;
    v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
    v = (v | v << 2) & 0x1249249249249249ULL;
    return v;
}

typedef struct morton_entry {
    uint64_t code;
    int32_t cell;
} morton_entry;

static int compare_morton(const void *a, const void *b)
{
    const morton_entry *x = a, *y = b;
    if (x->code != y->code)
        return x->code < y->code ? -1 : 1;
    return x->cell - y->cell;
}

static bdl_result rank_cells(bdl_neighbor *nb)
{
    morton_entry *e = malloc((size_t)nb->cell_count * sizeof *e);
    if (!e)
        return BDL_ERR_NOMEM;
    for (long c = 0; c < nb->cell_count; ++c) {
        uint64_t cx = (uint64_t)(c % nb->dims[0]);
        uint64_t cy = (uint64_t)((c / nb->dims[0]) % nb->dims[1]);
        uint64_t cz = (uint64_t)(c / ((long)nb->dims[0] * nb->dims[1]));
        e[c].code = spread_bits(cx) | spread_bits(cy) << 1 | spread_bits(cz) << 2;
        e[c].cell = (int32_t)c;
    }
    qsort(e, (size_t)nb->cell_count, sizeof *e, compare_morton);
    for (long r = 0; r < nb->cell_count; ++r)
        nb->cell_rank[e[r].cell] = (int32_t)r;
    free(e);
    return BDL_OK;
}

bdl_result bdl_neighbor_init(bdl_neighbor *nb, bdl_vec3 lo, bdl_vec3 hi, const int periodic[3],
                             double cutoff, double skin, long max_particles, int friction,
                             int hertz, int rolling, int rods)
{
    memset(nb, 0, sizeof *nb);
    nb->origin = lo;
    nb->length = bdl_v3_sub(hi, lo);
    nb->skin = skin;
    nb->friction = friction;
    nb->mindlin = friction && hertz;
    nb->rolling = rolling;
    nb->rods = rods;
    nb->parallel_min = BDL_PARALLEL_MIN;
    long max_cells = 4 * max_particles + 4096;
    double size = cutoff;
    for (;;) {
        long total = 1;
        for (int a = 0; a < 3; ++a) {
            double len = bdl_v3_comp(nb->length, a);
            // Clamped as a number: a nanometre cutoff over a metre is beyond an int.
            const double n = floor(len / size);
            const int d = n >= (double)(1 << 20) ? 1 << 20 : (n < 1.0 ? 1 : (int)n);
            nb->dims[a] = d;
            nb->cell[a] = len / d;
            nb->periodic[a] = periodic[a];
            total *= d;
        }
        nb->cell_count = total;
        if (total <= max_cells)
            break;
        size *= 1.25;
    }
    for (int a = 0; a < 3; ++a)
        if (nb->periodic[a] && nb->dims[a] < 3)
            return BDL_ERR_SCENE;
    if (!bdl_grow((void **)&nb->cell_rank, nb->cell_count, sizeof(int32_t)) ||
        !bdl_grow((void **)&nb->cell_start, nb->cell_count + 1, sizeof(int32_t)) ||
        !bdl_grow((void **)&nb->cell_cursor, nb->cell_count, sizeof(int32_t)))
        return BDL_ERR_NOMEM;
    return rank_cells(nb);
}

void bdl_neighbor_free(bdl_neighbor *nb)
{
    void *arrays[] = {nb->cell_rank,
                      nb->cell_start,
                      nb->cell_cursor,
                      nb->start,
                      nb->partner,
                      nb->history,
                      nb->spring_work,
                      nb->stash_history,
                      nb->stash_spring_work,
                      nb->stash_partner,
                      nb->stash_start,
                      nb->touching,
                      nb->wall_start,
                      nb->wall_prim,
                      nb->wall_history,
                      nb->wall_spring_work,
                      nb->wall_force,
                      nb->wall_touching,
                      nb->old_wall_start,
                      nb->old_wall_prim,
                      nb->old_wall_history,
                      nb->old_wall_spring_work,
                      nb->perm,
                      nb->pcell,
                      nb->ghost_head,
                      nb->ghost_next,
                      nb->scratch};
    for (size_t k = 0; k < sizeof arrays / sizeof arrays[0]; ++k)
        free(arrays[k]);
    memset(nb, 0, sizeof *nb);
}

/// The cell of coordinate x along an axis, clamped to the grid; clamped before the conversion, so
/// that a runaway particle (or a NaN) gives an edge cell instead of an undefined conversion.
static inline int clamp_cell(double x, double size, int dims)
{
    const double c = floor(x / size);
    return !(c >= 0.0) ? 0 : (c >= (double)dims ? dims - 1 : (int)c);
}

static inline void cell_of(const bdl_neighbor *nb, bdl_vec3 x, int c[3])
{
    c[0] = clamp_cell(x.x - nb->origin.x, nb->cell[0], nb->dims[0]);
    c[1] = clamp_cell(x.y - nb->origin.y, nb->cell[1], nb->dims[1]);
    c[2] = clamp_cell(x.z - nb->origin.z, nb->cell[2], nb->dims[2]);
}

/// Cell index along an axis after a step of -1, 0, +1; -1 when outside a non-periodic grid.
static inline int step_cell(const bdl_neighbor *nb, int axis, int c)
{
    int d = nb->dims[axis];
    if (c < 0)
        return nb->periodic[axis] ? c + d : -1;
    if (c >= d)
        return nb->periodic[axis] ? c - d : -1;
    return c;
}

/// Whether j comes within the skin of i: the centres closer than r_i + r_j + skin, or with rods
/// the shafts (the centres first, within the rods' half lengths).
static inline int listed(const bdl_neighbor *nb, const bdl_particles *p, long i, long j, bdl_vec3 d)
{
    double cut = p->radius[i] + p->radius[j] + nb->skin;
    if (!nb->rods)
        return bdl_v3_len2(d) < cut * cut;
    const double reach = cut + p->half_length[i] + p->half_length[j];
    if (!(bdl_v3_len2(d) < reach * reach))
        return 0;
    double l, m;
    const double d2 =
        bdl_shafts_closest(d, p->axis[i], p->half_length[i], p->axis[j], p->half_length[j], &l, &m);
    return d2 < cut * cut;
}

/// Visits every j > i listed with i (see `listed`); `out` NULL counts only. Across the z faces of
/// a sheared box the images have slid along x: the whole x row is searched there.
static int32_t scan_pairs(const bdl_neighbor *nb, const bdl_particles *p, long i, int32_t *out)
{
    int c[3];
    cell_of(nb, p->pos[i], c);
    int32_t n = 0;
    bdl_vec3 xi = p->pos[i];
    for (int dz = -1; dz <= 1; ++dz) {
        int z = step_cell(nb, 2, c[2] + dz);
        if (z < 0)
            continue;
        const int row = nb->shear_velocity != 0.0 && z != c[2] + dz;
        const int x_first = row ? 0 : -1, x_last = row ? nb->dims[0] - 1 : 1;
        for (int dy = -1; dy <= 1; ++dy) {
            int y = step_cell(nb, 1, c[1] + dy);
            if (y < 0)
                continue;
            for (int dx = x_first; dx <= x_last; ++dx) {
                int x = row ? dx : step_cell(nb, 0, c[0] + dx);
                if (x < 0)
                    continue;
                long cell = x + (long)nb->dims[0] * (y + (long)nb->dims[1] * z);
                int32_t r = nb->cell_rank[cell];
                for (int32_t j = nb->cell_start[r]; j < nb->cell_start[r + 1]; ++j) {
                    if (j <= i)
                        continue;
                    if (listed(nb, p, i, j, bdl_neighbor_delta(nb, xi, p->pos[j]))) {
                        if (out)
                            out[n] = j;
                        ++n;
                    }
                }
                for (int32_t j = nb->ghosted ? nb->ghost_head[r] : -1; j >= 0;
                     j = nb->ghost_next[j - nb->owned])
                    if (j > i && listed(nb, p, i, j, bdl_neighbor_delta(nb, xi, p->pos[j]))) {
                        if (out)
                            out[n] = j;
                        ++n;
                    }
            }
        }
    }
    return n;
}

static bdl_result reserve_particles(bdl_neighbor *nb, long n);

bdl_result bdl_neighbor_none(bdl_neighbor *nb, long n)
{
    if (reserve_particles(nb, n) != BDL_OK)
        return BDL_ERR_NOMEM;
    memset(nb->start, 0, (size_t)(n + 1) * sizeof(int32_t));
    memset(nb->wall_start, 0, (size_t)(n + 1) * sizeof(int32_t));
    nb->count = n;
    return BDL_OK;
}

static bdl_result reserve_particles(bdl_neighbor *nb, long n)
{
    if (n <= nb->scratch_count && nb->start)
        return BDL_OK;
    long cap = n + n / 16 + 16;
    int ok = bdl_grow((void **)&nb->start, cap + 1, sizeof(int32_t)) &&
             bdl_grow((void **)&nb->stash_start, cap + 1, sizeof(int32_t)) &&
             bdl_grow((void **)&nb->wall_start, cap + 1, sizeof(int32_t)) &&
             bdl_grow((void **)&nb->old_wall_start, cap + 1, sizeof(int32_t)) &&
             bdl_grow((void **)&nb->perm, cap, sizeof(int32_t)) &&
             bdl_grow((void **)&nb->pcell, cap, sizeof(int32_t)) &&
             bdl_grow(&nb->scratch, cap, sizeof(bdl_vec3));
    if (!ok)
        return BDL_ERR_NOMEM;
    nb->scratch_count = cap;
    return BDL_OK;
}

static bdl_result reserve_pairs(bdl_neighbor *nb, long pairs)
{
    if (pairs <= nb->pair_capacity && nb->partner)
        return BDL_OK;
    long cap = pairs + pairs / 16 + 64;
    int ok = bdl_grow((void **)&nb->partner, cap, sizeof(int32_t)) &&
             bdl_grow((void **)&nb->touching, cap, 1);
    if (ok && nb->friction)
        ok = bdl_grow((void **)&nb->history, cap, sizeof(bdl_vec3));
    if (ok && nb->mindlin)
        ok = bdl_grow((void **)&nb->spring_work, cap, sizeof(double));
    if (!ok)
        return BDL_ERR_NOMEM;
    nb->pair_capacity = cap;
    return BDL_OK;
}

/// Packs the history of the pairs that were touching, grouped by their (old) first particle, so
/// the rebuilt list can look it up by the particles' old indices.
static bdl_result stash_history(bdl_neighbor *nb)
{
    long touching = 0;
    for (long k = 0; k < nb->pair_count; ++k)
        touching += nb->touching[k];
    if (touching > nb->stash_capacity) {
        long cap = touching + touching / 8 + 64;
        if (!bdl_grow((void **)&nb->stash_history, cap, sizeof(bdl_vec3)) ||
            !bdl_grow((void **)&nb->stash_partner, cap, sizeof(int32_t)) ||
            (nb->mindlin && !bdl_grow((void **)&nb->stash_spring_work, cap, sizeof(double))))
            return BDL_ERR_NOMEM;
        nb->stash_capacity = cap;
    }
    long c = 0;
    nb->stash_start[0] = 0;
    for (long i = 0; i < nb->count; ++i) {
        for (int32_t k = nb->start[i]; k < nb->start[i + 1]; ++k) {
            if (!nb->touching[k])
                continue;
            nb->stash_history[c] = nb->history[k];
            if (nb->mindlin)
                nb->stash_spring_work[c] = nb->spring_work[k];
            nb->stash_partner[c] = nb->partner[k];
            ++c;
        }
        nb->stash_start[i + 1] = (int32_t)c;
    }
    return BDL_OK;
}

/// The stash entry of the pair of old indices oi and oj, or -1.
static int32_t find_stashed(const bdl_neighbor *nb, long old_count, int32_t oi, int32_t oj)
{
    if (oi < 0 || oj < 0 || oi >= old_count || oj >= old_count)
        return -1;
    int32_t a = oi < oj ? oi : oj, b = oi < oj ? oj : oi;
    for (int32_t k = nb->stash_start[a]; k < nb->stash_start[a + 1]; ++k)
        if (nb->stash_partner[k] == b)
            return k;
    return -1;
}

/// Sorts the particles by ranked cell; those with drop[i] set (when drop is not NULL) are left
/// out, and the count shrinks by their number.
static void sort_particles(bdl_neighbor *nb, bdl_particles *p, const uint8_t *drop)
{
    long n = p->count, kept = 0;
    memset(nb->cell_start, 0, (size_t)(nb->cell_count + 1) * sizeof(int32_t));
    for (long i = 0; i < n; ++i) {
        if (drop && drop[i]) {
            nb->pcell[i] = -1;
            continue;
        }
        ++kept;
        int c[3];
        cell_of(nb, p->pos[i], c);
        long cell = c[0] + (long)nb->dims[0] * (c[1] + (long)nb->dims[1] * c[2]);
        nb->pcell[i] = nb->cell_rank[cell];
        nb->cell_start[nb->pcell[i] + 1]++;
    }
    for (long r = 0; r < nb->cell_count; ++r)
        nb->cell_start[r + 1] += nb->cell_start[r];
    // Stable counting sort by ranked cell: perm[new] = old.
    memcpy(nb->cell_cursor, nb->cell_start, (size_t)nb->cell_count * sizeof(int32_t));
    for (long i = 0; i < n; ++i)
        if (nb->pcell[i] >= 0)
            nb->perm[nb->cell_cursor[nb->pcell[i]]++] = (int32_t)i;
    p->count = kept; // history is looked up by old index (perm), so dropping needs nothing more
    bdl_particles_permute(p, nb->perm, nb->scratch);
}

void bdl_neighbor_set_shear(bdl_neighbor *nb, double rate, double time)
{
    const double lx = nb->length.x;
    nb->shear_velocity = rate * nb->length.z;
    nb->shear_travel = nb->shear_velocity * time;
    nb->shear_shift = nb->shear_travel - lx * floor(nb->shear_travel / lx + 0.5);
}

/// Lees–Edwards: particles beyond a z face come back through the other at their image's place and
/// velocity (x wrapped after).
static void wrap_sheared(const bdl_neighbor *nb, bdl_particles *p)
{
    const double lo = nb->origin.z, len = nb->length.z;
    for (long i = 0; i < p->count; ++i) {
        const double z = p->pos[i].z;
        if (z >= lo && z < lo + len)
            continue;
        const double images = floor((z - lo) / len); // the image (above: > 0) it is in
        p->pos[i].x -= images * nb->shear_shift;
        p->vel[i].x -= images * nb->shear_velocity;
    }
}

static void wrap_periodic(const bdl_neighbor *nb, bdl_particles *p)
{
    if (nb->shear_velocity != 0.0)
        wrap_sheared(nb, p);
    for (int a = 0; a < 3; ++a) {
        if (!nb->periodic[a])
            continue;
        double lo = bdl_v3_comp(nb->origin, a), len = bdl_v3_comp(nb->length, a);
        for (long i = 0; i < p->count; ++i) {
            double x = bdl_v3_comp(p->pos[i], a);
            if (x < lo || x >= lo + len) {
                x -= len * floor((x - lo) / len);
                if (x >= lo + len)
                    x = lo;
                bdl_v3_set_comp(&p->pos[i], a, x);
            }
        }
    }
}

/// The springs of particle i's pairs that touched before the rebuild, from the stash.
static void restore_history(bdl_neighbor *nb, long old_count, long i)
{
    for (int32_t k = nb->start[i]; k < nb->start[i + 1]; ++k) {
        const int32_t oi = nb->perm[i], oj = nb->perm[nb->partner[k]];
        const int32_t e = find_stashed(nb, old_count, oi, oj);
        // The spring is kept as seen from the lower particle: it turns round with the order.
        const bdl_vec3 u = e < 0 ? bdl_v3_zero() : nb->stash_history[e];
        nb->history[k] = oi < oj ? u : bdl_v3_neg(u);
        if (nb->mindlin)
            nb->spring_work[k] = e < 0 ? 0.0 : nb->stash_spring_work[e];
        nb->touching[k] = (uint8_t)(e >= 0);
    }
}

static bdl_result build_pairs(bdl_neighbor *nb, const bdl_particles *p, long old_count)
{
    long n = p->count;
    const int team = n >= nb->parallel_min;
    BDL_PARALLEL_FOR(team,
                     for (long i = 0; i < n; ++i) nb->start[i + 1] = scan_pairs(nb, p, i, NULL););
    nb->start[0] = 0;
    for (long i = 0; i < n; ++i)
        nb->start[i + 1] += nb->start[i];
    long pairs = nb->start[n];
    if (pairs > INT32_MAX)
        return BDL_ERR_NOMEM;
    bdl_result r = reserve_pairs(nb, pairs);
    if (r != BDL_OK)
        return r;
    nb->pair_count = pairs;
    BDL_PARALLEL_FOR(team, for (long i = 0; i < n; ++i)
                               scan_pairs(nb, p, i, nb->partner + nb->start[i]););
    // A pair marked touching is visited by the next force pass either way: it is evaluated, or
    // cleared (history included) if it no longer overlaps.
    memset(nb->touching, 0, (size_t)pairs);
    if (nb->friction)
        BDL_PARALLEL_FOR(team, for (long i = 0; i < n; ++i) restore_history(nb, old_count, i););
    return BDL_OK;
}

static bdl_result reserve_wall_pairs(bdl_neighbor *nb, long count);

/// The gap between particle i and wall primitive w: of its centre, or with rods of its nearer tip.
static double wall_gap(const bdl_neighbor *nb, const bdl_particles *p, const bdl_walls *walls,
                       long i, int w)
{
    bdl_vec3 normal;
    if (!nb->rods || p->half_length[i] == 0.0)
        return bdl_wall_gap(walls, w, p->pos[i], p->radius[i], &normal);
    const bdl_vec3 e = bdl_particle_half_axis(p, i);
    return fmin(bdl_wall_gap(walls, w, bdl_v3_add(p->pos[i], e), p->radius[i], &normal),
                bdl_wall_gap(walls, w, bdl_v3_sub(p->pos[i], e), p->radius[i], &normal));
}

/// Visits every wall surface within the skin of particle i; `out` NULL counts only.
static int32_t scan_walls(const bdl_neighbor *nb, const bdl_particles *p, const bdl_walls *walls,
                          long i, int32_t *out)
{
    int32_t n = 0;
    for (int w = 0; w < walls->prim_count; ++w) {
        if (wall_gap(nb, p, walls, i, w) < nb->skin) {
            if (out)
                out[n] = w;
            ++n;
        }
    }
    for (int w = 0; w < walls->wall_count; ++w) { // mesh walls hold spheres only
        const int32_t *near = NULL;
        const int m = bdl_walls_near(walls, w, p->pos[i], &near);
        for (int t = 0; t < m; ++t) {
            bdl_vec3 normal;
            if (bdl_wall_tri_gap(walls, near[t], p->pos[i], p->radius[i], &normal) < nb->skin) {
                if (out)
                    out[n] = walls->prim_count + near[t];
                ++n;
            }
        }
    }
    return n;
}

/// Lists the wall primitives near particle i, carrying the springs of those it touched before the
/// rebuild.
static void list_walls(bdl_neighbor *nb, const bdl_particles *p, const bdl_walls *walls,
                       long old_count, long i)
{
    scan_walls(nb, p, walls, i, nb->wall_prim + nb->wall_start[i]);
    const int32_t oi = nb->perm[i];
    for (int32_t k = nb->wall_start[i]; k < nb->wall_start[i + 1]; ++k) {
        nb->wall_history[k] = bdl_v3_zero();
        if (nb->mindlin)
            nb->wall_spring_work[k] = 0.0;
        nb->wall_touching[k] = 0;
        if (oi < 0 || oi >= old_count || !nb->old_wall_prim)
            continue;
        for (int32_t m = nb->old_wall_start[oi]; m < nb->old_wall_start[oi + 1]; ++m)
            if (nb->old_wall_prim[m] == nb->wall_prim[k]) {
                nb->wall_history[k] = nb->old_wall_history[m];
                if (nb->mindlin)
                    nb->wall_spring_work[k] = nb->old_wall_spring_work[m];
            }
    }
}

static bdl_result build_walls(bdl_neighbor *nb, const bdl_particles *p, const bdl_walls *walls,
                              long old_count)
{
    long n = p->count;
    // Keep the previous list for its history.
    int32_t *ts = nb->old_wall_start;
    nb->old_wall_start = nb->wall_start;
    nb->wall_start = ts;
    int32_t *tp = nb->old_wall_prim;
    nb->old_wall_prim = nb->wall_prim;
    nb->wall_prim = tp;
    bdl_vec3 *th = nb->old_wall_history;
    nb->old_wall_history = nb->wall_history;
    nb->wall_history = th;
    double *tw = nb->old_wall_spring_work;
    nb->old_wall_spring_work = nb->wall_spring_work;
    nb->wall_spring_work = tw;
    long tc = nb->old_wall_capacity;
    nb->old_wall_capacity = nb->wall_pair_capacity;
    nb->wall_pair_capacity = tc;

    const int team = n >= nb->parallel_min;
    BDL_PARALLEL_FOR(team, for (long i = 0; i < n; ++i) nb->wall_start[i + 1] =
                               scan_walls(nb, p, walls, i, NULL););
    nb->wall_start[0] = 0;
    for (long i = 0; i < n; ++i)
        nb->wall_start[i + 1] += nb->wall_start[i];
    long count = nb->wall_start[n];
    bdl_result r = reserve_wall_pairs(nb, count);
    if (r != BDL_OK)
        return r;
    nb->wall_pair_count = count;
    BDL_PARALLEL_FOR(team, for (long i = 0; i < n; ++i) list_walls(nb, p, walls, old_count, i););
    for (int w = 0; w < walls->wall_count; ++w) {
        nb->wall_offset_at_build[w] = walls->offset[w];
        nb->wall_angle_at_build[w] = walls->angle[w];
    }
    return BDL_OK;
}

/// The lists of the p->count particles in their places (nb->perm: where each was at the last
/// build, for the history; old_count particles then, 0 to start afresh).
static bdl_result build_lists(bdl_neighbor *nb, bdl_particles *p, const bdl_walls *walls,
                              long old_count)
{
    const long n = p->count;
    for (long i = 0; i < n; ++i)
        p->pos_at_build[i] = p->pos[i];
    if (p->rods)
        for (long i = 0; i < n; ++i)
            p->axis_at_build[i] = bdl_particle_half_axis(p, i);
    bdl_result r = build_pairs(nb, p, old_count);
    if (r == BDL_OK)
        r = build_walls(nb, p, walls, nb->builds > 0 ? nb->count : 0);
    if (r != BDL_OK)
        return r;
    nb->count = n;
    nb->shear_travel_at_build = nb->shear_travel;
    nb->builds++;
    nb->version++;
    return BDL_OK;
}

/// Room for n particles, and the history of the lists being replaced stashed; `old_count` gets
/// the particles those lists had (0 when no history is carried).
static bdl_result prepare(bdl_neighbor *nb, long n, long *old_count)
{
    *old_count = nb->count;
    bdl_result r = reserve_particles(nb, n);
    if (r != BDL_OK)
        return r;
    if (nb->friction && *old_count > 0)
        return stash_history(nb);
    *old_count = 0;
    return BDL_OK;
}

bdl_result bdl_neighbor_build(bdl_neighbor *nb, bdl_particles *p, const bdl_walls *walls,
                              const uint8_t *drop)
{
    long old_count;
    bdl_result r = prepare(nb, p->count, &old_count);
    if (r != BDL_OK)
        return r;
    wrap_periodic(nb, p);
    sort_particles(nb, p, drop);
    nb->ghosted = 0;
    return build_lists(nb, p, walls, old_count);
}

bdl_result bdl_neighbor_sort(bdl_neighbor *nb, bdl_particles *p)
{
    bdl_result r = reserve_particles(nb, p->count);
    if (r != BDL_OK)
        return r;
    wrap_periodic(nb, p);
    sort_particles(nb, p, NULL);
    return BDL_OK;
}

/// The ghosts [owned, p->count) into their cells' lists, each list in the ghosts' order.
static bdl_result list_ghosts(bdl_neighbor *nb, const bdl_particles *p, long owned)
{
    const long ghosts = p->count - owned;
    if (!nb->ghost_head && !bdl_grow((void **)&nb->ghost_head, nb->cell_count, sizeof(int32_t)))
        return BDL_ERR_NOMEM;
    if (ghosts > nb->ghost_capacity) {
        const long cap = ghosts + ghosts / 8 + 64;
        if (!bdl_grow((void **)&nb->ghost_next, cap, sizeof(int32_t)))
            return BDL_ERR_NOMEM;
        nb->ghost_capacity = cap;
    }
    for (long c = 0; c < nb->cell_count; ++c)
        nb->ghost_head[c] = -1;
    for (long g = p->count - 1; g >= owned; --g) { // backwards: each list runs forwards
        int c[3];
        cell_of(nb, p->pos[g], c);
        const int32_t r =
            nb->cell_rank[c[0] + (long)nb->dims[0] * (c[1] + (long)nb->dims[1] * c[2])];
        nb->ghost_next[g - owned] = nb->ghost_head[r];
        nb->ghost_head[r] = (int32_t)g;
    }
    nb->owned = owned;
    nb->ghosted = 1;
    return BDL_OK;
}

bdl_result bdl_neighbor_build_from(bdl_neighbor *nb, bdl_particles *p, const bdl_walls *walls,
                                   const int32_t *origin, long owned)
{
    long old_count;
    bdl_result r = prepare(nb, p->count, &old_count);
    if (r == BDL_OK)
        r = list_ghosts(nb, p, owned);
    if (r != BDL_OK)
        return r;
    memcpy(nb->perm, origin, (size_t)p->count * sizeof *nb->perm);
    return build_lists(nb, p, walls, old_count);
}

int bdl_neighbor_needs_build(const bdl_neighbor *nb, const bdl_particles *p, const bdl_walls *walls,
                             double max_move2)
{
    if (nb->builds == 0 || p->count != nb->count)
        return 1;
    double max2 = max_move2;
    if (max2 < 0.0) {
        max2 = 0.0;
        const long n = p->count;
        if (n < nb->parallel_min) {
            for (long i = 0; i < n; ++i)
                max2 = fmax(max2, bdl_particle_move2(p, i));
        } else {
#pragma omp parallel for schedule(static) reduction(max : max2)
            for (long i = 0; i < n; ++i) {
                const double d2 = bdl_particle_move2(p, i);
                if (d2 > max2)
                    max2 = d2;
            }
        }
    }
    double move = sqrt(max2);
    double wall_move =
        bdl_walls_max_shift(walls, nb->wall_offset_at_build, nb->wall_angle_at_build);
    double slide = fabs(nb->shear_travel - nb->shear_travel_at_build);
    return 2.0 * move + slide > nb->skin || move + wall_move > nb->skin;
}

long bdl_neighbor_bytes(const bdl_neighbor *nb)
{
    const long work = nb->mindlin ? (long)sizeof(double) : 0;
    long per_pair = (long)sizeof(int32_t) + 1 + (nb->friction ? (long)sizeof(bdl_vec3) : 0) + work;
    long per_particle = 6 * (long)sizeof(int32_t) + (long)sizeof(bdl_vec3);
    long per_wall = (long)(sizeof(int32_t) + 2 * sizeof(bdl_vec3) + 1) + work;
    return nb->pair_capacity * per_pair + nb->scratch_count * per_particle +
           nb->stash_capacity * ((long)(sizeof(bdl_vec3) + sizeof(int32_t)) + work) +
           (nb->wall_pair_capacity + nb->old_wall_capacity) * per_wall +
           nb->cell_count * 3 * (long)sizeof(int32_t);
}

static bdl_result reserve_wall_pairs(bdl_neighbor *nb, long count)
{
    if (count <= nb->wall_pair_capacity && nb->wall_prim)
        return BDL_OK;
    long cap = count + count / 8 + 64;
    // Force and contact flags are not double-buffered: they must fit either list.
    long shared = cap > nb->old_wall_capacity ? cap : nb->old_wall_capacity;
    int ok = bdl_grow((void **)&nb->wall_prim, cap, sizeof(int32_t)) &&
             bdl_grow((void **)&nb->wall_history, cap, sizeof(bdl_vec3)) &&
             (!nb->mindlin || bdl_grow((void **)&nb->wall_spring_work, cap, sizeof(double))) &&
             bdl_grow((void **)&nb->wall_force, shared, sizeof(bdl_vec3)) &&
             bdl_grow((void **)&nb->wall_touching, shared, 1);
    if (!ok)
        return BDL_ERR_NOMEM;
    nb->wall_pair_capacity = cap;
    return BDL_OK;
}

bdl_result bdl_neighbor_reserve(bdl_neighbor *nb, long particles, long pairs, long wall_pairs)
{
    bdl_result r = reserve_particles(nb, particles);
    if (r == BDL_OK)
        r = reserve_pairs(nb, pairs);
    if (r == BDL_OK)
        r = reserve_wall_pairs(nb, wall_pairs);
    return r;
}

/// Offsets start[0..n] of lists holding `count` entries: from 0, never decreasing, to count.
static int check_offsets(const int32_t *start, long n, long count, const char *what, char *why,
                         size_t len)
{
    if (start[0] != 0) {
        snprintf(why, len, "the %s of particle 0 start at %d, not 0", what, (int)start[0]);
        return 0;
    }
    for (long i = 0; i < n; ++i)
        if (start[i + 1] < start[i]) {
            snprintf(why, len, "the %s of particle %ld end at %d, before they start (%d)", what, i,
                     (int)start[i + 1], (int)start[i]);
            return 0;
        }
    if (start[n] != count) {
        snprintf(why, len, "the %s of %ld particles end at %d, but %ld are stored", what, n,
                 (int)start[n], count);
        return 0;
    }
    return 1;
}

static int check_pairs(const bdl_neighbor *nb, long n, char *why, size_t len)
{
    for (long i = 0; i < n; ++i)
        for (int32_t k = nb->start[i]; k < nb->start[i + 1]; ++k) {
            const int32_t j = nb->partner[k];
            if (j < 0 || j >= n) {
                snprintf(why, len, "pair %d refers to particle %d of %ld", (int)k, (int)j, n);
                return 0;
            }
            if (j <= i) {
                snprintf(why, len,
                         "pair %d of particle %ld refers to particle %d (a pair is listed with "
                         "its lower particle, for the higher one)",
                         (int)k, i, (int)j);
                return 0;
            }
            if (nb->touching[k] > 1 || (nb->history && !bdl_v3_isfinite(nb->history[k])) ||
                (nb->spring_work && !isfinite(nb->spring_work[k]))) {
                snprintf(why, len,
                         "pair %d has a contact flag of %d or a tangential spring that "
                         "is not finite (its displacement or its stored work)",
                         (int)k, (int)nb->touching[k]);
                return 0;
            }
        }
    return 1;
}

int bdl_neighbor_check(const bdl_neighbor *nb, long n, long prims, char *why, size_t len)
{
    if (!check_offsets(nb->start, n, nb->pair_count, "pairs", why, len) ||
        !check_pairs(nb, n, why, len) ||
        !check_offsets(nb->wall_start, n, nb->wall_pair_count, "wall contacts", why, len))
        return 0;
    for (long k = 0; k < nb->wall_pair_count; ++k) {
        if (nb->wall_prim[k] < 0 || nb->wall_prim[k] >= prims) {
            snprintf(why, len, "wall contact %ld refers to wall surface %d of %ld", k,
                     (int)nb->wall_prim[k], prims);
            return 0;
        }
        if (nb->wall_touching[k] > 1 || !bdl_v3_isfinite(nb->wall_history[k]) ||
            !bdl_v3_isfinite(nb->wall_force[k]) ||
            (nb->wall_spring_work && !isfinite(nb->wall_spring_work[k]))) {
            snprintf(why, len,
                     "wall contact %ld has a contact flag of %d or a spring or force "
                     "that is not finite",
                     k, (int)nb->wall_touching[k]);
            return 0;
        }
    }
    if (!isfinite(nb->shear_travel_at_build)) {
        snprintf(why, len, "the images' slide at the last list build is not finite");
        return 0;
    }
    for (int w = 0; w < BDL_MAX_WALLS; ++w)
        if (!bdl_v3_isfinite(nb->wall_offset_at_build[w]) ||
            !isfinite(nb->wall_angle_at_build[w])) {
            snprintf(why, len,
                     "the offset or angle of wall %d at the last list build is not finite", w);
            return 0;
        }
    return 1;
}
