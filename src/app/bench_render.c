// bedlam bench render — frames per second of the headless renderer, and what a frame dump costs
// the solver.
//
// Frames: a dense bed of spheres in a cube (random centres at the number density of a packed
// bed), seen from the default iso camera, lit, coloured by speed, overlay on, drawn and read back
// at the frame size, for 10^4, 10^5 and 10^6 particles. A frame is counted once its pixels are in
// memory (what a frame dump needs); PNG encoding runs on its own thread in a run and is timed
// separately. With --rods every particle is a rod (tip to tip three diameters, a random axis) at
// the same number density, drawn as capsules.
//
// Solver cost: a falling bed is stepped for a fixed number of steps without frames, with frames
// every k steps, and without frames again, each time from the same initial state; the ratio of
// the step rates, measured in one run, is the cost. Two dumps: 30 frames per simulated second
// (k = 1/(30 dt), a video at real-time speed), and 30 frames per second of wall time (k from the
// measured step rate), which asks more of the renderer than it can give on a small machine, so
// the solver waits for free frame slots and the cost shows the renderer's throughput.
#include <math.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app/app.h"
#include "app/options.h"
#include "dem/material.h"
#include "core/rng.h"
#include "core/timer.h"
#include "io/png.h"
#include "render/context.h"
#include "render/frames.h"
#include "render/renderer.h"
#include "run/loop.h"
#include "run/run.h"

static const char usage[] =
    "usage: bedlam bench render [options]\n"
    "\n"
    "Frames per second of the headless renderer at 1280x720 (draw + read back; PNG encoding\n"
    "timed apart) for 1e4, 1e5 and 1e6 spheres, and the solver's particle-steps/s with and\n"
    "without a 30 fps frame dump: 30 frames per simulated second (a real-time video), and\n"
    "30 frames per wall-clock second (the renderer's limit).\n"
    "\n"
    "options:\n"
    "  --gl BACKEND     egl (default: auto) or osmesa\n"
    "  --size WxH       frame size (default 1280x720)\n"
    "  --samples N      multisampling (default 4)\n"
    "  --max N          largest particle count of the frame series (default 1000000)\n"
    "  --video N        particles of the bed dumped at 30 frames per simulated second, the\n"
    "                   rate of a real-time video (default 2000; 0 skips it)\n"
    "  --solver N       particles of the bed dumped at 30 frames per wall-clock second, as\n"
    "                   fast as the renderer takes them (default 20000; 0 skips it)\n"
    "  --threads N      solver threads for the solver-cost part (default: all cores)\n"
    "  --rods           the frame series with rods (capsules three diameters long, random axes)\n";

typedef struct render_opts {
    bdl_gl_backend backend;
    int width, height, samples, threads, rods;
    long max, solver, video;
} render_opts;

static const char bed_scene[] =
    "[run]\nend_time = 100\n"
    "[domain]\nmin = 0 0 0\nmax = %.17g %.17g %.17g\n"
    "[contact]\nlaw = %s\n"
    "[species glass]\ndiameter = 0.001\ndensity = 2500\nyoungs_modulus = 1e7\n"
    "poisson_ratio = 0.25\nrestitution = 0.5\nfriction = 0.5\n"
    "[wall floor]\ntype = box\nmin = 0 0 0\nmax = %.17g %.17g %.17g\n"
    "[create bed]\ntype = random\nspecies = glass\nregion_min = 0 0 0\n"
    "region_max = %.17g %.17g %.17g\ncount = %ld\n"
    "[output]\nframe_width = %d\nframe_height = %d\nframe_samples = %d\n";

static int load_scene(bdl_scene *scene, long n, const render_opts *o)
{
    // A cube holding n spheres at solids fraction 0.3, twice as tall.
    double side = cbrt((double)n * BDL_PI / 6.0 * 1e-9 / 0.3);
    char text[2048];
    snprintf(text, sizeof text, bed_scene, side, side, 2.0 * side,
             bdl_normal_law_names[BDL_LAW_HERTZ], side, side, 2.0 * side, side, side, side, n,
             o->width, o->height, o->samples);
    bdl_scene_error err;
    if (bdl_scene_load_string(text, "bench-render", NULL, 0, scene, &err) != BDL_OK) {
        fprintf(stderr, "bench render: %s\n", err.message);
        return 0;
    }
    return 1;
}

/// A snapshot of n spheres of the scene's diameter with centres uniformly at random in a cube at
/// the number density of a packed bed (solids fraction 0.6): as opaque as a settled bed, which
/// is what the culling and the fill rate see (overlaps do not matter to the renderer). Rods get
/// axes uniformly distributed over the directions.
static int bed_snapshot(bdl_snapshot *s, const bdl_scene *scene, long n, int rods)
{
    if (rods && !bdl_snapshot_reserve_axis(s, n))
        return 0;
    s->pos = malloc((size_t)n * 3 * sizeof(float));
    s->vel = malloc((size_t)n * 3 * sizeof(float));
    s->radius = malloc((size_t)n * sizeof(float));
    s->coordination = malloc((size_t)n);
    s->species = calloc((size_t)n, sizeof(int32_t));
    s->id = malloc((size_t)n * sizeof(uint32_t));
    if (!s->pos || !s->vel || !s->radius || !s->coordination || !s->species || !s->id)
        return 0;
    double d = scene->species[0].diameter;
    double side = cbrt((double)n * BDL_PI / 6.0 * d * d * d / 0.6);
    double x0 = 0.5 * (scene->domain_max.x - side);
    bdl_rng rng;
    bdl_rng_seed(&rng, 7);
    for (long i = 0; i < n; ++i) {
        float *p = &s->pos[3 * i], *v = &s->vel[3 * i];
        p[0] = (float)(x0 + side * bdl_rng_uniform(&rng));
        p[1] = (float)(x0 + side * bdl_rng_uniform(&rng));
        p[2] = (float)(side * bdl_rng_uniform(&rng));
        for (int k = 0; k < 3; ++k)
            v[k] = (float)(bdl_rng_uniform(&rng) - 0.5);
        s->radius[i] = (float)(0.5 * d);
        s->coordination[i] = (uint8_t)(bdl_rng_uniform(&rng) * 7);
        s->id[i] = (uint32_t)i;
        if (rods) {
            double z = 2.0 * bdl_rng_uniform(&rng) - 1.0,
                   phi = 2.0 * BDL_PI * bdl_rng_uniform(&rng);
            double h = d, rho = sqrt(1.0 - z * z); // half shaft: three diameters tip to tip
            s->axis[3 * i] = (float)(h * rho * cos(phi));
            s->axis[3 * i + 1] = (float)(h * rho * sin(phi));
            s->axis[3 * i + 2] = (float)(h * z);
        }
    }
    s->count = s->capacity = n;
    return 1;
}

static void time_frames(const render_opts *o, long n, bdl_scene *scene, uint8_t *rgb)
{
    if (!load_scene(scene, n, o))
        return;
    bdl_snapshot s = {0};
    bdl_renderer *r = NULL;
    char why[1024];
    bdl_renderer_def rd = {.scene = scene,
                           .headless = 1,
                           .width = o->width,
                           .height = o->height,
                           .samples = o->samples};
    if (!bed_snapshot(&s, scene, n, o->rods) ||
        bdl_renderer_create(&rd, &r, why, sizeof why) != BDL_OK) {
        fprintf(stderr, "bench render: %s\n", why);
        bdl_snapshot_free(&s);
        return;
    }
    bdl_view v;
    bdl_view_from_scene(scene, (float)o->width / (float)o->height, &v);
    for (int k = 0; k < 2; ++k) { // warm up: shader compilation, buffer sizes
        bdl_renderer_draw(r, &s, &v, o->width, o->height);
        bdl_renderer_read(r, rgb);
    }
    int frames = 0;
    double t0 = bdl_wall_seconds(), t;
    do {
        bdl_renderer_draw(r, &s, &v, o->width, o->height);
        bdl_renderer_read(r, rgb);
        ++frames;
        t = bdl_wall_seconds() - t0;
    } while (t < 3.0 && frames < 200);
    double encode0 = bdl_wall_seconds();
    bdl_png_write("bench_render_frame.png", rgb, o->width, o->height, 3, 0);
    double encode = bdl_wall_seconds() - encode0;
    printf("%10ld %12.2f %12.1f %14.1f %10ld\n", n, frames / t, 1e3 * t / frames, 1e3 * encode,
           bdl_renderer_drawn(r));
    fflush(stdout);
    bdl_renderer_destroy(r);
    bdl_snapshot_free(&s);
}

typedef struct dump_state {
    bdl_frames *frames;
    long every, next_index;
} dump_state;

static bdl_result submit_frames(void *user, bdl_world *w)
{
    dump_state *d = user;
    if (d->frames && w->step % d->every == 0)
        return bdl_run_frame(d->frames, w, d->next_index++);
    return BDL_OK;
}

/// Creates the world of `scene` afresh and steps it `steps` times on the solver thread, with
/// frames every `every` steps when `frames` is set, drawing them on this thread. Every
/// measurement starts from the same state, so all of them time the same physics. Returns
/// particle-steps/s, and the world's time step in *dt.
static double solver_rate(const bdl_scene *scene, long steps, int threads, bdl_frames *frames,
                          long every, double *dt)
{
    bdl_world *w = NULL;
    bdl_scene_error err;
    if (bdl_world_create(scene, &w, &err) != BDL_OK) {
        fprintf(stderr, "bench render: %s\n", err.message);
        return 0.0;
    }
    *dt = w->dt;
    dump_state d = {frames, every, 0};
    bdl_loop_def ld = bdl_default_loop_def();
    ld.world = w;
    ld.end_time = 1e30;
    ld.max_steps = steps;
    ld.threads = threads;
    ld.on_step = submit_frames;
    ld.user = &d;
    double t0 = bdl_wall_seconds();
    bdl_loop *loop = bdl_loop_start(&ld);
    if (!loop) {
        bdl_world_destroy(w);
        return 0.0;
    }
    for (;;) {
        double t;
        long step, particles;
        int finished;
        bdl_loop_progress(loop, &t, &step, &particles, &finished);
        if (finished)
            break;
        if (frames)
            bdl_frames_pump(frames, 0.01);
        else
            bdl_sleep(0.01);
    }
    bdl_loop_join(loop);
    bdl_loop_destroy(loop);
    double rate = (double)steps * (double)w->particles.count / (bdl_wall_seconds() - t0);
    bdl_world_destroy(w);
    return rate;
}

/// The frames went to the working folder: removes them.
static void remove_frames(long written)
{
    for (long k = 0; k < written; ++k) {
        char path[64];
        snprintf(path, sizeof path, "frame_%06ld.png", k);
        remove(path);
    }
}

/// Solver speed without frames, with frames every `every` steps, and without frames again (the
/// two frame-less runs bracket the one with frames and show the timing noise). every <= 0 asks
/// for about 30 frames per second of wall time.
static void dump_cost(const render_opts *o, bdl_scene *scene, long n, double sim_fps)
{
    if (!load_scene(scene, n, o))
        return;
    int threads = o->threads > 0 ? o->threads : omp_get_num_procs();
    double dt = 0.0;
    // Size the runs from a short probe: about 10 s each, and at least 8 frames at sim_fps.
    double probe = solver_rate(scene, 300, threads, NULL, 1, &dt) / (double)n; // steps/s
    long every = sim_fps > 0.0 ? lrint(1.0 / (sim_fps * dt)) : lrint(probe / 30.0);
    every = every < 1 ? 1 : every;
    long steps = lrint(10.0 * probe);
    if (sim_fps > 0.0 && steps < 8 * every)
        steps = 8 * every;
    steps = steps < 1000 ? 1000 : steps;
    char why[1024];
    bdl_frames_def fd = {.scene = scene, .folder = ".", .backend = o->backend};
    bdl_frames *frames = NULL;
    if (bdl_frames_open(&fd, &frames, why, sizeof why) != BDL_OK) {
        fprintf(stderr, "bench render: %s\n", why);
        return;
    }
    double base0 = solver_rate(scene, steps, threads, NULL, 1, &dt);
    double with = solver_rate(scene, steps, threads, frames, every, &dt);
    double base1 = solver_rate(scene, steps, threads, NULL, 1, &dt);
    long written = 0;
    bdl_frames_close(frames, &written);
    remove_frames(written);
    double base = 0.5 * (base0 + base1), wall = (double)steps * (double)n / with;
    printf("%-26s %9ld %8d %11.3e %11.3e %8ld %9.2f %7.1f %% (+-%.1f)\n",
           sim_fps > 0.0 ? "30 frames per simulated s" : "30 frames per wall s", n, threads, base,
           with, written, (double)written / wall, 100.0 * (1.0 - with / base),
           50.0 * fabs(base0 - base1) / base);
}

static void solver_cost(const render_opts *o, bdl_scene *scene)
{
    printf("\nsolver particle-steps/s with and without a frame dump (%dx%d, %d samples)\n",
           o->width, o->height, o->samples);
    printf("%-26s %9s %8s %11s %11s %8s %9s %s\n", "dump", "particles", "threads", "no frames",
           "frames", "written", "frames/s", "cost (noise)");
    if (o->video > 0)
        dump_cost(o, scene, o->video, 30.0);
    if (o->solver > 0)
        dump_cost(o, scene, o->solver, 0.0);
}

static const bdl_option render_options[] = {
    {"--samples", BDL_OPTION_INT, offsetof(render_opts, samples)},
    {"--max", BDL_OPTION_LONG, offsetof(render_opts, max)},
    {"--solver", BDL_OPTION_LONG, offsetof(render_opts, solver)},
    {"--video", BDL_OPTION_LONG, offsetof(render_opts, video)},
    {"--threads", BDL_OPTION_INT, offsetof(render_opts, threads)},
    {"--rods", BDL_OPTION_SET, offsetof(render_opts, rods)},
};

/// --gl (not sdl: frames are headless) and --size WxH, which the table cannot hold.
static int take_gl_size(void *opts, int argc, char **argv, int i)
{
    render_opts *o = opts;
    const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
    if (v && strcmp(a, "--gl") == 0 && bdl_gl_backend_parse(v, &o->backend) &&
        o->backend != BDL_GL_SDL)
        return 2;
    if (v && strcmp(a, "--size") == 0 && sscanf(v, "%dx%d", &o->width, &o->height) == 2)
        return 2;
    fprintf(stderr, "error: bench render: bad option '%s'\n\n%s", a, usage);
    return 0;
}

/// Reads the options into *o; *help when --help was printed.
static bdl_result parse_render(int argc, char **argv, render_opts *o, int *help)
{
    static const bdl_option_parser parser = {render_options, BDL_OPTION_COUNT(render_options),
                                             usage, 0, take_gl_size};
    bdl_result r = bdl_option_parse(&parser, argc, argv, 1, o, help);
    if (r != BDL_OK || *help)
        return r;
    if (o->width < 16 || o->height < 16 || o->width > 8192 || o->height > 8192 || o->samples < 0 ||
        o->samples > 16 || o->max < 1 || o->solver < 0 || o->video < 0 || o->threads < 0) {
        fprintf(stderr, "error: bench render: size 16..8192, samples 0..16, --max >= 1\n");
        return BDL_ERR_ARGS;
    }
    return BDL_OK;
}

bdl_result bdl_bench_render(int argc, char **argv)
{
    render_opts o = {BDL_GL_AUTO, 1280, 720, 4, 0, 0, 1000000, 20000, 2000};
    int help;
    bdl_result r = parse_render(argc, argv, &o, &help);
    if (r != BDL_OK || help)
        return r;
    char why[1024];
    bdl_context *ctx = NULL;
    bdl_context_def cd = {.backend = o.backend, .width = o.width, .height = o.height};
    if ((r = bdl_context_create(&cd, &ctx, why, sizeof why)) != BDL_OK) {
        fprintf(stderr, "error: %s\n", why);
        return r;
    }
    bdl_scene *scene = calloc(1, sizeof *scene);
    uint8_t *rgb = malloc((size_t)o.width * (size_t)o.height * 3);
    if (!scene || !rgb) {
        free(scene);
        free(rgb);
        bdl_context_destroy(ctx);
        return BDL_ERR_NOMEM;
    }
    printf("bedlam bench render: %s, %dx%d, %d samples, lit %s coloured by speed\n",
           bdl_gl_backend_name(bdl_context_backend(ctx)), o.width, o.height, o.samples,
           o.rods ? "rods" : "spheres");
    printf("%10s %12s %12s %14s %10s\n", "particles", "frames/s", "ms/frame", "PNG encode ms",
           "drawn");
    for (long n = 10000; n <= o.max; n *= 10)
        time_frames(&o, n, scene, rgb);
    remove("bench_render_frame.png");
    bdl_context_destroy(ctx); // the frame dump makes its own context
    solver_cost(&o, scene);
    free(scene);
    free(rgb);
    return BDL_OK;
}
