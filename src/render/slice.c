// bedlam — the snapshot's gas-field slice: one flat colour per cell (the sequential map over the
// slice's own range) on a quad across the domain, blended over what is behind it. Depth test on
// and depth writes off, so particles in front of it hide it and it hides none behind it.
#include <math.h>
#include <stdlib.h>

#include "render/colormap.h"
#include "render/renderer_internal.h"

int bdl_render_slice_create(bdl_renderer *r, char *why, size_t why_len)
{
    bdl_render_slice *sl = &r->slice;
    if (!bdl_gl_mesh_create(&sl->mesh, "slice.vert", "slice.frag", why, why_len))
        return 0;
    // 6 vertices of xyz and uv.
    glEnableVertexAttribArray(0);
    glVertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 20, (void *)0);
    glEnableVertexAttribArray(1);
    glVertexAttribPointer(1, 2, GL_FLOAT, GL_FALSE, 20, (void *)12);
    return 1;
}

void bdl_render_slice_destroy(bdl_renderer *r)
{
    bdl_render_slice *sl = &r->slice;
    bdl_gl_mesh_destroy(&sl->mesh);
    if (sl->texture)
        glDeleteTextures(1, &sl->texture);
    free(sl->rgb);
}

/// The cells' colours into sl->rgb, over the range of their values (returned in `range`).
static int color_cells(bdl_render_slice *sl, const float *values, long cells, float range[2])
{
    if (cells > sl->rgb_capacity) {
        uint8_t *p = realloc(sl->rgb, (size_t)cells * 3);
        if (!p)
            return 0;
        sl->rgb = p;
        sl->rgb_capacity = cells;
    }
    float lo = values[0], hi = values[0];
    for (long c = 1; c < cells; ++c)
        lo = fminf(lo, values[c]), hi = fmaxf(hi, values[c]);
    const float span = hi > lo ? hi - lo : 1.0f;
    for (long c = 0; c < cells; ++c) {
        float rgb[3];
        bdl_colormap_eval(BDL_CMAP_SEQUENTIAL, (values[c] - lo) / span, rgb);
        for (int k = 0; k < 3; ++k)
            sl->rgb[3 * c + k] = bdl_color_byte(rgb[k]);
    }
    range[0] = lo;
    range[1] = hi;
    return 1;
}

static void upload_cells(bdl_render_slice *sl, const int n[2])
{
    if (!sl->texture)
        sl->texture = bdl_gl_texture_2d(GL_RGB8, 1, 1, GL_RGB, sl->rgb, GL_NEAREST);
    glBindTexture(GL_TEXTURE_2D, sl->texture);
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB8, n[0], n[1], 0, GL_RGB, GL_UNSIGNED_BYTE, sl->rgb);
}

/// The quad as two triangles of xyz and uv: the slice's two axes span the box, the normal axis
/// sits at slice_at.
static void slice_quad(const bdl_snapshot *s, float quad[6][5])
{
    const int a = s->slice_axis, b = (a + 1) % 3, c = (a + 2) % 3;
    static const int corner[6][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 0}, {1, 1}, {0, 1}};
    for (int k = 0; k < 6; ++k) {
        quad[k][a] = s->slice_at;
        quad[k][b] = corner[k][0] ? s->slice_hi[b] : s->slice_lo[b];
        quad[k][c] = corner[k][1] ? s->slice_hi[c] : s->slice_lo[c];
        quad[k][3] = (float)corner[k][0];
        quad[k][4] = (float)corner[k][1];
    }
}

static void draw_quad(bdl_render_slice *sl, float quad[6][5], float opacity, const float *view_proj)
{
    glUseProgram(sl->mesh.program);
    glUniformMatrix4fv(glGetUniformLocation(sl->mesh.program, "u_view_proj"), 1, GL_FALSE,
                       view_proj);
    glUniform1f(glGetUniformLocation(sl->mesh.program, "u_alpha"), opacity);
    glUniform1i(glGetUniformLocation(sl->mesh.program, "u_cells"), 0);
    glActiveTexture(GL_TEXTURE0);
    glBindVertexArray(sl->mesh.vao);
    glBindBuffer(GL_ARRAY_BUFFER, sl->mesh.vbo);
    glBufferData(GL_ARRAY_BUFFER, 6 * 5 * sizeof(float), quad, GL_STREAM_DRAW);
    glEnable(GL_BLEND);
    glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    glDepthMask(GL_FALSE);
    glDrawArrays(GL_TRIANGLES, 0, 6);
    glDepthMask(GL_TRUE);
    glDisable(GL_BLEND);
}

void bdl_render_slice_draw(bdl_renderer *r, const bdl_snapshot *s, const bdl_view *v,
                           const bdl_render_frame *f)
{
    bdl_render_slice *sl = &r->slice;
    sl->drawn = BDL_GAS_FIELD_NONE;
    const long cells = (long)s->slice_n[0] * s->slice_n[1];
    if (cells <= 0 || !s->slice || !(v->gas_opacity > 0.0f))
        return;
    float range[2];
    if (!color_cells(sl, s->slice, cells, range))
        return;
    upload_cells(sl, s->slice_n);
    float quad[6][5];
    slice_quad(s, quad);
    draw_quad(sl, quad, v->gas_opacity, f->view_proj);
    sl->range[0] = range[0];
    sl->range[1] = range[1];
    sl->drawn = s->slice_field;
}
