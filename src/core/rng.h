// bedlam — deterministic random numbers (xoshiro256** seeded by splitmix64).
//
// Every random draw in the solver goes through a bdl_rng owned by the caller, so a run is
// reproducible from its seed and the generator state can be checkpointed.
#ifndef BDL_RNG_H
#define BDL_RNG_H

#include <stdint.h>

#include "core/vec3.h"

typedef struct bdl_rng {
    uint64_t s[4];
} bdl_rng;

void bdl_rng_seed(bdl_rng *rng, uint64_t seed);
uint64_t bdl_rng_next(bdl_rng *rng);
/// Uniform in [0, 1).
double bdl_rng_uniform(bdl_rng *rng);
/// Uniform in [lo, hi).
double bdl_rng_range(bdl_rng *rng, double lo, double hi);
/// Standard normal (Box–Muller, no cached second value so the state stays a plain array).
double bdl_rng_normal(bdl_rng *rng);
/// A unit vector uniform over directions (three normal deviates, normalised).
bdl_vec3 bdl_rng_direction(bdl_rng *rng);

/// 64-bit FNV-1a over bytes, for state hashes.
uint64_t bdl_hash_bytes(uint64_t h, const void *data, unsigned long n);
#define BDL_HASH_INIT 1469598103934665603ULL

#endif
