// bedlam — gas solver: boundary ghosts, TVD convection, projection with implicit drag.
#include "core/minmax.h"
#include "core/parallel.h"
#include "cfd/gas.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define G BDL_GRID_GHOST

BDL_CHOICE_WORDS(bdl_gas_side, BDL_GAS_SIDES);
BDL_CHOICE_WORDS(bdl_convection, BDL_CONVECTIONS);
const char *const bdl_convection_labels[] = {BDL_CONVECTIONS(BDL_ENUM_LABEL) NULL};
BDL_CHOICE_WORDS(bdl_convection_step, BDL_CONVECTION_STEPS);
const char *const bdl_convection_step_labels[] = {BDL_CONVECTION_STEPS(BDL_ENUM_LABEL) NULL};

static int periodic_axis(const bdl_gas *g, int a)
{
    return g->def.side[2 * a].type == BDL_SIDE_PERIODIC;
}

bdl_gas_def bdl_default_gas_def(void)
{
    bdl_gas_def d;
    memset(&d, 0, sizeof d);
    for (int a = 0; a < 3; ++a) {
        d.n[a] = 1;
        d.hi[a] = 1.0;
    }
    d.density = 1.2; // air at 20 C
    d.viscosity = 1.8e-5;
    d.convection = BDL_CONVECTION_VANLEER;
    d.tolerance = 1e-8;
    d.max_iterations = 200;
    return d; // every side a no-slip wall, no gravity
}

/// An inlet through a porous plate: a fixed pressure (the plenum's) behind a resistance, which
/// the pressure solver sees as a Dirichlet side whose face coefficient is h / (2 R) (gas.h).
static int distributor(const bdl_gas_side *sd)
{
    return sd->type == BDL_SIDE_INLET && sd->resistance > 0.0;
}

bdl_result bdl_gas_create(const bdl_gas_def *def, bdl_gas **out)
{
    *out = NULL;
    if (!(def->tolerance > 0.0) || def->max_iterations < 1 || !(def->density > 0.0) ||
        !(def->viscosity > 0.0))
        return BDL_ERR_ARGS;
    int periodic[3];
    for (int a = 0; a < 3; ++a) {
        int lo = def->side[2 * a].type == BDL_SIDE_PERIODIC;
        int hi = def->side[2 * a + 1].type == BDL_SIDE_PERIODIC;
        if (lo != hi)
            return BDL_ERR_ARGS;
        periodic[a] = lo;
    }
    for (int s = 0; s < 6; ++s)
        if (!(def->side[s].resistance >= 0.0) || (distributor(&def->side[s]) && def->side[s].jet))
            return BDL_ERR_ARGS;
    bdl_gas *g = calloc(1, sizeof *g);
    if (!g)
        return BDL_ERR_NOMEM;
    g->def = *def;
    if (!bdl_grid_init(&g->grid, def->n, def->lo, def->hi, periodic)) {
        free(g);
        return BDL_ERR_ARGS;
    }
    int dirichlet[6];
    for (int s = 0; s < 6; ++s)
        dirichlet[s] = def->side[s].type == BDL_SIDE_OUTLET || distributor(&def->side[s]);
    g->poisson = bdl_poisson_create_solver(&g->grid, dirichlet, def->pressure_solver);
    int ok = g->poisson != NULL;
    for (int a = 0; a < 3; ++a) {
        g->u[a] = bdl_grid_alloc(&g->grid);
        g->bv[a] = bdl_grid_alloc(&g->grid);
        g->beta[a] = bdl_grid_alloc(&g->grid);
        g->source[a] = bdl_grid_alloc(&g->grid);
        g->ustar[a] = bdl_grid_alloc(&g->grid);
        g->coef[a] = bdl_grid_alloc(&g->grid);
        g->d[a] = bdl_grid_alloc(&g->grid);
        if (def->pressure_share)
            ok = ok && (g->share[a] = bdl_grid_alloc(&g->grid)) &&
                 (g->grad_p[a] = bdl_grid_alloc(&g->grid)) &&
                 (g->flux_u[a] = bdl_grid_alloc(&g->grid)) &&
                 (g->flux_p[a] = bdl_grid_alloc(&g->grid)) &&
                 (g->flux_0[a] = bdl_grid_alloc(&g->grid));
        ok = ok && g->u[a] && g->bv[a] && g->beta[a] && g->source[a] && g->ustar[a] && g->coef[a] &&
             g->d[a];
    }
    g->p = bdl_grid_alloc(&g->grid);
    g->eps = bdl_grid_alloc(&g->grid);
    g->eps_old = bdl_grid_alloc(&g->grid);
    g->rhs = bdl_grid_alloc(&g->grid);
    ok = ok && g->p && g->eps && g->eps_old && g->rhs;
    if (!ok) {
        bdl_gas_destroy(g);
        return BDL_ERR_NOMEM;
    }
    for (long i = 0; i < g->grid.size; ++i)
        g->eps[i] = g->eps_old[i] = 1.0;
    *out = g;
    return BDL_OK;
}

void bdl_gas_destroy(bdl_gas *g)
{
    if (!g)
        return;
    bdl_poisson_destroy(g->poisson);
    for (int a = 0; a < 3; ++a) {
        free(g->u[a]);
        free(g->bv[a]);
        free(g->beta[a]);
        free(g->source[a]);
        free(g->ustar[a]);
        free(g->coef[a]);
        free(g->d[a]);
        free(g->share[a]);
        free(g->grad_p[a]);
        free(g->flux_u[a]);
        free(g->flux_p[a]);
        free(g->flux_0[a]);
    }
    free(g->p);
    free(g->eps);
    free(g->eps_old);
    free(g->rhs);
    free(g);
}

// ---------------------------------------------------------------------------------------------
// Ghost values.

/// Superficial inflow through the boundary face at padded index `idx` of side `side`.
static double inflow_at(const bdl_gas *g, int side, long idx)
{
    const bdl_gas_side *sd = &g->def.side[side];
    if (!sd->jet)
        return sd->inflow;
    const bdl_grid *gr = &g->grid;
    const int a = side / 2;
    int ix[3];
    bdl_grid_position(gr, idx, ix);
    for (int b = 0; b < 3; ++b) {
        if (b == a)
            continue;
        double x = gr->origin[b] + (ix[b] + 0.5) * gr->h[b];
        if (x < sd->jet_lo[b] || x > sd->jet_hi[b])
            return sd->inflow;
    }
    return sd->jet_inflow;
}

static double face_eps(const bdl_gas *g, const double *eps, int a, long idx)
{
    return 0.5 * (eps[idx] + eps[idx - g->grid.stride[a]]);
}

/// Boundary and ghost values of velocity component a (the normal faces of a side hold the
/// boundary condition; ghost faces and ghost rows mirror it).
static void velocity_ghosts(const bdl_gas *g, int a, double *u, const double *eps)
{
    const bdl_grid *gr = &g->grid;
    for (int b = 0; b < 3; ++b) {
        const long s = gr->stride[b];
        const int n = gr->n[b];
        if (gr->periodic[b]) {
            bdl_grid_wrap_axis(gr, u, b, b == a);
            continue;
        }
        for (int side = 0; side < 2; ++side) {
            const bdl_gas_side *sd = &g->def.side[2 * b + side];
            const double dir = side == 0 ? 1.0 : -1.0; // into the domain
            if (b == a) {
                // Normal faces: the boundary face at 0 or n, ghosts beyond it.
                BDL_GRID_FOR_PLANE(gr, b, side == 0 ? 0 : n, {
                    if (sd->type == BDL_SIDE_WALL || sd->type == BDL_SIDE_SLIP)
                        u[idx] = 0.0;
                    else if (sd->type == BDL_SIDE_INLET && !distributor(sd))
                        u[idx] = dir * inflow_at(g, 2 * b + side, idx) / face_eps(g, eps, b, idx);
                    for (int l = 1; l <= G; ++l) {
                        long ghost = idx - (long)dir * l * s, mirror = idx + (long)dir * l * s;
                        int odd = sd->type == BDL_SIDE_WALL || sd->type == BDL_SIDE_SLIP;
                        u[ghost] = odd ? -u[mirror] : u[idx];
                    }
                });
            } else {
                // Tangential rows: ghost cells beyond the side.
                const double w = sd->type == BDL_SIDE_WALL ? sd->wall_velocity[a] : 0.0;
                BDL_GRID_FOR_PLANE(gr, b, side == 0 ? 0 : n - 1, {
                    for (int l = 1; l <= G; ++l) {
                        long ghost = idx - (long)dir * l * s;
                        long mirror = idx + (long)dir * (l - 1) * s;
                        switch (sd->type) {
                        case BDL_SIDE_WALL:
                        case BDL_SIDE_INLET:
                            u[ghost] = 2.0 * w - u[mirror];
                            break;
                        case BDL_SIDE_SLIP:
                            u[ghost] = u[mirror];
                            break;
                        default: // outlet: zero gradient
                            u[ghost] = u[idx];
                            break;
                        }
                    }
                });
            }
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Convection.

/// The value at the face between m1 and p1, upwinded by the sign of the flux q, with a TVD
/// limiter on the second-order correction.
static double face_value(bdl_convection scheme, double q, double m2, double m1, double p1,
                         double p2)
{
    double up, c, down;
    if (q >= 0.0) {
        up = m2, c = m1, down = p1;
    } else {
        up = p2, c = p1, down = m1;
    }
    if (scheme == BDL_CONVECTION_CENTRAL)
        return 0.5 * (m1 + p1);
    double delta = down - c;
    if (scheme == BDL_CONVECTION_UPWIND || delta == 0.0)
        return c;
    double r = (c - up) / delta, psi;
    if (scheme == BDL_CONVECTION_SUPERBEE)
        psi = bdl_max(0.0, bdl_max(bdl_min(2.0 * r, 1.0), bdl_min(r, 2.0)));
    else
        psi = (r + fabs(r)) / (1.0 + fabs(r));
    return c + 0.5 * psi * delta;
}

/// div(eps u u_a) at the a-face `idx`, with q[b] = eps u_b on the b-faces, by the scheme
/// (`value`) and by upwinding (`upwind`), and the outflow through the face's control volume
/// (`out`, 1/s times eps: the upwind form's diagonal, upwind = out u_a - inflows).
typedef struct convection_terms {
    double value, upwind, out;
} convection_terms;

static convection_terms convection(const bdl_gas *g, int a, long idx, const double *u,
                                   double *const q[3])
{
    const bdl_grid *gr = &g->grid;
    const bdl_convection sc = g->def.convection;
    const long sa = gr->stride[a];
    convection_terms t = {0.0, 0.0, 0.0};
    for (int b = 0; b < 3; ++b) {
        // One cell along b: between walls the b-fluxes vanish on both faces, and across a period
        // of one cell they are equal; either way the b-term is zero.
        if (gr->n[b] == 1)
            continue;
        const long s = gr->stride[b];
        double qhi, qlo;
        if (b == a) {
            qhi = 0.5 * (q[a][idx] + q[a][idx + s]);
            qlo = 0.5 * (q[a][idx - s] + q[a][idx]);
        } else {
            qhi = 0.5 * (q[b][idx + s] + q[b][idx + s - sa]);
            qlo = 0.5 * (q[b][idx] + q[b][idx - sa]);
        }
        const double um = u[idx - s], u0 = u[idx], up = u[idx + s];
        double fhi = qhi * face_value(sc, qhi, um, u0, up, u[idx + 2 * s]);
        double flo = qlo * face_value(sc, qlo, u[idx - 2 * s], um, u0, up);
        t.value += (fhi - flo) / gr->h[b];
        t.upwind += (qhi * (qhi >= 0.0 ? u0 : up) - qlo * (qlo >= 0.0 ? um : u0)) / gr->h[b];
        t.out += (bdl_max(qhi, 0.0) + bdl_max(-qlo, 0.0)) / gr->h[b];
    }
    return t;
}

/// The Laplacian of u at idx, inv_h2[b] = 1 / h_b^2 (a flat axis adds nothing: its neighbours
/// are the cell itself).
static double laplacian(const bdl_grid *gr, long idx, const double *u, const double inv_h2[3])
{
    double sum = 0.0;
    for (int b = 0; b < 3; ++b) {
        const long s = gr->stride[b];
        if (s != 0)
            sum += (u[idx + s] - 2.0 * u[idx] + u[idx - s]) * inv_h2[b];
    }
    return sum;
}

// ---------------------------------------------------------------------------------------------
// The step.

/// Range of unknown faces of component a along a: [lo, hi].
static void unknown_faces(const bdl_gas *g, int a, int *lo, int *hi)
{
    const int n = g->grid.n[a];
    if (periodic_axis(g, a)) {
        *lo = 0;
        *hi = n - 1;
        return;
    }
    *lo = g->def.side[2 * a].type == BDL_SIDE_OUTLET ? 0 : 1;
    *hi = g->def.side[2 * a + 1].type == BDL_SIDE_OUTLET ? n : n - 1;
}

#define FOR_FACES(gr, a, flo, fhi, ...)                                                            \
    BDL_PARALLEL_FOR((gr)->size >= BDL_GRID_PARALLEL_MIN,                                          \
                     for (int k = 0; k < (gr)->n[2] + ((a) == 2);                                  \
                          ++k) for (int j = 0; j < (gr)->n[1] + ((a) == 1);                        \
                                    ++j) for (int i = 0; i < (gr)->n[0] + ((a) == 0); ++i) {       \
                         const int ia_ = (a) == 0 ? i : (a) == 1 ? j : k;                          \
                         if (ia_ < (flo) || ia_ > (fhi))                                           \
                             continue;                                                             \
                         const long idx = bdl_grid_index(gr, i, j, k);                             \
                         __VA_ARGS__;                                                              \
                     })

/// The particles' volume flux still to come on the face at idx of axis a (gas.h: flux_u, flux_p,
/// flux_0) for the face velocity u, with the pressure gradient's part when `grad` (NULL: without).
static double solids_flux(const bdl_gas *g, int a, long idx, const double *u, const double *grad)
{
    if (!g->flux_u[a])
        return 0.0;
    const double f = g->flux_u[a][idx] * u[idx] + g->flux_0[a][idx];
    return grad ? f - g->flux_p[a][idx] * grad[idx] : f;
}

/// d eps/dt + div(eps u + the particles' flux still to come) in the cell at idx, for face
/// velocities u (and face pressure gradients grad, NULL: the flux's part in it left out).
static double volume_change(const bdl_gas *g, double *const u[3], double *const grad[3], long idx,
                            double dt)
{
    const bdl_grid *gr = &g->grid;
    double div = (g->eps[idx] - g->eps_old[idx]) / dt;
    for (int a = 0; a < 3; ++a) {
        const long s = gr->stride[a];
        const double *ga = grad ? grad[a] : NULL;
        div += (face_eps(g, g->eps, a, idx + s) * u[a][idx + s] -
                face_eps(g, g->eps, a, idx) * u[a][idx] + solids_flux(g, a, idx + s, u[a], ga) -
                solids_flux(g, a, idx, u[a], ga)) /
               gr->h[a];
    }
    return div;
}

/// Volume fluxes eps u on every face (ghosts included), for the convection.
static void face_fluxes(bdl_gas *g, double *q[3])
{
    const bdl_grid *gr = &g->grid;
    for (int a = 0; a < 3; ++a) {
        const long s = gr->stride[a];
        BDL_PARALLEL_FOR(gr->size >= BDL_GRID_PARALLEL_MIN,
                         for (long idx = s; idx < gr->size; ++idx) q[a][idx] =
                             0.5 * (g->eps_old[idx] + g->eps_old[idx - s]) * g->u[a][idx];);
    }
}

/// Predictor u* with the drag implicit, and d = eps / (rho eps / dt + beta), on the unknown faces.
static void predict(bdl_gas *g, double *const q[3], const int active[3], double dt)
{
    const bdl_grid *gr = &g->grid;
    const double rho = g->def.density, mu = g->def.viscosity, rho_dt = rho / dt;
    const int implicit = g->def.convection_step == BDL_CONVECTION_POINT_IMPLICIT;
    double inv_h2[3];
    for (int b = 0; b < 3; ++b)
        inv_h2[b] = 1.0 / (gr->h[b] * gr->h[b]);
    for (int a = 0; a < 3; ++a) {
        if (!active[a])
            continue;
        int flo, fhi;
        unknown_faces(g, a, &flo, &fhi);
        const double *u = g->u[a];
        double *us = g->ustar[a], *d = g->d[a];
        FOR_FACES(gr, a, flo, fhi, {
            const double e0 = face_eps(g, g->eps_old, a, idx), e1 = face_eps(g, g->eps, a, idx);
            const double beta = g->beta[a][idx], bv = g->bv[a][idx];
            const convection_terms ct = convection(g, a, idx, u, q);
            double A = rho_dt * e1 + beta, conv = ct.value;
            if (implicit) { // out u* - inflows, the correction explicit (gas.h)
                A += rho * ct.out;
                const double weight = bdl_min(1.0, e1 / (dt * ct.out)); // 1 / Courant, at most 1
                conv = ct.upwind - ct.out * u[idx] + (ct.value - ct.upwind) * weight;
            }
            const double r = rho_dt * e0 * u[idx] - rho * conv +
                             mu * e0 * laplacian(gr, idx, u, inv_h2) +
                             e1 * rho * g->def.gravity[a] + bv + g->source[a][idx];
            const double inv_A = 1.0 / A;
            us[idx] = r * inv_A;
            d[idx] = (g->share[a] ? g->share[a][idx] : e1) * inv_A;
        });
    }
}

/// u* on the boundary faces: prescribed, or (outlets) extrapolated; periodic images copied.
static void boundary_faces(bdl_gas *g, double dt)
{
    const bdl_grid *gr = &g->grid;
    const double rho = g->def.density;
    for (int a = 0; a < 3; ++a) {
        const long s = gr->stride[a];
        const int n = gr->n[a];
        const double h = gr->h[a];
        if (periodic_axis(g, a)) {
            bdl_grid_copy_plane(gr, g->ustar[a], a, n, 0);
            bdl_grid_copy_plane(gr, g->d[a], a, n, 0);
            if (g->flux_u[a]) {
                bdl_grid_copy_plane(gr, g->flux_u[a], a, n, 0);
                bdl_grid_copy_plane(gr, g->flux_p[a], a, n, 0);
                bdl_grid_copy_plane(gr, g->flux_0[a], a, n, 0);
            }
            continue;
        }
        for (int side = 0; side < 2; ++side) {
            const bdl_gas_side *sd = &g->def.side[2 * a + side];
            double *us = g->ustar[a], *d = g->d[a];
            BDL_GRID_FOR_PLANE(gr, a, side == 0 ? 0 : n, {
                if (sd->type == BDL_SIDE_OUTLET)
                    us[idx] = us[idx + (side == 0 ? s : -s)];
                else if (distributor(sd)) // all of the flux through the plate's resistance
                    us[idx] = 0.0,
                    d[idx] = 0.5 * h / (sd->resistance * face_eps(g, g->eps, a, idx));
                else if (sd->type == BDL_SIDE_INLET)
                    us[idx] = (side == 0 ? 1.0 : -1.0) * inflow_at(g, 2 * a + side, idx) /
                              face_eps(g, g->eps, a, idx);
                else
                    us[idx] = 0.0;
                if (sd->type == BDL_SIDE_OUTLET) {
                    double e1 = face_eps(g, g->eps, a, idx);
                    d[idx] =
                        (g->share[a] ? g->share[a][idx] : e1) / (rho * e1 / dt + g->beta[a][idx]);
                }
            });
        }
    }
}

/// The pressure equation div(c grad p) = div(eps u* + E u* + F) + d eps / dt, c = eps d + E d +
/// C (gas.h); returns whether the solver converged.
static int solve_pressure(bdl_gas *g, double dt, const double p_side[6])
{
    const bdl_grid *gr = &g->grid;
    for (int a = 0; a < 3; ++a) {
        const long s = gr->stride[a];
        double *c = g->coef[a];
        BDL_PARALLEL_FOR(gr->size >= BDL_GRID_PARALLEL_MIN,
                         for (long idx = s; idx < gr->size; ++idx) c[idx] =
                             0.5 * (g->eps[idx] + g->eps[idx - s]) * g->d[a][idx];);
        if (g->flux_u[a])
            for (long idx = s; idx < gr->size; ++idx)
                c[idx] += g->flux_u[a][idx] * g->d[a][idx] + g->flux_p[a][idx];
    }
    bdl_poisson_set_coefficients(g->poisson, g->coef);
    BDL_PARALLEL_FOR(
        gr->size >= BDL_GRID_PARALLEL_MIN,
        for (int k = 0; k < gr->n[2]; ++k) for (int j = 0; j < gr->n[1];
                                                ++j) for (int i = 0; i < gr->n[0]; ++i) {
            const long idx = bdl_grid_index(gr, i, j, k);
            g->rhs[idx] = volume_change(g, g->ustar, NULL, idx, dt);
        });
    int converged = bdl_poisson_solve(g->poisson, g->p, g->rhs, p_side, g->def.tolerance,
                                      g->def.max_iterations, &g->last_solve);
    bdl_grid_wrap_cells(gr, g->p);
    return converged;
}

/// u = u* - d grad p on the unknown faces; prescribed boundary faces keep u*.
static void correct(bdl_gas *g, const int active[3], const double p_side[6])
{
    const bdl_grid *gr = &g->grid;
    for (int a = 0; a < 3; ++a) {
        if (!active[a])
            continue;
        int flo, fhi;
        unknown_faces(g, a, &flo, &fhi);
        if (!periodic_axis(g, a)) { // a plate's faces follow from the pressure as an outlet's do
            flo = distributor(&g->def.side[2 * a]) ? 0 : flo;
            fhi = distributor(&g->def.side[2 * a + 1]) ? gr->n[a] : fhi;
        }
        const long s = gr->stride[a];
        const int n = gr->n[a];
        const double h = gr->h[a], p_lo = p_side[2 * a], p_hi = p_side[2 * a + 1];
        const int periodic = periodic_axis(g, a);
        double *u = g->u[a];
        const double *us = g->ustar[a], *d = g->d[a], *p = g->p;
        memcpy(u, us, (size_t)gr->size * sizeof(double));
        FOR_FACES(gr, a, flo, fhi, {
            const int ia = a == 0 ? i : a == 1 ? j : k;
            double grad;
            if (!periodic && ia == 0)
                grad = 2.0 * (p[idx] - p_lo) / h;
            else if (!periodic && ia == n)
                grad = 2.0 * (p_hi - p[idx - s]) / h;
            else
                grad = (p[idx] - p[idx - s]) / h;
            u[idx] = us[idx] - d[idx] * grad;
            if (g->grad_p[a])
                g->grad_p[a][idx] = grad;
        });
        if (periodic) {
            bdl_grid_copy_plane(gr, u, a, n, 0);
            if (g->grad_p[a])
                bdl_grid_copy_plane(gr, g->grad_p[a], a, n, 0);
        }
    }
}

/// The volume balance of the gas in every cell after the step (into mass_imbalance); returns
/// whether every velocity is finite.
static int check_balance(bdl_gas *g, double dt)
{
    const bdl_grid *gr = &g->grid;
    int finite = 1;
    double worst = 0.0;
    for (int k = 0; k < gr->n[2]; ++k)
        for (int j = 0; j < gr->n[1]; ++j)
            for (int i = 0; i < gr->n[0]; ++i) {
                const long idx = bdl_grid_index(gr, i, j, k);
                for (int a = 0; a < 3; ++a)
                    finite = finite && isfinite(g->u[a][idx]);
                worst = fmax(worst, fabs(volume_change(g, g->u, g->grad_p, idx, dt)) * dt);
            }
    g->mass_imbalance = worst;
    return finite;
}

/// The plenum pressure under distributor side `side` that makes the plate's inflow average the
/// side's superficial velocity U with the pressures p of the cells above it: P = mean(p) + U R
/// (a uniform grid: every face has the same area). Stored in g->plenum.
static double plenum_pressure(bdl_gas *g, int side)
{
    const int a = side / 2, layer = side % 2 ? g->grid.n[a] - 1 : 0;
    const bdl_gas_side *sd = &g->def.side[side];
    g->plenum[side] = bdl_grid_layer_mean(&g->grid, g->p, a, layer) + sd->inflow * sd->resistance;
    return g->plenum[side];
}

int bdl_gas_axis_inert(const bdl_gas *g, int a)
{
    const bdl_grid *gr = &g->grid;
    if (gr->n[a] != 1 || !gr->periodic[a] || g->def.gravity[a] != 0.0)
        return 0;
    for (int s = 0; s < 6; ++s)
        if (g->def.side[s].wall_velocity[a] != 0.0)
            return 0;
    const double *u = g->u[a], *bv = g->bv[a], *f = g->source[a];
    for (long i = 0; i < gr->size; ++i)
        if (u[i] != 0.0 || bv[i] != 0.0 || f[i] != 0.0)
            return 0;
    return 1;
}

bdl_result bdl_gas_step(bdl_gas *g, double dt)
{
    int active[3]; // the axes whose velocities are stepped (bdl_gas_axis_inert: the others stay 0)
    for (int a = 0; a < 3; ++a)
        active[a] = !bdl_gas_axis_inert(g, a);
    return bdl_gas_step_axes(g, dt, active);
}

bdl_result bdl_gas_step_axes(bdl_gas *g, double dt, const int active[3])
{
    bdl_grid_extend_cells(&g->grid, g->eps);
    bdl_grid_extend_cells(&g->grid, g->eps_old);
    for (int a = 0; a < 3; ++a)
        if (active[a])
            velocity_ghosts(g, a, g->u[a], g->eps_old);
    double *q[3] = {g->coef[0], g->coef[1], g->coef[2]};
    face_fluxes(g, q);
    predict(g, q, active, dt);
    boundary_faces(g, dt);
    double p_side[6];
    for (int s = 0; s < 6; ++s)
        p_side[s] = distributor(&g->def.side[s]) ? plenum_pressure(g, s) : g->def.side[s].pressure;
    const int converged = solve_pressure(g, dt, p_side);
    correct(g, active, p_side);
    const int finite = check_balance(g, dt);
    memcpy(g->eps_old, g->eps, (size_t)g->grid.size * sizeof(double));
    g->time += dt;
    g->steps++;
    return converged && finite ? BDL_OK : BDL_ERR_UNSTABLE;
}

void bdl_gas_set_inflow(bdl_gas *g, double inflow, double jet_inflow)
{
    for (int s = 0; s < 6; ++s) {
        g->def.side[s].inflow = inflow;
        g->def.side[s].jet_inflow = jet_inflow;
    }
}

void bdl_gas_set_gravity(bdl_gas *g, const double gravity[3])
{
    for (int a = 0; a < 3; ++a)
        g->def.gravity[a] = gravity[a];
}

double bdl_gas_stable_dt(const bdl_gas *g)
{
    const bdl_grid *gr = &g->grid;
    double cfl = INFINITY, inv_h2 = 0.0;
    for (int a = 0; a < 3; ++a) {
        double umax = 0.0;
        for (int k = 0; k < gr->n[2]; ++k)
            for (int j = 0; j < gr->n[1]; ++j)
                for (int i = 0; i < gr->n[0]; ++i)
                    umax = fmax(umax, fabs(g->u[a][bdl_grid_index(gr, i, j, k)]));
        if (umax > 0.0 && g->def.convection_step == BDL_CONVECTION_EXPLICIT)
            cfl = fmin(cfl, 0.5 * gr->h[a] / umax);
        if (!(gr->n[a] == 1 && gr->periodic[a]))
            inv_h2 += 1.0 / (gr->h[a] * gr->h[a]);
    }
    double nu = g->def.viscosity / g->def.density;
    double visc = nu > 0.0 ? 1.0 / (2.0 * nu * inv_h2) : INFINITY;
    return fmin(cfl, visc);
}

double bdl_gas_cell_velocity(const bdl_gas *g, int a, int i, int j, int k)
{
    long idx = bdl_grid_index(&g->grid, i, j, k);
    return 0.5 * (g->u[a][idx] + g->u[a][idx + g->grid.stride[a]]);
}
