// bedlam — contact parameters per species pair and per species–wall pair.
//
// Species carry material data (Young's modulus and Poisson ratio for the Hertz law, spring
// constants for the linear law, restitution, friction). Here they are mixed once into a table of
// bdl_contact_params, pair overrides applied, and the damping coefficient that realises the
// configured restitution is solved for.
//
// Mixing rules (docs/theory-dem.md):
//   1/E* = (1 - nu_i^2)/E_i + (1 - nu_j^2)/E_j            1/G* = (2 - nu_i)/G_i + (2 - nu_j)/G_j
//   k_n  = 2 k_i k_j / (k_i + k_j)   (two equal springs give k)
//   e, mu, mu_r: arithmetic mean of the two sides.
// A wall acts as a body of infinite mass and radius; where a wall material key is not given the
// particle species' own value is used.
#ifndef BDL_MATERIAL_H
#define BDL_MATERIAL_H

#include "scene/scene.h"

typedef struct bdl_contact_params {
    double kn;     ///< linear law: normal stiffness [N/m]
    double kt;     ///< linear law: tangential stiffness [N/m]
    double e_star; ///< Hertz law: effective Young's modulus E* [Pa]
    double g_star; ///< Hertz law: effective shear modulus G* [Pa]
    double
        damping; ///< linear: damping ratio zeta [-]; Hertz: coefficient c [-] (see contact_law.h)
    double tangential_damping_ratio; ///< eta_t / eta_n [-]
    double friction;                 ///< Coulomb coefficient mu [-]
    double rolling_friction;         ///< mu_r [-]
    double restitution;              ///< configured e [-]
    double duration_ratio;           ///< damped (clamped) contact duration / elastic duration [-]
} bdl_contact_params;

/// Closed-form damping ratio of a linear spring-dashpot whose force may turn attractive:
/// zeta = -ln e / sqrt(pi^2 + ln^2 e).
double bdl_linear_damping_ratio(double restitution);
/// The closed form used by LIGGGHTS/EDEM for Hertz: c = sqrt(5) zeta(e).
double bdl_hertz_damping_closed_form(double restitution);

/// Damping coefficients that realise restitution e exactly with the normal force clamped at zero
/// (no attraction): solved numerically on the dimensionless impact (see material.c).
double bdl_linear_damping_exact(double restitution);
double bdl_hertz_damping_exact(double restitution);

/// Restitution realised by a contact with damping coefficient c (zeta for linear) and the clamp.
double bdl_restitution_of(int hertz, double c);
/// Duration of the damped, clamped impact relative to the elastic one.
double bdl_contact_duration_ratio(int hertz, double c);
double bdl_hertz_restitution_of(double c);

/// Fills params for every species pair (species_count^2, symmetric) and every wall-species pair
/// (wall_count * species_count, index wall * species_count + species).
void bdl_contact_table_build(const bdl_scene *scene, bdl_contact_params *pair_params,
                             bdl_contact_params *wall_params);

/// Duration of a contact [s]: the elastic one, linear pi sqrt(m*/k_n) or Hertz
/// 2.87 (m*^2 / (R* E*^2 v))^(1/5) at impact speed v, times the duration ratio of the damped,
/// clamped impact (which ends sooner the stronger the damping).
double bdl_contact_time(const bdl_contact_params *cp, bdl_normal_law law, double m_eff,
                        double r_eff, double impact_speed);

#endif
