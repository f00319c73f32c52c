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

#define BDL_PARALLEL_FOR(cond, ...)                                                                \
    do {                                                                                           \
        if (cond) {                                                                                \
            _Pragma("omp parallel for schedule(static)") __VA_ARGS__                               \
        } else {                                                                                   \
            __VA_ARGS__                                                                            \
        }                                                                                          \
    } while (0)

#endif
