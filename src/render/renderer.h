// bedlam — draws a snapshot: sphere impostors coloured by a field, the container's outline, and
// an overlay of text and a colour bar. Reads snapshots only; never touches the solver.
//
// In a window it draws into the default framebuffer; headless it draws into its own
// (multisampled) framebuffer object, which bdl_renderer_read copies out.
#ifndef BDL_RENDERER_H
#define BDL_RENDERER_H

#include <stdint.h>

#include "analysis/tent.h"
#include "core/error.h"
#include "io/snapshot.h"
#include "render/camera.h"
#include "scene/scene.h"

/// What a frame shows; the viewer changes it between frames.
typedef struct bdl_view {
    bdl_camera camera;
    bdl_color_mode color;
    int range_fixed;      ///< use `range`, else the range of the data in each frame
    float range[2];       ///< colour map range (unit of the field)
    int clip;             ///< hide particles on the normal's side of the clipping plane
    float clip_point[3];  ///< [m]
    float clip_normal[3]; ///< unit
    int lighting;         ///< shaded (else flat colours)
    int overlay;          ///< text and colour bar
    int outlines;         ///< domain and wall outlines
    int no_culling;       ///< draw hidden particles too (same image, slower; for tests)
    float background[3];  ///< sRGB 0..1
    float gas_opacity;    ///< of the snapshot's gas-field slice (0: not drawn)
    const char *status;   ///< extra overlay line, or NULL
    const char *help;     ///< help text box in the middle, or NULL
} bdl_view;

/// The view the scene's [camera] asks for (the distance fitted to the domain at this aspect).
void bdl_view_from_scene(const bdl_scene *scene, float aspect, bdl_view *view);

typedef struct bdl_renderer_def {
    const bdl_scene *scene; ///< domain, walls and species (copied)
    int headless;           ///< draw into an own framebuffer of width x height
    int width, height;      ///< [px] (headless)
    int samples;            ///< multisampling of the own framebuffer (0: none)
    const char *font_path;  ///< NULL: bdl_font_default_path(); no font: no text, with a warning
} bdl_renderer_def;

typedef struct bdl_renderer bdl_renderer;

/// Needs a current GL context. On failure returns BDL_ERR_GL with a sentence in `why`.
bdl_result bdl_renderer_create(const bdl_renderer_def *def, bdl_renderer **out, char *why,
                               size_t why_len);
void bdl_renderer_destroy(bdl_renderer *r);

/// Draws a frame of width x height pixels (headless: the own framebuffer's size).
void bdl_renderer_draw(bdl_renderer *r, const bdl_snapshot *snap, const bdl_view *view, int width,
                       int height);

/// Copies the last headless frame into `rgb` (width * height * 3 bytes, rows top to bottom).
bdl_result bdl_renderer_read(bdl_renderer *r, uint8_t *rgb);

/// Copies the window's back buffer (after a draw, before presenting) into `rgb`.
bdl_result bdl_renderer_read_window(bdl_renderer *r, uint8_t *rgb, int width, int height);

/// Particles drawn in the last frame (the others were hidden, clipped or off screen).
long bdl_renderer_drawn(const bdl_renderer *r);

/// Colour of one particle as the renderer draws it (sRGB bytes) for a given range: the
/// reference the golden-image tests predict pixels with. `local`: the particle's voidage or
/// solids fraction in those modes.
void bdl_particle_color(bdl_color_mode mode, const bdl_snapshot *snap, long i, float local,
                        const float range[2], uint8_t rgb[3]);

/// The sphere shader's shading on the CPU (the tests' reference): the colour of a surface point
/// with unit normal n seen along unit `view` (towards the eye), both in view space, sRGB 0..1.
void bdl_shade(const float base[3], const float n[3], const float view[3], float out[3]);

/// Unit and label of a colour mode, e.g. "speed", "m/s".
const char *bdl_color_mode_label(bdl_color_mode mode);
const char *bdl_color_mode_unit(bdl_color_mode mode);

/// The gas's voidage of a snapshot as the field the solids and voidage colours sample with the
/// coupling's tent kernel (cell NULL: no gas).
bdl_tent_field bdl_render_voidage_field(const bdl_snapshot *s);

#endif
