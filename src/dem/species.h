// bedlam — species: the kinds of particle a scene holds (shape, size distribution, density,
// material).
//
// A species is a particle shape with a size and a material. Spheres are the one shape today; the
// shape is a property of the species so that a non-spherical one (spherocylinders) adds its
// contact geometry, its inertia tensor and an orientation per particle without changing spheres:
// the orientation arrays exist only in a scene that has a non-spherical species
// (docs/architecture.md, "Adding a particle shape").
#ifndef BDL_SPECIES_H
#define BDL_SPECIES_H

#include "core/rng.h"
#include "dem/material.h"

#define BDL_MAX_SPECIES 16

/// Particle shape of a species ([species NAME] shape).
#define BDL_SHAPES(X) X(SHAPE_SPHERE, "sphere", "sphere")
BDL_CHOICES(bdl_shape, BDL_SHAPES);

/// Diameter distribution of a species.
#define BDL_SIZE_DISTS(X)                                                                          \
    X(SIZE_SINGLE, "single", "all particles have `diameter`")                                      \
    X(SIZE_UNIFORM, "uniform", "uniform in [diameter_min, diameter_max]")                          \
    X(SIZE_NORMAL, "normal",                                                                       \
      "normal(diameter, diameter_std) truncated to [diameter_min, diameter_max]")
BDL_CHOICES(bdl_size_dist, BDL_SIZE_DISTS);

typedef struct bdl_species_def {
    char name[BDL_NAME_LEN];
    bdl_shape shape;
    bdl_size_dist size_dist;
    double diameter;           ///< [m] (mean for distributions)
    double diameter_min;       ///< [m]
    double diameter_max;       ///< [m]
    double diameter_std;       ///< [m] (normal distribution)
    double density;            ///< [kg/m^3]
    double background_damping; ///< b [1/s]: force -b m v on every particle of the species
    bdl_material material;
} bdl_species_def;

/// Diameter drawn from a species' distribution [m].
double bdl_species_draw_diameter(const bdl_species_def *s, bdl_rng *rng);

/// Largest and smallest diameter a species can have [m].
double bdl_species_max_diameter(const bdl_species_def *s);
double bdl_species_min_diameter(const bdl_species_def *s);

#endif
