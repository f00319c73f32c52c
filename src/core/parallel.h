// bedlam — loops that go parallel only when they are worth it.
//
// An OpenMP `if (0)` clause still enters the runtime: every such region costs a futex call, and a
// small gas grid runs hundreds of regions per step (figures: docs/performance.md, "Why these
// thresholds"). BDL_PARALLEL_FOR(cond, loop) runs `loop` under `omp parallel for schedule(static)`
// when `cond` holds and as plain C otherwise. The loop's results must not depend on which: the
// fixed static partition and per-chunk partial sums (see poisson.c's CHUNKS) keep them
// bit-identical.
#ifndef BDL_PARALLEL_H
#define BDL_PARALLEL_H

/// Below this many particles a parallel particle loop costs more than it saves: small beds gain
/// little from a second thread, and in the spells when the machine's parallel regions slow down
/// they lose (figures: docs/performance.md, "Why these thresholds").
#define BDL_PARALLEL_MIN 4096

/// Vectorised kernels are compiled for AVX2 and for any x86-64, and the loader picks one through
/// an ifunc resolver. ThreadSanitizer instruments the resolver, which runs before its runtime is
/// set up and crashes the program at start: a TSan build keeps the portable version only.
#if defined(__SANITIZE_THREAD__)
#define BDL_SIMD_CLONES
#elif defined(__has_feature)
#if __has_feature(thread_sanitizer)
#define BDL_SIMD_CLONES
#endif
#endif
#ifndef BDL_SIMD_CLONES
#define BDL_SIMD_CLONES __attribute__((target_clones("avx2", "default")))
#endif

#define BDL_PARALLEL_FOR(cond, ...)                                                                \
    do {                                                                                           \
        if (cond) {                                                                                \
            _Pragma("omp parallel for schedule(static)") __VA_ARGS__                               \
        } else {                                                                                   \
            __VA_ARGS__                                                                            \
        }                                                                                          \
    } while (0)

#endif
