// bedlam analyze dia CAMERA_DIR — the image-analysis chain of the thesis (dia/bed_height.h,
// dia/orient.h, dia/piv.h) run on a synthetic camera's images and scored against the truth
// written beside them: the bed height from the row-averaged intensity gradient against the same
// definition on the true solids fraction, the orientation of the rods lying along the front wall
// (detection rate, angle error), PIV against the true velocities of what the camera sees per
// cell, and the coalignment length of the detected rods against that of the true ones; by wall
// zone, and with a calibration fit the solids mass flux, in analyze_dia_flux.c.
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app/analyze.h"
#include "app/analyze_dia.h"
#include "app/analyze_files.h"
#include "core/file.h"
#include "core/vec3.h"
#include "dia/bed_height.h"
#include "dia/orient.h"
#include "dia/piv.h"
#include "io/png.h"

static int json_vec(const char *text, const char *key, bdl_vec3 *out)
{
    double v[3];
    if (!bdl_analyze_json_vec3(text, key, v))
        return 0;
    *out = bdl_v3(v[0], v[1], v[2]);
    return 1;
}

static bdl_result read_camera(const char *dir, dia_camera *cam)
{
    char text[8192];
    double w = 0, h = 0;
    const int read = bdl_analyze_read_text(dir, "camera.json", text, sizeof text);
    const char *cells = strstr(text, "\"cells\":");
    const int ok = read && bdl_analyze_json_number(text, "width", &w) &&
                   bdl_analyze_json_number(text, "height", &h) &&
                   bdl_analyze_json_number(text, "pixel_size", &cam->pixel_size) &&
                   bdl_analyze_json_number(text, "pair_dt", &cam->pair_dt) &&
                   json_vec(text, "position", &cam->position) &&
                   json_vec(text, "right", &cam->right) && json_vec(text, "down", &cam->down) &&
                   json_vec(text, "forward", &cam->forward) && cells &&
                   sscanf(cells + 8, " [%d, %d]", &cam->cells[0], &cam->cells[1]) == 2 &&
                   strstr(text, "\"orthographic\"");
    if (!ok) {
        fprintf(stderr,
                "error: %s/camera.json: not the camera.json of an orthographic dia camera\n", dir);
        return BDL_ERR_ARGS;
    }
    cam->width = (int)w, cam->height = (int)h;
    cam->back_lit = strstr(text, "\"lighting\": \"back\"") != NULL;
    return BDL_OK;
}

/// Reads the columns `names` of DIR/FILE (bdl_analyze_read_column); 0 when the first is missing.
/// The columns must have the same length as the first (else they are left out, NULL).
static int read_table(const char *dir, const char *file, const char *const *names, int count,
                      dia_table *t)
{
    memset(t, 0, sizeof *t);
    for (int c = 0; c < count; ++c) {
        long n = 0;
        if (bdl_analyze_read_column(dir, file, names[c], &t->col[c], &n) && c > 0 && n != t->rows) {
            free(t->col[c]);
            t->col[c] = NULL;
        }
        if (c == 0)
            t->rows = t->col[0] ? n : 0;
    }
    return t->rows > 0;
}

static void free_table(dia_table *t)
{
    for (int c = 0; c < 12; ++c)
        free(t->col[c]);
}

/// The angle in the image of a rod of world axis a: 0 upright, +-90 lying, positive leaning right
/// (the convention of dia/orient.h) [deg].
static double image_angle(const dia_camera *cam, bdl_vec3 a)
{
    double angle = atan2(bdl_v3_dot(a, cam->right), -bdl_v3_dot(a, cam->down)) * 180.0 / BDL_PI;
    angle = angle > 90.0 ? angle - 180.0 : angle <= -90.0 ? angle + 180.0 : angle;
    return angle;
}

/// |a - b| of two axis angles, folded to [0, 90] degrees.
static double angle_gap(double a, double b)
{
    double d = fmod(fabs(a - b), 180.0);
    return d > 90.0 ? 180.0 - d : d;
}

/// Scores of all frames together.
typedef struct dia_totals {
    long frames, truth_rods, matched, within10, detections;
    double angle_err, level_err_max, level_err_sum;
    double *level_err; ///< |relative error| of the bed height per frame
    double *piv_err;   ///< |PIV - truth| per cell with particles [px]
    double truth_disp;
    long piv_n, piv_cap;
    double xi_img, xi_truth;
    long xi_frames;
    dia_coalign zones; ///< C(r) by wall zone, pooled
    dia_flux *flux;    ///< with --fit: the solids mass flux
} dia_totals;

/// Bed heights from the image and from the true solids fraction of the cells, the same way [m].
static void bed_heights(const dia_camera *cam, const double *img, const dia_table *cells,
                        double smooth_px, double *from_image, double *truth)
{
    const int nx = cam->cells[0], ny = cam->cells[1];
    const double cell_h = cells->col[3][0] - cells->col[1][0]; // v1 - v0 of row 0 [px]
    *from_image = dia_row_height(cam, bdl_dia_bed_level_image(img, cam->width, cam->height,
                                                              smooth_px, BDL_DIA_RISES_INTO_BED));
    const double level = bdl_dia_bed_level_field(cells->col[5], nx, ny, smooth_px / cell_h);
    *truth = dia_row_height(cam, cells->col[1][0] + level * cell_h);
}

/// The true rods the camera sees lying along the front wall: mostly visible, axis within 20
/// degrees of the image plane. Writes their pixel centres and image angles; returns their count.
static long wall_rods(const dia_camera *cam, const dia_table *parts, double *u, double *v,
                      double *angle)
{
    long n = 0;
    for (long k = 0; k < parts->rows; ++k) {
        const bdl_vec3 a = bdl_v3(parts->col[3][k], parts->col[4][k], parts->col[5][k]);
        if (!(parts->col[2][k] >= 0.7) || !(parts->col[6][k] > 0.0) ||
            fabs(bdl_v3_dot(a, cam->forward)) > sin(20.0 * BDL_PI / 180.0))
            continue;
        u[n] = parts->col[0][k], v[n] = parts->col[1][k], angle[n] = image_angle(cam, a);
        ++n;
    }
    return n;
}

/// Coalignment length of rods at (u, v) with angles, in rod lengths (lp px): C(r) over 0 .. 5 lp.
static double coalignment_length(const double *u, const double *v, const double *angle, long n,
                                 double lp)
{
    enum { BINS = 20 };
    double c[BINS], r[BINS];
    long pairs[BINS];
    if (bdl_dia_coalignment(u, v, angle, n, 5.0 * lp, BINS, -INFINITY, INFINITY, c, pairs, r) !=
        BDL_OK)
        return NAN;
    return bdl_dia_coalignment_fit(r, c, pairs, BINS, 0.0, 1, NULL) / lp;
}

/// Detects the rods of an image and scores them against the true wall rods (the nearest
/// detection within half a rod length not taken by another): adds to the totals.
static void score_rods(const dia_camera *cam, const double *img, const dia_table *parts, double lp,
                       dia_totals *tot)
{
    const long n = parts->rows;
    double *u = malloc((size_t)n * 3 * sizeof(double));
    bdl_dia_rod *found = malloc((size_t)n * sizeof(bdl_dia_rod));
    long count = 0;
    bdl_dia_orient_def def = bdl_default_orient_def();
    def.min_area = (long)(0.3 * lp * lp / 4.0); // a third of a rod seen broadside
    def.min_aspect = 1.8;
    if (!u || !found ||
        bdl_dia_detect_rods(img, cam->width, cam->height, &def, found, n, &count) != BDL_OK) {
        free(u), free(found);
        return;
    }
    count = count < n ? count : n;
    double *v = u + n, *angle = u + 2 * n;
    const long truth = wall_rods(cam, parts, u, v, angle);
    for (long k = 0; k < truth; ++k) {
        long best = -1;
        double best_d2 = 0.25 * lp * lp;
        for (long m = 0; m < count; ++m) {
            const double du = found[m].u - u[k], dv = found[m].v - v[k];
            if (found[m].area > 0 && du * du + dv * dv < best_d2)
                best = m, best_d2 = du * du + dv * dv;
        }
        if (best < 0)
            continue;
        found[best].area = -found[best].area; // taken: one true rod per blob
        const double err = angle_gap(found[best].angle, angle[k]);
        ++tot->matched;
        tot->within10 += err <= 10.0;
        tot->angle_err += err;
    }
    tot->truth_rods += truth;
    tot->detections += count;
    const double xi_truth = coalignment_length(u, v, angle, truth, lp);
    dia_coalign_add(&tot->zones, 1, u, v, angle, truth, lp, cam->width);
    for (long m = 0; m < count; ++m)
        u[m] = found[m].u, v[m] = found[m].v, angle[m] = found[m].angle;
    const double xi_img = coalignment_length(u, v, angle, count, lp);
    dia_coalign_add(&tot->zones, 0, u, v, angle, count, lp, cam->width);
    if (isfinite(xi_img) && isfinite(xi_truth)) {
        tot->xi_img += xi_img, tot->xi_truth += xi_truth;
        ++tot->xi_frames;
    }
    free(u), free(found);
}

/// PIV of a double frame against the true displacement of what the camera sees in each cell
/// (the cells' du, dv times the pair's interval): the PIV vectors whose window centre lies in a
/// cell with visible particles are averaged and compared; the errors go to the totals. With a fit,
/// the mass flux of the pair too.
static void score_piv(const dia_camera *cam, bdl_dia_piv *piv, const double *a, const double *b,
                      const dia_table *cells, dia_totals *tot)
{
    bdl_dia_piv_field f;
    if (bdl_dia_piv_run(piv, a, b, &f) != BDL_OK)
        return;
    if (tot->flux && dia_flux_add(tot->flux, cam, a, &f, cells) != BDL_OK)
        fprintf(stderr, "warning: no mass flux from a frame: its cells do not match the camera or "
                        "lack the fit's truth\n");
    for (long c = 0; c < cells->rows; ++c) {
        double su, sv;
        if (!(cells->col[6][c] > 0.0) ||
            dia_piv_cell_mean(&f, cells->col[0][c], cells->col[1][c], cells->col[2][c],
                              cells->col[3][c], &su, &sv) == 0)
            continue;
        const double tu = cells->col[7][c] * cam->pair_dt, tv = cells->col[8][c] * cam->pair_dt;
        if (tot->piv_n == tot->piv_cap) {
            const long cap = 2 * tot->piv_cap + 256;
            double *grown = realloc(tot->piv_err, (size_t)cap * sizeof(double));
            if (!grown)
                return;
            tot->piv_err = grown, tot->piv_cap = cap;
        }
        tot->piv_err[tot->piv_n++] = hypot(su - tu, sv - tv);
        tot->truth_disp += hypot(tu, tv);
    }
}

static int file_exists(const char *path)
{
    char why[256];
    return bdl_check_regular_file(path, NULL, why, sizeof why) == BDL_OK;
}

static int compare_doubles(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static const char *const particle_columns[] = {"u",  "v",  "visible_fraction", "ux",
                                               "uy", "uz", "half_length",      "radius"};
static const char *const cell_columns[] = {
    "u0", "v0", "u1",          "v1", "area_fraction", "solids_depth", "visible_particles",
    "du", "dv", "solids_layer"};

/// Frame `frame` of the camera in `dir`: the images (a pair when there is one), its particles
/// and cells; scores what it can. Returns 0 when the frame's files are missing.
static int score_frame(const char *dir, long frame, const dia_camera *cam, bdl_dia_piv *piv,
                       FILE *rows, dia_totals *tot)
{
    char stem[1200], path[1300];
    snprintf(stem, sizeof stem, "%s/frame_%06ld", dir, frame);
    snprintf(path, sizeof path, "%s_a.png", stem);
    const int pair = file_exists(path);
    double *a = NULL, *b = NULL;
    int w, h, bits;
    if (!pair)
        snprintf(path, sizeof path, "%s.png", stem);
    if (bdl_png_read_gray(path, &a, &w, &h, &bits) != BDL_OK || w != cam->width ||
        h != cam->height) {
        free(a);
        return 0;
    }
    dia_table parts, cells;
    char file[64];
    snprintf(file, sizeof file, "frame_%06ld%s_particles.csv", frame, pair ? "_a" : "");
    int ok = read_table(dir, file, particle_columns, 8, &parts);
    snprintf(file, sizeof file, "frame_%06ld_cells.csv", frame);
    ok = read_table(dir, file, cell_columns, 10, &cells) && ok;
    long rod = -1;
    for (long k = 0; ok && k < parts.rows && rod < 0; ++k)
        rod = parts.col[6] && parts.col[6][k] > 0.0 ? k : -1;
    ok = ok && parts.col[7] && cells.col[8] && cells.rows == (long)cam->cells[0] * cam->cells[1];
    if (ok) {
        const double lp = rod >= 0 ? 2.0 * (parts.col[6][rod] + parts.col[7][rod]) / cam->pixel_size
                                   : 2.0 * parts.col[7][0] / cam->pixel_size;
        double level_img, level_truth;
        bed_heights(cam, a, &cells, lp, &level_img, &level_truth);
        const double err = (level_img - level_truth) / level_truth;
        tot->level_err_max = fmax(tot->level_err_max, fabs(err));
        tot->level_err_sum += fabs(err);
        double *grown = realloc(tot->level_err, (size_t)(tot->frames + 1) * sizeof(double));
        if (grown)
            tot->level_err = grown, grown[tot->frames] = fabs(err);
        const long matched = tot->matched, truth = tot->truth_rods, piv_n = tot->piv_n;
        if (rod >= 0)
            score_rods(cam, a, &parts, lp, tot);
        snprintf(path, sizeof path, "%s_b.png", stem);
        if (pair && piv && bdl_png_read_gray(path, &b, &w, &h, &bits) == BDL_OK &&
            w == cam->width && h == cam->height)
            score_piv(cam, piv, a, b, &cells, tot);
        fprintf(rows, "%ld,%.6g,%.6g,%.6g,%ld,%ld,%ld\n", frame, level_img, level_truth, err,
                tot->truth_rods - truth, tot->matched - matched, tot->piv_n - piv_n);
        ++tot->frames;
    }
    free_table(&parts), free_table(&cells), free(a), free(b);
    return ok;
}

/// The summary of all frames on stdout.
static void report(const dia_totals *t)
{
    qsort(t->level_err, (size_t)t->frames, sizeof(double), compare_doubles);
    printf("%ld frames: bed height from the images against the same definition on the true solids "
           "fraction: |error| median %.2f %%, mean %.2f %%, largest %.2f %%\n",
           t->frames, 100.0 * t->level_err[t->frames / 2],
           100.0 * t->level_err_sum / (double)t->frames, 100.0 * t->level_err_max);
    if (t->truth_rods > 0)
        printf("rods along the front wall: %ld in the truth, %.1f %% detected, %.1f %% of those "
               "within 10 degrees (mean error %.2f degrees); %ld blobs taken for rods, %.1f %% of "
               "them on a true wall rod\n",
               t->truth_rods, 100.0 * t->matched / t->truth_rods,
               t->matched ? 100.0 * t->within10 / t->matched : 0.0,
               t->matched ? t->angle_err / t->matched : 0.0, t->detections,
               t->detections ? 100.0 * t->matched / t->detections : 0.0);
    if (t->xi_frames > 0)
        printf("coalignment length: %.2f rod lengths from the detected rods, %.2f from the true "
               "ones (mean over %ld frames)\n",
               t->xi_img / t->xi_frames, t->xi_truth / t->xi_frames, t->xi_frames);
    if (t->piv_n > 0) {
        qsort(t->piv_err, (size_t)t->piv_n, sizeof(double), compare_doubles);
        printf("PIV against the true mean displacement of the visible particles, %ld cells: "
               "median error %.3f px, 90th percentile %.3f px (mean true displacement %.3f px)\n",
               t->piv_n, t->piv_err[t->piv_n / 2], t->piv_err[(long)(0.9 * (t->piv_n - 1))],
               t->truth_disp / t->piv_n);
    }
}

bdl_result bdl_analyze_dia(const bdl_analyze_opts *o)
{
    dia_camera cam;
    dia_totals tot = {0};
    char path[1200];
    double *frame = NULL;
    long frames = 0;
    bdl_result r = dia_flux_open(o, &tot.flux);
    if (r == BDL_OK && (r = read_camera(o->run, &cam)) == BDL_OK &&
        !bdl_analyze_read_column(o->run, "frames.csv", "frame", &frame, &frames))
        r = BDL_ERR_ARGS;
    if (r != BDL_OK) {
        dia_flux_free(tot.flux);
        return r;
    }
    bdl_dia_piv *piv = NULL;
    const bdl_dia_piv_def def = bdl_default_piv_def();
    if (cam.pair_dt > 0.0 && bdl_dia_piv_create(&def, cam.width, cam.height, &piv) != BDL_OK)
        fprintf(stderr, "warning: no PIV (the images are smaller than its windows)\n");
    snprintf(path, sizeof path, "%s/dia_scores.csv", o->out);
    bdl_atomic_file af;
    if ((r = bdl_atomic_open_csv(&af, path,
                                 "frame,bed_height_image,bed_height_truth,"
                                 "relative_error,wall_rods,matched,piv_cells")) != BDL_OK) {
        free(frame), bdl_dia_piv_destroy(piv), dia_flux_free(tot.flux);
        return r;
    }
    for (long k = 0; k < frames; ++k)
        if (k > 0 && frame[k] == frame[k - 1])
            continue; // a double frame's second image has a row of its own
        else if (!score_frame(o->run, lround(frame[k]), &cam, piv, af.file, &tot))
            fprintf(stderr, "warning: frame %ld: its files are missing or unreadable\n",
                    lround(frame[k]));
    r = bdl_atomic_commit(&af);
    if (tot.frames == 0 && r == BDL_OK)
        r = BDL_ERR_ARGS;
    if (tot.frames > 0)
        report(&tot);
    printf("per frame: %s\n", path);
    bdl_result w = BDL_OK;
    if (tot.frames > 0 && tot.truth_rods + tot.detections > 0)
        w = dia_coalign_report(&tot.zones, o->out);
    if (tot.frames > 0 && tot.flux && w == BDL_OK)
        w = dia_flux_report(tot.flux, o->height, o->out);
    free(frame), free(tot.piv_err), free(tot.level_err), bdl_dia_piv_destroy(piv);
    dia_flux_free(tot.flux);
    return r != BDL_OK ? r : w;
}
