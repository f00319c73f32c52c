// bedlam — DIA image analysis: Otsu and adaptive thresholds, cell fractions, calibration fits,
// blob detection.
#include "dia/analysis.h"

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

const char *const bdl_dia_model_names[BDL_DIA_MODEL_COUNT] = {"rational", "power"};

/// Otsu's global threshold of grey values in [0, 1] (256 bins): the level that maximises the
/// between-class variance.
static double otsu(const double *img, long n)
{
    long hist[256] = {0};
    for (long k = 0; k < n; ++k) {
        int b = (int)(img[k] * 255.0 + 0.5);
        hist[b < 0 ? 0 : b > 255 ? 255 : b]++;
    }
    double total = 0.0;
    for (int b = 0; b < 256; ++b)
        total += (double)b * hist[b];
    double w0 = 0.0, sum0 = 0.0, best = -1.0;
    int level = 127;
    for (int t = 0; t < 255; ++t) { // class 0: bins 0..t
        w0 += (double)hist[t];
        sum0 += (double)t * hist[t];
        double w1 = (double)n - w0;
        if (w0 == 0.0 || w1 == 0.0)
            continue;
        double m0 = sum0 / w0, m1 = (total - sum0) / w1;
        double between = w0 * w1 * (m0 - m1) * (m0 - m1);
        if (between > best) {
            best = between;
            level = t;
        }
    }
    return (level + 0.5) / 255.0; // between bin t and t + 1
}

void bdl_dia_threshold(const double *img, int w, int h, int bright_particles, int window,
                       double offset, unsigned char *mask)
{
    const long n = (long)w * h;
    const double global = otsu(img, n);
    double *integral = NULL;
    if (window > 0) // summed-area table, (w + 1) x (h + 1)
        integral = calloc((size_t)(w + 1) * (size_t)(h + 1), sizeof(double));
    if (integral)
        for (int y = 0; y < h; ++y) {
            double row = 0.0;
            for (int x = 0; x < w; ++x) {
                row += img[(size_t)y * w + x];
                integral[(size_t)(y + 1) * (w + 1) + x + 1] =
                    integral[(size_t)y * (w + 1) + x + 1] + row;
            }
        }
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            double level = global, g = img[(size_t)y * w + x];
            if (integral) {
                int x0 = x - window < 0 ? 0 : x - window,
                    x1 = x + window + 1 > w ? w : x + window + 1;
                int y0 = y - window < 0 ? 0 : y - window,
                    y1 = y + window + 1 > h ? h : y + window + 1;
                double sum =
                    integral[(size_t)y1 * (w + 1) + x1] - integral[(size_t)y0 * (w + 1) + x1] -
                    integral[(size_t)y1 * (w + 1) + x0] + integral[(size_t)y0 * (w + 1) + x0];
                double mean = sum / ((double)(x1 - x0) * (y1 - y0));
                // A window that is all background or all particle has no edge to adapt to.
                double local = bright_particles ? mean + offset : mean - offset;
                if (fabs(mean - global) < 0.5 * fabs(global - (bright_particles ? 0.0 : 1.0)))
                    level = local;
            }
            mask[(size_t)y * w + x] = bright_particles ? g > level : g < level;
        }
    free(integral);
}

void bdl_dia_cell_fractions(const unsigned char *mask, int w, int h, int nx, int ny,
                            double *fraction)
{
    long *count = calloc((size_t)nx * ny, sizeof(long));
    memset(fraction, 0, (size_t)nx * ny * sizeof(double));
    if (!count)
        return;
    for (int y = 0; y < h; ++y) {
        int cy = (int)((long)y * ny / h);
        for (int x = 0; x < w; ++x) {
            int cx = (int)((long)x * nx / w);
            fraction[cy * nx + cx] += mask[(size_t)y * w + x];
            count[cy * nx + cx]++;
        }
    }
    for (int k = 0; k < nx * ny; ++k)
        fraction[k] = count[k] > 0 ? fraction[k] / (double)count[k] : 0.0;
    free(count);
}

static double model_value(bdl_dia_model m, const double *p, double x)
{
    return m == BDL_DIA_MODEL_RATIONAL ? p[0] * x / (p[1] - x) : p[0] * pow(x, p[1]);
}

/// Derivatives of the model with respect to its two parameters.
static void model_grad(bdl_dia_model m, const double *p, double x, double *g)
{
    if (m == BDL_DIA_MODEL_RATIONAL) {
        g[0] = x / (p[1] - x);
        g[1] = -p[0] * x / ((p[1] - x) * (p[1] - x));
    } else {
        double xb = x > 0.0 ? pow(x, p[1]) : 0.0;
        g[0] = xb;
        g[1] = x > 0.0 ? p[0] * xb * log(x) : 0.0;
    }
}

static int params_valid(bdl_dia_model m, const double *p, const double *x, long n)
{
    if (m == BDL_DIA_MODEL_POWER)
        return p[0] > 0.0 && isfinite(p[1]);
    for (long k = 0; k < n; ++k)
        if (!(x[k] < p[1]))
            return 0;
    return p[0] > 0.0;
}

static double sse(bdl_dia_model m, const double *p, const double *x, const double *y, long n)
{
    double s = 0.0;
    for (long k = 0; k < n; ++k) {
        double r = y[k] - model_value(m, p, x[k]);
        s += r * r;
    }
    return s;
}

bdl_dia_fit bdl_dia_fit_model(bdl_dia_model model, const double *f2d, const double *f3d, long n)
{
    bdl_dia_fit fit = {model, {NAN, NAN}, NAN, NAN, NAN, n, 0};
    if (n < 3)
        return fit;
    double p[2];
    double xmax = 0.0;
    for (long k = 0; k < n; ++k)
        xmax = fmax(xmax, f2d[k]);
    if (model == BDL_DIA_MODEL_RATIONAL) {
        // Start: B a little above the data, A from the mean ratio.
        p[1] = xmax + 0.05;
        double num = 0.0, den = 0.0;
        for (long k = 0; k < n; ++k) {
            double g = f2d[k] / (p[1] - f2d[k]);
            num += g * f3d[k];
            den += g * g;
        }
        p[0] = den > 0.0 ? num / den : 0.05;
    } else { // log-linear start on the positive points
        double sx = 0, sy = 0, sxx = 0, sxy = 0;
        long m = 0;
        for (long k = 0; k < n; ++k)
            if (f2d[k] > 0.0 && f3d[k] > 0.0) {
                double lx = log(f2d[k]), ly = log(f3d[k]);
                sx += lx, sy += ly, sxx += lx * lx, sxy += lx * ly, ++m;
            }
        double det = m * sxx - sx * sx;
        p[1] = m > 1 && det != 0.0 ? (m * sxy - sx * sy) / det : 1.0;
        p[0] = m > 0 ? exp((sy - p[1] * sx) / m) : 1.0;
    }
    // Levenberg-Marquardt on the 2 x 2 normal equations.
    double lambda = 1e-3, cost = sse(model, p, f2d, f3d, n);
    for (int it = 0; it < 500; ++it) {
        double jtj[3] = {0, 0, 0}, jtr[2] = {0, 0};
        for (long k = 0; k < n; ++k) {
            double g[2], r = f3d[k] - model_value(model, p, f2d[k]);
            model_grad(model, p, f2d[k], g);
            jtj[0] += g[0] * g[0], jtj[1] += g[0] * g[1], jtj[2] += g[1] * g[1];
            jtr[0] += g[0] * r, jtr[1] += g[1] * r;
        }
        int improved = 0;
        for (int tries = 0; tries < 30 && !improved; ++tries) {
            double a = jtj[0] * (1.0 + lambda), b = jtj[1], c = jtj[2] * (1.0 + lambda);
            double det = a * c - b * b;
            if (det == 0.0)
                break;
            double q[2] = {p[0] + (c * jtr[0] - b * jtr[1]) / det,
                           p[1] + (a * jtr[1] - b * jtr[0]) / det};
            double cq = params_valid(model, q, f2d, n) ? sse(model, q, f2d, f3d, n) : INFINITY;
            if (cq < cost) {
                double change = fabs(cost - cq) / fmax(cost, 1e-300);
                p[0] = q[0], p[1] = q[1], cost = cq;
                lambda *= 0.3;
                improved = 1;
                if (change < 1e-14)
                    it = 1000; // converged
            } else {
                lambda *= 10.0;
            }
        }
        if (!improved || it >= 1000) {
            fit.converged = 1;
            break;
        }
    }
    fit.p[0] = p[0], fit.p[1] = p[1];
    double mean = 0.0, tss = 0.0;
    for (long k = 0; k < n; ++k)
        mean += f3d[k];
    mean /= (double)n;
    fit.max_abs = 0.0;
    for (long k = 0; k < n; ++k) {
        tss += (f3d[k] - mean) * (f3d[k] - mean);
        fit.max_abs = fmax(fit.max_abs, fabs(f3d[k] - model_value(model, p, f2d[k])));
    }
    fit.r2 = tss > 0.0 ? 1.0 - cost / tss : NAN;
    fit.rms = sqrt(cost / (double)n);
    return fit;
}

double bdl_dia_fit_cap_f2d(const bdl_dia_fit *fit, double cap)
{
    if (fit->model == BDL_DIA_MODEL_RATIONAL) // A x/(B - x) = cap
        return cap * fit->p[1] / (fit->p[0] + cap);
    if (!(fit->p[0] > 0.0) || fit->p[1] == 0.0)
        return NAN;
    double x = pow(cap / fit->p[0], 1.0 / fit->p[1]);
    return x <= 1.0 ? x : NAN;
}

double bdl_dia_fit_apply(const bdl_dia_fit *fit, double f2d, double cap)
{
    double xc = bdl_dia_fit_cap_f2d(fit, cap);
    if (f2d <= 0.0)
        return 0.0;
    if (isfinite(xc) && f2d >= xc)
        return cap;
    double f = model_value(fit->model, fit->p, f2d);
    return f < cap ? f : cap;
}

bdl_result bdl_dia_blobs(const unsigned char *mask, const double *img, int w, int h,
                         bdl_dia_blob *blobs, long max, long *count)
{
    const size_t n = (size_t)w * (size_t)h;
    unsigned char *seen = calloc(n, 1);
    int32_t *stack = malloc(n * sizeof(int32_t));
    int32_t *ring = img ? malloc(n * sizeof(int32_t)) : NULL;
    long *ring_mark = img ? calloc(n, sizeof(long)) : NULL;
    if (!seen || !stack || (img && (!ring || !ring_mark))) {
        free(seen);
        free(stack);
        free(ring);
        free(ring_mark);
        return BDL_ERR_NOMEM;
    }
    double background = 0.0;
    if (img) {
        long outside = 0;
        for (size_t k = 0; k < n; ++k)
            if (!mask[k]) {
                background += img[k];
                ++outside;
            }
        background = outside > 0 ? background / (double)outside : 0.0;
    }
    *count = 0;
    for (size_t start = 0; start < n; ++start) {
        if (!mask[start] || seen[start])
            continue;
        double su = 0.0, sv = 0.0, sw = 0.0;
        long pixels = 0, top = 0, rings = 0, blob_id = *count + 1;
        stack[top++] = (int32_t)start;
        seen[start] = 1;
        while (top > 0) { // flood fill, 4-connected
            int32_t k = stack[--top];
            int x = (int)(k % w), y = (int)(k / w);
            double wk = img ? fabs(img[k] - background) : 1.0;
            su += wk * (x + 0.5), sv += wk * (y + 0.5), sw += wk, ++pixels;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) {
                    int xx = x + dx, yy = y + dy;
                    if (xx < 0 || yy < 0 || xx >= w || yy >= h)
                        continue;
                    size_t q = (size_t)yy * w + xx;
                    if (mask[q] && !seen[q] && (dx == 0 || dy == 0)) {
                        seen[q] = 1;
                        stack[top++] = (int32_t)q;
                    } else if (img && !mask[q] && ring_mark[q] != blob_id) {
                        ring_mark[q] = blob_id; // the one-pixel ring around the blob
                        ring[rings++] = (int32_t)q;
                    }
                }
        }
        for (long m = 0; m < rings; ++m) {
            int32_t k = ring[m];
            double wk = fabs(img[k] - background);
            su += wk * (k % w + 0.5), sv += wk * (k / w + 0.5), sw += wk;
        }
        if (*count < max)
            blobs[*count] = (bdl_dia_blob){su / sw, sv / sw, pixels};
        ++*count;
    }
    free(seen);
    free(stack);
    free(ring);
    free(ring_mark);
    return BDL_OK;
}
