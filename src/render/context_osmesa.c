// OSMesa headless context: Mesa's off-screen software renderer, the fallback when EGL is
// missing. libOSMesa is opened with dlopen. OSMesa draws into a buffer of ours, which becomes
// the default framebuffer; the renderer still draws into its own framebuffer object, as with EGL,
// so both headless paths are the same from there on.
#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "render/context_internal.h"

// From GL/osmesa.h, which cannot be included here: it pulls in GL/gl.h, whose prototypes clash
// with the function table of render/gl.h. OSMesa's ABI has kept these values since Mesa 11.2.
#define OSMESA_FORMAT                0x22
#define OSMESA_DEPTH_BITS            0x30
#define OSMESA_PROFILE               0x33
#define OSMESA_CORE_PROFILE          0x34
#define OSMESA_CONTEXT_MAJOR_VERSION 0x36
#define OSMESA_CONTEXT_MINOR_VERSION 0x37
#define OSMESA_RGBA                  GL_RGBA
typedef void *OSMesaContext;
typedef void (*OSMESAproc)(void);

typedef OSMesaContext (*create_attribs_fn)(const int *attribs, OSMesaContext share);
typedef GLboolean (*make_current_fn)(OSMesaContext, void *, GLenum, GLsizei, GLsizei);
typedef void (*destroy_fn)(OSMesaContext);
typedef OSMESAproc (*get_proc_fn)(const char *);

static struct {
    create_attribs_fn CreateContextAttribs;
    make_current_fn MakeCurrent;
    destroy_fn DestroyContext;
    get_proc_fn GetProcAddress;
} osm;

static bdl_gl_proc lookup(const char *name)
{
    OSMESAproc p = osm.GetProcAddress(name);
    return bdl_context_proc(&p);
}

static void close_osmesa(bdl_context *c)
{
    if (c->handle)
        osm.DestroyContext(c->handle);
    free(c->buffer);
}

bdl_result bdl_context_open_osmesa(bdl_context *c, char *why, size_t why_len)
{
    void *lib = dlopen("libOSMesa.so.8", RTLD_NOW | RTLD_LOCAL);
    if (!lib)
        lib = dlopen("libOSMesa.so.6", RTLD_NOW | RTLD_LOCAL);
    if (!lib) {
        snprintf(why, why_len, "osmesa: cannot load libOSMesa.so.8 (Debian: libosmesa6)");
        return BDL_ERR_GL;
    }
    c->library = lib;
    if (!bdl_context_symbol(lib, "OSMesaCreateContextAttribs", &osm.CreateContextAttribs) ||
        !bdl_context_symbol(lib, "OSMesaMakeCurrent", &osm.MakeCurrent) ||
        !bdl_context_symbol(lib, "OSMesaDestroyContext", &osm.DestroyContext) ||
        !bdl_context_symbol(lib, "OSMesaGetProcAddress", &osm.GetProcAddress)) {
        snprintf(why, why_len,
                 "osmesa: libOSMesa lacks OSMesaCreateContextAttribs (Mesa >= 11.2 "
                 "needed)");
        return BDL_ERR_GL;
    }
    c->close = close_osmesa;
    static const int attribs[] = {OSMESA_FORMAT,
                                  OSMESA_RGBA,
                                  OSMESA_DEPTH_BITS,
                                  24,
                                  OSMESA_PROFILE,
                                  OSMESA_CORE_PROFILE,
                                  OSMESA_CONTEXT_MAJOR_VERSION,
                                  3,
                                  OSMESA_CONTEXT_MINOR_VERSION,
                                  3,
                                  0};
    c->handle = osm.CreateContextAttribs(attribs, NULL);
    if (!c->handle) {
        snprintf(why, why_len, "osmesa: no OpenGL 3.3 core context");
        return BDL_ERR_GL;
    }
    // The default framebuffer is never drawn to: a small buffer suffices.
    c->buffer = calloc(16 * 16, 4);
    if (!c->buffer || !osm.MakeCurrent(c->handle, c->buffer, GL_UNSIGNED_BYTE, 16, 16)) {
        snprintf(why, why_len, "osmesa: cannot make the context current");
        return BDL_ERR_GL;
    }
    return bdl_context_finish(c, lookup, why, why_len);
}
