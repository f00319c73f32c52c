// bedlam — kernel deposition and interpolation, semi-implicit drag exchange.
#include "core/parallel.h"
#include "couple/coupling_internal.h"

#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/memory.h"
#include "core/vec3.h"

bdl_coupling_def bdl_default_coupling_def(const bdl_grid *grid)
{
    const double h = fmax(fmax(grid->h[0], grid->h[1]), grid->h[2]);
    return (bdl_coupling_def){.drag = BDL_DRAG_GIDASPOW,
                              .drag_params = bdl_drag_default_params(),
                              .kernel_width = 1.5 * h,
                              .max_solids = 0.7};
}

/// The most points along an axis that carry weight at a half-width of `reach` points: those
/// closer than the half-width, floor(2 reach) + 1 of them, or 2 reach when that is a whole number
/// and the weight 1 - |m - u| / reach rounds to zero at |m - u| = reach (as at one point: the
/// parcels' trilinear kernel, 2); at most BDL_KERNEL_MAX.
static int most_points(double reach)
{
    const double two = 2.0 * reach;
    const int whole = two == floor(two) && reach * (1.0 / reach) >= 1.0;
    const int most = (int)floor(two) + (whole ? 0 : 1);
    return most < BDL_KERNEL_MAX ? most : BDL_KERNEL_MAX;
}

bdl_result bdl_coupling_init(bdl_coupling *c, const bdl_coupling_def *def, const bdl_gas *gas)
{
    *c = (bdl_coupling){0};
    c->def = *def;
    c->parallel_min = BDL_COUPLING_PARALLEL_MIN;
    for (int a = 0; a < 3; ++a) {
        double h = gas->grid.h[a];
        c->width[a] = fmin(fmax(def->kernel_width, h), 4.0 * h);
        c->inv_h[a] = 1.0 / h;
        c->reach[a] = c->width[a] / h;
        c->inv_reach[a] = 1.0 / c->reach[a];
        // An axis one cell across, with no outlet on it (through which a face can still carry
        // weight), has one cell, and either no momentum face or (periodic) one: one point.
        const int flat =
            gas->grid.n[a] == 1 &&
            (gas->grid.periodic[a] || (gas->def.side[2 * a].type != BDL_SIDE_OUTLET &&
                                       gas->def.side[2 * a + 1].type != BDL_SIDE_OUTLET));
        c->points[a] = flat ? 1 : most_points(c->reach[a]);
        c->kmax = c->points[a] > c->kmax ? c->points[a] : c->kmax;
        if (!(c->grad[a] = bdl_grid_alloc(&gas->grid))) {
            bdl_coupling_free(c);
            return BDL_ERR_NOMEM;
        }
    }
    for (int f = 0; f < 7 && def->mean_drag; ++f)
        if (!(c->mean[f] = bdl_grid_alloc(&gas->grid))) {
            bdl_coupling_free(c);
            return BDL_ERR_NOMEM;
        }
    const int *n = c->points;
    c->shape = n[0] == 2 && n[1] == 2 && n[2] == 2   ? BDL_KERNEL_TRILINEAR
               : n[0] == 2 && n[1] == 1 && n[2] == 2 ? BDL_KERNEL_FLAT_Y
                                                     : BDL_KERNEL_GENERAL;
    return BDL_OK;
}

void bdl_coupling_free(bdl_coupling *c)
{
    free(c->first);
    free(c->offset);
    free(c->lo);
    free(c->hi);
    for (int a = 0; a < 3; ++a)
        free(c->grad[a]);
    for (int f = 0; f < 7; ++f)
        free(c->mean[f]);
    free(c->target);
    free(c->mean_vel);
    free(c->weight);
    free(c->factor);
    free(c->accel);
    free(c->drag);
    free(c->pressure);
    free(c->listed);
    free(c->order_key);
    free(c->order_perm);
    free(c->order_scratch);
    free(c->order_start);
    free(c->pool);
    free(c->chunk_lo);
    free(c->chunk_hi);
    free(c->chunk_base);
    *c = (bdl_coupling){0};
}

/// Room for n particles with `points` kernel points.
static bdl_result reserve(bdl_coupling *c, long n, long points)
{
    if (points > c->point_capacity) {
        const long cap = points + points / 2 + 16;
        if (!bdl_grow((void **)&c->offset, cap, 6 * (size_t)c->kmax * sizeof(int)) ||
            !bdl_grow((void **)&c->lo, cap, sizeof(int)) ||
            !bdl_grow((void **)&c->hi, cap, sizeof(int)) ||
            !bdl_grow((void **)&c->weight, cap, 6 * (size_t)c->kmax * sizeof(double)))
            return BDL_ERR_NOMEM;
        c->point_capacity = cap;
    }
    if (n <= c->capacity && c->first)
        return BDL_OK;
    const long cap = n + n / 2 + 16;
    if (!bdl_grow((void **)&c->first, cap + 1, sizeof(long)) ||
        !bdl_grow((void **)&c->factor, cap, sizeof(double)) ||
        !bdl_grow((void **)&c->accel, cap, sizeof(bdl_vec3)) ||
        !bdl_grow((void **)&c->drag, cap, sizeof(bdl_vec3)) ||
        !bdl_grow((void **)&c->pressure, cap, sizeof(bdl_vec3)) ||
        (c->def.mean_drag && (!bdl_grow((void **)&c->target, cap, sizeof(bdl_vec3)) ||
                              !bdl_grow((void **)&c->mean_vel, cap, sizeof(bdl_vec3)))) ||
        !bdl_grow((void **)&c->listed, cap, sizeof(int32_t)))
        return BDL_ERR_NOMEM;
    c->capacity = cap;
    return BDL_OK;
}

/// Normalised to sum 1: the count weights w[] that sum to `sum`. Inside the grid the tent's
/// weights often sum to 1 exactly: no division then.
static void normalise(double *w, int count, double sum)
{
    const double norm = sum == 1.0 ? 1.0 : 1.0 / sum;
    for (int k = 0; k < count; ++k)
        w[k] *= norm;
}

/// The points m = lo..hi (all of them on a periodic axis, unwrapped) within the half-width of u,
/// of positive weight 1 - |m - u| / reach, in order into pts[], their weights normalised into
/// w[]; returns how many (at most c->points[a]).
static int tent_points(const bdl_coupling *c, const bdl_grid *g, int a, double u, int lo, int hi,
                       int *pts, double *w)
{
    const double reach = c->reach[a], inv_reach = c->inv_reach[a];
    // ceil and floor by truncation: libm's are calls here, and this runs 6 times per point.
    double lo_x = u - reach, hi_x = u + reach;
    int from = (int)lo_x, to = (int)hi_x;
    from += (double)from < lo_x;
    to -= (double)to > hi_x;
    if (!g->periodic[a]) {
        from = from < lo ? lo : from;
        to = to > hi ? hi : to;
    }
    if (to - from + 1 > BDL_KERNEL_MAX)
        to = from + BDL_KERNEL_MAX - 1;
    int count = 0;
    double sum = 0.0;
    for (int m = from; m <= to; ++m) {
        const double wm = 1.0 - fabs(m - u) * inv_reach;
        BDL_ASSERT(!(wm > 0.0) || count < c->points[a]); // most_points: no more carry weight
        if (wm > 0.0 && count < c->points[a])
            pts[count] = m, w[count++] = wm, sum += wm;
    }
    normalise(w, count, sum);
    return count;
}

/// tent_points at a half-width of one point (the parcels' trilinear kernel): only the two points
/// around u can carry weight, and in tent_points they are the ones that do; the same weights,
/// normalised before they are stored (reading back what was just stored stalls).
static int tent_one(const bdl_grid *g, int a, double u, int lo, int hi, int *pts, double *w)
{
    const int periodic = g->periodic[a];
    int m0 = (int)u;
    m0 -= (double)m0 > u; // floor
    const double w0 = 1.0 - fabs(m0 - u), w1 = 1.0 - fabs(m0 + 1 - u);
    const int in0 = w0 > 0.0 && (periodic || (m0 >= lo && m0 <= hi));
    const int in1 = w1 > 0.0 && (periodic || (m0 + 1 >= lo && m0 + 1 <= hi));
    const double first = in0 ? w0 : w1, sum = in0 && in1 ? w0 + w1 : first;
    const double norm = sum == 1.0 ? 1.0 : 1.0 / sum;
    pts[0] = in0 ? m0 : m0 + 1, w[0] = first * norm;
    pts[1] = m0 + 1, w[1] = w1 * norm; // the padding replaces it when only one point counts
    return in0 + in1;
}

/// Weights of one particle along axis a over the points m = lo..hi at (m + offset) h (cell
/// centres: offset 1/2; faces: 0) within the half-width, normalised to sum 1. On a periodic axis
/// lo..hi is the whole period and the points wrap. Only the points of positive weight are kept,
/// into pts[] and w[], and the rest of the axis's c->points[a] entries are padded with weight 0 on
/// the last point kept (so every kernel loops over the same number of points, and the padding
/// adds nothing: a sum that starts at +0 is never -0, so adding +-0 leaves its bits). Returns
/// how many points carry weight; 0: none at all (the padding then sits on point lo).
static int axis_weights(const bdl_coupling *c, const bdl_grid *g, int a, double offset, int lo,
                        int hi, double x, int *pts, double *w)
{
    const int n = g->n[a], most = c->points[a];
    int count = 0;
    if (hi == lo) { // a single point takes it all (the tent's weight, normalised, or the nearest)
        pts[0] = lo, w[0] = 1.0, count = 1;
    } else if (hi >= lo) {
        double u = (x - g->origin[a]) * c->inv_h[a] - offset; // position in point units
        // A runaway particle (or a NaN) is held far outside the grid, where it stays outside, so
        // that the conversions to int are defined.
        const double far = 4.0 * (n + BDL_KERNEL_MAX);
        u = !(u > -far) ? -far : u < far ? u : far;
        count = c->reach[a] == 1.0 ? tent_one(g, a, u, lo, hi, pts, w)
                                   : tent_points(c, g, a, u, lo, hi, pts, w);
        if (count == 0) { // outside the domain: the nearest point takes it all
            const int m = (int)floor(u + 0.5);
            pts[0] = m < lo ? lo : m > hi ? hi : m, w[0] = 1.0, count = 1;
        }
    }
    for (int k = count; k < most; ++k)
        pts[k] = count > 0 ? pts[count - 1] : lo, w[k] = 0.0;
    return count;
}

/// The faces normal to axis a that carry a momentum equation: all of a period, or the interior
/// ones plus those on an outlet.
static void momentum_faces(const bdl_gas *gas, int a, int *lo, int *hi)
{
    const int n = gas->grid.n[a];
    if (gas->grid.periodic[a]) {
        *lo = 0, *hi = n - 1;
        return;
    }
    *lo = gas->def.side[2 * a].type == BDL_SIDE_OUTLET ? 0 : 1;
    *hi = gas->def.side[2 * a + 1].type == BDL_SIDE_OUTLET ? n : n - 1;
}

static int wrap(int m, int n)
{
    m %= n;
    return m < 0 ? m + n : m;
}

/// Kernel points of particle i: a rod's satellites, else its centre.
static int point_count(const bdl_particles *p, long i)
{
    return p->rods && p->half_length[i] > 0.0 ? BDL_ROD_SATELLITES : 1;
}

bdl_vec3 bdl_coupling_point(const bdl_particles *p, long i, int k)
{
    if (point_count(p, i) == 1)
        return p->pos[i];
    // Four stations at -3/4, -1/4, 1/4, 3/4 of the half length tip to tip, h + r; at each, four
    // points at 1/sqrt(2) of the local radius (the circle that halves the cross-section's area),
    // in the body's x and y directions, so that they turn with the rod.
    const double h = p->half_length[i], r = p->radius[i];
    const double z = (0.5 * (k / 4) - 0.75) * (h + r), beyond = fabs(z) > h ? fabs(z) - h : 0.0;
    const double rho = sqrt(0.5 * (r * r - beyond * beyond));
    const bdl_quat q = p->orient[i];
    const int side = k % 4;
    const bdl_vec3 across =
        bdl_q_rotate(q, side % 2 ? bdl_v3(0.0, 1.0, 0.0) : bdl_v3(1.0, 0.0, 0.0));
    return bdl_v3_madd(bdl_v3_madd(p->pos[i], p->axis[i], z), across, side < 2 ? rho : -rho);
}

/// Kernel weights of point pt at x: the cell centres and the momentum faces along each axis; the
/// lowest and highest padded index it reaches in any slot into c->lo and c->hi (where the
/// deposits in chunks look).
static void locate_point(bdl_coupling *c, const bdl_grid *g, const int flo[3], const int fhi[3],
                         long pt, bdl_vec3 x)
{
    int low = 0, high = 0;
    for (int a = 0; a < 3; ++a) {
        int lowest = INT_MAX, highest = INT_MIN;
        for (int slot = a; slot < 6; slot += 3) { // 0-2: cell centres; 3-5: faces of component a
            const long at = (6 * pt + slot) * c->kmax;
            int pts[BDL_KERNEL_MAX];
            if (slot < 3)
                axis_weights(c, g, a, 0.5, 0, g->n[a] - 1, bdl_v3_comp(x, a), pts, &c->weight[at]);
            else
                axis_weights(c, g, a, 0.0, flo[a], fhi[a], bdl_v3_comp(x, a), pts, &c->weight[at]);
            for (int m = 0; m < c->points[a]; ++m) {
                const int pt_m = g->periodic[a] ? wrap(pts[m], g->n[a]) : pts[m];
                const int off = (pt_m + BDL_GRID_GHOST) * (int)g->stride[a];
                c->offset[at + m] = off;
                lowest = off < lowest ? off : lowest;
                highest = off > highest ? off : highest;
            }
        }
        low += lowest, high += highest;
    }
    c->lo[pt] = low, c->hi[pt] = high;
}

bdl_result bdl_coupling_locate(bdl_coupling *c, const bdl_gas *gas, const bdl_particles *p)
{
    const long count = p->count;
    long points = 0;
    for (long i = 0; i < count; ++i)
        points += point_count(p, i);
    if (reserve(c, count, points) != BDL_OK)
        return BDL_ERR_NOMEM;
    c->first[0] = 0;
    for (long i = 0; i < count; ++i)
        c->first[i + 1] = c->first[i] + point_count(p, i);
    int flo[3], fhi[3];
    for (int a = 0; a < 3; ++a)
        momentum_faces(gas, a, &flo[a], &fhi[a]);
    const bdl_grid *g = &gas->grid;
    BDL_PARALLEL_FOR(
        count >= c->parallel_min, for (long i = 0; i < count; ++i) {
            for (long pt = c->first[i]; pt < c->first[i + 1]; ++pt)
                locate_point(c, g, flo, fhi, pt, bdl_coupling_point(p, i, (int)(pt - c->first[i])));
        });
    return bdl_coupling_plan_chunks(c, count);
}

bdl_result bdl_coupling_relocate(bdl_coupling *c, const bdl_gas *gas, const bdl_particles *p,
                                 const uint8_t *which)
{
    int flo[3], fhi[3];
    for (int a = 0; a < 3; ++a)
        momentum_faces(gas, a, &flo[a], &fhi[a]);
    const bdl_grid *g = &gas->grid;
    long n = 0; // the particles to locate, listed: those that moved may be bunched in space
    for (long i = 0; i < p->count; ++i)
        if (which[i])
            c->listed[n++] = (int32_t)i;
    BDL_PARALLEL_FOR(
        n >= c->parallel_min, for (long k = 0; k < n; ++k) {
            const long i = c->listed[k];
            for (long pt = c->first[i]; pt < c->first[i + 1]; ++pt)
                locate_point(c, g, flo, fhi, pt, bdl_coupling_point(p, i, (int)(pt - c->first[i])));
        });
    return bdl_coupling_plan_chunks(c, p->count);
}

/// Calls body with `idx` (padded index) and `w` (weight) for every point of the separable
/// kernel made of slots sx, sy, sz of kernel point i: kz, ky, kx over nz, ny, nx points.
#define FOR_SLOTS_N(c, i, sx, sy, sz, nx, ny, nz, ...)                                             \
    do {                                                                                           \
        const long at_ = 6 * (i) * (c)->kmax;                                                      \
        const int *ox_ = &(c)->offset[at_ + (sx) * (c)->kmax],                                     \
                  *oy_ = &(c)->offset[at_ + (sy) * (c)->kmax],                                     \
                  *oz_ = &(c)->offset[at_ + (sz) * (c)->kmax];                                     \
        const double *wx_ = &(c)->weight[at_ + (sx) * (c)->kmax],                                  \
                     *wy_ = &(c)->weight[at_ + (sy) * (c)->kmax],                                  \
                     *wz_ = &(c)->weight[at_ + (sz) * (c)->kmax];                                  \
        for (int kz_ = 0; kz_ < (nz); ++kz_)                                                       \
            for (int ky_ = 0; ky_ < (ny); ++ky_) {                                                 \
                const long oyz_ = (long)oz_[kz_] + oy_[ky_];                                       \
                const double wyz_ = wz_[kz_] * wy_[ky_];                                           \
                for (int kx_ = 0; kx_ < (nx); ++kx_) {                                             \
                    const long idx = oyz_ + ox_[kx_];                                              \
                    const double w = wyz_ * wx_[kx_];                                              \
                    __VA_ARGS__;                                                                   \
                }                                                                                  \
            }                                                                                      \
    } while (0)

/// FOR_SLOTS_N over every point of each axis, with the trilinear kernel (two points per axis,
/// the parcels' default, or one across a grid one cell deep) spelt out for the compiler to unroll.
#define FOR_SLOTS(c, i, sx, sy, sz, ...)                                                           \
    do {                                                                                           \
        if ((c)->shape == BDL_KERNEL_FLAT_Y)                                                       \
            FOR_SLOTS_N(c, i, sx, sy, sz, 2, 1, 2, __VA_ARGS__);                                   \
        else if ((c)->shape == BDL_KERNEL_TRILINEAR)                                               \
            FOR_SLOTS_N(c, i, sx, sy, sz, 2, 2, 2, __VA_ARGS__);                                   \
        else                                                                                       \
            FOR_SLOTS_N(c, i, sx, sy, sz, (c)->points[0], (c)->points[1], (c)->points[2],          \
                        __VA_ARGS__);                                                              \
    } while (0)

/// Over the cell centres of kernel point i.
#define FOR_KERNEL(c, i, ...) FOR_SLOTS(c, i, 0, 1, 2, __VA_ARGS__)

/// Over the momentum faces of component a of kernel point i: face weights along a, cell weights
/// across.
#define FOR_FACE_KERNEL(c, i, a, ...)                                                              \
    FOR_SLOTS(c, i, (a) == 0 ? 3 : 0, (a) == 1 ? 4 : 1, (a) == 2 ? 5 : 2, __VA_ARGS__)

static double cell_volume(const bdl_grid *g) { return g->h[0] * g->h[1] * g->h[2]; }

/// Density of particle i from its mass and volume [kg/m^3].
static double particle_density(const bdl_particles *p, long i)
{
    return 1.0 / (p->inv_mass[i] * bdl_particle_solids_volume(p, i));
}

/// The share of each of particle i's kernel points: 1 / their count.
static double point_share(const bdl_coupling *c, long i)
{
    return 1.0 / (double)(c->first[i + 1] - c->first[i]);
}

/// The solids volume of particle i on the cell centres.
static void deposit_volume(const bdl_coupling *c, const void *ctx, long i, long shift,
                           double *const *out)
{
    const bdl_particles *p = ctx;
    const double v = bdl_particle_solids_volume(p, i) * point_share(c, i);
    for (long pt = c->first[i]; pt < c->first[i + 1]; ++pt)
        FOR_KERNEL(c, pt, out[0][idx - shift] += w * v);
}

void bdl_coupling_voidage(const bdl_coupling *c, bdl_gas *gas, const bdl_particles *p)
{
    const bdl_grid *g = &gas->grid;
    const double vc = cell_volume(g);
    double *solid = gas->rhs; // scratch: the gas step overwrites it
    bdl_coupling_deposit(c, g, p->count, 1, &solid, deposit_volume, p);
    const double lowest = 1.0 - c->def.max_solids;
    for (int k = 0; k < g->n[2]; ++k)
        for (int j = 0; j < g->n[1]; ++j)
            for (int i = 0; i < g->n[0]; ++i) {
                long idx = bdl_grid_index(g, i, j, k);
                gas->eps[idx] = fmax(1.0 - solid[idx] / vc, lowest);
            }
}

double bdl_coupling_interpolate(const bdl_coupling *c, long i, const double *f)
{
    const double share = point_share(c, i);
    double total = 0.0;
    for (long pt = c->first[i]; pt < c->first[i + 1]; ++pt) {
        double sum = 0.0;
        FOR_KERNEL(c, pt, sum += w * f[idx]);
        total += share * sum;
    }
    return total;
}

int bdl_coupling_touches(const bdl_coupling *c, long i, const double *f)
{
    // A padded entry repeats a point of positive weight along its axis, so every combination of
    // entries is a cell of positive weight: the offsets alone answer.
    const int *n = c->points;
    int any = 0;
    for (long pt = c->first[i]; pt < c->first[i + 1]; ++pt) {
        const int *o = &c->offset[6 * pt * c->kmax];
        const int *ox = o, *oy = o + c->kmax, *oz = o + 2 * c->kmax;
        for (int kz = 0; kz < n[2]; ++kz)
            for (int ky = 0; ky < n[1]; ++ky)
                for (int kx = 0; kx < n[0]; ++kx)
                    any |= f[(long)oz[kz] + oy[ky] + ox[kx]] > 0.0;
    }
    return any;
}

int bdl_coupling_gains(const bdl_coupling *c, const bdl_gas *gas, long i, bdl_vec3 from,
                       const double *f)
{
    BDL_ASSERT(c->first[i + 1] - c->first[i] == 1); // one kernel point: a sphere or a parcel
    const bdl_grid *g = &gas->grid;
    // The cell kernel at `from`, per axis: padded offsets and weights.
    int off[3][BDL_KERNEL_MAX];
    double w0[3][BDL_KERNEL_MAX];
    for (int a = 0; a < 3; ++a) {
        int pts[BDL_KERNEL_MAX];
        axis_weights(c, g, a, 0.5, 0, g->n[a] - 1, bdl_v3_comp(from, a), pts, w0[a]);
        for (int m = 0; m < c->points[a]; ++m)
            off[a][m] = ((g->periodic[a] ? wrap(pts[m], g->n[a]) : pts[m]) + BDL_GRID_GHOST) *
                        (int)g->stride[a];
    }
    const int *n = c->points;
    int gains = 0;
    const long pt = c->first[i];
    FOR_KERNEL(c, pt, {
        if (!gains && w > 0.0 && f[idx] > 0.0) {
            double before = 0.0; // padded entries repeat a point with weight 0: sum them all
            for (int kz = 0; kz < n[2]; ++kz)
                for (int ky = 0; ky < n[1]; ++ky)
                    for (int kx = 0; kx < n[0]; ++kx)
                        if ((long)off[2][kz] + off[1][ky] + off[0][kx] == idx)
                            before += w0[2][kz] * w0[1][ky] * w0[0][kx];
            gains = w > before;
        }
    });
    return gains;
}

/// n face fields at particle i (n <= 2), the mean over its kernel points: component a of f[k]
/// from f[k][a] on the momentum faces of component a, into u[k][a]. One pass over the weights;
/// each sum in the order of one field alone.
static inline void face_averages(const bdl_coupling *c, long i, int n, double *const *const f[],
                                 double u[][3])
{
    const double share = point_share(c, i);
    for (int k = 0; k < n; ++k)
        u[k][0] = u[k][1] = u[k][2] = 0.0;
    for (long pt = c->first[i]; pt < c->first[i + 1]; ++pt) {
        double sum[2][3] = {{0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}};
        FOR_FACE_KERNEL(c, pt, 0, for (int k = 0; k < n; ++k) sum[k][0] += w * f[k][0][idx]);
        FOR_FACE_KERNEL(c, pt, 1, for (int k = 0; k < n; ++k) sum[k][1] += w * f[k][1][idx]);
        FOR_FACE_KERNEL(c, pt, 2, for (int k = 0; k < n; ++k) sum[k][2] += w * f[k][2][idx]);
        for (int k = 0; k < n; ++k)
            for (int a = 0; a < 3; ++a)
                u[k][a] += share * sum[k][a];
    }
}

/// A face field at particle i: face_averages of one field.
static void face_average(const bdl_coupling *c, long i, double *const f[3], double u[3])
{
    double *const *const fields[1] = {f};
    double out[1][3];
    face_averages(c, i, 1, fields, out);
    u[0] = out[0][0], u[1] = out[0][1], u[2] = out[0][2];
}

/// Gas velocity at particle i.
static void gas_velocity_at(const bdl_coupling *c, const bdl_gas *gas, long i, double u[3])
{
    face_average(c, i, gas->u, u);
}

bdl_vec3 bdl_coupling_face_average(const bdl_coupling *c, long i, double *const f[3])
{
    double u[3];
    face_average(c, i, f, u);
    return bdl_v3(u[0], u[1], u[2]);
}

void bdl_coupling_face_average2(const bdl_coupling *c, long i, double *const f[3],
                                double *const g[3], bdl_vec3 *at_f, bdl_vec3 *at_g)
{
    double *const *const fields[2] = {f, g};
    double out[2][3];
    face_averages(c, i, 2, fields, out);
    *at_f = bdl_v3(out[0][0], out[0][1], out[0][2]);
    *at_g = bdl_v3(out[1][0], out[1][1], out[1][2]);
}

/// The drag law's K = beta / phi for particle i at voidage eps, gas velocity u and slip: a sphere
/// by its diameter, a rod by its shape and the angle between its axis and the slip.
static double drag_per_volume(const bdl_coupling *c, const bdl_particles *p, long i, double eps,
                              const double u[3], double slip, double rho, double mu)
{
    const double d = 2.0 * p->radius[i];
    if (point_count(p, i) == 1)
        return bdl_drag_per_volume(c->def.drag, &c->def.drag_params, eps, d, slip, rho, mu);
    const bdl_vec3 s = bdl_v3_sub(bdl_v3(u[0], u[1], u[2]), p->vel[i]);
    const bdl_drag_shape shape = {.diameter = d,
                                  .shaft = 2.0 * p->half_length[i],
                                  .cos_theta = slip > 0.0 ? bdl_v3_dot(s, p->axis[i]) / slip : 1.0};
    return bdl_drag_shape_per_volume(c->def.drag, &c->def.drag_params, eps, &shape, slip, rho, mu);
}

bdl_vec3 bdl_coupling_gas_velocity(const bdl_coupling *c, const bdl_gas *gas, long i)
{
    double u[3];
    gas_velocity_at(c, gas, i, u);
    return bdl_v3(u[0], u[1], u[2]);
}

/// What the drag set-up deposits (deposit_drag): the drag and, for parcels, the pressure share
/// and the volume flux still to come.
typedef struct drag_deposit {
    const bdl_particles *p;
    const bdl_vec3 *accel, *moved;
    const bdl_vec3 *mean; ///< the mean targets (def.mean_drag), else NULL
    double dt, cell_volume;
    int share; ///< deposit the pressure share's and the flux's sums too
} drag_deposit;

/// The velocity the drag pulls the gas towards at particle i: v + dt A (with mean_drag their
/// mean around it).
static void drag_target(const drag_deposit *d, long i, double target[3])
{
    if (d->mean) {
        for (int a = 0; a < 3; ++a)
            target[a] = bdl_v3_comp(d->mean[i], a);
        return;
    }
    for (int a = 0; a < 3; ++a)
        target[a] =
            bdl_v3_comp(d->p->vel[i], a) + d->dt * (d->accel ? bdl_v3_comp(d->accel[i], a) : 0.0);
}

/// Whether the drag takes the solids' mean velocity: def.mean_drag, and not for parcels (whose
/// drag is implicit in their own velocity; the scene refuses the pair).
static int uses_mean(const bdl_coupling *c, const bdl_gas *gas)
{
    return c->def.mean_drag && !gas->def.pressure_share;
}

/// Particle i's solids volume, and that times its v and its A, on the cell centres (mean_drag).
static void deposit_motion(const bdl_coupling *c, const void *ctx, long i, long shift,
                           double *const *out)
{
    const drag_deposit *d = ctx;
    const double v = bdl_particle_solids_volume(d->p, i) * point_share(c, i);
    double t[6];
    for (int a = 0; a < 3; ++a) {
        t[a] = v * bdl_v3_comp(d->p->vel[i], a);
        t[3 + a] = d->accel ? v * bdl_v3_comp(d->accel[i], a) : 0.0;
    }
    for (long pt = c->first[i]; pt < c->first[i + 1]; ++pt)
        FOR_KERNEL(c, pt, {
            out[0][idx - shift] += w * v;
            for (int f = 0; f < 6; ++f)
                out[1 + f][idx - shift] += w * t[f];
        });
}

/// The cells' means of v and A weighted by solids volume (into c->mean[1..6]), and at every
/// particle the mean v read back into c->mean_vel and the mean drag target v + dt A into
/// c->target (a cell a particle's kernel reaches holds some of its volume: no empty cell is
/// read).
static void mean_targets(bdl_coupling *c, const bdl_grid *g, const drag_deposit *d)
{
    bdl_coupling_deposit(c, g, d->p->count, 7, c->mean, deposit_motion, d);
    for (long idx = 0; idx < g->size; ++idx)
        for (int f = 1; f < 7; ++f)
            c->mean[f][idx] = c->mean[0][idx] > 0.0 ? c->mean[f][idx] / c->mean[0][idx] : 0.0;
    BDL_PARALLEL_FOR(
        d->p->count >= c->parallel_min, for (long i = 0; i < d->p->count; ++i) {
            double v[3], t[3];
            for (int a = 0; a < 3; ++a) {
                v[a] = bdl_coupling_interpolate(c, i, c->mean[1 + a]);
                t[a] = v[a] + d->dt * bdl_coupling_interpolate(c, i, c->mean[4 + a]);
            }
            c->mean_vel[i] = bdl_v3(v[0], v[1], v[2]);
            c->target[i] = bdl_v3(t[0], t[1], t[2]);
        });
}

/// Adds f[k] times the flux weights of kernel point pt across the faces normal to axis a to
/// into[k] (k < 3). The weights are those whose divergence is the change of the point's cell
/// weights as it moves along a: with the trilinear kernel (a tent of one cell) the face between
/// the two cell centres that bracket the point along a takes it whole (none when one cell takes
/// all of the point's weight along a, beside a wall), times the cell weights across a — the
/// charge-conserving deposit of particle-in-cell codes (Villasenor & Buneman 1992). The gas's
/// continuity then sees exactly the volume the parcels' cell deposit moves (to first order in
/// the move); the face kernel's weights would see a parcel at a cell centre move nothing. Wider
/// tents take the face kernel's weights.
static void deposit_flux(const bdl_coupling *c, long pt, int a, const double f[3],
                         double *const into[3])
{
    if (c->reach[a] != 1.0) {
        FOR_FACE_KERNEL(c, pt, a, {
            into[0][idx] += w * f[0];
            into[1][idx] += w * f[1];
            into[2][idx] += w * f[2];
        });
        return;
    }
    const long at = 6 * pt * c->kmax;
    const int *off = &c->offset[at];
    const double *wt = &c->weight[at];
    const long along = a * c->kmax;
    if (c->points[a] < 2 || !(wt[along] > 0.0 && wt[along + 1] > 0.0))
        return;
    const int b = (a + 1) % 3, d = (a + 2) % 3;
    const long ab = b * c->kmax, ad = d * c->kmax;
    for (int kd = 0; kd < c->points[d]; ++kd)
        for (int kb = 0; kb < c->points[b]; ++kb) {
            const long idx = (long)off[along + 1] + off[ab + kb] + off[ad + kd];
            const double w = wt[ab + kb] * wt[ad + kd];
            into[0][idx] += w * f[0];
            into[1][idx] += w * f[1];
            into[2][idx] += w * f[2];
        }
}

/// beta = sum W a / V_cell into out[0..2], (beta v) = sum W a (v + dt A) / V_cell into out[3..5],
/// and with d->share C_pr's sum W V / (1 + D dt) / V_cell into out[6..8] (V / (1 + D dt) =
/// V (1 - a dt / m)) and the volume flux still to come, sum W V (v^{n+1} - v - m) / V_cell with
/// v^{n+1} = ((v + dt A) + D dt u - dt grad p / rho_p) / (1 + D dt) (m: d->moved), as its
/// factors of u (out[9..11]), of -grad p (out[12..14]) and the rest (out[15..17]).
static void deposit_drag(const bdl_coupling *c, const void *ctx, long i, long shift,
                         double *const *out)
{
    const drag_deposit *d = ctx;
    const double share = point_share(c, i);
    const double f = c->factor[i] / d->cell_volume * share;
    double target[3];
    drag_target(d, i, target);
    if (!d->share) {
        for (long pt = c->first[i]; pt < c->first[i + 1]; ++pt)
            for (int a = 0; a < 3; ++a)
                FOR_FACE_KERNEL(c, pt, a, {
                    out[a][idx - shift] += w * f;
                    out[3 + a][idx - shift] += w * f * target[a];
                });
        return;
    }
    const double whole = bdl_particle_solids_volume(d->p, i) / d->cell_volume * share;
    const double s = whole * (1.0 - c->factor[i] * d->dt * d->p->inv_mass[i]);
    const double by_p = s * d->dt / particle_density(d->p, i);
    double rest[3];
    for (int a = 0; a < 3; ++a)
        rest[a] = s * target[a] - whole * (bdl_v3_comp(d->p->vel[i], a) +
                                           (d->moved ? bdl_v3_comp(d->moved[i], a) : 0.0));
    for (long pt = c->first[i]; pt < c->first[i + 1]; ++pt)
        for (int a = 0; a < 3; ++a) {
            FOR_FACE_KERNEL(c, pt, a, {
                out[a][idx - shift] += w * f;
                out[3 + a][idx - shift] += w * f * target[a];
                out[6 + a][idx - shift] += w * s;
            });
            const double flux[3] = {whole - s, by_p, rest[a]};
            double *const into[3] = {out[9 + a] - shift, out[12 + a] - shift, out[15 + a] - shift};
            deposit_flux(c, pt, a, flux, into);
        }
}

void bdl_coupling_drag_setup(bdl_coupling *c, bdl_gas *gas, const bdl_particles *p,
                             const bdl_vec3 *accel, const bdl_vec3 *moved, double dt)
{
    const bdl_grid *g = &gas->grid;
    const double rho = gas->def.density, mu = gas->def.viscosity, vc = cell_volume(g);
    const int mean = uses_mean(c, gas);
    const drag_deposit ctx = {
        p, accel, moved, mean ? c->target : NULL, dt, vc, gas->def.pressure_share};
    if (mean)
        mean_targets(c, g, &ctx);
    BDL_PARALLEL_FOR(
        p->count >= c->parallel_min, for (long i = 0; i < p->count; ++i) {
            double u[3];
            gas_velocity_at(c, gas, i, u);
            const bdl_vec3 vi = mean ? c->mean_vel[i] : p->vel[i];
            const double v[3] = {vi.x, vi.y, vi.z};
            double slip = sqrt((u[0] - v[0]) * (u[0] - v[0]) + (u[1] - v[1]) * (u[1] - v[1]) +
                               (u[2] - v[2]) * (u[2] - v[2]));
            double eps = bdl_coupling_interpolate(c, i, gas->eps);
            double K = drag_per_volume(c, p, i, eps, u, slip, rho, mu);
            const double density = particle_density(p, i);
            double D = K / density, m = density * bdl_particle_solids_volume(p, i);
            c->factor[i] = m * D / (1.0 + D * dt);
        });
    double *const out[BDL_COUPLING_FIELDS] = {
        gas->beta[0],   gas->beta[1],   gas->beta[2],   gas->bv[0],     gas->bv[1],
        gas->bv[2],     gas->share[0],  gas->share[1],  gas->share[2],  gas->flux_u[0],
        gas->flux_u[1], gas->flux_u[2], gas->flux_p[0], gas->flux_p[1], gas->flux_p[2],
        gas->flux_0[0], gas->flux_0[1], gas->flux_0[2]};
    bdl_coupling_deposit(c, g, p->count, ctx.share ? BDL_COUPLING_FIELDS : 6, out, deposit_drag,
                         &ctx);
    if (!ctx.share)
        return;
    for (int a = 0; a < 3; ++a)
        for (long idx = 0; idx < g->size; ++idx)
            gas->share[a][idx] = 1.0 - gas->share[a][idx];
}

/// dp/dx_a at the centre of the cell at idx (axis coordinate m), as the particles there feel it:
/// the hydrostatic part rho g_a whole, and the rest (the dynamic pressure p - rho g.x) as the mean
/// of its gradients on the cell's two faces. A face with a momentum equation carries its
/// difference (p_hi - p_lo) / h; at an outlet the ghost value 2 p_out - p stands beyond the face;
/// a wall or inlet face, where the gas has no momentum equation, carries none. The particles then
/// take from the pressure exactly what the gas leaves: summed over the domain, the particles'
/// share (1 - eps_f) and the gas's eps_f of every interior or periodic face make the mixture's
/// pressure force telescope to the pressures of the end layers, as the drag's two sides cancel.
/// (Particles in an outlet's layer feel half the outlet face's difference, the part inside the
/// domain, while the gas's momentum cell of that face reaches half a cell beyond it.) A one-sided
/// difference at the inlet layer gave the particles below its centre a force the measured
/// pressure drop did not carry: 1.4 % of a slugging bed's weight.
static double pressure_gradient(const bdl_gas *gas, int a, int m, long idx)
{
    const bdl_grid *g = &gas->grid;
    const int n = g->n[a];
    const long s = g->stride[a];
    const double h = g->h[a], *p = gas->p, hydro = gas->def.density * gas->def.gravity[a];
    if (g->periodic[a] || (m > 0 && m < n - 1))
        return (p[idx + s] - p[idx - s]) / (2.0 * h);
    const bdl_gas_side *lo = &gas->def.side[2 * a], *hi = &gas->def.side[2 * a + 1];
    double below, above; // dynamic pressure differences across the lower and upper face
    if (m > 0)
        below = p[idx] - p[idx - s] - hydro * h;
    else
        below = lo->type == BDL_SIDE_OUTLET ? 2.0 * (p[idx] - lo->pressure) - hydro * h : 0.0;
    if (m < n - 1)
        above = p[idx + s] - p[idx] - hydro * h;
    else
        above = hi->type == BDL_SIDE_OUTLET ? 2.0 * (hi->pressure - p[idx]) - hydro * h : 0.0;
    return hydro + (below + above) / (2.0 * h);
}

void bdl_coupling_forces(const bdl_coupling *c, const bdl_gas *gas, const bdl_particles *p,
                         const bdl_vec3 *accel, double dt, bdl_vec3 *drag, bdl_vec3 *pressure)
{
    const bdl_grid *g = &gas->grid;
    const int mean = uses_mean(c, gas); // targets from the set-up
    if (pressure) // the cell-centred pressure gradient, into the coupling's scratch fields
        for (int k = 0; k < g->n[2]; ++k)
            for (int j = 0; j < g->n[1]; ++j)
                for (int i = 0; i < g->n[0]; ++i) {
                    const long idx = bdl_grid_index(g, i, j, k);
                    const int m[3] = {i, j, k};
                    for (int a = 0; a < 3; ++a)
                        c->grad[a][idx] = pressure_gradient(gas, a, m[a], idx);
                }
    BDL_PARALLEL_FOR(
        p->count >= c->parallel_min, for (long i = 0; i < p->count; ++i) {
            if (drag) {
                double u[3], f[3];
                gas_velocity_at(c, gas, i, u);
                for (int a = 0; a < 3; ++a)
                    f[a] = mean ? c->factor[i] * (u[a] - bdl_v3_comp(c->target[i], a))
                                : c->factor[i] * (u[a] - bdl_v3_comp(p->vel[i], a) -
                                                  dt * (accel ? bdl_v3_comp(accel[i], a) : 0.0));
                drag[i] = (bdl_vec3){f[0], f[1], f[2]};
            }
            if (pressure) {
                const double share = point_share(c, i);
                double grad[3] = {0, 0, 0};
                for (long pt = c->first[i]; pt < c->first[i + 1]; ++pt) {
                    double at[3] = {0, 0, 0};
                    FOR_KERNEL(c, pt, {
                        at[0] += w * c->grad[0][idx];
                        at[1] += w * c->grad[1][idx];
                        at[2] += w * c->grad[2][idx];
                    });
                    for (int a = 0; a < 3; ++a)
                        grad[a] += share * at[a];
                }
                const double v = bdl_particle_solids_volume(p, i);
                pressure[i] = (bdl_vec3){-v * grad[0], -v * grad[1], -v * grad[2]};
            }
        });
}

void bdl_coupling_gas_drag(const bdl_gas *gas, double *const u[3], double total[3])
{
    const bdl_grid *g = &gas->grid;
    const double vc = cell_volume(g);
    for (int a = 0; a < 3; ++a) {
        int lo, hi;
        momentum_faces(gas, a, &lo, &hi);
        double sum = 0.0;
        for (int k = 0; k < g->n[2] + (a == 2); ++k)
            for (int j = 0; j < g->n[1] + (a == 1); ++j)
                for (int i = 0; i < g->n[0] + (a == 0); ++i) {
                    int m = a == 0 ? i : a == 1 ? j : k;
                    if (m < lo || m > hi)
                        continue;
                    long idx = bdl_grid_index(g, i, j, k);
                    sum += (gas->bv[a][idx] - gas->beta[a][idx] * u[a][idx]) * vc;
                }
        total[a] = sum;
    }
}
