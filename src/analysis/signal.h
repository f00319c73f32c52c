// bedlam — analysis of a diagnostic's time series: power spectrum and its dominant frequency.
#ifndef BDL_SIGNAL_H
#define BDL_SIGNAL_H

#include "core/error.h"

/// Power spectrum of n samples spaced dt apart: the mean removed, a Hamming window, zero-padded to
/// the next power of two, radix-2 FFT. Writes *count = padded/2 + 1 bins (frequency k/(N dt),
/// power |X_k|^2) into malloc'ed arrays. BDL_ERR_ARGS for n < 4 or dt <= 0.
bdl_result bdl_power_spectrum(const double *x, long n, double dt, double **freq, double **power,
                              long *count);

/// Welch's estimate: the mean of the power spectra (as bdl_power_spectrum) of `segments` equal
/// pieces of the n samples, each half overlapping the next (1: the whole series). When `peaks` is
/// not NULL, peaks[k] is piece k's dominant frequency between fmin and fmax (its spread says
/// whether the peak has converged). BDL_ERR_ARGS for segments < 1 or pieces under 4 samples.
bdl_result bdl_welch_spectrum(const double *x, long n, double dt, int segments, double fmin,
                              double fmax, double *peaks, double **freq, double **power,
                              long *count);

/// The frequency of the largest power between fmin and fmax, refined by a parabola through the
/// peak bin and its neighbours; NAN when no bin lies in the band.
double bdl_dominant_frequency(const double *freq, const double *power, long count, double fmin,
                              double fmax);

#endif
