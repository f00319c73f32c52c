// Janssen's silo (bdl_verify_janssen_silo; scenes/silo_janssen.ini): beds of 1500 to 15 000
// glass beads (fill heights 1.4 to 14 radii) settled in a cylinder 40 mm across, the floor then
// lowered slowly (5 mm/s) through the measurement so that the beads slide down the wall and its
// friction carries part of the weight. Asserted: the floor's load, as a share of the weight,
// falls with the fill height and saturates (each of the two tallest beds adds less than a tenth
// of its extra weight to the floor); and the floor's load agrees within 15 % with Janssen's
// rho_b g A lambda (1 - exp(-H / lambda)), lambda = R / (2 mu K), for the K and the wall
// friction mu the beds mobilise (both measured in the middle half of each bed; with the wall's
// friction coefficient 0.5 in place of the mobilised friction Janssen's load is printed beside).
#include <math.h>
#include <stdio.h>

#include "check.h"
#include "verify/verify.h"

#define FILLS 5

int main(void)
{
    const long count[FILLS] = {1500, 3000, 6000, 10000, 15000};
    bdl_verify_janssen j[FILLS];
    printf(
        "| beads | H (mm) | rho_b | K | mobilised mu | floor / weight | Janssen (K, mobilised "
        "mu) | floor / Janssen | Janssen (K, mu = 0.5) |\n|---|---|---|---|---|---|---|---|---|\n");
    for (int k = 0; k < FILLS; ++k)
        CHECK(bdl_verify_janssen_silo(count[k], &j[k]) == BDL_OK);
    for (int k = 0; k < FILLS; ++k) {
        // A bed under 8 diameters has no middle slabs to measure K in: the next bed's K and mu.
        const bdl_verify_janssen *m = isnan(j[k].k) && k + 1 < FILLS ? &j[k + 1] : &j[k];
        const double jm =
            bdl_verify_janssen_mass(j[k].bulk_density, 0.02, m->mobilised, m->k, j[k].height);
        const double j5 = bdl_verify_janssen_mass(j[k].bulk_density, 0.02, 0.5, m->k, j[k].height);
        printf("| %ld | %.1f | %.0f | %.3f | %.3f | %.3f | %.3f | %.3f | %.3f |\n", count[k],
               1000.0 * j[k].height, j[k].bulk_density, m->k, m->mobilised,
               j[k].floor_mass / j[k].fill_mass, jm / j[k].fill_mass, j[k].floor_mass / jm,
               j5 / j[k].fill_mass);
        CHECK_MSG(fabs(j[k].floor_mass / jm - 1.0) < 0.15, "%ld beads: floor %.4g kg, Janssen %.4g",
                  count[k], j[k].floor_mass, jm);
        if (k > 0)
            CHECK(j[k].floor_mass / j[k].fill_mass < j[k - 1].floor_mass / j[k - 1].fill_mass);
    }
    for (int k = 3; k < FILLS; ++k) {
        const double extra =
            (j[k].floor_mass - j[k - 1].floor_mass) / (j[k].fill_mass - j[k - 1].fill_mass);
        printf("floor's share of the weight added from %ld to %ld beads: %.3f\n", count[k - 1],
               count[k], extra);
        CHECK(extra < 0.1);
    }
    return bdl_test_summary("test_janssen");
}
