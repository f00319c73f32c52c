// The two-fluid model's verification cases (src/verify/verify_tfm.c), asserted as `bedlam
// verify` reports them: a homogeneous cooling state against Haff's law with its first order in
// the time step, and a settling column against Kynch's theory with its order, which then packs
// at Schaeffer's fraction for its weight without overshoot, no fraction below zero as the
// suspension's cells empty and none above packing where the sediment forms.
#include <math.h>
#include <stdio.h>

#include "check.h"
#include "solids/phase.h"
#include "verify/verify.h"

static void test_cooling(void)
{
    double err[3];
    long steps = 0;
    for (int m = 0; m < 3; ++m) {
        CHECK(bdl_verify_tfm_cooling(10 << m, &err[m], &steps) == BDL_OK);
        printf("cooling, %d steps per tau: |theta/theta_Haff - 1| = %.4e\n", 10 << m, err[m]);
    }
    const double order = log2(err[1] / err[2]);
    printf("cooling: observed order %.3f\n", order);
    CHECK(err[2] < 0.03);
    CHECK(order > 0.95 && order < 1.05);
    // The time scale from Lun et al.'s dissipation by hand: e 0.97, eps 0.3, g0 2.478, 2.49 mm,
    // 2526 kg/m^3, theta0 0.01 m^2/s^2.
    const bdl_solids_def sd = bdl_default_solids_def();
    CHECK_CLOSE(bdl_verify_tfm_cooling_time(0.3, 0.01, &sd), 0.25112, 1e-4);
}

static void test_settling(void)
{
    double err[3];
    for (int m = 0; m < 3; ++m) {
        const int cells = 40 << m;
        bdl_verify_sediment s;
        CHECK(bdl_verify_tfm_settling(cells, &s) == BDL_OK);
        err[m] = fabs(s.interface - s.expected) / (0.1 - s.expected);
        printf("settling, %d cells, %ld steps: top %.5f m (Kynch %.5f), relative error %.3e; "
               "fraction %.3g to %.5f, bed %.5f (Schaeffer %.5f), drift %.1e, speed %.2e m/s\n",
               cells, s.steps, s.interface, s.expected, err[m], s.eps_low, s.eps_peak, s.eps_bed,
               s.eps_bed_expected, s.volume_drift, s.speed_end);
        CHECK(s.eps_low >= 0.0);
        CHECK(s.eps_peak < s.eps_bed_expected + 2e-3); // the impact compacts a little, briefly
        CHECK(fabs(s.eps_bed - s.eps_bed_expected) < 5e-4);
        CHECK(fabs(s.volume_drift) < 1e-12);
    }
    const double order = log2(err[1] / err[2]);
    printf("settling: observed order %.3f\n", order);
    CHECK(err[2] < 0.02);
    CHECK(order > 0.8);
}

int main(void)
{
    test_cooling();
    test_settling();
    return bdl_test_summary("test_tfm_verify");
}
