#include "core/rng.h"

#include <math.h>

static uint64_t splitmix64(uint64_t *x)
{
    uint64_t z = (*x += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
}

static uint64_t rotl(uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }

void bdl_rng_seed(bdl_rng *rng, uint64_t seed)
{
    uint64_t x = seed;
    for (int i = 0; i < 4; ++i)
        rng->s[i] = splitmix64(&x);
}

uint64_t bdl_rng_next(bdl_rng *rng)
{
    uint64_t *s = rng->s;
    uint64_t result = rotl(s[1] * 5, 7) * 9;
    uint64_t t = s[1] << 17;
    s[2] ^= s[0];
    s[3] ^= s[1];
    s[1] ^= s[2];
    s[0] ^= s[3];
    s[2] ^= t;
    s[3] = rotl(s[3], 45);
    return result;
}

double bdl_rng_uniform(bdl_rng *rng) { return (double)(bdl_rng_next(rng) >> 11) * 0x1.0p-53; }

double bdl_rng_range(bdl_rng *rng, double lo, double hi)
{
    return lo + (hi - lo) * bdl_rng_uniform(rng);
}

double bdl_rng_normal(bdl_rng *rng)
{
    double u1 = bdl_rng_uniform(rng);
    double u2 = bdl_rng_uniform(rng);
    if (u1 < 1e-300)
        u1 = 1e-300;
    return sqrt(-2.0 * log(u1)) * cos(2.0 * 3.14159265358979323846 * u2);
}

uint64_t bdl_hash_bytes(uint64_t h, const void *data, unsigned long n)
{
    const unsigned char *p = data;
    for (unsigned long i = 0; i < n; ++i) {
        h ^= p[i];
        h *= 1099511628211ULL;
    }
    return h;
}

bdl_vec3 bdl_rng_direction(bdl_rng *rng)
{
    bdl_vec3 u;
    u.x = bdl_rng_normal(rng); // one draw per statement: argument order is unspecified in C
    u.y = bdl_rng_normal(rng);
    u.z = bdl_rng_normal(rng);
    return bdl_v3_normalize(u);
}
