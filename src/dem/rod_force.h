// bedlam — the contact-force pass of scenes with rods (spherocylinders; spheres among them are rods
// without a shaft): pairs, walls at the rods' tips, background damping and the closing half kick
// of the rigid-body step, with sums that do not depend on the thread count (rod_force.c).
#ifndef BDL_ROD_FORCE_H
#define BDL_ROD_FORCE_H

#include "dem/contact_force.h"

/// Where two rods touch: unit normal (from j to i), overlap, and the arms from the centres of i and
/// j to the contact point in the middle of the overlap (j's from its image nearest to i).
typedef struct bdl_rod_contact {
    bdl_vec3 n, arm_i, arm_j;
    double overlap; ///< [m]
} bdl_rod_contact;

/// The contact of the pair (i, j) of rods; 0 when they do not touch.
int bdl_rod_contact_of(const bdl_particles *p, const bdl_neighbor *nb, long i, long j,
                       bdl_rod_contact *c);

/// Where rod i touches wall primitive `prim` (arm_j unused): 0 when it does not; see
/// rod_force.c for the stretch of the shaft beyond the wall and its contact point.
int bdl_rod_wall_contact_of(const bdl_particles *p, const bdl_walls *walls, long i, int prim,
                            bdl_rod_contact *c);

/// The inverse mass 1/m + (a x n).I^-1 (a x n) that particle i shows along n at the point of arm
/// a from its centre [1/kg].
double bdl_rod_inv_mass_at(const bdl_particles *p, long i, bdl_vec3 arm, bdl_vec3 n);

/// As bdl_dem_forces for particles with rods (p->rods): the closing half kick is v += h (F/m + g),
/// L += h T, and the angular velocity follows from the new angular momentum.
bdl_result bdl_rod_forces(bdl_particles *p, bdl_neighbor *nb, const bdl_walls *walls,
                          const bdl_force_def *def, bdl_force_work *fw, uint8_t *coordination,
                          double kick);

#endif
