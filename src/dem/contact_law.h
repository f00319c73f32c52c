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
// onset: in the step where a contact begins, the dashpots act, and the spring stretches, for the
//   fraction of the step spent in contact, delta / (-v_n dt).
// stored work (Mindlin): with k_t changing with the overlap the force -k_t(delta) u is not the
//   gradient of a potential, and 1/2 k_t |u|^2 is not what the spring holds (a spring stretched
//   while the contact was small reads 1/2 k_t |u|^2 once the contact has grown, though the bodies
//   never did the difference's work). The spring books the work its force takes from the bodies,
//   W += 1/2 (k_t' u' + k_t u) . (u - u'), primes a step ago (the trapezoid in which velocity
//   Verlet applies every force), over its own stretch (slip and dashpot work are dissipated, not
//   stored). What W still holds when the contact ends, the spring having fallen to zero with the
//   overlap, has left the bodies: the force pass adds it to bdl_neighbor.spring_work_left. With a
//   constant k_t (linear law) W is 1/2 k_t |u|^2 exactly, and nothing is booked.
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

/// The tangential spring of a contact.
typedef struct bdl_spring {
    bdl_vec3 u;  ///< displacement [m]
    double work; ///< Mindlin: the work it holds, taken from the bodies since first touch [J]
} bdl_spring;

typedef struct bdl_contact_result {
    bdl_vec3 force;    ///< on body i [N]
    bdl_vec3 n_x_ft;   ///< n x F_t: body i gets torque -a_i n x F_t, body j -a_j n x F_t [N]
    bdl_spring spring; ///< tangential spring after this step (friction only)
    double normal;     ///< F_n >= 0 [N]
    int exceptional;   ///< trial evaluation only: evaluate again in full
} bdl_contact_result;

#if defined(__GNUC__)
#define BDL_FORCE_INLINE inline __attribute__((always_inline))
#else
#define BDL_FORCE_INLINE inline
#endif

/// Component-wise c ? a : b (a select, not a branch: keeps bdl_contact_eval vectorisable).
static BDL_FORCE_INLINE bdl_vec3 bdl_v3_select(int c, bdl_vec3 a, bdl_vec3 b)
{
    return (bdl_vec3){c ? a.x : b.x, c ? a.y : b.y, c ? a.z : b.z};
}

/// Below this (u.n)^2 / |u|^2 the rotated spring is rescaled with a series (next comment).
#define BDL_ROTATION_SERIES_MAX 1e-6

/// The spring u rotated into the plane normal to n, keeping its length (a spring of zero length,
/// or one along the normal, has no direction in the plane and becomes zero). See
/// bdl_contact_eval_mode for the rescale and `trial`, which sets *exceptional.
static BDL_FORCE_INLINE bdl_vec3 bdl_spring_rotated(bdl_vec3 u, bdl_vec3 n, int trial,
                                                    int *exceptional)
{
    double u2 = bdl_v3_len2(u);
    double un = bdl_v3_dot(u, n);
    bdl_vec3 up = bdl_v3_madd(u, n, -un);
    double up2 = bdl_v3_len2(up);
    double eps = un * un / u2;
    int series = eps < BDL_ROTATION_SERIES_MAX;
    double factor = 1.0 + eps * (0.5 + 0.375 * eps);
    if (trial)
        *exceptional = (u2 > 0.0) & !series;
    else
        factor = series ? factor : sqrt(u2 / up2);
    bdl_vec3 rotated = bdl_v3_select(up2 > 0.0, bdl_v3_scale(up, factor), bdl_v3_zero());
    return bdl_v3_select(u2 > 0.0, rotated, u);
}

/// The work a Mindlin spring takes from the bodies in one step [J]: the trapezoid of its force over
/// its stretch from u_before (a step ago, turned into this step's plane) to u, with the stiffness
/// k_t now and 8 G* sqrt(R* before) a step ago, `before` the overlap then (delta + v_n dt; below
/// zero before first touch, where the spring had no stiffness).
static BDL_FORCE_INLINE double bdl_spring_work_step(const bdl_contact_params *cp, double r_eff,
                                                    double before, double kt, bdl_vec3 u_before,
                                                    bdl_vec3 u)
{
    double kt_before = 8.0 * cp->g_star * sqrt(r_eff * (before > 0.0 ? before : 0.0));
    bdl_vec3 stretch = bdl_v3_sub(u, u_before);
    return 0.5 * (kt_before * bdl_v3_dot(u_before, stretch) + kt * bdl_v3_dot(u, stretch));
}

/// Evaluates the contact. With `friction`, `spring` is the tangential spring (and with `hertz`
/// the work it holds) and the result holds its new state. `hertz` and `friction` should be
/// constants at the call site: the body has no other branch (only selects), so a loop over contacts
/// vectorises.
///
/// The rotated spring u_p = u - (u.n) n is rescaled to the length of u by the factor
/// (1 - eps)^(-1/2), eps = (u.n)^2 / |u|^2: for eps < BDL_ROTATION_SERIES_MAX (a normal that
/// turned by less than 1e-3 rad since the last step) by its series 1 + eps/2 + 3 eps^2/8, whose
/// error (< 3e-19) is below rounding, else by sqrt(|u|^2 / |u_p|^2).
///
/// With `trial`, the rescale of a spring whose normal turned more than the series covers (rare:
/// it needs a square root and a division of its own), and with `hertz` the first step of a
/// contact's spring (a division), are left out: then `res.exceptional` is set, and the caller
/// evaluates that contact again without `trial` (which gives exactly what `trial` gives for every
/// other contact).
static BDL_FORCE_INLINE bdl_contact_result bdl_contact_eval_mode(const bdl_contact_params *cp,
                                                                 int hertz, int friction,
                                                                 bdl_contact_geom geom,
                                                                 bdl_spring spring, double dt,
                                                                 int trial)
{
    const bdl_contact_geom *g = &geom;
    bdl_contact_result res;
    double vn = bdl_v3_dot(g->v_c, g->n);
    // A contact that began during this step (`starting`: the overlap a step ago, delta + v_n dt,
    // was negative) has spent only delta / (-v_n dt) of it in contact: the fraction `in_contact`.
    // A Hertz contact needs it only for its spring, and rarely: a trial flags a starting contact
    // to be evaluated again in full instead of dividing for every contact.
    double onset = -vn * dt;
    int starting = (vn < 0.0) & (g->overlap < onset);
    double in_contact = hertz && trial ? 1.0 : (starting ? g->overlap / onset : 1.0);
    double k, kt, eta;
    if (hertz) {
        double s = sqrt(g->r_eff * g->overlap);
        k = (4.0 / 3.0) * cp->e_star * s;
        kt = 8.0 * cp->g_star * s;
        eta = cp->damping * sqrt(g->m_eff * k);
    } else {
        k = cp->kn;
        kt = cp->kt;
        // The linear dashpots act for the fraction of the step in contact, which resolves the
        // jump of the linear damping force at first touch. (Hertz damping grows from zero with
        // delta^(1/4): no jump to resolve.)
        eta = 2.0 * cp->damping * sqrt(g->m_eff * k) * in_contact;
    }
    double fn = k * g->overlap - eta * vn;
    fn = fn < 0.0 ? 0.0 : fn; // no attraction: a damped contact releases when its force is zero
    res.normal = fn;
    res.force = bdl_v3_scale(g->n, fn);
    res.n_x_ft = bdl_v3_zero();
    res.spring = spring;
    res.exceptional = 0;
    if (!friction)
        return res;

    bdl_vec3 vt = bdl_v3_madd(g->v_c, g->n, -vn);
    bdl_vec3 u = spring.u;
    u = bdl_spring_rotated(u, g->n, trial, &res.exceptional);
    if (hertz && trial)
        res.exceptional |= starting;
    const bdl_vec3 u_before = u; // a step ago, in this step's plane
    // The spring stretches only while in contact: in the step where the contact began, for the
    // fraction of it in contact (else the first increment, and with it the tangential rebound,
    // would depend on where in the step the contact began: a first-order error).
    u = bdl_v3_madd(u, vt, dt * in_contact);
    double eta_t = cp->tangential_damping_ratio * eta;
    bdl_vec3 ft = bdl_v3_add(bdl_v3_scale(u, -kt), bdl_v3_scale(vt, -eta_t));
    double ft2 = bdl_v3_len2(ft);
    double limit = cp->friction * (fn > 0.0 ? fn : 0.0);
    // Sliding: the force is scaled back to the Coulomb cone, and the spring alone carries the
    // capped force. (Leaving the dashpot's share in it would make the spring point against the
    // slip, and with the Mindlin stiffness growing as the overlap does it would push along the
    // slip on the next step.)
    // One reciprocal serves both: F_t limit / |F_t| and u = -F_t limit / (|F_t| k_t).
    int slide = ft2 > limit * limit;
    double ftl = sqrt(ft2);
    double kt_or_1 = kt > 0.0 ? kt : 1.0;
    double r = 1.0 / (ftl * kt_or_1);
    bdl_vec3 capped = bdl_v3_select(ftl > 0.0, bdl_v3_scale(ft, limit * kt_or_1 * r), ft);
    bdl_vec3 u_capped = bdl_v3_select(kt > 0.0, bdl_v3_scale(ft, -limit * r), bdl_v3_zero());
    ft = bdl_v3_select(slide, capped, ft);
    u = bdl_v3_select(slide, u_capped, u);
    res.spring.u = u;
    if (hertz)
        res.spring.work += bdl_spring_work_step(cp, g->r_eff, g->overlap - onset, kt, u_before, u);
    res.force = bdl_v3_add(res.force, ft);
    res.n_x_ft = bdl_v3_cross(g->n, ft);
    return res;
}

/// The full contact law (see bdl_contact_eval_mode).
static BDL_FORCE_INLINE bdl_contact_result bdl_contact_eval(const bdl_contact_params *cp, int hertz,
                                                            int friction, bdl_contact_geom geom,
                                                            bdl_spring spring, double dt)
{
    return bdl_contact_eval_mode(cp, hertz, friction, geom, spring, dt, 0);
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

/// Elastic energy stored in a contact [J]: the normal spring's potential, and the tangential
/// spring's (zero without friction): 1/2 k_t |u|^2 for the linear law, the work booked in the
/// spring for Mindlin's (see the head of this file).
static inline double bdl_contact_elastic_energy(const bdl_contact_params *cp, int hertz,
                                                double overlap, double r_eff, bdl_spring spring)
{
    if (hertz)
        return (8.0 / 15.0) * cp->e_star * sqrt(r_eff) * pow(overlap, 2.5) + spring.work;
    return 0.5 * cp->kn * overlap * overlap + 0.5 * cp->kt * bdl_v3_dot(spring.u, spring.u);
}

#endif
