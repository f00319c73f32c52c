// bedlam — voidage (gas volume fraction) from particles alone, on a uniform cell grid.
//
// Each sphere is split into BDL_VOIDAGE_POINTS sub-volumes of equal volume (shells of equal
// volume times directions spread evenly over the sphere); each sub-volume goes to the cell
// holding its centre. The solid volume deposited is exactly the spheres' volume, spheres
// crossing a cell face are shared between the cells in proportion (to within 3 % of the sphere's
// volume), and the result depends on the order of the particles only through rounding.
#ifndef BDL_VOIDAGE_H
#define BDL_VOIDAGE_H

#include "core/error.h"

#define BDL_VOIDAGE_SHELLS     4
#define BDL_VOIDAGE_DIRECTIONS 32
#define BDL_VOIDAGE_POINTS     (BDL_VOIDAGE_SHELLS * BDL_VOIDAGE_DIRECTIONS)

typedef struct bdl_voidage_grid {
    double origin[3]; ///< lower corner of the domain
    double cell;      ///< the requested cell size
    double h[3];      ///< actual cell size per axis: the domain divided into whole cells
    int dims[3];      ///< cells per axis
    int periodic[3];  ///< periodic axes wrap; on others, volume outside goes to the edge cell
    double *solid;    ///< solid volume per cell, x fastest
    double *voidage;  ///< 1 - solid / cell volume, clamped to [0, 1]
} bdl_voidage_grid;

/// Divides the box lo..hi into cells of about `cell` (at least one per axis).
/// BDL_ERR_NOMEM when the grid cannot be allocated, BDL_ERR_ARGS for an empty box or cell <= 0.
bdl_result bdl_voidage_grid_init(bdl_voidage_grid *g, const double lo[3], const double hi[3],
                                 double cell, const int periodic[3]);
void bdl_voidage_grid_free(bdl_voidage_grid *g);

/// Clears the grid and deposits `count` spheres (positions xyz packed, radii), then fills
/// the voidage.
void bdl_voidage_deposit(bdl_voidage_grid *g, long count, const float *pos, const float *radius);

/// Voidage at a point, interpolated trilinearly between cell centres (periodic axes wrap,
/// others hold the edge value).
float bdl_voidage_at(const bdl_voidage_grid *g, const float x[3]);

#endif
