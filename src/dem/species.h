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
#define BDL_SHAPES(X)                                                                              \
    X(SHAPE_SPHERE, "sphere", "sphere")                                                            \
    X(SHAPE_ROD, "rod", "spherocylinder: a cylinder with hemispherical caps")
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
    double length;             ///< rod: tip-to-tip length [m] (> diameter); 0 for spheres
    double density;            ///< [kg/m^3]
    double background_damping; ///< b [1/s]: force -b m v (Lees–Edwards: v less the shear profile)
    bdl_material material;
    // Parcels (MP-PIC, src/parcels/): a species with one of these set is made of parcels, each
    // standing for many real particles of the species' diameter and density.
    double parcel_particles; ///< real particles per parcel; 0: not set
    double parcel_volume;    ///< solids volume per parcel [m^3] (equal volume); 0: not set
} bdl_species_def;

/// Whether the species is made of parcels.
static inline int bdl_species_is_parcel(const bdl_species_def *s)
{
    return s->parcel_particles > 0.0 || s->parcel_volume > 0.0;
}

/// Real particles in a parcel of the species whose particles have diameter d: parcel_particles,
/// or parcel_volume over the volume of one; 1 for a species that is not made of parcels.
double bdl_species_parcel_count(const bdl_species_def *s, double d);

/// Solids volume of a parcel of the species at its mean diameter (of one particle if it is not
/// made of parcels) [m^3].
double bdl_species_parcel_volume(const bdl_species_def *s);

/// Diameter drawn from a species' distribution [m].
double bdl_species_draw_diameter(const bdl_species_def *s, bdl_rng *rng);

/// Mass [kg] and principal moments of inertia [kg m^2] of a spherocylinder of radius r around a
/// shaft of length `shaft` (0: a sphere) of uniform density: axial pi rho (r^4 L/2 + 8/15 r^5),
/// transverse pi rho (r^2 L^3/12 + 3/4 r^4 L + 1/3 r^3 L^2 + 8/15 r^5), L the shaft length.
void bdl_rod_mass_properties(double r, double shaft, double density, double *mass, double *axial,
                             double *transverse);

/// Volume of one particle of the species of diameter d [m^3] (a rod: of its length).
double bdl_species_volume(const bdl_species_def *s, double d);

/// Largest extent of a particle of the species: its diameter, or a rod's length [m].
double bdl_species_max_extent(const bdl_species_def *s);

/// Largest and smallest diameter a species can have [m].
double bdl_species_max_diameter(const bdl_species_def *s);
double bdl_species_min_diameter(const bdl_species_def *s);

#endif
