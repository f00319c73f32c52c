// bedlam — verification of the two-fluid model (solids/phase.h): a homogeneous cooling state,
// which checks the granular energy's dissipation inside the full step, and a settling column,
// which checks the solids' momentum with drag and continuity against Kynch's theory, and then
// checks that the plastic regime stops the sediment at packing without overshoot; and a
// manufactured solution of the granular energy's transport equation (solids/energy.h).
#include <math.h>
#include <stdlib.h>

#include "cfd/gas.h"
#include "solids/kinetic.h"
#include "solids/phase.h"
#include "verify/verify.h"

#define PI 3.14159265358979323846

typedef struct tfm_box {
    bdl_gas *gas;
    bdl_solids *solids;
} tfm_box;

/// A closed column of nz cells of h (one cell across, periodic along x and y), walls below and
/// above, gravity g along z.
static bdl_result box_create(tfm_box *b, int nz, double h, double g, const bdl_solids_def *sd)
{
    b->gas = NULL;
    b->solids = NULL;
    bdl_gas_def gd = bdl_default_gas_def();
    gd.n[0] = gd.n[1] = 1, gd.n[2] = nz;
    gd.hi[0] = gd.hi[1] = h, gd.hi[2] = nz * h;
    gd.gravity[2] = g;
    gd.pressure_share = 1;
    gd.convection = BDL_CONVECTION_SUPERBEE;
    gd.tolerance = 1e-11;
    gd.max_iterations = 1000;
    for (int s = 0; s < 4; ++s)
        gd.side[s].type = BDL_SIDE_PERIODIC;
    bdl_result r = bdl_gas_create(&gd, &b->gas);
    if (r == BDL_OK)
        r = bdl_solids_create(sd, b->gas, &b->solids);
    return r;
}

static void box_destroy(tfm_box *b)
{
    bdl_solids_destroy(b->solids);
    bdl_gas_destroy(b->gas);
}

static double *cell(const tfm_box *b, double *f, int k)
{
    return &f[bdl_grid_index(&b->solids->grid, 0, 0, k)];
}

double bdl_verify_tfm_cooling_time(double eps, double theta0, const bdl_solids_def *sd)
{
    // Lun et al. (1984): the collisional dissipation gamma = 12 (1 - e^2) rho eps^2 g0
    // theta^(3/2) / (sqrt(pi) d), in (3/2) rho eps d(theta)/dt = -gamma.
    const double e = sd->restitution, g0 = bdl_g0_carnahan_starling(eps);
    const double gamma_over = 12.0 * (1.0 - e * e) * sd->density * eps * eps * g0 /
                              (sqrt(PI) * sd->diameter); // gamma / theta^(3/2)
    return 3.0 * sd->density * eps / (gamma_over * sqrt(theta0));
}

bdl_result bdl_verify_tfm_cooling(int per_tau, double *error, long *steps)
{
    const double eps = 0.3, theta0 = 0.01, periods = 3.0;
    const bdl_solids_def sd = bdl_default_solids_def();
    const double tau = bdl_verify_tfm_cooling_time(eps, theta0, &sd);
    tfm_box b;
    bdl_result r = box_create(&b, 2, 0.01, 0.0, &sd);
    *error = INFINITY;
    if (r == BDL_OK) {
        for (int k = 0; k < 2; ++k) {
            *cell(&b, b.solids->eps, k) = eps;
            *cell(&b, b.solids->phase[0].theta, k) = theta0;
        }
        bdl_solids_share_voidage(b.solids, b.gas);
        const long n = lrint(periods * per_tau);
        for (long s = 0; s < n && r == BDL_OK; ++s)
            r = bdl_solids_step(b.solids, b.gas, tau / per_tau);
        const double haff = theta0 / ((1.0 + periods) * (1.0 + periods));
        double worst = 0.0;
        for (int k = 0; k < 2; ++k)
            worst = fmax(worst, fabs(*cell(&b, b.solids->phase[0].theta, k) / haff - 1.0));
        if (r == BDL_OK && isfinite(worst))
            *error = worst;
        *steps = n;
    }
    box_destroy(&b);
    return r;
}

/// Height of the suspension's top as a sharp interface: z_ref plus the solids volume above z_ref
/// (a face of every grid) over eps0. The suspension's top is a shock with a structure of its
/// own (the solids take a relaxation time to reach the faster fall of a thinner suspension), so
/// the crossing of a fraction would not converge to Kynch's position; this height moves with the
/// suspension below it whatever the structure.
static double top_interface(const tfm_box *b, double eps0, double z_ref)
{
    const bdl_grid *gr = &b->solids->grid;
    const double h = gr->h[2];
    double above = 0.0;
    for (int k = (int)lrint(z_ref / h); k < gr->n[2]; ++k)
        above += *cell(b, b->solids->eps, k) * h;
    return z_ref + above / eps0;
}

/// The solids fraction of a packed layer whose Schaeffer pressure carries `load` [Pa].
static double packed_fraction(const bdl_solids_def *sd, double load)
{
    double lo = sd->eps_star, hi = 1.0;
    for (int k = 0; k < 200; ++k) {
        const double mid = 0.5 * (lo + hi);
        if (bdl_schaeffer_pressure(mid, 1.0 - mid, 1.0 - sd->eps_star, sd->schaeffer_a,
                                   sd->schaeffer_n) < load)
            lo = mid;
        else
            hi = mid;
    }
    return 0.5 * (lo + hi);
}

bdl_result bdl_verify_tfm_settling(int cells, bdl_verify_sediment *out)
{
    const double height = 0.2, filled = 0.1, eps0 = 0.3, g = 9.81;
    bdl_solids_def sd = bdl_default_solids_def();
    sd.diameter = 100e-6;
    sd.drag = BDL_DRAG_STOKES;
    const double h = height / cells;
    tfm_box b;
    bdl_result r = box_create(&b, cells, h, -g, &sd);
    *out = (bdl_verify_sediment){.eps_low = INFINITY};
    if (r != BDL_OK) {
        box_destroy(&b);
        return r;
    }
    for (int k = 0; k < cells; ++k)
        *cell(&b, b.solids->eps, k) = (k + 0.5) * h < filled ? eps0 : 0.0;
    bdl_solids_share_voidage(b.solids, b.gas);
    const double volume = bdl_solids_volume(b.solids, -1);
    // The uniform suspension: (rho_s eps_g + rho_g eps) dw/dt = (rho_s - rho_g) g - k w / eps_g
    // for the slip w = u - v, with v = -eps_g w (no net volume flux through a layer).
    const double rg = b.gas->def.density, eg = 1.0 - eps0;
    const double k = 18.0 * b.gas->def.viscosity / (sd.diameter * sd.diameter);
    const double fall = eg * eg * (sd.density - rg) * g / k;
    const double tau = eg * (sd.density * eg + rg * eps0) / k;
    const double z_ref = 0.05, t_probe = 0.08, t_end = 0.5, dt = 0.25 * h / fall * (20.0 / cells);
    out->expected = filled - fall * (t_probe - tau * (1.0 - exp(-t_probe / tau)));
    out->fall_speed = fall;
    double t = 0.0;
    while (t < t_end - 1e-12 && r == BDL_OK) {
        const double step = fmin(dt, t_end - t);
        const int probe = t < t_probe && t + step >= t_probe - 1e-12;
        r = bdl_solids_step(b.solids, b.gas, probe ? t_probe - t : step);
        t += probe ? t_probe - t : step;
        out->steps++;
        out->eps_peak = fmax(out->eps_peak, b.solids->stats.eps_max);
        out->eps_low = fmin(out->eps_low, b.solids->stats.eps_min);
        if (probe)
            out->interface = top_interface(&b, eps0, z_ref);
    }
    const double bottom = *cell(&b, b.solids->eps, 0);
    out->eps_bed = bottom;
    out->eps_bed_expected =
        packed_fraction(&sd, (sd.density - rg) * g * (volume / (h * h) - 0.5 * h * bottom));
    out->volume_drift = bdl_solids_volume(b.solids, -1) / volume - 1.0;
    double speed = 0.0;
    for (int kk = 0; kk < cells; ++kk)
        if (*cell(&b, b.solids->eps, kk) > 0.01)
            speed = fmax(speed, fabs(bdl_solids_cell_velocity(b.solids, 0, 2, 0, 0, kk)));
    out->speed_end = speed;
    box_destroy(&b);
    return r;
}

// ---------------------------------------------------------------------------------------------
// The granular energy's transport: a manufactured solution.

static const double mms_length = 0.04, mms_c = 1.7e-3; // m; theta = C / (eps^2 g0), ~0.01 m^2/s^2

static double mms_eps(double x) { return 0.3 + 0.05 * sin(2.0 * PI * x / mms_length); }

static double mms_theta(double x)
{
    const double e = mms_eps(x);
    return mms_c / (e * e * bdl_g0_carnahan_starling(e));
}

/// k_theta dtheta/dx at x, the solids at rest in still gas (the drag at zero slip).
static double mms_heat_flux(const bdl_solids_def *d, const bdl_gas *gas, double x)
{
    const double e = mms_eps(x), g0 = bdl_g0_carnahan_starling(e), dx = 1e-7 * mms_length;
    const double kd = bdl_drag_per_volume(d->drag, &d->drag_params, 1.0 - e, d->diameter, 0.0,
                                          gas->def.density, gas->def.viscosity);
    const double k =
        bdl_ktgf_conductivity(e, g0, d->diameter, d->density, d->restitution, mms_theta(x), e * kd);
    return k * (mms_theta(x + dx) - mms_theta(x - dx)) / (2.0 * dx);
}

/// The fractions and temperatures of the manufactured solution in the cells, and the source
/// that keeps that temperature steady; returns the conduction's largest share of the source.
static double mms_fill(bdl_solids *s, const bdl_gas *gas, double *source)
{
    const bdl_grid *gr = &s->grid;
    const bdl_solids_def *d = &s->def;
    const double dx = 1e-6 * mms_length,
                 k4 = 12.0 * (1.0 - d->restitution * d->restitution) * d->density /
                      (sqrt(PI) * d->diameter),
                 wall = sqrt(3.0) * PI * (1.0 - d->wall_restitution * d->wall_restitution) *
                        d->density / (4.0 * d->eps_star);
    double share = 0.0;
    for (int k = 0; k < 2; ++k)
        for (int i = 0; i < gr->n[0]; ++i) {
            const double x = (i + 0.5) * gr->h[0], e = mms_eps(x), th = mms_theta(x);
            const double g0 = bdl_g0_carnahan_starling(e), th32 = th * sqrt(th);
            const long idx = bdl_grid_index(gr, i, 0, k);
            s->eps[idx] = e;
            s->phase[0].theta[idx] = th;
            const double conduction =
                (mms_heat_flux(d, gas, x + dx) - mms_heat_flux(d, gas, x - dx)) / (2.0 * dx);
            // the collisions, the dissipation at the cell's wall, less what conduction brings
            source[idx] = k4 * g0 * e * e * th32 + wall * e * g0 * th32 / gr->h[2] - conduction;
            share = fmax(share, fabs(conduction / source[idx]));
        }
    bdl_solids_share_voidage(s, (bdl_gas *)gas);
    return share;
}

bdl_result bdl_verify_tfm_energy(int cells, bdl_verify_energy *out)
{
    *out = (bdl_verify_energy){0};
    bdl_solids_def sd = bdl_default_solids_def();
    sd.granular_energy = BDL_GRANULAR_ENERGY_TRANSPORT;
    sd.specularity = 0.3;
    bdl_gas_def gd = bdl_default_gas_def();
    gd.n[0] = cells, gd.n[1] = 1, gd.n[2] = 2; // each layer of cells beside one wall
    gd.hi[0] = mms_length, gd.hi[1] = mms_length / cells, gd.hi[2] = 0.02;
    gd.pressure_share = 1;
    gd.tolerance = 1e-12;
    gd.max_iterations = 1000;
    for (int side = 0; side < 4; ++side)
        gd.side[side].type = BDL_SIDE_PERIODIC; // x and y; walls below and above
    tfm_box b = {NULL, NULL};
    double *source = NULL;
    bdl_result r = bdl_gas_create(&gd, &b.gas);
    if (r == BDL_OK)
        r = bdl_solids_create(&sd, b.gas, &b.solids);
    if (r == BDL_OK && !(source = calloc((size_t)b.gas->grid.size, sizeof *source)))
        r = BDL_ERR_NOMEM;
    if (r == BDL_OK) {
        bdl_solids *s = b.solids;
        const bdl_grid *gr = &s->grid;
        out->conduction_share = mms_fill(s, b.gas, source);
        s->theta_source = source;
        for (int step = 0; step < 4000 && r == BDL_OK; ++step, ++out->steps) {
            r = bdl_solids_step(s, b.gas, 1e-3);
            for (int k = 0; k < 2; ++k)
                for (int i = 0; i < cells; ++i) {
                    const long idx = bdl_grid_index(gr, i, 0, k);
                    out->speed = fmax(
                        out->speed, fmax(fabs(s->phase[0].v[0][idx]), fabs(s->phase[0].v[2][idx])));
                }
        }
        for (int k = 0; k < 2; ++k)
            for (int i = 0; i < cells; ++i) {
                const double x = (i + 0.5) * gr->h[0];
                const double th = s->phase[0].theta[bdl_grid_index(gr, i, 0, k)];
                out->error = fmax(out->error, fabs(th / mms_theta(x) - 1.0));
            }
        s->theta_source = NULL;
    }
    free(source);
    box_destroy(&b);
    return r;
}
