// bedlam — free rotation of rigid bodies (see rigid.h).
#include "dem/rigid.h"

/// The body rotated about its own axis a (0, 1, 2) by `angle`: q (cos, sin e_a) on the right.
static bdl_quat turn_body(bdl_quat q, int a, double angle)
{
    const double c = cos(0.5 * angle), s = sin(0.5 * angle);
    const bdl_quat r = {c, a == 0 ? s : 0.0, a == 1 ? s : 0.0, a == 2 ? s : 0.0};
    return bdl_q_mul(q, r);
}

/// The exact flow of H_a = rate pi_a^2 / 2 for dt: the body turns about its axis a by
/// rate pi_a dt, pi = R^T L (pi_a itself does not change under this flow).
static bdl_quat flow_body_axis(bdl_quat q, bdl_vec3 L, int a, double rate, double dt)
{
    return turn_body(q, a, rate * bdl_v3_comp(bdl_q_unrotate(q, L), a) * dt);
}

/// Swaps the axes o[i] and o[i + 1] when o[i + 1] has the larger inverse moment.
static void order_pair(bdl_vec3 inv_inertia, int o[3], int i)
{
    if (bdl_v3_comp(inv_inertia, o[i + 1]) > bdl_v3_comp(inv_inertia, o[i])) {
        const int swap = o[i];
        o[i] = o[i + 1], o[i + 1] = swap;
    }
}

/// The body axes by inverse moment: o[0] the largest, o[1] the middle one, o[2] the smallest
/// (ties keep the lower index first).
static void order_axes(bdl_vec3 inv_inertia, int o[3])
{
    o[0] = 0, o[1] = 1, o[2] = 2;
    order_pair(inv_inertia, o, 0);
    order_pair(inv_inertia, o, 1);
    order_pair(inv_inertia, o, 0);
}

bdl_quat bdl_rigid_rotate(bdl_quat q, bdl_vec3 L, bdl_vec3 inv_inertia, double dt)
{
    int axis[3];
    order_axes(inv_inertia, axis);
    const double c = bdl_v3_comp(inv_inertia, axis[1]);
    // c |pi|^2 / 2: a rotation about the constant L, commuting with the two parts that follow.
    const double l = bdl_v3_len(L);
    if (l > 0.0)
        q = bdl_q_mul(bdl_q_axis_angle(bdl_v3_scale(L, 1.0 / l), c * l * dt), q);
    // The remainder, Strang-split: outer axis for dt/2, inner axis for dt, outer axis for dt/2.
    const double outer = bdl_v3_comp(inv_inertia, axis[0]) - c;
    const double inner = bdl_v3_comp(inv_inertia, axis[2]) - c;
    // For an axisymmetric body one of the two vanishes (and is skipped): the step is then exact.
    if (outer != 0.0)
        q = flow_body_axis(q, L, axis[0], outer, 0.5 * dt);
    if (inner != 0.0)
        q = flow_body_axis(q, L, axis[2], inner, dt);
    if (outer != 0.0)
        q = flow_body_axis(q, L, axis[0], outer, 0.5 * dt);
    return bdl_q_normalize(q);
}

/// cos and sin of the half angle a / 2: the series 1 - h^2/2 + h^4/24 - h^6/720 and
/// h - h^3/6 + h^5/120 below |h| = 1e-3 (the next terms, h^8/40320 and h^7/5040, are below 1e-24,
/// under the rounding of 1 and of h), the library's cos and sin above.
static void half_angle(double a, double *c, double *s)
{
    const double h = 0.5 * a, h2 = h * h;
    if (fabs(h) < 1e-3) {
        *c = 1.0 - h2 * (0.5 - h2 * (1.0 / 24.0 - h2 * (1.0 / 720.0)));
        *s = h * (1.0 - h2 * (1.0 / 6.0 - h2 * (1.0 / 120.0)));
    } else {
        *c = cos(h);
        *s = sin(h);
    }
}

bdl_quat bdl_rigid_rotate_axisymmetric(bdl_quat q, bdl_vec3 u, bdl_vec3 L, double inv_t,
                                       double inv_a, double dt)
{
    double c, s;
    const double l = bdl_v3_len(L);
    if (l > 0.0) { // about L, in the world frame
        half_angle(inv_t * l * dt, &c, &s);
        const double k = s / l;
        q = bdl_q_mul((bdl_quat){c, L.x * k, L.y * k, L.z * k}, q);
    }
    half_angle((inv_a - inv_t) * bdl_v3_dot(L, u) * dt, &c, &s); // about the body axis
    q = bdl_q_mul(q, (bdl_quat){c, 0.0, 0.0, s});
    return bdl_q_normalize(q);
}
