// bedlam bench dem — particle-steps per second and bytes per particle of a settled dense bed.
//
// The bed (docs/performance.md): frictional Hertz-Mindlin spheres (d = 1 mm, 2500 kg/m^3,
// E = 10 MPa, nu = 0.25, e = 0.5, mu = 0.5) on a floor, periodic in x and y. The box is as wide as
// it takes for the settled bed to be `height` diameters deep whatever the particle count, so every
// size has the same packing (that is what makes the 10^3..10^6 scaling series comparable). The
// spheres are placed at random (solids fraction 0.33), fall and compact under 5 g with light
// background damping until their kinetic energy has died down, are unloaded to 1 g under strong
// damping, held, and relaxed without damping; then the steps are timed. Timings are reported,
// never asserted.
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app/app.h"
#include "core/timer.h"
#include "core/file.h"
#include "output/checkpoint.h"
#include "world/world.h"

static const char bench_usage[] =
    "usage: bedlam bench dem [options]\n"
    "       bedlam bench render --help\n"
    "       bedlam bench coupled --help\n"
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
    "  --skin X          neighbour-list skin as a fraction of the diameter (default: the scene\n"
    "                    default, 0.1)\n"
    "  --csv FILE        append the rows to FILE\n"
    "  --bed-dir DIR     keep settled beds in DIR as checkpoints and start from them when they\n"
    "                    exist (same size, depth and skin): repeated timings skip the settling\n"
    "  --quiet           no settling progress\n";

// The protocol (docs/performance.md, "The bed").
#define BED_D           1e-3 ///< diameter [m]
#define BED_PHI         0.6  ///< solids fraction assumed for the settled bed (sizes the box)
#define BED_FILL_PHI    0.33 ///< solids fraction of the random fill
#define BED_G           9.81 ///< [m/s^2]
#define BED_COMPACT_G   5.0  ///< gravity while falling and compacting [g]
#define BED_FALL_DAMP   50.0 ///< background damping while falling [1/s]
#define BED_UNLOAD_DAMP 1000.0
#define BED_HOLD_DAMP   200.0
#define BED_SETTLE_DT   0.05 ///< time step while settling [contact times at 1 m/s]
#define BED_RUN_DT      0.02 ///< time step of the timed steps [contact times at 1 m/s]
#define BED_SETTLED_KE  3e-3 ///< fall ends when KE per particle < this * m g d (at 5 g)
#define BED_FALL_MIN    1000
#define BED_FALL_MAX    40000
#define BED_UNLOAD      2000 ///< steps from 5 g to 1 g
#define BED_HOLD1       1000 ///< steps at 1 g with BED_UNLOAD_DAMP
#define BED_HOLD2       2000 ///< steps at 1 g with BED_HOLD_DAMP
#define BED_RELAX       1000 ///< undamped steps at the timed time step

typedef struct bench_opts {
    long particles;
    long steps; ///< 0: from the particle count
    int repeat;
    int threads[16], thread_count;
    int scaling, quiet;
    double height, skin;
    const char *csv;
    const char *bed_dir; ///< settled-bed cache (NULL: none)
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
    const bdl_particles *p = &w->particles;
    const bdl_neighbor *nb = &w->neighbor;
    double most = 0.0;
    for (long i = 0; i < p->count; ++i)
        for (int32_t k = nb->start[i]; k < nb->start[i + 1]; ++k) {
            int32_t j = nb->partner[k];
            double gap = bdl_v3_len(bdl_neighbor_delta(nb, p->pos[i], p->pos[j])) - p->radius[i] -
                         p->radius[j];
            most = fmax(most, -gap);
        }
    return most;
}

static int steps(bdl_world *w, long count)
{
    for (long s = 0; s < count; ++s)
        if (bdl_world_step(w) != BDL_OK)
            return 0;
    return 1;
}

/// Brings a freshly filled bed to rest at 1 g (the protocol at the top of the file).
static int settle(bdl_world *w, long n, const bench_opts *o, double tc, double mgd)
{
    // Fall and compact at 5 g until the kinetic energy has died down.
    long fall = 0;
    int ok = 1;
    while (ok && fall < BED_FALL_MAX) {
        ok = steps(w, 250);
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
    for (long s = 0; ok && s < BED_UNLOAD; ++s) {
        double g = BED_COMPACT_G + (1.0 - BED_COMPACT_G) * (double)(s + 1) / BED_UNLOAD;
        w->scene.gravity = bdl_v3(0.0, 0.0, -g * BED_G);
        ok = bdl_world_step(w) == BDL_OK;
    }
    ok = ok && steps(w, BED_HOLD1);
    w->background_damping[0] = BED_HOLD_DAMP;
    ok = ok && steps(w, BED_HOLD2);
    w->background_damping[0] = 0.0;
    w->dt = BED_RUN_DT * tc;
    w->contact_time_dt_ratio = w->dt / tc;
    ok = ok && steps(w, BED_RELAX);
    if (!ok)
        fprintf(stderr, "bench: a settling step failed\n");
    return ok;
}

/// A settled, dense bed of n spheres (see the top of the file).
static bdl_world *make_bed(long n, const bench_opts *o, bed_info *info)
{
    double t0 = bdl_wall_seconds();
    double d = BED_D;
    double solid = (double)n * 3.14159265358979323846 / 6.0 * d * d * d;
    double side = sqrt(solid / BED_PHI / (o->height * d));
    // The fill region's height gives the fill solids fraction in the volume the centres can
    // reach (the region less a radius at each side), which matters for small beds.
    double fill =
        o->height * d * BED_PHI / BED_FILL_PHI * (side * side) / ((side - d) * (side - d)) + d;
    char skin[64] = "";
    if (o->skin > 0.0)
        snprintf(skin, sizeof skin, "skin = %.17g\n", o->skin);
    char text[4096];
    snprintf(text, sizeof text,
             "[run]\nend_time = 1\ngravity = 0 0 %.17g\nseed = 3\n"
             "[domain]\nmin = 0 0 0\nmax = %.17g %.17g %.17g\nperiodic = x y\n"
             "[contact]\nlaw = hertz\n%s"
             "[species glass]\ndiameter = %.17g\ndensity = 2500\nyoungs_modulus = 1e7\n"
             "poisson_ratio = 0.25\nrestitution = 0.5\nfriction = 0.5\nbackground_damping = %g\n"
             "[wall floor]\ntype = plane\npoint = 0 0 0\nnormal = 0 0 1\n"
             "[create bed]\ntype = random\nspecies = glass\nregion_min = 0 0 0\n"
             "region_max = %.17g %.17g %.17g\ncount = %ld\n",
             -BED_COMPACT_G * BED_G, side, side, fill + 4.0 * d, skin, d, BED_FALL_DAMP, side, side,
             fill, n);
    bdl_scene *scene = calloc(1, sizeof *scene);
    bdl_scene_error err;
    bdl_world *w = NULL;
    if (scene && bdl_scene_load_string(text, "bench-dem", NULL, 0, scene, &err) == BDL_OK) {
        if (bdl_world_create(scene, &w, &err) != BDL_OK) {
            fprintf(stderr, "bench: %s\n", err.message);
            w = NULL;
        }
    } else if (scene) {
        fprintf(stderr, "bench: %s\n", err.message);
    }
    free(scene);
    if (!w)
        return NULL;
    // The time step is a fixed fraction of the contact time at 1 m/s (not of the world's
    // reference speed, which grows with the box): the same at every size.
    double tc = bdl_world_min_contact_time(w, 1.0, NULL, 0);
    w->contact_time = tc;
    w->dt = BED_SETTLE_DT * tc;
    double m = 1.0 / w->particles.inv_mass[0];
    double mgd = m * BED_G * d * (double)w->particles.count;
    char cached[1024] = "";
    if (o->bed_dir)
        snprintf(cached, sizeof cached, "%s/bed-%ld-h%g-s%g.chk", o->bed_dir, n, o->height,
                 o->skin);
    char why[256];
    FILE *exists = cached[0] ? fopen(cached, "rb") : NULL;
    int loaded = 0;
    if (exists) {
        fclose(exists);
        loaded = bdl_checkpoint_load(w, cached, why, sizeof why) == BDL_OK;
        if (!loaded)
            fprintf(stderr, "bench: settling again: %s\n", why);
    }
    if (loaded) {
        w->scene.gravity = bdl_v3(0.0, 0.0, -BED_G);
        w->background_damping[0] = 0.0;
        if (!o->quiet)
            printf("  settled bed loaded from %s\n", cached);
    } else if (!settle(w, n, o, tc, mgd)) {
        bdl_world_destroy(w);
        return NULL;
    }
    if (cached[0] && !loaded && bdl_checkpoint_save(w, cached) != BDL_OK)
        fprintf(stderr, "bench: cannot save the settled bed to %s (timing goes on)\n", cached);

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
    return w;
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
        double t0 = bdl_wall_seconds();
        steps(w, count);
        seconds[r] = bdl_wall_seconds() - t0;
    }
    qsort(seconds, (size_t)repeat, sizeof seconds[0], compare_double);
    bench_result res;
    long n = w->particles.count;
    res.particles = n;
    res.threads = threads;
    res.rate = (double)n * (double)count / seconds[0];
    res.rate_median = (double)n * (double)count / seconds[repeat / 2];
    res.bytes = (double)(bdl_particles_bytes(&w->particles) + bdl_neighbor_bytes(&w->neighbor) +
                         bdl_force_work_bytes(&w->force_work) + w->coordination_capacity) /
                (double)n;
    res.contacts = mean_coordination(w);
    res.pairs = (double)w->neighbor.pair_count / (double)n;
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

bdl_result bdl_cmd_bench(int argc, char **argv)
{
    bench_opts o = {50000, 0, 3, {1, 2}, 2, 0, 0, 12.0, 0.0, NULL, NULL};
    int k = 1;
    if (k < argc && strcmp(argv[k], "render") == 0)
        return bdl_bench_render(argc - 1, argv + 1);
    if (k < argc && strcmp(argv[k], "coupled") == 0)
        return bdl_bench_coupled(argc - 1, argv + 1);
    if (k < argc && strcmp(argv[k], "dem") == 0)
        ++k;
    for (; k < argc; ++k) {
        const char *a = argv[k], *v = k + 1 < argc ? argv[k + 1] : NULL;
        if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
            fputs(bench_usage, stdout);
            return BDL_OK;
        } else if (strcmp(a, "--scaling") == 0) {
            o.scaling = 1;
        } else if (strcmp(a, "--quiet") == 0) {
            o.quiet = 1;
        } else if (v && strcmp(a, "--particles") == 0) {
            o.particles = atol(v), ++k;
        } else if (v && strcmp(a, "--steps") == 0) {
            o.steps = atol(v), ++k;
        } else if (v && strcmp(a, "--repeat") == 0) {
            o.repeat = atoi(v), ++k;
        } else if (v && strcmp(a, "--height") == 0) {
            o.height = atof(v), ++k;
        } else if (v && strcmp(a, "--skin") == 0) {
            o.skin = atof(v), ++k;
        } else if (v && strcmp(a, "--bed-dir") == 0) {
            o.bed_dir = v, ++k;
        } else if (v && strcmp(a, "--csv") == 0) {
            o.csv = v, ++k;
        } else if (v && strcmp(a, "--threads") == 0) {
            o.thread_count = 0;
            char buf[128];
            snprintf(buf, sizeof buf, "%s", v);
            for (char *t = strtok(buf, ","); t && o.thread_count < 16; t = strtok(NULL, ","))
                o.threads[o.thread_count++] = atoi(t);
            ++k;
        } else {
            fprintf(stderr, "error: unknown bench option '%s'\n\n%s", a, bench_usage);
            return BDL_ERR_ARGS;
        }
    }
    int bad_threads = o.thread_count < 1;
    for (int t = 0; t < o.thread_count; ++t)
        bad_threads |= o.threads[t] < 1;
    if (o.particles < 100 || o.steps < 0 || o.repeat < 1 || bad_threads || !(o.height >= 2.0) ||
        o.skin < 0.0 || o.skin > 1.0) {
        fprintf(stderr, "error: bench needs --particles >= 100, --steps >= 1, --repeat >= 1, "
                        "--threads >= 1, --height >= 2, 0 < --skin <= 1\n");
        return BDL_ERR_ARGS;
    }
    if (o.bed_dir && bdl_mkdir_p(o.bed_dir) != BDL_OK) {
        fprintf(stderr, "error: --bed-dir: cannot create the folder '%s'\n", o.bed_dir);
        return BDL_ERR_OUTPUT_DIR;
    }
    FILE *csv = o.csv ? fopen(o.csv, "a") : NULL;
    if (o.csv && !csv) {
        fprintf(stderr, "error: cannot open '%s'\n", o.csv);
        return BDL_ERR_OUTPUT_DIR;
    }
    printf("bedlam bench dem: settled frictional Hertz-Mindlin bed, %d repetitions\n", o.repeat);
    bed_info bed;
    bdl_world *w = make_bed(o.particles, &o, &bed);
    if (!w)
        return BDL_ERR_NOMEM;
    report_locality(w);
    long count = timed_steps(&o, w->particles.count);
    printf("timed: %ld steps per repetition\n", count);
    report_header();
    double base = 0.0, base_median = 0.0;
    for (int t = 0; t < o.thread_count; ++t) {
        bench_result r = time_steps(w, o.threads[t], count, o.repeat);
        report(&r, &bed, csv);
        if (t == 0) {
            base = r.rate;
            base_median = r.rate_median;
        } else {
            printf("  speed-up %d vs %d threads: %.2fx (medians: %.2fx)\n", o.threads[t],
                   o.threads[0], r.rate / base, r.rate_median / base_median);
        }
    }
    bdl_world_destroy(w);
    if (o.scaling) {
        printf("scaling on one thread (settling on all threads):\n");
        for (long n = 1000; n <= 1000000; n *= 10) {
            omp_set_num_threads(omp_get_num_procs());
            bdl_world *ws = make_bed(n, &o, &bed);
            if (!ws)
                return BDL_ERR_NOMEM;
            report_header();
            bench_result r = time_steps(ws, 1, timed_steps(&o, n), o.repeat);
            report(&r, &bed, csv);
            bdl_world_destroy(ws);
        }
    }
    if (csv)
        fclose(csv);
    return BDL_OK;
}
