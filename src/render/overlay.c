// bedlam — the overlay: status text at the top left, a colour bar or a discrete legend on the
// right, and the viewer's help box. Everything is a quad in pixels, collected per frame into
// three batches by shader mode (flat, text from the font atlas, the colour map) and drawn over
// the scene without depth.
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/log.h"
#include "render/colormap.h"
#include "render/renderer_internal.h"

#define FONT_PX   15
#define MAX_QUADS 4096

#define BDL_X_ONE(name, word, label, unit) +1
enum { GAS_FIELD_COUNT = 0 BDL_GAS_FIELDS(BDL_X_ONE) };
#undef BDL_X_ONE

static const uint8_t text_color[4] = {235, 235, 235, 255};

int bdl_render_overlay_init(bdl_renderer *r, const char *font_path)
{
    bdl_render_overlay *o = &r->overlay;
    for (int k = 0; k < BDL_OVERLAY_MODES; ++k) {
        o->quads[k] = malloc((size_t)MAX_QUADS * 6 * sizeof(bdl_overlay_vertex));
        if (!o->quads[k])
            return 0;
    }
    if (!font_path)
        font_path = bdl_font_default_path();
    o->font = font_path ? bdl_font_load(font_path, FONT_PX) : NULL;
    if (!o->font)
        bdl_warn("no font found (fonts-dejavu-core, or set BDL_FONT): frames have no text");
    return 1;
}

int bdl_render_overlay_create(bdl_renderer *r, char *why, size_t why_len)
{
    bdl_render_overlay *o = &r->overlay;
    if (!bdl_gl_mesh_create(&o->mesh, "overlay.vert", "overlay.frag", why, why_len))
        return 0;
    const GLsizei stride = sizeof(bdl_overlay_vertex);
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, stride, (void *)0);
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 2, GL_FLOAT, GL_FALSE, stride, (void *)8);
    glEnableVertexAttribArray(2);
    glVertexAttribPointer(2, 4, GL_UNSIGNED_BYTE, GL_TRUE, stride, (void *)16);

    uint8_t table[BDL_COLORMAP_SIZE][3];
    for (int k = 0; k < BDL_CMAP_KINDS; ++k) {
        bdl_colormap_table((bdl_colormap_kind)k, table);
        o->colormap_texture[k] =
            bdl_gl_texture_2d(GL_RGB8, BDL_COLORMAP_SIZE, 1, GL_RGB, table, GL_LINEAR);
    }
    if (o->font) {
        int w, h;
        const uint8_t *atlas = bdl_font_atlas(o->font, &w, &h);
        o->font_texture = bdl_gl_texture_2d(GL_R8, w, h, GL_RED, atlas, GL_NEAREST);
    }
    return 1;
}

void bdl_render_overlay_destroy(bdl_renderer *r)
{
    bdl_render_overlay *o = &r->overlay;
    if (o->mesh.vao) {
        glDeleteTextures(1, &o->font_texture);
        glDeleteTextures(BDL_CMAP_KINDS, o->colormap_texture);
    }
    bdl_gl_mesh_destroy(&o->mesh);
    if (o->font)
        bdl_font_destroy(o->font);
    for (int k = 0; k < BDL_OVERLAY_MODES; ++k)
        free(o->quads[k]);
}

// ---------------------------------------------------------------------------------------------
// Shapes.

static void quad(bdl_render_overlay *o, int mode, float x0, float y0, float x1, float y1, float u0,
                 float v0, float u1, float v1, const uint8_t rgba[4])
{
    if (o->quad_count[mode] >= MAX_QUADS)
        return;
    bdl_overlay_vertex *q = &o->quads[mode][6 * o->quad_count[mode]++];
    bdl_overlay_vertex c[4] = {
        {x0, y0, u0, v0, {0}}, {x1, y0, u1, v0, {0}}, {x1, y1, u1, v1, {0}}, {x0, y1, u0, v1, {0}}};
    static const int order[6] = {0, 1, 2, 0, 2, 3};
    for (int k = 0; k < 6; ++k) {
        q[k] = c[order[k]];
        memcpy(q[k].rgba, rgba, 4);
    }
}

static void rect(bdl_render_overlay *o, float x0, float y0, float x1, float y1,
                 const uint8_t rgba[4])
{
    quad(o, BDL_OVERLAY_FLAT, x0, y0, x1, y1, 0, 0, 0, 0, rgba);
}

/// Text with its top-left corner at (x, y), on a dark shadow so it reads on any background.
static void text(bdl_render_overlay *o, float x, float y, const char *s, const uint8_t rgba[4])
{
    if (!o->font)
        return;
    bdl_glyph_quad g[256];
    float base = y + bdl_font_ascent(o->font);
    static const uint8_t shadow[4] = {0, 0, 0, 200};
    for (int pass = 0; pass < 2; ++pass) {
        float d = pass == 0 ? 1.0f : 0.0f;
        int n = bdl_font_layout(o->font, s, x + d, base + d, g, 256);
        for (int k = 0; k < n; ++k)
            quad(o, BDL_OVERLAY_TEXT, g[k].x0, g[k].y0, g[k].x1, g[k].y1, g[k].u0, g[k].v0, g[k].u1,
                 g[k].v1, pass == 0 ? shadow : rgba);
    }
}

static float text_width(const bdl_render_overlay *o, const char *s)
{
    return o->font ? bdl_font_text_width(o->font, s) : 0.0f;
}

static void format_value(char *buf, size_t size, float x)
{
    snprintf(buf, size, "%.3g", fabsf(x) < 1e-7f ? 0.0f : x);
}

// ---------------------------------------------------------------------------------------------
// Parts.

/// Below the colour bar: the grey of particles without a value (spheres among rods, upright
/// rods' azimuth).
static void missing_swatch(bdl_render_overlay *o, float x0, float y, float lh)
{
    float grey[3];
    bdl_colormap_missing(grey);
    uint8_t rgba[4] = {bdl_color_byte(grey[0]), bdl_color_byte(grey[1]), bdl_color_byte(grey[2]),
                       255};
    rect(o, x0, y, x0 + 16.0f, y + 12.0f, rgba);
    text(o, x0 + 25.0f, y + 6.0f - 0.5f * lh, "none", text_color);
}

/// A continuous colour bar on the right: the map, labels at both ends and the middle.
static void colour_bar(bdl_render_overlay *o, const float range[2], bdl_color_mode mode, int width,
                       int height)
{
    float x0 = (float)width - 80.0f, x1 = x0 + 16.0f;
    float y0 = 0.3f * (float)height, y1 = 0.7f * (float)height;
    static const uint8_t frame[4] = {20, 20, 20, 255};
    rect(o, x0 - 1, y0 - 1, x1 + 1, y1 + 1, frame);
    // The map runs bottom (low) to top (high).
    quad(o, BDL_OVERLAY_COLORMAP, x0, y0, x1, y1, 1.0f, 0.5f, 1.0f, 0.5f, text_color);
    bdl_overlay_vertex *q =
        &o->quads[BDL_OVERLAY_COLORMAP][6 * (o->quad_count[BDL_OVERLAY_COLORMAP] - 1)];
    for (int k = 0; k < 6; ++k)
        q[k].u = q[k].y == y0 ? 1.0f : 0.0f;
    float lh = o->font ? bdl_font_line_height(o->font) : 0.0f;
    for (int k = 0; k < 3; ++k) {
        float t = 0.5f * (float)k;
        char label[32];
        format_value(label, sizeof label, range[0] + t * (range[1] - range[0]));
        float y = y1 - t * (y1 - y0);
        rect(o, x1, y - 0.5f, x1 + 4, y + 0.5f, text_color);
        text(o, x1 + 9, y - 0.5f * lh, label, text_color);
    }
    if (mode == BDL_COLOR_TILT || mode == BDL_COLOR_AZIMUTH)
        missing_swatch(o, x0, y1 + 0.6f * lh, lh);
    char title[64];
    const char *unit = bdl_color_mode_unit(mode);
    snprintf(title, sizeof title, "%s%s%s%s", bdl_color_mode_label(mode), unit[0] ? " [" : "", unit,
             unit[0] ? "]" : "");
    float w = text_width(o, title);
    text(o, fminf(x0, (float)width - w - 8.0f), y0 - 1.6f * lh, title, text_color);
}

/// The colour a particle of this species and coordination number is drawn in.
static void swatch_color(bdl_color_mode mode, const float range[2], int32_t species,
                         uint8_t coordination, uint8_t rgba[4])
{
    float zero_vel[3] = {0, 0, 0};
    bdl_snapshot one = {0};
    one.species = &species;
    one.coordination = &coordination;
    one.vel = zero_vel;
    one.count = 1;
    bdl_particle_color(mode, &one, 0, 0.0f, range, rgba);
    rgba[3] = 255;
}

/// A discrete legend: one swatch per coordination number or species.
static void legend(bdl_renderer *r, bdl_color_mode mode, int width, int height)
{
    bdl_render_overlay *o = &r->overlay;
    const float *range = r->colors.range;
    int species = mode == BDL_COLOR_SPECIES;
    int count = species ? r->scene.species_count : (int)lrintf(range[1] - range[0]) + 1;
    if (count > 16)
        count = 16;
    float lh = o->font ? bdl_font_line_height(o->font) : 14.0f;
    float box = fminf(lh, 0.4f * (float)height / (float)count);
    float x0 = (float)width - 110.0f;
    float y = 0.5f * (float)height + 0.5f * box * (float)count;
    for (int k = 0; k < count; ++k) {
        uint8_t coordination = (uint8_t)(range[0] + (float)k);
        uint8_t rgba[4];
        swatch_color(mode, range, k, coordination, rgba);
        float top = y - box * (float)(k + 1);
        rect(o, x0, top + 1, x0 + box - 2, top + box - 1, rgba);
        char label[64];
        if (species)
            snprintf(label, sizeof label, "%s", r->scene.species[k].name);
        else
            snprintf(label, sizeof label, "%d", (int)coordination);
        text(o, x0 + box + 4, top + 0.5f * (box - lh), label, text_color);
    }
    const char *title = bdl_color_mode_label(mode);
    text(o, fminf(x0, (float)width - text_width(o, title) - 8.0f),
         y - box * (float)count - 1.6f * lh, title, text_color);
}

#define HELP_COLUMNS 6

/// The cells of one help line: the text between runs of two or more spaces (a key, what it
/// does, the next key, ...). Returns their number; each cell is copied into cells[k].
static int help_cells(const char *line, size_t n, char cells[HELP_COLUMNS][128])
{
    int count = 0;
    size_t k = 0;
    while (k < n && count < HELP_COLUMNS) {
        while (k < n && line[k] == ' ')
            ++k;
        size_t start = k;
        while (k < n && !(line[k] == ' ' && (k + 1 >= n || line[k + 1] == ' ')))
            ++k;
        if (k > start)
            snprintf(cells[count++], 128, "%.*s", (int)(k - start), line + start);
    }
    return count;
}

/// The viewer's key help, centred: one line of text per line of `help`, its cells set in
/// columns as wide as their widest entry (the font is proportional, so spaces cannot align); the
/// last cell of a line with fewer cells than the others spans the columns left.
static void help_box(bdl_render_overlay *o, const char *help, int width, int height)
{
    const float lh = bdl_font_line_height(o->font), gap = 18.0f;
    float column[HELP_COLUMNS] = {0}, span = 0.0f;
    char cells[HELP_COLUMNS][128];
    int lines = 0, most = 0;
    for (const char *s = help; *s; ++lines) {
        const char *e = strchr(s, '\n');
        const size_t n = e ? (size_t)(e - s) : strlen(s);
        most = help_cells(s, n, cells) > most ? help_cells(s, n, cells) : most;
        s += n + (e != NULL);
    }
    for (int pass = 0; pass < 2; ++pass) // the columns, then what the spanning cells need
        for (const char *s = help; *s;) {
            const char *e = strchr(s, '\n');
            const size_t n = e ? (size_t)(e - s) : strlen(s);
            const int m = help_cells(s, n, cells);
            float x = 0.0f;
            for (int c = 0; c < m; ++c) {
                const int spans = c == m - 1 && m < most;
                if (pass == 0 && !spans)
                    column[c] = fmaxf(column[c], text_width(o, cells[c]));
                if (pass == 1 && spans)
                    span = fmaxf(span, x + text_width(o, cells[c]));
                x += column[c] + gap;
            }
            s += n + (e != NULL);
        }
    float w = -gap;
    for (int c = 0; c < most; ++c)
        w += column[c] + gap;
    w = fmaxf(w, span);
    const float x0 = 0.5f * ((float)width - w) - 16.0f,
                y0 = 0.5f * ((float)height - lh * (float)lines) - 12.0f;
    static const uint8_t shade[4] = {10, 12, 16, 215};
    rect(o, x0, y0, x0 + w + 32.0f, y0 + lh * (float)lines + 24.0f, shade);
    float y = y0 + 12.0f;
    for (const char *s = help; *s; y += lh) {
        const char *e = strchr(s, '\n');
        const size_t n = e ? (size_t)(e - s) : strlen(s);
        const int m = help_cells(s, n, cells);
        float x = x0 + 16.0f;
        for (int c = 0; c < m; ++c) {
            text(o, x, y, cells[c], text_color);
            x += column[c] + gap;
        }
        s += n + (e != NULL);
    }
}

/// Top left: time, step and particle count, the view's status line, the slice's range.
static void status_lines(bdl_renderer *r, const bdl_snapshot *s, const bdl_view *v)
{
    bdl_render_overlay *o = &r->overlay;
    char line[256];
    if (s->parcels)
        snprintf(line, sizeof line, "t = %.5f s   step %ld   %ld parcels (%.3g particles)", s->time,
                 s->step, s->count, s->real_particles);
    else
        snprintf(line, sizeof line, "t = %.5f s   step %ld   %ld particles", s->time, s->step,
                 s->count);
    float lh = o->font ? bdl_font_line_height(o->font) : 0.0f;
    text(o, 10, 8, line, text_color);
    float y = 8 + lh;
    if (v->status)
        text(o, 10, y, v->status, text_color), y += lh;
    const bdl_render_slice *sl = &r->slice;
    if (sl->drawn > BDL_GAS_FIELD_NONE && sl->drawn < GAS_FIELD_COUNT) {
        char lo[32], hi[32];
        format_value(lo, sizeof lo, sl->range[0]);
        format_value(hi, sizeof hi, sl->range[1]);
        snprintf(line, sizeof line, "slice: %s %s to %s %s", bdl_gas_field_labels[sl->drawn], lo,
                 hi, bdl_gas_field_units[sl->drawn]);
        text(o, 10, y, line, text_color);
    }
}

static void build(bdl_renderer *r, const bdl_snapshot *s, const bdl_view *v, int width, int height)
{
    bdl_render_overlay *o = &r->overlay;
    for (int k = 0; k < BDL_OVERLAY_MODES; ++k)
        o->quad_count[k] = 0;
    o->bar_map = bdl_color_mode_map(v->color);
    if (v->overlay) {
        status_lines(r, s, v);
        if (v->color == BDL_COLOR_SPECIES || v->color == BDL_COLOR_COORDINATION)
            legend(r, v->color, width, height);
        else
            colour_bar(o, r->colors.range, v->color, width, height);
    }
    if (v->help && o->font)
        help_box(o, v->help, width, height);
}

static void draw_batches(const bdl_render_overlay *o, int width, int height)
{
    glDisable(GL_DEPTH_TEST);
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    glUseProgram(o->mesh.program);
    glUniform2f(glGetUniformLocation(o->mesh.program, "u_viewport"), (float)width, (float)height);
    glUniform1i(glGetUniformLocation(o->mesh.program, "u_texture"), 0);
    glBindVertexArray(o->mesh.vao);
    glBindBuffer(GL_ARRAY_BUFFER, o->mesh.vbo);
    glActiveTexture(GL_TEXTURE0);
    // Flat shapes first, then the colour map, then text on top.
    static const int order[BDL_OVERLAY_MODES] = {BDL_OVERLAY_FLAT, BDL_OVERLAY_COLORMAP,
                                                 BDL_OVERLAY_TEXT};
    for (int k = 0; k < BDL_OVERLAY_MODES; ++k) {
        int mode = order[k];
        if (o->quad_count[mode] == 0)
            continue;
        if (mode == BDL_OVERLAY_TEXT)
            glBindTexture(GL_TEXTURE_2D, o->font_texture);
        if (mode == BDL_OVERLAY_COLORMAP)
            glBindTexture(GL_TEXTURE_2D, o->colormap_texture[o->bar_map]);
        glUniform1i(glGetUniformLocation(o->mesh.program, "u_mode"), mode);
        GLsizeiptr bytes =
            (GLsizeiptr)o->quad_count[mode] * 6 * (GLsizeiptr)sizeof(bdl_overlay_vertex);
        glBufferData(GL_ARRAY_BUFFER, bytes, o->quads[mode], GL_STREAM_DRAW);
        glDrawArrays(GL_TRIANGLES, 0, 6 * o->quad_count[mode]);
    }
    glDisable(GL_BLEND);
}

void bdl_render_overlay_draw(bdl_renderer *r, const bdl_snapshot *s, const bdl_view *v,
                             const bdl_render_frame *f)
{
    build(r, s, v, f->width, f->height);
    draw_batches(&r->overlay, f->width, f->height);
}
