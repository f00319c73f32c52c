// Time series of a run on constructed inputs with known answers: the rows of a time window, the
// statistics of the samples in it (non-finite ones left out), block means (exact on a staircase,
// the known standard error of independent samples, and the larger one of correlated samples that
// sd/sqrt(n) misses), and a sine and a cosine folded over their period: the phase curve, the
// range over cycles, the intervals below a threshold and the slack at a cycle's start.
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "analysis/phase.h"
#include "analysis/series.h"
#include "check.h"
#include "core/rng.h"
#include "core/vec3.h"

static void test_time_window(void)
{
    double t[12];
    for (int i = 0; i < 12; ++i)
        t[i] = 0.25 * i; // exact in binary: the window's edges are met exactly
    bdl_time_window w = bdl_time_window_of(t, 12, 1.0, 2.0);
    CHECK(w.first == 4 && w.count == 5);
    CHECK(w.dt == 0.25);
    w = bdl_time_window_of(t, 12, -INFINITY, INFINITY);
    CHECK(w.first == 0 && w.count == 12 && w.dt == 0.25);
    w = bdl_time_window_of(t, 12, 1.1, 1.4); // one row: no spacing
    CHECK(w.first == 5 && w.count == 1 && isnan(w.dt));
    w = bdl_time_window_of(t, 12, 5.0, 9.0); // after the end
    CHECK(w.first == 12 && w.count == 0);
    w = bdl_time_window_of(t, 12, 2.0, 1.0); // empty
    CHECK(w.count == 0);
}

static void test_sample_stats(void)
{
    const double t[] = {0, 1, 2, 3, 4, 5, 6};
    const double x[] = {NAN, 1, 2, 3, 4, INFINITY, 5};
    bdl_sample_stats s = bdl_sample_stats_in(t, x, 7, -INFINITY, INFINITY);
    CHECK(s.count == 5 && s.first == 1 && s.last == 6);
    CHECK_CLOSE(s.mean, 3.0, 1e-15);
    CHECK_CLOSE(s.sd, sqrt(2.0), 1e-15);
    CHECK(s.min == 1.0 && s.max == 5.0);
    s = bdl_sample_stats_in(t, x, 7, 2.0, 4.5);
    CHECK(s.count == 3 && s.first == 2 && s.last == 4);
    CHECK_CLOSE(s.mean, 3.0, 1e-15);
    CHECK_CLOSE(s.sd, sqrt(2.0 / 3.0), 1e-15);
    s = bdl_sample_stats_in(t, x, 7, 4.5, 5.5); // only the infinite sample
    CHECK(s.count == 0 && s.first == -1 && s.last == -1 && isnan(s.mean));
}

static void test_block_mean_exact(void)
{
    // A staircase: rows 2b and 2b+1 hold b, so the ten block means are 0..9 about 4.5.
    double t[23], x[23];
    for (int i = 0; i < 23; ++i)
        t[i] = i, x[i] = i / 2;
    bdl_block_mean m = bdl_block_mean_in(t, x, 20, -INFINITY, INFINITY, 10);
    CHECK(m.samples.count == 20);
    CHECK_CLOSE(m.samples.mean, 4.5, 1e-15);
    CHECK_CLOSE(m.standard_error, sqrt(82.5 / 9.0) / sqrt(10.0), 1e-14);
    // 23 rows: blocks of two, the last takes rows 18 to 22 (mean 20 of x = i).
    for (int i = 0; i < 23; ++i)
        x[i] = i;
    m = bdl_block_mean_in(t, x, 23, -INFINITY, INFINITY, 10);
    double scatter = 0.0;
    for (int b = 0; b < 10; ++b) {
        const double bm = b < 9 ? 2.0 * b + 0.5 : 20.0;
        scatter += (bm - 11.0) * (bm - 11.0);
    }
    CHECK_CLOSE(m.samples.mean, 11.0, 1e-15);
    CHECK_CLOSE(m.standard_error, sqrt(scatter / 9.0) / sqrt(10.0), 1e-14);
    m = bdl_block_mean_in(t, x, 23, 30.0, 40.0, 10); // no samples
    CHECK(m.samples.count == 0 && isnan(m.standard_error));
}

/// The mean over `replicas` series of n samples of the squared standard error from 10 blocks, and
/// of sd^2/n. phi: the AR(1) coefficient (0: independent samples), unit variance either way.
static void block_variance(double phi, long n, int replicas, double *se2, double *naive2)
{
    double *t = malloc((size_t)n * sizeof(double)), *x = malloc((size_t)n * sizeof(double));
    bdl_rng rng;
    bdl_rng_seed(&rng, 21);
    *se2 = *naive2 = 0.0;
    for (int r = 0; r < replicas && t && x; ++r) {
        double v = bdl_rng_normal(&rng);
        for (long i = 0; i < n; ++i) {
            t[i] = (double)i;
            x[i] = v;
            v = phi * v + sqrt(1.0 - phi * phi) * bdl_rng_normal(&rng);
        }
        const bdl_block_mean m = bdl_block_mean_in(t, x, n, -INFINITY, INFINITY, 10);
        *se2 += m.standard_error * m.standard_error / replicas;
        *naive2 += m.samples.sd * m.samples.sd / (double)n / replicas;
    }
    free(t), free(x);
}

static void test_block_mean_statistics(void)
{
    // Independent unit normals: Var(mean) = 1/n, which the block estimate gives without bias
    // (its scatter over 400 replicas: sqrt(2/9)/20, about 2 %).
    double se2, naive2;
    block_variance(0.0, 1000, 400, &se2, &naive2);
    printf("block means, independent samples: <se^2> n = %.4f (1), <sd^2/n> n = %.4f (1)\n",
           se2 * 1000, naive2 * 1000);
    CHECK_CLOSE(se2, 1.0 / 1000, 0.1);
    CHECK_CLOSE(naive2, 1.0 / 1000, 0.02);
    // AR(1) with phi = 0.9 (correlation time about 10 rows, blocks of 1000): Var(mean) =
    // (1 + phi)/(1 - phi)/n = 19/n, which sd^2/n misses by that factor.
    block_variance(0.9, 10000, 200, &se2, &naive2);
    printf("block means, AR(1) phi 0.9: <se^2> n = %.3f (19), <sd^2/n> n = %.3f (1)\n", se2 * 10000,
           naive2 * 10000);
    CHECK_CLOSE(se2, 19.0 / 10000, 0.15);
    CHECK_CLOSE(naive2, 1.0 / 10000, 0.05);
}

static void test_phase_fold(void)
{
    // One sample at each bin's centre phase in cycles 0..11 of a sine of period 0.2 s starting
    // at t = 0.3 s; odd cycles are lifted by 0.1. Folded over cycles 2..9.
    enum { BINS = 10, CYCLES = 12, N = BINS * CYCLES + 5 };
    const double period = 0.2, start = 0.3;
    double t[N], x[N];
    for (int i = 0; i < BINS * CYCLES; ++i) {
        const int cycle = i / BINS, b = i % BINS;
        t[i] = start + period * (cycle + (b + 0.5) / BINS);
        x[i] = sin(2.0 * BDL_PI * (b + 0.5) / BINS) + 0.1 * (cycle % 2);
    }
    for (int i = BINS * CYCLES; i < N; ++i) // after the cycles asked for
        t[i] = start + period * (CYCLES + 1), x[i] = 100.0;
    const bdl_phase_def def = {period, start, 2, 10, BINS};
    bdl_phase_fold f;
    CHECK(bdl_phase_fold_of(t, x, N, &def, &f) == BDL_OK);
    CHECK(f.used == 8 * BINS && f.first_cycle == 2 && f.last_cycle == 9);
    for (int b = 0; b < BINS; ++b) {
        const double s = sin(2.0 * BDL_PI * (b + 0.5) / BINS);
        CHECK(f.count[b] == 8);
        CHECK_CLOSE(f.mean[b], s + 0.05, 1e-12);
        CHECK_CLOSE(f.min[b], s, 1e-12);
        CHECK_CLOSE(f.max[b], s + 0.1, 1e-12);
    }
    const bdl_phase_extremes e = bdl_phase_fold_extremes(&f);
    CHECK(e.at_largest == 2 && e.at_smallest == 7); // phases 0.25 and 0.75
    CHECK_CLOSE(e.largest, 1.05, 1e-12);
    CHECK_CLOSE(e.smallest, -0.95, 1e-12);
    int start_bin[BINS], end_bin[BINS];
    // sin(2 pi phase) + 0.05 < -0.5 + 0.05 from phase 7/12 to 11/12: the bins 0.6-0.9.
    int runs = bdl_phase_runs_below(&f, -0.45, start_bin, end_bin, BINS);
    CHECK(runs == 1 && start_bin[0] == 6 && end_bin[0] == 9);
    bdl_phase_fold_free(&f);
    // A cosine turned over is below -0.5 around phase 0: two runs, the second up to the end.
    for (int i = 0; i < BINS * CYCLES; ++i)
        x[i] = -cos(2.0 * BDL_PI * (i % BINS + 0.5) / BINS);
    CHECK(bdl_phase_fold_of(t, x, N, &def, &f) == BDL_OK);
    runs = bdl_phase_runs_below(&f, -0.5, start_bin, end_bin, BINS);
    CHECK(runs == 2 && start_bin[0] == 0 && end_bin[0] == 2);
    CHECK(start_bin[1] == 8 && end_bin[1] == BINS);
    CHECK(bdl_phase_runs_below(&f, -0.5, start_bin, end_bin, 1) == 1); // room for one
    bdl_phase_fold_free(&f);
}

static void test_phase_edges(void)
{
    // (0.7 - 0.1)/0.2 is 2.9999999999999996 in floating point: the sample taken at the start of
    // cycle 3 belongs to its first bin, not to the last bin of cycle 2.
    const double t[] = {0.05, 0.7, 0.75};
    const double x[] = {9.0, 1.0, NAN};
    const bdl_phase_def def = {0.2, 0.1, 0, 1L << 40, 4};
    bdl_phase_fold f;
    CHECK(bdl_phase_fold_of(t, x, 3, &def, &f) == BDL_OK);
    CHECK(f.used == 1 && f.first_cycle == 3 && f.last_cycle == 3); // before the start; NAN
    CHECK(f.count[0] == 1 && f.mean[0] == 1.0);
    CHECK(f.count[3] == 0 && isnan(f.mean[3]) && f.min[3] == INFINITY && f.max[3] == -INFINITY);
    int s[4], e[4];
    CHECK(bdl_phase_runs_below(&f, 10.0, s, e, 4) == 1 && s[0] == 0 && e[0] == 1); // empty: not
    bdl_phase_fold_free(&f);
}

int main(void)
{
    test_time_window();
    test_sample_stats();
    test_block_mean_exact();
    test_block_mean_statistics();
    test_phase_fold();
    test_phase_edges();
    return bdl_test_summary("test_series");
}
