// bedlam bench dem — particle-steps per second and bytes per particle of a settled dense bed.
//
// With --shape rod the particles are rods of the same diameter and four diameters long (aspect
// ratio 4, the thesis's rods), placed with random axes; everything else is as for spheres.
//
// The bed (docs/performance.md): frictional Hertz-Mindlin spheres (d = 1 mm, 2500 kg/m^3,
// E = 10 MPa, nu = 0.25, e = 0.5, mu = 0.5 or --friction) on a floor, periodic in x and y. The box
// is as wide as it takes for the settled bed to be `height` diameters deep whatever the particle
// count, so every size has the same packing (that is what makes the 10^3..10^6 scaling series
// comparable). The spheres are placed at random (solids fraction 0.33), fall and compact under
// 5 g with light background damping until their kinetic energy has died down, are unloaded to 1 g
// under strong damping, held, and relaxed without damping; then the steps are timed. Timings are
// reported, never asserted.
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app/app.h"
#include "app/options.h"
#include "core/comm.h"
#include "core/log.h"
#include "core/timer.h"
#include "core/file.h"
#include "dem/material.h"
#include "dist/exchange.h"
#include "output/checkpoint.h"
#include "world/world.h"

static const char bench_usage[] =
    "usage: bedlam bench dem [options]\n"
    "       bedlam bench render --help\n"
    "       bedlam bench coupled --help\n"
    "       bedlam bench parcels --help\n"
    "\n"
    "Times a settled, dense bed of frictional Hertz-Mindlin spheres (periodic in x and y, on a\n"
    "floor) and reports particle-steps per second, nanoseconds per particle-step, contacts and\n"
    "listed pairs per particle and bytes per particle, for each thread count.\n"
    "\n"
    "options:\n"
    "  --particles N     bed size (default 50000)\n"
    "  --steps S         timed steps per repetition (default: 5e7 particle-steps / N, >= 20)\n"
    "  --repeat R        timed repetitions per thread count; the fastest is reported (default 3)\n"
    "  --threads LIST    comma-separated thread counts (default 1,2)\n"
    "  --scaling         also time 1e3, 1e4, 1e5 and 1e6 particles on one thread (the 1e6 bed\n"
    "                    takes about 20 minutes to settle on two cores)\n"
    "  --height H        settled bed depth in diameters (default 12)\n"
    "  --shape S         sphere (default) or rod: rods of aspect ratio 4 (length 4 d)\n"
    "  --skin X          neighbour-list skin as a fraction of the diameter (default: the scene\n"
    "                    default, 0.1)\n"
    "  --friction MU     sliding friction of the particles and the floor (default 0.5): less\n"
    "                    friction settles a denser bed with more contacts per particle\n"
    "  --csv FILE        append the rows to FILE\n"
    "  --bed-dir DIR     keep settled beds in DIR as checkpoints and start from them when they\n"
    "                    exist (same size, depth and skin): repeated timings skip the settling\n"
    "  --quiet           no settling progress\n";

// The protocol (docs/performance.md, "The bed").
#define BED_D            1e-3 ///< diameter [m]
#define BED_PHI          0.6  ///< solids fraction assumed for the settled bed (sizes the box)
#define BED_FILL_PHI     0.33 ///< solids fraction of the random fill
#define BED_G            9.81 ///< [m/s^2]
#define BED_COMPACT_G    5.0  ///< gravity while falling and compacting [g]
#define BED_FALL_DAMP    50.0 ///< background damping while falling [1/s]
#define BED_UNLOAD_DAMP  1000.0
#define BED_HOLD_DAMP    200.0
#define BED_SETTLE_DT    0.05 ///< time step while settling [contact times at 1 m/s]
#define BED_RUN_DT       0.02 ///< time step of the timed steps [contact times at 1 m/s]
#define BED_SETTLED_KE   3e-3 ///< fall ends when KE per particle < this * m g d (at 5 g)
#define BED_FALL_MIN     1000
#define BED_FALL_MAX     40000
#define BED_UNLOAD       2000 ///< steps from 5 g to 1 g
#define BED_HOLD1        1000 ///< steps at 1 g with BED_UNLOAD_DAMP
#define BED_HOLD2        2000 ///< steps at 1 g with BED_HOLD_DAMP
#define BED_RELAX        1000 ///< undamped steps at the timed time step
#define BED_ROD_ASPECT   4.0  ///< --shape rod: length / diameter
#define BED_ROD_FILL_PHI 0.2  ///< --shape rod: solids fraction of the random fill (rods jam sooner)

typedef struct bench_opts {
    long particles;
    long steps; ///< 0: from the particle count
    int repeat;
    int threads[16], thread_count;
    int scaling, quiet;
    double height, skin;
    double friction; ///< sliding friction coefficient of the bed
    const char *csv;
    const char *bed_dir; ///< settled-bed cache (NULL: none)
    const char *shape;   ///< "sphere" or "rod"
    int rods;            ///< shape is rod
} bench_opts;

typedef struct bed_info {
    double setup_seconds; ///< creation and settling, wall clock
    long settle_steps;
    double dt;           ///< time step of the timed steps [s]
    double ke;           ///< kinetic energy per particle / (m g d) after settling
    double max_overlap;  ///< largest particle-particle overlap / d
    double coordination; ///< contacts per particle (each contact counted for both)
    double depth;        ///< height of the highest particle centre / d
} bed_info;

typedef struct bench_result {
    long particles;
    int threads;
    double rate;        ///< particle-steps/s, fastest repetition
    double rate_median; ///< particle-steps/s, median repetition
    double bytes;       ///< per particle
    double contacts;    ///< mean coordination
    double pairs;       ///< listed (half-list) pairs per particle
    double rebuilds;    ///< neighbour list rebuilds per 1000 steps
} bench_result;

static double kinetic_energy(const bdl_world *w)
{
    const bdl_particles *p = &w->particles;
    double e = 0.0;
    for (long i = 0; i < p->count; ++i)
        e += 0.5 * bdl_v3_len2(p->vel[i]) / p->inv_mass[i];
    return e;
}

static double mean_coordination(const bdl_world *w)
{
    long c = 0;
    for (long i = 0; i < w->particles.count; ++i)
        c += w->coordination[i];
    return w->particles.count > 0 ? (double)c / (double)w->particles.count : 0.0;
}

static double max_overlap(const bdl_world *w)
{
    const bdl_neighbor *nb = &w->neighbor;
    double most = 0.0;
    for (long i = 0; i < w->particles.count; ++i)
        for (int32_t k = nb->start[i]; k < nb->start[i + 1]; ++k) {
            bdl_world_contact c;
            if (bdl_world_pair_contact(w, i, nb->partner[k], &c))
                most = fmax(most, c.overlap);
        }
    return most;
}

static bdl_result steps(bdl_world *w, long count)
{
    bdl_result r = BDL_OK;
    for (long s = 0; r == BDL_OK && s < count; ++s)
        r = bdl_world_step(w);
    if (r != BDL_OK)
        bdl_error("%s", w->failure);
    return r;
}

/// Brings a freshly filled bed to rest at 1 g (the protocol at the top of the file).
static bdl_result settle(bdl_world *w, long n, const bench_opts *o, double tc, double mgd)
{
    // Fall and compact at 5 g until the kinetic energy has died down.
    long fall = 0;
    bdl_result r = BDL_OK;
    while (r == BDL_OK && fall < BED_FALL_MAX) {
        r = steps(w, 250);
        fall += 250;
        double ke = kinetic_energy(w) / (BED_COMPACT_G * mgd);
        if (!o->quiet)
            printf("  settling %ld: fall %ld steps, KE/(m g d) %.2e, coordination %.2f\n", n, fall,
                   ke, mean_coordination(w));
        if (fall >= BED_FALL_MIN && ke < BED_SETTLED_KE)
            break;
    }
    // Unload to 1 g slowly under strong damping, so that the stored elastic energy does not
    // throw the bed up; hold; relax without damping at the timed time step.
    w->background_damping[0] = BED_UNLOAD_DAMP;
    for (long s = 0; r == BDL_OK && s < BED_UNLOAD; ++s) {
        double g = BED_COMPACT_G + (1.0 - BED_COMPACT_G) * (double)(s + 1) / BED_UNLOAD;
        w->scene.gravity = bdl_v3(0.0, 0.0, -g * BED_G);
        r = bdl_world_step(w);
    }
    r = r == BDL_OK ? steps(w, BED_HOLD1) : r;
    w->background_damping[0] = BED_HOLD_DAMP;
    r = r == BDL_OK ? steps(w, BED_HOLD2) : r;
    w->background_damping[0] = 0.0;
    w->dt = BED_RUN_DT * tc;
    w->contact_time_dt_ratio = w->dt / tc;
    r = r == BDL_OK ? steps(w, BED_RELAX) : r;
    if (r != BDL_OK)
        fprintf(stderr, "bench: a settling step failed\n");
    return r;
}

/// The scene of the bed of n spheres: a box `side` wide, filled to `fill` (see the top of the
/// file).
static void bed_scene(long n, const bench_opts *o, char *text, size_t len, double *side)
{
    const double d = BED_D, pi = 3.14159265358979323846;
    const double solid = (double)n * (o->rods ? pi / 4.0 * d * d * (BED_ROD_ASPECT - 1.0 / 3.0) * d
                                              : pi / 6.0 * d * d * d);
    *side = sqrt(solid / BED_PHI / (o->height * d));
    // The fill region's height gives the fill solids fraction in the volume the centres can
    // reach (the region less a radius at each side), which matters for small beds.
    const double fill_phi = o->rods ? BED_ROD_FILL_PHI : BED_FILL_PHI;
    const double fill =
        o->height * d * BED_PHI / fill_phi * (*side * *side) / ((*side - d) * (*side - d)) + d;
    char skin[64] = "", shape[64] = "";
    if (o->skin > 0.0)
        snprintf(skin, sizeof skin, "skin = %.17g\n", o->skin);
    if (o->rods)
        snprintf(shape, sizeof shape, "shape = rod\nlength = %.17g\n", BED_ROD_ASPECT * d);
    snprintf(text, len,
             "[run]\nend_time = 1\ngravity = 0 0 %.17g\nseed = 3\n"
             "[domain]\nmin = 0 0 0\nmax = %.17g %.17g %.17g\nperiodic = x y\n"
             "[contact]\nlaw = %s\n%s"
             "[species glass]\n%sdiameter = %.17g\ndensity = 2500\nyoungs_modulus = 1e7\n"
             "poisson_ratio = 0.25\nrestitution = 0.5\nfriction = %.17g\nbackground_damping = %g\n"
             "[wall floor]\ntype = plane\npoint = 0 0 0\nnormal = 0 0 1\n"
             "[create bed]\ntype = random\nspecies = glass\nregion_min = 0 0 0\n"
             "region_max = %.17g %.17g %.17g\ncount = %ld\n",
             -BED_COMPACT_G * BED_G, *side, *side, fill + 4.0 * d,
             bdl_normal_law_names[BDL_LAW_HERTZ], skin, shape, d, o->friction, BED_FALL_DAMP, *side,
             *side, fill, n);
}

/// The world of a scene text; prints why there is none.
static bdl_result bed_world(const char *text, bdl_world **w)
{
    bdl_scene *scene = calloc(1, sizeof *scene);
    if (!scene)
        return BDL_ERR_NOMEM;
    bdl_scene_error err;
    bdl_result r = bdl_scene_load_string(text, "bench-dem", NULL, 0, scene, &err);
    if (r == BDL_OK) // settled whole on every rank (or loaded), divided afterwards (make_bed)
        r = bdl_world_create_whole(scene, w, &err);
    if (r != BDL_OK)
        fprintf(stderr, "bench: %s\n", r == BDL_ERR_SCENE ? err.message : bdl_result_text(r));
    free(scene);
    return r;
}

/// Loads the settled bed from the --bed-dir checkpoint when there is one, else settles it and
/// keeps it there. A failed load leaves the world's state undefined, so the world is built again
/// from the scene `text` before it settles. mgd: m g d summed over the particles.
static bdl_result settle_or_load(bdl_world **wp, const char *text, long n, const bench_opts *o,
                                 double tc, double mgd)
{
    bdl_world *w = *wp;
    char cached[1024] = "", why[256], friction[64] = ""; // the default friction is not named
    if (o->friction != 0.5)
        snprintf(friction, sizeof friction, "-mu%g", o->friction);
    if (o->bed_dir)
        snprintf(cached, sizeof cached, "%s/bed-%ld-h%g-s%g%s%s.chk", o->bed_dir, n, o->height,
                 o->skin, o->rods ? "-rod" : "", friction);
    FILE *exists = cached[0] ? fopen(cached, "rb") : NULL;
    int loaded = 0;
    if (exists) {
        fclose(exists);
        loaded = bdl_checkpoint_load(w, cached, NULL, why, sizeof why) == BDL_OK;
        if (!loaded) {
            fprintf(stderr, "bench: settling again: %s\n", why);
            bdl_world_destroy(w);
            *wp = w = NULL;
            const bdl_result r = bed_world(text, wp);
            if (r != BDL_OK)
                return r == BDL_ERR_SCENE ? BDL_ERR_NOMEM : r;
            w = *wp;
            w->contact_time = tc;
            w->dt = BED_SETTLE_DT * tc;
        }
    }
    if (loaded) { // as settle() leaves it: 1 g, no damping, the timed time step
        w->scene.gravity = bdl_v3(0.0, 0.0, -BED_G);
        w->background_damping[0] = 0.0;
        w->dt = BED_RUN_DT * tc;
        w->contact_time_dt_ratio = w->dt / tc;
        if (!o->quiet)
            printf("  settled bed loaded from %s\n", cached);
        return BDL_OK;
    }
    bdl_result r = settle(w, n, o, tc, mgd);
    if (r == BDL_OK && cached[0] && bdl_comm_rank() == 0 &&
        bdl_checkpoint_save(w, cached) != BDL_OK)
        fprintf(stderr, "bench: cannot save the settled bed to %s (timing goes on)\n", cached);
    return r;
}

static void describe_bed(const bdl_world *w, double side, double mgd, double t0, bed_info *info)
{
    const double d = BED_D;
    info->setup_seconds = bdl_wall_seconds() - t0;
    info->settle_steps = w->step;
    info->dt = w->dt;
    info->ke = kinetic_energy(w) / mgd;
    info->max_overlap = max_overlap(w) / d;
    info->coordination = mean_coordination(w);
    double top = 0.0;
    for (long i = 0; i < w->particles.count; ++i)
        top = fmax(top, w->particles.pos[i].z);
    info->depth = top / d;
    printf("bed: %ld particles, %.0f x %.0f d base, top centre at %.1f d, coordination %.2f, "
           "largest overlap %.2f%% of d, KE %.1e m g d per particle, dt %.3g s; set up in %ld "
           "steps, %.1f s\n",
           w->particles.count, side / d, side / d, info->depth, info->coordination,
           100.0 * info->max_overlap, info->ke, w->dt, info->settle_steps, info->setup_seconds);
}

/// A settled, dense bed of n spheres (see the top of the file).
static bdl_result make_bed(long n, const bench_opts *o, bed_info *info, bdl_world **out)
{
    const double t0 = bdl_wall_seconds();
    char text[4096];
    double side;
    bed_scene(n, o, text, sizeof text, &side);
    bdl_world *w = NULL;
    bdl_result r = bed_world(text, &w);
    if (r == BDL_ERR_SCENE) // exit 1 for a bed the bench cannot build, as for any failure of it
        return BDL_ERR_NOMEM;
    if (r != BDL_OK)
        return r;
    // The time step is a fixed fraction of the contact time at 1 m/s (not of the world's
    // reference speed, which grows with the box): the same at every size.
    const double tc = bdl_world_min_contact_time(w, 1.0, NULL, 0);
    w->contact_time = tc;
    w->dt = BED_SETTLE_DT * tc;
    const double m = 1.0 / w->particles.inv_mass[0];
    const double mgd = m * BED_G * BED_D * (double)w->particles.count;
    if ((r = settle_or_load(&w, text, n, o, tc, mgd)) != BDL_OK) {
        bdl_world_destroy(w);
        return r;
    }
    describe_bed(w, side, mgd, t0, info);
    if (bdl_comm_size() > 1) { // under mpirun: each rank keeps its part of the settled bed
        bdl_scene_error err;
        if ((r = bdl_world_dist_init(w, &err)) != BDL_OK) {
            fprintf(stderr, "bench: %s\n", r == BDL_ERR_SCENE ? err.message : bdl_result_text(r));
            bdl_world_destroy(w);
            return r;
        }
        double most = (double)w->particles.count, total = most;
        most = bdl_comm_max(most);
        bdl_comm_sum(&total, 1);
        const bdl_decomp *d = bdl_dist_decomp(w->dist);
        printf("ranks: %d, boxes %d x %d x %d; particles per rank at most %.0f, on average %.1f "
               "(max/mean %.3f)\n",
               bdl_comm_size(), d->dims[0], d->dims[1], d->dims[2], most, total / bdl_comm_size(),
               most * bdl_comm_size() / total);
    }
    *out = w;
    return BDL_OK;
}

/// How far apart in memory the partners of the listed pairs are: the share of pairs whose
/// partner lies more than 64, 1024 and 16384 places after the particle (the particles are in
/// Morton order of their cells; far partners are the ones the caches miss).
static void report_locality(const bdl_world *w)
{
    const bdl_neighbor *nb = &w->neighbor;
    long pairs = 0, far[3] = {0, 0, 0};
    for (long i = 0; i < w->particles.count; ++i)
        for (int32_t k = nb->start[i]; k < nb->start[i + 1]; ++k) {
            long gap = (long)nb->partner[k] - i;
            ++pairs;
            far[0] += gap > 64;
            far[1] += gap > 1024;
            far[2] += gap > 16384;
        }
    if (pairs > 0)
        printf("partners more than 64 / 1024 / 16384 places away: %.1f / %.1f / %.1f %% of the "
               "pairs\n",
               100.0 * (double)far[0] / (double)pairs, 100.0 * (double)far[1] / (double)pairs,
               100.0 * (double)far[2] / (double)pairs);
}

static int compare_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : (x > y ? 1 : 0);
}

static bench_result time_steps(bdl_world *w, int threads, long count, int repeat)
{
    omp_set_num_threads(threads);
    steps(w, 20); // warm up the thread pool and the caches
    long builds = w->neighbor.builds;
    double seconds[64];
    if (repeat > 64)
        repeat = 64;
    for (int r = 0; r < repeat; ++r) {
        bdl_comm_barrier(); // under mpirun: the slowest rank's time
        double t0 = bdl_wall_seconds();
        steps(w, count);
        seconds[r] = bdl_comm_max(bdl_wall_seconds() - t0);
    }
    qsort(seconds, (size_t)repeat, sizeof seconds[0], compare_double);
    bench_result res;
    // Under mpirun the figures of every rank together (per particle: the sums over them).
    double sums[4] = {(double)w->particles.count, (double)w->neighbor.pair_count, 0.0,
                      (double)(bdl_particles_bytes(&w->particles) +
                               bdl_neighbor_bytes(&w->neighbor) +
                               bdl_force_work_bytes(&w->force_work) + w->coordination_capacity)};
    for (long i = 0; i < w->particles.count; ++i)
        sums[2] += w->coordination[i];
    bdl_comm_sum(sums, 4);
    long n = (long)sums[0];
    res.particles = n;
    res.threads = threads;
    res.rate = (double)n * (double)count / seconds[0];
    res.rate_median = (double)n * (double)count / seconds[repeat / 2];
    res.bytes = sums[3] / (double)n;
    res.contacts = sums[2] / (double)n;
    res.pairs = sums[1] / (double)n;
    res.rebuilds = 1000.0 * (double)(w->neighbor.builds - builds) / ((double)count * repeat);
    return res;
}

static void report_header(void)
{
    printf("%10s %7s %12s %12s %10s %11s %8s %8s %9s %10s\n", "particles", "threads", "p-steps/s",
           "(median)", "ns/p-step", "ns x thr", "coord.", "pairs", "bytes/p", "builds/1k");
}

static void report(const bench_result *r, const bed_info *bed, FILE *csv)
{
    double ns = 1e9 / r->rate;
    printf("%10ld %7d %12.4g %12.4g %10.1f %11.1f %8.2f %8.2f %9.1f %10.2f\n", r->particles,
           r->threads, r->rate, r->rate_median, ns, ns * r->threads, r->contacts, r->pairs,
           r->bytes, r->rebuilds);
    if (csv)
        fprintf(csv, "%ld,%d,%.6g,%.6g,%.2f,%.2f,%.3f,%.3f,%.1f,%.3f,%.1f\n", r->particles,
                r->threads, r->rate, r->rate_median, ns, ns * r->threads, r->contacts, r->pairs,
                r->bytes, r->rebuilds, bed->setup_seconds);
}

static long timed_steps(const bench_opts *o, long n)
{
    if (o->steps > 0)
        return o->steps;
    long s = (long)(5e7 / (double)n);
    return s < 20 ? 20 : s;
}

static const bdl_option bench_options[] = {
    {"--scaling", BDL_OPTION_SET, offsetof(bench_opts, scaling)},
    {"--quiet", BDL_OPTION_SET, offsetof(bench_opts, quiet)},
    {"--particles", BDL_OPTION_LONG, offsetof(bench_opts, particles)},
    {"--steps", BDL_OPTION_LONG, offsetof(bench_opts, steps)},
    {"--repeat", BDL_OPTION_INT, offsetof(bench_opts, repeat)},
    {"--height", BDL_OPTION_NUMBER, offsetof(bench_opts, height)},
    {"--skin", BDL_OPTION_NUMBER, offsetof(bench_opts, skin)},
    {"--friction", BDL_OPTION_NUMBER, offsetof(bench_opts, friction)},
    {"--bed-dir", BDL_OPTION_TEXT, offsetof(bench_opts, bed_dir)},
    {"--csv", BDL_OPTION_TEXT, offsetof(bench_opts, csv)},
    {"--shape", BDL_OPTION_TEXT, offsetof(bench_opts, shape)},
};

/// --threads 1,2,4: at most 16 counts.
static void parse_thread_list(const char *list, bench_opts *o)
{
    o->thread_count = 0;
    char buf[128];
    snprintf(buf, sizeof buf, "%s", list);
    for (char *t = strtok(buf, ","); t && o->thread_count < 16; t = strtok(NULL, ","))
        o->threads[o->thread_count++] = atoi(t);
}

/// --threads LIST, the one option the table cannot hold.
static int take_threads(void *opts, int argc, char **argv, int i)
{
    if (i + 1 < argc && strcmp(argv[i], "--threads") == 0) {
        parse_thread_list(argv[i + 1], opts);
        return 2;
    }
    fprintf(stderr, "error: unknown bench option '%s'\n\n%s", argv[i], bench_usage);
    return 0;
}

/// Reads argv[k..] (after the case name) into *o; *help when --help was printed.
static bdl_result parse_bench(int argc, char **argv, int k, bench_opts *o, int *help)
{
    static const bdl_option_parser parser = {bench_options, BDL_OPTION_COUNT(bench_options),
                                             bench_usage, 0, take_threads};
    bdl_result r = bdl_option_parse(&parser, argc, argv, k, o, help);
    if (r != BDL_OK || *help)
        return r;
    int bad_threads = o->thread_count < 1;
    for (int t = 0; t < o->thread_count; ++t)
        bad_threads |= o->threads[t] < 1;
    const int shape_ok = strcmp(o->shape, "sphere") == 0 || strcmp(o->shape, "rod") == 0;
    if (o->particles < 100 || o->steps < 0 || o->repeat < 1 || bad_threads || !(o->height >= 2.0) ||
        o->skin < 0.0 || o->skin > 1.0 || !(o->friction >= 0.0 && o->friction <= 2.0) ||
        !shape_ok) {
        fprintf(stderr,
                "error: bench needs --particles >= 100, --steps >= 1, --repeat >= 1, "
                "--threads >= 1, --height >= 2, 0 < --skin <= 1, 0 <= --friction <= 2, --shape "
                "sphere or rod\n");
        return BDL_ERR_ARGS;
    }
    o->rods = strcmp(o->shape, "rod") == 0;
    return BDL_OK;
}

/// The bed of --particles timed on each thread count, with the speed-up against the first.
static bdl_result time_threads(const bench_opts *o, FILE *csv)
{
    bed_info bed;
    bdl_world *w = NULL;
    bdl_result r = make_bed(o->particles, o, &bed, &w);
    if (r != BDL_OK)
        return r;
    report_locality(w);
    long count = timed_steps(o, w->particles.count);
    printf("timed: %ld steps per repetition\n", count);
    report_header();
    double base = 0.0, base_median = 0.0;
    for (int t = 0; t < o->thread_count; ++t) {
        bench_result res = time_steps(w, o->threads[t], count, o->repeat);
        report(&res, &bed, csv);
        if (t == 0) {
            base = res.rate;
            base_median = res.rate_median;
        } else {
            printf("  speed-up %d vs %d threads: %.2fx (medians: %.2fx)\n", o->threads[t],
                   o->threads[0], res.rate / base, res.rate_median / base_median);
        }
    }
    bdl_world_destroy(w);
    return BDL_OK;
}

/// Beds of 10^3 to 10^6 particles, each timed on one thread.
static bdl_result time_scaling(const bench_opts *o, FILE *csv)
{
    printf("scaling on one thread (settling on all threads):\n");
    for (long n = 1000; n <= 1000000; n *= 10) {
        omp_set_num_threads(omp_get_num_procs());
        bed_info bed;
        bdl_world *w = NULL;
        bdl_result r = make_bed(n, o, &bed, &w);
        if (r != BDL_OK)
            return r;
        report_header();
        bench_result res = time_steps(w, 1, timed_steps(o, n), o->repeat);
        report(&res, &bed, csv);
        bdl_world_destroy(w);
    }
    return BDL_OK;
}

bdl_result bdl_cmd_bench(int argc, char **argv)
{
    bench_opts o = {50000, 0, 3, {1, 2}, 2, 0, 0, 12.0, 0.0, 0.5, NULL, NULL, "sphere", 0};
    int k = 1, help;
    if (bdl_comm_size() > 1 && k < argc && argv[k][0] != '-' && strcmp(argv[k], "dem") != 0) {
        fprintf(stderr, "error: under mpirun only bench dem divides its work between ranks\n");
        return BDL_ERR_ARGS;
    }
    if (k < argc && strcmp(argv[k], "render") == 0)
        return bdl_bench_render(argc - 1, argv + 1);
    if (k < argc && strcmp(argv[k], "coupled") == 0)
        return bdl_bench_coupled(argc - 1, argv + 1);
    if (k < argc && strcmp(argv[k], "parcels") == 0)
        return bdl_bench_parcels(argc - 1, argv + 1);
    if (k < argc && strcmp(argv[k], "dem") == 0)
        ++k;
    bdl_result r = parse_bench(argc, argv, k, &o, &help);
    if (r != BDL_OK || help)
        return r;
    if (o.bed_dir && bdl_mkdir_p(o.bed_dir) != BDL_OK) {
        fprintf(stderr, "error: --bed-dir: cannot create the folder '%s'\n", o.bed_dir);
        return BDL_ERR_OUTPUT_DIR;
    }
    // Under mpirun the first rank writes the rows; every rank learns whether it could.
    FILE *csv = o.csv && bdl_comm_rank() == 0 ? fopen(o.csv, "a") : NULL;
    if (bdl_comm_broadcast_int(o.csv && bdl_comm_rank() == 0 && !csv, 0)) {
        fprintf(stderr, "error: cannot open '%s'\n", o.csv);
        return BDL_ERR_OUTPUT_DIR;
    }
    printf("bedlam bench dem: settled frictional Hertz-Mindlin bed of %ss, %d repetitions\n",
           o.shape, o.repeat);
    r = time_threads(&o, csv);
    if (r == BDL_OK && o.scaling)
        r = time_scaling(&o, csv);
    if (csv)
        fclose(csv);
    return r;
}
