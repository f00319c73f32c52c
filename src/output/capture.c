// bedlam — snapshots and particle views of a world.
#include "output/capture.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "cfd/gas.h"
#include "couple/coupling.h"
#include "solids/phase.h"

_Static_assert(BDL_SNAPSHOT_WALLS >= BDL_MAX_WALLS, "a snapshot holds every wall");

/// The [camera] gas_field on its slice: the layer of cells the slice position falls in.
static int capture_slice(bdl_snapshot *s, const bdl_world *w)
{
    const bdl_camera_def *cam = &w->scene.camera;
    s->slice_n[0] = s->slice_n[1] = 0;
    if (!w->gas || cam->gas_field == BDL_GAS_FIELD_NONE)
        return 1;
    const bdl_gas *gas = w->gas;
    const bdl_grid *g = &gas->grid;
    const int a = cam->gas_slice_axis, b = (a + 1) % 3, c = (a + 2) % 3;
    if (!bdl_snapshot_reserve_slice(s, (long)g->n[b] * g->n[c]))
        return 0;
    int m = (int)floor(cam->gas_slice_position * g->n[a]);
    m = m < 0 ? 0 : m >= g->n[a] ? g->n[a] - 1 : m;
    for (int jc = 0; jc < g->n[c]; ++jc)
        for (int jb = 0; jb < g->n[b]; ++jb) {
            int ix[3];
            ix[a] = m, ix[b] = jb, ix[c] = jc;
            const long idx = bdl_grid_index(g, ix[0], ix[1], ix[2]);
            double v = gas->eps[idx];
            if (cam->gas_field == BDL_GAS_FIELD_PRESSURE) {
                v = gas->p[idx];
            } else if (cam->gas_field == BDL_GAS_FIELD_SPEED) {
                double sum = 0.0;
                for (int d = 0; d < 3; ++d) {
                    double u = bdl_gas_cell_velocity(gas, d, ix[0], ix[1], ix[2]);
                    sum += u * u;
                }
                v = sqrt(sum);
            }
            s->slice[(long)jc * g->n[b] + jb] = (float)v;
        }
    s->slice_field = (int)cam->gas_field;
    s->slice_axis = a;
    for (int d = 0; d < 3; ++d) {
        s->slice_lo[d] = (float)g->origin[d];
        s->slice_hi[d] = (float)(g->origin[d] + g->n[d] * g->h[d]);
    }
    s->slice_at =
        s->slice_lo[a] + (float)cam->gas_slice_position * (s->slice_hi[a] - s->slice_lo[a]);
    s->slice_n[0] = g->n[b];
    s->slice_n[1] = g->n[c];
    return 1;
}

/// The gas's voidage in its cells and the coupling kernel's half-width, for the solids colour.
static int capture_voidage(bdl_snapshot *s, const bdl_world *w)
{
    s->voidage_n[0] = s->voidage_n[1] = s->voidage_n[2] = 0;
    if (!w->gas || !w->coupling)
        return 1;
    const bdl_grid *g = &w->gas->grid;
    if (!bdl_snapshot_reserve_voidage(s, (long)g->n[0] * g->n[1] * g->n[2]))
        return 0;
    long c = 0;
    for (int k = 0; k < g->n[2]; ++k)
        for (int j = 0; j < g->n[1]; ++j)
            for (int i = 0; i < g->n[0]; ++i)
                s->voidage[c++] = (float)w->gas->eps[bdl_grid_index(g, i, j, k)];
    for (int a = 0; a < 3; ++a) {
        s->voidage_n[a] = g->n[a];
        s->voidage_periodic[a] = g->periodic[a];
        s->voidage_lo[a] = g->origin[a];
        s->voidage_h[a] = g->h[a];
        s->voidage_kernel[a] = w->coupling->width[a];
    }
    return 1;
}

/// The radius particle i is drawn with: its own, or with [parcels] display = parcel the radius
/// of the sphere of the parcel's solids volume, cbrt(3 V / (4 pi)).
static float display_radius(const bdl_world *w, long i)
{
    const bdl_particles *p = &w->particles;
    if (!p->parcels || w->scene.parcels.display != BDL_PARCEL_DISPLAY_PARCEL)
        return (float)p->radius[i];
    return (float)cbrt(0.75 / BDL_PI * bdl_particle_solids_volume(p, i));
}

/// Parcels: how many real particles they stand for; no contacts (coordination 0).
static void capture_parcels(bdl_snapshot *s, const bdl_world *w)
{
    const bdl_particles *p = &w->particles;
    s->parcels = p->parcels;
    s->real_particles = 0.0;
    if (!p->parcels) {
        memcpy(s->coordination, w->coordination, (size_t)p->count);
        return;
    }
    for (long i = 0; i < p->count; ++i)
        s->real_particles += p->parcel_count[i];
    memset(s->coordination, 0, (size_t)p->count);
}

/// Most spheres a solids phase is drawn with: above it each stands for more solids volume.
#define SOLIDS_DISPLAY_MAX 200000

/// A number in [0, 1) fixed by (cell, k): where sphere k of a cell sits, and whether it shows.
static double cell_hash(uint64_t cell, uint64_t k, uint64_t salt)
{
    uint64_t x = cell * 0x9E3779B97F4A7C15u + k * 0xBF58476D1CE4E5B9u + salt;
    x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9u;
    x = (x ^ (x >> 27)) * 0x94D049BB133111EBu;
    x ^= x >> 31;
    return (double)(x >> 11) * 0x1.0p-53;
}

/// Where along axis a in cell `at` a sphere of radius r sits for the number x in [0, 1): clear of
/// the domain's sides (walls, and periodic sides too: neither the pictures nor a camera's truth
/// wrap a sphere), so that the spheres hold the field's volume inside the domain. A cell thinner
/// than the sphere has it at its middle (sticking out: the sphere cannot fit).
static double inside(const bdl_grid *g, int a, int at, double r, double x)
{
    const double lo = at == 0 ? r : 0.0, hi = at == g->n[a] - 1 ? r : 0.0;
    const double room = g->h[a] - lo - hi;
    return room > 0.0 ? lo + x * room : 0.5 * g->h[a];
}

/// One sampled sphere: its index, centre, velocity, radius and phase.
typedef void (*sphere_fn)(void *ctx, long n, const double pos[3], const double vel[3],
                          double radius, int phase);

/// A solids phase drawn as particles sampled from its field: each cell holds as many spheres of
/// the phase's particle diameter as its solids volume makes (the fraction left over decides one
/// more), at places fixed for the cell and phase and clear of the domain's sides, with the
/// phase's velocity at the cell; the species index is the phase's. Above SOLIDS_DISPLAY_MAX
/// spheres in all, each stands for a larger volume and is drawn that large. Hands each sphere to
/// `emit` (none when NULL) and returns their count.
static long sample_solids(const bdl_world *w, sphere_fn emit, void *ctx)
{
    const bdl_solids *so = w->solids;
    const bdl_grid *g = &so->grid;
    const double cell = g->h[0] * g->h[1] * g->h[2];
    const double least = bdl_solids_volume(so, -1) / SOLIDS_DISPLAY_MAX; // per sphere, at least
    long n = 0;
    for (int m = 0; m < so->count; ++m) {
        const double d = so->phase[m].def.diameter;
        const double volume = fmax(BDL_PI * d * d * d / 6.0, least);
        const double radius = cbrt(0.75 / BDL_PI * volume);
        const uint64_t salt = 8u * (uint64_t)m;
        for (int k = 0; k < g->n[2]; ++k)
            for (int j = 0; j < g->n[1]; ++j)
                for (int i = 0; i < g->n[0]; ++i) {
                    const uint64_t c = (uint64_t)((k * g->n[1] + j) * g->n[0] + i);
                    const double want =
                        fmax(so->phase[m].eps[bdl_grid_index(g, i, j, k)], 0.0) * cell / volume;
                    const long q_end =
                        (long)want + (cell_hash(c, 0, 1 + salt) < want - floor(want));
                    for (long q = 0; q < q_end && emit; ++q) {
                        const int ix[3] = {i, j, k};
                        double pos[3], vel[3];
                        for (int a = 0; a < 3; ++a) {
                            const double x = cell_hash(c, (uint64_t)q, salt + 2 + a);
                            pos[a] =
                                g->origin[a] + ix[a] * g->h[a] + inside(g, a, ix[a], radius, x);
                            vel[a] = bdl_solids_cell_velocity(so, m, a, i, j, k);
                        }
                        emit(ctx, n + q, pos, vel, radius, m);
                    }
                    n += q_end;
                }
    }
    return n;
}

static void snapshot_sphere(void *ctx, long n, const double pos[3], const double vel[3],
                            double radius, int phase)
{
    bdl_snapshot *s = ctx;
    for (int a = 0; a < 3; ++a) {
        s->pos[3 * n + a] = (float)pos[a];
        s->vel[3 * n + a] = (float)vel[a];
    }
    s->radius[n] = (float)radius;
    s->species[n] = (uint8_t)phase;
    s->id[n] = (uint32_t)n;
    s->coordination[n] = 0;
}

static int capture_solids(bdl_snapshot *s, const bdl_world *w)
{
    const long n = sample_solids(w, NULL, NULL);
    if (!bdl_snapshot_reserve(s, n))
        return 0;
    sample_solids(w, snapshot_sphere, s);
    s->count = n;
    return 1;
}

static void sample_sphere(void *ctx, long n, const double pos[3], const double vel[3],
                          double radius, int phase)
{
    bdl_solids_sample *s = ctx;
    s->pos[n] = (bdl_vec3){pos[0], pos[1], pos[2]};
    s->vel[n] = (bdl_vec3){vel[0], vel[1], vel[2]};
    s->radius[n] = radius;
    s->species[n] = phase;
    s->id[n] = (uint32_t)n;
}

int bdl_capture_solids_view(bdl_solids_sample *s, const bdl_world *w, bdl_particle_view *view)
{
    *view = bdl_capture_view(w);
    if (!w->solids)
        return 1;
    const long n = sample_solids(w, NULL, NULL);
    if (n > s->capacity) {
        bdl_solids_sample_free(s);
        s->pos = malloc((size_t)n * sizeof *s->pos);
        s->vel = malloc((size_t)n * sizeof *s->vel);
        s->radius = malloc((size_t)n * sizeof *s->radius);
        s->id = malloc((size_t)n * sizeof *s->id);
        s->species = malloc((size_t)n * sizeof *s->species);
        if (!s->pos || !s->vel || !s->radius || !s->id || !s->species) {
            bdl_solids_sample_free(s);
            return 0;
        }
        s->capacity = n;
    }
    sample_solids(w, sample_sphere, s);
    view->count = n;
    view->pos = s->pos, view->vel = s->vel, view->radius = s->radius;
    view->id = s->id, view->species = s->species;
    view->orient = NULL, view->half_length = NULL;
    return 1;
}

void bdl_solids_sample_free(bdl_solids_sample *s)
{
    free(s->pos);
    free(s->vel);
    free(s->radius);
    free(s->id);
    free(s->species);
    *s = (bdl_solids_sample){0};
}

int bdl_capture(bdl_snapshot *s, const bdl_world *w)
{
    const bdl_particles *p = &w->particles;
    if (w->solids) {
        if (!capture_solids(s, w))
            return 0;
        s->time = w->time;
        s->step = w->step;
        s->wall_count = 0;
        return capture_slice(s, w) && capture_voidage(s, w);
    }
    if (!bdl_snapshot_reserve(s, p->count))
        return 0;
    for (long i = 0; i < p->count; ++i) {
        s->pos[3 * i] = (float)p->pos[i].x;
        s->pos[3 * i + 1] = (float)p->pos[i].y;
        s->pos[3 * i + 2] = (float)p->pos[i].z;
        s->vel[3 * i] = (float)p->vel[i].x;
        s->vel[3 * i + 1] = (float)p->vel[i].y;
        s->vel[3 * i + 2] = (float)p->vel[i].z;
        s->radius[i] = display_radius(w, i);
    }
    if (p->rods) {
        if (!bdl_snapshot_reserve_axis(s, p->count))
            return 0;
        for (long i = 0; i < p->count; ++i) {
            const bdl_vec3 a = bdl_particle_half_axis(p, i);
            s->axis[3 * i] = (float)a.x;
            s->axis[3 * i + 1] = (float)a.y;
            s->axis[3 * i + 2] = (float)a.z;
        }
    }
    capture_parcels(s, w);
    memcpy(s->species, p->species, (size_t)p->count * sizeof(int32_t));
    memcpy(s->id, p->id, (size_t)p->count * sizeof(uint32_t));
    s->count = p->count;
    s->time = w->time;
    s->step = w->step;
    s->wall_count = w->walls.wall_count;
    for (int k = 0; k < w->walls.wall_count; ++k) {
        // A repeating wall is drawn where it looks the same: its offset modulo the period.
        for (int a = 0; a < 3; ++a) {
            const double len = bdl_v3_comp(w->walls.wrap_length[k], a);
            const double o = bdl_v3_comp(w->walls.offset[k], a);
            s->wall_offset[k][a] = (float)(len > 0.0 ? o - len * round(o / len) : o);
        }
        s->wall_angle[k] = (float)w->walls.angle[k];
    }
    return capture_slice(s, w) && capture_voidage(s, w);
}

bdl_particle_view bdl_capture_view(const bdl_world *w)
{
    const bdl_particles *p = &w->particles;
    return (bdl_particle_view){.count = p->count,
                               .pos = p->pos,
                               .vel = p->vel,
                               .radius = p->radius,
                               .id = p->id,
                               .species = p->species,
                               .orient = p->orient,
                               .half_length = p->half_length,
                               .time = w->time,
                               .dt = w->dt,
                               .step = w->step};
}
