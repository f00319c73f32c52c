// bedlam — an OpenGL 3.3 core context from one of three backends.
//
//   SDL2    a window on a display (`bedlam view`); the default framebuffer is the window.
//   EGL     headless: Mesa's surfaceless platform (llvmpipe without a GPU), or an EGL device.
//   OSMesa  headless fallback: Mesa's off-screen software renderer.
//
// EGL and OSMesa are opened with dlopen, so a machine without them still runs everything else
// and gets a sentence saying what is missing. Headless contexts have no usable default
// framebuffer: the renderer draws into its own framebuffer object there.
#ifndef BDL_CONTEXT_H
#define BDL_CONTEXT_H

#include <stddef.h>

#include "core/error.h"

typedef enum bdl_gl_backend {
    BDL_GL_AUTO, ///< window: SDL2; headless: EGL, then OSMesa
    BDL_GL_SDL,
    BDL_GL_EGL,
    BDL_GL_OSMESA,
} bdl_gl_backend;

typedef struct bdl_context_def {
    bdl_gl_backend backend;
    int window;        ///< a window on the display (else headless)
    int width, height; ///< window size [px]
    const char *title; ///< window title
} bdl_context_def;

typedef struct bdl_context bdl_context;

/// Creates the context and makes it current on the calling thread, with the GL functions
/// loaded. On failure returns BDL_ERR_GL and writes what is missing into `why`.
bdl_result bdl_context_create(const bdl_context_def *def, bdl_context **out, char *why,
                              size_t why_len);
void bdl_context_destroy(bdl_context *c);
/// Shows the finished frame (window); nothing for headless contexts.
void bdl_context_present(bdl_context *c);
/// Size of the window's drawable in pixels (can differ from the window size on HiDPI screens).
void bdl_context_drawable_size(bdl_context *c, int *width, int *height);
bdl_gl_backend bdl_context_backend(const bdl_context *c);

const char *bdl_gl_backend_name(bdl_gl_backend b);
/// Parses "auto", "sdl", "egl", "osmesa". Returns 0 for anything else.
int bdl_gl_backend_parse(const char *text, bdl_gl_backend *out);

#endif
