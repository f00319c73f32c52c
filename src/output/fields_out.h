// bedlam — the files of the time-averaged solids fields (analysis/fields.h):
//
//   fields.vti   solids_fraction and solids_velocity per cell (VTK ImageData, ParaView), written
//                by `bedlam analyze fields`
#ifndef BDL_FIELDS_OUT_H
#define BDL_FIELDS_OUT_H

#include "analysis/fields.h"
#include "world/world.h"

/// Writes fields.vti of the samples so far (at least one): solids_fraction and solids_velocity
/// per cell, atomically.
bdl_result bdl_fields_vti_write(const bdl_fields *f, const char *path);

#endif
