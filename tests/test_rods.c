// Rods against known answers: a rod dropped flat on a plane rebounds with the configured
// restitution; a rod dropped at an angle starts turning with the angular impulse of a rigid-body
// collision; a rod falling against another at an angle conserves momentum and angular momentum;
// rod scenes give the same bits on one and two threads and after a checkpoint.
#define _GNU_SOURCE // memmem
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <unistd.h>

#include <string.h>

#include "check.h"
#include "dem/rigid.h"
#include "output/checkpoint.h"
#include "output/diagnostics.h"
#include "output/world_vtk.h"
#include "scene/scene.h"
#include "scene_util.h"

/// The thesis's small rod (Mahajan 2019, table 4.1): 6 mm tip to tip, 1.5 mm across, 1395 kg/m^3,
/// linear springs of 6000 N/m, restitution 0.43; no gravity, so the rebound is a clean measure.
static const char one_rod[] = "[run]\nend_time = 1\ngravity = 0 0 0\ndt_fraction = %g\n"
                              "[domain]\nmin = -0.02 -0.02 0\nmax = 0.02 0.02 0.05\n"
                              "[contact]\nlaw = linear\n"
                              "[species rod]\nshape = rod\ndiameter = 1.5e-3\nlength = 6e-3\n"
                              "density = 1395\nstiffness = 6000\nrestitution = 0.43\nfriction = 0\n"
                              "[wall floor]\ntype = plane\npoint = 0 0 0\nnormal = 0 0 1\n"
                              "[create one]\ntype = lattice\nregion_min = -0.004 -0.004 0.01\n"
                              "region_max = 0.004 0.004 0.0175\ncount = 1\n";

/// Puts the one rod of w at height z with axis u, velocity v and no spin, and rebuilds the lists.
static void place(bdl_world *w, double z, bdl_vec3 u, bdl_vec3 v)
{
    bdl_particles *p = &w->particles;
    p->pos[0] = bdl_v3(0.0, 0.0, z);
    p->vel[0] = v;
    bdl_particle_set_orient(p, 0, bdl_q_from_z(bdl_v3_normalize(u)));
    p->ang_mom[0] = p->omega[0] = bdl_v3_zero();
    CHECK(bdl_neighbor_build(&w->neighbor, p, &w->walls, NULL) == BDL_OK);
    CHECK(bdl_world_compute_forces(w) == BDL_OK);
}

/// Steps until the rod has left the floor again (at most `limit` steps); returns 1 if it did.
static int bounce(bdl_world *w, long limit)
{
    int touched = 0;
    for (long s = 0; s < limit; ++s) {
        CHECK(bdl_world_step(w) == BDL_OK);
        int touching = w->neighbor.wall_pair_count > 0 && w->neighbor.wall_touching[0];
        touched |= touching;
        if (touched && !touching)
            return 1;
    }
    return 0;
}

/// Flat on the floor: both tips hit together, the contact sits in the middle of the shaft, and
/// the rod leaves with e times its approach speed and no spin. The error of the realised
/// restitution is first order in dt, as for spheres (test_bounce), so the check is made at
/// t_c/400 with the spheres' bound there.
static void test_flat_drop(void)
{
    bdl_world *w = bdl_test_world(one_rod, 1.0 / 400);
    const double v0 = 0.5, r = w->particles.radius[0];
    place(w, r + 2e-4, bdl_v3(1, 0, 0), bdl_v3(0, 0, -v0));
    CHECK(bounce(w, 200000));
    const double e = w->particles.vel[0].z / v0;
    const double spin = bdl_v3_len(w->particles.omega[0]);
    printf("flat drop: realised restitution %.5f (configured 0.43), spin after %.3g rad/s, "
           "dt = t_c / %.0f\n",
           e, spin, 1.0 / w->contact_time_dt_ratio);
    CHECK_CLOSE(e, 0.43, 0.005); // the spheres' bound at t_c/400 (test_bounce)
    CHECK(spin < 1e-9);
    bdl_world_destroy(w);
}

/// The rigid-body answer for a rod struck at the point of arm a from its centre along the normal
/// n, approaching at v_n: the impulse J n that reverses the point's normal velocity with
/// restitution e, J = (1 + e) v_n / (1/m + (a x n).I^-1 (a x n)); the spin after is I^-1 (a x J n).
static bdl_vec3 rigid_spin(const bdl_particles *p, bdl_vec3 a, bdl_vec3 n, double v_n, double e)
{
    const bdl_vec3 axn = bdl_v3_cross(a, n);
    const double inv_m =
        p->inv_mass[0] +
        bdl_v3_len2(axn) * bdl_rigid_inv_inertia_along(p->orient[0], p->inv_inertia[0],
                                                       bdl_v3_scale(axn, 1.0 / bdl_v3_len(axn)));
    const double J = (1.0 + e) * v_n / inv_m;
    return bdl_rigid_omega(p->orient[0], bdl_v3_scale(axn, J), p->inv_inertia[0]);
}

/// Tilted by 45 degrees in the x-z plane: only the lower tip hits, and the rod leaves turning as
/// the impulse of a rigid-body collision with the configured restitution turns it.
static void test_tilted_drop(void)
{
    bdl_world *w = bdl_test_world(one_rod, 1.0 / 50);
    bdl_particles *p = &w->particles;
    const double v0 = 0.5, r = p->radius[0], h = 0.5 * 6e-3 - r;
    const bdl_vec3 u = bdl_v3_normalize(bdl_v3(1, 0, 1));
    place(w, r + h * u.z + 1e-4, u, bdl_v3(0, 0, -v0));
    // The arm at impact: from the centre to the lower tip's lowest point.
    const bdl_vec3 arm = bdl_v3_madd(bdl_v3_scale(u, -h), bdl_v3(0, 0, 1), -r);
    const bdl_vec3 expected = rigid_spin(p, arm, bdl_v3(0, 0, 1), v0, 0.43);
    CHECK(bounce(w, 200000));
    const bdl_vec3 w_after = p->omega[0];
    printf("tilted drop: spin after %.5f rad/s about y (rigid body %.5f), x %.2g, z %.2g\n",
           w_after.y, expected.y, w_after.x, w_after.z);
    CHECK_CLOSE(w_after.y, expected.y, 0.02); // the bound
    CHECK(fabs(w_after.x) < 1e-9 * fabs(expected.y) && fabs(w_after.z) < 1e-9 * fabs(expected.y));
    bdl_world_destroy(w);
}

/// Pairs and wall pairs of w in contact now.
static long touching(const bdl_world *w)
{
    long n = 0;
    for (long k = 0; k < w->neighbor.pair_count; ++k)
        n += w->neighbor.touching[k];
    for (long k = 0; k < w->neighbor.wall_pair_count; ++k)
        n += w->neighbor.wall_touching[k];
    return n;
}

static uint64_t run(bdl_world *w, int steps)
{
    for (int s = 0; s < steps; ++s)
        if (bdl_world_step(w) != BDL_OK)
            return 0;
    return bdl_world_hash(w);
}

/// A frictional bed of rods poured into a box: the same bits on one and two threads (every loop
/// run in parallel), and after a checkpoint.
static void test_threads_and_resume(void)
{
    static const char bed[] =
        "[run]\nend_time = 1\ngravity = 0 0 -300\ndt_fraction = 0.05\n[domain]\nmin = 0 0 0\nmax = "
        "0.03 0.03 0.06\n"
        "[contact]\nlaw = linear\nrolling = constant\n"
        "[species rod]\nshape = rod\ndiameter = 1.5e-3\nlength = 6e-3\ndensity = 1395\n"
        "stiffness = 6000\nrestitution = 0.43\nfriction = 0.46\nrolling_friction = 0.025\n"
        "[species ball]\ndiameter = 2e-3\ndensity = 2500\nstiffness = 6000\nrestitution = 0.6\n"
        "friction = 0.3\n"
        "[wall box]\ntype = box\nmin = 0 0 0\nmax = 0.03 0.03 0.06\nfriction = 0.33\n"
        "[create rods]\ntype = random\nspecies = rod\nregion_min = 0 0 0.005\n"
        "region_max = 0.03 0.03 0.06\ncount = 600\n"
        "[create balls]\ntype = random\nspecies = ball\nregion_min = 0 0 0.005\n"
        "region_max = 0.03 0.03 0.06\ncount = 100\n";
    uint64_t hash[2];
    for (int t = 1; t <= 2; ++t) {
        omp_set_num_threads(t);
        bdl_world *w = bdl_test_world("%s", bed);
        w->parallel_min = 1;
        hash[t - 1] = run(w, 6000);
        const long contacts = touching(w);
        printf("rods, threads %d: %ld particles, %ld contacts, %ld builds, hash %016llx\n", t,
               w->particles.count, contacts, w->neighbor.builds, (unsigned long long)hash[t - 1]);
        CHECK(contacts > 100); // rods piling up on the floor and on each other, not a gas
        bdl_world_destroy(w);
    }
    CHECK(hash[0] != 0);
    CHECK_MSG(hash[0] == hash[1], "rod state differs between 1 and 2 threads");
    omp_set_num_threads(1);
    char path[] = "/tmp/bedlam-rods-XXXXXX";
    int fd = mkstemp(path);
    CHECK(fd >= 0);
    if (fd >= 0)
        close(fd);
    bdl_world *a = bdl_test_world("%s", bed), *b = bdl_test_world("%s", bed);
    run(a, 3000);
    CHECK(bdl_checkpoint_save(a, path) == BDL_OK);
    const uint64_t straight = run(a, 3000);
    char why[256];
    CHECK(bdl_checkpoint_load(b, path, NULL, why, sizeof why) == BDL_OK);
    const uint64_t resumed = run(b, 3000);
    printf("rods: uninterrupted %016llx, resumed %016llx\n", (unsigned long long)straight,
           (unsigned long long)resumed);
    CHECK_MSG(straight == resumed, "a resumed rod run differs from the uninterrupted one");
    unlink(path);
    bdl_world_destroy(a);
    bdl_world_destroy(b);
}

/// Builds the world of a rod scene whose one creator reads `csv`; returns the world, or NULL with
/// the message in err.
static bdl_world *world_from_csv(const char *csv, bdl_scene_error *err)
{
    char path[] = "/tmp/bedlam-rods-csv-XXXXXX";
    int fd = mkstemp(path);
    CHECK(fd >= 0);
    if (fd < 0)
        return NULL;
    CHECK(write(fd, csv, strlen(csv)) == (ssize_t)strlen(csv));
    close(fd);
    char text[1024];
    snprintf(text, sizeof text,
             "[run]\nend_time = 1\n[domain]\nmin = -0.01 -0.01 0\nmax = 0.01 0.01 "
             "0.02\n[contact]\nlaw = linear\n"
             "[species rod]\nshape = rod\ndiameter = 1.5e-3\nlength = 6e-3\ndensity = 1395\n"
             "stiffness = 6000\nrestitution = 0.43\n"
             "[create file]\ntype = file\nspecies = rod\nfile = %s\n",
             path);
    static bdl_scene scene;
    bdl_world *w = NULL;
    if (bdl_scene_load_string(text, "rods.ini", NULL, 0, &scene, err) == BDL_OK)
        bdl_world_create(&scene, &w, err);
    unlink(path);
    return w;
}

/// The particle file of a rod world names the orientation, axis and length arrays, and holds the
/// first rod's axis and length among its bytes.
static void check_vtp(const bdl_world *w)
{
    char path[] = "/tmp/bedlam-rods-vtp-XXXXXX";
    int fd = mkstemp(path);
    CHECK(fd >= 0);
    if (fd < 0)
        return;
    close(fd);
    CHECK(bdl_world_vtp_write(w, path) == BDL_OK);
    static char buf[1 << 16];
    FILE *f = fopen(path, "rb");
    const size_t n = f ? fread(buf, 1, sizeof buf, f) : 0;
    if (f)
        fclose(f);
    unlink(path);
    buf[n < sizeof buf ? n : sizeof buf - 1] = 0;
    CHECK(strstr(buf, "Name=\"orientation\" NumberOfComponents=\"4\"") != NULL);
    CHECK(strstr(buf, "Name=\"axis\" NumberOfComponents=\"3\"") != NULL);
    CHECK(strstr(buf, "Name=\"length\" NumberOfComponents=\"1\"") != NULL);
    const bdl_vec3 axis = bdl_q_axis_z(w->particles.orient[0]);
    const double length = 6e-3;
    CHECK(memmem(buf, n, &axis, sizeof axis) != NULL);
    CHECK(memmem(buf, n, &length, sizeof length) != NULL);
}

/// Rods from a CSV file: the axis columns ux, uy, uz set the orientation (any length), rods
/// without them get random axes, and rows or headers that describe no rod are refused by name.
static void test_file(void)
{
    bdl_scene_error err = {{0}};
    bdl_world *w = world_from_csv("x,y,z,ux,uy,uz\n0,0,0.005,3,0,0\n0,0,0.010,0,0,0.5\n", &err);
    CHECK_MSG(w != NULL, "%s", err.message);
    if (!w)
        return;
    for (long i = 0; i < w->particles.count; ++i) {
        const bdl_vec3 a = bdl_particle_half_axis(&w->particles, i);
        const bdl_vec3 want = w->particles.pos[i].z < 0.0075 ? bdl_v3(1, 0, 0) : bdl_v3(0, 0, 1);
        CHECK_CLOSE(bdl_v3_dot(a, want), 0.5 * (6e-3 - 1.5e-3), 1e-12);
    }
    check_vtp(w);
    bdl_world_destroy(w);
    static const struct {
        const char *csv, *words;
    } bad[] = {
        {"x,y,z,ux,uy\n0,0,0.005,1,0\n", "some of ux, uy, uz"},
        {"x,y,z,diameter\n0,0,0.005,0.001\n", "is a rod"},
        {"x,y,z,ux,uy,uz\n0,0,0.005,0,0,0\n", ":2: axis (0, 0, 0) must be a nonzero"},
    };
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; ++k) {
        w = world_from_csv(bad[k].csv, &err);
        CHECK(w == NULL);
        CHECK_MSG(strstr(err.message, bad[k].words) != NULL, "%s", err.message);
        if (w)
            bdl_world_destroy(w);
    }
}

/// The guards see a rod's overlap along its shaft: two rods crossed at right angles, the end of
/// one shaft 0.75 mm above the other's axis, overlap by half a diameter (a ratio of 1 to the
/// radius), though their centres are 2.4 mm apart, farther than a diameter.
static void test_overlap_seen(void)
{
    bdl_world *w = bdl_test_world(one_rod, 1.0 / 50);
    bdl_particles *p = &w->particles;
    p->count = 0; // the scene's rod out, two placed by hand, well above the floor
    // Axis of a along x, centred at x = 2.25 mm (its tip sphere's centre over the origin); b
    // along y through the origin, 0.75 mm below.
    CHECK(bdl_particles_add_rod(p, bdl_v3(2.25e-3, 0, 0.02075), bdl_v3_zero(), 0.75e-3, 2.25e-3,
                                bdl_q_from_z(bdl_v3(1, 0, 0)), 1395, 0) >= 0);
    CHECK(bdl_particles_add_rod(p, bdl_v3(0, 0, 0.02), bdl_v3_zero(), 0.75e-3, 2.25e-3,
                                bdl_q_from_z(bdl_v3(0, 1, 0)), 1395, 0) >= 0);
    CHECK(bdl_neighbor_build(&w->neighbor, p, &w->walls, NULL) == BDL_OK);
    CHECK(bdl_world_compute_forces(w) == BDL_OK);
    bdl_diagnostics d;
    bdl_diagnostics_compute(w, 0.0, &d);
    printf("crossed rods: largest overlap / radius %.6f (expected 1)\n", d.max_overlap_ratio);
    CHECK_CLOSE(d.max_overlap_ratio, 1.0, 1e-9);
    bdl_world_destroy(w);
}

int main(void)
{
    test_overlap_seen();
    test_file();
    test_flat_drop();
    test_tilted_drop();
    test_threads_and_resume();
    return bdl_test_summary("test_rods");
}
