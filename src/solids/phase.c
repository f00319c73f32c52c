// bedlam — a solids phase on the gas grid: closures in the cells, momentum on the faces with
// the gas's elimination hooks, continuity, and the plastic regime's implicit correction.
#include "solids/phase.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/minmax.h"
#include "solids/energy.h"
#include "solids/kinetic.h"

#define PI 3.14159265358979323846

BDL_CHOICE_WORDS(bdl_granular_energy, BDL_GRANULAR_ENERGIES);
BDL_CHOICE_WORDS(bdl_kinetic_pressure, BDL_KINETIC_PRESSURES);

bdl_solids_def bdl_default_solids_def(void)
{
    bdl_solids_def d;
    memset(&d, 0, sizeof d);
    d.diameter = 2.49e-3;
    d.density = 2526.0;
    d.restitution = 0.97;
    d.drag = BDL_DRAG_SYAMLAL_OBRIEN;
    d.drag_params = bdl_drag_default_params();
    d.eps_star = 0.58;
    d.schaeffer_a = 1e24;
    d.schaeffer_n = 10.0;
    d.friction_angle = 30.0;
    d.mu_max = 100.0;
    d.dilute = 1e-6;
    d.tolerance = 1e-10;
    d.max_iterations = 2000;
    d.wall_restitution = 0.6;
    return d;
}

static int valid_def(const bdl_solids_def *d)
{
    return d->diameter > 0.0 && d->density > 0.0 && d->restitution > 0.0 && d->restitution < 1.0 &&
           d->eps_star > 0.0 && d->eps_star < 1.0 && d->schaeffer_a > 0.0 && d->schaeffer_n > 0.0 &&
           d->friction_angle >= 0.0 && d->friction_angle < 90.0 && d->mu_max > 0.0 &&
           d->dilute > 0.0 && d->tolerance > 0.0 && d->max_iterations > 0 &&
           d->phase_friction >= 0.0 && d->specularity >= 0.0 && d->specularity <= 1.0 &&
           d->hindrance >= 0.0 && (unsigned)d->drag < BDL_DRAG_LAW_COUNT &&
           d->wall_restitution >= 0.0 && d->wall_restitution <= 1.0 && d->wave_weight >= 0.0 &&
           d->wave_weight <= 1.0 &&
           (d->granular_energy == BDL_GRANULAR_ENERGY_LOCAL ||
            d->granular_energy == BDL_GRANULAR_ENERGY_TRANSPORT) &&
           (d->kinetic_pressure == BDL_KINETIC_PRESSURE_EXPLICIT ||
            d->kinetic_pressure == BDL_KINETIC_PRESSURE_IMPLICIT);
}

/// The face arrays of a phase and its cell arrays; 0 when out of memory.
static int phase_alloc(const bdl_grid *gr, bdl_solids_phase *p, int mixture)
{
    int ok = (p->eps = bdl_grid_alloc(gr)) && (p->theta = bdl_grid_alloc(gr)) &&
             (p->pressure = bdl_grid_alloc(gr)) && (p->mu = bdl_grid_alloc(gr)) &&
             (p->slip = bdl_grid_alloc(gr)) && (p->wall = bdl_grid_alloc(gr)) &&
             (!mixture || (p->star = bdl_grid_alloc(gr)));
    for (int a = 0; a < 3; ++a)
        ok =
            ok && (p->v[a] = bdl_grid_alloc(gr)) && (p->a[a] = bdl_grid_alloc(gr)) &&
            (p->b[a] = bdl_grid_alloc(gr)) && (p->k[a] = bdl_grid_alloc(gr)) &&
            (p->up[a] = bdl_grid_alloc(gr)) && (p->flux[a] = bdl_grid_alloc(gr)) &&
            (!mixture || ((p->drag[a] = bdl_grid_alloc(gr)) && (p->cflux[a] = bdl_grid_alloc(gr))));
    return ok;
}

static void phase_free(bdl_solids_phase *p)
{
    free(p->eps);
    free(p->theta);
    free(p->pressure);
    free(p->mu);
    free(p->slip);
    free(p->wall);
    free(p->star);
    for (int a = 0; a < 3; ++a) {
        free(p->v[a]);
        free(p->a[a]);
        free(p->b[a]);
        free(p->k[a]);
        free(p->up[a]);
        free(p->flux[a]);
        free(p->drag[a]);
        free(p->cflux[a]);
    }
}

bdl_result bdl_solids_create_mixture(const bdl_solids_def *defs, int count, const bdl_gas *gas,
                                     bdl_solids **out)
{
    *out = NULL;
    if (count < 1 || count > BDL_SOLIDS_PHASES || !gas->share[0] ||
        (count > 1 && defs[0].kinetic_pressure != BDL_KINETIC_PRESSURE_EXPLICIT))
        return BDL_ERR_ARGS; // (the implicit kinetic pressure is one phase's)
    for (int m = 0; m < count; ++m) {
        bdl_solids_def d = defs[0]; // the mixture's values, the phase's own particles
        d.diameter = defs[m].diameter, d.density = defs[m].density;
        d.restitution = defs[m].restitution;
        d.drag = defs[m].drag, d.drag_params = defs[m].drag_params;
        if (!valid_def(&d))
            return BDL_ERR_ARGS;
    }
    bdl_solids *s = calloc(1, sizeof *s);
    if (!s)
        return BDL_ERR_NOMEM;
    s->def = defs[0];
    s->grid = gas->grid;
    s->count = count;
    const bdl_grid *gr = &s->grid;
    const int mixture = count > 1;
    int ok = 1;
    for (int m = 0; m < count; ++m) {
        bdl_solids_phase *p = &s->phase[m];
        p->def = defs[0];
        p->def.diameter = defs[m].diameter, p->def.density = defs[m].density;
        p->def.restitution = defs[m].restitution;
        p->def.drag = defs[m].drag, p->def.drag_params = defs[m].drag_params;
        ok = ok && phase_alloc(gr, p, mixture);
    }
    for (int q = 0; q < count * (count - 1) / 2; ++q)
        ok = ok && (s->rel[q] = bdl_grid_alloc(gr));
    s->eps = mixture ? bdl_grid_alloc(gr) : s->phase[0].eps;
    ok = ok && (!mixture || (s->plastic = bdl_grid_alloc(gr)));
    for (int a = 0; a < 3; ++a) {
        s->a[a] = mixture ? bdl_grid_alloc(gr) : s->phase[0].a[a];
        ok = ok && s->a[a] && (s->c[a] = bdl_grid_alloc(gr)) && (s->weight[a] = bdl_grid_alloc(gr));
    }
    for (int w = 0; w < BDL_SOLIDS_WORK; ++w)
        ok = ok && (s->work[w] = bdl_grid_alloc(gr));
    ok = ok && (s->free_cells = malloc((size_t)gr->n[0] * gr->n[1] * gr->n[2] * sizeof(long)));
    if (!ok || !s->eps) {
        bdl_solids_destroy(s);
        return BDL_ERR_NOMEM;
    }
    *out = s;
    return BDL_OK;
}

bdl_result bdl_solids_create(const bdl_solids_def *def, const bdl_gas *gas, bdl_solids **out)
{
    return bdl_solids_create_mixture(def, 1, gas, out);
}

void bdl_solids_destroy(bdl_solids *s)
{
    if (!s)
        return;
    const int mixture = s->count > 1;
    if (mixture)
        free(s->eps);
    free(s->plastic);
    for (int a = 0; a < 3; ++a) {
        if (mixture)
            free(s->a[a]);
        free(s->c[a]);
        free(s->weight[a]);
    }
    for (int m = 0; m < s->count; ++m)
        phase_free(&s->phase[m]);
    for (int q = 0; q < BDL_SOLIDS_PAIRS; ++q)
        free(s->rel[q]);
    for (int w = 0; w < BDL_SOLIDS_WORK; ++w)
        free(s->work[w]);
    free(s->free_cells);
    free(s->kept);
    free(s);
}

// ---------------------------------------------------------------------------------------------
// Keeping the state a step starts from.

enum { KEPT_GAS = 6, KEPT_PHASE = 8 }; ///< padded arrays kept of the gas and of each phase

static void mixture_fraction(const bdl_solids *s);

/// The arrays of the state, gas first: `out` gets their addresses, the count returned.
static int kept_arrays(bdl_solids *s, bdl_gas *gas, double **out)
{
    int n = 0;
    for (int a = 0; a < 3; ++a)
        out[n++] = gas->u[a];
    out[n++] = gas->p, out[n++] = gas->eps, out[n++] = gas->eps_old;
    for (int m = 0; m < s->count; ++m) {
        bdl_solids_phase *p = &s->phase[m];
        out[n++] = p->eps, out[n++] = p->theta;
        for (int a = 0; a < 3; ++a)
            out[n++] = p->v[a], out[n++] = p->flux[a];
    }
    return n;
}

/// The clocks and counters kept beside the arrays, as doubles.
enum { KEPT_SCALARS = 8 };

bdl_result bdl_solids_keep(bdl_solids *s, bdl_gas *gas)
{
    double *arrays[KEPT_GAS + KEPT_PHASE * BDL_SOLIDS_PHASES];
    const int n = kept_arrays(s, gas, arrays);
    const size_t cells = (size_t)s->grid.size;
    if (!s->kept && !(s->kept = malloc((n * cells + KEPT_SCALARS) * sizeof(double))))
        return BDL_ERR_NOMEM;
    for (int q = 0; q < n; ++q)
        memcpy(s->kept + q * cells, arrays[q], cells * sizeof(double));
    double *t = s->kept + n * cells;
    t[0] = gas->time, t[1] = (double)gas->steps, t[2] = gas->mass_imbalance;
    t[3] = s->time, t[4] = (double)s->steps;
    return BDL_OK;
}

void bdl_solids_undo(bdl_solids *s, bdl_gas *gas)
{
    double *arrays[KEPT_GAS + KEPT_PHASE * BDL_SOLIDS_PHASES];
    const int n = kept_arrays(s, gas, arrays);
    const size_t cells = (size_t)s->grid.size;
    for (int q = 0; q < n; ++q)
        memcpy(arrays[q], s->kept + q * cells, cells * sizeof(double));
    const double *t = s->kept + n * cells;
    gas->time = t[0], gas->steps = (long)t[1], gas->mass_imbalance = t[2];
    s->time = t[3], s->steps = (long)t[4];
    mixture_fraction(s);
}

/// The mixture's fraction, the sum of the phases' (with one phase the same array).
static void mixture_fraction(const bdl_solids *s)
{
    if (s->count == 1)
        return;
    for (long i = 0; i < s->grid.size; ++i) {
        double sum = 0.0;
        for (int m = 0; m < s->count; ++m)
            sum += s->phase[m].eps[i];
        s->eps[i] = sum;
    }
}

void bdl_solids_share_voidage(const bdl_solids *s, bdl_gas *gas)
{
    for (int m = 0; m < s->count; ++m)
        bdl_grid_extend_cells(&s->grid, s->phase[m].eps);
    mixture_fraction(s);
    for (long i = 0; i < s->grid.size; ++i)
        gas->eps[i] = gas->eps_old[i] = 1.0 - s->eps[i];
}

// ---------------------------------------------------------------------------------------------
// Loops and ghosts.

/// Runs the statements for every cell (i, j, k; index idx) of the grid.
#define FOR_CELLS(gr, ...)                                                                         \
    for (int k = 0; k < (gr)->n[2]; ++k)                                                           \
        for (int j = 0; j < (gr)->n[1]; ++j)                                                       \
            for (int i = 0; i < (gr)->n[0]; ++i) {                                                 \
                const long idx = bdl_grid_index(gr, i, j, k);                                      \
                __VA_ARGS__;                                                                       \
            }

/// Runs the statements for every face of axis a that lies between two cells (on a periodic
/// axis, faces 0 to n - 1; face n is face 0's image).
#define FOR_INNER_FACES(gr, a, ...)                                                                \
    for (int k = 0; k < (gr)->n[2]; ++k)                                                           \
        for (int j = 0; j < (gr)->n[1]; ++j)                                                       \
            for (int i = 0; i < (gr)->n[0]; ++i) {                                                 \
                const int ia_ = (a) == 0 ? i : (a) == 1 ? j : k;                                   \
                if (ia_ == 0 && !(gr)->periodic[a])                                                \
                    continue;                                                                      \
                const long idx = bdl_grid_index(gr, i, j, k);                                      \
                __VA_ARGS__;                                                                       \
            }

/// Face n of a periodic axis a as the image of face 0, for the listed face arrays.
static void wrap_face(const bdl_grid *gr, int a, double *f)
{
    if (!gr->periodic[a])
        return;
    bdl_grid_copy_plane(gr, f, a, gr->n[a], 0);
}

/// Ghosts of the velocity component a: free-slip walls on every side that is not periodic (the
/// normal component zero on the wall and odd beyond it, the tangential ones even).
static void velocity_ghosts(const bdl_grid *gr, int a, double *v)
{
    const int G = BDL_GRID_GHOST;
    for (int b = 0; b < 3; ++b) {
        const long s = gr->stride[b];
        const int n = gr->n[b];
        if (gr->periodic[b]) {
            bdl_grid_wrap_axis(gr, v, b, b == a);
        } else if (b == a) {
            BDL_GRID_FOR_PLANE(gr, b, 0, {
                v[idx] = v[idx + n * s] = 0.0;
                for (int l = 1; l <= G; ++l) {
                    v[idx - l * s] = -v[idx + l * s];
                    v[idx + (n + l) * s] = -v[idx + (n - l) * s];
                }
            });
        } else {
            BDL_GRID_FOR_PLANE(gr, b, 0, {
                for (int l = 1; l <= G; ++l) {
                    v[idx - l * s] = v[idx + (l - 1) * s];
                    v[idx + (n - 1 + l) * s] = v[idx + (n - l) * s];
                }
            });
        }
    }
}

double bdl_solids_cell_velocity(const bdl_solids *s, int m, int a, int i, int j, int k)
{
    const long idx = bdl_grid_index(&s->grid, i, j, k);
    const double *v = s->phase[m].v[a];
    return 0.5 * (v[idx] + v[idx + s->grid.stride[a]]);
}

double bdl_solids_volume(const bdl_solids *s, int m)
{
    const bdl_grid *gr = &s->grid;
    const double *eps = m < 0 ? s->eps : s->phase[m].eps;
    double sum = 0.0;
    FOR_CELLS(gr, sum += eps[idx]);
    return sum * gr->h[0] * gr->h[1] * gr->h[2];
}

double bdl_solids_mean_height(const bdl_solids *s, int m, int a)
{
    const bdl_grid *gr = &s->grid;
    const double *eps = m < 0 ? s->eps : s->phase[m].eps;
    double sum = 0.0, mass = 0.0;
    FOR_CELLS(gr, {
        const int at[3] = {i, j, k};
        sum += eps[idx] * (at[a] + 0.5) * gr->h[a], mass += eps[idx];
    });
    return mass > 0.0 ? sum / mass : 0.0;
}

// ---------------------------------------------------------------------------------------------
// Closures in the cells.

/// Rate of strain of the phase's velocity at the centre of cell idx: D (symmetric, 3 x 3).
static void strain_rate(const bdl_grid *gr, const bdl_solids_phase *p, long idx, double D[3][3])
{
    double grad[3][3]; // grad[a][b] = d v_a / d x_b
    for (int a = 0; a < 3; ++a) {
        const double *v = p->v[a];
        const long sa = gr->stride[a];
        for (int b = 0; b < 3; ++b) {
            const long sb = gr->stride[b];
            if (b == a) {
                grad[a][b] = (v[idx + sa] - v[idx]) / gr->h[a];
            } else if (gr->n[b] == 1) {
                grad[a][b] = 0.0;
            } else {
                const double hi = v[idx + sb] + v[idx + sb + sa],
                             lo = v[idx - sb] + v[idx - sb + sa];
                grad[a][b] = 0.25 * (hi - lo) / gr->h[b];
            }
        }
    }
    for (int a = 0; a < 3; ++a)
        for (int b = 0; b < 3; ++b)
            D[a][b] = 0.5 * (grad[a][b] + grad[b][a]);
}

/// Syamlal's viscous regime with the granular energy's balance in time: (3/2) rho eps (theta -
/// theta^n) / dt = -P tr D + 2 mu D:D + lambda tr(D)^2 - k4 eps^2 theta^(3/2), backward Euler, a
/// cubic in x = sqrt(theta):
///     k4 eps x^3 + (3 rho / (2 dt) + k1 eps tr D) x^2 - (2 k3 D:D + k2 tr(D)^2) x
///       - 3 rho theta^n / (2 dt) = 0
/// (divided by eps). As dt / (the collisions' relaxation time) grows it tends to the algebraic
/// balance MFIX offers (the quadratic without the time terms); unlike that one it cannot jump
/// from cell to cell with the local strain rate within a step, which on fine grids grew into a
/// checkerboard of pressures that diverged. g0 is Carnahan & Starling's for one phase, Lebowitz's
/// g0_mm for a phase of a mixture (which balances its own collisions only). With the transport
/// terms e (solids/energy.h; NULL: none) the time term gains e->diag, the old energy e->nb and
/// the dissipation e->k4: the same cubic.
static void viscous_regime(const bdl_solids_def *d, const bdl_ktgf_factors *f, double eps,
                           double g0, double trace, double ddot, double theta_old, double dt,
                           const bdl_energy_terms *e, double *theta, double *p, double *mu)
{
    bdl_ktgf_coefficients c = bdl_ktgf_syamlal_at(f, eps, g0);
    if (e) { // 3/2 rho eps / dt' = 3/2 rho eps / dt + diag, theta_old' its weighted mean
        const double rate = 1.5 * d->density * eps / dt;
        theta_old = (rate * theta_old + e->nb) / (rate + e->diag);
        dt = 1.5 * d->density * eps / (rate + e->diag);
        c.k4 += e->k4;
    }
    *theta = bdl_ktgf_temperature_step(&c, eps, d->density, trace, ddot, theta_old, dt);
    *p = c.k1 * eps * eps * *theta;
    *mu = c.k3 * eps * sqrt(*theta);
}

/// The cell's phase fractions and diameters, for Lebowitz's g0.
static void cell_mixture(const bdl_solids *s, long idx, double *eps, double *d)
{
    for (int m = 0; m < s->count; ++m)
        eps[m] = s->phase[m].eps[idx], d[m] = s->phase[m].def.diameter;
}

double bdl_solids_cell_slip(const bdl_solids *s, int m, const bdl_gas *gas, int i, int j, int k)
{
    double sum = 0.0;
    for (int a = 0; a < 3; ++a) {
        const double r =
            bdl_gas_cell_velocity(gas, a, i, j, k) - bdl_solids_cell_velocity(s, m, a, i, j, k);
        sum += r * r;
    }
    return sqrt(sum);
}

double bdl_solids_phase_g0(const bdl_solids *s, int m, long idx)
{
    if (s->count == 1)
        return bdl_g0_carnahan_starling(s->eps[idx]);
    double e[BDL_SOLIDS_PHASES], dm[BDL_SOLIDS_PHASES];
    cell_mixture(s, idx, e, dm);
    return bdl_g0_lebowitz(e, dm, s->count, m, m);
}

/// Johnson & Jackson's (1987) wall friction coefficient: the wall's shear stress on the solids is
/// -C v_slip, C = pi sqrt(3) phi' rho eps g0 sqrt(theta) / (6 eps_max), with eps_max the
/// plastic regime's fraction (MFIX's 1 - ep_star).
static double wall_coefficient(const bdl_solids_def *d, double eps, double g0, double theta)
{
    return PI * sqrt(3.0) * d->specularity * d->density * eps * g0 * sqrt(theta) /
           (6.0 * d->eps_star);
}

/// Phase m's temperature, pressure and viscosity in every cell, and the slip |u - v| the drag
/// sees. Above eps_star (all phases together) Schaeffer's pressure of the mixture, each phase's
/// share in proportion to its fraction.
static void phase_closures(bdl_solids *s, int m, const bdl_gas *gas, double dt)
{
    const bdl_grid *gr = &s->grid;
    bdl_solids_phase *ph = &s->phase[m];
    const bdl_solids_def *d = &ph->def;
    const double phi = d->friction_angle * PI / 180.0; // radians
    double pmax = s->stats.pressure_max;
    const int transport = s->def.granular_energy == BDL_GRANULAR_ENERGY_TRANSPORT;
    if (transport)
        bdl_solids_energy_prepare(s, m, gas);
    const bdl_ktgf_factors f = bdl_ktgf_syamlal_factors(d->diameter, d->density, d->restitution);
    FOR_CELLS(gr, {
        const double eps = ph->eps[idx], total = s->eps[idx];
        double D[3][3], theta = 0.0, p = 0.0, mu = 0.0, wall = 0.0;
        strain_rate(gr, ph, idx, D);
        const double trace = D[0][0] + D[1][1] + D[2][2];
        double ddot = 0.0, i2d = 0.0;
        for (int a = 0; a < 3; ++a)
            for (int b = 0; b < 3; ++b) {
                ddot += D[a][b] * D[a][b];
                const double dev = D[a][b] - (a == b ? trace / 3.0 : 0.0);
                i2d += 0.5 * dev * dev;
            }
        if (total >= d->eps_star) {
            const double pt = bdl_schaeffer_pressure(total, 1.0 - total, 1.0 - d->eps_star,
                                                     d->schaeffer_a, d->schaeffer_n);
            p = pt * (eps / total);
            mu = bdl_schaeffer_viscosity(p, phi, i2d, d->mu_max);
            pmax = bdl_max(pmax, pt);
            if (s->plastic)
                s->plastic[idx] = pt;
        } else if (eps > d->dilute) {
            const double g0 = bdl_solids_phase_g0(s, m, idx);
            bdl_energy_terms terms, *e = NULL;
            if (transport) {
                const int at[3] = {i, j, k};
                terms = bdl_solids_energy_terms(s, m, gas, idx, at, g0);
                e = &terms;
            }
            viscous_regime(d, &f, eps, g0, trace, ddot, ph->theta[idx], dt, e, &theta, &p, &mu);
            wall = wall_coefficient(d, eps, g0, theta);
            pmax = bdl_max(pmax, p);
        }
        ph->theta[idx] = theta;
        ph->pressure[idx] = p;
        ph->mu[idx] = mu;
        ph->slip[idx] = bdl_solids_cell_slip(s, m, gas, i, j, k);
        ph->wall[idx] = wall;
    });
    bdl_grid_extend_cells(gr, ph->pressure);
    bdl_grid_extend_cells(gr, ph->mu);
    bdl_grid_extend_cells(gr, ph->slip);
    bdl_grid_extend_cells(gr, ph->wall); // a face's two cells: across a period the image's
    s->stats.pressure_max = pmax;
}

/// |v_l - v_m| of every pair of phases in the cells (pairs in the order (0,1), (0,2), ...).
static void relative_speeds(bdl_solids *s)
{
    const bdl_grid *gr = &s->grid;
    int q = 0;
    for (int l = 0; l < s->count; ++l)
        for (int m = l + 1; m < s->count; ++m, ++q) {
            double *rel = s->rel[q];
            FOR_CELLS(gr, {
                double r2 = 0.0;
                for (int a = 0; a < 3; ++a) {
                    const double r = bdl_solids_cell_velocity(s, l, a, i, j, k) -
                                     bdl_solids_cell_velocity(s, m, a, i, j, k);
                    r2 += r * r;
                }
                rel[idx] = sqrt(r2);
            });
            bdl_grid_extend_cells(gr, rel);
        }
}

/// Temperature, pressure and viscosity of every phase, the slips and the phases' relative speeds.
static void closures(bdl_solids *s, const bdl_gas *gas, double dt)
{
    s->stats.pressure_max = 0.0;
    if (s->plastic)
        memset(s->plastic, 0, (size_t)s->grid.size * sizeof *s->plastic);
    for (int m = 0; m < s->count; ++m)
        phase_closures(s, m, gas, dt);
    if (s->plastic)
        bdl_grid_extend_cells(&s->grid, s->plastic);
    relative_speeds(s);
}

// ---------------------------------------------------------------------------------------------
// Momentum on the faces.

/// An operator at the a-face idx split as diag v_a[idx] - nb, nb the neighbours' part (both
/// non-negative where the operator is bounded): treated point-implicitly (diag into A, nb into
/// B), a step is a weighted mean of old and neighbouring values and stays bounded at any time
/// step.
typedef struct face_terms {
    double diag, nb;
} face_terms;

/// div(F v_a) - v_a div(F) at the a-face idx, v_a upwind, F the last step's solids volume fluxes
/// (the flux form less the face's continuity times v_a, as Patankar writes it): only what flows
/// in counts, diag = sum of inflows / h.
static face_terms transport(const bdl_grid *gr, const bdl_solids_phase *p, int a, long idx)
{
    const double *va = p->v[a];
    const long sa = gr->stride[a];
    face_terms t = {0.0, 0.0};
    for (int b = 0; b < 3; ++b) {
        if (gr->n[b] == 1)
            continue;
        const long sb = gr->stride[b];
        const double *fb = p->flux[b];
        double hi, lo;
        if (b == a) {
            hi = 0.5 * (fb[idx] + fb[idx + sb]);
            lo = 0.5 * (fb[idx - sb] + fb[idx]);
        } else {
            hi = 0.5 * (fb[idx + sb] + fb[idx + sb - sa]);
            lo = 0.5 * (fb[idx] + fb[idx - sa]);
        }
        const double in_hi = bdl_max(-hi, 0.0) / gr->h[b], in_lo = bdl_max(lo, 0.0) / gr->h[b];
        t.diag += in_hi + in_lo;
        t.nb += in_hi * va[idx + sb] + in_lo * va[idx - sb];
    }
    return t;
}

/// -div(mu grad v_a) at the a-face idx (at: its cell's indices): mu from the cells beside a face
/// of the same axis, the mean of the four cells around an edge otherwise. Beside a wall along b
/// != a, with a specularity, Johnson & Jackson's partial slip replaces the viscous flux through
/// the wall: the stress -C v_a, C the mean of the face's two cells' coefficients, over h_b.
static face_terms viscous(const bdl_grid *gr, const bdl_solids_phase *p, int a, long idx,
                          const int at[3], const int wall[6])
{
    const double *v = p->v[a], *mu = p->mu;
    const long sa = gr->stride[a];
    face_terms t = {0.0, 0.0};
    for (int b = 0; b < 3; ++b) {
        if (gr->n[b] == 1)
            continue;
        const long sb = gr->stride[b];
        const int low = at[b] == 0 && wall[2 * b], high = at[b] == gr->n[b] - 1 && wall[2 * b + 1];
        if (b != a && p->def.specularity > 0.0 && (low || high)) {
            const double C = 0.5 * (p->wall[idx] + p->wall[idx - sa]), h2 = gr->h[b] * gr->h[b];
            double m_in = 0.25 * (mu[idx] + mu[idx - sa]), v_in;
            m_in += low ? 0.25 * (mu[idx + sb] + mu[idx + sb - sa])
                        : 0.25 * (mu[idx - sb] + mu[idx - sb - sa]);
            v_in = low ? v[idx + sb] : v[idx - sb];
            t.diag += m_in / h2 + C / gr->h[b];
            t.nb += m_in * v_in / h2;
            continue;
        }
        double mhi, mlo;
        if (b == a) {
            mhi = mu[idx], mlo = mu[idx - sa];
        } else {
            mhi = 0.25 * (mu[idx] + mu[idx - sa] + mu[idx + sb] + mu[idx + sb - sa]);
            mlo = 0.25 * (mu[idx] + mu[idx - sa] + mu[idx - sb] + mu[idx - sb - sa]);
        }
        const double h2 = gr->h[b] * gr->h[b];
        t.diag += (mhi + mlo) / h2;
        t.nb += (mhi * v[idx + sb] + mlo * v[idx - sb]) / h2;
    }
    return t;
}

/// The gas's hooks on every face of axis a before the solids' terms: no drag, the whole
/// pressure gradient on the gas's fraction, no solids flux.
static void reset_hooks(const bdl_solids *s, bdl_gas *gas, int a)
{
    const bdl_grid *gr = &s->grid;
    const long sa = gr->stride[a];
    for (long idx = 0; idx < gr->size; ++idx) {
        gas->beta[a][idx] = gas->bv[a][idx] = 0.0;
        gas->flux_u[a][idx] = gas->flux_p[a][idx] = gas->flux_0[a][idx] = 0.0;
        gas->share[a][idx] = idx >= sa ? 1.0 - 0.5 * (s->eps[idx] + s->eps[idx - sa]) : 1.0;
    }
}

/// Phase m's equation on every face of axis a, per unit solids volume (A, B, k), and the upwind
/// solids fraction by the old velocity's sign. With one phase also the gas's hooks: its drag,
/// drag source and pressure share after the elimination, and the solids' flux still to come
/// (several phases: couple() below). Faces on a side that is not periodic carry no solids.
static void momentum(bdl_solids *s, int m, bdl_gas *gas, int a, double dt)
{
    const bdl_grid *gr = &s->grid;
    bdl_solids_phase *p = &s->phase[m];
    const bdl_solids_def *d = &p->def;
    const long sa = gr->stride[a];
    const double rho = d->density, rg = gas->def.density, mug = gas->def.viscosity;
    for (long idx = 0; idx < gr->size; ++idx)
        p->a[a][idx] = 1.0, p->b[a][idx] = p->k[a][idx] = p->up[a][idx] = 0.0;
    int wall[6]; // the gas's walls (an inlet or outlet has no Johnson & Jackson friction)
    for (int side = 0; side < 6; ++side)
        wall[side] =
            gas->def.side[side].type == BDL_SIDE_WALL || gas->def.side[side].type == BDL_SIDE_SLIP;
    FOR_INNER_FACES(gr, a, {
        const double es = 0.5 * (p->eps[idx] + p->eps[idx - sa]);
        const double eg = 1.0 - 0.5 * (s->eps[idx] + s->eps[idx - sa]);
        const double slip = 0.5 * (p->slip[idx] + p->slip[idx - sa]);
        const double kd =
            bdl_drag_per_volume(d->drag, &d->drag_params, eg, d->diameter, slip, rg, mug);
        // rho es (v^{n+1} - v^n) / dt + rho (div(F v) - v div F) = -grad P_s + div(mu grad v) + ...
        // with the transport and the viscous term point-implicit.
        double A = rho / dt + kd, B = rho * p->v[a][idx] / dt + rho * gas->def.gravity[a];
        if (es > d->dilute) {
            const int at[3] = {i, j, k};
            const face_terms conv = transport(gr, p, a, idx),
                             visc = viscous(gr, p, a, idx, at, wall);
            A += (rho * conv.diag + visc.diag) / es;
            B += (rho * conv.nb + visc.nb - (p->pressure[idx] - p->pressure[idx - sa]) / gr->h[a]) /
                 es;
        }
        const double up = p->v[a][idx] >= 0.0 ? p->eps[idx - sa] : p->eps[idx];
        p->a[a][idx] = A, p->b[a][idx] = B, p->k[a][idx] = kd, p->up[a][idx] = up;
        if (s->count > 1) {
            p->drag[a][idx] = kd;
            continue;
        }
        gas->beta[a][idx] = es * kd * (A - kd) / A;
        gas->bv[a][idx] = es * kd * B / A;
        gas->share[a][idx] = eg + es * kd / A;
        gas->flux_u[a][idx] = up * kd / A;
        gas->flux_p[a][idx] = up / A;
        gas->flux_0[a][idx] = up * B / A;
    });
}

/// Solves S x = r for the columns of R (n x cols), in place; S (n x n, n <= BDL_SOLIDS_PHASES)
/// an M-matrix (diagonally dominant by rows), so Gaussian elimination without pivoting.
static void solve_small(int n, double S[][BDL_SOLIDS_PHASES], double R[][3], int cols)
{
    for (int p = 0; p < n; ++p)
        for (int r = p + 1; r < n; ++r) {
            const double f = S[r][p] / S[p][p];
            for (int c = p; c < n; ++c)
                S[r][c] -= f * S[p][c];
            for (int c = 0; c < cols; ++c)
                R[r][c] -= f * R[p][c];
        }
    for (int p = n - 1; p >= 0; --p)
        for (int c = 0; c < cols; ++c) {
            double x = R[p][c];
            for (int q = p + 1; q < n; ++q)
                x -= S[p][q] * R[q][c];
            R[p][c] = x / S[p][p];
        }
}

/// Syamlal's drag between phases l and m per unit fraction of each at the a-face idx (Sun eq.
/// 3.18; the relative speed and Lebowitz's g0 from the face's two cells), with Gera et al.'s
/// hindrance C1 P_plastic (P the mean of the face's two cells; the fractions it is divided by
/// no smaller than the dilute limit).
static double pair_drag(const bdl_solids *s, int q, int l, int m, int a, long idx)
{
    const long sa = s->grid.stride[a];
    const bdl_solids_def *dl = &s->phase[l].def, *dm = &s->phase[m].def;
    double eps[BDL_SOLIDS_PHASES], d[BDL_SOLIDS_PHASES], lo[BDL_SOLIDS_PHASES];
    cell_mixture(s, idx, eps, d);
    cell_mixture(s, idx - sa, lo, d);
    for (int n = 0; n < s->count; ++n)
        eps[n] = 0.5 * (eps[n] + lo[n]);
    const double g0 = bdl_g0_lebowitz(eps, d, s->count, l, m);
    const double speed = 0.5 * (s->rel[q][idx] + s->rel[q][idx - sa]);
    double f =
        bdl_solids_drag_syamlal(0.5 * (dl->restitution + dm->restitution), s->def.phase_friction,
                                g0, dl->diameter, dl->density, dm->diameter, dm->density, speed);
    if (s->def.hindrance > 0.0) {
        const double P = 0.5 * (s->plastic[idx] + s->plastic[idx - sa]), floor_eps = s->def.dilute;
        f += s->def.hindrance * P / (fmax(eps[l], floor_eps) * fmax(eps[m], floor_eps));
    }
    return f;
}

/// Several phases on every inner a-face: with the drag F_lm (v_l - v_m) between them, per unit
/// solids volume of m, the phases' equations A_m v_m = B_m + k_m u - G + sum_l F_lm (v_l - v_m) /
/// eps_m form S v = B + k u - G 1 (S an M-matrix), solved for v = alpha + beta u - gamma G. Each
/// phase keeps v = (B' + k' u - G) / A' with A' = 1 / gamma, B' = alpha A', k' = beta A'; the
/// gas's drag sum_m eps_m kd_m (1 - beta_m), its source sum_m eps_m kd_m alpha_m, its share
/// eps_g + sum_m eps_m kd_m gamma_m, the solids' flux sum_m up_m (alpha_m + beta_m u - gamma_m
/// G); and A of the mixture's plastic correction, 1/A the fraction-weighted mean of the gammas.
static void couple(bdl_solids *s, bdl_gas *gas, int a)
{
    const bdl_grid *gr = &s->grid;
    const long sa = gr->stride[a];
    const int n = s->count;
    for (long idx = 0; idx < gr->size; ++idx)
        s->a[a][idx] = 1.0;
    FOR_INNER_FACES(gr, a, {
        double S[BDL_SOLIDS_PHASES][BDL_SOLIDS_PHASES] = {{0}}, R[BDL_SOLIDS_PHASES][3];
        double es[BDL_SOLIDS_PHASES], total = 0.0;
        for (int m = 0; m < n; ++m) {
            const bdl_solids_phase *p = &s->phase[m];
            es[m] = 0.5 * (p->eps[idx] + p->eps[idx - sa]);
            total += es[m];
            S[m][m] = p->a[a][idx];
            R[m][0] = p->b[a][idx], R[m][1] = p->k[a][idx], R[m][2] = 1.0;
        }
        for (int l = 0, q = 0; l < n; ++l)
            for (int m = l + 1; m < n; ++m, ++q) {
                const double f = pair_drag(s, q, l, m, a, idx); // F_lm / (eps_l eps_m)
                S[m][m] += f * es[l], S[m][l] -= f * es[l];
                S[l][l] += f * es[m], S[l][m] -= f * es[m];
            }
        solve_small(n, S, R, 3);
        double beta = 0.0, bv = 0.0, share = 1.0 - total, fu = 0.0, fp = 0.0, f0 = 0.0, mob = 0.0;
        for (int m = 0; m < n; ++m) {
            bdl_solids_phase *p = &s->phase[m];
            const double kd = p->drag[a][idx], up = p->up[a][idx];
            const double alpha = R[m][0], b = R[m][1], gamma = R[m][2];
            beta += es[m] * kd * (1.0 - b);
            bv += es[m] * kd * alpha;
            share += es[m] * kd * gamma;
            fu += up * b, fp += up * gamma, f0 += up * alpha;
            mob += (total > 0.0 ? es[m] / total : 1.0 / n) * gamma;
            p->a[a][idx] = 1.0 / gamma, p->b[a][idx] = alpha / gamma, p->k[a][idx] = b / gamma;
        }
        gas->beta[a][idx] = beta, gas->bv[a][idx] = bv, gas->share[a][idx] = share;
        gas->flux_u[a][idx] = fu, gas->flux_p[a][idx] = fp, gas->flux_0[a][idx] = f0;
        s->a[a][idx] = 1.0 / mob;
    });
}

/// Phase m's v^{n+1} = (B + k u - G) / A on the inner faces (zero on the walls), and its volume
/// flux by the new velocity's upwind fraction. Where that differs from the fraction the pressure
/// equation was given, the difference is handed to the gas with the opposite sign, so that the
/// flux of the two together stays free of divergence.
static void new_velocity(bdl_solids *s, int m, bdl_gas *gas, int a)
{
    const bdl_grid *gr = &s->grid;
    bdl_solids_phase *p = &s->phase[m];
    const long sa = gr->stride[a];
    double *v = p->v[a], *f = p->flux[a];
    memset(f, 0, (size_t)gr->size * sizeof *f);
    memset(v, 0, (size_t)gr->size * sizeof *v);
    FOR_INNER_FACES(gr, a, {
        v[idx] =
            (p->b[a][idx] + p->k[a][idx] * gas->u[a][idx] - gas->grad_p[a][idx]) / p->a[a][idx];
        const double up = v[idx] >= 0.0 ? p->eps[idx - sa] : p->eps[idx];
        f[idx] = up * v[idx];
        if (up != p->up[a][idx]) {
            const double eg = 1.0 - 0.5 * (s->eps[idx] + s->eps[idx - sa]);
            gas->u[a][idx] -= (up - p->up[a][idx]) * v[idx] / eg;
        }
    });
    wrap_face(gr, a, v);
    wrap_face(gr, a, f);
    wrap_face(gr, a, gas->u[a]);
}

/// Phase m's fluxes limited so that no cell sends out more than it holds in a step: the
/// outgoing fluxes of a cell whose outflow dt sum(out) / h exceeds its fraction are scaled down
/// to it, and the gas takes the difference (the flux of the two together keeps its divergence).
/// Only nearly empty cells need it: the step's Courant limit (bdl_solids_stable_dt) leaves them
/// out, and their solids, carried by the gas at its speed, would otherwise set the step.
static void limit_outflow(bdl_solids *s, int m, bdl_gas *gas, double dt)
{
    const bdl_grid *gr = &s->grid;
    bdl_solids_phase *p = &s->phase[m];
    double *scale = s->work[4];
    int any = 0;
    FOR_CELLS(gr, {
        double out = 0.0;
        for (int a = 0; a < 3; ++a)
            out += (bdl_max(p->flux[a][idx + gr->stride[a]], 0.0) - bdl_min(p->flux[a][idx], 0.0)) /
                   gr->h[a];
        out *= dt;
        const double held = bdl_max(p->eps[idx], 0.0); // (round-off may leave a cell below zero)
        scale[idx] = out > held ? held / out : 1.0;
        any = any || scale[idx] < 1.0;
    });
    if (!any)
        return;
    bdl_grid_wrap_cells(gr, scale);
    for (int a = 0; a < 3; ++a) {
        const long sa = gr->stride[a];
        double *f = p->flux[a];
        FOR_INNER_FACES(gr, a, {
            const double c = scale[f[idx] >= 0.0 ? idx - sa : idx];
            if (c < 1.0) {
                const double df = (c - 1.0) * f[idx];
                f[idx] += df;
                gas->u[a][idx] -= df / (1.0 - 0.5 * (s->eps[idx] + s->eps[idx - sa]));
            }
        });
        wrap_face(gr, a, f);
        wrap_face(gr, a, gas->u[a]);
    }
}

/// The fractions the volume fluxes on the faces leave: out = before - dt div(face).
static void after_fluxes(const bdl_grid *gr, double *const face[3], const double *before, double dt,
                         double *out)
{
    FOR_CELLS(gr, {
        double div = 0.0;
        for (int a = 0; a < 3; ++a)
            div += (face[a][idx + gr->stride[a]] - face[a][idx]) / gr->h[a];
        out[idx] = before[idx] - dt * div;
    });
}

// ---------------------------------------------------------------------------------------------
// The plastic regime's implicit correction.
//
// The momentum step used the pressure P(eps^n). With the increment dP = P(eps^{n+1}) - P(eps^n)
// of the cells in the plastic regime (at eps^n or eps*; dP = 0 elsewhere) the solids' flux gains
// -grad(dP) / A, so that eps^{n+1} - eps^n = r + dt div(grad(dP) / A), r = eps* - eps^n. With dP
// modelled as S (eps^{n+1} - eps^n), S a chord of P, the unknown z = dP of those cells solves the
// symmetric positive system
//     z_i / S_i + sum_f w_f (z_i - z_j) = r_i,   w_f = dt / (A_f h_f^2),
// by conjugate gradients with a Jacobi preconditioner, z_i >= -P(eps^n_i) (no pressure below
// zero). The fluxes -grad(z) / A then move the solids (the volume is conserved whatever z is).
// With def.kinetic_pressure implicit P is Schaeffer's plus the viscous regime's k1 eps^2 theta
// (theta the step's), so every cell with a temperature is in the system too, and a cell is
// re-chorded by short_of_pressure() (its end point may then fall) instead of the plastic rule.

static double schaeffer(const bdl_solids_def *d, double eps)
{
    return bdl_schaeffer_pressure(eps, 1.0 - eps, 1.0 - d->eps_star, d->schaeffer_a,
                                  d->schaeffer_n);
}

/// dP/d(eps) of Schaeffer's pressure eps A (eps - eps_star)^n.
static double plastic_slope(const bdl_solids_def *d, double eps)
{
    const double x = eps - d->eps_star;
    if (x <= 0.0)
        return 0.0;
    return d->schaeffer_a * pow(x, d->schaeffer_n - 1.0) * (x + eps * d->schaeffer_n);
}

/// With the kinetic pressure implicit (one phase), the viscous regime's pressure k1(eps) eps^2
/// theta of cell idx at the step's temperature (zero in the plastic regime: theta is zero there);
/// zero otherwise.
static double kinetic_pressure(const bdl_solids *s, long idx, double eps)
{
    const bdl_solids_def *d = &s->def;
    const double theta = s->phase[0].theta[idx];
    if (d->kinetic_pressure != BDL_KINETIC_PRESSURE_IMPLICIT || !(theta > 0.0) || !(eps > 0.0))
        return 0.0;
    const double e = bdl_min(eps, 0.9); // (g0 grows without bound towards 1)
    const double k1 = 2.0 * (1.0 + d->restitution) * d->density * bdl_g0_carnahan_starling(e);
    return k1 * e * e * theta; // (k1 as bdl_ktgf_syamlal_g0 has it)
}

/// The work arrays holding each cell's modelled pressure at the step's start, P(eps^n), and the
/// correction's diagonal in its solve.
enum { BASE_PRESSURE = 13, DIAGONAL = 14 };

/// The pressure the correction models in cell idx as a function of its fraction.
static double cell_pressure(const bdl_solids *s, long idx, double eps)
{
    return schaeffer(&s->def, eps) + kinetic_pressure(s, idx, eps);
}

/// The slope of cell idx's pressure between fractions p and q: the chord (P(q) - P(p)) /
/// (q - p), the tangent where they meet; 0 where it has none (below eps_star at both, and no
/// kinetic pressure in the correction).
static double plastic_chord(const bdl_solids *s, long idx, double p, double q)
{
    const bdl_solids_def *d = &s->def;
    double slope = 0.0;
    if (fabs(q - p) > 1e-9) {
        if (p > d->eps_star || q > d->eps_star)
            slope = (schaeffer(d, q) - schaeffer(d, p)) / (q - p);
        return slope + (kinetic_pressure(s, idx, q) - kinetic_pressure(s, idx, p)) / (q - p);
    }
    const double e = bdl_max(p, q);
    slope = plastic_slope(d, e);
    if (d->kinetic_pressure == BDL_KINETIC_PRESSURE_IMPLICIT && e > d->dilute) {
        const double de = 1e-6 * e; // the tangent by a difference
        slope += (kinetic_pressure(s, idx, e + de) - kinetic_pressure(s, idx, e)) / de;
    }
    return slope;
}

/// (M z) of the free cell idx (M the matrix above; slope the cells' chords, s->weight the face
/// weights).
static inline double plastic_row(const bdl_solids *s, const double *slope, const double *z,
                                 long idx)
{
    const bdl_grid *gr = &s->grid;
    double sum = z[idx] / slope[idx];
    for (int a = 0; a < 3; ++a) {
        if (gr->n[a] == 1) // a period of one cell, or walls on both sides: no flux
            continue;
        const long sa = gr->stride[a];
        const double *w = s->weight[a];
        sum += w[idx] * (z[idx] - z[idx - sa]) + w[idx + sa] * (z[idx] - z[idx + sa]);
    }
    return sum;
}

/// plastic_row from the row's diagonal (1/slope and the face weights): without a division.
static inline double plastic_apply(const bdl_solids *s, const double *diag, const double *z,
                                   long idx)
{
    const bdl_grid *gr = &s->grid;
    double sum = diag[idx] * z[idx];
    for (int a = 0; a < 3; ++a) {
        if (gr->n[a] == 1)
            continue;
        const long sa = gr->stride[a];
        const double *w = s->weight[a];
        sum -= w[idx] * z[idx - sa] + w[idx + sa] * z[idx + sa];
    }
    return sum;
}

/// The free cells (slope > 0) into s->free_cells in the grid's order; returns their count.
static long list_free_cells(bdl_solids *s, const double *slope)
{
    long count = 0;
    FOR_CELLS(&s->grid, {
        if (slope[idx] > 0.0)
            s->free_cells[count++] = idx;
    });
    return count;
}

/// Solves M dz = r on the free cells (slope > 0; dz = 0 on the others) by preconditioned
/// conjugate gradients and adds dz to z; returns the iterations taken. The loops run over the
/// list of free cells, each sum in the grid's order. The residual is taken down to the tolerance
/// times the larger of |r| and *reference, the first pass's |r| (set by the first pass): a later
/// pass's increment needs the accuracy of the whole, not more.
static int plastic_solve(bdl_solids *s, const double *slope, const double *r, double *z,
                         double *reference)
{
    const bdl_grid *gr = &s->grid;
    double *res = s->work[4], *pre = s->work[5], *dir = s->work[6], *q = s->work[7];
    double *dz = s->work[10], *diagonal = s->work[DIAGONAL];
    const long *list = s->free_cells, count = list_free_cells(s, slope);
    memset(dz, 0, (size_t)gr->size * sizeof *dz);
    memset(dir, 0, (size_t)gr->size * sizeof *dir);
    double rr = 0.0, rz = 0.0;
    for (long n = 0; n < count; ++n) {
        const long idx = list[n];
        double diag = 1.0 / slope[idx];
        for (int a = 0; a < 3; ++a)
            if (gr->n[a] > 1) // (as plastic_row: no flux along an axis of one cell)
                diag += s->weight[a][idx] + s->weight[a][idx + gr->stride[a]];
        diagonal[idx] = diag;
        pre[idx] = 1.0 / diag;
        res[idx] = r[idx];
        dir[idx] = pre[idx] * res[idx];
        rr += res[idx] * res[idx];
        rz += res[idx] * dir[idx];
    }
    const double norm0 = sqrt(rr), goal = s->def.tolerance * bdl_max(norm0, *reference);
    if (!(*reference > 0.0))
        *reference = norm0;
    int it = 0;
    while (norm0 > goal && it < s->def.max_iterations) {
        bdl_grid_wrap_cells_wide(gr, dir);
        double dq = 0.0;
        for (long n = 0; n < count; ++n) {
            const long idx = list[n];
            q[idx] = plastic_apply(s, diagonal, dir, idx);
            dq += dir[idx] * q[idx];
        }
        const double alpha = rz / dq;
        double rz_new = 0.0;
        rr = 0.0;
        for (long n = 0; n < count; ++n) {
            const long idx = list[n];
            dz[idx] += alpha * dir[idx], res[idx] -= alpha * q[idx];
            rr += res[idx] * res[idx];
            rz_new += res[idx] * pre[idx] * res[idx];
        }
        ++it;
        if (sqrt(rr) <= goal)
            break;
        const double ratio = rz_new / rz;
        rz = rz_new;
        for (long n = 0; n < count; ++n) {
            const long idx = list[n];
            dir[idx] = pre[idx] * res[idx] + ratio * dir[idx];
        }
    }
    FOR_CELLS(gr, z[idx] += dz[idx]);
    bdl_grid_wrap_cells(gr, z);
    return it;
}

/// The correction's fluxes -grad(z) / A into c, and the fractions they leave, x = eps* - dt
/// div(c).
static void plastic_result(bdl_solids *s, const double *star, const double *z, double dt, double *x)
{
    const bdl_grid *gr = &s->grid;
    for (int a = 0; a < 3; ++a) {
        const long sa = gr->stride[a];
        memset(s->c[a], 0, (size_t)gr->size * sizeof(double));
        if (!s->active[a])
            continue;
        FOR_INNER_FACES(gr, a, s->c[a][idx] = -(z[idx] - z[idx - sa]) / (gr->h[a] * s->a[a][idx]));
        wrap_face(gr, a, s->c[a]);
    }
    after_fluxes(gr, s->c, star, dt, x);
}

/// The cell next to cell idx (at index `at` along axis a) on the side `side` (-1 or +1): across a
/// periodic side the cell at the other end; -1 beyond a wall.
static long cell_neighbour(const bdl_grid *gr, int a, int at, int side, long idx)
{
    const long sa = gr->stride[a];
    if (at + side >= 0 && at + side < gr->n[a])
        return idx + side * sa;
    if (!gr->periodic[a] || gr->n[a] < 2)
        return -1;
    return idx - side * (long)(gr->n[a] - 1) * sa;
}

/// With the kinetic pressure implicit, whether the pressure cell idx is modelled with falls
/// short at the fraction x it was moved to: the increment it is given there (its chord times
/// x - eps^n for a free cell, lo for a held one, none outside) below the true P(x) - P(eps^n) by
/// more than 1 % of that and 10^-3 Pa. P is convex, so a chord falls short on both sides of its
/// interval: beyond its end point and, for a cell moved back past where it started, below it.
/// (The plastic rule, any push of 10^-9 beyond the end point, kept a tail of packed cells
/// re-chorded pass after pass once most of the bed is free: their pushes shrink by a half to a
/// quarter a pass.)
static int short_of_pressure(const bdl_solids *s, long idx, double slope, double lo, double x)
{
    const double eps = s->eps[idx];
    if (!(fabs(x - eps) > 1e-9))
        return 0;
    const double dp = cell_pressure(s, idx, x) - s->work[BASE_PRESSURE][idx];
    const double model = slope > 0.0 ? slope * (x - eps) : slope < 0.0 ? lo : 0.0;
    return dp - model > 1e-2 * fabs(dp) + 1e-3;
}

/// One pass of the correction: the residual r - M z of the free cells (those with a slope), the
/// solve for its increment, then: the neighbours of a cell that would go below zero no longer
/// allowed a pressure below zero themselves; the free cells whose pressure fell below its bound
/// held there (z = lo: they leave the free set); the cells pushed past their end point given the
/// chord to where they were pushed (stiffer; a held cell or one outside the regime joins again
/// if that is above eps_star). Returns whether anything changed (another pass is needed).
static int plastic_pass(bdl_solids *s, double *slope, const double *star, double dt,
                        double *reference)
{
    const bdl_grid *gr = &s->grid;
    const bdl_solids_def *d = &s->def;
    double *z = s->work[1], *r = s->work[2], *x = s->work[9], *end = s->work[8];
    double *lo = s->work[11], *res = s->work[12];
    const int implicit = d->kinetic_pressure == BDL_KINETIC_PRESSURE_IMPLICIT;
    FOR_CELLS(gr, res[idx] = slope[idx] > 0.0 ? r[idx] - plastic_row(s, slope, z, idx) : 0.0);
    s->stats.iterations += plastic_solve(s, slope, res, z, reference);
    plastic_result(s, star, z, dt, x);
    int changed = 0;
    FOR_CELLS(gr, { // a cell emptied below zero: its neighbours with z < 0 draw nothing more
        if (x[idx] < 0.0) {
            const int at[3] = {i, j, k};
            for (int a = 0; a < 3; ++a)
                for (int side = -1; side <= 1; side += 2) {
                    const long n = cell_neighbour(gr, a, at[a], side, idx);
                    if (n < 0 || !(z[n] < 0.0))
                        continue;
                    changed |= lo[n] < 0.0 || !(slope[n] > 0.0);
                    lo[n] = 0.0; // a free one is held by the loop below; a held one here
                    if (!(slope[n] > 0.0))
                        z[n] = slope[n] = 0.0;
                }
        }
    });
    FOR_CELLS(gr, {
        if (slope[idx] > 0.0 && z[idx] < lo[idx] - 1e-9 * bdl_max(-lo[idx], 1.0)) {
            z[idx] = lo[idx];
            slope[idx] = lo[idx] < 0.0 ? -1.0 : 0.0; // held (at zero pressure: as outside)
            changed = 1;
        } else if (implicit
                       ? short_of_pressure(s, idx, slope[idx], lo[idx], x[idx])
                       : x[idx] > end[idx] + 1e-9 && (slope[idx] > 0.0 || x[idx] > d->eps_star)) {
            end[idx] = x[idx]; // pushed past its end point: a stiffer chord (or it joins again)
            slope[idx] = plastic_chord(s, idx, s->eps[idx], x[idx]);
            changed = 1;
        }
    });
    bdl_grid_wrap_cells(gr, z);
    return changed;
}

static void distribute(bdl_solids *s, bdl_gas *gas, const double *x, double dt);

/// The correction: the increment z of the plastic pressure on the cells in Schaeffer's regime at
/// the start or the end of the step, then the fluxes -grad(z) / A of solids (and the opposite of
/// gas) on the inner faces, the velocities and eps^{n+1} from them, and the fluxes added to the
/// step's. star holds eps*.
///
/// A cell's pressure is modelled by the chord of Schaeffer's P from eps^n to an end point, first
/// eps*: exact if the cell keeps what the momentum step brought it, stiffer than P where it gives
/// some back (P is convex). A cell that the others' correction pushes above its end point (a cell
/// below eps_star pushed above it joins) gets the chord to where it was pushed, stiffer, and the
/// system is solved again. A cell whose pressure would fall below zero (z < -P(eps^n)) is held
/// there: an opening cell draws back at most what its own pressure pushed out in the momentum
/// step. A few passes (at most ten); the end points only rise (with the kinetic pressure
/// implicit a cell is re-chorded where its chord falls short of P on either side of its
/// interval: short_of_pressure()).
static void plastic_correction(bdl_solids *s, bdl_gas *gas, const double *star, double dt)
{
    const bdl_grid *gr = &s->grid;
    double *slope = s->work[0], *z = s->work[1], *r = s->work[2], *end = s->work[8];
    double *x = s->work[9], *lo = s->work[11], *base = s->work[BASE_PRESSURE];
    memset(slope, 0, (size_t)gr->size * sizeof *slope);
    memset(z, 0, (size_t)gr->size * sizeof *z);
    int any = 0;
    FOR_CELLS(gr, {
        end[idx] = star[idx];
        slope[idx] = plastic_chord(s, idx, s->eps[idx], star[idx]);
        base[idx] = cell_pressure(s, idx, s->eps[idx]);
        lo[idx] = -base[idx];
        r[idx] = star[idx] - s->eps[idx];
        any = any || slope[idx] > 0.0;
    });
    s->stats.iterations = s->stats.passes = s->stats.unsettled = 0;
    s->stats.correction = 0.0;
    for (int a = 0; a < 3; ++a)
        memset(s->c[a], 0, (size_t)gr->size * sizeof(double));
    if (!any) {
        FOR_CELLS(gr, x[idx] = star[idx]);
        distribute(s, gas, x, dt); // no fluxes: each phase at its eps*
        return;
    }
    for (int a = 0; a < 3; ++a) {
        double *w = s->weight[a];
        memset(w, 0, (size_t)gr->size * sizeof *w);
        if (!s->active[a])
            continue;
        FOR_INNER_FACES(gr, a, w[idx] = dt / (s->a[a][idx] * gr->h[a] * gr->h[a]));
        wrap_face(gr, a, w);
    }
    int changed = 1;
    double reference = 0.0; // the first pass's residual
    for (s->stats.passes = 0; changed && s->stats.passes < 10; ++s->stats.passes)
        changed = plastic_pass(s, slope, star, dt, &reference);
    s->stats.unsettled = changed;
    plastic_result(s, star, z, dt, x);
    double worst = 0.0;
    FOR_CELLS(gr, worst = bdl_max(worst, fabs(x[idx] - star[idx])));
    s->stats.correction = worst;
    distribute(s, gas, x, dt);
}

/// The correction's fluxes c given to the phases and the gas: every phase's velocity gains
/// c / eps_s and the gas's loses c / eps_g; each phase takes the share of c its fraction has in
/// the cell c leaves (after the step's transport), so that no phase leaves a cell faster than
/// the others; eps^{n+1} of each phase from its share (x: the mixture's, with one phase its own).
static void distribute(bdl_solids *s, bdl_gas *gas, const double *x, double dt)
{
    const bdl_grid *gr = &s->grid;
    const int n = s->count;
    for (int m = 0; m < n && n > 1; ++m)
        bdl_grid_wrap_cells(gr, s->phase[m].star);
    for (int a = 0; a < 3; ++a) {
        const long sa = gr->stride[a];
        if (!s->active[a]) // (no correction along it: c is zero)
            continue;
        for (int m = 0; m < n && n > 1; ++m)
            memset(s->phase[m].cflux[a], 0, (size_t)gr->size * sizeof(double));
        FOR_INNER_FACES(gr, a, {
            const double df = s->c[a][idx];
            const double es = 0.5 * (s->eps[idx] + s->eps[idx - sa]);
            const long from = df >= 0.0 ? idx - sa : idx;
            double total = 0.0;
            for (int m = 0; m < n && n > 1; ++m)
                total += s->phase[m].star[from];
            for (int m = 0; m < n; ++m) {
                bdl_solids_phase *p = &s->phase[m];
                p->v[a][idx] += df / bdl_max(es, s->def.dilute);
                if (n > 1)
                    p->cflux[a][idx] = df * (total > 0.0 ? p->star[from] / total : 1.0 / n);
            }
            gas->u[a][idx] -= df / (1.0 - es);
        });
        for (int m = 0; m < n; ++m) {
            bdl_solids_phase *p = &s->phase[m];
            wrap_face(gr, a, p->v[a]);
            if (n > 1)
                wrap_face(gr, a, p->cflux[a]);
            double *const add = n > 1 ? p->cflux[a] : s->c[a];
            for (long idx = 0; idx < gr->size; ++idx)
                p->flux[a][idx] += add[idx];
        }
        wrap_face(gr, a, gas->u[a]);
    }
    if (n == 1) {
        FOR_CELLS(gr, s->eps[idx] = x[idx]);
        return;
    }
    for (int m = 0; m < n; ++m)
        after_fluxes(gr, s->phase[m].cflux, s->phase[m].star, dt, s->phase[m].eps);
    mixture_fraction(s);
}

// ---------------------------------------------------------------------------------------------
// The step.

/// Whether axis a is inert for the solids and the gas (bdl_gas_axis_inert): its solids
/// velocities all zero too. Such an axis (the depth of a two-dimensional run) is left out of the
/// step; its faces' velocities, fluxes and corrections stay zero, as its equations would give.
static int axis_inert(const bdl_solids *s, const bdl_gas *gas, int a)
{
    if (!bdl_gas_axis_inert(gas, a))
        return 0;
    for (int m = 0; m < s->count; ++m)
        for (long i = 0; i < s->grid.size; ++i)
            if (s->phase[m].v[a][i] != 0.0)
                return 0;
    return 1;
}

bdl_result bdl_solids_step(bdl_solids *s, bdl_gas *gas, double dt)
{
    const bdl_grid *gr = &s->grid;
    for (int a = 0; a < 3; ++a)
        s->active[a] = !axis_inert(s, gas, a);
    for (int m = 0; m < s->count; ++m)
        for (int a = 0; a < 3; ++a) { // the fluxes' images too: the transport reads a period
            if (!s->active[a])
                continue;
            velocity_ghosts(gr, a, s->phase[m].v[a]);
            velocity_ghosts(gr, a, s->phase[m].flux[a]);
        }
    bdl_solids_share_voidage(s, gas);
    closures(s, gas, dt);
    for (int a = 0; a < 3; ++a) {
        if (!s->active[a])
            continue;
        reset_hooks(s, gas, a);
        for (int m = 0; m < s->count; ++m)
            momentum(s, m, gas, a, dt);
        if (s->count > 1)
            couple(s, gas, a);
    }
    const bdl_result r = bdl_gas_step_axes(gas, dt, s->active); // (an inert axis is the gas's)
    for (int a = 0; a < 3; ++a)
        for (int m = 0; m < s->count && s->active[a]; ++m)
            new_velocity(s, m, gas, a);
    for (int m = 0; m < s->count; ++m)
        limit_outflow(s, m, gas, dt);
    double *star = s->work[3];
    if (s->count == 1) {
        after_fluxes(gr, s->phase[0].flux, s->eps, dt, star);
    } else {
        memset(star, 0, (size_t)gr->size * sizeof *star);
        for (int m = 0; m < s->count; ++m) {
            bdl_solids_phase *p = &s->phase[m];
            after_fluxes(gr, p->flux, p->eps, dt, p->star);
            FOR_CELLS(gr, star[idx] += p->star[idx]);
        }
    }
    plastic_correction(s, gas, star, dt);
    bdl_solids_share_voidage(s, gas);
    double lo = INFINITY, hi = -INFINITY;
    int finite = 1;
    FOR_CELLS(gr, {
        hi = bdl_max(hi, s->eps[idx]);
        for (int m = 0; m < s->count; ++m) {
            lo = bdl_min(lo, s->phase[m].eps[idx]);
            finite = finite && isfinite(s->phase[m].eps[idx]);
            for (int a = 0; a < 3; ++a)
                finite = finite && isfinite(s->phase[m].v[a][idx]);
        }
    });
    s->stats.eps_min = lo;
    s->stats.eps_max = hi;
    s->time += dt;
    s->steps++;
    if (r != BDL_OK)
        return r;
    return finite && isfinite(lo) && isfinite(hi) ? BDL_OK : BDL_ERR_UNSTABLE;
}

/// The speed of the viscous regime's pressure waves in a cell of phase fraction eps (the
/// mixture's `total`, for the radial distribution) at temperature theta: c^2 = dP/d(eps) / rho at
/// fixed theta, P = k1 eps^2 theta, k1 = 2 (1 + e) rho g0 with Carnahan & Starling's g0 of the
/// total fraction (a mixture's Lebowitz g0_mm is of its size), the total moving with eps:
/// c^2 = 2 (1 + e) theta (2 eps g0 + eps^2 g0'), g0' = (5/2 - total) / (1 - total)^4. The
/// momentum step takes -grad P explicitly: a step above h / c would let the waves grow.
static double sound_speed(const bdl_solids_def *d, double eps, double total, double theta)
{
    const double q = 1.0 - total;
    const double g0 = bdl_g0_carnahan_starling(total), slope = (2.5 - total) / (q * q * q * q);
    const double c2 = 2.0 * (1.0 + d->restitution) * theta * eps * (2.0 * g0 + eps * slope);
    return sqrt(bdl_max(c2, 0.0));
}

double bdl_solids_stable_dt(const bdl_solids *s)
{
    const bdl_grid *gr = &s->grid;
    double inv_h = 0.0; // sum of 1/h over the axes with more than one cell
    for (int a = 0; a < 3; ++a)
        inv_h += gr->n[a] > 1 ? 1.0 / gr->h[a] : 0.0;
    double out = 0.0; // the largest rate at which a cell's faces carry its solids out [1/s]
    const double waves = s->def.kinetic_pressure == BDL_KINETIC_PRESSURE_IMPLICIT
                             ? s->def.wave_weight
                             : 1.0; // the weight of the pressure waves' speed
    for (int m = 0; m < s->count; ++m) {
        const bdl_solids_phase *p = &s->phase[m];
        FOR_CELLS(gr, {
            if (p->eps[idx] > s->def.dilute) {
                double rate = 0.0;
                for (int a = 0; a < 3; ++a)
                    rate +=
                        (bdl_max(p->v[a][idx + gr->stride[a]], 0.0) + bdl_max(-p->v[a][idx], 0.0)) /
                        gr->h[a];
                if (p->theta[idx] > 0.0 && waves > 0.0)
                    rate += waves * sound_speed(&p->def, p->eps[idx], s->eps[idx], p->theta[idx]) *
                            inv_h;
                out = bdl_max(out, rate);
            }
        });
    }
    return out > 0.0 ? 0.5 / out : INFINITY;
}
