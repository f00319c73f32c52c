// Time-averaged solids fields (analysis/fields.h, output/fields_out.h) against known answers: a
// lattice of equal spheres filling a box region gives its packing fraction in the cells inside it
// and nothing outside, every particle's volume lands on the grid, a translating lattice moves at
// its velocity, rods and parcels count their own volumes; the sums file comes back bit for bit and
// a damaged or foreign one is refused.
#define _POSIX_C_SOURCE 200809L // mkdtemp
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "check.h"
#include "scene_util.h"
#include "analysis/fields.h"
#include "core/file.h"
#include "output/fields_out.h"

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

static long size_of(const char *path)
{
    long size = -1;
    char why[256];
    bdl_check_regular_file(path, &size, why, sizeof why);
    return size;
}

/// A changed byte, a cut and a stranger's file are refused with the reason.
static void refused_sums(const char *path, const char *dir)
{
    char bad[1200], why[1400];
    size_t size = 0;
    char *data = bdl_read_file(path, &size);
    snprintf(bad, sizeof bad, "%s/bad.sums", dir);
    bdl_fields f;
    bdl_fields_stamp stamp;
    data[size / 2] ^= 0x10;
    bdl_write_file_atomic(bad, data, size);
    CHECK(bdl_fields_sums_load(&f, &stamp, bad, why, sizeof why) == BDL_ERR_CHECKPOINT);
    CHECK_MSG(strstr(why, "fails its checksum") != NULL, "%s", why);
    data[size / 2] ^= 0x10;
    bdl_write_file_atomic(bad, data, size - 9);
    CHECK(bdl_fields_sums_load(&f, &stamp, bad, why, sizeof why) == BDL_ERR_CHECKPOINT);
    CHECK_MSG(strstr(why, "is truncated") != NULL, "%s", why);
    bdl_write_file_atomic(bad, "BDLCKPT7 and more", 17);
    CHECK(bdl_fields_sums_load(&f, &stamp, bad, why, sizeof why) == BDL_ERR_CHECKPOINT);
    CHECK_MSG(strstr(why, "is not a fields.sums file") != NULL, "%s", why);
    free(data);
    unlink(bad);
}

/// The sums of a world's particles saved and loaded back bit for bit, matched against the
/// world's state; another step or setting does not match.
static void test_sums_file(void)
{
    bdl_world *w = bdl_test_world(
        "[run]\nend_time = 1\n[domain]\nmin = 0 0 0\nmax = 0.04 0.02 0.06\n"
        "[species s]\ndiameter = 0.004\ndensity = 2500\nyoungs_modulus = 1e7\nrestitution = 0.5\n"
        "[create bed]\ntype = lattice\ncount = 40\nregion_min = 0 0 0\nregion_max = 0.04 0.02 "
        "0.03\nvelocity = 0.1 0 -0.2\n[output]\nfields_interval = 0.01\n");
    CHECK_CLOSE(bdl_fields_world_cell(w), 0.012, 1e-12);
    bdl_fields f, back;
    char why[1400], dir[] = "/tmp/bedlam-fields-XXXXXX", path[1200];
    CHECK(mkdtemp(dir) != NULL);
    CHECK(bdl_fields_create_world(&f, w, bdl_fields_world_cell(w), why, sizeof why) == BDL_OK);
    CHECK(bdl_fields_add_world(&f, w) == BDL_OK && bdl_fields_add_world(&f, w) == BDL_OK);
    CHECK(f.deposited == f.total && f.particles == 80);
    const bdl_fields_stamp stamp = bdl_fields_stamp_of(w, bdl_fields_world_cell(w));
    snprintf(path, sizeof path, "%s/fields.sums", dir);
    CHECK(bdl_fields_sums_save(&f, &stamp, path) == BDL_OK);
    CHECK(size_of(path) ==
          8 + 4 + 8 + 5 * 8 + 16 + 48 + 16 + 32 + 4 * 8 * bdl_fields_cells(&f) + 4);
    bdl_fields_stamp got;
    CHECK(bdl_fields_sums_load(&back, &got, path, why, sizeof why) == BDL_OK);
    const size_t cells = (size_t)bdl_fields_cells(&f);
    CHECK(memcmp(&got, &stamp, sizeof stamp) == 0);
    CHECK(memcmp(back.n, f.n, sizeof f.n) == 0 && memcmp(back.h, f.h, sizeof f.h) == 0);
    CHECK(memcmp(back.volume, f.volume, cells * sizeof(double)) == 0);
    CHECK(memcmp(back.momentum, f.momentum, 3 * cells * sizeof(double)) == 0);
    CHECK(back.samples == 2 && back.deposited == f.deposited && back.last == f.last);
    CHECK(bdl_fields_stamp_matches(&back, &got, w, why, sizeof why));
    got.step = 7;
    CHECK(!bdl_fields_stamp_matches(&back, &got, w, why, sizeof why) && strstr(why, "step 7"));
    got.step = stamp.step;
    got.start = 0.5;
    CHECK(!bdl_fields_stamp_matches(&back, &got, w, why, sizeof why) && strstr(why, "0.5 s"));
    refused_sums(path, dir);
    snprintf(path, sizeof path, "%s/fields.vti", dir);
    CHECK(bdl_fields_vti_write(&f, path) == BDL_OK && size_of(path) > 0);
    unlink(path);
    snprintf(path, sizeof path, "%s/fields.sums", dir);
    unlink(path);
    rmdir(dir);
    bdl_fields_free(&f);
    bdl_fields_free(&back);
    bdl_world_destroy(w);
}

int main(void)
{
    test_lattice();
    test_volumes();
    test_grid();
    test_sums_file();
    return bdl_test_summary("test_fields");
}
