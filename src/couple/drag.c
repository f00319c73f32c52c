// bedlam — drag laws. Each is written as beta / phi, the drag per unit particle volume and unit
// slip, in a form that stays finite when the slip or the solids fraction goes to zero.
#include "couple/drag.h"

#include <math.h>

#include "core/vec3.h"

BDL_CHOICE_WORDS(bdl_drag_law, BDL_DRAG_LAWS);
const char *const bdl_drag_law_texts[] = {BDL_DRAG_LAWS(BDL_ENUM_LABEL) NULL};

bdl_drag_params bdl_drag_default_params(void)
{
    return (bdl_drag_params){.syamlal_c = 0.8, .syamlal_d = 2.65};
}

/// Schiller-Naumann, as a factor on Stokes drag: Cd Re / 24 = 1 + 0.15 Re^0.687 below Re = 1000,
/// Cd = 0.44 above.
static double schiller_naumann_factor(double re)
{
    return re < 1000.0 ? 1.0 + 0.15 * pow(re, 0.687) : 0.44 * re / 24.0;
}

/// Ergun (1952): beta = 150 phi^2 mu / (eps d^2) + 1.75 phi rho |u - v| / d.
static double ergun(double eps, double phi, double d, double slip, double rho, double mu)
{
    return 150.0 * phi * mu / (eps * d * d) + 1.75 * rho * slip / d;
}

/// Wen & Yu (1966): beta = 3/4 Cd eps phi rho |u - v| eps^-2.65 / d, Cd from Schiller-Naumann at
/// Re = eps rho d |u - v| / mu.
static double wen_yu(double eps, double d, double slip, double rho, double mu)
{
    double re = eps * rho * d * slip / mu;
    return 18.0 * mu / (d * d) * schiller_naumann_factor(re) * pow(eps, -2.65);
}

/// Tsuji, Kawaguchi & Tanaka (1993), as Sun (2007) writes it, eqs. 7.30-7.31: Ergun up to
/// eps = 0.8; above, beta = 3/4 Cd eps phi rho |u - v| eps^-2.7 / d with Cd = 24/Re (1 + 0.15
/// Re^0.687) below Re = 1000 and 0.43 from there, Re = eps rho d |u - v| / mu.
static double tsuji(double eps, double phi, double d, double slip, double rho, double mu)
{
    if (eps <= 0.8)
        return ergun(eps, phi, d, slip, rho, mu);
    const double re = eps * rho * d * slip / mu;
    const double cd_re = re < 1000.0 ? 1.0 + 0.15 * pow(re, 0.687) : 0.43 * re / 24.0;
    return 18.0 * mu / (d * d) * cd_re * pow(eps, -2.7);
}

/// Patankar & Joseph (2001), eq. 7: D_p = 3/8 Cd rho |u - v| / (rho_p R_p) with
/// Cd = 24/Re (1 + 0.15 Re^0.687) eps^-1.8 (0.44 eps^-1.8 from Re = 1000), Re = eps rho d |u - v| /
/// mu (the slip to the mixture taken as eps (u - v)): beta / phi = rho_p D_p, written
/// 18 mu / d^2 (Cd Re / 24) eps^-2.8 so that it stays finite at zero slip.
static double patankar(double eps, double d, double slip, double rho, double mu)
{
    double re = eps * rho * d * slip / mu;
    return 18.0 * mu / (d * d) * schiller_naumann_factor(re) * pow(eps, -2.8);
}

/// Syamlal & O'Brien (1988), as written out by Sun (2007), eqs. 3.10-3.16: beta = 3 phi eps rho /
/// (4 Vr^2 d) Cds(Re / Vr) |u - v| with the Dalla Valle Cds = (0.63 + 4.8 / sqrt(Re / Vr))^2 and
/// the terminal-velocity ratio Vr of Garside & Al-Dibouni; Re = rho d |u - v| / mu.
static double syamlal_obrien(const bdl_drag_params *p, double eps, double d, double slip,
                             double rho, double mu)
{
    double re = rho * d * slip / mu;
    // A = eps^4.14 = eps^4 t and, dense, B = c eps^1.28 = c eps t^2 with t = eps^0.14: one
    // exponential of one logarithm (a third of the cost of two pows).
    const double log_eps = log(eps), t = exp(0.14 * log_eps), e2 = eps * eps;
    double A = e2 * e2 * t;
    double B = eps <= 0.85 ? p->syamlal_c * eps * t * t : exp(p->syamlal_d * log_eps);
    double vr = 0.5 * (A - 0.06 * re + sqrt(0.0036 * re * re + 0.12 * re * (2.0 * B - A) + A * A));
    // Cds |u - v| = (0.63 sqrt|u - v| + 4.8 sqrt(Vr mu / (rho d)))^2, finite at zero slip.
    double root = 0.63 * sqrt(slip) + 4.8 * sqrt(vr * mu / (rho * d));
    return 3.0 * eps * rho / (4.0 * vr * vr * d) * root * root;
}

/// Di Felice (1994): F = Cd rho pi d^2 / 8 eps^2 |u - v| (u - v) eps^-chi with the Dalla Valle
/// Cd at Re = eps rho d |u - v| / mu and chi = 3.7 - 0.65 exp(-(1.5 - log10 Re)^2 / 2).
static double di_felice(double eps, double d, double slip, double rho, double mu)
{
    double re = eps * rho * d * slip / mu;
    double chi = re > 0.0 ? 3.7 - 0.65 * exp(-0.5 * pow(1.5 - log10(re), 2.0)) : 3.7;
    // Cd |u - v| = (0.63 sqrt|u - v| + 4.8 sqrt(mu / (eps rho d)))^2.
    double root = 0.63 * sqrt(slip) + 4.8 * sqrt(mu / (eps * rho * d));
    return 0.75 * rho * eps * eps * root * root * pow(eps, -chi) / d;
}

/// Beetstra, van der Hoef & Kuipers (2007), AIChE J. 53, 489, eq. 19: the drag (the total fluid
/// force times eps) over the Stokes drag at the superficial slip,
///   F = 10 phi / eps^2 + eps^2 (1 + 1.5 sqrt(phi))
///       + 0.413 Re / (24 eps^2) (1/eps + 3 eps phi + 8.4 Re^-0.343)
///         / (1 + 10^(3 phi) Re^-(1 + 4 phi)/2),   Re = eps rho d |u - v| / mu,
/// so beta / phi = 18 mu eps F / d^2.
static double beetstra(double eps, double phi, double d, double slip, double rho, double mu)
{
    double re = eps * rho * d * slip / mu;
    double f = 10.0 * phi / (eps * eps) + eps * eps * (1.0 + 1.5 * sqrt(phi));
    if (re > 0.0)
        f += 0.413 * re / (24.0 * eps * eps) *
             (1.0 / eps + 3.0 * eps * phi + 8.4 * pow(re, -0.343)) /
             (1.0 + pow(10.0, 3.0 * phi) * pow(re, -0.5 * (1.0 + 4.0 * phi)));
    return 18.0 * mu * eps * f / (d * d);
}

/// Tenneti's F (below) with the isolated particle's F_isol given.
static double tenneti_force(double eps, double re, double f_isol)
{
    double e3 = eps * eps * eps, phi = 1.0 - eps;
    return f_isol / e3 + 5.81 * phi / e3 + 0.48 * cbrt(phi) / (e3 * eps) +
           phi * phi * phi * re * (0.95 + 0.61 * phi * phi * phi / (eps * eps));
}

/// Tenneti, Garg & Subramaniam (2011), Int. J. Multiphase Flow 37, 1072, eqs. 9-11: the total
/// fluid force over the Stokes drag at the superficial slip,
///   F = F_isol(Re) / eps^3 + 5.81 phi / eps^3 + 0.48 phi^(1/3) / eps^4
///       + phi^3 Re (0.95 + 0.61 phi^3 / eps^2),
///   F_isol = 1 + 0.15 Re^0.687,  Re = eps rho d |u - v| / mu,
/// so (the drag being eps times the total force) beta / phi = 18 mu eps^2 F / d^2.
static double tenneti(double eps, double d, double slip, double rho, double mu)
{
    double re = eps * rho * d * slip / mu;
    return 18.0 * mu * eps * eps * tenneti_force(eps, re, schiller_naumann_factor(re)) / (d * d);
}

double bdl_drag_per_volume(bdl_drag_law law, const bdl_drag_params *p, double eps, double d,
                           double slip, double rho, double mu)
{
    bdl_drag_params defaults = bdl_drag_default_params();
    if (!p)
        p = &defaults;
    eps = fmin(fmax(eps, 1e-3), 1.0);
    slip = fabs(slip);
    const double phi = 1.0 - eps;
    switch (law) {
    case BDL_DRAG_STOKES:
        return 18.0 * mu / (d * d);
    case BDL_DRAG_SCHILLER_NAUMANN:
        return 18.0 * mu / (d * d) * schiller_naumann_factor(rho * d * slip / mu);
    case BDL_DRAG_WEN_YU:
        return wen_yu(eps, d, slip, rho, mu);
    case BDL_DRAG_ERGUN:
        return ergun(eps, phi, d, slip, rho, mu);
    case BDL_DRAG_GIDASPOW:
        return eps <= 0.8 ? ergun(eps, phi, d, slip, rho, mu) : wen_yu(eps, d, slip, rho, mu);
    case BDL_DRAG_TSUJI:
        return tsuji(eps, phi, d, slip, rho, mu);
    case BDL_DRAG_SYAMLAL_OBRIEN:
        return syamlal_obrien(p, eps, d, slip, rho, mu);
    case BDL_DRAG_DI_FELICE:
        return di_felice(eps, d, slip, rho, mu);
    case BDL_DRAG_PATANKAR:
        return patankar(eps, d, slip, rho, mu);
    case BDL_DRAG_BEETSTRA:
        return beetstra(eps, phi, d, slip, rho, mu);
    case BDL_DRAG_TENNETI:
        return tenneti(eps, d, slip, rho, mu);
    case BDL_DRAG_HDF:
    case BDL_DRAG_STE:
    case BDL_DRAG_STA: {
        const bdl_drag_shape sphere = {.diameter = d, .shaft = 0.0, .cos_theta = 1.0};
        return bdl_drag_shape_per_volume(law, p, eps, &sphere, slip, rho, mu);
    }
    default:
        return 0.0;
    }
}

double bdl_drag_beta(bdl_drag_law law, const bdl_drag_params *p, double eps, double d, double slip,
                     double rho, double mu)
{
    return (1.0 - fmin(fmax(eps, 1e-3), 1.0)) * bdl_drag_per_volume(law, p, eps, d, slip, rho, mu);
}

// ---- Rods: the drag laws of Mahajan (2019), ch. 3.4 ----
//
// Each is a single-particle law times a voidage correction. The single-particle force is
// F_0 = C_D rho/2 (pi/4) d_e^2 |v_r| v_r (v_r the interstitial slip); written below with
// C_D Re, which stays finite as the slip goes to zero: F_0 / |v_r| = (pi/8) d_e mu C_D Re / s,
// where Re = s rho d_e |v_r| / mu and s = eps for Hoelzer-Sommerfeld (its Re carries the
// voidage) and 1 for Sanjeevi's fit (a single particle in an unbounded fluid).

bdl_drag_sphericity bdl_drag_sphericities(const bdl_drag_shape *s)
{
    const double d = s->diameter, L = s->shaft, pi = BDL_PI;
    const double volume = pi * d * d * L / 4.0 + pi * d * d * d / 6.0;
    const double area = pi * d * L + pi * d * d;
    const double c = fmin(fabs(s->cos_theta), 1.0), sin_t = sqrt(1.0 - c * c);
    bdl_drag_sphericity sp;
    sp.d_e = cbrt(6.0 * volume / pi);
    const double a_e = pi * sp.d_e * sp.d_e / 4.0;
    sp.phi = 4.0 * a_e / area;
    sp.phi_perp = a_e / (pi * d * d / 4.0 + d * L * sin_t);
    sp.phi_par = 2.0 * a_e / (area - 2.0 * (pi * d * d / 4.0 + d * L * c));
    if (!(L > 0.0)) // a sphere exactly: (-log10 phi)^0.2 would turn a rounding of 1e-16 into 3e-4
        sp = (bdl_drag_sphericity){.phi = 1.0, .phi_perp = 1.0, .phi_par = 1.0, .d_e = d};
    return sp;
}

/// Hoelzer & Sommerfeld's C_D Re.
static double hs_cd_re(double re, const bdl_drag_sphericity *sp)
{
    const double newton = 0.42 * pow(10.0, 0.4 * pow(-log10(sp->phi), 0.2)) / sp->phi_perp;
    return 8.0 / sqrt(sp->phi_par) + 16.0 / sqrt(sp->phi) + 3.0 * sqrt(re) / pow(sp->phi, 0.75) +
           newton * re;
}

double bdl_drag_hs_cd(double re, const bdl_drag_sphericity *sp) { return hs_cd_re(re, sp) / re; }

/// Sanjeevi et al.'s C_D Re at 0 and 90 degrees: (a1 + a2 Re^(1 - a3)) e^(-a4 Re) +
/// a5 Re (1 - e^(-a4 Re)) (their table for aspect ratio 4).
static double sanjeevi_cd_re_at(double re, const double a[5])
{
    const double decay = exp(-a[3] * re);
    return (a[0] + a[1] * pow(re, 1.0 - a[2])) * decay + a[4] * re * (1.0 - decay);
}

static double sanjeevi_cd_re(double re, double sin2)
{
    static const double along[5] = {24.48, 3.965, 0.41, 0.0005, 0.15};
    static const double across[5] = {31.89, 5.519, 0.229, 0.0032, 1.089};
    const double c0 = sanjeevi_cd_re_at(re, along), c90 = sanjeevi_cd_re_at(re, across);
    return c0 + (c90 - c0) * sin2;
}

double bdl_drag_sanjeevi_cd(double re, double sin2) { return sanjeevi_cd_re(re, sin2) / re; }

double bdl_drag_di_felice_factor(double eps, double re)
{
    const double l = re > 0.0 ? 1.5 - log10(re) : INFINITY;
    const double beta = 3.7 - 0.65 * exp(-0.5 * l * l);
    return pow(eps, 2.0 - beta);
}

/// Tang et al. (2015), AIChE J. 61, 688: the drag over Stokes drag at the superficial slip.
static double tang_force(double eps, double re)
{
    const double phi = 1.0 - eps, e4 = eps * eps * eps * eps;
    return 10.0 * phi / (eps * eps) + eps * eps * (1.0 + 1.5 * sqrt(phi)) +
           (0.11 * phi * (1.0 + phi) - 0.00456 / e4) * re +
           (0.169 * eps + 0.0644 / e4) * pow(re, 0.657);
}

double bdl_drag_tang_ratio(double eps, double re)
{
    return tang_force(eps, re) / tang_force(1.0, re);
}

double bdl_drag_tenneti_ratio(double eps, double re)
{
    // F_isol = (Re/24) max((24/Re)(1 + 0.15 Re^0.687), 0.44), as Mahajan writes it.
    const double f_isol = fmax(1.0 + 0.15 * pow(re, 0.687), 0.44 * re / 24.0);
    return tenneti_force(eps, re, f_isol) / f_isol;
}

/// HDF: Hoelzer-Sommerfeld times Di Felice, both at Re = eps rho d_e |v_r| / mu; where the bed is
/// dense (eps <= 0.8) the smaller of that and Ergun's force with d = phi d_e. Returns F / |v_r|.
static double hdf_force(double eps, const bdl_drag_sphericity *sp, double slip, double rho,
                        double mu)
{
    const double d = sp->d_e, re = eps * rho * d * slip / mu;
    const double f =
        BDL_PI / 8.0 * d * mu * hs_cd_re(re, sp) / eps * bdl_drag_di_felice_factor(eps, re);
    if (eps > 0.8)
        return f;
    const double volume = BDL_PI / 6.0 * d * d * d, pd = sp->phi * d;
    const double ergun_f =
        volume * (150.0 * mu * (1.0 - eps) / (pd * pd * eps) + 1.75 * rho * slip / pd);
    return fmin(f, ergun_f);
}

double bdl_drag_shape_per_volume(bdl_drag_law law, const bdl_drag_params *p, double eps,
                                 const bdl_drag_shape *s, double slip, double rho, double mu)
{
    eps = fmin(fmax(eps, 1e-3), 1.0);
    slip = fabs(slip);
    const bdl_drag_sphericity sp = bdl_drag_sphericities(s);
    const double d = sp.d_e, volume = BDL_PI / 6.0 * d * d * d;
    if (law != BDL_DRAG_HDF && law != BDL_DRAG_STE && law != BDL_DRAG_STA)
        return bdl_drag_per_volume(law, p, eps, d, slip, rho, mu);
    if (law == BDL_DRAG_HDF)
        return hdf_force(eps, &sp, slip, rho, mu) / volume;
    // STE, STA: Sanjeevi's fit for rods (a sphere: Hoelzer-Sommerfeld's sphere), at the Re of a
    // single particle, times the ratio at the superficial Re.
    const double re = rho * d * slip / mu, c = s->cos_theta;
    const double cd_re = s->shaft > 0.0 ? sanjeevi_cd_re(re, 1.0 - c * c) : hs_cd_re(re, &sp);
    const double g = law == BDL_DRAG_STE ? bdl_drag_tenneti_ratio(eps, eps * re)
                                         : bdl_drag_tang_ratio(eps, eps * re);
    return BDL_PI / 8.0 * d * mu * cd_re * g / volume;
}
