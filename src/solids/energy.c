// bedlam — the granular energy's transport (solids/energy.h).
#include "solids/energy.h"

#include <math.h>

#include "solids/kinetic.h"

enum { OLD_THETA = 12, CONDUCTIVITY = 11 }; ///< the solids' work arrays this uses

static const double pi = 3.14159265358979323846;

void bdl_solids_energy_prepare(bdl_solids *s, int m, const bdl_gas *gas)
{
    const bdl_grid *gr = &s->grid;
    const bdl_solids_phase *p = &s->phase[m];
    const bdl_solids_def *d = &p->def;
    double *old = s->work[OLD_THETA], *kappa = s->work[CONDUCTIVITY];
    for (int k = 0; k < gr->n[2]; ++k)
        for (int j = 0; j < gr->n[1]; ++j)
            for (int i = 0; i < gr->n[0]; ++i) {
                const long idx = bdl_grid_index(gr, i, j, k);
                const double eps = p->eps[idx], total = s->eps[idx], theta = p->theta[idx];
                old[idx] = theta;
                kappa[idx] = 0.0;
                if (total >= s->def.eps_star || !(eps > d->dilute) || !(theta > 0.0))
                    continue;
                const double g0 = bdl_solids_phase_g0(s, m, idx);
                const double kd = bdl_drag_per_volume(
                    d->drag, &d->drag_params, 1.0 - total, d->diameter,
                    bdl_solids_cell_slip(s, m, gas, i, j, k), gas->def.density, gas->def.viscosity);
                kappa[idx] = bdl_ktgf_conductivity(eps, g0, d->diameter, d->density, d->restitution,
                                                   theta, eps * kd);
            }
    bdl_grid_extend_cells(gr, old);
    bdl_grid_extend_cells(gr, kappa);
}

/// Whether side `side` (2a + s) of the domain is a wall of the gas (an inlet or outlet is not).
static int wall_side(const bdl_gas *gas, int side)
{
    const bdl_gas_side_type t = gas->def.side[side].type;
    return t == BDL_SIDE_WALL || t == BDL_SIDE_SLIP;
}

bdl_energy_terms bdl_solids_energy_terms(const bdl_solids *s, int m, const bdl_gas *gas, long idx,
                                         const int at[3], double g0)
{
    const bdl_grid *gr = &s->grid;
    const bdl_solids_phase *p = &s->phase[m];
    const bdl_solids_def *d = &p->def;
    const double *old = s->work[OLD_THETA], *kappa = s->work[CONDUCTIVITY];
    const double rho = d->density, eps = p->eps[idx];
    bdl_energy_terms t = {0.0, 0.0, 0.0};
    for (int a = 0; a < 3; ++a) {
        // One cell along a: across a period its own image, between walls no flux (and no wall
        // friction: the momentum has none there either, phase.c: viscous).
        if (gr->n[a] == 1)
            continue;
        const long sa = gr->stride[a];
        const double h = gr->h[a];
        for (int side = 0; side < 2; ++side) {
            const long nb = side ? idx + sa : idx - sa;
            const int edge = side ? at[a] == gr->n[a] - 1 : at[a] == 0;
            if (edge && !gr->periodic[a]) { // a wall, an inlet or an outlet: no flux but a wall's
                if (d->specularity > 0.0 && wall_side(gas, 2 * a + side)) {
                    double v2 = 0.0; // the slip along the wall
                    for (int b = 0; b < 3; ++b) {
                        const double v =
                            b == a ? 0.0 : bdl_solids_cell_velocity(s, m, b, at[0], at[1], at[2]);
                        v2 += v * v;
                    }
                    const double c = pi * sqrt(3.0) * d->specularity * rho * eps * g0 *
                                     sqrt(old[idx]) / (6.0 * d->eps_star);
                    t.nb += c * v2 / h;
                    t.k4 += sqrt(3.0) * pi *
                            (1.0 - s->def.wall_restitution * s->def.wall_restitution) * rho * g0 /
                            (4.0 * d->eps_star * eps * h);
                }
                continue;
            }
            // Convection: what flows in through this face, with the neighbour's theta.
            const double f = side ? -p->flux[a][idx + sa] : p->flux[a][idx];
            const double in = 1.5 * rho * fmax(f, 0.0) / h;
            t.diag += in;
            t.nb += in * old[nb];
            // Conduction: the harmonic mean of the two cells' conductivities.
            const double kp = kappa[idx], kn = kappa[nb];
            const double kf = kp > 0.0 && kn > 0.0 ? 2.0 * kp * kn / (kp + kn) : 0.0;
            t.diag += kf / (h * h);
            t.nb += kf * old[nb] / (h * h);
        }
    }
    if (s->theta_source)
        t.nb += s->theta_source[idx];
    return t;
}
