// bedlam — a run's time series (a column of diagnostics.csv, species.csv or profile.csv against
// its time column): the rows of a time window, the statistics of the samples in it, and the
// standard error of their mean from block averages.
//
// Times are ascending, as a run writes them. Samples that are not finite (a quantity a run could
// not measure at that moment) are left out of every statistic.
#ifndef BDL_SERIES_H
#define BDL_SERIES_H

/// The rows of an ascending time column with from <= t <= to.
typedef struct bdl_time_window {
    long first; ///< the first row in the window (n when none is)
    long count; ///< rows in the window
    double dt;  ///< mean spacing of their times [s]; NAN with fewer than two rows
} bdl_time_window;

bdl_time_window bdl_time_window_of(const double *t, long n, double from, double to);

/// The finite samples x[i] with from <= t[i] <= to: their number, the first and last row used
/// (-1 when none), mean, population standard deviation, least and largest (NAN when none).
typedef struct bdl_sample_stats {
    long count;
    long first, last;
    double mean, sd, min, max;
} bdl_sample_stats;

bdl_sample_stats bdl_sample_stats_in(const double *t, const double *x, long n, double from,
                                     double to);

/// The most blocks bdl_block_mean_in takes.
#define BDL_BLOCKS_MAX 64

/// The samples of bdl_sample_stats_in, and the standard error of their mean from `blocks`
/// consecutive blocks of rows between the first and last sample used (blocks - 1 of equal length,
/// the last takes the rest; rows one by one when there are fewer samples than blocks). Blocks
/// longer than the series' correlation time have nearly independent means, which scatter about
/// the mean by the standard error times sqrt(blocks): the standard error allows for correlation
/// in time, where sd/sqrt(count) would not. An empty block counts as the mean. `blocks` from 2 to
/// BDL_BLOCKS_MAX; the standard error is NAN without samples.
typedef struct bdl_block_mean {
    bdl_sample_stats samples;
    double standard_error;
} bdl_block_mean;

bdl_block_mean bdl_block_mean_in(const double *t, const double *x, long n, double from, double to,
                                 int blocks);

#endif
