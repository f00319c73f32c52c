// Time-averaged solids fields (analysis/fields.h) against known answers: a lattice of equal
// spheres filling a box region gives its packing fraction in the cells inside it and nothing
// outside, every particle's volume lands on the grid, a translating lattice moves at its velocity,
// rods and parcels count their own volumes.
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "check.h"
#include "analysis/fields.h"

enum { NX = 10, NY = 10, NZ = 15, COUNT = NX * NY * NZ };
static const double spacing = 0.01, radius = 0.004;
static const double lo[3] = {0, 0, 0}, hi[3] = {0.2, 0.1, 0.3}, cell = 0.05;

/// A simple cubic lattice of COUNT spheres filling [0, 0.1] x [0, 0.1] x [0, 0.15], all moving
/// at `v`.
static void lattice(double *pos, double *vel, double *rad, const double v[3])
{
    long i = 0;
    for (int k = 0; k < NZ; ++k)
        for (int j = 0; j < NY; ++j)
            for (int m = 0; m < NX; ++m, ++i) {
                pos[3 * i] = (m + 0.5) * spacing;
                pos[3 * i + 1] = (j + 0.5) * spacing;
                pos[3 * i + 2] = (k + 0.5) * spacing;
                for (int a = 0; a < 3; ++a)
                    vel[3 * i + a] = v[a];
                rad[i] = radius;
            }
}

/// The translating lattice, three samples: 125 spheres in each cell inside the region, the packing
/// fraction there and the lattice's velocity; nothing outside (velocity NaN); every particle's
/// volume on the grid.
static void test_lattice(void)
{
    static double pos[3 * COUNT], vel[3 * COUNT], rad[COUNT];
    const double v[3] = {0.3, -0.2, 1.5};
    lattice(pos, vel, rad, v);
    bdl_fields f;
    CHECK(bdl_fields_create(&f, lo, hi, cell, 1e6) == BDL_OK);
    CHECK(f.n[0] == 4 && f.n[1] == 2 && f.n[2] == 6);
    for (int s = 0; s < 3; ++s)
        bdl_fields_add(&f, &(bdl_fields_sample){0.1 * s, COUNT, pos, vel, rad, NULL, NULL});
    CHECK(f.samples == 3 && f.particles == 3L * COUNT && f.first == 0.0 && f.last == 0.2);
    const double sphere = 4.0 / 3.0 * BDL_PI * radius * radius * radius;
    CHECK_CLOSE(f.total, 3.0 * COUNT * sphere, 1e-13);
    CHECK(f.deposited == f.total);
    const long cells = bdl_fields_cells(&f);
    double *phi = malloc((size_t)cells * sizeof(double));
    double *u = malloc((size_t)cells * 3 * sizeof(double));
    bdl_fields_means(&f, phi, u);
    const double packed = 125.0 * sphere / (cell * cell * cell); // pi / 6 (2 r / spacing)^3
    CHECK_CLOSE(packed, BDL_PI / 6.0 * pow(2.0 * radius / spacing, 3), 1e-14);
    double summed = 0.0;
    for (long c = 0; c < cells; ++c) {
        const int i = (int)(c % 4), k = (int)(c / 8); // 4 x 2 x 6 cells, x fastest
        const int inside = i < 2 && k < 3;
        CHECK_CLOSE(phi[c], inside ? packed : 0.0, 1e-13);
        for (int a = 0; a < 3; ++a)
            CHECK(inside ? fabs(u[3 * c + a] - v[a]) <= 1e-14 * fabs(v[a]) : isnan(u[3 * c + a]));
        summed += f.volume[c];
    }
    CHECK_CLOSE(summed, f.total, 1e-13);
    free(phi);
    free(u);
    bdl_fields_free(&f);
}

/// Rods (tip-to-tip lengths) and parcels (counts) deposit their own volumes; a centre outside the
/// grid (or on its upper face) is counted in the total only.
static void test_volumes(void)
{
    const double r = 0.00075, L = 0.006;
    CHECK_CLOSE(bdl_fields_volume(r, L),
                BDL_PI * r * r * (L - 2 * r) + 4.0 / 3.0 * BDL_PI * r * r * r, 1e-15);
    CHECK(bdl_fields_volume(r, 0.0) == bdl_fields_volume(r, 2 * r));
    bdl_fields f;
    CHECK(bdl_fields_create(&f, lo, hi, cell, 1e6) == BDL_OK);
    const double pos[9] = {0.01, 0.01, 0.01, 0.01, 0.01, 0.01, 0.2, 0.05, 0.05};
    const double vel[9] = {1, 0, 0, 0, 0, 2, 5, 5, 5};
    const double rad[3] = {r, r, r}, length[3] = {L, 2 * r, L}, count[3] = {1, 1000, 1};
    bdl_fields_add(&f, &(bdl_fields_sample){0, 3, pos, vel, rad, length, count});
    const double rod = bdl_fields_volume(r, L), parcel = 1000 * bdl_fields_volume(r, 0);
    CHECK_CLOSE(f.volume[0], rod + parcel, 1e-14);
    CHECK_CLOSE(f.momentum[0], rod, 1e-14);
    CHECK_CLOSE(f.momentum[2], 2 * parcel, 1e-14);
    CHECK_CLOSE(f.deposited, rod + parcel, 1e-14);
    CHECK_CLOSE(f.total, 2 * rod + parcel, 1e-14);
    bdl_fields_free(&f);
}

/// Whole cells per axis, at least one; too many cells and no cell refused.
static void test_grid(void)
{
    int n[3];
    double h[3];
    const double box_hi[3] = {0.1, 0.0045, 0.3};
    CHECK(bdl_fields_grid(lo, box_hi, 0.03, n, h) == 3.0 * 1 * 10);
    CHECK(n[0] == 3 && n[1] == 1 && n[2] == 10);
    CHECK_CLOSE(h[0], 0.1 / 3, 1e-15);
    CHECK(h[1] == 0.0045 && h[2] == 0.03);
    bdl_fields f;
    CHECK(bdl_fields_create(&f, lo, box_hi, 1e-5, 5e7) == BDL_ERR_ARGS && !f.volume);
    CHECK(bdl_fields_create(&f, lo, box_hi, 0.0, 5e7) == BDL_ERR_ARGS);
    CHECK(bdl_fields_create(&f, lo, box_hi, NAN, 5e7) == BDL_ERR_ARGS);
}

int main(void)
{
    test_lattice();
    test_volumes();
    test_grid();
    return bdl_test_summary("test_fields");
}
