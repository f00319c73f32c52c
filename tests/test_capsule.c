// bedlam — closest points of two segments (dem/capsule.h) against a brute-force reference.
//
// The reference: for segments a + s e_a and b + t e_b (s, t in [-1, 1]) the squared distance
// g(s, t) = |d + s e_a - t e_b|^2 is a convex quadratic, so f(s) = min_t g(s, t) is convex in s and
// its inner minimum is exact: t is the projection of the point a + s e_a onto b's line, clamped
// to [-1, 1]. A golden-section search on s (200 steps: the bracket shrinks below the spacing of
// doubles) finds min f; the endpoints s = -1, 1 are checked as well, and the same search with the
// roles of s and t swapped; the smaller of the two is the reference. Each candidate is a feasible
// pair (s, t), so the reference can only err upwards, by the rounding of g itself.
//
// Tolerance: the distances agree to 1e-12 of the distance, or of the segments' half lengths
// |e_a| + |e_b| when the distance is smaller than those: rounding in forming d + s e_a - t e_b
// (terms of the size of the segments) already puts the distance of the given numbers there.
//
// Both forms are checked: bdl_segments_closest (half axes, s and t in [-1, 1]) and the
// bdl_shafts_closest it calls (unit axes and half lengths), which the force pass calls directly.
//
// Last, the neighbour bounds: the excluded volume of two rods with the exact distance against
// Onsager's formula, and the thesis's three-sphere compound against it.
#include <math.h>
#include <stdio.h>

#include "check.h"
#include "core/rng.h"
#include "core/vec3.h"
#include "dem/capsule.h"

static const double tolerance = 1e-12;

/// g(s, t) at the t that minimises it for this s.
static double inner_min_t(bdl_vec3 d, bdl_vec3 ea, bdl_vec3 eb, double s)
{
    const bdl_vec3 p = bdl_v3_madd(d, ea, s); // a + s e_a relative to b
    const double C = bdl_v3_dot(eb, eb);
    const double t = C > 0.0 ? bdl_clamp_unit(bdl_v3_dot(p, eb) / C) : 0.0;
    return bdl_v3_len2(bdl_v3_madd(p, eb, -t));
}

/// min over s in [-1, 1] of the convex f(s) = min_t g(s, t): golden section plus the endpoints.
static double golden_min(bdl_vec3 d, bdl_vec3 ea, bdl_vec3 eb)
{
    const double r = 0.5 * (sqrt(5.0) - 1.0);
    double lo = -1.0, hi = 1.0;
    double best = fmin(inner_min_t(d, ea, eb, lo), inner_min_t(d, ea, eb, hi));
    double x1 = hi - r * (hi - lo), x2 = lo + r * (hi - lo);
    double f1 = inner_min_t(d, ea, eb, x1), f2 = inner_min_t(d, ea, eb, x2);
    for (int k = 0; k < 200; ++k) {
        best = fmin(best, fmin(f1, f2));
        if (f1 <= f2) {
            hi = x2, x2 = x1, f2 = f1;
            x1 = hi - r * (hi - lo), f1 = inner_min_t(d, ea, eb, x1);
        } else {
            lo = x1, x1 = x2, f1 = f2;
            x2 = lo + r * (hi - lo), f2 = inner_min_t(d, ea, eb, x2);
        }
    }
    return fmin(best, fmin(f1, f2));
}

/// The reference squared distance: the search over s and the search over t (d -> -d swaps roles).
static double brute_force(bdl_vec3 d, bdl_vec3 ea, bdl_vec3 eb)
{
    return fmin(golden_min(d, ea, eb), golden_min(bdl_v3_neg(d), eb, ea));
}

typedef struct stats {
    const char *name;
    long count;
    double worst;         // largest error in units of the tolerance's scale
    double worst_realise; // largest |g(s, t) - returned| in the same units
} stats;

/// One case: the function against the reference; s, t in range and realising the distance.
/// Returns the squared distance; s and t are written.
static double check_case(stats *st, bdl_vec3 d, bdl_vec3 ea, bdl_vec3 eb, double *s_out,
                         double *t_out)
{
    double s = 2.0, t = 2.0;
    const double got2 = bdl_segments_closest(d, ea, eb, &s, &t);
    const double ref = sqrt(brute_force(d, ea, eb)), got = sqrt(got2);
    const double scale = fmax(ref, bdl_v3_len(ea) + bdl_v3_len(eb));
    // The unit-axis form the force pass calls, directly: its own returned distance.
    const double ha = bdl_v3_len(ea), hb = bdl_v3_len(eb);
    const bdl_vec3 ua = ha > 0.0 ? bdl_v3_scale(ea, 1.0 / ha) : bdl_v3(1, 0, 0);
    const bdl_vec3 ub = hb > 0.0 ? bdl_v3_scale(eb, 1.0 / hb) : bdl_v3(0, 1, 0);
    double l = 0.0, m = 0.0;
    const double got_unit = sqrt(bdl_shafts_closest(d, ua, ha, ub, hb, &l, &m));
    CHECK(fabs(l) <= ha && fabs(m) <= hb);
    const double err = fmax(fabs(got - ref), fabs(got_unit - ref)) / (scale > 0.0 ? scale : 1.0);
    const double realised = bdl_v3_len(bdl_v3_sub(bdl_v3_madd(d, ea, s), bdl_v3_scale(eb, t)));
    const double err_realise = scale > 0.0 ? fabs(realised - got) / scale : fabs(realised - got);
    ++st->count;
    st->worst = fmax(st->worst, err);
    st->worst_realise = fmax(st->worst_realise, err_realise);
    CHECK_MSG(err <= tolerance && s >= -1.0 && s <= 1.0 && t >= -1.0 && t <= 1.0,
              "%s: distance %.17g, reference %.17g (error %.3g of %.3g), s %.17g t %.17g", st->name,
              got, ref, err, scale, s, t);
    CHECK_MSG(err_realise <= tolerance, "%s: s, t give %.17g, returned %.17g", st->name, realised,
              got);
    if (s_out)
        *s_out = s;
    if (t_out)
        *t_out = t;
    return got2;
}

/// A unit vector perpendicular to the unit vector u.
static bdl_vec3 perpendicular(bdl_vec3 u)
{
    const bdl_vec3 other = fabs(u.x) < 0.6 ? bdl_v3(1, 0, 0) : bdl_v3(0, 1, 0);
    return bdl_v3_normalize(bdl_v3_cross(u, other));
}

/// Half lengths from 0 to 1, a tenth of them exactly 0 (a sphere against a rod or a sphere).
static double random_half_length(bdl_rng *rng)
{
    return bdl_rng_uniform(rng) < 0.1 ? 0.0 : bdl_rng_uniform(rng);
}

static void random_pairs(stats *st, bdl_rng *rng, long n)
{
    for (long k = 0; k < n; ++k) {
        const double box = k % 2 ? 1.0 : 3.0; // crowded pairs (most cross) and looser ones
        const bdl_vec3 d = {bdl_rng_range(rng, -box, box), bdl_rng_range(rng, -box, box),
                            bdl_rng_range(rng, -box, box)};
        const bdl_vec3 ea = bdl_v3_scale(bdl_rng_direction(rng), random_half_length(rng));
        const bdl_vec3 eb = bdl_v3_scale(bdl_rng_direction(rng), random_half_length(rng));
        check_case(st, d, ea, eb, NULL, NULL);
    }
}

/// Sizes over six decades: half lengths 10^-6..1, centres 10^-3..10 apart.
static void random_scaled_pairs(stats *st, bdl_rng *rng, long n)
{
    for (long k = 0; k < n; ++k) {
        const bdl_vec3 d =
            bdl_v3_scale(bdl_rng_direction(rng), pow(10.0, bdl_rng_range(rng, -3.0, 1.0)));
        const bdl_vec3 ea =
            bdl_v3_scale(bdl_rng_direction(rng), pow(10.0, bdl_rng_range(rng, -6.0, 0.0)));
        const bdl_vec3 eb =
            bdl_v3_scale(bdl_rng_direction(rng), pow(10.0, bdl_rng_range(rng, -6.0, 0.0)));
        check_case(st, d, ea, eb, NULL, NULL);
    }
}

/// Parallel and anti-parallel segments along u, a's centre at the origin, b's at offset x0 along
/// u and h across: the distance is known, and where they overlap the contact parameters must lie
/// in the middle of the common stretch.
static void parallel_case(stats *st, bdl_vec3 u, double ha, double hb, double x0, double h,
                          double sign)
{
    const bdl_vec3 across = perpendicular(u);
    const bdl_vec3 b = bdl_v3_add(bdl_v3_scale(u, x0), bdl_v3_scale(across, h));
    const bdl_vec3 ea = bdl_v3_scale(u, ha), eb = bdl_v3_scale(u, sign * hb);
    double s, t;
    const double got = sqrt(check_case(st, bdl_v3_neg(b), ea, eb, &s, &t));
    const double lo = fmax(-ha, x0 - hb), hi = fmin(ha, x0 + hb);
    const double gap = lo > hi ? lo - hi : 0.0; // along u, between facing ends
    const double scale = fmax(got, ha + hb);
    CHECK_MSG(fabs(got - sqrt(gap * gap + h * h)) <= tolerance * scale,
              "parallel: distance %.17g, expected %.17g", got, sqrt(gap * gap + h * h));
    if (lo < hi && ha > 0.0 && hb > 0.0) { // overlapping: the middle of the common stretch
        const double mid = 0.5 * (lo + hi);
        CHECK_MSG(fabs(s * ha - mid) <= tolerance * scale &&
                      fabs(x0 + sign * t * hb - mid) <= tolerance * scale,
                  "parallel overlap [%g, %g]: s %.17g t %.17g, middle %.17g", lo, hi, s, t, mid);
    }
}

static void parallel_cases(stats *st, bdl_rng *rng)
{
    static const double offsets[] = {0.0, 0.3, -0.7, 1.2, 1.5, 1.999, 2.0, 2.5, -4.0};
    static const bdl_vec3 axes[] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {-1, 0, 0}, {0, 0, -1}};
    for (int k = 0; k < 400; ++k) {
        // Exactly parallel along the axes, parallel to rounding along random directions.
        const bdl_vec3 u = k < 5 ? axes[k] : bdl_rng_direction(rng);
        const double ha = k % 5 == 0 ? 0.5 : bdl_rng_range(rng, 0.1, 1.0);
        const double hb = k % 7 == 0 ? 1.0 : bdl_rng_range(rng, 0.1, 1.0);
        for (int j = 0; j < 9; ++j)
            for (int sign = -1; sign <= 1; sign += 2) {
                const double h = j % 3 == 0 ? 0.0 : bdl_rng_range(rng, 0.0, 0.5);
                parallel_case(st, u, ha, hb, offsets[j] * (ha + hb) / 2.0, h, sign);
            }
    }
}

/// End to end on one line, a gap apart (touching when 0): a's front tip against b's near tip.
static void collinear_cases(stats *st, bdl_rng *rng)
{
    for (int k = 0; k < 200; ++k) {
        const bdl_vec3 u = bdl_rng_direction(rng);
        const double ha = bdl_rng_range(rng, 0.0, 1.0), hb = bdl_rng_range(rng, 0.0, 1.0);
        const double gap = k % 4 == 0 ? 0.0 : bdl_rng_range(rng, 0.0, 1.0);
        const double sign = k % 2 ? 1.0 : -1.0;
        const bdl_vec3 d = bdl_v3_scale(u, -(ha + hb + gap)); // b ahead of a along u
        const bdl_vec3 ea = bdl_v3_scale(u, ha), eb = bdl_v3_scale(u, sign * hb);
        double s, t;
        const double got = sqrt(check_case(st, d, ea, eb, &s, &t));
        CHECK_MSG(fabs(got - gap) <= tolerance * (ha + hb + gap), "collinear: %.17g, gap %.17g",
                  got, gap);
        CHECK_MSG(fabs(s - 1.0) <= tolerance, "collinear: s %.17g, gap %g", s, gap); // front tip
    }
}

/// Two segments whose lines' common perpendicular, of length h, joins a + s0 e_a and b + t0 e_b
/// (n a unit vector perpendicular to both): the distance is h when s0 and t0 lie in [-1, 1].
static void crossing_case(stats *st, bdl_vec3 ea, bdl_vec3 eb, bdl_vec3 n, double s0, double t0,
                          double h)
{
    const bdl_vec3 b = bdl_v3_madd(bdl_v3_madd(bdl_v3_scale(ea, s0), n, h), eb, -t0);
    double s, t;
    const double got = sqrt(check_case(st, bdl_v3_neg(b), ea, eb, &s, &t));
    const double scale = fmax(h, bdl_v3_len(ea) + bdl_v3_len(eb));
    CHECK_MSG(fabs(got - h) <= tolerance * scale, "%s: distance %.17g, expected %.17g", st->name,
              got, h);
}

static void crossing_cases(stats *st, bdl_rng *rng)
{
    for (int k = 0; k < 2000; ++k) {
        const bdl_vec3 u = bdl_rng_direction(rng), v = bdl_rng_direction(rng);
        const bdl_vec3 n = bdl_v3_normalize(bdl_v3_cross(u, v));
        const bdl_vec3 ea = bdl_v3_scale(u, bdl_rng_range(rng, 0.05, 1.0));
        const bdl_vec3 eb = bdl_v3_scale(v, bdl_rng_range(rng, 0.05, 1.0));
        const double s0 = k % 10 == 0 ? (k % 20 ? 1.0 : -1.0) : bdl_rng_range(rng, -1.0, 1.0);
        const double h = k % 3 == 0 ? 0.0 : bdl_rng_range(rng, 0.0, 1.0);
        crossing_case(st, ea, eb, n, s0, bdl_rng_range(rng, -1.0, 1.0), h);
    }
}

/// a random unit vector w with w.x >= 0 and w.y >= 0 for the given x, y.
static bdl_vec3 away_from(bdl_rng *rng, bdl_vec3 x, bdl_vec3 y)
{
    for (;;) {
        const bdl_vec3 w = bdl_rng_direction(rng);
        if (bdl_v3_dot(w, x) >= 0.0 && bdl_v3_dot(w, y) >= 0.0)
            return w;
    }
}

/// a's tip a + e_a a gap away from b's tip b - e_b along w, w pointing away from both segments
/// (w.e_a >= 0, w.e_b >= 0): each tip is the other's closest point, so the distance is the gap.
/// And a's tip above the point b + t0 e_b of b's shaft, along w perpendicular to e_b.
static void tip_cases(stats *st, stats *st_shaft, bdl_rng *rng)
{
    for (int k = 0; k < 2000; ++k) {
        const bdl_vec3 ea = bdl_v3_scale(bdl_rng_direction(rng), bdl_rng_range(rng, 0.05, 1.0));
        const bdl_vec3 eb = bdl_v3_scale(bdl_rng_direction(rng), bdl_rng_range(rng, 0.05, 1.0));
        const double gap = k % 2 ? 0.0 : bdl_rng_range(rng, 0.0, 1.0);
        const double scale = gap + bdl_v3_len(ea) + bdl_v3_len(eb);
        const bdl_vec3 w = away_from(rng, ea, eb);
        bdl_vec3 b = bdl_v3_add(bdl_v3_madd(ea, w, gap), eb); // b - e_b = a + e_a + gap w
        double got = sqrt(check_case(st, bdl_v3_neg(b), ea, eb, NULL, NULL));
        CHECK_MSG(fabs(got - gap) <= tolerance * scale, "tip-tip: %.17g, gap %.17g", got, gap);
        // On the shaft: w perpendicular to e_b, on the side a's tip faces away from a.
        bdl_vec3 across = bdl_v3_normalize(bdl_v3_cross(eb, bdl_rng_direction(rng)));
        if (bdl_v3_dot(across, ea) < 0.0)
            across = bdl_v3_neg(across);
        const double t0 = bdl_rng_range(rng, -1.0, 1.0);
        b = bdl_v3_madd(bdl_v3_madd(ea, across, gap), eb, -t0); // b + t0 e_b = a + e_a + gap w
        got = sqrt(check_case(st_shaft, bdl_v3_neg(b), ea, eb, NULL, NULL));
        CHECK_MSG(fabs(got - gap) <= tolerance * scale, "tip-shaft: %.17g, gap %.17g", got, gap);
    }
}

/// Segments at a small angle theta: b's direction u + tan(theta) p (p perpendicular to u), the
/// common perpendicular n = u x p. Lines crossing (h = 0) or passing at h inside both segments,
/// crossing beyond them, and side by side in one plane, converging.
static void nearly_parallel_cases(stats *st, bdl_rng *rng, double theta)
{
    for (int k = 0; k < 400; ++k) {
        const bdl_vec3 u = bdl_rng_direction(rng), p = perpendicular(u), n = bdl_v3_cross(u, p);
        const double ha = bdl_rng_range(rng, 0.1, 1.0), hb = bdl_rng_range(rng, 0.1, 1.0);
        const bdl_vec3 ea = bdl_v3_scale(u, ha);
        const bdl_vec3 eb = bdl_v3_scale(bdl_v3_madd(u, p, tan(theta)), (k % 2 ? 1 : -1) * hb);
        const double s0 = bdl_rng_range(rng, -1.0, 1.0), t0 = bdl_rng_range(rng, -1.0, 1.0);
        const double h = k % 4 == 0 ? 0.0 : bdl_rng_range(rng, 0.0, 0.3);
        crossing_case(st, ea, eb, n, s0, t0, h); // the lines' closest points within both
        // Beyond the ends, side by side in the plane of u and p, and anywhere nearby.
        const double far = bdl_rng_range(rng, 1.0, 5.0) * (k % 3 ? 1 : -1);
        const bdl_vec3 b1 = bdl_v3_madd(bdl_v3_madd(bdl_v3_scale(ea, far), n, h), eb, -t0);
        check_case(st, bdl_v3_neg(b1), ea, eb, NULL, NULL);
        const bdl_vec3 b2 = bdl_v3_madd(bdl_v3_scale(u, bdl_rng_range(rng, -1, 1)), p, h);
        check_case(st, bdl_v3_neg(b2), ea, eb, NULL, NULL);
        const bdl_vec3 b3 = {bdl_rng_range(rng, -1, 1), bdl_rng_range(rng, -1, 1),
                             bdl_rng_range(rng, -1, 1)};
        check_case(st, b3, ea, eb, NULL, NULL);
    }
}

/// The thesis's neighbour bound (Mahajan 2019, Eq. 3.16): three spheres of radius R_n on the axis,
/// at the centre and at +-x_sat, x_sat = (2 (d + L) - sqrt(4 d^2 + 2 d L + L^2)) / 3 and
/// R_n = sqrt((x_sat / 2)^2 + (d / 2)^2), L the shaft: they meet at radius d / 2 and reach the
/// tips. Do the compounds of rods a and b (centres d apart, d = x_a - x_b; unit axes ua, ub),
/// each grown by skin / 2, overlap?
static int compounds_overlap(bdl_vec3 d, bdl_vec3 ua, bdl_vec3 ub, double diameter, double shaft,
                             double skin)
{
    const double x = (2.0 * (diameter + shaft) -
                      sqrt(4.0 * diameter * diameter + 2.0 * diameter * shaft + shaft * shaft)) /
                     3.0;
    const double reach = 2.0 * sqrt(0.25 * x * x + 0.25 * diameter * diameter) + skin;
    for (int i = -1; i <= 1; ++i)
        for (int j = -1; j <= 1; ++j) {
            const bdl_vec3 w = bdl_v3_madd(bdl_v3_madd(d, ua, i * x), ub, -j * x);
            if (bdl_v3_len2(w) < reach * reach)
                return 1;
        }
    return 0;
}

/// Neighbour bounds for the thesis's small rod (d 1.5 mm, 6 mm tip to tip): the excluded volume
/// of two randomly oriented rods, i.e. the pairs a Verlet list holds per unit number density,
/// with the exact distance of the shafts (against Onsager's (4 pi / 3) D^3 + 2 pi D^2 L +
/// (pi / 2) D L^2, D = d + skin) and with the three-sphere compound, from 2e6 random pairs each.
/// The compound encloses the rod, so it lists every pair the exact test lists.
static void neighbour_bounds(bdl_rng *rng)
{
    const double diameter = 1.5, shaft = 4.5; // [mm]
    printf("\nneighbour bounds, small rod (d 1.5 mm, L_p 6 mm): excluded volume [mm^3]\n"
           "  skin/d   exact (Onsager)      compound   ratio\n");
    for (int k = 0; k < 3; ++k) {
        const double skin = 0.1 * k * diameter, D = diameter + skin, H = shaft + D;
        long exact = 0, compound = 0, missed = 0, n = 2000000;
        for (long m = 0; m < n; ++m) {
            const bdl_vec3 ua = bdl_rng_direction(rng), ub = bdl_rng_direction(rng);
            const bdl_vec3 d = {bdl_rng_range(rng, -H, H), bdl_rng_range(rng, -H, H),
                                bdl_rng_range(rng, -H, H)};
            double s, t;
            const int e = bdl_segments_closest(d, bdl_v3_scale(ua, 0.5 * shaft),
                                               bdl_v3_scale(ub, 0.5 * shaft), &s, &t) < D * D;
            const int c = compounds_overlap(d, ua, ub, diameter, shaft, skin);
            exact += e, compound += c, missed += e && !c;
        }
        const double box = 8.0 * H * H * H, v_exact = box * exact / n, v_comp = box * compound / n;
        const double onsager = 4.0 * BDL_PI / 3.0 * D * D * D + 2.0 * BDL_PI * D * D * shaft +
                               0.5 * BDL_PI * D * shaft * shaft;
        printf("  %4.1f    %6.1f (%6.1f)     %6.1f     %4.2f\n", 0.1 * k, v_exact, onsager, v_comp,
               v_comp / v_exact);
        CHECK_CLOSE(v_exact, onsager, 0.01); // 1 % is 4 standard errors
        CHECK(missed == 0);
    }
}

static void print_stats(const stats *st)
{
    printf("  %-28s %8ld   %9.2e   %9.2e\n", st->name, st->count, st->worst, st->worst_realise);
}

int main(void)
{
    bdl_rng rng;
    bdl_rng_seed(&rng, 20240611);
    printf("closest points of two segments against the brute force: worst distance error and\n"
           "worst |g(s, t) - returned| over each set, in units of max(distance, |e_a| + |e_b|)\n");
    printf("  %-28s %8s   %9s   %9s\n", "set", "pairs", "distance", "s, t");
    stats random = {"random (1e5)", 0, 0, 0};
    random_pairs(&random, &rng, 100000);
    print_stats(&random);
    stats scaled = {"random, six decades (1e5)", 0, 0, 0};
    random_scaled_pairs(&scaled, &rng, 100000);
    print_stats(&scaled);
    stats parallel = {"parallel, anti-parallel", 0, 0, 0};
    parallel_cases(&parallel, &rng);
    print_stats(&parallel);
    stats collinear = {"collinear end to end", 0, 0, 0};
    collinear_cases(&collinear, &rng);
    print_stats(&collinear);
    stats crossing = {"crossing", 0, 0, 0};
    crossing_cases(&crossing, &rng);
    print_stats(&crossing);
    stats tip = {"tip to tip", 0, 0, 0}, shaft = {"tip on shaft", 0, 0, 0};
    tip_cases(&tip, &shaft, &rng);
    print_stats(&tip);
    print_stats(&shaft);
    for (int e = 3; e <= 15; ++e) {
        char name[40];
        snprintf(name, sizeof name, "nearly parallel, 1e-%d rad", e);
        stats near = {name, 0, 0, 0};
        nearly_parallel_cases(&near, &rng, pow(10.0, -e));
        print_stats(&near);
    }
    neighbour_bounds(&rng);
    return bdl_test_summary("test_capsule");
}
