// bedlam tests — build a world from a printf-formatted scene string.
//
// bdl_test_world("[run]\nend_time = %g\n...", 1.0) formats the text, reads it with
// bdl_scene_load_string and builds the world; any error prints the scene's message (and the text)
// and aborts, so a test never runs on a half-built world. Particles are re-sorted at neighbour
// rebuilds: find them with bdl_test_find (by id), never by a fixed index.
#ifndef BDL_TEST_SCENE_UTIL_H
#define BDL_TEST_SCENE_UTIL_H

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>

#include "world/world.h"
#include "verify/verify.h"

#if defined(__GNUC__)
#define BDL_TEST_PRINTF(a, b) __attribute__((format(printf, a, b)))
#else
#define BDL_TEST_PRINTF(a, b)
#endif

static inline bdl_world *bdl_test_world(const char *format, ...) BDL_TEST_PRINTF(1, 2);

static inline bdl_world *bdl_test_world(const char *format, ...)
{
    va_list ap;
    va_start(ap, format);
    bdl_world *w = bdl_verify_world_v(format, ap);
    va_end(ap);
    if (!w)
        abort(); // the scene's message (and text) are printed already
    return w;
}

/// Index of the particle with stable id `id` (particles are re-sorted at rebuilds); aborts if
/// there is none.
static inline long bdl_test_find(const bdl_world *w, uint32_t id)
{
    for (long i = 0; i < w->particles.count; ++i)
        if (w->particles.id[i] == id)
            return i;
    fprintf(stderr, "bdl_test_find: no particle with id %u\n", (unsigned)id);
    abort();
}

#endif
