// bedlam — triangle meshes (for walls, and their outlines in the renderer): STL (ASCII and binary)
// and OBJ files, welded and checked.
//
// A mesh is read as a triangle soup, then welded: vertices with bitwise equal coordinates become
// one (CAD exporters write a shared corner with the same digits in every facet), and every edge
// gets an id shared by the triangles on either side. The ids let the wall contact tell a face,
// an edge and a vertex apart and count a contact on a shared edge or vertex once (dem/walls.h).
// Input is untrusted: a truncated binary STL, a header that claims more triangles than the file
// holds or than BDL_MESH_MAX_TRIANGLES, a coordinate that is not finite, a triangle of zero
// area, an edge shared by more than two triangles and an empty file are refused with the reason.
#ifndef BDL_MESH_H
#define BDL_MESH_H

#include <stddef.h>
#include <stdint.h>

#include "core/error.h"
#include "core/vec3.h"

/// Most triangles one mesh file may hold (some 200 bytes each once welded and binned).
#define BDL_MESH_MAX_TRIANGLES 4000000L

typedef struct bdl_mesh {
    long vertex_count, tri_count, edge_count;
    bdl_vec3 *vertex;       ///< welded vertices [m]
    int32_t (*tri)[3];      ///< vertex indices of each triangle
    int32_t (*tri_edge)[3]; ///< edge k of a triangle joins its vertices k and (k + 1) % 3
    int32_t (*edge)[2];     ///< the two vertices of each edge
} bdl_mesh;

/// Reads an STL (ASCII or binary, told apart by the size the binary header implies) or an OBJ
/// file (by the extension .obj), welds it and checks it. On failure returns BDL_ERR_IO (the
/// file cannot be read) or BDL_ERR_SCENE (its content is refused) with a phrase in `why` that
/// follows the path (naming the line or the triangle).
bdl_result bdl_mesh_read(const char *path, bdl_mesh *m, char *why, size_t why_len);

/// A flat ring (a disk when hole_radius is 0): centre, normal, outer and inner radius [m], as
/// `segments` quadrilaterals (a fan of triangles without a hole). The circles are polygons of
/// `segments` sides through points on them.
bdl_result bdl_mesh_disk(bdl_mesh *m, bdl_vec3 centre, bdl_vec3 normal, double radius,
                         double hole_radius, int segments, char *why, size_t why_len);
/// The side of a frustum, open at both ends: the centre of its base circle, the axis towards the
/// top, the radii of the base and the top (one of them may be 0: a cone) and the height [m].
bdl_result bdl_mesh_frustum(bdl_mesh *m, bdl_vec3 base, bdl_vec3 axis, double radius,
                            double radius_top, double height, int segments, char *why,
                            size_t why_len);

/// Scales about the origin, rotates by angles_deg about x, then y, then z (degrees, right hand),
/// then translates, every vertex.
void bdl_mesh_transform(bdl_mesh *m, double scale, bdl_vec3 angles_deg, bdl_vec3 translate);

/// The point of the triangle (a, b, c) nearest p: on a vertex or an edge (their Voronoi regions
/// first), or, with *face set, inside the face (the point returned is then p itself, the
/// distance the plane's). Within 1e-10 of an edge's length of a vertex, or of the face's height
/// of an edge, the point is put on that vertex or edge (so that round-off cannot put a point
/// over a shared vertex on different features of the triangles around it).
bdl_vec3 bdl_triangle_nearest(bdl_vec3 a, bdl_vec3 b, bdl_vec3 c, bdl_vec3 p, int *face);

/// An edge that keeps the mesh from being a closed, consistently turned surface: one that
/// borders one triangle only (*border set), or whose two triangles run it the same way (they turn
/// opposite ways); -1 when there is none, -2 when out of memory.
long bdl_mesh_unclosed_edge(const bdl_mesh *m, int *border);

/// The volume a closed mesh encloses, signed: positive when its triangles turn counter-clockwise
/// seen from outside [m^3].
double bdl_mesh_volume(const bdl_mesh *m);

/// The winding number of a closed mesh about x: the solid angle its triangles subtend at x over
/// 4 pi (Van Oosterom & Strackee's formula per triangle): +-1 inside, 0 outside, whichever way
/// the triangles turn.
double bdl_mesh_winding(const bdl_mesh *m, bdl_vec3 x);

/// The distance from x to the nearest point of the mesh [m].
double bdl_mesh_distance(const bdl_mesh *m, bdl_vec3 x);

void bdl_mesh_free(bdl_mesh *m);

#endif
