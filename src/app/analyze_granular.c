// bedlam analyze phase and networks: a column of a vibrated run folded over the vibration
// cycle (and followed cycle by cycle), and the force networks and force distribution of a
// contact file.
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/granular.h"
#include "app/analyze.h"
#include "core/file.h"

bdl_result bdl_analyze_phase(const char *run, const bdl_phase_opts *o)
{
    double *t = NULL, *x = NULL;
    long n = 0, m = 0;
    if (!bdl_analyze_read_column(run, o->file, "time", &t, &n) ||
        !bdl_analyze_read_column(run, o->file, o->column, &x, &m) || m != n) {
        free(t), free(x);
        return BDL_ERR_ARGS;
    }
    const int bins = o->bins;
    double *sum = calloc((size_t)bins, sizeof(double)), *lo = malloc(bins * sizeof(double));
    double *hi = malloc(bins * sizeof(double));
    long *count = calloc((size_t)bins, sizeof(long));
    if (!sum || !lo || !hi || !count) {
        free(t), free(x), free(sum), free(lo), free(hi), free(count);
        return BDL_ERR_NOMEM;
    }
    for (int b = 0; b < bins; ++b)
        lo[b] = INFINITY, hi[b] = -INFINITY;
    long used = 0, first_cycle = -1, last_cycle = -1;
    for (long i = 0; i < n; ++i) {
        const double c = (t[i] - o->start) / o->period;
        const long cycle = (long)floor(c + 1e-9);
        if (c < -1e-9 || cycle < o->from_cycle || cycle >= o->to_cycle || !isfinite(x[i]))
            continue;
        int b = (int)floor((c - (double)cycle) * bins + 1e-9);
        b = b < 0 ? 0 : b >= bins ? bins - 1 : b;
        sum[b] += x[i];
        lo[b] = fmin(lo[b], x[i]);
        hi[b] = fmax(hi[b], x[i]);
        count[b]++;
        used++;
        first_cycle = first_cycle < 0 ? cycle : first_cycle;
        last_cycle = cycle;
    }
    if (used < 2 * bins) {
        fprintf(stderr, "error: only %ld samples of %s in the cycles asked for (%d bins)\n", used,
                o->column, bins);
        free(t), free(x), free(sum), free(lo), free(hi), free(count);
        return BDL_ERR_NO_RESULT;
    }
    char path[1300];
    bdl_result rc = BDL_OK;
    snprintf(path, sizeof path, "%s/phase_%s.csv", o->out, o->column);
    bdl_atomic_file af;
    double best = -INFINITY, worst = INFINITY;
    int at_best = 0, at_worst = 0;
    if (bdl_atomic_open(&af, path) == BDL_OK) {
        fprintf(af.file, "phase,mean,min,max,samples\n");
        for (int b = 0; b < bins; ++b) {
            double mean = count[b] ? sum[b] / (double)count[b] : NAN;
            fprintf(af.file, "%.6g,%.8g,%.8g,%.8g,%ld\n", (b + 0.5) / bins, mean, lo[b], hi[b],
                    count[b]);
            if (count[b] && mean > best)
                best = mean, at_best = b;
            if (count[b] && mean < worst)
                worst = mean, at_worst = b;
        }
        rc = bdl_atomic_commit(&af);
    } else {
        rc = BDL_ERR_OUTPUT_DIR;
    }
    printf("%s over cycles %ld to %ld (%ld samples, %d phase bins): largest mean %.6g at phase "
           "%.3f, smallest %.6g at phase %.3f\n",
           o->column, first_cycle, last_cycle, used, bins, best, (at_best + 0.5) / bins, worst,
           (at_worst + 0.5) / bins);
    if (isfinite(o->below)) {
        // The phase intervals where the mean lies below the threshold (the bins' edges).
        for (int b = 0; b < bins; ++b) {
            const int in = count[b] && sum[b] / (double)count[b] < o->below;
            const int prev = b > 0 && count[b - 1] && sum[b - 1] / (double)count[b - 1] < o->below;
            if (in && !prev)
                printf("%s below %g from phase %.3f", o->column, o->below, (double)b / bins);
            if (!in && prev)
                printf(" to %.3f\n", (double)b / bins);
            if (in && b == bins - 1)
                printf(" to 1.000\n");
        }
    }
    if (rc == BDL_OK && o->plots) {
        snprintf(path, sizeof path, "%s/phase_%s.gp", o->out, o->column);
        FILE *g = fopen(path, "w");
        if (g) {
            fprintf(g,
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
                    o->out, o->column, o->column, o->out, o->column, first_cycle, last_cycle, run,
                    o->file, o->start, o->period, o->column, o->column);
            fclose(g);
            bdl_analyze_gnuplot(path);
        }
    }
    free(t), free(x), free(sum), free(lo), free(hi), free(count);
    return rc;
}

/// Reads a contacts file of a run (see output/granular_out.h). Returns the contact count (-1 on
/// error); *pos gets the centres by particle id (NAN where a particle has no contact).
static long read_contacts(const char *path, bdl_contact_rec **out, bdl_vec3 **pos, long *n)
{
    FILE *f = fopen(path, "r");
    if (!f) {
        fprintf(stderr, "error: cannot open %s\n", path);
        return -1;
    }
    long cap = 4096, nc = 0, pcap = 0;
    bdl_contact_rec *c = malloc((size_t)cap * sizeof *c);
    bdl_vec3 *p = NULL;
    char line[1024];
    *n = 0;
    int header = 0;
    while (c && fgets(line, sizeof line, f)) {
        if (line[0] == '#')
            continue;
        if (!header) {
            header = strncmp(line, "i,j,", 4) == 0;
            if (!header)
                break;
            continue;
        }
        long i, j;
        int si, sj;
        double xi, yi, zi, xj, yj, zj, ov, fn;
        if (sscanf(line, "%ld,%ld,%d,%d,%lf,%lf,%lf,%lf,%lf,%lf,%lf,%lf", &i, &j, &si, &sj, &xi,
                   &yi, &zi, &xj, &yj, &zj, &ov, &fn) != 12 ||
            i < 0 || i > 100000000 || j > 100000000) {
            fprintf(stderr, "error: %s: bad contact line: %s", path, line);
            free(c), free(p), fclose(f);
            return -1;
        }
        const long top = (i > j ? i : j) + 1;
        if (top > pcap) {
            long ncap = pcap ? pcap : 1024;
            while (ncap < top)
                ncap *= 2;
            bdl_vec3 *np = realloc(p, (size_t)ncap * sizeof *np);
            if (!np)
                break;
            for (long k = pcap; k < ncap; ++k)
                np[k] = (bdl_vec3){NAN, NAN, NAN};
            p = np, pcap = ncap;
        }
        *n = top > *n ? top : *n;
        p[i] = (bdl_vec3){xi, yi, zi};
        if (j >= 0)
            p[j] = (bdl_vec3){xj, yj, zj};
        if (nc == cap) {
            bdl_contact_rec *nw = realloc(c, (size_t)(cap *= 2) * sizeof *c);
            if (!nw)
                break;
            c = nw;
        }
        c[nc++] = (bdl_contact_rec){(int32_t)i, (int32_t)(j < 0 ? -1 : j), fn};
    }
    fclose(f);
    if (!header || !c || !p) {
        fprintf(stderr, "error: %s: not a contacts file of a run (no 'i,j,...' header)\n", path);
        free(c), free(p);
        return -1;
    }
    *out = c;
    *pos = p;
    return nc;
}

bdl_result bdl_analyze_networks(const char *file, const char *out, int bins, double fmax, int plots)
{
    bdl_contact_rec *c = NULL;
    bdl_vec3 *pos = NULL;
    long n = 0, nc = read_contacts(file, &c, &pos, &n);
    if (nc < 0)
        return BDL_ERR_ARGS;
    double *fn = malloc((size_t)(nc > 0 ? nc : 1) * sizeof(double));
    uint8_t *z = calloc((size_t)(n > 0 ? n : 1), 1);
    long pp = 0, walls = 0;
    double mean = 0.0;
    for (long k = 0; fn && z && k < nc; ++k) {
        if (c[k].j < 0) {
            walls++;
            continue;
        }
        if (c[k].fn > 0.0) {
            fn[pp++] = c[k].fn;
            mean += c[k].fn;
            z[c[k].i] += z[c[k].i] < 255;
            z[c[k].j] += z[c[k].j] < 255;
        }
    }
    mean = pp > 0 ? mean / (double)pp : 0.0;
    bdl_network_stats all, strong;
    if (!fn || !z || bdl_force_networks(n, c, nc, 0.0, pos, NULL, &all) != BDL_OK ||
        bdl_force_networks(n, c, nc, mean, pos, NULL, &strong) != BDL_OK) {
        free(c), free(pos), free(fn), free(z);
        return BDL_ERR_NOMEM;
    }
    const bdl_coordination_stats cs = bdl_coordination(z, n);
    printf("%s: %ld contacts (%ld with walls), %ld particle pairs with a normal force, mean force "
           "%.6g N; %ld particles touch another, mean coordination among them %.4f, multi-contact "
           "ratio %.4f\n",
           file, nc, walls, pp, mean, cs.in_contact,
           cs.in_contact ? cs.mean * (double)n / (double)cs.in_contact : 0.0,
           cs.multi_contact_ratio);
    printf("force networks: %ld; the largest has %ld particles and %ld contacts (mean "
           "coordination %.4f), length %.6g m; the other networks have %ld contacts\n",
           all.networks, all.largest, all.largest_edges, all.largest_mean_z, all.largest_length,
           all.other_edges);
    printf("strong networks (F_n above the mean): %ld; the largest has %ld particles\n",
           strong.networks, strong.largest);
    double *centre = malloc((size_t)bins * sizeof(double)), *pdf = malloc(bins * sizeof(double));
    bdl_force_pdf_fit fit;
    bdl_result rc = BDL_OK;
    if (!centre || !pdf || bdl_force_pdf(fn, pp, bins, fmax, centre, pdf, &fit) != BDL_OK) {
        fprintf(stderr, "error: too few forces for a distribution\n");
        rc = BDL_ERR_NO_RESULT;
    } else {
        printf("force distribution of f = F_n/<F_n>: P(f) = a (1 - b exp(-f^2)) exp(-beta f) "
               "with a = %.4f, b = %.4f, beta = %.4f (rms residual %.3g)\n",
               fit.a, fit.b, fit.beta, fit.rms);
        char path[1300];
        snprintf(path, sizeof path, "%s/force_pdf.csv", out);
        bdl_atomic_file af;
        if (bdl_atomic_open(&af, path) == BDL_OK) {
            fprintf(af.file, "f,pdf,fit\n");
            for (int k = 0; k < bins; ++k)
                fprintf(af.file, "%.6g,%.6g,%.6g\n", centre[k], pdf[k],
                        bdl_force_pdf_eval(&fit, centre[k]));
            fprintf(af.file, "# a %.6g b %.6g beta %.6g\n", fit.a, fit.b, fit.beta);
            rc = bdl_atomic_commit(&af);
        } else {
            rc = BDL_ERR_OUTPUT_DIR;
        }
        snprintf(path, sizeof path, "%s/force_pdf.gp", out);
        FILE *g = rc == BDL_OK && plots ? fopen(path, "w") : NULL;
        if (g) {
            fprintf(g,
                    "set terminal pngcairo size 800,520 font 'DejaVu Sans,11'\n"
                    "set output '%s/force_pdf.png'\nset datafile separator ','\n"
                    "set xlabel 'f = F_n / <F_n>'\nset ylabel 'P(f)'\nset logscale y\n"
                    "set grid\nset key top right\n"
                    "plot '%s/force_pdf.csv' every ::1 using 1:($2 > 0 ? $2 : 1/0) with points "
                    "pt 7 lc rgb '#3060c0' title 'contacts', '' every ::1 using 1:3 with lines "
                    "lw 2 lc rgb '#c03030' title sprintf('a(1-b e^{-f^2}) e^{-{/Symbol b} f}: "
                    "a %%.2f, b %%.2f, {/Symbol b} %%.2f', %.6g, %.6g, %.6g)\n",
                    out, out, fit.a, fit.b, fit.beta);
            fclose(g);
            bdl_analyze_gnuplot(path);
        }
    }
    free(c), free(pos), free(fn), free(z), free(centre), free(pdf);
    return rc;
}

bdl_result bdl_analyze_profile(const char *run, const char *out, double from, double to, int plots)
{
    char path[1300], header[65536];
    snprintf(path, sizeof path, "%s/profile.csv", run);
    FILE *f = fopen(path, "r");
    if (!f || !fgets(header, sizeof header, f)) {
        fprintf(stderr, "error: cannot read %s (written by runs with a gas)\n", path);
        if (f)
            fclose(f);
        return BDL_ERR_ARGS;
    }
    fclose(f);
    double *t = NULL;
    long n = 0;
    if (!bdl_analyze_read_column(run, "profile.csv", "time", &t, &n))
        return BDL_ERR_ARGS;
    snprintf(path, sizeof path, "%s/profile.csv", out);
    bdl_atomic_file af;
    if (bdl_atomic_open(&af, path) != BDL_OK) {
        fprintf(stderr, "error: cannot write %s\n", path);
        free(t);
        return BDL_ERR_OUTPUT_DIR;
    }
    fprintf(af.file, "height,solids_fraction,std\n");
    long used = 0;
    double peak = 0.0, peak_h = 0.0;
    for (char *tok = strtok(header, ",\r\n"); tok; tok = strtok(NULL, ",\r\n")) {
        if (strncmp(tok, "phi_at_", 7) != 0)
            continue;
        double *x = NULL;
        long m = 0;
        if (!bdl_analyze_read_column(run, "profile.csv", tok, &x, &m) || m != n) {
            free(x);
            continue;
        }
        double s = 0.0, s2 = 0.0;
        used = 0;
        for (long i = 0; i < n; ++i)
            if (t[i] >= from && t[i] <= to && isfinite(x[i])) {
                s += x[i], s2 += x[i] * x[i];
                used++;
            }
        free(x);
        if (used == 0)
            continue;
        const double mean = s / (double)used, h = atof(tok + 7);
        fprintf(af.file, "%.6g,%.6g,%.6g\n", h, mean,
                sqrt(fmax(0.0, s2 / (double)used - mean * mean)));
        if (mean > peak)
            peak = mean, peak_h = h;
    }
    free(t);
    if (used == 0) {
        bdl_atomic_abort(&af);
        fprintf(stderr, "error: no rows of %s/profile.csv between %g and %g s\n", run, from, to);
        return BDL_ERR_NO_RESULT;
    }
    if (bdl_atomic_commit(&af) != BDL_OK)
        return BDL_ERR_OUTPUT_DIR;
    printf("solids fraction against height, averaged over %ld rows: largest %.4f at %.4g m; "
           "table in %s\n",
           used, peak, peak_h, path);
    if (plots) {
        snprintf(path, sizeof path, "%s/profile.gp", out);
        FILE *g = fopen(path, "w");
        if (g) {
            fprintf(g,
                    "set terminal pngcairo size 600,700 font 'DejaVu Sans,11'\n"
                    "set output '%s/profile.png'\nset datafile separator ','\n"
                    "set xlabel 'solids fraction (layer mean)'\nset ylabel 'height [m]'\n"
                    "set grid\nset key top right\nset xrange [0:*]\n"
                    "plot '%s/profile.csv' every ::1 using 2:1:($2-$3):($2+$3) with xerrorlines "
                    "pt 7 lc rgb '#3060c0' title 'time average +- standard deviation'\n",
                    out, out);
            fclose(g);
            bdl_analyze_gnuplot(path);
        }
    }
    return BDL_OK;
}
