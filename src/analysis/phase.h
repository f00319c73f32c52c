// bedlam — a time series folded over a cycle (the vibration of a shaken bed): each sample goes to
// the bin of its phase, the fraction of its cycle elapsed, and every bin keeps the mean, least
// and largest of its samples over the cycles folded. What the bed does at each moment of the
// cycle (its flight, its landing) stands out of the noise of any one cycle.
#ifndef BDL_PHASE_H
#define BDL_PHASE_H

#include "core/error.h"

typedef struct bdl_phase_def {
    double period;   ///< of the cycle [s], > 0
    double start;    ///< time the first cycle starts [s]; samples before it are left out
    long from_cycle; ///< the first cycle folded (cycle 0 starts at `start`)
    long to_cycle;   ///< the cycle after the last one folded
    int bins;        ///< phase bins, >= 1: bin b holds the phases [b/bins, (b+1)/bins)
} bdl_phase_def;

typedef struct bdl_phase_fold {
    int bins;
    double *mean, *min, *max; ///< per bin: NAN, +inf and -inf where a bin has no sample
    long *count;              ///< samples per bin
    long used;                ///< samples folded (the finite ones in the cycles asked for)
    long first_cycle;         ///< cycle of the first sample folded (-1 when none)
    long last_cycle;          ///< cycle of the last sample folded (-1 when none)
} bdl_phase_fold;

/// Folds x[i] at times t[i] (ascending) into def->bins bins: sample i lies in cycle
/// floor((t - start)/period) at phase (t - start)/period - cycle. The rounding slack of 1e-9 of
/// a cycle puts a sample taken at a cycle's start time into that cycle's first bin. Fills *out
/// (free it with bdl_phase_fold_free). BDL_ERR_NOMEM when the bins cannot be allocated.
bdl_result bdl_phase_fold_of(const double *t, const double *x, long n, const bdl_phase_def *def,
                             bdl_phase_fold *out);

void bdl_phase_fold_free(bdl_phase_fold *fold);

/// The bins of the largest and smallest mean (the first of equals) and those means; -inf, +inf
/// and bin 0 when no bin has a sample.
typedef struct bdl_phase_extremes {
    double largest, smallest;
    int at_largest, at_smallest;
} bdl_phase_extremes;

bdl_phase_extremes bdl_phase_fold_extremes(const bdl_phase_fold *fold);

/// The runs of consecutive bins whose mean lies below `threshold` (an empty bin is not below):
/// run k covers the phases [start[k]/bins, end[k]/bins). Writes at most `max` runs into start[]
/// and end[] ((bins + 1)/2 runs at the most) and returns their number.
int bdl_phase_runs_below(const bdl_phase_fold *fold, double threshold, int *start, int *end,
                         int max);

#endif
