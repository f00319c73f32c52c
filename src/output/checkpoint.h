// bedlam — checkpoints: the complete dynamic state of a world, for --resume.
//
// A checkpoint holds everything the next step reads: particle state including this step's forces,
// the neighbour and wall-contact lists with their history and the positions they were built at,
// the random generator, pour counters, live parameters and energy bookkeeping, and with a gas its
// velocity, pressure and voidage, the gas's forces the particles carry between gas steps and the
// gas-step schedule. Restoring it into a world built from the same scene continues bit-for-bit.
// Files are written atomically.
//
// A checkpoint is read as untrusted input. The file is a 32-byte header (format version, payload
// size, a CRC-32 of the payload and one of the header) and a payload: a record of the scene it was
// written for, the scalars, the counts and the arrays. Loading refuses a file whose header,
// size or checksum is wrong before it reads any count, then checks the record against the scene
// and every count, index and number of the state against what the next step relies on. The
// layout and every check are in docs/checkpoints.md.
#ifndef BDL_CHECKPOINT_H
#define BDL_CHECKPOINT_H

#include <stdio.h>

#include "world/world.h"

bdl_result bdl_checkpoint_save(const bdl_world *w, const char *path);

/// What a successful load found besides the state.
typedef struct bdl_checkpoint_info {
    double dt; ///< the time step the checkpoint was written with [s]
    /// The contact parameters of the scene that differ from the checkpoint's, "; "-separated
    /// ("species 'rod': stiffness 6000 N/m in the checkpoint, 600000 N/m in the scene"); "" when
    /// none.
    char changes[1024];
} bdl_checkpoint_info;

/// Replaces the state of `w` (built from the same scene) by the checkpoint's. The time step stays
/// the world's, derived from its scene: `info` (may be NULL) gives the checkpoint's, and the
/// contact parameters that changed. On a damaged, inconsistent or mismatched file returns
/// BDL_ERR_CHECKPOINT with a sentence in `why` naming the file and what is wrong
/// (BDL_ERR_NOMEM when the state does not fit in memory); when it fails after the header the
/// state of `w` is undefined and `w` must be destroyed.
bdl_result bdl_checkpoint_load(bdl_world *w, const char *path, bdl_checkpoint_info *info, char *why,
                               size_t why_len);

/// bdl_checkpoint_load from an open binary stream that can seek (a file, or memory with
/// fmemopen); `name` stands for the file in messages.
bdl_result bdl_checkpoint_read(bdl_world *w, FILE *f, const char *name, bdl_checkpoint_info *info,
                               char *why, size_t why_len);

#endif
