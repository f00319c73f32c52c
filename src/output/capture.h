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

#endif
