// Synthetic camera (DIA) images: the pixel <-> world mapping is exact; a single layer of spheres
// at a known area fraction is recovered by thresholding within 1 %, and noise and blur at the
// documented levels move it by less than the documented amount; the sphere-in-box volume that
// the solids-fraction truth uses is exact; the calibration fit recovers known A and B within 2 %;
// and the velocity exported beside a PIV pair agrees with the displacement of the imaged particles
// between the two frames.
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

#include "check.h"
#include "core/rng.h"
#include "dia/analysis.h"
#include "dia/dia.h"
#include "io/png.h"

static bdl_dia_def ortho_def(int w, int h, double pixel)
{
    bdl_dia_def d = {0};
    d.projection = BDL_DIA_ORTHOGRAPHIC;
    d.position = bdl_v3(0.05, -0.5, 0.1);
    d.target = bdl_v3(0.05, 0.0, 0.1);
    d.up = bdl_v3(0, 0, 1);
    d.width = w, d.height = h;
    d.pixel_size = pixel;
    d.samples = 4;
    d.lighting = BDL_DIA_BACK_LIT;
    d.bright = 0.9;
    d.dark = 0.1;
    d.gamma = 1.0;
    d.bits = 8;
    d.seed = 7;
    return d;
}

static void test_mapping(void)
{
    double worst = 0.0, round_trip = 0.0;
    // Orthographic: 0.2 mm pixels, the view centred on (0.05, ., 0.1), x to the right, z up.
    bdl_dia_camera c;
    bdl_dia_def d = ortho_def(500, 1000, 2e-4);
    CHECK(bdl_dia_camera_init(&c, &d) == BDL_OK);
    const double pts[4][3] = {
        {0.05, 0.0, 0.1}, {0.0, 0.003, 0.2}, {0.1, 0.014, 0.0}, {0.0123, 0.007, 0.0456}};
    for (int k = 0; k < 4; ++k) {
        bdl_vec3 x = bdl_v3(pts[k][0], pts[k][1], pts[k][2]);
        double u, v, z;
        bdl_dia_project(&c, x, &u, &v, &z);
        double eu = 250.0 + (x.x - 0.05) / 2e-4, ev = 500.0 - (x.z - 0.1) / 2e-4;
        worst = fmax(worst, fmax(fabs(u - eu), fabs(v - ev)));
        round_trip = fmax(round_trip, bdl_v3_len(bdl_v3_sub(bdl_dia_unproject(&c, u, v, z), x)));
    }
    // Perspective: a 25 mm lens, 5 um pixels, 0.6 m in front of the bed.
    bdl_dia_def p = d;
    p.projection = BDL_DIA_PERSPECTIVE;
    p.position = bdl_v3(0.05, -0.6, 0.15);
    p.target = bdl_v3(0.05, 0.0, 0.15);
    p.pixel_size = 5e-6;
    p.focal_length = 0.025;
    p.width = 1000, p.height = 2000;
    CHECK(bdl_dia_camera_init(&c, &p) == BDL_OK);
    for (int k = 0; k < 4; ++k) {
        bdl_vec3 x = bdl_v3(pts[k][0], pts[k][1], pts[k][2]);
        double u, v, z;
        bdl_dia_project(&c, x, &u, &v, &z);
        double depth = x.y + 0.6; // pinhole model: u = W/2 + f X / (Z pitch)
        double eu = 500.0 + 0.025 * (x.x - 0.05) / (depth * 5e-6);
        double ev = 1000.0 - 0.025 * (x.z - 0.15) / (depth * 5e-6);
        worst = fmax(worst, fmax(fabs(u - eu), fabs(v - ev)));
        round_trip = fmax(round_trip, bdl_v3_len(bdl_v3_sub(bdl_dia_unproject(&c, u, v, z), x)));
    }
    printf("mapping: worst pixel error %.2e px, world round trip %.2e m\n", worst, round_trip);
    CHECK(worst < 1e-9);
    CHECK(round_trip < 1e-12);

    // A single rendered sphere: its silhouette's centroid is its projected centre.
    CHECK(bdl_dia_camera_init(&c, &p) == BDL_OK);
    bdl_vec3 x = bdl_v3(0.0437, 0.007, 0.1822), vel = bdl_v3(0, 0, 0);
    double r = 1.3e-3;
    uint32_t id = 0;
    bdl_dia_scene s = {1, &x, &vel, &r, &id};
    bdl_dia_image im;
    CHECK(bdl_dia_render(&c, &s, 0, &im) == BDL_OK);
    unsigned char *mask = malloc((size_t)im.width * im.height);
    bdl_dia_threshold(im.final, im.width, im.height, 0, 0, 0.0, mask);
    bdl_dia_blob blob;
    long count = 0;
    bdl_dia_blobs(mask, im.final, im.width, im.height, &blob, 1, &count);
    double u, v, z;
    bdl_dia_project(&c, x, &u, &v, &z);
    printf("one sphere: blob centroid (%.3f, %.3f) px, projected centre (%.3f, %.3f) px\n", blob.u,
           blob.v, u, v);
    CHECK(count == 1);
    CHECK(fabs(blob.u - u) < 0.5 && fabs(blob.v - v) < 0.5);
    free(mask);
    bdl_dia_image_free(&im);
}

/// Spheres of radius r on a square lattice with random jitter, one layer in the plane y = 0.007,
/// covering the whole image: the exact area fraction is the lattice's, n pi r^2 / cell area.
static double layer_fraction(bdl_dia_def d, double spacing, double r, double *exact)
{
    bdl_dia_camera c;
    bdl_dia_camera_init(&c, &d);
    const double w = d.width * d.pixel_size, h = d.height * d.pixel_size;
    const int nx = (int)(w / spacing), nz = (int)(h / spacing); // all inside the image
    long n = (long)nx * nz;
    bdl_vec3 *pos = malloc((size_t)n * sizeof(bdl_vec3)),
             *vel = calloc((size_t)n, sizeof(bdl_vec3));
    double *rad = malloc((size_t)n * sizeof(double));
    uint32_t *id = malloc((size_t)n * sizeof(uint32_t));
    bdl_rng rng;
    bdl_rng_seed(&rng, 3);
    const double slack = 0.5 * spacing - r;
    for (int i = 0; i < nx; ++i)
        for (int k = 0; k < nz; ++k) {
            long m = (long)i * nz + k;
            pos[m] = bdl_v3(
                0.05 + (i + 0.5 - 0.5 * nx) * spacing + bdl_rng_range(&rng, -slack, slack), 0.007,
                0.1 + (k + 0.5 - 0.5 * nz) * spacing + bdl_rng_range(&rng, -slack, slack));
            rad[m] = r;
            id[m] = (uint32_t)m;
        }
    bdl_dia_scene s = {n, pos, vel, rad, id};
    bdl_dia_image im;
    bdl_dia_render(&c, &s, 1, &im);
    *exact = (double)n * BDL_PI * r * r / (w * h); // every disc lies inside the image
    unsigned char *mask = malloc((size_t)im.width * im.height);
    bdl_dia_threshold(im.final, im.width, im.height, d.lighting == BDL_DIA_FRONT_LIT, 0, 0.0, mask);
    double f;
    bdl_dia_cell_fractions(mask, im.width, im.height, 1, 1, &f);
    free(mask);
    bdl_dia_image_free(&im);
    free(pos), free(vel), free(rad), free(id);
    return f;
}

static void test_area_fraction(void)
{
    bdl_dia_def d = ortho_def(400, 400, 1e-4); // 40 x 40 mm at 0.1 mm per pixel
    double exact, f = layer_fraction(d, 3.0e-3, 1.3e-3, &exact);
    printf("single layer, back-lit: thresholded %.5f, exact %.5f (%+.2f %%)\n", f, exact,
           100.0 * (f / exact - 1.0));
    CHECK_MSG(fabs(f / exact - 1.0) < 0.01, "area fraction %g vs %g", f, exact);
    // Documented levels (docs/dia.md): sensor noise sigma 0.02 of full scale and defocus blur
    // sigma 1 px together move the back-lit fraction by less than 1 %.
    bdl_dia_def dn = d;
    dn.noise = 0.02;
    dn.blur = 1.0;
    double fn = layer_fraction(dn, 3.0e-3, 1.3e-3, &exact);
    printf("back-lit with noise 0.02 and blur 1 px: %.5f (%+.2f %% of the clean image's)\n", fn,
           100.0 * (fn / f - 1.0));
    CHECK_MSG(fabs(fn / f - 1.0) < 0.01, "noise and blur moved the fraction by %g", fn / f - 1.0);
    // Front-lit: bright spheres on dark, Lambert shading plus ambient light. The rim is darker
    // than the centre, so a global threshold between the background and the mean sphere level
    // cuts the anti-aliased edge inside the true outline: a documented bias of at most 4 %.
    d.lighting = BDL_DIA_FRONT_LIT;
    d.dark = 0.05;
    d.bright = 1.0;
    d.ambient = 0.5;
    d.light_count = 1;
    d.light_position[0] = bdl_v3(0.05, -0.5, 0.3);
    d.light_intensity[0] = 0.5;
    double ff = layer_fraction(d, 3.0e-3, 1.3e-3, &exact);
    printf("single layer, front-lit: thresholded %.5f (%+.2f %%)\n", ff,
           100.0 * (ff / exact - 1.0));
    CHECK_MSG(ff < exact && ff > 0.96 * exact, "front-lit area fraction %g vs %g", ff, exact);
}

static void test_volume(void)
{
    const double r = 1e-3;
    bdl_vec3 x = bdl_v3(0.0, 0.0, 0.0);
    double full = 4.0 / 3.0 * BDL_PI * r * r * r;
    double whole = bdl_dia_sphere_box_volume(x, r, bdl_v3(-1, -1, -1), bdl_v3(1, 1, 1));
    double half = bdl_dia_sphere_box_volume(x, r, bdl_v3(0, -1, -1), bdl_v3(1, 1, 1));
    double octant = bdl_dia_sphere_box_volume(x, r, bdl_v3(0, 0, 0), bdl_v3(1, 1, 1));
    // A cap of height r/2: pi h^2 (3 r - h)/3.
    double hc = 0.5 * r, cap = BDL_PI * hc * hc * (3.0 * r - hc) / 3.0;
    double capped = bdl_dia_sphere_box_volume(x, r, bdl_v3(-1, -1, 0.5 * r), bdl_v3(1, 1, 1));
    printf("sphere in box: whole %.2e, half %.2e, octant %.2e, cap %.2e (relative errors)\n",
           fabs(whole / full - 1.0), fabs(half / (0.5 * full) - 1.0),
           fabs(octant / (0.125 * full) - 1.0), fabs(capped / cap - 1.0));
    CHECK_CLOSE(whole, full, 1e-6);
    CHECK_CLOSE(half, 0.5 * full, 1e-6);
    CHECK_CLOSE(octant, 0.125 * full, 1e-6);
    CHECK_CLOSE(capped, cap, 1e-5);
}

static void test_fit(void)
{
    // Synthetic data from f3D = A f2D / (B - f2D), A = 0.05, B = 0.45, with noise 0.005.
    const double A = 0.05, B = 0.45;
    enum { N = 400 };
    double x[N], y[N];
    bdl_rng rng;
    bdl_rng_seed(&rng, 12);
    for (int k = 0; k < N; ++k) {
        x[k] = bdl_rng_range(&rng, 0.02, 0.40);
        y[k] = A * x[k] / (B - x[k]) + 0.005 * bdl_rng_normal(&rng);
    }
    bdl_dia_fit f = bdl_dia_fit_model(BDL_DIA_MODEL_RATIONAL, x, y, N);
    bdl_dia_fit g = bdl_dia_fit_model(BDL_DIA_MODEL_POWER, x, y, N);
    printf("fit: A %.5f (%+.2f %%), B %.5f (%+.2f %%), R^2 %.4f, rms %.4f; power law a %.3f b "
           "%.3f R^2 %.4f; cap 0.49 reached at f2D %.4f\n",
           f.p[0], 100.0 * (f.p[0] / A - 1.0), f.p[1], 100.0 * (f.p[1] / B - 1.0), f.r2, f.rms,
           g.p[0], g.p[1], g.r2, bdl_dia_fit_cap_f2d(&f, 0.49));
    CHECK(f.converged);
    CHECK_CLOSE(f.p[0], A, 0.02);
    CHECK_CLOSE(f.p[1], B, 0.02);
    CHECK(f.r2 > g.r2); // the right model fits better
    CHECK_CLOSE(bdl_dia_fit_cap_f2d(&f, 0.49), 0.49 * f.p[1] / (f.p[0] + 0.49), 1e-12);
    CHECK(bdl_dia_fit_apply(&f, 0.44, 0.49) == 0.49);
}

/// Particles moving in solid-body rotation, imaged at t and t + dt: blobs matched between the
/// frames move as the exported truth velocity says.
static void test_piv_pair(void)
{
    bdl_dia_def d = ortho_def(300, 300, 1e-4); // 30 x 30 mm
    d.samples = 3;
    bdl_dia_camera c;
    bdl_dia_camera_init(&c, &d);
    enum { NX = 8, N = NX * NX };
    bdl_vec3 pos[N], pos2[N], vel[N];
    double rad[N];
    uint32_t id[N];
    const double omega = 20.0, dt = 2e-3; // rad/s; the PIV pair's separation [s]
    const bdl_vec3 centre = bdl_v3(0.05, 0.007, 0.1);
    bdl_rng rng;
    bdl_rng_seed(&rng, 9);
    for (int k = 0; k < N; ++k) {
        double px = (k % NX + 0.5) * 0.03 / NX - 0.015 + bdl_rng_range(&rng, -5e-4, 5e-4);
        double pz = (k / NX + 0.5) * 0.03 / NX - 0.015 + bdl_rng_range(&rng, -5e-4, 5e-4);
        pos[k] = bdl_v3(centre.x + px, centre.y, centre.z + pz);
        vel[k] = bdl_v3(-omega * pz, 0.0, omega * px); // rotation about y
        pos2[k] = bdl_v3_madd(pos[k], vel[k], dt);     // the truth moves each on its velocity
        rad[k] = 0.6e-3;
        id[k] = (uint32_t)k;
    }
    bdl_dia_scene s1 = {N, pos, vel, rad, id}, s2 = {N, pos2, vel, rad, id};
    bdl_dia_image a, b;
    bdl_dia_render(&c, &s1, 0, &a);
    bdl_dia_render(&c, &s2, 1, &b);
    bdl_dia_truth_def t = {{1, 1}, 0.0, 0.014, 2.0 * rad[0]};
    t.front = 0.5 - 0.001, t.back = 0.5 + 0.015; // depths from the camera at y = -0.5
    long visible[N];
    bdl_dia_truth(&c, &s1, &a, &t, NULL, visible);
    unsigned char *ma = malloc(300 * 300), *mb = malloc(300 * 300);
    bdl_dia_threshold(a.final, 300, 300, 0, 0, 0.0, ma);
    bdl_dia_threshold(b.final, 300, 300, 0, 0, 0.0, mb);
    bdl_dia_blob ba[2 * N], bb[2 * N];
    long na = 0, nb = 0;
    bdl_dia_blobs(ma, a.final, 300, 300, ba, 2 * N, &na);
    bdl_dia_blobs(mb, b.final, 300, 300, bb, 2 * N, &nb);
    // Track: each blob of frame a to the nearest blob of frame b; compare its displacement with
    // the truth velocity of the particle whose projected centre is nearest the blob, and, per
    // image cell, the mean tracked displacement with the cell's exported truth (du, dv).
    enum { CELLS = 3 };
    bdl_dia_truth_def tc = t;
    tc.cells[0] = tc.cells[1] = CELLS;
    bdl_dia_cell_truth cells[CELLS * CELLS];
    bdl_dia_truth(&c, &s1, &a, &tc, cells, NULL);
    double cell_sum[CELLS * CELLS][2] = {{0}}, cell_n[CELLS * CELLS] = {0};
    double worst = 0.0, mean_speed = 0.0;
    int tracked = 0;
    for (long i = 0; i < na; ++i) {
        long best = -1;
        double bd = INFINITY;
        for (long j = 0; j < nb; ++j) {
            double dd = hypot(bb[j].u - ba[i].u, bb[j].v - ba[i].v);
            if (dd < bd)
                bd = dd, best = j;
        }
        int p = -1;
        double pd = INFINITY;
        for (int k = 0; k < N; ++k) {
            double u, v, z;
            bdl_dia_project(&c, pos[k], &u, &v, &z);
            double dd = hypot(u - ba[i].u, v - ba[i].v);
            if (dd < pd)
                pd = dd, p = k;
        }
        // Whole particles only (blobs cut by the image edge move their centroid).
        double u, v, z;
        bdl_dia_project(&c, pos[p], &u, &v, &z);
        double rp = rad[p] / d.pixel_size;
        if (best < 0 || u < rp + 2 || v < rp + 2 || u > 298 - rp || v > 298 - rp)
            continue;
        double du = (bb[best].u - ba[i].u) / dt, dv = (bb[best].v - ba[i].v) / dt; // px/s
        double tu = bdl_v3_dot(vel[p], c.right) / d.pixel_size;
        double tv = bdl_v3_dot(vel[p], c.down) / d.pixel_size;
        worst = fmax(worst, hypot(du - tu, dv - tv) * dt); // in px of displacement
        mean_speed += hypot(tu, tv) * dt;
        ++tracked;
        CHECK(visible[p] > 0);
        int cell = (int)(ba[i].v * CELLS / 300) * CELLS + (int)(ba[i].u * CELLS / 300);
        cell_sum[cell][0] += du * dt, cell_sum[cell][1] += dv * dt, cell_n[cell] += 1.0;
    }
    // The exported cell velocity is the visible-area mean of the particles seen in the cell; the
    // tracked one the mean over whole blobs whose centres lie in it. Particles cut by a cell's
    // edge weigh differently in the two, so they agree to a fraction of the spread of the
    // displacements across a cell (here about 1.5 px).
    double worst_cell = 0.0;
    for (int k = 0; k < CELLS * CELLS; ++k) {
        if (cell_n[k] < 3)
            continue;
        double mu = cell_sum[k][0] / cell_n[k], mv = cell_sum[k][1] / cell_n[k];
        worst_cell = fmax(worst_cell, hypot(mu - cells[k].du * dt, mv - cells[k].dv * dt));
    }
    printf("PIV pair: per image cell, tracked mean displacement vs exported truth: worst %.3f px\n",
           worst_cell);
    CHECK_MSG(worst_cell < 0.3, "cell truth differs from the tracked mean by %g px", worst_cell);
    printf("PIV pair: %d particles tracked, mean displacement %.2f px, worst difference from the "
           "truth %.3f px\n",
           tracked, mean_speed / tracked, worst);
    CHECK(tracked >= 30);
    CHECK_MSG(worst < 0.05, "tracked displacement differs from the truth by %g px", worst);
    free(ma), free(mb);
    bdl_dia_image_free(&a);
    bdl_dia_image_free(&b);
}

/// Cell truth on a random single layer: the cells' solids add up to the particles' volume, the
/// first layer holds all of it when it spans the layer, and the covered samples per cell match
/// the rendered image.
static void test_truth(void)
{
    bdl_dia_def d = ortho_def(200, 300, 1e-4); // 20 x 30 mm
    bdl_dia_camera c;
    bdl_dia_camera_init(&c, &d);
    enum { N = 40 };
    bdl_vec3 pos[N], vel[N];
    double rad[N];
    uint32_t id[N];
    bdl_rng rng;
    bdl_rng_seed(&rng, 5);
    double volume = 0.0;
    for (int k = 0; k < N; ++k) { // overlaps allowed: the truth counts volume, not particles
        rad[k] = bdl_rng_range(&rng, 0.4e-3, 1.2e-3);
        pos[k] = bdl_v3(bdl_rng_range(&rng, 0.041 + rad[k], 0.059 - rad[k]),
                        bdl_rng_range(&rng, 0.0015, 0.0025),
                        bdl_rng_range(&rng, 0.086 + rad[k], 0.114 - rad[k]));
        vel[k] = bdl_v3(0.1 * k, 0.0, -0.05 * k);
        id[k] = (uint32_t)k;
        volume += 4.0 / 3.0 * BDL_PI * rad[k] * rad[k] * rad[k];
    }
    bdl_dia_scene s = {N, pos, vel, rad, id};
    bdl_dia_image im;
    bdl_dia_render(&c, &s, 0, &im);
    // The bed: depth 0 to 4 mm behind y = 0 (the camera is at y = -0.5); the layer 4 mm deep.
    bdl_dia_truth_def t = {{4, 5}, 0.5, 0.504, 0.004};
    bdl_dia_cell_truth cells[20];
    CHECK(bdl_dia_truth(&c, &s, &im, &t, cells, NULL) == BDL_OK);
    const double cell_volume = (0.02 / 4) * (0.03 / 5) * 0.004;
    double sum_depth = 0.0, sum_layer = 0.0, covered = 0.0, image_covered = 0.0;
    for (int k = 0; k < 20; ++k) {
        sum_depth += cells[k].solids_depth * cell_volume;
        sum_layer += cells[k].solids_layer * cell_volume;
        covered += cells[k].area_fraction / 20.0;
    }
    for (long k = 0; k < (long)im.width * im.samples * im.height * im.samples; ++k)
        image_covered += im.hit[k] >= 0;
    image_covered /= (double)im.width * im.samples * im.height * im.samples;
    printf("truth: cells hold %.8f of the particles' volume (first layer %.8f); covered %.5f of "
           "the image\n",
           sum_depth / volume, sum_layer / volume, covered);
    CHECK_CLOSE(sum_depth, volume, 1e-6);
    CHECK_CLOSE(sum_layer, volume, 1e-6);
    CHECK_CLOSE(covered, image_covered, 1e-12);
    bdl_dia_image_free(&im);
}

/// 8- and 16-bit grey PNGs read back to what was written, within half a grey level.
static void test_png_gray(void)
{
    bdl_dia_image im = {0};
    im.width = 37, im.height = 23;
    im.final = malloc(37 * 23 * sizeof(double));
    for (int k = 0; k < 37 * 23; ++k)
        im.final[k] = (k * 7919 % 1000) / 999.0;
    for (int bits = 8; bits <= 16; bits += 8) {
        char path[512];
        const char *tmp = getenv("TMPDIR");
        snprintf(path, sizeof path, "%s/bedlam_dia_test_%d_%d.png", tmp ? tmp : "/tmp", bits,
                 (int)getpid());
        CHECK(bdl_dia_write_png(&im, bits, path) == BDL_OK);
        double *back = NULL;
        int w = 0, h = 0, depth = 0;
        CHECK(bdl_png_read_gray(path, &back, &w, &h, &depth) == BDL_OK);
        CHECK(w == 37 && h == 23 && depth == bits);
        double worst = 0.0, full = bits == 8 ? 255.0 : 65535.0;
        for (int k = 0; back && k < 37 * 23; ++k)
            worst = fmax(worst, fabs(back[k] - im.final[k]) * full);
        printf("PNG %d-bit grey: worst round-trip error %.3f grey levels\n", bits, worst);
        CHECK(worst <= 0.5 + 1e-9);
        free(back);
        remove(path);
    }
    free(im.final);
}

int main(void)
{
    test_png_gray();
    test_truth();
    test_mapping();
    test_volume();
    test_area_fraction();
    test_fit();
    test_piv_pair();
    return bdl_test_summary("test_dia");
}
