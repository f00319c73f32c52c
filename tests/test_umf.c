// Minimum fluidization velocity from a velocity sweep, as in the laboratory: fluidize a bed, lower
// the gas velocity step by step, and find where the packed-bed pressure drop (Ergun's a U + b U^2
// at low velocity) meets the bed's weight. (The narrow periodic column slugs when fluidized, so
// the pressure drop above U_mf fluctuates by tens of per cent; the packed branch does not.)
// Compared with Wen & Yu (1966), Re_mf = sqrt(33.7^2 + 0.0408 Ar) - 33.7, for the same beads.
#include <math.h>
#include <stdio.h>

#include "check.h"
#include "verify/verify.h"

int main(void)
{
    double umf_down = 0.0, umf_up = 0.0, wen_yu = 1.0;
    bdl_result r = bdl_verify_umf(0.08, &umf_down, &umf_up, &wen_yu, 1, NULL);
    CHECK_MSG(r == BDL_OK, "the sweep failed: %s", bdl_result_text(r));
    printf("U_mf from the decreasing sweep %.3f m/s (%+.1f %%), from the increasing sweep %.3f m/s "
           "(%+.1f %%); Wen-Yu %.3f m/s\n",
           umf_down, 100.0 * (umf_down / wen_yu - 1.0), umf_up, 100.0 * (umf_up / wen_yu - 1.0),
           wen_yu);
    CHECK_MSG(fabs(umf_down / wen_yu - 1.0) < 0.1, "U_mf down %g vs Wen-Yu %g", umf_down, wen_yu);
    CHECK_MSG(fabs(umf_up / wen_yu - 1.0) < 0.1, "U_mf up %g vs Wen-Yu %g", umf_up, wen_yu);
    return bdl_test_summary("test_umf");
}
