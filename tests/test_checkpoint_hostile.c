// Checkpoints are untrusted input. Every damaged, truncated or crafted checkpoint is refused with
// BDL_ERR_CHECKPOINT and a reason (never a crash, a hang or a sanitizer report): one byte changed
// at 1000 positions, 100 truncations, and indices, counts, time steps and fields patched with the
// checksums recomputed (so that the range checks, not the checksum, must catch them). A scene
// whose layout differs is refused naming what differs; one whose contact parameters changed is
// resumed with its own time step, and the change is reported.
#define _POSIX_C_SOURCE 200809L // fmemopen, mkstemp
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "check.h"
#include "scene_util.h"
#include "cfd/gas.h"
#include "core/crc32.h"
#include "core/file.h"
#include "core/rng.h"
#include "output/checkpoint.h"

// Frictional beads with rolling resistance in a tube on a floor, poured onto a bed: contacts with
// tangential history, wall contacts, a pour counter. %g: the stiffness, %s: further sections.
static const char beads_format[] =
    "[run]\nend_time = 1\ndt_fraction = 0.05\nseed = 5\ngravity = 0 0 -100\n"
    "[domain]\nmin = -0.01 -0.01 0\nmax = 0.01 0.01 0.03\n"
    "[contact]\nlaw = linear\nrolling = constant\ndamping = closed_form\n"
    "[species bead]\ndiameter = %g\ndensity = 2500\nstiffness = %g\nrestitution = 0.5\n"
    "friction = %g\nrolling_friction = 0.02\n"
    "[wall floor]\ntype = plane\npoint = 0 0 0\nnormal = 0 0 1\n"
    "%s"
    "[create bed]\ntype = random\nspecies = bead\ncount = 60\nregion_min = -0.006 -0.006 0.001\n"
    "region_max = 0.006 0.006 0.015\n"
    "[create rain]\ntype = pour\nspecies = bead\ncount = 10\nrate = 2000\n"
    "region_min = -0.005 -0.005 0.02\nregion_max = 0.005 0.005 0.028\n%s";

static const char tube[] =
    "[wall tube]\ntype = cylinder\npoint = 0 0 0\naxis = 0 0 1\nradius = 0.009\n";

// Rods and balls settling in a box.
static const char rods_scene[] =
    "[run]\nend_time = 1\ngravity = 0 0 -300\ndt_fraction = 0.05\n"
    "[domain]\nmin = 0 0 0\nmax = 0.015 0.015 0.03\n"
    "[contact]\nlaw = linear\nrolling = constant\ndamping = closed_form\n"
    "[species rod]\nshape = rod\ndiameter = 1.5e-3\nlength = 6e-3\ndensity = 1395\n"
    "stiffness = 6000\nrestitution = 0.43\nfriction = 0.46\nrolling_friction = 0.025\n"
    "[species ball]\ndiameter = 2e-3\ndensity = 2500\nstiffness = 6000\nrestitution = 0.6\n"
    "friction = 0.3\n"
    "[wall box]\ntype = box\nmin = 0 0 0\nmax = 0.015 0.015 0.03\nfriction = 0.33\n"
    "[create rods]\ntype = random\nspecies = rod\nregion_min = 0 0 0.003\n"
    "region_max = 0.015 0.015 0.03\ncount = 30\n"
    "[create balls]\ntype = random\nspecies = ball\nregion_min = 0 0 0.003\n"
    "region_max = 0.015 0.015 0.03\ncount = 10\n";

static char beads_scene[4096], gas_scene[4096];

/// The beads' scene with a stiffness, a diameter, a friction, the tube or not, and a tail.
static void beads(char *out, size_t len, double stiffness, double diameter, double friction,
                  int with_tube, const char *tail)
{
    snprintf(out, len, beads_format, diameter, stiffness, friction, with_tube ? tube : "", tail);
}

static const char gas_tail[] = "[gas]\ncells = %s\nzmin = inlet\nzmax = outlet\n"
                               "inlet_velocity = 0.2\n[coupling]\ndrag = beetstra\n";

static void gas_beads(char *out, size_t len, const char *cells)
{
    char tail[256];
    snprintf(tail, sizeof tail, gas_tail, cells);
    beads(out, len, 1000.0, 0.002, 0.4, 1, tail);
}

/// The bytes of a checkpoint.
typedef struct blob {
    unsigned char *data;
    size_t size;
} blob;

/// Touching pairs of the world.
static long touching(const bdl_world *w)
{
    long n = 0;
    for (long k = 0; k < w->neighbor.pair_count; ++k)
        n += w->neighbor.touching[k];
    return n;
}

/// The world of `scene` stepped until `contacts` pairs touch (and a gas has stepped).
static bdl_world *stepped(const char *scene, long contacts)
{
    bdl_world *w = bdl_test_world("%s", scene);
    for (int s = 0; s < 40000 && (touching(w) < contacts || (w->gas && w->gas_steps < 3)); ++s)
        CHECK(bdl_world_step(w) == BDL_OK);
    CHECK(touching(w) >= contacts);
    return w;
}

/// The bytes of the world's checkpoint.
static blob saved(const bdl_world *w)
{
    char path[] = "/tmp/bedlam-hostile-XXXXXX";
    int fd = mkstemp(path);
    CHECK(fd >= 0);
    if (fd >= 0)
        close(fd);
    CHECK(bdl_checkpoint_save(w, path) == BDL_OK);
    blob b = {NULL, 0};
    b.data = (unsigned char *)bdl_read_file(path, &b.size);
    CHECK(b.data != NULL);
    unlink(path);
    return b;
}

/// Loads bytes into a new world of `scene`.
static bdl_result load(const char *scene, const unsigned char *data, size_t size, char *why,
                       size_t len, bdl_checkpoint_info *info)
{
    bdl_world *w = bdl_test_world("%s", scene);
    FILE *f = size > 0 ? fmemopen((void *)data, size, "rb") : tmpfile(); // an empty stream
    why[0] = '\0';
    bdl_result r = BDL_ERR_IO;
    if (f) {
        r = bdl_checkpoint_read(w, f, "test", info, why, len);
        fclose(f);
    }
    bdl_world_destroy(w);
    return r;
}

/// Where the patched fields lie (the layout of docs/checkpoints.md), and where the payload ends.
typedef struct layout {
    size_t dt, time, rng, poured, counts, species, start, partner, touching, history, spring_work,
        wall_prim, wall_spring_work, half_length, gas_every, eps, end;
    int64_t n, pairs, wall_pairs;
} layout;

static layout layout_of(const blob *b, long gas_cells)
{
    layout L = {0};
    int32_t head[11]; // the scene record's counts (the last: solids phases, 24 bytes each)
    memcpy(head, b->data + 32, sizeof head);
    size_t off = 32 + 44 + 24 + (size_t)head[0] * 120 + (size_t)head[1] * 68 +
                 (size_t)head[3] * 56 + (size_t)head[2] * 4 + (size_t)head[10] * 24;
    L.dt = off, L.time = off + 8, L.rng = off + 24, L.poured = off + 56;
    off += 8 + 8 + 8 + 32 + 16 * 8 + 33 * 8 + 4 * 8 + 3 * 8;
    L.counts = off;
    int64_t c[7];
    memcpy(c, b->data + off, sizeof c);
    off += sizeof c;
    const size_t n = (size_t)c[0], np = (size_t)c[2], nw = (size_t)c[3];
    L.n = c[0], L.pairs = c[2], L.wall_pairs = c[3];
    L.species = off + n * 160;
    // wall offsets and angles at the build, angles, the Lees-Edwards slide at the build
    off += n * 168 + n + 16 * 24 + 16 * 8 + 16 * 8 + 8;
    L.start = off, off += (n + 1) * 4;
    L.partner = off, off += np * 4;
    L.touching = off, off += np;
    if (head[7]) // friction: the tangential springs
        L.history = off, off += np * 24;
    const int mindlin = head[7] && head[4] == BDL_LAW_HERTZ;
    if (mindlin) // their work, and the work ended contacts left
        L.spring_work = off, off += np * 8 + 16;
    off += (n + 1) * 4;
    L.wall_prim = off, off += nw * 4 + nw * 24;
    if (mindlin)
        L.wall_spring_work = off, off += nw * 8;
    off += nw * 25;
    if (head[9]) // gas: the particles' gas forces
        off += n * 72;
    if (head[8]) // rods: orientation, axis, angular momentum, inertia, half length, axis at build
        L.half_length = off + n * 104, off += n * 136;
    if (head[9])
        L.gas_every = off, L.eps = off + 136 + 4 * (size_t)gas_cells * 8,
        off += 136 + 6 * (size_t)gas_cells * 8;
    L.end = off;
    return L;
}

/// A copy of b with `size` bytes at `offset` replaced and both checksums recomputed.
static blob patched(const blob *b, size_t offset, const void *bytes, size_t size)
{
    blob p = {malloc(b->size), b->size};
    memcpy(p.data, b->data, b->size);
    memcpy(p.data + offset, bytes, size);
    const uint32_t payload = bdl_crc32(0, p.data + 32, p.size - 32);
    memcpy(p.data + 24, &payload, 4);
    const uint32_t header = bdl_crc32(0, p.data, 28);
    memcpy(p.data + 28, &header, 4);
    return p;
}

/// The patched checkpoint is refused with a reason containing `expect`.
static void refused(const char *scene, const blob *b, size_t offset, const void *bytes, size_t size,
                    const char *expect)
{
    blob p = patched(b, offset, bytes, size);
    char why[1024];
    const bdl_result r = load(scene, p.data, p.size, why, sizeof why, NULL);
    CHECK_MSG(r == BDL_ERR_CHECKPOINT && strstr(why, expect), "expected '%s', got %d: %s", expect,
              (int)r, why);
    free(p.data);
}

/// One byte changed at `count` random positions, then `cuts` truncations: every load refused.
static void damage(const char *scene, const blob *b, int count, int cuts, uint64_t seed)
{
    bdl_rng rng;
    bdl_rng_seed(&rng, seed);
    unsigned char *copy = malloc(b->size);
    int refused_count = 0, checksum = 0, header = 0;
    char why[1024];
    for (int k = 0; k < count; ++k) {
        memcpy(copy, b->data, b->size);
        const size_t at = (size_t)(bdl_rng_next(&rng) % b->size);
        copy[at] ^= (unsigned char)(1 + bdl_rng_next(&rng) % 255);
        const bdl_result r = load(scene, copy, b->size, why, sizeof why, NULL);
        CHECK_MSG(r == BDL_ERR_CHECKPOINT && strstr(why, "checkpoint 'test': "),
                  "byte %zu changed: result %d (%s)", at, (int)r, why);
        refused_count += r == BDL_ERR_CHECKPOINT;
        checksum += strstr(why, "the checksum of its") != NULL;
        header += at < 32;
    }
    int cut_refused = 0;
    for (int k = 0; k < cuts; ++k) {
        const size_t length =
            k < 4 ? (size_t[]){0, 7, 31, b->size - 1}[k] : (size_t)(bdl_rng_next(&rng) % b->size);
        const bdl_result r = load(scene, b->data, length, why, sizeof why, NULL);
        CHECK_MSG(r == BDL_ERR_CHECKPOINT, "cut at %zu: result %d (%s)", length, (int)r, why);
        cut_refused += r == BDL_ERR_CHECKPOINT;
    }
    free(copy);
    printf("  %d of %d changed bytes refused (%d in the header, %d by the payload's checksum); "
           "%d of %d truncations refused\n",
           refused_count, count, header, checksum, cut_refused, cuts);
}

static void test_crc(void)
{
    CHECK(bdl_crc32(0, "123456789", 9) == 0xCBF43926u); // the CRC-32 check value
    CHECK(bdl_crc32(bdl_crc32(0, "1234", 4), "56789", 5) == 0xCBF43926u);
    CHECK(bdl_crc32(0, "", 0) == 0);
}

/// Indices, counts, flags and numbers patched with valid checksums: each refused by its check.
static void test_patches(const char *scene, const blob *b)
{
    const layout L = layout_of(b, 0);
    CHECK_MSG(L.end == b->size, "layout ends at %zu, the file at %zu", L.end, b->size);
    CHECK(L.pairs > 20 && L.wall_pairs > 0);
    const int32_t far = (int32_t)L.n + 99999, zero32 = 0, big = 1 << 30, prim = 100000, seven = 7;
    char expect[128];
    snprintf(expect, sizeof expect, "pair 5 refers to particle %d of %lld", (int)far,
             (long long)L.n);
    refused(scene, b, L.partner + 5 * 4, &far, 4, expect);
    refused(scene, b, L.partner, &zero32, 4, "a pair is listed with its lower particle");
    refused(scene, b, L.start + 4 * (size_t)(L.n / 2), &big, 4, "before they start");
    refused(scene, b, L.start, &seven, 4, "the pairs of particle 0 start at 7");
    refused(scene, b, L.wall_prim, &prim, 4, "wall contact 0 refers to wall surface 100000 of");
    refused(scene, b, L.species + 4 * 3, &seven, 4, "particle 3 is of species 7; the scene has 1");
    const unsigned char two = 2;
    refused(scene, b, L.touching + 1, &two, 1, "pair 1 has a contact flag of 2");
    const double nan = NAN, zero = 0.0, negative = -1.0, inf = INFINITY;
    refused(scene, b, L.history + 24 * 2, &nan, 8, "tangential spring that is not finite");
    refused(scene, b, L.dt, &zero, 8, "its time step is 0 s (must be finite and > 0)");
    refused(scene, b, L.dt, &negative, 8, "its time step is -1 s");
    refused(scene, b, L.dt, &nan, 8, "its time step is nan s");
    refused(scene, b, L.dt, &inf, 8, "its time step is inf s");
    const double tiny = 1e-300, huge_dt = 1e3;
    refused(scene, b, L.dt, &tiny, 8, "its time step is 1e-300 s, not within a factor 1e+06");
    refused(scene, b, L.dt, &huge_dt, 8, "its time step is 1000 s, not within a factor 1e+06");
    refused(scene, b, L.time, &nan, 8, "its time is nan s");
    refused(scene, b, L.time, &negative, 8, "its time is -1 s");
    const long minus5 = -5;
    refused(scene, b, L.poured + 8, &minus5, 8, "creator 1 has poured -5 particles");
    const uint64_t no_state[4] = {0, 0, 0, 0};
    refused(scene, b, L.rng, no_state, sizeof no_state, "random generator's state is all zero");
    const int64_t fewer = L.pairs - 1, minus1 = -1, many = (int64_t)1 << 30, huge = INT64_MAX;
    refused(scene, b, L.counts + 16, &fewer, 8, "take"); // arrays of another size
    refused(scene, b, L.counts, &minus1, 8, "counts are out of range");
    refused(scene, b, L.counts, &huge, 8, "counts are out of range");
    refused(scene, b, L.counts + 16, &many, 8, "1073741824 pairs");
    refused(scene, b, L.counts + 8, &minus1, 8, "next particle id");
    refused(scene, b, L.counts + 40, &minus1, 8, "neighbour lists were built for -1 particles");
    refused(scene, b, L.counts + 48, &minus1, 8, "version -1");
    const int32_t species = 3;
    refused(scene, b, 32, &species, 4, "does not match the scene: 3 species in the checkpoint, 1");
    const uint32_t version = 6;
    refused(scene, b, 8, &version, 4, "header of version 6");
    const uint64_t payload = b->size; // 32 more than the file holds
    refused(scene, b, 16, &payload, 8, "is truncated: its header announces");
    refused(scene, b, 7, "5", 1, "another version of bedlam (checkpoint format '5'");
    refused(scene, b, 0, "GARBAGE!", 8, "is not a bedlam checkpoint");
    // A position (particle 2's x) that is not finite, or far outside the domain.
    const size_t pos = L.counts + 56 + 2 * 24;
    refused(scene, b, pos, &nan, 8, "particle 2 (id");
    const double far_x = 1e200;
    refused(scene, b, pos, &far_x, 8, "is at (1e+200, ");
}

/// The gas's and the rods' own fields.
static void test_gas_and_rod_patches(const blob *gas, long cells, const blob *rods)
{
    const layout G = layout_of(gas, cells), R = layout_of(rods, 0);
    CHECK_MSG(G.end == gas->size, "gas layout ends at %zu, the file at %zu", G.end, gas->size);
    CHECK_MSG(R.end == rods->size, "rod layout ends at %zu, the file at %zu", R.end, rods->size);
    const long zero_steps = 0, later = 1L << 40;
    const double zero = 0.0, above = 1.5, negative = -1e-3, nan = NAN;
    refused(gas_scene, gas, G.gas_every, &zero_steps, 8, "gas step of 0 particle steps");
    refused(gas_scene, gas, G.gas_every + 8, &later, 8, "gas schedule is out of range");
    const int32_t raised = 2; // after the step, the next, the steps taken and the stable step
    refused(gas_scene, gas, G.gas_every + 32, &raised, 4, "inflow-raised flag 2");
    refused(gas_scene, gas, G.eps + 8 * 17, &zero, 8, "voidage in cell 17");
    refused(gas_scene, gas, G.eps + 8 * 3, &above, 8, "must be in (0, 1]");
    refused(gas_scene, gas, G.eps - 8 * 5, &nan, 8, "gas pressure in cell");
    refused(rods_scene, rods, R.half_length + 8 * 4, &negative, 8, "a half length");
}

/// A scene whose layout differs refuses the checkpoint and says what differs; one whose
/// stiffness rose 100-fold takes it, steps with its own time step, and lists the change.
static void test_scenes(const blob *b, const bdl_world *written)
{
    char scene[4096], why[1024];
    struct {
        double stiffness, diameter, friction;
        int tube;
        const char *expect;
    } refuse[] = {
        {1000, 0.0025, 0.4, 1, "species 'bead': diameter 0.002 m in the checkpoint, 0.0025 m"},
        {1000, 0.002, 0.0, 1,
         "sliding friction (tangential history): some in the checkpoint, "
         "none in the scene"},
        {1000, 0.002, 0.4, 0, "2 walls in the checkpoint, 1 in the scene"},
    };
    for (size_t k = 0; k < sizeof refuse / sizeof refuse[0]; ++k) {
        beads(scene, sizeof scene, refuse[k].stiffness, refuse[k].diameter, refuse[k].friction,
              refuse[k].tube, "");
        const bdl_result r = load(scene, b->data, b->size, why, sizeof why, NULL);
        CHECK_MSG(r == BDL_ERR_CHECKPOINT && strstr(why, "does not match the scene") &&
                      strstr(why, refuse[k].expect),
                  "expected '%s': %s", refuse[k].expect, why);
    }
    CHECK(load(gas_scene, b->data, b->size, why, sizeof why, NULL) == BDL_ERR_CHECKPOINT &&
          strstr(why, "a gas: none in the checkpoint, some in the scene"));

    beads(scene, sizeof scene, 100000.0, 0.002, 0.4, 1, "");
    bdl_world *w = bdl_test_world("%s", scene);
    const double scene_dt = w->dt;
    bdl_checkpoint_info info;
    FILE *f = fmemopen(b->data, b->size, "rb");
    CHECK(f && bdl_checkpoint_read(w, f, "test", &info, why, sizeof why) == BDL_OK);
    if (f)
        fclose(f);
    CHECK_MSG(strstr(info.changes, "species 'bead': stiffness 1000 N/m in the checkpoint, "
                                   "100000 N/m in the scene") != NULL,
              "changes: %s", info.changes);
    CHECK(info.dt == written->dt && w->dt == scene_dt);
    CHECK_CLOSE(info.dt / scene_dt, 10.0, 1e-9); // contact time / 10: the saved step 10 x too big
    // The saved step is 2.5 times the scene's stable limit, dt_refuse = 0.2 of the contact time.
    CHECK_CLOSE(info.dt / (w->scene.guards.dt_refuse * w->contact_time), 2.5, 1e-9);
    printf("  stiffness x 100: checkpoint's dt %g s = %.3g x the scene's limit; resumed with "
           "the scene's %g s\n",
           info.dt, info.dt / (w->scene.guards.dt_refuse * w->contact_time), w->dt);
    const double t0 = w->time;
    for (int s = 0; s < 200; ++s)
        CHECK(bdl_world_step(w) == BDL_OK);
    CHECK_CLOSE(w->time - t0, 200 * scene_dt, 1e-9);
    bdl_world_destroy(w);
}

/// Hertz-Mindlin springs keep their work: a checkpoint of the beads with the Hertz law loads,
/// and one whose spring work is not finite is refused.
static void test_mindlin(void)
{
    char linear[4096], scene[4096];
    beads(linear, sizeof linear, 1000.0, 0.002, 0.4, 1, "");
    char *law = strstr(linear, "law = linear"), *kn = strstr(linear, "stiffness = 1000");
    CHECK(law && kn && law < kn);
    if (!law || !kn || kn < law)
        return;
    *law = *kn = '\0'; // the scene in three pieces around the two keys, set anew
    snprintf(scene, sizeof scene, "%slaw = hertz%syoungs_modulus = 1e7%s", linear,
             law + strlen("law = linear"), kn + strlen("stiffness = 1000"));
    bdl_world *w = stepped(scene, 30);
    blob b = saved(w);
    const layout L = layout_of(&b, 0);
    printf("Hertz-Mindlin beads: %zu bytes, %ld touching pairs\n", b.size, touching(w));
    CHECK_MSG(L.end == b.size, "Mindlin layout ends at %zu, the file at %zu", L.end, b.size);
    char why[1024];
    CHECK_MSG(load(scene, b.data, b.size, why, sizeof why, NULL) == BDL_OK, "%s", why);
    const double nan = NAN;
    long k = 0; // a touching pair's spring
    while (k < L.pairs && !w->neighbor.touching[k])
        ++k;
    refused(scene, &b, L.spring_work + 8 * (size_t)k, &nan, 8,
            "tangential spring that is not finite (its displacement or its stored work)");
    refused(scene, &b, L.wall_spring_work, &nan, 8, "wall contact 0 has a contact flag");
    bdl_world_destroy(w);
    free(b.data);
}

int main(void)
{
    test_crc();
    beads(beads_scene, sizeof beads_scene, 1000.0, 0.002, 0.4, 1, "");
    gas_beads(gas_scene, sizeof gas_scene, "4 4 8");
    bdl_world *bw = stepped(beads_scene, 30), *gw = stepped(gas_scene, 10),
              *rw = stepped(rods_scene, 10);
    blob b = saved(bw), g = saved(gw), r = saved(rw);
    printf("checkpoints: beads %zu bytes (%ld particles, %ld touching pairs, %ld poured), gas %zu "
           "bytes, rods %zu bytes\n",
           b.size, bw->particles.count, touching(bw), bw->poured[1], g.size, r.size);
    CHECK(bw->poured[1] > 0);
    // The file holds no stray bytes: a second save of the same world is the same file.
    blob again = saved(bw);
    CHECK(again.size == b.size && memcmp(again.data, b.data, b.size) == 0);
    // Each checkpoint loads back into its own scene.
    char why[1024];
    CHECK_MSG(load(beads_scene, b.data, b.size, why, sizeof why, NULL) == BDL_OK, "%s", why);
    CHECK_MSG(load(gas_scene, g.data, g.size, why, sizeof why, NULL) == BDL_OK, "%s", why);
    CHECK_MSG(load(rods_scene, r.data, r.size, why, sizeof why, NULL) == BDL_OK, "%s", why);
    printf("beads:\n");
    damage(beads_scene, &b, 1000, 100, 1);
    printf("gas:\n");
    damage(gas_scene, &g, 100, 20, 2);
    printf("rods:\n");
    damage(rods_scene, &r, 100, 20, 3);
    test_patches(beads_scene, &b);
    test_gas_and_rod_patches(&g, gw->gas->grid.size, &r);
    test_scenes(&b, bw);
    test_mindlin();
    char other_grid[4096];
    gas_beads(other_grid, sizeof other_grid, "4 4 6");
    CHECK(load(other_grid, g.data, g.size, why, sizeof why, NULL) == BDL_ERR_CHECKPOINT &&
          strstr(why, "gas grid 4 x 4 x 8 cells in the checkpoint, 4 x 4 x 6 in the scene"));
    bdl_world_destroy(bw);
    bdl_world_destroy(gw);
    bdl_world_destroy(rw);
    free(b.data);
    free(again.data);
    free(g.data);
    free(r.data);
    return bdl_test_summary("test_checkpoint_hostile");
}
