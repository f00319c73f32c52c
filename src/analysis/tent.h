// bedlam — a field of cell values read at a point with the gas coupling's tent kernel.
//
// The coupling (couple/coupling.h) spreads a particle over the cell centres within a half-width
// w of it, weight max(0, 1 - |x - x_c| / w) per axis, normalised over the centres inside the
// domain (a periodic axis wraps; at most BDL_TENT_MAX centres per axis); where no centre lies
// within reach, the nearest one takes it all. Read back with the same weights, a cell field
// gives the value the solver saw at the particle: the solids fraction of a parcel, 1 - eps, is
// this average of the gas's voidage. With w one cell (the parcels' default) it is the trilinear
// interpolation between cell centres, holding the edge value in the outer half cells.
#ifndef BDL_TENT_H
#define BDL_TENT_H

/// Most cell centres per axis one point reaches (couple/coupling.h: BDL_KERNEL_MAX).
#define BDL_TENT_MAX 8

typedef struct bdl_tent_field {
    int n[3];          ///< cells per axis
    int periodic[3];   ///< periodic axes wrap
    double lo[3];      ///< the grid's lower corner [m]
    double h[3];       ///< cell size per axis [m]
    double width[3];   ///< the kernel's half-width per axis [m] (at least h, at most 4 h)
    const float *cell; ///< n[0] n[1] n[2] values, x fastest
} bdl_tent_field;

/// The kernel average of the field at x.
double bdl_tent_sample(const bdl_tent_field *f, const double x[3]);

#endif
