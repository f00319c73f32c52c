// bedlam — DEM forces and the velocity-Verlet integrator.
//
//   v(t + dt/2) = v(t) + dt/2 (F(t)/m + g)         w(t + dt/2) = w(t) + dt/2 T(t)/I
//   x(t + dt)   = x(t) + dt v(t + dt/2)
//   F(t + dt)   = contacts(x(t + dt), v(t + dt/2)) - b m v      (gravity is added in the kicks)
//   v(t + dt)   = v(t + dt/2) + dt/2 (F(t + dt)/m + g)   (w likewise with T/I)
//
// Velocity-dependent forces (dashpots, friction, background damping) use the half-step
// velocity, as in LAMMPS and LIGGGHTS; the scheme is second order for conservative forces.
// Spheres need no orientation, only the spin w.
#ifndef BDL_INTEGRATE_H
#define BDL_INTEGRATE_H

#include "dem/material.h"
#include "dem/neighbor.h"
#include "dem/particles.h"
#include "dem/walls.h"

typedef struct bdl_force_def {
    const bdl_contact_params *pair_params; ///< species_count^2 table
    const bdl_contact_params *wall_params; ///< wall_count * species_count table
    int species_count;
    const double *background_damping;      ///< per species [1/s]
    bdl_vec3 gravity;                      ///< [m/s^2]
    int hertz, friction, rolling;
    double dt;                             ///< [s] (tangential spring increment)
} bdl_force_def;

/// Evaluates every listed pair once and stores its force (parallel over particles i).
void bdl_dem_pair_forces(bdl_particles *p, bdl_neighbor *nb, const bdl_force_def *def);

/// Sums each particle's pair forces in a fixed order, adds wall contacts and background damping
/// (gravity is applied in the kicks), and counts particle contacts into `coordination` (may be NULL). With kick h > 0 the
/// closing half kick v += h F/m, w += h T/I follows in the same pass.
void bdl_dem_gather(bdl_particles *p, bdl_neighbor *nb, const bdl_walls *walls,
                    const bdl_force_def *def, uint8_t *coordination, double kick);

/// The opening half of a step in one pass: v += h (F/m + g), w += h T/I, x += dt v. Returns the
/// largest squared displacement since the neighbour list was built [m^2].
double bdl_dem_kick_drift(bdl_particles *p, bdl_vec3 gravity, double h, double dt);

/// Power delivered by moving walls to the particles this step [W]: sum F_wall . v_wall.
double bdl_dem_wall_power(const bdl_particles *p, const bdl_neighbor *nb, const bdl_walls *walls);

/// Elastic energy stored in the contacts [J] (normal springs only).
double bdl_dem_elastic_energy(const bdl_particles *p, const bdl_neighbor *nb, const bdl_walls *walls,
                              const bdl_force_def *def);

#endif
