// The thesis's small bed of rods packed under gravity (Mahajan 2019, table 4.1; the bed of
// scenes/rod_bed_packed.ini): 8070 rods of 6 x 1.5 mm dropped with random axes into a column
// 0.1 x 0.014 m settle to the thesis's simulated packed height, 0.106 m within 5 %, and lie
// mostly flat. Slow (about 4 minutes on one core): label slow, run by `bedlam verify rod_bed`
// and `ctest -L slow`.
#include <math.h>
#include <stdio.h>

#include "check.h"
#include "verify/verify.h"

int main(void)
{
    bdl_verify_rod_bed b;
    CHECK(bdl_verify_rod_bed_run(0.05, &b) == BDL_OK);
    printf("rod bed: height %.4f m (thesis 0.106), solids fraction %.3f, %.2f s simulated in %ld "
           "steps, kinetic energy %.1e m g d per rod\n",
           b.height, b.bulk, b.time, b.steps, b.kinetic);
    printf("orientation: <|cos|> to the vertical %.3f (isotropic 0.5), nematic S %.3f\n",
           b.vertical_cos, b.order);
    printf("angle to the horizontal  share of the rods (isotropic)\n");
    for (int k = 0; k < BDL_VERIFY_TILT_BINS; ++k) {
        const double a = k * 10.0 * 3.14159265358979323846 / 180.0,
                     c = (k + 1) * 10.0 * 3.14159265358979323846 / 180.0;
        printf("  %2d-%2d deg               %.3f  (%.3f)\n", 10 * k, 10 * k + 10, b.tilt[k],
               sin(c) - sin(a));
    }
    CHECK(b.kinetic < 1e-6);                    // settled
    CHECK(fabs(b.height / 0.106 - 1.0) < 0.05); // the band
    // Mostly flat: more rods within 30 degrees of the horizontal than the half an isotropic set
    // has there, and the mean |cos| to the vertical well under the isotropic 1/2.
    const double flat = b.tilt[0] + b.tilt[1] + b.tilt[2];
    printf("within 30 degrees of the horizontal: %.3f (isotropic 0.500)\n", flat);
    CHECK(flat > 0.6);
    CHECK(b.vertical_cos < 0.4);
    return bdl_test_summary("test_rod_bed");
}
