// bedlam — staggered grid layout.
#include "cfd/grid.h"

#include <limits.h>
#include <stdlib.h>

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
    size_t sy = (size_t)g->n[0] + 2 * G + 1, sz, size, bytes;
    // Sizes checked: the padded layout of n^3 cells, and its bytes, must fit.
    if (!bdl_size_mul(sy, (size_t)g->n[1] + 2 * G + 1, &sz) ||
        !bdl_size_mul(sz, (size_t)g->n[2] + 2 * G + 1, &size) ||
        !bdl_size_mul(size, sizeof(double), &bytes) || size > (size_t)LONG_MAX)
        return 0;
    g->stride[0] = 1;
    g->stride[1] = (long)sy;
    g->stride[2] = (long)sz;
    g->size = (long)size;
    return 1;
}

double *bdl_grid_alloc(const bdl_grid *g) { return calloc((size_t)g->size, sizeof(double)); }

static void wrap_cells(const bdl_grid *g, double *f, int fewest)
{
    const int G = BDL_GRID_GHOST;
    for (int a = 0; a < 3; ++a) {
        if (!g->periodic[a] || g->n[a] < fewest)
            continue;
        const int b = (a + 1) % 3, c = (a + 2) % 3;
        const long sa = g->stride[a];
        for (int jc = -G; jc < g->n[c] + G; ++jc)
            for (int jb = -G; jb < g->n[b] + G; ++jb) {
                int idx[3];
                idx[a] = 0;
                idx[b] = jb;
                idx[c] = jc;
                long base = bdl_grid_index(g, idx[0], idx[1], idx[2]);
                for (int l = 1; l <= G; ++l) {
                    f[base - l * sa] = f[base + (g->n[a] - l) * sa];
                    f[base + (g->n[a] - 1 + l) * sa] = f[base + (l - 1) * sa];
                }
            }
    }
}

void bdl_grid_wrap_cells(const bdl_grid *g, double *f) { wrap_cells(g, f, 1); }

void bdl_grid_wrap_cells_wide(const bdl_grid *g, double *f) { wrap_cells(g, f, 2); }

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
