// bedlam — PTV: nearest-neighbour linking of centroids between frames; 2D coordination number.
//
// Between frames f and f + 1 every pair (p, q) with |x_q - x_p| < d_max is a candidate. Taking
// them by increasing distance and linking a pair when p has no successor and q no predecessor
// yet resolves conflicts (two particles near one, or one near two) in favour of the smallest
// displacement, as the thesis does. When every particle moves less than half the distance to its
// nearest neighbour, its own successor is the nearest of all and every link is right.
#include "dia/ptv.h"

#include <math.h>
#include <stdlib.h>

#include "dia/points.h"

typedef struct candidate {
    double distance;
    long p, q;
} candidate;

static int by_distance(const void *x, const void *y)
{
    const candidate *a = x, *b = y;
    if (a->distance != b->distance)
        return a->distance < b->distance ? -1 : 1;
    if (a->p != b->p)
        return a->p < b->p ? -1 : 1;
    return (a->q > b->q) - (a->q < b->q);
}

/// Candidate pairs from points p0 .. p1 - 1 to q0 .. q1 - 1 closer than dmax, into *list.
static bdl_result candidates(const double *u, const double *v, long p0, long p1, long q0, long q1,
                             double dmax, candidate **list, long *count, long *capacity)
{
    bdl_dia_point_grid g;
    bdl_result res = bdl_dia_point_grid_build(&g, u + q0, v + q0, q1 - q0, dmax);
    *count = 0;
    for (long p = p0; res == BDL_OK && p < p1; ++p) {
        int cx0, cx1, cy0, cy1;
        bdl_dia_point_grid_range(&g, u[p], v[p], dmax, &cx0, &cx1, &cy0, &cy1);
        for (int cy = cy0; cy <= cy1; ++cy)
            for (int cx = cx0; cx <= cx1; ++cx)
                for (long m = g.start[cy * g.nx + cx]; m < g.start[cy * g.nx + cx + 1]; ++m) {
                    long q = q0 + g.index[m];
                    double d = hypot(u[q] - u[p], v[q] - v[p]);
                    if (!(d < dmax))
                        continue;
                    if (*count == *capacity) {
                        long grown = *capacity ? 2 * *capacity : 1024;
                        candidate *bigger = realloc(*list, (size_t)grown * sizeof(candidate));
                        if (!bigger) {
                            bdl_dia_point_grid_free(&g);
                            return BDL_ERR_NOMEM;
                        }
                        *list = bigger, *capacity = grown;
                    }
                    (*list)[(*count)++] = (candidate){d, p, q};
                }
    }
    bdl_dia_point_grid_free(&g);
    return res;
}

/// next[p] = the point p is linked to in the following frame, or -1.
static bdl_result link_frames(const double *u, const double *v, const long *frame_start,
                              long frames, double dmax, long *next, unsigned char *has_prev)
{
    candidate *list = NULL;
    long count = 0, capacity = 0;
    bdl_result res = BDL_OK;
    for (long f = 0; f + 1 < frames && res == BDL_OK; ++f) {
        res = candidates(u, v, frame_start[f], frame_start[f + 1], frame_start[f + 1],
                         frame_start[f + 2], dmax, &list, &count, &capacity);
        if (res != BDL_OK)
            break;
        qsort(list, (size_t)count, sizeof(candidate), by_distance);
        for (long k = 0; k < count; ++k)
            if (next[list[k].p] < 0 && !has_prev[list[k].q]) {
                next[list[k].p] = list[k].q;
                has_prev[list[k].q] = 1;
            }
    }
    free(list);
    return res;
}

/// The frame a point belongs to (frame_start is sorted).
static long frame_of(const long *frame_start, long frames, long point)
{
    long lo = 0, hi = frames - 1;
    while (lo < hi) {
        long mid = (lo + hi + 1) / 2;
        if (frame_start[mid] <= point)
            lo = mid;
        else
            hi = mid - 1;
    }
    return lo;
}

/// Follows the links from every point without a predecessor; keeps the chains of min_length.
static bdl_result collect(const long *frame_start, long frames, const long *next,
                          const unsigned char *has_prev, long min_length, bdl_dia_tracks *t)
{
    const long n = frame_start[frames];
    t->count = 0;
    long kept_points = 0;
    for (long p = 0; p < n; ++p) {
        t->track[p] = -1;
        if (has_prev[p])
            continue;
        long length = 0;
        for (long q = p; q >= 0; q = next[q])
            ++length;
        if (length < min_length)
            continue;
        t->first_frame[t->count] = frame_of(frame_start, frames, p);
        t->start[t->count] = kept_points;
        for (long q = p; q >= 0; q = next[q])
            t->point[kept_points++] = q;
        t->count++;
    }
    t->start[t->count] = kept_points;
    for (long k = 0; k < t->count; ++k)
        for (long m = t->start[k]; m < t->start[k + 1]; ++m)
            t->track[t->point[m]] = k;
    return BDL_OK;
}

bdl_result bdl_dia_ptv_link(const double *u, const double *v, const long *frame_start, long frames,
                            double max_displacement, long min_length, bdl_dia_tracks *tracks)
{
    *tracks = (bdl_dia_tracks){0};
    if (!(max_displacement > 0.0) || frames < 1)
        return BDL_ERR_ARGS;
    const long n = frame_start[frames];
    const size_t size = (size_t)(n > 0 ? n : 1);
    long *next = malloc(size * sizeof(long));
    unsigned char *has_prev = calloc(size, 1);
    tracks->first_frame = malloc(size * sizeof(long));
    tracks->start = malloc((size + 1) * sizeof(long));
    tracks->point = malloc(size * sizeof(long));
    tracks->track = malloc(size * sizeof(long));
    bdl_result res =
        next && has_prev && tracks->first_frame && tracks->start && tracks->point && tracks->track
            ? BDL_OK
            : BDL_ERR_NOMEM;
    for (long p = 0; res == BDL_OK && p < n; ++p)
        next[p] = -1;
    if (res == BDL_OK)
        res = link_frames(u, v, frame_start, frames, max_displacement, next, has_prev);
    if (res == BDL_OK)
        res = collect(frame_start, frames, next, has_prev, min_length, tracks);
    free(next);
    free(has_prev);
    if (res != BDL_OK)
        bdl_dia_tracks_free(tracks);
    return res;
}

void bdl_dia_tracks_free(bdl_dia_tracks *t)
{
    free(t->first_frame), free(t->start), free(t->point), free(t->track);
    *t = (bdl_dia_tracks){0};
}

double bdl_dia_disc_in_rect(double u, double v, double r, const double *b)
{
    enum { STRIPS = 512 };
    const double h = 2.0 * r / STRIPS;
    double area = 0.0;
    for (int k = 0; k < STRIPS; ++k) {
        double x = u - r + (k + 0.5) * h;
        if (x < b[0] || x > b[2])
            continue;
        double half = sqrt(fmax(0.0, r * r - (x - u) * (x - u)));
        double lo = fmax(v - half, b[1]), hi = fmin(v + half, b[3]);
        if (hi > lo)
            area += (hi - lo) * h;
    }
    return area;
}

bdl_result bdl_dia_coordination_2d(const double *u, const double *v, long n, double radius,
                                   const double *bounds, double *cn)
{
    if (!(radius > 0.0))
        return BDL_ERR_ARGS;
    bdl_dia_point_grid g;
    bdl_result res = bdl_dia_point_grid_build(&g, u, v, n, radius);
    if (res != BDL_OK)
        return res;
    const double disc = 3.14159265358979323846 * radius * radius;
    for (long i = 0; i < n; ++i) {
        int cx0, cx1, cy0, cy1;
        long count = 0;
        bdl_dia_point_grid_range(&g, u[i], v[i], radius, &cx0, &cx1, &cy0, &cy1);
        for (int cy = cy0; cy <= cy1; ++cy)
            for (int cx = cx0; cx <= cx1; ++cx)
                for (long m = g.start[cy * g.nx + cx]; m < g.start[cy * g.nx + cx + 1]; ++m) {
                    long j = g.index[m];
                    count += j != i && hypot(u[j] - u[i], v[j] - v[i]) < radius;
                }
        double inside = bounds ? bdl_dia_disc_in_rect(u[i], v[i], radius, bounds) / disc : 1.0;
        cn[i] = inside > 0.0 ? (double)count / inside : 0.0;
    }
    bdl_dia_point_grid_free(&g);
    return BDL_OK;
}
