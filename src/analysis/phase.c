// bedlam — folding a time series over a cycle into phase bins.
#include "analysis/phase.h"

#include <math.h>
#include <stdlib.h>

static void fold_sample(bdl_phase_fold *f, double *sum, int b, double x, long cycle)
{
    sum[b] += x;
    f->min[b] = fmin(f->min[b], x);
    f->max[b] = fmax(f->max[b], x);
    f->count[b]++;
    f->used++;
    f->first_cycle = f->first_cycle < 0 ? cycle : f->first_cycle;
    f->last_cycle = cycle;
}

bdl_result bdl_phase_fold_of(const double *t, const double *x, long n, const bdl_phase_def *def,
                             bdl_phase_fold *out)
{
    BDL_ASSERT(def->period > 0.0 && def->bins >= 1);
    const int bins = def->bins;
    bdl_phase_fold f = {bins, NULL, NULL, NULL, NULL, 0, -1, -1};
    f.mean = calloc((size_t)bins, sizeof(double)); // the sums until the end
    f.min = malloc((size_t)bins * sizeof(double));
    f.max = malloc((size_t)bins * sizeof(double));
    f.count = calloc((size_t)bins, sizeof(long));
    if (!f.mean || !f.min || !f.max || !f.count) {
        bdl_phase_fold_free(&f);
        return BDL_ERR_NOMEM;
    }
    for (int b = 0; b < bins; ++b)
        f.min[b] = INFINITY, f.max[b] = -INFINITY;
    for (long i = 0; i < n; ++i) {
        const double c = (t[i] - def->start) / def->period;
        const long cycle = (long)floor(c + 1e-9);
        if (c < -1e-9 || cycle < def->from_cycle || cycle >= def->to_cycle || !isfinite(x[i]))
            continue;
        int b = (int)floor((c - (double)cycle) * bins + 1e-9);
        b = b < 0 ? 0 : b >= bins ? bins - 1 : b;
        fold_sample(&f, f.mean, b, x[i], cycle);
    }
    for (int b = 0; b < bins; ++b)
        f.mean[b] = f.count[b] ? f.mean[b] / (double)f.count[b] : NAN;
    *out = f;
    return BDL_OK;
}

void bdl_phase_fold_free(bdl_phase_fold *fold)
{
    free(fold->mean), free(fold->min), free(fold->max), free(fold->count);
    fold->mean = fold->min = fold->max = NULL;
    fold->count = NULL;
}

bdl_phase_extremes bdl_phase_fold_extremes(const bdl_phase_fold *fold)
{
    bdl_phase_extremes e = {-INFINITY, INFINITY, 0, 0};
    for (int b = 0; b < fold->bins; ++b) {
        if (fold->count[b] && fold->mean[b] > e.largest)
            e.largest = fold->mean[b], e.at_largest = b;
        if (fold->count[b] && fold->mean[b] < e.smallest)
            e.smallest = fold->mean[b], e.at_smallest = b;
    }
    return e;
}

int bdl_phase_runs_below(const bdl_phase_fold *fold, double threshold, int *start, int *end,
                         int max)
{
    int runs = 0, prev = 0;
    for (int b = 0; b <= fold->bins; ++b) {
        const int in = b < fold->bins && fold->mean[b] < threshold; // NAN (empty) is not below
        if (in && !prev && runs < max)
            start[runs] = b;
        if (!in && prev && runs < max)
            end[runs++] = b;
        prev = in;
    }
    return runs;
}
