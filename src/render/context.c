#include "render/context_internal.h"

#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "core/log.h"

static const char *const backend_names[] = {"auto", "sdl", "egl", "osmesa"};

const char *bdl_gl_backend_name(bdl_gl_backend b)
{
    return (unsigned)b < 4 ? backend_names[b] : "?";
}

int bdl_gl_backend_parse(const char *text, bdl_gl_backend *out)
{
    for (int k = 0; k < 4; ++k)
        if (strcmp(text, backend_names[k]) == 0) {
            *out = (bdl_gl_backend)k;
            return 1;
        }
    return 0;
}

bdl_gl_proc bdl_context_proc(const void *p)
{
    bdl_gl_proc q;
    memcpy(&q, p, sizeof q);
    return q;
}

int bdl_context_symbol(void *library, const char *name, void *slot)
{
    void *p = dlsym(library, name);
    memcpy(slot, &p, sizeof p); // a data pointer into a function pointer, as dlsym must
    return p != NULL;
}

bdl_result bdl_context_finish(bdl_context *c, bdl_gl_lookup lookup, char *why, size_t why_len)
{
    const char *missing = bdl_gl_load(lookup);
    if (missing) {
        snprintf(why, why_len, "%s: the OpenGL function %s is missing (OpenGL 3.3 needed)",
                 bdl_gl_backend_name(c->backend), missing);
        return BDL_ERR_GL;
    }
    GLint major = 0, minor = 0;
    glGetIntegerv(GL_MAJOR_VERSION, &major);
    glGetIntegerv(GL_MINOR_VERSION, &minor);
    if (major * 10 + minor < 33) {
        snprintf(why, why_len, "%s: OpenGL %d.%d, 3.3 needed", bdl_gl_backend_name(c->backend),
                 major, minor);
        return BDL_ERR_GL;
    }
    bdl_info("OpenGL %s: %s, %s", bdl_gl_backend_name(c->backend),
             (const char *)glGetString(GL_VERSION), (const char *)glGetString(GL_RENDERER));
    return BDL_OK;
}

static bdl_result open_backend(bdl_context *c, const bdl_context_def *def, char *why,
                               size_t why_len)
{
    switch (c->backend) {
    case BDL_GL_SDL:
        return bdl_context_open_sdl(c, def, why, why_len);
    case BDL_GL_EGL:
        return bdl_context_open_egl(c, why, why_len);
    case BDL_GL_OSMESA:
        return bdl_context_open_osmesa(c, why, why_len);
    case BDL_GL_AUTO:
        break;
    }
    return BDL_ERR_GL;
}

bdl_result bdl_context_create(const bdl_context_def *def, bdl_context **out, char *why,
                              size_t why_len)
{
    *out = NULL;
    bdl_gl_backend order[2] = {def->backend, BDL_GL_AUTO};
    if (def->backend == BDL_GL_AUTO) {
        order[0] = def->window ? BDL_GL_SDL : BDL_GL_EGL;
        order[1] = def->window ? BDL_GL_AUTO : BDL_GL_OSMESA;
    }
    if (def->window != (order[0] == BDL_GL_SDL)) {
        snprintf(why, why_len, "the %s backend cannot %s", bdl_gl_backend_name(order[0]),
                 def->window ? "open a window" : "draw headless");
        return BDL_ERR_GL;
    }
    char first[512] = "";
    bdl_result last = BDL_ERR_GL;
    for (int k = 0; k < 2 && order[k] != BDL_GL_AUTO; ++k) {
        bdl_context *c = calloc(1, sizeof *c);
        if (!c)
            return BDL_ERR_NOMEM;
        c->backend = order[k];
        c->width = def->width;
        c->height = def->height;
        bdl_result r = last = open_backend(c, def, why, why_len);
        if (r == BDL_OK) {
            *out = c;
            return BDL_OK;
        }
        bdl_context_destroy(c);
        if (k == 0 && order[1] != BDL_GL_AUTO) {
            snprintf(first, sizeof first, "%s", why);
            bdl_warn("%s; trying %s", first, bdl_gl_backend_name(order[1]));
        } else if (first[0]) {
            char second[512];
            snprintf(second, sizeof second, "%s", why);
            snprintf(why, why_len, "%s; %s", first, second);
        }
    }
    return last;
}

void bdl_context_destroy(bdl_context *c)
{
    if (!c)
        return;
    if (c->close)
        c->close(c);
    free(c);
}

void bdl_context_present(bdl_context *c)
{
    if (c->present)
        c->present(c);
}

void bdl_context_drawable_size(bdl_context *c, int *width, int *height)
{
    if (c->query_size)
        c->query_size(c);
    *width = c->width;
    *height = c->height;
}

bdl_gl_backend bdl_context_backend(const bdl_context *c) { return c->backend; }
