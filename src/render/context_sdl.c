// SDL2 window context for `bedlam view`. Built only with BDL_WITH_SDL (the default when SDL2 is
// found); without it the backend reports that it is missing.
#include <stdio.h>
#include <string.h>

#include "render/context_internal.h"

#ifdef BDL_WITH_SDL
#include <SDL.h>

static bdl_gl_proc lookup(const char *name)
{
    void *p = SDL_GL_GetProcAddress(name);
    bdl_gl_proc q;
    memcpy(&q, &p, sizeof q);
    return q;
}

static void present_sdl(bdl_context *c) { SDL_GL_SwapWindow(c->window); }

static void query_size_sdl(bdl_context *c)
{
    SDL_GL_GetDrawableSize(c->window, &c->width, &c->height);
}

static void close_sdl(bdl_context *c)
{
    if (c->handle)
        SDL_GL_DeleteContext(c->handle);
    if (c->window)
        SDL_DestroyWindow(c->window);
    SDL_QuitSubSystem(SDL_INIT_VIDEO);
}

bdl_result bdl_context_open_sdl(bdl_context *c, const bdl_context_def *def, char *why,
                                size_t why_len)
{
    if (SDL_InitSubSystem(SDL_INIT_VIDEO) != 0) {
        snprintf(why, why_len,
                 "sdl: no display (%s); headless frames need no display: use "
                 "`bedlam run` with [output] frame_interval",
                 SDL_GetError());
        return BDL_ERR_NO_DISPLAY;
    }
    c->close = close_sdl;
    // With no window system SDL falls back to drivers that show nothing ("offscreen", "dummy"):
    // a viewer would run unseen. Only a driver asked for by name is taken as meant.
    const char *driver = SDL_GetCurrentVideoDriver();
    if (driver && !getenv("SDL_VIDEODRIVER") &&
        (!strcmp(driver, "offscreen") || !strcmp(driver, "dummy"))) {
        snprintf(why, why_len,
                 "no display: neither X11 (DISPLAY) nor Wayland (WAYLAND_DISPLAY) can be reached, "
                 "and SDL's '%s' driver would show nothing. Run where a display is, or write "
                 "frames headless with `bedlam run` and [output] frame_interval "
                 "(SDL_VIDEODRIVER=%s forces the invisible window)",
                 driver, driver);
        return BDL_ERR_NO_DISPLAY;
    }
    SDL_GL_SetAttribute(SDL_GL_CONTEXT_PROFILE_MASK, SDL_GL_CONTEXT_PROFILE_CORE);
    SDL_GL_SetAttribute(SDL_GL_CONTEXT_MAJOR_VERSION, 3);
    SDL_GL_SetAttribute(SDL_GL_CONTEXT_MINOR_VERSION, 3);
    SDL_GL_SetAttribute(SDL_GL_DEPTH_SIZE, 24);
    SDL_GL_SetAttribute(SDL_GL_DOUBLEBUFFER, 1);
    c->window =
        SDL_CreateWindow(def->title ? def->title : "bedlam", SDL_WINDOWPOS_CENTERED,
                         SDL_WINDOWPOS_CENTERED, def->width, def->height,
                         SDL_WINDOW_OPENGL | SDL_WINDOW_RESIZABLE | SDL_WINDOW_ALLOW_HIGHDPI);
    if (!c->window) {
        snprintf(why, why_len, "sdl: cannot open a window: %s", SDL_GetError());
        return BDL_ERR_GL;
    }
    c->handle = SDL_GL_CreateContext(c->window);
    if (!c->handle) {
        snprintf(why, why_len, "sdl: no OpenGL 3.3 core context: %s", SDL_GetError());
        return BDL_ERR_GL;
    }
    SDL_GL_SetSwapInterval(1);
    c->present = present_sdl;
    c->query_size = query_size_sdl;
    query_size_sdl(c);
    return bdl_context_finish(c, lookup, why, why_len);
}

#else

bdl_result bdl_context_open_sdl(bdl_context *c, const bdl_context_def *def, char *why,
                                size_t why_len)
{
    (void)c;
    (void)def;
    snprintf(why, why_len,
             "sdl: this bedlam was built without SDL2 (BDL_WITH_SDL=OFF); "
             "headless frames still work");
    return BDL_ERR_GL;
}

#endif
