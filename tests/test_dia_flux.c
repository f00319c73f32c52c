// The solids mass flux and the coalignment by wall zone of `bedlam analyze dia`
// (app/analyze_dia_flux.c) on synthetic input with known answers: a striped image whose cells
// have f2D = 1/4 and 1/2, a calibration fit, and a PIV field made by hand give rho (1 - eps) v
// exactly, with outliers left out, cells without vectors or particles skipped and counted, the
// fit's normalisation taken from its own truth column, and frames averaged; rods placed by hand
// give C(r) per zone of the distance from the nearer side wall, pooled over frames by pairs.
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "app/analyze_dia.h"
#include "check.h"

enum { W = 64, H = 64, NX = 4, NY = 4, CELLS = NX * NY, PX = 8, PY = 8 };

static const dia_camera camera = {.width = W,
                                  .height = H,
                                  .cells = {NX, NY},
                                  .pixel_size = 1e-3,
                                  .pair_dt = 2e-3,
                                  .position = {0.032, -0.3, 0.032},
                                  .right = {1, 0, 0},
                                  .down = {0, 0, -1},
                                  .forward = {0, 1, 0}};

/// Front-lit: bright columns on a dark ground, one in four on the left half (f2D 1/4), two in
/// four on the right half (f2D 1/2).
static void striped_image(double *img)
{
    for (int j = 0; j < H; ++j)
        for (int i = 0; i < W; ++i)
            img[j * W + i] = (i % 4 == 0 || (i >= W / 2 && i % 4 == 1)) ? 0.9 : 0.1;
}

/// The truth of the cells: bounds, solids_depth 0.1, solids_layer 0.75, 5 visible particles
/// moving at (0.5, 1.0 up) m/s, but none in cell 6.
static void truth_cells(dia_table *t, double *data)
{
    memset(t, 0, sizeof *t);
    t->rows = CELLS;
    for (int k = 0; k < 10; ++k)
        t->col[k] = data + k * CELLS;
    for (int c = 0; c < CELLS; ++c) {
        const double u0 = (c % NX) * (double)W / NX, v0 = (c / NX) * (double)H / NY;
        t->col[DIA_U0][c] = u0, t->col[DIA_V0][c] = v0;
        t->col[DIA_U1][c] = u0 + (double)W / NX, t->col[DIA_V1][c] = v0 + (double)H / NY;
        t->col[DIA_AREA][c] = 0.5, t->col[DIA_DEPTH][c] = 0.1, t->col[DIA_LAYER][c] = 0.75;
        t->col[DIA_VISIBLE][c] = c == 6 ? 0 : 5;
        t->col[DIA_DU][c] = 500.0, t->col[DIA_DV][c] = -1000.0; // px/s at 1 mm/px
    }
}

/// A PIV field of PX x PY vectors, 4 per cell, all (1, dv) px; in cell 0 one more flagged vector
/// far off, and all of cell 5's flagged.
typedef struct piv_field {
    double u[PX * PY + 1], v[PX * PY + 1], du[PX * PY + 1], dv[PX * PY + 1];
    unsigned char outlier[PX * PY + 1];
    bdl_dia_piv_field f;
} piv_field;

static void make_field(piv_field *p, double dv)
{
    for (int k = 0; k < PX * PY; ++k) {
        p->u[k] = 4.0 + 8.0 * (k % PX), p->v[k] = 4.0 + 8.0 * (k / PX);
        p->du[k] = 1.0, p->dv[k] = dv;
        const int cell = (int)(p->v[k] / 16) * NX + (int)(p->u[k] / 16);
        p->outlier[k] = cell == 5;
    }
    p->u[PX * PY] = 2.0, p->v[PX * PY] = 2.0, p->du[PX * PY] = 40.0, p->dv[PX * PY] = 50.0;
    p->outlier[PX * PY] = 1;
    p->f = (bdl_dia_piv_field){.nx = PX * PY + 1,
                               .ny = 1,
                               .u = p->u,
                               .v = p->v,
                               .du = p->du,
                               .dv = p->dv,
                               .outlier = p->outlier};
}

static void test_cell_mean(void)
{
    piv_field p;
    make_field(&p, -3.0);
    double du, dv;
    CHECK(dia_piv_cell_mean(&p.f, 0, 0, 16, 16, &du, &dv) == 4); // the outlier is left out
    CHECK_CLOSE(du, 1.0, 1e-12);
    CHECK_CLOSE(dv, -3.0, 1e-12);
    CHECK(dia_piv_cell_mean(&p.f, 16, 16, 32, 32, &du, &dv) == 0); // cell 5: all flagged
    CHECK(dia_piv_cell_mean(&p.f, 0, 0, 4, 4, &du, &dv) == 0);     // u < u1 strictly
}

/// f3D = 0.2 f2D / (1 - f2D): 1/15 at f2D 1/4, 0.2 at 1/2; capped at 0.49.
static dia_flux_fit otsu_fit(void)
{
    dia_flux_fit fit = {.cap = 0.49, .offset = 0.02, .window = 15};
    fit.fit = (bdl_dia_fit){BDL_DIA_MODEL_RATIONAL, {0.2, 1.0}, 0, 0, 0, 0, 1};
    return fit;
}

/// Two double frames (upward PIV displacement 3 and 1 px in 2 ms at 1 mm/px: 1.5 and 0.5 m/s):
/// the time-mean flux per cell, left half 1000 (1/15) 1.0, right 1000 0.2 1.0 kg/(m^2 s); the
/// truth 1000 0.1 1.0 = 100 in every cell with data.
static void test_flux(void)
{
    double *img = malloc(sizeof(double) * W * H), data[10 * CELLS];
    dia_table cells;
    striped_image(img);
    truth_cells(&cells, data);
    dia_flux fx = {.fit = otsu_fit(), .density = 1000.0};
    piv_field p;
    make_field(&p, -3.0);
    CHECK(dia_flux_add(&fx, &camera, img, &p.f, &cells) == BDL_OK);
    make_field(&p, -1.0);
    CHECK(dia_flux_add(&fx, &camera, img, &p.f, &cells) == BDL_OK);
    CHECK(fx.cells == CELLS && fx.used == 2 * (CELLS - 2));
    CHECK(fx.no_particles == 2 && fx.no_vector == 2);
    for (int c = 0; c < CELLS; ++c) {
        if (c == 5 || c == 6) {
            CHECK(fx.frames[c] == 0 && fx.image_sum[c] == 0.0 && fx.truth_sum[c] == 0.0);
            continue;
        }
        const double f3d = c % NX < NX / 2 ? 1.0 / 15.0 : 0.2;
        CHECK(fx.frames[c] == 2);
        CHECK_CLOSE(fx.image_sum[c] / 2, 1000.0 * f3d * 1.0, 1e-9);
        CHECK_CLOSE(fx.truth_sum[c] / 2, 100.0, 1e-9);
    }
    CHECK_CLOSE(fx.x[0], 0.008, 1e-12); // u 8 px: 32 - 24 px from the camera's axis
    CHECK_CLOSE(fx.z[0], 0.056, 1e-12); // v 8 px, above the axis at 32 mm
    CHECK_CLOSE(fx.x[NX * NY - 1], 0.056, 1e-12);
    CHECK_CLOSE(fx.z[NX * NY - 1], 0.008, 1e-12);
    CHECK_CLOSE(fx.w_image / fx.used, 1.0, 1e-12);
    CHECK_CLOSE(fx.w_truth / fx.used, 1.0, 1e-12);

    // Normalised to the fit's truth (solids_layer, 12 in all): f2D doubled to 1/2 and 1, the
    // second capped. A frame whose cells lack that column gives no flux.
    dia_flux nf = {.fit = otsu_fit(), .density = 1000.0};
    nf.fit.normalise = 1, nf.fit.layer = 1;
    make_field(&p, -3.0);
    CHECK(dia_flux_add(&nf, &camera, img, &p.f, &cells) == BDL_OK);
    CHECK_CLOSE(nf.image_sum[0], 1000.0 * 0.2 * 1.5, 1e-9);
    CHECK_CLOSE(nf.image_sum[NX - 1], 1000.0 * 0.49 * 1.5, 1e-9);
    cells.col[DIA_LAYER] = NULL;
    CHECK(dia_flux_add(&nf, &camera, img, &p.f, &cells) == BDL_ERR_ARGS);
    CHECK(nf.frames[0] == 1);
    free(nf.image_sum), free(nf.truth_sum), free(nf.frames), free(nf.x), free(nf.z);
    free(fx.image_sum), free(fx.truth_sum), free(fx.frames), free(fx.x), free(fx.z);
    free(img);
}

static void write_text(const char *path, const char *text)
{
    FILE *f = fopen(path, "w");
    if (f) {
        fputs(text, f);
        fclose(f);
    }
}

/// A calibrate fit.json is read whole; a file without a rational fit, and --fit without
/// --density, are refused.
static void test_fit_file(const char *dir)
{
    char path[600];
    snprintf(path, sizeof path, "%s/fit.json", dir);
    write_text(path, "{\n  \"method\": \"adaptive\",\n  \"window\": 11,\n  \"offset\": 0.03,\n"
                     "  \"measure\": \"layer\",\n  \"normalise\": 1,\n  \"cap\": 0.45,\n"
                     "  \"points\": 10,\n  \"rational\": {\"p0\": 0.05, \"p1\": 0.45, \"r2\": 0.9, "
                     "\"cap_f2d\": 0.4},\n  \"power\": {\"p0\": 1.2, \"p1\": 1.1}\n}\n");
    dia_flux_fit fit;
    CHECK(dia_flux_read_fit(path, &fit) == BDL_OK);
    CHECK(fit.adaptive == 1 && fit.window == 11 && fit.layer == 1 && fit.normalise == 1);
    CHECK_CLOSE(fit.offset, 0.03, 1e-12);
    CHECK_CLOSE(fit.cap, 0.45, 1e-12);
    CHECK_CLOSE(fit.fit.p[0], 0.05, 1e-12);
    CHECK_CLOSE(fit.fit.p[1], 0.45, 1e-12);
    bdl_analyze_opts o = {.fit = path, .density = NAN};
    dia_flux *fx = NULL;
    CHECK(dia_flux_open(&o, &fx) == BDL_ERR_ARGS && !fx);
    o.density = 1395.0;
    CHECK(dia_flux_open(&o, &fx) == BDL_OK && fx && fx->density == 1395.0);
    dia_flux_free(fx);
    write_text(path, "{\"method\": \"otsu\", \"window\": 15, \"offset\": 0.02, \"measure\": "
                     "\"depth\", \"normalise\": 0, \"cap\": 0.49}\n");
    CHECK(dia_flux_read_fit(path, &fit) == BDL_ERR_ARGS);
    remove(path);
}

/// The report writes the time means per cell; NAN where a cell had no data.
static void test_report(const char *dir)
{
    double *img = malloc(sizeof(double) * W * H), data[10 * CELLS];
    dia_table cells;
    striped_image(img);
    truth_cells(&cells, data);
    dia_flux fx = {.fit = otsu_fit(), .density = 1000.0};
    piv_field p;
    make_field(&p, -3.0);
    CHECK(dia_flux_add(&fx, &camera, img, &p.f, &cells) == BDL_OK);
    CHECK(dia_flux_report(&fx, 0.04, dir) == BDL_OK);
    char path[600], line[256];
    snprintf(path, sizeof path, "%s/mass_flux.csv", dir);
    FILE *f = fopen(path, "r");
    int rows = 0, i = -1, j = -1, frames = -1;
    double x = 0, z = 0, image = 0, truth = 0;
    while (f && fgets(line, sizeof line, f))
        if (rows++ == 1 + 3) // the header, then cell 3: i 3, j 0
            sscanf(line, "%d,%d,%lf,%lf,%lf,%lf,%d", &i, &j, &x, &z, &image, &truth, &frames);
    if (f)
        fclose(f);
    CHECK(rows == 1 + CELLS);
    CHECK(i == 3 && j == 0 && frames == 1);
    CHECK_CLOSE(image, 1000.0 * 0.2 * 1.5, 1e-5);
    CHECK_CLOSE(truth, 100.0, 1e-5);
    remove(path);
    free(fx.image_sum), free(fx.truth_sum), free(fx.frames), free(fx.x), free(fx.z);
    free(img);
}

/// Rods placed by hand, rod length 10 px in an image 400 px wide: C(r) lands in the zone of its
/// reference rod's distance from the nearer side wall, and frames are pooled by pairs.
static void test_zones(void)
{
    dia_coalign z;
    memset(&z, 0, sizeof z);
    // frame 1: two parallel rods at the left wall (r 15 px: bin 6), two at right angles at the
    // right wall (r 20: bin 8), a rod 4 L_p from the left wall with one 7 L_p away (r 30: bin
    // 12, 30 degrees), two crossed rods in the middle (r 10: bin 4)
    const double u1[] = {5, 5, 392, 392, 40, 70, 200, 200};
    const double v1[] = {100, 115, 300, 320, 500, 500, 100, 110};
    const double a1[] = {10, 10, -30, 60, 0, 30, 0, 90};
    dia_coalign_add(&z, 1, u1, v1, a1, 8, 10.0, 400);
    // frame 2: three parallel rods in the middle (r 10, 10: bin 4; 14.1: bin 5)
    const double u2[] = {200, 200, 210}, v2[] = {100, 110, 100}, a2[] = {5, 5, 5};
    dia_coalign_add(&z, 1, u2, v2, a2, 3, 10.0, 400);
    double c[DIA_COALIGN_BINS], r[DIA_COALIGN_BINS];
    long pairs[DIA_COALIGN_BINS];
    dia_coalign_zone(&z, 1, 0, c, r, pairs);
    CHECK(pairs[6] == 2 && pairs[8] == 2);
    CHECK_CLOSE(c[6], 1.0, 1e-12);
    CHECK_CLOSE(c[8], -1.0, 1e-12);
    CHECK_CLOSE(r[6], 15.0, 1e-12);
    long all = 0;
    for (int m = 0; m < DIA_COALIGN_BINS; ++m)
        all += pairs[m];
    CHECK(all == 4);
    dia_coalign_zone(&z, 1, 1, c, r, pairs);
    CHECK(pairs[12] == 1);
    CHECK_CLOSE(c[12], 0.5, 1e-12);
    dia_coalign_zone(&z, 1, 2, c, r, pairs);
    CHECK(pairs[12] == 1 && pairs[4] == 2 + 4 && pairs[5] == 2);
    CHECK_CLOSE(c[4], (-2.0 + 4.0) / 6.0, 1e-12); // pooled: not the mean of -1 and 1
    CHECK_CLOSE(c[5], 1.0, 1e-12);
    dia_coalign_zone(&z, 0, 2, c, r, pairs);
    CHECK(pairs[4] == 0 && isnan(c[4]));
}

int main(void)
{
    const char *tmp = getenv("TMPDIR");
    char dir[512];
    snprintf(dir, sizeof dir, "%s/bedlam_dia_flux_XXXXXX", tmp ? tmp : "/tmp");
    const int have_dir = mkdtemp(dir) != NULL;
    CHECK(have_dir);
    test_cell_mean();
    test_flux();
    test_zones();
    if (have_dir) {
        test_fit_file(dir);
        test_report(dir);
        rmdir(dir);
    }
    return bdl_test_summary("test_dia_flux");
}
