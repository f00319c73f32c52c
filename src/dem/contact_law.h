// bedlam — contact force laws, composed from independent sub-models.
//
// For a contact between body i and body j (a wall is a body of infinite mass and radius) with
// unit normal n pointing from j to i, overlap delta > 0 and relative velocity of the contact
// point v_c = v_i - v_j - (a_i w_i + a_j w_j) x n (lever arms a below), the force on i is
//
//   F = F_n n + F_t,   F_n = max(0, k(delta) delta - eta(delta) v_n),     v_n = v_c . n
//
// normal sub-models
//   linear (spring-dashpot):  k = k_n,                       eta = 2 zeta sqrt(m* k_n)
//   Hertz:                    k = (4/3) E* sqrt(R* delta),    eta = c sqrt(m* k)
//     (the damping coefficient zeta or c realises the configured restitution: material.h)
// tangential sub-model (spring with history, Cundall & Strack; Luding; LIGGGHTS "history"):
//   the stored displacement u is rotated into the current contact plane (keeping its length),
//   u += v_t dt,  F_t = -k_t u - eta_t v_t,   k_t = k_t (linear) or 8 G* sqrt(R* delta) (Mindlin),
//   and if |F_t| > mu F_n the force is scaled back to the Coulomb cone and u reset so that the
//   spring alone, -k_t u, equals the capped force (sliding).
// onset (linear law): in the step where a contact begins, both dashpots act for the fraction of
//   the step spent in contact, delta / (-v_n dt).
// rolling sub-model (constant directional torque): M_r = -mu_r R* F_n w_rel/|w_rel|, limited so it
//   never reverses the relative spin within one step.
// The torque of F_t on body i is -a_i n x F_t and on body j -a_j n x F_t, with the lever arms
// a = r - delta/2 running to the middle of the overlap (they add up to the centre distance, so a
// pair conserves angular momentum exactly).
#ifndef BDL_CONTACT_LAW_H
#define BDL_CONTACT_LAW_H

#include "core/vec3.h"
#include "dem/material.h"

typedef struct bdl_contact_geom {
    bdl_vec3 n;     ///< unit normal from j to i
    double overlap; ///< delta > 0 [m]
    bdl_vec3 v_c;   ///< relative velocity of the contact point, i minus j [m/s]
    double m_eff;   ///< m* [kg]
    double r_eff;   ///< R* [m]
} bdl_contact_geom;

typedef struct bdl_contact_result {
    bdl_vec3 force;  ///< on body i [N]
    bdl_vec3 n_x_ft; ///< n x F_t: body i gets torque -a_i n x F_t, body j -a_j n x F_t [N]
    double normal;   ///< F_n >= 0 [N]
} bdl_contact_result;

#if defined(__GNUC__)
#define BDL_FORCE_INLINE inline __attribute__((always_inline))
#else
#define BDL_FORCE_INLINE inline
#endif

/// Evaluates the contact. `history` is the tangential spring displacement [m] (updated), or NULL
/// for frictionless contacts.
static BDL_FORCE_INLINE bdl_contact_result bdl_contact_eval(const bdl_contact_params *cp, int hertz,
                                                            const bdl_contact_geom *g,
                                                            bdl_vec3 *history, double dt)
{
    bdl_contact_result res;
    double vn = bdl_v3_dot(g->v_c, g->n);
    double k, kt;
    if (hertz) {
        double s = sqrt(g->r_eff * g->overlap);
        k = (4.0 / 3.0) * cp->e_star * s;
        kt = 8.0 * cp->g_star * s;
    } else {
        k = cp->kn;
        kt = cp->kt;
    }
    double eta = hertz ? cp->damping * sqrt(g->m_eff * k) : 2.0 * cp->damping * sqrt(g->m_eff * k);
    // A linear contact that began during this step has spent only delta / (-v_n dt) of it in
    // contact: the dashpots act for that fraction, which resolves the jump of the linear damping
    // force at first touch. (Hertz damping grows from zero with delta^(1/4): no jump to resolve.)
    if (!hertz && vn < 0.0 && g->overlap < -vn * dt)
        eta *= g->overlap / (-vn * dt);
    double fn = k * g->overlap - eta * vn;
    if (fn < 0.0)
        fn = 0.0; // no attraction: a damped contact releases when its force reaches zero
    res.normal = fn;
    res.force = bdl_v3_scale(g->n, fn);
    res.n_x_ft = bdl_v3_zero();
    if (!history)
        return res;

    bdl_vec3 vt = bdl_v3_madd(g->v_c, g->n, -vn);
    bdl_vec3 u = *history;
    double u2 = bdl_v3_len2(u);
    if (u2 > 0.0) {
        // Rotate the stored spring into the current tangent plane, keeping its length.
        double un = bdl_v3_dot(u, g->n);
        bdl_vec3 up = bdl_v3_madd(u, g->n, -un);
        // The normal turns little per step: for x = (u.n)^2/|u|^2 < 1e-5 the length factor
        // 1/sqrt(1 - x) = 1 + x/2 + 3x^2/8 + O(x^3) is exact to round-off without a square root.
        double x = un * un / u2;
        if (x < 1e-5) {
            u = bdl_v3_scale(up, 1.0 + x * (0.5 + 0.375 * x));
        } else {
            double up2 = bdl_v3_len2(up);
            u = up2 > 0.0 ? bdl_v3_scale(up, sqrt(u2 / up2)) : bdl_v3_zero();
        }
    }
    u = bdl_v3_madd(u, vt, dt);
    double eta_t = cp->tangential_damping_ratio * eta;
    bdl_vec3 ft = bdl_v3_add(bdl_v3_scale(u, -kt), bdl_v3_scale(vt, -eta_t));
    double ft2 = bdl_v3_len2(ft);
    double limit = cp->friction * (fn > 0.0 ? fn : 0.0);
    if (ft2 > limit * limit) {
        double ftl = sqrt(ft2);
        ft = ftl > 0.0 ? bdl_v3_scale(ft, limit / ftl) : ft;
        // The spring alone carries the capped force. (Leaving the dashpot's share in it would
        // make the spring point against the slip, and with the Mindlin stiffness growing as the
        // overlap does it would push along the slip on the next step.)
        u = kt > 0.0 ? bdl_v3_scale(ft, -1.0 / kt) : bdl_v3_zero();
    }
    *history = u;
    res.force = bdl_v3_add(res.force, ft);
    res.n_x_ft = bdl_v3_cross(g->n, ft);
    return res;
}

/// Rolling resistance torque on body i (body j gets the opposite). `w_rel` = w_i - w_j,
/// `inv_inertia_sum` = 1/I_i + 1/I_j (1/I_i for a wall).
static inline bdl_vec3 bdl_rolling_torque(const bdl_contact_params *cp, double normal_force,
                                          double r_eff, bdl_vec3 w_rel, double inv_inertia_sum,
                                          double dt)
{
    double w = bdl_v3_len(w_rel);
    if (w <= 0.0 || normal_force <= 0.0 || cp->rolling_friction <= 0.0)
        return bdl_v3_zero();
    double m = cp->rolling_friction * r_eff * normal_force;
    // A torque larger than this would reverse the relative spin within one step.
    double m_stop = w / (dt * inv_inertia_sum);
    if (m > m_stop)
        m = m_stop;
    return bdl_v3_scale(w_rel, -m / w);
}

#endif
