// bedlam — gas and coupling verification cases: Poiseuille, cavity, terminal slip, Ergun,
// minimum fluidization, hindered settling.
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/umf.h"
#include "core/log.h"
#include "cfd/gas.h"
#include "couple/coupling.h"
#include "output/diagnostics.h"
#include "verify/verify.h"

// ---- plane Poiseuille flow ----

double bdl_verify_poiseuille(int cells, double *cross, long *steps)
{
    bdl_gas_def d = bdl_default_gas_def();
    d.n[0] = 4, d.n[1] = cells, d.n[2] = 1;
    d.hi[0] = 0.5, d.hi[1] = 1.0, d.hi[2] = 0.1;
    d.density = 1.0;
    d.viscosity = 0.1;
    d.gravity[0] = 1.0; // the driving pressure gradient, as a body force
    for (int a = 0; a < 3; ++a)
        d.side[2 * a].type = d.side[2 * a + 1].type = BDL_SIDE_PERIODIC;
    d.side[2].type = d.side[3].type = BDL_SIDE_WALL;
    d.convection = BDL_CONVECTION_VANLEER;
    d.tolerance = 1e-10;
    bdl_gas *g = NULL;
    if (bdl_gas_create(&d, &g) != BDL_OK)
        return INFINITY;
    // Between walls at y = 0 and 1: u = g y (1 - y) / (2 nu).
    const double nu = d.viscosity / d.density, umax = d.gravity[0] / (8.0 * nu);
    const double dt = 0.9 * bdl_gas_stable_dt(g);
    const long mid = bdl_grid_index(&g->grid, 0, cells / 2, 0);
    double change = INFINITY;
    long s = 0;
    for (; s < 200000 && change > 1e-13 * umax; ++s) {
        double before = g->u[0][mid];
        if (bdl_gas_step(g, dt) != BDL_OK)
            break;
        change = fabs(g->u[0][mid] - before);
    }
    double err = 0.0;
    for (int j = 0; j < cells; ++j) {
        double y = (j + 0.5) / cells, exact = d.gravity[0] * y * (1.0 - y) / (2.0 * nu);
        for (int i = 0; i < d.n[0]; ++i)
            err = fmax(err, fabs(g->u[0][bdl_grid_index(&g->grid, i, j, 0)] - exact));
    }
    double vmax = 0.0; // the flow stays parallel
    for (int j = 0; j <= cells; ++j)
        vmax = fmax(vmax, fabs(g->u[1][bdl_grid_index(&g->grid, 1, j, 0)]));
    if (cross)
        *cross = vmax / umax;
    if (steps)
        *steps += s;
    bdl_gas_destroy(g);
    return change > 1e-13 * umax ? INFINITY : err / umax;
}

// ---- lid-driven cavity, Re 100 (Ghia, Ghia & Shin 1982, J. Comput. Phys. 48, tables I, II) ----

static const double ghia_y[] = {0.9766, 0.9688, 0.9609, 0.9531, 0.8516, 0.7344, 0.6172, 0.5000,
                                0.4531, 0.2813, 0.1719, 0.1016, 0.0703, 0.0625, 0.0547};
static const double ghia_u[] = {0.84123,  0.78871,  0.73722,  0.68717,  0.23151,
                                0.00332,  -0.13641, -0.20581, -0.21090, -0.15662,
                                -0.10150, -0.06434, -0.04775, -0.04192, -0.03717};
static const double ghia_x[] = {0.9688, 0.9609, 0.9531, 0.9453, 0.9063, 0.8594, 0.8047, 0.5000,
                                0.2344, 0.2266, 0.1563, 0.0938, 0.0781, 0.0703, 0.0625};
static const double ghia_v[] = {-0.05906, -0.07391, -0.08864, -0.10313, -0.16914,
                                -0.22445, -0.24533, 0.05454,  0.17527,  0.17507,
                                0.16077,  0.12317,  0.10890,  0.10091,  0.09233};

/// Linear interpolation of face values f(s) stored at s = (m + 0.5)/n, m = 0..n-1, with the
/// wall values w0 at s = 0 and w1 at s = 1.
static double along(const double *f, int n, double s, double w0, double w1)
{
    double x = s * n - 0.5;
    if (x < 0.0)
        return w0 + (f[0] - w0) * (s * n) / 0.5;
    if (x > n - 1)
        return f[n - 1] + (w1 - f[n - 1]) * (x - (n - 1)) / 0.5;
    int m = (int)x;
    if (m > n - 2)
        m = n - 2;
    return f[m] + (f[m + 1] - f[m]) * (x - m);
}

double bdl_verify_cavity(int n, int scheme, double *worst_u, double *worst_v, int table,
                         long *steps)
{
    bdl_gas_def d = bdl_default_gas_def();
    d.n[0] = d.n[1] = n, d.n[2] = 1;
    d.hi[0] = d.hi[1] = 1.0, d.hi[2] = 1.0 / n;
    d.density = 1.0;
    d.viscosity = 0.01; // Re = U L / nu = 100
    for (int s = 0; s < 4; ++s)
        d.side[s].type = BDL_SIDE_WALL;
    d.side[3].wall_velocity[0] = 1.0; // the lid at y = 1
    d.side[4].type = d.side[5].type = BDL_SIDE_PERIODIC;
    d.convection = (bdl_convection)scheme;
    d.tolerance = 1e-10;
    bdl_gas *g = NULL;
    if (bdl_gas_create(&d, &g) != BDL_OK)
        return -1.0;
    const double dt = fmin(0.8 / (2.0 * d.viscosity * 2.0 * n * n), 0.4 / n);
    double *before = malloc((size_t)g->grid.size * sizeof(double));
    double *uc = malloc((size_t)n * sizeof(double)), *vc = malloc((size_t)n * sizeof(double));
    double change = INFINITY, t = 0.0, result = -1.0;
    long s = 0;
    // Steady when no velocity changes faster than 1e-6 (lid velocities) per unit time.
    while (before && uc && vc && change > 1e-6 && t < 200.0) {
        memcpy(before, g->u[0], (size_t)g->grid.size * sizeof(double));
        for (int k = 0; k < 50; ++k, ++s)
            if (bdl_gas_step(g, dt) != BDL_OK)
                goto done;
        t += 50 * dt;
        change = 0.0;
        for (int j = 0; j < n; ++j)
            for (int i = 0; i <= n; ++i) {
                long idx = bdl_grid_index(&g->grid, i, j, 0);
                change = fmax(change, fabs(g->u[0][idx] - before[idx]) / (50 * dt));
            }
    }
    if (!before || !uc || !vc || change > 1e-6)
        goto done;
    // u on x = 0.5 (faces i = n/2), v on y = 0.5 (faces j = n/2).
    for (int m = 0; m < n; ++m) {
        uc[m] = g->u[0][bdl_grid_index(&g->grid, n / 2, m, 0)];
        vc[m] = g->u[1][bdl_grid_index(&g->grid, m, n / 2, 0)];
    }
    *worst_u = *worst_v = 0.0;
    if (table)
        printf("lid-driven cavity, Re = 100, %dx%d cells, steady at t = %.1f (%ld steps)\n"
               "   y      u        Ghia     |    x      v        Ghia\n",
               n, n, t, s);
    for (size_t k = 0; k < sizeof ghia_y / sizeof ghia_y[0]; ++k) {
        double u = along(uc, n, ghia_y[k], 0.0, 1.0), v = along(vc, n, ghia_x[k], 0.0, 0.0);
        *worst_u = fmax(*worst_u, fabs(u - ghia_u[k]));
        *worst_v = fmax(*worst_v, fabs(v - ghia_v[k]));
        if (table)
            printf("%.4f % .5f % .5f | %.4f % .5f % .5f\n", ghia_y[k], u, ghia_u[k], ghia_x[k], v,
                   ghia_v[k]);
    }
    result = fmax(*worst_u, *worst_v);
done:
    if (steps)
        *steps += s;
    free(before);
    free(uc);
    free(vc);
    bdl_gas_destroy(g);
    return result;
}

// ---- terminal slip of one sphere ----

double bdl_verify_implied_slip(bdl_drag_law law, double eps, double d, double rho, double mu,
                               double target, double hi)
{
    double lo = 0.0;
    for (int it = 0; it < 200; ++it) {
        double mid = 0.5 * (lo + hi);
        if (bdl_drag_per_volume(law, NULL, eps, d, mid, rho, mu) * mid < target)
            lo = mid;
        else
            hi = mid;
    }
    return 0.5 * (lo + hi);
}

/// The gas velocity at the one particle: the cell-centre velocities interpolated with the
/// particle's kernel.
static void gas_velocity_at(bdl_coupling *k, bdl_gas *g, const bdl_particles *p, double u[3])
{
    const int *n = g->grid.n;
    for (int a = 0; a < 3; ++a) {
        double *cell_u = g->rhs; // scratch: cell-centre velocity of component a
        for (int kk = 0; kk < n[2]; ++kk)
            for (int j = 0; j < n[1]; ++j)
                for (int i = 0; i < n[0]; ++i)
                    cell_u[bdl_grid_index(&g->grid, i, j, kk)] =
                        bdl_gas_cell_velocity(g, a, i, j, kk);
        bdl_coupling_locate(k, g, p);
        u[a] = bdl_coupling_interpolate(k, 0, cell_u);
    }
}

/// Explicit Euler step of the one particle of mass m under drag, pressure force and buoyant
/// gravity gz, wrapped into the periodic box [0, hi); returns its acceleration other than drag.
static bdl_vec3 push(bdl_particles *p, bdl_vec3 drag, bdl_vec3 pres, double m, double gz, double dt,
                     const double hi[3])
{
    bdl_vec3 other;
    for (int a = 0; a < 3; ++a) {
        double a_other = (a == 2 ? gz : 0.0) + bdl_v3_comp(pres, a) / m;
        double v = bdl_v3_comp(p->vel[0], a) + dt * (a_other + bdl_v3_comp(drag, a) / m);
        double x = bdl_v3_comp(p->pos[0], a) + dt * v;
        bdl_v3_set_comp(&p->vel[0], a, v);
        bdl_v3_set_comp(&other, a, a_other);
        bdl_v3_set_comp(&p->pos[0], a, fmod(fmod(x, hi[a]) + hi[a], hi[a]));
    }
    return other;
}

bdl_verify_terminal bdl_verify_terminal_slip(double d, double rho_p, bdl_drag_law law, int cells)
{
    const double rho = 1.2, mu = 1.8e-5, h = 24.0 * d / cells;
    bdl_verify_terminal res = {NAN, NAN, NAN, NAN, NAN, 0};
    bdl_gas_def gd = bdl_default_gas_def();
    gd.n[0] = gd.n[1] = cells, gd.n[2] = cells * 4 / 3;
    gd.hi[0] = gd.hi[1] = 24.0 * d, gd.hi[2] = gd.n[2] * h;
    gd.density = rho;
    gd.viscosity = mu;
    for (int s = 0; s < 6; ++s)
        gd.side[s].type = BDL_SIDE_PERIODIC;
    gd.convection = BDL_CONVECTION_VANLEER;
    gd.tolerance = 1e-10;
    bdl_gas *g = NULL;
    if (bdl_gas_create(&gd, &g) != BDL_OK)
        return res;
    bdl_coupling_def def = bdl_default_coupling_def(&g->grid);
    def.drag = law;
    def.kernel_width = 6.0 * d;
    bdl_coupling k;
    bdl_particles p = {0};
    if (bdl_coupling_init(&k, &def, g) != BDL_OK ||
        bdl_particles_add(&p, bdl_v3(12.4 * d, 11.6 * d, 0.75 * gd.hi[2]), bdl_v3_zero(), 0.5 * d,
                          rho_p, 0) < 0) {
        bdl_particles_free(&p);
        bdl_gas_destroy(g);
        return res;
    }
    const double m = rho_p * BDL_PI / 6.0 * d * d * d, gz = -9.81 * (1.0 - rho / rho_p);
    const double vt = bdl_verify_implied_slip(law, 1.0, d, rho, mu, (rho_p - rho) * 9.81, 100.0);
    const double tau = vt / 9.81; // time to terminal scale
    double dt = fmin(fmin(0.5 * h / vt, 0.2 * tau), 0.9 * bdl_gas_stable_dt(g));
    const long steps = (long)(6.0 * tau / dt) + 1;
    double slip_sum = 0.0, eps_sum = 0.0, u[3];
    long averaged = 0;
    double *src = g->source[2];
    bdl_vec3 acc = bdl_v3_zero(), drag, pres;
    const double vbox = gd.hi[0] * gd.hi[1] * gd.hi[2];
    for (long step = 0; step < steps; ++step) {
        dt = fmin(dt, 0.9 * bdl_gas_stable_dt(g));
        bdl_coupling_locate(&k, g, &p);
        bdl_coupling_voidage(&k, g, &p);
        if (step == 0)
            memcpy(g->eps_old, g->eps, (size_t)g->grid.size * sizeof(double));
        bdl_coupling_drag_setup(&k, g, &p, &acc, NULL, dt);
        if (bdl_gas_step(g, dt) != BDL_OK)
            break;
        ++res.steps;
        bdl_coupling_forces(&k, g, &p, &acc, dt, &drag, &pres);
        // The box's weight is carried by a uniform body force on the gas equal to the total
        // drag, as a container's base would.
        for (long i = 0; i < g->grid.size; ++i)
            src[i] = drag.z / vbox;
        acc = push(&p, drag, pres, m, gz, dt, gd.hi);
        if (step <= 2 * steps / 3)
            continue;
        gas_velocity_at(&k, g, &p, u);
        slip_sum += u[2] - p.vel[0].z;
        eps_sum += bdl_coupling_interpolate(&k, 0, g->eps);
        averaged++;
    }
    if (averaged > 0) {
        res.slip = slip_sum / averaged;
        res.voidage = eps_sum / averaged;
        res.expected =
            bdl_verify_implied_slip(law, res.voidage, d, rho, mu, (rho_p - rho) * 9.81, 100.0);
        res.re = rho * d * res.slip / mu;
        res.gas_speed = res.slip + p.vel[0].z;
    }
    bdl_particles_free(&p);
    bdl_coupling_free(&k);
    bdl_gas_destroy(g);
    return res;
}

// ---- packed bed against Ergun ----

double bdl_verify_ergun(double eps, double U, double d, double rho, double mu)
{
    double phi = 1.0 - eps;
    return 150.0 * phi * phi * mu * U / (eps * eps * eps * d * d) +
           1.75 * phi * rho * U * U / (eps * eps * eps * d);
}

static bdl_result run_until(bdl_world *w, double t, long *steps)
{
    while (w->time < t) {
        bdl_result r = bdl_world_step(w);
        if (r != BDL_OK) {
            bdl_error("%s", w->failure);
            return r;
        }
        ++*steps;
    }
    return BDL_OK;
}

bdl_result bdl_verify_packed_bed(int cells_z, const double *U, int n, double *ratio,
                                 double *eps_mean, long *steps)
{
    long ignored_steps = 0;
    if (!steps)
        steps = &ignored_steps;
    const double d = 0.002, rho = 1.2, mu = 1.8e-5, U0 = U[0];
    const int across = cells_z / 5 > 1 ? cells_z / 5 : 1;
    bdl_world *w = bdl_verify_world(
        "[run]\nend_time = 1\ndt_fraction = 0.05\ngravity = 0 0 -9.81\nseed = 5\n"
        "[domain]\nmin = 0 0 0\nmax = 0.02 0.02 0.1\nperiodic = x y\n"
        "[contact]\nlaw = linear\n"
        "[species glass]\ndiameter = 0.002\ndensity = 2500\nstiffness = 1000\n"
        "restitution = 0.3\nfriction = 0.5\nbackground_damping = 20\n"
        "[wall floor]\ntype = plane\npoint = 0 0 0\nnormal = 0 0 1\n"
        "[create bed]\ntype = random\nspecies = glass\ncount = 1400\nregion_min = 0 0 0\n"
        "region_max = 0.02 0.02 0.075\n"
        "[gas]\ncells = %d %d %d\nzmin = inlet\nzmax = outlet\ninlet_velocity = %g\n"
        "[coupling]\ndrag = ergun\n",
        across, across, cells_z, U0);
    if (!w || !w->gas) {
        if (w)
            bdl_world_destroy(w);
        return BDL_ERR_SCENE;
    }
    const bdl_grid *g = &w->gas->grid;
    double t = 0.3; // settle first
    bdl_result r = BDL_OK;
    for (int v = 0; v < n && r == BDL_OK; ++v) {
        bdl_world_set_parameter(w, "gas.inlet_scale", U[v] / U0);
        r = run_until(w, t, steps);
        t += 0.08;
        // Layers well inside the bed: between a quarter and three quarters of its height.
        double top = 0.0;
        for (long i = 0; i < w->particles.count; ++i)
            top = fmax(top, w->particles.pos[i].z);
        int lo = (int)(0.25 * top / g->h[2]), hi = (int)(0.75 * top / g->h[2]);
        double sum = 0.0, eps_sum = 0.0;
        int layers = 0;
        for (int k = lo; k < hi; ++k) {
            double dp = 0.0, eps = 0.0;
            for (int j = 0; j < g->n[1]; ++j)
                for (int i = 0; i < g->n[0]; ++i) {
                    long a = bdl_grid_index(g, i, j, k), b = bdl_grid_index(g, i, j, k + 1);
                    dp += w->gas->p[a] - w->gas->p[b];
                    eps += 0.5 * (w->gas->eps[a] + w->gas->eps[b]);
                }
            dp /= g->n[0] * g->n[1];
            eps /= g->n[0] * g->n[1];
            double gradient = dp / g->h[2] - rho * 9.81; // the gas's own weight is not drag
            sum += gradient / bdl_verify_ergun(eps, U[v], d, rho, mu);
            eps_sum += eps;
            ++layers;
        }
        ratio[v] = layers > 0 ? sum / layers : NAN;
        eps_mean[v] = layers > 0 ? eps_sum / layers : NAN;
    }
    bdl_world_destroy(w);
    return r;
}

// ---- minimum fluidization from a velocity sweep ----

static bdl_result mean_pressure_drop(bdl_world *w, double duration, double *mean, long *steps)
{
    double sum = 0.0, end = w->time + duration, start = w->time + 0.5 * duration;
    int n = 0;
    long seen = -1;
    while (w->time < end) {
        bdl_result r = bdl_world_step(w);
        if (r != BDL_OK) {
            bdl_error("%s", w->failure);
            return r;
        }
        ++*steps;
        if (w->time > start && w->gas_steps != seen) { // just after a gas step
            seen = w->gas_steps;
            bdl_diagnostics d;
            bdl_diagnostics_compute(w, 0.0, &d);
            sum += d.pressure_drop;
            ++n;
        }
    }
    *mean = n > 0 ? sum / n : 0.0;
    return BDL_OK;
}

/// One sweep through u[0..n-1]; Ergun's a U + b U^2 fitted (least squares) to the four lowest
/// velocities (surely a fixed bed), and U_mf where it reaches the bed's weight `target`.
static bdl_result sweep(bdl_world *w, const char *name, const double *u, int n, double U0,
                        double target, double gas_column, double dwell, int table, double *umf,
                        long *steps)
{
    double dp[16];
    if (table)
        printf("   %s sweep: U [m/s]   pressure drop / bed weight\n", name);
    for (int k = 0; k < n; ++k) {
        bdl_world_set_parameter(w, "gas.inlet_scale", u[k] / U0);
        bdl_result r = mean_pressure_drop(w, dwell, &dp[k], steps);
        if (r != BDL_OK)
            return r;
        dp[k] -= gas_column;
        if (table)
            printf("      %.2f      %.3f\n", u[k], dp[k] / target);
    }
    int use[16] = {0}; // the four lowest velocities
    for (int pass = 0; pass < 4; ++pass) {
        int best = -1;
        for (int k = 0; k < n; ++k)
            if (!use[k] && (best < 0 || u[k] < u[best]))
                best = k;
        use[best] = 1;
    }
    double a, b;
    *umf = bdl_umf_fit(u, dp, use, n, target, &a, &b);
    return BDL_OK;
}

bdl_result bdl_verify_umf(double dwell, double *umf_down, double *umf_up, double *wen_yu, int table,
                          long *steps)
{
    long ignored_steps = 0;
    if (!steps)
        steps = &ignored_steps;
    const double d = 0.002, rho = 1.2, rho_p = 2500.0, mu = 1.8e-5, U0 = 1.5;
    bdl_world *w = bdl_verify_world(
        "[run]\nend_time = 10\ndt_fraction = 0.05\ngravity = 0 0 -9.81\nseed = 5\n"
        "[domain]\nmin = 0 0 0\nmax = 0.02 0.02 0.12\nperiodic = x y\n"
        "[contact]\nlaw = linear\n"
        "[species glass]\ndiameter = 0.002\ndensity = 2500\nstiffness = 1000\n"
        "restitution = 0.3\nfriction = 0.5\n"
        "[wall floor]\ntype = plane\npoint = 0 0 0\nnormal = 0 0 1\n"
        "[create bed]\ntype = random\nspecies = glass\ncount = 1400\nregion_min = 0 0 0\n"
        "region_max = 0.02 0.02 0.075\n"
        "[gas]\ncells = 5 5 30\nzmin = inlet\nzmax = outlet\ninlet_velocity = %g\n"
        "[coupling]\ndrag = gidaspow\n",
        U0);
    if (!w || !w->gas) {
        if (w)
            bdl_world_destroy(w);
        return BDL_ERR_SCENE;
    }
    double mass = 0.0;
    for (long i = 0; i < w->particles.count; ++i)
        mass += 1.0 / w->particles.inv_mass[i];
    // The bed's weight per area less buoyancy; the gas column's own weight is taken off the
    // measured drop.
    const double gas_column = rho * 9.81 * 0.12;
    const double target = mass * (1.0 - rho / rho_p) * 9.81 / (0.02 * 0.02);
    const double ar = rho * (rho_p - rho) * 9.81 * d * d * d / (mu * mu);
    *wen_yu = (sqrt(33.7 * 33.7 + 0.0408 * ar) - 33.7) * mu / (rho * d);
    // Fluidize; then down from the fluidized bed, and back up through the packed bed it forms.
    static const double down[] = {1.4, 1.3, 1.2, 1.1, 1.0, 0.9, 0.8, 0.6, 0.4};
    static const double up[] = {0.4, 0.6, 0.8, 0.9, 1.0, 1.1, 1.2, 1.3, 1.4};
    double ignored;
    bdl_result r = mean_pressure_drop(w, 0.25, &ignored, steps);
    if (r == BDL_OK)
        r = sweep(w, "decreasing", down, 9, U0, target, gas_column, dwell, table, umf_down, steps);
    if (r == BDL_OK)
        r = sweep(w, "increasing", up, 9, U0, target, gas_column, dwell, table, umf_up, steps);
    bdl_world_destroy(w);
    return r;
}

// ---- hindered settling (Richardson & Zaki 1954) ----

static bdl_world *suspension_world(double phi, double dt_gas)
{
    const double d = 1e-4, side = 10 * d, height = 20 * d;
    const long count = lrint(phi * side * side * height / (BDL_PI / 6.0 * d * d * d));
    return bdl_verify_world(
        "[run]\nend_time = 1\ndt_fraction = 0.05\ngravity = 0 0 -9.81\nseed = 11\n"
        "[domain]\nmin = 0 0 0\nmax = %g %g %g\nperiodic = x y z\n"
        "[contact]\nlaw = linear\n"
        "[species glass]\ndiameter = %g\ndensity = 2500\nstiffness = 0.01\nrestitution = 0.5\n"
        "friction = 0\n"
        "[create cloud]\ntype = random\nspecies = glass\ncount = %ld\nregion_min = 0 0 0\n"
        "region_max = %g %g %g\n"
        "[gas]\ndensity = 1000\nviscosity = 1e-3\ncells = 4 4 8\ndt = %.17g\n"
        "[coupling]\ndrag = wen_yu\n",
        side, side, height, d, count, side, side, height, dt_gas);
}

bdl_result bdl_verify_suspension(double phi, int substeps, bdl_verify_settling *out)
{
    const double d = 1e-4, rho_p = 2500.0, rho = 1000.0, mu = 1e-3, g = 9.81;
    const double side = 10 * d, height = 20 * d;
    bdl_world *w = suspension_world(phi, 0.0);
    if (w && substeps > 0) { // the gas step is rounded down to whole particle steps
        double dt = w->dt;
        bdl_world_destroy(w);
        w = suspension_world(phi, (substeps + 0.5) * dt);
    }
    if (!w || !w->gas) {
        if (w)
            bdl_world_destroy(w);
        return BDL_ERR_SCENE;
    }
    const bdl_grid *gr = &w->gas->grid;
    const double vol1 = BDL_PI / 6.0 * d * d * d, volume = side * side * height;
    double sum = 0.0;
    long samples = 0;
    out->steps = 0;
    bdl_result r = BDL_OK;
    while (w->time < 0.06) {
        r = bdl_world_step(w);
        if (r != BDL_OK) {
            bdl_error("%s", w->failure);
            break;
        }
        ++out->steps;
        if (w->time < 0.03)
            continue;
        // Particle velocity relative to the volume flux of the mixture.
        double vp = 0.0, vol_p = 0.0, flux = 0.0;
        for (long i = 0; i < w->particles.count; ++i) {
            vp += vol1 * w->particles.vel[i].z;
            vol_p += vol1;
        }
        for (int k = 0; k < gr->n[2]; ++k)
            for (int j = 0; j < gr->n[1]; ++j)
                for (int i = 0; i < gr->n[0]; ++i) {
                    long idx = bdl_grid_index(gr, i, j, k);
                    double eps = 0.5 * (w->gas->eps[idx] + w->gas->eps[idx - gr->stride[2]]);
                    flux += eps * w->gas->u[2][idx] * gr->h[0] * gr->h[1] * gr->h[2];
                }
        sum += vp / vol_p - (vp + flux) / volume;
        ++samples;
    }
    bdl_world_destroy(w);
    // The drag law's settling speed v = eps w with K(eps, w) w = eps (rho_p - rho) g.
    const double eps = 1.0 - phi;
    const double target = (rho_p - rho) * g;
    out->measured = samples > 0 ? -sum / samples : NAN;
    out->expected =
        eps * bdl_verify_implied_slip(BDL_DRAG_WEN_YU, eps, d, rho, mu, eps * target, 1.0);
    out->vt = bdl_verify_implied_slip(BDL_DRAG_WEN_YU, 1.0, d, rho, mu, target, 1.0);
    out->re_t = rho * out->vt * d / mu;
    out->n = log(out->expected / out->vt) / log(eps);
    return r;
}
