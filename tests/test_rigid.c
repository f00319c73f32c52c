// bedlam — rigid bodies: quaternions (core/quat.h), the mass and inertia of a spherocylinder
// (dem/species.c) against a Monte Carlo integration, and the rotation (dem/rigid.c) against known
// answers: a torque-free asymmetric top (conservation, no drift, observed order 2), the free
// symmetric top (exact), the tennis-racket effect, and kick-rotate-kick under a constant torque
// (exact) and under gravity (the heavy symmetric top: energy of second order, the invariants to
// rounding, the turning point of the nutation). Tables go to stdout; docs/theory-rods.md quotes
// them.
#include <math.h>
#include <stdio.h>

#include "check.h"
#include "core/quat.h"
#include "core/rng.h"
#include "core/vec3.h"
#include "dem/rigid.h"
#include "dem/species.h"

/// The angle of the rotation taking q to p [rad].
static double angle_between(bdl_quat p, bdl_quat q)
{
    const bdl_quat r = bdl_q_mul(bdl_q_conj(q), p);
    return 2.0 * atan2(sqrt(r.x * r.x + r.y * r.y + r.z * r.z), fabs(r.w));
}

static bdl_quat random_orientation(bdl_rng *rng)
{
    return bdl_q_axis_angle(bdl_rng_direction(rng), bdl_rng_range(rng, 0.0, 2.0 * BDL_PI));
}

/// bdl_q_from_z takes z to u, to rounding, also for u next to -z where 1 + u.z cancels; the body
/// z axis is the rotated z; rotate and unrotate are inverse.
static void test_quaternions(bdl_rng *rng)
{
    double worst = 0.0;
    for (int k = 0; k < 20000; ++k) {
        bdl_vec3 u = bdl_rng_direction(rng);
        if (k % 2) { // within 1e-2 .. 1e-12 rad of -z or +z
            const double eps = pow(10.0, -bdl_rng_range(rng, 2.0, 12.0));
            u = bdl_v3_normalize(bdl_v3(eps * u.x, eps * u.y, k % 4 == 1 ? -1.0 : 1.0));
        }
        const bdl_quat q = bdl_q_from_z(u);
        worst = fmax(worst, bdl_v3_len(bdl_v3_sub(bdl_q_rotate(q, bdl_v3(0, 0, 1)), u)));
        CHECK(fabs(bdl_q_norm2(q) - 1.0) < 1e-15);
        const bdl_quat r = random_orientation(rng); // rounding: a few 1e-16
        CHECK(bdl_v3_len(bdl_v3_sub(bdl_q_axis_z(r), bdl_q_rotate(r, bdl_v3(0, 0, 1)))) < 4e-15);
        CHECK(bdl_v3_len(bdl_v3_sub(bdl_q_unrotate(r, bdl_q_rotate(r, u)), u)) < 4e-15);
    }
    const bdl_quat flip = bdl_q_from_z(bdl_v3(0, 0, -1));
    CHECK(bdl_v3_len(bdl_v3_sub(bdl_q_rotate(flip, bdl_v3(0, 0, 1)), bdl_v3(0, 0, -1))) < 1e-15);
    printf("quaternions: z to u, worst |R z - u| %.2e (u random, and within 1e-2..1e-12 rad of "
           "+-z)\n",
           worst);
    CHECK(worst < 4e-15);
}

/// Monte Carlo: mass and principal moments of the spherocylinder of radius r and shaft L (axis z)
/// from n uniform points of its bounding box; `sigma` gets the transverse moment's standard error.
static void monte_carlo(bdl_rng *rng, double r, double L, double density, long n, double out[3],
                        double *sigma)
{
    const double hz = 0.5 * L + r, box = 8.0 * r * r * hz;
    double count = 0.0, axial = 0.0, transverse = 0.0, transverse2 = 0.0;
    for (long k = 0; k < n; ++k) {
        const double x = bdl_rng_range(rng, -r, r), y = bdl_rng_range(rng, -r, r),
                     z = bdl_rng_range(rng, -hz, hz);
        const double zc = fmax(-0.5 * L, fmin(0.5 * L, z)); // the nearest point of the shaft
        if (x * x + y * y + (z - zc) * (z - zc) >= r * r)
            continue;
        count += 1.0;
        axial += x * x + y * y;
        const double t = 0.5 * (x * x + y * y) + z * z; // the mean of the x and y moments
        transverse += t;
        transverse2 += t * t;
    }
    const double w = density * box / (double)n;
    out[0] = w * count, out[1] = w * axial, out[2] = w * transverse;
    *sigma = w * sqrt(transverse2 - transverse * transverse / (double)n);
}

static void test_mass_properties(bdl_rng *rng)
{
    printf("\nspherocylinder mass properties against Monte Carlo (4e6 points each):\n"
           "  aspect  mass err   axial err  transverse err (1 sigma)\n");
    static const double aspect[] = {1.0, 1.5, 2.0, 4.0, 8.0};
    for (int k = 0; k < 5; ++k) {
        const double r = 0.5, L = 2.0 * r * (aspect[k] - 1.0), density = 1000.0;
        double m, ia, it, mc[3], sigma;
        bdl_rod_mass_properties(r, L, density, &m, &ia, &it);
        monte_carlo(rng, r, L, density, 4000000, mc, &sigma);
        printf("  %6.1f  %+.2e  %+.2e  %+.2e (%.1e)\n", aspect[k], mc[0] / m - 1.0,
               mc[1] / ia - 1.0, mc[2] / it - 1.0, sigma / it);
        CHECK_CLOSE(mc[0], m, 0.005);
        CHECK_CLOSE(mc[1], ia, 0.005);
        CHECK_CLOSE(mc[2], it, 0.005);
        if (k == 0) { // a sphere: 2/5 m r^2 about any axis
            CHECK_CLOSE(ia, 0.4 * m * r * r, 1e-14);
            CHECK_CLOSE(it, 0.4 * m * r * r, 1e-14);
        }
    }
    // The thesis's small rod: 6 mm tip to tip, d 1.5 mm, 1395 kg/m^3 (the digest's 3.67e-12 and
    // 3.64e-11 kg m^2; its transverse formula is the corrected one, the thesis's is garbled).
    double m, ia, it;
    bdl_rod_mass_properties(0.75e-3, 4.5e-3, 1395.0, &m, &ia, &it);
    printf("  small rod of the thesis: mass %.4e kg, axial %.4e, transverse %.4e kg m^2\n", m, ia,
           it);
    CHECK_CLOSE(ia, 3.67e-12, 0.01);
    CHECK_CLOSE(it, 3.64e-11, 0.01);
    CHECK_CLOSE(m, 1395.0 * BDL_PI * (0.75e-3 * 0.75e-3 * 4.5e-3 + 4.0 / 3.0 * pow(0.75e-3, 3)),
                1e-14);
}

/// The rotational energy L.w / 2.
static double energy(bdl_quat q, bdl_vec3 L, bdl_vec3 inv_inertia)
{
    return 0.5 * bdl_v3_dot(L, bdl_rigid_omega(q, L, inv_inertia));
}

/// For comparison: the 3-2-1-2-3 splitting of Dullweber, Leimkuhler & McLachlan (1997), each part
/// pi_k^2 / (2 I_k) turning the body about its axis k by pi_k dt_k / I_k.
static bdl_quat rotate_321(bdl_quat q, bdl_vec3 L, bdl_vec3 inv_inertia, double dt)
{
    static const int axis[5] = {2, 1, 0, 1, 2};
    static const double share[5] = {0.5, 0.5, 1.0, 0.5, 0.5};
    for (int k = 0; k < 5; ++k) {
        const double angle = share[k] * dt * bdl_v3_comp(bdl_q_unrotate(q, L), axis[k]) *
                             bdl_v3_comp(inv_inertia, axis[k]);
        const double s = sin(0.5 * angle);
        q = bdl_q_mul(q, (bdl_quat){cos(0.5 * angle), axis[k] == 0 ? s : 0.0,
                                    axis[k] == 1 ? s : 0.0, axis[k] == 2 ? s : 0.0});
    }
    return bdl_q_normalize(q);
}

typedef bdl_quat (*rotate_fn)(bdl_quat q, bdl_vec3 L, bdl_vec3 inv_inertia, double dt);

// The asymmetric top: moments 1, 2, 3; turning at w = (1, 0.3, 0.5) in its body frame (a generic
// motion, away from the separatrix); its rotation period 2 pi / |w|.
static const bdl_vec3 top_inv = {1.0, 0.5, 1.0 / 3.0};
static const bdl_vec3 top_w = {1.0, 0.3, 0.5};
static double top_period(void) { return 2.0 * BDL_PI / bdl_v3_len(top_w); }

typedef struct energy_record {
    double first, last, worst; // largest relative energy error: first and last tenth, overall
    double momentum;           // largest | |R^T L| / |L| - 1 |
    bdl_quat q;                // the final orientation
} energy_record;

/// n free steps of dt from the identity with the top's momentum.
static energy_record free_run(rotate_fn rotate, bdl_vec3 inv, bdl_vec3 w, double dt, long n)
{
    bdl_quat q = bdl_q_identity();
    const bdl_vec3 L = bdl_rigid_momentum(q, w, inv);
    const double e0 = energy(q, L, inv), l = bdl_v3_len(L);
    energy_record r = {0, 0, 0, 0, q};
    for (long k = 1; k <= n; ++k) {
        q = rotate(q, L, inv, dt);
        const double err = fabs(energy(q, L, inv) / e0 - 1.0);
        r.worst = fmax(r.worst, err);
        if (k <= n / 10)
            r.first = fmax(r.first, err);
        if (k > n - n / 10)
            r.last = fmax(r.last, err);
        r.momentum = fmax(r.momentum, fabs(bdl_v3_len(bdl_q_unrotate(q, L)) / l - 1.0));
    }
    r.q = q;
    return r;
}

/// 1e4 rotations of the asymmetric top: L exact, the energy error bounded (the last thousand
/// rotations no worse than the first), below 1e-6 at 1000 steps a rotation; the energy error
/// against the step, and the 3-2-1-2-3 splitting's for comparison.
static void test_free_top(void)
{
    const double period = top_period();
    printf("\nfree asymmetric top (moments 1, 2, 3; w = (1, 0.3, 0.5)), 1e4 rotations:\n"
           "  steps/rotation  splitting   energy err  first 1e3 rot.  last 1e3 rot.  |pi|/|L|-1\n");
    static const int per_rotation[] = {100, 1000};
    for (int k = 0; k < 2; ++k) {
        const long n = 10000L * per_rotation[k];
        const energy_record r =
            free_run(bdl_rigid_rotate, top_inv, top_w, period / per_rotation[k], n);
        printf("  %14d  bedlam      %.3e   %.3e       %.3e      %.1e\n", per_rotation[k], r.worst,
               r.first, r.last, r.momentum);
        CHECK(r.momentum < 1e-12);
        CHECK(r.last <= 1.05 * r.first); // bounded: no drift over 1e4 rotations
        CHECK(r.worst < (k == 0 ? 3e-5 : 1e-6));
    }
    // The energy error against the step, over 200 rotations, with the 3-2-1-2-3 splitting.
    printf("  over 200 rotations:\n  steps/rotation  bedlam     3-2-1-2-3  ratio\n");
    for (int steps = 50; steps <= 1600; steps *= 2) {
        const energy_record r =
            free_run(bdl_rigid_rotate, top_inv, top_w, period / steps, 200L * steps);
        const energy_record d = free_run(rotate_321, top_inv, top_w, period / steps, 200L * steps);
        printf("  %14d  %.3e  %.3e  %5.1f\n", steps, r.worst, d.worst, d.worst / r.worst);
        CHECK(d.worst > 5.0 * r.worst); // rigid.h: a tenth of the energy error
    }
    // L is the state: w from L and back gives L.
    const bdl_quat q = bdl_q_axis_angle(bdl_v3_normalize(bdl_v3(1, 2, 3)), 0.7);
    const bdl_vec3 L = bdl_v3(0.3, -1.1, 0.8);
    const bdl_vec3 back = bdl_rigid_momentum(q, bdl_rigid_omega(q, L, top_inv), top_inv);
    CHECK(bdl_v3_len(bdl_v3_sub(back, L)) < 4e-15 * bdl_v3_len(L));
    // The inverse inertia along a world direction: 1/I_k along the body axis k, e.(R I^-1 R^T e).
    for (int k = 0; k < 3; ++k) {
        bdl_vec3 ek = bdl_v3_zero();
        bdl_v3_set_comp(&ek, k, 1.0);
        CHECK_CLOSE(bdl_rigid_inv_inertia_along(q, top_inv, bdl_q_rotate(q, ek)),
                    bdl_v3_comp(top_inv, k), 1e-15);
    }
    const bdl_vec3 e = bdl_v3_normalize(bdl_v3(-2, 1, 5));
    CHECK_CLOSE(bdl_rigid_inv_inertia_along(q, top_inv, e),
                bdl_v3_dot(e, bdl_rigid_omega(q, e, top_inv)), 1e-15);
}

/// The orientation error at t = 5 rotations for dt = T/25 .. T/200 against T/25600, and the
/// largest energy error on the way: both of order 2.
static void test_free_order(void)
{
    const double period = top_period();
    const energy_record ref = free_run(bdl_rigid_rotate, top_inv, top_w, period / 25600, 5 * 25600);
    printf("\nfree asymmetric top, order: orientation error at 5 rotations, largest energy error\n"
           "  steps/rotation  orientation   order   energy err   order\n");
    double last_angle = 0.0, last_energy = 0.0;
    for (int steps = 25; steps <= 200; steps *= 2) {
        const energy_record r =
            free_run(bdl_rigid_rotate, top_inv, top_w, period / steps, 5 * steps);
        const double angle = angle_between(r.q, ref.q);
        if (steps == 25) {
            printf("  %14d  %.3e             %.3e\n", steps, angle, r.worst);
        } else {
            const double order = log2(last_angle / angle), eorder = log2(last_energy / r.worst);
            printf("  %14d  %.3e   %5.2f     %.3e    %5.2f\n", steps, angle, order, r.worst,
                   eorder);
            CHECK(fabs(order - 2.0) < 0.1);
            CHECK(fabs(eorder - 2.0) < 0.1);
        }
        last_angle = angle, last_energy = r.worst;
    }
}

/// The free symmetric top (I_t = 2, I_3 = 1, any step is exact): the axis precesses about L at
/// |L| / I_t and the body spins about its axis at (1/I_3 - 1/I_t) pi_3, so
/// q(t) = rot(L, |L| t / I_t) q0 rot(z, (1/I_3 - 1/I_t) pi_3 t). Both rotations: the general one
/// (axisymmetric = 0) and the rods' (1), with n steps of dt; the rods' takes the series of its
/// half angles when they are below 1e-3 rad (dt = 1e-3 here) and the library's sine above.
static void test_symmetric_exact(int axisymmetric, double dt, long n)
{
    const bdl_vec3 inv = {0.5, 0.5, 1.0};
    const bdl_quat q0 = bdl_q_axis_angle(bdl_v3(1, 0, 0), 0.7);
    const bdl_vec3 L = {0.0, 0.0, 1.3}; // along world z: the axis's azimuth is the precession
    const double pi3 = bdl_q_unrotate(q0, L).z;
    bdl_quat q = q0;
    double precession = 0.0, azimuth = atan2(bdl_q_axis_z(q).y, bdl_q_axis_z(q).x);
    for (long k = 0; k < n; ++k) {
        q = axisymmetric ? bdl_rigid_rotate_axisymmetric(q, bdl_q_axis_z(q), L, inv.x, inv.z, dt)
                         : bdl_rigid_rotate(q, L, inv, dt);
        const bdl_vec3 axis = bdl_q_axis_z(q);
        const double a = atan2(axis.y, axis.x);
        precession += remainder(a - azimuth, 2.0 * BDL_PI); // unwrapped
        azimuth = a;
    }
    const double t = n * dt, expected = bdl_v3_len(L) * inv.x * t;
    const bdl_quat exact = bdl_q_mul(bdl_q_mul(bdl_q_axis_angle(bdl_v3(0, 0, 1), expected), q0),
                                     bdl_q_axis_angle(bdl_v3(0, 0, 1), (inv.z - inv.x) * pi3 * t));
    printf("\nfree symmetric top (%s), %ld steps of %g: precession %.15g rad, |L| t / I_t %.15g "
           "(rel. error %.1e); orientation error %.1e rad\n",
           axisymmetric ? "rods' rotation" : "general rotation", n, dt, precession, expected,
           precession / expected - 1.0, angle_between(q, exact));
    CHECK_CLOSE(precession, expected, 1e-12);
    CHECK(angle_between(q, exact) < 1e-12 * expected);
}

/// The rods' rotation against the general one, one step each, for random orientations, momenta
/// and axisymmetric bodies (prolate and oblate), with steps that turn the body by 1e-9 to 1 rad
/// (both sides of the series' edge): the same rotation to rounding.
static void test_axisymmetric_rotation(bdl_rng *rng)
{
    double worst = 0.0;
    for (int k = 0; k < 100000; ++k) {
        const bdl_quat q = random_orientation(rng);
        const double inv_t = bdl_rng_range(rng, 0.2, 5.0), inv_a = bdl_rng_range(rng, 0.2, 5.0);
        const bdl_vec3 L = bdl_v3_scale(bdl_rng_direction(rng), bdl_rng_range(rng, 0.1, 2.0));
        const double turn = pow(10.0, bdl_rng_range(rng, -9.0, 0.0));
        const double dt = turn / (bdl_v3_len(L) * fmax(inv_t, inv_a));
        const bdl_quat a = bdl_rigid_rotate_axisymmetric(q, bdl_q_axis_z(q), L, inv_t, inv_a, dt);
        const bdl_quat b = bdl_rigid_rotate(q, L, bdl_v3(inv_t, inv_t, inv_a), dt);
        worst = fmax(worst, angle_between(a, b));
    }
    printf("\nrods' rotation against the general one, 1e5 random steps turning 1e-9..1 rad: "
           "largest difference %.1e rad\n",
           worst);
    CHECK(worst < 1e-14);
}

typedef struct spin_record {
    double lo, hi;        // range of the body's w along the spin axis, over its initial value
    double cross;         // largest |w| across the spin axis, over the initial |w|
    int flips;            // sign changes of w along the axis
    double first, spread; // the first flip's time; the spread of the intervals between flips
    double interval;      // the mean interval between flips [s]
} spin_record;

/// The top (moments 1, 2, 3) started spinning at 1 rad/s about its body axis a, perturbed by
/// 1e-3 rad/s about the other two; 3e5 steps of 1e-3.
static spin_record spin_about(int a)
{
    bdl_vec3 wb = {1e-3, 1e-3, 1e-3};
    bdl_v3_set_comp(&wb, a, 1.0);
    bdl_quat q = bdl_q_identity();
    const bdl_vec3 L = bdl_rigid_momentum(q, wb, top_inv);
    spin_record r = {1.0, 1.0, 0.0, 0, 0.0, 0.0, 0.0};
    double last_flip = -1.0, min_gap = 1e300, max_gap = 0.0, prev = 1.0;
    for (long k = 1; k <= 300000; ++k) {
        q = bdl_rigid_rotate(q, L, top_inv, 1e-3);
        const bdl_vec3 w = bdl_q_unrotate(q, bdl_rigid_omega(q, L, top_inv));
        const double along = bdl_v3_comp(w, a);
        r.lo = fmin(r.lo, along), r.hi = fmax(r.hi, along);
        r.cross = fmax(r.cross, sqrt(bdl_v3_len2(w) - along * along));
        if ((along < 0.0) != (prev < 0.0)) {
            const double t = k * 1e-3;
            if (r.flips == 0)
                r.first = t;
            else
                min_gap = fmin(min_gap, t - last_flip), max_gap = fmax(max_gap, t - last_flip);
            ++r.flips, last_flip = t;
        }
        prev = along;
    }
    r.spread = r.flips > 1 ? max_gap / min_gap - 1.0 : 0.0;
    r.interval = r.flips > 1 ? (last_flip - r.first) / (r.flips - 1) : 0.0;
    return r;
}

/// Half the period of w for the top spun about its intermediate axis (moments 1, 2, 3): Euler's
/// equations solved by Jacobi's elliptic functions (Landau & Lifshitz, Mechanics, section 37):
/// with L^2 > 2 E I_2 the period is 4 K(k) / lambda, lambda^2 = (I_3 - I_2)(L^2 - 2 E I_1) /
/// (I_1 I_2 I_3), k^2 = (I_2 - I_1)(2 E I_3 - L^2) / ((I_3 - I_2)(L^2 - 2 E I_1)); K by the
/// arithmetic-geometric mean, K = pi / (2 agm(1, sqrt(1 - k^2))).
static double racket_half_period(void)
{
    const double I[3] = {1.0, 2.0, 3.0}, w[3] = {1e-3, 1.0, 1e-3};
    double two_e = 0.0, l2 = 0.0;
    for (int k = 0; k < 3; ++k)
        two_e += I[k] * w[k] * w[k], l2 += I[k] * I[k] * w[k] * w[k];
    const double lambda = sqrt((I[2] - I[1]) * (l2 - two_e * I[0]) / (I[0] * I[1] * I[2]));
    const double k2 = (I[1] - I[0]) * (two_e * I[2] - l2) / ((I[2] - I[1]) * (l2 - two_e * I[0]));
    double a = 1.0, b = sqrt(1.0 - k2);
    for (int n = 0; n < 40; ++n) {
        const double m = 0.5 * (a + b);
        b = sqrt(a * b), a = m;
    }
    return 2.0 * (BDL_PI / (2.0 * a)) / lambda;
}

/// The tennis-racket (Dzhanibekov) effect: about the intermediate axis the spin turns over and
/// back periodically; about the smallest and largest axes it stays put.
static void test_tennis_racket(void)
{
    printf("\ntennis racket: spin 1 rad/s about a body axis, 1e-3 about the others, t = 300 s\n"
           "  axis (moment)  w along: min     max     largest w across  flips  intervals\n");
    for (int a = 0; a < 3; ++a) {
        const spin_record r = spin_about(a);
        printf("  %d (%d)          %+8.4f %+8.4f  %.2e          %5d  first at %.2f s, spread "
               "%.1e\n",
               a + 1, a + 1, r.lo, r.hi, r.cross, r.flips, r.first, r.spread);
        if (a == 1) { // over and back again, at equal intervals, all the way round
            CHECK(r.flips >= 4);
            CHECK(r.spread < 1e-2);
            CHECK(r.lo < -0.999 && r.hi > 0.999);
            const double half = racket_half_period();
            printf("  intermediate axis: mean interval between flips %.6f s, Jacobi's half period "
                   "%.6f s\n",
                   r.interval, half);
            CHECK_CLOSE(r.interval, half, 1e-4);
        } else {
            CHECK(r.flips == 0);
            CHECK(r.lo > 0.999 && r.hi < 1.001);
            CHECK(r.cross < 3e-3);
        }
    }
}

/// The torque on a body of orientation q: a constant one, or gravity on a top (below).
typedef bdl_vec3 (*torque_fn)(bdl_quat q, const double *param);

/// One step under torque, as the solver takes it: L += dt/2 T; free rotation; L += dt/2 T.
static bdl_quat kick_rotate_kick(bdl_quat q, bdl_vec3 *L, bdl_vec3 inv, double dt, torque_fn torque,
                                 const double *param)
{
    *L = bdl_v3_madd(*L, torque(q, param), 0.5 * dt);
    q = bdl_rigid_rotate(q, *L, inv, dt);
    *L = bdl_v3_madd(*L, torque(q, param), 0.5 * dt);
    return q;
}

static bdl_vec3 constant_torque(bdl_quat q, const double *param)
{
    (void)q;
    return bdl_v3(param[0], param[1], param[2]);
}

/// A body at rest under a constant torque tau about its principal axis k: L = tau t,
/// w = tau t / I_k, and it turns about that axis by tau t^2 / (2 I_k). Kick-rotate-kick is exact
/// here (the angle after n steps is tau dt^2 / I_k times 1/2 + 3/2 + ... = n^2 / 2).
static void test_constant_torque(bdl_rng *rng)
{
    static const bdl_vec3 bodies[2] = {{0.5, 0.5, 1.0}, {1.0, 0.5, 1.0 / 3.0}};
    double worst_angle = 0.0, worst_w = 0.0;
    for (int b = 0; b < 2; ++b)
        for (int k = 0; k < 3; ++k) {
            const bdl_quat q0 = random_orientation(rng);
            bdl_vec3 ek = bdl_v3_zero();
            bdl_v3_set_comp(&ek, k, 1.0);
            const bdl_vec3 axis = bdl_q_rotate(q0, ek), T = bdl_v3_scale(axis, 0.7);
            const double param[3] = {T.x, T.y, T.z}, dt = 0.01, inv_k = bdl_v3_comp(bodies[b], k);
            bdl_quat q = q0;
            bdl_vec3 L = bdl_v3_zero();
            for (int n = 0; n < 1000; ++n)
                q = kick_rotate_kick(q, &L, bodies[b], dt, constant_torque, param);
            const double t = 1000 * dt, angle = 0.7 * inv_k * t * t / 2.0;
            const bdl_quat exact = bdl_q_mul(bdl_q_axis_angle(axis, angle), q0);
            const bdl_vec3 w = bdl_rigid_omega(q, L, bodies[b]);
            worst_angle = fmax(worst_angle, angle_between(q, exact) / angle);
            worst_w = fmax(worst_w, bdl_v3_len(bdl_v3_sub(w, bdl_v3_scale(axis, 0.7 * inv_k * t))) /
                                        (0.7 * inv_k * t));
        }
    printf("\nconstant torque about a principal axis, from rest (axisymmetric and moments 1, 2, 3;"
           " 1000 steps):\n  worst relative error of the angle %.1e, of w %.1e\n",
           worst_angle, worst_w);
    // Rounding over 1000 steps (1e-12 to 1e-11 depending on the random axes drawn); an error of
    // the method would show at the size of dt^2 = 1e-4.
    CHECK(worst_angle < 1e-10);
    CHECK(worst_w < 1e-10);
}

/// Gravity on a top whose centre of mass lies at l on its axis above a fixed pivot (the moments
/// taken about the pivot): V = m g l e_3.z, T = m g l z x e_3; param[0] = m g l.
static bdl_vec3 gravity_torque(bdl_quat q, const double *param)
{
    return bdl_v3_scale(bdl_v3_cross(bdl_v3(0, 0, 1), bdl_q_axis_z(q)), param[0]);
}

typedef struct top_record {
    double first, last, worst; // largest |E - E0| / E0: first and last tenth, overall
    double invariants;         // largest change of L_z or pi_3, over |L|
    double max_tilt;           // [rad]
    bdl_quat q;
} top_record;

// The heavy symmetric top: I_t = 2, I_3 = 1 about the pivot, m g l = 1, tilted by 0.5 rad and
// spinning at 4 rad/s about its axis, released without precession.
static const bdl_vec3 heavy_inv = {0.5, 0.5, 1.0};
static const double heavy_mgl = 1.0, heavy_tilt = 0.5, heavy_spin = 4.0;

static double heavy_energy(bdl_quat q, bdl_vec3 L)
{
    return energy(q, L, heavy_inv) + heavy_mgl * bdl_q_axis_z(q).z;
}

static top_record heavy_top(double dt, long n)
{
    bdl_quat q = bdl_q_axis_angle(bdl_v3(1, 0, 0), heavy_tilt);
    bdl_vec3 L = bdl_rigid_momentum(q, bdl_q_rotate(q, bdl_v3(0, 0, heavy_spin)), heavy_inv);
    const double e0 = heavy_energy(q, L), lz = L.z, pi3 = bdl_v3_dot(L, bdl_q_axis_z(q));
    top_record r = {0, 0, 0, 0, heavy_tilt, q};
    for (long k = 1; k <= n; ++k) {
        q = kick_rotate_kick(q, &L, heavy_inv, dt, gravity_torque, &heavy_mgl);
        const double err = fabs(heavy_energy(q, L) / e0 - 1.0);
        r.worst = fmax(r.worst, err);
        if (k <= n / 10)
            r.first = fmax(r.first, err);
        if (k > n - n / 10)
            r.last = fmax(r.last, err);
        const double drift = fmax(fabs(L.z - lz), fabs(bdl_v3_dot(L, bdl_q_axis_z(q)) - pi3));
        r.invariants = fmax(r.invariants, drift / bdl_v3_len(L));
        r.max_tilt = fmax(r.max_tilt, acos(bdl_q_axis_z(q).z));
    }
    r.q = q;
    return r;
}

/// The other turning point of the nutation: with L_z = pi_3 cos(theta_0) and no tilt rate at
/// theta_0, energy conservation gives a c^2 - pi_3^2 c + pi_3^2 cos(theta_0) - a = 0 for
/// c = cos(theta_1), a = 2 I_t m g l.
static double heavy_turning_point(void)
{
    const double pi3 = heavy_spin / heavy_inv.z, p2 = pi3 * pi3, a = 2.0 / heavy_inv.x * heavy_mgl;
    const double c = (p2 - sqrt(p2 * p2 - 4.0 * a * (p2 * cos(heavy_tilt) - a))) / (2.0 * a);
    return acos(c);
}

/// Kick-rotate-kick on the heavy top: the energy error of order 2 and bounded over 1e6 steps, L_z
/// and pi_3 (both conserved by the exact motion) to rounding, the orientation of order 2, and the
/// largest tilt converging to the turning point.
static void test_heavy_top(void)
{
    const double turning = heavy_turning_point();
    const top_record ref = heavy_top(1e-4, 100000); // t = 10
    printf("\nheavy symmetric top (I_t 2, I_3 1, m g l 1, tilt 0.5 rad, spin 4 rad/s); turning "
           "point %.6f rad\n  dt      energy err (t<100)  order  orientation (t=10)  order  "
           "max tilt - turning  L_z, pi_3 change\n",
           turning);
    double last_energy = 0.0, last_angle = 0.0;
    for (double dt = 0.04; dt > 0.004; dt /= 2.0) {
        const top_record r = heavy_top(dt, lround(100.0 / dt));
        const double angle = angle_between(heavy_top(dt, lround(10.0 / dt)).q, ref.q);
        printf("  %.3f  %.3e", dt, r.worst);
        if (dt < 0.039) {
            const double eorder = log2(last_energy / r.worst), order = log2(last_angle / angle);
            printf("           %5.2f  %.3e           %5.2f", eorder, angle, order);
            CHECK(fabs(eorder - 2.0) < 0.1);
            CHECK(fabs(order - 2.0) < 0.1);
        } else {
            printf("                  %.3e                ", angle);
        }
        printf("  %+.2e           %.1e\n", r.max_tilt - turning, r.invariants);
        CHECK(r.invariants < 1e-12);
        CHECK(fabs(r.max_tilt - turning) < 200.0 * dt * dt * turning);
        last_energy = r.worst, last_angle = angle;
    }
    const top_record r = heavy_top(0.01, 1000000);
    printf("  1e6 steps of 0.01: energy error %.3e, first tenth %.3e, last tenth %.3e; L_z, pi_3 "
           "%.1e\n",
           r.worst, r.first, r.last, r.invariants);
    CHECK(r.last <= 1.05 * r.first);
    CHECK(r.invariants < 1e-12);
}

int main(void)
{
    bdl_rng rng;
    bdl_rng_seed(&rng, 20240612);
    test_quaternions(&rng);
    test_mass_properties(&rng);
    test_free_top();
    test_free_order();
    test_symmetric_exact(0, 0.37, 10000);
    test_symmetric_exact(1, 0.37, 10000);
    test_symmetric_exact(1, 1e-3, 100000);
    test_axisymmetric_rotation(&rng);
    test_tennis_racket();
    test_constant_torque(&rng);
    test_heavy_top();
    return bdl_test_summary("test_rigid");
}
