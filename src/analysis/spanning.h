// bedlam — Euclidean minimum spanning trees of particle centres, taken again with the edges
// already chosen lengthened (Sun 2007, ch. 6.4: the multi-pass MST), and the spatial
// correlation of contact forces (Sun's eq. 6.12, after Mueth et al. 1998).
//
// Pass 1 is the minimum spanning tree of the centres, edge length the centre distance. Before
// each further pass the lengths of the edges chosen so far are multiplied by `factor` (once for
// each pass that chose them), and the tree is taken again; the union of the chosen edges grows,
// from n - 1 towards the contacts of a packing. Sun keeps the edges that join contacting
// particles, the "trees of contacting particles", and compares them with the force networks
// (table 6.2). Prim's algorithm on the complete graph, O(n^2) per pass; ties go to the lower
// index, so the result does not depend on anything but the positions.
#ifndef BDL_SPANNING_H
#define BDL_SPANNING_H

#include <stdint.h>

#include "core/error.h"
#include "core/vec3.h"

/// An edge of the union: its two particles (i < j) and the pass that first chose it (1, 2 ...).
typedef struct bdl_span_edge {
    int32_t i, j;
    int32_t pass;
} bdl_span_edge;

/// The union of `passes` spanning trees of the n centres pos (a centre with a NaN coordinate
/// takes no part), each pass lengthening the edges already chosen by `factor`. `edges` has room
/// for passes * (n - 1); *count gets the union's size, ordered by pass, then as chosen.
bdl_result bdl_spanning_passes(long n, const bdl_vec3 *pos, int passes, double factor,
                               bdl_span_edge *edges, long *count);

/// F(r) = sum over pairs of contacts a, b at distance r of f_a f_b / their number (eq. 6.12),
/// for the n contacts at points at[] with forces f[] (normalised by the caller, as f = F / <F>),
/// in `bins` bins of width dr from 0: F[] gets the bin's mean product (NaN where no pair falls),
/// pairs[] (may be NULL) the number of pairs. O(n^2).
void bdl_force_correlation(long n, const bdl_vec3 *at, const double *f, int bins, double dr,
                           double *F, long *pairs);

#endif
