// bedlam analyze dia — the thesis's coalignment by wall zone and solids mass flux (Mahajan 2019,
// eqs. 2.5 and 2.6) on a synthetic camera's images, against the truth beside them. Called by
// analyze_dia.c frame by frame (app/analyze_dia.h).
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app/analyze_dia.h"
#include "app/analyze_files.h"
#include "core/file.h"
#include "dia/orient.h"

long dia_piv_cell_mean(const bdl_dia_piv_field *f, double u0, double v0, double u1, double v1,
                       double *du, double *dv)
{
    double su = 0.0, sv = 0.0;
    long n = 0;
    for (long k = 0; k < (long)f->nx * f->ny; ++k)
        if (!f->outlier[k] && f->u[k] >= u0 && f->u[k] < u1 && f->v[k] >= v0 && f->v[k] < v1)
            su += f->du[k], sv += f->dv[k], ++n;
    *du = n > 0 ? su / (double)n : 0.0;
    *dv = n > 0 ? sv / (double)n : 0.0;
    return n;
}

/// The zones' bounds in rod lengths from the nearer side wall, and their names.
static const double zone_edges[DIA_ZONES + 1] = {0.0, 2.0, 6.0, INFINITY};
static const char *const zone_names[DIA_ZONES] = {"0-2", "2-6", "6+"};

void dia_coalign_add(dia_coalign *z, int truth, const double *u, const double *v,
                     const double *angle, long n, double lp, int width)
{
    enum { BINS = DIA_COALIGN_BINS };
    z->lp = lp;
    const double half = 0.5 * width;
    for (int k = 0; n >= 2 && k < DIA_ZONES; ++k)
        for (int side = 0; side < 2; ++side) { // the left wall's strip, then the right one's
            const double a = zone_edges[k] * lp, b = zone_edges[k + 1] * lp;
            const double lo = side == 0 ? (k == 0 ? -INFINITY : a) : fmax(width - b, half);
            const double hi = side == 0 ? fmin(b, half) : (k == 0 ? INFINITY : width - a);
            double c[BINS], r[BINS];
            long pairs[BINS];
            if (!(lo < hi) ||
                bdl_dia_coalignment(u, v, angle, n, 5.0 * lp, BINS, lo, hi, c, pairs, r) != BDL_OK)
                continue;
            for (int m = 0; m < BINS; ++m)
                if (pairs[m] > 0) {
                    z->c_sum[truth][k][m] += c[m] * (double)pairs[m];
                    z->r_sum[truth][k][m] += r[m] * (double)pairs[m];
                    z->pairs[truth][k][m] += pairs[m];
                }
        }
}

double dia_coalign_zone(const dia_coalign *z, int truth, int zone, double *c, double *r,
                        long *pairs)
{
    for (int m = 0; m < DIA_COALIGN_BINS; ++m) {
        pairs[m] = z->pairs[truth][zone][m];
        c[m] = pairs[m] > 0 ? z->c_sum[truth][zone][m] / (double)pairs[m] : NAN;
        r[m] = pairs[m] > 0 ? z->r_sum[truth][zone][m] / (double)pairs[m] : NAN;
    }
    return z->lp > 0.0
               ? bdl_dia_coalignment_fit(r, c, pairs, DIA_COALIGN_BINS, 0.0, 1, NULL) / z->lp
               : NAN;
}

static long total_pairs(const long *pairs)
{
    long n = 0;
    for (int m = 0; m < DIA_COALIGN_BINS; ++m)
        n += pairs[m];
    return n;
}

bdl_result dia_coalign_report(const dia_coalign *z, const char *out)
{
    char path[1200];
    snprintf(path, sizeof path, "%s/coalignment.csv", out);
    bdl_atomic_file af;
    bdl_result r = bdl_atomic_open_csv(&af, path,
                                       "zone,r_over_lp,c_detected,pairs_detected,c_truth,"
                                       "pairs_truth");
    if (r != BDL_OK)
        return r;
    printf("coalignment by the reference rod's distance from the nearer side wall (the image's "
           "edges), C(r) pooled over all frames, length (A = 1) in rod lengths:\n");
    for (int k = 0; k < DIA_ZONES; ++k) {
        double c[2][DIA_COALIGN_BINS], rm[2][DIA_COALIGN_BINS], xi[2];
        long pairs[2][DIA_COALIGN_BINS];
        for (int t = 0; t < 2; ++t)
            xi[t] = dia_coalign_zone(z, t, k, c[t], rm[t], pairs[t]);
        printf("  %-3s L_p: detected %.2f (%ld pairs), true wall rods %.2f (%ld pairs)\n",
               zone_names[k], xi[0], total_pairs(pairs[0]), xi[1], total_pairs(pairs[1]));
        for (int m = 0; m < DIA_COALIGN_BINS; ++m)
            fprintf(af.file, "%s,%.4f,%.6g,%ld,%.6g,%ld\n", zone_names[k],
                    (m + 0.5) * 5.0 / DIA_COALIGN_BINS, c[0][m], pairs[0][m], c[1][m], pairs[1][m]);
    }
    r = bdl_atomic_commit(&af);
    printf("C(r) per zone: %s\n", path);
    return r;
}

/// `"key": "word"` in a small flat JSON text.
static int json_is(const char *text, const char *key, const char *word)
{
    char pattern[96];
    snprintf(pattern, sizeof pattern, "\"%s\": \"%s\"", key, word);
    return strstr(text, pattern) != NULL;
}

bdl_result dia_flux_read_fit(const char *path, dia_flux_fit *fit)
{
    char *json = bdl_analyze_read_regular(path, "--fit");
    if (!json)
        return BDL_ERR_ARGS;
    memset(fit, 0, sizeof *fit);
    fit->fit = (bdl_dia_fit){BDL_DIA_MODEL_RATIONAL, {NAN, NAN}, 0, 0, 0, 0, 1};
    const char *rational = strstr(json, "\"rational\":");
    double window = 0.0, normalise = 0.0;
    fit->adaptive = json_is(json, "method", "adaptive");
    fit->layer = json_is(json, "measure", "layer");
    const int ok = (fit->adaptive || json_is(json, "method", "otsu")) &&
                   (fit->layer || json_is(json, "measure", "depth")) &&
                   bdl_analyze_json_number(json, "window", &window) &&
                   bdl_analyze_json_number(json, "offset", &fit->offset) &&
                   bdl_analyze_json_number(json, "normalise", &normalise) &&
                   bdl_analyze_json_number(json, "cap", &fit->cap) && rational &&
                   bdl_analyze_json_number(rational, "p0", &fit->fit.p[0]) &&
                   bdl_analyze_json_number(rational, "p1", &fit->fit.p[1]) && fit->cap > 0.0 &&
                   window >= 1.0 && isfinite(fit->fit.p[0]) && isfinite(fit->fit.p[1]);
    free(json);
    fit->window = (int)window, fit->normalise = normalise != 0.0;
    if (!ok) {
        fprintf(stderr,
                "error: --fit %s: not a fit of bedlam calibrate (method, window, offset, measure, "
                "normalise, cap, rational p0 and p1)\n",
                path);
        return BDL_ERR_ARGS;
    }
    return BDL_OK;
}

bdl_result dia_flux_open(const bdl_analyze_opts *o, dia_flux **fx)
{
    *fx = NULL;
    if (!o->fit) {
        if (isfinite(o->density))
            fprintf(stderr, "warning: --density is used with --fit only\n");
        return BDL_OK;
    }
    if (!(o->density > 0.0) || !isfinite(o->density)) {
        fprintf(stderr, "error: --fit needs --density RHO, the particles' density [kg/m^3]\n");
        return BDL_ERR_ARGS;
    }
    dia_flux_fit fit;
    const bdl_result r = dia_flux_read_fit(o->fit, &fit);
    if (r != BDL_OK)
        return r;
    if (!(*fx = calloc(1, sizeof **fx)))
        return BDL_ERR_NOMEM;
    (*fx)->fit = fit, (*fx)->density = o->density;
    return BDL_OK;
}

void dia_flux_free(dia_flux *fx)
{
    if (!fx)
        return;
    free(fx->image_sum), free(fx->truth_sum), free(fx->frames), free(fx->x), free(fx->z);
    free(fx);
}

/// The per-cell arrays and the cells' centres, at the first frame; BDL_ERR_ARGS when the cells
/// table does not match the camera's grid (or an earlier frame's).
static bdl_result flux_cells(dia_flux *fx, const dia_camera *cam, const dia_table *cells)
{
    const long n = (long)cam->cells[0] * cam->cells[1];
    if (cells->rows != n || !cells->col[DIA_DV] || (fx->cells > 0 && fx->cells != n))
        return BDL_ERR_ARGS;
    if (fx->cells > 0)
        return BDL_OK;
    fx->image_sum = calloc((size_t)n, sizeof(double));
    fx->truth_sum = calloc((size_t)n, sizeof(double));
    fx->frames = calloc((size_t)n, sizeof(long));
    fx->x = malloc((size_t)n * sizeof(double));
    fx->z = malloc((size_t)n * sizeof(double));
    if (!fx->image_sum || !fx->truth_sum || !fx->frames || !fx->x || !fx->z)
        return BDL_ERR_NOMEM;
    for (long c = 0; c < n; ++c) {
        const double u = 0.5 * (cells->col[DIA_U0][c] + cells->col[DIA_U1][c]);
        const double v = 0.5 * (cells->col[DIA_V0][c] + cells->col[DIA_V1][c]);
        fx->x[c] = bdl_v3_dot(cam->position, cam->right) + (u - 0.5 * cam->width) * cam->pixel_size;
        fx->z[c] = dia_row_height(cam, v);
    }
    fx->cells = n, fx->nx = cam->cells[0], fx->ny = cam->cells[1];
    return BDL_OK;
}

/// f2D per image cell as bedlam calibrate measures it: the fit's threshold, the fraction of
/// particle pixels per cell, and with `normalise` the scaling of the image's f2D to the solids
/// the truth puts in it (the fit's measure: solids_depth or solids_layer).
static bdl_result image_f2d(const dia_flux_fit *fit, const dia_camera *cam, const double *img,
                            const dia_table *cells, double *f2d)
{
    const int nx = cam->cells[0], ny = cam->cells[1];
    const double *truth = cells->col[fit->layer ? DIA_LAYER : DIA_DEPTH];
    if (fit->normalise && !truth)
        return BDL_ERR_ARGS;
    unsigned char *mask = malloc((size_t)cam->width * (size_t)cam->height);
    if (!mask)
        return BDL_ERR_NOMEM;
    bdl_dia_threshold(img, cam->width, cam->height, !cam->back_lit, fit->adaptive ? fit->window : 0,
                      fit->offset, mask);
    bdl_dia_cell_fractions(mask, cam->width, cam->height, nx, ny, f2d);
    free(mask);
    if (fit->normalise) { // as calibrate's add_frame
        double s2 = 0.0, s3 = 0.0;
        for (long c = 0; c < (long)nx * ny; ++c)
            s2 += f2d[c], s3 += truth[c];
        for (long c = 0; s2 > 0.0 && c < (long)nx * ny; ++c)
            f2d[c] *= s3 / s2;
    }
    return BDL_OK;
}

bdl_result dia_flux_add(dia_flux *fx, const dia_camera *cam, const double *img,
                        const bdl_dia_piv_field *f, const dia_table *cells)
{
    bdl_result r = flux_cells(fx, cam, cells);
    if (r != BDL_OK)
        return r;
    double *f2d = malloc((size_t)fx->cells * sizeof(double));
    if (!f2d)
        return BDL_ERR_NOMEM;
    if ((r = image_f2d(&fx->fit, cam, img, cells, f2d)) != BDL_OK) {
        free(f2d);
        return r;
    }
    const double s = cam->pixel_size, to_ms = s / cam->pair_dt;
    for (long c = 0; c < fx->cells; ++c) {
        double du, dv;
        if (!(cells->col[DIA_VISIBLE][c] > 0.0)) {
            ++fx->no_particles;
            continue;
        }
        if (dia_piv_cell_mean(f, cells->col[DIA_U0][c], cells->col[DIA_V0][c],
                              cells->col[DIA_U1][c], cells->col[DIA_V1][c], &du, &dv) == 0) {
            ++fx->no_vector;
            continue;
        }
        const double f3d = bdl_dia_fit_apply(&fx->fit.fit, f2d[c], fx->fit.cap);
        // image v points down: the upward velocity is -dv
        double eps[2] = {1.0 - f3d, 1.0 - cells->col[DIA_DEPTH][c]};
        double vu[2] = {du * to_ms, cells->col[DIA_DU][c] * s};
        double vw[2] = {-dv * to_ms, -cells->col[DIA_DV][c] * s}, fu[2], fw[2];
        bdl_dia_mass_flux(eps, vu, vw, 2, fx->density, fu, fw);
        fx->image_sum[c] += fw[0], fx->truth_sum[c] += fw[1], ++fx->frames[c], ++fx->used;
        fx->f3d_image += f3d, fx->f3d_truth += cells->col[DIA_DEPTH][c];
        fx->w_image += vw[0], fx->w_truth += vw[1];
    }
    free(f2d);
    return BDL_OK;
}

static bdl_result flux_csv(const dia_flux *fx, const char *out)
{
    char path[1200];
    snprintf(path, sizeof path, "%s/mass_flux.csv", out);
    bdl_atomic_file af;
    bdl_result r = bdl_atomic_open_csv(
        &af, path, "i,j,x_center_m,z_center_m,flux_z_image,flux_z_truth,frames");
    if (r != BDL_OK)
        return r;
    for (long c = 0; c < fx->cells; ++c) {
        const double n = (double)fx->frames[c];
        fprintf(af.file, "%ld,%ld,%.6g,%.6g,%.6g,%.6g,%ld\n", c % fx->nx, c / fx->nx, fx->x[c],
                fx->z[c], n > 0 ? fx->image_sum[c] / n : NAN, n > 0 ? fx->truth_sum[c] / n : NAN,
                fx->frames[c]);
    }
    r = bdl_atomic_commit(&af);
    printf("per cell: %s\n", path);
    return r;
}

/// The time-mean upward flux across the width at the row of cells nearest `height`.
static void flux_profile(const dia_flux *fx, double height)
{
    long row = 0;
    for (long j = 1; j < fx->ny; ++j)
        if (fabs(fx->z[j * fx->nx] - height) < fabs(fx->z[row * fx->nx] - height))
            row = j;
    printf("time-mean upward solids mass flux [kg/(m^2 s)] across the width at z = %.4f m (cell "
           "row %ld, the nearest to %.4f m):\n  x [mm]      image      truth  frames\n",
           fx->z[row * fx->nx], row, height);
    for (long i = 0; i < fx->nx; ++i) {
        const long c = row * fx->nx + i;
        if (fx->frames[c] > 0)
            printf("  %6.1f  %9.2f  %9.2f  %6ld\n", 1e3 * fx->x[c],
                   fx->image_sum[c] / (double)fx->frames[c],
                   fx->truth_sum[c] / (double)fx->frames[c], fx->frames[c]);
        else
            printf("  %6.1f  %9s  %9s  %6d\n", 1e3 * fx->x[c], "-", "-", 0);
    }
}

/// The time-mean upward flux of the cells with data, image against truth: the rms difference
/// relative to the truth's rms, and the correlation coefficient.
static void flux_errors(const dia_flux *fx)
{
    double sd = 0.0, si = 0.0, st = 0.0, sii = 0.0, stt = 0.0, sit = 0.0;
    long n = 0;
    for (long c = 0; c < fx->cells; ++c) {
        if (fx->frames[c] == 0)
            continue;
        const double a = fx->image_sum[c] / (double)fx->frames[c];
        const double b = fx->truth_sum[c] / (double)fx->frames[c];
        sd += (a - b) * (a - b), si += a, st += b, sii += a * a, stt += b * b, sit += a * b;
        ++n;
    }
    if (n == 0) {
        printf("no cell with both a PIV vector and visible particles: no mass flux\n");
        return;
    }
    const double cov = sit - si * st / n, vi = sii - si * si / n, vt = stt - st * st / n;
    const double corr = vi > 0.0 && vt > 0.0 ? cov / sqrt(vi * vt) : NAN; // NAN: one is uniform
    printf("time-mean upward flux over the %ld cells with data: rms difference %.2f kg/(m^2 s) = "
           "%.1f %% of the truth's rms (%.2f); correlation %.3f\n",
           n, sqrt(sd / n), 100.0 * sqrt(sd / stt), sqrt(stt / n), corr);
}

bdl_result dia_flux_report(const dia_flux *fx, double height, const char *out)
{
    if (fx->cells == 0) {
        printf("mass flux: no double frame with PIV\n");
        return BDL_OK;
    }
    const double used = fx->used > 0 ? (double)fx->used : NAN;
    printf("mass flux rho_p (1 - eps) v, eps from the fit f3D = %.5g f2D/(%.5g - f2D) capped at "
           "%.3f (%s threshold%s), rho_p %.0f kg/m^3: %ld cell-frames with a PIV vector and "
           "visible particles; skipped %ld without visible particles, %ld without a PIV vector\n",
           fx->fit.fit.p[0], fx->fit.fit.p[1], fx->fit.cap, fx->fit.adaptive ? "adaptive" : "Otsu",
           fx->fit.normalise ? ", f2D normalised to the solids in the image" : "", fx->density,
           fx->used, fx->no_particles, fx->no_vector);
    printf("  their mean solids fraction %.4f from the image, %.4f true; mean upward velocity "
           "%.4f m/s by PIV, %.4f m/s true\n",
           fx->f3d_image / used, fx->f3d_truth / used, fx->w_image / used, fx->w_truth / used);
    flux_profile(fx, height);
    flux_errors(fx);
    return flux_csv(fx, out);
}
