// The shear cell's boundaries (docs/validation/rheology.md): Lees–Edwards images — separations
// and velocities across the z faces, the pair lists against a brute force at any slide of the
// images, a dilute gas carried on the shear profile through the faces (also in a medium that
// moves with the shear), an inelastic collision
// across a face against the restitution — and a repeating corrugated plate that carries a bead
// through the periodic x faces for ever.
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "check.h"
#include "core/rng.h"
#include "dem/neighbor.h"
#include "scene_util.h"
#include "world/world.h"

/// Separations and image velocities of a box 0.06 x 0.04 x 0.05 m slid by hand.
static void test_images(void)
{
    bdl_neighbor nb;
    const int periodic[3] = {1, 1, 1};
    CHECK(bdl_neighbor_init(&nb, bdl_v3(0, 0, 0), bdl_v3(0.06, 0.04, 0.05), periodic, 0.005, 0.0005,
                            100, 0, 0, 0, 0) == BDL_OK);
    bdl_neighbor_set_shear(&nb, 20.0, 0.02); // U = 1 m/s, travel 0.02 m
    CHECK_CLOSE(nb.shear_velocity, 1.0, 1e-15);
    CHECK_CLOSE(nb.shear_shift, 0.02, 1e-12);
    bdl_neighbor_set_shear(&nb, 20.0, 0.05); // travel 0.05 m: -0.01 m modulo 0.06
    CHECK_CLOSE(nb.shear_shift, -0.01, 1e-12);
    // i at the top, j at the bottom: j's image above sits at x_j + shift, z_j + 0.05.
    const bdl_vec3 xi = bdl_v3(0.030, 0.02, 0.049), xj = bdl_v3(0.038, 0.02, 0.001);
    bdl_vec3 d = bdl_neighbor_delta(&nb, xi, xj);
    CHECK_CLOSE(d.x, 0.030 - (0.038 - 0.01), 1e-12);
    CHECK_CLOSE(d.z, -0.002, 1e-12);
    CHECK_CLOSE(bdl_neighbor_image_velocity(&nb, xi, xj).x, 1.0, 1e-15);
    d = bdl_neighbor_delta(&nb, xj, xi); // and the other way round
    CHECK_CLOSE(d.x, 0.038 - (0.030 + 0.01), 1e-12);
    CHECK_CLOSE(d.z, 0.002, 1e-12);
    CHECK_CLOSE(bdl_neighbor_image_velocity(&nb, xj, xi).x, -1.0, 1e-15);
    // Inside the box nothing changes.
    d = bdl_neighbor_delta(&nb, bdl_v3(0.01, 0.01, 0.02), bdl_v3(0.013, 0.01, 0.024));
    CHECK_CLOSE(d.x, -0.003, 1e-12);
    CHECK(bdl_neighbor_image_velocity(&nb, bdl_v3(0, 0, 0.02), bdl_v3(0, 0, 0.024)).x == 0.0);
    bdl_neighbor_free(&nb);
}

/// Pairs closer than r_i + r_j + skin, by brute force over every pair.
static long brute_pairs(const bdl_neighbor *nb, const bdl_particles *p)
{
    long n = 0;
    for (long i = 0; i < p->count; ++i)
        for (long j = i + 1; j < p->count; ++j) {
            const double cut = p->radius[i] + p->radius[j] + nb->skin;
            n += bdl_v3_len2(bdl_neighbor_delta(nb, p->pos[i], p->pos[j])) < cut * cut;
        }
    return n;
}

/// Every listed pair is within reach, and the list holds as many pairs as the brute force finds,
/// at slides of the images that put the cells across the faces at every offset.
static void test_lists(void)
{
    bdl_world *w = bdl_test_world(
        "[run]\nend_time = 1\ngravity = 0 0 0\n[domain]\nmin = 0 0 0\nmax = 0.06 0.04 0.05\n"
        "periodic = x y z\nshear_rate = 20\n[contact]\nlaw = linear\n"
        "[species s]\ndiameter = 0.004\ndensity = 2500\nstiffness = 1e4\nrestitution = 0.9\n"
        "[create bed]\ntype = random\nspecies = s\ncount = 1000\nregion_min = 0 0 0\n"
        "region_max = 0.06 0.04 0.05\n");
    bdl_neighbor *nb = &w->neighbor;
    bdl_particles *p = &w->particles;
    for (long i = 0; i < p->count; ++i) // the fill's sides meet in the middle, not at the faces
        p->pos[i].z += 0.025;
    long listed_total = 0, across = 0;
    for (int k = 0; k < 13; ++k) {
        bdl_neighbor_set_shear(nb, 20.0, 0.0023 * k * k); // slides of 0 to 0.36 m
        CHECK(bdl_neighbor_build(nb, p, &w->walls, NULL) == BDL_OK);
        int ok = 1;
        for (long i = 0; i < p->count; ++i)
            for (int32_t q = nb->start[i]; q < nb->start[i + 1]; ++q) {
                const long j = nb->partner[q];
                const double cut = p->radius[i] + p->radius[j] + nb->skin;
                ok &= bdl_v3_len2(bdl_neighbor_delta(nb, p->pos[i], p->pos[j])) < cut * cut;
                across += fabs(p->pos[i].z - p->pos[j].z) > 0.025;
            }
        const long brute = brute_pairs(nb, p);
        CHECK_MSG(ok && nb->pair_count == brute, "slide %d: %ld listed, %ld by brute force", k,
                  nb->pair_count, brute);
        listed_total += nb->pair_count;
    }
    printf("lists: %ld pairs over 13 slides, %ld of them across the z faces\n", listed_total,
           across);
    CHECK(across > 100);
    bdl_world_destroy(w);
}

/// Beads too far apart to meet, started on the profile u_x = rate (z - middle) and rising at
/// 0.3 m/s, keep their x velocity but at each pass through the top face lose the images' speed:
/// v_x - rate (z - middle) = -rate 0.3 t for each of them, through the faces as between them.
static void test_profile(void)
{
    bdl_world *w = bdl_test_world(
        "[run]\nend_time = 1\ngravity = 0 0 0\n[domain]\nmin = 0 0 0\nmax = 0.06 0.04 0.05\n"
        "periodic = x y z\nshear_rate = 20\n[contact]\nlaw = linear\n"
        "[species s]\ndiameter = 0.001\ndensity = 2500\nstiffness = 10\nrestitution = 0.9\n"
        "[create bed]\ntype = lattice\nspecies = s\nspacing = 0.01\nregion_min = 0 0 0\n"
        "region_max = 0.06 0.04 0.05\nvelocity = 0 0 0.3\n");
    const double rate = 20.0, middle = 0.025;
    double worst = 0.0;
    long crossings = 0;
    for (int s = 0; s < 20000; ++s) {
        CHECK(bdl_world_step(w) == BDL_OK);
        const bdl_particles *p = &w->particles;
        for (long i = 0; i < p->count; ++i)
            worst = fmax(worst,
                         fabs(p->vel[i].x - rate * (p->pos[i].z - middle) + rate * 0.3 * w->time));
    }
    crossings = w->neighbor.builds;
    printf("profile: %ld beads, %ld list builds over %.3g s, worst |v_x - profile| %.3g m/s\n",
           w->particles.count, crossings, w->time, worst);
    CHECK(w->time * 0.3 > 0.05); // each bead went through the z faces at least once
    CHECK(worst < 1e-9);
    bdl_world_destroy(w);
}

/// The same gas in a medium that moves with the shear (background damping b = 5/s): the damping
/// acts on the velocity relative to the profile, so a bead keeps to u = v_x - rate (z - middle)
/// = -rate w0 t e^(-b t) (du/dt = -b u - rate v_z, v_z = w0 e^(-b t)) through the faces, where
/// damping of the lab velocity would pull every bead to rest.
static void test_profile_damped(void)
{
    bdl_world *w = bdl_test_world(
        "[run]\nend_time = 1\ngravity = 0 0 0\n[domain]\nmin = 0 0 0\nmax = 0.06 0.04 0.05\n"
        "periodic = x y z\nshear_rate = 20\n[contact]\nlaw = linear\n"
        "[species s]\ndiameter = 0.001\ndensity = 2500\nstiffness = 10\nrestitution = 0.9\n"
        "background_damping = 5\n[create bed]\ntype = lattice\nspecies = s\nspacing = 0.01\n"
        "region_min = 0 0 0\nregion_max = 0.06 0.04 0.05\nvelocity = 0 0 0.3\n");
    const double rate = 20.0, middle = 0.025, b = 5.0, w0 = 0.3;
    double worst_u = 0.0, worst_w = 0.0;
    const long steps = 60000;
    for (long s = 0; s < steps; ++s)
        CHECK(bdl_world_step(w) == BDL_OK);
    const double t = w->time, decay = exp(-b * t);
    const bdl_particles *p = &w->particles;
    for (long i = 0; i < p->count; ++i) {
        const double u = p->vel[i].x - rate * (p->pos[i].z - middle);
        worst_u = fmax(worst_u, fabs(u + rate * w0 * t * decay));
        worst_w = fmax(worst_w, fabs(p->vel[i].z - w0 * decay));
    }
    printf("damped profile: %ld beads over %.3g s, |u - exact| %.3g of %.3g m/s, |v_z - exact| "
           "%.3g of %.3g m/s\n",
           p->count, t, worst_u, rate * w0 * t * decay, worst_w, w0 * decay);
    CHECK(w0 * (1.0 - decay) / b > 0.05); // each bead went through the z faces at least once
    CHECK(worst_u < 1e-3 * rate * w0 * t * decay);
    CHECK(worst_w < 1e-3 * w0 * decay);
    bdl_world_destroy(w);
}

/// The outcome of an oblique collision: the normal at first touch, the normal relative velocity
/// after over before, the tangential one after over before, and the pair's lab momentum change.
typedef struct collision {
    bdl_vec3 normal;
    double normal_ratio, tangential_ratio, momentum_jumps, momentum_z;
} collision;

/// Two beads of 5 mm meet obliquely, the upper 2 mm ahead along x, approaching at 0.4 m/s along
/// z with no relative motion along x. Sheared: A rises below the top face of a Lees–Edwards box,
/// B sinks above its bottom face, and B's image above moves with A (the images' speed 1 m/s).
/// Else the same pair in a closed box at rest, B above A.
static collision collide(int sheared)
{
    bdl_world *w = bdl_test_world(
        "[run]\nend_time = 1\ngravity = 0 0 0\ndt = 1e-6\n[domain]\nmin = 0 0 0\n"
        "max = 0.06 0.04 0.05\n%s\n[contact]\nlaw = linear\n"
        "damping = closed_form\n[species s]\ndiameter = 0.005\ndensity = 2500\nstiffness = 1e5\n"
        "restitution = 0.5\n[create bed]\ntype = lattice\nspecies = s\ncount = 2\n"
        "spacing = 0.01\nregion_min = 0 0 0\nregion_max = 0.06 0.04 0.05\n",
        sheared ? "periodic = x y z\nshear_rate = 20" : "");
    bdl_particles *p = &w->particles;
    const double u = sheared ? 1.0 : 0.0; // the images' speed: 20/s x 0.05 m
    p->pos[0] = bdl_v3(0.030, 0.02, sheared ? 0.0465 : 0.0215);
    p->vel[0] = bdl_v3(0.5 * u, 0.0, 0.2);
    p->pos[1] = bdl_v3(0.028, 0.02, sheared ? 0.0015 : 0.0265);
    p->vel[1] = bdl_v3(-0.5 * u, 0.0, -0.2);
    const uint32_t id_a = p->id[0], id_b = p->id[1];
    CHECK(bdl_world_compute_forces(w) == BDL_OK);
    const double m = 1.0 / p->inv_mass[0];
    const bdl_vec3 momentum0 = bdl_v3_scale(bdl_v3_add(p->vel[0], p->vel[1]), m);
    collision c = {.normal = bdl_v3_zero()};
    int touched = 0;
    bdl_vec3 rel = bdl_v3_zero();
    for (int s = 0; s < 3000; ++s) {
        CHECK(bdl_world_step(w) == BDL_OK);
        const long a = bdl_test_find(w, id_a), b = bdl_test_find(w, id_b);
        const bdl_vec3 d = bdl_neighbor_delta(&w->neighbor, p->pos[b], p->pos[a]);
        if (bdl_v3_len(d) < 0.005 && !touched) {
            touched = 1;
            c.normal = bdl_v3_normalize(d);
        }
        // B (or its image) less A
        rel = bdl_v3_sub(
            bdl_v3_add(p->vel[b], bdl_neighbor_image_velocity(&w->neighbor, p->pos[a], p->pos[b])),
            p->vel[a]);
    }
    CHECK(touched);
    const bdl_vec3 v0 = bdl_v3(0.0, 0.0, -0.4), n = c.normal;
    const double vn0 = bdl_v3_dot(v0, n), vn1 = bdl_v3_dot(rel, n);
    c.normal_ratio = -vn1 / vn0;
    c.tangential_ratio =
        bdl_v3_len(bdl_v3_madd(rel, n, -vn1)) / bdl_v3_len(bdl_v3_madd(v0, n, -vn0));
    const bdl_vec3 momentum = bdl_v3_scale(bdl_v3_add(p->vel[0], p->vel[1]), m);
    c.momentum_jumps = sheared ? (momentum.x - momentum0.x) / (m * u) : momentum.x - momentum0.x;
    c.momentum_z = (momentum.z - momentum0.z) / m;
    bdl_world_destroy(w);
    return c;
}

/// The collision across a face comes out as the same collision in a closed box: the restitution
/// sees the relative velocity of the image, the geometry the image's slid place.
static void test_collision(void)
{
    const collision s = collide(1), r = collide(0);
    printf("collision across the face: normal (%.3f, %.3f, %.3f), v_n ratio %.5f, v_t ratio %.5f; "
           "in a closed box: normal (%.3f, %.3f, %.3f), %.5f, %.5f\n",
           s.normal.x, s.normal.y, s.normal.z, s.normal_ratio, s.tangential_ratio, r.normal.x,
           r.normal.y, r.normal.z, r.normal_ratio, r.tangential_ratio);
    CHECK(fabs(s.normal.x) > 0.3); // oblique
    CHECK(bdl_v3_len(bdl_v3_sub(s.normal, r.normal)) < 1e-6);
    CHECK_CLOSE(s.normal_ratio, r.normal_ratio, 1e-6);
    CHECK_CLOSE(s.tangential_ratio, r.tangential_ratio, 1e-6);
    CHECK_CLOSE(r.normal_ratio, 0.5, 0.15);     // the law's own (its force never pulls)
    CHECK_CLOSE(r.tangential_ratio, 1.0, 0.01); // frictionless
    // Lab momentum kept, unless a bead went through a face (then by m U exactly).
    CHECK(fabs(s.momentum_jumps - round(s.momentum_jumps)) < 1e-9 && fabs(s.momentum_z) < 1e-12);
    CHECK(fabs(r.momentum_jumps) < 1e-12 && fabs(r.momentum_z) < 1e-12);
}

/// A bead in a dimple of the corrugated plate, which starts at 0.2 s to move along x at 0.5 m/s
/// through the periodic box: once it has settled again after the jolt, it goes round the box
/// more than ten times carried at the plate's speed, and never falls through.
static void test_plate(void)
{
    bdl_world *w = bdl_test_world(
        "[run]\nend_time = 2\n[domain]\nmin = 0 0 -0.01\nmax = 0.072 0.048 0.04\n"
        "periodic = x y\n[contact]\nlaw = linear\n"
        "[species s]\ndiameter = 0.0053\ndensity = 1395\nstiffness = 6e5\nrestitution = 0.7\n"
        "[wall plate]\ntype = mesh\nfile = ../scenes/meshes/shear_plate.obj\nperiodic = x y\n"
        "motion = move\nvelocity = 0.5 0 0\nstart = 0.2\n"
        "[create bead]\ntype = lattice\nspecies = s\ncount = 1\nspacing = 0.01\n"
        "region_min = 0.00335 0.00335 0.00435\nregion_max = 0.01335 0.01335 0.01435\n");
    const double from = 0.8;
    double x_unwrapped = 0.0, x_prev = w->particles.pos[0].x, z_min = 1.0, x_from = 0.0;
    while (w->time < 2.0) {
        CHECK(bdl_world_step(w) == BDL_OK);
        const double x = w->particles.pos[0].x;
        double dx = x - x_prev;
        dx -= 0.072 * round(dx / 0.072);
        x_unwrapped += dx;
        x_prev = x;
        z_min = fmin(z_min, w->particles.pos[0].z);
        if (w->time < from)
            x_from = x_unwrapped;
    }
    const double speed = (x_unwrapped - x_from) / (w->time - from);
    printf("plate: bead carried %.4f m in %.3f s (%.4f m/s; the plate 0.5), lowest centre %.4f m\n",
           x_unwrapped - x_from, w->time - from, speed, z_min);
    CHECK(w->particles.count == 1);
    CHECK_CLOSE(speed, 0.5, 1e-3);
    CHECK(z_min > 0.003); // in a dimple the centre sits 3.25 mm above its bottom
    bdl_world_destroy(w);
    // A repeating plate too short to reach beyond the faces is refused.
    bdl_world *bad = bdl_verify_world(
        "[run]\nend_time = 1\n[domain]\nmin = 0 0 -0.01\nmax = 0.09 0.048 0.04\n"
        "periodic = x y\n[contact]\nlaw = linear\n"
        "[species s]\ndiameter = 0.0053\ndensity = 1395\nstiffness = 6e5\nrestitution = 0.7\n"
        "[wall plate]\ntype = mesh\nfile = ../scenes/meshes/shear_plate.obj\nperiodic = x y\n"
        "[create bead]\ntype = lattice\nspecies = s\ncount = 1\nspacing = 0.01\n"
        "region_min = 0.0015 0.0015 0.004\nregion_max = 0.0105 0.0105 0.01\n");
    CHECK(bad == NULL);
    bdl_world_destroy(bad);
}

int main(void)
{
    test_images();
    test_lists();
    test_profile();
    test_profile_damped();
    test_collision();
    test_plate();
    return bdl_test_summary("test_shear_cell");
}
