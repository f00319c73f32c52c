// Static overlaps in a column of spheres (MFiX DEM03-style static check:
// stacked, compressed particles).
//
// Five equal spheres stand in a perfectly aligned vertical column on a plane under gravity
// (frictionless, damped by a low restitution and background damping, so it comes to rest). At
// rest the contact below the k-th sphere from the top carries k m g:
//   linear: delta_k = k m g / k_n                          (the wall contact likewise, k = 5)
//   Hertz:  delta_k = (k m g / ((4/3) E* sqrt(R*)))^(2/3),  E* = E/(2(1 - nu^2)),
//           R* = r/2 between spheres, R* = r against the wall (same material).
// Velocity Verlet's fixed point is exact force balance, so once the motion has died the overlaps
// must match within 0.1 % (we run until the kinetic energy is below 1e-12 of m g r per sphere;
// the residual vibration is then far below 1e-4 of the overlaps). The spheres must also stay
// aligned: no lateral force arises.
#include <math.h>
#include <omp.h>
#include <stdio.h>

#include "check.h"
#include "verify/verify.h"

#define N BDL_VERIFY_COLUMN

static void column(int hertz)
{
    bdl_verify_column c = bdl_verify_static_column(hertz, 0.02);
    CHECK_MSG(c.kinetic < c.kinetic_limit, "column not at rest after %g s (KE = %g J)", c.time,
              c.kinetic);
    printf("| %s | contact | load (m g) | overlap measured (m) | theory (m) | rel. error |\n",
           hertz ? "hertz" : "linear");
    printf("|---|---|---|---|---|---|\n");
    for (int k = 0; k < N; ++k) {
        printf("| | %s | %d | %.6e | %.6e | %.1e |\n", k == 0 ? "wall - bottom" : "sphere - sphere",
               N - k, c.overlap[k], c.theory[k], fabs(c.overlap[k] - c.theory[k]) / c.theory[k]);
        CHECK_CLOSE(c.overlap[k], c.theory[k], 1e-3);
    }
    printf("\nsettled after %.3f s (%ld steps, dt = t_c/%.0f); largest lateral offset %.1e m\n\n",
           c.time, c.steps, 1.0 / c.dt_ratio, c.lateral);
    CHECK(c.lateral < 1e-12);
}

int main(void)
{
    omp_set_num_threads(1);
    printf("Static column of %d spheres on a plane: overlaps at rest\n\n", N);
    column(0);
    column(1);
    return bdl_test_summary("test_column");
}
