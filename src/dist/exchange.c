#include "dist/exchange.h"

#include <limits.h>
#include <stdlib.h>
#include <string.h>

#include "core/comm.h"
#include "core/memory.h"

#if defined(BDL_WITH_MPI)
#include <mpi.h>

typedef struct id_slot {
    uint32_t id;
    int32_t index;
} id_slot;

/// Doubles per ghost in a refresh: position, velocity, spin.
#define REFRESH 9

struct bdl_dist {
    bdl_decomp d;
    long owned, ghosts;
    long migrated, rebuilds;
    // The ghosts this rank sends at each refresh, grouped by rank: its own particle and the shift.
    int32_t *send_index;
    bdl_vec3 *send_shift;
    long send_capacity;
    int *send_count, *send_displ, *recv_count, *recv_displ; ///< per rank, in entries
    int *byte_count, *byte_displ, *rbyte_count, *rbyte_displ;
    double *send_buf, *recv_buf;
    long send_buf_capacity, recv_buf_capacity;
    // The ids of the particles the lists were built for, by their index then: the contact
    // history is found by them however the particles were moved since.
    id_slot *built;
    long built_count;
};

bdl_result bdl_dist_create(const bdl_decomp *d, bdl_dist **out)
{
    bdl_dist *dd = calloc(1, sizeof *dd);
    if (!dd)
        return BDL_ERR_NOMEM;
    dd->d = *d;
    const size_t n = (size_t)d->size;
    dd->send_count = calloc(n, sizeof(int));
    dd->send_displ = calloc(n + 1, sizeof(int));
    dd->recv_count = calloc(n, sizeof(int));
    dd->recv_displ = calloc(n + 1, sizeof(int));
    dd->byte_count = calloc(n, sizeof(int));
    dd->byte_displ = calloc(n + 1, sizeof(int));
    dd->rbyte_count = calloc(n, sizeof(int));
    dd->rbyte_displ = calloc(n + 1, sizeof(int));
    if (!dd->send_count || !dd->send_displ || !dd->recv_count || !dd->recv_displ ||
        !dd->byte_count || !dd->byte_displ || !dd->rbyte_count || !dd->rbyte_displ)
        bdl_comm_abort("out of memory dividing the particles"); // the others go on to exchange
    *out = dd;
    return BDL_OK;
}

void bdl_dist_destroy(bdl_dist *dd)
{
    if (!dd)
        return;
    free(dd->send_index);
    free(dd->send_shift);
    free(dd->send_count);
    free(dd->send_displ);
    free(dd->recv_count);
    free(dd->recv_displ);
    free(dd->byte_count);
    free(dd->byte_displ);
    free(dd->rbyte_count);
    free(dd->rbyte_displ);
    free(dd->send_buf);
    free(dd->recv_buf);
    free(dd->built);
    free(dd);
}

const bdl_decomp *bdl_dist_decomp(const bdl_dist *dd) { return &dd->d; }
long bdl_dist_owned(const bdl_dist *dd) { return dd->owned; }
long bdl_dist_ghosts(const bdl_dist *dd) { return dd->ghosts; }
long bdl_dist_migrated(const bdl_dist *dd) { return dd->migrated; }
long bdl_dist_rebuilds(const bdl_dist *dd) { return dd->rebuilds; }

int bdl_dist_any(int mine)
{
    int any = mine;
    MPI_Allreduce(&mine, &any, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
    return any;
}

// ---------------------------------------------------------------------------------------------
// Whole particles: every array of the table, packed one particle after the other.

static int all_arrays(const bdl_particles *p, bdl_particle_array *arrays, size_t *bytes)
{
    const int n = bdl_particles_arrays(
        p, BDL_ARRAYS_ALWAYS | BDL_ARRAYS_WITH_GAS | BDL_ARRAYS_WITH_RODS | BDL_ARRAYS_WITH_PARCELS,
        arrays);
    *bytes = 0;
    for (int a = 0; a < n; ++a)
        *bytes += arrays[a].element;
    return n;
}

/// Particle `from` copied to slot `to` in every array (a compaction: to <= from).
static void move_particle(bdl_particles *p, long from, long to)
{
    if (from == to)
        return;
    bdl_particle_array arrays[BDL_PARTICLE_ARRAYS];
    size_t bytes;
    const int n = all_arrays(p, arrays, &bytes);
    for (int a = 0; a < n; ++a)
        memcpy((char *)arrays[a].data + (size_t)to * arrays[a].element,
               (const char *)arrays[a].data + (size_t)from * arrays[a].element, arrays[a].element);
}

static void pack(const bdl_particles *p, long i, bdl_vec3 shift, char *out)
{
    bdl_particle_array arrays[BDL_PARTICLE_ARRAYS];
    size_t bytes;
    const int n = all_arrays(p, arrays, &bytes);
    for (int a = 0; a < n; ++a) {
        memcpy(out, (const char *)arrays[a].data + (size_t)i * arrays[a].element,
               arrays[a].element);
        out += arrays[a].element;
    }
    bdl_vec3 x = p->pos[i];
    x = bdl_v3_add(x, shift);
    memcpy(out - bytes, &x, sizeof x); // pos is the table's first array
}

static void unpack(bdl_particles *p, long i, const char *in)
{
    bdl_particle_array arrays[BDL_PARTICLE_ARRAYS];
    size_t bytes;
    const int n = all_arrays(p, arrays, &bytes);
    for (int a = 0; a < n; ++a) {
        memcpy((char *)arrays[a].data + (size_t)i * arrays[a].element, in, arrays[a].element);
        in += arrays[a].element;
    }
}

/// Sends, per rank, the particles listed (index and shift, grouped by rank: counts[r] of them
/// from displ[r]), and appends what arrives after slot `at`; returns the count received (out of
/// memory ends the job: the others wait in the exchange). recv_count and recv_displ get the
/// counts received per rank.
static long send_particles(bdl_dist *dd, bdl_particles *p, const int32_t *index,
                           const bdl_vec3 *shift, const int *counts, const int *displ, long at,
                           int *recv_count, int *recv_displ)
{
    bdl_particle_array arrays[BDL_PARTICLE_ARRAYS];
    size_t bytes;
    all_arrays(p, arrays, &bytes);
    const int size = dd->d.size;
    MPI_Alltoall(counts, 1, MPI_INT, recv_count, 1, MPI_INT, MPI_COMM_WORLD);
    long sent = 0, got = 0;
    for (int r = 0; r < size; ++r)
        sent += counts[r], got += recv_count[r];
    if ((double)sent * (double)bytes > INT_MAX || (double)got * (double)bytes > INT_MAX)
        bdl_comm_abort("more than 2 GB of particles to send between two exchanges: use more ranks");
    got = 0;
    for (int r = 0; r < size; ++r) { // in bytes: below 2^31 (checked above)
        dd->byte_count[r] = (int)((long)counts[r] * (long)bytes);
        dd->byte_displ[r] = (int)((long)displ[r] * (long)bytes);
        recv_displ[r] = (int)got;
        dd->rbyte_count[r] = (int)((long)recv_count[r] * (long)bytes);
        dd->rbyte_displ[r] = (int)(got * (long)bytes);
        got += recv_count[r];
    }
    recv_displ[size] = (int)got;
    char *out = malloc((size_t)(sent > 0 ? sent : 1) * bytes);
    char *in = malloc((size_t)(got > 0 ? got : 1) * bytes);
    if (!out || !in || bdl_particles_reserve(p, at + got + 16) != BDL_OK)
        bdl_comm_abort("out of memory in a particle exchange"); // the others wait in it
    for (long e = 0; e < sent; ++e)
        pack(p, index[e], shift ? shift[e] : bdl_v3_zero(), out + (size_t)e * bytes);
    MPI_Alltoallv(out, dd->byte_count, dd->byte_displ, MPI_BYTE, in, dd->rbyte_count,
                  dd->rbyte_displ, MPI_BYTE, MPI_COMM_WORLD);
    for (long e = 0; e < got; ++e)
        unpack(p, at + e, in + (size_t)e * bytes);
    free(out);
    free(in);
    return got;
}

// ---------------------------------------------------------------------------------------------
// Old indices by id, for the contact history.

static int compare_id(const void *a, const void *b)
{
    const uint32_t x = ((const id_slot *)a)->id, y = ((const id_slot *)b)->id;
    return (x > y) - (x < y);
}

static id_slot *index_ids(const bdl_particles *p, long n)
{
    id_slot *slots = malloc((size_t)(n > 0 ? n : 1) * sizeof *slots);
    if (!slots)
        return NULL;
    for (long i = 0; i < n; ++i)
        slots[i] = (id_slot){p->id[i], (int32_t)i};
    qsort(slots, (size_t)n, sizeof *slots, compare_id);
    return slots;
}

static int32_t old_index(const id_slot *slots, long n, uint32_t id)
{
    const id_slot key = {id, 0};
    const id_slot *hit = bsearch(&key, slots, (size_t)n, sizeof *slots, compare_id);
    return hit ? hit->index : -1;
}

// ---------------------------------------------------------------------------------------------
// Ghosts and lists.

/// The ghosts' send list from this rank's (sorted) particles: those near its faces, per rank.
static bdl_result list_ghosts(bdl_dist *dd, const bdl_particles *p)
{
    const int size = dd->d.size;
    memset(dd->send_count, 0, (size_t)size * sizeof(int));
    int ranks[BDL_DECOMP_MAX_TARGETS];
    bdl_vec3 shifts[BDL_DECOMP_MAX_TARGETS];
    long total = 0;
    for (long i = 0; i < dd->owned; ++i) {
        const int n = bdl_decomp_ghost_targets(&dd->d, p->pos[i], ranks, shifts);
        for (int t = 0; t < n; ++t)
            dd->send_count[ranks[t]]++;
        total += n;
    }
    if (total > dd->send_capacity) {
        const long cap = total + total / 4 + 64;
        if (!bdl_grow((void **)&dd->send_index, cap, sizeof(int32_t)) ||
            !bdl_grow((void **)&dd->send_shift, cap, sizeof(bdl_vec3)))
            bdl_comm_abort("out of memory listing ghosts"); // the others go on to exchange
        dd->send_capacity = cap;
    }
    dd->send_displ[0] = 0;
    for (int r = 0; r < size; ++r)
        dd->send_displ[r + 1] = dd->send_displ[r] + dd->send_count[r];
    int *cursor = malloc((size_t)size * sizeof *cursor);
    if (!cursor)
        bdl_comm_abort("out of memory listing ghosts");
    memcpy(cursor, dd->send_displ, (size_t)size * sizeof *cursor);
    for (long i = 0; i < dd->owned; ++i) {
        const int n = bdl_decomp_ghost_targets(&dd->d, p->pos[i], ranks, shifts);
        for (int t = 0; t < n; ++t) {
            const int e = cursor[ranks[t]]++;
            dd->send_index[e] = (int32_t)i;
            dd->send_shift[e] = shifts[t];
        }
    }
    free(cursor);
    return BDL_OK;
}

/// After the owned particles are in place (p->count = owned): sorts them, takes the ghosts and
/// builds the lists, carrying history from the `old` slots (old_count of them, by id).
static bdl_result settle(bdl_dist *dd, bdl_particles *p, bdl_neighbor *nb, const bdl_walls *walls)
{
    const id_slot *old = dd->built;
    const long old_count = dd->built_count;
    p->count = dd->owned;
    bdl_result r = bdl_neighbor_sort(nb, p);
    if (r == BDL_OK)
        r = list_ghosts(dd, p);
    if (r != BDL_OK) // the others go on to the exchange below
        bdl_comm_abort("out of memory sorting the particles at a rebuild");
    const long got = send_particles(dd, p, dd->send_index, dd->send_shift, dd->send_count,
                                    dd->send_displ, dd->owned, dd->recv_count, dd->recv_displ);
    dd->ghosts = got;
    const long total = dd->owned + dd->ghosts;
    int32_t *origin = malloc((size_t)(total > 0 ? total : 1) * sizeof *origin);
    if (!origin)
        bdl_comm_abort("out of memory at a rebuild");
    for (long i = 0; i < total; ++i)
        origin[i] = old_index(old, old_count, p->id[i]);
    p->count = total;
    r = bdl_neighbor_build_from(nb, p, walls, origin, dd->owned);
    free(origin);
    if (r == BDL_OK) {
        free(dd->built);
        dd->built = index_ids(p, total);
        dd->built_count = total;
        r = dd->built ? BDL_OK : BDL_ERR_NOMEM;
    }
    p->count = dd->owned;
    dd->rebuilds++;
    return r;
}

bdl_result bdl_dist_start(bdl_dist *dd, bdl_particles *p, bdl_neighbor *nb, const bdl_walls *walls)
{
    const long all = p->count;
    free(dd->built);
    dd->built = index_ids(p, all); // the whole run's lists, built on every rank
    dd->built_count = all;
    if (!dd->built)
        bdl_comm_abort("out of memory dividing the particles");
    // Every rank has every particle: each keeps its own, in their order (no message).
    long kept = 0;
    for (long i = 0; i < all; ++i) {
        const bdl_vec3 x = bdl_decomp_wrap(&dd->d, p->pos[i]);
        if (bdl_decomp_owner(&dd->d, x) != dd->d.rank)
            continue;
        move_particle(p, i, kept);
        p->pos[kept] = x;
        ++kept;
    }
    dd->owned = kept;
    return settle(dd, p, nb, walls);
}

/// The springs of the touching contacts of the own particles that leave (dest[i] != this rank),
/// per destination: its pairs (with any partner) and its walls. They go with the particle: the
/// rank it goes to may hold a pair of two of its ghosts whose copy began after the contact did
/// (when the two came into its margin touching); the owner's copy is the one that counts.
static bdl_dist_spring *leaving_springs(const bdl_dist *dd, const bdl_particles *p,
                                        const bdl_neighbor *nb, const int *dest, int *counts,
                                        long *total)
{
    const int me = dd->d.rank, size = dd->d.size;
    const long owned = dd->owned;
    memset(counts, 0, (size_t)size * sizeof *counts);
    long n = 0;
    for (int pass = 0; pass < 2; ++pass) { // count, then fill grouped by destination
        bdl_dist_spring *out = NULL;
        int *cursor = NULL;
        if (pass == 1) {
            out = malloc((size_t)(n > 0 ? n : 1) * sizeof *out);
            cursor = calloc((size_t)size + 1, sizeof *cursor);
            if (!out || !cursor)
                bdl_comm_abort("out of memory sending the springs of migrating particles");
            for (int q = 0; q < size; ++q)
                cursor[q + 1] = cursor[q] + counts[q];
        }
        for (long f = 0; nb->history && f < nb->count; ++f) {
            const int leaves_f = f < owned && dest[f] != me;
            for (int32_t k = nb->start[f]; k < nb->start[f + 1]; ++k) {
                const long j = nb->partner[k];
                const int leaves_j = j < owned && dest[j] != me;
                if (!nb->touching[k] || (!leaves_f && !leaves_j))
                    continue;
                const uint32_t a = p->id[f], b = p->id[j];
                const bdl_dist_spring sp = {a < b ? a : b,
                                            a < b ? b : a,
                                            -1,
                                            0,
                                            a < b ? nb->history[k] : bdl_v3_neg(nb->history[k]),
                                            nb->spring_work ? nb->spring_work[k] : 0.0};
                for (int side = 0; side < 2; ++side) {
                    const long i = side ? j : f;
                    if (!(side ? leaves_j : leaves_f))
                        continue;
                    if (pass == 0)
                        counts[dest[i]]++, ++n;
                    else
                        out[cursor[dest[i]]++] = sp;
                }
            }
            for (int32_t k = nb->wall_start[f]; leaves_f && k < nb->wall_start[f + 1]; ++k) {
                if (!nb->wall_touching[k])
                    continue;
                if (pass == 0) {
                    counts[dest[f]]++, ++n;
                    continue;
                }
                out[cursor[dest[f]]++] =
                    (bdl_dist_spring){p->id[f],
                                      0,
                                      nb->wall_prim[k],
                                      0,
                                      nb->wall_history[k],
                                      nb->wall_spring_work ? nb->wall_spring_work[k] : 0.0};
            }
        }
        if (pass == 1) {
            free(cursor);
            *total = n;
            return out;
        }
    }
    return NULL;
}

/// Sends the springs (counts[r] of them to rank r, grouped by rank); returns those received,
/// sorted by (a, b, wall), their number in *got.
static bdl_dist_spring *send_springs(const bdl_dist *dd, const bdl_dist_spring *springs,
                                     const int *counts, long *got)
{
    const int size = dd->d.size, record = (int)sizeof *springs;
    int *rc = calloc((size_t)size, sizeof *rc), *sb = calloc((size_t)size, sizeof *sb),
        *sd = calloc((size_t)size, sizeof *sd), *rb = calloc((size_t)size, sizeof *rb),
        *rdp = calloc((size_t)size, sizeof *rdp);
    if (!rc || !sb || !sd || !rb || !rdp)
        bdl_comm_abort("out of memory sending springs");
    MPI_Alltoall(counts, 1, MPI_INT, rc, 1, MPI_INT, MPI_COMM_WORLD);
    long sent = 0, in = 0;
    for (int q = 0; q < size; ++q) {
        sb[q] = counts[q] * record, sd[q] = (int)(sent * record), sent += counts[q];
        rb[q] = rc[q] * record, rdp[q] = (int)(in * record), in += rc[q];
    }
    bdl_dist_spring *recv = malloc((size_t)(in > 0 ? in : 1) * sizeof *recv);
    if (!recv)
        bdl_comm_abort("out of memory receiving springs");
    MPI_Alltoallv(springs, sb, sd, MPI_BYTE, recv, rb, rdp, MPI_BYTE, MPI_COMM_WORLD);
    qsort(recv, (size_t)in, sizeof *recv, bdl_dist_spring_order);
    free(rc), free(sb), free(sd), free(rb), free(rdp);
    *got = in;
    return recv;
}

/// The springs that came with the arrivals put into the new lists: each listed pair or wall
/// contact they name gets the owner's spring (turned to be seen from the lower index).
static void apply_springs(const bdl_particles *p, long count, bdl_neighbor *nb,
                          const bdl_dist_spring *springs, long n)
{
    if (n == 0 || !nb->history)
        return;
    id_slot *at = index_ids(p, count);
    if (!at)
        bdl_comm_abort("out of memory placing springs");
    for (long e = 0; e < n; ++e) {
        const bdl_dist_spring *sp = &springs[e];
        const int32_t ia = old_index(at, count, sp->a);
        const int32_t ib = sp->wall < 0 ? old_index(at, count, sp->b) : -1;
        if (ia < 0 || (sp->wall < 0 && ib < 0))
            continue;
        if (sp->wall >= 0) {
            for (int32_t k = nb->wall_start[ia]; k < nb->wall_start[ia + 1]; ++k)
                if (nb->wall_prim[k] == sp->wall) {
                    nb->wall_history[k] = sp->u;
                    nb->wall_touching[k] = 1;
                    if (nb->wall_spring_work)
                        nb->wall_spring_work[k] = sp->work;
                }
            continue;
        }
        const int32_t lo = ia < ib ? ia : ib, hi = ia < ib ? ib : ia;
        for (int32_t k = nb->start[lo]; k < nb->start[lo + 1]; ++k)
            if (nb->partner[k] == hi) {
                nb->history[k] = ia < ib ? sp->u : bdl_v3_neg(sp->u); // a has the lower id
                nb->touching[k] = 1;
                if (nb->spring_work)
                    nb->spring_work[k] = sp->work;
            }
    }
    free(at);
}

bdl_result bdl_dist_rebuild(bdl_dist *dd, bdl_particles *p, bdl_neighbor *nb,
                            const bdl_walls *walls)
{
    const int size = dd->d.size;
    const long old_count = dd->owned + dd->ghosts;
    int32_t *leave = malloc((size_t)(dd->owned > 0 ? dd->owned : 1) * sizeof *leave);
    int *dest = malloc((size_t)(dd->owned > 0 ? dd->owned : 1) * sizeof *dest);
    int *counts = calloc((size_t)size, sizeof *counts),
        *displ = calloc((size_t)size + 1, sizeof *displ);
    int *rc = calloc((size_t)size, sizeof *rc), *rd = calloc((size_t)size + 1, sizeof *rd);
    if (!leave || !dest || !counts || !displ || !rc || !rd)
        bdl_comm_abort("out of memory at a rebuild"); // the others go on to its exchanges
    bdl_result r = BDL_OK;
    long leaving = 0;
    for (long i = 0; r == BDL_OK && i < dd->owned; ++i) {
        p->pos[i] = bdl_decomp_wrap(&dd->d, p->pos[i]);
        dest[i] = bdl_decomp_owner(&dd->d, p->pos[i]);
        if (dest[i] != dd->d.rank)
            counts[dest[i]]++, ++leaving;
    }
    // The springs of the leaving particles first: the old lists still index them.
    long spring_count = 0, springs_got = 0;
    bdl_dist_spring *springs_out = leaving_springs(dd, p, nb, dest, rc, &spring_count);
    bdl_dist_spring *springs_in = send_springs(dd, springs_out, rc, &springs_got);
    free(springs_out);
    if (r == BDL_OK) {
        for (int q = 0; q < size; ++q)
            displ[q + 1] = displ[q] + counts[q];
        memcpy(rc, displ, (size_t)size * sizeof *rc); // a cursor for now
        for (long i = 0; i < dd->owned; ++i)
            if (dest[i] != dd->d.rank)
                leave[rc[dest[i]]++] = (int32_t)i;
        // The old ghosts are dropped: the arrivals go after the own particles.
        const long got = send_particles(dd, p, leave, NULL, counts, displ, old_count, rc, rd);
        // Keep the own that stay, then the arrivals (parked after the old ghosts).
        long kept = 0;
        for (long i = 0; i < dd->owned + got; ++i) {
            if (i < dd->owned && dest[i] != dd->d.rank)
                continue;
            move_particle(p, i < dd->owned ? i : old_count + (i - dd->owned), kept++);
        }
        dd->owned = kept;
        dd->migrated += leaving;
        r = settle(dd, p, nb, walls);
        if (r == BDL_OK)
            apply_springs(p, dd->owned + dd->ghosts, nb, springs_in, springs_got);
    }
    free(springs_in);
    free(leave);
    free(dest);
    free(counts);
    free(displ);
    free(rc);
    free(rd);
    return r;
}

bdl_result bdl_dist_remove(bdl_dist *dd, bdl_particles *p, const uint8_t *drop)
{
    long kept = 0;
    for (long i = 0; i < dd->owned; ++i)
        if (!drop[i])
            move_particle(p, i, kept++);
    // The exchange plan stays as it is until the rebuild: a refresh before it moves stale values
    // between the slots after the own particles, which the rebuild then replaces.
    dd->owned = kept;
    p->count = kept;
    return BDL_OK;
}

bdl_result bdl_dist_refresh(bdl_dist *dd, bdl_particles *p)
{
    const int size = dd->d.size;
    const long sent = dd->send_displ[size], got = dd->ghosts;
    if (sent * REFRESH > dd->send_buf_capacity) {
        if (!bdl_grow((void **)&dd->send_buf, sent * REFRESH + 64, sizeof(double)))
            bdl_comm_abort("out of memory refreshing ghosts");
        dd->send_buf_capacity = sent * REFRESH + 64;
    }
    if (got * REFRESH > dd->recv_buf_capacity) {
        if (!bdl_grow((void **)&dd->recv_buf, got * REFRESH + 64, sizeof(double)))
            bdl_comm_abort("out of memory refreshing ghosts");
        dd->recv_buf_capacity = got * REFRESH + 64;
    }
    for (long e = 0; e < sent; ++e) {
        const long i = dd->send_index[e];
        const bdl_vec3 x = bdl_v3_add(p->pos[i], dd->send_shift[e]);
        double *b = dd->send_buf + e * REFRESH;
        b[0] = x.x, b[1] = x.y, b[2] = x.z;
        b[3] = p->vel[i].x, b[4] = p->vel[i].y, b[5] = p->vel[i].z;
        b[6] = p->omega[i].x, b[7] = p->omega[i].y, b[8] = p->omega[i].z;
    }
    for (int r = 0; r < size; ++r) {
        dd->byte_count[r] = dd->send_count[r] * REFRESH;
        dd->byte_displ[r] = dd->send_displ[r] * REFRESH;
        dd->rbyte_count[r] = dd->recv_count[r] * REFRESH;
        dd->rbyte_displ[r] = dd->recv_displ[r] * REFRESH;
    }
    MPI_Alltoallv(dd->send_buf, dd->byte_count, dd->byte_displ, MPI_DOUBLE, dd->recv_buf,
                  dd->rbyte_count, dd->rbyte_displ, MPI_DOUBLE, MPI_COMM_WORLD);
    for (long e = 0; e < got; ++e) {
        const long i = dd->owned + e;
        const double *b = dd->recv_buf + e * REFRESH;
        p->pos[i] = bdl_v3(b[0], b[1], b[2]);
        p->vel[i] = bdl_v3(b[3], b[4], b[5]);
        p->omega[i] = bdl_v3(b[6], b[7], b[8]);
        p->load[i] = (bdl_wrench){bdl_v3_zero(), bdl_v3_zero()};
    }
    return BDL_OK;
}

// ---------------------------------------------------------------------------------------------
// Gathering.

typedef struct gathered_row {
    double pos[3], vel[3], omega[3];
    uint32_t id, pad;
} gathered_row;

static int compare_row(const void *a, const void *b)
{
    const uint32_t x = ((const gathered_row *)a)->id, y = ((const gathered_row *)b)->id;
    return (x > y) - (x < y);
}

/// Gathers `mine` bytes from every rank on root; *all (malloc'ed on root) gets them in rank
/// order, *total their size.
static bdl_result gather_bytes(const void *mine, long bytes, int root, char **all, long *total)
{
    int rank = 0, size = 1;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    if (bytes > INT_MAX)
        bdl_comm_abort("a rank's part of the gathered state is above 2 GB: use more ranks");
    const int n = (int)bytes;
    int *counts = calloc((size_t)size, sizeof *counts),
        *displ = calloc((size_t)size, sizeof *displ);
    if (!counts || !displ)
        bdl_comm_abort("out of memory gathering the state"); // the others wait in the gather
    bdl_result r = BDL_OK;
    MPI_Gather(&n, 1, MPI_INT, counts, 1, MPI_INT, root, MPI_COMM_WORLD);
    *total = 0;
    *all = NULL;
    if (rank == root) {
        for (int q = 0; q < size; ++q) {
            if (*total + counts[q] > INT_MAX) // MPI's displacements are ints
                bdl_comm_abort("the gathered state is above 2 GB: the first rank cannot hold it "
                               "for the outputs (a run this large needs parallel output)");
            displ[q] = (int)*total, *total += counts[q];
        }
        *all = malloc((size_t)(*total > 0 ? *total : 1));
        if (!*all)
            bdl_comm_abort("out of memory gathering the state on the first rank");
    }
    MPI_Gatherv(mine, n, MPI_BYTE, *all, counts, displ, MPI_BYTE, root, MPI_COMM_WORLD);
    free(counts);
    free(displ);
    return r;
}

bdl_result bdl_dist_gather(const bdl_particles *p, int root, bdl_dist_gathered *out)
{
    memset(out, 0, sizeof *out);
    gathered_row *rows = malloc((size_t)(p->count > 0 ? p->count : 1) * sizeof *rows);
    for (long i = 0; rows && i < p->count; ++i) {
        const bdl_vec3 x = p->pos[i], v = p->vel[i], w = p->omega[i];
        rows[i] = (gathered_row){{x.x, x.y, x.z}, {v.x, v.y, v.z}, {w.x, w.y, w.z}, p->id[i], 0};
    }
    char *bytes = NULL;
    long total = 0;
    bdl_result r =
        gather_bytes(rows, rows ? p->count * (long)sizeof *rows : 0, root, &bytes, &total);
    gathered_row *all = (gathered_row *)bytes;
    const long n = total / (long)sizeof(gathered_row);
    if (r == BDL_OK && all) {
        qsort(all, (size_t)n, sizeof *all, compare_row);
        out->count = n;
        out->id = malloc((size_t)(n > 0 ? n : 1) * sizeof *out->id);
        out->pos = malloc((size_t)(n > 0 ? n : 1) * sizeof *out->pos);
        out->vel = malloc((size_t)(n > 0 ? n : 1) * sizeof *out->vel);
        out->omega = malloc((size_t)(n > 0 ? n : 1) * sizeof *out->omega);
        if (!out->id || !out->pos || !out->vel || !out->omega)
            r = BDL_ERR_NOMEM;
        for (long i = 0; r == BDL_OK && i < n; ++i) {
            out->id[i] = all[i].id;
            out->pos[i] = bdl_v3(all[i].pos[0], all[i].pos[1], all[i].pos[2]);
            out->vel[i] = bdl_v3(all[i].vel[0], all[i].vel[1], all[i].vel[2]);
            out->omega[i] = bdl_v3(all[i].omega[0], all[i].omega[1], all[i].omega[2]);
        }
    }
    free(all);
    free(rows);
    return rows ? r : BDL_ERR_NOMEM;
}

typedef struct order_key {
    uint32_t id;
    int32_t at;
} order_key;

static int compare_key(const void *x, const void *y)
{
    const uint32_t a = ((const order_key *)x)->id, b = ((const order_key *)y)->id;
    return (a > b) - (a < b);
}

bdl_result bdl_dist_gather_whole(const bdl_particles *p, const uint8_t *coordination, int root,
                                 bdl_particles *out, uint8_t *coordination_out)
{
    bdl_particle_array arrays[BDL_PARTICLE_ARRAYS];
    size_t bytes;
    all_arrays(p, arrays, &bytes);
    const size_t record = bytes + 1; // and the coordination
    char *mine = malloc((size_t)(p->count > 0 ? p->count : 1) * record);
    if (!mine)
        bdl_comm_abort("out of memory gathering the state");
    for (long i = 0; i < p->count; ++i) {
        pack(p, i, bdl_v3_zero(), mine + (size_t)i * record);
        mine[(size_t)i * record + bytes] = (char)(coordination ? coordination[i] : 0);
    }
    char *all = NULL;
    long total = 0;
    bdl_result r = gather_bytes(mine, p->count * (long)record, root, &all, &total);
    free(mine);
    if (r != BDL_OK || !all) {
        free(all);
        return r;
    }
    const long n = total / (long)record;
    order_key *keys = malloc((size_t)(n > 0 ? n : 1) * sizeof *keys);
    if (!keys || bdl_particles_reserve(out, n) != BDL_OK)
        bdl_comm_abort("out of memory for the whole state on the first rank");
    // The id is the table's ninth array: read it through a particle unpacked in place.
    for (long k = 0; k < n; ++k) {
        unpack(out, k, all + (size_t)k * record);
        keys[k] = (order_key){out->id[k], (int32_t)k};
    }
    qsort(keys, (size_t)n, sizeof *keys, compare_key);
    for (long k = 0; k < n; ++k) {
        unpack(out, k, all + (size_t)keys[k].at * record);
        if (coordination_out)
            coordination_out[k] = (uint8_t)all[(size_t)keys[k].at * record + bytes];
    }
    out->count = n;
    free(keys);
    free(all);
    return BDL_OK;
}

int bdl_dist_spring_order(const void *x, const void *y)
{
    const bdl_dist_spring *a = x, *b = y;
    if (a->a != b->a)
        return a->a < b->a ? -1 : 1;
    if (a->b != b->b)
        return a->b < b->b ? -1 : 1;
    return (a->wall > b->wall) - (a->wall < b->wall);
}

bdl_result bdl_dist_gather_springs(const bdl_neighbor *nb, const bdl_particles *p, long owned,
                                   int root, bdl_dist_spring **out, long *count)
{
    *out = NULL;
    *count = 0;
    long n = 0;
    for (long k = 0; nb->history && k < nb->pair_count; ++k)
        n += nb->touching[k];
    for (long k = 0; nb->history && k < nb->wall_pair_count; ++k)
        n += nb->wall_touching[k];
    bdl_dist_spring *mine = malloc((size_t)(n > 0 ? n : 1) * sizeof *mine);
    if (!mine)
        bdl_comm_abort("out of memory gathering springs");
    long m = 0;
    for (long i = 0; nb->history && i < nb->count; ++i) {
        for (int32_t k = nb->start[i]; k < nb->start[i + 1]; ++k) {
            const long j = nb->partner[k];
            const uint32_t ii = p->id[i], jj = p->id[j];
            // Each pair once: by the rank that owns its particle of the lower id.
            if (!nb->touching[k] || (ii < jj ? i : j) >= owned)
                continue;
            const bdl_vec3 u = nb->history[k]; // as seen from i, the lower index
            mine[m++] = (bdl_dist_spring){ii < jj ? ii : jj,
                                          ii < jj ? jj : ii,
                                          -1,
                                          0,
                                          ii < jj ? u : bdl_v3_neg(u),
                                          nb->spring_work ? nb->spring_work[k] : 0.0};
        }
        for (int32_t k = nb->wall_start[i]; i < owned && k < nb->wall_start[i + 1]; ++k)
            if (nb->wall_touching[k])
                mine[m++] = (bdl_dist_spring){p->id[i],
                                              0,
                                              nb->wall_prim[k],
                                              0,
                                              nb->wall_history[k],
                                              nb->wall_spring_work ? nb->wall_spring_work[k] : 0.0};
    }
    char *all = NULL;
    long total = 0;
    bdl_result r = gather_bytes(mine, m * (long)sizeof *mine, root, &all, &total);
    free(mine);
    if (r == BDL_OK && all) {
        *out = (bdl_dist_spring *)all;
        *count = total / (long)sizeof **out;
        qsort(*out, (size_t)*count, sizeof **out, bdl_dist_spring_order);
    } else {
        free(all);
    }
    return r;
}

void bdl_dist_gathered_free(bdl_dist_gathered *g)
{
    free(g->id);
    free(g->pos);
    free(g->vel);
    free(g->omega);
    memset(g, 0, sizeof *g);
}

#else // one process: nothing to divide

struct bdl_dist {
    bdl_decomp d;
};

bdl_result bdl_dist_create(const bdl_decomp *d, bdl_dist **out)
{
    (void)d;
    *out = NULL;
    return BDL_ERR_ARGS;
}
void bdl_dist_destroy(bdl_dist *dd) { free(dd); }
const bdl_decomp *bdl_dist_decomp(const bdl_dist *dd) { return &dd->d; }
long bdl_dist_owned(const bdl_dist *dd) { return dd ? 0 : 0; }
long bdl_dist_ghosts(const bdl_dist *dd) { return dd ? 0 : 0; }
long bdl_dist_migrated(const bdl_dist *dd) { return dd ? 0 : 0; }
long bdl_dist_rebuilds(const bdl_dist *dd) { return dd ? 0 : 0; }
bdl_result bdl_dist_start(bdl_dist *dd, bdl_particles *p, bdl_neighbor *nb, const bdl_walls *walls)
{
    (void)dd, (void)p, (void)nb, (void)walls;
    return BDL_ERR_ARGS;
}
int bdl_dist_any(int mine) { return mine; }
bdl_result bdl_dist_rebuild(bdl_dist *dd, bdl_particles *p, bdl_neighbor *nb,
                            const bdl_walls *walls)
{
    (void)dd, (void)p, (void)nb, (void)walls;
    return BDL_ERR_ARGS;
}
bdl_result bdl_dist_remove(bdl_dist *dd, bdl_particles *p, const uint8_t *drop)
{
    (void)dd, (void)p, (void)drop;
    return BDL_ERR_ARGS;
}
bdl_result bdl_dist_refresh(bdl_dist *dd, bdl_particles *p)
{
    (void)dd, (void)p;
    return BDL_ERR_ARGS;
}
bdl_result bdl_dist_gather(const bdl_particles *p, int root, bdl_dist_gathered *out)
{
    (void)p, (void)root;
    memset(out, 0, sizeof *out);
    return BDL_ERR_ARGS;
}
void bdl_dist_gathered_free(bdl_dist_gathered *g) { (void)g; }
bdl_result bdl_dist_gather_whole(const bdl_particles *p, const uint8_t *coordination, int root,
                                 bdl_particles *out, uint8_t *coordination_out)
{
    (void)p, (void)coordination, (void)root, (void)out, (void)coordination_out;
    return BDL_ERR_ARGS;
}
int bdl_dist_spring_order(const void *x, const void *y)
{
    (void)x, (void)y;
    return 0;
}
bdl_result bdl_dist_gather_springs(const bdl_neighbor *nb, const bdl_particles *p, long owned,
                                   int root, bdl_dist_spring **out, long *count)
{
    (void)nb, (void)p, (void)owned, (void)root;
    *out = NULL;
    *count = 0;
    return BDL_ERR_ARGS;
}

#endif
