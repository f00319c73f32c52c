// Contact parameter tables and the restitution <-> damping relations.
//
// The normal force never pulls: F_n = max(0, k(delta) delta - eta(delta) v_n). A damped contact
// therefore ends when the force reaches zero (slightly before the overlap does), and the classic
// closed forms, which let the force turn attractive, are only approximate at low restitution.
// We solve for the damping coefficient that realises the configured e with the clamp included.
//
// Dimensionless impacts (x: overlap, unit approach speed, e = -x' at the end of contact):
//   linear, t scaled by 1/omega_0, delta by v/omega_0:   x'' = -x - 2 zeta x'
//   Hertz,  k_h = (4/3) E* sqrt(R*), delta* = (m* v^2/k_h)^(2/5), t* = delta*/v:
//                                                         x'' = -x^(3/2) - c x^(1/4) x'
// Either way e depends on the damping coefficient alone (not on the impact speed), so it is
// computed once per distinct restitution value with classical RK4 and inverted by bisection.
#include "dem/material.h"
#include "dem/species.h"
#include "dem/walls.h"

#include <math.h>

#define PI 3.14159265358979323846

double bdl_linear_damping_ratio(double restitution)
{
    double l = log(restitution);
    return -l / sqrt(PI * PI + l * l);
}

double bdl_hertz_damping_closed_form(double restitution)
{
    return sqrt(5.0) * bdl_linear_damping_ratio(restitution);
}

/// Acceleration and (clamped) contact force of the dimensionless impact.
static double impact_accel(int hertz, double c, double x, double v)
{
    double xp = x > 0.0 ? x : 0.0;
    double f = hertz ? xp * sqrt(xp) + c * sqrt(sqrt(xp)) * v : xp + 2.0 * c * v;
    return f > 0.0 ? -f : 0.0;
}

/// Integrates the dimensionless impact; returns e and, in *duration, the contact time in the
/// impact's own time unit.
static double impact(int hertz, double c, double h, double *duration)
{
    double x = 0.0, v = 1.0;
    for (long step = 0; step < 50000000L; ++step) {
        double k1x = v, k1v = impact_accel(hertz, c, x, v);
        double k2x = v + 0.5 * h * k1v, k2v = impact_accel(hertz, c, x + 0.5 * h * k1x, k2x);
        double k3x = v + 0.5 * h * k2v, k3v = impact_accel(hertz, c, x + 0.5 * h * k2x, k3x);
        double k4x = v + h * k3v, k4v = impact_accel(hertz, c, x + h * k3x, k4x);
        double xn = x + h / 6.0 * (k1x + 2.0 * k2x + 2.0 * k3x + k4x);
        double vn = v + h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v);
        // Contact ends when the overlap closes or the clamped force has released the body
        // (moving apart with zero force: the speed no longer changes).
        if (step > 0 && (xn <= 0.0 || (vn < 0.0 && impact_accel(hertz, c, xn, vn) == 0.0))) {
            *duration = (double)(step + 1) * h;
            return vn < 0.0 ? -vn : 0.0;
        }
        x = xn;
        v = vn;
    }
    *duration = INFINITY;
    return 0.0;
}

double bdl_restitution_of(int hertz, double c)
{
    double duration;
    return impact(hertz, c, 2.0e-4, &duration);
}

double bdl_contact_duration_ratio(int hertz, double c)
{
    double damped, elastic;
    impact(hertz, c, 2.0e-4, &damped);
    impact(hertz, 0.0, 2.0e-4, &elastic);
    return damped / elastic;
}

/// Damping coefficient (zeta or c) that realises restitution e with the clamped force: e(c) is
/// smooth and decreasing, so a bracketing secant (Illinois) search converges in a few dozen
/// impacts.
static double damping_exact(int hertz, double restitution)
{
    if (restitution >= 1.0)
        return 0.0;
    double guess =
        hertz ? bdl_hertz_damping_closed_form(restitution) : bdl_linear_damping_ratio(restitution);
    double lo = 0.0, hi = 2.0 * guess + 0.1;
    double flo = 1.0 - restitution, fhi = bdl_restitution_of(hertz, hi) - restitution;
    while (fhi > 0.0 && hi < 1e6) {
        lo = hi;
        flo = fhi;
        hi *= 2.0;
        fhi = bdl_restitution_of(hertz, hi) - restitution;
    }
    int side = 0;
    double mid = 0.5 * (lo + hi);
    for (int it = 0; it < 100; ++it) {
        mid = (lo * fhi - hi * flo) / (fhi - flo);
        double fm = bdl_restitution_of(hertz, mid) - restitution;
        if (fabs(fm) < 1e-13 || hi - lo < 1e-13 * hi)
            break;
        if (fm > 0.0) {
            lo = mid;
            flo = fm;
            if (side == 1)
                fhi *= 0.5;
            side = 1;
        } else {
            hi = mid;
            fhi = fm;
            if (side == -1)
                flo *= 0.5;
            side = -1;
        }
    }
    return mid;
}

static double mean2(double a, double b) { return 0.5 * (a + b); }

BDL_CHOICE_WORDS(bdl_normal_law, BDL_NORMAL_LAWS);
BDL_CHOICE_WORDS(bdl_damping_mode, BDL_DAMPING_MODES);
BDL_CHOICE_WORDS(bdl_rolling_model, BDL_ROLLING_MODELS);

static double pick(double wall_value, double particle_value)
{
    return wall_value >= 0.0 ? wall_value : particle_value;
}

static double shear_modulus(double e, double nu) { return e / (2.0 * (1.0 + nu)); }

/// Hertz damping coefficients are memoised per restitution value: solving takes milliseconds.
typedef struct damping_cache {
    int count;
    double e[BDL_MAX_SPECIES * BDL_MAX_SPECIES + BDL_MAX_WALLS * BDL_MAX_SPECIES];
    double c[BDL_MAX_SPECIES * BDL_MAX_SPECIES + BDL_MAX_WALLS * BDL_MAX_SPECIES];
} damping_cache;

static double damping_for(const bdl_contact_table_def *def, damping_cache *cache, double e)
{
    int hertz = def->law == BDL_LAW_HERTZ;
    if (def->damping == BDL_DAMPING_CLOSED_FORM)
        return hertz ? bdl_hertz_damping_closed_form(e) : bdl_linear_damping_ratio(e);
    for (int k = 0; k < cache->count; ++k)
        if (cache->e[k] == e)
            return cache->c[k];
    double c = damping_exact(hertz, e);
    cache->e[cache->count] = e;
    cache->c[cache->count] = c;
    cache->count++;
    return c;
}

static double linear_kt(const bdl_material *m)
{
    return m->tangential_stiffness >= 0.0 ? m->tangential_stiffness : 2.0 / 7.0 * m->stiffness;
}

static void mix_pair(const bdl_material *a, const bdl_material *b, bdl_contact_params *cp)
{
    cp->kn = 2.0 * a->stiffness * b->stiffness / (a->stiffness + b->stiffness);
    double kta = linear_kt(a), ktb = linear_kt(b);
    cp->kt = kta + ktb > 0.0 ? 2.0 * kta * ktb / (kta + ktb) : 0.0;
    cp->e_star = 1.0 / ((1.0 - a->poisson_ratio * a->poisson_ratio) / a->youngs_modulus +
                        (1.0 - b->poisson_ratio * b->poisson_ratio) / b->youngs_modulus);
    cp->g_star =
        1.0 / ((2.0 - a->poisson_ratio) / shear_modulus(a->youngs_modulus, a->poisson_ratio) +
               (2.0 - b->poisson_ratio) / shear_modulus(b->youngs_modulus, b->poisson_ratio));
    cp->restitution = mean2(a->restitution, b->restitution);
    cp->friction = mean2(a->friction, b->friction);
    cp->rolling_friction = mean2(a->rolling_friction, b->rolling_friction);
    cp->tangential_damping_ratio = mean2(a->tangential_damping_ratio, b->tangential_damping_ratio);
}

/// The wall's effective material: every key not given falls back to the particle's.
static bdl_material wall_material(const bdl_material *w, const bdl_material *p)
{
    bdl_material m;
    m.youngs_modulus = pick(w->youngs_modulus, p->youngs_modulus);
    m.poisson_ratio = pick(w->poisson_ratio, p->poisson_ratio);
    m.stiffness = pick(w->stiffness, p->stiffness);
    m.tangential_stiffness = w->tangential_stiffness >= 0.0 ? w->tangential_stiffness
                             : w->stiffness >= 0.0          ? -1.0
                                                            : p->tangential_stiffness;
    m.restitution = pick(w->restitution, p->restitution);
    m.tangential_damping_ratio = pick(w->tangential_damping_ratio, p->tangential_damping_ratio);
    m.friction = pick(w->friction, p->friction);
    m.rolling_friction = pick(w->rolling_friction, p->rolling_friction);
    return m;
}

/// A wall is a body of infinite stiffness ratio one: E* and k_n use the wall's own value on the
/// wall side, so a wall of the particle's material gives the same contact as two particles.
static void mix_wall(const bdl_material *w, const bdl_material *p, bdl_contact_params *cp)
{
    bdl_material m = wall_material(w, p);
    mix_pair(&m, p, cp);
    // Wall-side restitution and friction replace the mean when given: they describe the contact.
    cp->restitution = m.restitution;
    cp->friction = m.friction;
    cp->rolling_friction = m.rolling_friction;
    cp->tangential_damping_ratio = m.tangential_damping_ratio;
}

static void apply_override(const bdl_pair_def *o, bdl_contact_params *cp)
{
    if (o->has_restitution)
        cp->restitution = o->restitution;
    if (o->has_friction)
        cp->friction = o->friction;
    if (o->has_rolling_friction)
        cp->rolling_friction = o->rolling_friction;
    if (o->has_stiffness) {
        cp->kt = cp->kn > 0.0 ? cp->kt * o->stiffness / cp->kn : 2.0 / 7.0 * o->stiffness;
        cp->kn = o->stiffness;
    }
}

void bdl_contact_table_build(const bdl_contact_table_def *def, bdl_contact_params *pair_params,
                             bdl_contact_params *wall_params)
{
    static const bdl_contact_params zero = {0};
    damping_cache cache = {0};
    int ns = def->species_count;
    for (int a = 0; a < ns; ++a)
        for (int b = 0; b < ns; ++b) {
            bdl_contact_params cp = zero;
            mix_pair(&def->species[a], &def->species[b], &cp);
            for (int k = 0; k < def->pair_count; ++k) {
                const bdl_pair_def *o = &def->pairs[k];
                if ((o->species_a == a && o->species_b == b) ||
                    (o->species_a == b && o->species_b == a))
                    apply_override(o, &cp);
            }
            cp.damping = damping_for(def, &cache, cp.restitution);
            cp.duration_ratio = bdl_contact_duration_ratio(def->law == BDL_LAW_HERTZ, cp.damping);
            pair_params[a * ns + b] = cp;
        }
    for (int w = 0; w < def->wall_count; ++w)
        for (int s = 0; s < ns; ++s) {
            bdl_contact_params cp = zero;
            mix_wall(&def->walls[w], &def->species[s], &cp);
            cp.damping = damping_for(def, &cache, cp.restitution);
            cp.duration_ratio = bdl_contact_duration_ratio(def->law == BDL_LAW_HERTZ, cp.damping);
            wall_params[w * ns + s] = cp;
        }
}

double bdl_contact_time(const bdl_contact_params *cp, bdl_normal_law law, double m_eff,
                        double r_eff, double impact_speed)
{
    double ratio = cp->duration_ratio > 0.0 ? cp->duration_ratio : 1.0;
    if (law == BDL_LAW_LINEAR)
        return ratio * PI * sqrt(m_eff / cp->kn);
    double v = impact_speed > 1e-12 ? impact_speed : 1e-12;
    return ratio * 2.87 * pow(m_eff * m_eff / (r_eff * cp->e_star * cp->e_star * v), 0.2);
}
