#include "dem/particles.h"
#include "core/memory.h"

#include <stdlib.h>
#include <string.h>

bdl_result bdl_particles_reserve(bdl_particles *p, long capacity)
{
    if (capacity <= p->capacity)
        return BDL_OK;
    int ok = bdl_grow((void **)&p->pos, capacity, sizeof(bdl_vec3)) &&
             bdl_grow((void **)&p->vel, capacity, sizeof(bdl_vec3)) &&
             bdl_grow((void **)&p->omega, capacity, sizeof(bdl_vec3)) &&
             bdl_grow((void **)&p->load, capacity, sizeof(bdl_wrench)) &&
             bdl_grow((void **)&p->pos_at_build, capacity, sizeof(bdl_vec3)) &&
             bdl_grow((void **)&p->radius, capacity, sizeof(double)) &&
             bdl_grow((void **)&p->inv_mass, capacity, sizeof(double)) &&
             bdl_grow((void **)&p->species, capacity, sizeof(int32_t)) &&
             bdl_grow((void **)&p->id, capacity, sizeof(uint32_t));
    if (ok && p->fluid)
        ok = bdl_grow((void **)&p->fluid_accel, capacity, sizeof(bdl_vec3)) &&
             bdl_grow((void **)&p->vel_mark, capacity, sizeof(bdl_vec3)) &&
             bdl_grow((void **)&p->drag_accel, capacity, sizeof(bdl_vec3));
    if (!ok)
        return BDL_ERR_NOMEM;
    p->capacity = capacity;
    return BDL_OK;
}

void bdl_particles_free(bdl_particles *p)
{
    free(p->pos);
    free(p->vel);
    free(p->omega);
    free(p->load);
    free(p->pos_at_build);
    free(p->radius);
    free(p->inv_mass);
    free(p->species);
    free(p->id);
    free(p->fluid_accel);
    free(p->vel_mark);
    free(p->drag_accel);
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
    double mass = density * (4.0 / 3.0) * 3.14159265358979323846 * radius * radius * radius;
    p->pos[i] = pos;
    p->vel[i] = vel;
    p->omega[i] = bdl_v3_zero();
    p->load[i] = (bdl_wrench){bdl_v3_zero(), bdl_v3_zero()};
    p->pos_at_build[i] = pos;
    p->radius[i] = radius;
    p->inv_mass[i] = 1.0 / mass;
    p->species[i] = species;
    p->id[i] = p->next_id++;
    if (p->fluid) {
        p->fluid_accel[i] = bdl_v3_zero();
        p->vel_mark[i] = vel;
        p->drag_accel[i] = bdl_v3_zero();
    }
    return i;
}

static void permute_array(void *array, size_t elem, long n, const int32_t *perm, void *scratch)
{
    char *src = array, *dst = scratch;
    for (long k = 0; k < n; ++k)
        memcpy(dst + (size_t)k * elem, src + (size_t)perm[k] * elem, elem);
    memcpy(array, scratch, (size_t)n * elem);
}

/// Permutes the force-torque records with scratch for one vector per particle: the forces go to
/// scratch, the torques to the freed force slots, then both to their places.
static void permute_load(bdl_wrench *load, long n, const int32_t *perm, bdl_vec3 *scratch)
{
    for (long k = 0; k < n; ++k)
        scratch[k] = load[perm[k]].force;
    for (long k = 0; k < n; ++k)
        load[k].force = load[perm[k]].torque;
    for (long k = 0; k < n; ++k)
        load[k] = (bdl_wrench){scratch[k], load[k].force};
}

void bdl_particles_permute(bdl_particles *p, const int32_t *perm, void *scratch)
{
    long n = p->count;
    permute_array(p->pos, sizeof(bdl_vec3), n, perm, scratch);
    permute_array(p->vel, sizeof(bdl_vec3), n, perm, scratch);
    permute_array(p->omega, sizeof(bdl_vec3), n, perm, scratch);
    permute_load(p->load, n, perm, scratch);
    permute_array(p->pos_at_build, sizeof(bdl_vec3), n, perm, scratch);
    permute_array(p->radius, sizeof(double), n, perm, scratch);
    permute_array(p->inv_mass, sizeof(double), n, perm, scratch);
    permute_array(p->species, sizeof(int32_t), n, perm, scratch);
    permute_array(p->id, sizeof(uint32_t), n, perm, scratch);
    if (p->fluid) {
        permute_array(p->fluid_accel, sizeof(bdl_vec3), n, perm, scratch);
        permute_array(p->vel_mark, sizeof(bdl_vec3), n, perm, scratch);
        permute_array(p->drag_accel, sizeof(bdl_vec3), n, perm, scratch);
    }
}

long bdl_particles_bytes(const bdl_particles *p)
{
    return p->capacity * (long)((6 + (p->fluid ? 3 : 0)) * sizeof(bdl_vec3) + 2 * sizeof(double) +
                                sizeof(int32_t) + sizeof(uint32_t));
}
