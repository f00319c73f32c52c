// The bulk stress of a shear cell (analysis/rheology.h) on constructed particles and contacts with
// known sums, and the kinetic theory of Lun et al. (1984) against identities it must satisfy.
#include <math.h>
#include <stdio.h>

#include "analysis/rheology.h"
#include "check.h"

static const double pi = 3.14159265358979323846;

/// Eight particles, two in each of four slabs of a 0.1 x 0.05 x 0.04 m region, on the profile
/// u_x = 50 z plus fluctuations (+-a, 0, +-c); a ninth above the region. Two contacts: one inside,
/// one with the particle outside (counted half).
static void test_stress(void)
{
    enum { N = 9 };
    bdl_vec3 pos[N], vel[N], axis[N];
    double mass[N], volume[N], diameter[N];
    const double a = 0.3, c = -0.2, rate = 50.0;
    for (int k = 0; k < 8; ++k) {
        const int slab = k / 2, sign = k % 2 ? -1 : 1;
        const double z = 0.005 + 0.01 * slab;
        pos[k] = bdl_v3(0.01 * k, 0.02, z);
        vel[k] = bdl_v3(rate * z + sign * a, 0.0, sign * c);
        mass[k] = 0.002;
        volume[k] = 1e-6;
        diameter[k] = 0.0124;
        axis[k] = bdl_v3(cos(20.0 * pi / 180.0), 0.0, sin(20.0 * pi / 180.0));
    }
    pos[8] = bdl_v3(0.05, 0.02, 0.045);
    vel[8] = bdl_v3(5.0, 5.0, 5.0);
    mass[8] = 1.0, volume[8] = 1.0, diameter[8] = 1.0, axis[8] = bdl_v3(0, 0, 1);
    const long ci[2] = {0, 1}, cj[2] = {2, 8};
    const bdl_vec3 branch[2] = {bdl_v3(0.001, 0.0, 0.004), bdl_v3(0.0, 0.0, -0.005)};
    const bdl_vec3 force[2] = {bdl_v3(2.0, 0.5, 8.0), bdl_v3(0.0, 0.0, -3.0)};
    bdl_rheology_input in = {.count = N,
                             .pos = pos,
                             .vel = vel,
                             .mass = mass,
                             .volume = volume,
                             .diameter = diameter,
                             .axis = axis,
                             .contacts = 2,
                             .ci = ci,
                             .cj = cj,
                             .branch = branch,
                             .force = force,
                             .x_length = 0.1,
                             .y_length = 0.05,
                             .z_lo = 0.0,
                             .z_hi = 0.04,
                             .bins = 4,
                             .rate = NAN};
    bdl_rheology_sample s;
    CHECK(bdl_rheology_measure(&in, &s) == 1);
    const double V = 0.1 * 0.05 * 0.04, m = 0.002;
    CHECK(s.particles == 8);
    CHECK_CLOSE(s.shear_rate, rate, 1e-12);
    CHECK_CLOSE(s.solids_fraction, 8e-6 / V, 1e-12);
    CHECK_CLOSE(s.temperature, (a * a + c * c) / 3.0, 1e-12);
    CHECK_CLOSE(s.streaming[0][0], 8 * m * a * a / V, 1e-12);
    CHECK_CLOSE(s.streaming[2][2], 8 * m * c * c / V, 1e-12);
    CHECK_CLOSE(s.streaming[0][2], 8 * m * a * c / V, 1e-12);
    CHECK(fabs(s.streaming[1][1]) < 1e-15);
    // contact: b1 f1 + b2 f2 / 2
    CHECK_CLOSE(s.contact[0][0], 0.001 * 2.0 / V, 1e-12);
    CHECK_CLOSE(s.contact[0][1], 0.001 * 0.5 / V, 1e-12);
    CHECK_CLOSE(s.contact[2][0], 0.004 * 2.0 / V, 1e-12);
    CHECK_CLOSE(s.contact[0][2], 0.001 * 8.0 / V, 1e-12);
    CHECK_CLOSE(s.contact[2][2], (0.004 * 8.0 + 0.5 * 0.005 * 3.0) / V, 1e-12);
    const double p_stream = 8 * m * (a * a + c * c) / (3 * V);
    const double p_contact = (0.001 * 2.0 + 0.004 * 8.0 + 0.5 * 0.015) / (3 * V);
    CHECK_CLOSE(s.pressure_streaming, p_stream, 1e-12);
    CHECK_CLOSE(s.pressure_contact, p_contact, 1e-12);
    CHECK_CLOSE(s.pressure, p_stream + p_contact, 1e-12);
    // tau = -(s_xz + s_zx)/2: streaming -8 m a c / V, contact -(0.008 + 0.008)/(2 V)
    CHECK_CLOSE(s.shear_streaming, -8 * m * a * c / V, 1e-12);
    CHECK_CLOSE(s.shear_contact, -(0.008 + 0.008) / (2 * V), 1e-12);
    CHECK_CLOSE(s.friction, s.shear_stress / s.pressure, 1e-12);
    CHECK_CLOSE(s.n1, s.stress[0][0] - s.stress[2][2], 1e-12);
    CHECK_CLOSE(s.n2, s.stress[2][2] - s.stress[1][1], 1e-12);
    CHECK_CLOSE(s.diameter, 0.0124, 1e-12);
    CHECK_CLOSE(s.density, m / 1e-6, 1e-12);
    CHECK_CLOSE(s.inertial_number, rate * 0.0124 * sqrt(2000.0 / s.pressure), 1e-12);
    CHECK_CLOSE(s.alignment, 20.0, 1e-9);
    // The same flow the other way round: the shear stress keeps its sign (it resists the shear).
    for (int k = 0; k < 8; ++k)
        vel[k].x = -vel[k].x;
    bdl_rheology_sample r;
    CHECK(bdl_rheology_measure(&in, &r) == 1);
    CHECK_CLOSE(r.shear_rate, -rate, 1e-12);
    CHECK_CLOSE(r.shear_streaming, s.shear_streaming, 1e-12);
    // An imposed rate replaces the slope (and only it).
    in.rate = -40.0;
    CHECK(bdl_rheology_measure(&in, &r) == 1);
    CHECK_CLOSE(r.shear_rate, -40.0, 1e-15);
    CHECK_CLOSE(r.temperature, s.temperature, 1e-12);
    in.rate = NAN;
    // Too few particles in the region: no sample.
    in.z_lo = 0.041;
    in.z_hi = 0.044;
    CHECK(bdl_rheology_measure(&in, &r) == 0 && isnan(r.pressure));
    printf("stress of the constructed bulk: p %.6g Pa (streaming %.6g, contact %.6g), tau %.6g Pa, "
           "T %.6g, alignment %.3f deg\n",
           s.pressure, s.pressure_streaming, s.pressure_contact, s.shear_stress, s.temperature,
           s.alignment);
}

/// Lun et al.'s simple shear: the Carnahan–Starling equation of state when elastic, production
/// balancing dissipation, the dilute limit, and a value at nu = 0.3, e = 0.7.
static void test_lun(void)
{
    const double d = 0.0053, rho = 1395.0, g = 100.0;
    for (double nu = 0.05; nu < 0.55; nu += 0.1) {
        const bdl_lun_state s = bdl_lun_simple_shear(nu, 0.9, d, rho, g);
        // at any e, the pressure's collisional factor with e = 1 is Carnahan–Starling's
        const double cs = (1 + nu + nu * nu - nu * nu * nu) / pow(1 - nu, 3);
        CHECK_CLOSE(1.0 + 4.0 * nu * s.g0, cs, 1e-12);
        // tau g = (48/sqrt(pi)) eta (1 - eta) rho nu^2 g0 T^1.5 / d, eta = 0.95
        const double gamma =
            48.0 / sqrt(pi) * 0.95 * 0.05 * rho * nu * nu * s.g0 * pow(s.temperature, 1.5) / d;
        CHECK_CLOSE(s.shear_stress * g, gamma, 1e-12);
    }
    // Dilute: tau -> (5 sqrt(pi)/96) rho d sqrt(T) g / (eta (2 - eta)).
    const bdl_lun_state dilute = bdl_lun_simple_shear(1e-7, 0.7, d, rho, g);
    CHECK_CLOSE(dilute.shear_stress,
                5.0 * sqrt(pi) / 96.0 * rho * d * sqrt(dilute.temperature) * g / (0.85 * 1.15),
                1e-5);
    // Bagnold: stresses scale with the shear rate squared.
    const bdl_lun_state a = bdl_lun_simple_shear(0.3, 0.7, d, rho, g);
    const bdl_lun_state b = bdl_lun_simple_shear(0.3, 0.7, d, rho, 3.0 * g);
    CHECK_CLOSE(b.pressure, 9.0 * a.pressure, 1e-12);
    CHECK_CLOSE(b.shear_stress, 9.0 * a.shear_stress, 1e-12);
    // nu = 0.3, e = 0.7, d = 5.3 mm, rho = 1395, 100/s (evaluated by hand from the formulas)
    CHECK_CLOSE(a.g0, 2.4781341107871726, 1e-12);
    CHECK_CLOSE(a.temperature, 0.10592377661895562, 1e-10);
    CHECK_CLOSE(a.pressure, 156.37962572358558, 1e-10);
    CHECK_CLOSE(a.shear_stress, 69.87668990708289, 1e-10);
    printf("Lun et al. at nu 0.3, e 0.7, 100/s: T %.6g, p %.6g Pa, tau %.6g Pa\n", a.temperature,
           a.pressure, a.shear_stress);
}

/// The jamming fit recovers nu_cr and A from points on the law, and from points with noise.
static void test_jamming(void)
{
    const double nu[5] = {0.3, 0.4, 0.5, 0.55, 0.57};
    double y[5], cr, a;
    for (int k = 0; k < 5; ++k)
        y[k] = 0.02 * pow(0.59 - nu[k], -4.0);
    double r = bdl_rheology_fit_jamming(nu, y, 5, 4.0, &cr, &a);
    CHECK_CLOSE(cr, 0.59, 1e-6);
    CHECK_CLOSE(a, 0.02, 1e-4);
    CHECK(r < 1e-6);
    const double noise[5] = {1.05, 0.96, 1.03, 0.98, 1.02};
    for (int k = 0; k < 5; ++k)
        y[k] *= noise[k];
    r = bdl_rheology_fit_jamming(nu, y, 5, 4.0, &cr, &a);
    printf("jamming fit with 5 %% noise: nu_cr %.4f (0.59), A %.4f (0.02), rms %.3f\n", cr, a, r);
    CHECK(fabs(cr - 0.59) < 0.005);
    CHECK(isnan(bdl_rheology_fit_jamming(nu, y, 2, 4.0, &cr, &a))); // too few points
    // With A known each point gives nu_cr alone: exact on the law, and a 5 % error in y moves it
    // by (0.59 - nu) / 4 * 5 %.
    for (int k = 0; k < 5; ++k) {
        const double exact = 0.02 * pow(0.59 - nu[k], -4.0);
        CHECK_CLOSE(bdl_rheology_jamming_point(nu[k], exact, 4.0, 0.02), 0.59, 1e-12);
        const double moved = bdl_rheology_jamming_point(nu[k], y[k], 4.0, 0.02) - 0.59;
        CHECK_CLOSE(moved, (0.59 - nu[k]) * (pow(noise[k], -0.25) - 1.0), 1e-12);
    }
    CHECK(isnan(bdl_rheology_jamming_point(0.5, 0.0, 4.0, 0.02)));
    CHECK(isnan(bdl_rheology_jamming_point(0.5, 1.0, 4.0, -1.0)));
}

/// The soft dense branch of eq. 6.3: its inertial limit is the law A D^-4 (slow shear, or a2 = 0);
/// an independent evaluation of the thesis's closure (friction 0.46, nu 0.5, nu_cr 0.59, 10/s:
/// P_c = 8.331 Pa); its peak where g** = b2 X / (a1 a2), of P** = (X / (2 b1 a2))^2; a pressure
/// taken from either side of the peak gives its nu_cr back; one above the peak is past jamming.
static void test_jamming_soft(void)
{
    const double d = 5.295e-3, rho = 1395.0, b2 = 82.64, a = 1.0 / (b2 * b2), a2 = 39.56;
    bdl_jamming_branch b = {4.0, a, a2, 6e5};
    const double slow = bdl_rheology_branch_pressure(&b, 0.1, 0.01, d, rho);
    CHECK_CLOSE(slow, a * rho * d * d * 1e-4 * pow(0.1, -4.0), 1e-3);
    CHECK_CLOSE(bdl_rheology_branch_pressure(&b, 0.09, 10.0, 5.3e-3, rho), 8.331, 1e-3);
    // The peak: a scan of the distance against the closed form.
    const double a1 = 2.0 / 3.0, b1 = 7.0 / 3.0, k = 6e5, rate = 100.0;
    const double g_peak = b2 * 4.0 / (a1 * a2);
    const double d_peak = pow(rate * d / (g_peak * sqrt(k / (rho * d))), 1.0 / b1);
    const double p_peak = k / d * pow(d_peak, a1) * pow(4.0 / (2.0 * b1 * a2), 2.0);
    double top = 0.0, at = 0.0;
    for (int i = 1; i <= 100000; ++i) {
        const double p = bdl_rheology_branch_pressure(&b, 1e-5 * i, rate, d, rho);
        if (p > top)
            top = p, at = 1e-5 * i;
    }
    printf("soft branch at 100/s: the largest contact pressure below jamming %.0f Pa at a "
           "distance %.4f (closed form %.0f Pa at %.4f)\n",
           top, at, p_peak, d_peak);
    CHECK_CLOSE(top, p_peak, 1e-6);
    CHECK(fabs(at - d_peak) < 2e-5);
    int beyond = 1;
    double near = 0.0;
    for (int i = 0; i < 3; ++i) {
        const double far_side = 0.06 + 0.03 * i, near_side = d_peak * (0.2 + 0.3 * i);
        const double p = bdl_rheology_branch_pressure(&b, far_side, rate, d, rho);
        const double cr = bdl_rheology_jamming_soft(&b, 0.5, p, rate, d, rho, &beyond, &near);
        CHECK_CLOSE(cr, 0.5 + far_side, 1e-9);
        CHECK(beyond == 0 && near > 0.5 && near < 0.5 + d_peak);
        const double q = bdl_rheology_branch_pressure(&b, near_side, rate, d, rho);
        bdl_rheology_jamming_soft(&b, 0.5, q, rate, d, rho, &beyond, &near);
        CHECK_CLOSE(near, 0.5 + near_side, 1e-9);
        // The inertial limit alone overstates the pressure, so it puts nu_cr farther away.
        CHECK(bdl_rheology_jamming_point(0.5, p / (rho * d * d * rate * rate), 4.0, a) > cr);
    }
    CHECK(bdl_rheology_jamming_soft(&b, 0.55, 1.01 * p_peak, rate, d, rho, &beyond, &near) == 0.55);
    CHECK(beyond == 1);
    bdl_rheology_jamming_soft(&b, 0.55, 0.99 * p_peak, rate, d, rho, &beyond, &near);
    CHECK(beyond == 0);
    // Inputs that are not finite and positive give no answer, not a place past jamming.
    CHECK(isnan(bdl_rheology_jamming_soft(&b, 0.5, -1.0, rate, d, rho, &beyond, &near)));
    CHECK(isnan(bdl_rheology_jamming_soft(&b, 0.5, 100.0, NAN, d, rho, &beyond, &near)));
    CHECK(isnan(bdl_rheology_jamming_soft(&b, 0.5, 100.0, INFINITY, d, rho, &beyond, &near)));
    CHECK(beyond == 0);
    CHECK(isnan(bdl_rheology_jamming_point(0.5, INFINITY, 4.0, a)));
    b.a2 = 0.0; // no springs' limit: the law A D^-4 exactly, crossed once
    const double p = 800.0, y = p / (rho * d * d * rate * rate);
    CHECK_CLOSE(bdl_rheology_jamming_soft(&b, 0.5, p, rate, d, rho, &beyond, &near),
                bdl_rheology_jamming_point(0.5, y, 4.0, a), 1e-9);
    CHECK(isnan(near));
}

/// Grad's dilute solution: the three balances it solves, re-checked from its outputs; the elastic
/// gas's viscosity as e -> 1; and its ratios to Lun et al.'s dilute limit, 18/23 and (18/23)^1.5
/// at e = 0.7 (zeta/beta = 0.2125/0.9775 = 5/23).
static void test_grad(void)
{
    const double d = 0.0053, rho = 1395.0, g = 100.0, nu = 0.01;
    for (double e = 0.5; e < 0.95; e += 0.2) {
        const bdl_grad_shear s = bdl_grad_dilute_shear(nu, e, d, rho, g);
        const double zeta = 5.0 / 12.0 * (1 - e * e), beta = (1 + e) * (3 - e) / 4;
        const double nu0 = 96.0 / 5.0 * nu * sqrt(s.temperature) / (d * sqrt(pi));
        const double pzz = s.pressure - s.n1 / 3.0; // P_xx = P_zz + N1, P_yy = P_zz
        CHECK_CLOSE(s.shear_stress * g, 1.5 * zeta * nu0 * s.pressure, 1e-12);
        CHECK_CLOSE(s.shear_stress, g / nu0 * pzz / beta, 1e-12);
        CHECK_CLOSE(pzz, s.pressure * (1 - zeta / beta), 1e-12);
        CHECK_CLOSE(s.reduced_rate, g / nu0, 1e-12);
    }
    CHECK_CLOSE(bdl_grad_dilute_shear(nu, 1.0 - 1e-9, d, rho, g).viscosity, 1.0, 1e-8);
    const bdl_grad_shear s = bdl_grad_dilute_shear(1e-7, 0.7, d, rho, g);
    const bdl_lun_state l = bdl_lun_simple_shear(1e-7, 0.7, d, rho, g);
    CHECK_CLOSE(s.temperature / l.temperature, 18.0 / 23.0, 1e-5);
    CHECK_CLOSE(s.pressure / l.pressure, 18.0 / 23.0, 1e-5);
    CHECK_CLOSE(s.shear_stress / l.shear_stress, pow(18.0 / 23.0, 1.5), 1e-5);
    CHECK_CLOSE(s.n1 / s.pressure, 15.0 / 23.0, 1e-12);
    // The reduced viscosity and shear rate read back from each theory's own state: Grad's, and
    // Lun et al.'s dilute limit, 1/beta and sqrt((3/2) zeta beta) (beta 0.9775, zeta 0.2125).
    double visc, rate;
    bdl_rheology_reduced(1e-7, d, rho, s.temperature, s.shear_stress, g, &visc, &rate);
    CHECK_CLOSE(visc, s.viscosity, 1e-12);
    CHECK_CLOSE(rate, s.reduced_rate, 1e-12);
    bdl_rheology_reduced(1e-7, d, rho, l.temperature, l.shear_stress, g, &visc, &rate);
    CHECK_CLOSE(visc, 1.0 / 0.9775, 1e-5);
    CHECK_CLOSE(rate, sqrt(1.5 * 0.2125 * 0.9775), 1e-5);
    printf("Grad, dilute, e 0.7: a* %.4f, eta/eta0 %.4f; of Lun et al.: T %.4f, tau %.4f; N1/p "
           "%.4f\n",
           s.reduced_rate, s.viscosity, s.temperature / l.temperature,
           s.shear_stress / l.shear_stress, s.n1 / s.pressure);
}

/// Grad's sheared gas with a drag -b m (v - u): its four balances re-derived from its outputs,
/// its limit b -> 0, a drag that lowers T, elastic spheres held by the drag alone, and no root
/// from b = 0.166 g on (e = 0.7).
static void test_grad_damped(void)
{
    const double d = 0.0053, rho = 1395.0, g = 100.0, nu = 0.01, e = 0.7;
    const double zeta = 5.0 / 12.0 * (1 - e * e), beta = (1 + e) * (3 - e) / 4;
    const bdl_grad_shear dry = bdl_grad_dilute_shear(nu, e, d, rho, g);
    double t_last = dry.temperature;
    for (double b = 1.0; b < 10.0; b *= 3.0) { // no root from b = 16.6/s on
        const bdl_grad_shear s = bdl_grad_dilute_shear_damped(nu, e, d, rho, g, b);
        const double nu0 = 96.0 / 5.0 * nu * sqrt(s.temperature) / (d * sqrt(pi));
        const double pzz = s.pressure - s.n1 / 3.0, pxx = pzz + s.n1;
        CHECK_CLOSE(s.shear_stress * g, 1.5 * zeta * nu0 * s.pressure + 3.0 * b * s.pressure,
                    1e-10);
        CHECK_CLOSE(s.shear_stress * (beta * nu0 + 2.0 * b), g * pzz, 1e-10);
        CHECK_CLOSE(pzz * (beta * nu0 + 2.0 * b), s.pressure * nu0 * (beta - zeta), 1e-10);
        CHECK_CLOSE(pxx * (beta * nu0 + 2.0 * b),
                    s.pressure * nu0 * (beta - zeta) + 2.0 * g * s.shear_stress, 1e-10);
        CHECK_CLOSE(s.reduced_rate, g / nu0, 1e-10);
        CHECK(s.temperature < t_last);
        t_last = s.temperature;
    }
    // Elastic spheres have a steady state only with the drag: heating g tau = 3 b p, no cooling,
    // P_zz = p / (1 + 2 b*), tau = g P_zz / (nu0 + 2 b).
    const bdl_grad_shear el = bdl_grad_dilute_shear_damped(nu, 1.0, d, rho, g, 3.0);
    const double nu0_el = 96.0 / 5.0 * nu * sqrt(el.temperature) / (d * sqrt(pi));
    CHECK(isfinite(el.temperature) && el.temperature > 0.0);
    CHECK_CLOSE(el.shear_stress * g, 3.0 * 3.0 * el.pressure, 1e-10);
    CHECK_CLOSE(el.shear_stress * (nu0_el + 6.0), g * (el.pressure - el.n1 / 3.0), 1e-10);
    CHECK_CLOSE((el.pressure - el.n1 / 3.0) * (nu0_el + 6.0), el.pressure * nu0_el, 1e-10);
    const bdl_grad_shear tiny = bdl_grad_dilute_shear_damped(nu, e, d, rho, g, 1e-9);
    CHECK_CLOSE(tiny.temperature, dry.temperature, 1e-9);
    CHECK_CLOSE(tiny.n1, dry.n1, 1e-9);
    // No root: the least shear rate of b grows with b (0.166 g at e = 0.7).
    CHECK(isnan(bdl_grad_dilute_shear_damped(nu, e, d, rho, g, 1e4).temperature));
    CHECK(isnan(bdl_grad_dilute_shear_damped(nu, e, d, rho, 1.0, 100.0).pressure));
}

int main(void)
{
    test_stress();
    test_lun();
    test_grad();
    test_grad_damped();
    test_jamming();
    test_jamming_soft();
    return bdl_test_summary("test_rheology");
}
