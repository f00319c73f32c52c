// bedlam — geometry of spherocylinders (capsules): the closest points of two segments.
//
// A rod is the set of points within its radius of a segment, its shaft: centre x, half-axis
// e = h u (h half the shaft length, u the unit axis), points x + s e for s in [-1, 1]. Two rods
// touch when the distance of their shafts is below the sum of their radii; the contact normal
// runs between the two closest points, and the contact point lies in the middle of the overlap.
// A sphere is a rod with e = 0.
//
// Closest points (Vega & Lago 1994; Pournin et al. 2005), written here with unit axes u and
// half lengths h (e = h u; the formulas below in e are the same with A = C = 1 and the clamps at
// +-h): with d = x_a - x_b, A = e_a.e_a,
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

/// x clamped to [-h, h].
static inline double bdl_clamp_half(double x, double h)
{
    x = x < -h ? -h : x; // two selects, no branch (the same as one nested ?:)
    return x > h ? h : x;
}

/// Closest points of the shafts a + l u_a (l in [-h_a, h_a]) and b + m u_b (m in [-h_b, h_b]),
/// u_a and u_b unit axes, h_a, h_b >= 0 half lengths, given d = a - b: writes l and m [m] and
/// returns the squared distance |d + l u_a - m u_b|^2. With unit axes the re-projections need no
/// division: one division in all, for the infinite lines' minimiser.
static inline double bdl_shafts_closest(bdl_vec3 d, bdl_vec3 ua, double ha, bdl_vec3 ub, double hb,
                                        double *l_out, double *m_out)
{
    const double B = bdl_v3_dot(ua, ub), D = bdl_v3_dot(ua, d), E = bdl_v3_dot(ub, d);
    const bdl_vec3 n = bdl_v3_cross(ua, ub);
    const double n2 = bdl_v3_len2(n); // 1 - B^2 without the cancellation
    // Both candidates, then a select: no branch, so that a loop over pairs vectorises.
    const int parallel = !(n2 > 1e-26);
    // (The denominator is never 1: x / 1 would be folded into a branch around the division.)
    const double l_lines = bdl_v3_dot(n, bdl_v3_cross(ub, d)) / (parallel ? 1e-26 : n2);
    // parallel: the middle of the stretch of a facing b (or of a's nearer end)
    const double l1 = B * hb - D, l2 = -B * hb - D; // b's ends projected onto a
    const double lo = l1 < l2 ? l1 : l2, hi = l1 < l2 ? l2 : l1;
    const double l_middle = 0.5 * ((lo > -ha ? lo : -ha) + (hi < ha ? hi : ha));
    double l = bdl_clamp_half(parallel ? l_middle : l_lines, ha);
    const double m = bdl_clamp_half(E + l * B, hb);
    l = bdl_clamp_half(m * B - D, ha);
    *l_out = l;
    *m_out = m;
    const bdl_vec3 w = bdl_v3_sub(bdl_v3_madd(d, ua, l), bdl_v3_scale(ub, m));
    return bdl_v3_len2(w);
}

/// Closest points of the segments a + s e_a and b + t e_b (s, t in [-1, 1]), given d = a - b:
/// writes s and t, returns the squared distance |d + s e_a - t e_b|^2. bdl_shafts_closest with
/// the half axes split into unit axes and half lengths.
static inline double bdl_segments_closest(bdl_vec3 d, bdl_vec3 ea, bdl_vec3 eb, double *s_out,
                                          double *t_out)
{
    const double ha = bdl_v3_len(ea), hb = bdl_v3_len(eb);
    const bdl_vec3 ua = ha > 0.0 ? bdl_v3_scale(ea, 1.0 / ha) : bdl_v3(0.0, 0.0, 1.0);
    const bdl_vec3 ub = hb > 0.0 ? bdl_v3_scale(eb, 1.0 / hb) : bdl_v3(0.0, 0.0, 1.0);
    double l, m;
    bdl_shafts_closest(d, ua, ha, ub, hb, &l, &m);
    *s_out = ha > 0.0 ? bdl_clamp_unit(l / ha) : 0.0;
    *t_out = hb > 0.0 ? bdl_clamp_unit(m / hb) : 0.0;
    const bdl_vec3 w = bdl_v3_sub(bdl_v3_madd(d, ea, *s_out), bdl_v3_scale(eb, *t_out));
    return bdl_v3_len2(w);
}

#endif
