// bedlam analyze ptv CAMERA_DIR — particle tracking velocimetry as the thesis did it (Mahajan
// 2019, ch. 2.3: rods detected in every frame of a high-speed camera, nearest-neighbour links,
// tracks of at least four frames, the 2D coordination number of the tracked particles; dia/ptv.h)
// on a synthetic camera's single images, scored against the truth written beside them: which
// particle each detection is, whether a link joins the same particle in both frames, the tracks'
// velocities against the particles' true velocities, and the coordination numbers of the tracked
// rods against those of the true rods along the wall.
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app/analyze.h"
#include "app/analyze_files.h"
#include "core/file.h"
#include "core/vec3.h"
#include "dia/orient.h"
#include "dia/points.h"
#include "dia/ptv.h"
#include "io/png.h"

enum { CN_CLASSES = 3 }; // the thesis's colour classes: dilute < 5, medium 5-8, dense >= 9

static int cn_class(double cn) { return cn < 5.0 ? 0 : cn < 9.0 ? 1 : 2; }

/// What the analysis needs of camera.json.
typedef struct ptv_camera {
    int width, height;
    double pixel_size;
    double right[3], down[3];
} ptv_camera;

/// Detections of all frames, frame after frame, with the truth each one is matched to.
typedef struct ptv_points {
    long frames, n, cap;
    long *start;     ///< frames + 1 offsets
    double *time;    ///< per frame [s]
    double *u, *v;   ///< centroids [px]
    long *id;        ///< the true particle (id column), -1 when none lies within reach
    double *tu, *tv; ///< its true velocity in the image [px/s]
    double lp;       ///< a rod's length [px]
    long truth_cn_n[CN_CLASSES];
    double truth_cn_sum, truth_w_sum[CN_CLASSES];
    long truth_n;
} ptv_points;

static bdl_result read_camera(const char *dir, ptv_camera *cam)
{
    char text[8192];
    double w = 0.0, h = 0.0;
    const int ok =
        bdl_analyze_read_text(dir, "camera.json", text, sizeof text) &&
        bdl_analyze_json_number(text, "width", &w) && bdl_analyze_json_number(text, "height", &h) &&
        bdl_analyze_json_number(text, "pixel_size", &cam->pixel_size) &&
        bdl_analyze_json_vec3(text, "right", cam->right) &&
        bdl_analyze_json_vec3(text, "down", cam->down) && strstr(text, "\"orthographic\"");
    if (!ok) {
        fprintf(stderr,
                "error: %s/camera.json: not the camera.json of an orthographic dia camera\n", dir);
        return BDL_ERR_ARGS;
    }
    cam->width = (int)w, cam->height = (int)h;
    return BDL_OK;
}

static int grow_points(ptv_points *p, long more)
{
    if (p->n + more <= p->cap)
        return 1;
    const size_t cap = (size_t)(2 * (p->n + more));
    double **arrays[4] = {&p->u, &p->v, &p->tu, &p->tv};
    for (int k = 0; k < 4; ++k) {
        double *grown = realloc(*arrays[k], cap * sizeof(double));
        if (!grown)
            return 0; // the arrays grown so far stay valid: cap is unchanged
        *arrays[k] = grown;
    }
    long *id = realloc(p->id, cap * sizeof(long));
    if (!id)
        return 0;
    p->id = id, p->cap = (long)cap;
    return 1;
}

/// The truth of one image: column k of the particles file is col[k].
enum { T_ID, T_U, T_V, T_VIS, T_VX, T_VY, T_VZ, T_UX, T_UY, T_UZ, T_HALF, T_R, T_COLS };
static const char *const truth_columns[T_COLS] = {"id", "u",  "v",           "visible_fraction",
                                                  "vx", "vy", "vz",          "ux",
                                                  "uy", "uz", "half_length", "radius"};

typedef struct truth {
    long n;
    double *col[T_COLS];
} truth;

static void free_truth(truth *t)
{
    for (int c = 0; c < T_COLS; ++c)
        free(t->col[c]);
}

static int read_truth(const char *dir, const char *file, truth *t)
{
    memset(t, 0, sizeof *t);
    for (int c = 0; c < T_COLS; ++c) {
        long n = 0;
        if (!bdl_analyze_read_column(dir, file, truth_columns[c], &t->col[c], &n) ||
            (c > 0 && n != t->n)) {
            free_truth(t);
            return 0;
        }
        t->n = n;
    }
    return 1;
}

static double dot3(const double *a, double x, double y, double z)
{
    return a[0] * x + a[1] * y + a[2] * z;
}

/// Matches detections p->u/v[from ..) of a frame to the nearest visible true particle within
/// half a rod length (a blob's centroid lies on the visible part of its rod).
static bdl_result match_truth(ptv_points *p, long from, const truth *t, const ptv_camera *cam)
{
    bdl_dia_point_grid g;
    bdl_result r = bdl_dia_point_grid_build(&g, t->col[T_U], t->col[T_V], t->n, 0.5 * p->lp);
    for (long k = from; r == BDL_OK && k < p->n; ++k) {
        int cx0, cx1, cy0, cy1;
        long best = -1;
        double best_d = 0.5 * p->lp;
        bdl_dia_point_grid_range(&g, p->u[k], p->v[k], best_d, &cx0, &cx1, &cy0, &cy1);
        for (int cy = cy0; cy <= cy1; ++cy)
            for (int cx = cx0; cx <= cx1; ++cx)
                for (long m = g.start[cy * g.nx + cx]; m < g.start[cy * g.nx + cx + 1]; ++m) {
                    const long q = g.index[m];
                    const double d = hypot(t->col[T_U][q] - p->u[k], t->col[T_V][q] - p->v[k]);
                    if (t->col[T_VIS][q] >= 0.3 && d < best_d)
                        best = q, best_d = d;
                }
        p->id[k] = best >= 0 ? lround(t->col[T_ID][best]) : -1;
        p->tu[k] = p->tv[k] = NAN;
        if (best >= 0) {
            const double vx = t->col[T_VX][best], vy = t->col[T_VY][best], vz = t->col[T_VZ][best];
            p->tu[k] = dot3(cam->right, vx, vy, vz) / cam->pixel_size;
            p->tv[k] = dot3(cam->down, vx, vy, vz) / cam->pixel_size;
        }
    }
    bdl_dia_point_grid_free(&g);
    return r;
}

/// The coordination number of the true rods along the wall (mostly visible, axis within 20
/// degrees of the image plane) in one frame, by class, with their upward velocities [m/s].
static void truth_coordination(ptv_points *p, const truth *t, const ptv_camera *cam)
{
    double *u = malloc((size_t)t->n * 3 * sizeof(double));
    if (!u)
        return;
    double *v = u + t->n, *cn = u + 2 * t->n, *w = NULL;
    long n = 0;
    double forward[3] = {cam->right[1] * cam->down[2] - cam->right[2] * cam->down[1],
                         cam->right[2] * cam->down[0] - cam->right[0] * cam->down[2],
                         cam->right[0] * cam->down[1] - cam->right[1] * cam->down[0]};
    w = malloc((size_t)t->n * sizeof(double));
    for (long k = 0; w && k < t->n; ++k) {
        const double ax = dot3(forward, t->col[T_UX][k], t->col[T_UY][k], t->col[T_UZ][k]);
        if (!(t->col[T_VIS][k] >= 0.7) || !(t->col[T_HALF][k] > 0.0) ||
            fabs(ax) > sin(20.0 * BDL_PI / 180.0))
            continue;
        u[n] = t->col[T_U][k], v[n] = t->col[T_V][k];
        w[n++] = -dot3(cam->down, t->col[T_VX][k], t->col[T_VY][k], t->col[T_VZ][k]);
    }
    const double bounds[4] = {0.0, 0.0, cam->width, cam->height};
    if (w && n > 0 && bdl_dia_coordination_2d(u, v, n, p->lp, bounds, cn) == BDL_OK)
        for (long k = 0; k < n; ++k) {
            const int c = cn_class(cn[k]);
            p->truth_cn_n[c]++, p->truth_w_sum[c] += w[k], p->truth_cn_sum += cn[k];
            p->truth_n++;
        }
    free(u), free(w);
}

/// Detects the rods of frame `frame` (its image and truth in dir) and appends them to p.
static int add_frame(const char *dir, long frame, double time, const ptv_camera *cam, ptv_points *p)
{
    char name[64], path[1300];
    snprintf(name, sizeof name, "frame_%06ld.png", frame);
    snprintf(path, sizeof path, "%s/%s", dir, name);
    double *img = NULL;
    int w, h, bits;
    truth t;
    snprintf(name, sizeof name, "frame_%06ld_particles.csv", frame);
    if (bdl_png_read_gray(path, &img, &w, &h, &bits) != BDL_OK || w != cam->width ||
        h != cam->height || !read_truth(dir, name, &t)) {
        free(img);
        return 0;
    }
    if (p->lp == 0.0)
        for (long k = 0; k < t.n && p->lp == 0.0; ++k)
            if (t.col[T_HALF][k] > 0.0)
                p->lp = 2.0 * (t.col[T_HALF][k] + t.col[T_R][k]) / cam->pixel_size;
    bdl_dia_rod *found = malloc((size_t)(t.n + 1) * sizeof(bdl_dia_rod));
    long count = 0;
    bdl_dia_orient_def def = bdl_default_orient_def();
    def.min_area = (long)(0.3 * p->lp * p->lp / 4.0); // a third of a rod seen broadside
    def.min_aspect = 1.8;
    int ok = found && p->lp > 0.0 &&
             bdl_dia_detect_rods(img, w, h, &def, found, t.n + 1, &count) == BDL_OK;
    count = count < t.n + 1 ? count : t.n + 1;
    ok = ok && grow_points(p, count);
    const long from = p->n;
    for (long k = 0; ok && k < count; ++k)
        p->u[p->n] = found[k].u, p->v[p->n] = found[k].v, p->n++;
    ok = ok && match_truth(p, from, &t, cam) == BDL_OK;
    if (ok) {
        truth_coordination(p, &t, cam);
        p->time[p->frames] = time;
        p->start[++p->frames] = p->n;
    } else
        p->n = from;
    free(found), free(img), free_truth(&t);
    return ok;
}

/// Scores of the links and tracks.
typedef struct ptv_scores {
    long links, known_links, right_links, tracks, pure_tracks, points;
    double *vel_err; ///< |track velocity - true velocity| per interior point [m/s]
    double speed_sum;
    long vel_n;
    long cn_n[CN_CLASSES];
    double cn_sum, w_sum[CN_CLASSES];
    long cn_points;
} ptv_scores;

/// Frame of point k.
static long frame_of(const ptv_points *p, long k)
{
    long lo = 0, hi = p->frames; // start[lo] <= k < start[hi]
    while (hi - lo > 1) {
        const long mid = (lo + hi) / 2;
        *(p->start[mid] <= k ? &lo : &hi) = mid;
    }
    return lo;
}

/// Link and track purity; velocities by central differences along the tracks. vel_u/vel_v get
/// each tracked point's velocity [px/s] (NAN at a track's ends).
static void score_tracks(const ptv_points *p, const bdl_dia_tracks *tr, const ptv_camera *cam,
                         double *vel_u, double *vel_v, ptv_scores *s)
{
    for (long k = 0; k < p->n; ++k)
        vel_u[k] = vel_v[k] = NAN;
    for (long t = 0; t < tr->count; ++t) {
        const long a = tr->start[t], b = tr->start[t + 1];
        int pure = p->id[tr->point[a]] >= 0;
        for (long m = a; m + 1 < b; ++m) {
            const long i = tr->point[m], j = tr->point[m + 1];
            s->links++;
            if (p->id[i] >= 0 && p->id[j] >= 0) {
                s->known_links++;
                s->right_links += p->id[i] == p->id[j];
            }
            pure = pure && p->id[i] == p->id[j];
        }
        s->tracks++, s->pure_tracks += pure, s->points += b - a;
        for (long m = a + 1; m + 1 < b; ++m) {
            const long i = tr->point[m - 1], j = tr->point[m + 1], k = tr->point[m];
            const double dt = p->time[frame_of(p, j)] - p->time[frame_of(p, i)];
            vel_u[k] = (p->u[j] - p->u[i]) / dt, vel_v[k] = (p->v[j] - p->v[i]) / dt;
            if (p->id[k] < 0 || !isfinite(p->tu[k]))
                continue;
            s->vel_err[s->vel_n++] =
                hypot(vel_u[k] - p->tu[k], vel_v[k] - p->tv[k]) * cam->pixel_size;
            s->speed_sum += hypot(p->tu[k], p->tv[k]) * cam->pixel_size;
        }
    }
}

/// 2D coordination numbers of the tracked points frame by frame, by class, with the upward
/// velocity of each class; one row per tracked point to `rows`.
static void score_coordination(const ptv_points *p, const bdl_dia_tracks *tr, const ptv_camera *cam,
                               const double *vel_v, FILE *rows, ptv_scores *s)
{
    double *u = malloc((size_t)(p->n + 1) * 3 * sizeof(double));
    long *which = malloc((size_t)(p->n + 1) * sizeof(long));
    const double bounds[4] = {0.0, 0.0, cam->width, cam->height};
    for (long f = 0; u && which && f < p->frames; ++f) {
        double *v = u + p->n + 1, *cn = v + p->n + 1;
        long n = 0;
        for (long k = p->start[f]; k < p->start[f + 1]; ++k)
            if (tr->track[k] >= 0)
                u[n] = p->u[k], v[n] = p->v[k], which[n++] = k;
        if (n == 0 || bdl_dia_coordination_2d(u, v, n, p->lp, bounds, cn) != BDL_OK)
            continue;
        for (long m = 0; m < n; ++m) {
            const long k = which[m];
            const double w = -vel_v[k] * cam->pixel_size; // upward [m/s]: v grows downward
            fprintf(rows, "%ld,%ld,%.3f,%.3f,%ld,%.4g,%.6g\n", tr->track[k], f, p->u[k], p->v[k],
                    p->id[k], cn[m], w);
            s->cn_sum += cn[m], s->cn_points++;
            if (isfinite(w)) {
                const int c = cn_class(cn[m]);
                s->cn_n[c]++, s->w_sum[c] += w;
            }
        }
    }
    free(u), free(which);
}

static int compare_doubles(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

static void report(const ptv_points *p, const ptv_scores *s, double max_step)
{
    printf("PTV over %ld frames: %ld rods detected (%.0f per frame), links of at most %.1f px "
           "(%.2f rod lengths), %ld tracks of 4 frames or more holding %ld detections (%.1f frames "
           "each)\n",
           p->frames, p->n, (double)p->n / (double)p->frames, max_step, max_step / p->lp, s->tracks,
           s->points, s->tracks ? (double)s->points / (double)s->tracks : 0.0);
    printf("links joining the same particle: %.2f %% of %ld links whose both ends lie on a "
           "particle (%ld links in all); tracks on one particle throughout: %.1f %%\n",
           s->known_links ? 100.0 * s->right_links / s->known_links : 0.0, s->known_links, s->links,
           s->tracks ? 100.0 * s->pure_tracks / s->tracks : 0.0);
    if (s->vel_n > 0) {
        qsort(s->vel_err, (size_t)s->vel_n, sizeof(double), compare_doubles);
        printf("velocity from the tracks against the particles' true velocity, %ld points: "
               "median error %.4f m/s, 90th percentile %.4f m/s (mean true speed %.4f m/s)\n",
               s->vel_n, s->vel_err[s->vel_n / 2], s->vel_err[(long)(0.9 * (s->vel_n - 1))],
               s->speed_sum / s->vel_n);
    }
    static const char *const names[CN_CLASSES] = {"dilute (< 5)", "medium (5-8)", "dense (>= 9)"};
    const long tn = s->cn_n[0] + s->cn_n[1] + s->cn_n[2];
    printf("2D coordination number (neighbours within one rod length, wall-corrected): tracked "
           "rods %.2f, true rods along the wall %.2f\n",
           s->cn_points ? s->cn_sum / s->cn_points : 0.0,
           p->truth_n ? p->truth_cn_sum / p->truth_n : 0.0);
    for (int c = 0; c < CN_CLASSES; ++c)
        printf("  %-13s tracked %5.1f %% rising at %+.3f m/s | truth %5.1f %% rising at %+.3f "
               "m/s\n",
               names[c], tn ? 100.0 * s->cn_n[c] / tn : 0.0,
               s->cn_n[c] ? s->w_sum[c] / s->cn_n[c] : 0.0,
               p->truth_n ? 100.0 * p->truth_cn_n[c] / p->truth_n : 0.0,
               p->truth_cn_n[c] ? p->truth_w_sum[c] / p->truth_cn_n[c] : 0.0);
}

/// Reads every frame listed in dir/frames.csv into p.
static bdl_result read_frames(const char *dir, const ptv_camera *cam, ptv_points *p)
{
    double *frame = NULL, *time = NULL;
    long frames = 0, times = 0;
    if (!bdl_analyze_read_column(dir, "frames.csv", "frame", &frame, &frames) ||
        !bdl_analyze_read_column(dir, "frames.csv", "time", &time, &times) || times != frames) {
        free(frame), free(time);
        return BDL_ERR_ARGS;
    }
    p->start = calloc((size_t)frames + 1, sizeof(long));
    p->time = malloc((size_t)frames * sizeof(double));
    bdl_result r = p->start && p->time ? BDL_OK : BDL_ERR_NOMEM;
    for (long k = 0; r == BDL_OK && k < frames; ++k)
        if (k > 0 && frame[k] == frame[k - 1]) {
            fprintf(stderr, "error: %s: double frames (PIV pairs); PTV needs single images\n", dir);
            r = BDL_ERR_ARGS;
        } else if (!add_frame(dir, lround(frame[k]), time[k], cam, p))
            fprintf(stderr, "warning: frame %ld: its files are missing or unreadable\n",
                    lround(frame[k]));
    if (r == BDL_OK && p->frames < 4) {
        fprintf(stderr, "error: %s: %ld readable frames; tracks need 4\n", dir, p->frames);
        r = BDL_ERR_ARGS;
    }
    free(frame), free(time);
    return r;
}

static void free_points(ptv_points *p)
{
    free(p->start), free(p->time), free(p->u), free(p->v), free(p->id), free(p->tu), free(p->tv);
}

bdl_result bdl_analyze_ptv(const bdl_analyze_opts *o)
{
    ptv_camera cam;
    ptv_points p = {0};
    bdl_result r = read_camera(o->run, &cam);
    if (r == BDL_OK)
        r = read_frames(o->run, &cam, &p);
    if (r != BDL_OK) {
        free_points(&p);
        return r;
    }
    const double max_step = o->max_step > 0.0 ? o->max_step : 0.5 * p.lp;
    bdl_dia_tracks tr;
    r = bdl_dia_ptv_link(p.u, p.v, p.start, p.frames, max_step, 4, &tr);
    ptv_scores s = {.vel_err = malloc((size_t)(p.n + 1) * sizeof(double))};
    double *vel = malloc((size_t)(p.n + 1) * 2 * sizeof(double));
    char path[1200];
    snprintf(path, sizeof path, "%s/ptv_tracks.csv", o->out);
    bdl_atomic_file af;
    if (r == BDL_OK && (!s.vel_err || !vel))
        r = BDL_ERR_NOMEM;
    if (r == BDL_OK &&
        (r = bdl_atomic_open_csv(&af, path, "track,frame,u,v,true_id,coordination,w")) == BDL_OK) {
        score_tracks(&p, &tr, &cam, vel, vel + p.n + 1, &s);
        score_coordination(&p, &tr, &cam, vel + p.n + 1, af.file, &s);
        r = bdl_atomic_commit(&af);
        report(&p, &s, max_step);
        printf("per tracked point: %s\n", path);
    }
    bdl_dia_tracks_free(&tr);
    free(s.vel_err), free(vel), free_points(&p);
    return r;
}
