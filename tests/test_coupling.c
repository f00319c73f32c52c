// Gas-particle coupling: deposited volume conserved, linear fields interpolated exactly, the
// drag the gas feels equal and opposite to the drag the particles feel, and single spheres
// settling at the terminal slip velocity their drag law implies (Re about 0.1, 10 and 500).
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "core/vec3.h"
#include "couple/coupling.h"
#include "verify/verify.h"

static double uniform(unsigned *state, double lo, double hi)
{
    *state = *state * 1664525u + 1013904223u;
    return lo + (hi - lo) * (*state >> 8) / 16777216.0;
}

static bdl_gas *make_gas(int n0, int n1, int n2, double h, int periodic_x, int outlet)
{
    bdl_gas_def d = bdl_default_gas_def();
    d.n[0] = n0, d.n[1] = n1, d.n[2] = n2;
    d.hi[0] = n0 * h, d.hi[1] = n1 * h, d.hi[2] = n2 * h;
    for (int s = 0; s < 6; ++s)
        d.side[s].type = BDL_SIDE_WALL;
    if (periodic_x)
        d.side[0].type = d.side[1].type = BDL_SIDE_PERIODIC;
    if (outlet)
        d.side[5].type = BDL_SIDE_OUTLET;
    d.tolerance = 1e-12;
    bdl_gas *g = NULL;
    bdl_gas_create(&d, &g);
    return g;
}

/// Particles of 2500 kg/m^3 at random in the gas's box, with random velocities and other
/// accelerations.
typedef struct cloud {
    bdl_particles p;
    bdl_vec3 *acc;
} cloud;

static cloud make_cloud(long n, const bdl_gas *g, unsigned seed)
{
    cloud c = {.acc = malloc((size_t)n * sizeof(bdl_vec3))};
    for (long i = 0; i < n; ++i) {
        double x[3], v[3];
        for (int a = 0; a < 3; ++a) {
            double len = g->grid.n[a] * g->grid.h[a];
            x[a] = uniform(&seed, 0.0, len);
            v[a] = uniform(&seed, -0.5, 0.5);
            bdl_v3_set_comp(&c.acc[i], a, uniform(&seed, -10.0, 10.0));
        }
        double r = uniform(&seed, 0.2e-3, 0.5e-3);
        bdl_particles_add(&c.p, bdl_v3(x[0], x[1], x[2]), bdl_v3(v[0], v[1], v[2]), r, 2500.0, 0);
    }
    return c;
}

static void free_cloud(cloud *c)
{
    bdl_particles_free(&c->p);
    free(c->acc);
}

static void test_conservation_and_balance(int periodic_x, double width_cells)
{
    bdl_gas *g = make_gas(8, 6, 10, 2e-3, periodic_x, 1);
    cloud c = make_cloud(400, g, 11);
    const bdl_particles *p = &c.p;
    bdl_coupling_def def = bdl_default_coupling_def(&g->grid);
    def.kernel_width = width_cells * 2e-3;
    bdl_coupling k;
    bdl_coupling_init(&k, &def, g);
    CHECK(bdl_coupling_locate(&k, g, p) == BDL_OK);
    bdl_coupling_voidage(&k, g, p);
    double solid = 0.0, volume = 0.0, vc = 8e-9;
    for (int kk = 0; kk < 10; ++kk)
        for (int j = 0; j < 6; ++j)
            for (int i = 0; i < 8; ++i)
                solid += (1.0 - g->eps[bdl_grid_index(&g->grid, i, j, kk)]) * vc;
    for (long i = 0; i < p->count; ++i)
        volume += 4.0 / 3.0 * BDL_PI * pow(p->radius[i], 3);
    CHECK_CLOSE(solid, volume, 1e-12);
    memcpy(g->eps_old, g->eps, (size_t)g->grid.size * sizeof(double));
    // A stirred gas: random face velocities, then a few steps with the particles' drag.
    unsigned seed = 5;
    for (int a = 0; a < 3; ++a)
        for (long i = 0; i < g->grid.size; ++i)
            g->u[a][i] = uniform(&seed, -0.3, 0.3);
    double worst = 0.0;
    const double dt = 2e-4;
    for (int step = 0; step < 5; ++step) {
        bdl_coupling_drag_setup(&k, g, p, c.acc, NULL, dt);
        CHECK(bdl_gas_step(g, dt) == BDL_OK);
        bdl_vec3 *drag = malloc((size_t)p->count * sizeof(bdl_vec3));
        double sum[3] = {0, 0, 0}, gas[3], scale = 0.0;
        bdl_coupling_forces(&k, g, p, c.acc, dt, drag, NULL);
        for (long i = 0; i < p->count; ++i)
            for (int a = 0; a < 3; ++a) {
                sum[a] += bdl_v3_comp(drag[i], a);
                scale += fabs(bdl_v3_comp(drag[i], a));
            }
        bdl_coupling_gas_drag(g, g->u, gas);
        for (int a = 0; a < 3; ++a)
            worst = fmax(worst, fabs(sum[a] + gas[a]) / scale);
        free(drag);
    }
    printf("kernel %.1f cells, periodic x %d: deposited volume exact; drag on particles + drag on "
           "gas = %.1e of the total |drag|\n",
           width_cells, periodic_x, worst);
    CHECK_MSG(worst < 1e-12, "momentum exchange does not balance: %g", worst);
    bdl_coupling_free(&k);
    free_cloud(&c);
    bdl_gas_destroy(g);
}

static void test_linear_interpolation(void)
{
    bdl_gas *g = make_gas(10, 10, 10, 1e-3, 1, 0);
    bdl_coupling_def def = bdl_default_coupling_def(&g->grid);
    def.drag = BDL_DRAG_STOKES;
    def.kernel_width = 1e-3;
    bdl_coupling k;
    bdl_coupling_init(&k, &def, g);
    double *f = bdl_grid_alloc(&g->grid);
    for (int kk = 0; kk < 10; ++kk)
        for (int j = 0; j < 10; ++j)
            for (int i = 0; i < 10; ++i)
                f[bdl_grid_index(&g->grid, i, j, kk)] = 1.0 + 2.0 * (j + 0.5) - 0.5 * (kk + 0.5);
    bdl_particles p = {0};
    bdl_particles_add(&p, bdl_v3(0.0044, 0.0031, 0.0067), bdl_v3_zero(), 1e-4, 2500.0, 0);
    CHECK(bdl_coupling_locate(&k, g, &p) == BDL_OK);
    CHECK_CLOSE(bdl_coupling_interpolate(&k, 0, f), 1.0 + 2.0 * 3.1 - 0.5 * 6.7, 1e-12);
    bdl_particles_free(&p);
    free(f);
    bdl_coupling_free(&k);
    bdl_gas_destroy(g);
}

/// One sphere settling through gas in a periodic box (cells of 4 d; see bdl_verify_terminal_slip).
static void test_terminal(double d, double rho_p, bdl_drag_law law)
{
    bdl_verify_terminal t = bdl_verify_terminal_slip(d, rho_p, law, 6);
    printf("%s, d %.0f um, rho_p %.0f: Re %.3g, terminal slip %.5g m/s, drag law %.5g m/s "
           "(%+.3f %%), gas at the particle %.3g m/s\n",
           bdl_drag_law_names[law], d * 1e6, rho_p, t.re, t.slip, t.expected,
           100.0 * (t.slip / t.expected - 1.0), t.gas_speed);
    CHECK_MSG(fabs(t.slip / t.expected - 1.0) < 0.01, "terminal slip %g vs %g", t.slip, t.expected);
}

/// A coupled step sequence on 1 and 2 threads: the same bits in the gas and the forces.
static void test_threads(void)
{
    double *u1 = NULL;
    bdl_vec3 *f1 = NULL;
    long size = 0;
    for (int threads = 1; threads <= 2; ++threads) {
        omp_set_num_threads(threads);
        bdl_gas *g = make_gas(8, 6, 10, 2e-3, 1, 1);
        cloud c = make_cloud(300, g, 3);
        bdl_particles *p = &c.p;
        bdl_coupling_def def = bdl_default_coupling_def(&g->grid);
        def.drag = BDL_DRAG_BEETSTRA;
        def.kernel_width = 3e-3;
        bdl_coupling k;
        bdl_coupling_init(&k, &def, g);
        k.parallel_min = 0; // the parallel loops, even for these few particles
        bdl_vec3 *f = malloc((size_t)p->count * sizeof(bdl_vec3));
        for (int step = 0; step < 5; ++step) {
            bdl_coupling_locate(&k, g, p);
            bdl_coupling_voidage(&k, g, p);
            if (step == 0)
                memcpy(g->eps_old, g->eps, (size_t)g->grid.size * sizeof(double));
            bdl_coupling_drag_setup(&k, g, p, c.acc, NULL, 1e-4);
            CHECK(bdl_gas_step(g, 1e-4) == BDL_OK);
            bdl_coupling_forces(&k, g, p, c.acc, 1e-4, f, NULL);
            for (long i = 0; i < p->count; ++i)
                p->pos[i] = bdl_v3_madd(p->pos[i], p->vel[i], 1e-4);
        }
        size = g->grid.size;
        if (threads == 1) {
            u1 = malloc((size_t)size * sizeof(double));
            memcpy(u1, g->u[2], (size_t)size * sizeof(double));
            f1 = f;
        } else {
            CHECK(memcmp(u1, g->u[2], (size_t)size * sizeof(double)) == 0);
            CHECK(memcmp(f1, f, (size_t)p->count * sizeof(bdl_vec3)) == 0);
            free(f);
        }
        bdl_coupling_free(&k);
        free_cloud(&c);
        bdl_gas_destroy(g);
    }
    free(u1);
    free(f1);
    omp_set_num_threads(1);
}

/// Pressure differences across the faces of axis a, as the particles' share of them: the sum
/// over the faces with a momentum equation of (1 - eps_f) times the dynamic part of the
/// difference, (p_hi - p_lo - rho g_a h) A; at an outlet on the high side, the part of that face
/// inside the domain: half the top layer's solids times the difference to the outlet plane,
/// 2 (p_out - p) - rho g_a h.
static double solid_share(const bdl_gas *g, int a)
{
    const bdl_grid *gr = &g->grid;
    const long s = gr->stride[a];
    const double h = gr->h[a], area = gr->h[0] * gr->h[1] * gr->h[2] / h;
    const double hydro = g->def.density * g->def.gravity[a];
    double sum = 0.0;
    bdl_grid_wrap_cells(gr, g->eps);
    for (int k = 0; k < gr->n[2]; ++k)
        for (int j = 0; j < gr->n[1]; ++j)
            for (int i = 0; i < gr->n[0]; ++i) {
                const int m = a == 0 ? i : a == 1 ? j : k;
                if (m == 0 && !gr->periodic[a])
                    continue; // a wall or inlet face: no momentum equation
                const long idx = bdl_grid_index(gr, i, j, k);
                const double solid = 1.0 - 0.5 * (g->eps[idx] + g->eps[idx - s]);
                sum += solid * (g->p[idx] - g->p[idx - s] - hydro * h) * area;
                if (m == gr->n[a] - 1 && g->def.side[2 * a + 1].type == BDL_SIDE_OUTLET)
                    sum += 0.5 * (1.0 - g->eps[idx]) *
                           (2.0 * (g->def.side[2 * a + 1].pressure - g->p[idx]) - hydro * h) * area;
            }
    return sum;
}

/// The particles take from the pressure what the gas leaves: summed over all particles, the
/// pressure force is the buoyancy -rho g V_s minus the particles' share (1 - eps_f) of the
/// dynamic pressure difference on every interior or periodic face (half the outlet face's, the
/// part inside the domain), so that with the gas's share eps_f the mixture's pressure force
/// telescopes to the end layers' pressures (the particle momentum balance of a bed on its inlet,
/// bedlam verify bed_balance). Any pressure field; particles next to walls, on the inlet and the
/// outlet layer, across the periodic axis. And in a fluid at rest (hydrostatic pressure, the
/// outlet's pressure with it) every particle, in the boundary layers too, feels exactly its
/// buoyancy.
static void test_pressure_shares(void)
{
    bdl_gas *g = make_gas(6, 5, 10, 2e-3, 1, 1);
    g->def.side[4].type = BDL_SIDE_INLET;
    g->def.density = 1000.0; // a liquid: buoyancy well above round-off
    bdl_gas_set_gravity(g, (double[3]){0.0, 0.0, -9.81});
    unsigned seed = 5;
    bdl_particles p = {0};
    for (int i = 0; i < 300; ++i) // in every layer, the outlet's too
        bdl_particles_add(&p,
                          bdl_v3(uniform(&seed, 0.0, 12e-3), uniform(&seed, 0.0, 10e-3),
                                 uniform(&seed, 0.0, 20e-3)),
                          bdl_v3_zero(), uniform(&seed, 0.2e-3, 0.5e-3), 2500.0, 0);
    bdl_coupling_def def = bdl_default_coupling_def(&g->grid);
    bdl_coupling k;
    bdl_coupling_init(&k, &def, g);
    CHECK(bdl_coupling_locate(&k, g, &p) == BDL_OK);
    bdl_coupling_voidage(&k, g, &p);
    bdl_vec3 *f = malloc((size_t)p.count * sizeof(bdl_vec3));
    double volume = 0.0;
    for (long i = 0; i < p.count; ++i)
        volume += bdl_particle_volume(&p, i);
    for (int field = 0; field < 2; ++field) { // random, then hydrostatic
        const bdl_grid *gr = &g->grid;
        for (int kk = 0; kk < gr->n[2]; ++kk)
            for (int j = 0; j < gr->n[1]; ++j)
                for (int i = 0; i < gr->n[0]; ++i)
                    g->p[bdl_grid_index(gr, i, j, kk)] =
                        field == 0 ? uniform(&seed, -50.0, 50.0)
                                   : 1e5 - 1000.0 * 9.81 * (kk + 0.5) * gr->h[2];
        g->def.side[5].pressure = field == 0 ? 7.0 : 1e5 - 1000.0 * 9.81 * 20e-3;
        bdl_grid_wrap_cells(gr, g->p); // the periodic ghosts, as the gas step leaves them
        bdl_coupling_forces(&k, g, &p, NULL, 1e-4, NULL, f);
        double total[3] = {0, 0, 0}, worst = 0.0;
        for (long i = 0; i < p.count; ++i) {
            total[0] += f[i].x, total[1] += f[i].y, total[2] += f[i].z;
            const double buoyancy = 1000.0 * 9.81 * bdl_particle_volume(&p, i);
            worst = fmax(worst, fabs(f[i].z - buoyancy) / buoyancy + fabs(f[i].x) / buoyancy +
                                    fabs(f[i].y) / buoyancy);
        }
        const double share[3] = {-solid_share(g, 0), -solid_share(g, 1),
                                 1000.0 * 9.81 * volume - solid_share(g, 2)};
        const double scale = 1000.0 * 9.81 * volume + fabs(share[2]);
        for (int a = 0; a < 3; ++a)
            CHECK_MSG(fabs(total[a] - share[a]) < 1e-12 * scale,
                      "pressure field %d, axis %d: particles %.15g N, their share %.15g N", field,
                      a, total[a], share[a]);
        if (field == 1)
            CHECK_MSG(worst < 1e-10, "hydrostatic: worst relative buoyancy error %g", worst);
    }
    free(f);
    bdl_coupling_free(&k);
    bdl_particles_free(&p);
    bdl_gas_destroy(g);
}

/// Drag on each particle of a cloud in a stirred gas after one step, by the solids velocity of
/// `mean_drag`; the gas's drag in gas_total. Particles 400 and 401 share a place and a size
/// but move differently.
static void cloud_drag(int mean_drag, int same_motion, bdl_vec3 *drag, double gas_total[3])
{
    bdl_gas *g = make_gas(8, 6, 10, 2e-3, 1, 1);
    cloud c = make_cloud(402, g, 11);
    c.p.pos[401] = c.p.pos[400];
    c.p.radius[401] = c.p.radius[400];
    c.p.inv_mass[401] = c.p.inv_mass[400];
    c.p.vel[401] = bdl_v3(0.4, -0.2, 0.1);
    if (same_motion)
        for (long i = 0; i < c.p.count; ++i)
            c.p.vel[i] = bdl_v3(0.1, 0.0, -0.2), c.acc[i] = bdl_v3(0.0, 0.0, -9.81);
    bdl_coupling_def def = bdl_default_coupling_def(&g->grid);
    def.mean_drag = mean_drag;
    bdl_coupling k;
    CHECK(bdl_coupling_init(&k, &def, g) == BDL_OK);
    CHECK(bdl_coupling_locate(&k, g, &c.p) == BDL_OK);
    bdl_coupling_voidage(&k, g, &c.p);
    memcpy(g->eps_old, g->eps, (size_t)g->grid.size * sizeof(double));
    unsigned seed = 5;
    for (int a = 0; a < 3; ++a)
        for (long i = 0; i < g->grid.size; ++i)
            g->u[a][i] = uniform(&seed, -0.3, 0.3);
    const double dt = 2e-4;
    bdl_coupling_drag_setup(&k, g, &c.p, c.acc, NULL, dt);
    CHECK(bdl_gas_step(g, dt) == BDL_OK);
    bdl_coupling_forces(&k, g, &c.p, c.acc, dt, drag, NULL);
    bdl_coupling_gas_drag(g, g->u, gas_total);
    bdl_coupling_free(&k);
    free_cloud(&c);
    bdl_gas_destroy(g);
}

/// Sun's "averaged" drag (drag_velocity = mean): the gas feels what the particles feel, in sum;
/// two particles at one place and of one size feel the same drag however they move (with their
/// own velocities they do not); and when every particle moves alike it is the drag of their own
/// velocities.
static void test_mean_drag(void)
{
    bdl_vec3 own[402], mean[402];
    double gas[3], sum[3] = {0, 0, 0}, scale = 0.0;
    cloud_drag(1, 0, mean, gas);
    for (long i = 0; i < 402; ++i)
        for (int a = 0; a < 3; ++a) {
            sum[a] += bdl_v3_comp(mean[i], a);
            scale += fabs(bdl_v3_comp(mean[i], a));
        }
    double worst = 0.0;
    for (int a = 0; a < 3; ++a)
        worst = fmax(worst, fabs(sum[a] + gas[a]) / scale);
    CHECK_MSG(worst < 1e-12, "mean drag: momentum exchange does not balance: %g", worst);
    const double pair = bdl_v3_len(bdl_v3_sub(mean[400], mean[401])) / bdl_v3_len(mean[400]);
    cloud_drag(0, 0, own, gas);
    const double apart = bdl_v3_len(bdl_v3_sub(own[400], own[401])) / bdl_v3_len(own[400]);
    CHECK(pair < 1e-12);
    CHECK(apart > 0.1);
    cloud_drag(1, 1, mean, gas);
    cloud_drag(0, 1, own, gas);
    double alike = 0.0;
    for (long i = 0; i < 402; ++i)
        alike = fmax(alike, bdl_v3_len(bdl_v3_sub(mean[i], own[i])) / bdl_v3_len(own[i]));
    printf("mean drag: balance %.1e; two particles at one place %.1e apart (own velocities "
           "%.2f); all alike: %.1e from the particles' own\n",
           worst, pair, apart, alike);
    CHECK(alike < 1e-12);
}

int main(void)
{
    test_threads();
    test_mean_drag();
    test_linear_interpolation();
    test_pressure_shares();
    test_conservation_and_balance(0, 1.0);
    test_conservation_and_balance(1, 2.5);
    test_terminal(40e-6, 1000.0, BDL_DRAG_SCHILLER_NAUMANN);  // Re about 0.1
    test_terminal(200e-6, 2500.0, BDL_DRAG_SCHILLER_NAUMANN); // Re about 10
    test_terminal(1.0e-3, 2500.0, BDL_DRAG_SCHILLER_NAUMANN); // Re about 500
    test_terminal(200e-6, 2500.0, BDL_DRAG_WEN_YU);
    return bdl_test_summary("test_coupling");
}
