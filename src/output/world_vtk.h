// bedlam — a world's particles and gas fields as VTK XML files (ParaView).
//
//   particles .vtp: centres, radius, velocity, spin, id, species, coordination (parcels: the
//                   real particles each stands for, parcel_count)
//   gas .vti:       voidage, pressure and gas velocity (face values averaged to the centres)
#ifndef BDL_WORLD_VTK_H
#define BDL_WORLD_VTK_H

#include "world/world.h"

/// Writes the particles to `path` (atomically).
bdl_result bdl_world_vtp_write(const bdl_world *w, const char *path);

/// Writes the gas's cell fields to `path` (atomically); the world must have a gas.
bdl_result bdl_world_gas_vti_write(const bdl_world *w, const char *path);

#endif
