// bedlam — what the coupling's files share: the deposits in a fixed order (coupling_deposit.c).
#ifndef BDL_COUPLING_INTERNAL_H
#define BDL_COUPLING_INTERNAL_H

#include "couple/coupling.h"

/// What a deposit adds for particle i: its contribution at padded index idx goes to
/// out[f][idx - shift].
typedef void bdl_deposit_fn(const bdl_coupling *c, const void *ctx, long i, long shift,
                            double *const *out);

/// Splits `count` particles into the deposits' chunks (bdl_coupling_def.chunk), finds the padded
/// indices each chunk's kernel points reach (c->lo, c->hi) and makes room for the chunks' sums.
/// After every change of the kernels (locate, relocate).
bdl_result bdl_coupling_plan_chunks(bdl_coupling *c, long count);

/// Clears the nf (<= BDL_COUPLING_FIELDS) fields out[] and adds every particle's fn(i) to them in
/// a fixed order: in particle order when there are no chunks (the order the DEM's results were
/// made with); else each chunk's particles into sums of its own (the chunks in parallel), the
/// sums then added cell by cell in chunk order. The sums never depend on the number of threads.
void bdl_coupling_deposit(const bdl_coupling *c, const bdl_grid *g, long count, int nf,
                          double *const *out, bdl_deposit_fn *fn, const void *ctx);

#endif
