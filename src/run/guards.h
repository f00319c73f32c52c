// bedlam — stability guards, before and during a run.
//
// Before: the time step against the smallest contact time of every species pair and wall
// (refused above [guards] dt_refuse, warned above dt_warn). During, every check_interval steps:
// NaN/Inf in the state, an overlap beyond max_overlap of the smaller radius, a particle that left
// the domain, and mechanical energy that grew by more than energy_growth of the active energy
// without a source (moving walls and inserted particles are sources); before every checkpoint
// all but the energy balance. Before every other output the state is checked to be finite, and
// each row to be written too, so that no output holds a non-finite number. A violation produces a
// message saying what (the array, the particle or cell), when (the step) and where to look.
#ifndef BDL_GUARDS_H
#define BDL_GUARDS_H

#include <stddef.h>

#include "output/diagnostics.h"
#include "world/world.h"

typedef struct bdl_guard_state {
    double energy0;    ///< total energy at the start [J]
    double active_max; ///< largest kinetic + rotational + elastic energy seen [J]
    long finite_step;  ///< the last step the state was found finite at
} bdl_guard_state;

/// Checks dt against the contact time. Returns BDL_ERR_SCENE (refuse) with a message, or BDL_OK;
/// a warning, if any, is written to `warning` (empty otherwise).
bdl_result bdl_guards_check_dt(const bdl_world *w, char *message, size_t len, char *warning,
                               size_t warning_len);

void bdl_guards_init(bdl_guard_state *g, const bdl_world *w, const bdl_diagnostics *d);

/// The checks of the state itself: finite, every particle in the domain, no overlap beyond
/// max_overlap. A checkpoint is written only of a state that passes them. BDL_ERR_UNSTABLE with
/// a message on a violation; `d` must be current.
bdl_result bdl_guards_check_state(const bdl_world *w, bdl_guard_state *g, const bdl_diagnostics *d,
                                  char *message, size_t len);

/// In-run checks: those of the state, and the energy balance. Returns BDL_ERR_UNSTABLE with a
/// message on a violation. `d` must be current.
bdl_result bdl_guards_check(const bdl_world *w, bdl_guard_state *g, const bdl_diagnostics *d,
                            char *message, size_t len);

/// Whether every number the next step starts from is finite: the particles' positions,
/// velocities, spins, forces and torques (with rods their orientations and angular momenta, with
/// a gas the gas's forces on them) and the gas's velocity, pressure and voidage. Otherwise
/// BDL_ERR_UNSTABLE and a message naming the first non-finite number (array, particle id or
/// cell, component, value) and the step. Cheap: one pass over the arrays; run before every
/// output.
bdl_result bdl_guards_check_finite(const bdl_world *w, bdl_guard_state *g, char *message,
                                   size_t len);

/// Whether a row about to be written to `file` (`count` values, columns `names`, NULL: numbered)
/// is finite, but for NaN in columns `may_be_nan` accepts (NULL: none). BDL_ERR_UNSTABLE and a
/// message naming the column otherwise.
bdl_result bdl_guards_check_row(const bdl_world *w, const char *file, const char *const *names,
                                const double *row, int count, int (*may_be_nan)(int), char *message,
                                size_t len);

#endif
