// bedlam — the estimate of what a scene will need, and its refusal (see budget.h).
#include "world/budget.h"

#include <math.h>
#include <stdio.h>

#include "analysis/fields.h"
#include "cfd/grid.h"
#include "cfd/poisson.h"
#include "core/memory.h"
#include "couple/coupling.h"
#include "dem/create.h"
#include "world/world.h"

enum {
    BUDGET_LISTS = 64,    ///< per particle: list starts, sort scratch, coordination, flags
    BUDGET_COUPLING = 88, ///< per particle with a gas: its factor, forces and first point
    /// per kernel point (a sphere has one, a rod BDL_ROD_SATELLITES): offsets and weights
    BUDGET_POINT = 6 * BDL_KERNEL_MAX * (sizeof(int) + sizeof(double)) + 6 * sizeof(int),
    BUDGET_SNAPSHOT = 192,   ///< per particle with frames or cameras: snapshots on their way
    BUDGET_PAIR = 64,        ///< per pair: partner, flag, tangential history and its stash
    BUDGET_PAIRS = 8,        ///< pairs per particle (per unit of a rod's aspect ratio)
    BUDGET_GAS_CELL = 344,   ///< per padded gas cell: 43 doubles
    BUDGET_FIELDS_CELL = 64, ///< per cell of the fields: 4 doubles of sums, 4 of means
};

/// Share of the physical memory a scene may use when [guards] max_memory is not given.
#define BUDGET_MEMORY_SHARE 0.8

static int has_rods(const bdl_scene *s)
{
    for (int k = 0; k < s->species_count; ++k)
        if (s->species[k].shape == BDL_SHAPE_ROD)
            return 1;
    return 0;
}

/// Neighbour pairs per particle of species sp.
static double pairs_each(const bdl_species_def *sp)
{
    return BUDGET_PAIRS * (sp->shape == BDL_SHAPE_ROD ? sp->length / sp->diameter : 1.0);
}

/// Bytes a particle of species sp costs, its pairs included.
static double particle_bytes(const bdl_scene *s, const bdl_species_def *sp)
{
    const int images = s->output.frame_interval > 0.0 || s->dia_count > 0;
    const double points = sp->shape == BDL_SHAPE_ROD ? BDL_ROD_SATELLITES : 1;
    return (double)bdl_particles_bytes_each(s->gas.enabled, has_rods(s), s->parcels.enabled) +
           BUDGET_LISTS + (s->gas.enabled ? BUDGET_COUPLING + points * BUDGET_POINT : 0) +
           (images ? BUDGET_SNAPSHOT : 0) + pairs_each(sp) * BUDGET_PAIR;
}

static double creator_bytes(const bdl_scene *s, const bdl_budget *b, int c)
{
    return b->create_particles[c] * particle_bytes(s, &s->species[s->creates[c].species]);
}

/// Cells of the padded gas grid (cfd/grid.h: ghost layers and one more plane on each axis; none
/// on a flat axis, a periodic y or z of one cell).
static double gas_cells(const bdl_scene *s)
{
    if (!s->gas.enabled)
        return 0.0;
    double cells = 1.0;
    for (int a = 0; a < 3; ++a) {
        const double n = bdl_v3_comp(s->gas.cells, a);
        cells *= bdl_grid_flat(a, (int)n, s->periodic[a]) ? 1.0 : n + 2 * BDL_GRID_GHOST + 1;
    }
    return cells;
}

/// The direct pressure solver's band: band + 1 doubles a cell (cfd/poisson.h).
static double direct_band_bytes(const bdl_scene *s)
{
    if (!s->gas.enabled || s->gas.pressure_solver != BDL_PRESSURE_DIRECT)
        return 0.0;
    const int n[3] = {(int)s->gas.cells.x, (int)s->gas.cells.y, (int)s->gas.cells.z};
    const int band = bdl_poisson_direct_band(n, s->periodic);
    return band < 0 ? 0.0 : (double)n[0] * n[1] * n[2] * (band + 1.0) * sizeof(double);
}

/// Frames: three RGB buffers, the multisampled colour and depth, and the resolved image.
static double frame_bytes(const bdl_output_def *o)
{
    if (!(o->frame_interval > 0.0))
        return 0.0;
    const int samples = o->frame_samples > 1 ? o->frame_samples : 1;
    return (double)o->frame_width * o->frame_height * (9.0 + 8.0 * samples + 8.0);
}

/// A synthetic camera: grey, final and blurred values per pixel, a hit and a depth per sample.
static double camera_bytes(const bdl_dia_scene_def *d)
{
    const double pixels = (double)d->width * d->height;
    return (d->pair_dt > 0.0 ? 2.0 : 1.0) * pixels * (20.0 + 8.0 * d->samples * d->samples);
}

double bdl_budget_fields_cell(const bdl_scene *s)
{
    if (s->output.fields_cell > 0.0)
        return s->output.fields_cell;
    double sum = 0.0;
    for (int k = 0; k < s->species_count; ++k)
        sum += s->species[k].diameter;
    return 3.0 * sum / s->species_count;
}

/// Cells of the fields' grid over the domain; 0 without fields.
static double fields_cells(const bdl_scene *s)
{
    if (!(s->output.fields_interval > 0.0) || s->species_count == 0)
        return 0.0;
    const double lo[3] = {s->domain_min.x, s->domain_min.y, s->domain_min.z};
    const double hi[3] = {s->domain_max.x, s->domain_max.y, s->domain_max.z};
    int n[3];
    double h[3];
    return bdl_fields_grid(lo, hi, bdl_budget_fields_cell(s), n, h);
}

static double memory_limit(const bdl_scene *s)
{
    if (s->guards.max_memory > 0.0)
        return s->guards.max_memory;
    const double physical = bdl_physical_memory();
    return physical > 0.0 ? BUDGET_MEMORY_SHARE * physical : INFINITY;
}

void bdl_budget_estimate(const bdl_world *w, bdl_budget *b)
{
    const bdl_scene *s = &w->scene;
    *b = (bdl_budget){0};
    for (int c = 0; c < s->create_count; ++c) {
        const bdl_species_def *sp = &s->species[s->creates[c].species];
        const double n = bdl_create_expected(&s->creates[c], sp);
        b->create_particles[c] = n;
        b->particles += n;
        b->pairs += n * pairs_each(sp);
        b->particle_bytes += creator_bytes(s, b, c);
    }
    b->gas_cells = gas_cells(s);
    b->gas_bytes = b->gas_cells * BUDGET_GAS_CELL + direct_band_bytes(s);
    b->image_bytes = frame_bytes(&s->output);
    for (int k = 0; k < s->dia_count; ++k)
        b->image_bytes += camera_bytes(&s->dias[k]);
    b->fields_cells = fields_cells(s);
    b->fields_bytes = b->fields_cells * BUDGET_FIELDS_CELL;
    b->bytes = b->particle_bytes + b->gas_bytes + b->image_bytes + b->fields_bytes;
    b->max_memory = memory_limit(s);
    // The step the world will take; with no particle yet, the reference speed is the scene's.
    b->dt = s->dt > 0.0 ? s->dt
                        : s->dt_fraction *
                              bdl_world_min_contact_time(w, bdl_world_reference_speed(w), NULL, 0);
    b->steps = s->end_time / b->dt;
}

/// The part of a scene that asks for the most memory: where it is written and what it is.
typedef struct culprit {
    double bytes;
    char where[BDL_PATH_LEN + 256];
    char what[128];
} culprit;

/// "FILE:LINE: [create NAME] KEY = VALUE" for the key that sets the creator's count.
static void describe_creator(const bdl_scene *s, int c, char *buf, size_t size)
{
    const bdl_create_def *d = &s->creates[c];
    const bdl_species_def *sp = &s->species[d->species];
    int n = snprintf(buf, size, "%s:%d: [create %s] ", s->path, s->line.creates[c], d->name);
    if (n < 0 || (size_t)n >= size)
        return;
    buf += n, size -= (size_t)n;
    if (d->kind == BDL_CREATE_FILE)
        snprintf(buf, size, "file = %s", d->file);
    else if (d->count > 0)
        snprintf(buf, size, "count = %ld", d->count);
    else if (d->kind == BDL_CREATE_RANDOM)
        snprintf(buf, size, "volume_fraction = %g of particles of [species %s] diameter = %g m",
                 d->volume_fraction, sp->name, sp->diameter);
    else
        snprintf(buf, size, "type = lattice of [species %s] diameter = %g m, spacing = %g m",
                 sp->name, bdl_species_max_extent(sp),
                 d->spacing > 0.0 ? d->spacing : 1.0001 * bdl_species_max_extent(sp));
}

/// The creator, the gas or the images that ask for the most memory.
static void find_culprit(const bdl_scene *s, const bdl_budget *b, culprit *c)
{
    *c = (culprit){.bytes = -1.0};
    for (int k = 0; k < s->create_count; ++k)
        if (creator_bytes(s, b, k) > c->bytes) {
            c->bytes = creator_bytes(s, b, k);
            describe_creator(s, k, c->where, sizeof c->where);
            snprintf(c->what, sizeof c->what, "%.3g particles", b->create_particles[k]);
        }
    if (b->gas_bytes > c->bytes) {
        c->bytes = b->gas_bytes;
        snprintf(c->where, sizeof c->where, "%s: [gas] cells = %g %g %g", s->path, s->gas.cells.x,
                 s->gas.cells.y, s->gas.cells.z);
        snprintf(c->what, sizeof c->what, "a gas grid of %.3g cells", b->gas_cells);
    }
    if (frame_bytes(&s->output) > c->bytes) {
        c->bytes = frame_bytes(&s->output);
        snprintf(c->where, sizeof c->where,
                 "%s: [output] frame_width = %d, frame_height = %d, frame_samples = %d", s->path,
                 s->output.frame_width, s->output.frame_height, s->output.frame_samples);
        snprintf(c->what, sizeof c->what, "the frame buffers");
    }
    if (b->fields_bytes > c->bytes) {
        c->bytes = b->fields_bytes;
        snprintf(c->where, sizeof c->where, "%s: [output] fields_cell = %g m%s", s->path,
                 bdl_budget_fields_cell(s), s->output.fields_cell > 0.0 ? "" : " (the default)");
        snprintf(c->what, sizeof c->what, "a fields grid of %.3g cells", b->fields_cells);
    }
    for (int k = 0; k < s->dia_count; ++k)
        if (camera_bytes(&s->dias[k]) > c->bytes) {
            const bdl_dia_scene_def *d = &s->dias[k];
            c->bytes = camera_bytes(d);
            snprintf(c->where, sizeof c->where,
                     "%s:%d: [camera %s] width = %d, height = %d, samples = %d", s->path, d->line,
                     d->name, d->width, d->height, d->samples);
            snprintf(c->what, sizeof c->what, "the image buffers");
        }
}

bdl_result bdl_budget_check(const bdl_world *w, const bdl_budget *b, bdl_scene_error *err)
{
    const bdl_scene *s = &w->scene;
    if (!(b->bytes > b->max_memory))
        return bdl_budget_check_steps(w, b->dt, err);
    culprit c;
    find_culprit(s, b, &c);
    snprintf(err->message, sizeof err->message,
             "%s: about %.2g bytes for %s, above [guards] max_memory = %.3g bytes (%s; the whole "
             "scene needs about %.2g bytes)",
             c.where, c.bytes, c.what, b->max_memory,
             s->guards.max_memory > 0.0 ? "as given" : "80 % of the physical memory", b->bytes);
    return BDL_ERR_SCENE;
}

bdl_result bdl_budget_check_steps(const bdl_world *w, double dt, bdl_scene_error *err)
{
    const bdl_scene *s = &w->scene;
    const double steps = s->end_time / dt;
    if (!(steps > s->guards.max_steps))
        return BDL_OK;
    char how[160] = "";
    if (!(s->dt > 0.0))
        snprintf(how, sizeof how, " (dt_fraction = %g of the smallest contact time, %.3g s)",
                 s->dt_fraction, dt / s->dt_fraction);
    snprintf(err->message, sizeof err->message,
             "%s: [run] end_time = %g s with dt = %.3g s%s: %.3g steps, above [guards] max_steps "
             "= %g; lower end_time, or %s",
             s->path, s->end_time, dt, how, steps, s->guards.max_steps,
             s->dt > 0.0 ? "raise dt"
                         : "make the contact time longer (larger or softer particles)");
    return BDL_ERR_SCENE;
}
