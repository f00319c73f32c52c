// bedlam calibrate — the 2D-to-3D solids-fraction relation of a pseudo-2D bed from synthetic
// camera images and their ground truth, and its application to other images.
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "app/analyze_files.h"
#include "app/app.h"
#include "app/options.h"
#include "dia/analysis.h"
#include "scene/scene.h"
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
    double v;
    return bdl_analyze_json_number(text, key, &v) ? v : NAN;
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

/// One image cell: the solids fraction the camera sees and the truth behind it.
typedef struct cell_point {
    double f2d, f3d;
    int frame, cell, test;
} cell_point;

typedef struct point_set {
    long n, cap;
    cell_point *p;
} point_set;

static int add_point(point_set *s, cell_point point)
{
    if (s->n == s->cap) {
        long cap = s->cap ? 2 * s->cap : 4096;
        cell_point *p = realloc(s->p, (size_t)cap * sizeof *p);
        if (!p)
            return 0;
        s->p = p, s->cap = cap;
    }
    s->p[s->n++] = point;
    return 1;
}

/// Thresholds an image into its cell fractions (nx x ny, malloc'ed in *out). BDL_ERR_ARGS
/// (printed) when the image cannot be read.
static bdl_result image_fractions(const options *o, const char *path, int nx, int ny, int back_lit,
                                  double **out)
{
    double *img = NULL;
    int w, h, bits;
    *out = NULL;
    if (bdl_png_read_gray(path, &img, &w, &h, &bits) != BDL_OK) {
        fprintf(stderr, "error: cannot read the image %s\n", path);
        return BDL_ERR_ARGS;
    }
    unsigned char *mask = malloc((size_t)w * (size_t)h);
    double *f = malloc((size_t)nx * ny * sizeof(double));
    if (mask && f) {
        bdl_dia_threshold(img, w, h, !back_lit, o->adaptive ? o->window : 0, o->offset, mask);
        bdl_dia_cell_fractions(mask, w, h, nx, ny, f);
        *out = f, f = NULL;
    }
    free(img), free(mask), free(f);
    return *out ? BDL_OK : BDL_ERR_NOMEM;
}

/// Reads the truth column of a cells CSV (solids_depth or solids_layer) into f3d (n values).
static int read_truth(const char *path, int layer, double *f3d, long n)
{
    char why[256];
    FILE *f = bdl_open_regular(path, why, sizeof why);
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

/// The cell grid and the lighting of a camera folder (camera.json).
static bdl_result read_camera(const char *dir, int *nx, int *ny, int *back_lit)
{
    char path[1200];
    snprintf(path, sizeof path, "%s/camera.json", dir);
    char *json = bdl_analyze_read_regular(path, "");
    if (!json)
        return BDL_ERR_ARGS;
    char lighting[16];
    json_string(json, "lighting", lighting, sizeof lighting);
    *back_lit = strcmp(lighting, bdl_dia_lighting_names[BDL_DIA_BACK_LIT]) == 0;
    const char *cells = strstr(json, "\"cells\": [");
    *nx = *ny = 0;
    if (cells)
        sscanf(cells, "\"cells\": [%d, %d]", nx, ny);
    free(json);
    if (*nx < 1 || *ny < 1) {
        fprintf(stderr, "error: %s has no cell grid (\"cells\")\n", path);
        return BDL_ERR_ARGS;
    }
    return BDL_OK;
}

/// A camera folder: its grid and lighting, and what the frames are for.
typedef struct camera_set {
    const char *dir;
    int nx, ny, back_lit;
    int holdout;  ///< frames with index % holdout == holdout - 1 are test frames (0: none)
    int all_test; ///< every frame is a test frame
} camera_set;

/// Adds the cells in the bed of one frame (its image and its truth `cellfile`) to the points.
static bdl_result add_frame(const options *o, const camera_set *cs, long frame, const char *image,
                            const char *cellfile, double *truth, point_set *p)
{
    const int cells = cs->nx * cs->ny;
    char full[1300];
    snprintf(full, sizeof full, "%s/%s", cs->dir, image);
    double *f2d;
    bdl_result rc = image_fractions(o, full, cs->nx, cs->ny, cs->back_lit, &f2d);
    if (rc != BDL_OK)
        return rc;
    snprintf(full, sizeof full, "%s/%s", cs->dir, cellfile);
    if (!read_truth(full, o->layer, truth, cells)) {
        fprintf(stderr, "error: cannot read the truth %s\n", full);
        free(f2d);
        return BDL_ERR_ARGS;
    }
    if (o->normalise) { // Mahajan (2019): pixel area scaled to the known solids in the image
        double s2 = 0.0, s3 = 0.0;
        for (int c = 0; c < cells; ++c)
            s2 += f2d[c], s3 += truth[c];
        for (int c = 0; s2 > 0.0 && c < cells; ++c)
            f2d[c] *= s3 / s2;
    }
    const int test = cs->all_test || (cs->holdout > 0 && frame % cs->holdout == cs->holdout - 1);
    for (int c = 0; c < cells && rc == BDL_OK; ++c)
        if (f2d[c] > IN_BED || truth[c] > IN_BED)
            if (!add_point(p, (cell_point){f2d[c], truth[c], (int)frame, c, test}))
                rc = BDL_ERR_NOMEM;
    free(f2d);
    return rc;
}

/// Collects (f2D, f3D) from every frame of a camera folder (frames.csv); *frames counts them.
static bdl_result collect(const options *o, camera_set *cs, point_set *p, int *frames)
{
    bdl_result rc = read_camera(cs->dir, &cs->nx, &cs->ny, &cs->back_lit);
    if (rc != BDL_OK)
        return rc;
    char path[1200];
    snprintf(path, sizeof path, "%s/frames.csv", cs->dir);
    char why[256];
    FILE *f = bdl_open_regular(path, why, sizeof why);
    if (!f) {
        fprintf(stderr, "error: %s %s\n", path, why);
        return BDL_ERR_ARGS;
    }
    char line[1200];
    double *truth = malloc((size_t)cs->nx * cs->ny * sizeof(double));
    rc = !truth ? BDL_ERR_NOMEM : fgets(line, sizeof line, f) ? BDL_OK : BDL_ERR_ARGS;
    *frames = 0;
    while (rc == BDL_OK && fgets(line, sizeof line, f)) {
        long frame;
        double time;
        char image[300], parts[300], cellfile[300] = "";
        int fields = sscanf(line, "%ld,%lf,%299[^,],%299[^,\n],%299[^,\n]", &frame, &time, image,
                            parts, cellfile);
        if (fields < 5 || !cellfile[0])
            continue; // a second PIV frame: its truth is the first's
        if ((rc = add_frame(o, cs, frame, image, cellfile, truth, p)) == BDL_OK)
            ++*frames;
    }
    fclose(f);
    free(truth);
    return rc == BDL_OK && *frames == 0 ? BDL_ERR_ARGS : rc;
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
        if (p->p[k].test != test)
            continue;
        double d = bdl_dia_fit_apply(fit, p->p[k].f2d, cap) - p->p[k].f3d;
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
    if (bdl_atomic_open_csv(&af, path, "frame,cell,f2d,f3d,set") != BDL_OK)
        return 0;
    for (long k = 0; k < p->n; ++k) {
        const cell_point *c = &p->p[k];
        fprintf(af.file, "%d,%d,%.6f,%.6f,%s\n", c->frame, c->cell, c->f2d, c->f3d,
                c->test ? "test" : "train");
    }
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

/// The rational fit and cap of a fit.json (--cap overrides its cap).
static bdl_result read_fit(const options *o, bdl_dia_fit *fit, double *cap)
{
    size_t length;
    char why[256];
    char *json = bdl_check_regular_file(o->apply, NULL, why, sizeof why) == BDL_OK
                     ? bdl_read_file(o->apply, &length)
                     : NULL;
    if (!json) {
        fprintf(stderr, "error: %s %s\n", o->apply, why);
        return BDL_ERR_ARGS;
    }
    const char *rat = strstr(json, "\"rational\":");
    *fit = (bdl_dia_fit){BDL_DIA_MODEL_RATIONAL, {NAN, NAN}, 0, 0, 0, 0, 1};
    if (rat) {
        fit->p[0] = json_number(rat, "p0");
        fit->p[1] = json_number(rat, "p1");
    }
    *cap = isfinite(o->cap) ? o->cap : json_number(json, "cap");
    free(json);
    if (!isfinite(fit->p[0]) || !isfinite(fit->p[1]) || !isfinite(*cap)) {
        fprintf(stderr, "error: %s holds no rational fit (p0, p1) or cap\n", o->apply);
        return BDL_ERR_ARGS;
    }
    return BDL_OK;
}

/// The voidage map of one image: IMAGE_voidage.csv in --out.
static bdl_result apply_to_image(const options *o, const char *image, const bdl_dia_fit *fit,
                                 double cap)
{
    const int nx = o->cells[0], ny = o->cells[1];
    double *f2d;
    bdl_result rc = image_fractions(o, image, nx, ny, o->back_lit, &f2d);
    if (rc != BDL_OK)
        return rc;
    char path[1200];
    const char *base = strrchr(image, '/');
    base = base ? base + 1 : image;
    snprintf(path, sizeof path, "%s/%.*s_voidage.csv", o->out,
             (int)(strlen(base) > 4 ? strlen(base) - 4 : strlen(base)), base);
    bdl_atomic_file af;
    if (bdl_atomic_open(&af, path) != BDL_OK) {
        free(f2d);
        fprintf(stderr, "error: cannot write %s\n", path);
        return BDL_ERR_OUTPUT_DIR;
    }
    fprintf(af.file, "column,row,f2d,f3d,voidage\n");
    double mean = 0.0;
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
            double f3 = bdl_dia_fit_apply(fit, f2d[j * nx + i], cap);
            mean += f3 / (nx * ny);
            fprintf(af.file, "%d,%d,%.6f,%.6f,%.6f\n", i, j, f2d[j * nx + i], f3, 1.0 - f3);
        }
    free(f2d);
    if (bdl_atomic_commit(&af) != BDL_OK) {
        fprintf(stderr, "error: cannot write %s\n", path);
        return BDL_ERR_OUTPUT_DIR;
    }
    printf("%s: mean solids fraction %.4f -> %s\n", image, mean, path);
    return BDL_OK;
}

/// --apply: voidage maps of images with a saved fit (no truth needed).
static bdl_result apply_fit(const options *o)
{
    bdl_dia_fit fit;
    double cap;
    bdl_result rc = read_fit(o, &fit, &cap);
    for (int k = 0; rc == BDL_OK && k < o->image_count; ++k)
        rc = apply_to_image(o, o->images[k], &fit, cap);
    return rc;
}

static const bdl_option calibrate_options[] = {
    {"--test", BDL_OPTION_TEXT, offsetof(options, test)},
    {"--apply", BDL_OPTION_TEXT, offsetof(options, apply)},
    {"--offset", BDL_OPTION_NUMBER, offsetof(options, offset)},
    {"--out", BDL_OPTION_TEXT, offsetof(options, out)},
    {"--normalise", BDL_OPTION_SET, offsetof(options, normalise)},
    {"--no-plots", BDL_OPTION_CLEAR, offsetof(options, plots)},
};

/// The numbers with a range, checked as they are read.
static const bdl_option ranged_options[] = {
    {"--holdout", BDL_OPTION_INT, offsetof(options, holdout)},
    {"--window", BDL_OPTION_INT, offsetof(options, window)},
    {"--cap", BDL_OPTION_NUMBER, offsetof(options, cap)},
};

/// The range of a ranged option just read from `value`.
static int in_range(const options *o, const char *name, const char *value)
{
    if (strcmp(name, "--holdout") == 0 && o->holdout < 0) {
        fprintf(stderr, "error: --holdout %s: expected an integer >= 0\n", value);
        return 0;
    }
    if (strcmp(name, "--window") == 0 && (o->window < 1 || o->window > 1000)) {
        fprintf(stderr, "error: --window %s: expected 1..1000 pixels\n", value);
        return 0;
    }
    if (strcmp(name, "--cap") == 0 && !(o->cap > 0.0 && o->cap <= 1.0)) {
        fprintf(stderr, "error: --cap %s: expected a fraction in (0, 1]\n", value);
        return 0;
    }
    return 1;
}

/// --method, --measure, --lighting: one of two words, which sets an int to whether it is the
/// first. Returns the arguments taken (0: not one of them, or no value), or -1 for a word it does
/// not know (printed).
static int set_choice(options *o, const char *name, const char *value)
{
    static const struct {
        const char *name, *word, *other;
        const char *expected; ///< NULL: any word but `word` means the other (--lighting)
        size_t field;
    } choices[] = {
        {"--method", "adaptive", "otsu", "otsu or adaptive", offsetof(options, adaptive)},
        {"--measure", "layer", "depth", "depth or layer", offsetof(options, layer)},
        {"--lighting", "back", "front", NULL, offsetof(options, back_lit)},
    };
    for (size_t k = 0; value && k < sizeof choices / sizeof choices[0]; ++k) {
        if (strcmp(name, choices[k].name) != 0)
            continue;
        const int is_word = strcmp(value, choices[k].word) == 0;
        if (choices[k].expected && !is_word && strcmp(value, choices[k].other) != 0) {
            fprintf(stderr, "error: %s %s: expected %s\n", name, value, choices[k].expected);
            return -1;
        }
        *(int *)((char *)o + choices[k].field) = is_word;
        return 2;
    }
    return 0;
}

/// --cells NX NY: 3 arguments, -1 for values that are not positive (printed), 0 when they are
/// not both there.
static int set_cells(options *o, int argc, char **argv, int i)
{
    if (strcmp(argv[i], "--cells") != 0 || i + 2 >= argc)
        return 0;
    o->cells[0] = atoi(argv[i + 1]);
    o->cells[1] = atoi(argv[i + 2]);
    if (o->cells[0] < 1 || o->cells[1] < 1) {
        fprintf(stderr, "error: --cells: expected two positive integers\n");
        return -1;
    }
    return 3;
}

/// The folder, or with --apply an image: 1, or 0 for an unknown option or a second folder.
static int take_argument(options *o, const char *a)
{
    if (a[0] == '-') {
        fprintf(stderr, "error: unknown option '%s'\n\n%s", a, calibrate_usage);
        return 0;
    } else if (o->apply) {
        if (o->image_count < 256)
            o->images[o->image_count++] = a;
    } else if (!o->dir) {
        o->dir = a;
    } else {
        fprintf(stderr, "error: more than one folder given ('%s')\n", a);
        return 0;
    }
    return 1;
}

/// What the option table does not take: ranged numbers, choices, --cells, the folder or images.
static int take_other(void *opts, int argc, char **argv, int i)
{
    options *o = opts;
    const char *a = argv[i], *value = i + 1 < argc ? argv[i + 1] : NULL;
    int used = bdl_option_set(ranged_options, BDL_OPTION_COUNT(ranged_options), o, a, value);
    if (used > 0)
        return in_range(o, a, value) ? used : 0;
    if ((used = set_choice(o, a, value)) != 0 || (used = set_cells(o, argc, argv, i)) != 0)
        return used > 0 ? used : 0;
    return take_argument(o, a);
}

static bdl_result parse(int argc, char **argv, options *o)
{
    static const bdl_option_parser parser = {calibrate_options, BDL_OPTION_COUNT(calibrate_options),
                                             calibrate_usage, 0, take_other};
    memset(o, 0, sizeof *o);
    o->holdout = 4, o->window = 15, o->offset = 0.02, o->plots = 1, o->cap = NAN;
    o->cells[0] = 12, o->cells[1] = 36;
    bdl_result rc = bdl_option_parse(&parser, argc, argv, 1, o, &o->help);
    if (rc != BDL_OK || o->help)
        return rc;
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

/// The cap: given, or the packed value the truth reaches (its 99.5th percentile, so that a few
/// over-full cells at walls do not set it), or Mahajan's 0.49.
static double choose_cap(const options *o, const double *f3d, long n)
{
    double cap = o->cap;
    if (!isfinite(cap) && n >= 3) {
        double *sorted = malloc((size_t)n * sizeof(double));
        if (sorted) {
            memcpy(sorted, f3d, (size_t)n * sizeof(double));
            qsort(sorted, (size_t)n, sizeof(double), compare_double);
            cap = sorted[(long)(0.995 * (double)(n - 1))];
            free(sorted);
        }
    }
    return isfinite(cap) ? cap : 0.49;
}

/// Fits both models to the training points and prints each with its errors; 0 when a fit has
/// no finite parameters.
static int fit_models(const point_set *p, const double *x, const double *y, long n_train,
                      double cap, bdl_dia_fit *fits, errors *test)
{
    for (int m = 0; m < BDL_DIA_MODEL_COUNT; ++m) {
        fits[m] = bdl_dia_fit_model((bdl_dia_model)m, x, y, n_train);
        const errors train = evaluate(&fits[m], p, 0, cap);
        test[m] = evaluate(&fits[m], p, 1, cap);
        const bdl_dia_fit *f = &fits[m];
        printf("  %-8s %s = %.5f, %s = %.5f  R^2 %.4f  rms %.4f  max |residual| %.4f  cap %.2f at "
               "f2D %.4f%s\n",
               bdl_dia_model_names[m], m ? "a" : "A", f->p[0], m ? "b" : "B", f->p[1], f->r2,
               train.rms, train.max_abs, cap, bdl_dia_fit_cap_f2d(f, cap),
               f->converged ? "" : "  (not converged)");
        if (test[m].n > 0)
            printf("           held out: %ld cells, error in solids fraction (= in voidage) rms "
                   "%.4f, bias %+.4f, max %.4f\n",
                   test[m].n, test[m].rms, test[m].bias, test[m].max_abs);
        if (m == BDL_DIA_MODEL_RATIONAL && f->p[1] > 2.0)
            printf("           B far above 1: the data have no curvature, and the rational form "
                   "is the line f3D = %.4f f2D\n",
                   f->p[0] / f->p[1]);
        if (!isfinite(f->p[0]) || !isfinite(f->p[1]))
            return 0;
    }
    return 1;
}

/// Fits the points, prints the fits and writes fit.json, points.csv and the plot into o->out.
static bdl_result fit_and_write(const options *o, const point_set *p, int frames)
{
    long n_train = 0;
    double *x = malloc((size_t)(p->n > 0 ? p->n : 1) * sizeof(double));
    double *y = malloc((size_t)(p->n > 0 ? p->n : 1) * sizeof(double));
    for (long k = 0; x && y && k < p->n; ++k)
        if (!p->p[k].test) {
            x[n_train] = p->p[k].f2d;
            y[n_train++] = p->p[k].f3d;
        }
    const double cap = choose_cap(o, y, n_train);
    printf("calibrate %s: %d frames%s, %ld cells in the bed (%ld fitted, %ld held out), threshold "
           "%s%s, truth: solids over the %s\n",
           o->dir, frames, o->test ? " (with the test set)" : "", p->n, n_train, p->n - n_train,
           o->adaptive ? "adaptive" : "Otsu",
           o->normalise ? ", f2D normalised to the image's solids" : "",
           o->layer ? "first layer" : "whole depth");
    bdl_dia_fit fits[BDL_DIA_MODEL_COUNT];
    errors test[BDL_DIA_MODEL_COUNT];
    bdl_result rc = !x || !y ? BDL_ERR_NOMEM : BDL_OK;
    int ok = rc == BDL_OK && n_train >= 3 && fit_models(p, x, y, n_train, cap, fits, test);
    free(x), free(y);
    if (!ok)
        return rc != BDL_OK ? rc : BDL_ERR_NO_RESULT;
    char path[1300];
    snprintf(path, sizeof path, "%s/fit.json", o->out);
    ok = write_fit(path, fits, test, cap, o, n_train);
    snprintf(path, sizeof path, "%s/points.csv", o->out);
    ok = ok && write_points(path, p);
    if (ok && o->plots)
        plot(o->out, fits, cap);
    printf("  -> %s/fit.json, points.csv%s\n", o->out, o->plots ? ", fit.png" : "");
    return ok ? BDL_OK : BDL_ERR_NO_RESULT;
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
    camera_set train = {.dir = o.dir, .holdout = o.test ? 0 : o.holdout};
    camera_set test = {.dir = o.test, .all_test = 1};
    rc = collect(&o, &train, &p, &frames);
    if (rc == BDL_OK && o.test)
        rc = collect(&o, &test, &p, &test_frames);
    if (rc == BDL_OK)
        rc = fit_and_write(&o, &p, frames + test_frames);
    free(p.p);
    return rc;
}
