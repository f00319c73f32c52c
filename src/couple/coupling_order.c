// bedlam — particles in the order of the gas cells that hold them, so that the kernels' deposits
// and reads of neighbouring particles touch neighbouring memory.
#include "couple/coupling.h"

#include <stdlib.h>
#include <string.h>

#include "core/memory.h"

/// The cell holding x, clamped to the grid: its number among the grid's cells, x fastest.
static int32_t cell_key(const bdl_grid *g, const double inv_h[3], bdl_vec3 x)
{
    int32_t key = 0;
    for (int a = 2; a >= 0; --a) {
        const double u = (bdl_v3_comp(x, a) - g->origin[a]) * inv_h[a];
        const int m = !(u > 0.0) ? 0 : u < g->n[a] - 1 ? (int)u : g->n[a] - 1;
        key = key * g->n[a] + m;
    }
    return key;
}

/// Room for the sort of n particles over `cells` cells.
static bdl_result reserve_order(bdl_coupling *c, long n, long cells)
{
    if (n > c->order_capacity) {
        const long cap = n + n / 4 + 64;
        if (!bdl_grow((void **)&c->order_key, cap, sizeof(int32_t)) ||
            !bdl_grow((void **)&c->order_perm, cap, sizeof(int32_t)) ||
            !bdl_grow((void **)&c->order_scratch, cap, sizeof(bdl_vec3)))
            return BDL_ERR_NOMEM;
        c->order_capacity = cap;
    }
    if (!c->order_start && !(c->order_start = calloc((size_t)cells + 1, sizeof(int32_t))))
        return BDL_ERR_NOMEM;
    return BDL_OK;
}

bdl_result bdl_coupling_sort(bdl_coupling *c, const bdl_gas *gas, bdl_particles *p, int *sorted)
{
    const bdl_grid *g = &gas->grid;
    const long n = p->count, cells = (long)g->n[0] * g->n[1] * g->n[2];
    if (sorted)
        *sorted = 0;
    if (reserve_order(c, n, cells) != BDL_OK)
        return BDL_ERR_NOMEM;
    long descents = 0; // a loop too light to be worth a parallel region
    for (long i = 0; i < n; ++i) {
        c->order_key[i] = cell_key(g, c->inv_h, p->pos[i]);
        descents += i > 0 && c->order_key[i] < c->order_key[i - 1];
    }
    if (descents <= n / BDL_COUPLING_DISORDER)
        return BDL_OK;
    // A stable counting sort: perm[new] = old.
    int32_t *start = c->order_start;
    memset(start, 0, (size_t)(cells + 1) * sizeof(int32_t));
    for (long i = 0; i < n; ++i)
        start[c->order_key[i] + 1]++;
    for (long k = 0; k < cells; ++k)
        start[k + 1] += start[k];
    for (long i = 0; i < n; ++i)
        c->order_perm[start[c->order_key[i]]++] = (int32_t)i;
    bdl_particles_permute(p, c->order_perm, c->order_scratch);
    if (sorted)
        *sorted = 1;
    return BDL_OK;
}
