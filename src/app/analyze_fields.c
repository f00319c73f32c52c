// bedlam analyze fields — time-averaged solids fraction and solids velocity on a grid, from the
// particle files (particles.pvd, vtk/particles_NNNNNN.vtp) of a run.
//
// Each particle file in the window adds each particle's volume to the cell that holds its centre
// (V = 4/3 pi r^3; a rod, with the `length` array, pi r^2 (L - 2r) + 4/3 pi r^3), and its volume
// times its velocity. The solids fraction of a cell is its volume summed over the files, over
// the cell's volume and the number of files; the solids velocity is the volume-weighted mean
// velocity of what passed through the cell (NaN where nothing did). The grid covers the domain
// (from run.log) in cubic cells of --cell metres (default three mean diameters), the last cell
// of an axis stretched to fit. Centres outside the domain are not counted (the summary says how
// much volume that was).
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app/analyze.h"
#include "core/file.h"
#include "io/vtk.h"

/// The domain from run.log's "domain:" line; 0 when there is none.
static int read_domain(const char *run, double lo[3], double hi[3])
{
    char path[1100], *text;
    size_t size;
    snprintf(path, sizeof path, "%s/run.log", run);
    if (!(text = bdl_read_file(path, &size)))
        return 0;
    const char *at = strstr(text, "domain: ");
    const int ok = at && sscanf(at, "domain: %lf %lf %lf to %lf %lf %lf", &lo[0], &lo[1], &lo[2],
                                &hi[0], &hi[1], &hi[2]) == 6;
    free(text);
    return ok;
}

typedef struct field_grid {
    int n[3];
    double lo[3], h[3];
    double *volume, *momentum; ///< per cell: summed V, and V v (3 per cell)
    double deposited, total;   ///< solids volume put on the grid, and of every particle [m^3]
    long particles, files;
} field_grid;

static long cell_of(const field_grid *g, const double *x)
{
    long index = 0;
    for (int a = 2; a >= 0; --a) {
        const double c = (x[a] - g->lo[a]) / g->h[a];
        if (!(c >= 0.0 && c < g->n[a]))
            return -1;
        index = index * g->n[a] + (long)c;
    }
    return index;
}

/// Adds one particle file to the sums; the reason in why on failure.
static bdl_result add_file(field_grid *g, const char *path, char *why, size_t len)
{
    bdl_vtp_file f;
    bdl_result r = bdl_vtp_open(path, &f, why, len);
    double *x = NULL, *v = NULL, *rad = NULL, *length = NULL;
    if (r == BDL_OK)
        r = bdl_vtp_array(&f, "Points", 3, &x, why, len);
    if (r == BDL_OK)
        r = bdl_vtp_array(&f, "velocity", 3, &v, why, len);
    if (r == BDL_OK)
        r = bdl_vtp_array(&f, "radius", 1, &rad, why, len);
    char ignored[8];
    if (r == BDL_OK && bdl_vtp_array(&f, "length", 1, &length, ignored, sizeof ignored) != BDL_OK)
        length = NULL; // spheres
    for (long i = 0; r == BDL_OK && i < f.points; ++i) {
        const double ri = rad[i], shaft = length ? fmax(0.0, length[i] - 2.0 * ri) : 0.0;
        const double vol = 4.0 / 3.0 * BDL_PI * ri * ri * ri + BDL_PI * ri * ri * shaft;
        g->total += vol;
        const long c = cell_of(g, x + 3 * i);
        if (c < 0)
            continue;
        g->volume[c] += vol;
        for (int a = 0; a < 3; ++a)
            g->momentum[3 * c + a] += vol * v[3 * i + a];
        g->deposited += vol;
    }
    if (r == BDL_OK) {
        g->particles += f.points;
        ++g->files;
    }
    free(x), free(v), free(rad), free(length);
    bdl_vtp_close(&f);
    return r;
}

/// Sizes the grid over the domain in cubes of `cell` metres.
static bdl_result make_grid(field_grid *g, const double lo[3], const double hi[3], double cell)
{
    long cells = 1;
    for (int a = 0; a < 3; ++a) {
        const double span = hi[a] - lo[a];
        g->n[a] = (int)fmax(1.0, floor(span / cell + 1e-9));
        g->lo[a] = lo[a];
        g->h[a] = span / g->n[a];
        cells *= g->n[a];
    }
    if (cells > 50000000L) {
        fprintf(stderr, "error: --cell %g gives %ld cells (at most 5e7)\n", cell, cells);
        return BDL_ERR_ARGS;
    }
    g->volume = calloc((size_t)cells, sizeof(double));
    g->momentum = calloc((size_t)cells * 3, sizeof(double));
    return g->volume && g->momentum ? BDL_OK : BDL_ERR_NOMEM;
}

/// The mean radius in the first particle file of the window (for the default cell).
static double first_radius(const char *run, const bdl_pvd *pvd, long first)
{
    double t, *rad = NULL, mean = NAN;
    char path[2200], why[256];
    snprintf(path, sizeof path, "%s/%s", run, bdl_pvd_file(pvd, first, &t));
    bdl_vtp_file f;
    if (bdl_vtp_open(path, &f, why, sizeof why) == BDL_OK &&
        bdl_vtp_array(&f, "radius", 1, &rad, why, sizeof why) == BDL_OK && f.points > 0) {
        mean = 0.0;
        for (long i = 0; i < f.points; ++i)
            mean += rad[i] / (double)f.points;
    }
    free(rad);
    bdl_vtp_close(&f);
    return mean;
}

static bdl_result write_fields(const bdl_analyze_opts *o, const field_grid *g)
{
    const long cells = (long)g->n[0] * g->n[1] * g->n[2];
    double *phi = malloc((size_t)cells * sizeof(double));
    double *vel = malloc((size_t)cells * 3 * sizeof(double));
    bdl_result r = BDL_ERR_NOMEM;
    if (phi && vel) {
        const double cell_volume = g->h[0] * g->h[1] * g->h[2];
        for (long c = 0; c < cells; ++c) {
            phi[c] = g->volume[c] / (cell_volume * (double)g->files);
            for (int a = 0; a < 3; ++a)
                vel[3 * c + a] = g->volume[c] > 0.0 ? g->momentum[3 * c + a] / g->volume[c] : NAN;
        }
        const bdl_vtk_array arrays[2] = {{"solids_fraction", BDL_VTK_FLOAT64, 1, phi},
                                         {"solids_velocity", BDL_VTK_FLOAT64, 3, vel}};
        char path[1200];
        snprintf(path, sizeof path, "%s/fields.vti", o->out);
        r = bdl_vti_write(path, g->n, g->lo, g->h, arrays, 2);
        if (r != BDL_OK)
            fprintf(stderr, "error: cannot write %s\n", path);
        else
            printf("wrote %s: %d x %d x %d cells of %.3g x %.3g x %.3g m\n", path, g->n[0], g->n[1],
                   g->n[2], g->h[0], g->h[1], g->h[2]);
    }
    free(phi);
    free(vel);
    return r;
}

bdl_result bdl_analyze_fields(const bdl_analyze_opts *o)
{
    char path[1100], why[512];
    double lo[3], hi[3];
    if (!read_domain(o->run, lo, hi)) {
        fprintf(stderr, "error: %s/run.log names no domain (a run of this version writes it)\n",
                o->run);
        return BDL_ERR_ARGS;
    }
    snprintf(path, sizeof path, "%s/particles.pvd", o->run);
    bdl_pvd *pvd = bdl_pvd_read(path, why, sizeof why);
    if (!pvd) {
        fprintf(stderr, "error: %s %s\n", path, why);
        return BDL_ERR_ARGS;
    }
    long first = -1, last = -1;
    for (long k = 0; k < bdl_pvd_count(pvd); ++k) {
        double t;
        bdl_pvd_file(pvd, k, &t);
        if (t >= o->from && t <= o->to) {
            first = first < 0 ? k : first;
            last = k;
        }
    }
    field_grid g = {0};
    bdl_result r = BDL_OK;
    double cell = o->cell > 0.0 ? o->cell : 6.0 * first_radius(o->run, pvd, first);
    if (first < 0 || !(cell > 0.0)) {
        fprintf(stderr, "error: %s holds no particle file between %g and %g s\n", path, o->from,
                o->to);
        r = BDL_ERR_ARGS;
    }
    if (r == BDL_OK)
        r = make_grid(&g, lo, hi, cell);
    for (long k = first; r == BDL_OK && k <= last; ++k) {
        double t;
        char file[2200];
        snprintf(file, sizeof file, "%s/%s", o->run, bdl_pvd_file(pvd, k, &t));
        if ((r = add_file(&g, file, why, sizeof why)) != BDL_OK) {
            fprintf(stderr, "error: %s %s\n", file, why);
            r = r == BDL_ERR_NOMEM ? r : BDL_ERR_ARGS; // a damaged input file: exit 2
        }
    }
    if (r == BDL_OK) {
        double t0, t1;
        bdl_pvd_file(pvd, first, &t0);
        bdl_pvd_file(pvd, last, &t1);
        printf("%ld particle files from %g to %g s, %ld particle samples; solids volume on the "
               "grid %.6g m^3 of %.6g (the rest had left the domain)\n",
               g.files, t0, t1, g.particles, g.deposited, g.total);
        r = write_fields(o, &g);
    }
    bdl_pvd_destroy(pvd);
    free(g.volume);
    free(g.momentum);
    return r;
}
