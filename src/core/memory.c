#define _DEFAULT_SOURCE // madvise
#include "core/memory.h"

#include <stdint.h>
#include <stdlib.h>
#include <sys/mman.h>
#include <unistd.h>

enum { HUGE_PAGE = 2 << 20 }; ///< also the smallest block worth advising

/// Advises huge pages for the whole 2 MiB pages inside [p, p + bytes). Only pages first touched
/// after the advice are affected, which is why it follows every (re)allocation; failure (no
/// transparent huge pages, or a kernel without them) changes nothing but speed.
static void advise_huge(void *p, size_t bytes)
{
#ifdef MADV_HUGEPAGE
    uintptr_t begin = ((uintptr_t)p + HUGE_PAGE - 1) & ~(uintptr_t)(HUGE_PAGE - 1);
    uintptr_t end = ((uintptr_t)p + bytes) & ~(uintptr_t)(HUGE_PAGE - 1);
    if (end > begin)
        (void)madvise((void *)begin, end - begin, MADV_HUGEPAGE);
#else
    (void)p, (void)bytes;
#endif
}

int bdl_size_mul(size_t a, size_t b, size_t *out)
{
    size_t product;
    if (__builtin_mul_overflow(a, b, &product))
        return 0;
    *out = product;
    return 1;
}

int bdl_size_add(size_t a, size_t b, size_t *out)
{
    size_t sum;
    if (__builtin_add_overflow(a, b, &sum))
        return 0;
    *out = sum;
    return 1;
}

int bdl_size_mul3(size_t a, size_t b, size_t c, size_t *out)
{
    size_t ab;
    return bdl_size_mul(a, b, &ab) && bdl_size_mul(ab, c, out);
}

double bdl_physical_memory(void)
{
    const long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
    return pages > 0 && page > 0 ? (double)pages * (double)page : 0.0;
}

int bdl_grow(void **ptr, long count, size_t elem)
{
    size_t bytes;
    if (!bdl_size_mul((size_t)(count > 0 ? count : 1), elem, &bytes))
        return 0;
    void *q = realloc(*ptr, bytes);
    if (!q)
        return 0;
    *ptr = q;
    if (bytes >= HUGE_PAGE)
        advise_huge(q, bytes);
    return 1;
}
