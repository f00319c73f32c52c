// bedlam — drag laws. Each is written as beta / phi, the drag per unit particle volume and unit
// slip, in a form that stays finite when the slip or the solids fraction goes to zero.
#include "couple/drag.h"

#include <math.h>

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

/// Syamlal & O'Brien (1988), as written out by Sun (2007), eqs. 3.10-3.16: beta = 3 phi eps rho /
/// (4 Vr^2 d) Cds(Re / Vr) |u - v| with the Dalla Valle Cds = (0.63 + 4.8 / sqrt(Re / Vr))^2 and
/// the terminal-velocity ratio Vr of Garside & Al-Dibouni; Re = rho d |u - v| / mu.
static double syamlal_obrien(const bdl_drag_params *p, double eps, double d, double slip,
                             double rho, double mu)
{
    double re = rho * d * slip / mu;
    double A = pow(eps, 4.14);
    double B = eps <= 0.85 ? p->syamlal_c * pow(eps, 1.28) : pow(eps, p->syamlal_d);
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

/// Tenneti, Garg & Subramaniam (2011), Int. J. Multiphase Flow 37, 1072, eqs. 9-11: the total
/// fluid force over the Stokes drag at the superficial slip,
///   F = F_isol(Re) / eps^3 + 5.81 phi / eps^3 + 0.48 phi^(1/3) / eps^4
///       + phi^3 Re (0.95 + 0.61 phi^3 / eps^2),
///   F_isol = 1 + 0.15 Re^0.687,  Re = eps rho d |u - v| / mu,
/// so (the drag being eps times the total force) beta / phi = 18 mu eps^2 F / d^2.
static double tenneti(double eps, double phi, double d, double slip, double rho, double mu)
{
    double re = eps * rho * d * slip / mu;
    double e3 = eps * eps * eps;
    double f = schiller_naumann_factor(re) / e3 + 5.81 * phi / e3 + 0.48 * cbrt(phi) / (e3 * eps) +
               phi * phi * phi * re * (0.95 + 0.61 * phi * phi * phi / (eps * eps));
    return 18.0 * mu * eps * eps * f / (d * d);
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
    case BDL_DRAG_SYAMLAL_OBRIEN:
        return syamlal_obrien(p, eps, d, slip, rho, mu);
    case BDL_DRAG_DI_FELICE:
        return di_felice(eps, d, slip, rho, mu);
    case BDL_DRAG_BEETSTRA:
        return beetstra(eps, phi, d, slip, rho, mu);
    case BDL_DRAG_TENNETI:
        return tenneti(eps, phi, d, slip, rho, mu);
    default:
        return 0.0;
    }
}

double bdl_drag_beta(bdl_drag_law law, const bdl_drag_params *p, double eps, double d, double slip,
                     double rho, double mu)
{
    return (1.0 - fmin(fmax(eps, 1e-3), 1.0)) * bdl_drag_per_volume(law, p, eps, d, slip, rho, mu);
}
