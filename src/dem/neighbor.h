// bedlam — neighbour search: cell grid + Verlet pair list with skin, contact history.
//
// Particles are binned into cells of size >= d_max + skin and sorted by the cells' Morton
// (Z-order) rank at every rebuild, so neighbours sit close in memory. The half pair list holds
// every pair (i < j) closer than r_i + r_j + skin; it stays valid until a particle has moved
// skin/2 (or a particle plus a wall have moved skin together), so it is rebuilt only then.
//
// With rods the cells are at least a rod's length plus the skin, a pair is listed when the
// distance of the two shafts (dem/capsule.h) is below r_i + r_j + skin, and a wall when either
// tip comes within the skin of it (a shaft's distance to a plane, or to a cylinder's inside, is
// smallest at a tip): the lists stay valid until a tip has moved skin/2. (The thesis bounds a rod
// by three spheres, Mahajan 2019 §3.2.4; the exact shaft distance lists fewer pairs for the same
// guarantee.)
//
// Tangential history follows each pair across rebuilds and re-sorts (looked up by the particles'
// previous indices). How forces are summed deterministically is described in contact_force.c.
//
// Lees–Edwards boundaries (a box under simple shear u_x = shear rate x z, periodic in x and z):
// the image of the box above sits shifted along x by shear_shift and moves at +shear_velocity
// (shear rate x L_z), the one below the opposite way. A pair whose separation is taken across the
// z faces sees its partner's image there; a particle leaving through a z face comes back in
// through the other at its image's place and velocity. The cells next to a z face search the
// whole x row across it, and the lists are rebuilt once the images have slid far enough that a
// pair across the faces may have come within reach (2 max|x - x_build| + |shift since| > skin).
#ifndef BDL_NEIGHBOR_H
#define BDL_NEIGHBOR_H

#include <stddef.h>
#include <stdint.h>

#include "core/exact_sum.h"
#include "dem/particles.h"
#include "dem/walls.h"

typedef struct bdl_neighbor {
    // cell grid
    bdl_vec3 origin; ///< lower corner of the grid [m]
    bdl_vec3 length; ///< domain length per axis [m]
    double cell[3];  ///< cell size per axis [m]
    int dims[3];     ///< cells per axis
    int periodic[3];
    long cell_count;
    int32_t *cell_rank;   ///< Morton rank of each cell
    int32_t *cell_start;  ///< first particle of each ranked cell (cell_count + 1)
    int32_t *cell_cursor; ///< scratch for the counting sort
    double skin;          ///< [m]

    // pairs (half list, i < j, grouped by i)
    long count; ///< particles the list was built for
    long pair_count, pair_capacity;
    int32_t *start;      ///< pairs of i are [start[i], start[i+1])
    int32_t *partner;    ///< j of each pair
    bdl_vec3 *history;   ///< tangential displacement [m] (NULL without friction)
    double *spring_work; ///< the work the spring holds [J] (Hertz-Mindlin only, else NULL)
    uint8_t *touching;   ///< 1 if the pair overlapped this step
    long version;        ///< incremented at every rebuild (derived per-step structures follow it)

    // History of the touching pairs, packed by their first particle's previous index while a
    // rebuild renumbers the particles.
    bdl_vec3 *stash_history;
    double *stash_spring_work;
    int32_t *stash_partner;
    int32_t *stash_start;
    long stash_capacity;
    // wall contacts (grouped by particle)
    long wall_pair_count, wall_pair_capacity;
    int32_t *wall_start; ///< (count + 1)
    int32_t *wall_prim;
    bdl_vec3 *wall_history;
    double *wall_spring_work; ///< as spring_work (Hertz-Mindlin only, else NULL)
    bdl_vec3 *wall_force;     ///< force on the particle [N]
    uint8_t *wall_touching;
    // previous wall list, kept to carry history across rebuilds
    int32_t *old_wall_start, *old_wall_prim;
    bdl_vec3 *old_wall_history;
    double *old_wall_spring_work;
    long old_wall_capacity;

    bdl_vec3 wall_offset_at_build[BDL_MAX_WALLS];
    double wall_angle_at_build[BDL_MAX_WALLS]; ///< turned angles of the walls then [rad]
    int32_t *perm;                             ///< scratch: new index -> old index
    int32_t *pcell;                            ///< scratch: ranked cell of each particle
    void *scratch;                             ///< scratch for permutations (count * 24 bytes)
    long scratch_count;
    int friction, rolling;
    int mindlin; ///< Hertz-Mindlin springs (friction and the Hertz law): their work is kept
    /// The work the springs held when their contacts ended, since the start [J]: it left the
    /// bodies. Summed exactly (core/exact_sum.h): the force pass's threads add to it.
    bdl_exact_sum spring_work_left;
    int rods; ///< the particles are rods (bdl_particles.rods)
    // MPI ranks (bdl_neighbor_build_from): particles [0, owned) sit in the cells by cell_start,
    // the ghosts after them in a list per ranked cell (ghost_head, ghost_next; -1 ends it).
    int ghosted;         ///< 0: no ghosts (one process)
    long owned;          ///< particles before the ghosts
    int32_t *ghost_head; ///< first ghost of each ranked cell (cell_count)
    int32_t *ghost_next; ///< the next ghost in its cell, by ghost (index - owned)
    long ghost_capacity;
    long parallel_min; ///< fewer particles than this: builds on one thread (core/parallel.h)
    long builds;       ///< rebuilds so far

    // Lees–Edwards (bdl_neighbor_set_shear); all 0 without
    double shear_velocity;        ///< velocity of the image above: shear rate x L_z [m/s]
    double shear_shift;           ///< x offset of the image above, in [-L_x/2, L_x/2) [m]
    double shear_travel;          ///< shear_velocity x time, not wrapped [m]
    double shear_travel_at_build; ///< shear_travel at the last rebuild [m]
} bdl_neighbor;

/// Sets up the grid for the domain; `cutoff` = the largest particle extent (a diameter, or a
/// rod's length) + skin [m]. `max_particles` bounds the cell count (cells grow when the domain is
/// much larger than the particles need). `rods`: the particles are rods (the lists follow them).
/// `hertz`: the Hertz law (with friction the springs' stored work is kept beside them).
bdl_result bdl_neighbor_init(bdl_neighbor *nb, bdl_vec3 lo, bdl_vec3 hi, const int periodic[3],
                             double cutoff, double skin, long max_particles, int friction,
                             int hertz, int rolling, int rods);
void bdl_neighbor_free(bdl_neighbor *nb);

/// Empty lists for n particles, without a cell grid (parcels, which have no contacts): every
/// particle's pair and wall list is empty, so that what walks the lists finds nothing.
bdl_result bdl_neighbor_none(bdl_neighbor *nb, long n);

/// Wraps positions into periodic axes, re-sorts the particles, rebuilds pair and wall lists and
/// carries contact history over. Particles with drop[i] set are removed (drop may be NULL).
bdl_result bdl_neighbor_build(bdl_neighbor *nb, bdl_particles *p, const bdl_walls *walls,
                              const uint8_t *drop);

/// A process of an MPI run (dist/exchange.h), the build in two halves. First the p->count
/// particles it owns are wrapped into the periodic axes and sorted as bdl_neighbor_build does;
/// nb->perm then says where each came from.
bdl_result bdl_neighbor_sort(bdl_neighbor *nb, bdl_particles *p);
/// Then, with the ghosts appended after the `owned` sorted ones, the lists of all p->count
/// particles (the ghosts are not moved: they are put in their cells' lists): origin[i] is the
/// index particle i had when the lists were last built (-1: it was not here), which carries its
/// contact history over.
bdl_result bdl_neighbor_build_from(bdl_neighbor *nb, bdl_particles *p, const bdl_walls *walls,
                                   const int32_t *origin, long owned);

/// True when the lists may have missed a contact: 2 max|x - x_build| > skin, or a particle and a
/// wall together moved more than the skin (x: the centre, or with rods either tip). `max_move2`
/// is that largest squared displacement when the caller knows it (from the drift), or < 0 to
/// have it computed.
int bdl_neighbor_needs_build(const bdl_neighbor *nb, const bdl_particles *p, const bdl_walls *walls,
                             double max_move2);

/// Lees–Edwards: the images slid by `rate` x L_z x `time` (rate [1/s], the shear rate du_x/dz; the
/// x and z axes must be periodic). Called with the time of the positions before the lists are
/// built or forces evaluated.
void bdl_neighbor_set_shear(bdl_neighbor *nb, double rate, double time);

/// Lees–Edwards: +1 when the separation z_i - z_j (not wrapped) is taken to the partner's image
/// above, -1 below, 0 inside the box (always 0 without shear).
static inline double bdl_neighbor_image_side(const bdl_neighbor *nb, double dz)
{
    const double half = 0.5 * nb->length.z;
    return nb->shear_velocity == 0.0 ? 0.0 : (double)((dz > half) - (dz < -half));
}

/// The velocity of particle j's image that particle i meets, less j's own: (side x shear_velocity,
/// 0, 0) across the z faces of a sheared box, else zero.
static inline bdl_vec3 bdl_neighbor_image_velocity(const bdl_neighbor *nb, bdl_vec3 xi, bdl_vec3 xj)
{
    return bdl_v3(bdl_neighbor_image_side(nb, xi.z - xj.z) * nb->shear_velocity, 0.0, 0.0);
}

/// Minimum-image separation x_i - x_j (with Lees–Edwards, to j's image across the z faces).
static inline bdl_vec3 bdl_neighbor_delta(const bdl_neighbor *nb, bdl_vec3 xi, bdl_vec3 xj)
{
    bdl_vec3 d = bdl_v3_sub(xi, xj);
    d.x -= bdl_neighbor_image_side(nb, d.z) * nb->shear_shift;
    if (nb->periodic[0]) {
        if (d.x > 0.5 * nb->length.x)
            d.x -= nb->length.x;
        else if (d.x < -0.5 * nb->length.x)
            d.x += nb->length.x;
    }
    if (nb->periodic[1]) {
        if (d.y > 0.5 * nb->length.y)
            d.y -= nb->length.y;
        else if (d.y < -0.5 * nb->length.y)
            d.y += nb->length.y;
    }
    if (nb->periodic[2]) {
        if (d.z > 0.5 * nb->length.z)
            d.z -= nb->length.z;
        else if (d.z < -0.5 * nb->length.z)
            d.z += nb->length.z;
    }
    return d;
}

/// Bytes allocated by the neighbour structures.
long bdl_neighbor_bytes(const bdl_neighbor *nb);

/// Makes room for `particles` particles, `pairs` pairs and `wall_pairs` wall contacts (used when
/// a checkpoint restores the lists verbatim).
bdl_result bdl_neighbor_reserve(bdl_neighbor *nb, long particles, long pairs, long wall_pairs);

/// Checks lists restored from a file against what the force pass relies on, for `n` particles and
/// `prims` wall primitives: the offsets of each particle's pairs and wall contacts rise from 0 to
/// the counts stored, every pair (i, j) has i < j < n, every wall contact names a primitive in
/// [0, prims), contact flags are 0 or 1, springs, their stored work and forces are finite. Returns
/// 1, or 0 with the first violation in `why` ("pair 1234 refers to particle 99999 of 8070").
int bdl_neighbor_check(const bdl_neighbor *nb, long n, long prims, char *why, size_t len);

#endif
