// bedlam — rotation of rigid bodies with a full inertia tensor.
//
// A body's state is its orientation q (body frame to world frame) and its angular momentum L in
// the world frame; its inertia is diagonal in the body frame, I = diag(I_1, I_2, I_3), kept
// inverted. The angular velocity is w = R I^-1 R^T L (R the rotation of q), the rotational energy
// L.w / 2.
//
// A step under torque T is split as velocity Verlet splits a force (the same half kicks as the
// translation): L += dt/2 T; free rotation for dt; L += dt/2 T (the torque of the new state).
// The free rotation conserves L in the world frame and moves q:
//   - axisymmetric bodies (I_1 = I_2 = I_t; rods, spheres): exactly, as the composition of a
//     rotation about L by |L| dt / I_t (in the world frame) and a rotation about the body's own
//     axis by (1/I_3 - 1/I_t) pi_3 dt, pi = R^T L (the classical solution of the free symmetric
//     top);
//   - any other body: by the symmetric splitting of the kinetic energy into its three body axes
//     (Dullweber, Leimkuhler & McLachlan 1997, "Symplectic splitting methods for rigid body
//     molecular dynamics", J. Chem. Phys. 107; Miller et al. 2002, "Symplectic quaternion scheme
//     for biophysical molecular dynamics"): each part H_k = pi_k^2 / (2 I_k) rotates the body
//     about its axis k exactly, in the order 3, 2, 1, 2, 3 with half, half, full, half, half
//     steps. Symplectic and time-reversible, |L| exact, the energy error bounded and of second
//     order in dt, the orientation second order (docs/theory-rods.md).
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
/// frame without torque): exact for axisymmetric bodies (inv_inertia.x == inv_inertia.y), the
/// symmetric splitting otherwise (see above). Returns a unit quaternion.
bdl_quat bdl_rigid_rotate(bdl_quat q, bdl_vec3 L, bdl_vec3 inv_inertia, double dt);

#endif
