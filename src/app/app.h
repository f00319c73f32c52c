// bedlam — the command line: one function per subcommand.
#ifndef BDL_APP_H
#define BDL_APP_H

int bdl_cmd_run(int argc, char **argv);
int bdl_cmd_check(int argc, char **argv);
int bdl_cmd_bench(int argc, char **argv);
int bdl_cmd_view(int argc, char **argv);
int bdl_cmd_verify(int argc, char **argv);
int bdl_cmd_calibrate(int argc, char **argv);
int bdl_cmd_analyze(int argc, char **argv);
/// `bedlam bench render` (argv[0] is "render").
int bdl_bench_render(int argc, char **argv);
int bdl_bench_coupled(int argc, char **argv);

/// Shared option parsing for subcommands that take a scene: --set, --threads, --out, --until,
/// --resume, --quiet. Returns 0 and fills `opts`, or prints an error and returns 2; returns -1
/// after printing help.
typedef struct bdl_scene_opts {
    const char *scene;
    const char *overrides[256];
    int override_count;
    const char *out;
    const char *resume;
    double until;
    long steps;
    int threads;
    int quiet;
    int gl_backend;     ///< bdl_gl_backend from --gl
    int width, height;  ///< --size WxH (0: default)
    const char *script; ///< --script FILE (view)
    int paused;         ///< --paused (view)
} bdl_scene_opts;

int bdl_parse_scene_opts(int argc, char **argv, const char *usage, bdl_scene_opts *opts);

#endif
