// bedlam — what the context backends share (render/context*.c only).
#ifndef BDL_CONTEXT_INTERNAL_H
#define BDL_CONTEXT_INTERNAL_H

#include "render/context.h"
#include "render/gl.h"

struct bdl_context {
    bdl_gl_backend backend;
    int width, height;
    void *library; ///< dlopen handle (EGL, OSMesa)
    void *display; ///< EGLDisplay
    void *handle;  ///< EGLContext, OSMesaContext or SDL_GLContext
    void *window;  ///< SDL_Window
    void *buffer;  ///< OSMesa colour buffer
    void (*present)(bdl_context *c);
    void (*close)(bdl_context *c);
    void (*query_size)(bdl_context *c); ///< refreshes width and height (windows)
};

bdl_result bdl_context_open_egl(bdl_context *c, char *why, size_t why_len);
bdl_result bdl_context_open_osmesa(bdl_context *c, char *why, size_t why_len);
bdl_result bdl_context_open_sdl(bdl_context *c, const bdl_context_def *def, char *why,
                                size_t why_len);

/// Looks up `name` in a dlopen'ed library into the function pointer at `slot`; 0 if missing.
int bdl_context_symbol(void *library, const char *name, void *slot);

/// The function pointer at `p` (of any function type) as a GL procedure.
bdl_gl_proc bdl_context_proc(const void *p);

/// Loads the GL table and checks the version; on failure writes why.
bdl_result bdl_context_finish(bdl_context *c, bdl_gl_lookup lookup, char *why, size_t why_len);

#endif
