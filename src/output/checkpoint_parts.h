// bedlam — the parts of a checkpoint file, shared by checkpoint.c (the format: header, payload,
// save and load), checkpoint_scene.c (the record of the scene a checkpoint was written for, and
// its comparison with the scene it is resumed with) and checkpoint_state.c (the range checks of
// a restored state). Not for other modules: they use output/checkpoint.h.
#ifndef BDL_CHECKPOINT_PARTS_H
#define BDL_CHECKPOINT_PARTS_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#include "world/world.h"

/// Writes the payload, counting its bytes and their CRC-32 as they go.
typedef struct bdl_ckpt_writer {
    FILE *f;
    int ok;         ///< 0 once a write failed
    uint64_t bytes; ///< written so far
    uint32_t crc;   ///< CRC-32 of what was written so far
} bdl_ckpt_writer;

/// Reads the payload and never past its end: a read longer than what is `left` fails.
typedef struct bdl_ckpt_reader {
    FILE *f;
    int ok;        ///< 0 once a read fell short
    uint64_t left; ///< bytes of the payload not read yet
} bdl_ckpt_reader;

void bdl_ckpt_put(bdl_ckpt_writer *out, const void *data, size_t size);
void bdl_ckpt_get(bdl_ckpt_reader *in, void *data, size_t size);

/// Writes the record of the world's scene: what the saved state's layout and meaning depend on
/// (species, walls, creators, contact law, gas grid) and the contact parameters.
void bdl_ckpt_put_scene(bdl_ckpt_writer *out, const bdl_world *w);

/// Reads a scene record and compares it with the scene of `w`. Returns 0 with the reason in `why`
/// when the state cannot be restored into `w` (species, walls, creators, law, sliding friction or
/// gas grid differ); else 1, with the contact parameters that differ listed in `changes` ("" when
/// none).
int bdl_ckpt_check_scene(bdl_ckpt_reader *in, const bdl_world *w, char *why, size_t why_len,
                         char *changes, size_t changes_len);

/// Range checks of a state just restored into `w`: every count, index, flag and number the next
/// step reads. `saved_dt` is the time step in the file. Returns 0 with the reason in `why`.
int bdl_ckpt_check_state(const bdl_world *w, double saved_dt, char *why, size_t why_len);

#endif
