// The closures of a solids phase (solids/kinetic.h): Jenkins & Zhang's effective restitution
// against the segregation thesis's table 5.1, the radial distribution functions against the
// exact first-order term of hard spheres (from their third virial coefficient) and each other,
// Syamlal's collisional pressure against Lun et al.'s, the simple-shear temperature's balance and
// scaling, and Schaeffer's plastic regime.
#include <math.h>
#include <stdio.h>

#include "analysis/rheology.h"
#include "check.h"
#include "solids/kinetic.h"

/// Sun (2007) table 5.1: e = 0.97, beta0 = 0.33; particles with friction 0.15 (small) and 0.10
/// (large), walls 0.10 and 0.09: e_eff 0.83, 0.86, 0.86, 0.87 to the two digits printed. The
/// intermediate terms of the small particles' case as evaluated from eqs. 5.12-5.18.
static void test_jenkins_zhang(void)
{
    const double mu[4] = {0.15, 0.10, 0.10, 0.09}, table[4] = {0.83, 0.86, 0.86, 0.87};
    for (int k = 0; k < 4; ++k) {
        const bdl_jenkins_zhang j = bdl_jenkins_zhang_effective(0.97, mu[k], 0.33);
        printf("friction %.2f: mu0 %.4f, e_eff %.4f (table 5.1: %.2f)\n", mu[k], j.mu0, j.e_eff,
               table[k]);
        CHECK(fabs(j.e_eff - table[k]) < 0.005);
    }
    const bdl_jenkins_zhang s = bdl_jenkins_zhang_effective(0.97, 0.15, 0.33);
    CHECK(fabs(s.mu0 - 0.7776) < 1e-4);
    CHECK(fabs(s.a1 - 0.3622) < 1e-4);
    CHECK(fabs(s.a2 - 0.5454) < 1e-4);
    CHECK(fabs(s.b1 - 0.0140) < 1e-4);
    CHECK(fabs(s.b2 - 0.1046) < 1e-4);
    CHECK(fabs(s.temperature_ratio - 0.134) < 1e-3);
    CHECK(fabs(bdl_jenkins_zhang_effective(0.97, 0.10, 0.33).mu0 - 0.5184) < 1e-4);
    // Smooth spheres keep their restitution; more friction dissipates more.
    CHECK(bdl_jenkins_zhang_effective(0.9, 0.0, 0.33).e_eff == 0.9);
    CHECK(bdl_jenkins_zhang_effective(0.97, 0.15, 0.33).e_eff <
          bdl_jenkins_zhang_effective(0.97, 0.05, 0.33).e_eff);
}

/// Both radial distributions start as 1 + 2.5 eps, exact for hard spheres (Z = 1 + 4 eps + 10 eps^2
/// + ..., g0 = (Z - 1) / (4 eps)); values at 0.4 and 0.45 by hand; Lebowitz's mixture of two phases
/// of one diameter is its one-phase value at the total solids fraction, for any split, and grows
/// for the pair of the larger particles.
static void test_g0(void)
{
    CHECK(bdl_g0_carnahan_starling(0.0) == 1.0);
    const double eps = 1e-5, one_d = 0.002;
    CHECK_CLOSE((bdl_g0_carnahan_starling(eps) - 1.0) / eps, 2.5, 1e-4);
    CHECK_CLOSE((bdl_g0_lebowitz(&eps, &one_d, 1, 0, 0) - 1.0) / eps, 2.5, 1e-4);
    CHECK_CLOSE(bdl_g0_carnahan_starling(0.3), 0.85 / (0.7 * 0.7 * 0.7), 1e-14);
    CHECK_CLOSE(bdl_g0_carnahan_starling(0.4), 3.7037037, 1e-7);
    const double at = 0.45;
    CHECK_CLOSE(bdl_g0_lebowitz(&at, &one_d, 1, 0, 0), 4.0495868, 1e-7); // 1/0.55 + 0.675/0.55^2
    const double split[2] = {0.1, 0.35}, same_d[2] = {0.002, 0.002}, total = 0.45;
    const double one = bdl_g0_lebowitz(&total, same_d, 1, 0, 0);
    CHECK_CLOSE(bdl_g0_lebowitz(split, same_d, 2, 0, 1), one, 1e-14);
    CHECK_CLOSE(bdl_g0_lebowitz(split, same_d, 2, 1, 1), one, 1e-14);
    const double d[2] = {0.00152, 0.00249};
    CHECK(bdl_g0_lebowitz(split, d, 2, 1, 1) > bdl_g0_lebowitz(split, d, 2, 0, 1));
    CHECK(bdl_g0_lebowitz(split, d, 2, 0, 1) > bdl_g0_lebowitz(split, d, 2, 0, 0));
}

/// Syamlal's pressure K1 eps^2 theta is the collisional part of Lun et al.'s, p - rho eps T, at
/// any state (analysis/rheology.h has Lun's simple shear).
static void test_pressure_against_lun(void)
{
    const double eps[3] = {0.1, 0.3, 0.5}, e[3] = {0.7, 0.9, 0.97};
    const double d = 0.0025, rho = 2526.0;
    for (int k = 0; k < 3; ++k) {
        const bdl_lun_state lun = bdl_lun_simple_shear(eps[k], e[k], d, rho, 40.0);
        const bdl_ktgf_coefficients c = bdl_ktgf_syamlal(eps[k], d, rho, e[k]);
        CHECK_CLOSE(c.g0, lun.g0, 1e-14);
        CHECK_CLOSE(c.k1 * eps[k] * eps[k] * lun.temperature,
                    lun.pressure - rho * eps[k] * lun.temperature, 1e-12);
    }
}

/// The simple-shear temperature balances production and dissipation, scales as (rate d)^2
/// (Bagnold), and grows without bound as the collisions become elastic.
static void test_shear_temperature(void)
{
    const double eps = 0.4, d = 0.0025, rho = 2526.0, e = 0.9, rate = 20.0;
    const double t = bdl_ktgf_shear_temperature(eps, d, rho, e, rate);
    const bdl_ktgf_coefficients c = bdl_ktgf_syamlal(eps, d, rho, e);
    CHECK_CLOSE(c.k3 * eps * sqrt(t) * rate * rate, c.k4 * eps * eps * pow(t, 1.5), 1e-12);
    CHECK_CLOSE(bdl_ktgf_shear_temperature(eps, 2.0 * d, rho, e, 3.0 * rate), 36.0 * t, 1e-12);
    CHECK_CLOSE(bdl_ktgf_shear_temperature(eps, d, 2.0 * rho, e, rate), t, 1e-12);
    CHECK(bdl_ktgf_shear_temperature(eps, d, rho, 0.99, rate) >
          5.0 * bdl_ktgf_shear_temperature(eps, d, rho, 0.9, rate));
    // K2 and K3 at eps 0.4, e 0.9, 2.5 mm, 2526 kg/m^3, evaluated by hand from eqs. 3.23-3.25.
    CHECK_CLOSE(c.k3, 10.611706, 1e-6);
    CHECK_CLOSE(c.k2, 6.297240, 1e-6);
    CHECK(c.k1 > 0.0 && c.k4 > 0.0);
    // The second viscosity lambda = K2 eps sqrt(theta) turns negative in a dilute phase.
    CHECK(bdl_ktgf_syamlal(0.05, d, rho, e).k2 < 0.0);
}

/// The cell's energy balance in time (the solver's, solids/phase.c): under simple shear v_x =
/// rate z (D:D = rate^2 / 2, tr D = 0) its steady state and its dt -> infinity form are the
/// closed-form temperature; without shear it cools by Haff's law, theta0 / (1 + t / tau)^2 with
/// tau = 3 rho / (k4 eps sqrt(theta0)) (Haff 1983), to first order in dt.
static void test_energy_balance(void)
{
    const double eps = 0.4, d = 0.0025, rho = 2526.0, e = 0.9, rate = 20.0;
    const bdl_ktgf_coefficients c = bdl_ktgf_syamlal(eps, d, rho, e);
    const double shear = bdl_ktgf_shear_temperature(eps, d, rho, e, rate), ddot = 0.5 * rate * rate;
    CHECK_CLOSE(bdl_ktgf_temperature_step(&c, eps, rho, 0.0, ddot, 0.0, INFINITY), shear, 1e-12);
    const double tau = 3.0 * rho / (c.k4 * eps * sqrt(shear));
    double theta = 0.0;
    for (int n = 0; n < 400; ++n)
        theta = bdl_ktgf_temperature_step(&c, eps, rho, 0.0, ddot, theta, 0.1 * tau);
    printf("simple shear at %g/s: steady theta %.10g m^2/s^2, closed form %.10g\n", rate, theta,
           shear);
    CHECK_CLOSE(theta, shear, 1e-10);
    double err[3];
    for (int m = 0; m < 3; ++m) {
        const int per_tau = 10 << m;
        theta = shear;
        for (int n = 0; n < 3 * per_tau; ++n)
            theta = bdl_ktgf_temperature_step(&c, eps, rho, 0.0, 0.0, theta, tau / per_tau);
        err[m] = fabs(theta * 16.0 / shear - 1.0); // Haff at t = 3 tau: theta0 / 16
    }
    const double order = log2(err[1] / err[2]);
    printf("homogeneous cooling to 3 tau: errors %.3e %.3e %.3e at 10, 20, 40 steps per tau, "
           "order %.3f\n",
           err[0], err[1], err[2], order);
    CHECK(err[2] < 0.05 && order > 0.9 && order < 1.1);
}

/// Schaeffer: no plastic pressure at or above the critical gas fraction, growing as the bed is
/// squeezed; the viscosity carries P sin(phi) over 2 sqrt(I2D), capped.
static void test_schaeffer(void)
{
    const double a = 1e24, n = 10.0, star = 0.42;
    CHECK(bdl_schaeffer_pressure(0.58, 0.42, star, a, n) == 0.0);
    CHECK(bdl_schaeffer_pressure(0.50, 0.50, star, a, n) == 0.0);
    const double p1 = bdl_schaeffer_pressure(0.59, 0.41, star, a, n);
    const double p2 = bdl_schaeffer_pressure(0.60, 0.40, star, a, n);
    CHECK_CLOSE(p1, 0.59 * a * pow(0.01, n), 1e-12);
    CHECK(p2 > p1 * 1000.0);
    const double phi = 30.0 * 3.14159265358979323846 / 180.0;
    CHECK_CLOSE(bdl_schaeffer_viscosity(p1, phi, 4.0, 1e9) * 2.0 * 2.0, p1 * 0.5, 1e-12);
    CHECK(bdl_schaeffer_viscosity(p1, phi, 0.0, 100.0) == 100.0);
    CHECK(bdl_schaeffer_viscosity(p1, phi, 1e-30, 100.0) == 100.0);
    CHECK(bdl_schaeffer_viscosity(0.0, phi, 0.0, 100.0) == 0.0);
}

/// Lun et al.'s conductivity with Ma & Ahmadi's gas correction: at no drag the dilute limit
/// 75 rho d sqrt(pi theta) / (48 eta (41 - 33 eta)) / g0 times its bracket; the drag's reduction
/// K* = K / (1 + 1.2 beta K / (rho^2 eps^2 g0 theta)); zero at zero temperature.
static void test_conductivity(void)
{
    const double eps = 0.35, d = 2.49e-3, rho = 2526.0, e = 0.9, theta = 0.02,
                 pi = 3.141592653589793;
    const double g0 = bdl_g0_carnahan_starling(eps), eta = 0.95;
    const double k = 75.0 * rho * d * sqrt(pi * theta) / (48.0 * eta * (41.0 - 33.0 * eta));
    const double bracket = (1.0 / g0 + 12.0 / 5.0 * eta * eps) *
                               (1.0 + 12.0 / 5.0 * eta * eta * (4.0 * eta - 3.0) * eps * g0) +
                           64.0 / (25.0 * pi) * (41.0 - 33.0 * eta) * eta * eta * eps * eps * g0;
    CHECK_CLOSE(bdl_ktgf_conductivity(eps, g0, d, rho, e, theta, 0.0), k * bracket, 1e-13);
    const double beta = 3e4,
                 reduced = k / (1.0 + 1.2 * beta * k / (rho * rho * eps * eps * g0 * theta));
    CHECK_CLOSE(bdl_ktgf_conductivity(eps, g0, d, rho, e, theta, beta), reduced * bracket, 1e-13);
    CHECK(bdl_ktgf_conductivity(eps, g0, d, rho, e, 0.0, beta) == 0.0);
    printf("conductivity at eps %.2f, theta %.2f: %.4f kg/(m s) without drag, %.4f with beta %g\n",
           eps, theta, k * bracket, reduced * bracket, beta);
}

/// The coefficients from the particles' factors (the form the cell loops use) are Syamlal's to
/// round-off, from dilute to dense, for elastic and inelastic spheres.
static void test_factors(void)
{
    const double d = 2.49e-3, rho = 2526.0, e[3] = {1.0, 0.97, 0.7};
    double worst = 0.0;
    for (int q = 0; q < 3; ++q) {
        const bdl_ktgf_factors f = bdl_ktgf_syamlal_factors(d, rho, e[q]);
        for (double eps = 1e-4; eps < 0.63; eps += 0.0137) {
            const double g0 = bdl_g0_carnahan_starling(eps);
            const bdl_ktgf_coefficients a = bdl_ktgf_syamlal_at(&f, eps, g0),
                                        b = bdl_ktgf_syamlal_g0(eps, g0, d, rho, e[q]);
            const double got[5] = {a.g0, a.k1, a.k2, a.k3, a.k4},
                         want[5] = {b.g0, b.k1, b.k2, b.k3, b.k4};
            for (int k = 0; k < 5; ++k) {
                CHECK_CLOSE(got[k], want[k], 1e-13);
                if (want[k] != 0.0)
                    worst = fmax(worst, fabs(got[k] / want[k] - 1.0));
            }
        }
    }
    printf("Syamlal's coefficients from the particles' factors: worst relative difference %.2g\n",
           worst);
}

int main(void)
{
    test_factors();
    test_conductivity();
    test_jenkins_zhang();
    test_g0();
    test_pressure_against_lun();
    test_shear_temperature();
    test_energy_balance();
    test_schaeffer();
    return bdl_test_summary("test_kinetic");
}
