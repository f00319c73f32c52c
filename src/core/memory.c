#define _DEFAULT_SOURCE // madvise
#include "core/memory.h"

#include <stdint.h>
#include <stdlib.h>
#include <sys/mman.h>

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

int bdl_grow(void **ptr, long count, size_t elem)
{
    size_t bytes = (size_t)(count > 0 ? count : 1) * elem;
    void *q = realloc(*ptr, bytes);
    if (!q)
        return 0;
    *ptr = q;
    if (bytes >= HUGE_PAGE)
        advise_huge(q, bytes);
    return 1;
}
