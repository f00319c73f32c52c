// bedlam — closures of a solids phase on the grid: the kinetic theory of granular flow as the
// segregation thesis uses it (J. Sun, PhD thesis, Iowa State 2007, ch. 3, 5 and 7;
// docs/theory-tfm.md).
//
// Each function is the closure at one point: solids fraction eps (of the phase), granular
// temperature theta (translational, theta = <C^2>/3, m^2/s^2), diameter d, material density rho,
// normal restitution e. SI units throughout.
//
//   radial distribution at contact   Carnahan & Starling (one phase); Lebowitz (a mixture, the
//                                    form MFIX takes for more than one phase)
//   viscous regime (Syamlal 1987)    P = K1 eps^2 theta, mu = K3 eps sqrt(theta),
//                                    lambda = K2 eps sqrt(theta) (Sun eqs. 3.21-3.25)
//   collisional dissipation          gamma = K4 eps^2 theta^(3/2), K4 = 12 (1 - e^2) rho g0 /
//                                    (sqrt(pi) d) (Sun eq. 5.7)
//   plastic regime (Schaeffer 1987)  P = eps_s A (eps_g* - eps_g)^n,
//                                    mu = P sin(phi) / (2 sqrt(I2D))
//   particle rotation                Jenkins & Zhang (2002): the effective restitution of
//                                    slightly frictional spheres (Sun eqs. 5.12-5.19)
#ifndef BDL_SOLIDS_KINETIC_H
#define BDL_SOLIDS_KINETIC_H

/// g0 = (1 - eps/2) / (1 - eps)^3 for one phase of solids fraction eps in [0, 1).
double bdl_g0_carnahan_starling(double eps);

/// Lebowitz's g0 between phases l and m of a mixture: 1/eps_g + 3 d_l d_m S / (eps_g^2 (d_l +
/// d_m)), S = sum_k eps_k / d_k over the `count` phases (eps_g = 1 - sum_k eps_k).
double bdl_g0_lebowitz(const double *eps, const double *d, int count, int l, int m);

/// The viscous-regime coefficients of Syamlal (1987) for one phase: P = k1 eps^2 theta,
/// lambda = k2 eps sqrt(theta), mu = k3 eps sqrt(theta), dissipation k4 eps^2 theta^(3/2).
typedef struct bdl_ktgf_coefficients {
    double g0, k1, k2, k3, k4;
} bdl_ktgf_coefficients;
bdl_ktgf_coefficients bdl_ktgf_syamlal(double eps, double d, double rho, double e);
/// The same with the radial distribution g0 given (a phase of a mixture: Lebowitz's g0_mm).
bdl_ktgf_coefficients bdl_ktgf_syamlal_g0(double eps, double g0, double d, double rho, double e);

/// Syamlal's coefficients split into what depends on the particles only, for loops over cells:
/// k1 = f.k1 g0, k3 = f.k3 + f.k3_dense eps g0, k2 = f.k2_dense eps g0 - 2/3 k3, k4 = f.k4 g0.
typedef struct bdl_ktgf_factors {
    double k1, k3, k3_dense, k2_dense, k4;
} bdl_ktgf_factors;
bdl_ktgf_factors bdl_ktgf_syamlal_factors(double d, double rho, double e);

/// bdl_ktgf_syamlal_g0 from the factors (the same to round-off).
static inline bdl_ktgf_coefficients bdl_ktgf_syamlal_at(const bdl_ktgf_factors *f, double eps,
                                                        double g0)
{
    const double eg = eps * g0;
    bdl_ktgf_coefficients c;
    c.g0 = g0;
    c.k1 = f->k1 * g0;
    c.k3 = f->k3 + f->k3_dense * eg;
    c.k2 = f->k2_dense * eg - 2.0 / 3.0 * c.k3;
    c.k4 = f->k4 * g0;
    return c;
}

/// Syamlal's (1987) drag between solids phases l and m (Sun 2007, eq. 3.18) divided by the two
/// fractions: F_lm / (eps_l eps_m) = 3 (1 + e) (pi/2 + cf pi^2/8) rho_l rho_m (d_l + d_m)^2 g0
/// |v_l - v_m| / (2 pi (rho_l d_l^3 + rho_m d_m^3)), e the restitution between the phases, cf
/// their friction coefficient, g0 their radial distribution at contact, `speed` |v_l - v_m|
/// [kg/(m^3 s)] per unit fraction of each: finite as either phase vanishes.
double bdl_solids_drag_syamlal(double e, double cf, double g0, double d_l, double rho_l, double d_m,
                               double rho_m, double speed);

/// The granular temperature of homogeneous simple shear at `shear_rate` in the viscous regime:
/// production mu shear_rate^2 equal to the dissipation, theta = k3 shear_rate^2 / (k4 eps)
/// (e in [0, 1): elastic particles have no balance).
double bdl_ktgf_shear_temperature(double eps, double d, double rho, double e, double shear_rate);

/// One backward-Euler step of the granular energy balance of a cell without its transport (no
/// convection, no conduction), in the viscous regime of coefficients c:
///     (3/2) rho eps (theta - theta_old) / dt = -P tr D + 2 mu D:D + lambda tr(D)^2
///                                              - k4 eps^2 theta^(3/2),
/// P, mu and lambda those of the new theta. `trace` is tr D and `ddot` D:D of the cell's rate of
/// strain. Returns theta >= 0, the root of a cubic in sqrt(theta) (Newton steps inside a bracket).
/// dt = INFINITY gives the algebraic balance (production equal to dissipation, MFIX's algebraic
/// form); a homogeneous cooling state follows Haff's law to first order in dt.
double bdl_ktgf_temperature_step(const bdl_ktgf_coefficients *c, double eps, double rho,
                                 double trace, double ddot, double theta_old, double dt);

/// The granular conductivity k_theta [kg/(m s)] of Lun et al. (1984) with Ma & Ahmadi's (1988)
/// reduction by the interstitial gas, as MFIX's granular-energy transport branch writes it
/// (eta = (1 + e)/2, beta the gas-solids drag coefficient per unit volume [kg/(m^3 s)]):
///     K = 75 rho d sqrt(pi theta) / (48 eta (41 - 33 eta)),
///     K* = K / (1 + 1.2 beta K / (rho^2 eps^2 g0 theta)),
///     k_theta = K* [(1/g0 + 12/5 eta eps)(1 + 12/5 eta^2 (4 eta - 3) eps g0)
///                   + 64/(25 pi) (41 - 33 eta) (eta eps)^2 g0].
/// 0 at theta = 0.
double bdl_ktgf_conductivity(double eps, double g0, double d, double rho, double e, double theta,
                             double beta);

/// Schaeffer's plastic regime: the solids pressure eps_s A (eps_g_star - eps_g)^n when the gas
/// fraction eps_g is below eps_g_star (else 0), and the frictional viscosity P sin(phi) /
/// (2 sqrt(i2d)) for the second invariant i2d of the rate-of-strain deviator, never above mu_max
/// (MFIX's cap; it is mu_max where i2d vanishes and a pressure acts).
double bdl_schaeffer_pressure(double eps_s, double eps_g, double eps_g_star, double a, double n);
double bdl_schaeffer_viscosity(double pressure, double phi, double i2d, double mu_max);

/// Jenkins & Zhang (2002) for slightly frictional spheres (friction mu, tangential restitution
/// beta0): the rotational to translational temperature ratio b1/b2 where the rotational energy
/// is in balance, and the effective restitution e - a1/2 + a2 b1 / (2 b2) that carries the
/// friction's dissipation in a smooth-sphere theory.
typedef struct bdl_jenkins_zhang {
    double mu0, a1, a2, b1, b2, temperature_ratio, e_eff;
} bdl_jenkins_zhang;
bdl_jenkins_zhang bdl_jenkins_zhang_effective(double e, double mu, double beta0);

#endif
