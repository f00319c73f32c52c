#include "dem/particles.h"
#include "dem/species.h"
#include "core/memory.h"

#include <stddef.h>
#include <stdlib.h>
#include <string.h>

#define ALWAYS       BDL_ARRAYS_ALWAYS
#define WITH_GAS     BDL_ARRAYS_WITH_GAS
#define WITH_RODS    BDL_ARRAYS_WITH_RODS
#define WITH_PARCELS BDL_ARRAYS_WITH_PARCELS

/// One per-particle array of bdl_particles: where its pointer lives and how many bytes each
/// particle takes in it.
typedef struct particle_array {
    size_t offset; ///< of the pointer in bdl_particles
    size_t elem;   ///< bytes per particle
    int when;      ///< BDL_ARRAYS_*: when it exists
} particle_array;

// clang-format off
#define ARRAY(field, when) \
    {offsetof(bdl_particles, field), sizeof *((bdl_particles *)0)->field, when}

/// Every per-particle array, in the order they are grown, permuted and counted (see particles.h).
static const particle_array arrays[] = {
    ARRAY(pos,          ALWAYS),
    ARRAY(vel,          ALWAYS),
    ARRAY(omega,        ALWAYS),
    ARRAY(load,         ALWAYS),
    ARRAY(pos_at_build, ALWAYS),
    ARRAY(radius,       ALWAYS),
    ARRAY(inv_mass,     ALWAYS),
    ARRAY(species,      ALWAYS),
    ARRAY(id,           ALWAYS),
    ARRAY(fluid_accel,  WITH_GAS),
    ARRAY(vel_mark,     WITH_GAS),
    ARRAY(drag_accel,   WITH_GAS),
    ARRAY(orient,        WITH_RODS),
    ARRAY(axis,          WITH_RODS),
    ARRAY(ang_mom,       WITH_RODS),
    ARRAY(inv_inertia,   WITH_RODS),
    ARRAY(half_length,   WITH_RODS),
    ARRAY(axis_at_build, WITH_RODS),
    ARRAY(parcel_count,  WITH_PARCELS),
};
// clang-format on

#define ARRAY_COUNT ((int)(sizeof arrays / sizeof arrays[0]))

/// The pointer of array a in p.
static void **array_pointer(bdl_particles *p, const particle_array *a)
{
    return (void **)((char *)p + a->offset);
}

static int has_array(const bdl_particles *p, const particle_array *a)
{
    return a->when == ALWAYS || (a->when == WITH_GAS && p->fluid) ||
           (a->when == WITH_RODS && p->rods) || (a->when == WITH_PARCELS && p->parcels);
}

int bdl_particles_arrays(const bdl_particles *p, int when, bdl_particle_array *out)
{
    int count = 0;
    for (int a = 0; a < ARRAY_COUNT; ++a)
        if ((arrays[a].when & when) && has_array(p, &arrays[a]))
            out[count++] = (bdl_particle_array){
                *(void *const *)((const char *)p + arrays[a].offset), arrays[a].elem};
    return count;
}

bdl_result bdl_particles_reserve(bdl_particles *p, long capacity)
{
    if (capacity <= p->capacity)
        return BDL_OK;
    for (int a = 0; a < ARRAY_COUNT; ++a)
        if (has_array(p, &arrays[a]) &&
            !bdl_grow(array_pointer(p, &arrays[a]), capacity, arrays[a].elem))
            return BDL_ERR_NOMEM;
    p->capacity = capacity;
    return BDL_OK;
}

void bdl_particles_free(bdl_particles *p)
{
    for (int a = 0; a < ARRAY_COUNT; ++a)
        free(*array_pointer(p, &arrays[a]));
    memset(p, 0, sizeof *p);
}

long bdl_particles_add(bdl_particles *p, bdl_vec3 pos, bdl_vec3 vel, double radius, double density,
                       int species)
{
    if (p->count == p->capacity) {
        long cap = p->capacity < 64 ? 64 : p->capacity + p->capacity / 2;
        if (bdl_particles_reserve(p, cap) != BDL_OK)
            return -1;
    }
    long i = p->count++;
    // Every array starts at zero, so that an array added to the table needs no line here unless
    // a new particle's value is not zero.
    for (int a = 0; a < ARRAY_COUNT; ++a)
        if (has_array(p, &arrays[a]))
            memset((char *)*array_pointer(p, &arrays[a]) + (size_t)i * arrays[a].elem, 0,
                   arrays[a].elem);
    double mass = density * (4.0 / 3.0) * 3.14159265358979323846 * radius * radius * radius;
    if (p->rods) { // a sphere among rods: a rod without a shaft
        const double inv = 2.5 / (mass * radius * radius);
        bdl_particle_set_orient(p, i, bdl_q_identity());
        p->inv_inertia[i] = bdl_v3(inv, inv, inv);
    }
    p->pos[i] = pos;
    p->vel[i] = vel;
    p->pos_at_build[i] = pos;
    p->radius[i] = radius;
    p->inv_mass[i] = 1.0 / mass;
    p->species[i] = species;
    p->id[i] = p->next_id++;
    if (p->fluid)
        p->vel_mark[i] = vel;
    return i;
}

long bdl_particles_add_rod(bdl_particles *p, bdl_vec3 pos, bdl_vec3 vel, double radius,
                           double half_length, bdl_quat orient, double density, int species)
{
    long i = bdl_particles_add(p, pos, vel, radius, density, species);
    if (i < 0)
        return -1;
    double mass, axial, transverse;
    bdl_rod_mass_properties(radius, 2.0 * half_length, density, &mass, &axial, &transverse);
    p->inv_mass[i] = 1.0 / mass;
    bdl_particle_set_orient(p, i, orient);
    p->half_length[i] = half_length;
    p->inv_inertia[i] = bdl_v3(1.0 / transverse, 1.0 / transverse, 1.0 / axial);
    p->axis_at_build[i] = bdl_particle_half_axis(p, i);
    return i;
}

/// Bytes per particle of the scratch that bdl_particles_permute is given.
#define SCRATCH_ELEM sizeof(bdl_vec3)

/// Permutes one array a column at a time, a column being as wide as the scratch element: a record
/// wider than that (the force-torque record) is moved in several columns.
static inline void permute_columns(char *array, size_t elem, long n, const int32_t *perm,
                                   char *scratch)
{
    for (size_t at = 0; at < elem; at += SCRATCH_ELEM) {
        size_t width = elem - at < SCRATCH_ELEM ? elem - at : SCRATCH_ELEM;
        for (long k = 0; k < n; ++k)
            memcpy(scratch + (size_t)k * width, array + (size_t)perm[k] * elem + at, width);
        if (width == elem) {
            memcpy(array, scratch, (size_t)n * elem);
            continue;
        }
        for (long k = 0; k < n; ++k)
            memcpy(array + (size_t)k * elem + at, scratch + (size_t)k * width, width);
    }
}

/// The sizes in use are spelled out so that each element is copied with a move or two instead of
/// a call.
static void permute_array(char *array, size_t elem, long n, const int32_t *perm, char *scratch)
{
    switch (elem) {
    case sizeof(int32_t):
        permute_columns(array, sizeof(int32_t), n, perm, scratch);
        break;
    case sizeof(double):
        permute_columns(array, sizeof(double), n, perm, scratch);
        break;
    case sizeof(bdl_vec3):
        permute_columns(array, sizeof(bdl_vec3), n, perm, scratch);
        break;
    case sizeof(bdl_wrench):
        permute_columns(array, sizeof(bdl_wrench), n, perm, scratch);
        break;
    default:
        permute_columns(array, elem, n, perm, scratch);
    }
}

void bdl_particles_permute(bdl_particles *p, const int32_t *perm, void *scratch)
{
    for (int a = 0; a < ARRAY_COUNT; ++a)
        if (has_array(p, &arrays[a]))
            permute_array(*array_pointer(p, &arrays[a]), arrays[a].elem, p->count, perm, scratch);
}

size_t bdl_particles_bytes_each(int fluid, int rods, int parcels)
{
    const bdl_particles p = {.fluid = fluid, .rods = rods, .parcels = parcels};
    size_t bytes = 0;
    for (int a = 0; a < ARRAY_COUNT; ++a)
        bytes += has_array(&p, &arrays[a]) ? arrays[a].elem : 0;
    return bytes;
}

long bdl_particles_bytes(const bdl_particles *p)
{
    return p->capacity * (long)bdl_particles_bytes_each(p->fluid, p->rods, p->parcels);
}
