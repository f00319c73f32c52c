// bedlam — points bucketed into square cells (a counting sort by cell).
#include "dia/points.h"

#include <math.h>
#include <stdlib.h>

static int cell_of(double x, double x0, double cell, int n)
{
    long c = (long)floor((x - x0) / cell);
    return c < 0 ? 0 : c >= n ? n - 1 : (int)c;
}

bdl_result bdl_dia_point_grid_build(bdl_dia_point_grid *g, const double *u, const double *v, long n,
                                    double cell)
{
    *g = (bdl_dia_point_grid){0};
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (long k = 0; k < n; ++k) {
        lo[0] = fmin(lo[0], u[k]), hi[0] = fmax(hi[0], u[k]);
        lo[1] = fmin(lo[1], v[k]), hi[1] = fmax(hi[1], v[k]);
    }
    if (n == 0)
        lo[0] = lo[1] = hi[0] = hi[1] = 0.0;
    double side = cell;
    while ((hi[0] - lo[0]) / side * ((hi[1] - lo[1]) / side) > (double)(1 << 22))
        side *= 2.0;
    g->u0 = lo[0], g->v0 = lo[1], g->cell = side;
    g->nx = (int)floor((hi[0] - lo[0]) / side) + 1;
    g->ny = (int)floor((hi[1] - lo[1]) / side) + 1;
    const long cells = (long)g->nx * g->ny;
    g->start = calloc((size_t)cells + 1, sizeof(long));
    g->index = malloc((size_t)(n > 0 ? n : 1) * sizeof(long));
    long *fill = calloc((size_t)cells, sizeof(long));
    if (!g->start || !g->index || !fill) {
        free(fill);
        bdl_dia_point_grid_free(g);
        return BDL_ERR_NOMEM;
    }
    for (long k = 0; k < n; ++k) {
        long c =
            (long)cell_of(v[k], g->v0, side, g->ny) * g->nx + cell_of(u[k], g->u0, side, g->nx);
        g->start[c + 1]++;
    }
    for (long c = 0; c < cells; ++c)
        g->start[c + 1] += g->start[c];
    for (long k = 0; k < n; ++k) {
        long c =
            (long)cell_of(v[k], g->v0, side, g->ny) * g->nx + cell_of(u[k], g->u0, side, g->nx);
        g->index[g->start[c] + fill[c]++] = k;
    }
    free(fill);
    return BDL_OK;
}

void bdl_dia_point_grid_free(bdl_dia_point_grid *g)
{
    free(g->start);
    free(g->index);
    *g = (bdl_dia_point_grid){0};
}

void bdl_dia_point_grid_range(const bdl_dia_point_grid *g, double u, double v, double reach,
                              int *cx0, int *cx1, int *cy0, int *cy1)
{
    double a0 = floor((u - reach - g->u0) / g->cell), a1 = floor((u + reach - g->u0) / g->cell);
    double b0 = floor((v - reach - g->v0) / g->cell), b1 = floor((v + reach - g->v0) / g->cell);
    *cx0 = a0 < 0.0 ? 0 : a0 >= g->nx ? g->nx : (int)a0;
    *cx1 = a1 < 0.0 ? -1 : a1 >= g->nx ? g->nx - 1 : (int)a1;
    *cy0 = b0 < 0.0 ? 0 : b0 >= g->ny ? g->ny : (int)b0;
    *cy1 = b1 < 0.0 ? -1 : b1 >= g->ny ? g->ny - 1 : (int)b1;
    if (*cy0 > *cy1)
        *cx0 = 1, *cx1 = 0;
}
