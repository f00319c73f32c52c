// bedlam — bubbles in a voidage field (analysis/bubbles.h): a union-find over the cells above
// the threshold, joined with their face neighbours (across the sides of periodic axes too),
// then one pass that sums each region's volume and height and marks the regions that reach the
// top layer.
#include "analysis/bubbles.h"

#include <math.h>
#include <stdlib.h>

#define PI 3.14159265358979323846

static long find(long *parent, long i)
{
    while (parent[i] != i) {
        parent[i] = parent[parent[i]]; // path halving
        i = parent[i];
    }
    return i;
}

static void join(long *parent, long i, long j)
{
    const long a = find(parent, i), b = find(parent, j);
    if (a < b)
        parent[b] = a; // the lower index is the root: the labelling depends on nothing else
    else if (b < a)
        parent[a] = b;
}

typedef struct region {
    double volume, height;
    int top;
} region;

/// Joins every cell above the threshold with its neighbours above it along each axis.
static void link_cells(const double *f, const bdl_bubble_grid *g, double threshold, long *parent)
{
    const long stride[3] = {1, g->n[0], (long)g->n[0] * g->n[1]};
    for (int k = 0; k < g->n[2]; ++k)
        for (int j = 0; j < g->n[1]; ++j)
            for (int i = 0; i < g->n[0]; ++i) {
                const long c = i + stride[1] * j + stride[2] * k;
                if (!(f[c] > threshold))
                    continue;
                const int at[3] = {i, j, k};
                for (int a = 0; a < 3; ++a) {
                    long next = -1;
                    if (at[a] + 1 < g->n[a])
                        next = c + stride[a];
                    else if (g->periodic[a] && g->n[a] > 1)
                        next = c - (long)(g->n[a] - 1) * stride[a];
                    if (next >= 0 && f[next] > threshold)
                        join(parent, c, next);
                }
            }
}

static double equivalent_diameter(const bdl_bubble_grid *g, double volume)
{
    for (int a = 0; a < 3; ++a)
        if (g->n[a] == 1 && a != g->up)
            return sqrt(4.0 * volume / (g->h[a] * PI)); // one cell deep: a circle's area
    return cbrt(6.0 * volume / PI);
}

bdl_result bdl_bubbles_find(const double *voidage, const bdl_bubble_grid *g, double threshold,
                            bdl_bubbles *out)
{
    *out = (bdl_bubbles){0};
    if (g->n[0] < 1 || g->n[1] < 1 || g->n[2] < 1 || g->up < 0 || g->up > 2)
        return BDL_ERR_ARGS;
    const long cells = (long)g->n[0] * g->n[1] * g->n[2];
    long *parent = malloc((size_t)cells * sizeof *parent);
    region *r = calloc((size_t)cells, sizeof *r);
    if (!parent || !r) {
        free(parent);
        free(r);
        return BDL_ERR_NOMEM;
    }
    for (long c = 0; c < cells; ++c)
        parent[c] = c;
    link_cells(voidage, g, threshold, parent);
    const double cell = g->h[0] * g->h[1] * g->h[2], hu = g->h[g->up];
    const int top = g->up_sign > 0 ? g->n[g->up] - 1 : 0;
    for (int k = 0; k < g->n[2]; ++k)
        for (int j = 0; j < g->n[1]; ++j)
            for (int i = 0; i < g->n[0]; ++i) {
                const long c = i + (long)g->n[0] * (j + (long)g->n[1] * k);
                if (!(voidage[c] > threshold))
                    continue;
                const int at[3] = {i, j, k}, layer = at[g->up];
                region *q = &r[find(parent, c)];
                q->volume += cell;
                q->height += cell * hu * (g->up_sign > 0 ? layer + 0.5 : g->n[g->up] - layer - 0.5);
                q->top = q->top || layer == top;
            }
    double diameters = 0.0, heights = 0.0;
    for (long c = 0; c < cells; ++c) {
        if (parent[c] != c || r[c].volume == 0.0 || r[c].top)
            continue;
        const double d = equivalent_diameter(g, r[c].volume);
        out->count++;
        out->volume += r[c].volume;
        diameters += d;
        heights += r[c].height;
        out->max_diameter = fmax(out->max_diameter, d);
    }
    if (out->count > 0) {
        out->mean_diameter = diameters / out->count;
        out->mean_height = heights / out->volume;
    }
    free(parent);
    free(r);
    return BDL_OK;
}
