// bedlam — the coupling's deposits in a fixed order: in one pass, or in chunks of particles summed
// on their own (in parallel) and then cell by cell in chunk order.
#include "core/parallel.h"
#include "couple/coupling_internal.h"

#include <limits.h>
#include <stdlib.h>
#include <string.h>

#include "core/comm.h"
#include "core/memory.h"

/// How many chunks `count` particles go in: 0 (one pass) when def.chunk is 0 or they fit in
/// one; else one per def.chunk particles, at most BDL_COUPLING_CHUNKS.
static long chunk_count(const bdl_coupling *c, long count)
{
    const long chunk = c->def.chunk;
    if (chunk <= 0 || count <= chunk)
        return 0;
    const long chunks = (count + chunk - 1) / chunk;
    return chunks < BDL_COUPLING_CHUNKS ? chunks : BDL_COUPLING_CHUNKS;
}

/// Room for n more chunk records.
static bdl_result reserve_records(bdl_coupling *c, long chunks)
{
    if (chunks <= c->chunk_capacity)
        return BDL_OK;
    if (!bdl_grow((void **)&c->chunk_lo, chunks, sizeof(long)) ||
        !bdl_grow((void **)&c->chunk_hi, chunks, sizeof(long)) ||
        !bdl_grow((void **)&c->chunk_base, chunks, sizeof(long)))
        return BDL_ERR_NOMEM;
    c->chunk_capacity = chunks;
    return BDL_OK;
}

bdl_result bdl_coupling_plan_chunks(bdl_coupling *c, long count)
{
    const long chunks = chunk_count(c, count);
    c->chunks = chunks;
    c->chunk_particles = chunks > 0 ? (count + chunks - 1) / chunks : count;
    c->chunk_planned = count;
    if (chunks == 0)
        return BDL_OK;
    if (reserve_records(c, chunks) != BDL_OK)
        return BDL_ERR_NOMEM;
    long total = 0;
    for (long k = 0; k < chunks; ++k) {
        const long from = k * c->chunk_particles;
        const long to = from + c->chunk_particles < count ? from + c->chunk_particles : count;
        long lo = LONG_MAX, hi = LONG_MIN;
        for (long pt = c->first[from]; pt < c->first[to]; ++pt) {
            lo = c->lo[pt] < lo ? c->lo[pt] : lo;
            hi = c->hi[pt] > hi ? c->hi[pt] : hi;
        }
        if (lo > hi) // no particle: an empty range
            lo = 0, hi = -1;
        c->chunk_lo[k] = lo, c->chunk_hi[k] = hi, c->chunk_base[k] = total;
        total += (hi - lo + 1) * BDL_COUPLING_FIELDS;
    }
    if (total <= c->pool_capacity)
        return BDL_OK;
    const long cap = total + total / 4;
    double *pool = calloc((size_t)cap, sizeof(double)); // kept zero between deposits
    if (!pool)
        return BDL_ERR_NOMEM;
    free(c->pool);
    c->pool = pool;
    c->pool_capacity = cap;
    return BDL_OK;
}

/// Chunk k's sums of field f: over its range, the first at chunk_lo[k].
static double *chunk_sums(const bdl_coupling *c, long k, int f)
{
    return c->pool + c->chunk_base[k] + f * (c->chunk_hi[k] - c->chunk_lo[k] + 1);
}

/// Sums each of the nf fields cell by cell over the chunks that reach the cell, in chunk order,
/// into out[] (zero where none does), and clears the chunks' sums for the next deposit. On a large
/// grid the cells go in blocks, in parallel: each cell's sum is made by one thread, in chunk order.
static void combine(const bdl_coupling *c, long size, int nf, double *const *out)
{
    const long *lo = c->chunk_lo, *hi = c->chunk_hi, block = 4096;
    const long blocks = (size + block - 1) / block;
    BDL_PARALLEL_FOR(
        size >= BDL_GRID_PARALLEL_MIN, for (long b = 0; b < blocks; ++b) {
            const long from = b * block, to = from + block < size ? from + block : size;
            for (int f = 0; f < nf; ++f) {
                memset(out[f] + from, 0, (size_t)(to - from) * sizeof(double));
                for (long k = 0; k < c->chunks; ++k) {
                    double *sum = chunk_sums(c, k, f);
                    const long first = lo[k] > from ? lo[k] : from;
                    const long last = hi[k] < to - 1 ? hi[k] : to - 1;
                    for (long idx = first; idx <= last; ++idx)
                        out[f][idx] += sum[idx - lo[k]];
                    if (first <= last)
                        memset(sum + (first - lo[k]), 0,
                               (size_t)(last - first + 1) * sizeof(double));
                }
            }
        });
}

void bdl_coupling_deposit(const bdl_coupling *c, const bdl_grid *g, long count, int nf,
                          double *const *out, bdl_deposit_fn *fn, const void *ctx)
{
    BDL_ASSERT(nf <= BDL_COUPLING_FIELDS && c->chunk_planned == count);
    if (c->chunks == 0) {
        for (int f = 0; f < nf; ++f)
            memset(out[f], 0, (size_t)g->size * sizeof(double));
        for (long i = 0; i < count; ++i)
            fn(c, ctx, i, 0, out);
    }
    BDL_PARALLEL_FOR(
        count >= c->parallel_min, for (long k = 0; k < c->chunks; ++k) {
            const long from = k * c->chunk_particles;
            const long to = from + c->chunk_particles < count ? from + c->chunk_particles : count;
            double *sums[BDL_COUPLING_FIELDS];
            for (int f = 0; f < nf; ++f)
                sums[f] = chunk_sums(c, k, f);
            for (long i = from; i < to; ++i)
                fn(c, ctx, i, c->chunk_lo[k], sums);
        });
    if (c->chunks > 0)
        combine(c, g->size, nf, out);
    for (int f = 0; f < nf && c->divided; ++f) // every rank's particles
        bdl_comm_sum(out[f], (int)g->size);
}
