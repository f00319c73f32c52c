// bedlam — the larger and the smaller of two doubles, inlined and without branches.
//
// fmax and fmin are library calls on x86-64 unless NaNs and signed zeros are ruled out for the
// whole program, and written as comparisons compilers often branch (mispredicted in a limiter
// whose ratio changes sign from face to face). These are a > b ? a : b and a < b ? a : b, on
// x86-64 as one SSE2 instruction that means exactly that: with a NaN in either they return b
// (fmax and fmin return the other argument). A loop folding values in as b keeps a NaN only
// until the next number: check finiteness where it matters.
#ifndef BDL_MINMAX_H
#define BDL_MINMAX_H

#ifdef __SSE2__
#include <emmintrin.h>

static inline double bdl_max(double a, double b)
{
    return _mm_cvtsd_f64(_mm_max_sd(_mm_set_sd(a), _mm_set_sd(b)));
}
static inline double bdl_min(double a, double b)
{
    return _mm_cvtsd_f64(_mm_min_sd(_mm_set_sd(a), _mm_set_sd(b)));
}
#else
static inline double bdl_max(double a, double b) { return a > b ? a : b; }
static inline double bdl_min(double a, double b) { return a < b ? a : b; }
#endif

#endif
