// bedlam — the padded grid layout (cfd/grid.h): indices, positions, planes and periodic images,
// and the flat axis (a periodic y or z of one cell, stored without padding).
#include <stdlib.h>
#include <string.h>

#include "cfd/grid.h"
#include "check.h"

static bdl_grid make(int nx, int ny, int nz, int px, int py, int pz)
{
    bdl_grid g;
    const int n[3] = {nx, ny, nz}, periodic[3] = {px, py, pz};
    const double lo[3] = {0, 0, 0}, hi[3] = {0.1 * nx, 0.1 * ny, 0.1 * nz};
    CHECK(bdl_grid_init(&g, n, lo, hi, periodic));
    return g;
}

/// Which axes are flat, and the array's length: padding on every other axis.
static void test_flat_axes(void)
{
    const int G = BDL_GRID_GHOST;
    const bdl_grid flat_y = make(15, 1, 45, 0, 1, 0), wall_y = make(15, 1, 45, 0, 0, 0),
                   two_y = make(15, 2, 45, 0, 1, 0), flat_yz = make(7, 1, 1, 1, 1, 1),
                   one_x = make(1, 4, 5, 1, 0, 0);
    CHECK(flat_y.stride[1] == 0 && flat_y.stride[2] == 15 + 2 * G + 1);
    CHECK(flat_y.size == (long)(15 + 2 * G + 1) * (45 + 2 * G + 1));
    CHECK(wall_y.stride[1] == 15 + 2 * G + 1); // walls: the ghosts are mirrors, not the cell
    CHECK(two_y.stride[1] == 15 + 2 * G + 1);
    CHECK(flat_yz.stride[1] == 0 && flat_yz.stride[2] == 0 && flat_yz.size == 7 + 2 * G + 1);
    CHECK(one_x.stride[0] == 1 &&
          one_x.size == (long)(1 + 2 * G + 1) * (4 + 2 * G + 1) * (5 + 2 * G + 1));
    // Along a flat axis every ghost and face is the cell itself.
    for (int j = -G; j <= 1 + G; ++j)
        CHECK(bdl_grid_index(&flat_y, 3, j, 7) == bdl_grid_index(&flat_y, 3, 0, 7));
}

/// bdl_grid_position inverts bdl_grid_index over every padded position.
static void check_positions(const bdl_grid *g)
{
    int bad = 0;
    for (int k = bdl_grid_pad_lo(g, 2); k <= bdl_grid_pad_hi(g, 2); ++k)
        for (int j = bdl_grid_pad_lo(g, 1); j <= bdl_grid_pad_hi(g, 1); ++j)
            for (int i = bdl_grid_pad_lo(g, 0); i <= bdl_grid_pad_hi(g, 0); ++i) {
                const long idx = bdl_grid_index(g, i, j, k);
                int ix[3];
                bdl_grid_position(g, idx, ix);
                bad += idx < 0 || idx >= g->size || ix[0] != i || ix[1] != j || ix[2] != k;
            }
    CHECK(bad == 0);
}

/// BDL_GRID_FOR_PLANE visits each position of a plane once, and every plane together covers the
/// array once.
static void check_planes(const bdl_grid *g)
{
    int *seen = calloc((size_t)g->size, sizeof *seen);
    CHECK(seen != NULL);
    if (!seen)
        return;
    for (int a = 0; a < 3; ++a) {
        memset(seen, 0, (size_t)g->size * sizeof *seen);
        for (int at = bdl_grid_pad_lo(g, a); at <= bdl_grid_pad_hi(g, a); ++at)
            BDL_GRID_FOR_PLANE(g, a, at, seen[idx]++);
        int once = 1;
        for (long i = 0; i < g->size; ++i)
            once = once && seen[i] == 1;
        CHECK_MSG(once, "axis %d", a);
    }
    free(seen);
}

/// The periodic images: after bdl_grid_wrap_cells a ghost holds its image's value; along a flat
/// axis nothing moves (copy_plane onto itself is no copy).
static void test_images(void)
{
    const int G = BDL_GRID_GHOST;
    const bdl_grid g = make(6, 1, 5, 1, 1, 0);
    double *f = bdl_grid_alloc(&g);
    CHECK(f != NULL);
    if (!f)
        return;
    for (int k = 0; k < 5; ++k)
        for (int i = 0; i < 6; ++i)
            f[bdl_grid_index(&g, i, 0, k)] = 10.0 * k + i;
    bdl_grid_wrap_cells(&g, f);
    bdl_grid_copy_plane(&g, f, 1, 1, 0);
    int bad = 0;
    for (int k = 0; k < 5; ++k)
        for (int j = -G; j <= G; ++j)
            for (int i = -G; i < 6 + G; ++i) {
                const int image = (i + 6) % 6;
                bad += f[bdl_grid_index(&g, i, j, k)] != 10.0 * k + image;
            }
    CHECK(bad == 0);
    free(f);
}

int main(void)
{
    test_flat_axes();
    const bdl_grid grids[] = {make(15, 1, 45, 0, 1, 0), make(4, 3, 5, 1, 1, 1),
                              make(7, 1, 1, 1, 1, 1), make(3, 2, 1, 0, 0, 1),
                              make(1, 1, 3, 1, 0, 0)};
    for (size_t q = 0; q < sizeof grids / sizeof grids[0]; ++q) {
        check_positions(&grids[q]);
        check_planes(&grids[q]);
    }
    test_images();
    return bdl_test_summary("test_grid");
}
