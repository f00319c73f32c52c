// bedlam — staggered grid layout.
#include "cfd/grid.h"

#include <limits.h>
#include <stdlib.h>
#include <string.h>

#include "core/memory.h"

int bdl_grid_init(bdl_grid *g, const int n[3], const double lo[3], const double hi[3],
                  const int periodic[3])
{
    *g = (bdl_grid){0};
    for (int a = 0; a < 3; ++a) {
        if (n[a] < 1 || !(hi[a] > lo[a]))
            return 0;
        g->n[a] = n[a];
        g->h[a] = (hi[a] - lo[a]) / n[a];
        g->origin[a] = lo[a];
        g->periodic[a] = periodic ? periodic[a] != 0 : 0;
    }
    const int G = BDL_GRID_GHOST;
    int flat[3] = {0, 0, 0}; // a periodic y or z axis of one cell (grid.h)
    size_t extent[3];        // padded positions per axis
    for (int a = 0; a < 3; ++a) {
        flat[a] = bdl_grid_flat(a, g->n[a], g->periodic[a]);
        extent[a] = flat[a] ? 1 : (size_t)g->n[a] + 2 * G + 1;
    }
    size_t sy = extent[0], sz, size, bytes;
    // Sizes checked: the padded layout of n^3 cells, and its bytes, must fit.
    if (!bdl_size_mul(sy, extent[1], &sz) || !bdl_size_mul(sz, extent[2], &size) ||
        !bdl_size_mul(size, sizeof(double), &bytes) || size > (size_t)LONG_MAX)
        return 0;
    g->stride[0] = 1;
    g->stride[1] = flat[1] ? 0 : (long)sy;
    g->stride[2] = flat[2] ? 0 : (long)sz;
    g->size = (long)size;
    return 1;
}

double *bdl_grid_alloc(const bdl_grid *g) { return calloc((size_t)g->size, sizeof(double)); }

/// The ghost layers of f along every periodic axis of at least `fewest` cells, from their
/// images. Along y and z, rows along x are copied whole (the rows are contiguous); each ghost
/// plane l is filled after plane l - 1, which it reads when the axis has fewer cells than ghosts.
static void wrap_cells(const bdl_grid *g, double *f, int fewest)
{
    const int G = BDL_GRID_GHOST;
    for (int a = 0; a < 3; ++a) {
        if (!g->periodic[a] || g->n[a] < fewest || g->stride[a] == 0) // (flat: no images)
            continue;
        const long sa = g->stride[a];
        const int n = g->n[a];
        int lo[3], hi[3]; // the padded positions of the plane at 0 along a (hi exclusive)
        for (int b = 0; b < 3; ++b)
            lo[b] = bdl_grid_pad_lo(g, b), hi[b] = g->stride[b] == 0 ? 1 : g->n[b] + G;
        lo[a] = 0, hi[a] = 1;
        const long row = a == 0 ? 1 : hi[0] - lo[0]; // positions copied at a time
        for (int k = lo[2]; k < hi[2]; ++k)
            for (int j = lo[1]; j < hi[1]; ++j)
                for (int i = lo[0]; i < hi[0]; i += (int)row) {
                    const long base = bdl_grid_index(g, i, j, k);
                    const size_t bytes = (size_t)row * sizeof(double);
                    for (int l = 1; l <= G; ++l) {
                        memcpy(f + base - l * sa, f + base + (n - l) * sa, bytes);
                        memcpy(f + base + (n - 1 + l) * sa, f + base + (l - 1) * sa, bytes);
                    }
                }
    }
}

void bdl_grid_wrap_cells(const bdl_grid *g, double *f) { wrap_cells(g, f, 1); }

void bdl_grid_wrap_cells_wide(const bdl_grid *g, double *f) { wrap_cells(g, f, 2); }

void bdl_grid_copy_plane(const bdl_grid *g, double *f, int a, int to, int from)
{
    const long shift = (long)(to - from) * g->stride[a];
    if (shift == 0) // (along a flat axis every plane is the one)
        return;
    int lo[3], hi[3]; // the padded positions of the plane at `from` (hi inclusive)
    for (int b = 0; b < 3; ++b)
        lo[b] = bdl_grid_pad_lo(g, b), hi[b] = bdl_grid_pad_hi(g, b);
    lo[a] = hi[a] = from;
    const int row = a == 0 ? 1 : hi[0] - lo[0] + 1; // positions copied at a time
    for (int k = lo[2]; k <= hi[2]; ++k)
        for (int j = lo[1]; j <= hi[1]; ++j)
            for (int i = lo[0]; i <= hi[0]; i += row) {
                const long at = bdl_grid_index(g, i, j, k);
                memcpy(f + at + shift, f + at, (size_t)row * sizeof(double));
            }
}

void bdl_grid_wrap_axis(const bdl_grid *g, double *f, int a, int faces)
{
    const int n = g->n[a], last = faces ? n : n - 1; // the plane holding the image of plane 0
    if (faces)
        bdl_grid_copy_plane(g, f, a, n, 0);
    for (int l = 1; l <= BDL_GRID_GHOST; ++l) {
        bdl_grid_copy_plane(g, f, a, -l, n - l);
        bdl_grid_copy_plane(g, f, a, last + l, last + l - n);
    }
}

void bdl_grid_position(const bdl_grid *g, long idx, int ix[3])
{
    for (int a = 2; a >= 0; --a) {
        if (g->stride[a] == 0) {
            ix[a] = 0;
            continue;
        }
        ix[a] = (int)(idx / g->stride[a]) - BDL_GRID_GHOST;
        idx %= g->stride[a];
    }
}

double bdl_grid_layer_mean(const bdl_grid *g, const double *field, int a, int m)
{
    const int b = (a + 1) % 3, c = (a + 2) % 3;
    double sum = 0.0;
    for (int jc = 0; jc < g->n[c]; ++jc)
        for (int jb = 0; jb < g->n[b]; ++jb) {
            int ix[3];
            ix[a] = m, ix[b] = jb, ix[c] = jc;
            sum += field[bdl_grid_index(g, ix[0], ix[1], ix[2])];
        }
    return sum / ((double)g->n[b] * g->n[c]);
}

void bdl_grid_extend_cells(const bdl_grid *gr, double *f)
{
    for (int a = 0; a < 3; ++a) {
        const long s = gr->stride[a];
        const int n = gr->n[a];
        if (gr->periodic[a])
            continue;
        BDL_GRID_FOR_PLANE(gr, a, 0, {
            for (int l = 1; l <= BDL_GRID_GHOST; ++l) {
                f[idx - l * s] = f[idx];
                f[idx + (n - 1 + l) * s] = f[idx + (n - 1) * s];
            }
        });
    }
    bdl_grid_wrap_cells(gr, f);
}
