// bedlam — the checkpoint file: header, payload, save and load.
//
//   header (32 bytes)   "BDLCKPT7", format version (u32, 7), header size (u32, 32), payload size
//                       (u64), CRC-32 of the payload (u32), CRC-32 of the 28 bytes before it (u32)
//   payload             the scene record (checkpoint_scene.c), the time step, the scalars, the
//                       counts, the arrays (state_fields), in the machine's byte order
//
// Loading trusts nothing it has not checked: the header and its checksum, the payload's size
// against the file's and its checksum, all before a count is read; then the scene record against
// the scene, the counts against their limits and the payload's size, and the restored state
// against the ranges the next step relies on (checkpoint_state.c). A crafted file can carry valid
// checksums, so the range checks do not depend on them.
#define _POSIX_C_SOURCE 200809L // fseeko, ftello
#include "output/checkpoint.h"

#include <stdarg.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/types.h>

#include "cfd/gas.h"
#include "solids/phase.h"
#include "core/crc32.h"
#include "core/file.h"
#include "output/checkpoint_parts.h"

// Versions 2-5 grew the state (the gas, outflow, force and torque records); 6 made the file
// untrusted input: header with sizes and checksums, the scene record, range checks; 7 holds the
// work in the Hertz-Mindlin springs (held, and left by ended contacts) and, with a gas, whether
// the live inflow rose since the last gas step (the next gas step starts short); 8 the walls'
// turned angles (now and at the last list build); 9 how far the Lees–Edwards images had slid at
// the last list build; 10 a solids phase's fields; 11 the solids phases in the scene's record;
// 12 a grid without padding along a periodic y or z of one cell (cfd/grid.h).
static const char magic[8] = {'B', 'D', 'L', 'C', 'K', 'P', 'T', '7'};
enum { VERSION = 12, HEADER_BYTES = 32 };

void bdl_ckpt_put(bdl_ckpt_writer *out, const void *data, size_t size)
{
    if (!out->ok || size == 0)
        return;
    if (fwrite(data, 1, size, out->f) != size) {
        out->ok = 0;
        return;
    }
    out->crc = bdl_crc32(out->crc, data, size);
    out->bytes += size;
}

void bdl_ckpt_get(bdl_ckpt_reader *in, void *data, size_t size)
{
    if (!in->ok || size == 0)
        return;
    if (size > in->left || fread(data, 1, size, in->f) != size) {
        in->ok = 0;
        return;
    }
    in->left -= size;
}

/// The scalar fields saved and restored, in file order (the time step is saved before them).
// clang-format off
#define SCALARS(X) \
    X(time) X(step) X(rng) X(poured) X(live) X(wall_work) X(inserted_energy) X(damping_work) \
    X(energy0) X(removed) X(removed_mass) X(removed_energy)
// clang-format on

/// The counts that size the arrays, in file order.
enum { C_PARTICLES, C_NEXT_ID, C_PAIRS, C_WALL_PAIRS, C_BUILDS, C_LISTED, C_VERSION, C_COUNT };

/// One array of the saved state.
typedef struct field {
    void *data;
    size_t bytes;
} field;

#define MAX_FIELDS 96

/// The arrays of the state in file order, for the counts `c`. Save and load walk the same table,
/// so the two cannot drift apart; the load also sizes the payload with it before it allocates.
static int state_fields(bdl_world *w, const int64_t *c, field *f)
{
    bdl_particles *p = &w->particles;
    bdl_neighbor *nb = &w->neighbor;
    size_t n = (size_t)c[C_PARTICLES], np = (size_t)c[C_PAIRS], nw = (size_t)c[C_WALL_PAIRS];
    size_t v = sizeof(bdl_vec3), i32 = sizeof(int32_t);
    int k = 0;
    bdl_particle_array arrays[BDL_PARTICLE_ARRAYS];
    int count = bdl_particles_arrays(p, BDL_ARRAYS_ALWAYS, arrays);
    for (int a = 0; a < count; ++a)
        f[k++] = (field){arrays[a].data, n * arrays[a].element};
    f[k++] = (field){w->coordination, n};
    f[k++] = (field){nb->wall_offset_at_build, sizeof nb->wall_offset_at_build};
    f[k++] = (field){nb->wall_angle_at_build, sizeof nb->wall_angle_at_build};
    f[k++] = (field){w->walls.angle, sizeof w->walls.angle};
    f[k++] = (field){&nb->shear_travel_at_build, sizeof nb->shear_travel_at_build};
    f[k++] = (field){nb->start, (n + 1) * i32};
    f[k++] = (field){nb->partner, np * i32};
    f[k++] = (field){nb->touching, np};
    if (nb->friction)
        f[k++] = (field){nb->history, np * v};
    if (nb->mindlin) {
        f[k++] = (field){nb->spring_work, np * sizeof(double)};
        f[k++] = (field){&nb->spring_work_left, sizeof nb->spring_work_left};
    }
    f[k++] = (field){nb->wall_start, (n + 1) * i32};
    f[k++] = (field){nb->wall_prim, nw * i32};
    f[k++] = (field){nb->wall_history, nw * v};
    if (nb->mindlin)
        f[k++] = (field){nb->wall_spring_work, nw * sizeof(double)};
    f[k++] = (field){nb->wall_force, nw * v};
    f[k++] = (field){nb->wall_touching, nw};
    // The gas's forces on the particles, held between gas steps; the rods' orientations; the
    // parcels' particle counts.
    count = bdl_particles_arrays(
        p, BDL_ARRAYS_WITH_GAS | BDL_ARRAYS_WITH_RODS | BDL_ARRAYS_WITH_PARCELS, arrays);
    for (int a = 0; a < count; ++a)
        f[k++] = (field){arrays[a].data, n * arrays[a].element};
    bdl_gas *g = w->gas;
    if (g) {
        const size_t cells = (size_t)g->grid.size * sizeof(double);
        f[k++] = (field){&w->gas_every, sizeof w->gas_every};
        f[k++] = (field){&w->gas_next, sizeof w->gas_next};
        f[k++] = (field){&w->gas_steps, sizeof w->gas_steps};
        f[k++] = (field){&w->gas_stable, sizeof w->gas_stable};
        f[k++] = (field){&w->gas_inflow_raised, sizeof w->gas_inflow_raised};
        f[k++] = (field){&w->gas_work, sizeof w->gas_work};
        f[k++] = (field){w->particle_drag, sizeof w->particle_drag};
        f[k++] = (field){w->gas_drag, sizeof w->gas_drag};
        f[k++] = (field){&g->time, sizeof g->time};
        f[k++] = (field){&g->steps, sizeof g->steps};
        // Field by field: the struct has padding, which must not reach the file.
        f[k++] = (field){&g->last_solve.iterations, sizeof g->last_solve.iterations};
        f[k++] = (field){&g->last_solve.residual, sizeof g->last_solve.residual};
        f[k++] = (field){&g->last_solve.initial_residual, sizeof g->last_solve.initial_residual};
        f[k++] = (field){&g->mass_imbalance, sizeof g->mass_imbalance};
        for (int a = 0; a < 3; ++a)
            f[k++] = (field){g->u[a], cells};
        f[k++] = (field){g->p, cells};
        f[k++] = (field){g->eps, cells};
        f[k++] = (field){g->eps_old, cells};
    }
    bdl_solids *s = w->solids;
    if (s) { // the closures and the elimination's coefficients are made anew every step
        const size_t cells = (size_t)s->grid.size * sizeof(double);
        f[k++] = (field){&s->time, sizeof s->time};
        f[k++] = (field){&s->steps, sizeof s->steps};
        for (int m = 0; m < s->count; ++m) { // the phase count is the scene's
            const bdl_solids_phase *ph = &s->phase[m];
            f[k++] = (field){ph->eps, cells};
            f[k++] = (field){ph->theta, cells}; // the granular energy's balance starts from it
            for (int a = 0; a < 3; ++a) {
                f[k++] = (field){ph->v[a], cells};
                f[k++] = (field){ph->flux[a], cells};
            }
        }
    }
    return k;
}

/// The 32 bytes of the header for a payload of `bytes` bytes with CRC-32 `crc`.
static void make_header(unsigned char *h, uint64_t bytes, uint32_t crc)
{
    const uint32_t version = VERSION, header_bytes = HEADER_BYTES;
    memcpy(h, magic, 8);
    memcpy(h + 8, &version, 4);
    memcpy(h + 12, &header_bytes, 4);
    memcpy(h + 16, &bytes, 8);
    memcpy(h + 24, &crc, 4);
    const uint32_t own = bdl_crc32(0, h, 28);
    memcpy(h + 28, &own, 4);
}

bdl_result bdl_checkpoint_save(const bdl_world *w, const char *path)
{
    bdl_atomic_file af;
    bdl_result res = bdl_atomic_open(&af, path);
    if (res != BDL_OK)
        return res;
    unsigned char header[HEADER_BYTES] = {0};
    bdl_ckpt_writer out = {.f = af.file,
                           .ok = fwrite(header, 1, sizeof header, af.file) == sizeof header};
    bdl_ckpt_put_scene(&out, w);
    bdl_ckpt_put(&out, &w->dt, sizeof w->dt);
#define PUT_SCALAR(name) bdl_ckpt_put(&out, &w->name, sizeof w->name);
    SCALARS(PUT_SCALAR)
#undef PUT_SCALAR
    const bdl_particles *p = &w->particles;
    const bdl_neighbor *nb = &w->neighbor;
    const int64_t counts[C_COUNT] = {p->count,   p->next_id, nb->pair_count, nb->wall_pair_count,
                                     nb->builds, nb->count,  nb->version};
    bdl_ckpt_put(&out, counts, sizeof counts);
    field f[MAX_FIELDS];
    // The table takes a mutable world; saving only reads through it.
    int count = state_fields((bdl_world *)w, counts, f);
    for (int k = 0; k < count; ++k)
        bdl_ckpt_put(&out, f[k].data, f[k].bytes);
    make_header(header, out.bytes, out.crc);
    if (!out.ok || fseeko(af.file, 0, SEEK_SET) != 0 ||
        fwrite(header, 1, sizeof header, af.file) != sizeof header) {
        bdl_atomic_abort(&af);
        return BDL_ERR_IO;
    }
    return bdl_atomic_commit(&af);
}

/// "checkpoint 'NAME': " and the formatted reason, into why; BDL_ERR_CHECKPOINT.
static bdl_result fail(char *why, size_t len, const char *name, const char *format, ...)
{
    int used = snprintf(why, len, "checkpoint '%s': ", name);
    if (used >= 0 && (size_t)used < len) {
        va_list args;
        va_start(args, format);
        vsnprintf(why + used, len - (size_t)used, format, args);
        va_end(args);
    }
    return BDL_ERR_CHECKPOINT;
}

/// Checks the header against the file's size (`file_bytes`); 0 with the reason in `what`.
static int check_header(const unsigned char *h, uint64_t file_bytes, uint32_t *crc, char *what,
                        size_t len)
{
    if (file_bytes < 7 || memcmp(h, magic, 7) != 0) {
        snprintf(what, len, "is not a bedlam checkpoint (it does not start with \"BDLCKPT\")");
        return 0;
    }
    if (file_bytes >= 8 && h[7] != (unsigned char)magic[7]) {
        snprintf(what, len,
                 "was written by another version of bedlam (checkpoint format '%c'; "
                 "this bedlam reads format '%c')",
                 h[7] >= 32 && h[7] < 127 ? h[7] : '?', magic[7]);
        return 0;
    }
    if (file_bytes < HEADER_BYTES) {
        snprintf(what, len, "is truncated: %llu bytes, shorter than its %d-byte header",
                 (unsigned long long)file_bytes, HEADER_BYTES);
        return 0;
    }
    uint32_t version, header_bytes, own;
    uint64_t payload;
    memcpy(&version, h + 8, 4);
    memcpy(&header_bytes, h + 12, 4);
    memcpy(&payload, h + 16, 8);
    memcpy(crc, h + 24, 4);
    memcpy(&own, h + 28, 4);
    if (own != bdl_crc32(0, h, 28)) {
        snprintf(what, len, "is damaged: its header's checksum does not match");
        return 0;
    }
    if (version != VERSION || header_bytes != HEADER_BYTES) {
        snprintf(what, len,
                 "has a header of version %u, %u bytes (this bedlam reads version %d, "
                 "%d bytes)",
                 version, header_bytes, VERSION, HEADER_BYTES);
        return 0;
    }
    if (payload != file_bytes - HEADER_BYTES) {
        snprintf(what, len, "is %s: its header announces %llu bytes of state, the file holds %llu",
                 payload > file_bytes - HEADER_BYTES ? "truncated" : "damaged (it has extra bytes)",
                 (unsigned long long)payload, (unsigned long long)(file_bytes - HEADER_BYTES));
        return 0;
    }
    return 1;
}

/// The CRC-32 of the next `bytes` bytes of f; 0 in *ok when they cannot be read.
static uint32_t stream_crc(FILE *f, uint64_t bytes, int *ok)
{
    unsigned char buffer[1 << 14];
    uint32_t crc = 0;
    *ok = 1;
    while (bytes > 0) {
        const size_t chunk = bytes < sizeof buffer ? (size_t)bytes : sizeof buffer;
        if (fread(buffer, 1, chunk, f) != chunk) {
            *ok = 0;
            return 0;
        }
        crc = bdl_crc32(crc, buffer, chunk);
        bytes -= chunk;
    }
    return crc;
}

/// Opens the payload: header, size and checksum verified. 0 with the reason in `what`.
static int open_payload(FILE *f, bdl_ckpt_reader *in, char *what, size_t len)
{
    unsigned char h[HEADER_BYTES] = {0};
    off_t end = -1;
    if (fseeko(f, 0, SEEK_END) != 0 || (end = ftello(f)) < 0 || fseeko(f, 0, SEEK_SET) != 0) {
        snprintf(what, len, "cannot be read (no size)");
        return 0;
    }
    const uint64_t file_bytes = (uint64_t)end;
    const size_t head = file_bytes < HEADER_BYTES ? (size_t)file_bytes : HEADER_BYTES;
    uint32_t crc = 0;
    if (fread(h, 1, head, f) != head) {
        snprintf(what, len, "cannot be read");
        return 0;
    }
    if (!check_header(h, file_bytes, &crc, what, len))
        return 0;
    int ok;
    const uint32_t actual = stream_crc(f, file_bytes - HEADER_BYTES, &ok);
    if (!ok || fseeko(f, HEADER_BYTES, SEEK_SET) != 0) {
        snprintf(what, len, "cannot be read");
        return 0;
    }
    if (actual != crc) {
        snprintf(what, len,
                 "is damaged: the checksum of its %llu bytes of state does not match "
                 "(CRC-32 %08x, the header says %08x)",
                 (unsigned long long)(file_bytes - HEADER_BYTES), actual, crc);
        return 0;
    }
    *in = (bdl_ckpt_reader){f, 1, file_bytes - HEADER_BYTES};
    return 1;
}

/// The counts within their limits and consistent with each other; 0 with the reason.
static int check_counts(const int64_t *c, char *what, size_t len)
{
    // Indices are int32_t: a particle count leaves room for the end offset of its lists.
    if (c[C_PARTICLES] < 0 || c[C_PARTICLES] >= INT32_MAX || c[C_PAIRS] < 0 ||
        c[C_PAIRS] > INT32_MAX || c[C_WALL_PAIRS] < 0 || c[C_WALL_PAIRS] > INT32_MAX) {
        snprintf(what, len,
                 "its counts are out of range: %lld particles, %lld pairs, %lld wall "
                 "contacts (at most %d each)",
                 (long long)c[C_PARTICLES], (long long)c[C_PAIRS], (long long)c[C_WALL_PAIRS],
                 INT32_MAX - 1);
        return 0;
    }
    if (c[C_NEXT_ID] < c[C_PARTICLES] || c[C_NEXT_ID] > UINT32_MAX) {
        snprintf(what, len, "its next particle id %lld is below its %lld particles or above %u",
                 (long long)c[C_NEXT_ID], (long long)c[C_PARTICLES], UINT32_MAX);
        return 0;
    }
    if (c[C_LISTED] != c[C_PARTICLES] || c[C_BUILDS] < 0 || c[C_VERSION] < 0) {
        snprintf(what, len,
                 "its neighbour lists were built for %lld particles (of %lld), %lld "
                 "times, version %lld",
                 (long long)c[C_LISTED], (long long)c[C_PARTICLES], (long long)c[C_BUILDS],
                 (long long)c[C_VERSION]);
        return 0;
    }
    return 1;
}

/// Makes room for the counts `c` and sets them; BDL_ERR_NOMEM when out of memory.
static bdl_result reserve(bdl_world *w, const int64_t *c)
{
    bdl_particles *p = &w->particles;
    bdl_neighbor *nb = &w->neighbor;
    if (bdl_particles_reserve(p, c[C_PARTICLES] + 1) != BDL_OK ||
        bdl_neighbor_reserve(nb, c[C_PARTICLES], c[C_PAIRS], c[C_WALL_PAIRS]) != BDL_OK)
        return BDL_ERR_NOMEM;
    uint8_t *coord = realloc(w->coordination, (size_t)p->capacity);
    if (!coord)
        return BDL_ERR_NOMEM;
    w->coordination = coord;
    w->coordination_capacity = p->capacity;
    p->count = c[C_PARTICLES];
    p->next_id = (uint32_t)c[C_NEXT_ID];
    nb->pair_count = c[C_PAIRS];
    nb->wall_pair_count = c[C_WALL_PAIRS];
    nb->builds = c[C_BUILDS];
    nb->count = c[C_LISTED];
    nb->version = c[C_VERSION];
    w->force_work.version = -1; // derived from the lists: rebuilt on the next step
    return BDL_OK;
}

/// The counts and the arrays they size: checked against the payload's size before anything is
/// allocated. BDL_ERR_CHECKPOINT with the reason in `what`, or BDL_ERR_NOMEM.
static bdl_result read_arrays(bdl_world *w, bdl_ckpt_reader *in, char *what, size_t len)
{
    int64_t c[C_COUNT];
    bdl_ckpt_get(in, c, sizeof c);
    if (!in->ok) {
        snprintf(what, len, "ends before its counts");
        return BDL_ERR_CHECKPOINT;
    }
    if (!check_counts(c, what, len))
        return BDL_ERR_CHECKPOINT;
    field f[MAX_FIELDS];
    int count = state_fields(w, c, f);
    uint64_t need = 0;
    for (int k = 0; k < count; ++k)
        need += f[k].bytes;
    if (need != in->left) {
        snprintf(what, len,
                 "holds %llu bytes of state after its counts, but %lld particles, %lld "
                 "pairs and %lld wall contacts take %llu",
                 (unsigned long long)in->left, (long long)c[C_PARTICLES], (long long)c[C_PAIRS],
                 (long long)c[C_WALL_PAIRS], (unsigned long long)need);
        return BDL_ERR_CHECKPOINT;
    }
    bdl_result r = reserve(w, c);
    if (r != BDL_OK)
        return r;
    count = state_fields(w, c, f);
    for (int k = 0; k < count; ++k)
        bdl_ckpt_get(in, f[k].data, f[k].bytes);
    if (!in->ok) {
        snprintf(what, len, "cannot be read");
        return BDL_ERR_CHECKPOINT;
    }
    return BDL_OK;
}

/// A checkpoint written with another time step than the world's: the gas's schedule, counted in
/// particle steps, is brought within the world's (the current gas step ends as planned, the
/// next ones follow the scene's).
static void reschedule_gas(bdl_world *w)
{
    if (!w->gas)
        return;
    if (w->gas_fixed || w->gas_every > w->gas_every_max)
        w->gas_every = w->gas_every_max;
    if (w->gas_next > w->step + w->gas_every)
        w->gas_next = w->step + w->gas_every;
}

bdl_result bdl_checkpoint_read(bdl_world *w, FILE *f, const char *name, bdl_checkpoint_info *info,
                               char *why, size_t why_len)
{
    char what[768], changes[1024];
    bdl_ckpt_reader in;
    if (!open_payload(f, &in, what, sizeof what))
        return fail(why, why_len, name, "%s", what);
    if (!bdl_ckpt_check_scene(&in, w, what, sizeof what, changes, sizeof changes))
        return fail(why, why_len, name, "%s", what);
    double saved_dt = 0.0;
    bdl_ckpt_get(&in, &saved_dt, sizeof saved_dt);
#define GET_SCALAR(field_name) bdl_ckpt_get(&in, &w->field_name, sizeof w->field_name);
    SCALARS(GET_SCALAR)
#undef GET_SCALAR
    if (!in.ok)
        return fail(why, why_len, name, "ends before its counts");
    bdl_result r = read_arrays(w, &in, what, sizeof what);
    if (r == BDL_ERR_NOMEM) {
        fail(why, why_len, name, "does not fit in memory");
        return BDL_ERR_NOMEM;
    }
    if (r != BDL_OK || !bdl_ckpt_check_state(w, saved_dt, what, sizeof what))
        return fail(why, why_len, name, "%s", what);
    if (saved_dt != w->dt)
        reschedule_gas(w);
    if (w->solids) // the mixture's fraction and the gas's voidage from the phases read
        bdl_solids_share_voidage(w->solids, w->gas);
    if (info) {
        info->dt = saved_dt;
        snprintf(info->changes, sizeof info->changes, "%s", changes);
    }
    bdl_world_apply_live(w);
    return BDL_OK;
}

bdl_result bdl_checkpoint_load(bdl_world *w, const char *path, bdl_checkpoint_info *info, char *why,
                               size_t why_len)
{
    FILE *f = fopen(path, "rb");
    if (!f)
        return fail(why, why_len, path, "cannot be opened");
    bdl_result r = bdl_checkpoint_read(w, f, path, info, why, why_len);
    fclose(f);
    return r;
}
