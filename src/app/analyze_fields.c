// bedlam analyze fields — time-averaged solids fraction and solids velocity on a grid, from the
// particle files (particles.pvd, vtk/particles_NNNNNN.vtp) of a run.
//
// Each particle file in the window is one sample of analysis/fields.h, the arithmetic a run with
// [output] fields_interval does as it goes: each particle's volume (a rod's from the `length`
// array, a parcel's times its `parcel_count`) in the cell that holds its centre, and its volume
// times its velocity. The grid covers the domain (from run.log) in cells of about --cell metres
// (default three mean diameters of the first file of the window). Centres outside the domain are
// not counted (the summary says how much volume that was).
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/fields.h"
#include "app/analyze.h"
#include "core/file.h"
#include "io/vtk.h"
#include "output/fields_out.h"
#include "scene/scene.h"

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

/// Adds one particle file to the sums; the reason in why on failure.
static bdl_result add_file(bdl_fields *g, const char *path, double time, char *why, size_t len)
{
    bdl_vtp_file f;
    bdl_result r = bdl_vtp_open(path, &f, why, len);
    double *x = NULL, *v = NULL, *rad = NULL, *length = NULL, *count = NULL;
    if (r == BDL_OK)
        r = bdl_vtp_array(&f, "Points", 3, &x, why, len);
    if (r == BDL_OK)
        r = bdl_vtp_array(&f, "velocity", 3, &v, why, len);
    if (r == BDL_OK)
        r = bdl_vtp_array(&f, "radius", 1, &rad, why, len);
    char ignored[8];
    if (r == BDL_OK && bdl_vtp_array(&f, "length", 1, &length, ignored, sizeof ignored) != BDL_OK)
        length = NULL; // spheres
    if (r == BDL_OK &&
        bdl_vtp_array(&f, "parcel_count", 1, &count, ignored, sizeof ignored) != BDL_OK)
        count = NULL; // particles, not parcels
    if (r == BDL_OK)
        bdl_fields_add(g, &(bdl_fields_sample){time, f.points, x, v, rad, length, count});
    free(x), free(v), free(rad), free(length), free(count);
    bdl_vtp_close(&f);
    return r;
}

/// Sizes the grid over the domain in cubes of `cell` metres.
static bdl_result make_grid(bdl_fields *g, const double lo[3], const double hi[3], double cell)
{
    const bdl_result r = bdl_fields_create(g, lo, hi, cell, BDL_MAX_FIELD_CELLS);
    if (r == BDL_ERR_ARGS) {
        int n[3];
        double h[3];
        fprintf(stderr, "error: --cell %g gives %.3g cells (at most %g)\n", cell,
                bdl_fields_grid(lo, hi, cell, n, h), BDL_MAX_FIELD_CELLS);
    }
    return r;
}

/// The default cell from the first particle file of the window.
static double first_cell(const char *run, const bdl_pvd *pvd, long first)
{
    double t, *rad = NULL, cell = NAN;
    char path[2200], why[256];
    snprintf(path, sizeof path, "%s/%s", run, bdl_pvd_file(pvd, first, &t));
    bdl_vtp_file f;
    if (bdl_vtp_open(path, &f, why, sizeof why) == BDL_OK &&
        bdl_vtp_array(&f, "radius", 1, &rad, why, sizeof why) == BDL_OK)
        cell = bdl_fields_default_cell(f.points, rad);
    free(rad);
    bdl_vtp_close(&f);
    return cell;
}

static bdl_result write_fields(const bdl_analyze_opts *o, const bdl_fields *g)
{
    char path[1200];
    snprintf(path, sizeof path, "%s/fields.vti", o->out);
    const bdl_result r = bdl_fields_vti_write(g, path);
    if (r != BDL_OK)
        fprintf(stderr, "error: cannot write %s\n", path);
    else
        printf("wrote %s: %d x %d x %d cells of %.3g x %.3g x %.3g m\n", path, g->n[0], g->n[1],
               g->n[2], g->h[0], g->h[1], g->h[2]);
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
    bdl_fields g = {0};
    bdl_result r = BDL_OK;
    double cell = o->cell;
    if (!(cell > 0.0) && first >= 0) // the default, from the first file of the window
        cell = first_cell(o->run, pvd, first);
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
        if ((r = add_file(&g, file, t, why, sizeof why)) != BDL_OK) {
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
               g.samples, t0, t1, g.particles, g.deposited, g.total);
        r = write_fields(o, &g);
    }
    bdl_pvd_destroy(pvd);
    bdl_fields_free(&g);
    return r;
}
