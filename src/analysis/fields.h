// bedlam — time-averaged solids fields on a grid: the solids volume fraction and the
// volume-weighted mean solids velocity, from samples of the particles.
//
// A grid of n[0] x n[1] x n[2] cells covers the box lo..hi, n_a = max(1, floor(span_a / cell))
// along each axis, the cells of an axis all span_a / n_a long (a little longer than `cell` where
// it does not divide the span). Each sample deposits each particle's solids volume V_i, and V_i
// times its velocity v_i, in the cell that holds its centre; after N samples
//
//     phi_c = (sum of V_i deposited in c) / (V_c N),      u_c = (sum of V_i v_i) / (sum of V_i),
//
// V_c the cell's volume: phi is the solids fraction averaged over the samples, u the mean
// velocity of the solids that passed through the cell (NaN where none did). V_i is a sphere's
// 4/3 pi r^3, a rod's (a spherocylinder of tip-to-tip length L) pi r^2 (L - 2r) + 4/3 pi r^3, and
// a parcel's that of the real particles it stands for. A centre outside the box is not deposited
// (`deposited` against `total` says how much volume that was). The particles are added one after
// the other in their order, so the sums are the same bits on any number of threads.
//
// Used by a run while it goes ([output] fields_interval) and by `bedlam analyze fields` on the
// particle files of a finished one.
#ifndef BDL_FIELDS_H
#define BDL_FIELDS_H

#include "core/error.h"
#include "core/vec3.h"

typedef struct bdl_fields {
    int n[3];         ///< cells along x, y, z
    double lo[3];     ///< lower corner of the grid [m]
    double h[3];      ///< cell size along x, y, z [m]
    double *volume;   ///< per cell, x fastest: the solids volume deposited [m^3]
    double *momentum; ///< per cell: the deposited volume times velocity, 3 per cell [m^4/s]
    long samples;     ///< samples added
    long particles;   ///< particles over all samples
    double deposited; ///< solids volume deposited on the grid [m^3]
    double total;     ///< solids volume of every particle of every sample [m^3]
    double first;     ///< time of the first sample [s] (NaN before it)
    double last;      ///< time of the last sample [s]
} bdl_fields;

/// One sample: n particles, each array n long (3 numbers each for the vectors).
typedef struct bdl_fields_sample {
    double time; ///< [s]
    long n;
    const double *pos;    ///< centres, x y z after x y z [m]
    const double *vel;    ///< velocities, likewise [m/s]
    const double *radius; ///< [m]
    const double *length; ///< tip-to-tip lengths of rods [m]; NULL: all spheres
    const double *count;  ///< real particles each stands for (parcels); NULL: one each
} bdl_fields_sample;

/// The grid over lo..hi for cells of about `cell` [m] (> 0): n and h as described above. Returns
/// the number of cells, as a double so that no count overflows (an axis of more than 1e9 cells is
/// stored as 1e9 in n).
double bdl_fields_grid(const double lo[3], const double hi[3], double cell, int n[3], double h[3]);

/// An empty grid over lo..hi for cells of about `cell` [m]. BDL_ERR_ARGS when cell is not > 0 or
/// the grid would have more than `max_cells` cells (nothing is then allocated), BDL_ERR_NOMEM.
bdl_result bdl_fields_create(bdl_fields *f, const double lo[3], const double hi[3], double cell,
                             double max_cells);
void bdl_fields_free(bdl_fields *f);

/// Cells of the grid.
long bdl_fields_cells(const bdl_fields *f);

/// Volume of a sphere of `radius` [m], or of a rod of tip-to-tip `length` (lengths up to the
/// diameter give the sphere) [m^3].
double bdl_fields_volume(double radius, double length);

/// The cell size when none is asked for: three times the mean diameter of the n particles of
/// `radius` [m] (NaN for n = 0).
double bdl_fields_default_cell(long n, const double *radius);

/// Adds one sample.
void bdl_fields_add(bdl_fields *f, const bdl_fields_sample *s);

/// The averages after the samples so far: the solids fraction of each cell and its solids
/// velocity (3 per cell; NaN where no solids passed). With no sample the fraction is NaN.
void bdl_fields_means(const bdl_fields *f, double *fraction, double *velocity);

#endif
