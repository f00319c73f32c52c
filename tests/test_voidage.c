// Particle-only voidage: exact volume conservation, exact lattice voidage, the share of a
// sphere cut by a cell face against the spherical-cap volume, and interpolation.
#include <math.h>
#include <stdlib.h>

#include "analysis/voidage.h"
#include "check.h"
#include "core/vec3.h"

static double total_solid(const bdl_voidage_grid *g)
{
    double sum = 0.0;
    for (long c = 0; c < (long)g->dims[0] * g->dims[1] * g->dims[2]; ++c)
        sum += g->solid[c];
    return sum;
}

static double uniform(unsigned *state, double lo, double hi)
{
    *state = *state * 1664525u + 1013904223u;
    return lo + (hi - lo) * (*state >> 8) / 16777216.0;
}

static void test_conservation(int periodic_x)
{
    const double lo[3] = {0, 0, 0}, hi[3] = {0.1, 0.05, 0.08};
    const int periodic[3] = {periodic_x, 0, 0};
    bdl_voidage_grid g;
    CHECK(bdl_voidage_grid_init(&g, lo, hi, 0.0123, periodic) == BDL_OK);
    enum { N = 500 };
    float pos[3 * N], radius[N];
    unsigned state = 7;
    double volume = 0.0;
    for (int i = 0; i < N; ++i) {
        for (int a = 0; a < 3; ++a)
            pos[3 * i + a] = (float)uniform(&state, lo[a] - 0.002, hi[a] + 0.002);
        radius[i] = (float)uniform(&state, 0.001, 0.004);
        volume += 4.0 / 3.0 * BDL_PI * pow(radius[i], 3);
    }
    bdl_voidage_deposit(&g, N, pos, radius);
    CHECK_CLOSE(total_solid(&g), volume, 1e-12);
    // Depositing again starts from a clear grid.
    bdl_voidage_deposit(&g, N, pos, radius);
    CHECK_CLOSE(total_solid(&g), volume, 1e-12);
    bdl_voidage_grid_free(&g);
}

/// Touching spheres on a simple cubic lattice, cells holding whole spheres: 1 - pi/6 exactly.
static void test_lattice(void)
{
    const double a = 0.002, lo[3] = {0, 0, 0}, hi[3] = {10 * a, 10 * a, 10 * a};
    bdl_voidage_grid g;
    CHECK(bdl_voidage_grid_init(&g, lo, hi, 2 * a, NULL) == BDL_OK);
    CHECK(g.dims[0] == 5 && g.dims[1] == 5 && g.dims[2] == 5);
    float pos[3 * 1000], radius[1000];
    int n = 0;
    for (int k = 0; k < 10; ++k)
        for (int j = 0; j < 10; ++j)
            for (int i = 0; i < 10; ++i, ++n) {
                pos[3 * n] = (float)((i + 0.5) * a);
                pos[3 * n + 1] = (float)((j + 0.5) * a);
                pos[3 * n + 2] = (float)((k + 0.5) * a);
                radius[n] = (float)(0.5 * a * (1.0 - 1e-6)); // just inside the cell
            }
    bdl_voidage_deposit(&g, n, pos, radius);
    double worst = 0.0;
    for (int c = 0; c < 125; ++c)
        worst = fmax(worst, fabs(g.voidage[c] - (1.0 - BDL_PI / 6.0)));
    CHECK_MSG(worst < 1e-5, "lattice voidage off by %g", worst);
    const float inside[3] = {0.0071f, 0.0033f, 0.0150f};
    CHECK_CLOSE(bdl_voidage_at(&g, inside), 1.0 - BDL_PI / 6.0, 1e-5);
    bdl_voidage_grid_free(&g);
}

/// One sphere at distance s from the face between two cells: the share on the far side
/// against the spherical cap of height r - s.
static void test_cap_share(void)
{
    const double lo[3] = {0, 0, 0}, hi[3] = {0.02, 0.01, 0.01}, r = 0.002;
    bdl_voidage_grid g;
    CHECK(bdl_voidage_grid_init(&g, lo, hi, 0.01, NULL) == BDL_OK);
    double worst = 0.0;
    for (int k = -9; k <= 9; ++k) {
        double s = k / 10.0 * r; // centre left of the face at x = 0.01 by s
        float pos[3] = {(float)(0.01 - s), 0.005f, 0.005f}, radius = (float)r;
        bdl_voidage_deposit(&g, 1, pos, &radius);
        double h = r - s, cap = BDL_PI * h * h * (3.0 * r - h) / 3.0;
        double sphere = 4.0 / 3.0 * BDL_PI * r * r * r;
        double right = g.solid[1] / sphere, expected = cap / sphere;
        worst = fmax(worst, fabs(right - expected));
    }
    printf("cap share: worst error %.4f of the sphere volume\n", worst);
    // 128 sub-volumes: a plane cuts the sphere to within a few sub-volumes.
    CHECK_MSG(worst < 0.03, "share of a cut sphere off by %g", worst);
    bdl_voidage_grid_free(&g);
}

static void test_interpolation(void)
{
    const double lo[3] = {0, 0, 0}, hi[3] = {4, 1, 1};
    const int periodic[3] = {1, 0, 0};
    bdl_voidage_grid g;
    CHECK(bdl_voidage_grid_init(&g, lo, hi, 1.0, periodic) == BDL_OK);
    // Spheres of volume 0.5, each inside one cell.
    float r = (float)cbrt(0.5 * 3.0 / (4.0 * BDL_PI));
    // Cell 1 gets a second sphere: voidage 0.5 in cell 0, 0 in cell 1, 1 in cells 2 and 3.
    float pos3[9] = {0.5f, 0.5f, 0.5f, 1.5f, 0.5f, 0.5f, 1.5f, 0.5f, 0.5f};
    float radius3[3] = {r, r, r};
    bdl_voidage_deposit(&g, 3, pos3, radius3);
    CHECK_CLOSE(g.voidage[0], 0.5, 1e-6);
    CHECK(g.voidage[1] == 0.0); // clamped: overlapping spheres
    CHECK(g.voidage[2] == 1.0 && g.voidage[3] == 1.0);
    const float at_centre[3] = {0.5f, 0.5f, 0.5f}, between[3] = {1.0f, 0.2f, 0.9f},
                wrap[3] = {0.0f, 0.5f, 0.5f}, quarter[3] = {3.75f, 0.5f, 0.5f};
    CHECK_CLOSE(bdl_voidage_at(&g, at_centre), 0.5, 1e-6);
    CHECK_CLOSE(bdl_voidage_at(&g, between), 0.25, 1e-6);
    CHECK_CLOSE(bdl_voidage_at(&g, wrap), 0.75, 1e-6);     // cells 3 and 0 across the wrap
    CHECK_CLOSE(bdl_voidage_at(&g, quarter), 0.875, 1e-6); // a quarter of the way to cell 0
    bdl_voidage_grid_free(&g);

    // Bad grids.
    CHECK(bdl_voidage_grid_init(&g, lo, hi, 0.0, NULL) == BDL_ERR_ARGS);
    CHECK(bdl_voidage_grid_init(&g, hi, lo, 1.0, NULL) == BDL_ERR_ARGS);
}

int main(void)
{
    test_conservation(0);
    test_conservation(1);
    test_lattice();
    test_cap_share();
    test_interpolation();
    return bdl_test_summary("test_voidage");
}
