/* The one deterministic generator for seeded random cases, for the tests,
 * the benchmarks and the validation (no libc rand, no <random>
 * distribution: the same numbers on every platform and standard library).
 * A case's seed is its generator's state, so a printed seed reruns that
 * case. Header only, C99 and C++. */
#ifndef BALL_KIT_SEEDED_H
#define BALL_KIT_SEEDED_H

#include <stdint.h>

typedef struct seeded_rng {
  uint64_t s; /* the state: start it at the seed */
} seeded_rng;

/* Uniform in [lo, hi): a 64-bit LCG, its top 53 bits. */
static inline double seeded_uniform(seeded_rng *r, double lo, double hi) {
  r->s = r->s * 6364136223846793005ULL + 1442695040888963407ULL;
  return lo + (hi - lo) * ((double)(r->s >> 11) / 9007199254740992.0);
}

/* Uniform in {0, 1, ..., n - 1} (n >= 1), from the top bits (an LCG's low
 * bits have short periods). */
static inline int seeded_below(seeded_rng *r, int n) {
  int k = (int)seeded_uniform(r, 0.0, (double)n);
  return k < n ? k : n - 1;
}

/* A generator of its own for case set `stream` of `seed`, so that one set
 * does not change when another grows: the state is both, mixed by
 * splitmix64's output function, so nearby seeds and streams start far
 * apart. */
static inline seeded_rng seeded_stream(uint64_t seed, uint64_t stream) {
  uint64_t z = seed ^ (stream * 0x9E3779B97F4A7C15ULL + 0x632BE59BD9B4E019ULL);
  seeded_rng r;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  r.s = z ^ (z >> 31);
  return r;
}

#endif /* BALL_KIT_SEEDED_H */
