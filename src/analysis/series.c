// bedlam — time windows, sample statistics and block means of a run's time series.
#include "analysis/series.h"

#include <math.h>

#include "core/error.h"

bdl_time_window bdl_time_window_of(const double *t, long n, double from, double to)
{
    long first = 0, end = n;
    while (first < n && t[first] < from)
        ++first;
    while (end > first && t[end - 1] > to)
        --end;
    const long count = end - first;
    const double dt = count >= 2 ? (t[end - 1] - t[first]) / (double)(count - 1) : NAN;
    return (bdl_time_window){first, count, dt};
}

static int in_window(double t, double x, double from, double to)
{
    return t >= from && t <= to && isfinite(x);
}

bdl_sample_stats bdl_sample_stats_in(const double *t, const double *x, long n, double from,
                                     double to)
{
    bdl_sample_stats s = {0, -1, -1, NAN, NAN, NAN, NAN};
    double sum = 0.0, sum2 = 0.0, lo = INFINITY, hi = -INFINITY;
    for (long i = 0; i < n; ++i) {
        if (!in_window(t[i], x[i], from, to))
            continue;
        s.first = s.first < 0 ? i : s.first;
        s.last = i;
        s.count++;
        sum += x[i], sum2 += x[i] * x[i];
        lo = fmin(lo, x[i]), hi = fmax(hi, x[i]);
    }
    if (s.count == 0)
        return s;
    s.mean = sum / (double)s.count;
    s.sd = sqrt(fmax(0.0, sum2 / (double)s.count - s.mean * s.mean));
    s.min = lo, s.max = hi;
    return s;
}

bdl_block_mean bdl_block_mean_in(const double *t, const double *x, long n, double from, double to,
                                 int blocks)
{
    BDL_ASSERT(blocks >= 2 && blocks <= BDL_BLOCKS_MAX);
    bdl_block_mean r = {bdl_sample_stats_in(t, x, n, from, to), NAN};
    const bdl_sample_stats *s = &r.samples;
    if (s->count == 0)
        return r;
    double sum[BDL_BLOCKS_MAX] = {0};
    long in_block[BDL_BLOCKS_MAX] = {0};
    const long per = s->count >= blocks ? (s->last - s->first + 1) / blocks : 1;
    for (long i = s->first; i <= s->last; ++i) {
        if (!in_window(t[i], x[i], from, to))
            continue;
        const long b = (i - s->first) / per;
        const int k = b > blocks - 1 ? blocks - 1 : (int)b;
        sum[k] += x[i];
        in_block[k]++;
    }
    double scatter = 0.0;
    for (int k = 0; k < blocks; ++k) {
        const double m = in_block[k] > 0 ? sum[k] / (double)in_block[k] : s->mean;
        scatter += (m - s->mean) * (m - s->mean);
    }
    r.standard_error = sqrt(scatter / (double)(blocks - 1)) / sqrt((double)blocks);
    return r;
}
