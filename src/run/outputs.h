// bedlam — the files a run writes while it goes, at their times (private to the run driver).
//
// Every output is due at multiples of its [output] interval from t = 0, so a resumed run keeps
// the first run's output times and numbering; a time is due when a step lands within half a step
// of it. The per-step callback runs on the solver thread; the error figures it leaves for the
// progress line are atomics, read from the caller's thread.
#ifndef BDL_RUN_OUTPUTS_H
#define BDL_RUN_OUTPUTS_H

#include <stdatomic.h>

#include "dia/dia_run.h"
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
    bdl_csv *profile_csv; ///< profile.csv, with a gas only
    double *profile_row;
    bdl_csv *orientation_csv; ///< orientation.csv, with rods and [output] orientation_interval
    bdl_pvd *pvd;
    bdl_pvd *gas_pvd; ///< gas fields, with [gas] only
    bdl_guard_state guard;
    double energy0;
    double start_wall; ///< wall clock when the outputs opened [s]
    double next_diag, next_vtk, next_checkpoint, next_contacts, next_frame, next_orientation;
    long vtk_index, frame_index;
    bdl_frames *frames; ///< NULL: no frames
    bdl_dia_run *dia;   ///< synthetic cameras ([camera NAME]); NULL without
    char failure[1024]; ///< what an unstable step ran into
    // The errors of the last diagnostics, for the progress line.
    _Atomic double energy_balance, energy_in, weight_ratio, gas_mass, momentum;
    _Atomic long particles_out;
    _Atomic int measured;
} bdl_run_outputs;

/// Opens every output of a run in folder `out` (created, writable) for the world as it stands,
/// and writes what is due at the start. `resume`: the files exist and continue.
bdl_result bdl_run_outputs_open(bdl_run_outputs *o, bdl_world *w, const char *out, int resume,
                                int gl_backend);

/// The solver thread's per-step callback (bdl_loop_def.on_step): guards, and what is due.
bdl_result bdl_run_outputs_step(void *user, bdl_world *w);

/// The error figures of the last diagnostics into a status.
void bdl_run_outputs_status(bdl_run_outputs *o, bdl_run_status *s);

/// Closes the frame writer, the cameras and every file. When the solver ran (`solved`) and stopped
/// with result *r, first writes the last diagnostics row (after a clean end) and the checkpoint.
/// Returns the checkpoint's result; *r becomes the frame writer's error after a clean end.
bdl_result bdl_run_outputs_close(bdl_run_outputs *o, int solved, bdl_result *r);

#endif
