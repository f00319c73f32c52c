// bedlam analyze spectrum, mean and profile — a column of a run's time series: its power
// spectrum, its time average with a standard error, and the time-averaged solids fraction of
// each gas cell layer (analysis/signal.h, analysis/series.h).
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/series.h"
#include "analysis/signal.h"
#include "app/analyze.h"
#include "app/analyze_files.h"
#include "core/file.h"

/// The spectrum of a column between two times: its bins and the peak in the band asked for.
typedef struct spectrum {
    double *freq, *power;
    long bins;
    double peak;   ///< dominant frequency [Hz]
    double t0, t1; ///< times of the first and last sample [s]
} spectrum;

static bdl_result write_spectrum(const bdl_analyze_opts *o, const spectrum *s)
{
    char path[1300];
    snprintf(path, sizeof path, "%s/spectrum_%s.csv", o->out, o->column);
    bdl_atomic_file af;
    if (bdl_atomic_open_csv(&af, path, "frequency,power") != BDL_OK)
        return BDL_ERR_OUTPUT_DIR;
    for (long k = 0; k < s->bins; ++k)
        fprintf(af.file, "%.6g,%.6g\n", s->freq[k], s->power[k]);
    fprintf(af.file, "# %s, %.6g to %.6g s, dominant %.6g Hz\n", o->column, s->t0, s->t1, s->peak);
    return bdl_atomic_commit(&af);
}

static void plot_spectrum(const bdl_analyze_opts *o, const spectrum *s)
{
    char path[1300], pieces[64] = "";
    if (o->segments > 1)
        snprintf(pieces, sizeof pieces, " (Welch, %d pieces)", o->segments);
    snprintf(path, sizeof path, "%s/spectrum_%s.gp", o->out, o->column);
    bdl_analyze_plot(
        path,
        "set terminal pngcairo size 900,500 font 'DejaVu Sans,11'\n"
        "set output '%s/spectrum_%s.png'\nset datafile separator ','\n"
        "set xlabel 'frequency [Hz]'\nset ylabel 'power (|FFT|^2, Hamming window)'\n"
        "set xrange [0:%g]\nset grid\nset key top right\n"
        "set arrow from %g, graph 0 to %g, graph 1 nohead dt 2 lc rgb '#c03030'\n"
        "plot '%s/spectrum_%s.csv' every ::1 using 1:2 with lines lw 2 lc rgb '#3060c0' "
        "title '%s, %.1f-%.1f s%s; peak %.2f Hz' noenhanced\n",
        o->out, o->column, o->fmax, s->peak, s->peak, o->out, o->column, o->column, s->t0, s->t1,
        pieces, s->peak);
}

/// The dominant frequency of each of Welch's pieces: their mean, standard error and range.
static void print_pieces(const double *peaks, int n, double span)
{
    double sum = 0.0, sum2 = 0.0, lo = INFINITY, hi = -INFINITY;
    for (int k = 0; k < n; ++k) {
        sum += peaks[k], sum2 += peaks[k] * peaks[k];
        lo = fmin(lo, peaks[k]), hi = fmax(hi, peaks[k]);
    }
    const double mean = sum / n, var = fmax(sum2 / n - mean * mean, 0.0) * n / (n - 1);
    printf("Welch's average over %d half-overlapping pieces of %.3g s; the pieces' dominant "
           "frequencies: mean %.3f Hz, standard error %.3f Hz (pieces overlap: not independent), "
           "range %.3f to %.3f Hz\n",
           n, 2.0 * span / (n + 1), mean, sqrt(var / n), lo, hi);
}

bdl_result bdl_analyze_spectrum(const bdl_analyze_opts *o)
{
    double *t = NULL, *x = NULL;
    long n = 0;
    if (!bdl_analyze_read_series(o->run, o->file, o->column, &t, &x, &n))
        return BDL_ERR_ARGS;
    const bdl_time_window w = bdl_time_window_of(t, n, o->from, o->to);
    if (w.count < 16) {
        fprintf(stderr, "error: only %ld samples between %g and %g s\n", w.count, o->from, o->to);
        free(t), free(x);
        return BDL_ERR_NO_RESULT;
    }
    spectrum s = {.t0 = t[w.first], .t1 = t[w.first + w.count - 1]};
    double *peaks = calloc((size_t)o->segments, sizeof(double));
    bdl_result rc = peaks ? bdl_welch_spectrum(x + w.first, w.count, w.dt, o->segments, o->fmin,
                                               o->fmax, peaks, &s.freq, &s.power, &s.bins)
                          : BDL_ERR_NOMEM;
    free(t), free(x);
    if (rc == BDL_ERR_ARGS && o->segments > 1) {
        fprintf(stderr, "error: %ld samples make pieces too short for %d segments\n", w.count,
                o->segments);
        free(peaks);
        return BDL_ERR_NO_RESULT;
    }
    if (rc == BDL_ERR_NOMEM) { // otherwise equal times: no bins, no peak, no result
        fprintf(stderr, "error: %s\n", bdl_result_text(rc));
        free(peaks);
        return rc;
    }
    s.peak = bdl_dominant_frequency(s.freq, s.power, s.bins, o->fmin, o->fmax);
    printf("%s from %.3f to %.3f s: %ld samples %.4g s apart (Nyquist %.3g Hz, resolution %.3g "
           "Hz); dominant frequency in [%g, %g] Hz: %.3f Hz\n",
           o->column, s.t0, s.t1, w.count, w.dt, 0.5 / w.dt, s.bins > 1 ? s.freq[1] : NAN, o->fmin,
           o->fmax, s.peak);
    if (o->segments > 1 && rc == BDL_OK)
        print_pieces(peaks, o->segments, s.t1 - s.t0);
    free(peaks);
    rc = write_spectrum(o, &s);
    if (rc == BDL_OK && o->plots)
        plot_spectrum(o, &s);
    free(s.freq), free(s.power);
    return rc != BDL_OK ? rc : isfinite(s.peak) ? BDL_OK : BDL_ERR_NO_RESULT;
}

bdl_result bdl_analyze_mean(const bdl_analyze_opts *o)
{
    double *t = NULL, *x = NULL;
    long n = 0;
    if (!bdl_analyze_read_series(o->run, o->file, o->column, &t, &x, &n))
        return BDL_ERR_ARGS;
    const bdl_block_mean m = bdl_block_mean_in(t, x, n, o->from, o->to, 10);
    const bdl_sample_stats *s = &m.samples;
    if (s->count < 20) {
        fprintf(stderr, "error: only %ld samples of %s between %g and %g s\n", s->count, o->column,
                o->from, o->to);
        free(t), free(x);
        return BDL_ERR_NO_RESULT;
    }
    printf("%s from %.4g to %.4g s (%ld samples): mean %.6g, standard deviation %.4g, standard "
           "error %.3g (10 blocks), range %.6g to %.6g\n",
           o->column, t[s->first], t[s->last], s->count, s->mean, s->sd, m.standard_error, s->min,
           s->max);
    free(t), free(x);
    return BDL_OK;
}

/// The solids phases of a multi-fluid run's profile.csv: the NAMEs of its phase_NAME_at_H
/// columns, in order (at most BDL_PROFILE_PHASES); returns their count.
#define BDL_PROFILE_PHASES 4
static int profile_phases(const char *header, char names[][64])
{
    int count = 0;
    for (const char *at = strstr(header, "phase_"); at && count < BDL_PROFILE_PHASES;
         at = strstr(at + 1, "phase_")) {
        const char *end = strstr(at, "_at_");
        const size_t len = end ? (size_t)(end - at - 6) : 0;
        if (!end || len == 0 || len >= 64 || (at != header && at[-1] != ','))
            continue;
        char name[64];
        memcpy(name, at + 6, len);
        name[len] = '\0';
        int seen = 0;
        for (int k = 0; k < count; ++k)
            seen |= strcmp(names[k], name) == 0;
        if (!seen)
            snprintf(names[count++], 64, "%s", name);
    }
    return count;
}

/// The table's rows: one per phi_at_HEIGHT column of RUN/profile.csv (named in `header`), its
/// samples in the time window averaged, and each phase's phase_NAME_at_HEIGHT so averaged.
/// *used: the samples of the last column read (0: none).
static void profile_rows(const bdl_analyze_opts *o, char *header, const double *t, long n,
                         FILE *table, long *used, double *peak, double *peak_h)
{
    char phases[BDL_PROFILE_PHASES][64];
    const int count = profile_phases(header, phases);
    *used = 0, *peak = 0.0, *peak_h = 0.0;
    for (char *tok = strtok(header, ",\r\n"); tok; tok = strtok(NULL, ",\r\n")) {
        if (strncmp(tok, "phi_at_", 7) != 0)
            continue;
        double *x = NULL;
        long m = 0;
        if (!bdl_analyze_read_column(o->run, "profile.csv", tok, &x, &m) || m != n) {
            free(x);
            continue;
        }
        const bdl_sample_stats s = bdl_sample_stats_in(t, x, n, o->from, o->to);
        free(x);
        *used = s.count;
        if (s.count == 0)
            continue;
        const double h = atof(tok + 7);
        fprintf(table, "%.6g,%.6g,%.6g", h, s.mean, s.sd);
        for (int k = 0; k < count; ++k) {
            char column[160];
            snprintf(column, sizeof column, "phase_%s_at_%s", phases[k], tok + 7);
            double *y = NULL;
            long q = 0;
            const int ok = bdl_analyze_read_column(o->run, "profile.csv", column, &y, &q) && q == n;
            fprintf(table, ",%.6g", ok ? bdl_sample_stats_in(t, y, n, o->from, o->to).mean : NAN);
            free(y);
        }
        fprintf(table, "\n");
        if (s.mean > *peak)
            *peak = s.mean, *peak_h = h;
    }
}

static void plot_profile(const char *out, char phases[][64], int count)
{
    char path[1300], extra[1024] = "";
    size_t at = 0;
    for (int k = 0; k < count && at < sizeof extra; ++k)
        at += (size_t)snprintf(extra + at, sizeof extra - at,
                               ", '%s/profile.csv' every ::1 using %d:1 with lines lw 2 title "
                               "'phase %s'",
                               out, 4 + k, phases[k]);
    snprintf(path, sizeof path, "%s/profile.gp", out);
    bdl_analyze_plot(path,
                     "set terminal pngcairo size 600,700 font 'DejaVu Sans,11'\n"
                     "set output '%s/profile.png'\nset datafile separator ','\n"
                     "set xlabel 'solids fraction (layer mean)'\nset ylabel 'height [m]'\n"
                     "set grid\nset key top right noenhanced\nset xrange [0:*]\n"
                     "plot '%s/profile.csv' every ::1 using 2:1:($2-$3):($2+$3) with xerrorlines "
                     "pt 7 lc rgb '#3060c0' title 'time average +- standard deviation'%s\n",
                     out, out, extra);
}

/// The header line of RUN/profile.csv (its columns name the layers' heights).
static int read_profile_header(const char *run, char *header, int len)
{
    char path[1300];
    snprintf(path, sizeof path, "%s/profile.csv", run);
    char why[256];
    FILE *f = bdl_open_regular(path, why, sizeof why);
    const int ok = f && fgets(header, len, f);
    if (f)
        fclose(f);
    if (!ok)
        fprintf(stderr, "error: cannot read %s (written by runs with a gas)\n", path);
    return ok;
}

bdl_result bdl_analyze_profile(const bdl_analyze_opts *o)
{
    char header[65536];
    double *t = NULL;
    long n = 0;
    if (!read_profile_header(o->run, header, sizeof header) ||
        !bdl_analyze_read_column(o->run, "profile.csv", "time", &t, &n))
        return BDL_ERR_ARGS;
    char path[1300];
    snprintf(path, sizeof path, "%s/profile.csv", o->out);
    bdl_atomic_file af;
    if (bdl_atomic_open(&af, path) != BDL_OK) {
        fprintf(stderr, "error: cannot write %s\n", path);
        free(t);
        return BDL_ERR_OUTPUT_DIR;
    }
    char phases[BDL_PROFILE_PHASES][64];
    const int count = profile_phases(header, phases);
    fprintf(af.file, "height,solids_fraction,std");
    for (int k = 0; k < count; ++k)
        fprintf(af.file, ",%s", phases[k]);
    fprintf(af.file, "\n");
    long used;
    double peak, peak_h;
    profile_rows(o, header, t, n, af.file, &used, &peak, &peak_h);
    free(t);
    if (used == 0) {
        bdl_atomic_abort(&af);
        fprintf(stderr, "error: no rows of %s/profile.csv between %g and %g s\n", o->run, o->from,
                o->to);
        return BDL_ERR_NO_RESULT;
    }
    if (bdl_atomic_commit(&af) != BDL_OK)
        return BDL_ERR_OUTPUT_DIR;
    char names[BDL_PROFILE_PHASES * 66] = "";
    for (int k = 0; k < count; ++k)
        snprintf(names + strlen(names), sizeof names - strlen(names), "%s%s", k ? ", " : "",
                 phases[k]);
    printf("solids fraction against height%s%s%s, averaged over %ld rows: largest %.4f at %.4g m; "
           "table in %s\n",
           count ? " (and each phase's: " : "", names, count ? ")" : "", used, peak, peak_h, path);
    if (o->plots)
        plot_profile(o->out, phases, count);
    return BDL_OK;
}
