// bedlam — the stress of a sheared granular bulk from its particles (Mahajan 2019, §5.2; the
// standard micro-mechanical average, e.g. Campbell 1989):
//
//     sigma = (1/V) [ sum_i m_i v'_i v'_i  +  sum_contacts w_c r_ij F_ij ]
//
// streaming plus contact part, positive in compression. V is the bulk region: the box's x and y
// extent between z_lo and z_hi (away from driving walls). v' = v - <v>(bin) is the velocity less
// the mass-weighted mean of its slab among `bins` equal slabs of z across the region; r_ij the
// separation x_i - x_j of the centres (to the partner's periodic image), F_ij the force on i from
// j. A contact counts 1/2 for each of its particles whose centre lies in the region.
//
// From it, with shear along x and the gradient along z (u_x = shear_rate z):
//   shear_rate   the least-squares slope of the slabs' mean u_x against their centres' z, or the
//                rate the boundaries impose when given (Lees–Edwards: the box's mean rate
//                exactly, where a fitted slope is biased by a shear band in a dense flow);
//   temperature  T = <|v'|^2>/3 (mass-weighted);
//   pressure     p = tr(sigma)/3; shear stress tau = -(sigma_xz + sigma_zx)/2, signed so that it
//                is positive when it resists the shear rate's sense (tau sign(shear_rate));
//   N1 = sigma_xx - sigma_zz, N2 = sigma_zz - sigma_yy; mu = tau / p;
//   inertial number I = |shear_rate| d sqrt(rho_p / p) (d, rho_p: volume-weighted means);
//   with rods the flow-alignment angle 0.5 atan2(2 S_xz, S_xx - S_zz) of the order tensor
//   S = <u u> [deg] (Mahajan 2019, §5.2).
// Sums run in index order, so the result does not depend on the thread count.
#ifndef BDL_RHEOLOGY_H
#define BDL_RHEOLOGY_H

#include "core/vec3.h"

/// One instant of a bulk: its particles and the forces of its contacts, borrowed.
typedef struct bdl_rheology_input {
    long count;
    const bdl_vec3 *pos, *vel; ///< [m], [m/s]
    const double *mass;        ///< [kg]
    const double *volume;      ///< [m^3]
    const double *diameter;    ///< sphere, or volume-equivalent sphere, diameter [m]
    const bdl_vec3 *axis;      ///< rods: unit axes (NULL for spheres)
    long contacts;
    const long *ci, *cj;       ///< the two particles of each contact
    const bdl_vec3 *branch;    ///< x_i - x_j [m]
    const bdl_vec3 *force;     ///< on i from j [N]
    double x_length, y_length; ///< the box's extent across the flow [m]
    double z_lo, z_hi;         ///< the bulk region [m]
    int bins;                  ///< slabs of the mean velocity (>= 2)
    double rate;               ///< the imposed shear rate [1/s], or NAN: the slabs' slope
} bdl_rheology_input;

typedef struct bdl_rheology_sample {
    long particles;                        ///< centres in the region
    double solids_fraction;                ///< their volume over V
    double shear_rate;                     ///< [1/s]
    double temperature;                    ///< [m^2/s^2]
    double stress[3][3];                   ///< total [Pa]
    double streaming[3][3], contact[3][3]; ///< its parts [Pa]
    double pressure, shear_stress, n1, n2, friction, inertial_number;
    double pressure_streaming, pressure_contact, shear_streaming, shear_contact;
    double alignment;         ///< rods [deg]; NAN for spheres
    double diameter, density; ///< volume-weighted means of the region's particles [m], [kg/m^3]
} bdl_rheology_sample;

/// The sample of one instant (above). Returns 0, with the sample's values NAN, when the region
/// holds fewer than two particles or its slabs fewer than two with particles.
int bdl_rheology_measure(const bdl_rheology_input *in, bdl_rheology_sample *out);

/// Kinetic theory of Lun et al. (1984) for steady simple shear of smooth inelastic spheres
/// (diameter d, density rho, restitution e, solids fraction nu, shear rate g): the granular
/// temperature T, pressure p and shear stress tau from the balance of production and
/// dissipation (Carnahan–Starling g0; eta = (1 + e)/2).
typedef struct bdl_lun_state {
    double g0, temperature, pressure, shear_stress;
} bdl_lun_state;
bdl_lun_state bdl_lun_simple_shear(double nu, double e, double d, double rho, double g);

/// The same flow in the dilute limit, solved from the Boltzmann equation by Grad's method
/// (Montanero, Garzó, Santos & Brey 1999; Santos, Garzó & Dufty 2004): the distribution a
/// Maxwellian times one plus a quadratic form in the stress's traceless part, the collision
/// integrals linear in it. With nu0 = p / eta0 (eta0 = (5/96) rho d sqrt(pi T), the elastic
/// gas's viscosity) the traceless stress relaxes at beta nu0, beta = (1 + e)(3 - e)/4, and the
/// temperature falls at zeta nu0, zeta = (5/12)(1 - e^2). The steady balances of the stress
/// components in shear fix the reduced shear rate a = g / nu0, a^2 = (3/2) zeta beta^2 /
/// (beta - zeta); the viscosity is (beta - zeta)/beta^2 of eta0, and the normal stress along the
/// flow exceeds the other two, which are equal, by 3 zeta/beta of p. Lun et al.'s theory has the
/// same beta and zeta but is first order in the shear: its dilute limit is a^2 = (3/2) zeta beta
/// and a viscosity 1/beta of eta0, so that at one shear rate T and p are 1 - zeta/beta of Lun
/// et al.'s and tau is (1 - zeta/beta)^(3/2) of theirs (0.783 and 0.692 at e = 0.7). The
/// limit nu -> 0: g0 = 1, no collisional transfer; flow along x, gradient along z; 0 <= e < 1
/// (an elastic gas has no steady shear: T = inf).
typedef struct bdl_grad_shear {
    double reduced_rate;                        ///< a = g / nu0
    double viscosity;                           ///< eta / eta0
    double temperature, pressure, shear_stress; ///< [m^2/s^2], [Pa], [Pa]
    double n1;                                  ///< sigma_xx - sigma_zz, flow minus gradient [Pa]
} bdl_grad_shear;
bdl_grad_shear bdl_grad_dilute_shear(double nu, double e, double d, double rho, double g);
/// The same with a drag -b m (v - u) on every sphere, u the shear profile (a medium moving with
/// the shear: [species] background_damping in a Lees–Edwards box; the suspension model of
/// Chamorro, Vega Reyes & Garzó 2015). The drag adds 2 b P_ij to each balance, so with
/// b* = b / nu0: P_zz = p (beta - zeta) / (beta + 2 b*), eta / eta0 = (beta - zeta) /
/// (beta + 2 b*)^2, N1 = 3 (zeta + 2 b*) / (beta + 2 b*) p and a^2 = (3/2) (zeta + 2 b*)
/// (beta + 2 b*)^2 / (beta - zeta). nu0, which grows with sqrt(T), solves a cubic: the hot root
/// is the sheared gas. Below a least shear rate (g < b / 0.166 at e = 0.7) there is no root, and
/// every field is NAN: the truncation fails there (a run at b = 0.2 g still shears, with N1/p
/// 2). b = 0 is bdl_grad_dilute_shear; b >= 0.
bdl_grad_shear bdl_grad_dilute_shear_damped(double nu, double e, double d, double rho, double g,
                                            double b);
/// Grad's reduced viscosity eta/eta0, shear rate g/nu0 and N1/p of that flow at a reduced drag
/// b* = b / nu0 (b* >= 0; 0: (beta - zeta)/beta^2, sqrt((3/2) zeta beta^2/(beta - zeta)) and
/// 3 zeta/beta): a run's own temperature fixes nu0 and so b*, where it is compared.
void bdl_grad_dilute_reduced(double e, double b_reduced, double *viscosity, double *rate,
                             double *n1_over_p);
/// A shear flow's reduced viscosity eta/eta0 and reduced shear rate g/nu0 at its own temperature
/// t: eta0 = (5/96) rho d sqrt(pi t), the elastic gas's viscosity, nu0 = rho nu t / eta0. In the
/// dilute limit both depend on e alone (Grad: reduced_rate and viscosity above).
void bdl_rheology_reduced(double nu, double d, double rho, double t, double tau, double g,
                          double *viscosity, double *rate);

/// The distance to jamming from a sweep of solids fractions (Chialvo, Sun & Sundaresan 2012;
/// Mahajan 2019, §6.3): in the inertial regime the contact pressure scaled by rho d^2 (shear
/// rate)^2 grows as y = A (nu_cr - nu)^-exponent (4 for AR-4 rods, from the thesis's a1 = 2/3 and
/// b1 = 7/3: 2 b1 - a1; 2 for spheres). Least squares on log y over the n points (nu_cr searched
/// above the largest nu, log A solved for each); returns the root-mean-square residual of log y,
/// or NAN with fewer than three points or a y that is not positive.
double bdl_rheology_fit_jamming(const double *nu, const double *y, int n, double exponent,
                                double *nu_cr, double *a);
/// The same law with A known: the nu_cr that puts one point (nu, y) on it, nu + (A/y)^(1/exponent);
/// NAN unless y, A and the exponent are positive.
double bdl_rheology_jamming_point(double nu, double y, double exponent, double a);

/// The whole dense branch of the thesis's collapse with soft contacts (Mahajan 2019, eq. 6.3):
/// with D = nu_cr - nu, P* = P_c / D^a1 and g* = shear rate / D^b1 (a1 = 2/3, b1 = (exponent +
/// a1)/2: 7/3 for rods, 4/3 for spheres), P** = P* d / k_n and g** = g* d / sqrt(k_n / (rho d)),
/// P** = (g** / (a2 g** + b2))^2, b2 = 1/sqrt(A). Its inertial limit (g** small) is the law
/// above; as D -> 0 the springs take over and P_c falls again, so at one shear rate the branch
/// has a largest pressure. The contact pressure at distance D:
typedef struct bdl_jamming_branch {
    double exponent, a, a2, stiffness; ///< 2 b1 - a1; A; a2; k_n [N/m]
} bdl_jamming_branch;
double bdl_rheology_branch_pressure(const bdl_jamming_branch *b, double distance, double rate,
                                    double d, double rho);
/// The nu_cr that puts a run's contact pressure p_c on the branch, on its inertial side (D above
/// the peak's, where the pressure does not depend on k_n); below the peak the branch gives p_c a
/// second time, on the springs' side nearer jamming: that nu_cr goes to *near (NAN without a
/// peak, a2 = 0). A p_c above the branch's peak at this rate lies past jamming: *beyond = 1 and
/// nu itself is returned (nu_cr <= nu). NAN for inputs not finite and positive.
double bdl_rheology_jamming_soft(const bdl_jamming_branch *b, double nu, double pc, double rate,
                                 double d, double rho, int *beyond, double *near);

#endif
