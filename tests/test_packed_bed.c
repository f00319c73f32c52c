// A packed bed below minimum fluidization: the pressure gradient through its interior follows the
// Ergun equation at the bed's local voidage, at three superficial velocities.
#include <math.h>
#include <stdio.h>

#include "check.h"
#include "verify/verify.h"

int main(void)
{
    const double velocities[3] = {0.3, 0.6, 0.9}; // U_mf of these beads is about 1.1 m/s
    double ratio[3], eps[3];
    bdl_result r = bdl_verify_packed_bed(25, velocities, 3, ratio, eps, NULL);
    CHECK_MSG(r == BDL_OK, "the packed bed run failed: %s", bdl_result_text(r));
    if (r != BDL_OK)
        return bdl_test_summary("test_packed_bed");
    printf("   U [m/s]  mean eps  -dp/dz measured / Ergun\n");
    for (int v = 0; v < 3; ++v) {
        printf("   %.1f      %.3f     %.4f\n", velocities[v], eps[v], ratio[v]);
        CHECK_MSG(fabs(ratio[v] - 1.0) < 0.03, "U = %g: pressure gradient %.4f of Ergun",
                  velocities[v], ratio[v]);
    }
    return bdl_test_summary("test_packed_bed");
}
