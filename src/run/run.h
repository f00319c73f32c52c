// bedlam — a headless run: scene in, one output folder out.
//
//   OUT/run.log          version, scene, resolved parameters, active modules, limits, commands
//   OUT/diagnostics.csv  one row per [output] diagnostics_interval
//   OUT/vtk/particles_NNNNNN.vtp + OUT/particles.pvd   every vtk_interval (ParaView)
//   OUT/frames/frame_NNNNNN.png  every frame_interval (render/frames.h)
//   OUT/fields.vti       the solids fields averaged over samples every fields_interval, at every
//                        checkpoint and the end; their sums in OUT/checkpoint/fields.sums
//   OUT/checkpoint/state.bdlckpt  every checkpoint_interval, at the end and on a stop, of a state
//                                 that passes the guards; the state at a failure goes beside it,
//                                 to OUT/checkpoint/failed.bdlckpt
//
// The driver goes through named phases: read the scene, open the output folder, build the world
// (and resume it), open the outputs, run the solver thread while reporting progress, and close
// with the last row and a checkpoint. It prints nothing itself but its log (core/log.h); the
// caller turns the progress it reports into a line, the result into an exit code, and signals
// into the stop flag.
#ifndef BDL_RUN_H
#define BDL_RUN_H

#include <signal.h>

#include "core/error.h"
#include "render/frames.h"
#include "world/world.h"

/// How far a run is, in raw figures: the caller formats them.
typedef struct bdl_run_status {
    double time;              ///< simulated time [s]
    double start_time;        ///< where this run started (resumed: the checkpoint's time) [s]
    double end_time;          ///< [s]
    long step;                ///< steps taken since t = 0
    long start_step;          ///< the step this run started at
    long particles;           ///< particles now
    double wall_seconds;      ///< wall time since the outputs opened [s]
    double progress_interval; ///< [output] progress_interval: wall seconds between reports [s]
    int finished;             ///< the solver has stopped: the last report of the run
    int gas;                  ///< the run has a gas (the gas figures below mean something)
    // The run's own errors at the last diagnostics (measured = 0 before the first):
    int measured;
    double energy_balance;       ///< energy now - at the start - work put in [J]
    double energy_in;            ///< work put in by walls, gas and insertion [J]
    double weight_ratio;         ///< pressure drop over the bed's weight
    double gas_volume_imbalance; ///< worst cell's gas volume imbalance of the last gas step
    double momentum_imbalance;   ///< interphase momentum imbalance
    long particles_out;          ///< particles that left through gas outlets
} bdl_run_status;

typedef void (*bdl_run_progress_fn)(void *user, const bdl_run_status *status);

typedef struct bdl_run_def {
    const char *scene_path;
    const char *const *overrides; ///< "section.key=value" strings
    int override_count;
    const char *out_dir; ///< the output folder (created when missing)
    double until;        ///< end time [s]; < 0: the scene's end_time
    long max_steps;      ///< stop after this many steps (0: no limit)
    int threads;         ///< <= 0: the scene's [run] threads (0 = all cores)
    const char *resume;  ///< checkpoint file or run folder to continue from; NULL for a new run
    int gl_backend;      ///< bdl_gl_backend for frames (0: automatic)
    /// Nonzero: stop cleanly after the current step (a signal handler sets it). NULL: never.
    const volatile sig_atomic_t *stop;
    bdl_run_progress_fn progress; ///< called every [output] progress_interval; NULL: never
    void *user;                   ///< passed to `progress`
} bdl_run_def;

/// Where a run stopped.
typedef struct bdl_run_report {
    double time;         ///< simulated time [s]
    long step;           ///< steps since t = 0
    long particles;      ///< particles at the end
    double wall_seconds; ///< wall time of the solver and outputs [s]
} bdl_run_report;

bdl_run_def bdl_default_run_def(void);

/// Runs to the end time (or max_steps, or a stop). Returns BDL_ERR_SCENE, BDL_ERR_ARGS,
/// BDL_ERR_OUTPUT_DIR or BDL_ERR_CHECKPOINT for bad input, another error for a failure while
/// running (each logged with what, where and when): BDL_ERR_UNSTABLE, or BDL_ERR_IO when an
/// output or the last checkpoint could not be written (the message names the file and says
/// why, "no space left on device" for a full disk); `report` (may be NULL) says where it
/// stopped.
bdl_result bdl_run(const bdl_run_def *def, bdl_run_report *report);

/// The checkpoint file of a --resume path: the path itself, or PATH/checkpoint/state.bdlckpt
/// when it is a run folder (returns 1 then).
int bdl_run_checkpoint_path(const char *resume, char *out, size_t len);

/// Queues frame number `index` of the world as it is now with a frame writer (solver thread).
bdl_result bdl_run_frame(bdl_frames *frames, const bdl_world *w, long index);

#endif
