// bedlam — the contact-force pass: every listed pair once, the walls, background damping and
// the closing half kick of the velocity-Verlet step (integrate.h), in one pass over the particles
// whose sums do not depend on the thread count (how: contact_force.c).
#ifndef BDL_CONTACT_FORCE_H
#define BDL_CONTACT_FORCE_H

#include "dem/material.h"
#include "dem/neighbor.h"
#include "dem/particles.h"
#include "dem/walls.h"

typedef struct bdl_force_def {
    const bdl_contact_params *pair_params; ///< species_count^2 table
    const bdl_contact_params *wall_params; ///< wall_count * species_count table
    int species_count;
    const double *background_damping; ///< per species [1/s]
    /// Lees–Edwards: background damping acts on the velocity relative to the imposed shear
    /// profile u_x = shear_rate (z - shear_middle), the medium moving with the shear (0: at rest)
    double shear_rate;   ///< [1/s]
    double shear_middle; ///< [m]
    bdl_vec3 gravity;    ///< [m/s^2]
    int hertz, friction, rolling;
    double dt;         ///< [s] (tangential spring increment)
    long parallel_min; ///< fewer particles than this: one thread
    int loads_cleared; ///< force and torque are zero already (bdl_dem_kick_drift cleared them)
} bdl_force_def;

#define BDL_MAX_FORCE_THREADS 256

/// The velocity of particle i that background damping acts on: its own, less the Lees–Edwards
/// shear profile where the box is sheared.
static inline bdl_vec3 bdl_background_slip(const bdl_force_def *def, const bdl_particles *p, long i)
{
    bdl_vec3 v = p->vel[i];
    v.x -= def->shear_rate * (p->pos[i].z - def->shear_middle);
    return v;
}

/// An evaluated boundary pair: a pair whose j lies in a later thread's range, kept for j's owner.
typedef struct bdl_pair_result {
    bdl_vec3 force;    ///< on i [N]
    bdl_vec3 torque_i; ///< [N m]
    bdl_vec3 torque_j; ///< [N m]
    int touching;
} bdl_pair_result;

/// Per-step bookkeeping of the parallel force pass (see contact_force.c): the particle range of
/// each thread and the boundary pairs between ranges. Rebuilt when the lists or the thread count
/// change; a steady-state step allocates nothing.
typedef struct bdl_force_work {
    int threads;
    long version; ///< neighbour list version it was built for
    long count;   ///< particle count it was built for
    long range[BDL_MAX_FORCE_THREADS + 1];
    long out_start[BDL_MAX_FORCE_THREADS + 1]; ///< boundary pairs by source thread
    long in_start[BDL_MAX_FORCE_THREADS + 1];  ///< entries by target thread
    int32_t *pair;                             ///< pair index of each boundary entry
    int32_t *pair_i;                           ///< its first particle
    int32_t *owner;                            ///< first particle of every listed pair
    int32_t owner_count;                       ///< listed pairs
    long owner_capacity;
    int32_t *target;         ///< boundary entries ordered by target thread
    bdl_pair_result *result; ///< evaluated boundary pairs
    long capacity;
    struct bdl_pair_batch *batch[BDL_MAX_FORCE_THREADS]; ///< per-thread pair batches
    /// Per thread, during a pass: the work Hertz-Mindlin springs held when their contacts ended
    /// (added to bdl_neighbor.spring_work_left after the pass; exact sums, so the same on any
    /// thread count).
    bdl_exact_sum released[BDL_MAX_FORCE_THREADS];
    int uniform;     ///< every particle has the same species, radius and mass (these:)
    int species;     ///< species of particle 0
    double radius;   ///< radius of particle 0 [m]
    double inv_mass; ///< 1/m of particle 0 [1/kg]
} bdl_force_work;

void bdl_force_work_free(bdl_force_work *fw);

/// Splits the particles into one range per thread (equal work: a particle and its pairs) and lists
/// the boundary pairs between the ranges; nothing to do while the lists, the particle count and
/// the thread count stay the same. Both force passes (spheres here, rods in rod_force.c) use it.
bdl_result bdl_force_partition(bdl_force_work *fw, const bdl_neighbor *nb, const bdl_particles *p,
                               int threads);
long bdl_force_work_bytes(const bdl_force_work *fw);

/// The two halves of a force pass on thread t's range: the boundary pairs, stored for the owners
/// of their second particle, then everything else in index order.
typedef struct bdl_force_pass {
    void (*boundary)(bdl_particles *p, bdl_neighbor *nb, const bdl_force_def *def,
                     bdl_force_work *fw, int t);
    void (*range)(bdl_particles *p, bdl_neighbor *nb, const bdl_walls *walls,
                  const bdl_force_def *def, bdl_force_work *fw, uint8_t *coordination, double kick,
                  int t);
} bdl_force_pass;

/// Partitions the particles and runs `pass` on every thread (one thread below
/// def->parallel_min particles): the driver both force passes share.
bdl_result bdl_force_run(const bdl_force_pass *pass, bdl_particles *p, bdl_neighbor *nb,
                         const bdl_walls *walls, const bdl_force_def *def, bdl_force_work *fw,
                         uint8_t *coordination, double kick);

/// Evaluates all contacts in one pass over the particles: pair forces (each pair once), wall
/// contacts and background damping (gravity is applied in the kicks), counts particle contacts
/// into `coordination`, and with kick h > 0 applies the closing half kick v += h (F/m + g),
/// w += h T/I. The sums do not depend on the thread count.
bdl_result bdl_dem_forces(bdl_particles *p, bdl_neighbor *nb, const bdl_walls *walls,
                          const bdl_force_def *def, bdl_force_work *fw, uint8_t *coordination,
                          double kick);

#endif
