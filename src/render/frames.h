// bedlam — headless PNG frames of a run: frames/frame_NNNNNN.png every [output] frame_interval.
//
// Three threads share the work, so the solver never draws or encodes:
//   solver   fills a free snapshot slot at each frame time (and waits only when all slots are
//            full: a dump never drops a frame);
//   caller   (the thread that opened the frames and owns the GL context) draws each queued
//            snapshot and reads the pixels back;
//   encoder  compresses the pixels to PNG and writes the file atomically.
#ifndef BDL_FRAMES_H
#define BDL_FRAMES_H

#include "io/snapshot.h"
#include "render/context.h"
#include "scene/scene.h"

typedef struct bdl_frames_def {
    const bdl_scene *scene;
    const char *folder;     ///< where frame_NNNNNN.png go (must exist)
    bdl_gl_backend backend; ///< BDL_GL_AUTO, BDL_GL_EGL or BDL_GL_OSMESA
} bdl_frames_def;

typedef struct bdl_frames bdl_frames;

/// Creates the headless context and renderer on the calling thread and starts the encoder.
/// On failure returns BDL_ERR_GL (no context) or BDL_ERR_NOMEM with a sentence in `why`.
bdl_result bdl_frames_open(const bdl_frames_def *def, bdl_frames **out, char *why, size_t why_len);

/// Solver thread: a free snapshot slot to fill with the next frame; blocks while every slot is
/// queued. NULL after an error of the drawing or encoding threads (bdl_frames_commit returns it).
bdl_snapshot *bdl_frames_slot(bdl_frames *f);

/// Solver thread: queues the slot bdl_frames_slot gave, now filled, as frame number `index`
/// (`filled` 0: filling it ran out of memory). Returns the first error of any thread.
bdl_result bdl_frames_commit(bdl_frames *f, long index, int filled);

/// Solver thread: waits until every committed frame is written to its file (and on the disk:
/// PNG files are written atomically), while the caller's thread goes on pumping. A run calls it
/// before a checkpoint, so that a run killed after the checkpoint lacks none of the frames before
/// it. Returns the first error of any thread.
bdl_result bdl_frames_sync(bdl_frames *f);

/// After an error from bdl_frames_commit or bdl_frames_sync: the file a write failed on, and
/// why ("PATH: no space left on device ..."); empty for other errors.
const char *bdl_frames_failure(const bdl_frames *f);

/// Caller thread: draws every queued frame, waiting up to `timeout` seconds for the first.
/// Returns the number drawn.
int bdl_frames_pump(bdl_frames *f, double timeout);

/// Caller thread: draws what is still queued, waits for the encoder, frees everything. Returns
/// the first error, and the number of frames written in `written`.
bdl_result bdl_frames_close(bdl_frames *f, long *written);

#endif
