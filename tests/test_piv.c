// PIV by multi-pass FFT cross-correlation (dia/piv.h), on images of Gaussian particle images
// integrated over the pixels: a uniform sub-pixel shift is recovered within 0.05 px (small and
// near the thesis's largest 20 px), a solid-body rotation and a simple shear within 0.1 px rms;
// the defaults are the thesis's passes; a bad definition is refused; and the mass flux per cell
// is density (1 - voidage) velocity, zero across a plane where dense slow upflow balances dilute
// fast downflow although the mean velocity there points down.
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "check.h"
#include "dia/piv.h"
#include "dia_draw.h"

enum { W = 512, H = 512, MARGIN = 40 };

/// A displacement field: where a point at (x, y) is in the second image.
typedef void (*motion_fn)(double x, double y, const double *param, double *dx, double *dy);

static void shift(double x, double y, const double *p, double *dx, double *dy)
{
    (void)x, (void)y;
    *dx = p[0], *dy = p[1];
}

static void rotation(double x, double y, const double *p, double *dx, double *dy)
{
    double c = cos(p[0]), s = sin(p[0]), rx = x - 0.5 * W, ry = y - 0.5 * H;
    *dx = c * rx - s * ry - rx, *dy = s * rx + c * ry - ry;
}

static void shear(double x, double y, const double *p, double *dx, double *dy)
{
    (void)x;
    *dx = p[0] * (y - 0.5 * H), *dy = 0.0;
}

/// Renders the pair: particles (sigma 1 px, 0.02 per px^2) at random positions, then moved.
static void render_pair(motion_fn motion, const double *param, double *a, double *b)
{
    bdl_rng rng;
    bdl_rng_seed(&rng, 17);
    for (long k = 0; k < (long)W * H; ++k)
        a[k] = b[k] = 0.05;
    const long n = (long)(0.02 * (W + 2 * MARGIN) * (H + 2 * MARGIN));
    for (long k = 0; k < n; ++k) {
        double x = bdl_rng_range(&rng, -MARGIN, W + MARGIN);
        double y = bdl_rng_range(&rng, -MARGIN, H + MARGIN);
        double amplitude = bdl_rng_range(&rng, 0.3, 0.6), dx, dy;
        motion(x, y, param, &dx, &dy);
        draw_gaussian_spot(a, W, H, x, y, 1.0, amplitude);
        draw_gaussian_spot(b, W, H, x + dx, y + dy, 1.0, amplitude);
    }
    add_noise(a, (long)W * H, 0.01, &rng);
    add_noise(b, (long)W * H, 0.01, &rng);
}

/// Runs the default PIV on the pair; returns the rms error of the vectors against the motion at
/// their window centres, the worst in *worst.
static double piv_error(bdl_dia_piv *piv, motion_fn motion, const double *param, double *worst,
                        int *outliers)
{
    double *a = malloc(sizeof(double) * W * H), *b = malloc(sizeof(double) * W * H);
    render_pair(motion, param, a, b);
    bdl_dia_piv_field f;
    CHECK(bdl_dia_piv_run(piv, a, b, &f) == BDL_OK);
    double sum = 0.0;
    *worst = 0.0, *outliers = 0;
    for (int m = 0; m < f.nx * f.ny; ++m) {
        double tx, ty;
        motion(f.u[m], f.v[m], param, &tx, &ty);
        double e = hypot(f.du[m] - tx, f.dv[m] - ty);
        sum += e * e, *worst = fmax(*worst, e), *outliers += f.outlier[m];
    }
    free(a), free(b);
    return sqrt(sum / (f.nx * f.ny));
}

static void test_motions(void)
{
    bdl_dia_piv_def def = bdl_default_piv_def();
    bdl_dia_piv *piv = NULL;
    CHECK(bdl_dia_piv_create(&def, W, H, &piv) == BDL_OK);
    struct {
        const char *name;
        motion_fn motion;
        double param[2], rms, worst;
    } cases[] = {
        {"uniform shift (3.37, -1.82) px", shift, {3.37, -1.82}, 0.05, 0.05},
        {"uniform shift (19.71, 6.45) px", shift, {19.71, 6.45}, 0.05, 0.05},
        {"uniform shift (-0.5, 0.25) px", shift, {-0.5, 0.25}, 0.05, 0.05},
        {"rotation 0.02 rad (up to 7.2 px)", rotation, {0.02, 0.0}, 0.1, 0.3},
        {"shear 0.02 (up to 5.1 px)", shear, {0.02, 0.0}, 0.1, 0.3},
    };
    for (int c = 0; c < (int)(sizeof cases / sizeof cases[0]); ++c) {
        double worst;
        int outliers;
        double rms = piv_error(piv, cases[c].motion, cases[c].param, &worst, &outliers);
        printf("PIV %s: error rms %.4f px, worst %.4f px, %d vectors flagged by the median test\n",
               cases[c].name, rms, worst, outliers);
        CHECK_MSG(rms < cases[c].rms, "%s: rms %g", cases[c].name, rms);
        CHECK_MSG(worst < cases[c].worst, "%s: worst %g", cases[c].name, worst);
        CHECK(outliers == 0);
    }
    bdl_dia_piv_destroy(piv);
}

/// A uniform shift with a patch of image b, 200 px square, replaced by unrelated particles:
/// of the windows wholly inside the patch at least half are flagged by the median test (a cluster
/// of bad vectors is its own neighbourhood: here 3 of 4), none beyond it, and vectors beyond it
/// stay within 0.05 px.
static void test_outliers(void)
{
    const double param[2] = {3.37, -1.82};
    double *a = malloc(sizeof(double) * W * H), *b = malloc(sizeof(double) * W * H);
    render_pair(shift, param, a, b);
    bdl_rng rng;
    bdl_rng_seed(&rng, 99);
    const double lo = 160.0, hi = 360.0;
    for (int y = (int)lo; y < (int)hi; ++y)
        for (int x = (int)lo; x < (int)hi; ++x)
            b[y * W + x] = 0.05;
    for (int k = 0; k < (int)(0.02 * (hi - lo) * (hi - lo)); ++k)
        draw_gaussian_spot(b, W, H, bdl_rng_range(&rng, lo, hi), bdl_rng_range(&rng, lo, hi), 1.0,
                           0.5);
    bdl_dia_piv_def def = bdl_default_piv_def();
    def.passes = 2; // 256 px, then 128 px: the patch holds whole 128 px windows
    bdl_dia_piv *piv = NULL;
    CHECK(bdl_dia_piv_create(&def, W, H, &piv) == BDL_OK);
    bdl_dia_piv_field f;
    bdl_dia_piv_run(piv, a, b, &f);
    int inside = 0, flagged_inside = 0, flagged_outside = 0;
    double worst_outside = 0.0;
    for (int m = 0; m < f.nx * f.ny; ++m) {
        // in: the window [u - 64, u + 64) and its shift by 4 px lie inside the patch; far: both
        // lie outside it
        int in = fabs(f.u[m] - 260.0) <= 32.0 && fabs(f.v[m] - 260.0) <= 32.0;
        int far = fabs(f.u[m] - 260.0) >= 168.0 || fabs(f.v[m] - 260.0) >= 168.0;
        inside += in, flagged_inside += in && f.outlier[m];
        flagged_outside += far && f.outlier[m];
        if (far)
            worst_outside = fmax(worst_outside, hypot(f.du[m] - param[0], f.dv[m] - param[1]));
    }
    printf("PIV outliers: %d of %d windows within the unrelated patch flagged, %d away from it; "
           "vectors away from it within %.4f px\n",
           flagged_inside, inside, flagged_outside, worst_outside);
    CHECK(inside > 0 && 2 * flagged_inside >= inside && flagged_outside == 0);
    CHECK(worst_outside < 0.05);
    bdl_dia_piv_destroy(piv);
    free(a), free(b);
}

static void test_definition(void)
{
    bdl_dia_piv_def def = bdl_default_piv_def();
    CHECK(def.passes == 4 && def.pass[0].window == 256 && def.pass[0].overlap == 0.5);
    CHECK(def.pass[1].window == 128 && def.pass[3].overlap == 0.75);
    bdl_dia_piv *piv = NULL;
    CHECK(bdl_dia_piv_create(&def, 200, 600, &piv) == BDL_ERR_ARGS && piv == NULL);
    def.pass[2].overlap = 1.0;
    CHECK(bdl_dia_piv_create(&def, 512, 512, &piv) == BDL_ERR_ARGS);
    def = bdl_default_piv_def();
    def.passes = 0;
    CHECK(bdl_dia_piv_create(&def, 512, 512, &piv) == BDL_ERR_ARGS);
    // The final grid: 128 px windows every 32 px over 600 x 520 px, centred.
    def = bdl_default_piv_def();
    CHECK(bdl_dia_piv_create(&def, 600, 520, &piv) == BDL_OK);
    double *img = calloc(600 * 520, sizeof(double));
    bdl_dia_piv_field f;
    bdl_dia_piv_run(piv, img, img, &f);
    CHECK(f.nx == 15 && f.ny == 13);
    CHECK(f.u[0] == 64.0 + 12.0 && f.v[0] == 64.0 + 4.0 && f.u[1] - f.u[0] == 32.0);
    free(img);
    bdl_dia_piv_destroy(piv);
}

static void test_mass_flux(void)
{
    // Two cells across a plane: dense slow upflow, dilute fast downflow (v up positive).
    const double voidage[2] = {0.5, 0.9}, vu[2] = {0.1, -0.2}, vv[2] = {0.4, -2.0};
    double fu[2], fv[2];
    bdl_dia_mass_flux(voidage, vu, vv, 2, 2500.0, fu, fv);
    CHECK_CLOSE(fv[0], 500.0, 1e-15);  // 2500 * 0.5 * 0.4 kg/(m^2 s)
    CHECK_CLOSE(fv[1], -500.0, 1e-15); // 2500 * 0.1 * -2.0
    CHECK_CLOSE(fu[0], 125.0, 1e-15);
    CHECK_CLOSE(fu[1], -50.0, 1e-15);
    CHECK(vv[0] + vv[1] < 0.0 && fabs(fv[0] + fv[1]) < 1e-12);
}

int main(void)
{
    test_definition();
    test_motions();
    test_outliers();
    test_mass_flux();
    return bdl_test_summary("test_piv");
}
