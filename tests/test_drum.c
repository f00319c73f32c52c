// A rotating drum in the rolling regime (bdl_verify_drum_repose; scenes/rotating_drum.ini):
// 2600 glass beads of 3 mm fill 39 % of a drum of 100 mm, periodic along its axis. Asserted, as
// the rolling regime's known trends (Mellmann 2001; Yang et al. 2003): the dynamic angle of
// repose rises with the beads' friction (0.3 -> 0.6 at 1 rad/s) and with the rate (1 -> 3 rad/s
// at friction 0.6), lies in the 20-40 degree range of glass beads, and the drum's wall drives the
// bed without slip: the beads meet the wall at its speed (ratio within 5 % of 1).
#include <math.h>
#include <stdio.h>

#include "check.h"
#include "verify/verify.h"

int main(void)
{
    const double mu[3] = {0.3, 0.6, 0.6}, omega[3] = {1.0, 1.0, 3.0};
    bdl_verify_drum d[3];
    printf("| bead friction | rate (rad/s) | Froude w^2 R / g | angle (deg) | sd | carried at the "
           "wall |\n|---|---|---|---|---|---|\n");
    for (int k = 0; k < 3; ++k) {
        CHECK(bdl_verify_drum_repose(mu[k], omega[k], &d[k]) == BDL_OK);
        printf("| %.1f | %.0f | %.4f | %.2f | %.2f | %.3f |\n", mu[k], omega[k],
               omega[k] * omega[k] * 0.05 / 9.81, d[k].angle, d[k].angle_sd, d[k].carried);
        CHECK(d[k].angle > 20.0 && d[k].angle < 40.0);
        CHECK(fabs(d[k].carried - 1.0) < 0.05);
    }
    CHECK_MSG(d[1].angle > d[0].angle + 1.0, "friction 0.3 -> 0.6: %.2f -> %.2f degrees",
              d[0].angle, d[1].angle);
    CHECK_MSG(d[2].angle > d[1].angle + 1.0, "1 -> 3 rad/s: %.2f -> %.2f degrees", d[1].angle,
              d[2].angle);
    return bdl_test_summary("test_drum");
}
