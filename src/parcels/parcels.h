// bedlam — parcels (MP-PIC): computational particles that each stand for many real spheres of one
// size, density and velocity, after Patankar & Joseph (2001), "Modeling and numerical simulation
// of particulate flows by the Eulerian-Lagrangian approach", Int. J. Multiphase Flow 27.
//
// A parcel lives in the particle store (dem/particles.h: `parcels`, parcel_count): its radius is
// a real particle's, its mass the whole parcel's. Contacts are replaced by an interparticle
// stress on the gas grid (model A, the paper's eqs. 14-15):
//
//   tau = P_s theta^beta / max(theta_cs - theta, floor),   A_cp = -grad tau / (theta rho_p)
//
// and a parcel steps at the gas's pace. One step of length dt (bdl_parcels_step):
//  1. drift: x += v dt in `substeps` equal parts; a parcel that reaches a side of the domain is
//     reflected with the wall restitution (walls and inlets), wrapped (periodic) or removed
//     (an outlet, counted with its mass);
//  2. the packing guard: while a cell's solids fraction exceeds theta_cs, every parcel whose
//     kernel touches such a cell goes back to where the step began, its velocity zeroed (the
//     state at the start of the step had no such cell, so this ends) — what keeps theta below
//     close packing however hard the parcels are driven; each held parcel is counted;
//  3. the solids fraction theta^{n+1} (the coupling's kernels: the seed's trilinear kernel is
//     the tent of half-width one cell), the stress in the cells and its gradient on the faces,
//     A_cp at every parcel;
//  4. the drag set-up of the implicit scheme (couple/coupling.h, the paper's eqs. 21-23): per
//     parcel a_i = m D / (1 + D dt), deposited as beta and beta (v + dt A_b) with A_b = g + A_cp,
//     and the pressure share of the gas 1 - C_pr, C_pr = sum W V / (1 + D dt) / V_cell;
//  5. the gas step (cfd/gas.h, with `share`);
//  6. the parcels' velocities, implicit in the drag with the new gas velocity u and pressure
//     gradient at the parcel (interpolated with the weights the drag was deposited with):
//       v^{n+1} = (v^n + dt (D u - grad p / rho_p + A_b)) / (1 + D dt),
//     so that what the gas gives in drag and pressure, the parcels receive, to round-off.
#ifndef BDL_PARCELS_H
#define BDL_PARCELS_H

#include "cfd/gas.h"
#include "core/error.h"
#include "core/names.h"
#include "couple/coupling.h"
#include "dem/particles.h"

/// How parcels keep from close packing ([parcels] model).
#define BDL_PARCEL_MODELS(X)                                                                       \
    X(PARCEL_STRESS, "stress",                                                                     \
      "model A: interparticle stress P_s theta^beta / (theta_cs - theta) on the grid")
BDL_CHOICES(bdl_parcel_model, BDL_PARCEL_MODELS);

typedef struct bdl_parcels_def {
    bdl_parcel_model model;
    double stress_pressure;  ///< P_s [Pa]
    double stress_exponent;  ///< beta
    double close_packing;    ///< theta_cs
    double stress_floor;     ///< least theta_cs - theta in the stress's denominator
    int substeps;            ///< K: the drift in this many parts (walls met within a step)
    double wall_restitution; ///< normal restitution of a parcel reflected at a side
} bdl_parcels_def;

/// The paper's values: model A, P_s = 100 Pa, beta = 3, theta_cs = 0.6; a floor of 1e-3; one
/// drift part; restitution 0.9.
bdl_parcels_def bdl_default_parcels_def(void);

/// tau(theta) of the definition [Pa].
double bdl_parcels_stress(const bdl_parcels_def *def, double theta);

typedef struct bdl_parcels {
    bdl_parcels_def def;
    long capacity;
    bdl_vec3 *start;   ///< position at the start of the step [m]
    bdl_vec3 *start_v; ///< velocity at the start of the step [m/s]
    bdl_vec3 *accel;   ///< A_b = g + A_cp over the step [m/s^2]
    double *value;     ///< scratch per parcel
    int32_t *perm;     ///< scratch: survivors of a removal
    void *scratch;     ///< scratch for bdl_particles_permute
    uint8_t *held;     ///< scratch: the guard's parcels of this round
    double *tau;       ///< stress in the cells [Pa] (padded grid field)
    double *grad[3];   ///< grad tau / theta on the faces [Pa/m]
} bdl_parcels;

/// One step's settings.
typedef struct bdl_parcels_step_def {
    double dt;        ///< [s]
    int first;        ///< the first step: the solids fraction has no earlier value
    bdl_vec3 gravity; ///< at mid-step [m/s^2]
} bdl_parcels_step_def;

/// What a step did.
typedef struct bdl_parcels_report {
    long removed;            ///< parcels that left through outlets
    double removed_mass;     ///< their mass [kg]
    long held;               ///< parcels the packing guard held back
    double max_solids;       ///< largest solids fraction of a cell after the step
    double particle_drag[3]; ///< drag on all parcels [N]
    double gas_drag[3];      ///< drag of the parcels on the gas [N]
    double stable_dt;        ///< the gas's stable step after this one [s]; 0 if it failed
    double gas_seconds;      ///< wall time of the gas step [s]
    double parcel_seconds;   ///< wall time of the rest [s]
} bdl_parcels_report;

bdl_result bdl_parcels_init(bdl_parcels *pc, const bdl_parcels_def *def, const bdl_gas *gas);
void bdl_parcels_free(bdl_parcels *pc);

/// One step (see above). BDL_ERR_UNSTABLE when the gas step failed (report->stable_dt 0) or
/// went beyond twice its stable step; BDL_ERR_NOMEM.
bdl_result bdl_parcels_step(bdl_parcels *pc, bdl_coupling *c, bdl_gas *gas, bdl_particles *p,
                            const bdl_parcels_step_def *def, bdl_parcels_report *report);

/// Total solids volume of the parcels [m^3].
double bdl_parcels_solids_volume(const bdl_particles *p);

#endif
