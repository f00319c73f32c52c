// bedlam — checkpoints: the complete dynamic state of a world, for --resume.
//
// A checkpoint holds everything the next step reads: particle state including this step's forces,
// the neighbour and wall-contact lists with their history and the positions they were built at,
// the random generator, pour counters, live parameters and energy bookkeeping, and with a gas its
// velocity, pressure and voidage, the gas's forces the particles carry between gas steps and the
// gas-step schedule. Restoring it into a world built from the same scene continues bit-for-bit.
// Files are written atomically.
#ifndef BDL_CHECKPOINT_H
#define BDL_CHECKPOINT_H

#include "world/world.h"

bdl_result bdl_checkpoint_save(const bdl_world *w, const char *path);

/// Replaces the state of `w` (built from the same scene) by the checkpoint's. On a mismatch or a
/// damaged file returns BDL_ERR_CHECKPOINT with a sentence in `why`; when it fails after the
/// header (a truncated or damaged file) the state of `w` is undefined and `w` must be destroyed.
bdl_result bdl_checkpoint_load(bdl_world *w, const char *path, char *why, size_t why_len);

#endif
