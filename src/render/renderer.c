#include "render/renderer.h"

#include <cglm/cglm.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/voidage.h"
#include "core/log.h"
#include "render/colormap.h"
#include "render/cull.h"
#include "render/font.h"
#include "render/gl.h"

const char *bdl_shader_source(const char *name); // generated from shaders/

#define FONT_PX     15
#define MAX_QUADS   4096
#define CIRCLE_SEGS 64

/// One overlay vertex: pixel position, texture coordinate, colour.
typedef struct overlay_vertex {
    float x, y, u, v;
    uint8_t rgba[4];
} overlay_vertex;

/// A run of outline vertices that moves with one wall (-1: the domain box).
typedef struct line_group {
    int wall, first, count;
} line_group;

struct bdl_renderer {
    bdl_scene scene;
    int headless, width, height, samples;
    GLuint sphere_prog, line_prog, overlay_prog, slice_prog;
    GLuint slice_vao, slice_vbo, slice_tex;
    uint8_t *slice_rgb; ///< the slice's cells as colours
    long slice_rgb_capacity;
    float slice_range[2]; ///< value range of the last slice drawn
    int slice_drawn;
    GLuint sphere_vao, point_vao, sphere_vbo;
    float point_max;   ///< largest point size the driver draws [px]
    float max_radius;  ///< of the last snapshot [m]
    long vbo_capacity; ///< particles the sphere buffer holds
    bdl_cull cull;
    uint8_t *visible; ///< per particle, from the occlusion culling
    long visible_capacity;
    long drawn; ///< particles drawn in the last frame
    GLuint line_vao, line_vbo;
    GLuint overlay_vao, overlay_vbo;
    GLuint font_tex, cmap_tex[2];
    GLuint fbo, color_rb, depth_rb, resolve_fbo, resolve_rb;
    bdl_font *font;
    line_group groups[BDL_MAX_WALLS + 1];
    int group_count;
    float *lines; ///< xyz per vertex
    int line_count, line_capacity;
    uint8_t *instances; ///< per particle: 4 floats (centre, radius), 4 bytes colour
    long instance_capacity;
    overlay_vertex *quads[3]; ///< per overlay mode: 0 flat, 1 text, 2 colour map
    int quad_count[3];
    bdl_voidage_grid voidage;
    int voidage_ready;
    float *voidage_at; ///< per particle, when colouring by voidage
    long voidage_capacity;
    float last_range[2];
    int bar_diverging; ///< the colour bar shows the diverging map
};

// ---------------------------------------------------------------------------------------------
// Colours.

const char *bdl_color_mode_label(bdl_color_mode mode)
{
    return (unsigned)mode < BDL_COLOR_MODE_COUNT ? bdl_color_mode_labels[mode] : "?";
}

const char *bdl_color_mode_unit(bdl_color_mode mode)
{
    return (unsigned)mode < BDL_COLOR_MODE_COUNT ? bdl_color_mode_units[mode] : "";
}

static int diverging(bdl_color_mode mode)
{
    return mode == BDL_COLOR_VX || mode == BDL_COLOR_VY || mode == BDL_COLOR_VZ;
}

/// The scalar a mode maps through the colour map.
static float field_value(bdl_color_mode mode, const bdl_snapshot *s, long i, float voidage)
{
    const float *v = &s->vel[3 * i];
    switch (mode) {
    case BDL_COLOR_COORDINATION:
        return (float)s->coordination[i];
    case BDL_COLOR_SPEED:
        return sqrtf(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    case BDL_COLOR_VX:
    case BDL_COLOR_VY:
    case BDL_COLOR_VZ:
        return v[mode - BDL_COLOR_VX];
    case BDL_COLOR_VOIDAGE:
        return voidage;
    default:
        return 0.0f;
    }
}

static uint8_t to_byte(float c)
{
    c = c < 0.0f ? 0.0f : (c > 1.0f ? 1.0f : c);
    return (uint8_t)lrintf(255.0f * c);
}

void bdl_particle_color(bdl_color_mode mode, const bdl_snapshot *snap, long i, float voidage,
                        const float range[2], uint8_t rgb[3])
{
    float c[3];
    if (mode == BDL_COLOR_SPECIES) {
        bdl_category_color(snap->species[i], c);
    } else {
        float x = field_value(mode, snap, i, voidage);
        float span = range[1] - range[0];
        float t = span > 0.0f ? (x - range[0]) / span : 0.5f;
        bdl_colormap_eval(diverging(mode) ? BDL_CMAP_DIVERGING : BDL_CMAP_SEQUENTIAL, t, c);
    }
    for (int k = 0; k < 3; ++k)
        rgb[k] = to_byte(c[k]);
}

/// The data's range for automatic colouring: speeds from 0, velocity components symmetric about
/// 0, coordination numbers from 0 in whole steps.
static void auto_range(const bdl_renderer *r, bdl_color_mode mode, const bdl_snapshot *s,
                       float range[2])
{
    float lo = INFINITY, hi = -INFINITY;
    for (long i = 0; i < s->count; ++i) {
        float x = field_value(mode, s, i, r->voidage_at ? r->voidage_at[i] : 1.0f);
        lo = fminf(lo, x);
        hi = fmaxf(hi, x);
    }
    if (s->count == 0)
        lo = hi = 0.0f;
    switch (mode) {
    case BDL_COLOR_COORDINATION:
        range[0] = 0.0f;
        range[1] = fmaxf(hi, 1.0f);
        break;
    case BDL_COLOR_SPEED:
        range[0] = 0.0f;
        range[1] = hi > 0.0f ? hi : 1.0f;
        break;
    case BDL_COLOR_VX:
    case BDL_COLOR_VY:
    case BDL_COLOR_VZ: {
        float m = fmaxf(fabsf(lo), fabsf(hi));
        range[0] = m > 0.0f ? -m : -1.0f;
        range[1] = m > 0.0f ? m : 1.0f;
        break;
    }
    default:
        range[0] = lo;
        range[1] = hi > lo ? hi : lo + 1.0f;
        break;
    }
}

static void compute_voidage(bdl_renderer *r, const bdl_snapshot *s)
{
    if (!r->voidage_ready) {
        double lo[3] = {r->scene.domain_min.x, r->scene.domain_min.y, r->scene.domain_min.z};
        double hi[3] = {r->scene.domain_max.x, r->scene.domain_max.y, r->scene.domain_max.z};
        double d = 0.0;
        for (int k = 0; k < r->scene.species_count; ++k)
            d = fmax(d, fmax(r->scene.species[k].diameter, r->scene.species[k].diameter_max));
        // Cells of three diameters: enough particles per cell for a mean, small enough to
        // resolve bubbles and the free surface.
        if (bdl_voidage_grid_init(&r->voidage, lo, hi, 3.0 * d, r->scene.periodic) != BDL_OK)
            return;
        r->voidage_ready = 1;
    }
    if (s->count > r->voidage_capacity) {
        float *a = realloc(r->voidage_at, (size_t)s->count * sizeof(float));
        if (!a)
            return;
        r->voidage_at = a;
        r->voidage_capacity = s->count;
    }
    bdl_voidage_deposit(&r->voidage, s->count, s->pos, s->radius);
    for (long i = 0; i < s->count; ++i)
        r->voidage_at[i] = bdl_voidage_at(&r->voidage, &s->pos[3 * i]);
}

// ---------------------------------------------------------------------------------------------
// GL objects.

static GLuint compile(GLenum kind, const char *name, char *why, size_t why_len)
{
    const char *source = bdl_shader_source(name);
    if (!source) {
        snprintf(why, why_len, "shader %s is not embedded", name);
        return 0;
    }
    GLuint s = glCreateShader(kind);
    glShaderSource(s, 1, &source, NULL);
    glCompileShader(s);
    GLint ok = 0;
    glGetShaderiv(s, GL_COMPILE_STATUS, &ok);
    if (!ok) {
        char log[1024] = "";
        glGetShaderInfoLog(s, sizeof log, NULL, log);
        snprintf(why, why_len, "shader %s does not compile: %s", name, log);
        glDeleteShader(s);
        return 0;
    }
    return s;
}

static GLuint program(const char *vert, const char *frag, char *why, size_t why_len)
{
    GLuint v = compile(GL_VERTEX_SHADER, vert, why, why_len);
    GLuint f = v ? compile(GL_FRAGMENT_SHADER, frag, why, why_len) : 0;
    if (!f) {
        if (v)
            glDeleteShader(v);
        return 0;
    }
    GLuint p = glCreateProgram();
    glAttachShader(p, v);
    glAttachShader(p, f);
    glLinkProgram(p);
    glDeleteShader(v);
    glDeleteShader(f);
    GLint ok = 0;
    glGetProgramiv(p, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[1024] = "";
        glGetProgramInfoLog(p, sizeof log, NULL, log);
        snprintf(why, why_len, "shaders %s + %s do not link: %s", vert, frag, log);
        glDeleteProgram(p);
        return 0;
    }
    return p;
}

static GLuint texture_2d(GLenum internal, int w, int h, GLenum format, const void *data,
                         GLint filter)
{
    GLuint t;
    glGenTextures(1, &t);
    glBindTexture(GL_TEXTURE_2D, t);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexImage2D(GL_TEXTURE_2D, 0, (GLint)internal, w, h, 0, format, GL_UNSIGNED_BYTE, data);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, filter);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, filter);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return t;
}

static int make_framebuffer(bdl_renderer *r, char *why, size_t why_len)
{
    glGenFramebuffers(1, &r->fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, r->fbo);
    glGenRenderbuffers(1, &r->color_rb);
    glBindRenderbuffer(GL_RENDERBUFFER, r->color_rb);
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, r->samples, GL_RGBA8, r->width, r->height);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, r->color_rb);
    glGenRenderbuffers(1, &r->depth_rb);
    glBindRenderbuffer(GL_RENDERBUFFER, r->depth_rb);
    glRenderbufferStorageMultisample(GL_RENDERBUFFER, r->samples, GL_DEPTH_COMPONENT24, r->width,
                                     r->height);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, r->depth_rb);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
        snprintf(why, why_len, "no %dx%d framebuffer with %d samples", r->width, r->height,
                 r->samples);
        return 0;
    }
    // Multisampled pixels cannot be read directly: they are resolved into a plain one.
    glGenFramebuffers(1, &r->resolve_fbo);
    glBindFramebuffer(GL_FRAMEBUFFER, r->resolve_fbo);
    glGenRenderbuffers(1, &r->resolve_rb);
    glBindRenderbuffer(GL_RENDERBUFFER, r->resolve_rb);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, r->width, r->height);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, r->resolve_rb);
    if (glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
        snprintf(why, why_len, "no %dx%d resolve framebuffer", r->width, r->height);
        return 0;
    }
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    return 1;
}

static void make_vertex_arrays(bdl_renderer *r)
{
    glGenVertexArrays(1, &r->sphere_vao);
    glBindVertexArray(r->sphere_vao);
    glGenBuffers(1, &r->sphere_vbo);
    glBindBuffer(GL_ARRAY_BUFFER, r->sphere_vbo);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 4, GL_FLOAT, GL_FALSE, 20, (void *)0);
    glVertexAttribDivisor(0, 1);
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 4, GL_UNSIGNED_BYTE, GL_TRUE, 20, (void *)16);
    glVertexAttribDivisor(1, 1);
    // The same buffer as one point per particle.
    glGenVertexArrays(1, &r->point_vao);
    glBindVertexArray(r->point_vao);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 4, GL_FLOAT, GL_FALSE, 20, (void *)0);
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 4, GL_UNSIGNED_BYTE, GL_TRUE, 20, (void *)16);
    GLfloat range[2] = {1.0f, 1.0f};
    glGetFloatv(GL_POINT_SIZE_RANGE, range);
    r->point_max = range[1];

    glGenVertexArrays(1, &r->line_vao);
    glBindVertexArray(r->line_vao);
    glGenBuffers(1, &r->line_vbo);
    glBindBuffer(GL_ARRAY_BUFFER, r->line_vbo);
    glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)r->line_count * 3 * (GLsizeiptr)sizeof(float),
                 r->lines, GL_STATIC_DRAW);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 12, (void *)0);

    glGenVertexArrays(1, &r->overlay_vao);
    glBindVertexArray(r->overlay_vao);
    glGenBuffers(1, &r->overlay_vbo);
    glBindBuffer(GL_ARRAY_BUFFER, r->overlay_vbo);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, sizeof(overlay_vertex), (void *)0);
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 2, GL_FLOAT, GL_FALSE, sizeof(overlay_vertex), (void *)8);
    glEnableVertexAttribArray(2);
    glVertexAttribPointer(2, 4, GL_UNSIGNED_BYTE, GL_TRUE, sizeof(overlay_vertex), (void *)16);

    // The gas slice: 6 vertices of xyz and uv.
    glGenVertexArrays(1, &r->slice_vao);
    glBindVertexArray(r->slice_vao);
    glGenBuffers(1, &r->slice_vbo);
    glBindBuffer(GL_ARRAY_BUFFER, r->slice_vbo);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 20, (void *)0);
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 2, GL_FLOAT, GL_FALSE, 20, (void *)12);
    glBindVertexArray(0);
}

static void make_textures(bdl_renderer *r)
{
    uint8_t table[BDL_COLORMAP_SIZE][3];
    bdl_colormap_table(BDL_CMAP_SEQUENTIAL, table);
    r->cmap_tex[0] = texture_2d(GL_RGB8, BDL_COLORMAP_SIZE, 1, GL_RGB, table, GL_LINEAR);
    bdl_colormap_table(BDL_CMAP_DIVERGING, table);
    r->cmap_tex[1] = texture_2d(GL_RGB8, BDL_COLORMAP_SIZE, 1, GL_RGB, table, GL_LINEAR);
    if (r->font) {
        int w, h;
        const uint8_t *atlas = bdl_font_atlas(r->font, &w, &h);
        r->font_tex = texture_2d(GL_R8, w, h, GL_RED, atlas, GL_NEAREST);
    }
}

// ---------------------------------------------------------------------------------------------
// Outlines of the domain and the walls, as line segments.

static int push_vertex(bdl_renderer *r, bdl_vec3 p)
{
    if (r->line_count == r->line_capacity) {
        int cap = r->line_capacity ? 2 * r->line_capacity : 256;
        float *a = realloc(r->lines, (size_t)cap * 3 * sizeof(float));
        if (!a)
            return 0;
        r->lines = a;
        r->line_capacity = cap;
    }
    float *v = &r->lines[3 * r->line_count++];
    v[0] = (float)p.x;
    v[1] = (float)p.y;
    v[2] = (float)p.z;
    return 1;
}

static void push_segment(bdl_renderer *r, bdl_vec3 a, bdl_vec3 b)
{
    push_vertex(r, a);
    push_vertex(r, b);
}

static bdl_vec3 corner(bdl_vec3 lo, bdl_vec3 hi, int k)
{
    return bdl_v3((k & 1) ? hi.x : lo.x, (k & 2) ? hi.y : lo.y, (k & 4) ? hi.z : lo.z);
}

static void push_box(bdl_renderer *r, bdl_vec3 lo, bdl_vec3 hi)
{
    for (int k = 0; k < 8; ++k)
        for (int axis = 0; axis < 3; ++axis)
            if (!(k & (1 << axis)))
                push_segment(r, corner(lo, hi, k), corner(lo, hi, k | (1 << axis)));
}

/// Two unit vectors spanning the plane normal to n.
static void basis(bdl_vec3 n, bdl_vec3 *u, bdl_vec3 *v)
{
    bdl_vec3 a = fabs(n.x) < 0.9 ? bdl_v3(1, 0, 0) : bdl_v3(0, 1, 0);
    *u = bdl_v3_normalize(bdl_v3_cross(n, a));
    *v = bdl_v3_cross(n, *u);
}

/// The polygon where a plane cuts the domain box, its corners sorted by angle.
static void push_plane(bdl_renderer *r, bdl_vec3 point, bdl_vec3 n, bdl_vec3 lo, bdl_vec3 hi)
{
    bdl_vec3 hits[12];
    int count = 0;
    for (int k = 0; k < 8; ++k)
        for (int axis = 0; axis < 3; ++axis) {
            if (k & (1 << axis))
                continue;
            bdl_vec3 a = corner(lo, hi, k), b = corner(lo, hi, k | (1 << axis));
            double da = bdl_v3_dot(bdl_v3_sub(a, point), n);
            double db = bdl_v3_dot(bdl_v3_sub(b, point), n);
            if ((da <= 0.0 && db > 0.0) || (da > 0.0 && db <= 0.0) || (da == 0.0 && db == 0.0))
                hits[count++] =
                    bdl_v3_add(a, bdl_v3_scale(bdl_v3_sub(b, a), da == db ? 0.0 : da / (da - db)));
        }
    if (count < 3)
        return;
    bdl_vec3 c = bdl_v3_zero();
    for (int k = 0; k < count; ++k)
        c = bdl_v3_add(c, hits[k]);
    c = bdl_v3_scale(c, 1.0 / count);
    bdl_vec3 u, v;
    basis(n, &u, &v);
    double angle[12];
    for (int k = 0; k < count; ++k) {
        bdl_vec3 q = bdl_v3_sub(hits[k], c);
        angle[k] = atan2(bdl_v3_dot(q, v), bdl_v3_dot(q, u));
    }
    for (int i = 1; i < count; ++i) // insertion sort by angle
        for (int j = i; j > 0 && angle[j] < angle[j - 1]; --j) {
            double ta = angle[j];
            angle[j] = angle[j - 1];
            angle[j - 1] = ta;
            bdl_vec3 th = hits[j];
            hits[j] = hits[j - 1];
            hits[j - 1] = th;
        }
    for (int k = 0; k < count; ++k)
        push_segment(r, hits[k], hits[(k + 1) % count]);
}

/// Circles where the cylinder leaves the domain box, and four lines along it.
static void push_cylinder(bdl_renderer *r, bdl_vec3 point, bdl_vec3 axis, double radius,
                          bdl_vec3 lo, bdl_vec3 hi)
{
    double t0 = INFINITY, t1 = -INFINITY;
    for (int k = 0; k < 8; ++k) {
        double t = bdl_v3_dot(bdl_v3_sub(corner(lo, hi, k), point), axis);
        t0 = fmin(t0, t);
        t1 = fmax(t1, t);
    }
    bdl_vec3 u, v;
    basis(axis, &u, &v);
    for (int end = 0; end < 2; ++end) {
        bdl_vec3 c = bdl_v3_add(point, bdl_v3_scale(axis, end ? t1 : t0));
        for (int s = 0; s < CIRCLE_SEGS; ++s) {
            double a = 2.0 * BDL_PI * s / CIRCLE_SEGS, b = 2.0 * BDL_PI * (s + 1) / CIRCLE_SEGS;
            push_segment(r,
                         bdl_v3_add(c, bdl_v3_add(bdl_v3_scale(u, radius * cos(a)),
                                                  bdl_v3_scale(v, radius * sin(a)))),
                         bdl_v3_add(c, bdl_v3_add(bdl_v3_scale(u, radius * cos(b)),
                                                  bdl_v3_scale(v, radius * sin(b)))));
        }
    }
    for (int s = 0; s < 4; ++s) {
        bdl_vec3 off = bdl_v3_scale(s & 1 ? v : u, s & 2 ? -radius : radius);
        push_segment(r, bdl_v3_add(bdl_v3_add(point, bdl_v3_scale(axis, t0)), off),
                     bdl_v3_add(bdl_v3_add(point, bdl_v3_scale(axis, t1)), off));
    }
}

static void build_outlines(bdl_renderer *r)
{
    const bdl_scene *s = &r->scene;
    r->groups[0] = (line_group){-1, 0, 0};
    push_box(r, s->domain_min, s->domain_max);
    r->groups[0].count = r->line_count;
    r->group_count = 1;
    for (int w = 0; w < s->wall_count; ++w) {
        const bdl_wall_def *d = &s->walls[w];
        int first = r->line_count;
        if (d->kind == BDL_WALL_BOX)
            push_box(r, d->box_min, d->box_max);
        else if (d->kind == BDL_WALL_PLANE)
            push_plane(r, d->point, d->normal, s->domain_min, s->domain_max);
        else
            push_cylinder(r, d->point, d->normal, d->radius, s->domain_min, s->domain_max);
        r->groups[r->group_count++] = (line_group){w, first, r->line_count - first};
    }
}

// ---------------------------------------------------------------------------------------------
// Overlay: quads in pixels, in three batches (flat, text, colour map).

static void quad(bdl_renderer *r, int mode, float x0, float y0, float x1, float y1, float u0,
                 float v0, float u1, float v1, const uint8_t rgba[4])
{
    if (r->quad_count[mode] >= MAX_QUADS)
        return;
    overlay_vertex *q = &r->quads[mode][6 * r->quad_count[mode]++];
    overlay_vertex c[4] = {
        {x0, y0, u0, v0, {0}}, {x1, y0, u1, v0, {0}}, {x1, y1, u1, v1, {0}}, {x0, y1, u0, v1, {0}}};
    static const int order[6] = {0, 1, 2, 0, 2, 3};
    for (int k = 0; k < 6; ++k) {
        q[k] = c[order[k]];
        memcpy(q[k].rgba, rgba, 4);
    }
}

static void rect(bdl_renderer *r, float x0, float y0, float x1, float y1, const uint8_t rgba[4])
{
    quad(r, 0, x0, y0, x1, y1, 0, 0, 0, 0, rgba);
}

static const uint8_t text_color[4] = {235, 235, 235, 255};

/// Text with its top-left corner at (x, y), on a dark shadow so it reads on any background.
static void text(bdl_renderer *r, float x, float y, const char *s, const uint8_t rgba[4])
{
    if (!r->font)
        return;
    bdl_glyph_quad g[256];
    float base = y + bdl_font_ascent(r->font);
    static const uint8_t shadow[4] = {0, 0, 0, 200};
    for (int pass = 0; pass < 2; ++pass) {
        float o = pass == 0 ? 1.0f : 0.0f;
        int n = bdl_font_layout(r->font, s, x + o, base + o, g, 256);
        for (int k = 0; k < n; ++k)
            quad(r, 1, g[k].x0, g[k].y0, g[k].x1, g[k].y1, g[k].u0, g[k].v0, g[k].u1, g[k].v1,
                 pass == 0 ? shadow : rgba);
    }
}

static float text_width(const bdl_renderer *r, const char *s)
{
    return r->font ? bdl_font_text_width(r->font, s) : 0.0f;
}

static void format_value(char *buf, size_t size, float x)
{
    snprintf(buf, size, "%.3g", fabsf(x) < 1e-7f ? 0.0f : x);
}

/// A continuous colour bar on the right: the map, labels at both ends and the middle.
static void colour_bar(bdl_renderer *r, const bdl_view *v, int width, int height)
{
    float x0 = (float)width - 80.0f, x1 = x0 + 16.0f;
    float y0 = 0.3f * (float)height, y1 = 0.7f * (float)height;
    static const uint8_t frame[4] = {20, 20, 20, 255};
    rect(r, x0 - 1, y0 - 1, x1 + 1, y1 + 1, frame);
    // The map runs bottom (low) to top (high).
    quad(r, 2, x0, y0, x1, y1, 1.0f, 0.5f, 1.0f, 0.5f, text_color);
    overlay_vertex *q = &r->quads[2][6 * (r->quad_count[2] - 1)];
    for (int k = 0; k < 6; ++k)
        q[k].u = q[k].y == y0 ? 1.0f : 0.0f;
    float lh = r->font ? bdl_font_line_height(r->font) : 0.0f;
    for (int k = 0; k < 3; ++k) {
        float t = 0.5f * (float)k;
        char label[32];
        format_value(label, sizeof label,
                     r->last_range[0] + t * (r->last_range[1] - r->last_range[0]));
        float y = y1 - t * (y1 - y0);
        rect(r, x1, y - 0.5f, x1 + 4, y + 0.5f, text_color);
        text(r, x1 + 9, y - 0.5f * lh, label, text_color);
    }
    char title[64];
    const char *unit = bdl_color_mode_unit(v->color);
    snprintf(title, sizeof title, "%s%s%s%s", bdl_color_mode_label(v->color), unit[0] ? " [" : "",
             unit, unit[0] ? "]" : "");
    float w = text_width(r, title);
    text(r, fminf(x0, (float)width - w - 8.0f), y0 - 1.6f * lh, title, text_color);
}

/// A discrete legend: one swatch per coordination number or species.
static void legend(bdl_renderer *r, const bdl_view *v, int width, int height)
{
    int discrete_count;
    if (v->color == BDL_COLOR_SPECIES)
        discrete_count = r->scene.species_count;
    else
        discrete_count = (int)lrintf(r->last_range[1] - r->last_range[0]) + 1;
    if (discrete_count > 16)
        discrete_count = 16;
    float lh = r->font ? bdl_font_line_height(r->font) : 14.0f;
    float box = fminf(lh, 0.4f * (float)height / (float)discrete_count);
    float x0 = (float)width - 110.0f;
    float y = 0.5f * (float)height + 0.5f * box * (float)discrete_count;
    bdl_snapshot one = {0};
    int32_t species;
    uint8_t coordination;
    one.species = &species;
    one.coordination = &coordination;
    one.count = 1;
    float zero_vel[3] = {0, 0, 0};
    one.vel = zero_vel;
    for (int k = 0; k < discrete_count; ++k) {
        uint8_t rgb[3];
        species = k;
        coordination = (uint8_t)(r->last_range[0] + (float)k);
        bdl_particle_color(v->color, &one, 0, 0.0f, r->last_range, rgb);
        uint8_t rgba[4] = {rgb[0], rgb[1], rgb[2], 255};
        float top = y - box * (float)(k + 1);
        rect(r, x0, top + 1, x0 + box - 2, top + box - 1, rgba);
        char label[64];
        if (v->color == BDL_COLOR_SPECIES)
            snprintf(label, sizeof label, "%s", r->scene.species[k].name);
        else
            snprintf(label, sizeof label, "%d", (int)coordination);
        text(r, x0 + box + 4, top + 0.5f * (box - lh), label, text_color);
    }
    const char *title = bdl_color_mode_label(v->color);
    text(r, fminf(x0, (float)width - text_width(r, title) - 8.0f),
         y - box * (float)discrete_count - 1.6f * lh, title, text_color);
}

static void help_box(bdl_renderer *r, const char *help, int width, int height)
{
    float lh = bdl_font_line_height(r->font);
    int lines = 1;
    float w = 0.0f;
    char line[256];
    for (const char *s = help; *s;) {
        const char *e = strchr(s, '\n');
        size_t n = e ? (size_t)(e - s) : strlen(s);
        snprintf(line, sizeof line, "%.*s", (int)(n < 255 ? n : 255), s);
        w = fmaxf(w, text_width(r, line));
        s += n + (e != NULL);
        lines += e != NULL;
    }
    float x0 = 0.5f * ((float)width - w) - 16.0f, y0 = 0.5f * ((float)height - lh * lines) - 12.0f;
    static const uint8_t shade[4] = {10, 12, 16, 215};
    rect(r, x0, y0, x0 + w + 32.0f, y0 + lh * lines + 24.0f, shade);
    text(r, x0 + 16.0f, y0 + 12.0f, help, text_color);
}

static void build_overlay(bdl_renderer *r, const bdl_snapshot *s, const bdl_view *v, int width,
                          int height)
{
    r->quad_count[0] = r->quad_count[1] = r->quad_count[2] = 0;
    r->bar_diverging = diverging(v->color);
    if (!v->overlay && !v->help)
        return;
    if (v->overlay) {
        char line[256];
        snprintf(line, sizeof line, "t = %.5f s   step %ld   %ld particles", s->time, s->step,
                 s->count);
        float lh = r->font ? bdl_font_line_height(r->font) : 0.0f;
        text(r, 10, 8, line, text_color);
        float y = 8 + lh;
        if (v->status)
            text(r, 10, y, v->status, text_color), y += lh;
        if (r->slice_drawn > 0 && r->slice_drawn < 4) {
            char lo[32], hi[32];
            format_value(lo, sizeof lo, r->slice_range[0]);
            format_value(hi, sizeof hi, r->slice_range[1]);
            snprintf(line, sizeof line, "slice: %s %s to %s %s",
                     bdl_gas_field_labels[r->slice_drawn], lo, hi,
                     bdl_gas_field_units[r->slice_drawn]);
            text(r, 10, y, line, text_color);
        }
        if (v->color == BDL_COLOR_SPECIES || v->color == BDL_COLOR_COORDINATION)
            legend(r, v, width, height);
        else
            colour_bar(r, v, width, height);
    }
    if (v->help && r->font)
        help_box(r, v->help, width, height);
}

static void draw_overlay(bdl_renderer *r, int width, int height)
{
    glDisable(GL_DEPTH_TEST);
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    glUseProgram(r->overlay_prog);
    glUniform2f(glGetUniformLocation(r->overlay_prog, "u_viewport"), (float)width, (float)height);
    glUniform1i(glGetUniformLocation(r->overlay_prog, "u_texture"), 0);
    glBindVertexArray(r->overlay_vao);
    glBindBuffer(GL_ARRAY_BUFFER, r->overlay_vbo);
    glActiveTexture(GL_TEXTURE0);
    // Flat shapes first, then the colour map, then text on top.
    static const int order[3] = {0, 2, 1};
    for (int k = 0; k < 3; ++k) {
        int mode = order[k];
        if (r->quad_count[mode] == 0)
            continue;
        if (mode == 1)
            glBindTexture(GL_TEXTURE_2D, r->font_tex);
        if (mode == 2)
            glBindTexture(GL_TEXTURE_2D, r->cmap_tex[r->bar_diverging]);
        glUniform1i(glGetUniformLocation(r->overlay_prog, "u_mode"), mode);
        GLsizeiptr bytes = (GLsizeiptr)r->quad_count[mode] * 6 * (GLsizeiptr)sizeof(overlay_vertex);
        glBufferData(GL_ARRAY_BUFFER, bytes, r->quads[mode], GL_STREAM_DRAW);
        glDrawArrays(GL_TRIANGLES, 0, 6 * r->quad_count[mode]);
    }
    glDisable(GL_BLEND);
}

// ---------------------------------------------------------------------------------------------
// Frames.

void bdl_view_from_scene(const bdl_scene *scene, float aspect, bdl_view *view)
{
    const bdl_camera_def *d = &scene->camera;
    memset(view, 0, sizeof *view);
    bdl_camera_from_scene(scene, &view->camera);
    if (view->camera.distance <= 0.0f) {
        float lo[3] = {(float)scene->domain_min.x, (float)scene->domain_min.y,
                       (float)scene->domain_min.z};
        float hi[3] = {(float)scene->domain_max.x, (float)scene->domain_max.y,
                       (float)scene->domain_max.z};
        bdl_camera_fit(&view->camera, lo, hi, aspect);
    }
    view->color = d->color;
    view->range_fixed = d->has_color_min && d->has_color_max;
    view->range[0] = (float)d->color_min;
    view->range[1] = (float)d->color_max;
    view->clip = d->clip;
    bdl_vec3 cp = d->has_clip_point ? d->clip_point
                                    : bdl_v3(view->camera.target[0], view->camera.target[1],
                                             view->camera.target[2]);
    view->clip_point[0] = (float)cp.x;
    view->clip_point[1] = (float)cp.y;
    view->clip_point[2] = (float)cp.z;
    view->clip_normal[0] = (float)d->clip_normal.x;
    view->clip_normal[1] = (float)d->clip_normal.y;
    view->clip_normal[2] = (float)d->clip_normal.z;
    view->lighting = d->lighting;
    view->overlay = d->overlay;
    view->outlines = d->outlines;
    view->background[0] = (float)d->background.x;
    view->background[1] = (float)d->background.y;
    view->background[2] = (float)d->background.z;
    view->gas_opacity = d->gas_field != BDL_GAS_FIELD_NONE ? (float)d->gas_opacity : 0.0f;
}

static int reserve_instances(bdl_renderer *r, long n)
{
    if (n <= r->instance_capacity)
        return 1;
    long cap = n + n / 4 + 64;
    uint8_t *a = realloc(r->instances, (size_t)cap * 20);
    if (!a)
        return 0;
    r->instances = a;
    r->instance_capacity = cap;
    return 1;
}

/// Writes the instance data of the particles that may be seen; returns their number.
static long fill_instances(bdl_renderer *r, const bdl_snapshot *s, const bdl_view *v,
                           const float *view, const float *proj, int width, int height)
{
    if (s->count > r->visible_capacity) {
        uint8_t *a = realloc(r->visible, (size_t)s->count);
        if (!a)
            return 0;
        r->visible = a;
        r->visible_capacity = s->count;
    }
    float clip[4];
    const float *n = v->clip_normal, *q = v->clip_point;
    clip[0] = n[0], clip[1] = n[1], clip[2] = n[2];
    clip[3] = -(n[0] * q[0] + n[1] * q[1] + n[2] * q[2]);
    if (v->no_culling)
        memset(r->visible, 1, (size_t)s->count);
    else
        bdl_cull_spheres(&r->cull, s->pos, s->radius, s->count, view, proj, v->camera.ortho, width,
                         height, v->clip ? clip : NULL, r->visible);
    if (v->color == BDL_COLOR_VOIDAGE)
        compute_voidage(r, s);
    if (v->range_fixed) {
        r->last_range[0] = v->range[0];
        r->last_range[1] = v->range[1];
    } else if (v->color != BDL_COLOR_SPECIES) {
        auto_range(r, v->color, s, r->last_range);
    }
    float rmax = 0.0f;
    long m = 0;
    for (long i = 0; i < s->count; ++i) {
        if (!r->visible[i])
            continue;
        rmax = fmaxf(rmax, s->radius[i]);
        uint8_t *out = &r->instances[20 * m++];
        float sphere[4] = {s->pos[3 * i], s->pos[3 * i + 1], s->pos[3 * i + 2], s->radius[i]};
        memcpy(out, sphere, 16);
        float voidage = r->voidage_at && v->color == BDL_COLOR_VOIDAGE ? r->voidage_at[i] : 1.0f;
        bdl_particle_color(v->color, s, i, voidage, r->last_range, out + 16);
        out[19] = 255;
    }
    r->max_radius = rmax;
    return m;
}

/// Whether every sphere fits in a point sprite: its projected size, bounded from the nearest
/// particle depth, with room for the stretch of off-axis spheres in perspective.
static int points_fit(const bdl_renderer *r, const bdl_snapshot *s, const bdl_view *v,
                      const float *view, int height)
{
    float half = bdl_camera_half_height(&v->camera);
    float ppm = 0.5f * (float)height / half; // pixels per metre at the target's depth
    float size;
    if (v->camera.ortho) {
        size = 2.0f * r->max_radius * ppm;
    } else {
        float nearest = INFINITY;
        for (long i = 0; i < s->count; ++i) {
            const float *p = &s->pos[3 * i];
            float z = -(view[2] * p[0] + view[6] * p[1] + view[10] * p[2] + view[14]);
            nearest = fminf(nearest, z);
        }
        float depth = nearest - r->max_radius;
        if (!(depth > 0.0f))
            return 0;
        size = 2.0f * 1.5f * r->max_radius * ppm * v->camera.distance / depth;
    }
    return size + 2.0f < r->point_max;
}

/// The light comes from above-left of the viewer (view space, towards the light).
static void light_direction(float l[3])
{
    vec3 d = {-0.35f, 0.55f, 0.76f};
    glm_vec3_normalize(d);
    memcpy(l, d, sizeof d);
}

void bdl_shade(const float base[3], const float n[3], const float view[3], float out[3])
{
    float l[3];
    light_direction(l);
    vec3 h = {l[0] + view[0], l[1] + view[1], l[2] + view[2]};
    glm_vec3_normalize(h);
    float diffuse = fmaxf(n[0] * l[0] + n[1] * l[1] + n[2] * l[2], 0.0f);
    float specular = powf(fmaxf(n[0] * h[0] + n[1] * h[1] + n[2] * h[2], 0.0f), 48.0f);
    for (int k = 0; k < 3; ++k)
        out[k] = base[k] * (0.35f + 0.65f * diffuse) + 0.22f * specular;
}

static void draw_spheres(bdl_renderer *r, const bdl_snapshot *s, long count, const bdl_view *v,
                         const float *view, const float *proj, int width, int height)
{
    int points = points_fit(r, s, v, view, height);
    glUseProgram(r->sphere_prog);
    GLuint p = r->sphere_prog;
    glUniformMatrix4fv(glGetUniformLocation(p, "u_view"), 1, GL_FALSE, view);
    glUniformMatrix4fv(glGetUniformLocation(p, "u_proj"), 1, GL_FALSE, proj);
    glUniform1i(glGetUniformLocation(p, "u_ortho"), v->camera.ortho);
    glUniform2f(glGetUniformLocation(p, "u_viewport"), (float)width, (float)height);
    glUniform1i(glGetUniformLocation(p, "u_lighting"), v->lighting);
    glUniform1i(glGetUniformLocation(p, "u_clip_on"), v->clip);
    const float *n = v->clip_normal, *q = v->clip_point;
    glUniform4f(glGetUniformLocation(p, "u_clip"), n[0], n[1], n[2],
                -(n[0] * q[0] + n[1] * q[1] + n[2] * q[2]));
    vec3 light;
    light_direction(light);
    glUniform3f(glGetUniformLocation(p, "u_light"), light[0], light[1], light[2]);
    glUniform1i(glGetUniformLocation(p, "u_points"), points);
    glBindBuffer(GL_ARRAY_BUFFER, r->sphere_vbo);
    // Storage is reallocated only when the particles outgrow it: a fresh allocation each frame
    // costs page faults in a software driver.
    if (count > r->vbo_capacity) {
        r->vbo_capacity = count + count / 4;
        glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)r->vbo_capacity * 20, NULL, GL_DYNAMIC_DRAW);
    }
    glBufferSubData(GL_ARRAY_BUFFER, 0, (GLsizeiptr)count * 20, r->instances);
    if (points) {
        glEnable(GL_PROGRAM_POINT_SIZE);
        glBindVertexArray(r->point_vao);
        glDrawArrays(GL_POINTS, 0, (GLsizei)count);
    } else {
        glBindVertexArray(r->sphere_vao);
        glDrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, (GLsizei)count);
    }
}

/// The snapshot's gas-field slice: one flat colour per cell (sequential map over the slice's
/// range), blended over what is behind it; particles in front of it hide it.
static void draw_slice(bdl_renderer *r, const bdl_snapshot *s, const bdl_view *v,
                       const float *view_proj)
{
    r->slice_drawn = 0;
    const long cells = (long)s->slice_n[0] * s->slice_n[1];
    if (cells <= 0 || !s->slice || !(v->gas_opacity > 0.0f))
        return;
    if (cells > r->slice_rgb_capacity) {
        uint8_t *p = realloc(r->slice_rgb, (size_t)cells * 3);
        if (!p)
            return;
        r->slice_rgb = p;
        r->slice_rgb_capacity = cells;
    }
    float lo = s->slice[0], hi = s->slice[0];
    for (long c = 1; c < cells; ++c)
        lo = fminf(lo, s->slice[c]), hi = fmaxf(hi, s->slice[c]);
    const float span = hi > lo ? hi - lo : 1.0f;
    for (long c = 0; c < cells; ++c) {
        float rgb[3];
        bdl_colormap_eval(BDL_CMAP_SEQUENTIAL, (s->slice[c] - lo) / span, rgb);
        for (int k = 0; k < 3; ++k)
            r->slice_rgb[3 * c + k] = to_byte(rgb[k]);
    }
    if (!r->slice_tex)
        r->slice_tex = texture_2d(GL_RGB8, 1, 1, GL_RGB, r->slice_rgb, GL_NEAREST);
    glBindTexture(GL_TEXTURE_2D, r->slice_tex);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB8, s->slice_n[0], s->slice_n[1], 0, GL_RGB,
                 GL_UNSIGNED_BYTE, r->slice_rgb);
    // The quad: the slice's two axes span the box, the normal axis sits at slice_at.
    const int a = s->slice_axis, b = (a + 1) % 3, c2 = (a + 2) % 3;
    float quad[6][5];
    static const int corner[6][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 0}, {1, 1}, {0, 1}};
    for (int k = 0; k < 6; ++k) {
        quad[k][a] = s->slice_at;
        quad[k][b] = corner[k][0] ? s->slice_hi[b] : s->slice_lo[b];
        quad[k][c2] = corner[k][1] ? s->slice_hi[c2] : s->slice_lo[c2];
        quad[k][3] = (float)corner[k][0];
        quad[k][4] = (float)corner[k][1];
    }
    glUseProgram(r->slice_prog);
    glUniformMatrix4fv(glGetUniformLocation(r->slice_prog, "u_view_proj"), 1, GL_FALSE, view_proj);
    glUniform1f(glGetUniformLocation(r->slice_prog, "u_alpha"), v->gas_opacity);
    glUniform1i(glGetUniformLocation(r->slice_prog, "u_cells"), 0);
    glActiveTexture(GL_TEXTURE0);
    glBindVertexArray(r->slice_vao);
    glBindBuffer(GL_ARRAY_BUFFER, r->slice_vbo);
    glBufferData(GL_ARRAY_BUFFER, sizeof quad, quad, GL_STREAM_DRAW);
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    glDepthMask(GL_FALSE);
    glDrawArrays(GL_TRIANGLES, 0, 6);
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
    r->slice_range[0] = lo;
    r->slice_range[1] = hi;
    r->slice_drawn = s->slice_field;
}

static void draw_outlines(bdl_renderer *r, const bdl_snapshot *s, const bdl_view *v,
                          const float *view_proj)
{
    glUseProgram(r->line_prog);
    glBindVertexArray(r->line_vao);
    GLint offset_at = glGetUniformLocation(r->line_prog, "u_view_proj");
    GLint color_at = glGetUniformLocation(r->line_prog, "u_color");
    float light = v->background[0] + v->background[1] + v->background[2] < 1.5f;
    for (int g = 0; g < r->group_count; ++g) {
        const line_group *lg = &r->groups[g];
        mat4 m;
        memcpy(m, view_proj, sizeof m);
        if (lg->wall >= 0 && lg->wall < s->wall_count)
            glm_translate(m, (float *)s->wall_offset[lg->wall]);
        glUniformMatrix4fv(offset_at, 1, GL_FALSE, (const float *)m);
        // The domain box is faint; walls are clearer.
        float a = lg->wall < 0 ? 0.35f : 0.8f;
        float c = light ? 0.85f : 0.25f;
        glUniform4f(color_at, c, c, c, a);
        glDrawArrays(GL_LINES, lg->first, lg->count);
    }
}

void bdl_renderer_draw(bdl_renderer *r, const bdl_snapshot *snap, const bdl_view *view, int width,
                       int height)
{
    if (r->headless) {
        width = r->width;
        height = r->height;
        glBindFramebuffer(GL_FRAMEBUFFER, r->fbo);
    } else {
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
    }
    glViewport(0, 0, width, height);
    glClearColor(view->background[0], view->background[1], view->background[2], 1.0f);
    glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    float aspect = (float)width / (float)(height > 0 ? height : 1);
    bdl_vec3 extent = bdl_v3_sub(r->scene.domain_max, r->scene.domain_min);
    float depth = 2.0f * (float)bdl_v3_len(extent) + fabsf(view->camera.distance) * 0.0f;
    float v[16], p[16];
    bdl_camera_matrices(&view->camera, aspect, depth, v, p);
    mat4 vp;
    glm_mat4_mul(*(mat4 *)p, *(mat4 *)v, vp);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    r->drawn = 0;
    if (snap && snap->count > 0 && reserve_instances(r, snap->count)) {
        r->drawn = fill_instances(r, snap, view, v, p, width, height);
        if (r->drawn > 0)
            draw_spheres(r, snap, r->drawn, view, v, p, width, height);
    }
    bdl_snapshot none = {0};
    if (snap)
        draw_slice(r, snap, view, (const float *)vp);
    if (view->outlines) {
        glEnable(GL_BLEND);
        glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
        draw_outlines(r, snap ? snap : &none, view, (const float *)vp);
        glDisable(GL_BLEND);
    }
    build_overlay(r, snap ? snap : &none, view, width, height);
    draw_overlay(r, width, height);
    glBindVertexArray(0);
}

/// Reads the bound read framebuffer into rgb, top row first (GL rows run bottom to top).
static bdl_result read_rows(uint8_t *rgb, int width, int height)
{
    glPixelStorei(GL_PACK_ALIGNMENT, 1);
    glReadPixels(0, 0, width, height, GL_RGB, GL_UNSIGNED_BYTE, rgb);
    size_t row = (size_t)width * 3;
    uint8_t *tmp = malloc(row);
    if (!tmp)
        return BDL_ERR_NOMEM;
    for (int y = 0; y < height / 2; ++y) {
        uint8_t *a = rgb + (size_t)y * row, *b = rgb + (size_t)(height - 1 - y) * row;
        memcpy(tmp, a, row);
        memcpy(a, b, row);
        memcpy(b, tmp, row);
    }
    free(tmp);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
    return glGetError() == GL_NO_ERROR ? BDL_OK : BDL_ERR_GL;
}

bdl_result bdl_renderer_read(bdl_renderer *r, uint8_t *rgb)
{
    if (!r->headless)
        return BDL_ERR_GL;
    glBindFramebuffer(GL_READ_FRAMEBUFFER, r->fbo);
    glBindFramebuffer(GL_DRAW_FRAMEBUFFER, r->resolve_fbo);
    glBlitFramebuffer(0, 0, r->width, r->height, 0, 0, r->width, r->height, GL_COLOR_BUFFER_BIT,
                      GL_NEAREST);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, r->resolve_fbo);
    glReadBuffer(GL_COLOR_ATTACHMENT0);
    return read_rows(rgb, r->width, r->height);
}

bdl_result bdl_renderer_read_window(bdl_renderer *r, uint8_t *rgb, int width, int height)
{
    if (r->headless)
        return bdl_renderer_read(r, rgb);
    glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
    glReadBuffer(GL_BACK);
    return read_rows(rgb, width, height);
}

long bdl_renderer_drawn(const bdl_renderer *r) { return r->drawn; }

void bdl_renderer_last_range(const bdl_renderer *r, float range[2])
{
    range[0] = r->last_range[0];
    range[1] = r->last_range[1];
}

bdl_result bdl_renderer_create(const bdl_renderer_def *def, bdl_renderer **out, char *why,
                               size_t why_len)
{
    *out = NULL;
    bdl_renderer *r = calloc(1, sizeof *r);
    if (!r)
        return BDL_ERR_NOMEM;
    r->scene = *def->scene;
    r->headless = def->headless;
    r->width = def->width;
    r->height = def->height;
    r->samples = def->samples;
    for (int k = 0; k < 3; ++k) {
        r->quads[k] = malloc((size_t)MAX_QUADS * 6 * sizeof(overlay_vertex));
        if (!r->quads[k]) {
            bdl_renderer_destroy(r);
            return BDL_ERR_NOMEM;
        }
    }
    const char *font_path = def->font_path ? def->font_path : bdl_font_default_path();
    r->font = font_path ? bdl_font_load(font_path, FONT_PX) : NULL;
    if (!r->font)
        bdl_warn("no font found (fonts-dejavu-core, or set BDL_FONT): frames have no text");
    build_outlines(r);
    r->sphere_prog = program("sphere.vert", "sphere.frag", why, why_len);
    r->line_prog = r->sphere_prog ? program("line.vert", "line.frag", why, why_len) : 0;
    r->overlay_prog = r->line_prog ? program("overlay.vert", "overlay.frag", why, why_len) : 0;
    r->slice_prog = r->overlay_prog ? program("slice.vert", "slice.frag", why, why_len) : 0;
    if (!r->slice_prog || (r->headless && !make_framebuffer(r, why, why_len))) {
        bdl_renderer_destroy(r);
        return BDL_ERR_GL;
    }
    make_vertex_arrays(r);
    make_textures(r);
    *out = r;
    return BDL_OK;
}

void bdl_renderer_destroy(bdl_renderer *r)
{
    if (!r)
        return;
    if (r->sphere_prog)
        glDeleteProgram(r->sphere_prog);
    if (r->line_prog)
        glDeleteProgram(r->line_prog);
    if (r->overlay_prog)
        glDeleteProgram(r->overlay_prog);
    if (r->slice_prog)
        glDeleteProgram(r->slice_prog);
    if (r->slice_vao) {
        glDeleteBuffers(1, &r->slice_vbo);
        glDeleteVertexArrays(1, &r->slice_vao);
    }
    if (r->slice_tex)
        glDeleteTextures(1, &r->slice_tex);
    free(r->slice_rgb);
    GLuint buffers[3] = {r->sphere_vbo, r->line_vbo, r->overlay_vbo};
    GLuint arrays[4] = {r->sphere_vao, r->line_vao, r->overlay_vao, r->point_vao};
    GLuint textures[3] = {r->font_tex, r->cmap_tex[0], r->cmap_tex[1]};
    GLuint renderbuffers[3] = {r->color_rb, r->depth_rb, r->resolve_rb};
    GLuint framebuffers[2] = {r->fbo, r->resolve_fbo};
    if (r->sphere_vao) {
        glDeleteBuffers(3, buffers);
        glDeleteVertexArrays(4, arrays);
        glDeleteTextures(3, textures);
    }
    if (r->fbo) {
        glDeleteRenderbuffers(3, renderbuffers);
        glDeleteFramebuffers(2, framebuffers);
    }
    if (r->font)
        bdl_font_destroy(r->font);
    if (r->voidage_ready)
        bdl_voidage_grid_free(&r->voidage);
    free(r->voidage_at);
    bdl_cull_free(&r->cull);
    free(r->visible);
    free(r->lines);
    free(r->instances);
    for (int k = 0; k < 3; ++k)
        free(r->quads[k]);
    free(r);
}
