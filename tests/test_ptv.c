// PTV (dia/ptv.h): particles moving at known velocities are linked without a single wrong link,
// and the tracks are exactly the runs of at least 4 consecutive detections, when every particle
// moves less than half its distance to any other (with missed detections, particles entering
// and leaving); discs rendered in frames, detected as blobs and tracked give their velocities
// within 0.02 px per frame; and the 2D coordination number is 6 inside a hexagonal lattice, and
// for random points, corrected by the part of the search disc inside the bed, unbiased at the
// edges.
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "check.h"
#include "dia/analysis.h"
#include "dia/ptv.h"
#include "dia_draw.h"

enum { FRAMES = 15, MAXP = 400 };

typedef struct motion {
    int n;
    double x[MAXP], y[MAXP], vx[MAXP], vy[MAXP]; ///< position at frame 0, velocity [px/frame]
} motion;

/// Particles in a box of side L at random positions and velocities (speed <= vmax) that stay at
/// least `gap` px from one another in every frame (a candidate is kept only if it does).
static void make_motion(motion *m, int want, double side, double vmax, double gap, bdl_rng *rng)
{
    m->n = 0;
    for (int tries = 0; tries < 200 * want && m->n < want; ++tries) {
        double x = bdl_rng_range(rng, 0, side), y = bdl_rng_range(rng, 0, side);
        double s = vmax * sqrt(bdl_rng_uniform(rng)), a = bdl_rng_range(rng, 0, 6.283185307);
        double vx = s * cos(a), vy = s * sin(a);
        int ok = 1;
        for (int k = 0; k < m->n && ok; ++k)
            for (int f = 0; f < FRAMES && ok; ++f)
                ok = hypot(x + vx * f - m->x[k] - m->vx[k] * f,
                           y + vy * f - m->y[k] - m->vy[k] * f) >= gap;
        if (ok) {
            m->x[m->n] = x, m->y[m->n] = y, m->vx[m->n] = vx, m->vy[m->n] = vy;
            m->n++;
        }
    }
}

static void test_linking(void)
{
    const double side = 300.0, view0 = 20.0, view1 = 280.0; // detected only inside the view
    motion m;
    bdl_rng rng;
    bdl_rng_seed(&rng, 8);
    make_motion(&m, 350, side, 3.0, 8.0, &rng);
    static double u[FRAMES * MAXP], v[FRAMES * MAXP];
    static int who[FRAMES * MAXP], seen[FRAMES][MAXP];
    long start[FRAMES + 1], n = 0;
    for (int f = 0; f < FRAMES; ++f) {
        start[f] = n;
        for (int k = 0; k < m.n; ++k) {
            double x = m.x[k] + m.vx[k] * f, y = m.y[k] + m.vy[k] * f;
            seen[f][k] = x >= view0 && x < view1 && y >= view0 && y < view1 &&
                         bdl_rng_uniform(&rng) > 0.05; // 5 % missed
            if (seen[f][k])
                u[n] = x, v[n] = y, who[n] = k, ++n;
        }
    }
    start[FRAMES] = n;
    // The answer: every run of >= 4 consecutive detections of a particle is a track.
    long runs = 0, run_points = 0;
    for (int k = 0; k < m.n; ++k)
        for (int f = 0, len = 0; f <= FRAMES; ++f) {
            if (f < FRAMES && seen[f][k]) {
                ++len;
                continue;
            }
            runs += len >= 4, run_points += len >= 4 ? len : 0, len = 0;
        }
    bdl_dia_tracks t;
    CHECK(bdl_dia_ptv_link(u, v, start, FRAMES, 4.5, 4, &t) == BDL_OK);
    long wrong = 0, links = 0;
    for (long k = 0; k < t.count; ++k)
        for (long p = t.start[k]; p + 1 < t.start[k + 1]; ++p, ++links)
            wrong += who[t.point[p]] != who[t.point[p + 1]];
    printf("PTV: %d particles (speed <= 3 px/frame, >= 8 px apart), %d frames, 5 %% missed: %ld "
           "tracks (%ld expected), %ld points in them (%ld expected), %ld of %ld links wrong\n",
           m.n, FRAMES, t.count, runs, t.start[t.count], run_points, wrong, links);
    CHECK(m.n > 300);
    CHECK(t.count == runs && t.start[t.count] == run_points && wrong == 0);
    for (long k = 0; k < t.count; ++k) // each track starts where a run starts
        CHECK(t.first_frame[k] == 0 || !seen[t.first_frame[k] - 1][who[t.point[t.start[k]]]]);
    bdl_dia_tracks_free(&t);
    CHECK(bdl_dia_ptv_link(u, v, start, FRAMES, 0.0, 4, &t) == BDL_ERR_ARGS);
}

/// Discs (r = 4 px, Gaussian edge) drawn in 8 frames, detected by threshold and blobs, linked,
/// and each track's velocity (least-squares slope of its positions) compared with the truth.
static void test_tracked_images(void)
{
    enum { W = 320, H = 320, F = 8 };
    motion m;
    bdl_rng rng;
    bdl_rng_seed(&rng, 12);
    make_motion(&m, 40, 220.0, 5.0, 30.0, &rng);
    static double u[F * 100], v[F * 100];
    long start[F + 1], n = 0;
    double *img = malloc(sizeof(double) * W * H);
    unsigned char *mask = malloc(W * H);
    for (int f = 0; f < F; ++f) {
        for (int k = 0; k < W * H; ++k)
            img[k] = 0.1;
        for (int k = 0; k < m.n; ++k) // offset by 30 + 20 px: inside the image in every frame
            draw_capsule(img, W, H, 50 + m.x[k] + m.vx[k] * f, 50 + m.y[k] + m.vy[k] * f, 8.0, 8.0,
                         0.0, 0.8, 4);
        add_noise(img, W * H, 0.01, &rng);
        bdl_dia_threshold(img, W, H, 1, 0, 0.0, mask);
        bdl_dia_blob blobs[100];
        long count = 0;
        bdl_dia_blobs(mask, img, W, H, blobs, 100, &count);
        start[f] = n;
        for (long b = 0; b < count && b < 100; ++b)
            u[n] = blobs[b].u, v[n] = blobs[b].v, ++n;
    }
    start[F] = n;
    bdl_dia_tracks t;
    CHECK(bdl_dia_ptv_link(u, v, start, F, 8.0, 4, &t) == BDL_OK);
    double worst = 0.0;
    int full = 0;
    for (long k = 0; k < t.count; ++k) {
        const long p0 = t.start[k], len = t.start[k + 1] - p0;
        full += len == F;
        double sf = 0, su = 0, sv = 0, sff = 0, sfu = 0, sfv = 0;
        for (long j = 0; j < len; ++j) {
            double f = (double)j, x = u[t.point[p0 + j]], y = v[t.point[p0 + j]];
            sf += f, su += x, sv += y, sff += f * f, sfu += f * x, sfv += f * y;
        }
        double den = len * sff - sf * sf;
        double vx = (len * sfu - sf * su) / den, vy = (len * sfv - sf * sv) / den;
        int best = 0; // the particle that was at the track's first point
        double bd = INFINITY, x0 = u[t.point[p0]] - 50, y0 = v[t.point[p0]] - 50;
        for (int q = 0; q < m.n; ++q) {
            double d = hypot(m.x[q] + m.vx[q] * t.first_frame[k] - x0,
                             m.y[q] + m.vy[q] * t.first_frame[k] - y0);
            if (d < bd)
                bd = d, best = q;
        }
        worst = fmax(worst, hypot(vx - m.vx[best], vy - m.vy[best]));
    }
    printf("PTV on images: %d discs (r = 4 px, up to 5 px/frame), %ld tracks, %d over all %d "
           "frames; track velocities within %.4f px/frame of the truth\n",
           m.n, t.count, full, F, worst);
    CHECK(t.count == m.n && full == m.n);
    CHECK(worst < 0.02);
    bdl_dia_tracks_free(&t);
    free(img), free(mask);
}

static void test_coordination(void)
{
    // Hexagonal lattice, spacing 10 px, cut-off 12 px: 6 neighbours inside.
    enum { NX = 20, NY = 20 };
    static double u[4000], v[4000], cn[4000];
    long n = 0;
    for (int j = 0; j < NY; ++j)
        for (int i = 0; i < NX; ++i)
            u[n] = 10.0 * i + 5.0 * (j % 2), v[n] = 10.0 * sqrt(0.75) * j, ++n;
    CHECK(bdl_dia_coordination_2d(u, v, n, 12.0, NULL, cn) == BDL_OK);
    int interior_six = 1;
    for (long k = 0; k < n; ++k) {
        int i = (int)(k % NX), j = (int)(k / NX);
        if (i > 0 && j > 0 && i < NX - 1 && j < NY - 1)
            interior_six &= cn[k] == 6.0;
    }
    CHECK(interior_six);
    CHECK(cn[0] == 2.0); // corner of an even row: right and the one above-right
    // Random points: the mean count is (n - 1) / area * pi r^2 away from the edges; corrected by
    // the part of the disc inside the bed, the edge particles agree with it too.
    bdl_rng rng;
    bdl_rng_seed(&rng, 4);
    const double side = 1000.0, r = 20.0, bounds[4] = {0.0, 0.0, side, side};
    n = 4000;
    for (long k = 0; k < n; ++k)
        u[k] = bdl_rng_range(&rng, 0, side), v[k] = bdl_rng_range(&rng, 0, side);
    double expected = (n - 1) / (side * side) * 3.14159265358979323846 * r * r, raw = 0, cor = 0;
    double edge_raw = 0.0, edge_cor = 0.0;
    int edge = 0;
    bdl_dia_coordination_2d(u, v, n, r, NULL, cn);
    for (long k = 0; k < n; ++k)
        raw += cn[k] / n;
    static double cn_raw[4000];
    for (long k = 0; k < n; ++k)
        cn_raw[k] = cn[k];
    bdl_dia_coordination_2d(u, v, n, r, bounds, cn);
    for (long k = 0; k < n; ++k) {
        cor += cn[k] / n;
        if (fmin(fmin(u[k], side - u[k]), fmin(v[k], side - v[k])) < 0.5 * r)
            edge_raw += cn_raw[k], edge_cor += cn[k], ++edge;
    }
    printf("2D coordination, random points: expected %.3f; mean %.3f uncorrected, %.3f with the "
           "wall correction; within r/2 of an edge (%d points) %.3f and %.3f\n",
           expected, raw, cor, edge, edge_raw / edge, edge_cor / edge);
    CHECK(fabs(cor - expected) < 0.15 && raw < expected - 0.1);
    CHECK(fabs(edge_cor / edge - expected) < 0.5 && edge_raw / edge < 0.8 * expected);
    // The disc-in-rectangle area: half a disc, a quarter, all.
    const double box[4] = {0.0, 0.0, 100.0, 100.0}, pi = 3.14159265358979323846;
    CHECK_CLOSE(bdl_dia_disc_in_rect(0.0, 50.0, 10.0, box), 0.5 * pi * 100.0, 1e-4);
    CHECK_CLOSE(bdl_dia_disc_in_rect(100.0, 100.0, 10.0, box), 0.25 * pi * 100.0, 1e-4);
    CHECK_CLOSE(bdl_dia_disc_in_rect(50.0, 50.0, 10.0, box), pi * 100.0, 1e-4);
}

int main(void)
{
    test_linking();
    test_tracked_images();
    test_coordination();
    return bdl_test_summary("test_ptv");
}
