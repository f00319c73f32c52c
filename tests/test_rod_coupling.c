// Rods in a gas (couple/coupling.h): a rod's volume on the grid through its satellite points,
// conserved to round-off and moving smoothly as the rod sweeps across cell faces at any angle;
// the drag the gas feels equal and opposite to the drag on the rods for the rod laws; and the
// drag of a single rod in a uniform stream depending on its angle as the single-particle law says.
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "core/vec3.h"
#include "couple/coupling.h"
#include "scene_util.h"
#include "world/world.h"

#define H 8.33e-3 ///< cell size [m]: the thesis's small bed (0.1 m / 12)

static double uniform(unsigned *state, double lo, double hi)
{
    *state = *state * 1664525u + 1013904223u;
    return lo + (hi - lo) * (*state >> 8) / 16777216.0;
}

static bdl_gas *make_gas(int n0, int n1, int n2)
{
    bdl_gas_def d = bdl_default_gas_def();
    d.n[0] = n0, d.n[1] = n1, d.n[2] = n2;
    d.hi[0] = n0 * H, d.hi[1] = n1 * H, d.hi[2] = n2 * H;
    for (int s = 0; s < 6; ++s)
        d.side[s].type = BDL_SIDE_WALL;
    d.side[5].type = BDL_SIDE_OUTLET;
    d.tolerance = 1e-12;
    bdl_gas *g = NULL;
    bdl_gas_create(&d, &g);
    return g;
}

/// The solids volume on the grid, sum of (1 - eps) V_c [m^3].
static double grid_solids(const bdl_gas *g, double *cells)
{
    const double vc = g->grid.h[0] * g->grid.h[1] * g->grid.h[2];
    double sum = 0.0;
    long c = 0;
    for (int k = 0; k < g->grid.n[2]; ++k)
        for (int j = 0; j < g->grid.n[1]; ++j)
            for (int i = 0; i < g->grid.n[0]; ++i, ++c) {
                const double v = (1.0 - g->eps[bdl_grid_index(&g->grid, i, j, k)]) * vc;
                if (cells)
                    cells[c] = v;
                sum += v;
            }
    return sum;
}

/// The small rods of the thesis (6 x 1.5 mm) swept over two cells along a tilted line at several
/// orientations: the volume on the grid equals the rod's at every position, and no cell's share
/// jumps: the largest change per step is bounded by the kernel's slope.
static void test_sweep(void)
{
    bdl_gas *g = make_gas(6, 6, 6);
    bdl_coupling k;
    bdl_coupling_def def = bdl_default_coupling_def(&g->grid);
    bdl_coupling_init(&k, &def, g);
    const long ncell = 6 * 6 * 6;
    double *before = malloc(ncell * sizeof(double)), *now = malloc(ncell * sizeof(double));
    const double tilts[5] = {0.0, 0.3, 0.7851, 1.2, 1.5708};
    double worst_volume = 0.0, worst_jump = 0.0;
    const int steps = 400;
    const double travel = 2.0 * H, dx = travel / steps;
    for (int t = 0; t < 5; ++t) {
        bdl_particles p = {.rods = 1};
        const bdl_quat q = bdl_q_normalize(bdl_q_mul(bdl_q_axis_angle(bdl_v3(0, 0, 1), 0.4 * t),
                                                     bdl_q_axis_angle(bdl_v3(1, 0, 0), tilts[t])));
        bdl_particles_add_rod(&p, bdl_v3(2.1 * H, 2.3 * H, 2.2 * H), bdl_v3_zero(), 0.75e-3,
                              2.25e-3, q, 1395.0, 0);
        const double volume = bdl_particle_volume(&p, 0);
        for (int s = 0; s <= steps; ++s) {
            p.pos[0] = bdl_v3(2.1 * H + dx * s, 2.3 * H + 0.7 * dx * s, 2.2 * H + 0.4 * dx * s);
            CHECK(bdl_coupling_locate(&k, g, &p) == BDL_OK);
            bdl_coupling_voidage(&k, g, &p);
            const double on_grid = grid_solids(g, now);
            worst_volume = fmax(worst_volume, fabs(on_grid - volume) / volume);
            if (s > 0)
                for (long c = 0; c < ncell; ++c)
                    worst_jump = fmax(worst_jump, fabs(now[c] - before[c]) / volume);
            memcpy(before, now, ncell * sizeof(double));
        }
        bdl_particles_free(&p);
    }
    // Each tent weight moves by at most |dx_a| / w per step along each axis (w = 1.5 cells); a
    // cell's product of three weights by at most their sum, so a share by < 3 |dx| / w.
    const double bound = 3.0 * dx / (1.5 * H);
    printf("rod sweeping across faces: volume on the grid %.1e relative; largest change of a "
           "cell's share per step %.2e of the rod (bound %.2e, step %.3f cells)\n",
           worst_volume, worst_jump, bound, dx / H);
    CHECK_MSG(worst_volume < 1e-12, "volume not conserved: %g", worst_volume);
    CHECK_MSG(worst_jump < bound, "a cell's share jumps: %g > %g", worst_jump, bound);
    bdl_coupling_free(&k);
    bdl_gas_destroy(g);
    free(before);
    free(now);
}

/// Random rods (and a few spheres) in a stirred gas: the drag on the gas is minus the drag on the
/// particles, for each rod law.
static void test_balance(void)
{
    static const bdl_drag_law laws[3] = {BDL_DRAG_HDF, BDL_DRAG_STE, BDL_DRAG_STA};
    for (int l = 0; l < 3; ++l) {
        bdl_gas *g = make_gas(6, 4, 10);
        bdl_particles p = {.rods = 1};
        unsigned seed = 7;
        bdl_vec3 *acc = malloc(300 * sizeof(bdl_vec3));
        for (long i = 0; i < 300; ++i) {
            const bdl_vec3 x = bdl_v3(uniform(&seed, 0, 6 * H), uniform(&seed, 0, 4 * H),
                                      uniform(&seed, 0, 10 * H));
            const bdl_vec3 v = bdl_v3(uniform(&seed, -0.5, 0.5), uniform(&seed, -0.5, 0.5),
                                      uniform(&seed, -0.5, 0.5));
            const bdl_quat q =
                bdl_q_normalize((bdl_quat){uniform(&seed, -1, 1), uniform(&seed, -1, 1),
                                           uniform(&seed, -1, 1), uniform(&seed, -1, 1)});
            if (i % 10 == 9)
                bdl_particles_add_rod(&p, x, v, 1e-3, 0.0, q, 2500.0, 1);
            else
                bdl_particles_add_rod(&p, x, v, 0.75e-3, 2.25e-3, q, 1395.0, 0);
            acc[i] = bdl_v3(uniform(&seed, -10, 10), uniform(&seed, -10, 10), -9.81);
        }
        bdl_coupling_def def = bdl_default_coupling_def(&g->grid);
        def.drag = laws[l];
        bdl_coupling k;
        bdl_coupling_init(&k, &def, g);
        CHECK(bdl_coupling_locate(&k, g, &p) == BDL_OK);
        bdl_coupling_voidage(&k, g, &p);
        memcpy(g->eps_old, g->eps, (size_t)g->grid.size * sizeof(double));
        for (int a = 0; a < 3; ++a)
            for (long i = 0; i < g->grid.size; ++i)
                g->u[a][i] = uniform(&seed, -0.3, 0.3);
        double worst = 0.0;
        const double dt = 2e-4;
        bdl_vec3 *drag = malloc(300 * sizeof(bdl_vec3));
        for (int step = 0; step < 4; ++step) {
            bdl_coupling_drag_setup(&k, g, &p, acc, NULL, dt);
            CHECK(bdl_gas_step(g, dt) == BDL_OK);
            bdl_coupling_forces(&k, g, &p, acc, dt, drag, NULL);
            double sum[3] = {0, 0, 0}, gas[3], scale = 0.0;
            for (long i = 0; i < p.count; ++i)
                for (int a = 0; a < 3; ++a) {
                    sum[a] += bdl_v3_comp(drag[i], a);
                    scale += fabs(bdl_v3_comp(drag[i], a));
                }
            bdl_coupling_gas_drag(g, g->u, gas);
            for (int a = 0; a < 3; ++a)
                worst = fmax(worst, fabs(sum[a] + gas[a]) / scale);
        }
        printf("%s, 270 rods and 30 spheres: drag on particles + drag on gas = %.1e of the "
               "total |drag|\n",
               bdl_drag_law_names[laws[l]], worst);
        CHECK_MSG(worst < 1e-12, "momentum exchange does not balance: %g", worst);
        free(drag);
        free(acc);
        bdl_coupling_free(&k);
        bdl_particles_free(&p);
        bdl_gas_destroy(g);
    }
}

/// One rod at rest in a uniform upward stream (U = 0.8 m/s): the drag along the stream is
/// K(eps, theta) V_p U for the rod's angle to the stream, with the voidage at the rod.
static void test_single_rod(void)
{
    bdl_gas *g = make_gas(5, 5, 5);
    for (int a = 0; a < 3; ++a)
        for (long i = 0; i < g->grid.size; ++i)
            g->u[a][i] = a == 2 ? 0.8 : 0.0;
    bdl_coupling_def def = bdl_default_coupling_def(&g->grid);
    def.drag = BDL_DRAG_HDF;
    bdl_coupling k;
    bdl_coupling_init(&k, &def, g);
    const double rho = g->def.density, mu = g->def.viscosity;
    double f_along = 0.0, f_across = 0.0;
    for (int t = 0; t < 2; ++t) {
        bdl_particles p = {.rods = 1};
        const bdl_quat q = bdl_q_axis_angle(bdl_v3(1, 0, 0), t ? 0.5 * BDL_PI : 0.0);
        bdl_particles_add_rod(&p, bdl_v3(2.5 * H, 2.5 * H, 2.5 * H), bdl_v3_zero(), 0.75e-3,
                              2.25e-3, q, 1395.0, 0);
        CHECK(bdl_coupling_locate(&k, g, &p) == BDL_OK);
        bdl_coupling_voidage(&k, g, &p);
        const double eps = bdl_coupling_interpolate(&k, 0, g->eps);
        bdl_coupling_drag_setup(&k, g, &p, NULL, NULL, 1e-12);
        bdl_vec3 drag;
        bdl_coupling_forces(&k, g, &p, NULL, 1e-12, &drag, NULL);
        const bdl_drag_shape s = {.diameter = 1.5e-3, .shaft = 4.5e-3, .cos_theta = t ? 0.0 : 1.0};
        const double expected =
            bdl_drag_shape_per_volume(BDL_DRAG_HDF, NULL, eps, &s, 0.8, rho, mu) *
            bdl_particle_volume(&p, 0) * 0.8;
        CHECK_CLOSE(drag.z, expected, 1e-9);
        CHECK(fabs(drag.x) < 1e-12 * expected && fabs(drag.y) < 1e-12 * expected);
        *(t ? &f_across : &f_along) = drag.z;
        bdl_particles_free(&p);
    }
    printf("single rod at 0.8 m/s: drag along the stream %.4e N, across it %.4e N (ratio %.3f)\n",
           f_along, f_across, f_across / f_along);
    CHECK(f_across > 1.2 * f_along); // broadside meets more drag than end-on
    bdl_coupling_free(&k);
    bdl_gas_destroy(g);
}

/// The slip at which the drag of a horizontal rod (shaft 4.5 mm, 1.5 mm across) carries its
/// weight less buoyancy, by bisection [m/s].
static double implied_slip(bdl_drag_law law, double eps, double rho_p, double rho, double mu)
{
    const bdl_drag_shape s = {.diameter = 1.5e-3, .shaft = 4.5e-3, .cos_theta = 0.0};
    double lo = 0.0, hi = 20.0;
    for (int k = 0; k < 200; ++k) {
        const double mid = 0.5 * (lo + hi);
        const double a = bdl_drag_shape_per_volume(law, NULL, eps, &s, mid, rho, mu) * mid;
        *(a < (rho_p - rho) * 9.81 ? &lo : &hi) = mid;
    }
    return 0.5 * (lo + hi);
}

/// A rod lying flat in a column of air falls at the slip its drag law implies (relative to the gas
/// at the rod, which it drags along a little), through the whole chain: scene, coupling, gas and
/// the rods' integrator.
static void test_falling_rod(void)
{
    bdl_world *w = bdl_test_world(
        "[run]\nend_time = 1\ngravity = 0 0 -9.81\n[domain]\nmin = 0 0 0\nmax = 0.1 0.1 1.0\n"
        "[contact]\nlaw = linear\n"
        "[species rod]\nshape = rod\ndiameter = 1.5e-3\nlength = 6e-3\ndensity = 100\n"
        "stiffness = 6000\nrestitution = 0.43\n"
        "[create one]\ntype = lattice\nspecies = rod\ncount = 1\nregion_min = 0.04 0.04 0.9\n"
        "region_max = 0.06 0.06 0.92\n"
        "[gas]\ncells = 6 6 60\nzmax = outlet\ntolerance = 1e-10\n[coupling]\ndrag = hdf\n");
    CHECK(w != NULL);
    if (!w)
        return;
    bdl_particle_set_orient(&w->particles, 0, bdl_q_axis_angle(bdl_v3(1, 0, 0), 0.5 * BDL_PI));
    double t_end = 0.5, slip = 0.0;
    while (w->time < t_end && bdl_world_step(w) == BDL_OK)
        ;
    slip = bdl_coupling_gas_velocity(w->coupling, w->gas, 0).z - w->particles.vel[0].z;
    const double eps = bdl_coupling_interpolate(w->coupling, 0, w->gas->eps);
    const double expected = implied_slip(BDL_DRAG_HDF, eps, 100.0, 1.2, 1.8e-5);
    printf("flat rod falling in air (hdf): %.4f m/s after %.2f s, drag law %.4f m/s (%+.2f %%), "
           "still horizontal: axis z %.1e\n",
           slip, w->time, expected, 100.0 * (slip / expected - 1.0), w->particles.axis[0].z);
    CHECK(w->particles.pos[0].z > 0.2); // still falling freely, far above the floor
    CHECK_MSG(fabs(slip / expected - 1.0) < 0.01, "terminal %g vs %g", slip, expected);
    bdl_world_destroy(w);
}

/// Rods and a few spheres fluidized by an inlet, every loop parallel: the same bits on one and two
/// threads.
static void test_threads(void)
{
    uint64_t hash[2] = {0, 0};
    for (int t = 1; t <= 2; ++t) {
        omp_set_num_threads(t);
        bdl_world *w = bdl_test_world(
            "[run]\nend_time = 1\ngravity = 0 0 -9.81\n[domain]\nmin = 0 0 0\nmax = 0.03 0.012 "
            "0.1\n[contact]\nlaw = linear\n"
            "[species rod]\nshape = rod\ndiameter = 1.5e-3\nlength = 6e-3\ndensity = 1395\n"
            "stiffness = 6000\nrestitution = 0.43\nfriction = 0.46\n"
            "[species ball]\ndiameter = 2e-3\ndensity = 1395\nstiffness = 6000\n"
            "restitution = 0.43\nfriction = 0.46\n"
            "[wall box]\ntype = box\nmin = 0 0 0\nmax = 0.03 0.012 0.1\n"
            "[create rods]\ntype = random\nspecies = rod\ncount = 300\nregion_min = 0 0 0\n"
            "region_max = 0.03 0.012 0.06\n"
            "[create balls]\ntype = random\nspecies = ball\ncount = 30\nregion_min = 0 0 0\n"
            "region_max = 0.03 0.012 0.06\n"
            "[gas]\ncells = 4 2 12\nzmin = inlet\nzmax = outlet\ninlet_velocity = 1.5\n"
            "[coupling]\ndrag = sta\n");
        CHECK(w != NULL);
        if (!w)
            return;
        w->parallel_min = 1;
        w->coupling->parallel_min = 1;
        for (int s = 0; s < 3000 && bdl_world_step(w) == BDL_OK; ++s)
            ;
        hash[t - 1] = bdl_world_hash(w);
        printf("rods in gas, threads %d: t = %.4f s, hash %016llx\n", t, w->time,
               (unsigned long long)hash[t - 1]);
        bdl_world_destroy(w);
    }
    omp_set_num_threads(1);
    CHECK(hash[0] != 0);
    CHECK_MSG(hash[0] == hash[1], "rods in gas differ between 1 and 2 threads");
}

int main(void)
{
    test_sweep();
    test_balance();
    test_single_rod();
    test_falling_rod();
    test_threads();
    return bdl_test_summary("test_rod_coupling");
}
