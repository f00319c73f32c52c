#include "analysis/granular.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

bdl_coordination_stats bdl_coordination(const uint8_t *count, long n)
{
    bdl_coordination_stats s = {0};
    long sum = 0, multi = 0;
    for (long i = 0; i < n; ++i) {
        sum += count[i];
        s.in_contact += count[i] > 0;
        multi += count[i] > 1;
    }
    s.mean = n > 0 ? (double)sum / (double)n : 0.0;
    s.multi_contact_ratio = s.in_contact > 0 ? (double)multi / (double)s.in_contact : 0.0;
    s.mean_touching = s.in_contact > 0 ? s.mean * (double)n / (double)s.in_contact : 0.0;
    return s;
}

bdl_contact_forces bdl_contact_forces_of(const bdl_contact_rec *c, long nc, double *fn,
                                         uint8_t *count)
{
    bdl_contact_forces s = {0, 0, 0.0};
    for (long k = 0; k < nc; ++k) {
        if (c[k].j < 0) {
            s.walls++;
            continue;
        }
        if (c[k].fn > 0.0) {
            fn[s.pairs++] = c[k].fn;
            s.mean += c[k].fn;
            count[c[k].i] += count[c[k].i] < 255;
            count[c[k].j] += count[c[k].j] < 255;
        }
    }
    s.mean = s.pairs > 0 ? s.mean / (double)s.pairs : 0.0;
    return s;
}

static int compare_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

double bdl_height_quantile(double *h, long n, double q)
{
    if (n <= 0)
        return NAN;
    qsort(h, (size_t)n, sizeof(double), compare_double);
    long k = (long)floor(q * (double)(n - 1));
    return h[k < 0 ? 0 : k >= n ? n - 1 : k];
}

static int cell_of(double x, double lo, double hi, int n)
{
    int c = (int)floor((x - lo) / (hi - lo) * n);
    return c < 0 ? -1 : c >= n ? -1 : c;
}

double bdl_lacey(const bdl_vec3 *pos, const uint8_t *is_a, long n, bdl_vec3 lo, bdl_vec3 hi,
                 const int cells[3], long min_count)
{
    const long total = (long)cells[0] * cells[1] * cells[2];
    if (total < 2 || n == 0)
        return NAN;
    long *all = calloc((size_t)total, sizeof(long)), *of_a = calloc((size_t)total, sizeof(long));
    if (!all || !of_a) {
        free(all);
        free(of_a);
        return NAN;
    }
    for (long i = 0; i < n; ++i) {
        int cx = cell_of(pos[i].x, lo.x, hi.x, cells[0]);
        int cy = cell_of(pos[i].y, lo.y, hi.y, cells[1]);
        int cz = cell_of(pos[i].z, lo.z, hi.z, cells[2]);
        if (cx < 0 || cy < 0 || cz < 0)
            continue;
        long c = ((long)cz * cells[1] + cy) * cells[0] + cx;
        all[c]++;
        of_a[c] += is_a[i] != 0;
    }
    // p over the cells used, so that a fully segregated bed gives s^2 = s0^2 exactly.
    long used = 0, in_used = 0, a_used = 0;
    for (long c = 0; c < total; ++c)
        if (all[c] >= min_count && all[c] > 0) {
            in_used += all[c];
            a_used += of_a[c];
            used++;
        }
    double m = NAN;
    const double p = in_used > 0 ? (double)a_used / (double)in_used : 0.0;
    if (used >= 2 && p > 0.0 && p < 1.0) {
        // Each cell weighted by its particle count (its number of samples): cells holding many
        // small particles and cells holding few large ones count as what they hold.
        double s2 = 0.0;
        for (long c = 0; c < total; ++c)
            if (all[c] >= min_count && all[c] > 0) {
                double x = (double)of_a[c] / (double)all[c] - p;
                s2 += (double)all[c] * x * x;
            }
        s2 /= (double)in_used;
        const double nbar = (double)in_used / (double)used;
        const double s0 = p * (1.0 - p), sr = s0 / nbar;
        if (nbar > 1.0)
            m = (s0 - s2) / (s0 - sr);
    }
    free(all);
    free(of_a);
    return m;
}

static int32_t find_root(int32_t *parent, int32_t i)
{
    while (parent[i] != i) {
        parent[i] = parent[parent[i]];
        i = parent[i];
    }
    return i;
}

bdl_result bdl_force_networks(long n, const bdl_contact_rec *c, long nc, double threshold,
                              const bdl_vec3 *pos, int32_t *label, bdl_network_stats *out)
{
    memset(out, 0, sizeof *out);
    int32_t *parent = malloc((size_t)(n > 0 ? n : 1) * sizeof(int32_t));
    long *size = calloc((size_t)(n > 0 ? n : 1), sizeof(long));
    long *edges = calloc((size_t)(n > 0 ? n : 1), sizeof(long));
    if (!parent || !size || !edges) {
        free(parent);
        free(size);
        free(edges);
        return BDL_ERR_NOMEM;
    }
    for (long i = 0; i < n; ++i)
        parent[i] = (int32_t)i;
    for (long k = 0; k < nc; ++k) {
        if (c[k].j < 0 || c[k].fn <= threshold || c[k].i >= n || c[k].j >= n)
            continue;
        int32_t a = find_root(parent, c[k].i), b = find_root(parent, c[k].j);
        // The smaller index becomes the root: labels do not depend on the contacts' order.
        if (a < b)
            parent[b] = a;
        else if (b < a)
            parent[a] = b;
    }
    for (long i = 0; i < n; ++i)
        size[find_root(parent, (int32_t)i)]++;
    for (long k = 0; k < nc; ++k)
        if (c[k].j >= 0 && c[k].fn > threshold && c[k].i < n && c[k].j < n)
            edges[find_root(parent, c[k].i)]++;
    long best = -1;
    long total_edges = 0;
    for (long i = 0; i < n; ++i) {
        if (parent[i] != i || size[i] < 2)
            continue;
        out->networks++;
        total_edges += edges[i];
        if (best < 0 || size[i] > size[best])
            best = i;
    }
    if (best >= 0) {
        out->largest = size[best];
        out->largest_edges = edges[best];
        out->largest_mean_z = 2.0 * (double)edges[best] / (double)size[best];
        out->other_edges = total_edges - edges[best];
        if (pos) {
            // Every pair of the largest network: exact, O(m^2) for m members.
            long m = 0;
            long *member = malloc((size_t)size[best] * sizeof(long));
            if (!member) {
                free(parent);
                free(size);
                free(edges);
                return BDL_ERR_NOMEM;
            }
            for (long i = 0; i < n; ++i)
                if (parent[i] == best)
                    member[m++] = i;
            double d2 = 0.0;
            for (long a = 0; a < m; ++a)
                for (long b = a + 1; b < m; ++b) {
                    double x = bdl_v3_len2(bdl_v3_sub(pos[member[a]], pos[member[b]]));
                    d2 = x > d2 ? x : d2;
                }
            out->largest_length = sqrt(d2);
            free(member);
        }
    }
    if (label)
        for (long i = 0; i < n; ++i)
            label[i] = parent[i];
    free(parent);
    free(size);
    free(edges);
    return BDL_OK;
}

double bdl_force_pdf_eval(const bdl_force_pdf_fit *fit, double f)
{
    return fit->a * (1.0 - fit->b * exp(-f * f)) * exp(-fit->beta * f);
}

/// For a fixed beta, P = a e^(-beta f) - c e^(-f^2 - beta f) is linear in a and c = a b: the
/// least-squares a and c; returns the sum of squared residuals.
static double fit_linear(const double *x, const double *y, int n, double beta, double *a, double *c)
{
    double s11 = 0, s12 = 0, s22 = 0, r1 = 0, r2 = 0;
    for (int k = 0; k < n; ++k) {
        double g1 = exp(-beta * x[k]), g2 = -exp(-x[k] * x[k] - beta * x[k]);
        s11 += g1 * g1, s12 += g1 * g2, s22 += g2 * g2;
        r1 += g1 * y[k], r2 += g2 * y[k];
    }
    double det = s11 * s22 - s12 * s12;
    if (fabs(det) < 1e-300)
        return INFINITY;
    *a = (r1 * s22 - r2 * s12) / det;
    *c = (s11 * r2 - s12 * r1) / det;
    double ss = 0.0;
    for (int k = 0; k < n; ++k) {
        double e = *a * exp(-beta * x[k]) - *c * exp(-x[k] * x[k] - beta * x[k]) - y[k];
        ss += e * e;
    }
    return ss;
}

bdl_result bdl_force_pdf(const double *fn, long n, int bins, double fmax, double *centre,
                         double *pdf, bdl_force_pdf_fit *fit)
{
    long positive = 0;
    double sum = 0.0;
    for (long i = 0; i < n; ++i)
        if (fn[i] > 0.0) {
            positive++;
            sum += fn[i];
        }
    if (positive < 10 || bins < 3 || !(fmax > 0.0))
        return BDL_ERR_ARGS;
    const double mean = sum / (double)positive, w = fmax / bins;
    for (int k = 0; k < bins; ++k) {
        centre[k] = (k + 0.5) * w;
        pdf[k] = 0.0;
    }
    for (long i = 0; i < n; ++i) {
        if (fn[i] <= 0.0)
            continue;
        int k = (int)(fn[i] / mean / w);
        if (k < bins)
            pdf[k] += 1.0;
    }
    for (int k = 0; k < bins; ++k)
        pdf[k] /= (double)positive * w;
    double a, c, best_beta = 0.05, best = INFINITY;
    for (double beta = 0.05; beta <= 6.0; beta += 0.01) {
        double ss = fit_linear(centre, pdf, bins, beta, &a, &c);
        if (ss < best) {
            best = ss;
            best_beta = beta;
        }
    }
    // Golden section on [beta - 0.01, beta + 0.01].
    const double phi = 0.5 * (sqrt(5.0) - 1.0);
    double lo = best_beta - 0.01, hi = best_beta + 0.01;
    for (int it = 0; it < 40; ++it) {
        double m1 = hi - phi * (hi - lo), m2 = lo + phi * (hi - lo);
        if (fit_linear(centre, pdf, bins, m1, &a, &c) < fit_linear(centre, pdf, bins, m2, &a, &c))
            hi = m2;
        else
            lo = m1;
    }
    fit->beta = 0.5 * (lo + hi);
    double ss = fit_linear(centre, pdf, bins, fit->beta, &a, &c);
    fit->a = a;
    fit->b = a != 0.0 ? c / a : 0.0;
    fit->rms = sqrt(ss / bins);
    return BDL_OK;
}

void bdl_orientation_add(bdl_orientation_sums *s, bdl_vec3 u, bdl_vec3 up)
{
    s->n += 1.0;
    s->abs_cos += fabs(bdl_v3_dot(u, up));
    const double uu[6] = {u.x * u.x, u.y * u.y, u.z * u.z, u.x * u.y, u.x * u.z, u.y * u.z};
    for (int k = 0; k < 6; ++k)
        s->uu[k] += uu[k];
}

void bdl_orientation_merge(bdl_orientation_sums *into, const bdl_orientation_sums *s)
{
    into->n += s->n;
    into->abs_cos += s->abs_cos;
    for (int k = 0; k < 6; ++k)
        into->uu[k] += s->uu[k];
}

double bdl_orientation_vertical(const bdl_orientation_sums *s)
{
    return s->n > 0.0 ? s->abs_cos / s->n : NAN;
}

/// The largest eigenvalue of the symmetric 3x3 matrix a (xx yy zz xy xz yz), by the
/// trigonometric solution of the characteristic cubic.
static double largest_eigenvalue(const double a[6])
{
    const double off = a[3] * a[3] + a[4] * a[4] + a[5] * a[5];
    const double mean = (a[0] + a[1] + a[2]) / 3.0;
    const double d0 = a[0] - mean, d1 = a[1] - mean, d2 = a[2] - mean;
    const double p = sqrt((d0 * d0 + d1 * d1 + d2 * d2 + 2.0 * off) / 6.0);
    if (p == 0.0)
        return mean; // a multiple of the identity
    // B = (A - mean I) / p; det(B) / 2 = cos(3 phi).
    const double b0 = d0 / p, b1 = d1 / p, b2 = d2 / p;
    const double b3 = a[3] / p, b4 = a[4] / p, b5 = a[5] / p;
    const double det =
        b0 * (b1 * b2 - b5 * b5) - b3 * (b3 * b2 - b5 * b4) + b4 * (b3 * b5 - b1 * b4);
    const double c = fmin(1.0, fmax(-1.0, 0.5 * det));
    return mean + 2.0 * p * cos(acos(c) / 3.0);
}

double bdl_orientation_order(const bdl_orientation_sums *s)
{
    if (!(s->n > 0.0))
        return NAN;
    double q[6];
    for (int k = 0; k < 6; ++k)
        q[k] = 1.5 * s->uu[k] / s->n - (k < 3 ? 0.5 : 0.0);
    return largest_eigenvalue(q);
}

/// Adds volume v spread evenly over [a, b] to the layers of thickness dz of phi.
static void spread_volume(double *phi, long layers, double dz, double a, double b, double v)
{
    a = fmax(a, 0.0);
    if (!(b > a)) {
        const long k = (long)(a / dz);
        phi[k < layers ? k : layers - 1] += v;
        return;
    }
    const double density = v / (b - a);
    for (long k = (long)(a / dz); k < layers && k * dz < b; ++k)
        phi[k] += density * (fmin(b, (double)(k + 1) * dz) - fmax(a, (double)k * dz));
}

bdl_result bdl_bed_surface_of(const double *lo, const double *hi, const double *vol, long n,
                              double area, double dz, bdl_bed_surface *out)
{
    if (n < 1 || !(area > 0.0) || !(dz > 0.0))
        return BDL_ERR_ARGS;
    double top = 0.0;
    for (long k = 0; k < n; ++k)
        top = fmax(top, hi[k]);
    const long layers = (long)ceil(top / dz) + 1;
    double *phi = calloc((size_t)layers, sizeof *phi);
    if (!phi)
        return BDL_ERR_NOMEM;
    for (long k = 0; k < n; ++k)
        spread_volume(phi, layers, dz, lo[k], hi[k], vol[k]);
    for (long k = 0; k < layers; ++k)
        phi[k] /= area * dz;
    double bulk = 0.0;
    long used = 0;
    for (long k = 0; k < layers; ++k) {
        const double z = (k + 0.5) * dz;
        if (z >= 0.2 * top && z <= 0.6 * top) {
            bulk += phi[k];
            ++used;
        }
    }
    bulk = used > 0 ? bulk / (double)used : 0.0;
    double height = 0.0;
    for (long k = layers - 1; k > 0; --k)
        if (phi[k - 1] >= 0.5 * bulk && phi[k] < 0.5 * bulk) {
            const double f = (phi[k - 1] - 0.5 * bulk) / (phi[k - 1] - phi[k]);
            height = (k - 0.5 + f) * dz;
            break;
        }
    free(phi);
    *out = (bdl_bed_surface){height, bulk, top, layers};
    return BDL_OK;
}
