// bedlam — sums of doubles that do not depend on the order of their terms.
//
// A floating-point sum depends on the order of its terms in the last bits, so a sum that threads
// add to in an order that depends on how the work is split would differ between thread counts.
// Each term is rounded, on its own, to a fixed point of 2^-96 (1.3e-29) and the fixed-point
// numbers are added exactly as 128-bit integers: any order gives the same bits. Terms and sums
// must stay below 2^30 in magnitude (about 1e9: joules, for the energies summed this way); a term
// beyond that, or not finite, counts as zero (only a run that has already failed produces one).
#ifndef BDL_EXACT_SUM_H
#define BDL_EXACT_SUM_H

#include <math.h>

__extension__ typedef __int128 bdl_exact_sum;

/// The term x in the sum's fixed point.
static inline bdl_exact_sum bdl_exact_term(double x)
{
    return fabs(x) < 0x1p30 ? (bdl_exact_sum)(x * 0x1p96) : 0;
}

/// The value of a sum.
static inline double bdl_exact_value(bdl_exact_sum s) { return (double)s * 0x1p-96; }

#endif
