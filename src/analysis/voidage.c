// bedlam — particle-only voidage by equal-volume sub-sphere deposition.
#include "analysis/voidage.h"

#include <math.h>
#include <pthread.h>
#include <stdlib.h>

#include "core/vec3.h"

/// Sub-volume centres of the unit sphere: shell k holds the radii between (k/S)^(1/3) and
/// ((k+1)/S)^(1/3), so every shell has the same volume; its points sit at the radius halving
/// the shell's volume, in directions from a Fibonacci lattice turned by a different angle in
/// every shell.
static float unit_points[BDL_VOIDAGE_POINTS][3];
static pthread_once_t points_once = PTHREAD_ONCE_INIT;

static void build_points(void)
{
    const double golden = BDL_PI * (3.0 - sqrt(5.0));
    for (int k = 0; k < BDL_VOIDAGE_SHELLS; ++k) {
        double r = cbrt((k + 0.5) / BDL_VOIDAGE_SHELLS);
        for (int j = 0; j < BDL_VOIDAGE_DIRECTIONS; ++j) {
            double z = 1.0 - (2.0 * j + 1.0) / BDL_VOIDAGE_DIRECTIONS;
            double s = sqrt(1.0 - z * z), phi = golden * j + 0.9 * k;
            float *p = unit_points[k * BDL_VOIDAGE_DIRECTIONS + j];
            p[0] = (float)(r * s * cos(phi));
            p[1] = (float)(r * s * sin(phi));
            p[2] = (float)(r * z);
        }
    }
}

bdl_result bdl_voidage_grid_init(bdl_voidage_grid *g, const double lo[3], const double hi[3],
                                 double cell, const int periodic[3])
{
    *g = (bdl_voidage_grid){0};
    if (!(cell > 0.0))
        return BDL_ERR_ARGS;
    long n = 1;
    for (int a = 0; a < 3; ++a) {
        double length = hi[a] - lo[a];
        if (!(length > 0.0))
            return BDL_ERR_ARGS;
        double cells = fmax(1.0, floor(length / cell + 0.5));
        if (cells > 4096.0)
            cells = 4096.0;
        g->dims[a] = (int)cells;
        g->h[a] = length / cells;
        g->origin[a] = lo[a];
        g->periodic[a] = periodic ? periodic[a] != 0 : 0;
        n *= g->dims[a];
    }
    g->cell = cell;
    g->solid = calloc((size_t)n, sizeof *g->solid);
    g->voidage = malloc((size_t)n * sizeof *g->voidage);
    if (!g->solid || !g->voidage) {
        bdl_voidage_grid_free(g);
        return BDL_ERR_NOMEM;
    }
    for (long c = 0; c < n; ++c)
        g->voidage[c] = 1.0;
    pthread_once(&points_once, build_points);
    return BDL_OK;
}

void bdl_voidage_grid_free(bdl_voidage_grid *g)
{
    free(g->solid);
    free(g->voidage);
    g->solid = g->voidage = NULL;
}

/// Cell index along axis a of coordinate x: wrapped on periodic axes, clamped on others.
static int cell_index(const bdl_voidage_grid *g, int a, double x)
{
    int i = (int)floor((x - g->origin[a]) / g->h[a]);
    int n = g->dims[a];
    if (g->periodic[a]) {
        i %= n;
        return i < 0 ? i + n : i;
    }
    return i < 0 ? 0 : i >= n ? n - 1 : i;
}

void bdl_voidage_deposit(bdl_voidage_grid *g, long count, const float *pos, const float *radius)
{
    const long n = (long)g->dims[0] * g->dims[1] * g->dims[2];
    for (long c = 0; c < n; ++c)
        g->solid[c] = 0.0;
    for (long i = 0; i < count; ++i) {
        const double r = radius[i];
        const double share = 4.0 / 3.0 * BDL_PI * r * r * r / BDL_VOIDAGE_POINTS;
        const double cx = pos[3 * i], cy = pos[3 * i + 1], cz = pos[3 * i + 2];
        // A sphere well inside one cell needs no splitting.
        int ix = cell_index(g, 0, cx), iy = cell_index(g, 1, cy), iz = cell_index(g, 2, cz);
        int whole = 1;
        for (int a = 0; a < 3 && whole; ++a) {
            double x = a == 0 ? cx : a == 1 ? cy : cz;
            double local = x - g->origin[a] - (a == 0 ? ix : a == 1 ? iy : iz) * g->h[a];
            whole = local >= r && local <= g->h[a] - r;
        }
        if (whole) {
            g->solid[((long)iz * g->dims[1] + iy) * g->dims[0] + ix] += share * BDL_VOIDAGE_POINTS;
            continue;
        }
        for (int k = 0; k < BDL_VOIDAGE_POINTS; ++k) {
            const float *p = unit_points[k];
            int jx = cell_index(g, 0, cx + r * p[0]);
            int jy = cell_index(g, 1, cy + r * p[1]);
            int jz = cell_index(g, 2, cz + r * p[2]);
            g->solid[((long)jz * g->dims[1] + jy) * g->dims[0] + jx] += share;
        }
    }
    const double volume = g->h[0] * g->h[1] * g->h[2];
    for (long c = 0; c < n; ++c) {
        double e = 1.0 - g->solid[c] / volume;
        g->voidage[c] = e < 0.0 ? 0.0 : e > 1.0 ? 1.0 : e;
    }
}

/// The two cell-centre indices bracketing x along axis a and the weight of the upper one.
static void bracket(const bdl_voidage_grid *g, int a, double x, int *i0, int *i1, double *w)
{
    const int n = g->dims[a];
    double u = (x - g->origin[a]) / g->h[a] - 0.5;
    double f = floor(u);
    int i = (int)f;
    *w = u - f;
    if (g->periodic[a]) {
        i %= n;
        if (i < 0)
            i += n;
        *i0 = i;
        *i1 = (i + 1) % n;
        return;
    }
    if (i < 0) {
        *i0 = *i1 = 0;
        *w = 0.0;
    } else if (i >= n - 1) {
        *i0 = *i1 = n - 1;
        *w = 0.0;
    } else {
        *i0 = i;
        *i1 = i + 1;
    }
}

float bdl_voidage_at(const bdl_voidage_grid *g, const float x[3])
{
    int i[3][2];
    double w[3];
    for (int a = 0; a < 3; ++a)
        bracket(g, a, x[a], &i[a][0], &i[a][1], &w[a]);
    double sum = 0.0;
    for (int c = 0; c < 8; ++c) {
        int bx = c & 1, by = (c >> 1) & 1, bz = (c >> 2) & 1;
        double weight =
            (bx ? w[0] : 1.0 - w[0]) * (by ? w[1] : 1.0 - w[1]) * (bz ? w[2] : 1.0 - w[2]);
        if (weight == 0.0)
            continue;
        sum +=
            weight * g->voidage[((long)i[2][bz] * g->dims[1] + i[1][by]) * g->dims[0] + i[0][bx]];
    }
    return (float)sum;
}
