// Hindered settling of a homogeneous suspension (Richardson & Zaki 1954): in a box periodic in
// every direction, the particles' velocity relative to the zero-volume-flux frame against the one
// the drag law implies, v = eps w with K(eps, w) w = eps (rho_p - rho) g, i.e. v / v_t = eps^n
// with n from the drag law (4.65 for Wen-Yu in creeping flow).
#include <math.h>
#include <stdio.h>

#include "check.h"
#include "verify/verify.h"

static void suspension(double phi)
{
    bdl_verify_settling s;
    bdl_result r = bdl_verify_suspension(phi, 0, &s);
    CHECK_MSG(r == BDL_OK, "phi %.2f: the run failed: %s", phi, bdl_result_text(r));
    printf("phi %.2f: settling %.5g m/s, drag law %.5g m/s (%+.2f %%); v_t %.4g m/s, "
           "Re_t %.2f, n = %.2f\n",
           phi, s.measured, s.expected, 100.0 * (s.measured / s.expected - 1.0), s.vt, s.re_t, s.n);
    CHECK_MSG(fabs(s.measured / s.expected - 1.0) < 0.05, "phi %g: %g vs %g", phi, s.measured,
              s.expected);
}

int main(void)
{
    suspension(0.1);
    suspension(0.2);
    suspension(0.3);
    return bdl_test_summary("test_settling");
}
