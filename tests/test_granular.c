// Granular analyses on constructed inputs with known answers: coordination and the
// multi-contact ratio, the normal forces and contact counts of a contact list, the bed-height
// quantile, Lacey's index of segregated, random and
// perfectly ordered mixtures, force networks of a chain and a lattice (and their independence
// from the contacts' order), the fit of the force distribution to samples drawn from it, and the
// orientation order of aligned, isotropic and planar sets of axes; the multi-pass spanning trees
// of a square and a chain (which edges each pass adds), and the force correlation of three
// contacts on a line.
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "analysis/granular.h"
#include "analysis/spanning.h"
#include "check.h"
#include "core/rng.h"

static void test_coordination(void)
{
    const uint8_t count[] = {0, 1, 2, 3, 0, 1};
    bdl_coordination_stats s = bdl_coordination(count, 6);
    CHECK_CLOSE(s.mean, 7.0 / 6.0, 1e-15);
    CHECK(s.in_contact == 4);
    CHECK_CLOSE(s.multi_contact_ratio, 0.5, 1e-15);
    CHECK_CLOSE(s.mean_touching, 7.0 / 4.0, 1e-15);
    s = bdl_coordination(count, 1); // one particle, no contact
    CHECK(s.mean == 0.0 && s.multi_contact_ratio == 0.0 && s.mean_touching == 0.0);
}

static void test_contact_forces(void)
{
    // A chain 0-1-2 pressed, 0-2 touching without force, 3-4 apart, one wall contact.
    const bdl_contact_rec c[] = {{0, 1, 2.0}, {1, 2, 4.0}, {2, -1, 3.0}, {0, 2, 0.0}, {3, 4, 6.0}};
    double fn[5];
    uint8_t count[6] = {0};
    bdl_contact_forces s = bdl_contact_forces_of(c, 5, fn, count);
    CHECK(s.walls == 1 && s.pairs == 3);
    CHECK_CLOSE(s.mean, 4.0, 1e-15);
    CHECK(fn[0] == 2.0 && fn[1] == 4.0 && fn[2] == 6.0);
    CHECK(count[0] == 1 && count[1] == 2 && count[2] == 1 && count[3] == 1 && count[4] == 1);
    CHECK(count[5] == 0);
    const bdl_coordination_stats z = bdl_coordination(count, 6);
    CHECK(z.in_contact == 5);
    CHECK_CLOSE(z.mean_touching, 6.0 / 5.0, 1e-15);
    // A particle pressed by 300 others: its count stops at 255, what a uint8_t holds.
    enum { MANY = 300 };
    static bdl_contact_rec star[MANY];
    static double star_fn[MANY];
    static uint8_t star_count[MANY + 1];
    for (int k = 0; k < MANY; ++k)
        star[k] = (bdl_contact_rec){0, k + 1, 1.0};
    s = bdl_contact_forces_of(star, MANY, star_fn, star_count);
    CHECK(s.pairs == MANY && star_count[0] == 255 && star_count[MANY] == 1);
    s = bdl_contact_forces_of(c, 0, fn, count); // no contacts
    CHECK(s.walls == 0 && s.pairs == 0 && s.mean == 0.0);
}

static void test_height_quantile(void)
{
    enum { N = 100 };
    double h[N];
    for (int i = 0; i < N; ++i)
        h[i] = (double)((i * 37) % N + 1); // 1..100, shuffled
    CHECK(bdl_height_quantile(h, N, 0.95) == 95.0);
    CHECK(bdl_height_quantile(h, N, 1.0) == 100.0);
    CHECK(bdl_height_quantile(h, N, 0.0) == 1.0);
    CHECK(isnan(bdl_height_quantile(h, 0, 0.5)));
}

static void test_lacey(void)
{
    enum { N = 40000 };
    static bdl_vec3 pos[N];
    static uint8_t a[N];
    bdl_rng rng;
    bdl_rng_seed(&rng, 11);
    const bdl_vec3 lo = {0, 0, 0}, hi = {1, 1, 1};
    const int grid[3] = {10, 10, 10}, columns[3] = {10, 10, 1}, layers[3] = {1, 1, 10};
    // Segregated: species A below z = 0.5, B above.
    for (int i = 0; i < N; ++i) {
        pos[i] = (bdl_vec3){bdl_rng_uniform(&rng), bdl_rng_uniform(&rng), bdl_rng_uniform(&rng)};
        a[i] = pos[i].z < 0.5;
    }
    double m_layers = bdl_lacey(pos, a, N, lo, hi, layers, 5);
    double m_columns = bdl_lacey(pos, a, N, lo, hi, columns, 5);
    double m_grid = bdl_lacey(pos, a, N, lo, hi, grid, 5);
    printf("lacey, segregated vertically: layers %.4f (0), columns %.4f (1), grid %.4f (0)\n",
           m_layers, m_columns, m_grid);
    // Every layer pure: s^2 = s0^2 and M = 0 when half the particles are A; random positions put
    // p within about 0.005 of 1/2, which moves M by about (p - 1/2)^2 / s0^2 = 1e-4.
    CHECK(fabs(m_layers) < 2e-3);
    CHECK(fabs(m_grid) < 2e-3);
    // Columns of 400 particles each hold A at p = 0.5 up to sampling noise: M = 1 +- a few
    // sampling errors of s^2 (its relative error is sqrt(2/100) for 100 columns).
    CHECK(fabs(m_columns - 1.0) < 0.5);
    // Segregated with unequal cells: A packed three times as densely in the lower half as B in
    // the upper (small particles below large ones), p = 3/4. Weighted by count, every pure layer
    // is s0^2 and M = 0; unweighted (s^2 = 5/16 against s0^2 = 3/16), M would be -2/3.
    {
        int m = 0;
        for (int i = 0; i < N; ++i) {
            double z = bdl_rng_uniform(&rng);
            if (i % 4 == 3) { // a quarter of the particles: B above
                pos[m] = (bdl_vec3){bdl_rng_uniform(&rng), bdl_rng_uniform(&rng), 0.5 + 0.5 * z};
                a[m++] = 0;
            } else {
                pos[m] = (bdl_vec3){bdl_rng_uniform(&rng), bdl_rng_uniform(&rng), 0.5 * z};
                a[m++] = 1;
            }
        }
        double m_dense = bdl_lacey(pos, a, m, lo, hi, layers, 5);
        printf("lacey, segregated, A three times denser: layers %.4f (0)\n", m_dense);
        CHECK(fabs(m_dense) < 2e-3);
    }
    // Random: labels independent of position; M = 1 within the sampling error of s^2.
    for (int i = 0; i < N; ++i)
        a[i] = bdl_rng_uniform(&rng) < 0.3;
    double m_random = bdl_lacey(pos, a, N, lo, hi, grid, 5);
    printf("lacey, random: %.4f (1)\n", m_random);
    CHECK(fabs(m_random - 1.0) < 0.3);
    // Ordered: a lattice with exactly one A in every cell of 4: s^2 = 0 and M = 1/(1 - 1/nbar).
    int k = 0;
    for (int ix = 0; ix < 20; ++ix)
        for (int iy = 0; iy < 20; ++iy)
            for (int iz = 0; iz < 10; ++iz) {
                pos[k] = (bdl_vec3){(ix + 0.5) / 20.0, (iy + 0.5) / 20.0, (iz + 0.5) / 10.0};
                a[k] = ix % 2 == 0 && iy % 2 == 0;
                ++k;
            }
    const int cells4[3] = {10, 10, 10};
    double m_ordered = bdl_lacey(pos, a, k, lo, hi, cells4, 1);
    CHECK_CLOSE(m_ordered, 1.0 / (1.0 - 1.0 / 4.0), 1e-12);
    // One species only, or a single cell: undefined.
    for (int i = 0; i < k; ++i)
        a[i] = 1;
    CHECK(isnan(bdl_lacey(pos, a, k, lo, hi, cells4, 1)));
    const int one[3] = {1, 1, 1};
    CHECK(isnan(bdl_lacey(pos, a, k, lo, hi, one, 1)));
}

static void test_networks_chain(void)
{
    // 0-1-2-3 a chain, 5-6 a pair, 4 alone, 7-8 touching without force, 9 on a wall.
    bdl_vec3 pos[10];
    for (int i = 0; i < 10; ++i)
        pos[i] = (bdl_vec3){i * 1e-3, 0, 0};
    bdl_contact_rec c[] = {{2, 3, 1.0}, {0, 1, 2.0}, {6, 5, 0.5},
                           {1, 2, 3.0}, {7, 8, 0.0}, {9, -1, 4.0}};
    const long nc = sizeof c / sizeof c[0];
    int32_t label[10], label2[10];
    bdl_network_stats s;
    CHECK(bdl_force_networks(10, c, nc, 0.0, pos, label, &s) == BDL_OK);
    CHECK(s.networks == 2);
    CHECK(s.largest == 4 && s.largest_edges == 3);
    CHECK_CLOSE(s.largest_mean_z, 1.5, 1e-15);
    CHECK_CLOSE(s.largest_length, 3e-3, 1e-12);
    CHECK(s.other_edges == 1);
    CHECK(label[0] == 0 && label[3] == 0 && label[5] == 5 && label[6] == 5 && label[4] == 4);
    CHECK(label[7] == 7 && label[8] == 8 && label[9] == 9);
    // The same contacts in reverse order and with i, j swapped: the same labels.
    bdl_contact_rec r[6];
    for (long k = 0; k < nc; ++k) {
        r[k] = c[nc - 1 - k];
        if (r[k].j >= 0) {
            int32_t t = r[k].i;
            r[k].i = r[k].j;
            r[k].j = t;
        }
    }
    CHECK(bdl_force_networks(10, r, nc, 0.0, NULL, label2, &s) == BDL_OK);
    int same = 1;
    for (int i = 0; i < 10; ++i)
        same &= label[i] == label2[i];
    CHECK(same);
    // Only forces above 1.5: 0-1 and 1-2 remain.
    CHECK(bdl_force_networks(10, c, nc, 1.5, pos, NULL, &s) == BDL_OK);
    CHECK(s.networks == 1 && s.largest == 3 && s.largest_edges == 2 && s.other_edges == 0);
}

static void test_networks_lattice(void)
{
    // A simple cubic lattice of 10^3 particles, every nearest pair in contact.
    enum { L = 10, N = L * L * L };
    static bdl_vec3 pos[N];
    static bdl_contact_rec c[3 * N];
    long nc = 0;
    const double a = 2e-3;
    for (int x = 0; x < L; ++x)
        for (int y = 0; y < L; ++y)
            for (int z = 0; z < L; ++z) {
                int i = (x * L + y) * L + z;
                pos[i] = (bdl_vec3){x * a, y * a, z * a};
                if (x + 1 < L)
                    c[nc++] = (bdl_contact_rec){i, i + L * L, 1.0};
                if (y + 1 < L)
                    c[nc++] = (bdl_contact_rec){i, i + L, 1.0};
                if (z + 1 < L)
                    c[nc++] = (bdl_contact_rec){i, i + 1, 1.0};
            }
    bdl_network_stats s;
    CHECK(bdl_force_networks(N, c, nc, 0.0, pos, NULL, &s) == BDL_OK);
    CHECK(s.networks == 1 && s.largest == N && s.largest_edges == 3 * 9 * 100);
    CHECK_CLOSE(s.largest_mean_z, 5.4, 1e-12);
    CHECK_CLOSE(s.largest_length, sqrt(3.0) * 9 * a, 1e-12);
}

/// Mean of P(f) = (1 - b e^(-f^2)) e^(-beta f) (unnormalised), by the midpoint rule to f = 60.
static double pdf_mean(double b, double beta, double *norm)
{
    double s0 = 0.0, s1 = 0.0, h = 1e-3;
    for (double f = 0.5 * h; f < 60.0; f += h) {
        double p = (1.0 - b * exp(-f * f)) * exp(-beta * f);
        s0 += p * h;
        s1 += f * p * h;
    }
    *norm = s0;
    return s1 / s0;
}

static void test_force_pdf(void)
{
    // b = 0.8 and the beta that makes the mean 1, so f = F/<F> has exactly this density.
    const double b = 0.8;
    double lo = 0.5, hi = 3.0, norm = 0.0;
    for (int it = 0; it < 60; ++it) {
        double mid = 0.5 * (lo + hi);
        if (pdf_mean(b, mid, &norm) > 1.0)
            lo = mid;
        else
            hi = mid;
    }
    const double beta = 0.5 * (lo + hi);
    pdf_mean(b, beta, &norm);
    const double a = 1.0 / norm;
    enum { N = 400000 };
    double *fn = malloc(N * sizeof(double));
    CHECK(fn != NULL);
    if (!fn)
        return;
    bdl_rng rng;
    bdl_rng_seed(&rng, 5);
    // Rejection from the exponential e^(-beta f): accept with 1 - b e^(-f^2) <= 1.
    for (long k = 0; k < N;) {
        double f = -log(1.0 - bdl_rng_uniform(&rng)) / beta;
        if (bdl_rng_uniform(&rng) < 1.0 - b * exp(-f * f))
            fn[k++] = 3.7 * f; // any force unit: the fit sees F / <F>
    }
    enum { BINS = 40 };
    double centre[BINS], pdf[BINS];
    bdl_force_pdf_fit fit;
    CHECK(bdl_force_pdf(fn, N, BINS, 5.0, centre, pdf, &fit) == BDL_OK);
    printf("force pdf: fitted a %.3f b %.3f beta %.3f (true %.3f %.3f %.3f), rms %.2g\n", fit.a,
           fit.b, fit.beta, a, b, beta, fit.rms);
    // Sampling noise of 400 000 forces in 40 bins, and the sample mean's own error (0.2 %):
    CHECK_CLOSE(fit.beta, beta, 0.03);
    CHECK_CLOSE(fit.b, b, 0.05);
    CHECK_CLOSE(fit.a, a, 0.03);
    CHECK_CLOSE(bdl_force_pdf_eval(&fit, 1.0), a * (1.0 - b * exp(-1.0)) * exp(-beta), 0.03);
    CHECK(bdl_force_pdf(fn, 5, BINS, 5.0, centre, pdf, &fit) == BDL_ERR_ARGS);
    free(fn);
}

/// Orientation order: aligned axes give S = 1 (whatever the direction, and for either sign);
/// 2e5 isotropic axes S ~ 0 and <|cos|> ~ 1/2; axes spread over the horizontal plane S ~ 1/4
/// and <|cos|> = 0; the tolerances are a few standard errors of the samples.
static void test_orientation(void)
{
    bdl_orientation_sums aligned = {0}, iso = {0}, flat = {0}, halves[2] = {{0}};
    const bdl_vec3 up = bdl_v3(0, 0, 1), d = bdl_v3_normalize(bdl_v3(1, 2, -2));
    for (int k = 0; k < 10; ++k)
        bdl_orientation_add(&aligned, bdl_v3_scale(d, k % 2 ? 1.0 : -1.0), up);
    CHECK_CLOSE(bdl_orientation_order(&aligned), 1.0, 1e-12);
    CHECK_CLOSE(bdl_orientation_vertical(&aligned), 2.0 / 3.0, 1e-12);
    bdl_rng rng;
    bdl_rng_seed(&rng, 3);
    const long n = 200000;
    for (long k = 0; k < n; ++k) {
        bdl_vec3 u;
        u.x = bdl_rng_normal(&rng);
        u.y = bdl_rng_normal(&rng);
        u.z = bdl_rng_normal(&rng);
        bdl_orientation_add(&iso, bdl_v3_normalize(u), up);
        const bdl_vec3 h = bdl_v3_normalize(bdl_v3(u.x, u.y, 0.0));
        bdl_orientation_add(&flat, h, up);
        bdl_orientation_add(&halves[k % 2], h, up);
    }
    const double s_iso = bdl_orientation_order(&iso), s_flat = bdl_orientation_order(&flat);
    printf("orientation: isotropic S = %.4f <|cos|> = %.4f; planar S = %.4f\n", s_iso,
           bdl_orientation_vertical(&iso), s_flat);
    CHECK(fabs(s_iso) < 0.01);
    CHECK(fabs(bdl_orientation_vertical(&iso) - 0.5) < 0.003);
    CHECK(fabs(s_flat - 0.25) < 0.01);
    CHECK(bdl_orientation_vertical(&flat) == 0.0);
    bdl_orientation_merge(&halves[0], &halves[1]);
    CHECK_CLOSE(bdl_orientation_order(&halves[0]), s_flat, 1e-12);
    bdl_orientation_sums none = {0};
    CHECK(isnan(bdl_orientation_order(&none)) && isnan(bdl_orientation_vertical(&none)));
}

/// A bed of 100 layers 1 mm thick, each holding solids fraction 0.55 of a 1 cm^2 base in 7
/// particles: its surface is at 0.1 m and its bulk fraction 0.55, whatever the layer thickness of
/// the profile (a divisor of the layers' or not).
static void test_bed_surface(void)
{
    enum { LAYERS = 100, PER = 7 };
    static double lo[LAYERS * PER], hi[LAYERS * PER], vol[LAYERS * PER];
    const double d = 1e-3, area = 1e-4, phi = 0.55;
    for (int k = 0; k < LAYERS * PER; ++k) {
        lo[k] = (k / PER) * d;
        hi[k] = lo[k] + d;
        vol[k] = phi * area * d / PER;
    }
    const double dz[] = {0.5e-3, 0.25e-3, 0.3e-3};
    for (int m = 0; m < 3; ++m) {
        bdl_bed_surface b;
        CHECK(bdl_bed_surface_of(lo, hi, vol, LAYERS * PER, area, dz[m], &b) == BDL_OK);
        printf("bed surface, layers %.2g m: height %.6f m, bulk %.4f\n", dz[m], b.height, b.bulk);
        CHECK(fabs(b.height - 0.1) <= 0.5 * dz[m]);
        CHECK_CLOSE(b.bulk, phi, 1e-9);
        CHECK_CLOSE(b.top, 0.1, 1e-12);
    }
    bdl_bed_surface b;
    CHECK(bdl_bed_surface_of(lo, hi, vol, 0, area, 1e-3, &b) == BDL_ERR_ARGS);
}

/// A unit square: pass 1 takes three sides; pass 2, with those at 1.2, the fourth side; pass 3,
/// with two sides now at 1.44 (chosen twice), a diagonal (sqrt 2 = 1.414). A chain of unit steps
/// with its sixth point missing (a NaN centre takes no part): three passes keep the six edges
/// (the steps, and the jump 4-6 over the gap, which stays the shortest way across up to
/// 2 x 1.2^2 = 2.88 < 3); the fourth, with the jump at 2 x 1.2^3 = 3.46, crosses by a jump of 3.
static void test_spanning(void)
{
    const bdl_vec3 sq[4] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
    bdl_span_edge e[32];
    long count[4] = {0};
    for (int p = 1; p <= 3; ++p)
        CHECK(bdl_spanning_passes(4, sq, p, 1.2, e, &count[p]) == BDL_OK);
    printf("square: %ld, %ld, %ld edges after 1, 2, 3 passes\n", count[1], count[2], count[3]);
    CHECK(count[1] == 3 && count[2] == 4 && count[3] == 5);
    int diagonals = 0;
    for (long k = 0; k < count[3]; ++k)
        diagonals += e[k].pass == 3 && (e[k].j - e[k].i) == 2;
    CHECK(diagonals == 1);
    bdl_vec3 chain[8];
    for (int k = 0; k < 8; ++k)
        chain[k] = bdl_v3(k, 0.0, 0.0);
    chain[5] = bdl_v3(NAN, 0.0, 0.0); // takes no part: the chain 0-4, 6-7 joined by 4-6
    bdl_span_edge c[64];
    long three, four;
    CHECK(bdl_spanning_passes(8, chain, 3, 1.2, c, &three) == BDL_OK);
    CHECK(three == 6);
    int jump = 0;
    for (long k = 0; k < three; ++k)
        jump += c[k].i == 4 && c[k].j == 6;
    CHECK(jump == 1);
    for (long k = 0; k < three; ++k)
        CHECK(c[k].i != 5 && c[k].j != 5);
    CHECK(bdl_spanning_passes(8, chain, 4, 1.2, c, &four) == BDL_OK);
    CHECK(four > three);
}

static void test_force_correlation(void)
{
    const bdl_vec3 at[3] = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}};
    const double f[3] = {1.0, 2.0, 3.0};
    double F[6];
    long pairs[6];
    bdl_force_correlation(3, at, f, 6, 0.5, F, pairs);
    CHECK(isnan(F[0]) && pairs[0] == 0);
    CHECK_CLOSE(F[2], (1.0 * 2.0 + 2.0 * 3.0) / 2.0, 1e-15);
    CHECK(pairs[2] == 2);
    CHECK_CLOSE(F[4], 3.0, 1e-15);
    CHECK(pairs[4] == 1);
}

int main(void)
{
    test_orientation();
    test_bed_surface();
    test_coordination();
    test_contact_forces();
    test_height_quantile();
    test_lacey();
    test_networks_chain();
    test_networks_lattice();
    test_force_pdf();
    test_spanning();
    test_force_correlation();
    return bdl_test_summary("test_granular");
}
