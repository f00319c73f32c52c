// bedlam calibrate — the 2D-to-3D solids-fraction relation of a pseudo-2D bed from synthetic
// camera images and their ground truth, and its application to other images.
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app/app.h"
#include "dia/analysis.h"
#include "core/file.h"
#include "io/png.h"

static const char calibrate_usage[] =
    "usage: bedlam calibrate DIR [--test DIR2 | --holdout K] [options]\n"
    "       bedlam calibrate --apply FIT.json IMAGE... [--cells NX NY] [--lighting front|back]\n"
    "                        [options]\n"
    "\n"
    "Fits the relation between the solids fraction a camera sees (f2D: the fraction of\n"
    "particle pixels in an image cell after thresholding) and the true solids fraction behind it\n"
    "(f3D, over the bed's depth) on the images and ground truth a run wrote in DIR (dia/NAME of\n"
    "the run folder: camera.json, frames.csv, frame_*_cells.csv). Two models, both capped at\n"
    "--cap: f3D = A f2D / (B - f2D) (Mahajan 2019) and f3D = a f2D^b. Reports A, B (a, b), R^2,\n"
    "the residuals and the f2D where the cap is reached; then applies the fit to held-out frames\n"
    "(every K-th frame of DIR, --holdout K, default 4) or to another image set with truth\n"
    "(--test DIR2) and reports the error in solids fraction, which is the error in voidage.\n"
    "Writes fit.json, points.csv and fit.png (gnuplot).\n"
    "\n"
    "With --apply, reads a fit.json and turns any grey or colour PNG images (a real camera's\n"
    "too: no truth needed) into a voidage map per image cell: IMAGE_voidage.csv beside --out.\n"
    "\n"
    "options:\n"
    "  --method otsu|adaptive  threshold: Otsu's global level (default), or the mean of a\n"
    "                          square window around each pixel (--window N px, default 15)\n"
    "                          plus --offset X (grey levels 0..1, default 0.02)\n"
    "  --measure depth|layer   truth to fit: solids over the whole depth (default) or over the\n"
    "                          first particle layer\n"
    "  --normalise             scale each image's f2D so that its sum over the cells equals\n"
    "                          the solids the truth puts in the image (Mahajan's conversion\n"
    "                          of pixel area \"by the known total solid volume in the bed\")\n"
    "  --cap F                 the largest f3D (default: the packed value the truth reaches,\n"
    "                          its 99.5th percentile; Mahajan used 0.49)\n"
    "  --out DIR               where the fit and plots go (default: DIR/calibration)\n"
    "  --no-plots              skip gnuplot\n"
    "Exit codes: 0 done, 1 the fit failed, 2 bad options or unreadable input.\n";

typedef struct options {
    const char *dir, *test, *apply, *out;
    const char *images[256];
    int image_count;
    int holdout, adaptive, window, layer, plots, cells[2], back_lit, normalise;
    double offset, cap;
    int help; ///< --help was printed: nothing else to do
} options;

/// The value of a numeric key in a small flat JSON text (`"key": number`), or NAN.
static double json_number(const char *text, const char *key)
{
    char pattern[80];
    snprintf(pattern, sizeof pattern, "\"%s\":", key);
    const char *s = strstr(text, pattern);
    return s ? strtod(s + strlen(pattern), NULL) : NAN;
}

/// The string value of a key, copied into out (empty when absent).
static void json_string(const char *text, const char *key, char *out, size_t len)
{
    char pattern[80];
    snprintf(pattern, sizeof pattern, "\"%s\": \"", key);
    const char *s = strstr(text, pattern);
    out[0] = '\0';
    if (!s)
        return;
    s += strlen(pattern);
    const char *e = strchr(s, '"');
    if (e)
        snprintf(out, len, "%.*s", (int)(e - s), s);
}

static int compare_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/// Cells with some solids seen or present: the bed, not the empty freeboard.
#define IN_BED 0.005

typedef struct point_set {
    long n, cap;
    double *f2d, *f3d;
    int *frame, *cell, *test;
} point_set;

static int add_point(point_set *p, double f2d, double f3d, int frame, int cell, int test)
{
    if (p->n == p->cap) {
        long c = p->cap ? 2 * p->cap : 4096;
        double *a = realloc(p->f2d, (size_t)c * sizeof(double));
        if (a)
            p->f2d = a;
        double *b = realloc(p->f3d, (size_t)c * sizeof(double));
        if (b)
            p->f3d = b;
        int *fr = realloc(p->frame, (size_t)c * sizeof(int));
        if (fr)
            p->frame = fr;
        int *ce = realloc(p->cell, (size_t)c * sizeof(int));
        if (ce)
            p->cell = ce;
        int *te = realloc(p->test, (size_t)c * sizeof(int));
        if (te)
            p->test = te;
        if (!a || !b || !fr || !ce || !te)
            return 0;
        p->cap = c;
    }
    p->f2d[p->n] = f2d, p->f3d[p->n] = f3d;
    p->frame[p->n] = frame, p->cell[p->n] = cell, p->test[p->n] = test;
    p->n++;
    return 1;
}

/// Thresholds an image and returns its cell fractions (nx x ny, malloc'ed), or NULL.
static double *image_fractions(const options *o, const char *path, int nx, int ny, int back_lit)
{
    double *img = NULL;
    int w, h, bits;
    if (bdl_png_read_gray(path, &img, &w, &h, &bits) != BDL_OK) {
        fprintf(stderr, "error: cannot read the image %s\n", path);
        return NULL;
    }
    unsigned char *mask = malloc((size_t)w * (size_t)h);
    double *f = malloc((size_t)nx * ny * sizeof(double));
    if (mask && f) {
        bdl_dia_threshold(img, w, h, !back_lit, o->adaptive ? o->window : 0, o->offset, mask);
        bdl_dia_cell_fractions(mask, w, h, nx, ny, f);
    }
    free(img);
    free(mask);
    return f;
}

/// Reads the truth column of a cells CSV (solids_depth or solids_layer) into f3d (n values).
static int read_truth(const char *path, int layer, double *f3d, long n)
{
    FILE *f = fopen(path, "r");
    if (!f)
        return 0;
    char line[1024];
    long k = 0;
    if (!fgets(line, sizeof line, f)) {
        fclose(f);
        return 0;
    }
    while (k < n && fgets(line, sizeof line, f)) {
        // column,row,u0,v0,u1,v1,area_fraction,solids_depth,solids_layer,...
        char *s = line;
        for (int c = 0; c < (layer ? 8 : 7) && s; ++c) {
            s = strchr(s, ',');
            if (s)
                ++s;
        }
        if (!s)
            break;
        f3d[k++] = strtod(s, NULL);
    }
    fclose(f);
    return k == n;
}

/// Collects (f2D, f3D) from every frame of a run's camera folder; frames with index % holdout ==
/// holdout - 1 are marked test (holdout 0: none; all_test: every one).
static int collect(const options *o, const char *dir, int holdout, int all_test, point_set *p,
                   int *frames)
{
    char path[1200];
    snprintf(path, sizeof path, "%s/camera.json", dir);
    size_t length;
    char *json = bdl_read_file(path, &length);
    if (!json) {
        fprintf(stderr, "error: cannot read %s: %s\n", path, strerror(errno));
        return 0;
    }
    char lighting[16];
    json_string(json, "lighting", lighting, sizeof lighting);
    const char *cells = strstr(json, "\"cells\": [");
    int nx = 0, ny = 0;
    if (cells)
        sscanf(cells, "\"cells\": [%d, %d]", &nx, &ny);
    free(json);
    if (nx < 1 || ny < 1) {
        fprintf(stderr, "error: %s has no cell grid (\"cells\")\n", path);
        return 0;
    }
    snprintf(path, sizeof path, "%s/frames.csv", dir);
    FILE *f = fopen(path, "r");
    if (!f) {
        fprintf(stderr, "error: cannot read %s: %s\n", path, strerror(errno));
        return 0;
    }
    char line[1200];
    double *truth = malloc((size_t)nx * ny * sizeof(double));
    int ok = truth && fgets(line, sizeof line, f) != NULL;
    *frames = 0;
    while (ok && fgets(line, sizeof line, f)) {
        long frame;
        double time;
        char image[300], parts[300], cellfile[300] = "";
        int fields = sscanf(line, "%ld,%lf,%299[^,],%299[^,\n],%299[^,\n]", &frame, &time, image,
                            parts, cellfile);
        if (fields < 5 || !cellfile[0])
            continue; // a second PIV frame: its truth is the first's
        char full[1300];
        snprintf(full, sizeof full, "%s/%s", dir, image);
        double *f2d = image_fractions(o, full, nx, ny, strcmp(lighting, "back") == 0);
        snprintf(full, sizeof full, "%s/%s", dir, cellfile);
        if (!f2d || !read_truth(full, o->layer, truth, (long)nx * ny)) {
            if (f2d)
                fprintf(stderr, "error: cannot read the truth %s\n", full);
            free(f2d);
            ok = 0;
            break;
        }
        if (o->normalise) { // Mahajan (2019): pixel area scaled to the known solids in the image
            double s2 = 0.0, s3 = 0.0;
            for (int c = 0; c < nx * ny; ++c)
                s2 += f2d[c], s3 += truth[c];
            for (int c = 0; s2 > 0.0 && c < nx * ny; ++c)
                f2d[c] *= s3 / s2;
        }
        int test = all_test || (holdout > 0 && frame % holdout == holdout - 1);
        for (int c = 0; c < nx * ny; ++c)
            if (f2d[c] > IN_BED || truth[c] > IN_BED)
                ok = ok && add_point(p, f2d[c], truth[c], (int)frame, c, test);
        free(f2d);
        ++*frames;
    }
    fclose(f);
    free(truth);
    return ok && *frames > 0;
}

typedef struct errors {
    long n;
    double rms, bias, max_abs;
} errors;

/// Error of the capped fit on the points of one set (test or train).
static errors evaluate(const bdl_dia_fit *fit, const point_set *p, int test, double cap)
{
    errors e = {0, 0.0, 0.0, 0.0};
    for (long k = 0; k < p->n; ++k) {
        if (p->test[k] != test)
            continue;
        double d = bdl_dia_fit_apply(fit, p->f2d[k], cap) - p->f3d[k];
        e.rms += d * d, e.bias += d, e.max_abs = fmax(e.max_abs, fabs(d));
        e.n++;
    }
    if (e.n > 0) {
        e.rms = sqrt(e.rms / (double)e.n);
        e.bias /= (double)e.n;
    }
    return e;
}

static int write_fit(const char *path, const bdl_dia_fit *fits, const errors *test, double cap,
                     const options *o, long train_n)
{
    bdl_atomic_file af;
    if (bdl_atomic_open(&af, path) != BDL_OK)
        return 0;
    fprintf(af.file, "{\n  \"method\": \"%s\",\n  \"window\": %d,\n  \"offset\": %.6g,\n",
            o->adaptive ? "adaptive" : "otsu", o->window, o->offset);
    fprintf(af.file, "  \"measure\": \"%s\",\n  \"normalise\": %d,\n  \"cap\": %.6g,\n",
            o->layer ? "layer" : "depth", o->normalise, cap);
    fprintf(af.file, "  \"points\": %ld,\n", train_n);
    for (int m = 0; m < BDL_DIA_MODEL_COUNT; ++m) {
        const bdl_dia_fit *f = &fits[m];
        char cap_f2d[32];
        double xc = bdl_dia_fit_cap_f2d(f, cap);
        snprintf(cap_f2d, sizeof cap_f2d, isfinite(xc) ? "%.6f" : "null", xc); // JSON has no NaN
        fprintf(af.file,
                "  \"%s\": {\"p0\": %.9g, \"p1\": %.9g, \"r2\": %.6f, \"rms\": %.6f, "
                "\"max_residual\": %.6f, \"cap_f2d\": %s, \"test_rms\": %.6f, \"test_bias\": "
                "%.6f, \"test_points\": %ld}%s\n",
                bdl_dia_model_names[m], f->p[0], f->p[1], f->r2, f->rms, f->max_abs, cap_f2d,
                test[m].rms, test[m].bias, test[m].n, m + 1 < BDL_DIA_MODEL_COUNT ? "," : "");
    }
    fprintf(af.file, "}\n");
    return bdl_atomic_commit(&af) == BDL_OK;
}

static int write_points(const char *path, const point_set *p)
{
    bdl_atomic_file af;
    if (bdl_atomic_open(&af, path) != BDL_OK)
        return 0;
    fprintf(af.file, "frame,cell,f2d,f3d,set\n");
    for (long k = 0; k < p->n; ++k)
        fprintf(af.file, "%d,%d,%.6f,%.6f,%s\n", p->frame[k], p->cell[k], p->f2d[k], p->f3d[k],
                p->test[k] ? "test" : "train");
    return bdl_atomic_commit(&af) == BDL_OK;
}

static void plot(const char *out, const bdl_dia_fit *fits, double cap)
{
    char script[1200], cmd[1300];
    snprintf(script, sizeof script, "%s/fit.gp", out);
    FILE *f = fopen(script, "w");
    if (!f)
        return;
    const bdl_dia_fit *r = &fits[BDL_DIA_MODEL_RATIONAL], *q = &fits[BDL_DIA_MODEL_POWER];
    fprintf(f,
            "set terminal pngcairo size 900,650 font 'DejaVu Sans,11'\n"
            "set output '%s/fit.png'\nset datafile separator ','\n"
            "set xlabel 'f_{2D}: particle pixels in the image cell'\n"
            "set ylabel 'f_{3D}: solids fraction over the depth (truth)'\n"
            "set key top left\nset grid\nset xrange [0:*]\nset yrange [0:*]\n"
            "A = %.9g; B = %.9g; a = %.9g; b = %.9g; cap = %.6g\n"
            "rat(x) = x < B*cap/(A+cap) ? A*x/(B-x) : cap\n"
            "pow(x) = a*x**b < cap ? a*x**b : cap\n"
            "plot '%s/points.csv' using (strcol(5) eq \"train\" ? $3 : 1/0):4 every ::1 with "
            "points pt 7 "
            "ps 0.3 lc rgb '#8090a0' title 'cells, fitted frames', \\\n"
            "     '%s/points.csv' using (strcol(5) eq \"test\" ? $3 : 1/0):4 every ::1 with points "
            "pt 7 "
            "ps 0.3 lc rgb '#e0a040' title 'cells, held-out frames', \\\n"
            "     rat(x) lw 3 lc rgb '#c03030' title sprintf('A f/(B - f): A = %%.4f, B = %%.4f', "
            "A, B), \\\n"
            "     pow(x) lw 2 dt 2 lc rgb '#3060c0' title sprintf('a f^b: a = %%.3f, b = %%.3f', "
            "a, b), \\\n"
            "     (x < 0.45*0.49/(0.05+0.49) ? 0.05*x/(0.45-x) : 0.49) lw 2 dt 3 lc rgb '#208020' "
            "title 'Mahajan (2019): A = 0.05, B = 0.45'\n",
            out, r->p[0], r->p[1], q->p[0], q->p[1], cap, out, out);
    fclose(f);
    snprintf(cmd, sizeof cmd, "gnuplot '%s' 2>&1", script);
    if (system(cmd) != 0)
        fprintf(stderr, "warning: gnuplot failed or is missing: no fit.png\n");
    remove(script);
}

/// --apply: voidage maps of images with a saved fit (no truth needed).
static bdl_result apply_fit(const options *o)
{
    size_t length;
    char *json = bdl_read_file(o->apply, &length);
    if (!json) {
        fprintf(stderr, "error: cannot read %s: %s\n", o->apply, strerror(errno));
        return BDL_ERR_ARGS;
    }
    const char *rat = strstr(json, "\"rational\":");
    bdl_dia_fit fit = {BDL_DIA_MODEL_RATIONAL, {NAN, NAN}, 0, 0, 0, 0, 1};
    if (rat) {
        fit.p[0] = json_number(rat, "p0");
        fit.p[1] = json_number(rat, "p1");
    }
    double cap = isfinite(o->cap) ? o->cap : json_number(json, "cap");
    free(json);
    if (!isfinite(fit.p[0]) || !isfinite(fit.p[1]) || !isfinite(cap)) {
        fprintf(stderr, "error: %s holds no rational fit (p0, p1) or cap\n", o->apply);
        return BDL_ERR_ARGS;
    }
    const int nx = o->cells[0], ny = o->cells[1];
    for (int k = 0; k < o->image_count; ++k) {
        double *f2d = image_fractions(o, o->images[k], nx, ny, o->back_lit);
        if (!f2d)
            return BDL_ERR_ARGS;
        char path[1200];
        const char *base = strrchr(o->images[k], '/');
        base = base ? base + 1 : o->images[k];
        snprintf(path, sizeof path, "%s/%.*s_voidage.csv", o->out,
                 (int)(strlen(base) > 4 ? strlen(base) - 4 : strlen(base)), base);
        bdl_atomic_file af;
        if (bdl_atomic_open(&af, path) != BDL_OK) {
            free(f2d);
            fprintf(stderr, "error: cannot write %s\n", path);
            return BDL_ERR_ARGS;
        }
        fprintf(af.file, "column,row,f2d,f3d,voidage\n");
        double mean = 0.0;
        for (int j = 0; j < ny; ++j)
            for (int i = 0; i < nx; ++i) {
                double f3 = bdl_dia_fit_apply(&fit, f2d[j * nx + i], cap);
                mean += f3 / (nx * ny);
                fprintf(af.file, "%d,%d,%.6f,%.6f,%.6f\n", i, j, f2d[j * nx + i], f3, 1.0 - f3);
            }
        free(f2d);
        if (bdl_atomic_commit(&af) != BDL_OK) {
            fprintf(stderr, "error: cannot write %s\n", path);
            return BDL_ERR_ARGS;
        }
        printf("%s: mean solids fraction %.4f -> %s\n", o->images[k], mean, path);
    }
    return BDL_OK;
}

static bdl_result parse(int argc, char **argv, options *o)
{
    memset(o, 0, sizeof *o);
    o->holdout = 4, o->window = 15, o->offset = 0.02, o->plots = 1, o->cap = NAN;
    o->cells[0] = 12, o->cells[1] = 36;
    for (int i = 1; i < argc; ++i) {
        const char *a = argv[i];
        int more = i + 1 < argc;
        if (strcmp(a, "--help") == 0 || strcmp(a, "-h") == 0) {
            fputs(calibrate_usage, stdout);
            o->help = 1;
            return BDL_OK;
        } else if (strcmp(a, "--test") == 0 && more) {
            o->test = argv[++i];
        } else if (strcmp(a, "--holdout") == 0 && more) {
            o->holdout = atoi(argv[++i]);
            if (o->holdout < 0) {
                fprintf(stderr, "error: --holdout %s: expected an integer >= 0\n", argv[i]);
                return BDL_ERR_ARGS;
            }
        } else if (strcmp(a, "--apply") == 0 && more) {
            o->apply = argv[++i];
        } else if (strcmp(a, "--method") == 0 && more) {
            ++i;
            if (strcmp(argv[i], "adaptive") != 0 && strcmp(argv[i], "otsu") != 0) {
                fprintf(stderr, "error: --method %s: expected otsu or adaptive\n", argv[i]);
                return BDL_ERR_ARGS;
            }
            o->adaptive = strcmp(argv[i], "adaptive") == 0;
        } else if (strcmp(a, "--window") == 0 && more) {
            o->window = atoi(argv[++i]);
            if (o->window < 1 || o->window > 1000) {
                fprintf(stderr, "error: --window %s: expected 1..1000 pixels\n", argv[i]);
                return BDL_ERR_ARGS;
            }
        } else if (strcmp(a, "--offset") == 0 && more) {
            o->offset = atof(argv[++i]);
        } else if (strcmp(a, "--measure") == 0 && more) {
            ++i;
            if (strcmp(argv[i], "depth") != 0 && strcmp(argv[i], "layer") != 0) {
                fprintf(stderr, "error: --measure %s: expected depth or layer\n", argv[i]);
                return BDL_ERR_ARGS;
            }
            o->layer = strcmp(argv[i], "layer") == 0;
        } else if (strcmp(a, "--cap") == 0 && more) {
            o->cap = atof(argv[++i]);
            if (!(o->cap > 0.0 && o->cap <= 1.0)) {
                fprintf(stderr, "error: --cap %s: expected a fraction in (0, 1]\n", argv[i]);
                return BDL_ERR_ARGS;
            }
        } else if (strcmp(a, "--cells") == 0 && i + 2 < argc) {
            o->cells[0] = atoi(argv[++i]);
            o->cells[1] = atoi(argv[++i]);
            if (o->cells[0] < 1 || o->cells[1] < 1) {
                fprintf(stderr, "error: --cells: expected two positive integers\n");
                return BDL_ERR_ARGS;
            }
        } else if (strcmp(a, "--lighting") == 0 && more) {
            o->back_lit = strcmp(argv[++i], "back") == 0;
        } else if (strcmp(a, "--out") == 0 && more) {
            o->out = argv[++i];
        } else if (strcmp(a, "--normalise") == 0) {
            o->normalise = 1;
        } else if (strcmp(a, "--no-plots") == 0) {
            o->plots = 0;
        } else if (a[0] == '-') {
            fprintf(stderr, "error: unknown option '%s'\n\n%s", a, calibrate_usage);
            return BDL_ERR_ARGS;
        } else if (o->apply) {
            if (o->image_count < 256)
                o->images[o->image_count++] = a;
        } else if (!o->dir) {
            o->dir = a;
        } else {
            fprintf(stderr, "error: more than one folder given ('%s')\n", a);
            return BDL_ERR_ARGS;
        }
    }
    if (!o->apply && !o->dir) {
        fprintf(stderr, "error: no folder given\n\n%s", calibrate_usage);
        return BDL_ERR_ARGS;
    }
    if (o->apply && o->image_count == 0) {
        fprintf(stderr, "error: --apply needs images\n");
        return BDL_ERR_ARGS;
    }
    return BDL_OK;
}

bdl_result bdl_cmd_calibrate(int argc, char **argv)
{
    options o;
    bdl_result rc = parse(argc, argv, &o);
    if (rc != BDL_OK || o.help)
        return rc;
    char out[1100], why[512];
    snprintf(out, sizeof out, "%s", o.out ? o.out : o.apply ? "." : o.dir);
    if (!o.out && !o.apply)
        snprintf(out, sizeof out, "%s/calibration", o.dir);
    if (bdl_check_writable_dir(out, why, sizeof why) != BDL_OK) {
        fprintf(stderr, "error: --out %s: %s\n", out, why);
        return BDL_ERR_OUTPUT_DIR;
    }
    o.out = out;
    if (o.apply)
        return apply_fit(&o);
    point_set p = {0};
    int frames = 0, test_frames = 0;
    if (!collect(&o, o.dir, o.test ? 0 : o.holdout, 0, &p, &frames) ||
        (o.test && !collect(&o, o.test, 0, 1, &p, &test_frames))) {
        free(p.f2d), free(p.f3d), free(p.frame), free(p.cell), free(p.test);
        return BDL_ERR_ARGS;
    }
    // Fit on the training points.
    long n_train = 0;
    double *x = malloc((size_t)p.n * sizeof(double)), *y = malloc((size_t)p.n * sizeof(double));
    for (long k = 0; x && y && k < p.n; ++k)
        if (!p.test[k]) {
            x[n_train] = p.f2d[k];
            y[n_train++] = p.f3d[k];
        }
    // The cap: given, or the packed value the truth reaches (its 99.5th percentile, so that a few
    // over-full cells at walls do not set it).
    double cap = o.cap;
    if (!isfinite(cap) && n_train >= 3) {
        double *sorted = malloc((size_t)n_train * sizeof(double));
        if (sorted) {
            memcpy(sorted, y, (size_t)n_train * sizeof(double));
            qsort(sorted, (size_t)n_train, sizeof(double), compare_double);
            cap = sorted[(long)(0.995 * (double)(n_train - 1))];
            free(sorted);
        }
    }
    if (!isfinite(cap))
        cap = 0.49;
    bdl_dia_fit fits[BDL_DIA_MODEL_COUNT];
    errors test[BDL_DIA_MODEL_COUNT], train[BDL_DIA_MODEL_COUNT];
    int ok = x && y && n_train >= 3;
    printf("calibrate %s: %d frames%s, %ld cells in the bed (%ld fitted, %ld held out), threshold "
           "%s%s, truth: solids over the %s\n",
           o.dir, frames + test_frames, o.test ? " (with the test set)" : "", p.n, n_train,
           p.n - n_train, o.adaptive ? "adaptive" : "Otsu",
           o.normalise ? ", f2D normalised to the image's solids" : "",
           o.layer ? "first layer" : "whole depth");
    for (int m = 0; ok && m < BDL_DIA_MODEL_COUNT; ++m) {
        fits[m] = bdl_dia_fit_model((bdl_dia_model)m, x, y, n_train);
        train[m] = evaluate(&fits[m], &p, 0, cap);
        test[m] = evaluate(&fits[m], &p, 1, cap);
        const bdl_dia_fit *f = &fits[m];
        printf("  %-8s %s = %.5f, %s = %.5f  R^2 %.4f  rms %.4f  max |residual| %.4f  cap %.2f at "
               "f2D %.4f%s\n",
               bdl_dia_model_names[m], m ? "a" : "A", f->p[0], m ? "b" : "B", f->p[1], f->r2,
               train[m].rms, train[m].max_abs, cap, bdl_dia_fit_cap_f2d(f, cap),
               f->converged ? "" : "  (not converged)");
        if (test[m].n > 0)
            printf("           held out: %ld cells, error in solids fraction (= in voidage) rms "
                   "%.4f, bias %+.4f, max %.4f\n",
                   test[m].n, test[m].rms, test[m].bias, test[m].max_abs);
        if (m == BDL_DIA_MODEL_RATIONAL && f->p[1] > 2.0)
            printf("           B far above 1: the data have no curvature, and the rational form "
                   "is the line f3D = %.4f f2D\n",
                   f->p[0] / f->p[1]);
        ok = ok && isfinite(f->p[0]) && isfinite(f->p[1]);
    }
    char path[1300];
    if (ok) {
        snprintf(path, sizeof path, "%s/fit.json", out);
        ok = write_fit(path, fits, test, cap, &o, n_train);
        snprintf(path, sizeof path, "%s/points.csv", out);
        ok = ok && write_points(path, &p);
        if (ok && o.plots)
            plot(out, fits, cap);
        printf("  -> %s/fit.json, points.csv%s\n", out, o.plots ? ", fit.png" : "");
    }
    free(x), free(y);
    free(p.f2d), free(p.f3d), free(p.frame), free(p.cell), free(p.test);
    return ok ? BDL_OK : BDL_ERR_NO_RESULT;
}
