// bedlam — the domain divided between MPI ranks: a grid of boxes, one per rank.
//
// The box of the run is cut into dims[0] x dims[1] x dims[2] equal boxes (subdomains); rank r
// has the box at coord = (r mod dims[0], (r / dims[0]) mod dims[1], r / (dims[0] dims[1])). A
// rank owns the particles whose centres lie in its box and keeps copies (ghosts) of the
// particles of the boxes around it that lie within `margin` of its own: with the margin at least
// the reach of a contact (the largest particle plus the neighbour skin) and the skin again, every
// pair a rank's own particles can touch before the next rebuild is on the rank, listed before the
// two can touch (so the rank owning either holds the pair's spring; dist/exchange.h).
//
// Along a periodic axis that is cut, the boxes at its two ends are neighbours, and a ghost
// across the period sits at its image (shifted by the axis's length). Along an axis that is not
// cut the neighbour lists keep the periodic images as in one process (dem/neighbor.h).
//
// Nothing here calls MPI: the geometry is tested on its own.
#ifndef BDL_DECOMP_H
#define BDL_DECOMP_H

#include "core/vec3.h"

/// At most this many ghost copies of one particle (the 26 boxes around a box).
#define BDL_DECOMP_MAX_TARGETS 26

typedef struct bdl_decomp {
    int size, rank;
    int dims[3];                 ///< boxes (ranks) along each axis
    int coord[3];                ///< this rank's box
    double lo[3];                ///< the domain [m]
    double hi[3];                ///< [m]
    int periodic[3];             ///< the domain's periodic axes
    double sub_lo[3], sub_hi[3]; ///< this rank's box [m]
    double margin;               ///< ghost width [m]
} bdl_decomp;

/// The division of `size` ranks, among those whose boxes are at least 2 margin wide along every
/// cut axis (a ghost then has one image per rank), with the fewest particles in its fullest box
/// (the n particles at `pos`, which may be none), and of those the least face area between boxes
/// (the ghosts' volume). Returns 0 with dims untouched when there is none.
int bdl_decomp_choose(int size, const double lo[3], const double hi[3], const int periodic[3],
                      double margin, const bdl_vec3 *pos, long n, int dims[3]);

/// Whether dims divides the domain into boxes at least 2 margin wide along every cut axis.
int bdl_decomp_fits(const int dims[3], const double lo[3], const double hi[3], double margin);

/// Rank `rank`'s view of the division dims (dims[0] dims[1] dims[2] ranks).
void bdl_decomp_init(bdl_decomp *d, int rank, const int dims[3], const double lo[3],
                     const double hi[3], const int periodic[3], double margin);

/// The rank of box coord, wrapped along periodic axes; -1 beyond a side that is not periodic.
int bdl_decomp_rank_of(const bdl_decomp *d, const int coord[3]);

/// x with its coordinates brought into the domain along the periodic axes that are cut.
bdl_vec3 bdl_decomp_wrap(const bdl_decomp *d, bdl_vec3 x);

/// The rank whose box holds x (x wrapped as bdl_decomp_wrap does; beyond a side that is not
/// periodic, the box at that side).
int bdl_decomp_owner(const bdl_decomp *d, bdl_vec3 x);

/// The ranks that keep a ghost of a particle at x in this rank's box, and the shift that puts it
/// at its image there (zero unless across a period). Returns their count (at most
/// BDL_DECOMP_MAX_TARGETS).
int bdl_decomp_ghost_targets(const bdl_decomp *d, bdl_vec3 x, int *ranks, bdl_vec3 *shifts);

#endif
