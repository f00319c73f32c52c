// bedlam — entry point: dispatches to the subcommands.
#define _POSIX_C_SOURCE 200809L // setenv, execv
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "app/app.h"
#include "core/comm.h"
#include "core/log.h"

static const char usage[] =
    "bedlam " BDL_VERSION " — interactive simulator of gas–solid and granular flows\n"
    "\n"
    "usage: bedlam COMMAND [options]\n"
    "\n"
    "commands:\n"
    "  run SCENE     run a scene headless and write its outputs (run.log, diagnostics.csv, VTK,\n"
    "                checkpoints) into one folder\n"
    "  view SCENE    run a scene in a window: orbit, colour modes, pause, step, live parameters\n"
    "  check SCENE   validate a scene; print the active modules, contact time (for parcels:\n"
    "                parcels per cell, stress), stable time-step limit and the estimated cost\n"
    "  bench [CASE]  performance benchmarks (dem, render, coupled, parcels)\n"
    "  verify [CASE] verification cases at several refinements: error against run time,\n"
    "                observed orders, tables and plots in docs/validation/\n"
    "  calibrate DIR fit the 2D-to-3D solids fraction of synthetic camera images ([camera NAME]\n"
    "                kind = dia) against their truth; apply a fit to any images\n"
    "  analyze WHAT RUN  a finished run's outputs: sweep (U_mf), spectrum, mean, phase and\n"
    "                profile of a column, time-averaged fields, contact networks, dia images,\n"
    "                rod orientation, ptv tracks, shear-cell rheology (bedlam analyze --help)\n"
    "\n"
    "Every command takes --help. Exit codes: 0 success, 1 run-time failure (instability,\n"
    "interrupted), 2 bad input (scene, options).\n"
    "Documentation: README.md and docs/ (docs/scene-format.md lists every scene key).\n";

typedef struct command {
    const char *name;
    bdl_result (*fn)(int, char **);
} command;

int bdl_exit_code(bdl_result r)
{
    switch (r) {
    case BDL_OK:
        return 0;
    case BDL_ERR_SCENE:
    case BDL_ERR_ARGS:
    case BDL_ERR_OUTPUT_DIR:
    case BDL_ERR_CHECKPOINT:
    case BDL_ERR_NO_DISPLAY:
        return 2;
    default:
        return 1;
    }
}

/// OpenMP threads waiting at a barrier spin on their core by default (libgomp: about 300 000
/// rounds before they sleep). On a machine shared with other work that steals the core from a
/// thread that has work, and a parallel region then waits for a thread that cannot run. Unless the
/// user chose a policy, bedlam runs with OMP_WAIT_POLICY=passive: waiting threads sleep at once.
/// libgomp reads the variable when it loads, before main, so the program starts itself again with
/// it set (if that fails, it goes on as it is).
static void passive_wait(char **argv)
{
    if (getenv("OMP_WAIT_POLICY") || getenv("GOMP_SPINCOUNT"))
        return;
    if (setenv("OMP_WAIT_POLICY", "passive", 1) == 0)
        execv("/proc/self/exe", argv);
}

/// Runs a command between the start and the end of MPI (when built with it). Under mpirun every
/// rank runs it: `run` and `bench dem` divide their particles between them and the first rank
/// speaks and writes; the other commands do not divide their work, so more than one rank is
/// refused for them rather than run N times over.
static int run_command(const command *c, int argc, char **argv)
{
    if (bdl_comm_init(&argc, &argv) != 0) {
        fprintf(stderr, "error: MPI could not be started\n");
        return 1;
    }
    int code = 2;
    bdl_log_set_quiet(bdl_comm_rank() > 0);
    const int divides = strcmp(c->name, "run") == 0 || strcmp(c->name, "bench") == 0;
    if (bdl_comm_rank() > 0 && divides && !freopen("/dev/null", "w", stdout))
        return 1; // the first rank prints the tables
    if (bdl_comm_size() > 1 && !divides) {
        if (bdl_comm_rank() == 0)
            fprintf(stderr,
                    "error: bedlam %s runs on one rank (mpirun -np 1); this build does not "
                    "divide a run between %d ranks yet\n",
                    c->name, bdl_comm_size());
    } else {
        code = bdl_exit_code(c->fn(argc - 1, argv + 1));
    }
    bdl_comm_finalize();
    return code;
}

int main(int argc, char **argv)
{
    passive_wait(argv);
    static const command commands[] = {
        {"run", bdl_cmd_run},         {"view", bdl_cmd_view},     {"check", bdl_cmd_check},
        {"bench", bdl_cmd_bench},     {"verify", bdl_cmd_verify}, {"calibrate", bdl_cmd_calibrate},
        {"analyze", bdl_cmd_analyze},
    };
    if (argc < 2 || strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0 ||
        strcmp(argv[1], "help") == 0) {
        fputs(usage, argc < 2 ? stderr : stdout);
        return argc < 2 ? 2 : 0;
    }
    if (strcmp(argv[1], "--version") == 0) {
        printf("bedlam %s\n", BDL_VERSION);
        return 0;
    }
    for (size_t k = 0; k < sizeof commands / sizeof commands[0]; ++k)
        if (strcmp(argv[1], commands[k].name) == 0)
            return run_command(&commands[k], argc, argv);
    fprintf(stderr, "error: unknown command '%s'\n\n%s", argv[1], usage);
    return 2;
}
