// Duration of an elastic Hertz contact against Hertz theory (Johnson, Contact Mechanics, 1985):
//
//   t_c = 2.8683 (m*^2 / (R* E*^2 v))^(1/5)     (often rounded to 2.87)
//
// e = 1 (no damping), gravity off. A sphere hits a plane of the same material (m* = m, R* = r,
// E* = E/(2(1 - nu^2))) at 0.1 and 1 m/s, and two equal spheres collide head-on at relative speed
// 0.1 and 1 m/s (m* = m/2, R* = r/2, same E*). The contact starts and ends between steps: both
// instants are found by linear interpolation of the gap between the two steps that bracket them
// (dt = t_c/1000, so the interpolation error is far below the tolerance), and the duration must
// agree with the formula within 2 %. The rebound speed must equal the impact speed (e = 1).
#include <math.h>
#include <omp.h>
#include <stdio.h>

#include "check.h"
#include "verify/verify.h"

int main(void)
{
    omp_set_num_threads(1);
    printf("Hertz contact duration, e = 1 (dt = t_c/1000, start and end interpolated)\n\n");
    printf("| contact | v (m/s) | t_c theory (s) | t_c measured (s) | rel. error | rebound/impact "
           "speed |\n");
    printf("|---|---|---|---|---|---|\n");
    for (int pair = 0; pair <= 1; ++pair)
        for (int iv = 0; iv < 2; ++iv) {
            double v = iv == 0 ? 0.1 : 1.0;
            double ref = bdl_verify_hertz_time(pair, v);
            double rebound = 0.0;
            double tc = bdl_verify_hertz_duration(pair, v, ref / 1000.0, &rebound, NULL);
            printf("| %s | %.1f | %.5e | %.5e | %.2e | %.6f |\n",
                   pair ? "sphere-sphere" : "sphere-wall", v, ref, tc, fabs(tc - ref) / ref,
                   rebound);
            CHECK_CLOSE(tc, ref, 0.02);
            CHECK_CLOSE(rebound, 1.0, 1e-3);
        }
    // Second order in dt against the exact constant (bdl_verify_hertz_time uses 2.8683).
    double e[3], n[3] = {50, 100, 200};
    for (int k = 0; k < 3; ++k) {
        double ref = bdl_verify_hertz_time(0, 1.0), rebound;
        e[k] = fabs(bdl_verify_hertz_duration(0, 1.0, ref / n[k], &rebound, NULL) - ref) / ref;
    }
    double order = bdl_verify_order(n[1], e[1], n[2], e[2]);
    printf("\nerror at t_c/50, /100, /200: %.2e %.2e %.2e, order %.2f\n", e[0], e[1], e[2], order);
    CHECK_MSG(order > 1.8 && order < 2.2, "observed order %.2f", order);
    return bdl_test_summary("test_hertz_duration");
}
