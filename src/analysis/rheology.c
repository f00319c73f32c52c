#include "analysis/rheology.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"

static const double pi = 3.14159265358979323846;

static void set_nan(bdl_rheology_sample *s)
{
    const double nan = NAN;
    for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b)
            s->stress[a][b] = s->streaming[a][b] = s->contact[a][b] = nan;
    s->solids_fraction = s->shear_rate = s->temperature = nan;
    s->pressure = s->shear_stress = s->n1 = s->n2 = s->friction = s->inertial_number = nan;
    s->pressure_streaming = s->pressure_contact = s->shear_streaming = s->shear_contact = nan;
    s->alignment = s->diameter = s->density = nan;
}

/// The slab of height z in the region, or -1 outside it.
static int slab_of(const bdl_rheology_input *in, double z)
{
    if (!(z >= in->z_lo && z < in->z_hi))
        return -1;
    int b = (int)((z - in->z_lo) / (in->z_hi - in->z_lo) * in->bins);
    return b < in->bins ? b : in->bins - 1;
}

/// The mass-weighted mean velocity of each slab (mass[b] 0: none there); returns the least-squares
/// slope of the slabs' mean u_x against their centres, or NAN with fewer than two slabs in use.
static double slab_means(const bdl_rheology_input *in, double *mass, bdl_vec3 *mean)
{
    for (int b = 0; b < in->bins; ++b) {
        mass[b] = 0.0;
        mean[b] = bdl_v3_zero();
    }
    for (long i = 0; i < in->count; ++i) {
        const int b = slab_of(in, in->pos[i].z);
        if (b < 0)
            continue;
        mass[b] += in->mass[i];
        mean[b] = bdl_v3_madd(mean[b], in->vel[i], in->mass[i]);
    }
    double n = 0.0, sz = 0.0, su = 0.0, szz = 0.0, szu = 0.0;
    const double h = (in->z_hi - in->z_lo) / in->bins;
    for (int b = 0; b < in->bins; ++b) {
        if (!(mass[b] > 0.0))
            continue;
        mean[b] = bdl_v3_scale(mean[b], 1.0 / mass[b]);
        const double z = in->z_lo + (b + 0.5) * h;
        n += 1.0;
        sz += z;
        su += mean[b].x;
        szz += z * z;
        szu += z * mean[b].x;
    }
    const double det = n * szz - sz * sz;
    return n >= 2.0 && det > 0.0 ? (n * szu - sz * su) / det : NAN;
}

static void add_outer(double m[3][3], bdl_vec3 a, bdl_vec3 b, double w)
{
    const double av[3] = {a.x, a.y, a.z}, bv[3] = {b.x, b.y, b.z};
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c)
            m[r][c] += w * av[r] * bv[c];
}

/// Streaming sums over the region's particles: sum m v'v', the mass, volume, volume-weighted
/// diameter and density, and with rods the order tensor.
typedef struct bulk_sums {
    long particles;
    double mass, volume, d_volume, v2, order[3][3];
} bulk_sums;

static void streaming_sums(const bdl_rheology_input *in, const bdl_vec3 *mean, double kin[3][3],
                           bulk_sums *s)
{
    memset(s, 0, sizeof *s);
    for (long i = 0; i < in->count; ++i) {
        const int b = slab_of(in, in->pos[i].z);
        if (b < 0)
            continue;
        const bdl_vec3 v = bdl_v3_sub(in->vel[i], mean[b]);
        add_outer(kin, v, v, in->mass[i]);
        s->particles++;
        s->mass += in->mass[i];
        s->volume += in->volume[i];
        s->d_volume += in->diameter[i] * in->volume[i];
        s->v2 += in->mass[i] * bdl_v3_len2(v);
        if (in->axis)
            add_outer(s->order, in->axis[i], in->axis[i], 1.0);
    }
}

/// tau from a stress tensor, signed by the shear rate's sense.
static double shear_of(double m[3][3], double sense) { return -0.5 * (m[0][2] + m[2][0]) * sense; }

static double trace3(double m[3][3]) { return (m[0][0] + m[1][1] + m[2][2]) / 3.0; }

int bdl_rheology_measure(const bdl_rheology_input *in, bdl_rheology_sample *out)
{
    memset(out, 0, sizeof *out);
    set_nan(out);
    out->particles = 0;
    if (in->bins < 2 || !(in->z_hi > in->z_lo))
        return 0;
    double *mass = malloc((size_t)in->bins * sizeof *mass);
    bdl_vec3 *mean = malloc((size_t)in->bins * sizeof *mean);
    if (!mass || !mean) {
        free(mass);
        free(mean);
        return 0;
    }
    const double slope = slab_means(in, mass, mean);
    const double rate = isnan(in->rate) ? slope : in->rate;
    double kin[3][3] = {{0}}, con[3][3] = {{0}};
    bulk_sums s;
    streaming_sums(in, mean, kin, &s);
    free(mass);
    free(mean);
    out->particles = s.particles;
    if (s.particles < 2 || !isfinite(rate))
        return 0;
    for (long c = 0; c < in->contacts; ++c) {
        const double w = 0.5 * ((slab_of(in, in->pos[in->ci[c]].z) >= 0) +
                                (slab_of(in, in->pos[in->cj[c]].z) >= 0));
        if (w > 0.0)
            add_outer(con, in->branch[c], in->force[c], w);
    }
    const double volume = in->x_length * in->y_length * (in->z_hi - in->z_lo);
    for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b) {
            out->streaming[a][b] = kin[a][b] / volume;
            out->contact[a][b] = con[a][b] / volume;
            out->stress[a][b] = out->streaming[a][b] + out->contact[a][b];
        }
    const double sense = rate < 0.0 ? -1.0 : 1.0;
    out->solids_fraction = s.volume / volume;
    out->shear_rate = rate;
    out->temperature = s.v2 / (3.0 * s.mass);
    out->pressure = trace3(out->stress);
    out->pressure_streaming = trace3(out->streaming);
    out->pressure_contact = trace3(out->contact);
    out->shear_stress = shear_of(out->stress, sense);
    out->shear_streaming = shear_of(out->streaming, sense);
    out->shear_contact = shear_of(out->contact, sense);
    out->n1 = out->stress[0][0] - out->stress[2][2];
    out->n2 = out->stress[2][2] - out->stress[1][1];
    out->friction = out->shear_stress / out->pressure;
    const double d = s.d_volume / s.volume, rho = s.mass / s.volume;
    out->diameter = d;
    out->density = rho;
    out->inertial_number = fabs(rate) * d * sqrt(rho / out->pressure);
    if (in->axis)
        out->alignment =
            0.5 * atan2(2.0 * s.order[0][2], s.order[0][0] - s.order[2][2]) * 180.0 / pi;
    return 1;
}

/// The viscosity of an elastic dilute gas of spheres at temperature t, (5/96) rho d sqrt(pi t):
/// the scale of Lun et al.'s shear stress and of the reduced viscosity.
static double elastic_viscosity(double rho, double d, double t)
{
    return 5.0 / 96.0 * rho * d * sqrt(pi * t);
}

bdl_lun_state bdl_lun_simple_shear(double nu, double e, double d, double rho, double g)
{
    bdl_lun_state s;
    const double eta = 0.5 * (1.0 + e);
    s.g0 = (1.0 - 0.5 * nu) / ((1.0 - nu) * (1.0 - nu) * (1.0 - nu));
    const double a = 1.6 * eta * nu * s.g0;
    const double f = (1.0 + a) * (1.0 + a * (3.0 * eta - 2.0)) / (eta * (2.0 - eta) * s.g0) +
                     768.0 / (25.0 * pi) * eta * nu * nu * s.g0;
    // Production tau g = mu g^2 balances the dissipation (48/sqrt(pi)) eta (1 - eta) rho nu^2 g0
    // T^(3/2) / d, with mu = (5/96) rho d sqrt(pi T) F.
    s.temperature = 5.0 * pi / 4608.0 * f * d * d * g * g / (eta * (1.0 - eta) * nu * nu * s.g0);
    s.pressure = rho * nu * s.temperature * (1.0 + 4.0 * eta * nu * s.g0);
    s.shear_stress = elastic_viscosity(rho, d, s.temperature) * f * fabs(g);
    return s;
}

/// q(y) = (zeta y + 2b)(beta y + 2b)^2 / y, the damped balance's (2/3)(beta - zeta) g^2 as a
/// function of the collision frequency y = nu0.
static double damped_balance(double y, double zeta, double beta, double b)
{
    const double r = beta * y + 2.0 * b;
    return (zeta * y + 2.0 * b) * r * r / y;
}

/// The hot root y >= the minimum of q of q(y) = target (bisection on the rising side), or NAN.
static double damped_frequency(double target, double zeta, double beta, double b)
{
    // q' = 0 where beta zeta y^2 + b beta y - 2 b^2 = 0: the root in a form that stays exact as
    // zeta -> 0 (e = 1, where y_min = 2 b / beta).
    const double y_min = 4.0 * b / (sqrt(beta * beta + 8.0 * beta * zeta) + beta);
    if (!(damped_balance(y_min, zeta, beta, b) <= target) || !isfinite(target))
        return NAN;
    double lo = y_min, hi = 2.0 * y_min; // q grows at least linearly above y_min
    while (damped_balance(hi, zeta, beta, b) < target)
        hi *= 2.0;
    for (int k = 0; k < 200 && hi - lo > 1e-15 * hi; ++k) {
        const double mid = 0.5 * (lo + hi);
        if (damped_balance(mid, zeta, beta, b) < target)
            lo = mid;
        else
            hi = mid;
    }
    return 0.5 * (lo + hi);
}

/// Grad's rates in units of nu0: the cooling zeta = (5/12)(1 - e^2) and the stress's relaxation
/// beta = (1 + e)(3 - e)/4.
static void grad_rates(double e, double *zeta, double *beta)
{
    *zeta = 5.0 / 12.0 * (1.0 - e * e);
    *beta = 0.25 * (1.0 + e) * (3.0 - e);
}

void bdl_grad_dilute_reduced(double e, double b_reduced, double *viscosity, double *rate,
                             double *n1_over_p)
{
    double zeta, beta;
    grad_rates(e, &zeta, &beta);
    // Flow along x, gradient along z. Steady P_zz = P_yy = p (beta - zeta) / (beta + 2 b*)
    // (their relaxation against the cooling and the drag), P_xz = -a P_zz / (beta + 2 b*) (the
    // shear turning P_zz into P_xz), and -P_xz g = (3/2)(zeta + 2 b*) nu0 p (heating = cooling
    // and drag). e = 1 without drag has no steady state: T = inf.
    const double r = beta + 2.0 * b_reduced;
    *viscosity = (beta - zeta) / (r * r);
    *rate = sqrt(1.5 * (zeta + 2.0 * b_reduced) * r * r / (beta - zeta));
    *n1_over_p = 3.0 * (zeta + 2.0 * b_reduced) / r;
}

bdl_grad_shear bdl_grad_dilute_shear_damped(double nu, double e, double d, double rho, double g,
                                            double b)
{
    BDL_ASSERT(b >= 0.0);
    bdl_grad_shear s;
    double zeta, beta, n1_over_p;
    grad_rates(e, &zeta, &beta);
    // nu0 = p / eta0 = (96/5) nu sqrt(T) / (d sqrt(pi)) = y: with a drag it solves
    // q(y) = (2/3)(beta - zeta) g^2, and b* = b / y; without, y = g / a of b* = 0.
    double y = b > 0.0 ? damped_frequency(2.0 / 3.0 * (beta - zeta) * g * g, zeta, beta, b) : 0.0;
    bdl_grad_dilute_reduced(e, b > 0.0 ? b / y : 0.0, &s.viscosity, &s.reduced_rate, &n1_over_p);
    if (!(b > 0.0))
        y = fabs(g) / s.reduced_rate;
    const double root_t = 5.0 * sqrt(pi) * d * y / (96.0 * nu);
    s.temperature = root_t * root_t;
    s.pressure = rho * nu * s.temperature;
    s.shear_stress = s.viscosity * elastic_viscosity(rho, d, s.temperature) * fabs(g);
    s.n1 = n1_over_p * s.pressure;
    return s;
}

bdl_grad_shear bdl_grad_dilute_shear(double nu, double e, double d, double rho, double g)
{
    return bdl_grad_dilute_shear_damped(nu, e, d, rho, g, 0.0);
}

void bdl_rheology_reduced(double nu, double d, double rho, double t, double tau, double g,
                          double *viscosity, double *rate)
{
    const double eta0 = elastic_viscosity(rho, d, t);
    *viscosity = tau / (eta0 * fabs(g));
    *rate = fabs(g) * eta0 / (rho * nu * t);
}

/// The residual of log y = log A - exponent log(nu_cr - nu) for one nu_cr, with log A its best.
static double jamming_residual(const double *nu, const double *y, int n, double exponent,
                               double nu_cr, double *log_a)
{
    double mean = 0.0;
    for (int k = 0; k < n; ++k)
        mean += log(y[k]) + exponent * log(nu_cr - nu[k]);
    mean /= n;
    double r = 0.0;
    for (int k = 0; k < n; ++k) {
        const double e = log(y[k]) + exponent * log(nu_cr - nu[k]) - mean;
        r += e * e;
    }
    *log_a = mean;
    return sqrt(r / n);
}

double bdl_rheology_jamming_point(double nu, double y, double exponent, double a)
{
    if (!(y > 0.0 && a > 0.0 && exponent > 0.0) || !isfinite(nu) || !isfinite(y) || !isfinite(a))
        return NAN;
    return nu + pow(a / y, 1.0 / exponent);
}

/// The collapse's exponents: P* = P_c / D^a1 with a1 = 2/3 for rods and spheres alike, and
/// g* = rate / D^b1 with 2 b1 - a1 the inertial law's exponent.
static const double branch_a1 = 2.0 / 3.0;
static double branch_b1(const bdl_jamming_branch *b) { return 0.5 * (b->exponent + branch_a1); }

double bdl_rheology_branch_pressure(const bdl_jamming_branch *b, double distance, double rate,
                                    double d, double rho)
{
    const double a1 = branch_a1, b1 = branch_b1(b);
    const double g = fabs(rate) * d * pow(distance, -b1) / sqrt(b->stiffness / (rho * d));
    const double r = g / (b->a2 * g + 1.0 / sqrt(b->a));
    return b->stiffness / d * pow(distance, a1) * r * r;
}

/// The distance from jamming at which the branch's pressure peaks at this rate: where
/// a2 g** + b2 = 2 b1 b2 / a1, i.e. g** = b2 exponent / (a1 a2); 0 when a2 = 0 (no peak).
static double branch_peak(const bdl_jamming_branch *b, double rate, double d, double rho)
{
    if (b->a2 == 0.0)
        return 0.0;
    const double g = b->exponent / (sqrt(b->a) * branch_a1 * b->a2);
    return pow(fabs(rate) * d / (g * sqrt(b->stiffness / (rho * d))), 1.0 / branch_b1(b));
}

/// Bisection for the distance in [lo, hi] where the branch gives pc, the pressure rising with the
/// distance on that interval when `rising`, falling otherwise.
static double branch_root(const bdl_jamming_branch *b, double lo, double hi, double pc, double rate,
                          double d, double rho, int rising)
{
    for (int it = 0; it < 200; ++it) {
        const double mid = 0.5 * (lo + hi);
        if ((bdl_rheology_branch_pressure(b, mid, rate, d, rho) > pc) == rising)
            hi = mid;
        else
            lo = mid;
    }
    return 0.5 * (lo + hi);
}

double bdl_rheology_jamming_soft(const bdl_jamming_branch *b, double nu, double pc, double rate,
                                 double d, double rho, int *beyond, double *near)
{
    *beyond = 0;
    *near = NAN;
    const double in[8] = {nu, pc, rate, d, rho, b->a, b->a2, b->stiffness};
    for (int k = 0; k < 8; ++k)
        if (!isfinite(in[k]))
            return NAN;
    if (!(pc > 0.0 && b->a > 0.0 && b->a2 >= 0.0 && b->stiffness > 0.0 && b->exponent > 0.0 &&
          d > 0.0 && rho > 0.0 && rate != 0.0))
        return NAN;
    const double peak = branch_peak(b, rate, d, rho);
    if (peak > 0.0 && pc >= bdl_rheology_branch_pressure(b, peak, rate, d, rho)) {
        *beyond = 1;
        return nu;
    }
    if (bdl_rheology_branch_pressure(b, 1.0, rate, d, rho) > pc)
        return NAN; // farther than a distance of 1 from jamming: not a dense state
    if (peak > 0.0)
        *near = nu + branch_root(b, 0.0, peak, pc, rate, d, rho, 1);
    return nu + branch_root(b, peak, 1.0, pc, rate, d, rho, 0);
}

double bdl_rheology_fit_jamming(const double *nu, const double *y, int n, double exponent,
                                double *nu_cr, double *a)
{
    *nu_cr = *a = NAN;
    double top = -INFINITY;
    for (int k = 0; k < n; ++k) {
        if (!(y[k] > 0.0) || !isfinite(nu[k]))
            return NAN;
        top = fmax(top, nu[k]);
    }
    if (n < 3)
        return NAN;
    // A scan of nu_cr over (top, top + 1] on a geometric grid of its distance from top, then
    // golden-section refinement around the best.
    double best = INFINITY, at = NAN, log_a;
    for (int k = 0; k <= 400; ++k) {
        const double x = top + 1e-4 * pow(1e4, k / 400.0);
        const double r = jamming_residual(nu, y, n, exponent, x, &log_a);
        if (r < best) {
            best = r;
            at = x;
        }
    }
    double lo = top + (at - top) / 1.03, hi = top + (at - top) * 1.03;
    const double g = 0.5 * (sqrt(5.0) - 1.0);
    for (int it = 0; it < 100; ++it) {
        const double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
        if (jamming_residual(nu, y, n, exponent, x1, &log_a) <
            jamming_residual(nu, y, n, exponent, x2, &log_a))
            hi = x2;
        else
            lo = x1;
    }
    *nu_cr = 0.5 * (lo + hi);
    const double r = jamming_residual(nu, y, n, exponent, *nu_cr, &log_a);
    *a = exp(log_a);
    return r;
}
