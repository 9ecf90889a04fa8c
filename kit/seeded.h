/* A small deterministic generator for seeded random cases (no libc rand:
 * the same numbers on every platform), for the unit tests and the programs
 * that share their case sets (kit/swings.h). Header only, C99 and
 * C++. */
#ifndef BALL_KIT_SEEDED_H
#define BALL_KIT_SEEDED_H

typedef struct seeded_rng {
  unsigned long long s;
} seeded_rng;

/* Uniform in [lo, hi): a 64-bit LCG, its top 53 bits. */
static inline double seeded_uniform(seeded_rng *r, double lo, double hi) {
  r->s = r->s * 6364136223846793005ULL + 1442695040888963407ULL;
  return lo + (hi - lo) * ((double)(r->s >> 11) / 9007199254740992.0);
}

#endif /* BALL_KIT_SEEDED_H */
