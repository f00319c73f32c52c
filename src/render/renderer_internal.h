// bedlam — the renderer's state, shared by the files of render/ that draw a frame; never
// included outside render/.
//
// A frame is drawn in phases, each owned by one file that also owns its part of the state:
//
//   particles.c   sphere impostors: instance buffer, occlusion culling, the sphere shader
//   capsules.c    with rods, every particle as a capsule impostor instead (the capsule shader)
//   colors.c      the colour of each particle: field values, automatic range, voidage
//   slice.c       the translucent gas-field slice
//   outlines.c    the domain and wall outlines
//   overlay.c     text, colour bar or legend, help box
//
// renderer.c creates and destroys the renderer, runs the phases in order and reads pixels back;
// gl_util.c compiles shaders and makes textures for all of them; view.c fills a bdl_view from
// the scene.
#ifndef BDL_RENDERER_INTERNAL_H
#define BDL_RENDERER_INTERNAL_H

#include <stddef.h>
#include <stdint.h>

#include "analysis/voidage.h"
#include "render/colormap.h"
#include "render/cull.h"
#include "render/font.h"
#include "render/gl.h"
#include "render/renderer.h"

/// A shader program with its vertex array and vertex buffer.
typedef struct bdl_gl_mesh {
    GLuint program, vao, vbo;
} bdl_gl_mesh;

/// The matrices and size of the frame being drawn.
typedef struct bdl_render_frame {
    float view[16], proj[16], view_proj[16]; ///< column-major
    int width, height;                       ///< [px]
} bdl_render_frame;

/// Sphere impostors (particles.c).
typedef struct bdl_render_particles {
    bdl_gl_mesh mesh;   ///< the sphere program; its vertex array takes one instance per particle
    GLuint point_vao;   ///< the same buffer as one point per particle
    float point_max;    ///< largest point size the driver draws [px]
    float max_radius;   ///< of the last snapshot [m]
    long vbo_capacity;  ///< particles the sphere buffer holds
    uint8_t *instances; ///< per particle: 4 floats (centre, radius), 4 bytes colour
    long instance_capacity;
    bdl_cull cull;
    uint8_t *visible; ///< per particle, from the occlusion culling
    long visible_capacity;
} bdl_render_particles;

/// Capsule impostors, drawn instead of the spheres when the snapshot has axes (capsules.c).
typedef struct bdl_render_capsules {
    bdl_gl_mesh mesh;   ///< the capsule program; its vertex array takes one box per particle
    long vbo_capacity;  ///< particles the capsule buffer holds
    uint8_t *instances; ///< per particle: 4 floats (centre, radius), 3 (half shaft), 4 bytes colour
    long instance_capacity;
} bdl_render_capsules;

/// What the particles' colours are computed from (colors.c).
typedef struct bdl_render_colors {
    bdl_voidage_grid voidage;
    int voidage_ready;
    float *local_at; ///< per particle, when colouring by voidage or solids fraction: its value
    long local_capacity;
    float range[2]; ///< colour range of the last frame (unit of the field)
} bdl_render_colors;

/// A run of outline vertices that moves with one wall (-1: the domain box).
typedef struct bdl_line_group {
    int wall, first, count;
} bdl_line_group;

/// Domain and wall outlines (outlines.c).
typedef struct bdl_render_outlines {
    bdl_gl_mesh mesh;
    bdl_line_group groups[BDL_MAX_WALLS + 1];
    int group_count;
    float *lines; ///< xyz per vertex
    int line_count, line_capacity;
} bdl_render_outlines;

/// The gas-field slice (slice.c).
typedef struct bdl_render_slice {
    bdl_gl_mesh mesh;
    GLuint texture;
    uint8_t *rgb; ///< the slice's cells as colours
    long rgb_capacity;
    float range[2]; ///< value range of the last slice drawn
    int drawn;      ///< bdl_gas_field of the last slice drawn (BDL_GAS_FIELD_NONE: none)
} bdl_render_slice;

/// One overlay vertex: pixel position, texture coordinate, colour.
typedef struct bdl_overlay_vertex {
    float x, y, u, v;
    uint8_t rgba[4];
} bdl_overlay_vertex;

/// Overlay batches of quads in pixels, one per shader mode.
enum { BDL_OVERLAY_FLAT, BDL_OVERLAY_TEXT, BDL_OVERLAY_COLORMAP, BDL_OVERLAY_MODES };

/// Text and colour bar (overlay.c).
typedef struct bdl_render_overlay {
    bdl_gl_mesh mesh;
    GLuint font_texture, colormap_texture[BDL_CMAP_KINDS];
    bdl_font *font; ///< NULL: no text
    bdl_overlay_vertex *quads[BDL_OVERLAY_MODES];
    int quad_count[BDL_OVERLAY_MODES];
    bdl_colormap_kind bar_map; ///< the map the colour bar shows
} bdl_render_overlay;

struct bdl_renderer {
    bdl_scene scene;
    int headless, width, height, samples;
    GLuint fbo, color_rb, depth_rb, resolve_fbo, resolve_rb; ///< headless only
    long drawn;                                              ///< particles drawn in the last frame
    bdl_render_particles particles;
    bdl_render_capsules capsules;
    bdl_render_colors colors;
    bdl_render_slice slice;
    bdl_render_outlines outlines;
    bdl_render_overlay overlay;
};

// Each part: create its GL objects (0 with a sentence in `why` on failure), draw, free.

int bdl_render_particles_create(bdl_renderer *r, char *why, size_t why_len);
/// Draws the particles that may be seen; returns their number.
long bdl_render_particles_draw(bdl_renderer *r, const bdl_snapshot *s, const bdl_view *v,
                               const bdl_render_frame *f);
void bdl_render_particles_destroy(bdl_renderer *r);
/// The uniforms the sphere and capsule programs share (`points`: the spheres are point sprites).
void bdl_render_particle_uniforms(GLuint prog, const bdl_view *v, const bdl_render_frame *f,
                                  int points);

int bdl_render_capsules_create(bdl_renderer *r, char *why, size_t why_len);
/// Draws the particles particles.c's culling left visible as capsules; returns their number.
long bdl_render_capsules_draw(bdl_renderer *r, const bdl_snapshot *s, const bdl_view *v,
                              const bdl_render_frame *f);
void bdl_render_capsules_destroy(bdl_renderer *r);

/// Computes what the colours of this frame need (voidage, the range) before any is asked for.
void bdl_render_colors_prepare(bdl_renderer *r, const bdl_snapshot *s, const bdl_view *v);
/// The colour of particle i this frame, as bdl_particle_color gives it (sRGB bytes).
void bdl_render_colors_particle(const bdl_renderer *r, const bdl_snapshot *s, const bdl_view *v,
                                long i, uint8_t rgb[3]);
void bdl_render_colors_destroy(bdl_renderer *r);
/// The colour map a mode uses: diverging for signed values, cyclic for the azimuth, else
/// sequential.
bdl_colormap_kind bdl_color_mode_map(bdl_color_mode mode);
/// A colour channel in [0, 1] (clamped) as a byte.
uint8_t bdl_color_byte(float c);

int bdl_render_slice_create(bdl_renderer *r, char *why, size_t why_len);
void bdl_render_slice_draw(bdl_renderer *r, const bdl_snapshot *s, const bdl_view *v,
                           const bdl_render_frame *f);
void bdl_render_slice_destroy(bdl_renderer *r);

/// Builds the outline vertices from the scene (before create uploads them).
void bdl_render_outlines_build(bdl_renderer *r);
int bdl_render_outlines_create(bdl_renderer *r, char *why, size_t why_len);
void bdl_render_outlines_draw(bdl_renderer *r, const bdl_snapshot *s, const bdl_view *v,
                              const bdl_render_frame *f);
void bdl_render_outlines_destroy(bdl_renderer *r);

/// Allocates the quad batches and loads the font (NULL: the default one). Returns 0 when out of
/// memory; a missing font only warns.
int bdl_render_overlay_init(bdl_renderer *r, const char *font_path);
int bdl_render_overlay_create(bdl_renderer *r, char *why, size_t why_len);
void bdl_render_overlay_draw(bdl_renderer *r, const bdl_snapshot *s, const bdl_view *v,
                             const bdl_render_frame *f);
void bdl_render_overlay_destroy(bdl_renderer *r);

// gl_util.c

/// A program linked from two embedded shaders (shaders/NAME); 0 with a sentence in `why`.
GLuint bdl_gl_program(const char *vert, const char *frag, char *why, size_t why_len);

/// The program, vertex array and vertex buffer of a part of the renderer: created with the
/// program linked and the array and buffer bound (0 with a sentence in `why`); destroying one
/// that was never created is fine.
int bdl_gl_mesh_create(bdl_gl_mesh *m, const char *vert, const char *frag, char *why,
                       size_t why_len);
void bdl_gl_mesh_destroy(bdl_gl_mesh *m);
/// A 2D texture of bytes, clamped at the edges.
GLuint bdl_gl_texture_2d(GLenum internal, int w, int h, GLenum format, const void *data,
                         GLint filter);

#endif
