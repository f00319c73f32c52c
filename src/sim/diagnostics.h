// bedlam — per-run diagnostics: energies, coordination, overlaps and the energy balance.
//
// Sums over particles are taken in fixed blocks, in block order, so the numbers do not depend on
// the thread count.
#ifndef BDL_DIAGNOSTICS_H
#define BDL_DIAGNOSTICS_H

#include "sim/world.h"

typedef struct bdl_diagnostics {
    double time; ///< [s]
    long step;
    double wall_seconds; ///< wall-clock time since the run started [s]
    long particle_count;
    double kinetic_energy;    ///< translational [J]
    double rotational_energy; ///< [J]
    double potential_energy;  ///< gravitational, -m g.x summed [J]
    double elastic_energy;    ///< stored in contact springs [J]
    double mean_coordination; ///< particle-particle contacts per particle
    double max_overlap_ratio; ///< largest overlap / smaller radius [-]
    double wall_work;         ///< work done by walls on the particles since the start [J]
    double energy_balance;    ///< E - E0 - W_walls - E_inserted [J]; <= 0 for dissipative contacts
    double max_speed;         ///< [m/s]
} bdl_diagnostics;

/// Column names of diagnostics.csv, in the order of bdl_diagnostics_row.
extern const char *const bdl_diagnostics_columns[];
extern const int bdl_diagnostics_column_count;

/// Computes every diagnostic for the current state. `energy0` is the total energy at the start
/// (pass 0 when unknown).
void bdl_diagnostics_compute(const bdl_world *w, double energy0, bdl_diagnostics *d);

/// Total mechanical energy: kinetic + rotational + potential + elastic [J].
double bdl_diagnostics_total_energy(const bdl_diagnostics *d);

/// Values in column order.
void bdl_diagnostics_row(const bdl_diagnostics *d, double *values);

#endif
