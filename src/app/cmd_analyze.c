// bedlam analyze — analyses of a finished run from its diagnostics.csv: a pressure-drop sweep
// (U_mf, the fluidized pressure drop against the bed's weight) and the spectrum of a column.
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/signal.h"
#include "analysis/umf.h"
#include "app/analyze.h"
#include "app/app.h"
#include "core/file.h"
#include "io/csv.h"

static const char analyze_usage[] =
    "usage: bedlam analyze sweep RUN [--out DIR] [--no-plots]\n"
    "       bedlam analyze spectrum RUN [--column NAME] [--from T] [--to T] [--fmin F] [--fmax F]\n"
    "                               [--out DIR] [--no-plots]\n"
    "       bedlam analyze mean RUN --column NAME [--from T] [--to T]\n"
    "       bedlam analyze phase RUN --column NAME --period P [--start T] [--from-cycle A]\n"
    "                            [--to-cycle B] [--bins N] [--below X] [--out DIR] [--no-plots]\n"
    "       bedlam analyze profile RUN [--from T] [--to T] [--out DIR] [--no-plots]\n"
    "       bedlam analyze networks CONTACTS.csv [--bins N] [--fmax F] [--out DIR] [--no-plots]\n"
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
    "and --fmax (default 0.2 and 20 Hz). Writes spectrum.csv and spectrum.png.\n"
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
    "profile: the solids fraction of each gas cell layer (RUN/profile.csv, runs with a gas)\n"
    "averaged between --from and --to: the solids fraction against height. Writes profile.csv\n"
    "and profile.png.\n"
    "\n"
    "networks: a contact file of a run ([output] contacts_interval): the force networks\n"
    "(connected sets of particles touching with a normal force: their number, the largest one's\n"
    "particles, contacts, mean coordination and length), those of the forces above the mean, and\n"
    "the distribution of f = F_n/<F_n> in N bins (default 40) up to F (default 5), fitted with\n"
    "P(f) = a (1 - b exp(-f^2)) exp(-beta f). Writes force_pdf.csv and force_pdf.png.\n"
    "\n"
    "--out DIR: where the files go (default RUN/analysis, or the contact file's folder). Exit "
    "codes: 0 done, 1 the analysis\n"
    "found nothing (no sweep, too few samples), 2 bad options or unreadable input.\n";

typedef struct series {
    long n;
    double *t, *x;
} series;

int bdl_analyze_read_column(const char *run, const char *file, const char *column, double **out,
                            long *n)
{
    char path[1200];
    snprintf(path, sizeof path, "%s/%s", run, file);
    *out = NULL;
    long rows = bdl_csv_read_column(path, column, NULL, 0); // count, then read
    *out = rows > 0 ? malloc((size_t)rows * sizeof(double)) : NULL;
    *n = *out ? bdl_csv_read_column(path, column, *out, rows) : -1;
    if (*n <= 0) {
        fprintf(stderr, "error: %s: no column '%s' (or no rows)\n", path, column);
        free(*out);
        *out = NULL;
        return 0;
    }
    return 1;
}

static int read_column(const char *run, const char *column, double **out, long *n)
{
    return bdl_analyze_read_column(run, "diagnostics.csv", column, out, n);
}

void bdl_analyze_gnuplot(const char *script_path)
{
    char cmd[1300];
    snprintf(cmd, sizeof cmd, "gnuplot '%s' 2>&1", script_path);
    if (system(cmd) != 0)
        fprintf(stderr, "warning: gnuplot failed or is missing: no plot\n");
    remove(script_path);
}

typedef struct stage {
    double u, dp, dp_std, ratio;
    int branch; ///< +1 increasing, -1 decreasing
} stage;

static bdl_result analyze_sweep(const char *run, const char *out, int plots)
{
    double *t = NULL, *u = NULL, *dp = NULL, *wr = NULL;
    long n = 0, m;
    int ok = read_column(run, "time", &t, &n) && read_column(run, "inlet_velocity", &u, &m) &&
             m == n && read_column(run, "pressure_drop", &dp, &m) && m == n &&
             read_column(run, "weight_ratio", &wr, &m) && m == n;
    stage *st = ok ? calloc((size_t)n, sizeof(stage)) : NULL;
    int ns = 0;
    // Stages: runs of rows with the same inlet velocity; averages over the second half in time.
    for (long i = 0; st && i < n;) {
        long j = i;
        while (j < n && fabs(u[j] - u[i]) < 1e-9)
            ++j;
        double mid = 0.5 * (t[i] + t[j - 1]), s = 0, s2 = 0, r = 0;
        long c = 0;
        for (long k = i; k < j; ++k)
            if (t[k] >= mid) {
                s += dp[k], s2 += dp[k] * dp[k], r += wr[k], ++c;
            }
        if (c > 0 && u[i] > 0.0) {
            stage *g = &st[ns++];
            g->u = u[i];
            g->dp = s / c;
            g->dp_std = sqrt(fmax(0.0, s2 / c - g->dp * g->dp));
            g->ratio = r / c;
        }
        i = j;
    }
    for (int k = 0; k < ns; ++k) { // the branch: the direction the velocity moved to get here
        double prev = k > 0 ? st[k - 1].u : NAN, next = k + 1 < ns ? st[k + 1].u : NAN;
        st[k].branch = k > 0 ? (st[k].u > prev ? 1 : -1) : (next > st[k].u ? 1 : -1);
    }
    if (!ok || ns < 4) {
        fprintf(stderr,
                "error: %s: no sweep in diagnostics.csv (%d stages of the inlet velocity); "
                "set [gas] sweep\n",
                run, ns);
        free(t), free(u), free(dp), free(wr), free(st);
        return ok ? BDL_ERR_NO_RESULT : BDL_ERR_ARGS;
    }
    bdl_umf_result res[2];
    double plateau_ratio[2] = {NAN, NAN};
    for (int b = 0; b < 2; ++b) { // 0 increasing, 1 decreasing
        double bu[4096], bdp[4096], br[4096];
        int c = 0;
        for (int k = 0; k < ns && c < 4096; ++k)
            if (st[k].branch == (b == 0 ? 1 : -1)) {
                bu[c] = st[k].u, bdp[c] = st[k].dp, br[c] = st[k].ratio;
                ++c;
            }
        res[b] = bdl_umf_from_sweep(bu, bdp, c);
        double sum = 0.0;
        int cnt = 0;
        for (int k = 0; k < c; ++k)
            if (isfinite(res[b].umf) && bu[k] > res[b].umf) { // the plateau's stages
                sum += br[k];
                ++cnt;
            }
        plateau_ratio[b] = cnt ? sum / cnt : NAN;
        printf("%s branch: %d stages, U_mf %.4f m/s (packed fit a %.4g, b %.4g on %d points), "
               "plateau %.2f Pa over %d points = %.4f of the bed's weight per area\n",
               b ? "decreasing" : "increasing", c, res[b].umf, res[b].a, res[b].b, res[b].packed,
               res[b].plateau, res[b].fluidized, plateau_ratio[b]);
    }
    char path[1300];
    snprintf(path, sizeof path, "%s/sweep.csv", out);
    bdl_atomic_file af;
    if (bdl_atomic_open(&af, path) != BDL_OK) {
        fprintf(stderr, "error: cannot write %s\n", path);
        free(t), free(u), free(dp), free(wr), free(st);
        return BDL_ERR_OUTPUT_DIR;
    }
    fprintf(af.file, "stage,inlet_velocity,branch,pressure_drop,pressure_drop_std,weight_ratio\n");
    for (int k = 0; k < ns; ++k)
        fprintf(af.file, "%d,%.6g,%s,%.6g,%.6g,%.6g\n", k, st[k].u,
                st[k].branch > 0 ? "increasing" : "decreasing", st[k].dp, st[k].dp_std,
                st[k].ratio);
    fprintf(af.file, "# U_mf increasing %.6g m/s, decreasing %.6g m/s; plateau %.6g / %.6g Pa\n",
            res[0].umf, res[1].umf, res[0].plateau, res[1].plateau);
    bdl_atomic_commit(&af);
    if (plots) {
        snprintf(path, sizeof path, "%s/sweep.gp", out);
        FILE *f = fopen(path, "w");
        if (f) {
            const bdl_umf_result *d = &res[1];
            fprintf(
                f,
                "set terminal pngcairo size 900,600 font 'DejaVu Sans,11'\n"
                "set output '%s/sweep.png'\nset datafile separator ','\n"
                "set xlabel 'superficial gas velocity U_0 [m/s]'\n"
                "set ylabel 'pressure drop over the bed [Pa]'\nset key bottom right\n"
                "set grid\nset yrange [0:*]\n"
                "a = %.9g; b = %.9g; P = %.9g; umf = %.9g\n"
                "set arrow from umf, graph 0 to umf, graph 1 nohead dt 2 lc rgb '#808080'\n"
                "plot '%s/sweep.csv' using (strcol(3) eq 'increasing' ? $2 : 1/0):4:5 every "
                "::1 with yerrorlines pt 7 lc rgb '#c03030' title 'increasing', \\\n"
                "     '%s/sweep.csv' using (strcol(3) eq 'decreasing' ? $2 : 1/0):4:5 every "
                "::1 with yerrorlines pt 5 lc rgb '#3060c0' title 'decreasing', \\\n"
                "     (x <= umf ? a*x + b*x*x : 1/0) lw 2 lc rgb '#3060c0' dt 3 title "
                "'packed branch a U + b U^2', \\\n"
                "     P lw 1 lc rgb '#404040' dt 2 title sprintf('plateau; U_{mf} = %%.3f m/s', "
                "umf)\n",
                out, d->a, d->b, d->plateau, d->umf, out, out);
            fclose(f);
            bdl_analyze_gnuplot(path);
        }
    }
    free(t), free(u), free(dp), free(wr), free(st);
    return isfinite(res[1].umf) ? BDL_OK : BDL_ERR_NO_RESULT;
}

static bdl_result analyze_spectrum(const char *run, const char *file, const char *out,
                                   const char *column, double from, double to, double fmin,
                                   double fmax, int plots)
{
    double *t = NULL, *x = NULL;
    long n = 0, m = 0;
    if (!bdl_analyze_read_column(run, file, "time", &t, &n) ||
        !bdl_analyze_read_column(run, file, column, &x, &m) || m != n) {
        free(t), free(x);
        return BDL_ERR_ARGS;
    }
    long i0 = 0, i1 = n;
    while (i0 < n && t[i0] < from)
        ++i0;
    while (i1 > i0 && t[i1 - 1] > to)
        --i1;
    long count = i1 - i0;
    if (count < 16) {
        fprintf(stderr, "error: only %ld samples between %g and %g s\n", count, from, to);
        free(t), free(x);
        return BDL_ERR_NO_RESULT;
    }
    const double dt = (t[i1 - 1] - t[i0]) / (double)(count - 1);
    double *f = NULL, *p = NULL;
    long bins = 0;
    bdl_power_spectrum(x + i0, count, dt, &f, &p, &bins);
    double peak = bdl_dominant_frequency(f, p, bins, fmin, fmax);
    printf("%s from %.3f to %.3f s: %ld samples %.4g s apart (Nyquist %.3g Hz, resolution %.3g "
           "Hz); dominant frequency in [%g, %g] Hz: %.3f Hz\n",
           column, t[i0], t[i1 - 1], count, dt, 0.5 / dt, bins > 1 ? f[1] : NAN, fmin, fmax, peak);
    char path[1300];
    snprintf(path, sizeof path, "%s/spectrum.csv", out);
    bdl_atomic_file af;
    bdl_result rc = BDL_OK;
    if (bdl_atomic_open(&af, path) == BDL_OK) {
        fprintf(af.file, "frequency,power\n");
        for (long k = 0; k < bins; ++k)
            fprintf(af.file, "%.6g,%.6g\n", f[k], p[k]);
        fprintf(af.file, "# %s, %.6g to %.6g s, dominant %.6g Hz\n", column, t[i0], t[i1 - 1],
                peak);
        rc = bdl_atomic_commit(&af);
    } else {
        rc = BDL_ERR_OUTPUT_DIR;
    }
    if (rc == BDL_OK && plots) {
        snprintf(path, sizeof path, "%s/spectrum.gp", out);
        FILE *g = fopen(path, "w");
        if (g) {
            fprintf(g,
                    "set terminal pngcairo size 900,500 font 'DejaVu Sans,11'\n"
                    "set output '%s/spectrum.png'\nset datafile separator ','\n"
                    "set xlabel 'frequency [Hz]'\nset ylabel 'power (|FFT|^2, Hamming window)'\n"
                    "set xrange [0:%g]\nset grid\nset key top right\n"
                    "set arrow from %g, graph 0 to %g, graph 1 nohead dt 2 lc rgb '#c03030'\n"
                    "plot '%s/spectrum.csv' every ::1 using 1:2 with lines lw 2 lc rgb '#3060c0' "
                    "title '%s, %.1f-%.1f s; peak %.2f Hz' noenhanced\n",
                    out, fmax, peak, peak, out, column, t[i0], t[i1 - 1], peak);
            fclose(g);
            bdl_analyze_gnuplot(path);
        }
    }
    free(t), free(x), free(f), free(p);
    return rc != BDL_OK ? rc : isfinite(peak) ? BDL_OK : BDL_ERR_NO_RESULT;
}

static bdl_result analyze_mean(const char *run, const char *file, const char *column, double from,
                               double to)
{
    double *t = NULL, *x = NULL;
    long n = 0, m = 0;
    if (!bdl_analyze_read_column(run, file, "time", &t, &n) ||
        !bdl_analyze_read_column(run, file, column, &x, &m) || m != n) {
        free(t), free(x);
        return BDL_ERR_ARGS;
    }
    double sum = 0.0, sum2 = 0.0, lo = INFINITY, hi = -INFINITY, block[10] = {0};
    long count = 0, first = -1, last = -1;
    for (long i = 0; i < n; ++i)
        if (t[i] >= from && t[i] <= to && isfinite(x[i])) {
            if (first < 0)
                first = i;
            last = i;
            ++count;
        }
    const long per = count >= 10 ? (last - first + 1) / 10 : 1;
    long in_block[10] = {0};
    for (long i = first; count > 0 && i <= last; ++i) {
        if (!isfinite(x[i]))
            continue;
        sum += x[i], sum2 += x[i] * x[i];
        lo = fmin(lo, x[i]), hi = fmax(hi, x[i]);
        long b = (i - first) / per; // blocks of `per` rows, the last takes the rest
        b = b > 9 ? 9 : b;
        block[b] += x[i];
        in_block[b]++;
    }
    if (count < 20) {
        fprintf(stderr, "error: only %ld samples of %s between %g and %g s\n", count, column, from,
                to);
        free(t), free(x);
        return BDL_ERR_NO_RESULT;
    }
    double mean = sum / (double)count, sd = sqrt(fmax(0.0, sum2 / count - mean * mean));
    // Blocks of equal length: their means scatter by the standard error times sqrt(10).
    double bs = 0.0;
    for (int b = 0; b < 10; ++b) {
        double bm = in_block[b] > 0 ? block[b] / (double)in_block[b] : mean;
        bs += (bm - mean) * (bm - mean);
    }
    double se = sqrt(bs / 9.0) / sqrt(10.0);
    printf("%s from %.4g to %.4g s (%ld samples): mean %.6g, standard deviation %.4g, standard "
           "error %.3g (10 blocks), range %.6g to %.6g\n",
           column, t[first], t[last], count, mean, sd, se, lo, hi);
    free(t), free(x);
    return BDL_OK;
}

bdl_result bdl_cmd_analyze(int argc, char **argv)
{
    if (argc < 2 || strcmp(argv[1], "--help") == 0 || strcmp(argv[1], "-h") == 0) {
        fputs(analyze_usage, argc < 2 ? stderr : stdout);
        return argc < 2 ? BDL_ERR_ARGS : BDL_OK;
    }
    const char *what = argv[1], *run = NULL, *out_opt = NULL, *column = "pressure_drop";
    const char *file = "diagnostics.csv";
    double from = -INFINITY, to = INFINITY, fmin = 0.2, fmax = NAN;
    bdl_phase_opts ph = {.period = NAN,
                         .start = 0.0,
                         .below = NAN,
                         .from_cycle = 0,
                         .to_cycle = 1L << 40,
                         .bins = -1,
                         .plots = 1};
    int plots = 1;
    for (int i = 2; i < argc; ++i) {
        const char *a = argv[i];
        int more = i + 1 < argc;
        if (strcmp(a, "--help") == 0) {
            fputs(analyze_usage, stdout);
            return BDL_OK;
        } else if (strcmp(a, "--column") == 0 && more) {
            column = argv[++i];
        } else if (strcmp(a, "--from") == 0 && more) {
            from = atof(argv[++i]);
        } else if (strcmp(a, "--to") == 0 && more) {
            to = atof(argv[++i]);
        } else if (strcmp(a, "--fmin") == 0 && more) {
            fmin = atof(argv[++i]);
        } else if (strcmp(a, "--fmax") == 0 && more) {
            fmax = atof(argv[++i]);
        } else if (strcmp(a, "--file") == 0 && more) {
            file = argv[++i];
        } else if (strcmp(a, "--period") == 0 && more) {
            ph.period = atof(argv[++i]);
        } else if (strcmp(a, "--start") == 0 && more) {
            ph.start = atof(argv[++i]);
        } else if (strcmp(a, "--below") == 0 && more) {
            ph.below = atof(argv[++i]);
        } else if (strcmp(a, "--from-cycle") == 0 && more) {
            ph.from_cycle = atol(argv[++i]);
        } else if (strcmp(a, "--to-cycle") == 0 && more) {
            ph.to_cycle = atol(argv[++i]);
        } else if (strcmp(a, "--bins") == 0 && more) {
            ph.bins = atoi(argv[++i]);
        } else if (strcmp(a, "--out") == 0 && more) {
            out_opt = argv[++i];
        } else if (strcmp(a, "--no-plots") == 0) {
            plots = 0;
        } else if (a[0] == '-' || run) {
            fprintf(stderr, "error: unexpected argument '%s'\n\n%s", a, analyze_usage);
            return BDL_ERR_ARGS;
        } else {
            run = a;
        }
    }
    static const char *const whats[] = {"sweep", "spectrum", "mean",
                                        "phase", "networks", "profile"};
    int known = 0;
    for (int k = 0; k < 6; ++k)
        known |= strcmp(what, whats[k]) == 0;
    if (!run || !known) {
        fprintf(stderr,
                "error: expected 'sweep RUN', 'spectrum RUN', 'mean RUN', 'phase RUN', "
                "'profile RUN' or 'networks CONTACTS.csv'\n\n%s",
                analyze_usage);
        return BDL_ERR_ARGS;
    }
    if (strcmp(what, "mean") == 0)
        return analyze_mean(run, file, column, from, to);
    const int networks = strcmp(what, "networks") == 0;
    if (isnan(fmax))
        fmax = networks ? 5.0 : 20.0;
    if (ph.bins < 0)
        ph.bins = networks ? 40 : 50;
    if (!(fmax > fmin) || ph.bins < 3 || ph.bins > 100000) {
        fprintf(stderr, "error: --fmax must be above --fmin, --bins from 3 to 100000\n");
        return BDL_ERR_ARGS;
    }
    if (strcmp(what, "phase") == 0 && !(ph.period > 0.0)) {
        fprintf(stderr, "error: phase needs --period P > 0 [s]\n");
        return BDL_ERR_ARGS;
    }
    char out[1100], why[512];
    snprintf(out, sizeof out, "%s", out_opt ? out_opt : run);
    if (!out_opt && networks) { // next to the contact file
        const char *slash = strrchr(run, '/');
        snprintf(out, sizeof out, "%.*s", slash ? (int)(slash - run) : 1, slash ? run : ".");
    } else if (!out_opt) {
        snprintf(out, sizeof out, "%s/analysis", run);
    }
    if (bdl_check_writable_dir(out, why, sizeof why) != BDL_OK) {
        fprintf(stderr, "error: --out %s: %s\n", out, why);
        return BDL_ERR_OUTPUT_DIR;
    }
    if (strcmp(what, "sweep") == 0)
        return analyze_sweep(run, out, plots);
    if (networks)
        return bdl_analyze_networks(run, out, ph.bins, fmax, plots);
    if (strcmp(what, "profile") == 0)
        return bdl_analyze_profile(run, out, from, to, plots);
    if (strcmp(what, "phase") == 0) {
        ph.file = file, ph.column = column, ph.out = out, ph.plots = plots;
        return bdl_analyze_phase(run, &ph);
    }
    return analyze_spectrum(run, file, out, column, from, to, fmin, fmax, plots);
}
