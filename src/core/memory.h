// bedlam — growable arrays of the solver's per-particle and per-pair data, sizes computed without
// overflow, and the machine's memory.
#ifndef BDL_MEMORY_H
#define BDL_MEMORY_H

#include <stddef.h>

/// Resizes *ptr to hold `count` elements of `elem` bytes (at least one), keeping its contents;
/// leaves *ptr untouched and returns 0 when out of memory, or when count * elem does not fit in
/// a size_t. Blocks of 2 MiB or more are offered to the kernel for transparent huge pages: the
/// force pass gathers partners' state from arrays of tens of megabytes, and with 4 KiB pages most
/// of those loads also miss the TLB.
int bdl_grow(void **ptr, long count, size_t elem);

/// *out = a * b; returns 0 (and leaves *out alone) when the product does not fit in a size_t.
/// Every size that is multiplied before an allocation goes through these, so that a huge count
/// from a scene or a file ends in a refusal, never in a small allocation that is then overrun.
int bdl_size_mul(size_t a, size_t b, size_t *out);

/// *out = a + b; returns 0 (and leaves *out alone) when the sum does not fit in a size_t.
int bdl_size_add(size_t a, size_t b, size_t *out);

/// *out = a * b * c, with the same contract.
int bdl_size_mul3(size_t a, size_t b, size_t c, size_t *out);

/// Physical memory of the machine [bytes]: sysconf(_SC_PHYS_PAGES) * sysconf(_SC_PAGESIZE); 0
/// when the system does not say.
double bdl_physical_memory(void);

#endif
