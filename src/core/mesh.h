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

void bdl_mesh_free(bdl_mesh *m);

#endif
