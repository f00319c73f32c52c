// bedlam — the files a run writes while it goes, at their times (private to the run driver).
//
// Every output is due at multiples of its [output] interval from t = 0, so a resumed run keeps
// the first run's output times and numbering; a time is due when a step lands within half a step
// of it. The per-step callback runs on the solver thread; the error figures it leaves for the
// progress line are atomics, read from the caller's thread.
//
// Nothing is lost to a kill: before every checkpoint the time series (diagnostics, species,
// profile, orientation, the cameras' indexes) are flushed and fsynced and the queued frames
// written, so that a run killed at any moment and resumed from its last checkpoint has every row
// and file up to it; on resuming, the series drop their rows after the checkpoint's time, the
// .pvd collections keep their entries up to it with their true times, and the numbering goes on
// after the last output written before it. The sums of the time-averaged fields go beside each
// checkpoint (checkpoint/fields.sums; the previous ones stay, as fields.prev.sums, until the
// checkpoint is written), and a resumed run continues them. No output holds a non-finite number:
// the state is checked before every write. A checkpoint is written only of a state that passed
// every guard: the state at a failure goes to checkpoint/failed.bdlckpt, beside the last good one.
#ifndef BDL_RUN_OUTPUTS_H
#define BDL_RUN_OUTPUTS_H

#include <stdatomic.h>

#include "analysis/fields.h"
#include "dia/dia_run.h"
#include "output/capture.h"
#include "io/csv.h"
#include "io/vtk.h"
#include "output/diagnostics.h"
#include "render/frames.h"
#include "run/guards.h"
#include "run/run.h"

typedef struct bdl_run_outputs {
    const char *out; ///< the output folder
    bdl_world *world;
    const volatile sig_atomic_t *stop; ///< see bdl_run_def
    bdl_csv *csv;                      ///< diagnostics.csv
    bdl_csv *species_csv;              ///< species.csv, with two or more species only
    double *species_row;
    int species_columns;
    bdl_csv *profile_csv; ///< profile.csv, with a gas only
    double *profile_row;
    int profile_columns;
    bdl_csv *orientation_csv; ///< orientation.csv, with rods and [output] orientation_interval
    bdl_csv *rheology_csv;    ///< rheology.csv, with [output] rheology_interval
    double next_rheology;
    bdl_pvd *pvd;
    bdl_pvd *gas_pvd; ///< gas fields, with [gas] only
    bdl_guard_state guard;
    double energy0;
    double start_wall; ///< wall clock when the outputs opened [s]
    double next_diag, next_vtk, next_checkpoint, next_contacts, next_frame, next_orientation;
    long vtk_index, frame_index;
    bdl_frames *frames;              ///< NULL: no frames
    bdl_dia_run *dia;                ///< synthetic cameras ([camera NAME]); NULL without
    bdl_solids_sample solids_sample; ///< their view of solids phases on the grid
    // The time-averaged solids fields of fields.vti, with [output] fields_interval.
    int fields_on;
    bdl_fields fields;
    double fields_cell; ///< the cell asked of their grid (the default resolved) [m]
    double next_fields;
    int sums_at_good;   ///< checkpoint/fields.sums holds the sums of the last good checkpoint
    char failure[1400]; ///< what stopped the run: an unstable state, or a write that failed
    int write_failed;   ///< the run stopped on a failed write (the state itself is sound)
    char also[1400];    ///< a failure of the close after the run's own, reported after it
    // The last checkpoint of a state that passed every guard: the one a resume starts from.
    char good_path[1200]; ///< empty: none yet
    double good_time;     ///< its time [s]
    long good_step;
    char final_checkpoint[16]; ///< what the end wrote: "state.bdlckpt", "failed.bdlckpt" or ""
    long kill_at_step;         ///< tests only (BEDLAM_TEST_KILL_AT_STEP); -1: never
    // The errors of the last diagnostics, for the progress line.
    _Atomic double energy_balance, energy_in, weight_ratio, gas_mass, momentum;
    _Atomic long particles_out;
    _Atomic int measured;
} bdl_run_outputs;

/// Opens every output of a run in folder `out` (created, writable) for the world as it stands,
/// and writes what is due at the start. `resume`: the files exist and continue, and
/// `o->good_path` names the checkpoint the run resumed from.
bdl_result bdl_run_outputs_open(bdl_run_outputs *o, bdl_world *w, const char *out, int resume,
                                int gl_backend);

/// Whether anything (a row, a check, a file, a checkpoint) falls due at w's time and step: an
/// MPI run gathers its state for bdl_run_outputs_step only then.
int bdl_run_outputs_due(const bdl_run_outputs *o, const bdl_world *w);

/// The solver thread's per-step callback (bdl_loop_def.on_step): guards, and what is due.
bdl_result bdl_run_outputs_step(void *user, bdl_world *w);

/// The error figures of the last diagnostics into a status.
void bdl_run_outputs_status(bdl_run_outputs *o, bdl_run_status *s);

/// Closes the frame writer, the cameras and every file. When the solver ran (`solved`) and stopped
/// with result *r, first writes the last diagnostics row (after a clean end) and the checkpoint:
/// checkpoint/state.bdlckpt of a state that passes the guards, checkpoint/failed.bdlckpt of one
/// that does not (after an instability). *r becomes the first failure of these writes (BDL_ERR_IO,
/// with `failure` naming the file), or BDL_ERR_UNSTABLE when the state failed the guards only now.
/// Returns 1 when the state was written as a failed one.
int bdl_run_outputs_close(bdl_run_outputs *o, int solved, bdl_result *r);

#endif
