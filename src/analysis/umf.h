// bedlam — minimum fluidization velocity from a pressure-drop sweep.
//
// The method of Kunii & Levenspiel, as experimenters use it: the packed-bed branch of the
// pressure drop against the superficial velocity (measured while the velocity decreases, free of
// the packing's history) meets the fluidized plateau (the bed's weight per area) at U_mf. The
// packed branch is fitted with Ergun's form a U + b U^2.
#ifndef BDL_UMF_H
#define BDL_UMF_H

#include "core/error.h"

/// Least-squares a U + b U^2 through the points u[k], dp[k] with use[k] set; the U where it equals
/// `plateau` (*a, *b get the fit). NAN with fewer than two points.
double bdl_umf_fit(const double *u, const double *dp, const int *use, int n, double plateau,
                   double *a, double *b);

typedef struct bdl_umf_result {
    double umf;     ///< [m/s]; NAN when the sweep has no packed or no fluidized points
    double plateau; ///< the fluidized pressure drop: the mean over the fluidized points [Pa]
    double a, b;    ///< the packed branch a U + b U^2 [Pa s/m, Pa s^2/m^2]
    int packed;     ///< points fitted
    int fluidized;  ///< points averaged for the plateau
} bdl_umf_result;

/// From one branch of a sweep (any order): a two-piece regression, the packed branch below a
/// split velocity and the plateau (their mean) at and above it, the split chosen for the least
/// squared residual; U_mf where the two meet.
bdl_umf_result bdl_umf_from_sweep(const double *u, const double *dp, int n);

/// One stage of a sweep: the rows of a run during which the inlet velocity stays the same.
typedef struct bdl_sweep_stage {
    double u;      ///< inlet velocity [m/s]
    double dp;     ///< mean pressure drop over the stage's second half [Pa]
    double dp_std; ///< its standard deviation [Pa]
    double ratio;  ///< mean pressure drop over the bed's weight per area, same rows
    int branch;    ///< +1 increasing, -1 decreasing: the way the velocity moved to get here
} bdl_sweep_stage;

/// The rows of one stage of a sweep: [first, end), at inlet velocity u; the rows from time
/// `from` on (the middle of the stage's time span) are its second half, the ones averaged.
typedef struct bdl_sweep_span {
    long first, end;
    double u;    ///< [m/s]
    double from; ///< [s]
} bdl_sweep_span;

/// The stage that starts at row i < n of a time series (times t, inlet velocities u): the
/// stretch of consecutive rows whose velocity differs from row i's by less than 1e-9 m/s. The
/// next stage starts at s->end.
void bdl_sweep_span_at(const double *t, const double *u, long n, long i, bdl_sweep_span *s);

/// The stages of a sweep from a run's time series (time t, inlet velocity u, pressure drop dp,
/// weight ratio; n rows): the stretches of bdl_sweep_span_at, each averaged over its rows from
/// the middle of its time span on (the first half is the transient after the step), those with
/// u > 0 kept. The first stage's branch is the way the velocity goes next. `out` has room for n
/// stages; returns their number.
int bdl_sweep_stages(const double *t, const double *u, const double *dp, const double *ratio,
                     long n, bdl_sweep_stage *out);

/// U_mf of one branch of a sweep, and the weight ratio of its fluidized plateau.
typedef struct bdl_sweep_branch {
    int stages;           ///< stages on the branch
    bdl_umf_result fit;   ///< bdl_umf_from_sweep of them
    double plateau_ratio; ///< mean weight ratio of its stages above U_mf (NAN when none)
} bdl_sweep_branch;

/// The fit of the stages with the given branch (+1 or -1) of `count` stages. BDL_ERR_NOMEM when
/// the branch's arrays cannot be allocated.
bdl_result bdl_sweep_branch_fit(const bdl_sweep_stage *stages, int count, int branch,
                                bdl_sweep_branch *out);

#endif
