// bedlam bench dem — particle-steps per second and bytes per particle of a settled dense bed.
//
// The bed: frictional Hertz-Mindlin spheres (d = 1 mm, 2500 kg/m^3, E = 10 MPa, e = 0.5,
// mu = 0.5) on a floor, periodic in x and y, filled at random and compacted (make_bed) before
// timing. Timings are reported, never asserted.
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app/app.h"
#include "core/timer.h"
#include "sim/world.h"

static const char bench_usage[] =
    "usage: bedlam bench dem [options]\n"
    "\n"
    "Times a settled, dense bed of frictional Hertz-Mindlin spheres (periodic in x and y, on a\n"
    "floor) and reports particle-steps per second and bytes per particle, for each thread count.\n"
    "\n"
    "options:\n"
    "  --particles N     bed size (default 50000)\n"
    "  --settle S        compaction steps before timing (default 8000)\n"
    "  --steps S         timed steps (default 500)\n"
    "  --threads LIST    comma-separated thread counts (default 1,2)\n"
    "  --scaling         also time 1e3, 1e4, 1e5 and 1e6 particles on one thread\n"
    "  --csv FILE        append the rows to FILE\n";

typedef struct bench_result {
    long particles;
    int threads;
    double rate;     ///< particle-steps/s
    double bytes;    ///< per particle
    double contacts; ///< mean coordination
    double pairs;    ///< listed pairs per particle
    double rebuilds; ///< neighbour list rebuilds per 100 steps
} bench_result;

/// A settled, dense bed of n spheres: random fill at solids fraction 0.3 in a periodic square
/// box, compacted under 100 g with background damping 300 1/s for `settle` steps, unloaded to 1 g
/// over another `settle` steps, held at 1 g, still damped, for `settle` steps, then relaxed without
/// damping for settle/8 steps.
static bdl_world *make_bed(long n, int settle)
{
    double d = 1e-3;
    double solid = (double)n * 3.14159265358979323846 / 6.0 * d * d * d;
    // Base about twice as wide as the settled bed is high.
    double side = cbrt(2.0 * solid / 0.6) * 1.0;
    if (side < 6.0 * d)
        side = 6.0 * d;
    double fill = solid / 0.3 / (side * side);
    char text[4096];
    snprintf(text, sizeof text,
             "[run]\nend_time = 1\ndt_fraction = 0.02\ngravity = 0 0 -981\nseed = 3\n"
             "[domain]\nmin = 0 0 0\nmax = %.17g %.17g %.17g\nperiodic = x y\n"
             "[contact]\nlaw = hertz\n"
             "[species glass]\ndiameter = %.17g\ndensity = 2500\nyoungs_modulus = 1e7\n"
             "poisson_ratio = 0.25\nrestitution = 0.5\nfriction = 0.5\nbackground_damping = 300\n"
             "[wall floor]\ntype = plane\npoint = 0 0 0\nnormal = 0 0 1\n"
             "[create bed]\ntype = random\nspecies = glass\nregion_min = 0 0 0\n"
             "region_max = %.17g %.17g %.17g\ncount = %ld\n",
             side, side, 1.5 * fill + 4.0 * d, d, side, side, fill + 2.0 * d, n);
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
    for (int s = 0; s < settle; ++s)
        bdl_world_step(w);
    // Unload slowly, still damped, so the stored elastic energy does not throw the bed up.
    for (int s = 0; s < settle; ++s) {
        w->scene.gravity = bdl_v3(0.0, 0.0, -981.0 + (981.0 - 9.81) * (s + 1.0) / settle);
        bdl_world_step(w);
    }
    for (int s = 0; s < settle; ++s) // damped rest at 1 g
        bdl_world_step(w);
    w->background_damping[0] = 0.0;
    for (int s = 0; s < settle / 8; ++s)
        bdl_world_step(w);
    long contacts = 0;
    for (long i = 0; i < w->particles.count; ++i)
        contacts += w->coordination[i];
    printf("bed: %ld particles, dt = %.3g s, compacted for %.3g s, mean coordination %.2f\n",
           w->particles.count, w->dt, w->time, (double)contacts / (double)w->particles.count);
    return w;
}

static bench_result time_steps(bdl_world *w, int threads, int steps)
{
    omp_set_num_threads(threads);
    bdl_world_step(w); // warm up the thread pool
    long builds = w->neighbor.builds;
    double t0 = bdl_wall_seconds();
    for (int s = 0; s < steps; ++s)
        bdl_world_step(w);
    double dt = bdl_wall_seconds() - t0;
    bench_result r;
    long n = w->particles.count;
    r.particles = n;
    r.threads = threads;
    r.rate = (double)n * steps / dt;
    r.bytes = (double)(bdl_particles_bytes(&w->particles) + bdl_neighbor_bytes(&w->neighbor) +
                       bdl_force_work_bytes(&w->force_work) + w->coordination_capacity) /
              (double)n;
    long contacts = 0;
    for (long i = 0; i < n; ++i)
        contacts += w->coordination[i];
    r.contacts = (double)contacts / (double)n;
    r.pairs = (double)w->neighbor.pair_count / (double)n;
    r.rebuilds = 100.0 * (double)(w->neighbor.builds - builds) / steps;
    return r;
}

static void report(const bench_result *r, FILE *csv)
{
    printf("%10ld %8d %14.4g %12.1f %12.2f %14.2f %12.1f %10.2f\n", r->particles, r->threads,
           r->rate, 1e9 / r->rate * r->threads, r->contacts, r->pairs, r->bytes, r->rebuilds);
    if (csv)
        fprintf(csv, "%ld,%d,%.6g,%.2f,%.3f,%.3f,%.1f,%.2f\n", r->particles, r->threads, r->rate,
                1e9 / r->rate * r->threads, r->contacts, r->pairs, r->bytes, r->rebuilds);
}

int bdl_cmd_bench(int argc, char **argv)
{
    long particles = 50000;
    int settle = 8000, steps = 500, scaling = 0;
    int thread_list[16] = {1, 2}, thread_count = 2;
    const char *csv_path = NULL;
    int k = 1;
    if (k < argc && strcmp(argv[k], "dem") == 0)
        ++k;
    for (; k < argc; ++k) {
        const char *a = argv[k], *v = k + 1 < argc ? argv[k + 1] : NULL;
        if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
            fputs(bench_usage, stdout);
            return 0;
        } else if (strcmp(a, "--scaling") == 0) {
            scaling = 1;
        } else if (v && strcmp(a, "--particles") == 0) {
            particles = atol(v), ++k;
        } else if (v && strcmp(a, "--settle") == 0) {
            settle = atoi(v), ++k;
        } else if (v && strcmp(a, "--steps") == 0) {
            steps = atoi(v), ++k;
        } else if (v && strcmp(a, "--csv") == 0) {
            csv_path = v, ++k;
        } else if (v && strcmp(a, "--threads") == 0) {
            thread_count = 0;
            char buf[128];
            snprintf(buf, sizeof buf, "%s", v);
            for (char *t = strtok(buf, ","); t && thread_count < 16; t = strtok(NULL, ","))
                thread_list[thread_count++] = atoi(t);
            ++k;
        } else {
            fprintf(stderr, "error: unknown bench option '%s'\n\n%s", a, bench_usage);
            return 2;
        }
    }
    if (particles < 100 || steps < 1 || settle < 0 || thread_count < 1) {
        fprintf(stderr, "error: bench needs --particles >= 100, --steps >= 1, --settle >= 0\n");
        return 2;
    }
    FILE *csv = csv_path ? fopen(csv_path, "a") : NULL;
    printf("bedlam bench dem: settled frictional Hertz-Mindlin bed, %d timed steps\n", steps);
    printf("%10s %8s %14s %12s %12s %14s %12s %10s\n", "particles", "threads", "p-steps/s",
           "ns/p-step*thr", "coordination", "pairs/particle", "bytes/part", "builds/100");
    bdl_world *w = make_bed(particles, settle);
    if (!w)
        return 1;
    double base = 0.0;
    for (int t = 0; t < thread_count; ++t) {
        bench_result r = time_steps(w, thread_list[t], steps);
        report(&r, csv);
        if (t == 0)
            base = r.rate;
        else
            printf("  speed-up %d vs %d threads: %.2fx\n", thread_list[t], thread_list[0],
                   r.rate / base);
    }
    bdl_world_destroy(w);
    if (scaling) {
        printf("scaling on one thread:\n");
        for (long n = 1000; n <= 1000000; n *= 10) {
            bdl_world *ws = make_bed(n, settle);
            if (!ws)
                return 1;
            bench_result r = time_steps(ws, 1, n >= 1000000 ? steps / 2 + 1 : steps);
            report(&r, csv);
            bdl_world_destroy(ws);
        }
    }
    if (csv)
        fclose(csv);
    return 0;
}
