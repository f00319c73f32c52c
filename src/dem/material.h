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

#include "core/names.h"

/// Normal contact law, chosen per scene ([contact] law).
#define BDL_NORMAL_LAWS(X)                                                                         \
    X(LAW_LINEAR, "linear", "linear spring-dashpot: F = k_n delta - gamma v_n")                    \
    X(LAW_HERTZ, "hertz", "Hertz-Mindlin with delta^(1/4)-scaled (restitution-based) damping")
BDL_CHOICES(bdl_normal_law, BDL_NORMAL_LAWS);

/// How the damping coefficient is obtained from the restitution ([contact] damping).
#define BDL_DAMPING_MODES(X)                                                                       \
    X(DAMPING_EXACT, "exact", "solved once per pair so that the realised restitution matches")     \
    X(DAMPING_CLOSED_FORM, "closed_form", "the closed form of LIGGGHTS/EDEM (approximate at low e)")
BDL_CHOICES(bdl_damping_mode, BDL_DAMPING_MODES);

/// Rolling resistance model ([contact] rolling).
#define BDL_ROLLING_MODELS(X)                                                                      \
    X(ROLLING_NONE, "none", "none")                                                                \
    X(ROLLING_CONSTANT, "constant", "constant directional torque mu_r R* |F_n| against rolling")
BDL_CHOICES(bdl_rolling_model, BDL_ROLLING_MODELS);

/// Material and contact parameters shared by species, pair overrides and walls.
/// A value < 0 means "not given" where a default is derived (documented per key).
typedef struct bdl_material {
    double youngs_modulus;           ///< E [Pa] (Hertz law); < 0 if not given
    double poisson_ratio;            ///< nu [-]
    double stiffness;                ///< k_n [N/m] (linear law); < 0 if not given
    double tangential_stiffness;     ///< k_t [N/m] (linear law); < 0 -> 2/7 k_n
    double restitution;              ///< normal coefficient of restitution e in (0, 1]
    double tangential_damping_ratio; ///< gamma_t / gamma_n [-] (default 0: no tangential dashpot)
    double friction;                 ///< sliding friction coefficient mu [-]
    double rolling_friction;         ///< rolling friction coefficient mu_r [-]
} bdl_material;

/// Override of contact parameters for one pair of species ([pair A B]). Only the fields flagged
/// in `has_*` replace the mixed values.
typedef struct bdl_pair_def {
    int species_a, species_b; ///< species indices
    int has_restitution, has_friction, has_rolling_friction, has_stiffness;
    double restitution, friction, rolling_friction, stiffness;
} bdl_pair_def;

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

/// Restitution realised by a contact with damping coefficient c (zeta for linear) and the normal
/// force clamped at zero (no attraction). With BDL_DAMPING_EXACT, bdl_contact_table_build inverts
/// it numerically for the damping that realises the configured e (see material.c).
double bdl_restitution_of(int hertz, double c);
/// Duration of the damped, clamped impact relative to the elastic one.
double bdl_contact_duration_ratio(int hertz, double c);

/// What the table of contact parameters is mixed from.
typedef struct bdl_contact_table_def {
    bdl_normal_law law;
    bdl_damping_mode damping;
    int species_count;
    const bdl_material *species; ///< one material per species
    int pair_count;
    const bdl_pair_def *pairs; ///< overrides per species pair
    int wall_count;
    const bdl_material *walls; ///< one material per wall (fields < 0: the species' own)
} bdl_contact_table_def;

/// Fills params for every species pair (species_count^2, symmetric) and every wall-species pair
/// (wall_count * species_count, index wall * species_count + species).
void bdl_contact_table_build(const bdl_contact_table_def *def, bdl_contact_params *pair_params,
                             bdl_contact_params *wall_params);

/// Duration of a contact [s]: the elastic one, linear pi sqrt(m*/k_n) or Hertz
/// 2.87 (m*^2 / (R* E*^2 v))^(1/5) at impact speed v, times the duration ratio of the damped,
/// clamped impact (which ends sooner the stronger the damping).
double bdl_contact_time(const bdl_contact_params *cp, bdl_normal_law law, double m_eff,
                        double r_eff, double impact_speed);

#endif
