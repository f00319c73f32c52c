// bedlam — rotation of rigid bodies with a full inertia tensor.
//
// A body's state is its orientation q (body frame to world frame) and its angular momentum L in
// the world frame; its inertia is diagonal in the body frame, I = diag(I_1, I_2, I_3), kept
// inverted. The angular velocity is w = R I^-1 R^T L (R the rotation of q), the rotational energy
// L.w / 2.
//
// A step under torque T is split as velocity Verlet splits a force (the same half kicks as the
// translation): L += dt/2 T; free rotation for dt; L += dt/2 T (the torque of the new state).
// The free rotation conserves L in the world frame and moves q. Its energy is
//   H = (pi_1^2/I_1 + pi_2^2/I_2 + pi_3^2/I_3) / 2,   pi = R^T L the body-frame momentum,
// written with c = 1/I_m, the middle one of the three inverse moments, as
//   H = c |pi|^2 / 2 + (1/I_o - c) pi_o^2 / 2 + (1/I_i - c) pi_i^2 / 2,
// o the axis of the largest inverse moment, i that of the smallest. Each part is a rotation known
// exactly: the first turns the body about L by c |L| dt in the world frame and commutes with the
// others; the other two turn it about its own axis o, resp. i, by (1/I_k - c) pi_k dt, pi_k fixed
// during that part. The step is the symmetric composition (o for dt/2, i for dt, o for dt/2):
// symplectic, time-reversible, |L| exact, the energy error bounded and of second order in dt, the
// orientation second order, the leading error proportional to (1/I_o - c)(c - 1/I_i). It is
// exact for axisymmetric bodies (rods, spheres), where one of the two parts vanishes: it is then
// the classical solution of the free symmetric top (precession about L at |L| / I_t, spin about the
// axis at (1/I_3 - 1/I_t) pi_3). This is the splitting of Dullweber, Leimkuhler & McLachlan (1997,
// J. Chem. Phys. 107, 5840) with the isotropic part c |pi|^2 / 2 taken out first; for a body with
// moments 1, 2, 3 it has a tenth of the energy error of their 3-2-1-2-3 splitting (Fasso 2003, J.
// Comput. Phys. 189, 527, compares such splittings; docs/theory-rods.md has the measured figures).
#ifndef BDL_RIGID_H
#define BDL_RIGID_H

#include "core/quat.h"
#include "core/vec3.h"

/// The world-frame angular velocity w = R I^-1 R^T L [rad/s] of a body with orientation q,
/// angular momentum L [kg m^2/s] and body inverse inertia `inv_inertia` [1/(kg m^2)].
static inline bdl_vec3 bdl_rigid_omega(bdl_quat q, bdl_vec3 L, bdl_vec3 inv_inertia)
{
    const bdl_vec3 pi = bdl_q_unrotate(q, L);
    return bdl_q_rotate(q,
                        bdl_v3(pi.x * inv_inertia.x, pi.y * inv_inertia.y, pi.z * inv_inertia.z));
}

/// The angular momentum R I R^T w of a body turning at w [kg m^2/s].
static inline bdl_vec3 bdl_rigid_momentum(bdl_quat q, bdl_vec3 w, bdl_vec3 inv_inertia)
{
    const bdl_vec3 wb = bdl_q_unrotate(q, w);
    return bdl_q_rotate(q,
                        bdl_v3(wb.x / inv_inertia.x, wb.y / inv_inertia.y, wb.z / inv_inertia.z));
}

/// e . (R I^-1 R^T e): the inverse inertia about the world unit vector e [1/(kg m^2)].
static inline double bdl_rigid_inv_inertia_along(bdl_quat q, bdl_vec3 inv_inertia, bdl_vec3 e)
{
    const bdl_vec3 eb = bdl_q_unrotate(q, e);
    return eb.x * eb.x * inv_inertia.x + eb.y * eb.y * inv_inertia.y + eb.z * eb.z * inv_inertia.z;
}

/// The orientation after a free rotation for dt with angular momentum L (constant in the world
/// frame without torque): the splitting above, exact for axisymmetric bodies (two equal inverse
/// moments, about any of the body axes). Returns a unit quaternion.
bdl_quat bdl_rigid_rotate(bdl_quat q, bdl_vec3 L, bdl_vec3 inv_inertia, double dt);

/// bdl_rigid_rotate for a body symmetric about its body z axis (inverse moments inv_t about body
/// x and y, inv_a about z) whose axis in the world frame is u: the same rotation in the order the
/// solver's rods want it, with one turn about L by inv_t |L| dt and one about the body axis by
/// (inv_a - inv_t)(L.u) dt (L.u does not change under either), and the sines and cosines of the
/// small half angles of a time step by their series (exact to rounding below 2e-3 rad).
bdl_quat bdl_rigid_rotate_axisymmetric(bdl_quat q, bdl_vec3 u, bdl_vec3 L, double inv_t,
                                       double inv_a, double dt);

#endif
