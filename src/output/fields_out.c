// bedlam — the time-averaged solids fields of a run and their files (see fields_out.h).
#include "output/fields_out.h"

#include <errno.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "core/crc32.h"
#include "core/file.h"
#include "io/vtk.h"
#include "output/checkpoint_parts.h"
#include "world/budget.h"

_Static_assert(sizeof(bdl_vec3) == 3 * sizeof(double), "a bdl_vec3 array is x y z after x y z");

static const char magic[8] = {'B', 'D', 'L', 'S', 'U', 'M', 'S', '1'};
enum { VERSION = 1 };

bdl_result bdl_fields_vti_write(const bdl_fields *f, const char *path)
{
    const long cells = bdl_fields_cells(f);
    double *fraction = malloc((size_t)cells * sizeof(double));
    double *velocity = malloc((size_t)cells * 3 * sizeof(double));
    bdl_result r = BDL_ERR_NOMEM;
    if (fraction && velocity) {
        bdl_fields_means(f, fraction, velocity);
        const bdl_vtk_array arrays[2] = {{"solids_fraction", BDL_VTK_FLOAT64, 1, fraction},
                                         {"solids_velocity", BDL_VTK_FLOAT64, 3, velocity}};
        r = bdl_vti_write(path, f->n, f->lo, f->h, arrays, 2);
    }
    free(fraction);
    free(velocity);
    return r;
}

bdl_result bdl_fields_add_world(bdl_fields *f, const bdl_world *w)
{
    const bdl_particles *p = &w->particles;
    double *length = NULL;
    if (p->rods && p->count > 0) {
        if (!(length = malloc((size_t)p->count * sizeof(double))))
            return BDL_ERR_NOMEM;
        for (long i = 0; i < p->count; ++i) // tip to tip, as the particle files give it
            length[i] = 2.0 * (p->half_length[i] + p->radius[i]);
    }
    const bdl_fields_sample s = {.time = w->time,
                                 .n = p->count,
                                 .pos = (const double *)p->pos,
                                 .vel = (const double *)p->vel,
                                 .radius = p->radius,
                                 .length = length,
                                 .count = p->parcels ? p->parcel_count : NULL};
    bdl_fields_add(f, &s);
    free(length);
    return BDL_OK;
}

double bdl_fields_world_cell(const bdl_world *w)
{
    const bdl_particles *p = &w->particles;
    return p->count > 0 ? bdl_fields_default_cell(p->count, p->radius)
                        : bdl_budget_fields_cell(&w->scene);
}

static void domain_box(const bdl_world *w, double lo[3], double hi[3])
{
    for (int a = 0; a < 3; ++a) {
        lo[a] = bdl_v3_comp(w->scene.domain_min, a);
        hi[a] = bdl_v3_comp(w->scene.domain_max, a);
    }
}

bdl_result bdl_fields_create_world(bdl_fields *f, const bdl_world *w, double cell, char *why,
                                   size_t why_len)
{
    double lo[3], hi[3], h[3];
    int n[3];
    domain_box(w, lo, hi);
    const bdl_result r = bdl_fields_create(f, lo, hi, cell, BDL_MAX_FIELD_CELLS);
    if (r == BDL_ERR_ARGS)
        snprintf(why, why_len, "makes %.3g cells over the domain, more than %g",
                 bdl_fields_grid(lo, hi, cell, n, h), BDL_MAX_FIELD_CELLS);
    return r == BDL_ERR_ARGS ? BDL_ERR_SCENE : r;
}

bdl_fields_stamp bdl_fields_stamp_of(const bdl_world *w, double cell)
{
    const bdl_output_def *o = &w->scene.output;
    return (bdl_fields_stamp){w->step,         w->time,        o->fields_interval,
                              o->fields_start, o->fields_cell, cell};
}

// ---------------------------------------------------------------------------------------------
// The sums file.

// Written with the checkpoint's writer, which keeps the CRC-32 of what it wrote.
static void put_i64(bdl_ckpt_writer *out, int64_t v) { bdl_ckpt_put(out, &v, sizeof v); }

bdl_result bdl_fields_sums_save(const bdl_fields *f, const bdl_fields_stamp *stamp,
                                const char *path)
{
    bdl_atomic_file af;
    bdl_result r = bdl_atomic_open(&af, path);
    if (r != BDL_OK)
        return r;
    bdl_ckpt_writer out = {.f = af.file, .ok = 1};
    const uint32_t version = VERSION;
    const int32_t n[4] = {f->n[0], f->n[1], f->n[2], 0};
    const size_t cells = (size_t)bdl_fields_cells(f);
    bdl_ckpt_put(&out, magic, sizeof magic);
    bdl_ckpt_put(&out, &version, sizeof version);
    put_i64(&out, stamp->step);
    const double header[] = {stamp->time, stamp->interval, stamp->start, stamp->setting,
                             stamp->cell};
    bdl_ckpt_put(&out, header, sizeof header);
    bdl_ckpt_put(&out, n, sizeof n);
    bdl_ckpt_put(&out, f->lo, sizeof f->lo);
    bdl_ckpt_put(&out, f->h, sizeof f->h);
    put_i64(&out, f->samples);
    put_i64(&out, f->particles);
    const double totals[] = {f->deposited, f->total, f->first, f->last};
    bdl_ckpt_put(&out, totals, sizeof totals);
    bdl_ckpt_put(&out, f->volume, cells * sizeof(double));
    bdl_ckpt_put(&out, f->momentum, 3 * cells * sizeof(double));
    const uint32_t crc = out.crc;
    bdl_ckpt_put(&out, &crc, sizeof crc);
    if (!out.ok) {
        const int error = errno;
        bdl_atomic_abort(&af);
        errno = error;
        return BDL_ERR_IO;
    }
    return bdl_atomic_commit(&af);
}

/// A reader over a file loaded whole; `ok` falls to 0 when a read would pass its end.
typedef struct sums_reader {
    const char *data;
    size_t size, at;
    int ok;
} sums_reader;

static void get(sums_reader *in, void *data, size_t size)
{
    if (!in->ok || size > in->size - in->at) {
        in->ok = 0;
        memset(data, 0, size);
        return;
    }
    memcpy(data, in->data + in->at, size);
    in->at += size;
}

/// The header of a sums file up to its sums into f (grid and counts) and stamp; NULL when it
/// is sound, else what is wrong.
static const char *read_header(sums_reader *in, bdl_fields *f, bdl_fields_stamp *stamp)
{
    char head[8];
    uint32_t version;
    int64_t step, samples, particles;
    int32_t n[4];
    double header[5], totals[4];
    get(in, head, sizeof head);
    get(in, &version, sizeof version);
    if (!in->ok || memcmp(head, magic, sizeof magic) != 0)
        return "is not a fields.sums file";
    if (version != VERSION)
        return "is of another format version";
    get(in, &step, sizeof step);
    get(in, header, sizeof header);
    get(in, n, sizeof n);
    get(in, f->lo, sizeof f->lo);
    get(in, f->h, sizeof f->h);
    get(in, &samples, sizeof samples);
    get(in, &particles, sizeof particles);
    get(in, totals, sizeof totals);
    if (!in->ok)
        return "is truncated";
    *stamp = (bdl_fields_stamp){(long)step, header[0], header[1], header[2], header[3], header[4]};
    double cells = 1.0;
    for (int a = 0; a < 3; ++a) {
        f->n[a] = n[a];
        cells *= n[a] >= 1 ? n[a] : INFINITY;
    }
    if (!(cells <= BDL_MAX_FIELD_CELLS) || step < 0 || samples < 0 || particles < 0)
        return "holds a count out of range";
    f->samples = (long)samples;
    f->particles = (long)particles;
    f->deposited = totals[0];
    f->total = totals[1];
    f->first = totals[2];
    f->last = totals[3];
    return NULL;
}

/// Every sum finite, every volume at least zero.
static int sums_sound(const bdl_fields *f)
{
    const long cells = bdl_fields_cells(f);
    int sound = isfinite(f->deposited) && isfinite(f->total) && f->deposited >= 0.0;
    for (long c = 0; c < cells && sound; ++c)
        sound = isfinite(f->volume[c]) && f->volume[c] >= 0.0 && isfinite(f->momentum[3 * c]) &&
                isfinite(f->momentum[3 * c + 1]) && isfinite(f->momentum[3 * c + 2]);
    return sound;
}

/// Parses a loaded sums file; NULL when it is sound, else what is wrong (f->volume NULL when the
/// memory was short).
static const char *parse_sums(const char *data, size_t size, bdl_fields *f, bdl_fields_stamp *stamp)
{
    sums_reader in = {data, size, 0, 1};
    const char *wrong = read_header(&in, f, stamp);
    if (wrong)
        return wrong;
    const size_t cells = (size_t)bdl_fields_cells(f), bytes = 4 * cells * sizeof(double);
    uint32_t crc;
    if (in.size - in.at != bytes + sizeof crc)
        return in.size - in.at < bytes + sizeof crc ? "is truncated" : "is longer than its grid";
    memcpy(&crc, data + size - sizeof crc, sizeof crc);
    if (crc != bdl_crc32(0, data, size - sizeof crc))
        return "fails its checksum (damaged)";
    f->volume = malloc(cells * sizeof(double));
    f->momentum = malloc(3 * cells * sizeof(double));
    if (!f->volume || !f->momentum)
        return "does not fit in memory";
    get(&in, f->volume, cells * sizeof(double));
    get(&in, f->momentum, 3 * cells * sizeof(double));
    return sums_sound(f) ? NULL : "holds a sum that is not finite or a negative volume";
}

bdl_result bdl_fields_sums_load(bdl_fields *f, bdl_fields_stamp *stamp, const char *path, char *why,
                                size_t why_len)
{
    *f = (bdl_fields){0};
    char reason[256];
    if (bdl_check_regular_file(path, NULL, reason, sizeof reason) != BDL_OK) {
        snprintf(why, why_len, "%s %s", path, reason);
        return BDL_ERR_CHECKPOINT;
    }
    size_t size = 0;
    char *data = bdl_read_file(path, &size);
    if (!data) {
        snprintf(why, why_len, "%s cannot be read: %s", path, strerror(errno));
        return BDL_ERR_CHECKPOINT;
    }
    const char *wrong = parse_sums(data, size, f, stamp);
    free(data);
    if (!wrong)
        return BDL_OK;
    const int short_of_memory = strcmp(wrong, "does not fit in memory") == 0;
    bdl_fields_free(f);
    snprintf(why, why_len, "%s %s", path, wrong);
    return short_of_memory ? BDL_ERR_NOMEM : BDL_ERR_CHECKPOINT;
}

int bdl_fields_stamp_matches(const bdl_fields *f, const bdl_fields_stamp *stamp, const bdl_world *w,
                             char *why, size_t why_len)
{
    const bdl_fields_stamp now = bdl_fields_stamp_of(w, stamp->cell);
    double lo[3], hi[3], h[3];
    int n[3];
    domain_box(w, lo, hi);
    bdl_fields_grid(lo, hi, stamp->cell, n, h);
    int grid = 1;
    for (int a = 0; a < 3; ++a)
        grid = grid && n[a] == f->n[a] && lo[a] == f->lo[a] && h[a] == f->h[a];
    if (stamp->step != now.step || stamp->time != now.time)
        snprintf(why, why_len, "are of step %ld (t = %.17g s), not of the checkpoint's, step %ld",
                 stamp->step, stamp->time, now.step);
    else if (stamp->interval != now.interval || stamp->start != now.start ||
             stamp->setting != now.setting)
        snprintf(why, why_len,
                 "were taken with fields_interval = %g s, fields_start = %g s, fields_cell = %g m "
                 "(< 0: the default), not the scene's %g s, %g s, %g m",
                 stamp->interval, stamp->start, stamp->setting, now.interval, now.start,
                 now.setting);
    else if (!grid)
        snprintf(why, why_len, "are on a grid the scene's domain does not give");
    else
        return 1;
    return 0;
}
