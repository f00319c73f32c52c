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
#include "dem/species.h"
#include "dem/walls.h"

/// How a creator makes its particles ([create NAME] type).
#define BDL_CREATE_KINDS(X)                                                                        \
    X(CREATE_RANDOM, "random", "non-overlapping random fill of a box region")                      \
    X(CREATE_LATTICE, "lattice", "simple cubic lattice in a box region")                           \
    X(CREATE_POUR, "pour", "insert particles in a region at a rate during the run")                \
    X(CREATE_FILE, "file", "positions (and optionally diameter, velocity) from a CSV file")
BDL_CHOICES(bdl_create_kind, BDL_CREATE_KINDS);

/// The shape of a random or pour creator's region ([create NAME] region_shape).
#define BDL_REGION_SHAPES(X)                                                                       \
    X(REGION_BOX, "box", "the box region_min..region_max")                                         \
    X(REGION_CYLINDER, "cylinder",                                                                 \
      "the cylinder inscribed in that box along region_axis (a silo's or a drum's inside)")        \
    X(REGION_MESH, "mesh",                                                                         \
      "the inside of the closed mesh region_file, which must lie within the box (a vessel of "     \
      "any shape)")
BDL_CHOICES(bdl_region_shape, BDL_REGION_SHAPES);

typedef struct bdl_create_def {
    char name[BDL_NAME_LEN];
    bdl_create_kind kind;
    int species;                   ///< species index
    bdl_vec3 region_min;           ///< [m]
    bdl_vec3 region_max;           ///< [m]
    bdl_region_shape region_shape; ///< random, pour: box or the cylinder inscribed in it
    int region_axis;               ///< the cylinder's axis (0 x, 1 y, 2 z)
    long count;                    ///< number of particles (random, lattice, pour); -1 if not given
    double volume_fraction;  ///< target solids fraction of the region (random); < 0 if not given
    double spacing;          ///< lattice spacing [m]; < 0 -> 1.0001 max diameter
    double rate;             ///< pour rate [particles/s]
    double start_time;       ///< pour start [s]
    double stop_time;        ///< pour: no insertion from this time on (INFINITY: none) [s]
    bdl_vec3 velocity;       ///< initial velocity [m/s]
    double velocity_jitter;  ///< random velocity magnitude added [m/s]
    char file[BDL_PATH_LEN]; ///< CSV path
    char region_file[BDL_PATH_LEN]; ///< mesh region: STL or OBJ file of a closed surface
    double region_scale;            ///< mesh region: factor on the file's coordinates
    bdl_vec3 region_rotate;         ///< mesh region: angles about x, then y, then z [degrees]
    bdl_vec3 region_translate;      ///< mesh region: shift after scaling and rotating [m]
    double region_volume; ///< mesh region: the volume it encloses (set when the scene is read)
} bdl_create_def;

/// Volume of a creator's region: its box, the cylinder inscribed in it, or its mesh's [m^3].
double bdl_create_region_volume(const bdl_create_def *c);

/// The closed mesh of a creator with region_shape = mesh, read and placed.
bdl_result bdl_create_region_mesh(const bdl_create_def *c, bdl_mesh *m, char *why, size_t why_len);

/// What creators draw on besides their own definition.
typedef struct bdl_create_context {
    const bdl_species_def *species; ///< every species (creators place clear of the largest)
    int species_count;
    const bdl_walls *walls; ///< particles are placed clear of them
    bdl_rng *rng;           ///< every draw, in a fixed order
    const bdl_mesh *region; ///< the mesh of the creator run, with region_shape = mesh
} bdl_create_context;

/// Creates the particles of a random, lattice or file creator at the start of a run. A creator
/// that cannot make what it is asked for returns BDL_ERR_SCENE with the reason in `why`.
bdl_result bdl_create_initial(const bdl_create_def *c, const bdl_create_context *ctx,
                              bdl_particles *p, char *why, size_t why_len);

/// Pours the particles a pour creator owes by time t; `poured` counts what it has inserted so far
/// and is updated. A particle that finds no free place waits for a later step. Returns the
/// number added, -1 when out of memory.
long bdl_create_pour(const bdl_create_def *c, const bdl_create_context *ctx, double t, long *poured,
                     bdl_particles *p);

/// The number of particles creator c will make over a run, as a number (no count overflows):
/// its count; a random fill's volume fraction of the region over the volume of a particle of
/// the species' (mean) diameter; a lattice's sites (at most its count); a file's data rows (a
/// file that is not regular counts none); a pour's count. For estimating what a scene will need
/// before anything is allocated.
double bdl_create_expected(const bdl_create_def *c, const bdl_species_def *s);

/// Upper bound of the number of particles `count` creators will make (for sizing the cell grid).
long bdl_create_estimate_total(const bdl_create_def *creates, int count,
                               const bdl_species_def *species);

#endif
