// bedlam — the command line: one function per subcommand.
//
// Subcommands return a result code; main turns it into the process's exit code in one place
// (bdl_exit_code). Printing, signals and the default names of output folders are the app's.
#ifndef BDL_APP_H
#define BDL_APP_H

#include "core/error.h"

/// Process exit code of a result: 0 success; 2 bad input (scene, options, a checkpoint or an
/// output folder that cannot be used); 1 a failure while running (instability, interruption,
/// input/output, memory, no GL, a result the data do not give or outside its tolerance).
int bdl_exit_code(bdl_result r);

bdl_result bdl_cmd_run(int argc, char **argv);
bdl_result bdl_cmd_check(int argc, char **argv);
bdl_result bdl_cmd_bench(int argc, char **argv);
bdl_result bdl_cmd_view(int argc, char **argv);
bdl_result bdl_cmd_verify(int argc, char **argv);
bdl_result bdl_cmd_calibrate(int argc, char **argv);
bdl_result bdl_cmd_analyze(int argc, char **argv);
/// `bedlam bench render` (argv[0] is "render").
bdl_result bdl_bench_render(int argc, char **argv);
bdl_result bdl_bench_coupled(int argc, char **argv);
bdl_result bdl_bench_parcels(int argc, char **argv);

/// Shared option parsing for subcommands that take a scene: --set, --threads, --out, --until,
/// --resume, --quiet. Fills `opts` (opts->help after printing the usage), or prints an error and
/// returns BDL_ERR_ARGS.
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
    int help;           ///< --help was printed: nothing else to do
} bdl_scene_opts;

bdl_result bdl_parse_scene_opts(int argc, char **argv, const char *usage, bdl_scene_opts *opts);

typedef struct bdl_world bdl_world;

/// The world of the scene file at `path` with its --set overrides; prints why there is none.
bdl_result bdl_load_world(const char *path, const char *const *overrides, int override_count,
                          bdl_world **w);

#endif
