// bedlam — a headless run: scene in, one output folder out.
//
//   OUT/run.log          version, scene, resolved parameters, active modules, limits, commands
//   OUT/diagnostics.csv  one row per [output] diagnostics_interval
//   OUT/vtk/particles_NNNNNN.vtp + OUT/particles.pvd   every vtk_interval (ParaView)
//   OUT/frames/frame_NNNNNN.png  every frame_interval (render/frames.h)
//   OUT/checkpoint/state.bdlckpt  every checkpoint_interval, at the end, on Ctrl-C and on failure
#ifndef BDL_RUN_H
#define BDL_RUN_H

#include "render/frames.h"
#include "world/world.h"

typedef struct bdl_run_def {
    const char *scene_path;
    const char *const *overrides; ///< "section.key=value" strings
    int override_count;
    const char *out_dir; ///< NULL: runs/<scene name>
    double until;        ///< end time [s]; < 0: the scene's end_time
    long max_steps;      ///< stop after this many steps (0: no limit)
    int threads;         ///< <= 0: the scene's [run] threads (0 = all cores)
    const char *resume;  ///< checkpoint file or run folder to continue from; NULL for a new run
    int progress;        ///< 1: progress line on stderr (when it is a terminal), 0: never
    int gl_backend;      ///< bdl_gl_backend for frames (0: automatic)
} bdl_run_def;

bdl_run_def bdl_default_run_def(void);

/// Runs to the end time. Returns the process exit code (0 done, 1 run-time failure or
/// interrupted, 2 bad input) after printing any error.
int bdl_run(const bdl_run_def *def);

/// Queues frame number `index` of the world as it is now with a frame writer (solver thread).
bdl_result bdl_run_frame(bdl_frames *frames, const bdl_world *w, long index);

/// Set by the SIGINT handler; a run stops cleanly when it sees it.
void bdl_run_request_stop(void);

#endif
