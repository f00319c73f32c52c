// Orientation of wall-parallel rods (dia/orient.h): anti-aliased capsules at known angles and
// positions, with noise, are all detected, and their angles found within 3° by the thesis's
// largest-aspect method (aspect ratio 4, 40 and 20 px long; the binary blob's staircase edges
// pull angles within a few degrees of the image axes onto them) and within 1° and 2° by the
// principal axis; capsules rendered by the project's DIA camera are found at the angles of their
// axes; and the coalignment of rods whose angles perform a random walk with a prescribed
// correlation C(r) = exp(-r / xi) returns that C(r) and xi, per zone.
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "check.h"
#include "core/quat.h"
#include "dia/dia.h"
#include "dia/orient.h"
#include "dia_draw.h"

/// Matches each true rod with the detected one nearest its centre (within `near` px): counts
/// them and returns the worst angle error, the mean |error| in *mean.
static double match_rods(const double *tu, const double *tv, const double *ta, int n,
                         const bdl_dia_rod *rods, long found, double near, int *matched,
                         double *mean)
{
    double worst = 0.0, sum = 0.0;
    *matched = 0;
    for (int k = 0; k < n; ++k) {
        long best = -1;
        double bd = near;
        for (long m = 0; m < found; ++m) {
            double d = hypot(rods[m].u - tu[k], rods[m].v - tv[k]);
            if (d < bd)
                bd = d, best = m;
        }
        if (best < 0)
            continue;
        double e = fabs(angle_difference(rods[best].angle, ta[k]));

        worst = fmax(worst, e), sum += e;
        ++*matched;
    }
    *mean = *matched > 0 ? sum / *matched : NAN;
    return worst;
}

static void test_drawn_rods(double length, bdl_dia_angle_method method, double tolerance)
{
    enum { NX = 8, NY = 6, N = NX * NY };
    const double spacing = 1.6 * length, width = length / 4.0;
    const int w = (int)(NX * spacing), h = (int)(NY * spacing);
    double *img = malloc(sizeof(double) * w * h), tu[N], tv[N], ta[N];
    bdl_rng rng;
    bdl_rng_seed(&rng, 21);
    for (int k = 0; k < w * h; ++k)
        img[k] = 0.15;
    for (int k = 0; k < N; ++k) {
        tu[k] = (k % NX + 0.5) * spacing + bdl_rng_range(&rng, -1.0, 1.0);
        tv[k] = (k / NX + 0.5) * spacing + bdl_rng_range(&rng, -1.0, 1.0);
        ta[k] = bdl_rng_range(&rng, -90.0, 90.0);
        draw_capsule(img, w, h, tu[k], tv[k], length, width, ta[k], 0.8, 5);
    }
    add_noise(img, (long)w * h, 0.02, &rng);
    bdl_dia_orient_def def = bdl_default_orient_def();
    def.min_area = (long)(0.3 * length * width);
    def.max_area = (long)(2.0 * length * width);
    def.method = method;
    bdl_dia_rod rods[2 * N];
    long found = 0;
    CHECK(bdl_dia_detect_rods(img, w, h, &def, rods, 2 * N, &found) == BDL_OK);
    int matched;
    double mean, worst = match_rods(tu, tv, ta, N, rods, found, 0.2 * length, &matched, &mean);
    double aspect = 0.0;
    for (long m = 0; m < found && m < 2 * N; ++m)
        aspect += rods[m].aspect / found;
    printf("rods %.0f x %.0f px at random angles, %s: %d of %d detected (%ld blobs kept), angle "
           "error mean %.2f°, worst %.2f°; mean aspect %.2f (true 4)\n",
           length, width, method == BDL_DIA_ANGLE_ASPECT ? "largest aspect" : "principal axis",
           matched, N, found, mean, worst, aspect);
    CHECK(matched == N && found == N);
    CHECK_MSG(worst <= tolerance, "worst angle error %g°", worst);
    free(img);
}

/// Single rods at exactly 0°, 90° and 45°: the convention (0 upright, +90 horizontal, positive
/// leaning right) and the aspect ratio.
static void test_convention(void)
{
    enum { W = 80, H = 80 };
    const double angles[4] = {0.0, 90.0, 45.0, -30.0};
    for (int k = 0; k < 4; ++k) {
        double img[W * H];
        for (int i = 0; i < W * H; ++i)
            img[i] = 0.1;
        draw_capsule(img, W, H, 40.0, 40.0, 48.0, 12.0, angles[k], 0.9, 5);
        bdl_dia_orient_def def = bdl_default_orient_def();
        bdl_dia_rod rod;
        long found = 0;
        bdl_dia_detect_rods(img, W, H, &def, &rod, 1, &found);
        CHECK(found == 1);
        CHECK_MSG(fabs(angle_difference(rod.angle, angles[k])) < 1.0, "%g° found as %g°", angles[k],
                  rod.angle);
        CHECK_MSG(fabs(rod.aspect - 4.0) < 0.35, "aspect %g at %g°", rod.aspect, angles[k]);
        CHECK(fabs(rod.u - 40.0) < 0.2 && fabs(rod.v - 40.0) < 0.2);
    }
}

/// Rods rendered by the synthetic camera, back-lit, axes in the wall's plane (x-z, z up).
static void test_camera_rods(void)
{
    enum { NX = 4, NY = 3, N = NX * NY };
    bdl_dia_def d = {0};
    d.projection = BDL_DIA_ORTHOGRAPHIC;
    d.position = bdl_v3(0.0, -0.5, 0.0), d.target = bdl_v3(0.0, 0.0, 0.0);
    d.up = bdl_v3(0, 0, 1);
    d.width = 240, d.height = 180, d.pixel_size = 1e-4; // 24 x 18 mm
    d.samples = 3, d.lighting = BDL_DIA_BACK_LIT, d.bright = 0.9, d.dark = 0.1;
    d.gamma = 1.0, d.bits = 8, d.blur = 0.7, d.noise = 0.01, d.seed = 3;
    bdl_dia_camera c;
    CHECK(bdl_dia_camera_init(&c, &d) == BDL_OK);
    bdl_vec3 pos[N], vel[N], axis[N];
    double rad[N], half[N], tu[N], tv[N], ta[N];
    uint32_t id[N];
    bdl_rng rng;
    bdl_rng_seed(&rng, 4);
    for (int k = 0; k < N; ++k) { // rods 4 mm tip to tip, 1 mm across: 40 x 10 px
        ta[k] = bdl_rng_range(&rng, -90.0, 90.0);
        double a = ta[k] * 3.14159265358979323846 / 180.0, depth;
        pos[k] = bdl_v3((k % NX - 1.5) * 6e-3, 0.0, (1.0 - k / NX) * 6e-3);
        axis[k] = bdl_v3(sin(a), 0.0, cos(a)); // leaning right in the image when positive
        vel[k] = bdl_v3(0, 0, 0), rad[k] = 0.5e-3, half[k] = 1.5e-3, id[k] = (uint32_t)k;
        bdl_dia_project(&c, pos[k], &tu[k], &tv[k], &depth);
    }
    bdl_dia_scene s = {N, pos, vel, rad, id, axis, half};
    bdl_dia_image im;
    CHECK(bdl_dia_render(&c, &s, 0, &im) == BDL_OK);
    bdl_dia_orient_def def = bdl_default_orient_def();
    def.bright_particles = 0, def.min_area = 150, def.max_area = 800;
    bdl_dia_rod rods[2 * N];
    long found = 0;
    CHECK(bdl_dia_detect_rods(im.final, d.width, d.height, &def, rods, 2 * N, &found) == BDL_OK);
    int matched;
    double mean, worst = match_rods(tu, tv, ta, N, rods, found, 3.0, &matched, &mean);
    printf("rods rendered by the DIA camera (40 x 10 px, back-lit, blur 0.7 px, noise 0.01): %d "
           "of %d detected, angle error mean %.2f°, worst %.2f°\n",
           matched, N, mean, worst);
    CHECK(matched == N && found == N);
    CHECK_MSG(worst <= 2.0, "worst angle error %g°", worst);
    bdl_dia_image_free(&im);
}

/// Rods on vertical lines 250 px apart (further than r_max, so no pair spans two lines), with
/// random gaps of 5 to 15 px along each; along a line the angle performs a random walk whose
/// increments have variance gap / (2 xi) [rad^2]: then 2 (alpha_i - alpha_j) is Gaussian with
/// variance 2 r / xi and C(r) = <cos 2(alpha_i - alpha_j)> = exp(-r / xi) exactly. Lines left of
/// x = 250 * lines / 2 have xi_left, the others xi_right.
static long correlated_rods(double *u, double *v, double *a, int lines, double length,
                            double xi_left, double xi_right, bdl_rng *rng)
{
    long n = 0;
    for (int l = 0; l < lines; ++l) {
        double xi = l < lines / 2 ? xi_left : xi_right, alpha = bdl_rng_range(rng, -90.0, 90.0);
        for (double y = 0.0; y < length; ++n) {
            u[n] = 250.0 * l + 10.0, v[n] = y, a[n] = alpha;
            double gap = bdl_rng_range(rng, 5.0, 15.0);
            alpha += sqrt(gap / (2.0 * xi)) * bdl_rng_normal(rng) * 180.0 / 3.14159265358979323846;
            y += gap;
        }
    }
    return n;
}

static void test_coalignment(void)
{
    enum { LINES = 160, BINS = 20, MAX = LINES * 2100 };
    const double lp = 40.0, r_max = 5.0 * lp, xi[2] = {1.0 * lp, 3.0 * lp};
    double *u = malloc(sizeof(double) * MAX), *v = malloc(sizeof(double) * MAX);
    double *a = malloc(sizeof(double) * MAX), c[BINS], r[BINS];
    long pairs[BINS];
    bdl_rng rng;
    bdl_rng_seed(&rng, 33);
    long n = correlated_rods(u, v, a, LINES, 20000.0, xi[0], xi[1], &rng);
    for (int zone = 0; zone < 2; ++zone) {
        double x0 = zone == 0 ? -INFINITY : 250.0 * LINES / 2;
        double x1 = zone == 0 ? 250.0 * LINES / 2 : INFINITY;
        CHECK(bdl_dia_coalignment(u, v, a, n, r_max, BINS, x0, x1, c, pairs, r) == BDL_OK);
        double worst = 0.0, amplitude, amp_fixed;
        for (int b = 0; b < BINS; ++b) {
            if (b > 0) { // the first bin holds no pair closer than 5 px
                CHECK(r[b] >= b * r_max / BINS && r[b] < (b + 1) * r_max / BINS);
                worst = fmax(worst, fabs(c[b] - exp(-r[b] / xi[zone])));
            }
        }
        double fit = bdl_dia_coalignment_fit(r, c, pairs, BINS, lp, 0, &amplitude);
        double fit1 = bdl_dia_coalignment_fit(r, c, pairs, BINS, lp, 1, &amp_fixed);
        printf("coalignment, zone %d (%ld rods in all, %ld pairs at r ~ L_p): C(r) within %.4f of "
               "exp(-r/xi); xi = %.2f L_p (true %.0f, error %+.1f %%), amplitude %.3f; with the "
               "amplitude fixed at 1, xi = %.2f L_p (%+.1f %%)\n",
               zone, n, pairs[4], worst, fit / lp, xi[zone] / lp, 100.0 * (fit / xi[zone] - 1.0),
               amplitude, fit1 / lp, 100.0 * (fit1 / xi[zone] - 1.0));
        CHECK_MSG(worst < 0.02, "C(r) off by %g", worst);
        CHECK_MSG(fabs(fit / xi[zone] - 1.0) < 0.06, "xi %g, expected %g", fit, xi[zone]);
        CHECK_MSG(fabs(fit1 / xi[zone] - 1.0) < 0.04, "xi %g, expected %g", fit1, xi[zone]);
        CHECK(fabs(amplitude - 1.0) < 0.05 && amp_fixed == 1.0);
    }
    // Independent angles: no correlation at any distance.
    for (long k = 0; k < n; ++k)
        a[k] = bdl_rng_range(&rng, -90.0, 90.0);
    bdl_dia_coalignment(u, v, a, n, r_max, BINS, -INFINITY, INFINITY, c, pairs, NULL);
    double worst = 0.0;
    for (int b = 1; b < BINS; ++b)
        worst = fmax(worst, fabs(c[b]));
    printf("coalignment of independent angles: |C(r)| <= %.4f\n", worst);
    CHECK(worst < 0.01);
    free(u), free(v), free(a);
}

int main(void)
{
    test_convention();
    test_drawn_rods(40.0, BDL_DIA_ANGLE_ASPECT, 3.0);
    test_drawn_rods(20.0, BDL_DIA_ANGLE_ASPECT, 3.0);
    test_drawn_rods(40.0, BDL_DIA_ANGLE_MOMENTS, 1.0);
    test_drawn_rods(20.0, BDL_DIA_ANGLE_MOMENTS, 2.0);
    test_camera_rods();
    test_coalignment();
    return bdl_test_summary("test_orient");
}
