// bedlam — the options of the subcommands that take a scene (run, view, check), and the world of
// such a scene.
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app/app.h"
#include "app/options.h"
#include "render/context.h"
#include "world/world.h"

static int parse_number(const char *opt, const char *text, double lo, double *out)
{
    char *end;
    double v = strtod(text, &end);
    if (end == text || *end != '\0' || !(v >= lo)) {
        fprintf(stderr, "error: %s %s: expected a number >= %g\n", opt, text, lo);
        return 0;
    }
    *out = v;
    return 1;
}

static bdl_result set_override(const char *opt, const char *value, bdl_scene_opts *o)
{
    (void)opt;
    if (!strchr(value, '=') || o->override_count >= 256) {
        fprintf(stderr, "error: --set %s: expected section.key=value\n", value);
        return BDL_ERR_ARGS;
    }
    o->overrides[o->override_count++] = value;
    return BDL_OK;
}

static bdl_result set_until(const char *opt, const char *value, bdl_scene_opts *o)
{
    return parse_number(opt, value, 1e-300, &o->until) ? BDL_OK : BDL_ERR_ARGS;
}

static bdl_result set_steps(const char *opt, const char *value, bdl_scene_opts *o)
{
    double steps;
    if (!parse_number(opt, value, 1, &steps) || steps != (long)steps) {
        fprintf(stderr, "error: --steps %s: expected a whole number >= 1\n", value);
        return BDL_ERR_ARGS;
    }
    o->steps = (long)steps;
    return BDL_OK;
}

static bdl_result set_threads(const char *opt, const char *value, bdl_scene_opts *o)
{
    double threads;
    if (!parse_number(opt, value, 1, &threads) || threads > 256 || threads != (int)threads) {
        fprintf(stderr, "error: --threads %s: expected a whole number from 1 to 256\n", value);
        return BDL_ERR_ARGS;
    }
    o->threads = (int)threads;
    return BDL_OK;
}

static bdl_result set_gl(const char *opt, const char *value, bdl_scene_opts *o)
{
    (void)opt;
    bdl_gl_backend b;
    if (!bdl_gl_backend_parse(value, &b)) {
        fprintf(stderr, "error: --gl %s: expected auto, sdl, egl or osmesa\n", value);
        return BDL_ERR_ARGS;
    }
    o->gl_backend = (int)b;
    return BDL_OK;
}

static bdl_result set_size(const char *opt, const char *value, bdl_scene_opts *o)
{
    (void)opt;
    int w = 0, h = 0;
    char tail;
    if (sscanf(value, "%dx%d%c", &w, &h, &tail) != 2 || w < 16 || h < 16 || w > 8192 || h > 8192) {
        fprintf(stderr, "error: --size %s: expected WIDTHxHEIGHT, 16 to 8192 pixels\n", value);
        return BDL_ERR_ARGS;
    }
    o->width = w;
    o->height = h;
    return BDL_OK;
}

/// The options of scene commands that take a value that is checked, and what checks and
/// stores it.
typedef struct checked_option {
    const char *name;
    bdl_result (*set)(const char *opt, const char *value, bdl_scene_opts *o);
} checked_option;

static const checked_option checked_options[] = {
    {"--set", set_override}, {"--until", set_until}, {"--threads", set_threads},
    {"--steps", set_steps},  {"--gl", set_gl},       {"--size", set_size},
};

/// The ones whose value is taken as it is.
static const bdl_option text_options[] = {
    {"--out", BDL_OPTION_TEXT, offsetof(bdl_scene_opts, out)},
    {"--resume", BDL_OPTION_TEXT, offsetof(bdl_scene_opts, resume)},
    {"--script", BDL_OPTION_TEXT, offsetof(bdl_scene_opts, script)},
};

static const checked_option *find_checked(const char *name)
{
    for (size_t k = 0; k < BDL_OPTION_COUNT(checked_options); ++k)
        if (strcmp(name, checked_options[k].name) == 0)
            return &checked_options[k];
    return NULL;
}

/// A flag, or the scene; BDL_ERR_ARGS (printed) for anything else.
static bdl_result take_argument(const char *a, const char *usage, bdl_scene_opts *opts)
{
    if (strcmp(a, "--paused") == 0) {
        opts->paused = 1;
    } else if (strcmp(a, "--quiet") == 0 || strcmp(a, "-q") == 0) {
        opts->quiet = 1;
    } else if (a[0] == '-' && a[1] != '\0') {
        fprintf(stderr, "error: unknown option '%s'\n\n%s", a, usage);
        return BDL_ERR_ARGS;
    } else if (!opts->scene) {
        opts->scene = a;
    } else {
        fprintf(stderr, "error: unexpected argument '%s' (one scene only)\n\n%s", a, usage);
        return BDL_ERR_ARGS;
    }
    return BDL_OK;
}

bdl_result bdl_parse_scene_opts(int argc, char **argv, const char *usage, bdl_scene_opts *opts)
{
    memset(opts, 0, sizeof *opts);
    opts->until = -1.0;
    for (int k = 1; k < argc; ++k) {
        const char *a = argv[k];
        const char *next = k + 1 < argc ? argv[k + 1] : NULL;
        if (bdl_option_is_help(a)) {
            fputs(usage, stdout);
            opts->help = 1;
            return BDL_OK;
        }
        const checked_option *checked = find_checked(a);
        const int text = bdl_option_find(text_options, BDL_OPTION_COUNT(text_options), a) != NULL;
        if ((checked || text) && !next) {
            fprintf(stderr, "error: %s needs a value\n\n%s", a, usage);
            return BDL_ERR_ARGS;
        }
        bdl_result r = BDL_OK;
        if (checked)
            r = checked->set(a, next, opts);
        else if (text)
            bdl_option_set(text_options, BDL_OPTION_COUNT(text_options), opts, a, next);
        else
            r = take_argument(a, usage, opts);
        if (r != BDL_OK)
            return r;
        k += checked || text;
    }
    if (!opts->scene) {
        fprintf(stderr, "error: no scene file given\n\n%s", usage);
        return BDL_ERR_ARGS;
    }
    return BDL_OK;
}

bdl_result bdl_load_world(const char *path, const char *const *overrides, int override_count,
                          bdl_world **w)
{
    bdl_scene *scene = calloc(1, sizeof *scene);
    bdl_scene_error err;
    if (!scene) {
        fprintf(stderr, "error: %s\n", bdl_result_text(BDL_ERR_NOMEM));
        return BDL_ERR_NOMEM;
    }
    bdl_result r = bdl_scene_load(path, overrides, override_count, scene, &err);
    if (r != BDL_OK)
        fprintf(stderr, "error: %s\n", err.message);
    else if ((r = bdl_world_create(scene, w, &err)) != BDL_OK)
        fprintf(stderr, "error: %s\n", r == BDL_ERR_SCENE ? err.message : bdl_result_text(r));
    free(scene);
    return r;
}
