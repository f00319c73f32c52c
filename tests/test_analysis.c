// Analyses on constructed inputs with known answers: the dominant frequency of a noisy sinusoid,
// the spectrum's normalisation (Parseval), and U_mf from a sweep built from Ergun's packed
// branch and a flat fluidized plateau.
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

int main(void)
{
    test_spectrum();
    test_umf();
    return bdl_test_summary("test_analysis");
}
