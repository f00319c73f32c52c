// bedlam — parcels (MP-PIC): computational particles that each stand for many real spheres of one
// size, density and velocity, after Patankar & Joseph (2001), "Modeling and numerical simulation
// of particulate flows by the Eulerian-Lagrangian approach", Int. J. Multiphase Flow 27.
//
// A parcel lives in the particle store (dem/particles.h: `parcels`, parcel_count): its radius is
// a real particle's, its mass the whole parcel's. What keeps parcels from close packing is one of
// the paper's two models ([parcels] model):
//  - model A (`stress`, eqs. 14-15): an interparticle stress on the gas grid,
//      tau = P_s theta^beta / max(theta_cs - theta, floor),   A_cp = -grad tau / (theta rho_p);
//  - model B (`collisions`, eqs. 16-20; parcels/collisions.h): each parcel is the sphere of its
//    solids volume, and parcel spheres push each other and the domain's sides with a soft-sphere
//    force F_cp, A_cp = F_cp / M (M the parcel's mass).
// A parcel steps at the gas's pace. One step of length dt (bdl_parcels_step):
//  1. drift: x += w h in K = `substeps` equal parts h = dt / K (the move step 7 completes); a
//  parcel that reaches a side of
//     the domain is reflected with the wall restitution (walls and inlets), wrapped (periodic) or
//     removed (an outlet, counted with its mass). Model A: w = v^n. Model B sub-cycles the
//     collisions within the step (the spirit of the paper's eqs. 25-27): w starts at v^n, and
//     after each of the first K - 1 parts the collision acceleration a_k = A_cp(x_k, w) is
//     evaluated at the parcels' new positions and w += h a_k, so that the positions see the
//     collisions of the step as they happen (symplectic Euler with the step h for the collision
//     force); the velocity of the damping is w;
//  2. the packing guard: while a cell's solids fraction exceeds theta_cs and what it held at the
//     start of the step, every parcel whose move gave such a cell more of its kernel's weight
//     goes back to where the step began, its velocity (and model B's collision accelerations of
//     the step) zeroed (those cells then hold no more than at the start, so this ends) — what
//     keeps theta below close packing however hard the parcels are driven; each held parcel is
//     counted. Parcels moving out of a full cell, or past it, go on: a cell above close packing
//     at the start (a random fill's) empties to it, and a jammed region relaxes, rather than
//     freezing every parcel around it;
//  3. the solids fraction theta^{n+1} (the coupling's kernels: the seed's trilinear kernel is
//     the tent of half-width one cell), and A_b = g + A_cp at every parcel. Model A: the stress in
//     the cells and its gradient on the faces, A_cp interpolated to the parcel. Model B: the last
//     collision acceleration a_K = A_cp(x^{n+1}, w) at the step's final positions, and A_cp the
//     mean (a_1 + ... + a_K) / K, so that the velocity update below gives each parcel exactly the
//     collision impulse h (a_1 + ... + a_K) its positions were advanced with (the paper's eq. 27
//     recovers its effective A_cp from the positions in the same sense). With K = 1: x^{n+1} =
//     x^n + dt v^n, A_cp = A_cp(x^{n+1}, v^n);
//  4. the drag set-up of the implicit scheme (couple/coupling.h, the paper's eqs. 21-23): per
//     parcel a_i = m D / (1 + D dt), deposited as beta and beta (v + dt A_b), and the pressure
//     share of the gas 1 - C_pr, C_pr = sum W V / (1 + D dt) / V_cell; so A_cp, like gravity, is
//     implicit with the drag and reaches the gas through the drag's deposit;
//  5. the gas step (cfd/gas.h, with `share`); or, with `gas_substeps` G > 1, as many gas steps
//     m <= G of dt / m as the gas's CFL asks (m = ceil(dt / its stable step)), the solids
//     fraction moving linearly from theta^n to theta^{n+1} across them and the drag's beta,
//     beta (v + dt A_b) and share held: the gas, much cheaper than the parcels on the grids
//     parcels need, keeps its explicit convection's step while the parcels take theirs;
//  6. the parcels' velocities, implicit in the drag with the new gas velocity u and pressure
//     gradient at the parcel (interpolated with the weights the drag was deposited with):
//       v^{n+1} = (v^n + dt (D u - grad p / rho_p + A_b)) / (1 + D dt),
//     so that what the gas gives in drag and pressure, the parcels receive, to round-off (with
//     m gas steps, u and grad p are their means over the m steps: the drag and pressure the gas
//     gave, summed over its steps, is linear in them);
//  7. the rest of the move: every parcel goes on by dt (v^{n+1} - w) (w the velocity its drift
//     used), so that over the step it moved by dt v^{n+1}, the sides met and the guard kept as
//     in steps 1-2, and the solids fraction theta^{n+1} deposited anew. The gas's pressure
//     equation of step 5 counted that move: the drag set-up deposits the parcels' volume flux
//     still to come, sum W V (v^{n+1} - w) / V_cell, as linear in the face's u and grad p (the
//     paper's particle terms D_f of its pressure equation), so that the liquid makes room for the
//     volume the parcels really move. With theta^{n+1} from the drift alone (the old velocities'
//     flux) the liquid answers each step's solids flux a step late: in a sediment whose drag
//     ties it to the liquid (D dt >> 1) v^{n+1} = -theta / (1 - theta) v^n, an oscillation of
//     period two steps that grows once theta > 1/2.
// Model B's step is bounded by the paper's (Cundall & Strack's) dt / K < 2 sqrt(M / k_c) and by
// the explicit dashpot's dt / K < M / eta_c (bdl_parcels_collision_dt).
#ifndef BDL_PARCELS_H
#define BDL_PARCELS_H

#include "cfd/gas.h"
#include "core/error.h"
#include "core/names.h"
#include "couple/coupling.h"
#include "dem/particles.h"
#include "parcels/collisions.h"

/// How parcels keep from close packing ([parcels] model).
#define BDL_PARCEL_MODELS(X)                                                                       \
    X(PARCEL_STRESS, "stress",                                                                     \
      "model A: interparticle stress P_s theta^beta / (theta_cs - theta) on the grid")             \
    X(PARCEL_COLLISIONS, "collisions",                                                             \
      "model B: soft-sphere forces between parcel spheres and with the domain's sides")
BDL_CHOICES(bdl_parcel_model, BDL_PARCEL_MODELS);

typedef struct bdl_parcels_def {
    bdl_parcel_model model;
    double stress_pressure;  ///< P_s [Pa]
    double stress_exponent;  ///< beta
    double close_packing;    ///< theta_cs
    double stress_floor;     ///< least theta_cs - theta in the stress's denominator
    int substeps;            ///< K: the drift in this many parts (walls met within a step)
    int gas_substeps;        ///< most gas steps per parcel step (as its CFL asks); 1: one
    double wall_restitution; ///< normal restitution of a parcel reflected at a side
    // Model B (parcels/collisions.h):
    double collision_stiffness;   ///< k_c [N/m^m]
    double collision_exponent;    ///< m of k_c delta^m (the paper: 3/2)
    double collision_damping;     ///< eta_c [kg/s]; < 0: from the restitution (eq. 18)
    double collision_restitution; ///< e that eq. 18 builds eta_c from
    double collision_range;       ///< force range rho as a fraction of a parcel's diameter
} bdl_parcels_def;

/// The paper's values: model A, P_s = 100 Pa, beta = 3, theta_cs = 0.6; a floor of 1e-3; one
/// drift part; restitution 0.9; for model B k_c = 800, m = 3/2, eta_c from e = 0.9, range 0.075.
bdl_parcels_def bdl_default_parcels_def(void);

/// eta_c of the definition: collision_damping, or when that is negative eq. 18 with
/// collision_restitution, collision_stiffness and the parcel mass M [kg/s].
double bdl_parcels_collision_damping(const bdl_parcels_def *def, double mass);

/// The longest step model B allows for parcels of mass M at least (eta_c resolved): K times the
/// smaller of Cundall & Strack's 2 sqrt(M / k_c) (the paper's bound, that of a linear spring of
/// stiffness k_c; with m = 3/2 the spring's stiffness 1.5 k_c delta^(1/2) is below k_c for
/// delta < 0.44 m, so the bound is conservative there) and M / eta_c (the explicit dashpot: two
/// parcels' approach speed changes by 2 eta_c h / M in a part h); INFINITY for model A [s].
double bdl_parcels_collision_dt(const bdl_parcels_def *def, double mass);

/// tau(theta) of the definition [Pa].
double bdl_parcels_stress(const bdl_parcels_def *def, double theta);

typedef struct bdl_parcels {
    bdl_parcels_def def;
    long capacity;
    bdl_vec3 *start;   ///< position at the start of the step [m]
    bdl_vec3 *moved;   ///< the drift's velocity beyond v (model B's collisions), then the move
                       ///< still to come (step 7) [m/s, then m]
    bdl_vec3 *accel;   ///< A_b = g + A_cp over the step [m/s^2]
    double *value;     ///< scratch per parcel
    int32_t *perm;     ///< scratch: survivors of a removal
    void *scratch;     ///< scratch for bdl_particles_permute
    uint8_t *held;     ///< scratch: the parcels leaving through outlets in this step
    double *tau;       ///< stress in the cells [Pa] (padded grid field)
    double *eps_begin; ///< the gas's eps at the start of the step (padded grid field)
    double *grad[3];   ///< grad tau / theta on the faces [Pa/m]
    // Model B:
    bdl_parcel_collisions collisions; ///< the cell list and the force law (eta_c resolved)
    bdl_vec3 *sub_v;                  ///< scratch: w, the velocity along the step's parts [m/s]
    bdl_vec3 *push;                   ///< scratch: the collision force of one evaluation [N]
    // Gas sub-steps (gas_substeps > 1; NULL otherwise), padded grid fields:
    double *eps_start, *eps_end; ///< the gas's eps at the step's start and end
    double *u_mean[3];           ///< the gas velocity's mean over the gas steps [m/s]
    double *grad_p_mean[3];      ///< grad p's mean over the gas steps [Pa/m]
} bdl_parcels;

/// One step's settings.
typedef struct bdl_parcels_step_def {
    double dt;        ///< [s]
    int first;        ///< the first step: the solids fraction has no earlier value
    bdl_vec3 gravity; ///< at mid-step [m/s^2]
} bdl_parcels_step_def;

/// What a step did.
typedef struct bdl_parcels_report {
    long removed;                 ///< parcels that left through outlets
    double removed_mass;          ///< their mass [kg]
    long held;                    ///< parcels the packing guard held back
    double max_solids;            ///< largest solids fraction of a cell after the step
    double particle_drag[3];      ///< drag on all parcels [N]
    double gas_drag[3];           ///< drag of the parcels on the gas [N]
    double gas_work;              ///< work of the gas's drag and pressure on the parcels [J]
    bdl_parcel_contacts contacts; ///< model B: contacts at the step's final positions
    double stable_dt;             ///< the gas's stable step after this one, times gas_substeps
                                  ///< [s]; 0 if it failed
    int gas_steps;                ///< gas steps taken
    double failed_dt;      ///< > 0: the step (or gas sub-step) that passed the gas's CFL 1 [s];
                           ///< stable_dt is then the gas's stable step after it
    int failed_part;       ///< that was a gas sub-step
    double gas_seconds;    ///< wall time of the gas step [s]
    double parcel_seconds; ///< wall time of the rest [s]
} bdl_parcels_report;

/// The parcel solver on the gas's domain. For model B def->collision_damping must be resolved
/// (bdl_parcels_collision_damping; a negative value is taken as 0) and the domain's sides are
/// those of the gas: walls, slip sides and inlets push parcels back, outlets do not.
bdl_result bdl_parcels_init(bdl_parcels *pc, const bdl_parcels_def *def, const bdl_gas *gas);
void bdl_parcels_free(bdl_parcels *pc);

/// One step (see above). BDL_ERR_UNSTABLE when the gas step failed (report->stable_dt 0) or
/// went beyond twice its stable step; BDL_ERR_NOMEM.
bdl_result bdl_parcels_step(bdl_parcels *pc, bdl_coupling *c, bdl_gas *gas, bdl_particles *p,
                            const bdl_parcels_step_def *def, bdl_parcels_report *report);

/// Total solids volume of the parcels [m^3].
double bdl_parcels_solids_volume(const bdl_particles *p);

#endif
