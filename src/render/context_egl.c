// EGL headless context: Mesa's surfaceless platform first (llvmpipe needs no GPU and no
// display), then the first EGL device (a GPU machine without a display server), then the default
// display. libEGL is opened with dlopen.
#include <EGL/egl.h>
#include <EGL/eglext.h>
#include <dlfcn.h>
#include <stdio.h>
#include <string.h>

#include "render/context_internal.h"

typedef struct egl_api {
    PFNEGLGETPROCADDRESSPROC GetProcAddress;
    PFNEGLQUERYSTRINGPROC QueryString;
    PFNEGLGETDISPLAYPROC GetDisplay;
    PFNEGLINITIALIZEPROC Initialize;
    PFNEGLBINDAPIPROC BindAPI;
    PFNEGLCHOOSECONFIGPROC ChooseConfig;
    PFNEGLCREATECONTEXTPROC CreateContext;
    PFNEGLDESTROYCONTEXTPROC DestroyContext;
    PFNEGLMAKECURRENTPROC MakeCurrent;
    PFNEGLGETERRORPROC GetError;
    PFNEGLGETPLATFORMDISPLAYEXTPROC GetPlatformDisplayEXT;
    PFNEGLQUERYDEVICESEXTPROC QueryDevicesEXT;
} egl_api;

static egl_api egl;

static bdl_gl_proc lookup(const char *name)
{
    __eglMustCastToProperFunctionPointerType p = egl.GetProcAddress(name);
    return bdl_context_proc(&p);
}

static void close_egl(bdl_context *c)
{
    if (c->display) {
        egl.MakeCurrent(c->display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
        if (c->handle)
            egl.DestroyContext(c->display, c->handle);
    }
    // The display is left initialised and libEGL loaded: an EGL display is one per process
    // and is reused by the next context, and terminating it makes Mesa unload its driver
    // with that driver's process-lifetime allocations still live.
}

static int has_extension(const char *list, const char *name)
{
    size_t n = strlen(name);
    for (const char *s = list; s && (s = strstr(s, name)); s += n)
        if ((s == list || s[-1] == ' ') && (s[n] == ' ' || s[n] == '\0'))
            return 1;
    return 0;
}

/// The first display that initialises: surfaceless, device, default.
static EGLDisplay open_display(const char **platform)
{
    const char *client = egl.QueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
    EGLint major, minor;
    if (egl.GetPlatformDisplayEXT && has_extension(client, "EGL_MESA_platform_surfaceless")) {
        EGLDisplay d =
            egl.GetPlatformDisplayEXT(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, NULL);
        *platform = "surfaceless";
        if (d != EGL_NO_DISPLAY && egl.Initialize(d, &major, &minor))
            return d;
    }
    if (egl.GetPlatformDisplayEXT && egl.QueryDevicesEXT &&
        has_extension(client, "EGL_EXT_platform_device")) {
        EGLDeviceEXT devices[8];
        EGLint count = 0;
        if (egl.QueryDevicesEXT(8, devices, &count) && count > 0) {
            EGLDisplay d = egl.GetPlatformDisplayEXT(EGL_PLATFORM_DEVICE_EXT, devices[0], NULL);
            *platform = "device";
            if (d != EGL_NO_DISPLAY && egl.Initialize(d, &major, &minor))
                return d;
        }
    }
    EGLDisplay d = egl.GetDisplay(EGL_DEFAULT_DISPLAY);
    *platform = "default";
    if (d != EGL_NO_DISPLAY && egl.Initialize(d, &major, &minor))
        return d;
    return EGL_NO_DISPLAY;
}

static int load_api(char *why, size_t why_len, void **library)
{
    void *lib = dlopen("libEGL.so.1", RTLD_NOW | RTLD_LOCAL);
    if (!lib) {
        snprintf(why, why_len,
                 "egl: cannot load libEGL.so.1 (Debian: libegl1 and "
                 "libegl-mesa0)");
        return 0;
    }
    *library = lib;
    int ok = bdl_context_symbol(lib, "eglGetProcAddress", &egl.GetProcAddress) &&
             bdl_context_symbol(lib, "eglQueryString", &egl.QueryString) &&
             bdl_context_symbol(lib, "eglGetDisplay", &egl.GetDisplay) &&
             bdl_context_symbol(lib, "eglInitialize", &egl.Initialize) &&
             bdl_context_symbol(lib, "eglBindAPI", &egl.BindAPI) &&
             bdl_context_symbol(lib, "eglChooseConfig", &egl.ChooseConfig) &&
             bdl_context_symbol(lib, "eglCreateContext", &egl.CreateContext) &&
             bdl_context_symbol(lib, "eglDestroyContext", &egl.DestroyContext) &&
             bdl_context_symbol(lib, "eglMakeCurrent", &egl.MakeCurrent) &&
             bdl_context_symbol(lib, "eglGetError", &egl.GetError);
    if (!ok) {
        snprintf(why, why_len, "egl: libEGL.so.1 lacks EGL 1.4 functions");
        return 0;
    }
    __eglMustCastToProperFunctionPointerType p = egl.GetProcAddress("eglGetPlatformDisplayEXT");
    memcpy(&egl.GetPlatformDisplayEXT, &p, sizeof p);
    p = egl.GetProcAddress("eglQueryDevicesEXT");
    memcpy(&egl.QueryDevicesEXT, &p, sizeof p);
    return 1;
}

bdl_result bdl_context_open_egl(bdl_context *c, char *why, size_t why_len)
{
    if (!load_api(why, why_len, &c->library))
        return BDL_ERR_GL;
    c->close = close_egl;
    const char *platform = "";
    c->display = open_display(&platform);
    if (!c->display) {
        snprintf(why, why_len, "egl: no EGL display could be initialised (last tried: %s)",
                 platform);
        return BDL_ERR_GL;
    }
    if (!egl.BindAPI(EGL_OPENGL_API)) {
        snprintf(why, why_len, "egl: the %s display has no desktop OpenGL", platform);
        return BDL_ERR_GL;
    }
    static const EGLint config_attribs[] = {EGL_RENDERABLE_TYPE, EGL_OPENGL_BIT, EGL_SURFACE_TYPE,
                                            EGL_PBUFFER_BIT, EGL_NONE};
    EGLConfig config = NULL;
    EGLint configs = 0;
    if (!egl.ChooseConfig(c->display, config_attribs, &config, 1, &configs) || configs == 0)
        config = NULL; // EGL_KHR_no_config_context: the context needs no config
    static const EGLint context_attribs[] = {EGL_CONTEXT_MAJOR_VERSION,
                                             3,
                                             EGL_CONTEXT_MINOR_VERSION,
                                             3,
                                             EGL_CONTEXT_OPENGL_PROFILE_MASK,
                                             EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                                             EGL_NONE};
    c->handle = egl.CreateContext(c->display, config, EGL_NO_CONTEXT, context_attribs);
    if (!c->handle) {
        snprintf(why, why_len,
                 "egl: no OpenGL 3.3 core context on the %s display (EGL error "
                 "0x%x)",
                 platform, (unsigned)egl.GetError());
        return BDL_ERR_GL;
    }
    if (!egl.MakeCurrent(c->display, EGL_NO_SURFACE, EGL_NO_SURFACE, c->handle)) {
        snprintf(why, why_len,
                 "egl: cannot make the context current without a surface (EGL "
                 "error 0x%x)",
                 (unsigned)egl.GetError());
        return BDL_ERR_GL;
    }
    return bdl_context_finish(c, lookup, why, why_len);
}
