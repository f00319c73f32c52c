// bedlam — geometry of spherocylinders (capsules): the closest points of two segments.
//
// A rod is the set of points within its radius of a segment, its shaft: centre x, half-axis
// e = h u (h half the shaft length, u the unit axis), points x + s e for s in [-1, 1]. Two rods
// touch when the distance of their shafts is below the sum of their radii; the contact normal
// runs between the two closest points, and the contact point lies in the middle of the overlap.
// A sphere is a rod with e = 0.
//
// Closest points (Vega & Lago 1994; Pournin et al. 2005): with d = x_a - x_b, A = e_a.e_a,
// B = e_a.e_b, C = e_b.e_b, D = e_a.d, E = e_b.d, the infinite lines are closest at
//   s' = (B E - C D) / (A C - B^2) = n.(e_b x d) / |n|^2,   n = e_a x e_b;
// s' is clamped to [-1, 1], t re-projected onto b's segment for that s and clamped, s re-projected
// for that t and clamped again: the exact minimum of the (convex) distance over the two segments.
// s' is computed in the second form (Lagrange's identity): A C - B^2 = A C sin^2 theta loses its
// digits to cancellation as the angle theta between the segments goes to zero (at 1e-4 rad the
// first form already misplaces the distance by 1e-12 of the rods' length), while the cross
// product keeps a relative error of about 1e-16 / theta, which the distance, flat along the rods
// at the minimum, feels only as 1e-16 of the rods' length.
// When the segments are parallel to rounding (theta below 1e-13 rad, where n is noise) every s of
// their common stretch is a minimiser to 1e-13 of the length, and s is taken in the middle of it,
// so that two rods lying side by side touch at the middle of their overlap and not at an
// arbitrary end of it. Nearly parallel rods above that angle touch where they are closest: at the
// end of their overlap towards which they converge (docs/theory-rods.md).
#ifndef BDL_CAPSULE_H
#define BDL_CAPSULE_H

#include "core/vec3.h"

static inline double bdl_clamp_unit(double x) { return x < -1.0 ? -1.0 : x > 1.0 ? 1.0 : x; }

/// Closest points of the segments a + s e_a and b + t e_b (s, t in [-1, 1]), given d = a - b:
/// writes s and t, returns the squared distance |d + s e_a - t e_b|^2.
static inline double bdl_segments_closest(bdl_vec3 d, bdl_vec3 ea, bdl_vec3 eb, double *s_out,
                                          double *t_out)
{
    const double A = bdl_v3_dot(ea, ea), B = bdl_v3_dot(ea, eb), C = bdl_v3_dot(eb, eb);
    const double D = bdl_v3_dot(ea, d), E = bdl_v3_dot(eb, d);
    double s = 0.0, t = 0.0;
    if (A > 0.0 && C > 0.0) {
        const bdl_vec3 n = bdl_v3_cross(ea, eb);
        const double n2 = bdl_v3_len2(n); // A C - B^2 without the cancellation
        if (n2 > 1e-26 * A * C) {
            s = bdl_clamp_unit(bdl_v3_dot(n, bdl_v3_cross(eb, d)) / n2);
        } else { // parallel: the middle of the stretch of a facing b (or of a's nearer end)
            const double s1 = (B - D) / A, s2 = (-B - D) / A; // b's ends projected onto a
            const double lo = s1 < s2 ? s1 : s2, hi = s1 < s2 ? s2 : s1;
            s = bdl_clamp_unit(0.5 * ((lo > -1.0 ? lo : -1.0) + (hi < 1.0 ? hi : 1.0)));
        }
        t = bdl_clamp_unit((E + s * B) / C);
        s = bdl_clamp_unit((t * B - D) / A);
    } else if (A > 0.0) { // b is a point
        s = bdl_clamp_unit(-D / A);
    } else if (C > 0.0) { // a is a point
        t = bdl_clamp_unit(E / C);
    }
    *s_out = s;
    *t_out = t;
    const bdl_vec3 w = bdl_v3_sub(bdl_v3_madd(d, ea, s), bdl_v3_scale(eb, t));
    return bdl_v3_len2(w);
}

#endif
