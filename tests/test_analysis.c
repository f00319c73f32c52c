// Analyses on constructed inputs with known answers: the dominant frequency of a noisy sinusoid,
// the spectrum's normalisation (Parseval), Welch's average over pieces, U_mf from a sweep built
// from Ergun's packed branch and a flat fluidized plateau, and the stages and branches of such a
// sweep read from a time series as a run writes it.
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "analysis/signal.h"
#include "analysis/umf.h"
#include "check.h"
#include "core/rng.h"

static void test_spectrum(void)
{
    // 20 s at 100 Hz (as a pressure sensor): 3.1 Hz plus a weaker 11 Hz and noise.
    enum { N = 2000 };
    static double x[N];
    const double dt = 0.01;
    bdl_rng rng;
    bdl_rng_seed(&rng, 4);
    for (int i = 0; i < N; ++i) {
        double t = i * dt;
        x[i] = 50.0 + 12.0 * sin(2.0 * 3.14159265358979 * 3.1 * t) +
               4.0 * sin(2.0 * 3.14159265358979 * 11.0 * t + 1.0) + 6.0 * bdl_rng_normal(&rng);
    }
    double *f, *p;
    long count;
    CHECK(bdl_power_spectrum(x, N, dt, &f, &p, &count) == BDL_OK);
    double peak = bdl_dominant_frequency(f, p, count, 0.5, 50.0);
    double second = bdl_dominant_frequency(f, p, count, 6.0, 50.0);
    printf("spectrum: %ld bins of %.4f Hz; dominant %.3f Hz (3.1), next %.3f Hz (11)\n", count,
           f[1], peak, second);
    CHECK(count == 1025);
    CHECK_CLOSE(f[1], 1.0 / (2048 * dt), 1e-12);
    CHECK(fabs(peak - 3.1) < 0.5 * f[1]);
    CHECK(fabs(second - 11.0) < 0.5 * f[1]);
    free(f);
    free(p);
    CHECK(bdl_power_spectrum(x, 3, dt, &f, &p, &count) == BDL_ERR_ARGS);
    CHECK(f == NULL && p == NULL && count == 0);
}

/// Coefficient of variation of the power over the bins between f0 and f1.
static double spread(const double *f, const double *p, long count, double f0, double f1)
{
    double sum = 0.0, sum2 = 0.0;
    long n = 0;
    for (long k = 0; k < count; ++k)
        if (f[k] >= f0 && f[k] <= f1)
            sum += p[k], sum2 += p[k] * p[k], ++n;
    const double mean = sum / n;
    return sqrt(fmax(sum2 / n - mean * mean, 0.0)) / mean;
}

/// Welch's average over 8 half-overlapping pieces of 60 s of a 1.6 Hz oscillation in strong
/// noise: the peak stays where it is in every piece, and the noise floor's scatter, which a
/// single periodogram leaves at about its mean (chi-square with two degrees of freedom), falls
/// by about the square root of the pieces' count.
static void test_welch(void)
{
    enum { N = 12000, PIECES = 8 };
    static double x[N];
    const double dt = 0.005;
    bdl_rng rng;
    bdl_rng_seed(&rng, 9);
    for (int i = 0; i < N; ++i)
        x[i] =
            850.0 + 40.0 * sin(2.0 * 3.14159265358979 * 1.6 * i * dt) + 60.0 * bdl_rng_normal(&rng);
    double *f1, *p1, *fw, *pw, peaks[PIECES];
    long n1, nw;
    CHECK(bdl_power_spectrum(x, N, dt, &f1, &p1, &n1) == BDL_OK);
    CHECK(bdl_welch_spectrum(x, N, dt, PIECES, 0.2, 20.0, peaks, &fw, &pw, &nw) == BDL_OK);
    const double peak = bdl_dominant_frequency(fw, pw, nw, 0.2, 20.0);
    const double cv1 = spread(f1, p1, n1, 5.0, 50.0), cvw = spread(fw, pw, nw, 5.0, 50.0);
    double worst = 0.0;
    for (int k = 0; k < PIECES; ++k)
        worst = fmax(worst, fabs(peaks[k] - 1.6));
    printf("welch: %d pieces, %ld bins of %.4f Hz; peak %.4f Hz (1.6), pieces within %.4f Hz; "
           "noise floor scatter %.2f (one periodogram %.2f)\n",
           PIECES, nw, fw[1], peak, worst, cvw, cv1);
    CHECK(nw == 2049); // pieces of 2666 samples, padded to 4096
    CHECK(fabs(peak - 1.6) < 0.5 * fw[1]);
    CHECK(worst < fw[1]);
    CHECK_MSG(cv1 > 0.8 && cvw < 0.5, "scatter %g (one periodogram %g)", cvw, cv1);
    free(fw), free(pw);
    // One piece is the periodogram itself.
    CHECK(bdl_welch_spectrum(x, N, dt, 1, 0.2, 20.0, NULL, &fw, &pw, &nw) == BDL_OK);
    CHECK(nw == n1 && pw[17] == p1[17] && fw[17] == f1[17]);
    free(fw), free(pw), free(f1), free(p1);
    CHECK(bdl_welch_spectrum(x, N, dt, 0, 0.2, 20.0, NULL, &fw, &pw, &nw) == BDL_ERR_ARGS);
    CHECK(bdl_welch_spectrum(x, 6, dt, 3, 0.2, 20.0, NULL, &fw, &pw, &nw) == BDL_ERR_ARGS);
    CHECK(fw == NULL && pw == NULL && nw == 0);
}

static void test_umf(void)
{
    // Packed branch dp = a U + b U^2 up to U_mf = 1.04 m/s where it reaches 771 Pa, then the
    // plateau with 2 % scatter; velocities 0.2 ... 2.6 m/s in steps of 0.2.
    const double umf = 1.04, weight = 771.0, b = 150.0;
    const double a = (weight - b * umf * umf) / umf;
    double u[13], dp[13];
    bdl_rng rng;
    bdl_rng_seed(&rng, 9);
    for (int k = 0; k < 13; ++k) {
        u[k] = 2.6 - 0.2 * k; // a decreasing sweep
        dp[k] = u[k] < umf ? a * u[k] + b * u[k] * u[k]
                           : weight * (1.0 + 0.02 * bdl_rng_range(&rng, -1.0, 1.0));
    }
    bdl_umf_result r = bdl_umf_from_sweep(u, dp, 13);
    printf("U_mf from a constructed sweep: %.4f m/s (1.04), plateau %.1f Pa (771), %d packed and "
           "%d fluidized points, a %.1f b %.1f\n",
           r.umf, r.plateau, r.packed, r.fluidized, r.a, r.b);
    CHECK(r.packed == 5 && r.fluidized == 8);
    CHECK_CLOSE(r.a, a, 1e-9);
    CHECK_CLOSE(r.b, b, 1e-9);
    CHECK_CLOSE(r.plateau, weight, 0.01);
    CHECK_CLOSE(r.umf, umf, 0.01); // the plateau's scatter moves it a little
}

/// The sweep of test_umf as a run's time series: 10 rows a stage 0.01 s apart, the first half of
/// each a transient (the pressure drop off by 50 Pa), the second half -2, -1, 0, 1, 2 Pa about the
/// stage's value; a stage of no gas before the sweep, which is left out.
static void test_sweep_stages(void)
{
    const double umf = 1.04, weight = 771.0, b = 150.0, a = (weight - b * umf * umf) / umf;
    enum { STAGES = 1 + 13 + 12, ROWS = 10 * STAGES };
    double t[ROWS], u[ROWS], dp[ROWS], ratio[ROWS], su[STAGES];
    for (int k = 0; k < STAGES; ++k) // 0, then 0.2 ... 2.6 m/s up, 2.4 ... 0.2 m/s down
        su[k] = k == 0 ? 0.0 : k <= 13 ? 0.2 * k : 0.2 * (26 - k);
    for (int i = 0; i < ROWS; ++i) {
        const double v = su[i / 10];
        const double p = v < umf ? a * v + b * v * v : weight;
        t[i] = 0.01 * i;
        u[i] = v;
        dp[i] = i % 10 < 5 ? p + 50.0 : p + (double)(i % 10 - 7);
        ratio[i] = dp[i] / weight;
    }
    bdl_sweep_stage st[ROWS];
    const int ns = bdl_sweep_stages(t, u, dp, ratio, ROWS, st);
    CHECK(ns == STAGES - 1);
    for (int k = 0; k < ns; ++k) {
        const double v = su[k + 1], p = v < umf ? a * v + b * v * v : weight;
        CHECK_CLOSE(st[k].u, v, 1e-15);
        CHECK_CLOSE(st[k].dp, p, 1e-12);
        CHECK_CLOSE(st[k].dp_std, sqrt(2.0), 1e-6);
        CHECK_CLOSE(st[k].ratio, p / weight, 1e-12);
        CHECK(st[k].branch == (k < 13 ? 1 : -1));
    }
    // The decreasing branch: the same fit as its stages given directly, and the plateau's
    // stages (above U_mf) carry the bed's weight.
    bdl_sweep_branch down;
    CHECK(bdl_sweep_branch_fit(st, ns, -1, &down) == BDL_OK);
    double du[12], ddp[12];
    for (int k = 0; k < 12; ++k)
        du[k] = st[13 + k].u, ddp[k] = st[13 + k].dp;
    const bdl_umf_result direct = bdl_umf_from_sweep(du, ddp, 12);
    printf("sweep stages: %d, decreasing branch %d stages, U_mf %.4f m/s (1.04), plateau ratio "
           "%.4f (1)\n",
           ns, down.stages, down.fit.umf, down.plateau_ratio);
    CHECK(down.stages == 12);
    CHECK(down.fit.umf == direct.umf && down.fit.packed == direct.packed);
    CHECK_CLOSE(down.fit.umf, umf, 1e-6);
    CHECK_CLOSE(down.plateau_ratio, 1.0, 1e-12);
    // A single stage is on the decreasing branch (nothing follows it); no stage, no fit.
    CHECK(bdl_sweep_stages(t + 20, u + 20, dp + 20, ratio + 20, 10, st) == 1);
    CHECK(st[0].branch == -1);
    CHECK(bdl_sweep_branch_fit(st, 0, 1, &down) == BDL_OK && down.stages == 0);
    CHECK(isnan(down.fit.umf) && isnan(down.plateau_ratio));
}

int main(void)
{
    test_spectrum();
    test_welch();
    test_umf();
    test_sweep_stages();
    return bdl_test_summary("test_analysis");
}
