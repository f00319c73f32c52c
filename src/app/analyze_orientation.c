// bedlam analyze orientation — the PDF of the rods' in-plane angle near the front and back walls
// and in the bulk, from a run's orientation.csv ([output] orientation_interval): over a time
// window, or per stage of a gas sweep (analysis/rod_angles.h, analysis/umf.h).
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/rod_angles.h"
#include "analysis/umf.h"
#include "app/analyze.h"
#include "app/analyze_files.h"
#include "core/file.h"

#define LINE_MAX_CHARS 65536
#define MAX_COLUMNS    4096

/// orientation.csv read whole: the series and the storage behind it.
typedef struct orientation_data {
    bdl_rod_angle_series s;
    double *time, *u, *abs_cos[BDL_ROD_ZONES], *count[BDL_ROD_ZONES];
    long capacity;
    double *angle; ///< [bins]: the bins' centres from the header [deg]
    int *dest;     ///< per column: where its numbers go (column_kind, below)
    int columns;
} orientation_data;

/// Where a column goes: -1 nowhere, then time, inlet velocity, the zones' |cos|, and from
/// COLUMN_BIN on zone z's bin b at COLUMN_BIN + z * bins + b.
enum { COLUMN_NONE = -1, COLUMN_TIME, COLUMN_U, COLUMN_COS, COLUMN_BIN = COLUMN_COS + 2 };

static const char *const zone_names[BDL_ROD_ZONES] = {"wall", "bulk"};

static void free_data(orientation_data *d)
{
    free(d->time), free(d->u), free(d->angle), free(d->dest);
    for (int z = 0; z < BDL_ROD_ZONES; ++z)
        free(d->abs_cos[z]), free(d->count[z]);
}

/// The destination of a header field, given the bins of a zone; next[z] counts zone z's bins.
static int column_of(const char *name, int bins, int next[BDL_ROD_ZONES], orientation_data *d)
{
    if (strcmp(name, "time") == 0)
        return COLUMN_TIME;
    if (strcmp(name, "inlet_velocity") == 0)
        return COLUMN_U;
    for (int z = 0; z < BDL_ROD_ZONES; ++z) {
        const size_t len = strlen(zone_names[z]);
        if (strncmp(name, zone_names[z], len) != 0 || name[len] != '_')
            continue;
        if (strcmp(name + len, "_abs_cos") == 0)
            return COLUMN_COS + z;
        if (strncmp(name + len, "_at_", 4) == 0 && next[z] < bins) {
            if (z == 0)
                d->angle[next[0]] = atof(name + len + 4);
            return COLUMN_BIN + z * bins + next[z]++;
        }
    }
    return COLUMN_NONE;
}

/// Reads the header: the columns' destinations and the bins; 0 when it is not orientation.csv's.
static int parse_header(char *line, orientation_data *d)
{
    const char *names[MAX_COLUMNS];
    int bins = 0, bulk = 0;
    d->columns = 0;
    for (char *tok = strtok(line, ",\r\n"); tok; tok = strtok(NULL, ",\r\n")) {
        if (d->columns == MAX_COLUMNS)
            return 0;
        bins += strncmp(tok, "wall_at_", 8) == 0;
        bulk += strncmp(tok, "bulk_at_", 8) == 0;
        names[d->columns++] = tok;
    }
    if (bins < 1 || bins != bulk)
        return 0;
    int next[BDL_ROD_ZONES] = {0}, have = 0;
    for (int k = 0; k < d->columns; ++k) {
        d->dest[k] = column_of(names[k], bins, next, d);
        have |= d->dest[k] == COLUMN_TIME ? 1 : d->dest[k] == COLUMN_U ? 2 : 0;
    }
    d->s.bins = bins;
    const double width = 180.0 / bins;
    for (int b = 0; b < bins; ++b) // equal bins over [-90, 90], named by their centres
        if (fabs(d->angle[b] - (-90.0 + (b + 0.5) * width)) > 1e-3 * width)
            return 0;
    return have == 3;
}

/// Room for one more row.
static int grow(orientation_data *d)
{
    if (d->s.rows < d->capacity)
        return 1;
    const long cap = d->capacity ? 2 * d->capacity : 256;
    double **arrays[] = {&d->time,       &d->u,        &d->abs_cos[0],
                         &d->abs_cos[1], &d->count[0], &d->count[1]};
    for (int k = 0; k < 6; ++k) {
        const size_t per = k < 4 ? 1 : (size_t)d->s.bins;
        double *p = realloc(*arrays[k], (size_t)cap * per * sizeof(double));
        if (!p)
            return 0;
        *arrays[k] = p;
    }
    d->capacity = cap;
    return 1;
}

/// One data line into row d->s.rows. Returns 1 when stored, 0 for a line cut short (a killed
/// run's last), -1 for a bin count that is not a whole number >= 0.
static int parse_row(char *line, orientation_data *d)
{
    const long r = d->s.rows;
    const int bins = d->s.bins;
    char *p = line;
    for (int k = 0; k < d->columns; ++k) {
        char *end;
        const double v = strtod(p, &end);
        if (end == p && *p != ',')
            return 0;
        const int c = d->dest[k];
        if (c == COLUMN_TIME)
            d->time[r] = v;
        else if (c == COLUMN_U)
            d->u[r] = v;
        else if (c == COLUMN_COS || c == COLUMN_COS + 1)
            d->abs_cos[c - COLUMN_COS][r] = end == p ? NAN : v;
        else if (c >= COLUMN_BIN) {
            const int z = (c - COLUMN_BIN) / bins, b = (c - COLUMN_BIN) % bins;
            if (!(v >= 0.0 && v == floor(v)) || end == p)
                return -1;
            d->count[z][r * bins + b] = v;
        }
        p = end;
        if (k + 1 < d->columns && *p++ != ',')
            return 0;
    }
    return 1;
}

/// Reads RUN/orientation.csv into d; prints why not and returns BDL_ERR_ARGS.
static bdl_result read_orientation(const char *run, orientation_data *d)
{
    char path[1300];
    snprintf(path, sizeof path, "%s/orientation.csv", run);
    char why[256];
    FILE *f = bdl_open_regular(path, why, sizeof why);
    char *line = malloc(LINE_MAX_CHARS);
    d->angle = malloc(MAX_COLUMNS * sizeof(double));
    d->dest = malloc(MAX_COLUMNS * sizeof(int));
    bdl_result rc = BDL_ERR_ARGS;
    if (!f)
        fprintf(stderr,
                "error: %s %s (written by runs with rods and [output] "
                "orientation_interval)\n",
                path, why);
    else if (!line || !d->angle || !d->dest)
        fprintf(stderr, "error: out of memory\n"), rc = BDL_ERR_NOMEM;
    else if (!fgets(line, LINE_MAX_CHARS, f) || !parse_header(line, d))
        fprintf(stderr,
                "error: %s: not an orientation table (time, inlet_velocity, wall_at_A and "
                "bulk_at_A bins of equal width over [-90, 90])\n",
                path);
    else
        rc = BDL_OK;
    for (long n = 2; rc == BDL_OK && fgets(line, LINE_MAX_CHARS, f); ++n) {
        if (line[0] == '#' || line[0] == '\n')
            continue;
        const int ok = grow(d) ? parse_row(line, d) : -2;
        if (ok == 1)
            d->s.rows++;
        if (ok < 0) {
            if (ok == -2)
                fprintf(stderr, "error: out of memory\n");
            else
                fprintf(stderr, "error: %s:%ld: a bin count is not a whole number >= 0\n", path, n);
            rc = ok == -2 ? BDL_ERR_NOMEM : BDL_ERR_ARGS;
        }
    }
    if (f)
        fclose(f);
    free(line);
    d->s.time = d->time;
    for (int z = 0; z < BDL_ROD_ZONES; ++z)
        d->s.count[z] = d->count[z], d->s.abs_cos[z] = d->abs_cos[z];
    return rc;
}

/// One PDF of each zone: over a time window, or over the second half of one sweep stage.
typedef struct orientation_pdf {
    double u;        ///< mean inlet velocity of its rows [m/s]
    double from, to; ///< its rows' first and last time [s]
    bdl_rod_angle_average mean;
    double *pdf[BDL_ROD_ZONES]; ///< [bins] [1/deg]
} orientation_pdf;

/// The PDF of rows [first, end) with times in [from, to]; 0 when no row is there.
static int pdf_of(const orientation_data *d, long first, long end, double from, double to,
                  orientation_pdf *p)
{
    p->mean = bdl_rod_angle_pdf(&d->s, first, end, from, to, p->pdf);
    double u = 0.0;
    p->from = INFINITY, p->to = -INFINITY;
    for (long r = first; r < end; ++r)
        if (d->time[r] >= from && d->time[r] <= to) {
            u += d->u[r];
            p->from = fmin(p->from, d->time[r]), p->to = fmax(p->to, d->time[r]);
        }
    p->u = p->mean.rows > 0 ? u / p->mean.rows : NAN;
    return p->mean.rows > 0;
}

/// The PDFs asked for into p (room for d->s.rows with --by-velocity): one over [--from, --to], or
/// with
/// --by-velocity one per stage of the inlet velocity (u > 0) over its second half (the stages of
/// analyze sweep, bdl_sweep_span_at) within [--from, --to]. Returns their number.
static int pdfs_of(const bdl_analyze_opts *o, const orientation_data *d, orientation_pdf *p)
{
    if (!o->by_velocity)
        return pdf_of(d, 0, d->s.rows, o->from, o->to, &p[0]);
    int count = 0;
    bdl_sweep_span sp;
    for (long i = 0; i < d->s.rows; i = sp.end) {
        bdl_sweep_span_at(d->time, d->u, d->s.rows, i, &sp);
        if (sp.u > 0.0 && pdf_of(d, sp.first, sp.end, fmax(sp.from, o->from), o->to, &p[count]))
            ++count;
    }
    return count;
}

/// orientation.csv (stage, inlet velocity, angle, PDF near the walls and in the bulk, one line per
/// stage and bin) and orientation_summary.csv (per stage: its rows, rods and mean |cos|).
static bdl_result write_pdfs(const char *out, const orientation_data *d, const orientation_pdf *p,
                             int n)
{
    char path[1300], summary[1300];
    snprintf(path, sizeof path, "%s/orientation.csv", out);
    snprintf(summary, sizeof summary, "%s/orientation_summary.csv", out);
    bdl_atomic_file af, as;
    if (bdl_atomic_open_csv(&af, path, "stage,inlet_velocity,angle,wall_pdf,bulk_pdf") != BDL_OK)
        return BDL_ERR_OUTPUT_DIR;
    if (bdl_atomic_open_csv(&as, summary,
                            "stage,inlet_velocity,from,to,rows,wall_rods,wall_abs_cos,bulk_rods,"
                            "bulk_abs_cos") != BDL_OK) {
        bdl_atomic_abort(&af);
        return BDL_ERR_OUTPUT_DIR;
    }
    for (int k = 0; k < n; ++k) {
        const bdl_rod_angle_average *m = &p[k].mean;
        for (int b = 0; b < d->s.bins; ++b)
            fprintf(af.file, "%d,%.6g,%.6g,%.6g,%.6g\n", k, p[k].u, d->angle[b], p[k].pdf[0][b],
                    p[k].pdf[1][b]);
        fprintf(as.file, "%d,%.6g,%.6g,%.6g,%ld,%.6g,%.6g,%.6g,%.6g\n", k, p[k].u, p[k].from,
                p[k].to, m->rows, m->rods[0] / m->rows, m->abs_cos[0], m->rods[1] / m->rows,
                m->abs_cos[1]);
    }
    bdl_result rc = bdl_atomic_commit(&af);
    const bdl_result rs = bdl_atomic_commit(&as);
    return rc != BDL_OK || rs != BDL_OK ? BDL_ERR_OUTPUT_DIR : BDL_OK;
}

/// orientation.png: the PDF against the angle near the walls and in the bulk, one line per stage
/// coloured by its inlet velocity (--by-velocity), else one line.
static void plot_pdfs(const char *out, int n, int by_velocity)
{
    char path[1300], style[200];
    snprintf(path, sizeof path, "%s/orientation.gp", out);
    snprintf(style, sizeof style, "%s", by_velocity ? "lw 2 lc palette" : "lw 2 lc rgb '#3060c0'");
    bdl_analyze_plot(
        path,
        "set terminal pngcairo size 1200,500 font 'DejaVu Sans,11'\n"
        "set output '%s/orientation.png'\nset datafile separator ','\n"
        "set xlabel 'in-plane angle from the vertical [deg] (0 upright, +-90 lying)'\n"
        "set ylabel 'PDF [1/deg]'\nset xrange [-90:90]\nset xtics 30\nset yrange [0:*]\n"
        "set grid\nunset key\nset cblabel 'inlet velocity U_0 [m/s]'\n%s"
        "set multiplot layout 1,2\n"
        "set title 'within one rod length of the front and back walls'\n"
        "plot for [k=0:%d] '%s/orientation.csv' every ::1 using (column(1) == k ? $3 : 1/0):4:2 "
        "with lines %s\n"
        "set title 'bulk'\n"
        "plot for [k=0:%d] '%s/orientation.csv' every ::1 using (column(1) == k ? $3 : 1/0):5:2 "
        "with lines %s\n"
        "unset multiplot\n",
        out, by_velocity ? "" : "unset colorbox\n", n - 1, out, style, n - 1, out, style);
}

/// Prints each PDF's figures: rods, mean |cos|, and the share of rods within 30° of lying
/// (|angle| >= 60°) and of upright (|angle| <= 30°).
static void print_pdfs(const orientation_data *d, const orientation_pdf *p, int n)
{
    const double width = 180.0 / d->s.bins;
    for (int k = 0; k < n; ++k) {
        printf("%.4g to %.4g s (%ld rows), U0 %.4g m/s:", p[k].from, p[k].to, p[k].mean.rows,
               p[k].u);
        for (int z = 0; z < BDL_ROD_ZONES; ++z) {
            double lying = 0.0, upright = 0.0;
            for (int b = 0; b < d->s.bins; ++b) {
                lying += fabs(d->angle[b]) >= 60.0 ? p[k].pdf[z][b] * width : 0.0;
                upright += fabs(d->angle[b]) <= 30.0 ? p[k].pdf[z][b] * width : 0.0;
            }
            printf("  %s %.1f rods, |cos| %.3f, lying %.3f, upright %.3f", zone_names[z],
                   p[k].mean.rods[z] / p[k].mean.rows, p[k].mean.abs_cos[z], lying, upright);
        }
        printf("\n");
    }
}

/// Any rod counted in any row.
static int has_rods(const orientation_data *d)
{
    for (int z = 0; z < BDL_ROD_ZONES; ++z)
        for (long k = 0; k < d->s.rows * d->s.bins; ++k)
            if (d->count[z][k] > 0.0)
                return 1;
    return 0;
}

bdl_result bdl_analyze_orientation(const bdl_analyze_opts *o)
{
    orientation_data d = {0};
    bdl_result rc = read_orientation(o->run, &d);
    if (rc == BDL_OK && !has_rods(&d)) {
        fprintf(stderr, "error: %s/orientation.csv: no rods in %ld rows\n", o->run, d.s.rows);
        rc = BDL_ERR_ARGS;
    }
    // Room for a PDF per row (--by-velocity: at most one stage per row), else one.
    const long rows = rc != BDL_OK ? 0 : o->by_velocity ? d.s.rows : 1, bins = d.s.bins;
    orientation_pdf *p = rows > 0 ? calloc((size_t)rows, sizeof *p) : NULL;
    double *store = rows > 0 ? malloc((size_t)(rows * BDL_ROD_ZONES * bins) * sizeof *store) : NULL;
    if (rc == BDL_OK && (!p || !store)) {
        fprintf(stderr, "error: out of memory\n");
        rc = BDL_ERR_NOMEM;
    }
    for (long k = 0; rc == BDL_OK && k < rows; ++k)
        for (int z = 0; z < BDL_ROD_ZONES; ++z)
            p[k].pdf[z] = store + (k * BDL_ROD_ZONES + z) * bins;
    const int n = rc == BDL_OK ? pdfs_of(o, &d, p) : 0;
    if (rc == BDL_OK && n == 0) {
        fprintf(stderr, "error: %s/orientation.csv: no rows between %g and %g s%s\n", o->run,
                o->from, o->to,
                o->by_velocity ? " in the second half of a stage with an inlet velocity" : "");
        rc = BDL_ERR_NO_RESULT;
    }
    if (rc == BDL_OK) {
        print_pdfs(&d, p, n);
        if ((rc = write_pdfs(o->out, &d, p, n)) != BDL_OK)
            fprintf(stderr, "error: cannot write orientation.csv in %s\n", o->out);
    }
    if (rc == BDL_OK && o->plots)
        plot_pdfs(o->out, n, o->by_velocity);
    free(p), free(store);
    free_data(&d);
    return rc;
}
