// Colour maps: lightness linear in the value, near-uniform perceptual steps, a symmetric
// diverging map, distinct categories, and OKLab conversions that invert each other.
#include <math.h>
#include <stdint.h>
#include <stdlib.h>

#include "check.h"
#include "render/colormap.h"

static float delta_e(const float a[3], const float b[3])
{
    float la[3], lb[3];
    bdl_oklab_from_srgb(a, la);
    bdl_oklab_from_srgb(b, lb);
    return sqrtf((la[0] - lb[0]) * (la[0] - lb[0]) + (la[1] - lb[1]) * (la[1] - lb[1]) +
                 (la[2] - lb[2]) * (la[2] - lb[2]));
}

static float lightness(bdl_colormap_kind kind, double t)
{
    float c[3], lab[3];
    bdl_colormap_eval(kind, t, c);
    bdl_oklab_from_srgb(c, lab);
    return lab[0];
}

static void test_oklab(void)
{
    const float white[3] = {1, 1, 1}, black[3] = {0, 0, 0};
    float lab[3];
    bdl_oklab_from_srgb(white, lab);
    CHECK_CLOSE(lab[0], 1.0, 1e-4);
    CHECK(fabsf(lab[1]) < 1e-4f && fabsf(lab[2]) < 1e-4f);
    bdl_oklab_from_srgb(black, lab);
    CHECK(fabsf(lab[0]) < 1e-6f);
    // Round trip over a coarse cube of colours.
    float worst = 0.0f;
    for (int r = 0; r <= 4; ++r)
        for (int g = 0; g <= 4; ++g)
            for (int b = 0; b <= 4; ++b) {
                float c[3] = {r / 4.0f, g / 4.0f, b / 4.0f}, back[3];
                bdl_oklab_from_srgb(c, lab);
                bdl_srgb_from_oklab(lab, back);
                for (int k = 0; k < 3; ++k)
                    worst = fmaxf(worst, fabsf(back[k] - c[k]));
            }
    CHECK_MSG(worst < 1e-4f, "round trip error %g", worst);
}

static void test_sequential(void)
{
    const int n = 64;
    float prev[3], step_min = 1e9f, step_max = 0.0f, l_err = 0.0f;
    bdl_colormap_eval(BDL_CMAP_SEQUENTIAL, 0.0, prev);
    for (int i = 0; i <= n; ++i) {
        double t = (double)i / n;
        float c[3];
        bdl_colormap_eval(BDL_CMAP_SEQUENTIAL, t, c);
        l_err = fmaxf(l_err, fabsf(lightness(BDL_CMAP_SEQUENTIAL, t) - (float)(0.30 + 0.63 * t)));
        if (i > 0) {
            float d = delta_e(prev, c);
            step_min = fminf(step_min, d);
            step_max = fmaxf(step_max, d);
        }
        for (int k = 0; k < 3; ++k)
            prev[k] = c[k];
    }
    printf("sequential: lightness error %.4f, perceptual step %.4f .. %.4f\n", l_err, step_min,
           step_max);
    CHECK_MSG(l_err < 0.005f, "lightness departs from the linear ramp by %g", l_err);
    // Equal steps in the value look like near-equal steps in colour (measured 1.27x).
    CHECK_MSG(step_max < 1.35f * step_min, "steps %g .. %g", step_min, step_max);

    float lo[3], hi[3], lab_lo[3], lab_hi[3];
    bdl_colormap_eval(BDL_CMAP_SEQUENTIAL, 0.0, lo);
    bdl_colormap_eval(BDL_CMAP_SEQUENTIAL, 1.0, hi);
    bdl_oklab_from_srgb(lo, lab_lo);
    bdl_oklab_from_srgb(hi, lab_hi);
    CHECK(lab_lo[2] < -0.05f && lab_lo[1] > 0.0f); // violet
    CHECK(lab_hi[2] > 0.1f);                       // yellow
    CHECK(lo[2] > lo[1] && hi[0] > hi[2]);

    // Clamping outside [0, 1] and NaN.
    float c[3];
    bdl_colormap_eval(BDL_CMAP_SEQUENTIAL, -3.0, c);
    CHECK(c[0] == lo[0] && c[1] == lo[1] && c[2] == lo[2]);
    bdl_colormap_eval(BDL_CMAP_SEQUENTIAL, NAN, c);
    CHECK(c[0] == lo[0] && c[1] == lo[1] && c[2] == lo[2]);
    bdl_colormap_eval(BDL_CMAP_SEQUENTIAL, 7.0, c);
    CHECK(c[0] == hi[0] && c[1] == hi[1] && c[2] == hi[2]);
}

static void test_diverging(void)
{
    float asym = 0.0f;
    for (int i = 0; i <= 32; ++i) {
        double t = i / 64.0;
        asym = fmaxf(
            asym, fabsf(lightness(BDL_CMAP_DIVERGING, t) - lightness(BDL_CMAP_DIVERGING, 1.0 - t)));
        if (i < 32) // lightness rises towards the middle
            CHECK(lightness(BDL_CMAP_DIVERGING, t) <
                  lightness(BDL_CMAP_DIVERGING, t + 1.0 / 64) + 1e-4f);
    }
    CHECK_MSG(asym < 0.005f, "lightness asymmetry %g", asym);
    float mid[3], lab[3];
    bdl_colormap_eval(BDL_CMAP_DIVERGING, 0.5, mid);
    bdl_oklab_from_srgb(mid, lab);
    CHECK_CLOSE(lab[0], 0.95, 0.01);
    CHECK(hypotf(lab[1], lab[2]) < 0.01f);
    float blue[3], red[3];
    bdl_colormap_eval(BDL_CMAP_DIVERGING, 0.0, blue);
    bdl_colormap_eval(BDL_CMAP_DIVERGING, 1.0, red);
    CHECK(blue[2] > blue[0] + 0.2f);
    CHECK(red[0] > red[2] + 0.2f);
}

static void test_table_matches_eval(void)
{
    for (int kind = 0; kind < 2; ++kind) {
        uint8_t table[BDL_COLORMAP_SIZE][3];
        bdl_colormap_table((bdl_colormap_kind)kind, table);
        int worst = 0;
        for (int i = 0; i < BDL_COLORMAP_SIZE; ++i) {
            float c[3];
            bdl_colormap_eval((bdl_colormap_kind)kind, (double)i / (BDL_COLORMAP_SIZE - 1), c);
            for (int k = 0; k < 3; ++k) {
                int d = abs((int)lrintf(255.0f * c[k]) - table[i][k]);
                worst = d > worst ? d : worst;
            }
        }
        CHECK_MSG(worst == 0, "table and eval differ by %d levels", worst);
    }
}

static void test_categories(void)
{
    float c[8][3];
    for (int i = 0; i < 8; ++i) {
        bdl_category_color(i, c[i]);
        float lab[3];
        bdl_oklab_from_srgb(c[i], lab);
        CHECK_CLOSE(lab[0], 0.70, 0.02);
    }
    float closest = 1e9f;
    for (int i = 0; i < 8; ++i)
        for (int j = 0; j < i; ++j)
            closest = fminf(closest, delta_e(c[i], c[j]));
    printf("categories: closest pair of the first 8 is %.3f apart\n", closest);
    CHECK_MSG(closest > 0.05f, "two of the first 8 categories are only %g apart", closest);
}

int main(void)
{
    test_oklab();
    test_sequential();
    test_diverging();
    test_table_matches_eval();
    test_categories();
    return bdl_test_summary("test_colormap");
}
