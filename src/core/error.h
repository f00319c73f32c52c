// bedlam — result codes, assertions and user-facing messages.
//
// One X-macro list generates the enum and the message table (sokol's _SG_LOG_ITEMS habit), so
// tests can assert on codes and users read sentences.
#ifndef BDL_ERROR_H
#define BDL_ERROR_H

#include <stdio.h>
#include <stdlib.h>

#define BDL_RESULTS(X)                                                                             \
    X(OK, "success")                                                                               \
    X(ERR_SCENE, "invalid scene")                                                                  \
    X(ERR_ARGS, "invalid command-line arguments")                                                  \
    X(ERR_IO, "input/output failure")                                                              \
    X(ERR_OUTPUT_DIR, "the output folder cannot be written")                                       \
    X(ERR_NOMEM, "out of memory")                                                                  \
    X(ERR_UNSTABLE, "numerical instability detected")                                              \
    X(ERR_CHECKPOINT, "checkpoint is unreadable or does not match the scene")                      \
    X(ERR_INTERRUPTED, "run interrupted")                                                          \
    X(ERR_NO_RESULT, "the data do not determine a result")                                         \
    X(ERR_TOLERANCE, "a verified result is outside its tolerance")                                 \
    X(ERR_GL, "no OpenGL context (display, driver or library missing)")                            \
    X(ERR_NO_DISPLAY, "no display to open a window on")

typedef enum bdl_result {
#define BDL_X_ENUM(name, text) BDL_##name,
    BDL_RESULTS(BDL_X_ENUM)
#undef BDL_X_ENUM
        BDL_RESULT_COUNT
} bdl_result;

/// Human-readable text for a result code.
const char *bdl_result_text(bdl_result r);

#ifdef BDL_ENABLE_ASSERT
#define BDL_ASSERT(cond)                                                                           \
    do {                                                                                           \
        if (!(cond)) {                                                                             \
            fprintf(stderr, "%s:%d: assertion failed: %s\n", __FILE__, __LINE__, #cond);           \
            abort();                                                                               \
        }                                                                                          \
    } while (0)
#else
#define BDL_ASSERT(cond) ((void)0)
#endif

#endif
