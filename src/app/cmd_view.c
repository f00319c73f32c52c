// bedlam view SCENE — the interactive window.
//
// The solver runs on its own thread as in `bedlam run` (no output files); this thread owns the
// window, draws the newest snapshot at most 60 times a second and turns keys and the mouse into
// camera moves or solver commands. A slow frame never slows the solver, and a fast solver never
// floods the screen: the snapshot triple buffer hands over only the newest state.
//
// --script FILE replays key presses at given frame numbers ("FRAME KEY" per line, KEY an SDL key
// name such as "Space", "C", "F12"), so a session can be driven without a person (the tests do).
#include <math.h>
#include <stdio.h>

#include <omp.h>
#include <stdlib.h>
#include <string.h>

#include "app/app.h"
#include "core/log.h"
#include "core/timer.h"
#include "core/file.h"
#include "io/png.h"
#include "render/context.h"
#include "render/renderer.h"
#include "run/loop.h"
#include "world/world.h"

static const char view_usage[] =
    "usage: bedlam view SCENE [options]\n"
    "\n"
    "Runs SCENE in a window. Press H in the window for the keys.\n"
    "\n"
    "options:\n"
    "  --set SECTION.KEY=VALUE   override a scene key\n"
    "  --size WxH                window size in pixels (default 1280x720)\n"
    "  --threads N               solver threads (default: [run] threads, 0 = all cores)\n"
    "  --paused                  start paused\n"
    "  --out DIR                 folder for screenshots (default runs/<scene name>/screenshots)\n"
    "  --script FILE             replay key presses: lines 'FRAME KEY' (SDL key names), for\n"
    "                            scripted sessions and tests\n"
    "  --gl sdl                  the only window backend\n"
    "\n"
    "Needs a display (X11 or Wayland); for headless frames use 'bedlam run' with\n"
    "[output] frame_interval.\n";

static const char help_text[] =
    "Space    pause / resume          N        one step (paused)\n"
    "C / V    next / previous colour  1 2 3 4  iso, front, side, top view\n"
    "O        orthographic on/off     X        cut the bed open (clip plane)\n"
    "L        lighting on/off         T        text and colour bar on/off\n"
    "+ / -    faster / slower         0        full speed\n"
    "] / [    live parameter up/down  P, F12   screenshot (PNG)\n"
    "R        reset the scene         H, F1    this help\n"
    "mouse    left: orbit, right: pan, wheel: zoom\n"
    "Q, Esc   quit";

#ifdef BDL_WITH_SDL
#include <SDL.h>

typedef struct script_entry {
    long frame;
    SDL_Keycode key;
} script_entry;

typedef struct viewer {
    const bdl_scene_opts *opts;
    bdl_scene *scene;
    bdl_world *world;
    bdl_loop *loop;
    bdl_context *context;
    bdl_renderer *renderer;
    bdl_view view;
    int paused, show_help, quit;
    int reported_drawing; ///< the first frame with particles was logged (scripted sessions)
    double fps;           ///< frames drawn per second, over the last second or so
    double speed_limit;   ///< simulated s per wall s; 0 = full speed
    double live_scale;    ///< factor on the live parameter
    char live_key[96];    ///< "" when the scene exposes none
    char status[256];
    char shot_dir[1024];
    int shots;
    script_entry script[256];
    int script_count, script_next;
} viewer;

static int load_script(viewer *v, const char *path)
{
    char why[256];
    FILE *f = bdl_open_regular(path, why, sizeof why);
    if (!f) {
        fprintf(stderr, "error: --script %s %s\n", path, why);
        return 0;
    }
    char line[256];
    int lineno = 0;
    while (fgets(line, sizeof line, f) && v->script_count < 256) {
        ++lineno;
        long frame;
        char name[64];
        if (line[0] == '#' || sscanf(line, "%ld %63s", &frame, name) != 2)
            continue;
        SDL_Keycode key = SDL_GetKeyFromName(name);
        if (key == SDLK_UNKNOWN) {
            fprintf(stderr, "error: %s:%d: unknown key '%s'\n", path, lineno, name);
            fclose(f);
            return 0;
        }
        v->script[v->script_count++] = (script_entry){frame, key};
    }
    fclose(f);
    return 1;
}

/// The live parameter a scene exposes: the gas inlet velocity when the scene has an inlet, else
/// the first vibrating wall's amplitude or turning wall's rate.
static void find_live_parameter(viewer *v)
{
    v->live_key[0] = '\0';
    const bdl_gas_scene *g = &v->scene->gas;
    for (int s = 0; s < 6 && g->enabled; ++s)
        if (g->side[s] == BDL_SIDE_INLET && !v->scene->periodic[s / 2]) {
            snprintf(v->live_key, sizeof v->live_key, "gas.inlet_scale");
            return;
        }
    for (int k = 0; k < v->scene->wall_count; ++k)
        if (v->scene->walls[k].motion != BDL_MOTION_NONE) {
            snprintf(v->live_key, sizeof v->live_key, "wall.%s.%s_scale", v->scene->walls[k].name,
                     v->scene->walls[k].motion == BDL_MOTION_ROTATE ? "frequency" : "amplitude");
            return;
        }
}

static bdl_result start_world(viewer *v)
{
    bdl_scene_error err;
    // Only the solver thread runs an OpenMP team (see run/run.c): the main thread draws.
    omp_set_num_threads(1);
    bdl_result r = bdl_world_create(v->scene, &v->world, &err);
    if (r != BDL_OK) {
        fprintf(stderr, "error: %s\n", r == BDL_ERR_SCENE ? err.message : bdl_result_text(r));
        return r;
    }
    bdl_loop_def ld = bdl_default_loop_def();
    ld.world = v->world;
    ld.end_time = v->scene->end_time;
    ld.threads = v->opts->threads > 0 ? v->opts->threads : v->scene->threads;
    ld.publish = 1;
    ld.log_failures = 1;
    ld.start_paused = v->paused;
    v->loop = bdl_loop_start(&ld);
    if (!v->loop) {
        fprintf(stderr, "error: cannot start the solver thread\n");
        return BDL_ERR_NOMEM;
    }
    if (v->speed_limit > 0.0)
        bdl_loop_set_speed_limit(v->loop, v->speed_limit);
    v->live_scale = 1.0;
    return BDL_OK;
}

static void stop_world(viewer *v)
{
    if (v->loop) {
        bdl_loop_command(v->loop, &(bdl_command){.kind = BDL_CMD_STOP});
        bdl_loop_join(v->loop);
        bdl_loop_destroy(v->loop);
        v->loop = NULL;
    }
    bdl_world_destroy(v->world);
    v->world = NULL;
}

static void command(viewer *v, bdl_command_kind kind)
{
    bdl_loop_command(v->loop, &(bdl_command){.kind = kind});
}

static void screenshot(viewer *v)
{
    int w, h;
    bdl_context_drawable_size(v->context, &w, &h);
    uint8_t *rgb = malloc((size_t)w * (size_t)h * 3);
    if (!rgb)
        return;
    bdl_mkdir_p(v->shot_dir);
    char path[1200];
    snprintf(path, sizeof path, "%s/view_%04d.png", v->shot_dir, v->shots++);
    if (bdl_renderer_read_window(v->renderer, rgb, w, h) == BDL_OK &&
        bdl_png_write(path, rgb, w, h, 3, 0) == BDL_OK)
        printf("view: screenshot %s\n", path);
    free(rgb);
}

static void set_speed(viewer *v, double limit)
{
    v->speed_limit = limit;
    bdl_loop_set_speed_limit(v->loop, limit);
    if (limit > 0.0)
        printf("view: speed %g simulated s per s\n", limit);
    else
        printf("view: full speed\n");
}

static void change_live(viewer *v, double factor)
{
    if (!v->live_key[0]) {
        printf("view: this scene exposes no live parameter\n");
        return;
    }
    v->live_scale *= factor;
    bdl_command c = {.kind = BDL_CMD_SET, .value = v->live_scale};
    snprintf(c.key, sizeof c.key, "%s", v->live_key);
    bdl_loop_command(v->loop, &c);
    printf("view: %s = %.3g\n", v->live_key, v->live_scale);
}

static void reset(viewer *v, float aspect)
{
    stop_world(v);
    if (start_world(v) != BDL_OK)
        v->quit = 1;
    bdl_color_mode color = v->view.color;
    bdl_view_from_scene(v->scene, aspect, &v->view);
    v->view.color = color;
    printf("view: reset\n");
}

/// From full speed, the first step down is the speed the solver has now, halved.
static void slower(viewer *v)
{
    double now = v->speed_limit > 0.0 ? v->speed_limit : 0.0;
    if (now == 0.0) {
        const bdl_snapshot *s = bdl_loop_acquire(v->loop);
        now = s && s->steps_per_second > 0.0 ? s->steps_per_second * v->world->dt : 1.0;
    }
    set_speed(v, 0.5 * now);
}

/// Keys that drive the solver: pause, step, speed, the live parameter, reset. 0 for others.
static int solver_key(viewer *v, SDL_Keycode k, float aspect)
{
    switch (k) {
    case SDLK_SPACE:
        v->paused = !v->paused;
        command(v, v->paused ? BDL_CMD_PAUSE : BDL_CMD_RESUME);
        printf("view: %s\n", v->paused ? "paused" : "running");
        return 1;
    case SDLK_n:
        command(v, BDL_CMD_STEP);
        printf("view: step\n");
        return 1;
    case SDLK_PLUS:
    case SDLK_EQUALS:
    case SDLK_KP_PLUS:
        set_speed(v, v->speed_limit > 0.0 ? 2.0 * v->speed_limit : 0.0);
        return 1;
    case SDLK_MINUS:
    case SDLK_KP_MINUS:
        slower(v);
        return 1;
    case SDLK_0:
        set_speed(v, 0.0);
        return 1;
    case SDLK_RIGHTBRACKET:
    case SDLK_LEFTBRACKET:
        change_live(v, k == SDLK_RIGHTBRACKET ? 1.1 : 1.0 / 1.1);
        return 1;
    case SDLK_r:
        reset(v, aspect);
        return 1;
    default:
        return 0;
    }
}

/// The colour modes C and V cycle through: the orientation modes (last in the list) only when
/// the scene has rods.
static int color_modes(const bdl_scene *scene)
{
    for (int k = 0; k < scene->species_count; ++k)
        if (scene->species[k].shape == BDL_SHAPE_ROD)
            return BDL_COLOR_MODE_COUNT;
    return BDL_COLOR_TILT;
}

/// The colour after `mode` one step forward (step 1) or back (step -1); parcels have no
/// contacts, so their cycle leaves the coordination number out.
static bdl_color_mode next_color(const bdl_scene *scene, bdl_color_mode mode, int step)
{
    const int modes = color_modes(scene);
    int m = (int)mode;
    do
        m = (m + (step > 0 ? 1 : modes - 1)) % modes;
    while (scene->parcels.enabled && m == BDL_COLOR_COORDINATION);
    return (bdl_color_mode)m;
}

/// Keys that change the picture: colours, views, projection, clip plane, lighting, text.
static int picture_key(viewer *v, SDL_Keycode k)
{
    bdl_view *view = &v->view;
    switch (k) {
    case SDLK_c:
    case SDLK_v:
        view->color = next_color(v->scene, view->color, k == SDLK_c ? 1 : -1);
        view->range_fixed = 0;
        printf("view: colour %s\n", bdl_color_mode_names[view->color]);
        return 1;
    case SDLK_1:
    case SDLK_2:
    case SDLK_3:
    case SDLK_4:
        bdl_camera_preset((bdl_view_preset)(k - SDLK_1), &view->camera);
        printf("view: preset %d\n", (int)(k - SDLK_1) + 1);
        return 1;
    case SDLK_o:
        view->camera.ortho = !view->camera.ortho;
        printf("view: %s\n", bdl_projection_names[view->camera.ortho ? BDL_PROJ_ORTHOGRAPHIC
                                                                     : BDL_PROJ_PERSPECTIVE]);
        return 1;
    case SDLK_x:
        view->clip = !view->clip;
        printf("view: clip %s\n", view->clip ? "on" : "off");
        return 1;
    case SDLK_l:
        view->lighting = !view->lighting;
        return 1;
    case SDLK_t:
        view->overlay = !view->overlay;
        return 1;
    default:
        return 0;
    }
}

/// Keys of the session: screenshot, help, quit.
static void session_key(viewer *v, SDL_Keycode k)
{
    switch (k) {
    case SDLK_p:
    case SDLK_F12:
        screenshot(v);
        break;
    case SDLK_h:
    case SDLK_F1:
        v->show_help = !v->show_help;
        printf("view: help %s\n", v->show_help ? "on" : "off");
        break;
    case SDLK_q:
    case SDLK_ESCAPE:
        v->quit = 1;
        printf("view: quit\n");
        break;
    default:
        break;
    }
}

static void key(viewer *v, SDL_Keycode k, float aspect)
{
    if (!solver_key(v, k, aspect) && !picture_key(v, k))
        session_key(v, k);
    fflush(stdout);
}

static void mouse(viewer *v, const SDL_Event *e, int height)
{
    bdl_camera *cam = &v->view.camera;
    if (e->type == SDL_MOUSEMOTION) {
        if (e->motion.state & SDL_BUTTON_LMASK)
            bdl_camera_orbit(cam, -0.3f * (float)e->motion.xrel, 0.3f * (float)e->motion.yrel);
        else if (e->motion.state & (SDL_BUTTON_RMASK | SDL_BUTTON_MMASK))
            bdl_camera_pan(cam, -(float)e->motion.xrel / (float)height,
                           (float)e->motion.yrel / (float)height);
    } else if (e->type == SDL_MOUSEWHEEL) {
        bdl_camera_zoom(cam, powf(0.9f, (float)e->wheel.y));
    }
}

static void status_line(viewer *v, const bdl_snapshot *s)
{
    double sps = s ? s->steps_per_second : 0.0;
    char speed[64] = "full speed", live[128] = "";
    if (v->speed_limit > 0.0)
        snprintf(speed, sizeof speed, "limit %.3g sim s/s", v->speed_limit);
    if (v->live_key[0]) { // what ] and [ change, and its factor now
        char what[96];
        snprintf(what, sizeof what, "%s", v->live_key + (strncmp(v->live_key, "wall.", 5) ? 0 : 5));
        char *dot = strrchr(what, '.');
        if (dot) // "gas.inlet_scale" -> "gas inlet", "drum.frequency_scale" -> "drum frequency"
            *dot = ' ';
        char *tail = strstr(what, "_scale");
        if (tail)
            *tail = '\0';
        snprintf(live, sizeof live, "   ]/[: %s x%.3g", what, v->live_scale);
    }
    double t = 0.0;
    long step = 0, particles = 0;
    int finished = 0;
    if (v->loop)
        bdl_loop_progress(v->loop, &t, &step, &particles, &finished);
    const char *state = finished ? "FINISHED (R restarts)" : v->paused ? "PAUSED" : "running";
    snprintf(v->status, sizeof v->status,
             "%s   solver %.3g steps/s (%.3g sim s/s, %s)   %.0f frames/s   "
             "colour: %s%s   H: help",
             state, finished ? 0.0 : sps, finished ? 0.0 : sps * (v->world ? v->world->dt : 0.0),
             speed, v->fps, bdl_color_mode_names[v->view.color], live);
}

static void run_viewer(viewer *v)
{
    long frame = 0, counted = 0;
    double last = 0.0, start = bdl_wall_seconds(), mark = start, sim_start = -1.0, sim_end = 0.0;
    while (!v->quit) {
        int w, h;
        bdl_context_drawable_size(v->context, &w, &h);
        float aspect = (float)w / (float)(h > 0 ? h : 1);
        SDL_Event e;
        while (SDL_PollEvent(&e)) {
            if (e.type == SDL_QUIT)
                v->quit = 1;
            else if (e.type == SDL_KEYDOWN)
                key(v, e.key.keysym.sym, aspect);
            else
                mouse(v, &e, h);
        }
        while (v->script_next < v->script_count && v->script[v->script_next].frame <= frame) {
            SDL_Event k = {.type = SDL_KEYDOWN};
            k.key.keysym.sym = v->script[v->script_next++].key;
            SDL_PushEvent(&k);
        }
        const bdl_snapshot *s = bdl_loop_acquire(v->loop);
        status_line(v, s);
        v->view.status = v->status;
        v->view.help = v->show_help ? help_text : NULL;
        bdl_renderer_draw(v->renderer, s, &v->view, w, h);
        if (v->script_count > 0 && !v->reported_drawing && s && s->count > 0) {
            printf("view: drawing %ld particles (%ld visible) at %dx%d\n", s->count,
                   bdl_renderer_drawn(v->renderer), w, h);
            v->reported_drawing = 1;
        }
        bdl_context_present(v->context);
        ++frame;
        if (s && sim_start < 0.0)
            sim_start = s->time;
        sim_end = s ? s->time : sim_end;
        const double now_frame = bdl_wall_seconds();
        if (++counted, now_frame - mark >= 1.0) { // the rate over the last second or so
            v->fps = counted / (now_frame - mark);
            mark = now_frame, counted = 0;
        }
        // At most 60 frames a second, whatever the swap interval does.
        double now = bdl_wall_seconds(), wait = 1.0 / 60.0 - (now - last);
        if (wait > 0.0)
            SDL_Delay((Uint32)(wait * 1000.0));
        last = bdl_wall_seconds();
    }
    const double wall = bdl_wall_seconds() - start;
    printf("view: %ld frames in %.2f s (%.1f frames/s); %.3g s simulated meanwhile (%.3g of real "
           "time)\n",
           frame, wall, wall > 0.0 ? frame / wall : 0.0, sim_end - fmax(sim_start, 0.0),
           wall > 0.0 ? (sim_end - fmax(sim_start, 0.0)) / wall : 0.0);
}

/// Opens the window and its renderer for the scene; prints why when it cannot.
static bdl_result open_window(viewer *v)
{
    const bdl_scene_opts *o = v->opts;
    char why[1024];
    bdl_context_def cd = {.backend = BDL_GL_SDL,
                          .window = 1,
                          .width = o->width ? o->width : 1280,
                          .height = o->height ? o->height : 720,
                          .title = o->scene};
    bdl_result rc = bdl_context_create(&cd, &v->context, why, sizeof why);
    if (rc != BDL_OK) {
        fprintf(stderr, "error: cannot open a window: %s\n", why);
        return rc;
    }
    bdl_renderer_def rd = {.scene = v->scene};
    if ((rc = bdl_renderer_create(&rd, &v->renderer, why, sizeof why)) != BDL_OK) {
        fprintf(stderr, "error: %s\n", why);
        return rc;
    }
    int w, h;
    bdl_context_drawable_size(v->context, &w, &h);
    bdl_view_from_scene(v->scene, (float)w / (float)h, &v->view);
    return BDL_OK;
}

/// Reads the scene and the key script, and names the screenshot folder.
static bdl_result prepare(viewer *v)
{
    const bdl_scene_opts *o = v->opts;
    bdl_scene_error err;
    bdl_result rc = bdl_scene_load(o->scene, o->overrides, o->override_count, v->scene, &err);
    if (rc != BDL_OK) {
        fprintf(stderr, "error: %s\n", err.message);
        return rc;
    }
    if (o->script && !load_script(v, o->script))
        return BDL_ERR_ARGS;
    const char *stem = strrchr(o->scene, '/') ? strrchr(o->scene, '/') + 1 : o->scene;
    if (o->out)
        snprintf(v->shot_dir, sizeof v->shot_dir, "%s", o->out);
    else
        snprintf(v->shot_dir, sizeof v->shot_dir, "runs/%.*s/screenshots",
                 (int)(strcspn(stem, ".")), stem);
    find_live_parameter(v);
    return BDL_OK;
}

bdl_result bdl_cmd_view(int argc, char **argv)
{
    bdl_scene_opts o;
    bdl_result rc = bdl_parse_scene_opts(argc, argv, view_usage, &o);
    if (rc != BDL_OK || o.help)
        return rc;
    if (o.gl_backend != BDL_GL_AUTO && o.gl_backend != BDL_GL_SDL) {
        fprintf(stderr, "error: --gl %s: the window needs sdl\n",
                bdl_gl_backend_name((bdl_gl_backend)o.gl_backend));
        return BDL_ERR_ARGS;
    }
    viewer *v = calloc(1, sizeof *v);
    bdl_scene *scene = calloc(1, sizeof *scene);
    if (!v || !scene) {
        free(v);
        free(scene);
        return BDL_ERR_NOMEM;
    }
    v->opts = &o;
    v->scene = scene;
    v->paused = o.paused;
    if ((rc = prepare(v)) == BDL_OK && (rc = open_window(v)) == BDL_OK &&
        (rc = start_world(v)) == BDL_OK)
        run_viewer(v);
    stop_world(v);
    bdl_renderer_destroy(v->renderer);
    bdl_context_destroy(v->context);
    free(scene);
    free(v);
    return rc;
}

#else

bdl_result bdl_cmd_view(int argc, char **argv)
{
    (void)help_text;
    for (int k = 1; k < argc; ++k)
        if (strcmp(argv[k], "--help") == 0 || strcmp(argv[k], "-h") == 0) {
            fputs(view_usage, stdout);
            printf("\nThis bedlam was built without SDL2 (BDL_WITH_SDL=OFF): no window.\n");
            return BDL_OK;
        }
    fprintf(stderr, "error: this bedlam was built without SDL2 (BDL_WITH_SDL=OFF): no window; "
                    "headless frames work with 'bedlam run' and [output] frame_interval\n");
    return BDL_ERR_GL;
}

#endif
