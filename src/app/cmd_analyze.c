// bedlam analyze WHAT RUN — the analyses of a finished run: the command line, the output
// folder, and the call of the analysis asked for (app/analyze.h).
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app/analyze.h"
#include "app/app.h"
#include "app/options.h"
#include "core/file.h"

// The usage in four literals (C11 promises string literals of 4095 characters only), joined on
// first use.
static const char usage_first[] =
    "usage: bedlam analyze sweep RUN [--out DIR] [--no-plots]\n"
    "       bedlam analyze spectrum RUN [--column NAME] [--from T] [--to T] [--fmin F] [--fmax F]\n"
    "                               [--segments N]\n"
    "                               [--out DIR] [--no-plots]\n"
    "       bedlam analyze mean RUN --column NAME [--from T] [--to T]\n"
    "       bedlam analyze phase RUN --column NAME --period P [--start T] [--from-cycle A]\n"
    "                            [--to-cycle B] [--bins N] [--below X] [--out DIR] [--no-plots]\n"
    "       bedlam analyze profile RUN [--from T] [--to T] [--out DIR] [--no-plots]\n"
    "       bedlam analyze fields RUN [--from T] [--to T] [--cell H] [--out DIR]\n"
    "       bedlam analyze networks CONTACTS.csv [--file PARTICLES.vtp] [--bins N] [--fmax F]\n"
    "                               [--out DIR] [--no-plots]\n"
    "       bedlam analyze dia RUN/dia/NAME [--fit FIT.json --density RHO [--height H]]\n"
    "                          [--out DIR]\n"
    "       bedlam analyze orientation RUN [--from T] [--to T] [--by-velocity] [--out DIR]\n"
    "                                  [--no-plots]\n"
    "       bedlam analyze ptv RUN/dia/NAME [--max-step PX] [--out DIR]\n"
    "       bedlam analyze rheology RUN [RUN...] [--from T] [--to T] [--restitution E\n"
    "                               [--damping B]]\n"
    "                               [--jamming X [--amplitude A [--stiffness K --a2 C]]]\n"
    "                               [--out DIR] [--no-plots]\n"
    "\n"
    "Reads RUN/diagnostics.csv of a finished run (spectrum, mean and phase read another CSV of\n"
    "the run with --file NAME, e.g. --file species.csv).\n"
    "\n"
    "sweep: a run with a [gas] sweep. Each stage of the inlet velocity is averaged over its "
    "second\n"
    "half (the first is the transient); stages are split into the increasing and the decreasing\n"
    "branch; on each, a two-piece fit (the packed branch a U + b U^2 below a split velocity, the\n"
    "fluidized plateau above it, the split with the least residual) gives U_mf where the two\n"
    "meet (the decreasing branch is the experimenters' choice), and the plateau against the bed's\n"
    "weight per area (weight_ratio). Writes sweep.csv and sweep.png.\n"
    "\n"
    "spectrum: the power spectrum of a column (default pressure_drop) between --from and --to\n"
    "(default: the whole run), with a Hamming window, and its dominant frequency between --fmin\n"
    "and --fmax (default 0.2 and 20 Hz). --segments N: Welch's average over N half-overlapping\n"
    "pieces, and each piece's dominant frequency (their spread shows whether the peak has\n"
    "converged). Writes spectrum_COLUMN.csv and spectrum_COLUMN.png.\n"
    "\n"
    "mean: the time average of a column between --from and --to, its standard deviation, and the\n"
    "standard error of the average from 10 consecutive blocks (which allows for correlation in\n"
    "time).\n"
    "\n"
    "phase: a vibrated run's column folded over the vibration cycle of period P started at T\n"
    "(default 0): its mean, least and largest value in N phase bins (default 50) over cycles A\n"
    "to B-1 (default all), and the phase intervals where the mean is below X (--below; e.g.\n"
    "wall_force below a small value: the bed in flight). Writes phase_NAME.csv and\n"
    "phase_NAME.png (with the column against the cycle count beside it).\n"
    "\n"
    "fields: the solids fraction and the solids velocity averaged over the particle files\n"
    "(particles.pvd) between --from and --to, on cubic cells of --cell metres (default three\n"
    "mean diameters) over the domain: each particle's volume (and volume times velocity) in the\n"
    "cell of its centre. Writes fields.vti (ParaView; the velocity is NaN where no solids\n"
    "passed). A run with [output] fields_interval writes the same itself, without particle\n"
    "files.\n\n"
    "profile: the solids fraction of each gas cell layer (RUN/profile.csv, runs with a gas)\n"
    "averaged between --from and --to: the solids fraction against height. Writes profile.csv\n"
    "and profile.png.\n"
    "\n";
static const char usage_networks[] =
    "networks: a contact file of a run ([output] contacts_interval): the force networks\n"
    "(connected sets of particles touching with a normal force: their number, the largest one's\n"
    "particles, contacts, mean coordination and length), those of the forces above the mean, and\n"
    "the distribution of f = F_n/<F_n> in N bins (default 40) up to F (default 5), fitted with\n"
    "P(f) = a (1 - b exp(-f^2)) exp(-beta f), and the force correlation F(r) (Sun's eq. 6.12).\n"
    "Writes force_pdf.csv, force_pdf.png and force_correlation.csv. With --file, the run's\n"
    "particle file of the same moment: the union of 1 to 5 minimum spanning trees of all the\n"
    "centres (edges already chosen lengthened by 1.2 each pass), kept where particles touch,\n"
    "against the force networks (Sun's table 6.2).\n"
    "\n";
static const char usage_second[] =
    "dia: a synthetic camera's images (an orthographic [camera NAME] kind = dia) through the\n"
    "thesis's image analysis, scored against the truth beside them: the bed height from the\n"
    "row-averaged intensity gradient against the same definition on the true solids fraction;\n"
    "the rods lying along the front wall detected (adaptive threshold, blobs, the angle of\n"
    "largest aspect ratio) and their angle errors; PIV (256 px at 50 %, then 128 px at 75 %) of\n"
    "each double frame against the true displacement of the visible particles per cell; the\n"
    "coalignment length of the detected and of the true rods; C(r) pooled over the frames with\n"
    "its length in three zones by the reference rod's distance from the nearer side wall (< 2,\n"
    "2-6, > 6 rod lengths; the walls are taken to be the image's left and right edges, so the\n"
    "camera must see the bed's full width). Writes dia_scores.csv and coalignment.csv.\n"
    "With --fit (a fit.json of bedlam calibrate) and --density RHO [kg/m^3], which it then needs:\n"
    "the solids mass flux rho (1 - eps) v per image cell of each double frame: eps from the f2D\n"
    "of the first image, measured as calibrate did for the fit (its threshold and normalisation),\n"
    "through the fit; v from the PIV vectors in the cell. Against rho times the true solids\n"
    "fraction and the true velocity of the visible particles; cells without a PIV vector or\n"
    "visible particles are left out. Prints the time-mean vertical flux across the width at the\n"
    "cell row nearest --height H (default 0.0991 m, the thesis's small bed) and the error over\n"
    "all cells. Writes mass_flux.csv.\n"
    "\n"
    "orientation: the rods' in-plane angle (RUN/orientation.csv, runs with rods and [output]\n"
    "orientation_interval): the axis projected on the x-z plane, its angle from the vertical z\n"
    "(0 upright, +-90 lying, positive leaning to +x), as a camera at the front wall sees it. The\n"
    "histograms of the rows between --from and --to are pooled into a PDF [1/deg] near the walls\n"
    "(centres within one rod length of the front or back wall, y) and in the bulk; with\n"
    "--by-velocity one PDF per stage of the inlet velocity, over its second half as sweep takes\n"
    "it. Writes orientation.csv (stage, inlet_velocity, angle, wall_pdf, bulk_pdf),\n"
    "orientation_summary.csv (per stage: rows, rods, mean |cos| of the 3D angle to the vertical)\n"
    "and orientation.png.\n"
    "\n"
    "ptv: a high-speed synthetic camera's single images (a [camera NAME] kind = dia with a short\n"
    "interval, e.g. scenes/dia_rod_bed.ini's [camera ptv]) through the thesis's particle "
    "tracking:\n"
    "the rods detected in every frame as dia does, linked to the nearest detection of the next\n"
    "frame (conflicts to the smallest displacement, links of at most --max-step px, default half\n"
    "a rod length), tracks of 4 frames or more. Each detection is matched to the visible true\n"
    "particle nearest its centroid; reports the share of links joining the same particle, the\n"
    "tracks' velocities (central differences) against the true ones, and the 2D coordination\n"
    "number of the tracked rods (neighbours within one rod length, corrected for the part of\n"
    "that disc outside the image) against that of the true rods along the wall, in the thesis's\n"
    "classes with each class's mean vertical velocity. Writes ptv_tracks.csv.\n"
    "\n";
static const char usage_third[] =
    "rheology: shear cells ([output] rheology_interval; scenes/shear_cell.ini): each RUN's\n"
    "rheology.csv averaged between --from (default: a shear strain of 10) and --to, with the\n"
    "standard error from 10 blocks: solids fraction, shear rate, granular temperature, pressure,\n"
    "shear stress, mu = tau/p, inertial number, normal-stress differences, rods' alignment, and\n"
    "the stresses over rho d^2 (shear rate)^2. With --restitution E (smooth spheres) the kinetic\n"
    "theory of Lun et al. (1984) at each run's solids fraction and shear rate, and its pressure\n"
    "and shear stress at the run's own temperature; and the run's reduced viscosity eta/eta0\n"
    "and shear rate/nu0 (eta0 = (5/96) rho d sqrt(pi T), nu0 = rho nu T/eta0; written to the\n"
    "table for every run) and N1/p beside Lun et al.'s and beside the limit nu -> 0 of the\n"
    "Boltzmann equation's steady shear solved by Grad's method (e < 1), which the dilute flow\n"
    "follows where the theory, first order in the shear, fails. With --damping B as well (the\n"
    "runs' [species] background_damping in their Lees-Edwards box, 1/s): Grad's limit with that\n"
    "drag, at the reduced drag B/nu0 of each run's own temperature.\n"
    "With --jamming X (3 runs or more): the contact pressure over rho d^2 (shear rate)^2, y,\n"
    "fitted with A (nu_cr - nu)^-X over the runs, the distance to jamming (X = 4 for AR-4 rods,\n"
    "2 for spheres: Chialvo et al. 2012, Mahajan 2019 ch. 6). With --amplitude A as well, A is\n"
    "held (the thesis's collapse, its eq. 6.3: 1/b2^2 = 1.464e-4 for AR-4 rods) and each run\n"
    "gives its own nu_cr = nu + (A/y)^(1/X), one run or more. With --stiffness K (k_n, N/m) and\n"
    "--a2 C too (the thesis: 6e5 and 39.56), on the whole soft branch of eq. 6.3 instead of its\n"
    "inertial limit: the branch crosses a pressure below its peak twice, and the crossing on the\n"
    "inertial side is given first, the one on the springs' side after it; a contact pressure\n"
    "above the branch's peak at the run's shear rate lies past jamming (nu_cr <= nu).\n"
    "Writes rheology.csv (one row per run) and rheology.png into --out (default\n"
    "the first RUN's analysis folder).\n"
    "\n"
    "--out DIR: where the files go (default RUN/analysis, or the contact file's folder). Exit "
    "codes: 0 done, 1 the analysis\n"
    "found nothing (no sweep, too few samples), 2 bad options or unreadable input.\n";
static char analyze_usage[sizeof usage_first + sizeof usage_networks + sizeof usage_second +
                          sizeof usage_third];

static const bdl_option options[] = {
    {"--column", BDL_OPTION_TEXT, offsetof(bdl_analyze_opts, column)},
    {"--from", BDL_OPTION_NUMBER, offsetof(bdl_analyze_opts, from)},
    {"--to", BDL_OPTION_NUMBER, offsetof(bdl_analyze_opts, to)},
    {"--fmin", BDL_OPTION_NUMBER, offsetof(bdl_analyze_opts, fmin)},
    {"--fmax", BDL_OPTION_NUMBER, offsetof(bdl_analyze_opts, fmax)},
    {"--file", BDL_OPTION_TEXT, offsetof(bdl_analyze_opts, file)},
    {"--period", BDL_OPTION_NUMBER, offsetof(bdl_analyze_opts, period)},
    {"--start", BDL_OPTION_NUMBER, offsetof(bdl_analyze_opts, start)},
    {"--below", BDL_OPTION_NUMBER, offsetof(bdl_analyze_opts, below)},
    {"--from-cycle", BDL_OPTION_LONG, offsetof(bdl_analyze_opts, from_cycle)},
    {"--to-cycle", BDL_OPTION_LONG, offsetof(bdl_analyze_opts, to_cycle)},
    {"--bins", BDL_OPTION_INT, offsetof(bdl_analyze_opts, bins)},
    {"--segments", BDL_OPTION_INT, offsetof(bdl_analyze_opts, segments)},
    {"--out", BDL_OPTION_TEXT, offsetof(bdl_analyze_opts, out)},
    {"--no-plots", BDL_OPTION_CLEAR, offsetof(bdl_analyze_opts, plots)},
    {"--by-velocity", BDL_OPTION_SET, offsetof(bdl_analyze_opts, by_velocity)},
    {"--max-step", BDL_OPTION_NUMBER, offsetof(bdl_analyze_opts, max_step)},
    {"--fit", BDL_OPTION_TEXT, offsetof(bdl_analyze_opts, fit)},
    {"--density", BDL_OPTION_NUMBER, offsetof(bdl_analyze_opts, density)},
    {"--height", BDL_OPTION_NUMBER, offsetof(bdl_analyze_opts, height)},
    {"--cell", BDL_OPTION_NUMBER, offsetof(bdl_analyze_opts, cell)},
    {"--restitution", BDL_OPTION_NUMBER, offsetof(bdl_analyze_opts, restitution)},
    {"--jamming", BDL_OPTION_NUMBER, offsetof(bdl_analyze_opts, jamming)},
    {"--amplitude", BDL_OPTION_NUMBER, offsetof(bdl_analyze_opts, amplitude)},
    {"--stiffness", BDL_OPTION_NUMBER, offsetof(bdl_analyze_opts, stiffness)},
    {"--a2", BDL_OPTION_NUMBER, offsetof(bdl_analyze_opts, a2)},
    {"--damping", BDL_OPTION_NUMBER, offsetof(bdl_analyze_opts, damping)},
};

/// The run folder (or contact file): one, and no unknown option.
static int take_run(void *opts, int argc, char **argv, int i)
{
    (void)argc;
    bdl_analyze_opts *o = opts;
    const char *a = argv[i];
    const int many = strcmp(o->what, "rheology") == 0 && o->run_count < BDL_ANALYZE_RUNS_MAX;
    if (a[0] == '-' || (o->run && !many)) {
        fprintf(stderr, "error: unexpected argument '%s'\n\n%s", a, analyze_usage);
        return 0;
    }
    if (!o->run)
        o->run = a;
    o->runs[o->run_count++] = a;
    return 1;
}

/// The values of the options that take numbers are numbers (atof would read "abc" as 0).
static bdl_result check_numbers(int argc, char **argv)
{
    for (int i = 2; i + 1 < argc; ++i) {
        const bdl_option *opt = bdl_option_find(options, BDL_OPTION_COUNT(options), argv[i]);
        if (!opt || opt->kind == BDL_OPTION_TEXT || opt->kind == BDL_OPTION_SET ||
            opt->kind == BDL_OPTION_CLEAR)
            continue;
        char *end;
        const double v = strtod(argv[i + 1], &end);
        if (end == argv[i + 1] || *end != '\0' || isnan(v) ||
            (opt->kind != BDL_OPTION_NUMBER && v != floor(v))) {
            fprintf(stderr, "error: %s %s: not a%s number\n", argv[i], argv[i + 1],
                    opt->kind == BDL_OPTION_NUMBER ? "" : " whole");
            return BDL_ERR_ARGS;
        }
        ++i;
    }
    return BDL_OK;
}

/// Reads argv[2..] into *o; *help when --help was printed.
static bdl_result parse_options(int argc, char **argv, bdl_analyze_opts *o, int *help)
{
    static const bdl_option_parser parser = {options, BDL_OPTION_COUNT(options), analyze_usage, 1,
                                             take_run};
    *o = (bdl_analyze_opts){.what = argv[1],
                            .column = "pressure_drop",
                            .file = "diagnostics.csv",
                            .from = -INFINITY,
                            .to = INFINITY,
                            .fmin = 0.2,
                            .fmax = NAN,
                            .period = NAN,
                            .below = NAN,
                            .density = NAN,
                            .restitution = NAN,
                            .height = 0.0991,
                            .to_cycle = 1L << 40,
                            .bins = -1,
                            .segments = 1,
                            .plots = 1};
    *help = 0;
    const bdl_result rc = check_numbers(argc, argv);
    return rc != BDL_OK ? rc : bdl_option_parse(&parser, argc, argv, 2, o, help);
}

/// The defaults that depend on the analysis, and the checks of the options every analysis but
/// mean takes.
static bdl_result check_options(bdl_analyze_opts *o)
{
    const int networks = strcmp(o->what, "networks") == 0;
    if (networks && strcmp(o->file, "diagnostics.csv") == 0)
        o->file = NULL; // no particle file: no spanning trees
    if (isnan(o->fmax))
        o->fmax = networks ? 5.0 : 20.0;
    if (o->bins < 0)
        o->bins = networks ? 40 : 50;
    if (!(o->fmax > o->fmin) || o->bins < 3 || o->bins > 100000) {
        fprintf(stderr, "error: --fmax must be above --fmin, --bins from 3 to 100000\n");
        return BDL_ERR_ARGS;
    }
    if (o->segments < 1 || o->segments > 1000) {
        fprintf(stderr, "error: --segments from 1 to 1000\n");
        return BDL_ERR_ARGS;
    }
    if (!(o->from < o->to)) {
        fprintf(stderr, "error: --from must be below --to\n");
        return BDL_ERR_ARGS;
    }
    if (strcmp(o->what, "phase") == 0 && !(o->period > 0.0)) {
        fprintf(stderr, "error: phase needs --period P > 0 [s]\n");
        return BDL_ERR_ARGS;
    }
    return BDL_OK;
}

/// --out, or RUN/analysis, or the contact file's folder (networks); created if missing.
static bdl_result output_folder(const bdl_analyze_opts *o, char *out, size_t len)
{
    const char *slash = strrchr(o->run, '/');
    if (o->out)
        snprintf(out, len, "%s", o->out);
    else if (strcmp(o->what, "networks") == 0)
        snprintf(out, len, "%.*s", slash ? (int)(slash - o->run) : 1, slash ? o->run : ".");
    else
        snprintf(out, len, "%s/analysis", o->run);
    char why[512];
    if (bdl_check_writable_dir(out, why, sizeof why) != BDL_OK) {
        fprintf(stderr, "error: --out %s: %s\n", out, why);
        return BDL_ERR_OUTPUT_DIR;
    }
    return BDL_OK;
}

typedef struct analysis {
    const char *name;
    bdl_result (*fn)(const bdl_analyze_opts *);
} analysis;

static const analysis analyses[] = {
    {"sweep", bdl_analyze_sweep},       {"spectrum", bdl_analyze_spectrum},
    {"mean", bdl_analyze_mean},         {"phase", bdl_analyze_phase},
    {"networks", bdl_analyze_networks}, {"profile", bdl_analyze_profile},
    {"dia", bdl_analyze_dia},           {"orientation", bdl_analyze_orientation},
    {"ptv", bdl_analyze_ptv},           {"fields", bdl_analyze_fields},
    {"rheology", bdl_analyze_rheology},
};

bdl_result bdl_cmd_analyze(int argc, char **argv)
{
    if (!analyze_usage[0])
        snprintf(analyze_usage, sizeof analyze_usage, "%s%s%s%s", usage_first, usage_networks,
                 usage_second, usage_third);
    if (argc < 2 || strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0) {
        fputs(analyze_usage, argc < 2 ? stderr : stdout);
        return argc < 2 ? BDL_ERR_ARGS : BDL_OK;
    }
    bdl_analyze_opts o;
    int help;
    bdl_result rc = parse_options(argc, argv, &o, &help);
    if (rc != BDL_OK || help)
        return rc;
    const analysis *a = NULL;
    for (size_t k = 0; k < sizeof analyses / sizeof analyses[0]; ++k)
        if (strcmp(o.what, analyses[k].name) == 0)
            a = &analyses[k];
    if (!o.run || !a) {
        fprintf(stderr,
                "error: expected 'sweep RUN', 'spectrum RUN', 'mean RUN', 'phase RUN', "
                "'profile RUN', 'fields RUN', 'orientation RUN', 'rheology RUN...', "
                "'networks CONTACTS.csv', 'dia RUN/dia/NAME' or 'ptv RUN/dia/NAME'\n\n%s",
                analyze_usage);
        return BDL_ERR_ARGS;
    }
    if (a->fn == bdl_analyze_mean) // prints only: no folder, no bins
        return bdl_analyze_mean(&o);
    char out[1100];
    if ((rc = check_options(&o)) != BDL_OK || (rc = output_folder(&o, out, sizeof out)) != BDL_OK)
        return rc;
    o.out = out;
    return a->fn(&o);
}
