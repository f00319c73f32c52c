// bedlam — a solids phase on the gas grid: the two-fluid model's continuum of spheres.
//
// The phase's solids fraction eps lives in the gas's cells and its velocity v on the gas's faces
// (cfd/grid.h). One step, after the gas's voidage is set to 1 - eps:
//
//   per unit solids volume on every face, with k = beta / eps_s (couple/drag.h, finite as
//   eps_s -> 0) and G the gas pressure gradient,
//       A v^{n+1} = B + k u^{n+1} - G,
//       A = rho_s / dt + k + (rho_s D_conv + D_visc) / eps_s,
//       B = rho_s v^n / dt + rho_s g + (rho_s N_conv + N_visc - grad P_s) / eps_s,
//   the transport rho_s (div(F v) - v div F) (F the last step's solids fluxes, upwind) and the
//   viscous term div(mu_s grad v) point-implicit: their diagonal D in A, the neighbours' part N
//   in B, so that a step is a weighted mean and stays bounded;
//   the gas step (cfd/gas.h) then sees this equation eliminated from its own (partial
//   elimination: its drag becomes eps_s k (A - k) / A, its drag source eps_s k B / A, its
//   share of -grad p eps_g + eps_s k / A) and the solids' volume flux eps_up v written as
//   flux_u u - flux_p G + flux_0, so that the pressure equation makes the flux of gas and solids
//   together free of divergence, whatever the drag;
//   v^{n+1} from the step's u and G, and eps* = eps^n - dt div(eps_up v), eps_up upwind;
//   the plastic regime's pressure implicit: the increment dP = P_s(eps^{n+1}) - P_s(eps^n) of
//   the cells above eps_star at either end of the step adds the flux -grad(dP) / A, solved with
//   dP a chord of P_s times the change of eps and P_s kept >= 0 (a symmetric system, by
//   conjugate gradients, in a few passes), with an equal and opposite flux of gas (the volume
//   stays free of divergence; the gas's pressure is not corrected), so that a bed's stiff
//   frictional pressure holds it at its packing at the time steps the gas allows; with
//   def.kinetic_pressure implicit (one phase) the viscous regime's pressure k1 eps^2 theta, at
//   the step's theta, is corrected the same way in every cell that has one.
//
// Stresses: below eps_star Syamlal's viscous regime (solids/kinetic.h) with the granular
// temperature from the balance of production and dissipation in time, cell by cell, without
// transport (backward Euler; its limit dt -> infinity is MFIX's algebraic form), or with its
// transport (def.granular_energy: solids/energy.h), above it Schaeffer's plastic regime with the
// temperature set to zero (Sun 2007, eq. 7.7). The viscous term is div(mu_s grad v) (the
// transposed and bulk parts are left out). Every side of the domain that is not periodic is a
// wall to the solids: free-slip, or Johnson & Jackson's partial slip with def.specularity.
// docs/theory-tfm.md.
#ifndef BDL_SOLIDS_PHASE_H
#define BDL_SOLIDS_PHASE_H

#include "cfd/gas.h"
#include "core/error.h"
#include "core/names.h"
#include "couple/drag.h"

/// The granular energy: balanced in each cell in time without transport, or the transport
/// equation (solids/energy.h).
#define BDL_GRANULAR_ENERGIES(X)                                                                   \
    X(GRANULAR_ENERGY_LOCAL, "local", "balanced in each cell")                                     \
    X(GRANULAR_ENERGY_TRANSPORT, "transport", "transport equation")
BDL_CHOICES(bdl_granular_energy, BDL_GRANULAR_ENERGIES);

/// The viscous regime's pressure k1 eps^2 theta in the momentum step: explicit (its waves limit
/// the step to h / c), or made implicit by the plastic correction (one phase only).
#define BDL_KINETIC_PRESSURES(X)                                                                   \
    X(KINETIC_PRESSURE_EXPLICIT, "explicit", "in the momentum step only")                          \
    X(KINETIC_PRESSURE_IMPLICIT, "implicit", "corrected with the plastic regime's")
BDL_CHOICES(bdl_kinetic_pressure, BDL_KINETIC_PRESSURES);

typedef struct bdl_solids_def {
    double diameter; ///< [m]
    double density;  ///< [kg/m^3]
    double
        restitution; ///< normal restitution of the kinetic theory (an effective one for rotation)
    bdl_drag_law drag;
    bdl_drag_params drag_params;
    // The mixture's: with several phases the first phase's values hold for all.
    double eps_star;       ///< solids fraction where the plastic regime starts (Sun eq. 7.7: 0.58)
    double schaeffer_a;    ///< Schaeffer's P = eps A (eps - eps_star)^n: A [Pa]
    double schaeffer_n;    ///< and n
    double friction_angle; ///< angle of internal friction of the plastic regime [deg]
    double mu_max;         ///< cap of the frictional viscosity [Pa s]
    double dilute;         ///< below this solids fraction a face carries no stress
    double tolerance;      ///< relative residual of the plastic correction's solver
    int max_iterations;    ///< its iteration limit
    double phase_friction; ///< C_f of the drag between solids phases (Sun eq. 3.18)
    double specularity;    ///< Johnson & Jackson's phi' of the walls (0: free slip)
    bdl_granular_energy granular_energy;   ///< local balance or transport equation
    bdl_kinetic_pressure kinetic_pressure; ///< explicit, or implicit with the plastic regime's
    double wall_restitution; ///< Johnson & Jackson's e_w of the walls' energy flux (transport)
    double hindrance; ///< Gera et al.'s (2004) C1: the drag between phases gains C1 P_plastic
                      ///< [s/m^2] (0: Syamlal's alone)
    /// With the kinetic pressure implicit, the weight of its waves' speed in the stable step
    /// (bdl_solids_stable_dt): 0 leaves them out, 1 counts them as the explicit pressure does.
    double wave_weight;
} bdl_solids_def;

/// Glass beads of 2.49 mm (Goldschmidt's large particles, Sun 2007 table 5.1), e 0.97,
/// Syamlal-O'Brien drag with C 0.8 and D 2.65, the plastic regime from 0.58 with A = 1e24 Pa
/// (10^25 dyn/cm^2) and n = 10, a friction angle of 30 degrees and the viscosity capped at
/// 100 Pa s (MFIX's 1000 poise), no stress below a solids fraction of 1e-6; between phases no
/// friction.
bdl_solids_def bdl_default_solids_def(void);

typedef struct bdl_solids_stats {
    int iterations;      ///< the plastic correction's solver, last step (summed over its passes)
    int passes;          ///< the correction's passes, last step (at most 10)
    int unsettled;       ///< 1 if its last pass still changed its set: a step not converged
    double correction;   ///< largest |eps^{n+1} - eps*| it made
    double eps_max;      ///< largest solids fraction (all phases) after the step
    double eps_min;      ///< smallest of any phase (round-off below zero would show here)
    double pressure_max; ///< largest solids pressure [Pa]
} bdl_solids_stats;

#define BDL_SOLIDS_WORK   15
#define BDL_SOLIDS_PHASES 4 ///< most phases of a mixture
#define BDL_SOLIDS_PAIRS  (BDL_SOLIDS_PHASES * (BDL_SOLIDS_PHASES - 1) / 2)

/// One phase of spheres: its fields on the grid.
typedef struct bdl_solids_phase {
    bdl_solids_def def;
    double *eps;  ///< solids fraction in the cells (padded, cfd/grid.h)
    double *v[3]; ///< solids velocity on the faces [m/s]
    double
        *theta; ///< granular temperature in the cells [m^2/s^2] (state: the balance starts from it)
    double *pressure; ///< solids pressure in the cells [Pa]
    double *mu;       ///< solids shear viscosity in the cells [Pa s]
    double *slip;     ///< |u - v| in the cells [m/s]
    double *wall;     ///< Johnson & Jackson's wall friction coefficient of the cells [kg/(m^2 s)]
    /// Per face: A, B, k and eps_up of the momentum step (with several phases A, B and k after
    /// the phases' coupling: v = (B + k u - G) / A still), the solids' flux, the gas's drag.
    double *a[3], *b[3], *k[3], *up[3], *flux[3], *drag[3];
    double *cflux[3]; ///< its share of the plastic correction's flux (several phases)
    double *star;     ///< the fraction after the step's transport (several phases)
} bdl_solids_phase;

typedef struct bdl_solids {
    bdl_solids_def def; ///< the first phase's: the mixture's plastic regime and solver
    bdl_grid grid;
    int count;                                 ///< phases
    bdl_solids_phase phase[BDL_SOLIDS_PHASES]; ///< the phases
    double *eps; ///< all phases' solids fraction in the cells (the first phase's own with one)
    double *rel[BDL_SOLIDS_PAIRS]; ///< |v_l - v_m| of each pair of phases in the cells [m/s]
    double *plastic; ///< the mixture's plastic pressure in the cells [Pa] (several phases)
    /// Per face: A of the mixture's correction, 1/A = sum_m (eps_m / eps_s) gamma_m (the first
    /// phase's A with one phase); the correction's flux; its weights dt / (A h^2).
    double *a[3], *c[3], *weight[3];
    double *work[BDL_SOLIDS_WORK]; ///< cell arrays of the step and the plastic correction
    long *free_cells; ///< the plastic correction's unknowns: their indices, in the grid's order
    int active[3];    ///< the axes the step moves solids along (the others are inert: all zero)
    double *kept;     ///< the state bdl_solids_keep saved (NULL until it is first called)
    /// NULL, or a source of granular energy in each cell [W/m^3] with the transport equation
    /// (verification: manufactured solutions).
    double *theta_source;
    double time;
    long steps;
    bdl_solids_stats stats;
} bdl_solids;

/// A phase with no solids on the grid of `gas`, which must have been created with
/// def.pressure_share (its hooks carry the elimination). BDL_ERR_ARGS for a definition out of
/// range (a diameter, density, restitution outside (0, 1), eps_star outside (0, 1), A, n,
/// tolerance or iteration count not positive), BDL_ERR_NOMEM.
bdl_result bdl_solids_create(const bdl_solids_def *def, const bdl_gas *gas, bdl_solids **out);

/// A mixture of `count` phases (1 to BDL_SOLIDS_PHASES) with no solids: defs[m] gives phase m's
/// diameter, density, restitution and drag; defs[0] the rest. Between phases l and m Syamlal's
/// drag (Sun eq. 3.18) with the mean of their restitutions, defs[0].phase_friction, Lebowitz's
/// g0, and Gera et al.'s hindrance defs[0].hindrance times the plastic pressure; each phase's
/// kinetic theory with Lebowitz's g0_mm.
bdl_result bdl_solids_create_mixture(const bdl_solids_def *defs, int count, const bdl_gas *gas,
                                     bdl_solids **out);
void bdl_solids_destroy(bdl_solids *s);

/// Sets the mixture's fraction from the phases' and the gas's voidage to 1 - eps in every cell,
/// its ghosts included (start of a run, and after eps was changed by hand).
void bdl_solids_share_voidage(const bdl_solids *s, bdl_gas *gas);

/// Advances solids and gas together by dt. BDL_ERR_UNSTABLE when the gas step fails or a value
/// is not finite.
bdl_result bdl_solids_step(bdl_solids *s, bdl_gas *gas, double dt);

/// |u - v| of phase m in cell (i, j, k), by the gas's and the phase's velocities at its centre.
double bdl_solids_cell_slip(const bdl_solids *s, int m, const bdl_gas *gas, int i, int j, int k);

/// The radial distribution at contact of phase m in cell idx: Carnahan & Starling's of the
/// fraction for one phase, Lebowitz's g0_mm for a phase of a mixture.
double bdl_solids_phase_g0(const bdl_solids *s, int m, long idx);

/// Saves the state of the solids and the gas a step starts from (what a checkpoint holds of
/// them: the fractions, velocities, fluxes, temperatures, the gas's velocities, pressure and
/// voidages, and their clocks), so that bdl_solids_undo can take the step back and it can be
/// retaken with a shorter one. BDL_ERR_NOMEM if the copy cannot be allocated (the first call
/// allocates it).
bdl_result bdl_solids_keep(bdl_solids *s, bdl_gas *gas);

/// Puts back the state the last bdl_solids_keep saved.
void bdl_solids_undo(bdl_solids *s, bdl_gas *gas);

/// The largest stable time step of the solids' explicit terms, a Courant number of 1/2: 0.5 /
/// max over the cells above the dilute limit of sum_a (v_out,a + c) / h_a, v_out the velocities
/// of the faces a cell's solids leave by (the upwind transport keeps eps >= 0 up to twice this)
/// and c the speed of the viscous regime's pressure waves, c^2 = theta d(k1 eps^2)/d(eps) / rho_s
/// (the momentum step takes -grad P explicitly; with def.kinetic_pressure implicit the correction
/// takes its change implicitly at the step's temperature, and c counts with def.wave_weight,
/// 0 by default). The viscous term and the transport of
/// momentum are point-implicit, the plastic pressure implicit. Cells below the dilute limit do not
/// count: a step limits their outflow to what they hold (the gas takes the difference). INFINITY
/// with no such cell.
double bdl_solids_stable_dt(const bdl_solids *s);

/// Velocity component a of phase m at the centre of cell (i, j, k).
double bdl_solids_cell_velocity(const bdl_solids *s, int m, int a, int i, int j, int k);

/// Solids volume of phase m in the cells [m^3] (m = -1: all phases; conserved to round-off: no
/// side lets solids through).
double bdl_solids_volume(const bdl_solids *s, int m);

/// Mean height of phase m's solids (m = -1: all phases) above the grid's low side along axis a,
/// sum(eps x_a) / sum(eps) [m] (Sun 2007's <h_p> for a = z); 0 without solids.
double bdl_solids_mean_height(const bdl_solids *s, int m, int a);

#endif
