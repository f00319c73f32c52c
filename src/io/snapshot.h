// bedlam — what the drawing side and the writers are given of a step: plain data, no solver types.
//
// Two forms:
//  - bdl_snapshot: an owned copy of the particles in float (the drawing boundary), with the walls'
//    displacements and an optional slice of a gas field. The solver thread fills one (see
//    output/capture.h) and hands it to a viewer (through the solver loop's triple buffer) or to
//    the frame writer; the renderer draws it. It never points into the solver.
//  - bdl_particle_view: the particles as the solver holds them, in double, borrowed for the
//    length of one step's output callback. Writers whose numbers must be exact (the ground truth
//    the synthetic cameras write beside their images) read it; it is never stored.
#ifndef BDL_SNAPSHOT_H
#define BDL_SNAPSHOT_H

#include <stdint.h>

#include "core/quat.h"
#include "core/vec3.h"

/// Walls a snapshot carries displacements for (at least the scene's BDL_MAX_WALLS).
#define BDL_SNAPSHOT_WALLS 16

/// Particle data for drawing, in float. A reader's snapshot is valid until its next acquire.
typedef struct bdl_snapshot {
    long count, capacity;
    float *pos;    ///< xyz per particle [m]
    float *vel;    ///< xyz per particle [m/s]
    float *radius; ///< [m]
    float *axis;   ///< with rods: xyz per particle, half the shaft along the rod's axis (zero for a
                   ///< sphere) [m]; NULL in scenes without rods
    uint8_t *coordination;
    int32_t *species;
    uint32_t *id;
    double time; ///< [s]
    long step;
    int wall_count;
    float wall_offset[BDL_SNAPSHOT_WALLS]
                     [3];                 ///< displacement of each (vibrating) wall from rest [m]
    float wall_angle[BDL_SNAPSHOT_WALLS]; ///< angle each turning wall has turned [rad]
    double steps_per_second;              ///< the solver's recent speed (0 if unknown)
    // A slice of a gas field, when [camera] gas_field asks for one (slice_n[0] == 0: none).
    int slice_field;                ///< bdl_gas_field
    int slice_axis;                 ///< normal of the slice plane
    float slice_at;                 ///< its coordinate [m]
    float slice_lo[3], slice_hi[3]; ///< the box it spans [m]
    int slice_n[2];                 ///< cells along axes (axis + 1) % 3 and (axis + 2) % 3
    float *slice;                   ///< slice_n[0] x slice_n[1] values, the first axis fastest
    long slice_capacity;
    long axis_capacity;
    // Parcels (MP-PIC): each particle is a parcel of many real ones, drawn at the radius the
    // scene's [parcels] display chose (in `radius`); they have no contacts (coordination 0).
    int parcels;           ///< the particles are parcels
    double real_particles; ///< real particles the parcels stand for (parcels only)
    // The gas's voidage in its cells, when the world has a gas (voidage_n[0] == 0: none): what
    // the solids colour mode reads at each particle, with the coupling's tent kernel.
    int voidage_n[3];         ///< cells per axis
    int voidage_periodic[3];  ///< periodic axes
    double voidage_lo[3];     ///< the grid's lower corner [m]
    double voidage_h[3];      ///< cell size per axis [m]
    double voidage_kernel[3]; ///< the coupling kernel's half-width per axis [m]
    float *voidage;           ///< per cell, x fastest
    long voidage_capacity;
} bdl_snapshot;

/// Grows the particle arrays to hold n particles (contents kept). Returns 0 when out of memory.
int bdl_snapshot_reserve(bdl_snapshot *s, long n);
/// Grows the rods' axes to hold n particles (contents kept). Returns 0 when out of memory.
int bdl_snapshot_reserve_axis(bdl_snapshot *s, long n);
/// Grows the slice to hold `cells` values. Returns 0 when out of memory.
int bdl_snapshot_reserve_slice(bdl_snapshot *s, long cells);
/// Grows the gas voidage to hold `cells` values. Returns 0 when out of memory.
int bdl_snapshot_reserve_voidage(bdl_snapshot *s, long cells);
void bdl_snapshot_free(bdl_snapshot *s);

/// The particles of one step as the solver holds them: valid only inside the callback that was
/// given it.
typedef struct bdl_particle_view {
    long count;
    const bdl_vec3 *pos;  ///< centres [m]
    const bdl_vec3 *vel;  ///< [m/s]
    const double *radius; ///< [m]
    const uint32_t *id;   ///< stable ids
    const int32_t *species;
    const bdl_quat *orient;    ///< with rods: body to world (a rod's axis is body z); else NULL
    const double *half_length; ///< with rods: half the shaft length (0 for spheres) [m]; else NULL
    double time;               ///< simulated time [s]
    double dt;                 ///< the solver's time step [s]
    long step;
} bdl_particle_view;

#endif
