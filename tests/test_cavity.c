// Lid-driven cavity at Re = 100 against Ghia, Ghia & Shin (1982), J. Comput. Phys. 48,
// 387-411, table I (u on the vertical centreline) and table II (v on the horizontal one).
// Usage: test_cavity [cells per side, default 64] [scheme: central|vanleer|superbee]
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cfd/gas.h"
#include "check.h"
#include "verify/verify.h"

int main(int argc, char **argv)
{
    const int n = argc > 1 ? atoi(argv[1]) : 64;
    bdl_convection scheme = BDL_CONVECTION_CENTRAL;
    if (argc > 2 && strcmp(argv[2], "vanleer") == 0)
        scheme = BDL_CONVECTION_VANLEER;
    if (argc > 2 && strcmp(argv[2], "superbee") == 0)
        scheme = BDL_CONVECTION_SUPERBEE;
    double worst_u = 1.0, worst_v = 1.0;
    double worst = bdl_verify_cavity(n, (int)scheme, &worst_u, &worst_v, 1, NULL);
    CHECK_MSG(worst >= 0.0, "the cavity did not reach a steady state");
    printf("largest difference: u %.4f, v %.4f (lid velocity 1)\n", worst_u, worst_v);
    CHECK_MSG(worst_u < 0.02, "u differs from Ghia by %g", worst_u);
    CHECK_MSG(worst_v < 0.02, "v differs from Ghia by %g", worst_v);
    return bdl_test_summary("test_cavity");
}
