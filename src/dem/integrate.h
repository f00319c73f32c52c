// bedlam — the velocity-Verlet integrator of the particles.
//
//   v(t + dt/2) = v(t) + dt/2 (F(t)/m + g)         w(t + dt/2) = w(t) + dt/2 T(t)/I
//   x(t + dt)   = x(t) + dt v(t + dt/2)
//   F(t + dt)   = contacts(x(t + dt), v(t + dt/2)) - b m v      (gravity is added in the kicks)
//   v(t + dt)   = v(t + dt/2) + dt/2 (F(t + dt)/m + g)   (w likewise with T/I)
//
// Velocity-dependent forces (dashpots, friction, background damping) use the half-step
// velocity, as in LAMMPS and LIGGGHTS; the scheme is second order for conservative forces.
// Spheres need no orientation, only the spin w. The forces and the closing half kick are one pass
// over the particles, bdl_dem_forces (contact_force.h); the opening half kick and the drift are
// the other.
//
// Rods (and spheres in scenes with rods) carry an orientation q and the angular momentum L in the
// world frame; their rotation is split as the translation is (dem/rigid.h):
//   L(t + dt/2) = L(t) + dt/2 T(t),   q(t + dt) = free rotation of q(t) with L(t + dt/2) for dt,
//   L(t + dt)   = L(t + dt/2) + dt/2 T(t + dt),
// and the angular velocity the contacts read is w = R I^-1 R^T L after each kick.
#ifndef BDL_INTEGRATE_H
#define BDL_INTEGRATE_H

#include "dem/neighbor.h"
#include "dem/particles.h"
#include "dem/walls.h"

/// The opening half of a step in one pass: v += h (F/m + g), w += h T/I, x += dt v; then clears
/// F and T for the force pass (which may skip clearing them: bdl_force_def.loads_cleared). Returns
/// the largest squared displacement since the neighbour list was built [m^2].
double bdl_dem_kick_drift(bdl_particles *p, bdl_vec3 gravity, double h, double dt);

/// The same opening half for rods: v += h (F/m + g), L += h T, the free rotation for dt, w from L,
/// x += dt v. Returns the largest squared displacement of a tip since the lists were built [m^2].
double bdl_dem_kick_drift_rods(bdl_particles *p, bdl_vec3 gravity, double h, double dt);

/// Power delivered by moving walls to the particles this step [W]: sum F_wall . v_wall.
double bdl_dem_wall_power(const bdl_particles *p, const bdl_neighbor *nb, const bdl_walls *walls);

#endif
