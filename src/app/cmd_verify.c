// bedlam verify [CASE...] — every verification case at several refinements: error against run
// time, observed orders, CSV per case, a README with the tables and gnuplot work-precision plots.
#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "app/app.h"
#include "app/options.h"
#include "core/timer.h"
#include "core/file.h"
#include "verify/verify.h"

static const char verify_usage[] =
    "usage: bedlam verify [CASE...] [--quick] [--out DIR] [--threads N] [--no-plots] [--list]\n"
    "                     [--from DIR]\n"
    "\n"
    "Runs each verification case (all of them when none is named) at three or more refinements\n"
    "(time step, grid, averaging time, ...) and records, per run, the error against the case's\n"
    "known answer and the wall-clock time. Writes into DIR (default docs/validation):\n"
    "  CASE.csv   one row per run: series, refinement N, error, wall seconds, steps, threads\n"
    "  CASE.png   work-precision plot: error against N and against run time (needs gnuplot)\n"
    "  README.md  a table per case: reference, tolerance, error, observed order, run time\n"
    "\n"
    "  --quick      the reduced set (fewer refinements, the slowest cases left out), for CI\n"
    "  --out DIR    output folder (created if missing)\n"
    "  --threads N  OpenMP threads (default 1: these are small problems; timings compare)\n"
    "  --no-plots   skip gnuplot\n"
    "  --from DIR   run nothing: read the cases' CSV files from an earlier run in DIR and write\n"
    "               the plots and README.md again (after a gnuplot failure, or a changed text)\n"
    "  --list       list the cases and exit\n"
    "\n"
    "Exit codes: 0 every case within its tolerance (and its order, where one applies), 1 a case\n"
    "failed, 2 bad options or an unwritable output folder.\n";

#define MAX_POINTS 32

typedef struct point {
    int series;
    double n, wall;
    bdl_verify_result r;
    bdl_result status;
} point;

typedef struct case_run {
    const bdl_verify_case *c;
    int levels;
    int count;
    point p[MAX_POINTS];
    double wall;
    int pass;
    int plotted; ///< its plot was drawn
    char why[512];
} case_run;

static const point *find_point(const case_run *cr, int series, int level)
{
    for (int k = 0; k < cr->count; ++k)
        if (cr->p[k].series == series && cr->p[k].n == cr->c->level[level])
            return &cr->p[k];
    return NULL;
}

/// Observed order between levels k and k+1 of a series (NAN where it cannot be formed).
static double order_at(const case_run *cr, int series, int k)
{
    const point *a = find_point(cr, series, k), *b = find_point(cr, series, k + 1);
    if (!a || !b || !(a->r.error > 0.0) || !(b->r.error > 0.0) || !isfinite(a->r.error) ||
        !isfinite(b->r.error))
        return NAN;
    return bdl_verify_order(a->n, a->r.error, b->n, b->r.error);
}

/// Order of the successive differences over levels k-1, k, k+1 of a series (NAN if none).
static double diff_order_at(const case_run *cr, int series, int k)
{
    if (k < 1)
        return NAN;
    const point *a = find_point(cr, series, k - 1), *b = find_point(cr, series, k),
                *c = find_point(cr, series, k + 1);
    if (!a || !b || !c)
        return NAN;
    return bdl_verify_difference_order(a->n, a->r.error, b->n, b->r.error, c->n, c->r.error);
}

#if defined(__GNUC__)
__attribute__((format(printf, 2, 3)))
#endif
/// Appends a reason to a failed case's explanation.
static void
fail_case(case_run *cr, const char *format, ...)
{
    size_t used = strlen(cr->why);
    va_list ap;
    va_start(ap, format);
    if (used + 1 < sizeof cr->why)
        vsnprintf(cr->why + used, sizeof cr->why - used, format, ap);
    va_end(ap);
    cr->pass = 0;
}

static void judge(case_run *cr)
{
    const bdl_verify_case *c = cr->c;
    cr->pass = 1;
    cr->why[0] = '\0';
    for (int s = 0; s < c->series_count; ++s) {
        for (int k = 0; k < cr->levels; ++k) {
            const point *p = find_point(cr, s, k);
            if (p && p->status != BDL_OK)
                fail_case(cr, "%s N=%g: the run failed (%s); ", c->series[s], p->n,
                          bdl_result_text(p->status));
        }
        const point *t =
            c->tolerance_level < cr->levels ? find_point(cr, s, c->tolerance_level) : NULL;
        if (t && !(t->r.error <= c->tolerance))
            fail_case(cr, "%s: error %.3g at N=%g above the tolerance %g; ", c->series[s],
                      t->r.error, t->n, c->tolerance);
        double q = cr->levels >= 2 ? order_at(cr, s, cr->levels - 2) : NAN;
        if (c->order_min > 0.0 && !(q >= c->order_min))
            fail_case(cr, "%s: observed order %.2f over the finest pair, below %.2f; ",
                      c->series[s], q, c->order_min);
        double qd = cr->levels >= 3 ? diff_order_at(cr, s, cr->levels - 2) : NAN;
        if (c->diff_order_min > 0.0 && !(qd >= c->diff_order_min))
            fail_case(cr, "%s: order of the differences %.2f, below %.2f; ", c->series[s], qd,
                      c->diff_order_min);
    }
}

static void run_case(case_run *cr, int quick)
{
    const bdl_verify_case *c = cr->c;
    cr->levels = quick ? c->quick_levels : c->level_count;
    cr->count = 0;
    cr->wall = 0.0;
    printf("%s — %s\n", c->name, c->title);
    for (int s = 0; s < c->series_count; ++s)
        for (int k = 0; k < cr->levels && cr->count < MAX_POINTS; ++k) {
            point *p = &cr->p[cr->count++];
            memset(p, 0, sizeof *p);
            p->series = s;
            p->n = c->level[k];
            double t0 = bdl_wall_seconds();
            p->status = c->run(s, p->n, &p->r);
            p->wall = bdl_wall_seconds() - t0;
            cr->wall += p->wall;
            double q = k > 0 ? order_at(cr, s, k - 1) : NAN;
            printf("  %-14s N = %-8g error %-10.3e %8.3f s  %9ld steps", c->series[s], p->n,
                   p->r.error, p->wall, p->r.steps);
            if (isfinite(q))
                printf("  order %5.2f", q);
            printf("%s\n", p->status == BDL_OK ? "" : "  FAILED");
            fflush(stdout);
        }
    judge(cr);
    printf("  %s in %.1f s%s%s\n\n", cr->pass ? "pass" : "FAIL", cr->wall, cr->pass ? "" : ": ",
           cr->why);
}

static bdl_result write_csv(const char *dir, const case_run *cr, int threads)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/%s.csv", dir, cr->c->name);
    bdl_atomic_file af;
    bdl_result r = bdl_atomic_open_csv(
        &af, path, "case,series,N,error,value,reference,wall_seconds,steps,threads,status");
    if (r != BDL_OK)
        return r;
    for (int k = 0; k < cr->count; ++k) {
        const point *p = &cr->p[k];
        fprintf(af.file, "%s,%s,%.10g,%.6e,%.10g,%.10g,%.6f,%ld,%d,%s\n", cr->c->name,
                cr->c->series[p->series], p->n, p->r.error, p->r.value, p->r.exact, p->wall,
                p->r.steps, threads, bdl_result_text(p->status));
    }
    return bdl_atomic_commit(&af);
}

/// `src` as the inside of a gnuplot single-quoted string (a quote doubled).
static const char *gnuplot_text(const char *src, char *dst, size_t size)
{
    size_t k = 0;
    for (; *src && k + 2 < size; ++src) {
        if (*src == '\'')
            dst[k++] = '\'';
        dst[k++] = *src;
    }
    dst[k] = '\0';
    return dst;
}

/// gnuplot script for one case: error against N (left) and against wall time (right). Returns 1
/// when drawn, 0 when gnuplot failed, -1 when no run has a finite error (nothing to draw).
static int plot_case(const char *dir, const case_run *cr)
{
    int finite = 0;
    for (int k = 0; k < cr->count; ++k)
        finite |= cr->p[k].r.error > 0.0 && isfinite(cr->p[k].r.error);
    if (!finite)
        return -1;
    char script[1100], data[1100];
    snprintf(script, sizeof script, "%s/%s.gp", dir, cr->c->name);
    snprintf(data, sizeof data, "%s/%s.dat", dir, cr->c->name);
    FILE *f = fopen(data, "w");
    if (!f)
        return 0;
    // One gnuplot data block per series (blocks separated by two blank lines).
    for (int s = 0; s < cr->c->series_count; ++s) {
        fprintf(f, "# %s\n", cr->c->series[s]);
        for (int k = 0; k < cr->count; ++k) {
            const point *p = &cr->p[k];
            if (p->series == s && p->r.error > 0.0 && isfinite(p->r.error))
                fprintf(f, "%.10g %.6e %.6e\n", p->n, p->r.error, fmax(p->wall, 1e-4));
        }
        fprintf(f, "\n\n");
    }
    fclose(f);
    f = fopen(script, "w");
    if (!f)
        return 0;
    char title[512], param[512], series[256];
    fprintf(f,
            "set terminal pngcairo noenhanced size 1100,420 font 'DejaVu Sans,10'\n"
            "set output '%s/%s.png'\n"
            "set logscale xy\nset grid\nset key top right\nset format y '%%.0e'\n"
            "set multiplot layout 1,2 title '%s: %s'\n"
            "set xlabel '%s'\nset ylabel 'error'\n",
            dir, cr->c->name, cr->c->name, gnuplot_text(cr->c->title, title, sizeof title),
            gnuplot_text(cr->c->param, param, sizeof param));
    fprintf(f, "plot ");
    for (int s = 0; s < cr->c->series_count; ++s)
        fprintf(f, "%s'%s' index %d using 1:2 with linespoints lw 2 pt 7 title '%s'", s ? ", " : "",
                data, s, gnuplot_text(cr->c->series[s], series, sizeof series));
    fprintf(f, "\nset xlabel 'wall time [s]'\nplot ");
    for (int s = 0; s < cr->c->series_count; ++s)
        fprintf(f, "%s'%s' index %d using 3:2 with linespoints lw 2 pt 7 title '%s'", s ? ", " : "",
                data, s, gnuplot_text(cr->c->series[s], series, sizeof series));
    fprintf(f, "\nunset multiplot\n");
    fclose(f);
    char cmd[2400];
    snprintf(cmd, sizeof cmd, "gnuplot '%s' 2>&1", script);
    int ok = system(cmd) == 0;
    remove(script);
    remove(data);
    return ok;
}

static const char readme_intro[] =
    "Every model in bedlam is checked against a known answer — an analytic solution, a "
    "conservation law or published data — at several refinements. Each table below gives, per "
    "method or parameter (a *series*), the error at each refinement N, the wall time that run "
    "took, and the observed order of convergence p = log(e_k/e_k+1)/log(N_k+1/N_k) where the "
    "scheme has one. Where an error tends to a floor set by something the refinement does not "
    "touch (e_inf + c N^-p), the order of the successive differences, "
    "log((e_k-1 - e_k)/(e_k - e_k+1))/log(N_k+1/N_k), shows the order of the part that does "
    "converge. The plots show the same data as error against N and error against run time "
    "(work-precision: lower left is better).\n\n"
    "Wall times include building the case's world; for the one- and two-sphere cases that is "
    "most of it (a few milliseconds: bedlam solves once per species pair for the damping that "
    "realises the configured restitution), so their work-precision lines are nearly vertical.\n\n"
    "How to read them: *how accurate* is the error column at the refinement you would run; *at "
    "what cost* is the wall-time column (one thread, this machine); *where it breaks* is the "
    "last line of each section and [stability.md](stability.md), which tabulates the stiff and "
    "extreme cases and what bedlam does at and beyond each limit.\n\n"
    "This file, the CSV files and the plots are written by `bedlam verify` (all cases) or "
    "`bedlam verify --quick` (the reduced set CI runs); the ctest programs assert the same "
    "measurements with the tolerances listed.\n\n";

/// The summary table: a row per case.
static void write_summary(FILE *f, const case_run *runs, int n)
{
    fprintf(f, "## Summary\n\n| case | reference | tolerance | error at N | observed order "
               "(finest pair) | run time | result |\n|---|---|---|---|---|---|---|\n");
    for (int k = 0; k < n; ++k) {
        const case_run *cr = &runs[k];
        const bdl_verify_case *c = cr->c;
        fprintf(f, "| [%s](#%s) | %s | %g at N = %g | ", c->name, c->name, c->reference,
                c->tolerance, c->level[c->tolerance_level]);
        for (int s = 0; s < c->series_count; ++s) {
            const point *p =
                c->tolerance_level < cr->levels ? find_point(cr, s, c->tolerance_level) : NULL;
            fprintf(f, "%s%s %.2e", s ? "; " : "", c->series[s], p ? p->r.error : NAN);
        }
        fprintf(f, " | ");
        for (int s = 0; s < c->series_count && !c->no_order; ++s) {
            double q = cr->levels >= 2 ? order_at(cr, s, cr->levels - 2) : NAN;
            if (c->diff_order_min > 0.0) // the converging part of an error with a floor
                q = cr->levels >= 3 ? diff_order_at(cr, s, cr->levels - 2) : NAN;
            fprintf(f, "%s%s %.2f", s ? "; " : "", c->series[s], q);
        }
        if (c->no_order)
            fprintf(f, "none applies (see the case)");
        else if (c->diff_order_min > 0.0)
            fprintf(f, " (of the differences)");
        fprintf(f, " | %.1f s | %s |\n", cr->wall, cr->pass ? "pass" : "**FAIL**");
    }
}

/// The table row of one run of a case: error, orders, time.
static void write_point_row(FILE *f, const case_run *cr, int s, int l)
{
    const point *p = find_point(cr, s, l);
    if (!p)
        return;
    double q = l > 0 ? order_at(cr, s, l - 1) : NAN;
    fprintf(f, "| %s | %g | %.3e | ", cr->c->series[s], p->n, p->r.error);
    double qd = diff_order_at(cr, s, l - 1);
    if (isfinite(q))
        fprintf(f, "%.2f", q);
    else
        fprintf(f, "–");
    if (isfinite(qd))
        fprintf(f, " | %.2f", qd);
    else
        fprintf(f, " | –");
    fprintf(f, " | %.3f | %ld |\n", p->wall, p->r.steps);
}

/// The section of one case: what it checks, its acceptance, its runs and its result.
static void write_case(FILE *f, const case_run *cr)
{
    const bdl_verify_case *c = cr->c;
    fprintf(f, "\n## %s\n\n**%s.** Model: %s. Reference: %s. Error: %s. Refinement: %s.\n\n",
            c->name, c->title, c->model, c->reference, c->measure, c->param);
    fprintf(f, "Expected order: %s. Acceptance: error at most %g at N = %g", c->order_note,
            c->tolerance, c->level[c->tolerance_level]);
    if (c->order_min > 0.0)
        fprintf(f, ", observed order over the finest pair at least %.2g", c->order_min);
    if (c->diff_order_min > 0.0)
        fprintf(f, ", order of the successive differences over the finest three at least %.2g",
                c->diff_order_min);
    fprintf(f, ".\n\n| series | N | error | order | order of the differences | wall time [s] | "
               "steps |\n|---|---|---|---|---|---|---|\n");
    for (int s = 0; s < c->series_count; ++s)
        for (int l = 0; l < cr->levels; ++l)
            write_point_row(f, cr, s, l);
    fprintf(f, "\nResult: %s%s%s. Where it breaks: %s\n", cr->pass ? "pass" : "**FAIL**",
            cr->pass ? "" : " — ", cr->why, c->breaks);
    if (cr->plotted)
        fprintf(f, "\n![%s: error against N and against run time](%s.png)\n", c->name, c->name);
}

static bdl_result write_readme(const char *dir, const case_run *runs, int n, int quick, int threads,
                               double total, const char *from)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/README.md", dir);
    bdl_atomic_file af;
    bdl_result r = bdl_atomic_open(&af, path);
    if (r != BDL_OK)
        return r;
    time_t now = time(NULL);
    char date[32];
    strftime(date, sizeof date, "%Y-%m-%d", gmtime(&now));
    fprintf(af.file, "# Verification: error against run time\n\n%s", readme_intro);
    fprintf(af.file,
            "Run: `bedlam verify%s`, bedlam %s, %s, %d thread%s, %.0f s in all (%.1f min)%s.\n\n",
            quick ? " --quick" : "", BDL_VERSION, date, threads, threads == 1 ? "" : "s", total,
            total / 60.0,
            from ? "; the tables and plots drawn again from its CSV files (`--from`)" : "");
    write_summary(af.file, runs, n);
    for (int k = 0; k < n; ++k)
        write_case(af.file, &runs[k]);
    return bdl_atomic_commit(&af);
}

typedef struct verify_opts {
    int quick, threads, plots, list;
    const char *out;
    const char *from; ///< read the runs from this folder's CSV files instead of running them
    const char *names[64];
    int named;
    int help; ///< --help was printed: nothing else to do
} verify_opts;

static const bdl_option verify_options[] = {
    {"--quick", BDL_OPTION_SET, offsetof(verify_opts, quick)},
    {"--no-plots", BDL_OPTION_CLEAR, offsetof(verify_opts, plots)},
    {"--list", BDL_OPTION_SET, offsetof(verify_opts, list)},
    {"--out", BDL_OPTION_TEXT, offsetof(verify_opts, out)},
    {"--from", BDL_OPTION_TEXT, offsetof(verify_opts, from)},
};

/// --threads N (checked), or the name of a case.
static int take_other(void *opts, int argc, char **argv, int i)
{
    verify_opts *o = opts;
    if (strcmp(argv[i], "--threads") == 0 && i + 1 < argc) {
        char *end;
        long t = strtol(argv[i + 1], &end, 10);
        if (*end || t < 1 || t > 256) {
            fprintf(stderr, "error: --threads %s: expected an integer in [1, 256]\n", argv[i + 1]);
            return 0;
        }
        o->threads = (int)t;
        return 2;
    }
    if (argv[i][0] == '-') {
        fprintf(stderr, "error: unknown option '%s'\n\n%s", argv[i], verify_usage);
        return 0;
    }
    if (o->named < 64) {
        if (!bdl_verify_find(argv[i])) {
            fprintf(stderr, "error: unknown case '%s'; bedlam verify --list shows them\n", argv[i]);
            return 0;
        }
        o->names[o->named++] = argv[i];
    }
    return 1;
}

static bdl_result parse_verify(int argc, char **argv, verify_opts *o)
{
    static const bdl_option_parser parser = {verify_options, BDL_OPTION_COUNT(verify_options),
                                             verify_usage, 0, take_other};
    *o = (verify_opts){.threads = 1, .plots = 1, .out = "docs/validation"};
    return bdl_option_parse(&parser, argc, argv, 1, o, &o->help);
}

/// A case runs when it is named, or when none is and it belongs to the set (--quick: the
/// reduced one).
static int wanted(const verify_opts *o, const bdl_verify_case *c)
{
    int want = o->named == 0 ? (!o->quick || c->quick) : 0;
    for (int m = 0; m < o->named; ++m)
        want |= strcmp(o->names[m], c->name) == 0;
    return want;
}

/// Reads a case's runs back from DIR/CASE.csv (as write_csv wrote them); *threads gets theirs.
static bdl_result read_case(const char *dir, case_run *cr, int *threads)
{
    const bdl_verify_case *c = cr->c;
    char path[1024], line[1024];
    snprintf(path, sizeof path, "%s/%s.csv", dir, c->name);
    FILE *f = fopen(path, "r");
    if (!f)
        return BDL_ERR_IO;
    cr->count = cr->levels = 0;
    cr->wall = 0.0;
    while (fgets(line, sizeof line, f) && cr->count < MAX_POINTS) {
        // case, then the series (which may hold commas: write_csv does not quote), then eight
        // fields: taken from both ends.
        line[strcspn(line, "\n")] = '\0';
        char *field[10], *comma = strchr(line, ',');
        if (!comma || strncmp(line, c->name, (size_t)(comma - line)) != 0 ||
            strlen(c->name) != (size_t)(comma - line))
            continue; // the header, or not this case's
        field[1] = comma + 1;
        int nf = 10;
        while (nf > 2) {
            char *last = strrchr(field[1], ',');
            if (!last)
                break;
            *last = '\0';
            field[--nf] = last + 1;
        }
        if (nf != 2)
            continue;
        point *p = &cr->p[cr->count];
        memset(p, 0, sizeof *p);
        p->series = -1;
        for (int s = 0; s < c->series_count; ++s)
            p->series = strcmp(field[1], c->series[s]) == 0 ? s : p->series;
        p->n = strtod(field[2], NULL);
        p->r.error = strtod(field[3], NULL);
        p->r.value = strtod(field[4], NULL);
        p->r.exact = strtod(field[5], NULL);
        p->wall = strtod(field[6], NULL);
        p->r.steps = strtol(field[7], NULL, 10);
        *threads = (int)strtol(field[8], NULL, 10);
        p->status = BDL_ERR_UNSTABLE;
        for (int k = 0; k < BDL_RESULT_COUNT; ++k)
            p->status =
                strcmp(field[9], bdl_result_text((bdl_result)k)) == 0 ? (bdl_result)k : p->status;
        for (int k = 0; k < c->level_count; ++k)
            cr->levels = c->level[k] == p->n && k + 1 > cr->levels ? k + 1 : cr->levels;
        if (p->series < 0)
            continue;
        cr->wall += p->wall;
        cr->count++;
    }
    fclose(f);
    if (cr->count == 0)
        return BDL_ERR_IO;
    judge(cr);
    printf("%s — %s: %d runs read, %s\n", c->name, c->title, cr->count, cr->pass ? "pass" : "FAIL");
    return BDL_OK;
}

/// Runs the cases asked for into runs[] (*n of them), each written to its CSV as it ends.
static bdl_result run_cases(const verify_opts *o, const bdl_verify_case *cases, int count,
                            case_run *runs, int *n, int *failed, int *threads)
{
    *n = *failed = 0;
    *threads = o->threads;
    for (int k = 0; k < count; ++k) {
        if (!wanted(o, &cases[k]))
            continue;
        case_run *cr = &runs[(*n)++];
        cr->c = &cases[k];
        if (o->from) {
            if (read_case(o->from, cr, threads) != BDL_OK) {
                fprintf(stderr, "error: --from %s: no runs of %s in %s/%s.csv\n", o->from,
                        cr->c->name, o->from, cr->c->name);
                return BDL_ERR_ARGS;
            }
        } else {
            run_case(cr, o->quick && cases[k].quick_levels > 0);
        }
        *failed += !cr->pass;
        if (write_csv(o->out, cr, *threads) != BDL_OK) {
            fprintf(stderr, "error: cannot write %s/%s.csv: %s\n", o->out, cr->c->name,
                    strerror(errno));
            return BDL_ERR_IO;
        }
    }
    return BDL_OK;
}

/// The plots of the cases (not of one without a finite error); none after the first gnuplot
/// fails.
static void plot_cases(const char *out, case_run *runs, int n)
{
    for (int k = 0; k < n; ++k) {
        const int drawn = plot_case(out, &runs[k]);
        if (drawn == 0) {
            fprintf(stderr, "warning: gnuplot failed or is missing: no more plots written\n");
            return;
        }
        runs[k].plotted = drawn > 0;
    }
}

bdl_result bdl_cmd_verify(int argc, char **argv)
{
    verify_opts o;
    bdl_result r = parse_verify(argc, argv, &o);
    if (r != BDL_OK || o.help)
        return r;
    int count;
    const bdl_verify_case *cases = bdl_verify_cases(&count);
    if (o.list) {
        for (int k = 0; k < count; ++k)
            printf("%-18s %s%s\n", cases[k].name, cases[k].title,
                   cases[k].quick ? "" : " (full set only)");
        return BDL_OK;
    }
    char why[512];
    if (bdl_check_writable_dir(o.out, why, sizeof why) != BDL_OK) {
        fprintf(stderr, "error: --out %s: %s\n", o.out, why);
        return BDL_ERR_OUTPUT_DIR;
    }
    omp_set_num_threads(o.threads);
    case_run *runs = calloc((size_t)count, sizeof *runs);
    if (!runs)
        return BDL_ERR_NOMEM;
    int n, failed;
    double t0 = bdl_wall_seconds();
    int threads;
    r = run_cases(&o, cases, count, runs, &n, &failed, &threads);
    double total = bdl_wall_seconds() - t0;
    if (o.from) { // the runs' own time, less what lay between them
        total = 0.0;
        for (int k = 0; k < n; ++k)
            total += runs[k].wall;
    }
    if (r == BDL_OK && o.plots)
        plot_cases(o.out, runs, n);
    if (r == BDL_OK && write_readme(o.out, runs, n, o.quick, threads, total, o.from) != BDL_OK) {
        fprintf(stderr, "error: cannot write %s/README.md: %s\n", o.out, strerror(errno));
        r = BDL_ERR_IO;
    }
    if (r == BDL_OK)
        printf("%d case%s, %d failed, %.1f s; tables in %s/README.md\n", n, n == 1 ? "" : "s",
               failed, total, o.out);
    free(runs);
    return r != BDL_OK ? r : failed ? BDL_ERR_TOLERANCE : BDL_OK;
}
