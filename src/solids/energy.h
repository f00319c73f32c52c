// bedlam — the granular energy of a solids phase as a transport equation (Sun 2007, eq. 5.5):
//
//   3/2 [d(eps rho theta)/dt + div(eps rho theta v)] = -P tr D + 2 mu D:D + lambda tr(D)^2
//                                                     + div(k_theta grad theta) - gamma,
//
// with Johnson & Jackson's (1987) energy flux through the walls (Sun eq. 5.9): the wall's
// friction C |v_slip|^2 in and (sqrt(3) pi / (4 eps_max)) (1 - e_w^2) eps rho g0 theta^(3/2) out.
// Each cell's equation is point-implicit in its own theta, like the momentum's transport
// (phase.h): the convection is upwind in the Patankar form (only what flows in counts, with the
// neighbour's old theta), the conduction central between cells with the harmonic mean of their
// conductivities (bdl_ktgf_conductivity, of the old theta), no conduction through a wall. The
// cell's terms here are handed to its balance of production and dissipation
// (bdl_ktgf_temperature_step), which stays a cubic in sqrt(theta): the implicit part adds to the
// time term, the neighbours' part and the wall's production to the old energy, and the wall's
// dissipation to the collisions'.
#ifndef BDL_SOLIDS_ENERGY_H
#define BDL_SOLIDS_ENERGY_H

#include "cfd/gas.h"
#include "solids/phase.h"

/// A cell's transport terms, per unit volume: diag theta_P - nb is what its neighbours and walls
/// take (diag [kg/(m^3 s)], nb [W/m^3]), and k4 is added to the collisions' dissipation
/// coefficient (of eps^2 theta^(3/2)).
typedef struct bdl_energy_terms {
    double diag, nb, k4;
} bdl_energy_terms;

/// Before phase m's closures: its old temperatures and its cells' conductivities into the
/// solids' work arrays (the plastic regime's cells and those below the dilute limit conduct
/// nothing).
void bdl_solids_energy_prepare(bdl_solids *s, int m, const bdl_gas *gas);

/// The terms of phase m's cell idx (at: its indices) with radial distribution g0.
bdl_energy_terms bdl_solids_energy_terms(const bdl_solids *s, int m, const bdl_gas *gas, long idx,
                                         const int at[3], double g0);

#endif
