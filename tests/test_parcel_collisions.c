// Parcel collisions (model B of Patankar & Joseph 2001, src/parcels/collisions.h): the restitution
// of a head-on pair and of a parcel against a side, for the linear spring and the paper's
// delta^(3/2) law with the damping of eq. 18; the pair forces against a brute-force sum and their
// momentum; a parcel settled on the floor of a world under gravity; the step bound; the same
// state on one and two threads.
#include <omp.h>
#include <stdio.h>
#include <string.h>

#include "check.h"
#include "scene_util.h"
#include "core/rng.h"
#include "parcels/collisions.h"
#include "parcels/parcels.h"
#include "run/guards.h"

// The parcels of the jet bed (scenes/parcels_jet_bed.ini): 1000 beads of 500 um, 2500 kg/m^3.
#define BEAD_RADIUS  250e-6
#define BEAD_DENSITY 2500.0
#define BEADS        1000.0

static void parcel_store(bdl_particles *p)
{
    memset(p, 0, sizeof *p);
    p->parcels = 1;
}

static long add_parcel(bdl_particles *p, bdl_vec3 x, bdl_vec3 v)
{
    const long i = bdl_particles_add(p, x, v, BEAD_RADIUS, BEAD_DENSITY, 0);
    bdl_particle_set_parcel(p, i, BEADS);
    return i;
}

static bdl_parcel_box closed_box(double size)
{
    bdl_parcel_box box = {.lo = {0, 0, 0}, .hi = {size, size, size}};
    for (int s = 0; s < 6; ++s)
        box.solid[s] = 1;
    return box;
}

/// Model B's integration of the collision force alone (parcels.h, K = 1): x += h v, then
/// v += h F(x, v) / M, until no parcel touches anything after having touched. Returns the steps.
static long collide_alone(bdl_parcel_collisions *c, bdl_particles *p, double h, bdl_vec3 g)
{
    bdl_vec3 force[2];
    int touched = 0;
    for (long step = 1; step < 10000000; ++step) {
        for (long i = 0; i < p->count; ++i)
            p->pos[i] = bdl_v3_madd(p->pos[i], p->vel[i], h);
        bdl_parcel_contacts found;
        bdl_parcel_collisions_force(c, p, p->vel, NULL, force, &found);
        for (long i = 0; i < p->count; ++i)
            p->vel[i] = bdl_v3_madd(p->vel[i], bdl_v3_madd(g, force[i], p->inv_mass[i]), h);
        const int touching = found.pairs + found.walls > 0;
        touched |= touching;
        if (touched && !touching)
            return step;
    }
    return -1;
}

/// The restitution of mu x'' = -k x^m - eta x', x(0) = 0, x'(0) = v (until x returns to 0), by
/// RK4 with n steps per linear period: an independent reference for the pair and the wall.
static double reference_restitution(double mu, const bdl_parcel_collision_law *law, double v)
{
    const double h = 2e-4 * sqrt(mu / law->stiffness) * pow(fmax(v, 1e-3), -0.2);
    double x = 0.0, u = v;
#define ACC(X, U) (-(law->stiffness * pow(fmax(X, 0.0), law->exponent) + law->damping * (U)) / mu)
    for (long n = 0; n < 100000000; ++n) {
        const double k1x = u, k1u = ACC(x, u);
        const double k2x = u + 0.5 * h * k1u, k2u = ACC(x + 0.5 * h * k1x, u + 0.5 * h * k1u);
        const double k3x = u + 0.5 * h * k2u, k3u = ACC(x + 0.5 * h * k2x, u + 0.5 * h * k2u);
        const double k4x = u + h * k3u, k4u = ACC(x + h * k3x, u + h * k3u);
        const double xn = x + h / 6.0 * (k1x + 2 * k2x + 2 * k3x + k4x);
        const double un = u + h / 6.0 * (k1u + 2 * k2u + 2 * k3u + k4u);
        if (n > 0 && xn <= 0.0) // linear between the two: the speed where x crosses zero
            return -(u + (un - u) * x / (x - xn)) / v;
        x = xn;
        u = un;
    }
#undef ACC
    return NAN;
}

/// Two parcels meet head-on at relative speed v: their restitution, and the sum of their
/// momenta after it (they start with none).
static double pair_restitution(const bdl_parcel_collision_law *law, double v, double *momentum)
{
    bdl_particles p;
    parcel_store(&p);
    const double r = BEAD_RADIUS * cbrt(BEADS), gap = (1.0 + law->range) * 2.0 * r;
    add_parcel(&p, bdl_v3(0.05 - 0.5 * gap - 1e-6, 0.05, 0.05), bdl_v3(0.5 * v, 0, 0));
    add_parcel(&p, bdl_v3(0.05 + 0.5 * gap + 1e-6, 0.05, 0.05), bdl_v3(-0.5 * v, 0, 0));
    const bdl_parcel_box box = closed_box(0.1);
    bdl_parcel_collisions c;
    bdl_parcel_collisions_init(&c, law, &box);
    const double mass = 1.0 / p.inv_mass[0];
    collide_alone(&c, &p, 2e-3 * sqrt(mass / law->stiffness), bdl_v3_zero());
    const double e = (p.vel[1].x - p.vel[0].x) / v;
    *momentum = mass * (p.vel[0].x + p.vel[1].x);
    bdl_parcel_collisions_free(&c);
    bdl_particles_free(&p);
    return e;
}

/// A parcel meets the floor of a closed box at speed v: its restitution.
static double wall_restitution(const bdl_parcel_collision_law *law, double v)
{
    bdl_particles p;
    parcel_store(&p);
    const double r = BEAD_RADIUS * cbrt(BEADS);
    add_parcel(&p, bdl_v3(0.05, 0.05, r * (1.0 + 2.0 * law->range) + 1e-6), bdl_v3(0, 0, -v));
    const bdl_parcel_box box = closed_box(0.1);
    bdl_parcel_collisions c;
    bdl_parcel_collisions_init(&c, law, &box);
    collide_alone(&c, &p, 2e-3 * sqrt(1.0 / (p.inv_mass[0] * law->stiffness)), bdl_v3_zero());
    const double e = p.vel[0].z / v;
    bdl_parcel_collisions_free(&c);
    bdl_particles_free(&p);
    return e;
}

static void test_restitution(void)
{
    const double e = 0.9, mass = BEAD_DENSITY * 4.0 / 3.0 * BDL_PI * pow(BEAD_RADIUS, 3) * BEADS;
    bdl_parcels_def def = bdl_default_parcels_def();
    def.model = BDL_PARCEL_COLLISIONS;
    const double eta = bdl_parcels_collision_damping(&def, mass);
    CHECK_CLOSE(eta, 0.02426, 1e-3); // the digest's 0.0243 for Case A
    // Linear spring (m = 1): eq. 18 is exact against a side; a pair's relative motion has half the
    // mass, so its damping ratio is sqrt(2) times larger and e_pair = 0.862 rather than 0.9.
    bdl_parcel_collision_law linear = {
        .stiffness = 800, .exponent = 1, .damping = eta, .range = 0.075};
    const double zeta = eta / (2.0 * sqrt(0.5 * mass * 800.0));
    const double e_pair = exp(-BDL_PI * zeta / sqrt(1.0 - zeta * zeta));
    for (double v = 0.1; v < 2.0; v *= 4.0) {
        double momentum;
        const double ep = pair_restitution(&linear, v, &momentum);
        const double ew = wall_restitution(&linear, v);
        printf("linear spring, v = %.2f m/s: pair e = %.4f (linear theory %.4f, %+.1f%% from the "
               "e = %.2f the damping was built from), wall e = %.4f (%+.2f%%)\n",
               v, ep, e_pair, 100.0 * (ep / e - 1.0), e, ew, 100.0 * (ew / e - 1.0));
        CHECK_CLOSE(ep, e_pair, 5e-3);
        CHECK_CLOSE(ew, e, 5e-3);
        CHECK(fabs(momentum) <= 1e-14 * mass * v);
    }
    // The paper's law (m = 3/2) with the same eta: the restitution falls far below e and depends on
    // the impact speed (k_c = 800 N/m^1.5 is a much softer spring than 800 N/m at these overlaps,
    // so the contact lasts longer and the dashpot takes more). Checked against an RK4 reference.
    bdl_parcel_collision_law hertz = linear;
    hertz.exponent = 1.5;
    const double speeds[] = {0.1, 0.5, 1.0, 3.0};
    for (int k = 0; k < 4; ++k) {
        double momentum;
        const double ep = pair_restitution(&hertz, speeds[k], &momentum);
        const double ew = wall_restitution(&hertz, speeds[k]);
        const double rp = reference_restitution(0.5 * mass, &hertz, speeds[k]);
        const double rw = reference_restitution(mass, &hertz, speeds[k]);
        printf("delta^1.5, v = %.2f m/s: pair e = %.4f (reference %.4f), wall e = %.4f "
               "(reference %.4f); built from e = %.2f\n",
               speeds[k], ep, rp, ew, rw, e);
        CHECK_CLOSE(ep, rp, 5e-3);
        CHECK_CLOSE(ew, rw, 5e-3);
        CHECK(ep < 0.7 && ew < 0.8);
        CHECK(fabs(momentum) <= 1e-14 * mass * speeds[k]);
    }
}

/// The force on every parcel by brute force: every pair once, through the nearest image.
static void brute_force(const bdl_parcel_collisions *c, const bdl_particles *p, bdl_vec3 *f)
{
    const bdl_parcel_collision_law *law = &c->law;
    for (long i = 0; i < p->count; ++i) {
        f[i] = bdl_v3_zero();
        const double ri = bdl_parcel_sphere_radius(p, i);
        for (long j = 0; j < p->count; ++j) {
            if (j == i)
                continue;
            bdl_vec3 d = bdl_v3_sub(p->pos[i], p->pos[j]);
            for (int a = 0; a < 3; ++a) {
                const double L = c->box.hi[a] - c->box.lo[a], s = bdl_v3_comp(d, a);
                if (c->box.periodic[a])
                    bdl_v3_set_comp(&d, a, s - L * round(s / L));
            }
            const double reach = (1.0 + law->range) * (ri + bdl_parcel_sphere_radius(p, j));
            const double dist = bdl_v3_len(d);
            if (dist >= reach)
                continue;
            const bdl_vec3 n = bdl_v3_scale(d, 1.0 / dist);
            const double vn = bdl_v3_dot(bdl_v3_sub(p->vel[i], p->vel[j]), n);
            const double delta = reach - dist;
            f[i] = bdl_v3_madd(f[i], n, law->stiffness * pow(delta, 1.5) - law->damping * vn);
        }
        for (int a = 0; a < 3; ++a) {
            if (c->box.periodic[a])
                continue;
            const double x = bdl_v3_comp(p->pos[i], a), v = bdl_v3_comp(p->vel[i], a);
            const double reach = ri * (1.0 + 2.0 * law->range);
            const double lo = x - c->box.lo[a], hi = c->box.hi[a] - x;
            double fa = bdl_v3_comp(f[i], a);
            if (lo < reach)
                fa += law->stiffness * pow(reach - lo, 1.5) - law->damping * v;
            if (hi < reach)
                fa -= law->stiffness * pow(reach - hi, 1.5) + law->damping * v;
            bdl_v3_set_comp(&f[i], a, fa);
        }
    }
}

/// Random parcels, overlapping, in a box periodic along `periodic`: the cell list finds what the
/// brute force finds, and with no sides the forces sum to zero to round-off.
static void check_forces(const double size[3], const int periodic[3], long n, int threads)
{
    bdl_particles p;
    parcel_store(&p);
    bdl_rng rng;
    bdl_rng_seed(&rng, 11);
    bdl_parcel_box box = {.lo = {0, 0, 0}};
    for (int a = 0; a < 3; ++a) {
        box.hi[a] = size[a];
        box.periodic[a] = periodic[a];
        box.solid[2 * a] = box.solid[2 * a + 1] = !periodic[a];
    }
    for (long i = 0; i < n; ++i)
        add_parcel(&p,
                   bdl_v3(bdl_rng_range(&rng, 0, size[0]), bdl_rng_range(&rng, 0, size[1]),
                          bdl_rng_range(&rng, 0, size[2])),
                   bdl_v3_scale(bdl_rng_direction(&rng), bdl_rng_range(&rng, 0, 1)));
    const bdl_parcel_collision_law law = {
        .stiffness = 800, .exponent = 1.5, .damping = 0.0243, .range = 0.075};
    bdl_parcel_collisions c;
    bdl_parcel_collisions_init(&c, &law, &box);
    c.parallel_min = 1;
    bdl_vec3 *f = calloc((size_t)n, sizeof *f), *g = calloc((size_t)n, sizeof *g);
    omp_set_num_threads(threads);
    bdl_parcel_contacts found;
    CHECK(bdl_parcel_collisions_force(&c, &p, p.vel, NULL, f, &found) == BDL_OK);
    brute_force(&c, &p, g);
    double largest = 0.0, error = 0.0, scale = 0.0;
    bdl_vec3 sum = bdl_v3_zero();
    for (long i = 0; i < n; ++i) {
        largest = fmax(largest, bdl_v3_len(g[i]));
        error = fmax(error, bdl_v3_len(bdl_v3_sub(f[i], g[i])));
        sum = bdl_v3_add(sum, f[i]);
        scale += bdl_v3_len(f[i]);
    }
    printf("%ld parcels in %g x %g x %g m (periodic %d %d %d), %d thread(s): %ld pairs, %ld side "
           "contacts, cells %d x %d x %d; largest difference from brute force %.2g of the "
           "largest force; |sum of forces| %.2g of sum |F|\n",
           n, size[0], size[1], size[2], periodic[0], periodic[1], periodic[2], threads,
           found.pairs, found.walls, c.n[0], c.n[1], c.n[2], error / largest,
           bdl_v3_len(sum) / scale);
    CHECK(found.pairs > n / 4);
    CHECK(error <= 1e-12 * largest);
    if (periodic[0] && periodic[1] && periodic[2])
        CHECK(bdl_v3_len(sum) <= 1e-14 * scale);
    free(f);
    free(g);
    bdl_parcel_collisions_free(&c);
    bdl_particles_free(&p);
}

static void test_forces(void)
{
    const double cube[3] = {0.04, 0.04, 0.04}, slab[3] = {0.04, 0.012, 0.03};
    check_forces(cube, (const int[3]){1, 1, 1}, 400, 1);
    check_forces(cube, (const int[3]){1, 1, 1}, 400, 2);
    check_forces(slab, (const int[3]){1, 1, 0}, 150, 2); // two cells across y: the images meet
    check_forces(slab, (const int[3]){0, 0, 0}, 150, 1);
}

/// A closed box of still air with one parcel of the jet bed over the middle of the floor (where
/// the kernel's deposit is symmetric: off the middle, the gas pushes a parcel sideways by about
/// 1e-4 g on this coarse grid, and on the frictionless floor it slides).
static const char *const box_scene =
    "[run]\nend_time = 0.3\ndt = %g\ngravity = 0 0 -9.81\n"
    "[domain]\nmin = 0 0 0\nmax = 0.02 0.02 0.02\n"
    "[species glass]\ndiameter = 500e-6\ndensity = 2500\nparcel_particles = 1000\n"
    "[create one]\ntype = lattice\ncount = 1\nregion_min = 0.00975 0.00975 0.004\n"
    "region_max = 0.01475 0.01475 0.008\n"
    "[gas]\ndensity = 1.205\nviscosity = 1.8e-5\ncells = 2 2 2\n"
    "[coupling]\ndrag = patankar\n"
    "[parcels]\nmodel = collisions\nsubsteps = %d\n";

/// One parcel dropped on the floor settles where k_c delta^1.5 = M g (1 - rho_f / rho_p).
static void test_settle(void)
{
    bdl_world *w = bdl_test_world(box_scene, 2e-4, 1);
    while (w->time < 0.3)
        CHECK(bdl_world_step(w) == BDL_OK);
    const bdl_particles *p = &w->particles;
    const double r = bdl_parcel_sphere_radius(p, 0), mass = 1.0 / p->inv_mass[0];
    const double delta = r * (1.0 + 2.0 * 0.075) - p->pos[0].z;
    const double weight = mass * 9.81 * (1.0 - 1.205 / 2500.0);
    const double expected = pow(weight / 800.0, 2.0 / 3.0);
    printf("settled on the floor: overlap %.6g m, k_c delta^1.5 = M g' at %.6g m (%+.3g%%); "
           "speed %.2g m/s; %ld side contact(s)\n",
           delta, expected, 100.0 * (delta / expected - 1.0), bdl_v3_len(p->vel[0]),
           w->parcel_walls);
    CHECK_CLOSE(delta, expected, 1e-3);
    CHECK(bdl_v3_len(p->vel[0]) < 1e-5 && w->parcel_walls == 1);
    bdl_world_destroy(w);
}

/// The paper's bound dt / K < 2 sqrt(M / k_c) (9.04e-4 s for these parcels) refuses a long step;
/// substeps lift it.
static void test_step_bound(void)
{
    char message[1024], warning[256];
    bdl_world *w = bdl_test_world(box_scene, 1e-3, 1);
    const bdl_result r = bdl_guards_check_dt(w, message, sizeof message, warning, sizeof warning);
    printf("dt = 1e-3 s, K = 1: %s\n", r == BDL_OK ? "accepted" : message);
    CHECK(r == BDL_ERR_SCENE && strstr(message, "2 sqrt(M / k_c) = 0.000904"));
    CHECK_CLOSE(bdl_world_parcels_collision_dt(w), 2.0 * sqrt(1.636246e-4 / 800.0), 1e-5);
    bdl_world_destroy(w);
    w = bdl_test_world(box_scene, 1e-3, 2);
    CHECK(bdl_guards_check_dt(w, message, sizeof message, warning, sizeof warning) == BDL_OK);
    bdl_world_destroy(w);
}

/// A small jet bed: the state after a few hundred steps is the same on one and two threads.
static void test_determinism(int substeps)
{
    uint64_t hash[2];
    long pairs[2];
    for (int t = 1; t <= 2; ++t) {
        omp_set_num_threads(t);
        bdl_world *w = bdl_test_world(
            "[run]\nend_time = 1\ndt = 1e-4\ngravity = 0 0 -9.81\n"
            "[domain]\nmin = 0 0 0\nmax = 0.05 0.0275 0.1\n"
            "[species glass]\ndiameter = 500e-6\ndensity = 2500\nparcel_particles = 1000\n"
            "[create bed]\ntype = lattice\nspacing = 0.0054\nregion_min = 0.0005 0.0025 0.0025\n"
            "region_max = 0.0495 0.0255 0.06\nvelocity_jitter = 0.2\n"
            "[gas]\ndensity = 1.205\nviscosity = 1.8e-5\ncells = 5 5 10\nzmin = inlet\n"
            "zmax = outlet\ninlet_velocity = 0.3\njet_velocity = 5\njet_min = 0.02 0 0\n"
            "jet_max = 0.03 0.0275 0\n"
            "[coupling]\ndrag = patankar\n[parcels]\nmodel = collisions\nsubsteps = %d\n",
            substeps);
        w->parallel_min = 1;
        for (int s = 0; s < 300; ++s)
            CHECK(bdl_world_step(w) == BDL_OK);
        hash[t - 1] = bdl_world_hash(w);
        pairs[t - 1] = w->parcel_pairs;
        printf("jet bed of %ld parcels, K = %d, %d thread(s): %ld pairs touching, largest overlap "
               "%.3g R_ep, hash %016llx\n",
               w->particles.count, substeps, t, w->parcel_pairs, w->parcel_overlap,
               (unsigned long long)hash[t - 1]);
        bdl_world_destroy(w);
    }
    CHECK(pairs[0] > 100);
    CHECK_MSG(hash[0] == hash[1], "K = %d: the state differs between 1 and 2 threads", substeps);
}

int main(void)
{
    test_restitution();
    test_forces();
    test_settle();
    test_step_bound();
    test_determinism(1);
    test_determinism(3);
    return bdl_test_summary("test_parcel_collisions");
}
