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
