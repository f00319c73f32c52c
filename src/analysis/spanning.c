#include "analysis/spanning.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/// How many passes chose each edge: open addressing on the key i * n + j (i < j).
typedef struct edge_counts {
    int64_t *key; ///< -1: empty
    int32_t *count;
    long capacity; ///< a power of two
} edge_counts;

static long slot_of(const edge_counts *h, int64_t key)
{
    uint64_t x = (uint64_t)key * 0x9E3779B97F4A7C15ull;
    long s = (long)(x >> 17) & (h->capacity - 1);
    while (h->key[s] != -1 && h->key[s] != key)
        s = (s + 1) & (h->capacity - 1);
    return s;
}

static int32_t times_chosen(const edge_counts *h, int64_t key)
{
    const long s = slot_of(h, key);
    return h->key[s] == key ? h->count[s] : 0;
}

/// One pass of Prim's algorithm over the centres that take part; each chosen edge is counted
/// in h and, the first time, appended to edges.
static void prim_pass(long n, const bdl_vec3 *pos, const uint8_t *part, double factor, int pass,
                      edge_counts *h, double *best, int32_t *from, uint8_t *done,
                      bdl_span_edge *edges, long *count)
{
    long start = -1;
    for (long i = 0; i < n; ++i) {
        best[i] = INFINITY, from[i] = -1, done[i] = !part[i];
        start = start < 0 && part[i] ? i : start;
    }
    for (long u = start; u >= 0;) {
        done[u] = 1;
        if (from[u] >= 0) {
            const int32_t a = from[u] < u ? from[u] : (int32_t)u,
                          b = from[u] < u ? (int32_t)u : from[u];
            const int64_t key = (int64_t)a * n + b;
            const long s = slot_of(h, key);
            if (h->key[s] != key) {
                h->key[s] = key, h->count[s] = 0;
                edges[(*count)++] = (bdl_span_edge){a, b, pass};
            }
            h->count[s]++;
        }
        long next = -1;
        for (long v = 0; v < n; ++v) {
            if (done[v])
                continue;
            const int64_t key = u < v ? (int64_t)u * n + v : (int64_t)v * n + u;
            double w = bdl_v3_len(bdl_v3_sub(pos[u], pos[v]));
            for (int32_t k = times_chosen(h, key); k > 0; --k)
                w *= factor;
            if (w < best[v])
                best[v] = w, from[v] = (int32_t)u;
            if (next < 0 || best[v] < best[next])
                next = v;
        }
        u = next;
    }
}

bdl_result bdl_spanning_passes(long n, const bdl_vec3 *pos, int passes, double factor,
                               bdl_span_edge *edges, long *count)
{
    *count = 0;
    if (n < 2 || passes < 1)
        return BDL_OK;
    edge_counts h = {.capacity = 1024};
    while (h.capacity < 2L * passes * n)
        h.capacity *= 2;
    h.key = malloc((size_t)h.capacity * sizeof *h.key);
    h.count = malloc((size_t)h.capacity * sizeof *h.count);
    double *best = malloc((size_t)n * sizeof *best);
    int32_t *from = malloc((size_t)n * sizeof *from);
    uint8_t *done = malloc((size_t)n), *part = malloc((size_t)n);
    bdl_result r = h.key && h.count && best && from && done && part ? BDL_OK : BDL_ERR_NOMEM;
    if (r == BDL_OK) {
        memset(h.key, 0xff, (size_t)h.capacity * sizeof *h.key);
        for (long i = 0; i < n; ++i)
            part[i] = bdl_v3_isfinite(pos[i]);
        for (int p = 1; p <= passes; ++p)
            prim_pass(n, pos, part, factor, p, &h, best, from, done, edges, count);
    }
    free(h.key), free(h.count), free(best), free(from), free(done), free(part);
    return r;
}

void bdl_force_correlation(long n, const bdl_vec3 *at, const double *f, int bins, double dr,
                           double *F, long *pairs)
{
    double *sum = calloc((size_t)bins, sizeof *sum);
    long *m = calloc((size_t)bins, sizeof *m);
    if (sum && m)
        for (long a = 0; a < n; ++a)
            for (long b = a + 1; b < n; ++b) {
                const double r = bdl_v3_len(bdl_v3_sub(at[a], at[b]));
                const long k = (long)floor(r / dr);
                if (k < bins) {
                    sum[k] += f[a] * f[b];
                    m[k]++;
                }
            }
    for (int k = 0; k < bins; ++k) {
        F[k] = sum && m && m[k] > 0 ? sum[k] / (double)m[k] : NAN;
        if (pairs)
            pairs[k] = sum && m ? m[k] : 0;
    }
    free(sum), free(m);
}
