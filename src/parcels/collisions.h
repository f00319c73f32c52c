// bedlam — parcel collisions (model B of Patankar & Joseph 2001, "Modeling and numerical
// simulation of particulate flows by the Eulerian-Lagrangian approach", Int. J. Multiphase Flow
// 27, eqs. 16-20): a soft-sphere force between parcel spheres and between a parcel sphere and the
// sides of the domain, after Cundall & Strack (1979).
//
// A parcel occupies the sphere of its solids volume, R_ep = (3 N_p V_p / (4 pi))^(1/3) (eq. 16).
// Two parcels p, j at centre distance d, n the unit vector from j to p, feel (eq. 17)
//
//   F_pj = (k_c delta^m - eta_c (u_p - u_j) . n) n   when delta = R_ep + R_ej + rho - d > 0,
//
// and F_jp = -F_pj; zero otherwise. The paper's exponent is m = 3/2; rho is the force range,
// rho = range x (R_ep + R_ej), the paper's 0.075 x 2 R_ep for parcels of one size. The normal
// force is not clipped at zero (as in the paper): the dashpot may pull while the parcels part.
// A side of the domain that is a gas wall, slip side or inlet pushes a parcel whose centre is
// within R_ep + rho_w of it (rho_w = range x 2 R_ep), n the side's inward normal (eq. 19):
//
//   F_pw = (k_c delta_w^m - eta_c u_p . n) n,   delta_w = R_ep + rho_w - d_w.
//
// The paper prints delta_w = R_ep + 2 rho - d_w with the threshold d_w < R_ep + rho, which makes
// the force jump by k_c rho^m as contact begins; here the overlap is measured from the threshold,
// so the wall force, like the pair force, starts from zero. Outlet sides push nothing (a parcel
// beyond one leaves the run); periodic axes have no sides, and pairs meet across them through
// the nearest image.
//
// The search is a cell list of its own over the domain (parcels have no neighbour lists), with
// cells at least as wide as the longest reach (1 + range) x 2 max R_ep. Every parcel sums its own
// pairs, in a fixed order (the cells around it in a fixed order, the parcels of a cell by index),
// so the forces are the same bit for bit on any number of threads; a pair's two forces are exact
// negatives of each other, so the pair forces conserve momentum to round-off.
#ifndef BDL_PARCEL_COLLISIONS_H
#define BDL_PARCEL_COLLISIONS_H

#include <math.h>
#include <stdint.h>

#include "core/error.h"
#include "core/vec3.h"
#include "dem/particles.h"

/// The force law (eqs. 17-19) with its damping resolved.
typedef struct bdl_parcel_collision_law {
    double stiffness; ///< k_c [N/m^m]
    double exponent;  ///< m (the paper: 3/2)
    double damping;   ///< eta_c [kg/s]
    double range;     ///< rho / (2 R_ep): the force range as a fraction of a parcel's diameter
} bdl_parcel_collision_law;

/// Where the parcels are: the domain's box, its periodic axes and which of its six sides (x min,
/// x max, y min, ...) push parcels back (gas walls, slip sides and inlets; not outlets).
typedef struct bdl_parcel_box {
    double lo[3], hi[3];
    int periodic[3];
    int solid[6];
} bdl_parcel_box;

/// eta_c that gives a linear spring-dashpot of stiffness k and mass m the restitution e (eq. 18,
/// after Tsuji, Kawaguchi & Tanaka 1993): 2 alpha sqrt(m k / (1 + alpha^2)), alpha = -ln(e)/pi.
double bdl_parcel_collision_damping(double restitution, double mass, double stiffness);

/// The radius of the sphere of parcel i's solids volume, R_ep (eq. 16) [m].
static inline double bdl_parcel_sphere_radius(const bdl_particles *p, long i)
{
    return cbrt(0.75 / BDL_PI * bdl_particle_solids_volume(p, i));
}

/// What one evaluation found.
typedef struct bdl_parcel_contacts {
    long pairs;         ///< touching pairs (within the force range)
    long walls;         ///< parcel-side contacts
    double max_overlap; ///< largest delta / R_ep of a pair or a side
} bdl_parcel_contacts;

typedef struct bdl_parcel_collisions {
    bdl_parcel_collision_law law;
    bdl_parcel_box box;
    long parallel_min;      ///< the per-parcel pass goes parallel from this many parcels
    long capacity;          ///< parcels
    long cell_capacity;     ///< cells
    int n[3];               ///< cells per axis of the last evaluation
    double inv_cell[3];     ///< 1 / cell size per axis [1/m]
    double *sphere;         ///< per parcel: R_ep [m]
    int32_t *cell;          ///< per parcel: its cell (-1: left out)
    int32_t *order;         ///< parcels sorted by cell, by index within a cell
    double *overlap;        ///< per parcel: its largest delta / R_ep
    int32_t *touching;      ///< per parcel: its pair contacts (each pair counted twice)
    int32_t *touching_wall; ///< per parcel: its side contacts
    long *start;            ///< per cell: first entry in order (cells + 1)
} bdl_parcel_collisions;

bdl_result bdl_parcel_collisions_init(bdl_parcel_collisions *c, const bdl_parcel_collision_law *law,
                                      const bdl_parcel_box *box);
void bdl_parcel_collisions_free(bdl_parcel_collisions *c);

/// The collision force F_cp (eq. 20) on every parcel at positions p->pos with velocities `vel`
/// (the damping's), into `force` [N]. Parcels with skip[i] set (NULL: none) neither feel nor
/// exert a force. `found` (may be NULL) receives what the evaluation found. BDL_ERR_NOMEM.
bdl_result bdl_parcel_collisions_force(bdl_parcel_collisions *c, const bdl_particles *p,
                                       const bdl_vec3 *vel, const uint8_t *skip, bdl_vec3 *force,
                                       bdl_parcel_contacts *found);

#endif
