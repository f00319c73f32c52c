// bedlam — closures of a solids phase on the grid (solids/kinetic.h).
#include "solids/kinetic.h"

#include <math.h>

static const double pi = 3.14159265358979323846;

double bdl_g0_carnahan_starling(double eps)
{
    const double g = 1.0 - eps;
    return (1.0 - 0.5 * eps) / (g * g * g);
}

double bdl_g0_lebowitz(const double *eps, const double *d, int count, int l, int m)
{
    double solids = 0.0, s = 0.0;
    for (int k = 0; k < count; ++k) {
        solids += eps[k];
        s += eps[k] / d[k];
    }
    const double gas = 1.0 - solids;
    return 1.0 / gas + 3.0 * d[l] * d[m] * s / (gas * gas * (d[l] + d[m]));
}

bdl_ktgf_coefficients bdl_ktgf_syamlal(double eps, double d, double rho, double e)
{
    return bdl_ktgf_syamlal_g0(eps, bdl_g0_carnahan_starling(eps), d, rho, e);
}

bdl_ktgf_coefficients bdl_ktgf_syamlal_g0(double eps, double g0, double d, double rho, double e)
{
    bdl_ktgf_coefficients c;
    c.g0 = g0;
    const double eg = eps * c.g0, sqrt_pi = sqrt(pi);
    c.k1 = 2.0 * (1.0 + e) * rho * c.g0;
    c.k3 = 0.5 * d * rho *
           (sqrt_pi / (3.0 * (3.0 - e)) * (1.0 + 0.4 * (1.0 + e) * (3.0 * e - 1.0) * eg) +
            8.0 * eg * (1.0 + e) / (5.0 * sqrt_pi));
    c.k2 = 4.0 * d * rho * (1.0 + e) * eg / (3.0 * sqrt_pi) - 2.0 / 3.0 * c.k3;
    c.k4 = 12.0 * (1.0 - e * e) * rho * c.g0 / (sqrt_pi * d);
    return c;
}

bdl_ktgf_factors bdl_ktgf_syamlal_factors(double d, double rho, double e)
{
    const double sqrt_pi = sqrt(pi), dilute = sqrt_pi / (3.0 * (3.0 - e));
    bdl_ktgf_factors f;
    f.k1 = 2.0 * (1.0 + e) * rho;
    f.k3 = 0.5 * d * rho * dilute;
    f.k3_dense = 0.5 * d * rho *
                 (dilute * 0.4 * (1.0 + e) * (3.0 * e - 1.0) + 8.0 * (1.0 + e) / (5.0 * sqrt_pi));
    f.k2_dense = 4.0 * d * rho * (1.0 + e) / (3.0 * sqrt_pi);
    f.k4 = 12.0 * (1.0 - e * e) * rho / (sqrt_pi * d);
    return f;
}

double bdl_ktgf_conductivity(double eps, double g0, double d, double rho, double e, double theta,
                             double beta)
{
    if (!(theta > 0.0))
        return 0.0;
    const double eta = 0.5 * (1.0 + e), q = 41.0 - 33.0 * eta;
    const double k = 75.0 * rho * d * sqrt(pi * theta) / (48.0 * eta * q);
    const double held = rho * rho * eps * eps * g0 * theta; // K* = K held / (held + 1.2 beta K)
    const double k_star = k * held / (held + 1.2 * beta * k);
    return k_star *
           ((1.0 / g0 + 2.4 * eta * eps) * (1.0 + 2.4 * eta * eta * (4.0 * eta - 3.0) * eps * g0) +
            64.0 / (25.0 * pi) * q * eta * eta * eps * eps * g0);
}

double bdl_ktgf_shear_temperature(double eps, double d, double rho, double e, double shear_rate)
{
    const bdl_ktgf_coefficients c = bdl_ktgf_syamlal(eps, d, rho, e);
    return c.k3 * shear_rate * shear_rate / (c.k4 * eps);
}

/// The root x = sqrt(theta) >= 0 of f(x) = a3 x^3 + a2 x^2 - a1 x - a0 with a3 > 0 and a0 >= 0
/// (f(0) <= 0, f -> +inf; the signs of the coefficients change once: it is the only positive
/// root). Newton's steps from `guess` (the last step's root, which is near), kept inside the
/// bracket [lo, hi] their signs of f give (bisected, or doubled while no f > 0 is known, where a
/// step would leave it). Newton's error squares each step, so a Newton step below 10^-7 of x
/// leaves one of the order of 10^-14: it is the last.
static double cubic_root(double a3, double a2, double a1, double a0, double guess)
{
    if (!(a0 > 0.0) && !(a1 > 0.0) && a2 >= 0.0)
        return 0.0; // f > 0 for every x > 0
    double lo = 0.0, hi = INFINITY, x = guess > 1e-12 ? guess : 1.0;
    for (int k = 0; k < 200; ++k) {
        const double f = ((a3 * x + a2) * x - a1) * x - a0, df = (3.0 * a3 * x + 2.0 * a2) * x - a1;
        if (f > 0.0)
            hi = x;
        else if (f < 0.0)
            lo = x;
        else
            return f == 0.0 ? x : NAN; // NaN coefficients give NaN
        const double next = df > 0.0 ? x - f / df : NAN;
        if (!(next > lo && next < hi)) {
            x = hi < INFINITY ? 0.5 * (lo + hi) : 2.0 * x;
            continue;
        }
        if (fabs(next - x) <= 1e-7 * next)
            return next;
        x = next;
    }
    return x;
}

double bdl_ktgf_temperature_step(const bdl_ktgf_coefficients *c, double eps, double rho,
                                 double trace, double ddot, double theta_old, double dt)
{
    const double inertia = 1.5 * rho / dt; // 0 for dt = INFINITY: the algebraic balance
    const double q = 2.0 * c->k3 * ddot + c->k2 * trace * trace;
    const double x = cubic_root(c->k4 * eps, inertia + c->k1 * eps * trace, q, inertia * theta_old,
                                sqrt(theta_old));
    return x * x;
}

double bdl_schaeffer_pressure(double eps_s, double eps_g, double eps_g_star, double a, double n)
{
    return eps_g < eps_g_star ? eps_s * a * pow(eps_g_star - eps_g, n) : 0.0;
}

double bdl_schaeffer_viscosity(double pressure, double phi, double i2d, double mu_max)
{
    if (!(i2d > 0.0))
        return pressure > 0.0 ? mu_max : 0.0;
    return fmin(pressure * sin(phi) / (2.0 * sqrt(i2d)), mu_max);
}

bdl_jenkins_zhang bdl_jenkins_zhang_effective(double e, double mu, double beta0)
{
    bdl_jenkins_zhang j = {.e_eff = e};
    if (!(mu > 0.0))
        return j; // smooth spheres: no rotational dissipation, e unchanged
    const double m0 = 3.5 * mu * (1.0 + e) / (1.0 + beta0), r = mu / m0, m2 = m0 * m0;
    const double slide = m0 * (1.0 - 2.0 / pi * atan(m0)); // mu0 (1 - (2/pi) atan mu0)
    j.mu0 = m0;
    j.a1 = r * (pi * slide + 2.0 * m2 / (1.0 + m2) * (1.0 - 2.0 * r));
    j.a2 = 5.0 * r * (0.5 * pi * slide - m2 * m2 / ((1.0 + m2) * (1.0 + m2)));
    j.b1 = r * r * m2 / (1.0 + m2);
    j.b2 = 0.5 * r * (0.5 * pi * slide + m2 / (1.0 + m2));
    j.temperature_ratio = j.b1 / j.b2;
    j.e_eff = e - 0.5 * j.a1 + 0.5 * j.a2 * j.temperature_ratio;
    return j;
}

double bdl_solids_drag_syamlal(double e, double cf, double g0, double d_l, double rho_l, double d_m,
                               double rho_m, double speed)
{
    const double ds = d_l + d_m;
    return 3.0 * (1.0 + e) * (0.5 * pi + cf * pi * pi / 8.0) * rho_l * rho_m * ds * ds * g0 *
           speed / (2.0 * pi * (rho_l * d_l * d_l * d_l + rho_m * d_m * d_m * d_m));
}
