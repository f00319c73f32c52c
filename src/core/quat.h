// bedlam — unit quaternions for the orientation of rigid bodies.
//
// q = (w, x, y, z) with w the scalar part. A body's orientation q maps vectors from the body frame
// to the world frame: v_world = q v_body q*. Composition: rotating by q1, then by q2, is q2 q1.
// Small value type used by the solver; all functions are static inline.
#ifndef BDL_QUAT_H
#define BDL_QUAT_H

#include <math.h>

#include "core/vec3.h"

typedef struct bdl_quat {
    double w, x, y, z;
} bdl_quat;

static inline bdl_quat bdl_q_identity(void) { return (bdl_quat){1.0, 0.0, 0.0, 0.0}; }

static inline bdl_quat bdl_q_mul(bdl_quat a, bdl_quat b)
{
    return (bdl_quat){a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z,
                      a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y,
                      a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x,
                      a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w};
}

static inline bdl_quat bdl_q_conj(bdl_quat q) { return (bdl_quat){q.w, -q.x, -q.y, -q.z}; }

static inline double bdl_q_norm2(bdl_quat q)
{
    return q.w * q.w + q.x * q.x + q.y * q.y + q.z * q.z;
}

static inline bdl_quat bdl_q_normalize(bdl_quat q)
{
    double s = 1.0 / sqrt(bdl_q_norm2(q));
    return (bdl_quat){q.w * s, q.x * s, q.y * s, q.z * s};
}

/// Rotation by `angle` [rad] about the unit vector `axis`.
static inline bdl_quat bdl_q_axis_angle(bdl_vec3 axis, double angle)
{
    double s = sin(0.5 * angle);
    return (bdl_quat){cos(0.5 * angle), axis.x * s, axis.y * s, axis.z * s};
}

/// q v q* for a unit quaternion q: v from the body frame to the world frame.
static inline bdl_vec3 bdl_q_rotate(bdl_quat q, bdl_vec3 v)
{
    // v + 2 w (u x v) + 2 u x (u x v), u the vector part.
    bdl_vec3 u = {q.x, q.y, q.z};
    bdl_vec3 t = bdl_v3_scale(bdl_v3_cross(u, v), 2.0);
    return bdl_v3_add(bdl_v3_madd(v, t, q.w), bdl_v3_cross(u, t));
}

/// q* v q: v from the world frame to the body frame.
static inline bdl_vec3 bdl_q_unrotate(bdl_quat q, bdl_vec3 v)
{
    return bdl_q_rotate(bdl_q_conj(q), v);
}

/// The body's z axis in the world frame: the axis of a rod.
static inline bdl_vec3 bdl_q_axis_z(bdl_quat q)
{
    return (bdl_vec3){2.0 * (q.x * q.z + q.w * q.y), 2.0 * (q.y * q.z - q.w * q.x),
                      1.0 - 2.0 * (q.x * q.x + q.y * q.y)};
}

/// The rotation that takes the z axis to the unit vector u (the shortest one).
static inline bdl_quat bdl_q_from_z(bdl_vec3 u)
{
    // (1 + z.u, z x u) normalised: the rotation about z x u by the angle between z and u. Near
    // u = -z, 1 + u.z is formed as (u.x^2 + u.y^2) / (1 - u.z), which keeps the digits the sum
    // loses (10^-8 rad from -z the sum is 0); for u = -z exactly any perpendicular axis does.
    if (u.x == 0.0 && u.y == 0.0 && u.z < 0.0)
        return (bdl_quat){0.0, 1.0, 0.0, 0.0};
    const double w = u.z >= 0.0 ? 1.0 + u.z : (u.x * u.x + u.y * u.y) / (1.0 - u.z);
    return bdl_q_normalize((bdl_quat){w, -u.y, u.x, 0.0});
}

#endif
