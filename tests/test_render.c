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
#include "dem/capsule.h"
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

/// A snapshot of up to 4 particles (rods: point s.axis at axis).
typedef struct small_snapshot {
    bdl_snapshot s;
    float pos[12], vel[12], radius[4], axis[12];
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
        case BDL_COLOR_SOLIDS:
            v.range[0] = 0, v.range[1] = 1, t = -1.0f; // measured below
            break;
        case BDL_COLOR_TILT:
        case BDL_COLOR_AZIMUTH:
            v.range[0] = 0, v.range[1] = 90; // a sphere has no orientation: the missing value
            break;
        default:
            break;
        }
        draw(&ss, &v);
        float c[3];
        if (mode == BDL_COLOR_SPECIES)
            bdl_category_color(1, c);
        else if (mode == BDL_COLOR_TILT || mode == BDL_COLOR_AZIMUTH)
            bdl_colormap_missing(c);
        else if (mode == BDL_COLOR_VOIDAGE || mode == BDL_COLOR_SOLIDS)
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
        if (mode == BDL_COLOR_SOLIDS) {
            // No gas: 1 - the same voidage, low, so the pixel is in the map's lower half.
            float lab[3], pf[3] = {p[0] / 255.0f, p[1] / 255.0f, p[2] / 255.0f};
            bdl_oklab_from_srgb(pf, lab);
            float mid[3], mid_lab[3];
            bdl_colormap_eval(BDL_CMAP_SEQUENTIAL, 0.5f, mid);
            bdl_oklab_from_srgb(mid, mid_lab);
            CHECK_MSG(lab[0] < mid_lab[0], "solids colour lightness %.3f", lab[0]);
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

/// Draws snapshot s with and without occlusion culling, in perspective and parallel projection,
/// lit and multisampled: the images agree to the byte, and fewer than `most` particles are drawn.
static void check_culling(bdl_gl_backend backend, const bdl_snapshot *s, long most,
                          const char *what)
{
    const long N = s->count;
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
        bdl_renderer_draw(r, s, &v, W, H);
        long drawn = bdl_renderer_drawn(r);
        bdl_renderer_read(r, culled);
        v.no_culling = 1;
        bdl_renderer_draw(r, s, &v, W, H);
        bdl_renderer_read(r, full);
        int differ = 0;
        for (int k = 0; k < W * H * 3; ++k)
            differ += culled[k] != full[k];
        printf("%s culling%s (%s): %ld of %ld drawn, %d bytes differ\n",
               bdl_gl_backend_name(backend), what, ortho ? "orthographic" : "perspective", drawn, N,
               differ);
        CHECK(drawn < most);
        CHECK(differ == 0);
    }
    bdl_renderer_destroy(r);
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
    check_culling(backend, &s, N / 2, "");
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

// ---------------------------------------------------------------------------------------------
// Rods. Predictions come from a ray cast on the CPU that shares nothing with the shader's: the
// distance from a point of the ray to the shaft, minus r, is convex along the ray, so a ternary
// search finds where the ray passes closest to the shaft (a miss when that is farther than r)
// and a bisection before that point finds where it enters the capsule.

/// A capsule in world coordinates: the points within r of the segment c +- a (a = 0: a sphere).
typedef struct capsule {
    double c[3], a[3], r;
    int species;
} capsule;

static double dot3(const double *x, const double *y)
{
    return x[0] * y[0] + x[1] * y[1] + x[2] * y[2];
}

/// Distance from o + t d to the capsule's surface (negative inside); *s the shaft parameter of
/// the nearest point of the shaft, in [-1, 1].
static double surface_gap(const capsule *k, const double o[3], const double d[3], double t,
                          double *s)
{
    double q[3], aa = dot3(k->a, k->a);
    for (int i = 0; i < 3; ++i)
        q[i] = o[i] + t * d[i] - k->c[i];
    *s = aa > 0.0 ? fmax(-1.0, fmin(1.0, dot3(q, k->a) / aa)) : 0.0;
    for (int i = 0; i < 3; ++i)
        q[i] -= *s * k->a[i];
    return sqrt(dot3(q, q)) - k->r;
}

/// Focal length of base_view's cameras [px]: pixels per metre at the target's distance 0.2 m.
static double focal(void) { return (H / 2.0) / tan(20.0 * BDL_PI / 180.0); }

/// The view ray through pixel centre (x, y) in world coordinates: base_view's eye is at
/// y = -0.2 looking along +y, x right and z up.
static void pixel_ray(double x, double y, int ortho, double o[3], double d[3])
{
    double f = focal(), u = (x - W / 2.0) / f, w = (H / 2.0 - y) / f;
    if (ortho) {
        o[0] = 0.2 * u, o[1] = -0.2, o[2] = 0.2 * w;
        d[0] = 0.0, d[1] = 1.0, d[2] = 0.0;
        return;
    }
    double len = sqrt(u * u + 1.0 + w * w);
    o[0] = 0.0, o[1] = -0.2, o[2] = 0.0;
    d[0] = u / len, d[1] = 1.0 / len, d[2] = w / len;
}

/// A ray against a capsule: the distance along it to the first hit (INFINITY on a miss), the
/// unit normal there, pixels per metre at the hit's depth, and how far in pixels the ray passes
/// from the silhouette (rays that graze it are left out of comparisons).
typedef struct ray_hit {
    double t, n[3], px_per_m, edge_px;
} ray_hit;

static ray_hit cast(const capsule *k, const double o[3], const double d[3], int ortho)
{
    double to_c[3] = {k->c[0] - o[0], k->c[1] - o[1], k->c[2] - o[2]}, s;
    double tc = dot3(to_c, d), reach = sqrt(dot3(k->a, k->a)) + k->r;
    double lo = tc - reach, hi = tc + reach; // the closest pass and the entry lie in here
    for (int it = 0; it < 60; ++it) {
        double m1 = lo + (hi - lo) / 3.0, m2 = hi - (hi - lo) / 3.0;
        if (surface_gap(k, o, d, m1, &s) < surface_gap(k, o, d, m2, &s))
            hi = m2;
        else
            lo = m1;
    }
    double closest = 0.5 * (lo + hi), gap = surface_gap(k, o, d, closest, &s);
    ray_hit h = {INFINITY, {0.0, 0.0, 0.0}, 0.0, 0.0};
    h.px_per_m = ortho ? focal() / 0.2 : focal() / (closest * d[1]);
    h.edge_px = fabs(gap) * h.px_per_m;
    if (gap > 0.0)
        return h;
    lo = tc - reach, hi = closest;
    for (int it = 0; it < 60; ++it) {
        double mid = 0.5 * (lo + hi);
        if (surface_gap(k, o, d, mid, &s) > 0.0)
            lo = mid;
        else
            hi = mid;
    }
    h.t = 0.5 * (lo + hi);
    surface_gap(k, o, d, h.t, &s);
    for (int i = 0; i < 3; ++i)
        h.n[i] = (o[i] + h.t * d[i] - k->c[i] - s * k->a[i]) / k->r;
    return h;
}

/// The colour the renderer gives a capsule of `species` at a surface point: flat, or shaded
/// with the world normal n seen along the ray d (8-bit base colour, as the instance holds it).
static void predict(int species, int lit, const double n[3], const double d[3], int ortho,
                    uint8_t out[3])
{
    float base[3], shaded[3];
    bdl_category_color(species, base);
    for (int k = 0; k < 3; ++k)
        base[k] = lrintf(255 * base[k]) / 255.0f;
    // base_view's view space: x = world x, y = world z, z = -world y (towards the eye).
    float nv[3] = {(float)n[0], (float)n[2], (float)-n[1]}, view[3] = {0.0f, 0.0f, 1.0f};
    if (!ortho)
        view[0] = (float)-d[0], view[1] = (float)-d[2], view[2] = (float)d[1];
    if (lit)
        bdl_shade(base, nv, view, shaded);
    for (int k = 0; k < 3; ++k)
        out[k] = (uint8_t)lrintf(255 * fminf(lit ? shaded[k] : base[k], 1.0f));
}

/// Counts of a frame compared with the CPU ray cast.
typedef struct comparison {
    int compared, shared, wrong;
} comparison;

/// The frame against the ray cast of `count` capsules: at every pixel whose ray passes farther
/// than `edge` px from each silhouette, the nearest surface's colour within 1 level, or the
/// background where the ray hits none; pixels where two surfaces lie within 0.05 px of each
/// other in depth are left out (the existing two-sphere test's rule).
static comparison compare_capsules(const capsule *k, int count, int ortho, int lit, double edge)
{
    comparison c = {0, 0, 0};
    for (int py = 0; py < H; ++py)
        for (int px = 0; px < W; ++px) {
            double o[3], d[3];
            pixel_ray(px + 0.5, py + 0.5, ortho, o, d);
            ray_hit best = {INFINITY, {0, 0, 0}, 0, 0};
            int nearest = -1, hits = 0, skip = 0;
            for (int j = 0; j < count; ++j) {
                ray_hit h = cast(&k[j], o, d, ortho);
                skip |= h.edge_px < edge;
                if (h.t == INFINITY)
                    continue;
                skip |= hits > 0 && fabs(h.t - best.t) * h.px_per_m < 0.05;
                ++hits;
                if (h.t < best.t)
                    best = h, nearest = j;
            }
            if (skip)
                continue;
            uint8_t e[3] = {0, 0, 0};
            if (nearest >= 0)
                predict(k[nearest].species, lit, best.n, d, ortho, e);
            ++c.compared;
            c.shared += hits > 1;
            c.wrong += !close_color(pixel(px, py), e, 1);
        }
    return c;
}

/// A snapshot of the capsules, with axes.
static void capsule_snapshot(small_snapshot *ss, const capsule *k, int count)
{
    snapshot_init(ss, count);
    ss->s.axis = ss->axis;
    for (int j = 0; j < count; ++j) {
        for (int i = 0; i < 3; ++i) {
            ss->pos[3 * j + i] = (float)k[j].c[i];
            ss->axis[3 * j + i] = (float)k[j].a[i];
        }
        ss->radius[j] = (float)k[j].r;
        ss->species[j] = k[j].species;
    }
}

/// First and one-past-last non-background pixel along a row (dx = 1) or a column (dx = 0).
static int extent(int fixed, int dx)
{
    int first = -1, last = -1, n = dx ? W : H;
    for (int q = 0; q < n; ++q)
        if (!is_background(dx ? q : fixed, dx ? fixed : q)) {
            first = first < 0 ? q : first;
            last = q + 1;
        }
    return last - first;
}

/// Side-on, parallel projection: the silhouette is 2 (h + r) long and 2 r wide, and the pixel
/// at the centre has the flat colour, then the lit one for the cylinder's normal there.
static void test_capsule_side_on(void)
{
    const double h = 0.02, r = 0.008, ppm = focal() / 0.2;
    capsule k = {{0.0, 0.0, 0.0}, {h, 0.0, 0.0}, r, 1};
    small_snapshot ss;
    capsule_snapshot(&ss, &k, 1);
    bdl_view v;
    base_view(&v, 1);
    draw(&ss, &v);
    int length = extent(H / 2, 1), width = extent(W / 2, 0);
    printf("capsule side-on: %d x %d px, predicted %.2f x %.2f\n", length, width, 2 * (h + r) * ppm,
           2 * r * ppm);
    CHECK(fabs(length - 2 * (h + r) * ppm) <= 1.0);
    CHECK(fabs(width - 2 * r * ppm) <= 1.0);
    const float range[2] = {0.0f, 1.0f};
    uint8_t e[3];
    bdl_particle_color(BDL_COLOR_SPECIES, &ss.s, 0, 1.0f, range, e);
    const uint8_t *p = pixel(W / 2, H / 2);
    CHECK_MSG(close_color(p, e, 1), "flat: pixel %d %d %d, predicted %d %d %d", p[0], p[1], p[2],
              e[0], e[1], e[2]);
    v.lighting = 1;
    draw(&ss, &v);
    double o[3], d[3];
    pixel_ray(W / 2 + 0.5, H / 2 + 0.5, 1, o, d);
    ray_hit hit = cast(&k, o, d, 1);
    CHECK(hit.t < INFINITY && fabs(hit.n[0]) < 1e-9); // on the cylinder
    predict(1, 1, hit.n, d, 1, e);
    CHECK_MSG(close_color(p, e, 1), "lit: pixel %d %d %d, predicted %d %d %d", p[0], p[1], p[2],
              e[0], e[1], e[2]);
}

/// A capsule at a slant to every axis, lit, in both projections: every pixel not within
/// 0.05 px of the silhouette is inside or outside as predicted, with the shading of its normal.
static void test_capsule_silhouette(void)
{
    capsule k = {{0.005, 0.01, -0.004}, {0.012, 0.006, 0.009}, 0.006, 2};
    small_snapshot ss;
    capsule_snapshot(&ss, &k, 1);
    for (int ortho = 1; ortho >= 0; --ortho) {
        bdl_view v;
        base_view(&v, ortho);
        v.lighting = 1;
        draw(&ss, &v);
        comparison c = compare_capsules(&k, 1, ortho, 1, 0.05);
        printf("slanted capsule (%s): %d pixels compared, %d differ\n",
               ortho ? "orthographic" : "perspective", c.compared, c.wrong);
        CHECK(c.compared > W * H - 400);
        CHECK(c.wrong == 0);
    }
}

/// Seen along its axis a capsule is the ball of its nearer end: the frame equals that sphere's
/// (drawn without axes) within a level, and in parallel projection has its centre and radius.
static void test_capsule_end_on(void)
{
    for (int ortho = 1; ortho >= 0; --ortho) {
        // Parallel: off the image centre; perspective: on the optical axis, which is the rod's.
        capsule k = {{ortho ? 0.01 : 0.0, 0.02, ortho ? 0.005 : 0.0}, {0.0, 0.015, 0.0}, 0.01, 1};
        small_snapshot rod, ball;
        capsule_snapshot(&rod, &k, 1);
        snapshot_init(&ball, 1);
        ball.pos[0] = (float)k.c[0], ball.pos[1] = (float)(k.c[1] - k.a[1]);
        ball.pos[2] = (float)k.c[2], ball.radius[0] = (float)k.r, ball.species[0] = k.species;
        bdl_view v;
        base_view(&v, ortho);
        v.lighting = 1;
        static uint8_t sphere_rgb[W * H * 3];
        draw(&ball, &v);
        memcpy(sphere_rgb, fr.rgb, sizeof sphere_rgb);
        draw(&rod, &v);
        int differ = 0;
        for (int q = 0; q < W * H; ++q)
            differ += !close_color(&fr.rgb[3 * q], &sphere_rgb[3 * q], 1);
        double cx, cy, radius, ppm = focal() / 0.2;
        blob(&cx, &cy, &radius);
        printf("capsule end-on (%s): %d pixels differ from the sphere's; centre (%.2f, %.2f), "
               "radius %.2f px\n",
               ortho ? "orthographic" : "perspective", differ, cx, cy, radius);
        CHECK(differ == 0);
        if (ortho) {
            CHECK(fabs(cx - (W / 2.0 + k.c[0] * ppm)) <= 1.0);
            CHECK(fabs(cy - (H / 2.0 - k.c[2] * ppm)) <= 1.0);
            CHECK(fabs(radius - k.r * ppm) <= 1.0);
        }
    }
}

/// A capsule through a sphere: at every pixel both cover, the nearer surface's colour shows
/// (flat colours; pixels within 1.5 px of a silhouette left out, as for two spheres).
static void test_capsule_sphere_depth(void)
{
    capsule k[2] = {{{-0.002, 0.0, 0.0}, {0.016, 0.007, 0.005}, 0.006, 0},
                    {{0.006, 0.002, 0.003}, {0.0, 0.0, 0.0}, 0.009, 1}};
    small_snapshot ss;
    capsule_snapshot(&ss, k, 2);
    for (int ortho = 1; ortho >= 0; --ortho) {
        bdl_view v;
        base_view(&v, ortho);
        draw(&ss, &v);
        comparison c = compare_capsules(k, 2, ortho, 0, 1.5);
        printf("capsule through a sphere (%s): %d shared pixels, %d of %d pixels wrong\n",
               ortho ? "orthographic" : "perspective", c.shared, c.wrong, c.compared);
        CHECK(c.shared > 100);
        CHECK(c.wrong == 0);
    }
}

/// Rods of zero length are spheres: the frame with zero axes equals, byte for byte, the frame
/// of the same particles without axes (the sphere shader), lit, in both projections.
static void test_capsule_zero_axis(void)
{
    small_snapshot ss;
    snapshot_init(&ss, 3);
    const float pos[9] = {-0.005f, 0.0f, 0.0f, 0.006f, 0.004f, 0.002f, -0.02f, -0.03f, 0.015f};
    const float radius[3] = {0.012f, 0.011f, 0.004f};
    memcpy(ss.pos, pos, sizeof pos);
    memcpy(ss.radius, radius, sizeof radius);
    ss.species[1] = 1, ss.species[2] = 2;
    static uint8_t spheres[W * H * 3];
    for (int ortho = 1; ortho >= 0; --ortho) {
        bdl_view v;
        base_view(&v, ortho);
        v.lighting = 1;
        ss.s.axis = NULL;
        draw(&ss, &v);
        memcpy(spheres, fr.rgb, sizeof spheres);
        ss.s.axis = ss.axis; // all zero
        draw(&ss, &v);
        int differ = 0;
        for (int q = 0; q < W * H * 3; ++q)
            differ += fr.rgb[q] != spheres[q];
        printf("zero-length rods (%s): %d bytes differ from the spheres\n",
               ortho ? "orthographic" : "perspective", differ);
        CHECK(differ == 0);
    }
}

/// The cyclic map's ends are one colour (azimuth 0 and 180 deg are the same axis), and every hue
/// has its lightness.
static void check_cyclic_map(void)
{
    float first[3], last[3], c[3], lab[3], spread = 0.0f;
    bdl_colormap_eval(BDL_CMAP_CYCLIC, 0.0, first);
    bdl_colormap_eval(BDL_CMAP_CYCLIC, 1.0, last);
    for (int k = 0; k < 3; ++k)
        CHECK(fabsf(first[k] - last[k]) < 1e-6f);
    for (int i = 0; i <= 64; ++i) {
        bdl_colormap_eval(BDL_CMAP_CYCLIC, i / 64.0, c);
        bdl_oklab_from_srgb(c, lab);
        spread = fmaxf(spread, fabsf(lab[0] - 0.72f));
    }
    CHECK_MSG(spread < 0.005f, "cyclic map lightness off 0.72 by %.4f", spread);
}

/// The orientation colours: tilt on the sequential map over 0..90 deg, azimuth on the cyclic map
/// over 0..180 deg, the same for an axis and its opposite; a sphere among rods is grey.
static void test_orientation_colors(void)
{
    check_cyclic_map();
    const double deg = BDL_PI / 180.0, h = 0.012;
    struct {
        bdl_color_mode mode;
        double axis[3], t; ///< t < 0: the missing value
    } cases[] = {
        {BDL_COLOR_TILT, {h * sin(30 * deg), 0.0, h * cos(30 * deg)}, 30.0 / 90.0},
        {BDL_COLOR_TILT, {-h * sin(30 * deg), 0.0, -h * cos(30 * deg)}, 30.0 / 90.0},
        {BDL_COLOR_TILT, {0.0, h * sin(75 * deg), h * cos(75 * deg)}, 75.0 / 90.0},
        {BDL_COLOR_TILT, {0.0, 0.0, 0.0}, -1.0},
        {BDL_COLOR_AZIMUTH, {h * cos(120 * deg), h * sin(120 * deg), 0.0}, 120.0 / 180.0},
        {BDL_COLOR_AZIMUTH, {-h * cos(120 * deg), -h * sin(120 * deg), 0.0}, 120.0 / 180.0},
        {BDL_COLOR_AZIMUTH, {h * cos(10 * deg), h * sin(10 * deg), 0.004}, 10.0 / 180.0},
        {BDL_COLOR_AZIMUTH, {0.0, 0.0, h}, -1.0}, // upright: no azimuth
    };
    for (size_t j = 0; j < sizeof cases / sizeof cases[0]; ++j) {
        capsule k = {{0.0, 0.0, 0.0}, {0.0, 0.0, 0.0}, 0.005, 0};
        memcpy(k.a, cases[j].axis, sizeof k.a);
        small_snapshot ss;
        capsule_snapshot(&ss, &k, 1);
        bdl_view v;
        base_view(&v, 1);
        v.color = cases[j].mode;
        draw(&ss, &v);
        float c[3];
        if (cases[j].t < 0.0)
            bdl_colormap_missing(c);
        else
            bdl_colormap_eval(cases[j].mode == BDL_COLOR_TILT ? BDL_CMAP_SEQUENTIAL
                                                              : BDL_CMAP_CYCLIC,
                              cases[j].t, c);
        uint8_t e[3] = {(uint8_t)lrintf(255 * c[0]), (uint8_t)lrintf(255 * c[1]),
                        (uint8_t)lrintf(255 * c[2])};
        const uint8_t *p = pixel(W / 2, H / 2);
        CHECK_MSG(close_color(p, e, 1), "%s of axis %g %g %g: pixel %d %d %d, predicted %d %d %d",
                  bdl_color_mode_names[cases[j].mode], k.a[0], k.a[1], k.a[2], p[0], p[1], p[2],
                  e[0], e[1], e[2]);
    }
}

/// Occlusion culling stays conservative with rods: a dense random bed of rods and spheres drawn
/// with and without it gives the same image.
static void test_capsule_culling(bdl_gl_backend backend)
{
    enum { N = 3000 };
    bdl_snapshot s = {0};
    static float pos[3 * N], vel[3 * N], radius[N], axis[3 * N];
    static uint8_t coordination[N];
    static int32_t species[N];
    static uint32_t id[N];
    s.pos = pos, s.vel = vel, s.radius = radius, s.axis = axis, s.coordination = coordination;
    s.species = species, s.id = id, s.count = s.capacity = N;
    unsigned seed = 4321;
    for (int i = 0; i < N; ++i) {
        float u[6];
        for (int k = 0; k < 6; ++k) {
            seed = seed * 1103515245u + 12345u;
            u[k] = (float)(seed >> 8) / 16777216.0f - 0.5f;
        }
        for (int k = 0; k < 3; ++k) {
            pos[3 * i + k] = 0.06f * u[k];
            axis[3 * i + k] = i % 3 ? 0.012f * u[3 + k] : 0.0f; // a third are spheres
        }
        radius[i] = 0.0015f + 0.001f * (float)(i % 2);
        species[i] = i % 3;
    }
    check_culling(backend, &s, N, " of rods");
}

/// The picture of docs/rendering.md's rods (docs/img/render_rods.png), written when
/// BDL_RODS_PICTURE names a file: 240 rods and 120 spheres placed at random in the test domain
/// (rejecting any that would come within 1 mm of another), coloured by tilt, lit, with the colour
/// bar. Run `BDL_RODS_PICTURE=FILE
/// build/tests/test_render` to make it again.
static void write_rods_picture(void)
{
    static int written = 0; // by the first backend that works
    const char *path = getenv("BDL_RODS_PICTURE");
    if (!path || written++)
        return;
    enum { N = 360, PW = 960, PH = 540 };
    static float pos[3 * N], vel[3 * N], radius[N], axis[3 * N];
    static uint8_t coordination[N], rgb[PW * PH * 3];
    static int32_t species[N];
    static uint32_t id[N];
    bdl_snapshot s = {.count = N,
                      .capacity = N,
                      .pos = pos,
                      .vel = vel,
                      .radius = radius,
                      .axis = axis,
                      .coordination = coordination,
                      .species = species,
                      .id = id};
    unsigned seed = 2024;
    for (int i = 0; i < N; ++i) {
        capsule k = {{0}, {0}, 0.0025, 0};
        int placed = 0;
        while (!placed) { // rejection: bounding balls apart, so no two particles overlap
            double u[5];
            for (int j = 0; j < 5; ++j) {
                seed = seed * 1103515245u + 12345u;
                u[j] = (double)(seed >> 8) / 16777216.0;
            }
            double h = i % 3 == 2 ? 0.0 : 0.0075, z = 2.0 * u[3] - 1.0, phi = 2.0 * BDL_PI * u[4];
            for (int j = 0; j < 3; ++j)
                k.c[j] = 0.085 * (u[j] - 0.5);
            k.a[0] = h * sqrt(1.0 - z * z) * cos(phi), k.a[1] = h * sqrt(1.0 - z * z) * sin(phi);
            k.a[2] = h * z;
            placed = 1;
            for (int j = 0; j < i && placed; ++j) {
                bdl_vec3 d =
                    bdl_v3(k.c[0] - pos[3 * j], k.c[1] - pos[3 * j + 1], k.c[2] - pos[3 * j + 2]);
                bdl_vec3 ea = bdl_v3(k.a[0], k.a[1], k.a[2]);
                bdl_vec3 eb = bdl_v3(axis[3 * j], axis[3 * j + 1], axis[3 * j + 2]);
                double sa, sb, gap = k.r + radius[j] + 0.001;
                placed = bdl_segments_closest(d, ea, eb, &sa, &sb) > gap * gap;
            }
        }
        for (int j = 0; j < 3; ++j)
            pos[3 * i + j] = (float)k.c[j], axis[3 * i + j] = (float)k.a[j];
        radius[i] = (float)k.r, id[i] = (uint32_t)i;
    }
    char why[1024];
    bdl_renderer *r = NULL;
    bdl_renderer_def rd = {.scene = &scene, .headless = 1, .width = PW, .height = PH, .samples = 4};
    CHECK_MSG(bdl_renderer_create(&rd, &r, why, sizeof why) == BDL_OK, "%s", why);
    if (!r)
        return;
    bdl_view v;
    base_view(&v, 0);
    v.camera.yaw = 30.0f, v.camera.pitch = 25.0f, v.camera.distance = 0.24f;
    v.color = BDL_COLOR_TILT;
    v.lighting = v.overlay = v.outlines = 1;
    v.background[0] = v.background[1] = v.background[2] = 0.08f;
    bdl_renderer_draw(r, &s, &v, PW, PH);
    CHECK(bdl_renderer_read(r, rgb) == BDL_OK);
    CHECK(bdl_png_write(path, rgb, PW, PH, 3, 0) == BDL_OK);
    printf("rods picture: %s\n", path);
    bdl_renderer_destroy(r);
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
        test_capsule_side_on();
        test_capsule_silhouette();
        test_capsule_end_on();
        test_capsule_sphere_depth();
        test_capsule_zero_axis();
        test_orientation_colors();
        test_capsule_culling(backend);
        write_rods_picture();
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
