// bedlam — conservative occlusion culling of spheres (and rods) on the CPU.
//
// In a dense bed seen from outside, only the first few layers of particles can be seen; drawing
// the others costs a software rasteriser most of its time. Each sphere occludes the pixels that
// lie wholly inside a disk its projection surely covers, at the depth of its far side
// (view-space z_c + r: nothing it shows there is farther). A sphere is hidden when every pixel
// its projected bounding box touches is occluded nearer than its near side (z_c - r). Both bounds
// are conservative, so a culled sphere would not have shown a single pixel: the image is the same
// with and without culling (tests/test_render.c checks this).
//
// A rod (capsule: the points within r of the segment x +- a) occludes with balls of radius r
// along its shaft, which lie inside it, and is hidden only when the union of its two end balls'
// bounding boxes is occluded nearer than the nearer end ball's near side (the rod is the convex
// hull of the two balls): both bounds stay conservative.
#ifndef BDL_CULL_H
#define BDL_CULL_H

#include <stdint.h>

typedef struct bdl_cull {
    float *depth; ///< occluder depth per cell [m, view space]
    int cols, rows, capacity;
} bdl_cull;

/// Sets visible[i] to 1 for every particle that may show a pixel, 0 for the others (also those
/// off screen or behind the clipping plane `clip`, when not NULL: hidden where
/// clip.xyz . x + clip.w > 0). `axis` is NULL for spheres, else xyz per particle of the rods'
/// half shafts a (zero for a sphere). `view` and `proj` are column-major. Returns the visible
/// count.
long bdl_cull_particles(bdl_cull *c, const float *pos, const float *radius, const float *axis,
                        long count, const float view[16], const float proj[16], int ortho,
                        int width, int height, const float *clip, uint8_t *visible);

void bdl_cull_free(bdl_cull *c);

#endif
