// bedlam analyze phase — a column of a vibrated run folded over the vibration cycle
// (analysis/phase.h): phase_NAME.csv, the extremes and the intervals below a threshold, and
// phase_NAME.png with the column against the cycle count beside it.
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "analysis/phase.h"
#include "app/analyze.h"
#include "app/analyze_files.h"
#include "core/file.h"

static bdl_result write_phase(const bdl_analyze_opts *o, const bdl_phase_fold *f)
{
    char path[1300];
    snprintf(path, sizeof path, "%s/phase_%s.csv", o->out, o->column);
    bdl_atomic_file af;
    if (bdl_atomic_open_csv(&af, path, "phase,mean,min,max,samples") != BDL_OK)
        return BDL_ERR_OUTPUT_DIR;
    for (int b = 0; b < f->bins; ++b)
        fprintf(af.file, "%.6g,%.8g,%.8g,%.8g,%ld\n", (b + 0.5) / f->bins, f->mean[b], f->min[b],
                f->max[b], f->count[b]);
    return bdl_atomic_commit(&af);
}

static void print_phase(const bdl_analyze_opts *o, const bdl_phase_fold *f)
{
    const bdl_phase_extremes e = bdl_phase_fold_extremes(f);
    const int bins = f->bins;
    printf("%s over cycles %ld to %ld (%ld samples, %d phase bins): largest mean %.6g at phase "
           "%.3f, smallest %.6g at phase %.3f\n",
           o->column, f->first_cycle, f->last_cycle, f->used, bins, e.largest,
           (e.at_largest + 0.5) / bins, e.smallest, (e.at_smallest + 0.5) / bins);
    if (!isfinite(o->below))
        return;
    int *start = malloc((size_t)(bins / 2 + 1) * sizeof(int));
    int *end = malloc((size_t)(bins / 2 + 1) * sizeof(int));
    const int runs = start && end ? bdl_phase_runs_below(f, o->below, start, end, bins / 2 + 1) : 0;
    for (int k = 0; k < runs; ++k)
        printf("%s below %g from phase %.3f to %.3f\n", o->column, o->below,
               (double)start[k] / bins, (double)end[k] / bins);
    free(start), free(end);
}

static void plot_phase(const bdl_analyze_opts *o, const bdl_phase_fold *f)
{
    char path[1300];
    snprintf(path, sizeof path, "%s/phase_%s.gp", o->out, o->column);
    bdl_analyze_plot(path,
                     "set terminal pngcairo size 900,520 font 'DejaVu Sans,11'\n"
                     "set output '%s/phase_%s.png'\nset datafile separator ','\n"
                     "set multiplot layout 1,2\n"
                     "set xlabel 'phase of the vibration cycle'\nset ylabel '%s' noenhanced\n"
                     "set grid\nset key top left\nset xrange [0:1]\n"
                     "plot '%s/phase_%s.csv' every ::1 using 1:3:4 with filledcurves lc rgb "
                     "'#c8d4ec' title 'range', '' every ::1 using 1:2 with lines lw 2 lc rgb "
                     "'#3060c0' title 'mean over cycles %ld-%ld'\n"
                     "set xlabel 'cycles since the shaking started'\nset xrange [0:*]\n"
                     "plot '%s/%s' every ::1 using (($1-%.9g)/%.9g):(column('%s')) with lines "
                     "lc rgb '#c03030' title '%s' noenhanced\n"
                     "unset multiplot\n",
                     o->out, o->column, o->column, o->out, o->column, f->first_cycle, f->last_cycle,
                     o->run, o->file, o->start, o->period, o->column, o->column);
}

bdl_result bdl_analyze_phase(const bdl_analyze_opts *o)
{
    double *t = NULL, *x = NULL;
    long n = 0;
    if (!bdl_analyze_read_series(o->run, o->file, o->column, &t, &x, &n))
        return BDL_ERR_ARGS;
    const bdl_phase_def def = {o->period, o->start, o->from_cycle, o->to_cycle, o->bins};
    bdl_phase_fold f;
    bdl_result rc = bdl_phase_fold_of(t, x, n, &def, &f);
    free(t), free(x);
    if (rc != BDL_OK) {
        fprintf(stderr, "error: %s\n", bdl_result_text(rc));
        return rc;
    }
    if (f.used < 2 * f.bins) {
        fprintf(stderr, "error: only %ld samples of %s in the cycles asked for (%d bins)\n", f.used,
                o->column, f.bins);
        bdl_phase_fold_free(&f);
        return BDL_ERR_NO_RESULT;
    }
    rc = write_phase(o, &f);
    print_phase(o, &f);
    if (rc == BDL_OK && o->plots)
        plot_phase(o, &f);
    bdl_phase_fold_free(&f);
    return rc;
}
