// bedlam — U_mf where the packed-bed branch a U + b U^2 meets the fluidized plateau.
#include "analysis/umf.h"

#include <math.h>
#include <stdlib.h>

double bdl_umf_fit(const double *u, const double *dp, const int *use, int n, double plateau,
                   double *a, double *b)
{
    double s11 = 0, s12 = 0, s22 = 0, r1 = 0, r2 = 0;
    int count = 0;
    for (int k = 0; k < n; ++k) {
        if (!use[k])
            continue;
        double x = u[k], y = dp[k];
        s11 += x * x, s12 += x * x * x, s22 += x * x * x * x;
        r1 += x * y, r2 += x * x * y;
        ++count;
    }
    *a = *b = NAN;
    if (count < 2)
        return NAN;
    double det = s11 * s22 - s12 * s12;
    *a = (r1 * s22 - r2 * s12) / det;
    *b = (s11 * r2 - s12 * r1) / det;
    if (*b > 0.0)
        return (-*a + sqrt(*a * *a + 4.0 * *b * plateau)) / (2.0 * *b);
    return *a > 0.0 ? plateau / *a : NAN;
}

/// Sum of squared residuals of a U + b U^2 over the points with use[k].
static double packed_sse(const double *u, const double *dp, const int *use, int n, double a,
                         double b)
{
    double s = 0.0;
    for (int k = 0; k < n; ++k)
        if (use[k]) {
            double r = dp[k] - (a * u[k] + b * u[k] * u[k]);
            s += r * r;
        }
    return s;
}

bdl_umf_result bdl_umf_from_sweep(const double *u, const double *dp, int n)
{
    // Two-piece regression: every split velocity u_s puts the points below it on the packed
    // branch (fitted with a U + b U^2) and those at or above it on the plateau (their mean); the
    // split with the least total squared residual wins (at least two points on each side).
    bdl_umf_result r = {NAN, NAN, NAN, NAN, 0, 0};
    int *use = calloc((size_t)n, sizeof(int));
    if (!use)
        return r;
    double best = INFINITY;
    for (int s = 0; s < n; ++s) {
        int packed = 0, fluid = 0;
        double sum = 0.0;
        for (int k = 0; k < n; ++k) {
            use[k] = u[k] < u[s] && u[k] > 0.0;
            packed += use[k];
            if (u[k] >= u[s]) {
                sum += dp[k];
                ++fluid;
            }
        }
        if (packed < 2 || fluid < 2)
            continue;
        double plateau = sum / fluid, a, b, sse = 0.0;
        bdl_umf_fit(u, dp, use, n, plateau, &a, &b);
        for (int k = 0; k < n; ++k)
            if (u[k] >= u[s])
                sse += (dp[k] - plateau) * (dp[k] - plateau);
        sse += packed_sse(u, dp, use, n, a, b);
        if (sse < best) {
            best = sse;
            r.plateau = plateau, r.packed = packed, r.fluidized = fluid;
            r.umf = bdl_umf_fit(u, dp, use, n, plateau, &r.a, &r.b);
        }
    }
    free(use);
    return r;
}

void bdl_sweep_span_at(const double *t, const double *u, long n, long i, bdl_sweep_span *s)
{
    long j = i;
    while (j < n && fabs(u[j] - u[i]) < 1e-9)
        ++j;
    *s = (bdl_sweep_span){.first = i, .end = j, .u = u[i], .from = 0.5 * (t[i] + t[j - 1])};
}

/// Averages the rows of one stage over its second half in time; 0 when no row is there.
static int stage_average(const double *t, const double *dp, const double *ratio,
                         const bdl_sweep_span *sp, bdl_sweep_stage *g)
{
    double s = 0, s2 = 0, r = 0;
    long c = 0;
    for (long k = sp->first; k < sp->end; ++k)
        if (t[k] >= sp->from) {
            s += dp[k], s2 += dp[k] * dp[k], r += ratio[k], ++c;
        }
    if (c == 0)
        return 0;
    g->dp = s / c;
    g->dp_std = sqrt(fmax(0.0, s2 / c - g->dp * g->dp));
    g->ratio = r / c;
    return 1;
}

int bdl_sweep_stages(const double *t, const double *u, const double *dp, const double *ratio,
                     long n, bdl_sweep_stage *out)
{
    int count = 0;
    bdl_sweep_span sp;
    for (long i = 0; i < n; i = sp.end) {
        bdl_sweep_span_at(t, u, n, i, &sp);
        bdl_sweep_stage *g = &out[count];
        if (sp.u > 0.0 && stage_average(t, dp, ratio, &sp, g))
            g->u = sp.u, ++count;
    }
    for (int k = 0; k < count; ++k) {
        const double prev = k > 0 ? out[k - 1].u : NAN, next = k + 1 < count ? out[k + 1].u : NAN;
        out[k].branch = k > 0 ? (out[k].u > prev ? 1 : -1) : (next > out[k].u ? 1 : -1);
    }
    return count;
}

bdl_result bdl_sweep_branch_fit(const bdl_sweep_stage *stages, int count, int branch,
                                bdl_sweep_branch *out)
{
    const size_t size = (size_t)(count > 0 ? count : 1);
    double *u = calloc(size, sizeof(double)), *dp = calloc(size, sizeof(double));
    double *ratio = calloc(size, sizeof(double));
    if (!u || !dp || !ratio) {
        free(u), free(dp), free(ratio);
        return BDL_ERR_NOMEM;
    }
    int c = 0;
    for (int k = 0; k < count; ++k)
        if (stages[k].branch == branch) {
            u[c] = stages[k].u, dp[c] = stages[k].dp, ratio[c] = stages[k].ratio;
            ++c;
        }
    out->stages = c;
    out->fit = bdl_umf_from_sweep(u, dp, c);
    double sum = 0.0;
    int plateau = 0;
    for (int k = 0; k < c; ++k)
        if (isfinite(out->fit.umf) && u[k] > out->fit.umf) {
            sum += ratio[k];
            ++plateau;
        }
    out->plateau_ratio = plateau ? sum / plateau : NAN;
    free(u), free(dp), free(ratio);
    return BDL_OK;
}
