// Results do not depend on the thread count, and a checkpoint continues bit-for-bit.
#define _POSIX_C_SOURCE 200809L
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

#include "check.h"
#include "scene_util.h"
#include "output/checkpoint.h"
#include "run/loop.h"
#include "world/world.h"

// Pouring, friction, rolling resistance, a cylinder and a vibrating floor: every path that
// touches ordering (re-sorting, history transfer, insertion, wall lists).
static const char *const scene_text =
    "[run]\nend_time = 1\ndt_fraction = 0.02\nseed = 7\n"
    "[domain]\nmin = -0.03 -0.03 -0.01\nmax = 0.03 0.03 0.1\n"
    "[contact]\nlaw = hertz\nrolling = constant\n"
    "[species small]\ndiameter = 0.003\ndistribution = uniform\ndiameter_min = 0.0025\n"
    "diameter_max = 0.0035\ndensity = 2500\nyoungs_modulus = 5e6\nrestitution = 0.6\n"
    "friction = 0.4\nrolling_friction = 0.05\n"
    "[species big]\ndiameter = 0.006\ndensity = 1200\nyoungs_modulus = 5e6\nrestitution = "
    "0.8\nfriction = 0.3\n"
    "[wall tube]\ntype = cylinder\npoint = 0 0 0\naxis = 0 0 1\nradius = 0.025\n"
    "[wall floor]\ntype = plane\npoint = 0 0 0\nnormal = 0 0 1\nmotion = vibrate\n"
    "frequency = 20\namplitude = 0.002\n"
    "[create bed]\ntype = random\nspecies = small\ncount = 300\nregion_min = -0.017 -0.017 0.003\n"
    "region_max = 0.017 0.017 0.05\nvelocity_jitter = 0.1\n"
    "[create rain]\ntype = pour\nspecies = big\ncount = 40\nrate = 4000\n"
    "region_min = -0.015 -0.015 0.06\nregion_max = 0.015 0.015 0.09\nvelocity = 0 0 -0.3\n";

static bdl_world *make_world(void)
{
    bdl_world *w = bdl_test_world("%s", scene_text);
    w->parallel_min = 1; // exercise the parallel force pass even for this small scene
    return w;
}

static uint64_t run_steps(bdl_world *w, int steps)
{
    for (int s = 0; s < steps; ++s)
        if (bdl_world_step(w) != BDL_OK)
            return 0;
    return bdl_world_hash(w);
}

/// The same scene fluidized: gas through the floor of the tube (a grid large enough for the gas
/// loops to run on both threads), Beetstra drag. The hash includes the gas velocity and pressure.
static void test_coupled(void)
{
    uint64_t hashes[2];
    for (int t = 1; t <= 2; ++t) {
        omp_set_num_threads(t);
        bdl_world *w = bdl_test_world("%s[gas]\ncells = 20 20 30\nzmin = inlet\nzmax = outlet\n"
                                      "inlet_velocity = 0.8\n[coupling]\ndrag = beetstra\n",
                                      scene_text);
        CHECK(w != NULL && w->gas != NULL);
        if (!w)
            return;
        w->parallel_min = 1;
        hashes[t - 1] = run_steps(w, 1200);
        printf("coupled, threads %d: %ld gas steps, hash %016llx\n", t, w->gas_steps,
               (unsigned long long)hashes[t - 1]);
        CHECK(w->gas_steps > 10);
        bdl_world_destroy(w);
    }
    CHECK(hashes[0] != 0);
    CHECK_MSG(hashes[0] == hashes[1], "coupled state differs between 1 and 2 threads");

    // Resume a coupled run from a checkpoint taken between two gas steps.
    char path[] = "/tmp/bedlam-ckpt-gas-XXXXXX";
    int fd = mkstemp(path);
    CHECK(fd >= 0);
    if (fd >= 0)
        close(fd);
    const char *gas = "%s[gas]\ncells = 20 20 30\nzmin = inlet\nzmax = outlet\n"
                      "inlet_velocity = 0.8\n[coupling]\ndrag = beetstra\n";
    bdl_world *a = bdl_test_world(gas, scene_text), *b = bdl_test_world(gas, scene_text);
    run_steps(a, 605);
    CHECK(bdl_world_set_parameter(a, "gas.inlet_scale", 1.25) == 1); // live, saved with the rest
    CHECK(bdl_checkpoint_save(a, path) == BDL_OK);
    uint64_t straight = run_steps(a, 600);
    char why[256];
    CHECK(bdl_checkpoint_load(b, path, NULL, why, sizeof why) == BDL_OK);
    uint64_t resumed = run_steps(b, 600);
    printf("coupled: uninterrupted %016llx, resumed %016llx (%ld gas steps)\n",
           (unsigned long long)straight, (unsigned long long)resumed, b->gas_steps);
    CHECK_MSG(straight == resumed, "resumed coupled run differs from the uninterrupted one");
    unlink(path);
    bdl_world_destroy(a);
    bdl_world_destroy(b);
}

/// A scene on 1 and 2 threads, and resumed from a checkpoint halfway, gives the same bits.
/// Returns the particles removed on one thread.
static long same_bits(const char *name, const char *text, int steps)
{
    uint64_t hashes[2];
    long out = 0;
    for (int t = 1; t <= 2; ++t) {
        omp_set_num_threads(t);
        bdl_world *w = bdl_test_world("%s", text);
        w->parallel_min = 1;
        hashes[t - 1] = run_steps(w, steps);
        out = t == 1 ? w->removed : out;
        printf("%s, threads %d: %ld particles, %ld out, %ld wall surfaces, %ld neighbour builds, "
               "hash %016llx\n",
               name, t, w->particles.count, w->removed, bdl_wall_surfaces(&w->walls),
               w->neighbor.builds, (unsigned long long)hashes[t - 1]);
        bdl_world_destroy(w);
    }
    CHECK(hashes[0] != 0);
    CHECK_MSG(hashes[0] == hashes[1], "%s: state differs between 1 and 2 threads", name);
    char path[] = "/tmp/bedlam-ckpt-same-XXXXXX";
    int fd = mkstemp(path);
    CHECK(fd >= 0);
    if (fd >= 0)
        close(fd);
    bdl_world *a = bdl_test_world("%s", text), *b = bdl_test_world("%s", text);
    run_steps(a, steps / 2);
    CHECK(bdl_checkpoint_save(a, path) == BDL_OK);
    uint64_t straight = run_steps(a, steps - steps / 2);
    char why[256];
    CHECK(bdl_checkpoint_load(b, path, NULL, why, sizeof why) == BDL_OK);
    uint64_t resumed = run_steps(b, steps - steps / 2);
    CHECK_MSG(straight == resumed, "%s: resumed run differs from the uninterrupted one", name);
    unlink(path);
    bdl_world_destroy(a);
    bdl_world_destroy(b);
    return out;
}

// A vessel: a turning tube on a turning mesh floor smaller than it (beads fall past the floor's
// corners and leave through the bottom of the domain, removed and counted), a plug taken away and a
// piston pressing from above: mesh lists and patches, turning and moving walls, removals.
static const char *const vessel_text =
    "[run]\nend_time = 1\ndt_fraction = 0.05\nseed = 9\n"
    "[domain]\nmin = -0.03 -0.03 -0.02\nmax = 0.03 0.03 0.07\n[contact]\nlaw = linear\n"
    "[species glass]\ndiameter = 0.003\ndensity = 2500\nstiffness = 2000\nrestitution = 0.5\n"
    "friction = 0.5\n"
    "[wall tube]\ntype = cylinder\npoint = 0 0 0\naxis = 0 0 1\nradius = 0.025\n"
    "motion = rotate\nrotation_axis = 0 0 1\nrotation_center = 0 0 0\nangular_velocity = 20\n"
    "[wall floor]\ntype = mesh\nfile = scenes/meshes/plate.obj\nrotate = 0 0 30\n"
    "motion = rotate\nrotation_axis = 0 0 1\nrotation_center = 0.002 0 0\nangular_velocity = -15\n"
    "[wall plug]\ntype = plane\npoint = 0 0 -0.001\nnormal = 0 0 1\nopen_time = 0.005\n"
    "[wall piston]\ntype = plane\npoint = 0 0 0.06\nnormal = 0 0 -1\nmotion = move\n"
    "velocity = 0 0 -0.5\nstart = 0.002\nstop = 0.02\n"
    "[create bed]\ntype = random\nspecies = glass\ncount = 400\n"
    "region_min = -0.024 -0.024 0.0015\nregion_max = 0.024 0.024 0.035\n";

// Shear cells: frictional spheres and rods between Lees-Edwards images (springs carried across
// the z faces, particles passing through them), and spheres between two corrugated plates
// repeating through the periodic x and y faces as they move.
static const char *const sheared_text =
    "[run]\nend_time = 1\ngravity = 0 0 0\nseed = 3\n"
    "[domain]\nmin = 0 0 0\nmax = 0.03 0.02 0.025\nperiodic = x y z\nshear_rate = 60\n"
    "[contact]\nlaw = linear\n[species s]\ndiameter = 0.002\ndensity = 2500\nstiffness = 2000\n"
    "restitution = 0.7\nfriction = 0.4\n"
    "[create bed]\ntype = random\nspecies = s\ncount = 900\nregion_min = 0 0 0\n"
    "region_max = 0.03 0.02 0.025\n";
static const char *const sheared_rods_text =
    "[run]\nend_time = 1\ngravity = 0 0 0\nseed = 4\n"
    "[domain]\nmin = 0 0 0\nmax = 0.036 0.024 0.03\nperiodic = x y z\nshear_rate = 60\n"
    "[contact]\nlaw = linear\n[species rod]\nshape = rod\ndiameter = 0.0015\nlength = 0.006\n"
    "density = 1395\nstiffness = 2000\nrestitution = 0.5\nfriction = 0.4\n"
    "[create bed]\ntype = random\nspecies = rod\ncount = 400\nregion_min = 0 0 0\n"
    "region_max = 0.036 0.024 0.03\n";
static const char *const plates_text =
    "[run]\nend_time = 1\ngravity = 0 0 0\nseed = 5\n"
    "[domain]\nmin = 0 0 0\nmax = 0.072 0.048 0.048\nperiodic = x y\n"
    "[contact]\nlaw = linear\n[species s]\ndiameter = 0.0053\ndensity = 1395\nstiffness = 6e5\n"
    "restitution = 0.7\n"
    "[wall floor]\ntype = mesh\nfile = ../scenes/meshes/shear_plate.obj\nperiodic = x y\n"
    "motion = move\nvelocity = -2.4 0 0\n"
    "[wall lid]\ntype = mesh\nfile = ../scenes/meshes/shear_plate.obj\nrotate = 180 0 0\n"
    "translate = 0 0.048 0.048\nperiodic = x y\nmotion = move\nvelocity = 2.4 0 0\n"
    "[create bed]\ntype = random\nspecies = s\ncount = 500\nregion_min = 0 0 0.0031\n"
    "region_max = 0.072 0.048 0.0449\nvelocity_jitter = 0.5\n";

int main(void)
{
    const int steps = 1500;
    uint64_t hashes[2];
    long counts[2];
    for (int t = 1; t <= 2; ++t) {
        omp_set_num_threads(t);
        bdl_world *w = make_world();
        hashes[t - 1] = run_steps(w, steps);
        counts[t - 1] = w->particles.count;
        printf("threads %d: %ld particles, %ld neighbour builds, hash %016llx\n", t,
               w->particles.count, w->neighbor.builds, (unsigned long long)hashes[t - 1]);
        bdl_world_destroy(w);
    }
    CHECK(hashes[0] != 0);
    CHECK_MSG(hashes[0] == hashes[1], "state after %d steps differs between 1 and 2 threads",
              steps);
    CHECK(counts[0] > 300); // pouring happened
    test_coupled();
    { // Sun's "averaged" drag: the cells' mean solids velocity deposited and read back
        char mean_text[4096];
        snprintf(mean_text, sizeof mean_text,
                 "%s[gas]\ncells = 20 20 30\nzmin = inlet\nzmax = outlet\ninlet_velocity = 0.8\n"
                 "[coupling]\ndrag = beetstra\ndrag_velocity = mean\n",
                 scene_text);
        same_bits("coupled, mean drag", mean_text, 1200);
    }
    CHECK(same_bits("vessel", vessel_text, 6000) > 0); // beads left through the bottom
    same_bits("sheared", sheared_text, 4000);
    same_bits("sheared rods", sheared_rods_text, 3000);
    same_bits("plates", plates_text, 4000);

    // Resume: checkpoint half-way, continue in a new world, compare with the uninterrupted run.
    char path[] = "/tmp/bedlam-ckpt-XXXXXX";
    int fd = mkstemp(path);
    CHECK(fd >= 0);
    if (fd >= 0)
        close(fd);
    omp_set_num_threads(2);
    bdl_world *a = make_world();
    run_steps(a, steps / 2);
    CHECK(bdl_checkpoint_save(a, path) == BDL_OK);
    uint64_t straight = run_steps(a, steps - steps / 2);
    bdl_world *b = make_world();
    char why[256];
    CHECK(bdl_checkpoint_load(b, path, NULL, why, sizeof why) == BDL_OK);
    uint64_t resumed = run_steps(b, steps - steps / 2);
    printf("uninterrupted %016llx, resumed %016llx\n", (unsigned long long)straight,
           (unsigned long long)resumed);
    CHECK_MSG(straight == resumed, "resumed run differs from the uninterrupted one");
    // A damaged checkpoint is refused with a reason.
    FILE *f = fopen(path, "r+b");
    if (f) {
        fseek(f, 0, SEEK_SET);
        fputs("garbage!", f);
        fclose(f);
    }
    CHECK(bdl_checkpoint_load(b, path, NULL, why, sizeof why) == BDL_ERR_CHECKPOINT);
    unlink(path);
    bdl_world_destroy(a);
    bdl_world_destroy(b);
    return bdl_test_summary("test_determinism");
}
