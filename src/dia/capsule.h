// bedlam — capsules (spherocylinders) for the synthetic camera: the nearest hit of a ray, and the
// volume of a capsule inside the boxes of a grid (the solids-fraction truth of rods).
//
// A capsule is the set of points within r of the segment x - e .. x + e (e = h u: u the unit
// axis, h half the shaft length). It is a cylinder of length 2h between two hemispheres.
#ifndef BDL_DIA_CAPSULE_H
#define BDL_DIA_CAPSULE_H

#include "core/vec3.h"

/// The nearest point where the ray o + t d (d a unit vector) enters the capsule (centre x,
/// half-axis e with |e| > 0, radius r): 1 with its distance t > 0 and the outward unit normal
/// there, or 0 when the ray misses it or starts inside it.
int bdl_dia_ray_capsule(bdl_vec3 o, bdl_vec3 d, bdl_vec3 x, bdl_vec3 e, double r, double *t,
                        bdl_vec3 *normal);

/// Volume of a capsule of radius r and half shaft length h [m^3].
double bdl_dia_capsule_volume(double r, double h);

/// A rectilinear grid of boxes: n[a] cells along axis a between the increasing coordinates
/// plane[a][0 .. n[a]] [m].
typedef struct bdl_dia_grid {
    int n[3];
    const double *plane[3];
} bdl_dia_grid;

/// Adds the volume of the capsule (centre x, half-axis e, radius r) inside each box of the grid
/// to volume[(k n[1] + j) n[0] + i] (box i, j, k along axes 0, 1, 2) [m^3]; the part outside the
/// grid is not counted. The capsule is cut into discs across its axis, integrated by 8-point
/// Gauss-Legendre quadrature on the pieces between the positions where a face, an edge or a
/// corner of a box meets its surface; each disc's area is shared exactly among the boxes.
/// Returns 0 when out of memory (nothing added).
int bdl_dia_capsule_grid_volume(bdl_vec3 x, bdl_vec3 e, double r, const bdl_dia_grid *g,
                                double *volume);

/// Volume of the capsule inside the box lo..hi [m^3] (a grid of one box).
double bdl_dia_capsule_box_volume(bdl_vec3 x, bdl_vec3 e, double r, bdl_vec3 lo, bdl_vec3 hi);

#endif
