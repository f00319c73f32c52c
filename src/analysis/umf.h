// bedlam — minimum fluidization velocity from a pressure-drop sweep.
//
// The method of Kunii & Levenspiel, as experimenters use it: the packed-bed branch of the
// pressure drop against the superficial velocity (measured while the velocity decreases, free of
// the packing's history) meets the fluidized plateau (the bed's weight per area) at U_mf. The
// packed branch is fitted with Ergun's form a U + b U^2.
#ifndef BDL_UMF_H
#define BDL_UMF_H

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

#endif
