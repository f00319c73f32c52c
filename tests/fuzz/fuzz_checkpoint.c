// bedlam — a fuzz harness for the checkpoint reader (libFuzzer).
//
// An input is one selector byte and the bytes of a checkpoint file. The selector picks the world
// the file is loaded into (beads with friction, walls and a pour; the same with a gas; rods and
// balls in a box; the beads with the Hertz law, whose Mindlin springs keep their work) and whether
// the harness first rewrites the header's payload size and both checksums to fit the bytes: seven
// inputs in eight, so that mutations reach the scene record, the counts and the range checks
// instead of stopping at the checksum; the eighth keeps them as they are. A load must end in BDL_OK
// or in BDL_ERR_CHECKPOINT with a reason (BDL_ERR_NOMEM for a state too large for memory); a state
// it accepts is stepped three times. Anything else (a crash, a sanitizer report, a hang, another
// result) is a finding.
//
// With libFuzzer (clang):
//   CC=clang cmake -S . -B build-fuzz -DBDL_FUZZ=ON && cmake --build build-fuzz --target
//   fuzz_checkpoint fuzz_checkpoint_replay
//   build-fuzz/tests/fuzz/fuzz_checkpoint_replay --seeds corpus
//   build-fuzz/tests/fuzz/fuzz_checkpoint corpus -runs=100000
// Without it, fuzz_checkpoint_replay (any compiler) writes the seeds (--seeds DIR: one valid
// checkpoint of each world, with its selector byte) or loads the files it is given, such as a
// finding to reproduce.
#define _POSIX_C_SOURCE 200809L // fmemopen
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/crc32.h"
#include "core/file.h"
#include "output/checkpoint.h"
#include "world/world.h"

// Small worlds: building one per input is most of a run's cost.
#define BEADS_OF(law, stiffness)                                                                   \
    "[run]\nend_time = 1\ndt_fraction = 0.05\nseed = 5\ngravity = 0 0 -100\n"                      \
    "[domain]\nmin = -0.006 -0.006 0\nmax = 0.006 0.006 0.02\n"                                    \
    "[contact]\nlaw = " law "\nrolling = constant\ndamping = closed_form\n"                        \
    "[species bead]\ndiameter = 0.002\ndensity = 2500\n" stiffness "\nrestitution = 0.5\n"         \
    "friction = 0.4\nrolling_friction = 0.02\n"                                                    \
    "[wall floor]\ntype = plane\npoint = 0 0 0\nnormal = 0 0 1\n"                                  \
    "[wall tube]\ntype = cylinder\npoint = 0 0 0\naxis = 0 0 1\nradius = 0.0055\n"                 \
    "[create bed]\ntype = random\nspecies = bead\ncount = 16\nregion_min = -0.004 -0.004 0.001\n"  \
    "region_max = 0.004 0.004 0.01\n"                                                              \
    "[create rain]\ntype = pour\nspecies = bead\ncount = 4\nrate = 2000\n"                         \
    "region_min = -0.003 -0.003 0.014\nregion_max = 0.003 0.003 0.019\n"
#define BEADS BEADS_OF("linear", "stiffness = 1000")

enum { WORLDS = 4 };

static const char *const scenes[WORLDS] = {
    BEADS,
    BEADS "[gas]\ncells = 3 3 5\nzmin = inlet\nzmax = outlet\ninlet_velocity = 0.2\n"
          "[coupling]\ndrag = beetstra\n",
    "[run]\nend_time = 1\ngravity = 0 0 -300\ndt_fraction = 0.05\n"
    "[domain]\nmin = 0 0 0\nmax = 0.012 0.012 0.02\n"
    "[contact]\nlaw = linear\nrolling = constant\ndamping = closed_form\n"
    "[species rod]\nshape = rod\ndiameter = 1.5e-3\nlength = 6e-3\ndensity = 1395\n"
    "stiffness = 6000\nrestitution = 0.43\nfriction = 0.46\nrolling_friction = 0.025\n"
    "[species ball]\ndiameter = 2e-3\ndensity = 2500\nstiffness = 6000\nrestitution = 0.6\n"
    "friction = 0.3\n"
    "[wall box]\ntype = box\nmin = 0 0 0\nmax = 0.012 0.012 0.02\nfriction = 0.33\n"
    "[create rods]\ntype = random\nspecies = rod\nregion_min = 0 0 0.003\n"
    "region_max = 0.012 0.012 0.02\ncount = 12\n"
    "[create balls]\ntype = random\nspecies = ball\nregion_min = 0 0 0.003\n"
    "region_max = 0.012 0.012 0.02\ncount = 4\n",
    BEADS_OF("hertz", "youngs_modulus = 1e7"),
};

static bdl_world *make_world(int k)
{
    static bdl_scene scene; // large; one input at a time
    bdl_scene_error err;
    bdl_world *w = NULL;
    if (bdl_scene_load_string(scenes[k], "fuzz", NULL, 0, &scene, &err) != BDL_OK ||
        bdl_world_create(&scene, &w, &err) != BDL_OK) {
        fprintf(stderr, "fuzz_checkpoint: scene %d: %s\n", k, err.message);
        abort();
    }
    return w;
}

/// Writes the header's payload size and both checksums to fit `size` bytes.
static void fit_header(unsigned char *d, size_t size)
{
    if (size < 32)
        return;
    const uint64_t payload = size - 32;
    memcpy(d + 16, &payload, 8);
    const uint32_t crc = bdl_crc32(0, d + 32, size - 32);
    memcpy(d + 24, &crc, 4);
    const uint32_t own = bdl_crc32(0, d, 28);
    memcpy(d + 28, &own, 4);
}

/// Loads one input; returns the load's result.
static bdl_result load_one(const uint8_t *data, size_t size)
{
    if (size < 2)
        return BDL_ERR_CHECKPOINT;
    const int k = data[0] % WORLDS, keep = (data[0] / WORLDS) % 8 == 7;
    size_t n = size - 1;
    unsigned char *d = malloc(n);
    if (!d)
        abort();
    memcpy(d, data + 1, n);
    if (!keep)
        fit_header(d, n);
    bdl_world *w = make_world(k);
    FILE *f = fmemopen(d, n, "rb");
    if (!f)
        abort();
    char why[1024] = "";
    bdl_checkpoint_info info;
    const bdl_result r = bdl_checkpoint_read(w, f, "fuzz", &info, why, sizeof why);
    fclose(f);
    if (r != BDL_OK && r != BDL_ERR_CHECKPOINT && r != BDL_ERR_NOMEM)
        abort(); // a result no reader of a file may give
    if (r != BDL_OK && strncmp(why, "checkpoint 'fuzz': ", 19) != 0)
        abort(); // refused without a reason
    for (int s = 0; r == BDL_OK && s < 3; ++s)
        if (bdl_world_step(w) != BDL_OK)
            break; // a state may be unstable; it must not crash
    bdl_world_destroy(w);
    free(d);
    return r;
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    load_one(data, size);
    return 0;
}

#ifndef BDL_LIBFUZZER
/// One valid checkpoint of each world, stepped until it has contacts, as DIR/seed-K.
static int write_seeds(const char *dir)
{
    if (bdl_mkdir_p(dir) != BDL_OK) {
        fprintf(stderr, "fuzz_checkpoint: cannot create %s\n", dir);
        return 1;
    }
    int failed = 0;
    for (int k = 0; k < WORLDS; ++k) {
        bdl_world *w = make_world(k);
        for (int s = 0; s < 3000; ++s)
            bdl_world_step(w);
        char path[1024];
        snprintf(path, sizeof path, "%s/seed-%d.tmp", dir, k);
        size_t size = 0;
        char *bytes = bdl_checkpoint_save(w, path) == BDL_OK ? bdl_read_file(path, &size) : NULL;
        remove(path);
        unsigned char *seed = bytes ? malloc(size + 1) : NULL;
        if (seed) {
            seed[0] = (unsigned char)k; // fit the header (it fits already)
            memcpy(seed + 1, bytes, size);
            snprintf(path, sizeof path, "%s/seed-%d", dir, k);
            const bdl_result r = bdl_write_file_atomic(path, seed, size + 1);
            const bdl_result loaded = load_one(seed, size + 1);
            printf("%s: %zu bytes, %ld particles, %ld pairs; loads: %s\n", path, size + 1,
                   w->particles.count, w->neighbor.pair_count, bdl_result_text(loaded));
            failed += r != BDL_OK || loaded != BDL_OK;
        } else {
            failed++;
        }
        free(seed);
        free(bytes);
        bdl_world_destroy(w);
    }
    return failed != 0;
}

int main(int argc, char **argv)
{
    if (argc == 3 && strcmp(argv[1], "--seeds") == 0)
        return write_seeds(argv[2]);
    if (argc < 2) {
        fprintf(stderr, "usage: fuzz_checkpoint_replay --seeds DIR | FILE...\n");
        return 2;
    }
    for (int a = 1; a < argc; ++a) {
        size_t size = 0;
        char *bytes = bdl_read_file(argv[a], &size);
        if (!bytes) {
            fprintf(stderr, "fuzz_checkpoint: cannot read %s\n", argv[a]);
            return 2;
        }
        printf("%s: %s\n", argv[a], bdl_result_text(load_one((const uint8_t *)bytes, size)));
        free(bytes);
    }
    return 0;
}
#endif
