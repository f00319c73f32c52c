// bedlam — orientation of wall-parallel rods in an image, and their coalignment.
//
// Mahajan (2019) keeps, of all the rods a camera sees through the front wall, those that lie
// parallel to it: an adaptive threshold separates the front layer from the shadows behind, blobs
// of implausible area (fragments, touching rods) are dropped, and each remaining blob's angle is
// the one at which its aspect ratio is largest: the pixel coordinates about the centroid are
// projected on an axis at angle theta and on the one across it, and
//     aspect(theta) = extent_along(theta) / extent_across(theta)
// is maximised over theta in steps (each pixel adds its square's footprint |sin| + |cos| to an
// extent, so a one-pixel blob has aspect 1 at every angle). Near the rod's axis the extents
// change as |theta - alpha| (a cusp), so the maximum is sharp; a parabola through the best step
// and its neighbours places it within the step.
//
// Coalignment (eq. 2.5): C(r) = 2 <cos^2(alpha_i - alpha_j)> - 1 = <cos 2(alpha_i - alpha_j)>,
// 1 for parallel rods, 0 for independent ones, -1 for perpendicular ones; fitted beyond about
// one rod length by C ~ A exp(-r / xi).
#include "dia/orient.h"

#include <math.h>
#include <stdlib.h>

#include "dia/analysis.h"
#include "dia/points.h"

static const double deg = 3.14159265358979323846 / 180.0;

bdl_dia_orient_def bdl_default_orient_def(void)
{
    return (bdl_dia_orient_def){.bright_particles = 1,
                                .window = 15,
                                .offset = 0.05,
                                .min_area = 20,
                                .max_area = 100000,
                                .min_aspect = 1.0,
                                .step = 0.5,
                                .method = BDL_DIA_ANGLE_ASPECT};
}

bdl_result bdl_dia_label(const unsigned char *mask, int w, int h, int32_t *label, long *count)
{
    const size_t n = (size_t)w * (size_t)h;
    int32_t *stack = malloc((n > 0 ? n : 1) * sizeof(int32_t));
    if (!stack)
        return BDL_ERR_NOMEM;
    for (size_t k = 0; k < n; ++k)
        label[k] = 0;
    int32_t next = 0;
    for (size_t start = 0; start < n; ++start) {
        if (!mask[start] || label[start])
            continue;
        long top = 0;
        label[start] = ++next;
        stack[top++] = (int32_t)start;
        while (top > 0) { // flood fill, 4-connected
            int32_t k = stack[--top];
            int x = (int)(k % w), y = (int)(k / w);
            const int nb[4][2] = {{x - 1, y}, {x + 1, y}, {x, y - 1}, {x, y + 1}};
            for (int m = 0; m < 4; ++m) {
                if (nb[m][0] < 0 || nb[m][1] < 0 || nb[m][0] >= w || nb[m][1] >= h)
                    continue;
                size_t q = (size_t)nb[m][1] * w + nb[m][0];
                if (mask[q] && !label[q]) {
                    label[q] = next;
                    stack[top++] = (int32_t)q;
                }
            }
        }
    }
    free(stack);
    *count = next;
    return BDL_OK;
}

/// Aspect ratio of the pixels (offsets dx, dy from the centroid, v down) about the axis at
/// theta degrees from upright, leaning right; the extents go to *along and *across.
static double aspect_at(const double *dx, const double *dy, long n, double theta, double *along,
                        double *across)
{
    const double s = sin(theta * deg), c = cos(theta * deg);
    double a0 = INFINITY, a1 = -INFINITY, b0 = INFINITY, b1 = -INFINITY;
    for (long k = 0; k < n; ++k) {
        double a = dx[k] * s - dy[k] * c, b = dx[k] * c + dy[k] * s;
        a0 = fmin(a0, a), a1 = fmax(a1, a);
        b0 = fmin(b0, b), b1 = fmax(b1, b);
    }
    const double footprint = 1.0;
    *along = a1 - a0 + footprint;
    *across = b1 - b0 + footprint;
    return *along / *across;
}

static double wrap_angle(double a)
{
    while (a > 90.0)
        a -= 180.0;
    while (a <= -90.0)
        a += 180.0;
    return a;
}

bdl_dia_rod bdl_dia_measure_rod(const int *xs, const int *ys, long n, double step)
{
    bdl_dia_rod rod = {NAN, NAN, NAN, n, NAN, NAN, NAN};
    double *dx = malloc((size_t)(n > 0 ? n : 1) * sizeof(double));
    double *dy = malloc((size_t)(n > 0 ? n : 1) * sizeof(double));
    if (n <= 0 || !dx || !dy || !(step > 0.0)) {
        free(dx);
        free(dy);
        return rod;
    }
    double su = 0.0, sv = 0.0;
    for (long k = 0; k < n; ++k)
        su += xs[k] + 0.5, sv += ys[k] + 0.5;
    rod.u = su / n, rod.v = sv / n;
    for (long k = 0; k < n; ++k)
        dx[k] = xs[k] + 0.5 - rod.u, dy[k] = ys[k] + 0.5 - rod.v;
    const int steps = (int)ceil(180.0 / step - 1e-9);
    const double h = 180.0 / steps;
    int best = 0;
    double best_ratio = -1.0, along, across;
    for (int k = 0; k < steps; ++k) {
        double r = aspect_at(dx, dy, n, -90.0 + k * h, &along, &across);
        if (r > best_ratio)
            best_ratio = r, best = k;
    }
    double rm = aspect_at(dx, dy, n, -90.0 + (best - 1) * h, &along, &across);
    double rp = aspect_at(dx, dy, n, -90.0 + (best + 1) * h, &along, &across);
    double curvature = rm - 2.0 * best_ratio + rp, shift = 0.0;
    if (curvature < 0.0)
        shift = fmax(-0.5, fmin(0.5, 0.5 * (rm - rp) / curvature));
    rod.angle = wrap_angle(-90.0 + (best + shift) * h);
    rod.aspect = aspect_at(dx, dy, n, rod.angle, &rod.length, &rod.width);
    free(dx);
    free(dy);
    return rod;
}

double bdl_dia_principal_angle(const int *xs, const int *ys, long n)
{
    double su = 0.0, sv = 0.0, cuu = 0.0, cvv = 0.0, cuv = 0.0;
    for (long k = 0; k < n; ++k)
        su += xs[k], sv += ys[k];
    su /= (double)n, sv /= (double)n;
    for (long k = 0; k < n; ++k) {
        double du = xs[k] - su, dv = ys[k] - sv;
        cuu += du * du, cvv += dv * dv, cuv += du * dv;
    }
    // The major axis is at phi from +u with v down; upright (phi = 90°) is angle 0.
    double phi = 0.5 * atan2(2.0 * cuv, cuu - cvv) / deg;
    return n > 0 ? wrap_angle(phi + 90.0) : NAN;
}

/// Pixels grouped by label (a counting sort): label l's pixels are at xs/ys[first[l - 1] ..
/// first[l]).
static bdl_result group_pixels(const int32_t *label, int w, int h, long count, long **first,
                               int **xs, int **ys)
{
    const size_t n = (size_t)w * (size_t)h;
    *first = calloc((size_t)count + 1, sizeof(long));
    long *fill = calloc((size_t)count + 1, sizeof(long));
    *xs = malloc((n > 0 ? n : 1) * sizeof(int));
    *ys = malloc((n > 0 ? n : 1) * sizeof(int));
    if (!*first || !fill || !*xs || !*ys) {
        free(fill);
        return BDL_ERR_NOMEM;
    }
    for (size_t k = 0; k < n; ++k)
        if (label[k])
            (*first)[label[k]]++;
    for (long l = 0; l < count; ++l)
        (*first)[l + 1] += (*first)[l];
    for (size_t k = 0; k < n; ++k)
        if (label[k]) {
            long at = (*first)[label[k] - 1] + fill[label[k]]++;
            (*xs)[at] = (int)(k % w), (*ys)[at] = (int)(k / w);
        }
    free(fill);
    return BDL_OK;
}

/// The rod with its angle replaced, and its extents and aspect taken at the new angle.
static bdl_dia_rod measure_at(const int *xs, const int *ys, long n, bdl_dia_rod rod, double angle)
{
    double *dx = malloc((size_t)n * sizeof(double)), *dy = malloc((size_t)n * sizeof(double));
    if (dx && dy) {
        for (long k = 0; k < n; ++k)
            dx[k] = xs[k] + 0.5 - rod.u, dy[k] = ys[k] + 0.5 - rod.v;
        rod.angle = angle;
        rod.aspect = aspect_at(dx, dy, n, angle, &rod.length, &rod.width);
    }
    free(dx);
    free(dy);
    return rod;
}

bdl_result bdl_dia_detect_rods(const double *img, int w, int h, const bdl_dia_orient_def *def,
                               bdl_dia_rod *rods, long max, long *count)
{
    const size_t n = (size_t)w * (size_t)h;
    unsigned char *mask = malloc(n > 0 ? n : 1);
    int32_t *label = malloc((n > 0 ? n : 1) * sizeof(int32_t));
    long *first = NULL, blobs = 0;
    int *xs = NULL, *ys = NULL;
    bdl_result res = mask && label ? BDL_OK : BDL_ERR_NOMEM;
    if (res == BDL_OK) {
        bdl_dia_threshold(img, w, h, def->bright_particles, def->window, def->offset, mask);
        res = bdl_dia_label(mask, w, h, label, &blobs);
    }
    if (res == BDL_OK)
        res = group_pixels(label, w, h, blobs, &first, &xs, &ys);
    *count = 0;
    for (long l = 0; res == BDL_OK && l < blobs; ++l) {
        long area = first[l + 1] - first[l];
        if (area < def->min_area || area > def->max_area)
            continue;
        bdl_dia_rod rod = bdl_dia_measure_rod(xs + first[l], ys + first[l], area, def->step);
        if (def->method == BDL_DIA_ANGLE_MOMENTS)
            rod = measure_at(xs + first[l], ys + first[l], area, rod,
                             bdl_dia_principal_angle(xs + first[l], ys + first[l], area));
        if (!(rod.aspect >= def->min_aspect))
            continue;
        if (*count < max)
            rods[*count] = rod;
        ++*count;
    }
    free(mask);
    free(label);
    free(first);
    free(xs);
    free(ys);
    return res;
}

bdl_result bdl_dia_coalignment(const double *u, const double *v, const double *angle, long n,
                               double r_max, int bins, double x_min, double x_max, double *c,
                               long *pairs, double *r_mean)
{
    if (!(r_max > 0.0) || bins < 1)
        return BDL_ERR_ARGS;
    for (int b = 0; b < bins; ++b) {
        c[b] = 0.0, pairs[b] = 0;
        if (r_mean)
            r_mean[b] = 0.0;
    }
    bdl_dia_point_grid g;
    bdl_result res = bdl_dia_point_grid_build(&g, u, v, n, r_max);
    if (res != BDL_OK)
        return res;
    for (long i = 0; i < n; ++i) {
        if (!(u[i] >= x_min && u[i] < x_max))
            continue;
        int cx0, cx1, cy0, cy1;
        bdl_dia_point_grid_range(&g, u[i], v[i], r_max, &cx0, &cx1, &cy0, &cy1);
        for (int cy = cy0; cy <= cy1; ++cy)
            for (int cx = cx0; cx <= cx1; ++cx) {
                long cell = (long)cy * g.nx + cx;
                for (long m = g.start[cell]; m < g.start[cell + 1]; ++m) {
                    long j = g.index[m];
                    double r = hypot(u[j] - u[i], v[j] - v[i]);
                    if (j == i || !(r < r_max))
                        continue;
                    int b = (int)(r / r_max * bins);
                    b = b < bins ? b : bins - 1;
                    c[b] += cos(2.0 * (angle[i] - angle[j]) * deg);
                    pairs[b]++;
                    if (r_mean)
                        r_mean[b] += r;
                }
            }
    }
    for (int b = 0; b < bins; ++b) {
        c[b] = pairs[b] > 0 ? c[b] / (double)pairs[b] : NAN;
        if (r_mean)
            r_mean[b] = pairs[b] > 0 ? r_mean[b] / (double)pairs[b] : NAN;
    }
    bdl_dia_point_grid_free(&g);
    return BDL_OK;
}

double bdl_dia_coalignment_fit(const double *r, const double *c, const long *pairs, int bins,
                               double r_min, int fix_amplitude, double *amplitude)
{
    double sw = 0.0, sx = 0.0, sy = 0.0, sxx = 0.0, sxy = 0.0;
    int used = 0;
    for (int b = 0; b < bins; ++b) {
        if (!(r[b] >= r_min) || !(c[b] > 0.0) || pairs[b] <= 0)
            continue;
        // var(ln C) ~ var(C) / C^2, and var(C) ~ 1 / pairs
        double wb = (double)pairs[b] * c[b] * c[b], y = log(c[b]);
        sw += wb, sx += wb * r[b], sy += wb * y, sxx += wb * r[b] * r[b], sxy += wb * r[b] * y;
        ++used;
    }
    double slope = NAN, intercept = 0.0;
    if (fix_amplitude && used >= 1 && sxx > 0.0) {
        slope = sxy / sxx; // ln C = -r / xi through the origin
    } else if (!fix_amplitude && used >= 2) {
        double det = sw * sxx - sx * sx;
        if (det > 0.0) {
            slope = (sw * sxy - sx * sy) / det;
            intercept = (sy - slope * sx) / sw;
        }
    }
    if (amplitude)
        *amplitude = isfinite(slope) ? exp(intercept) : NAN;
    return slope < 0.0 ? -1.0 / slope : NAN;
}
