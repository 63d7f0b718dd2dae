/* bench_util.h -- what every benchmark program needs: a monotonic clock and
 * a deterministic random stream (the same figures' inputs on every
 * machine).  Header-only: each program is one file. */
#ifndef BENCH_UTIL_H
#define BENCH_UTIL_H

#include <stdint.h>
#include <time.h>

static inline double bench_seconds(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + (double)t.tv_nsec * 1e-9;
}

/* xorshift64*: uniform in [0, 1). */
static inline double bench_uniform01(uint64_t *state)
{
    *state ^= *state >> 12;
    *state ^= *state << 25;
    *state ^= *state >> 27;
    uint64_t bits = (*state * 2685821657736338717ULL) >> 11;
    return (double)bits / 9007199254740992.0;
}

/* Uniform in [-1, 1): a wrench component. */
static inline double bench_uniform(uint64_t *state) { return bench_uniform01(state) * 2 - 1; }

#endif
