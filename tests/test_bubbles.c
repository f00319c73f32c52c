// Bubbles in a voidage field (analysis/bubbles.h): discs and balls of gas drawn into a packed
// bed are found with their equivalent diameters, a bubble erupting into the freeboard is not one,
// a bubble across a periodic side is one, and the top may be either end of the vertical axis.
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "analysis/bubbles.h"
#include "check.h"

#define PI 3.14159265358979323846

enum { NX = 40, NZ = 60 };

/// A pseudo-2D bed (NX x 1 x NZ cells of 1 cm): voidage 0.45 below layer 40, 1 above.
static void bed(double *f)
{
    for (int k = 0; k < NZ; ++k)
        for (int i = 0; i < NX; ++i)
            f[i + NX * k] = k < 40 ? 0.45 : 1.0;
}

/// Sets the cells whose centres lie within r cells of (x, z) (in cells, x wrapped if asked) to
/// voidage 0.95; returns how many.
static int disc(double *f, double x, double z, double r, int wrap)
{
    int count = 0;
    for (int k = 0; k < NZ; ++k)
        for (int i = 0; i < NX; ++i) {
            double dx = i + 0.5 - x;
            if (wrap && dx > NX / 2)
                dx -= NX;
            if (wrap && dx < -NX / 2)
                dx += NX;
            const double dz = k + 0.5 - z;
            if (dx * dx + dz * dz <= r * r) {
                count += f[i + NX * k] < 0.9;
                f[i + NX * k] = 0.95;
            }
        }
    return count;
}

static void test_discs(void)
{
    double *f = malloc(NX * NZ * sizeof *f);
    bed(f);
    const int a = disc(f, 20.0, 15.0, 5.0, 0), b = disc(f, 8.0, 30.0, 3.0, 0);
    disc(f, 30.0, 38.0, 3.0, 0); // erupting: joined to the freeboard
    bdl_bubble_grid g = {.n = {NX, 1, NZ}, .h = {0.01, 0.01, 0.01}, .up = 2, .up_sign = 1};
    bdl_bubbles s;
    CHECK(bdl_bubbles_find(f, &g, 0.85, &s) == BDL_OK);
    const double da = sqrt(4.0 * a * 1e-4 / PI), db = sqrt(4.0 * b * 1e-4 / PI);
    printf("two discs of 10 and 6 cm: %d bubbles, diameters %.4f and %.4f m (mean %.4f), "
           "height %.4f m\n",
           s.count, da, db, s.mean_diameter, s.mean_height);
    CHECK(s.count == 2);
    CHECK_CLOSE(s.max_diameter, da, 1e-12);
    CHECK_CLOSE(s.mean_diameter, 0.5 * (da + db), 1e-12);
    CHECK_CLOSE(s.volume, (a + b) * 1e-6, 1e-12);
    CHECK(fabs(da - 0.10) < 0.005 && fabs(db - 0.06) < 0.005); // the discs' own diameters
    CHECK_CLOSE(s.mean_height, (a * 0.15 + b * 0.30) / (a + b), 1e-3);
    // Upside down (the top at layer 0): the freeboard touches layer 0 and is left out again.
    double *flip = malloc(NX * NZ * sizeof *flip);
    for (int k = 0; k < NZ; ++k)
        for (int i = 0; i < NX; ++i)
            flip[i + NX * k] = f[i + NX * (NZ - 1 - k)];
    g.up_sign = -1;
    bdl_bubbles u;
    CHECK(bdl_bubbles_find(flip, &g, 0.85, &u) == BDL_OK);
    CHECK(u.count == 2);
    CHECK_CLOSE(u.mean_height, s.mean_height, 1e-12);
    // A threshold above every value finds nothing.
    CHECK(bdl_bubbles_find(f, &g, 1.0, &u) == BDL_OK && u.count == 0 && u.mean_diameter == 0.0);
    free(flip);
    free(f);
}

static void test_periodic(void)
{
    double *f = malloc(NX * NZ * sizeof *f);
    bed(f);
    const int a = disc(f, 0.0, 15.0, 4.0, 1);
    bdl_bubble_grid g = {.n = {NX, 1, NZ}, .h = {0.01, 0.01, 0.01}, .up = 2, .up_sign = 1};
    bdl_bubbles s;
    CHECK(bdl_bubbles_find(f, &g, 0.85, &s) == BDL_OK);
    CHECK(s.count == 2); // walls: two halves
    g.periodic[0] = 1;
    CHECK(bdl_bubbles_find(f, &g, 0.85, &s) == BDL_OK);
    printf("a disc across a periodic side: %d bubble of %.4f m\n", s.count, s.mean_diameter);
    CHECK(s.count == 1);
    CHECK_CLOSE(s.mean_diameter, sqrt(4.0 * a * 1e-4 / PI), 1e-12);
    free(f);
}

static void test_ball(void)
{
    enum { N = 24 };
    double *f = malloc(N * N * N * sizeof *f);
    int cells = 0;
    for (int k = 0; k < N; ++k)
        for (int j = 0; j < N; ++j)
            for (int i = 0; i < N; ++i) {
                const double dx = i + 0.5 - 12, dy = j + 0.5 - 12, dz = k + 0.5 - 10;
                const int in = dx * dx + dy * dy + dz * dz <= 36.0;
                cells += in;
                f[i + N * (j + N * k)] = in ? 0.9 : (k > 20 ? 1.0 : 0.4);
            }
    bdl_bubble_grid g = {.n = {N, N, N}, .h = {0.005, 0.005, 0.005}, .up = 2, .up_sign = 1};
    bdl_bubbles s;
    CHECK(bdl_bubbles_find(f, &g, 0.85, &s) == BDL_OK);
    printf("a ball of 6 cm: %d bubble, equivalent diameter %.4f m\n", s.count, s.mean_diameter);
    CHECK(s.count == 1);
    CHECK_CLOSE(s.mean_diameter, cbrt(6.0 * cells * 1.25e-7 / PI), 1e-12);
    CHECK(fabs(s.mean_diameter - 0.06) < 0.002);
    CHECK_CLOSE(s.mean_height, 0.05, 1e-9); // its centre, 10 cells up
    g.up = 3;
    CHECK(bdl_bubbles_find(f, &g, 0.85, &s) == BDL_ERR_ARGS);
    free(f);
}

int main(void)
{
    test_discs();
    test_periodic();
    test_ball();
    return bdl_test_summary("test_bubbles");
}
