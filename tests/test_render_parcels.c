// Parcels in the pictures, headless: a snapshot of a bed of parcels carries each parcel at the
// radius [parcels] display asks for (the sphere of its solids volume, or one real particle's),
// the real particles they stand for and no contacts; drawn, the parcel display covers many more
// pixels than the real one; the solids fraction the solids colour reads at each parcel from the
// snapshot is the gas's 1 - eps at the parcel through the coupling's own kernel weights, at the
// start and after a step; and the colour the renderer gives a parcel in that mode is the map's
// colour of that value.
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/tent.h"
#include "check.h"
#include "couple/coupling.h"
#include "output/capture.h"
#include "render/colormap.h"
#include "render/context.h"
#include "render/renderer.h"
#include "scene_util.h"

#define W 240
#define H 320

// 200 um particles, 1000 to a parcel (the parcel's sphere: 2 mm across, ten times one particle),
// in the lower half of a 2 x 1 x 4 cm column of liquid; a 1.5-cell kernel, so that the kernel is
// not the trilinear one.
static const char scene_text[] =
    "[run]\nend_time = 1\ndt = 0.002\ngravity = 0 0 -9.81\nseed = 3\n"
    "[domain]\nmin = 0 0 0\nmax = 0.02 0.01 0.04\n"
    "[species sand]\ndiameter = 200e-6\ndensity = 2500\nparcel_particles = 1000\n"
    "[create bed]\ntype = random\nspecies = sand\nvolume_fraction = 0.3\n"
    "region_min = 0 0 0\nregion_max = 0.02 0.01 0.02\n"
    "[gas]\ndensity = 1000\nviscosity = 0.001\ncells = 4 2 8\n"
    "[coupling]\ndrag = patankar\nkernel_width = 0.0075\n"
    "[parcels]\ndisplay = %s\n";

/// What a snapshot carries of parcels: radii, the real particles, no contacts, the gas's voidage.
static void check_snapshot(const bdl_world *w, const bdl_snapshot *s, int parcel_display)
{
    const bdl_particles *p = &w->particles;
    CHECK(s->parcels == 1 && s->count == p->count && p->count > 100);
    double real = 0.0;
    int radii = 1, contacts = 0;
    for (long i = 0; i < p->count; ++i) {
        real += p->parcel_count[i];
        const double want =
            parcel_display ? cbrt(0.75 / BDL_PI * bdl_particle_solids_volume(p, i)) : p->radius[i];
        radii &= fabs(s->radius[i] - want) <= 1e-6 * want;
        contacts += s->coordination[i];
    }
    CHECK_CLOSE(s->real_particles, real, 1e-12);
    CHECK_CLOSE(s->real_particles, 1000.0 * (double)p->count, 1e-12);
    CHECK_MSG(radii, "a parcel drawn at another radius than display = %s asks",
              parcel_display ? "parcel" : "real");
    if (parcel_display)
        CHECK_CLOSE(s->radius[0], 10.0 * p->radius[0], 1e-6); // cbrt(1000) particles' radii
    CHECK(contacts == 0);
    CHECK(s->voidage_n[0] == 4 && s->voidage_n[1] == 2 && s->voidage_n[2] == 8);
}

/// The solids fraction the snapshot gives at each parcel against the coupling's own reading of
/// the gas's voidage with the weights it deposited the parcels with.
static void check_solids(const bdl_world *w, const bdl_snapshot *s, const char *when)
{
    const bdl_tent_field f = bdl_render_voidage_field(s);
    double worst = 0.0, most = 0.0;
    for (long i = 0; i < w->particles.count; ++i) {
        const double x[3] = {s->pos[3 * i], s->pos[3 * i + 1], s->pos[3 * i + 2]};
        const double from_snapshot = 1.0 - bdl_tent_sample(&f, x);
        const double solver = 1.0 - bdl_coupling_interpolate(w->coupling, i, w->gas->eps);
        worst = fmax(worst, fabs(from_snapshot - solver));
        most = fmax(most, solver);
    }
    // Floats in the snapshot: positions to 1e-7 relative (a few nm here), voidage to 6e-8.
    CHECK_MSG(worst < 1e-5, "%s: the snapshot's solids fraction differs from the coupling's by %g",
              when, worst);
    CHECK_MSG(most > 0.15 && most < 0.7, "%s: the largest solids fraction at a parcel is %g", when,
              most);
}

static long lit_pixels(const uint8_t *rgb)
{
    long n = 0;
    for (long k = 0; k < (long)W * H; ++k)
        n += rgb[3 * k] != 0 || rgb[3 * k + 1] != 0 || rgb[3 * k + 2] != 0;
    return n;
}

/// The front view of the scene's camera, flat colours on black, no text or outlines.
static void plain_view(const bdl_scene *scene, bdl_color_mode color, bdl_view *v)
{
    bdl_view_from_scene(scene, (float)W / (float)H, v);
    v->camera.ortho = 1;
    bdl_camera_preset(BDL_VIEW_FRONT, &v->camera);
    v->color = color;
    v->lighting = v->overlay = v->outlines = 0;
    v->background[0] = v->background[1] = v->background[2] = 0.0f;
}

/// Parcels drawn as the spheres of their solids volume against single real particles; and the
/// solids colour of a parcel in front.
static int draw_parcels(bdl_gl_backend backend, const bdl_world *w, const bdl_snapshot *parcel,
                        const bdl_snapshot *real)
{
    char why[1024];
    bdl_context *ctx = NULL;
    bdl_context_def cd = {.backend = backend, .width = W, .height = H};
    if (bdl_context_create(&cd, &ctx, why, sizeof why) != BDL_OK) {
        printf("%s: not available: %s\n", bdl_gl_backend_name(backend), why);
        return 0;
    }
    bdl_renderer *r = NULL;
    bdl_renderer_def rd = {.scene = &w->scene, .headless = 1, .width = W, .height = H};
    CHECK_MSG(bdl_renderer_create(&rd, &r, why, sizeof why) == BDL_OK, "%s", why);
    static uint8_t rgb[W * H * 3];
    bdl_view v;
    plain_view(&w->scene, BDL_COLOR_SPECIES, &v);
    long lit[2] = {0, 0};
    for (int k = 0; k < 2 && r; ++k) {
        bdl_renderer_draw(r, k == 0 ? parcel : real, &v, W, H);
        CHECK(bdl_renderer_read(r, rgb) == BDL_OK);
        lit[k] = lit_pixels(rgb);
    }
    printf("%s: %ld lit pixels with display = parcel, %ld with display = real\n",
           bdl_gl_backend_name(backend), lit[0], lit[1]);
    // The parcels' spheres are ten times as wide: the bed's lower half is covered (at least half
    // the picture's column of the domain), real particles leave most of it dark.
    CHECK_MSG(lit[0] > 4 * lit[1] && lit[1] > 0, "lit pixels: parcel %ld, real %ld", lit[0],
              lit[1]);
    bdl_renderer_destroy(r);
    bdl_context_destroy(ctx);
    return 1;
}

/// The colour the solids mode gives a parcel is the sequential map at its solids fraction.
static void check_solids_color(const bdl_snapshot *s)
{
    const float range[2] = {0.0f, 0.6f};
    uint8_t rgb[3];
    float c[3];
    bdl_particle_color(BDL_COLOR_SOLIDS, s, 0, 0.45f, range, rgb);
    bdl_colormap_eval(BDL_CMAP_SEQUENTIAL, 0.75f, c);
    for (int k = 0; k < 3; ++k)
        CHECK(abs((int)rgb[k] - (int)lrintf(255.0f * c[k])) <= 1);
}

int main(void)
{
    bdl_world *w = bdl_test_world(scene_text, "parcel");
    bdl_snapshot parcel = {0}, real = {0};
    CHECK(bdl_capture(&parcel, w));
    check_snapshot(w, &parcel, 1);
    check_solids(w, &parcel, "at the start");
    w->scene.parcels.display = BDL_PARCEL_DISPLAY_REAL;
    CHECK(bdl_capture(&real, w));
    check_snapshot(w, &real, 0);
    check_solids_color(&parcel);
    int drawn = draw_parcels(BDL_GL_EGL, w, &parcel, &real);
    drawn += draw_parcels(BDL_GL_OSMESA, w, &parcel, &real);
    CHECK_MSG(drawn > 0, "no headless OpenGL backend works here");
    for (int k = 0; k < 5; ++k)
        CHECK(bdl_world_step(w) == BDL_OK);
    CHECK(bdl_capture(&real, w));
    check_solids(w, &real, "after five steps");
    bdl_snapshot_free(&parcel);
    bdl_snapshot_free(&real);
    bdl_world_destroy(w);
    return bdl_test_summary("test_render_parcels");
}
