// bedlam — the gas phase: incompressible, volume-averaged continuity and momentum ("model A" as
// in Sanghishetty et al. 2024, "Structured bubbling in vibrated gas-fluidized beds of binary
// granular particles", Soft Matter, supplement eqs. 3-4: the gas carries -eps grad p, the
// particles the rest of the pressure force) on the staggered grid, advanced by a projection
// method with the interphase drag implicit:
//
//   (rho eps^{n+1}/dt + beta) u* = rho eps^n u^n/dt - rho div(eps u u)^n + eps mu lap(u^n)
//                                  + eps^{n+1} rho g + (beta v_p) + s
//   div(c grad p) = div(eps^{n+1} u* + E u* + F) + (eps^{n+1} - eps^n)/dt,
//       c = eps^{n+1} d + E d + C,  d = s / (rho eps^{n+1}/dt + beta),  s = eps^{n+1} (or `share`)
//   u^{n+1} = u* - d grad p
//
// (E, C, F: the parcels' flux still to come, flux_u, flux_p, flux_0 below; zero for DEM particles)
// so that the gas volume is conserved to the pressure solver's tolerance every step, and a drag
// coefficient beta far above rho/dt stays stable (u follows the particles' velocity v_p).
// beta and the product beta v_p are given on the velocity faces (deposited there by the
// coupling with the same weights it interpolates the gas velocity with), so that the drag the gas
// feels equals, summed, the drag the particles feel (src/couple).
// Convection is conservative and TVD (upwind, van Leer or Superbee limiter on the face values;
// central for tests), explicit or point-implicit (bdl_convection_step); viscosity is explicit,
// eps mu lap(u) (the terms with grad eps are left out). beta, v_p and eps come from the coupling;
// without particles eps = 1, beta = 0.
#ifndef BDL_GAS_H
#define BDL_GAS_H

#include "cfd/grid.h"
#include "cfd/poisson.h"
#include "core/error.h"
#include "core/names.h"

/// Boundary of the gas on one side of the domain: a no-slip wall (it may slide: wall_velocity), a
/// free-slip wall, an inlet of given superficial velocity (a jet patch optional) or an outlet of
/// given pressure (zero-gradient velocity). A periodic side is not a choice of its own: it
/// follows from a periodic axis of the domain, and comes after the list.
#define BDL_GAS_SIDES(X)                                                                           \
    X(SIDE_WALL, "wall", "no-slip wall")                                                           \
    X(SIDE_SLIP, "slip", "free-slip wall")                                                         \
    X(SIDE_INLET, "inlet", "inlet")                                                                \
    X(SIDE_OUTLET, "outlet", "pressure outlet")
typedef enum bdl_gas_side_type { BDL_GAS_SIDES(BDL_ENUM_ITEM) BDL_SIDE_PERIODIC } bdl_gas_side_type;
extern const char *const bdl_gas_side_names[]; ///< scene words (no "periodic"), NULL-terminated

/// Convection scheme of the momentum equation; central is second order but not bounded (for
/// verification at low cell Reynolds numbers).
#define BDL_CONVECTIONS(X)                                                                         \
    X(CONVECTION_UPWIND, "upwind", "upwind")                                                       \
    X(CONVECTION_VANLEER, "vanleer", "van Leer")                                                   \
    X(CONVECTION_SUPERBEE, "superbee", "Superbee")                                                 \
    X(CONVECTION_CENTRAL, "central", "central")
BDL_CHOICES(bdl_convection, BDL_CONVECTIONS);
extern const char *const bdl_convection_labels[]; ///< for logs ("van Leer")

/// How convection steps in time: explicit (stable up to a Courant number of 1/2), or point-
/// implicit: the upwind part's diagonal (the face's outflow) implicit, so that the upwind step is
/// a weighted mean of the old velocities at any Courant number c = dt outflow / eps; the
/// limiter's correction stays explicit, scaled by min(1, 1/c) (bounded with the limiters' psi <=
/// 2). Below c = 1 it is the explicit step with its convection divided by 1 + c: a wave moves at
/// U / (1 + c), slowed where c is not small (first order in dt, as the explicit step; the solids'
/// transport is treated the same way). Where the drag ties the gas to the solids, it is the drag
/// and not the convection that sets the gas's velocity.
#define BDL_CONVECTION_STEPS(X)                                                                    \
    X(CONVECTION_EXPLICIT, "explicit", "explicit")                                                 \
    X(CONVECTION_POINT_IMPLICIT, "point_implicit", "point-implicit")
BDL_CHOICES(bdl_convection_step, BDL_CONVECTION_STEPS);
extern const char *const bdl_convection_step_labels[];

typedef struct bdl_gas_side {
    bdl_gas_side_type type;
    double wall_velocity[3];     ///< tangential velocity of a no-slip wall [m/s]
    double inflow;               ///< inlet: superficial velocity into the domain [m/s]
    int jet;                     ///< inlet: a rectangle with its own superficial velocity
    double jet_lo[3], jet_hi[3]; ///< the rectangle (the normal coordinate is ignored) [m]
    double jet_inflow;           ///< superficial velocity through the rectangle [m/s]
    double pressure;             ///< outlet pressure [Pa]
    /// inlet: 0 for a uniform inflow; > 0 for a porous distributor plate over a plenum [Pa s/m]:
    /// the superficial velocity through each face is (P - p)/resistance, p the pressure of the
    /// cell above it, and the plenum pressure P holds the mean at `inflow` (set from the
    /// pressures of the last step, so the inflow's sum follows `inflow` within their change).
    /// No jet.
    double resistance;
} bdl_gas_side;

typedef struct bdl_gas_def {
    int n[3];
    double lo[3], hi[3];
    double density;   ///< [kg/m^3]
    double viscosity; ///< dynamic [Pa s]
    double gravity[3];
    bdl_gas_side side[6]; ///< 2a + s: side s (0 low, 1 high) of axis a
    bdl_convection convection;
    bdl_convection_step convection_step; ///< explicit, or point-implicit: no Courant limit
    double tolerance;                    ///< relative residual of the pressure solver
    int max_iterations;
    bdl_pressure_solver pressure_solver; ///< bedlam's MG-PCG (default), or hypre's
    int pressure_share;                  ///< keep `share` (below): parcels' implicit scheme
} bdl_gas_def;

typedef struct bdl_gas {
    bdl_gas_def def;
    bdl_grid grid;
    bdl_poisson *poisson;
    double *u[3];      ///< interstitial gas velocity on the faces [m/s]
    double *p;         ///< pressure in the cells [Pa]
    double *eps;       ///< voidage in the cells at the new time level
    double *eps_old;   ///< voidage at the previous time level
    double *beta[3];   ///< drag coefficient on the faces of each component [kg/(m^3 s)]
    double *bv[3];     ///< beta times the particles' velocity on those faces [kg/(m^2 s^2)]
    double *source[3]; ///< extra force per unit volume on the faces [N/m^3] (0 unless set)
    /// With def.pressure_share (NULL otherwise): the share of -grad p the gas's momentum carries
    /// on each face, in place of the face voidage. Parcels whose velocity is implicit in the drag
    /// hand the gas 1 - C_pr (Patankar & Joseph 2001, eq. 23): the gas carries -eps grad p and
    /// the drag's implicit response to the particles' own -grad p / rho_p.
    double *share[3];
    double *grad_p[3]; ///< with def.pressure_share: grad p on each face as the last step used it
    /// With def.pressure_share (NULL otherwise): the particles' volume flux on each face that the
    /// voidage eps^{n+1} does not hold yet, as it follows from the step's gas velocity and
    /// pressure gradient, flux = flux_u u - flux_p grad p + flux_0 (normal components) [m/s].
    /// Parcels moved with their old velocity (eps^{n+1}) and then with their new one, implicit in
    /// the drag, hand it over (Patankar & Joseph 2001, the particle terms D_f of their pressure
    /// equation): the continuity the pressure equation enforces is then that of the volume the
    /// parcels really move, and a sediment whose drag ties it to the liquid stays at rest (with
    /// the old velocity's flux alone, each step's liquid velocity answers the last step's solids
    /// flux, v^{n+1} = -theta / (1 - theta) v^n, which grows above theta = 1/2).
    double *flux_u[3], *flux_p[3], *flux_0[3];

    double *ustar[3], *coef[3], *rhs, *d[3]; ///< work arrays
    double time;
    long steps;
    bdl_poisson_stats last_solve;
    double mass_imbalance; ///< max over cells of |d eps/dt + div(eps u)| dt after the last step
    double plenum[6];      ///< distributor sides: the plenum pressure of the last step [Pa]
} bdl_gas;

/// The defaults: one cell over the unit cube, air (1.2 kg/m^3, 1.8e-5 Pa s), no-slip walls on
/// every side, no gravity, van Leer convection, pressure tolerance 1e-8 within 200 iterations.
bdl_gas_def bdl_default_gas_def(void);

/// Allocates the gas at rest (eps = 1, p = 0 plus the hydrostatic profile is not imposed).
/// BDL_ERR_NOMEM, or BDL_ERR_ARGS for a definition that cannot be solved (a periodic side paired
/// with a non-periodic one, no cells, a tolerance, iteration count, density or viscosity <= 0).
bdl_result bdl_gas_create(const bdl_gas_def *def, bdl_gas **out);
void bdl_gas_destroy(bdl_gas *g);

/// Advances the gas by dt with the eps, beta, bv and source currently set (eps_old holds the
/// voidage of the previous step; it is updated at the end). Returns BDL_ERR_UNSTABLE if the
/// pressure solver did not converge or a velocity is not finite.
bdl_result bdl_gas_step(bdl_gas *g, double dt);

/// bdl_gas_step with the axes whose velocities are stepped given: active[a] may be 0 only where
/// bdl_gas_axis_inert(g, a) holds (1 is always safe: an inert axis's equations give zero). For
/// a caller that has checked the axes already.
bdl_result bdl_gas_step_axes(bdl_gas *g, double dt, const int active[3]);

/// Sets the superficial velocity of every inlet side and of its jet patch [m/s] (live changes:
/// a velocity sweep, a command).
void bdl_gas_set_inflow(bdl_gas *g, double inflow, double jet_inflow);

/// Sets the acceleration the gas feels [m/s^2] (gravity, plus a vibrating container's inertial
/// acceleration in its frame).
void bdl_gas_set_gravity(bdl_gas *g, const double gravity[3]);

/// The largest stable time step of the explicit terms: CFL 0.5 on the convection, and the
/// viscous limit.
double bdl_gas_stable_dt(const bdl_gas *g);

/// Whether the gas's velocity along axis a is zero and stays so through the next step: one
/// cell along a, periodic (no gradient along it), no gravity, wall motion, drag source or extra
/// force along it, and every u_a zero. Such an axis (the depth of a two-dimensional run) is
/// left out of the step: its equations would give zero.
int bdl_gas_axis_inert(const bdl_gas *g, int a);

/// Velocity component a interpolated to the cell centre (i, j, k).
double bdl_gas_cell_velocity(const bdl_gas *g, int a, int i, int j, int k);

#endif
