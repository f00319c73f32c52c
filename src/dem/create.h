// bedlam — particle creation: random fill, lattice fill, pouring, and CSV files.
//
// Random fill is random sequential addition: candidates are drawn uniformly in the region and
// kept when they overlap nothing (particles, walls, region bounds). It jams near a solids
// fraction of 0.38 for equal spheres, so denser beds are made by pouring or a lattice and letting
// them settle. All draws use the world's seeded generator: a scene creates the same particles
// every time.
#ifndef BDL_CREATE_H
#define BDL_CREATE_H

#include "core/rng.h"
#include "dem/particles.h"
#include "dem/walls.h"
#include "scene/scene.h"

/// Diameter drawn from a species' distribution [m].
double bdl_species_draw_diameter(const bdl_species_def *s, bdl_rng *rng);

/// Largest diameter a species can have [m].
double bdl_species_max_diameter(const bdl_species_def *s);

/// Creates the particles of creator `c` (random, lattice or file) at the start of a run.
bdl_result bdl_create_initial(const bdl_scene *scene, int c, bdl_particles *p,
                              const bdl_walls *walls, bdl_rng *rng, bdl_scene_error *err);

/// Pours the particles creator `c` owes by time t; `poured` counts what it has inserted so far
/// and is updated. A particle that finds no free place waits for a later step.
long bdl_create_pour(const bdl_scene *scene, int c, double t, long *poured, bdl_particles *p,
                     const bdl_walls *walls, bdl_rng *rng);

/// Upper bound of the number of particles the scene will hold (for sizing the cell grid).
long bdl_create_estimate_total(const bdl_scene *scene);

#endif
