/* The one for-each-scheme driver of the C tests: EACH_SCHEME(test) in a
 * CMocka test table stands for two entries that run the test's body under
 * BALL_SCHEME_SAMPLED and under BALL_SCHEME_EXACT, named "test (sampled)"
 * and "test (exact)", so a failure says which. The body reads its scheme
 * with test_scheme(state). Header only, C99; include after <cmocka.h>. */
#ifndef BALL_TESTS_SCHEMES_H
#define BALL_TESTS_SCHEMES_H

#include "ball/ball.h"

/* The state a scheme's entry starts with (a pointer to the scheme). */
static inline void *scheme_state(ball_scheme scheme) {
  static ball_scheme schemes[BALL_SCHEME_COUNT] = {BALL_SCHEME_SAMPLED, BALL_SCHEME_EXACT};
  return &schemes[scheme];
}

/* The scheme the running entry is for. */
static inline ball_scheme test_scheme(void **state) { return *(const ball_scheme *)*state; }

#define EACH_SCHEME(test)                                                   \
  {#test " (sampled)", test, NULL, NULL, scheme_state(BALL_SCHEME_SAMPLED)}, \
  {#test " (exact)", test, NULL, NULL, scheme_state(BALL_SCHEME_EXACT)}

#endif /* BALL_TESTS_SCHEMES_H */
