#include "dist/decomp.h"

#include <math.h>
#include <stdlib.h>

int bdl_decomp_fits(const int dims[3], const double lo[3], const double hi[3], double margin)
{
    for (int a = 0; a < 3; ++a)
        if (dims[a] < 1 || (dims[a] > 1 && (hi[a] - lo[a]) / dims[a] < 2.0 * margin))
            return 0;
    return 1;
}

/// The most particles in one box of the division `dims`.
static long fullest(const int dims[3], const double lo[3], const double hi[3],
                    const int periodic[3], const bdl_vec3 *x, long n)
{
    const int size = dims[0] * dims[1] * dims[2];
    long *count = calloc((size_t)size, sizeof *count), most = 0;
    if (!count)
        return n;
    bdl_decomp d;
    bdl_decomp_init(&d, 0, dims, lo, hi, periodic, 0.0);
    for (long i = 0; i < n; ++i) {
        const int r = bdl_decomp_owner(&d, x[i]);
        if (++count[r] > most)
            most = count[r];
    }
    free(count);
    return most;
}

int bdl_decomp_choose(int size, const double lo[3], const double hi[3], const int periodic[3],
                      double margin, const bdl_vec3 *pos, long n, int dims[3])
{
    double best = INFINITY;
    long best_load = -1;
    int found = 0;
    for (int x = 1; x <= size; ++x) {
        if (size % x)
            continue;
        for (int y = 1; y <= size / x; ++y) {
            if ((size / x) % y)
                continue;
            const int trial[3] = {x, y, size / x / y};
            if (!bdl_decomp_fits(trial, lo, hi, margin))
                continue;
            // The area of the cuts: (dims_a - 1) cuts across axis a, each of the domain's section.
            double area = 0.0;
            for (int a = 0; a < 3; ++a) {
                const int b = (a + 1) % 3, c = (a + 2) % 3;
                area += (trial[a] - 1) * (hi[b] - lo[b]) * (hi[c] - lo[c]);
            }
            const long load = fullest(trial, lo, hi, periodic, pos, n);
            if (best_load < 0 || load < best_load ||
                (load == best_load && area < best * (1.0 - 1e-12))) {
                best = area;
                best_load = load;
                for (int a = 0; a < 3; ++a)
                    dims[a] = trial[a];
                found = 1;
            }
        }
    }
    return found;
}

void bdl_decomp_init(bdl_decomp *d, int rank, const int dims[3], const double lo[3],
                     const double hi[3], const int periodic[3], double margin)
{
    d->size = dims[0] * dims[1] * dims[2];
    d->rank = rank;
    d->margin = margin;
    d->coord[0] = rank % dims[0];
    d->coord[1] = (rank / dims[0]) % dims[1];
    d->coord[2] = rank / (dims[0] * dims[1]);
    for (int a = 0; a < 3; ++a) {
        d->dims[a] = dims[a];
        d->lo[a] = lo[a];
        d->hi[a] = hi[a];
        d->periodic[a] = periodic[a];
        const double w = (hi[a] - lo[a]) / dims[a];
        d->sub_lo[a] = lo[a] + w * d->coord[a];
        d->sub_hi[a] = d->coord[a] == dims[a] - 1 ? hi[a] : lo[a] + w * (d->coord[a] + 1);
    }
}

int bdl_decomp_rank_of(const bdl_decomp *d, const int coord[3])
{
    int c[3];
    for (int a = 0; a < 3; ++a) {
        c[a] = coord[a];
        if (c[a] < 0 || c[a] >= d->dims[a]) {
            if (!d->periodic[a])
                return -1;
            c[a] = ((c[a] % d->dims[a]) + d->dims[a]) % d->dims[a];
        }
    }
    return c[0] + d->dims[0] * (c[1] + d->dims[1] * c[2]);
}

bdl_vec3 bdl_decomp_wrap(const bdl_decomp *d, bdl_vec3 x)
{
    for (int a = 0; a < 3; ++a) {
        if (!d->periodic[a] || d->dims[a] == 1)
            continue;
        const double len = d->hi[a] - d->lo[a];
        double v = bdl_v3_comp(x, a);
        if (v < d->lo[a] || v >= d->hi[a]) {
            v -= len * floor((v - d->lo[a]) / len);
            if (v >= d->hi[a])
                v = d->lo[a];
            bdl_v3_set_comp(&x, a, v);
        }
    }
    return x;
}

int bdl_decomp_owner(const bdl_decomp *d, bdl_vec3 x)
{
    x = bdl_decomp_wrap(d, x);
    int c[3];
    for (int a = 0; a < 3; ++a) {
        const double w = (d->hi[a] - d->lo[a]) / d->dims[a];
        const double at = floor((bdl_v3_comp(x, a) - d->lo[a]) / w);
        c[a] = !(at >= 0.0) ? 0 : at >= d->dims[a] ? d->dims[a] - 1 : (int)at; // NaN: box 0
    }
    return c[0] + d->dims[0] * (c[1] + d->dims[1] * c[2]);
}

int bdl_decomp_ghost_targets(const bdl_decomp *d, bdl_vec3 x, int *ranks, bdl_vec3 *shifts)
{
    // Per axis the sides x is near (offsets -1 and +1 allowed), 0 always.
    int lo_side[3], hi_side[3];
    for (int a = 0; a < 3; ++a) {
        const double v = bdl_v3_comp(x, a);
        const int cut = d->dims[a] > 1;
        lo_side[a] =
            cut && v < d->sub_lo[a] + d->margin && (d->coord[a] > 0 || d->periodic[a]) ? -1 : 0;
        hi_side[a] =
            cut && v >= d->sub_hi[a] - d->margin && (d->coord[a] < d->dims[a] - 1 || d->periodic[a])
                ? 1
                : 0;
    }
    int n = 0;
    for (int oz = lo_side[2]; oz <= hi_side[2]; ++oz)
        for (int oy = lo_side[1]; oy <= hi_side[1]; ++oy)
            for (int ox = lo_side[0]; ox <= hi_side[0]; ++ox) {
                if (ox == 0 && oy == 0 && oz == 0)
                    continue;
                const int off[3] = {ox, oy, oz};
                int c[3];
                double shift[3] = {0.0, 0.0, 0.0};
                for (int a = 0; a < 3; ++a) {
                    c[a] = d->coord[a] + off[a];
                    if (c[a] < 0)
                        shift[a] = d->hi[a] - d->lo[a]; // across the low end: the image above
                    else if (c[a] >= d->dims[a])
                        shift[a] = -(d->hi[a] - d->lo[a]);
                }
                const int r = bdl_decomp_rank_of(d, c);
                if (r < 0)
                    continue;
                ranks[n] = r;
                shifts[n] = bdl_v3(shift[0], shift[1], shift[2]);
                ++n;
            }
    return n;
}
