// bedlam — power spectrum (Hamming window, radix-2 FFT), Welch's average of it over pieces,
// and its dominant frequency.
#include "analysis/signal.h"

#include <math.h>
#include <stdlib.h>

#define PI 3.14159265358979323846

/// In-place iterative radix-2 FFT of n (a power of two) complex values re + i im.
static void fft(double *re, double *im, long n)
{
    for (long i = 1, j = 0; i < n; ++i) { // bit-reversal permutation
        long bit = n >> 1;
        for (; j & bit; bit >>= 1)
            j ^= bit;
        j ^= bit;
        if (i < j) {
            double t = re[i];
            re[i] = re[j], re[j] = t;
            t = im[i];
            im[i] = im[j], im[j] = t;
        }
    }
    for (long len = 2; len <= n; len <<= 1) {
        double angle = -2.0 * PI / (double)len;
        for (long i = 0; i < n; i += len)
            for (long k = 0; k < len / 2; ++k) {
                double wr = cos(angle * (double)k), wi = sin(angle * (double)k);
                long a = i + k, b = i + k + len / 2;
                double xr = re[b] * wr - im[b] * wi, xi = re[b] * wi + im[b] * wr;
                re[b] = re[a] - xr, im[b] = im[a] - xi;
                re[a] += xr, im[a] += xi;
            }
    }
}

bdl_result bdl_power_spectrum(const double *x, long n, double dt, double **freq, double **power,
                              long *count)
{
    *freq = *power = NULL;
    *count = 0;
    if (n < 4 || !(dt > 0.0))
        return BDL_ERR_ARGS;
    long size = 1;
    while (size < n)
        size <<= 1;
    double *re = calloc((size_t)size, sizeof(double)), *im = calloc((size_t)size, sizeof(double));
    long bins = size / 2 + 1;
    double *f = malloc((size_t)bins * sizeof(double)), *p = malloc((size_t)bins * sizeof(double));
    if (!re || !im || !f || !p) {
        free(re), free(im), free(f), free(p);
        return BDL_ERR_NOMEM;
    }
    double mean = 0.0;
    for (long i = 0; i < n; ++i)
        mean += x[i];
    mean /= (double)n;
    for (long i = 0; i < n; ++i)
        re[i] = (x[i] - mean) * (0.54 - 0.46 * cos(2.0 * PI * (double)i / (double)(n - 1)));
    fft(re, im, size);
    for (long k = 0; k < bins; ++k) {
        f[k] = (double)k / ((double)size * dt);
        p[k] = re[k] * re[k] + im[k] * im[k];
    }
    free(re), free(im);
    *freq = f, *power = p, *count = bins;
    return BDL_OK;
}

bdl_result bdl_welch_spectrum(const double *x, long n, double dt, int segments, double fmin,
                              double fmax, double *peaks, double **freq, double **power,
                              long *count)
{
    *freq = *power = NULL;
    *count = 0;
    if (segments < 1 || n < 1)
        return BDL_ERR_ARGS;
    const long len = segments == 1 ? n : 2 * n / (segments + 1), step = len / 2;
    if (len < 4)
        return BDL_ERR_ARGS;
    double *sum = NULL, *f = NULL;
    long bins = 0;
    for (int k = 0; k < segments; ++k) {
        double *fk, *pk;
        long bk;
        const bdl_result rc = bdl_power_spectrum(x + k * step, len, dt, &fk, &pk, &bk);
        if (rc != BDL_OK) {
            free(sum), free(f);
            return rc;
        }
        if (peaks)
            peaks[k] = bdl_dominant_frequency(fk, pk, bk, fmin, fmax);
        if (!sum) { // the first piece's arrays hold the sum; every piece has the same bins
            sum = pk, f = fk, bins = bk;
            continue;
        }
        for (long b = 0; b < bins; ++b)
            sum[b] += pk[b];
        free(fk), free(pk);
    }
    for (long b = 0; b < bins; ++b)
        sum[b] /= segments;
    *freq = f, *power = sum, *count = bins;
    return BDL_OK;
}

double bdl_dominant_frequency(const double *freq, const double *power, long count, double fmin,
                              double fmax)
{
    long best = -1;
    for (long k = 0; k < count; ++k)
        if (freq[k] >= fmin && freq[k] <= fmax && (best < 0 || power[k] > power[best]))
            best = k;
    if (best < 0)
        return NAN;
    if (best == 0 || best == count - 1)
        return freq[best];
    // Parabola through (-1, p0), (0, p1), (1, p2): vertex at (p0 - p2) / (2 (p0 - 2 p1 + p2)).
    double p0 = power[best - 1], p1 = power[best], p2 = power[best + 1];
    double den = p0 - 2.0 * p1 + p2;
    double shift = den != 0.0 ? 0.5 * (p0 - p2) / den : 0.0;
    return freq[best] + shift * (freq[best + 1] - freq[best]);
}
