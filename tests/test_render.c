// Golden-image tests of the renderer, headless (llvmpipe in CI), on every headless backend that
// works here: a sphere lands on the predicted pixel with the predicted radius (orthographic and
// perspective), with the predicted colour in every colour mode, flat and lit; of two spheres the
// nearer one wins at every pixel they share, also where they intersect; the colour bar and the
// text are there; and a PNG read back equals the frame.
//
// Predictions are made independently of the GL code: pinhole and parallel projection written
// out here, ray-sphere depths per pixel, colours from the colour maps.
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "io/png.h"
#include "render/colormap.h"
#include "render/context.h"
#include "render/renderer.h"

#define W 320
#define H 240

static const char scene_text[] =
    "[run]\nend_time = 1\n"
    "[domain]\nmin = -0.05 -0.05 -0.05\nmax = 0.05 0.05 0.05\n"
    "[species red]\ndiameter = 0.01\ndensity = 1000\nyoungs_modulus = 1e7\nrestitution = 0.5\n"
    "[species blue]\ndiameter = 0.01\ndensity = 1000\nyoungs_modulus = 1e7\nrestitution = 0.5\n";

typedef struct frame {
    bdl_renderer *r;
    uint8_t rgb[W * H * 3];
} frame;

static frame fr;
static bdl_scene scene;

/// A snapshot of up to 4 particles.
typedef struct small_snapshot {
    bdl_snapshot s;
    float pos[12], vel[12], radius[4];
    uint8_t coordination[4];
    int32_t species[4];
    uint32_t id[4];
} small_snapshot;

static void snapshot_init(small_snapshot *ss, int count)
{
    memset(ss, 0, sizeof *ss);
    ss->s.count = ss->s.capacity = count;
    ss->s.pos = ss->pos;
    ss->s.vel = ss->vel;
    ss->s.radius = ss->radius;
    ss->s.coordination = ss->coordination;
    ss->s.species = ss->species;
    ss->s.id = ss->id;
    for (int i = 0; i < count; ++i)
        ss->id[i] = (uint32_t)i;
}

static void base_view(bdl_view *v, int ortho)
{
    memset(v, 0, sizeof *v);
    v->camera.fov = 40.0f;
    v->camera.distance = 0.2f;
    v->camera.ortho = ortho; // yaw 0, pitch 0: looking along +y, x right, z up
    v->color = BDL_COLOR_SPECIES;
    v->background[0] = v->background[1] = v->background[2] = 0.0f;
}

static void draw(const small_snapshot *ss, const bdl_view *v)
{
    bdl_renderer_draw(fr.r, &ss->s, v, W, H);
    CHECK(bdl_renderer_read(fr.r, fr.rgb) == BDL_OK);
}

static const uint8_t *pixel(int x, int y) { return &fr.rgb[3 * ((size_t)y * W + (size_t)x)]; }

static int is_background(int x, int y)
{
    const uint8_t *p = pixel(x, y);
    return p[0] == 0 && p[1] == 0 && p[2] == 0;
}

/// Centroid and equivalent radius of the non-background pixels.
static void blob(double *cx, double *cy, double *radius)
{
    double n = 0, sx = 0, sy = 0;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x)
            if (!is_background(x, y)) {
                n += 1;
                sx += x + 0.5;
                sy += y + 0.5;
            }
    *cx = n > 0 ? sx / n : -1;
    *cy = n > 0 ? sy / n : -1;
    *radius = sqrt(n / BDL_PI);
}

static int close_color(const uint8_t *p, const uint8_t *q, int tol)
{
    return abs(p[0] - q[0]) <= tol && abs(p[1] - q[1]) <= tol && abs(p[2] - q[2]) <= tol;
}

static void test_position_ortho(void)
{
    small_snapshot ss;
    snapshot_init(&ss, 1);
    float x = 0.012f, z = -0.007f, r = 0.01f;
    ss.pos[0] = x;
    ss.pos[2] = z;
    ss.radius[0] = r;
    bdl_view v;
    base_view(&v, 1);
    draw(&ss, &v);
    // Parallel projection: the visible half height is distance tan(fov / 2).
    double half = 0.2 * tan(20.0 * BDL_PI / 180.0), ppm = (H / 2.0) / half;
    double ex = W / 2.0 + x * ppm, ey = H / 2.0 - z * ppm, er = r * ppm;
    double cx, cy, radius;
    blob(&cx, &cy, &radius);
    printf("ortho: centre (%.2f, %.2f) predicted (%.2f, %.2f); radius %.2f predicted %.2f px\n", cx,
           cy, ex, ey, radius, er);
    CHECK(fabs(cx - ex) <= 1.0 && fabs(cy - ey) <= 1.0);
    CHECK(fabs(radius - er) <= 1.0);
    // The widest row spans the diameter.
    int row = (int)ey, left = W, right = -1;
    for (int px = 0; px < W; ++px)
        if (!is_background(px, row)) {
            left = px < left ? px : left;
            right = px;
        }
    CHECK_MSG(fabs((right - left + 1) / 2.0 - er) <= 1.0, "half width %.1f, radius %.2f px",
              (right - left + 1) / 2.0, er);
}

static void test_position_perspective(void)
{
    small_snapshot ss;
    snapshot_init(&ss, 1);
    float r = 0.01f;
    ss.radius[0] = r;
    bdl_view v;
    base_view(&v, 0);
    // On the axis: the silhouette is a circle of radius f tan(asin(r / d)).
    draw(&ss, &v);
    double f = (H / 2.0) / tan(20.0 * BDL_PI / 180.0), d = 0.2;
    double er = f * r / sqrt(d * d - r * r);
    double cx, cy, radius;
    blob(&cx, &cy, &radius);
    printf("perspective, on axis: centre (%.2f, %.2f) radius %.2f predicted %.2f px\n", cx, cy,
           radius, er);
    CHECK(fabs(cx - W / 2.0) <= 1.0 && fabs(cy - H / 2.0) <= 1.0);
    CHECK(fabs(radius - er) <= 1.0);
    // Off the axis: the centre projects through the pinhole; the sphere's image is an ellipse
    // whose centroid lies slightly outward, so check the pixel under the projected centre and
    // the silhouette's extent along x: tangent rays at angles atan(x/d') +- asin(r/|c|).
    float x = 0.03f, z = 0.02f;
    ss.pos[0] = x;
    ss.pos[2] = z;
    draw(&ss, &v);
    double px = W / 2.0 + f * x / d, py = H / 2.0 - f * z / d;
    CHECK(!is_background((int)px, (int)py));
    double dist = sqrt(x * x + d * d + z * z);
    double a = atan2(x, d), s = asin(r / sqrt(x * x + d * d));
    (void)dist;
    int row = (int)(H / 2.0 - f * z / d);
    // In the plane y-x at height z the silhouette's x extent follows from the 2D tangent
    // construction only for z = 0: use the row through the centre with z = 0 instead.
    ss.pos[2] = 0.0f;
    draw(&ss, &v);
    row = H / 2;
    int left = W, right = -1;
    for (int q = 0; q < W; ++q)
        if (!is_background(q, row)) {
            left = q < left ? q : left;
            right = q;
        }
    double el = W / 2.0 + f * tan(a - s), er2 = W / 2.0 + f * tan(a + s);
    printf("perspective, off axis: x extent [%d, %d] predicted [%.2f, %.2f] px\n", left, right + 1,
           el, er2);
    CHECK(fabs(left - el) <= 1.0 && fabs(right + 1 - er2) <= 1.0);
}

/// The pixel at the image centre for a particle at the origin, in each colour mode, flat.
static void test_colors(void)
{
    small_snapshot ss;
    snapshot_init(&ss, 1);
    ss.radius[0] = 0.01f;
    ss.species[0] = 1;
    ss.coordination[0] = 3;
    ss.vel[0] = -1.0f;
    ss.vel[1] = 0.5f;
    ss.vel[2] = 2.0f;
    bdl_view v;
    base_view(&v, 1);
    v.range_fixed = 1;
    for (int mode = 0; mode < BDL_COLOR_MODE_COUNT; ++mode) {
        v.color = (bdl_color_mode)mode;
        float t = 0.0f;
        int div = 0;
        switch (mode) {
        case BDL_COLOR_COORDINATION:
            v.range[0] = 0, v.range[1] = 6, t = 3.0f / 6.0f;
            break;
        case BDL_COLOR_SPEED:
            v.range[0] = 0, v.range[1] = 3, t = sqrtf(1.0f + 0.25f + 4.0f) / 3.0f;
            break;
        case BDL_COLOR_VX:
        case BDL_COLOR_VY:
        case BDL_COLOR_VZ:
            v.range[0] = -4, v.range[1] = 4, t = (ss.vel[mode - BDL_COLOR_VX] + 4.0f) / 8.0f;
            div = 1;
            break;
        case BDL_COLOR_VOIDAGE:
            v.range[0] = 0, v.range[1] = 1, t = -1.0f; // measured below
            break;
        default:
            break;
        }
        draw(&ss, &v);
        float c[3];
        if (mode == BDL_COLOR_SPECIES)
            bdl_category_color(1, c);
        else if (mode == BDL_COLOR_VOIDAGE)
            c[0] = c[1] = c[2] = -1.0f;
        else
            bdl_colormap_eval(div ? BDL_CMAP_DIVERGING : BDL_CMAP_SEQUENTIAL, t, c);
        const uint8_t *p = pixel(W / 2, H / 2);
        if (mode == BDL_COLOR_VOIDAGE) {
            // One 1 cm sphere in cells of 3 cm: the voidage at its centre is high but below 1,
            // and the pixel shows the sequential map somewhere in its upper half.
            float lab[3], pf[3] = {p[0] / 255.0f, p[1] / 255.0f, p[2] / 255.0f};
            bdl_oklab_from_srgb(pf, lab);
            float lo[3], lo_lab[3];
            bdl_colormap_eval(BDL_CMAP_SEQUENTIAL, 0.5f, lo);
            bdl_oklab_from_srgb(lo, lo_lab);
            CHECK_MSG(lab[0] > lo_lab[0], "voidage colour lightness %.3f", lab[0]);
            continue;
        }
        uint8_t e[3] = {(uint8_t)lrintf(255 * c[0]), (uint8_t)lrintf(255 * c[1]),
                        (uint8_t)lrintf(255 * c[2])};
        CHECK_MSG(close_color(p, e, 1), "mode %s: pixel %d %d %d, predicted %d %d %d",
                  bdl_color_mode_names[mode], p[0], p[1], p[2], e[0], e[1], e[2]);
    }
    // Lit: the normal at the centre of pixel (W/2, H/2), half a pixel right of and below the
    // sphere's centre; the view direction is +z (parallel projection).
    v.color = BDL_COLOR_SPECIES;
    v.lighting = 1;
    draw(&ss, &v);
    double ppm = (H / 2.0) / (0.2 * tan(20.0 * BDL_PI / 180.0));
    float nx = (float)(0.5 / (0.01 * ppm)), ny = -nx;
    float base[3], lit[3], n[3] = {nx, ny, sqrtf(1.0f - nx * nx - ny * ny)}, e_z[3] = {0, 0, 1};
    bdl_category_color(1, base);
    base[0] = lrintf(255 * base[0]) / 255.0f; // the instance colour is 8-bit
    base[1] = lrintf(255 * base[1]) / 255.0f;
    base[2] = lrintf(255 * base[2]) / 255.0f;
    bdl_shade(base, n, e_z, lit);
    uint8_t e[3];
    for (int k = 0; k < 3; ++k)
        e[k] = (uint8_t)lrintf(255 * fminf(lit[k], 1.0f));
    const uint8_t *p = pixel(W / 2, H / 2);
    CHECK_MSG(close_color(p, e, 1), "lit: pixel %d %d %d, predicted %d %d %d", p[0], p[1], p[2],
              e[0], e[1], e[2]);
}

/// Nearer sphere wins: for each pixel, the ray (parallel projection, along +y) against both
/// spheres; pixels within 1.5 px of either silhouette are left out (coverage rounding).
static void check_depth_order(const small_snapshot *ss, const char *what)
{
    bdl_view v;
    base_view(&v, 1);
    draw(ss, &v);
    double half = 0.2 * tan(20.0 * BDL_PI / 180.0), ppm = (H / 2.0) / half;
    uint8_t col[2][3];
    for (int s = 0; s < 2; ++s) {
        float c[3];
        bdl_category_color(ss->species[s], c);
        for (int k = 0; k < 3; ++k)
            col[s][k] = (uint8_t)lrintf(255 * c[k]);
    }
    int shared = 0, wrong = 0;
    for (int py = 0; py < H; ++py)
        for (int px = 0; px < W; ++px) {
            double x = (px + 0.5 - W / 2.0) / ppm, z = (H / 2.0 - py - 0.5) / ppm;
            double depth[2];
            int hit = 0, near_edge = 0;
            for (int s = 0; s < 2; ++s) {
                double dx = x - ss->pos[3 * s], dz = z - ss->pos[3 * s + 2];
                double r = ss->radius[s], q = sqrt(dx * dx + dz * dz);
                near_edge |= fabs(q - r) * ppm < 1.5;
                depth[s] = q < r ? ss->pos[3 * s + 1] - sqrt(r * r - q * q) : INFINITY;
                hit += q < r;
            }
            if (hit < 2 || near_edge || fabs(depth[0] - depth[1]) * ppm < 0.05)
                continue;
            ++shared;
            int nearer = depth[0] < depth[1] ? 0 : 1;
            if (!close_color(pixel(px, py), col[nearer], 1))
                ++wrong;
        }
    printf("%s: %d shared pixels, %d show the farther sphere\n", what, shared, wrong);
    CHECK(shared > 100);
    CHECK(wrong == 0);
}

static void test_depth(void)
{
    small_snapshot ss;
    snapshot_init(&ss, 2);
    // Apart in depth, overlapping on screen.
    ss.pos[0] = -0.004f, ss.pos[1] = 0.02f, ss.pos[2] = 0.0f, ss.radius[0] = 0.012f;
    ss.pos[3] = 0.006f, ss.pos[4] = -0.01f, ss.pos[5] = 0.003f, ss.radius[1] = 0.009f;
    ss.species[0] = 0, ss.species[1] = 1;
    check_depth_order(&ss, "separate spheres");
    // Intersecting in space: the intersection curve splits the shared pixels.
    ss.pos[0] = -0.005f, ss.pos[1] = 0.0f, ss.pos[2] = 0.0f, ss.radius[0] = 0.012f;
    ss.pos[3] = 0.006f, ss.pos[4] = 0.004f, ss.pos[5] = 0.002f, ss.radius[1] = 0.011f;
    check_depth_order(&ss, "intersecting spheres");
}

/// Occlusion culling leaves out only spheres that show no pixel: a dense random bed drawn with
/// and without it gives the same image, in perspective and parallel projection, with
/// multisampling.
static void test_culling(bdl_gl_backend backend)
{
    enum { N = 3000 };
    bdl_snapshot s = {0};
    static float pos[3 * N], vel[3 * N], radius[N];
    static uint8_t coordination[N];
    static int32_t species[N];
    static uint32_t id[N];
    s.pos = pos, s.vel = vel, s.radius = radius, s.coordination = coordination;
    s.species = species, s.id = id, s.count = s.capacity = N;
    unsigned seed = 12345;
    for (int i = 0; i < N; ++i) {
        for (int k = 0; k < 3; ++k) {
            seed = seed * 1103515245u + 12345u;
            pos[3 * i + k] = 0.06f * ((float)(seed >> 8) / 16777216.0f - 0.5f);
        }
        radius[i] = 0.002f + 0.001f * (float)(i % 3);
        species[i] = i % 2;
    }
    char why[1024];
    bdl_renderer *r = NULL;
    bdl_renderer_def rd = {.scene = &scene, .headless = 1, .width = W, .height = H, .samples = 4};
    CHECK_MSG(bdl_renderer_create(&rd, &r, why, sizeof why) == BDL_OK, "%s", why);
    if (!r)
        return;
    static uint8_t culled[W * H * 3], full[W * H * 3];
    for (int ortho = 0; ortho < 2; ++ortho) {
        bdl_view v;
        base_view(&v, ortho);
        v.camera.yaw = 30.0f;
        v.camera.pitch = 25.0f;
        v.lighting = 1;
        bdl_renderer_draw(r, &s, &v, W, H);
        long drawn = bdl_renderer_drawn(r);
        bdl_renderer_read(r, culled);
        v.no_culling = 1;
        bdl_renderer_draw(r, &s, &v, W, H);
        bdl_renderer_read(r, full);
        int differ = 0;
        for (int k = 0; k < W * H * 3; ++k)
            differ += culled[k] != full[k];
        printf("%s culling (%s): %ld of %d spheres drawn, %d bytes differ\n",
               bdl_gl_backend_name(backend), ortho ? "orthographic" : "perspective", drawn, N,
               differ);
        CHECK(drawn < N / 2);
        CHECK(differ == 0);
    }
    bdl_renderer_destroy(r);
}

static void test_overlay_and_png(const char *tag)
{
    small_snapshot ss;
    snapshot_init(&ss, 2);
    ss.radius[0] = ss.radius[1] = 0.005f;
    ss.pos[0] = 0.02f;
    ss.vel[0] = 1.0f;
    bdl_view v;
    base_view(&v, 0);
    v.color = BDL_COLOR_SPEED;
    v.overlay = 1;
    v.range_fixed = 1;
    v.range[0] = 0.0f;
    v.range[1] = 1.0f;
    draw(&ss, &v);
    // The colour bar: 16 px wide, from 0.3 H to 0.7 H, 80 px from the right edge; its top shows
    // the top of the map, its bottom the bottom.
    int x = W - 80 + 8;
    float top[3], bottom[3];
    bdl_colormap_eval(BDL_CMAP_SEQUENTIAL, 1.0f, top);
    bdl_colormap_eval(BDL_CMAP_SEQUENTIAL, 0.0f, bottom);
    uint8_t et[3], eb[3];
    for (int k = 0; k < 3; ++k) {
        et[k] = (uint8_t)lrintf(255 * top[k]);
        eb[k] = (uint8_t)lrintf(255 * bottom[k]);
    }
    const uint8_t *pt = pixel(x, (int)(0.3 * H) + 1), *pb = pixel(x, (int)(0.7 * H) - 2);
    CHECK_MSG(close_color(pt, et, 12), "bar top %d %d %d, map top %d %d %d", pt[0], pt[1], pt[2],
              et[0], et[1], et[2]);
    CHECK_MSG(close_color(pb, eb, 12), "bar bottom %d %d %d, map bottom %d %d %d", pb[0], pb[1],
              pb[2], eb[0], eb[1], eb[2]);
    // Text: bright pixels in the top-left line.
    int bright = 0;
    for (int py = 8; py < 26; ++py)
        for (int px = 10; px < 200; ++px)
            bright += pixel(px, py)[0] > 150 && pixel(px, py)[1] > 150;
    printf("text pixels in the first line: %d\n", bright);
    CHECK(bright > 50);
    // PNG round trip.
    char path[64];
    snprintf(path, sizeof path, "test_render_%s.png", tag);
    CHECK(bdl_png_write(path, fr.rgb, W, H, 3, 0) == BDL_OK);
    uint8_t *back = NULL;
    int bw = 0, bh = 0, bc = 0;
    CHECK(bdl_png_read(path, &back, &bw, &bh, &bc) == BDL_OK);
    CHECK(bw == W && bh == H && bc == 3);
    CHECK(back && memcmp(back, fr.rgb, sizeof fr.rgb) == 0);
    free(back);
    remove(path);
}

/// A gas-field slice: one flat colour per cell from the sequential map over the slice's range,
/// blended at the view's opacity; a sphere in front of it hides it; opacity 0 draws nothing.
static void test_gas_slice(void)
{
    small_snapshot ss;
    snapshot_init(&ss, 1);
    ss.pos[0] = 0.03f, ss.pos[1] = -0.02f, ss.pos[2] = 0.03f; // in front, over cell (1, 1)
    ss.radius[0] = 0.005f;
    float cells[4] = {0.0f, 1.0f, 2.0f, 3.0f}; // x fastest, then z
    ss.s.slice = cells;
    ss.s.slice_field = BDL_GAS_FIELD_VOIDAGE;
    ss.s.slice_axis = 1;   // normal y: the plane spans z (first) and x (second)
    ss.s.slice_at = 0.04f; // behind the particle for a view along +y
    for (int k = 0; k < 3; ++k)
        ss.s.slice_lo[k] = -0.05f, ss.s.slice_hi[k] = 0.05f;
    ss.s.slice_n[0] = 2;
    ss.s.slice_n[1] = 2;
    bdl_view v;
    base_view(&v, 1);
    v.gas_opacity = 0.5f;
    draw(&ss, &v);
    // Cells along z (first axis) then x: value (jz + 2 jx) / 3 of the range 0..3.
    double half = 0.2 * tan(20.0 * BDL_PI / 180.0), ppm = (H / 2.0) / half;
    int worst = 0;
    for (int jx = 0; jx < 2; ++jx)
        for (int jz = 0; jz < 2; ++jz) {
            float rgb[3];
            bdl_colormap_eval(BDL_CMAP_SEQUENTIAL, (jz + 2.0 * jx) / 3.0, rgb);
            double x = jx ? 0.015 : -0.015, z = jz ? 0.015 : -0.015;
            if (jx && jz)
                x = 0.015, z = 0.01; // beside the sphere
            const uint8_t *p = pixel((int)(W / 2.0 + x * ppm), (int)(H / 2.0 - z * ppm));
            for (int k = 0; k < 3; ++k) {
                int expect = (int)lrintf(0.5f * 255.0f * rgb[k]);
                worst = abs(p[k] - expect) > worst ? abs(p[k] - expect) : worst;
            }
        }
    printf("gas slice: 4 cells within %d levels of half their map colour over black\n", worst);
    CHECK_MSG(worst <= 3, "slice colours off by %d levels", worst);
    // The sphere in front hides the slice at its centre: no map colour mixed in there.
    const uint8_t *c = pixel((int)(W / 2.0 + 0.03 * ppm), (int)(H / 2.0 - 0.03 * ppm));
    float top[3];
    bdl_colormap_eval(BDL_CMAP_SEQUENTIAL, 1.0, top);
    CHECK_MSG(!(abs(c[0] - (int)lrintf(127.5f * top[0])) <= 3 &&
                abs(c[1] - (int)lrintf(127.5f * top[1])) <= 3),
              "the slice shows through the sphere");
    v.gas_opacity = 0.0f;
    draw(&ss, &v);
    CHECK(is_background((int)(W / 2.0 - 0.015 * ppm), (int)(H / 2.0 + 0.015 * ppm)));
}

static int run_backend(bdl_gl_backend backend)
{
    char why[1024];
    bdl_context *ctx = NULL;
    bdl_context_def cd = {.backend = backend, .width = W, .height = H};
    if (bdl_context_create(&cd, &ctx, why, sizeof why) != BDL_OK) {
        printf("%s: not available: %s\n", bdl_gl_backend_name(backend), why);
        return 0;
    }
    bdl_renderer_def rd = {.scene = &scene, .headless = 1, .width = W, .height = H};
    CHECK_MSG(bdl_renderer_create(&rd, &fr.r, why, sizeof why) == BDL_OK, "%s", why);
    if (fr.r) {
        printf("--- %s\n", bdl_gl_backend_name(backend));
        test_position_ortho();
        test_position_perspective();
        test_colors();
        test_depth();
        test_gas_slice();
        test_culling(backend);
        test_overlay_and_png(bdl_gl_backend_name(backend));
        bdl_renderer_destroy(fr.r);
        fr.r = NULL;
    }
    bdl_context_destroy(ctx);
    return 1;
}

int main(void)
{
    bdl_scene_error err;
    if (bdl_scene_load_string(scene_text, "render-test", NULL, 0, &scene, &err) != BDL_OK) {
        fprintf(stderr, "%s\n", err.message);
        return 1;
    }
    int ran = run_backend(BDL_GL_EGL);
    ran += run_backend(BDL_GL_OSMESA);
    CHECK_MSG(ran > 0, "no headless OpenGL backend works here");
    return bdl_test_summary("test_render");
}
