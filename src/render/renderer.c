// bedlam — the renderer: its creation from the parts that draw a frame (renderer_internal.h
// lists them), the frame as a list of phases, and reading the pixels back.
#include "render/renderer.h"

#include <cglm/cglm.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "render/renderer_internal.h"

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
    if (!bdl_render_overlay_init(r, def->font_path)) {
        bdl_renderer_destroy(r);
        return BDL_ERR_NOMEM;
    }
    bdl_render_outlines_build(r);
    int ok = bdl_render_particles_create(r, why, why_len) &&
             bdl_render_capsules_create(r, why, why_len) &&
             bdl_render_outlines_create(r, why, why_len) &&
             bdl_render_overlay_create(r, why, why_len) &&
             bdl_render_slice_create(r, why, why_len) &&
             (!r->headless || make_framebuffer(r, why, why_len));
    glBindVertexArray(0);
    if (!ok) {
        bdl_renderer_destroy(r);
        return BDL_ERR_GL;
    }
    *out = r;
    return BDL_OK;
}

void bdl_renderer_destroy(bdl_renderer *r)
{
    if (!r)
        return;
    bdl_render_particles_destroy(r);
    bdl_render_capsules_destroy(r);
    bdl_render_colors_destroy(r);
    bdl_render_slice_destroy(r);
    bdl_render_outlines_destroy(r);
    bdl_render_overlay_destroy(r);
    if (r->fbo) {
        GLuint renderbuffers[3] = {r->color_rb, r->depth_rb, r->resolve_rb};
        GLuint framebuffers[2] = {r->fbo, r->resolve_fbo};
        glDeleteRenderbuffers(3, renderbuffers);
        glDeleteFramebuffers(2, framebuffers);
    }
    free(r);
}

/// Binds the frame's target (headless: the own framebuffer at its own size), clears it, and
/// sets the camera's matrices.
static void begin_frame(bdl_renderer *r, const bdl_view *view, int width, int height,
                        bdl_render_frame *f)
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
    f->width = width;
    f->height = height;
    float aspect = (float)width / (float)(height > 0 ? height : 1);
    // Near and far planes far enough apart to hold the whole domain from any side.
    bdl_vec3 extent = bdl_v3_sub(r->scene.domain_max, r->scene.domain_min);
    float depth = 2.0f * (float)bdl_v3_len(extent);
    mat4 v, p, vp;
    bdl_camera_matrices(&view->camera, aspect, depth, (float *)v, (float *)p);
    glm_mat4_mul(p, v, vp);
    memcpy(f->view, v, sizeof f->view);
    memcpy(f->proj, p, sizeof f->proj);
    memcpy(f->view_proj, vp, sizeof f->view_proj);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
}

void bdl_renderer_draw(bdl_renderer *r, const bdl_snapshot *snap, const bdl_view *view, int width,
                       int height)
{
    const bdl_snapshot none = {0};
    const bdl_snapshot *s = snap ? snap : &none;
    bdl_render_frame f;
    begin_frame(r, view, width, height, &f);
    r->drawn = bdl_render_particles_draw(r, s, view, &f);
    if (snap)
        bdl_render_slice_draw(r, snap, view, &f);
    if (view->outlines)
        bdl_render_outlines_draw(r, s, view, &f);
    bdl_render_overlay_draw(r, s, view, &f);
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
