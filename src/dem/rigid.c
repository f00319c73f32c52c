// bedlam — free rotation of rigid bodies (see rigid.h).
#include "dem/rigid.h"

/// The body rotated about its own axis a (0, 1, 2) by `angle`: q (cos, sin e_a) on the right.
static bdl_quat turn_body(bdl_quat q, int a, double angle)
{
    const double c = cos(0.5 * angle), s = sin(0.5 * angle);
    const bdl_quat r = {c, a == 0 ? s : 0.0, a == 1 ? s : 0.0, a == 2 ? s : 0.0};
    return bdl_q_mul(q, r);
}

/// Free symmetric top: about L by |L| dt / I_t in the world frame, then about the body axis 3 by
/// (1/I_3 - 1/I_t) pi_3 dt.
static bdl_quat rotate_axisymmetric(bdl_quat q, bdl_vec3 L, bdl_vec3 inv_inertia, double dt)
{
    const double pi_3 = bdl_q_unrotate(q, L).z;
    q = turn_body(q, 2, (inv_inertia.z - inv_inertia.x) * pi_3 * dt);
    const double l = bdl_v3_len(L);
    if (l > 0.0)
        q = bdl_q_mul(bdl_q_axis_angle(bdl_v3_scale(L, 1.0 / l), l * inv_inertia.x * dt), q);
    return q;
}

/// The splitting 3, 2, 1, 2, 3 of the kinetic energy over the body axes: each part turns the body
/// about its axis k by pi_k dt_k / I_k, with pi = R^T L the body-frame momentum at that moment.
static bdl_quat rotate_split(bdl_quat q, bdl_vec3 L, bdl_vec3 inv_inertia, double dt)
{
    static const int axis[5] = {2, 1, 0, 1, 2};
    static const double share[5] = {0.5, 0.5, 1.0, 0.5, 0.5};
    for (int k = 0; k < 5; ++k) {
        const int a = axis[k];
        const double pi_a = bdl_v3_comp(bdl_q_unrotate(q, L), a);
        q = turn_body(q, a, share[k] * dt * pi_a * bdl_v3_comp(inv_inertia, a));
    }
    return q;
}

bdl_quat bdl_rigid_rotate(bdl_quat q, bdl_vec3 L, bdl_vec3 inv_inertia, double dt)
{
    q = inv_inertia.x == inv_inertia.y ? rotate_axisymmetric(q, L, inv_inertia, dt)
                                       : rotate_split(q, L, inv_inertia, dt);
    return bdl_q_normalize(q);
}
