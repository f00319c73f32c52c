// bedlam — growable arrays of the solver's per-particle and per-pair data.
#ifndef BDL_MEMORY_H
#define BDL_MEMORY_H

#include <stddef.h>

/// Resizes *ptr to hold `count` elements of `elem` bytes (at least one), keeping its contents;
/// leaves *ptr untouched and returns 0 when out of memory. Blocks of 2 MiB or more are
/// offered to the kernel for transparent huge pages: the force pass gathers partners' state from
/// arrays of tens of megabytes, and with 4 KiB pages most of those loads also miss the TLB.
int bdl_grow(void **ptr, long count, size_t elem);

#endif
