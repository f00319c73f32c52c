// bedlam — bubbles in a fluidized bed's voidage field: the regions of cells whose voidage is
// above a threshold, joined through their faces, that do not reach the grid's top layer (those
// are the freeboard, or a bubble erupting into it). A common definition in two-fluid and
// CFD-DEM studies of bubbling beds (Kuipers et al. 1992 draw a bubble's edge at voidage 0.85).
//
// The field is a plain array of cell values, x fastest, then y, then z; the same analysis serves
// the voidage a CFD-DEM run's particles leave in the gas's cells and a two-fluid model's 1 - eps_s.
// The equivalent diameter of a bubble is that of the circle of its area where the grid is one
// cell deep (a pseudo-two-dimensional bed; the depth axis is the one with a single cell) and of
// the sphere of its volume otherwise.
#ifndef BDL_BUBBLES_H
#define BDL_BUBBLES_H

#include "core/error.h"

typedef struct bdl_bubbles {
    int count;            ///< bubbles
    double volume;        ///< their total volume [m^3]
    double mean_diameter; ///< mean equivalent diameter [m] (0 without bubbles)
    double max_diameter;  ///< largest equivalent diameter [m]
    double mean_height;   ///< volume-weighted mean height of the bubbles above the low side [m]
} bdl_bubbles;

typedef struct bdl_bubble_grid {
    int n[3];        ///< cells per axis
    double h[3];     ///< cell sizes [m]
    int periodic[3]; ///< axes whose sides join (a bubble may cross them)
    int up;          ///< the vertical axis
    int up_sign;     ///< +1 if up is along +x_up, -1 if along -x_up
} bdl_bubble_grid;

/// The bubbles of `voidage` (g->n[0] g->n[1] g->n[2] values) above `threshold`. A region that
/// touches the top layer (along up_sign) is freeboard, not a bubble. BDL_ERR_ARGS for a grid
/// without cells or a vertical axis out of range, BDL_ERR_NOMEM.
bdl_result bdl_bubbles_find(const double *voidage, const bdl_bubble_grid *g, double threshold,
                            bdl_bubbles *out);

#endif
