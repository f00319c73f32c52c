// Bed height as the level of the steepest row-averaged gradient (dia/bed_height.h): a blurred,
// noisy intensity step at a known sub-pixel level is found within 0.1 px, front- and back-lit;
// and a bed of discs whose centres fill the image below a known level is found there, from its
// image and, through the same definition, from the field of particle-number density per cell.
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "check.h"
#include "dia/bed_height.h"
#include "dia_draw.h"

/// Mean over the pixel rows [j, j + 1) of a step at v0 blurred by a Gaussian of sigma.
static double blurred_step(int j, double v0, double sigma)
{
    double s = 0.0;
    for (int k = 0; k < 64; ++k)
        s += 0.5 * (1.0 + erf((j + (k + 0.5) / 64.0 - v0) / (sqrt(2.0) * sigma)));
    return s / 64.0;
}

static void test_step(int front_lit)
{
    enum { W = 200, H = 300 };
    const double v0 = 173.37, sigma = 2.0, dark = 0.15, bright = 0.7;
    double *img = malloc(sizeof(double) * W * H);
    bdl_rng rng;
    bdl_rng_seed(&rng, 11);
    for (int j = 0; j < H; ++j) {
        double f = blurred_step(j, v0, sigma); // the bed below v0
        double g = front_lit ? dark + (bright - dark) * f : bright - (bright - dark) * f;
        for (int i = 0; i < W; ++i)
            img[j * W + i] = g;
    }
    add_noise(img, W * H, 0.03, &rng);
    bdl_dia_polarity pol = front_lit ? BDL_DIA_RISES_INTO_BED : BDL_DIA_FALLS_INTO_BED;
    double level = bdl_dia_bed_level_image(img, W, H, 1.0, pol);
    double either = bdl_dia_bed_level_image(img, W, H, 1.0, BDL_DIA_EITHER_WAY);
    printf("bed height, %s-lit step at %.2f px (blur 2 px, noise 0.03): found %.3f px, error "
           "%.3f px\n",
           front_lit ? "front" : "back", v0, level, level - v0);
    CHECK_MSG(fabs(level - v0) < 0.1, "step level %g, expected %g", level, v0);
    CHECK(either == level);
    free(img);
}

static void test_disc_bed(void)
{
    enum { W = 400, H = 256, CELL = 8, N = 1600 };
    const double v0 = 100.5, radius = 4.0;
    double *img = calloc(W * H, sizeof(double));
    double field[(H / CELL) * (W / CELL)] = {0};
    bdl_rng rng;
    bdl_rng_seed(&rng, 5);
    for (int k = 0; k < N; ++k) { // centres uniform in [0, W) x [v0, H + radius)
        double u = bdl_rng_range(&rng, 0.0, W), v = bdl_rng_range(&rng, v0, H + radius);
        draw_capsule(img, W, H, u, v, 2.0 * radius, 2.0 * radius, 0.0, 0.8, 4);
        if (v < H)
            field[(int)(v / CELL) * (W / CELL) + (int)(u / CELL)] += 1.0;
    }
    double image_level = bdl_dia_bed_level_image(img, W, H, 2.0, BDL_DIA_RISES_INTO_BED);
    double field_level = bdl_dia_bed_level_field(field, W / CELL, H / CELL, 0.0) * CELL;
    printf("bed of discs (r = %.0f px, centres below %.1f px): image %.2f px (error %.2f), number "
           "density in %d px cells %.2f px (error %.2f)\n",
           radius, v0, image_level, image_level - v0, CELL, field_level, field_level - v0);
    CHECK_MSG(fabs(image_level - v0) <= radius, "image level %g", image_level);
    CHECK_MSG(fabs(field_level - v0) <= CELL, "field level %g", field_level);
    free(img);
}

static void test_degenerate(void)
{
    const double flat[5] = {1, 1, 1, 1, 1}, two[2] = {0, 1};
    CHECK(isnan(bdl_dia_profile_step(flat, 5, 0.0, BDL_DIA_RISES_INTO_BED)));
    CHECK(isnan(bdl_dia_profile_step(two, 2, 0.0, BDL_DIA_RISES_INTO_BED)));
    const double ramp[6] = {0, 0, 0, 1, 1, 1}; // a sharp step between rows 2 and 3: level 3
    CHECK_CLOSE(bdl_dia_profile_step(ramp, 6, 0.0, BDL_DIA_RISES_INTO_BED), 3.0, 1e-12);
    CHECK(isnan(bdl_dia_profile_step(ramp, 6, 0.0, BDL_DIA_FALLS_INTO_BED))); // no falling step
}

int main(void)
{
    test_step(1);
    test_step(0);
    test_disc_bed();
    test_degenerate();
    return bdl_test_summary("test_bed_height");
}
