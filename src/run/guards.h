// bedlam — stability guards, before and during a run.
//
// Before: the time step against the smallest contact time of every species pair and wall
// (refused above [guards] dt_refuse, warned above dt_warn). During, every check_interval steps:
// NaN/Inf in the state, an overlap beyond max_overlap of the smaller radius, a particle that left
// the domain, and mechanical energy that grew by more than energy_growth of the active energy
// without a source (moving walls and inserted particles are sources). A violation produces a
// message saying what, where, when and the likely fix.
#ifndef BDL_GUARDS_H
#define BDL_GUARDS_H

#include <stddef.h>

#include "output/diagnostics.h"
#include "world/world.h"

typedef struct bdl_guard_state {
    double energy0;    ///< total energy at the start [J]
    double active_max; ///< largest kinetic + rotational + elastic energy seen [J]
} bdl_guard_state;

/// Checks dt against the contact time. Returns BDL_ERR_SCENE (refuse) with a message, or BDL_OK;
/// a warning, if any, is written to `warning` (empty otherwise).
bdl_result bdl_guards_check_dt(const bdl_world *w, char *message, size_t len, char *warning,
                               size_t warning_len);

void bdl_guards_init(bdl_guard_state *g, const bdl_diagnostics *d);

/// In-run checks. Returns BDL_ERR_UNSTABLE with a message on a violation. `d` must be current.
bdl_result bdl_guards_check(const bdl_world *w, bdl_guard_state *g, const bdl_diagnostics *d,
                            char *message, size_t len);

#endif
