// bedlam — points in the image plane bucketed into square cells, for the pair searches of PTV,
// the 2D coordination number and the coalignment.
#ifndef BDL_DIA_POINTS_H
#define BDL_DIA_POINTS_H

#include "core/error.h"

/// n points (u, v) sorted by cell: cell (cx, cy) holds index[start[c] .. start[c + 1]) with
/// c = cy nx + cx, in increasing point order.
typedef struct bdl_dia_point_grid {
    double u0, v0, cell; ///< corner of cell (0, 0) and the cells' side [px]
    int nx, ny;
    long *start; ///< nx ny + 1 offsets
    long *index; ///< the points, cell by cell
} bdl_dia_point_grid;

/// Cells of side `cell` (> 0) over the points' bounding box (at most 2^22 cells: coarser when
/// the box would need more).
bdl_result bdl_dia_point_grid_build(bdl_dia_point_grid *g, const double *u, const double *v, long n,
                                    double cell);
void bdl_dia_point_grid_free(bdl_dia_point_grid *g);

/// The range of cells [*cx0, *cx1] x [*cy0, *cy1] that holds every point within `reach` of (u, v)
/// (empty, *cx0 > *cx1, when none can).
void bdl_dia_point_grid_range(const bdl_dia_point_grid *g, double u, double v, double reach,
                              int *cx0, int *cx1, int *cy0, int *cy1);

#endif
