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
    bdl_gas_def d = {0};
    d.n[0] = n0, d.n[1] = n1, d.n[2] = n2;
    d.hi[0] = n0 * h, d.hi[1] = n1 * h, d.hi[2] = n2 * h;
    d.density = 1.2;
    d.viscosity = 1.8e-5;
    for (int s = 0; s < 6; ++s)
        d.side[s].type = BDL_SIDE_WALL;
    if (periodic_x)
        d.side[0].type = d.side[1].type = BDL_SIDE_PERIODIC;
    if (outlet)
        d.side[5].type = BDL_SIDE_OUTLET;
    d.convection = BDL_CONVECTION_VANLEER;
    d.tolerance = 1e-12;
    bdl_gas *g = NULL;
    bdl_gas_create(&d, &g);
    return g;
}

typedef struct cloud {
    long n;
    double *pos, *vel, *acc, *radius, *density;
} cloud;

static cloud make_cloud(long n, const bdl_gas *g, unsigned seed)
{
    cloud c = {n, malloc(24 * n), malloc(24 * n), malloc(24 * n), malloc(8 * n), malloc(8 * n)};
    for (long i = 0; i < n; ++i) {
        for (int a = 0; a < 3; ++a) {
            double len = g->grid.n[a] * g->grid.h[a];
            c.pos[3 * i + a] = uniform(&seed, 0.0, len);
            c.vel[3 * i + a] = uniform(&seed, -0.5, 0.5);
            c.acc[3 * i + a] = uniform(&seed, -10.0, 10.0);
        }
        c.radius[i] = uniform(&seed, 0.2e-3, 0.5e-3);
        c.density[i] = 2500.0;
    }
    return c;
}

static void free_cloud(cloud *c)
{
    free(c->pos), free(c->vel), free(c->acc), free(c->radius), free(c->density);
}

static bdl_coupling_particles view(const cloud *c)
{
    return (bdl_coupling_particles){c->n, c->pos, c->vel, c->acc, c->radius, c->density};
}

static void test_conservation_and_balance(int periodic_x, double width_cells)
{
    bdl_gas *g = make_gas(8, 6, 10, 2e-3, periodic_x, 1);
    cloud c = make_cloud(400, g, 11);
    bdl_coupling_def def = {.drag = BDL_DRAG_GIDASPOW,
                            .drag_params = bdl_drag_default_params(),
                            .kernel_width = width_cells * 2e-3};
    bdl_coupling k;
    bdl_coupling_init(&k, &def, g);
    bdl_coupling_particles p = view(&c);
    CHECK(bdl_coupling_locate(&k, g, c.n, c.pos) == BDL_OK);
    bdl_coupling_voidage(&k, g, &p);
    double solid = 0.0, volume = 0.0, vc = 8e-9;
    for (int kk = 0; kk < 10; ++kk)
        for (int j = 0; j < 6; ++j)
            for (int i = 0; i < 8; ++i)
                solid += (1.0 - g->eps[bdl_grid_index(&g->grid, i, j, kk)]) * vc;
    for (long i = 0; i < c.n; ++i)
        volume += 4.0 / 3.0 * BDL_PI * pow(c.radius[i], 3);
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
        bdl_coupling_drag_setup(&k, g, &p, dt);
        CHECK(bdl_gas_step(g, dt) == BDL_OK);
        double *drag = malloc(24 * (size_t)c.n), sum[3] = {0, 0, 0}, gas[3], scale = 0.0;
        bdl_coupling_forces(&k, g, &p, dt, drag, NULL);
        for (long i = 0; i < c.n; ++i)
            for (int a = 0; a < 3; ++a) {
                sum[a] += drag[3 * i + a];
                scale += fabs(drag[3 * i + a]);
            }
        bdl_coupling_gas_drag(g, gas);
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
    bdl_coupling_def def = {.drag = BDL_DRAG_STOKES, .kernel_width = 1e-3};
    bdl_coupling k;
    bdl_coupling_init(&k, &def, g);
    double *f = bdl_grid_alloc(&g->grid);
    for (int kk = 0; kk < 10; ++kk)
        for (int j = 0; j < 10; ++j)
            for (int i = 0; i < 10; ++i)
                f[bdl_grid_index(&g->grid, i, j, kk)] = 1.0 + 2.0 * (j + 0.5) - 0.5 * (kk + 0.5);
    double pos[3] = {0.0044, 0.0031, 0.0067};
    CHECK(bdl_coupling_locate(&k, g, 1, pos) == BDL_OK);
    CHECK_CLOSE(bdl_coupling_interpolate(&k, 0, f), 1.0 + 2.0 * 3.1 - 0.5 * 6.7, 1e-12);
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
    double *u1 = NULL, *f1 = NULL;
    long size = 0;
    for (int threads = 1; threads <= 2; ++threads) {
        omp_set_num_threads(threads);
        bdl_gas *g = make_gas(8, 6, 10, 2e-3, 1, 1);
        cloud c = make_cloud(300, g, 3);
        bdl_coupling_def def = {.drag = BDL_DRAG_BEETSTRA, .kernel_width = 3e-3};
        bdl_coupling k;
        bdl_coupling_init(&k, &def, g);
        bdl_coupling_particles p = view(&c);
        double *f = malloc(24 * (size_t)c.n);
        for (int step = 0; step < 5; ++step) {
            bdl_coupling_locate(&k, g, c.n, c.pos);
            bdl_coupling_voidage(&k, g, &p);
            if (step == 0)
                memcpy(g->eps_old, g->eps, (size_t)g->grid.size * sizeof(double));
            bdl_coupling_drag_setup(&k, g, &p, 1e-4);
            CHECK(bdl_gas_step(g, 1e-4) == BDL_OK);
            bdl_coupling_forces(&k, g, &p, 1e-4, f, NULL);
            for (long i = 0; i < 3 * c.n; ++i)
                c.pos[i] += 1e-4 * c.vel[i];
        }
        size = g->grid.size;
        if (threads == 1) {
            u1 = malloc((size_t)size * sizeof(double));
            memcpy(u1, g->u[2], (size_t)size * sizeof(double));
            f1 = f;
        } else {
            CHECK(memcmp(u1, g->u[2], (size_t)size * sizeof(double)) == 0);
            CHECK(memcmp(f1, f, 24 * (size_t)c.n) == 0);
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

int main(void)
{
    test_threads();
    test_linear_interpolation();
    test_conservation_and_balance(0, 1.0);
    test_conservation_and_balance(1, 2.5);
    test_terminal(40e-6, 1000.0, BDL_DRAG_SCHILLER_NAUMANN);  // Re about 0.1
    test_terminal(200e-6, 2500.0, BDL_DRAG_SCHILLER_NAUMANN); // Re about 10
    test_terminal(1.0e-3, 2500.0, BDL_DRAG_SCHILLER_NAUMANN); // Re about 500
    test_terminal(200e-6, 2500.0, BDL_DRAG_WEN_YU);
    return bdl_test_summary("test_coupling");
}
