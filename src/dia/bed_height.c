// bedlam — bed height as the level of the steepest row-averaged gradient.
//
// Mahajan (2019) finds the bed's surface without a threshold, because the contrast between the
// particles and the back plate is low: average every pixel row, smooth the profile, difference
// it, and take the height where the gradient is largest. The simulation's bed height is the same
// definition applied to the particle density. Here a row profile p_k is smoothed by a discrete
// Gaussian (truncated at 4 sigma, renormalised at the ends), differenced g_k = p_{k+1} - p_k (the
// edge between rows k and k + 1, level k + 1), and the extreme g_m refined to sub-pixel by the
// vertex of the parabola through g_{m-1}, g_m, g_{m+1}: level = m + 1 + (g_{m-1} - g_{m+1}) /
// (2 (g_{m-1} - 2 g_m + g_{m+1})). For a blurred step the gradient is a symmetric bump about the
// edge, so the vertex lands on it to a small fraction of a row.
#include "dia/bed_height.h"

#include <math.h>
#include <stdlib.h>

void bdl_dia_row_means(const double *field, int w, int h, double *profile)
{
    for (int y = 0; y < h; ++y) {
        double s = 0.0;
        for (int x = 0; x < w; ++x)
            s += field[(size_t)y * w + x];
        profile[y] = w > 0 ? s / w : 0.0;
    }
}

/// Gaussian smoothing of n values into out; near the ends the kernel is cut and renormalised.
static void smooth_profile(const double *p, int n, double sigma, double *out)
{
    if (!(sigma > 0.0)) {
        for (int k = 0; k < n; ++k)
            out[k] = p[k];
        return;
    }
    int reach = (int)ceil(4.0 * sigma);
    for (int k = 0; k < n; ++k) {
        double s = 0.0, ws = 0.0;
        for (int j = k - reach; j <= k + reach; ++j) {
            if (j < 0 || j >= n)
                continue;
            double wj = exp(-0.5 * (j - k) * (j - k) / (sigma * sigma));
            s += wj * p[j];
            ws += wj;
        }
        out[k] = s / ws;
    }
}

double bdl_dia_profile_step(const double *profile, int n, double smooth, bdl_dia_polarity polarity)
{
    if (n < 3)
        return NAN;
    double *q = malloc((size_t)n * sizeof(double));
    if (!q)
        return NAN;
    smooth_profile(profile, n, smooth, q);
    const double sign = polarity == BDL_DIA_FALLS_INTO_BED ? -1.0 : 1.0;
    int best = -1;
    double best_g = 0.0;
    for (int k = 0; k + 1 < n; ++k) {
        double g = sign * (q[k + 1] - q[k]);
        if (polarity == BDL_DIA_EITHER_WAY)
            g = fabs(g);
        if (g > best_g) {
            best_g = g;
            best = k;
        }
    }
    double level = NAN;
    if (best >= 0) {
        level = best + 1.0;
        if (best > 0 && best + 2 < n) {
            double gm = sign * (q[best] - q[best - 1]), gp = sign * (q[best + 2] - q[best + 1]);
            double g0 = sign * (q[best + 1] - q[best]);
            if (polarity == BDL_DIA_EITHER_WAY)
                gm = fabs(gm), gp = fabs(gp), g0 = fabs(g0);
            double curvature = gm - 2.0 * g0 + gp;
            if (curvature < 0.0)
                level += 0.5 * (gm - gp) / curvature;
        }
    }
    free(q);
    return level;
}

static double bed_level(const double *field, int w, int h, double smooth, bdl_dia_polarity pol)
{
    if (w <= 0 || h <= 0)
        return NAN;
    double *profile = malloc((size_t)h * sizeof(double));
    if (!profile)
        return NAN;
    bdl_dia_row_means(field, w, h, profile);
    double level = bdl_dia_profile_step(profile, h, smooth, pol);
    free(profile);
    return level;
}

double bdl_dia_bed_level_image(const double *img, int w, int h, double smooth,
                               bdl_dia_polarity polarity)
{
    return bed_level(img, w, h, smooth, polarity);
}

double bdl_dia_bed_level_field(const double *field, int nx, int ny, double smooth)
{
    return bed_level(field, nx, ny, smooth, BDL_DIA_RISES_INTO_BED);
}
