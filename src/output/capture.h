// bedlam — taking a step's state out of the world for the drawing side and the writers.
#ifndef BDL_CAPTURE_H
#define BDL_CAPTURE_H

#include "io/snapshot.h"
#include "world/world.h"

/// Copies the world's particles, wall displacements and (when the scene's [camera] asks for one)
/// a slice of a gas field into a snapshot, growing it as needed. Returns 0 when out of memory.
int bdl_capture(bdl_snapshot *s, const bdl_world *w);

/// A view of the world's particles as they are now (borrowed: valid until the next step).
bdl_particle_view bdl_capture_view(const bdl_world *w);

/// Spheres sampled from the solids phases' fields, in double (the synthetic cameras' view of a
/// continuum). Zero-initialise; bdl_solids_sample_free releases it.
typedef struct bdl_solids_sample {
    long capacity;
    bdl_vec3 *pos, *vel;
    double *radius;
    uint32_t *id;
    int32_t *species; ///< the phase
} bdl_solids_sample;

/// The world's particles as bdl_capture_view gives them; for a world with solids phases on the
/// grid, the spheres they are drawn with (as bdl_capture samples them for frames and the viewer:
/// each cell holds the spheres its solids volume makes, with the phase's velocity at the cell),
/// held in `s`. Returns 0 when out of memory.
int bdl_capture_solids_view(bdl_solids_sample *s, const bdl_world *w, bdl_particle_view *view);
void bdl_solids_sample_free(bdl_solids_sample *s);

#endif
