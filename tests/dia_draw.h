// bedlam tests — synthetic images for the image-analysis chain: Gaussian particle images
// integrated exactly over each pixel, anti-aliased capsules (rods) by supersampling, sensor noise.
#ifndef BDL_TEST_DIA_DRAW_H
#define BDL_TEST_DIA_DRAW_H

#include <math.h>

#include "core/rng.h"

/// Adds a Gaussian particle image of peak `amplitude` and width sigma [px] centred at (u, v),
/// integrated over each pixel [i, i+1) x [j, j+1) (so a sub-pixel shift is exact).
static inline void draw_gaussian_spot(double *img, int w, int h, double u, double v, double sigma,
                                      double amplitude)
{
    const double s = sqrt(2.0) * sigma, reach = 4.0 * sigma;
    const double norm = amplitude * 2.0 * 3.14159265358979323846 * sigma * sigma / 4.0;
    int i0 = (int)floor(u - reach), i1 = (int)floor(u + reach);
    int j0 = (int)floor(v - reach), j1 = (int)floor(v + reach);
    for (int j = j0 < 0 ? 0 : j0; j <= j1 && j < h; ++j) {
        double gy = erf((j + 1 - v) / s) - erf((j - v) / s);
        for (int i = i0 < 0 ? 0 : i0; i <= i1 && i < w; ++i) {
            double gx = erf((i + 1 - u) / s) - erf((i - u) / s);
            img[(size_t)j * w + i] += norm * gx * gy;
        }
    }
}

/// Distance from (x, y) to the segment (ax, ay)-(bx, by).
static inline double segment_distance(double x, double y, double ax, double ay, double bx,
                                      double by)
{
    double ex = bx - ax, ey = by - ay, e2 = ex * ex + ey * ey;
    double t = e2 > 0.0 ? ((x - ax) * ex + (y - ay) * ey) / e2 : 0.0;
    t = t < 0.0 ? 0.0 : t > 1.0 ? 1.0 : t;
    return hypot(x - ax - t * ex, y - ay - t * ey);
}

/// Paints a capsule (tip-to-tip `length`, `width` across, centre (u, v), `angle` degrees from
/// upright, leaning right) with grey `level` over what is there, anti-aliased by ss x ss samples
/// per pixel.
static inline void draw_capsule(double *img, int w, int h, double u, double v, double length,
                                double width, double angle, double level, int ss)
{
    const double a = angle * 3.14159265358979323846 / 180.0, r = 0.5 * width;
    const double half = 0.5 * length - r, ex = sin(a) * half, ey = -cos(a) * half;
    int i0 = (int)floor(u - 0.5 * length - 1), i1 = (int)ceil(u + 0.5 * length + 1);
    int j0 = (int)floor(v - 0.5 * length - 1), j1 = (int)ceil(v + 0.5 * length + 1);
    for (int j = j0 < 0 ? 0 : j0; j <= j1 && j < h; ++j)
        for (int i = i0 < 0 ? 0 : i0; i <= i1 && i < w; ++i) {
            int inside = 0;
            for (int sy = 0; sy < ss; ++sy)
                for (int sx = 0; sx < ss; ++sx) {
                    double x = i + (sx + 0.5) / ss, y = j + (sy + 0.5) / ss;
                    inside += segment_distance(x, y, u - ex, v - ey, u + ex, v + ey) <= r;
                }
            double f = (double)inside / (ss * ss);
            double *p = &img[(size_t)j * w + i];
            *p = (1.0 - f) * *p + f * level;
        }
}

/// Gaussian sensor noise of sigma, clamped to [0, 1].
static inline void add_noise(double *img, long n, double sigma, bdl_rng *rng)
{
    for (long k = 0; k < n; ++k) {
        double g = img[k] + sigma * bdl_rng_normal(rng);
        img[k] = g < 0.0 ? 0.0 : g > 1.0 ? 1.0 : g;
    }
}

/// a - b in degrees, wrapped to (-90, 90] (rod angles are defined modulo 180°).
static inline double angle_difference(double a, double b)
{
    double d = fmod(a - b, 180.0);
    if (d > 90.0)
        d -= 180.0;
    if (d <= -90.0)
        d += 180.0;
    return d;
}

#endif
