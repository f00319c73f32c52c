// bedlam — per-run diagnostics: energies, coordination, overlaps, the energy balance and, with a
// gas, pressure drop, bed height and the conservation errors of the coupling.
//
// "Lowest" and "height" are along gravity (along z without gravity).
//
// Sums over particles are taken in fixed blocks, in block order, so the numbers do not depend on
// the thread count.
#ifndef BDL_DIAGNOSTICS_H
#define BDL_DIAGNOSTICS_H

#include "world/world.h"

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
    double energy_balance;    ///< E + E_out + W_left - E0 - W_walls - W_gas - E_inserted [J];
                              ///< <= 0 for dissipative contacts
    double max_speed;         ///< [m/s]
    // With a gas (0 without):
    double gas_work;             ///< work done by the gas on the particles since the start [J]
    double pressure_drop;        ///< mean pressure of the lowest cell layer minus the highest [Pa]
    double bed_height;           ///< height below which 95 % of the particle centres lie [m]
    double gas_volume_imbalance; ///< largest cell |d eps/dt + div(eps u)| dt of the last gas step
    double momentum_imbalance;   ///< |drag on particles + drag on gas| / |drag on particles| over
                                 ///< the axes the gas can move along
    double probe_pressure_drop;  ///< pressure at [gas] probe_low minus at probe_high [Pa]; NaN
                                 ///< without probes (with or without a gas)
    double weight_ratio;   ///< (pressure_drop - gas column's weight per area) / (particles' weight
                           ///< less buoyancy per base area): 1 when the gas carries the bed; NaN
                           ///< without a gas or along a periodic gravity axis
    long particles_out;    ///< particles that left through gas outlets since the start
    double mass_out;       ///< their mass [kg]
    double inlet_velocity; ///< superficial inlet velocity now (the sweep's stage) [m/s]
    double mean_height;    ///< with a gas: mean particle centre height above the floor [m]
    double multi_contact_ratio; ///< particles with >= 2 contacts / particles with >= 1
    double wall_force;          ///< sum of the normal forces of all particle-wall contacts [N]
    double spring_work_left;    ///< W_left: work the Hertz-Mindlin springs held when their
                                ///< contacts ended, since the start [J] (a spring whose stiffness
                                ///< fell with the overlap gives back less than it took: > 0)
    double bubble_count;        ///< with a gas: bubbles in its voidage field (analysis/bubbles.h)
    double bubble_diameter;     ///< their mean equivalent diameter [m] (0 without bubbles)
    double segregation; ///< Sun's s_p of two species of spheres (NAN with one or more than two)
    // Of the rods (NAN without; the columns are written only in scenes with rods):
    double rod_vertical_cos; ///< mean |cos| of the angle of the axes to the vertical
    double rod_order;        ///< nematic order parameter S of the axes (analysis/granular.h)
} bdl_diagnostics;

/// Column names of diagnostics.csv, in the order of bdl_diagnostics_row.
extern const char *const bdl_diagnostics_columns[];
extern const int bdl_diagnostics_column_count;

/// How many of the columns a run of w writes: all in scenes with rods, else all but the last two
/// (the rods' orientation).
int bdl_diagnostics_columns_for(const bdl_world *w);

/// Whether column `column` may hold NaN in a sound state, meaning "not defined here": the probe
/// pressure drop without probes, the weight ratio and mean height without a gas or particles, the
/// rods' orientation without rods. Every other column of a row is finite unless the state is not.
int bdl_diagnostics_may_be_undefined(int column);

/// Computes every diagnostic for the current state. `energy0` is the total energy at the start
/// (pass 0 when unknown).
void bdl_diagnostics_compute(const bdl_world *w, double energy0, bdl_diagnostics *d);

/// Total mechanical energy: kinetic + rotational + potential + elastic [J].
double bdl_diagnostics_total_energy(const bdl_diagnostics *d);

/// Values in column order.
void bdl_diagnostics_row(const bdl_diagnostics *d, double *values);

#endif
