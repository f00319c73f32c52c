// The rods' in-plane angle histogram (analysis/rod_angles.h) on constructed rod sets with known
// answers, and its averaging over rows of a time series into PDFs.
#include <math.h>
#include <string.h>

#include "analysis/rod_angles.h"
#include "analysis/umf.h"
#include "check.h"
#include "core/rng.h"

#define MAX_RODS 72000

static bdl_vec3 pos[MAX_RODS], axis[MAX_RODS];
static double half_length[MAX_RODS], radius[MAX_RODS];

/// n rods of 12 x 3 mm (L_p = 12 mm) in the middle of a 100 mm deep domain: all bulk.
static bdl_rod_set rods(long n)
{
    for (long i = 0; i < n; ++i) {
        pos[i] = bdl_v3(0.0, 0.05, 0.1);
        half_length[i] = 4.5e-3;
        radius[i] = 1.5e-3;
    }
    return (bdl_rod_set){n, pos, axis, half_length, radius, 0.0, 0.1};
}

static long total(const long *count)
{
    long s = 0;
    for (int b = 0; b < BDL_ROD_ANGLE_BINS; ++b)
        s += count[b];
    return s;
}

static void test_angles(void)
{
    CHECK_CLOSE(bdl_rod_plane_angle(bdl_v3(0, 0, 1)), 0.0, 1e-12);
    CHECK_CLOSE(bdl_rod_plane_angle(bdl_v3(0, 0, -1)), 0.0, 1e-12);
    CHECK_CLOSE(bdl_rod_plane_angle(bdl_v3(1, 0, 0)), 90.0, 1e-12);
    CHECK_CLOSE(bdl_rod_plane_angle(bdl_v3(-1, 0, 0)), 90.0, 1e-12);
    // Leaning with its upper end to +x (the camera's right) is positive, whichever end is u.
    CHECK_CLOSE(bdl_rod_plane_angle(bdl_v3(1, 0, 1)), 45.0, 1e-12);
    CHECK_CLOSE(bdl_rod_plane_angle(bdl_v3(-1, 0, -1)), 45.0, 1e-12);
    CHECK_CLOSE(bdl_rod_plane_angle(bdl_v3(-1, 0, 1)), -45.0, 1e-12);
    CHECK_CLOSE(bdl_rod_plane_angle(bdl_v3(-0.6, 0.5, 0.8)), -36.869897645844, 1e-12); // y: none
    CHECK(bdl_rod_angle_bin(-90.0, 36) == 0);
    CHECK(bdl_rod_angle_bin(0.0, 36) == 18);
    CHECK(bdl_rod_angle_bin(-0.1, 36) == 17);
    CHECK(bdl_rod_angle_bin(89.9, 36) == 35);
    CHECK(bdl_rod_angle_bin(90.0, 36) == 35);
}

/// Upright rods (either end up) all fall in the bin starting at 0°; |cos| is 1.
static void test_upright(void)
{
    bdl_rod_set set = rods(100);
    for (long i = 0; i < 100; ++i)
        axis[i] = bdl_v3(0, 0, i % 2 ? 1.0 : -1.0);
    bdl_rod_histogram h;
    bdl_rod_histogram_of(&set, &h);
    CHECK(h.rods[BDL_ROD_ZONE_BULK] == 100 && h.rods[BDL_ROD_ZONE_WALL] == 0);
    CHECK(h.count[BDL_ROD_ZONE_BULK][BDL_ROD_ANGLE_BINS / 2] == 100);
    CHECK_CLOSE(h.abs_cos[BDL_ROD_ZONE_BULK], 1.0, 1e-15);
    CHECK(isnan(h.abs_cos[BDL_ROD_ZONE_WALL]));
}

/// Rods lying along x, exactly or tipped by 0.05° either way, are all at ±90°: in the first and
/// the last bin, none elsewhere; |cos| is (nearly) 0.
static void test_lying(void)
{
    bdl_rod_set set = rods(90);
    const double tip = 0.05 * BDL_PI / 180.0;
    for (long i = 0; i < 90; ++i) {
        const double s = i % 3 == 0 ? 0.0 : i % 3 == 1 ? tip : -tip;
        axis[i] = bdl_v3(i % 2 ? cos(s) : -cos(s), 0.0, sin(s));
    }
    bdl_rod_histogram h;
    bdl_rod_histogram_of(&set, &h);
    const long *c = h.count[BDL_ROD_ZONE_BULK];
    CHECK(c[0] + c[BDL_ROD_ANGLE_BINS - 1] == 90);
    CHECK(c[0] > 0 && c[BDL_ROD_ANGLE_BINS - 1] > 0);
    CHECK(total(c) == 90);
    CHECK(h.abs_cos[BDL_ROD_ZONE_BULK] < 1e-3);
}

/// Axes spread evenly over the sphere: the projected angle is uniform over (-90°, 90°], so each
/// of the 36 bins expects N/36 rods with standard deviation sqrt(N/36 (1 - 1/36)) = 44.1 for
/// N = 72000. Tolerances: every bin within 5 standard deviations (220 rods, 11 %), and Pearson's
/// chi^2 over the bins below 35 + 5 sqrt(70) = 76.8 (35 degrees of freedom, mean 35, sd 11.8);
/// the mean |cos| of isotropic axes is 1/2, its standard error sqrt(1/12 / N) = 0.0011, checked
/// within 0.005.
static void test_isotropic(void)
{
    const long n = MAX_RODS;
    bdl_rod_set set = rods(n);
    bdl_rng rng;
    bdl_rng_seed(&rng, 20190101);
    for (long i = 0; i < n; ++i)
        axis[i] = bdl_rng_direction(&rng);
    bdl_rod_histogram h;
    bdl_rod_histogram_of(&set, &h);
    const long *c = h.count[BDL_ROD_ZONE_BULK];
    const double expected = (double)n / BDL_ROD_ANGLE_BINS;
    const double sd = sqrt(expected * (1.0 - 1.0 / BDL_ROD_ANGLE_BINS));
    double chi2 = 0.0, worst = 0.0;
    for (int b = 0; b < BDL_ROD_ANGLE_BINS; ++b) {
        chi2 += (c[b] - expected) * (c[b] - expected) / expected;
        worst = fmax(worst, fabs(c[b] - expected) / sd);
    }
    printf("isotropic: %ld axes, chi^2 %.1f over 36 bins, largest deviation %.2f sd, mean |cos| "
           "%.5f\n",
           n, chi2, worst, h.abs_cos[BDL_ROD_ZONE_BULK]);
    CHECK(total(c) == n);
    CHECK(worst < 5.0);
    CHECK(chi2 < 35.0 + 5.0 * sqrt(70.0));
    CHECK(fabs(h.abs_cos[BDL_ROD_ZONE_BULK] - 0.5) < 0.005);
}

/// Near-wall: the centre within L_p = 12 mm of y = 0 or y = 0.1 m. Spheres are not counted.
static void test_zones(void)
{
    bdl_rod_set set = rods(7);
    const double y[7] = {0.0119, 0.0121, 0.0881, 0.0879, 0.05, 0.001, 0.05};
    for (long i = 0; i < 7; ++i) {
        pos[i].y = y[i];
        axis[i] = bdl_v3(1, 0, 0); // lying in the bins' last
    }
    axis[0] = bdl_v3(0, 0, 1);
    half_length[6] = 0.0; // a sphere in a rod scene
    bdl_rod_histogram h;
    bdl_rod_histogram_of(&set, &h);
    CHECK(h.rods[BDL_ROD_ZONE_WALL] == 3 && h.rods[BDL_ROD_ZONE_BULK] == 3);
    CHECK(h.count[BDL_ROD_ZONE_WALL][BDL_ROD_ANGLE_BINS / 2] == 1);
    CHECK(h.count[BDL_ROD_ZONE_WALL][BDL_ROD_ANGLE_BINS - 1] == 2);
    CHECK(h.count[BDL_ROD_ZONE_BULK][BDL_ROD_ANGLE_BINS - 1] == 3);
    CHECK_CLOSE(h.abs_cos[BDL_ROD_ZONE_WALL], 1.0 / 3.0, 1e-15);
    CHECK_CLOSE(h.abs_cos[BDL_ROD_ZONE_BULK], 0.0, 1e-15);
}

/// Three rows of 4 bins (45° wide); the window [0.5, 2] takes the last two. Near the wall: rows
/// (1 3 0 0) with |cos| 0.5 and (0 2 2 0) with |cos| 0.2 pool to (1 5 2 0) / 8 rods / 45°, and
/// |cos| (4 0.5 + 4 0.2) / 8 = 0.35. The bulk has no rods in the window: NAN.
static void test_pdf(void)
{
    const double time[3] = {0.0, 1.0, 2.0};
    const double wall[12] = {9, 9, 9, 9, 1, 3, 0, 0, 0, 2, 2, 0};
    const double bulk[12] = {5, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
    const double wall_cos[3] = {0.9, 0.5, 0.2}, bulk_cos[3] = {1.0, NAN, NAN};
    const bdl_rod_angle_series s = {3, 4, time, {wall, bulk}, {wall_cos, bulk_cos}};
    double p0[4], p1[4];
    double *const pdf[2] = {p0, p1};
    bdl_rod_angle_average a = bdl_rod_angle_pdf(&s, 0, 3, 0.5, 2.0, pdf);
    CHECK(a.rows == 2);
    CHECK_CLOSE(a.rods[0], 8.0, 1e-15);
    CHECK_CLOSE(a.abs_cos[0], 0.35, 1e-14);
    const double want[4] = {1.0 / 360.0, 5.0 / 360.0, 2.0 / 360.0, 0.0};
    double integral = 0.0;
    for (int b = 0; b < 4; ++b) {
        CHECK_CLOSE(p0[b], want[b], 1e-14);
        CHECK(isnan(p1[b]));
        integral += p0[b] * 45.0;
    }
    CHECK_CLOSE(integral, 1.0, 1e-14);
    CHECK(isnan(a.abs_cos[1]));
    // The whole series: the first row's bulk rods, all upright.
    a = bdl_rod_angle_pdf(&s, 0, 3, -INFINITY, INFINITY, pdf);
    CHECK(a.rows == 3 && a.rods[1] == 5.0);
    CHECK_CLOSE(p1[0], 1.0 / 45.0, 1e-14);
    CHECK_CLOSE(a.abs_cos[1], 1.0, 1e-15);
}

/// The stages of a sweep as analyze sweep takes them: rows of one velocity, the second half.
static void test_spans(void)
{
    const double t[7] = {0, 1, 2, 3, 4, 5, 6}, u[7] = {0.5, 0.5, 0.5, 1.0, 1.0, 0.5, 0.5};
    bdl_sweep_span sp;
    bdl_sweep_span_at(t, u, 7, 0, &sp);
    CHECK(sp.first == 0 && sp.end == 3 && sp.u == 0.5 && sp.from == 1.0);
    bdl_sweep_span_at(t, u, 7, sp.end, &sp);
    CHECK(sp.first == 3 && sp.end == 5 && sp.u == 1.0 && sp.from == 3.5);
    bdl_sweep_span_at(t, u, 7, sp.end, &sp);
    CHECK(sp.first == 5 && sp.end == 7 && sp.from == 5.5);
}

int main(void)
{
    test_angles();
    test_upright();
    test_lying();
    test_isotropic();
    test_zones();
    test_pdf();
    test_spans();
    return bdl_test_summary("test_rod_angles");
}
