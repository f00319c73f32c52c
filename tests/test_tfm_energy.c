// The granular energy's transport equation (solids/energy.h) against a manufactured solution
// (verify/verify_tfm.c, `bedlam verify tfm_energy`): solids at rest in a layer periodic along x,
// two cells of 1 cm between walls with Johnson & Jackson's energy flux, with the fraction eps(x) =
// 0.3 + 0.05 sin(2 pi x / L) and the temperature theta(x) = C / (eps^2 g0(eps)), which keeps
// Syamlal's pressure the same everywhere (the solids stay at rest), steady under the source that
// balances its collisions, its walls' dissipation and its conduction. The errors on four grids show
// the conduction's second order.
#include <math.h>
#include <stdio.h>

#include "check.h"
#include "verify/verify.h"

int main(void)
{
    const int cells[4] = {8, 16, 32, 64};
    double err[4];
    for (int g = 0; g < 4; ++g) {
        bdl_verify_energy e;
        CHECK(bdl_verify_tfm_energy(cells[g], &e) == BDL_OK);
        printf("%3d cells: largest relative error of theta %.3e (solids moved at most %.2e m/s; "
               "the conduction up to %.2f of the source)\n",
               cells[g], e.error, e.speed, e.conduction_share);
        CHECK(e.conduction_share > 0.1); // the conduction matters to the balance
        CHECK(e.speed < 1e-3);           // the solids stay (nearly) at rest
        err[g] = e.error;
    }
    printf("observed orders %.2f, %.2f, %.2f\n", log2(err[0] / err[1]), log2(err[1] / err[2]),
           log2(err[2] / err[3]));
    CHECK(err[3] < 4e-4);
    const double order = log2(err[2] / err[3]);
    CHECK(order > 1.8 && order < 2.2);
    return bdl_test_summary("test_tfm_energy");
}
