// bedlam — particle storage (structure of arrays).
//
// Hot state (position, velocity, spin, force and torque) lives in separate arrays from cold
// metadata (species, id). Particles may be re-ordered for locality at neighbour-list rebuilds;
// `id` is stable for a particle's lifetime and is what output and checkpoints use.
//
// Adding a per-particle array (an orientation, a parcel's particle count, what a migration
// between processes carries): declare its pointer in bdl_particles and add one row to the table
// `arrays` in particles.c, with the condition under which it exists. Reserve, free, permute and
// the byte count all walk that table; a new particle starts with zero in it unless
// bdl_particles_add sets another value. Checkpoints save every array the table lists
// (bdl_particles_arrays), so a new one is saved and restored without a further line.
#ifndef BDL_PARTICLES_H
#define BDL_PARTICLES_H

#include <stddef.h>
#include <stdint.h>

#include "core/error.h"
#include "core/quat.h"
#include "core/vec3.h"

/// Force and torque on a particle, side by side: the force pass adds a pair's reaction to both of
/// the partner's, which then sit in one or two cache lines instead of two arrays' worth.
typedef struct bdl_wrench {
    bdl_vec3 force;  ///< contact, wall and damping force of this step, gravity excluded [N]
    bdl_vec3 torque; ///< total torque of this step [N m]
} bdl_wrench;

typedef struct bdl_particles {
    long count;             ///< live particles
    long capacity;          ///< allocated slots
    bdl_vec3 *pos;          ///< centre position [m]
    bdl_vec3 *vel;          ///< velocity [m/s]
    bdl_vec3 *omega;        ///< angular velocity [rad/s]
    bdl_wrench *load;       ///< force and torque of this step
    bdl_vec3 *pos_at_build; ///< position when the neighbour list was built [m]
    double *radius;         ///< [m]
    double *inv_mass;       ///< 1/m [1/kg]
    int32_t *species;       ///< species index
    uint32_t *id;           ///< stable id
    uint32_t next_id;       ///< id of the next particle added
    // With a gas only (NULL otherwise; set `fluid` before the first reserve):
    int fluid;             ///< keep the two arrays below
    bdl_vec3 *fluid_accel; ///< acceleration from the gas (drag + pressure), held over a gas step
    bdl_vec3 *vel_mark;    ///< velocity at the start of the current gas step [m/s]
    bdl_vec3 *drag_accel;  ///< the drag's part of fluid_accel [m/s^2]
    // With rods only (NULL otherwise; set `rods` before the first reserve). A rod is a
    // spherocylinder: a shaft of 2 half_length along its body z axis with caps of `radius`; in a
    // scene with rods a sphere is a rod of half_length 0. Every body is axisymmetric about its
    // body z axis (inv_inertia x = y), which the inline helpers below use.
    int rods;                ///< keep the arrays below
    bdl_quat *orient;        ///< orientation: body frame to world frame (set with set_orient)
    bdl_vec3 *axis;          ///< body z in the world frame, the axis of orient (kept with it)
    bdl_vec3 *ang_mom;       ///< angular momentum in the world frame [kg m^2/s]
    bdl_vec3 *inv_inertia;   ///< principal moments of inertia (body x, y, z), inverted [1/(kg m^2)]
    double *half_length;     ///< half the shaft length [m]
    bdl_vec3 *axis_at_build; ///< half_length times the axis when the lists were built [m]
    // With parcels only (NULL otherwise; set `parcels` before the first reserve). A parcel (MP-PIC,
    // src/parcels/) stands for parcel_count real spheres of `radius`, moving as one: inv_mass is
    // that of the whole parcel, the particle's volume that of one real sphere.
    int parcels;          ///< keep the array below
    double *parcel_count; ///< real particles in the parcel (not necessarily a whole number)
} bdl_particles;

bdl_result bdl_particles_reserve(bdl_particles *p, long capacity);
void bdl_particles_free(bdl_particles *p);

/// Appends a particle at rest (spin zero); returns its index or -1 when out of memory.
long bdl_particles_add(bdl_particles *p, bdl_vec3 pos, bdl_vec3 vel, double radius, double density,
                       int species);

/// Appends a rod of shaft length 2 half_length along the body z axis, oriented by `orient` (see
/// bdl_particles, `rods`), at rest; returns its index or -1 when out of memory.
long bdl_particles_add_rod(bdl_particles *p, bdl_vec3 pos, bdl_vec3 vel, double radius,
                           double half_length, bdl_quat orient, double density, int species);

/// Sets the orientation of rod-scene particle i, and its axis with it.
static inline void bdl_particle_set_orient(bdl_particles *p, long i, bdl_quat q)
{
    p->orient[i] = q;
    p->axis[i] = bdl_q_axis_z(q);
}

/// Half the shaft of particle i as a vector: half_length times its axis; zero for spheres [m].
static inline bdl_vec3 bdl_particle_half_axis(const bdl_particles *p, long i)
{
    return p->rods ? bdl_v3_scale(p->axis[i], p->half_length[i]) : bdl_v3_zero();
}

/// e . I^-1 e for rod-scene particle i, e a unit vector in the world frame: the inverse moment of
/// inertia about e, 1/I_t + (1/I_a - 1/I_t)(e . u)^2 for an axisymmetric body of axis u.
static inline double bdl_particle_inv_inertia_along(const bdl_particles *p, long i, bdl_vec3 e)
{
    const bdl_vec3 inv = p->inv_inertia[i];
    const double c = bdl_v3_dot(e, p->axis[i]);
    return inv.x + (inv.z - inv.x) * c * c;
}

/// The angular velocity of rod-scene particle i with angular momentum L (world frame):
/// I^-1 L = L / I_t + (1/I_a - 1/I_t)(L . u) u.
static inline bdl_vec3 bdl_particle_omega(const bdl_particles *p, long i, bdl_vec3 L)
{
    const bdl_vec3 inv = p->inv_inertia[i], u = p->axis[i];
    return bdl_v3_madd(bdl_v3_scale(L, inv.x), u, (inv.z - inv.x) * bdl_v3_dot(L, u));
}

/// The larger squared displacement of particle i's two tips since the lists were built (of its
/// centre when there are no rods): |dx|^2 + |de|^2 + 2 |dx . de|, de the change of the half axis.
static inline double bdl_particle_move2(const bdl_particles *p, long i)
{
    const bdl_vec3 dx = bdl_v3_sub(p->pos[i], p->pos_at_build[i]);
    if (!p->rods)
        return bdl_v3_len2(dx);
    const bdl_vec3 de = bdl_v3_sub(bdl_particle_half_axis(p, i), p->axis_at_build[i]);
    return bdl_v3_len2(dx) + bdl_v3_len2(de) + 2.0 * fabs(bdl_v3_dot(dx, de));
}

/// Volume of particle i: a sphere, or a rod's cylinder and two caps [m^3].
static inline double bdl_particle_volume(const bdl_particles *p, long i)
{
    const double r = p->radius[i], sphere = 4.0 / 3.0 * BDL_PI * r * r * r;
    return p->rods ? sphere + 2.0 * BDL_PI * r * r * p->half_length[i] : sphere;
}

/// Solids volume particle i stands for: its own volume, a parcel's times its particle count [m^3].
static inline double bdl_particle_solids_volume(const bdl_particles *p, long i)
{
    const double v = bdl_particle_volume(p, i);
    return p->parcels ? v * p->parcel_count[i] : v;
}

/// Sets particle i to stand for `count` real particles (a parcel), its mass with it.
static inline void bdl_particle_set_parcel(bdl_particles *p, long i, double count)
{
    p->inv_mass[i] *= p->parcel_count[i] > 0.0 ? p->parcel_count[i] / count : 1.0 / count;
    p->parcel_count[i] = count;
}

/// Moment of inertia of a solid sphere: I = 2/5 m r^2, returned as 1/I.
static inline double bdl_particle_inv_inertia(const bdl_particles *p, long i)
{
    return 2.5 * p->inv_mass[i] / (p->radius[i] * p->radius[i]);
}

/// Reorders all particle arrays so that new slot k holds old particle perm[k].
/// `scratch` must hold count * sizeof(bdl_vec3) bytes (wider records, as the force-torque record,
/// are moved a vector's width at a time).
void bdl_particles_permute(bdl_particles *p, const int32_t *perm, void *scratch);

/// Which per-particle arrays exist: always, only with a gas (bdl_particles.fluid), only with rods
/// (bdl_particles.rods), only with parcels (bdl_particles.parcels).
enum {
    BDL_ARRAYS_ALWAYS = 1,
    BDL_ARRAYS_WITH_GAS = 2,
    BDL_ARRAYS_WITH_RODS = 4,
    BDL_ARRAYS_WITH_PARCELS = 8
};

/// A per-particle array: its storage and the bytes each particle takes in it.
typedef struct bdl_particle_array {
    void *data;
    size_t element;
} bdl_particle_array;

/// The per-particle arrays that exist among the kinds in the mask `when`, in the table's order
/// (at most BDL_PARTICLE_ARRAYS); returns their count. Checkpoints, and later the migration of
/// particles between processes, move every array this lists.
#define BDL_PARTICLE_ARRAYS 16
int bdl_particles_arrays(const bdl_particles *p, int when, bdl_particle_array *out);

/// Bytes allocated for particle storage.
long bdl_particles_bytes(const bdl_particles *p);

/// Bytes each particle takes in the store's arrays, in a scene with (or without) a gas, rods and
/// parcels.
size_t bdl_particles_bytes_each(int fluid, int rods, int parcels);

#endif
