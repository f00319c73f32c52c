// bedlam — the solver thread: a fixed-step loop, commands between steps, snapshots out.
//
// The solver runs on its own thread and never waits for a consumer. Snapshots for drawing are
// published through a triple buffer: the solver writes the back slot and swaps it with the
// middle one; a reader takes the middle slot when it is newer than its own. Commands (pause,
// resume, single step, set a live parameter, stop) are queued by any thread and applied between
// steps; each is logged with the step it took effect at, so an interactive session can be
// replayed.
#ifndef BDL_LOOP_H
#define BDL_LOOP_H

#include <stdint.h>

#include "io/snapshot.h"
#include "world/world.h"

typedef enum bdl_command_kind {
    BDL_CMD_PAUSE,
    BDL_CMD_RESUME,
    BDL_CMD_STEP, ///< one step while paused
    BDL_CMD_SET,  ///< set a live parameter: key "wall.NAME.amplitude_scale" / ".frequency_scale"
    BDL_CMD_STOP, ///< finish after the current step
} bdl_command_kind;

typedef struct bdl_command {
    bdl_command_kind kind;
    char key[96];
    double value;
} bdl_command;

/// Called by the solver thread after every step (outputs, guards). A result other than BDL_OK
/// stops the loop with that result.
typedef bdl_result (*bdl_step_callback)(void *user, bdl_world *world);

typedef struct bdl_loop_def {
    bdl_world *world;
    double end_time; ///< stop when simulated time reaches this [s]
    long max_steps;  ///< stop after this many steps of this loop (0: no limit)
    int threads;     ///< OpenMP threads of the solver thread (0: the default)
    bdl_step_callback on_step;
    void *user;
    int publish;             ///< publish snapshots (a viewer is attached)
    int log_failures;        ///< log why a step failed (world->failure); bdl_run reports it itself
    double publish_interval; ///< wall seconds between snapshots
    int start_paused;
} bdl_loop_def;

bdl_loop_def bdl_default_loop_def(void);

typedef struct bdl_loop bdl_loop;

/// Starts the solver thread.
bdl_loop *bdl_loop_start(const bdl_loop_def *def);
void bdl_loop_command(bdl_loop *loop, const bdl_command *cmd);
/// Newest complete snapshot, or NULL before the first one.
const bdl_snapshot *bdl_loop_acquire(bdl_loop *loop);
/// Limits the solver to `sim_per_wall` simulated seconds per wall-clock second (0: no limit).
void bdl_loop_set_speed_limit(bdl_loop *loop, double sim_per_wall);
/// Progress, readable from any thread.
void bdl_loop_progress(bdl_loop *loop, double *time, long *step, long *particles, int *finished);
/// Waits for the solver thread and returns its result.
bdl_result bdl_loop_join(bdl_loop *loop);
void bdl_loop_destroy(bdl_loop *loop);

#endif
