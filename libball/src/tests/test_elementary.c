/* libball's own exp, expm1, log and log1p (elementary.c; docs/model.md, "The
 * same bits on every platform"):
 *
 *  - over more than 10^6 seeded inputs per function, spread over the whole
 *    domain (uniform in the exponent and the mantissa bits, both signs,
 *    subnormals) and packed near the places the algorithms branch (0, the
 *    range reductions' boundaries, k ln2 and (k + 1/2) ln2, sqrt(2)/2 and
 *    sqrt(2), -1 for log1p, the overflow and underflow thresholds), each
 *    result is within 1 ulp of glibc's (itself within 1 ulp of the true
 *    value), of the same sign, infinite where glibc's is; the counts of equal
 *    results and of results 1 ulp off are printed;
 *  - the same inputs give the same bits as on the day they were written down:
 *    a hash of every result per function, which any platform (x86_64 with or
 *    without FMA, aarch64, wasm32) must reproduce; it fails for any change of
 *    a coefficient, a threshold or the order of an operation;
 *  - the special values C99's Annex F gives, exactly (the sign of a zero too);
 *  - monotonicity on sorted inputs and across each branch's boundary, double
 *    by double. */
#include <float.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "core_common.h"
#include "../internal.h"

#define N_BITS 600000 /* inputs uniform in the exponent and mantissa bits, per function */
#define N_NEAR 600000 /* inputs near the branch points, per function */
#define WALK 4096     /* consecutive doubles on each side of a branch point (monotonicity) */

typedef double (*fn)(double);

static uint64_t bits_of(double x) {
  uint64_t u;
  memcpy(&u, &x, sizeof u);
  return u;
}
static double double_of(uint64_t u) {
  double x;
  memcpy(&x, &u, sizeof x);
  return x;
}
/* 64 random bits: the top halves of two of the kit's LCG's outputs (its low bits are weak). */
static uint64_t random_bits(seeded_rng *r) {
  uint64_t hi, lo;
  r->s = r->s * 6364136223846793005ULL + 1442695040888963407ULL;
  hi = r->s >> 32;
  r->s = r->s * 6364136223846793005ULL + 1442695040888963407ULL;
  lo = r->s >> 32;
  return hi << 32 | lo;
}
/* A double of sign s (0 +, 1 -, 2 either), exponent field in [e_lo, e_hi] and random mantissa. */
static double random_double(seeded_rng *r, int s, unsigned e_lo, unsigned e_hi) {
  uint64_t u = random_bits(r);
  uint64_t sign = s == 2 ? u >> 63 : (uint64_t)s;
  uint64_t e = e_lo + (uint64_t)seeded_below(r, (int)(e_hi - e_lo + 1));
  return double_of(sign << 63 | e << 52 | (u & 0xfffffffffffffULL));
}
/* x moved by k doubles (k < 0: towards -Inf), through 0 and the subnormals. */
static double step_doubles(double x, int64_t k) {
  /* the doubles in order as integers: -0 and +0 both 0 */
  uint64_t u = bits_of(x);
  int64_t key = (u >> 63) ? -(int64_t)(u & 0x7fffffffffffffffULL) : (int64_t)u;
  key += k;
  return key < 0 ? double_of(0x8000000000000000ULL | (uint64_t)(-key)) : double_of((uint64_t)key);
}
/* How many doubles apart a and b are; -1 when they cannot be compared so
 * (a NaN, an infinity against a finite, other signs of zero). */
static int64_t ulps_apart(double a, double b) {
  uint64_t ua = bits_of(a), ub = bits_of(b);
  int64_t ka, kb;
  if (isnan(a) || isnan(b)) return isnan(a) && isnan(b) ? 0 : -1;
  if (isinf(a) != isinf(b) || (ua >> 63) != (ub >> 63)) return -1;
  ka = (ua >> 63) ? -(int64_t)(ua & 0x7fffffffffffffffULL) : (int64_t)ua;
  kb = (ub >> 63) ? -(int64_t)(ub & 0x7fffffffffffffffULL) : (int64_t)ub;
  return ka > kb ? ka - kb : kb - ka;
}

/* ---- the inputs of each function ---- */

typedef struct fn_case {
  const char *name;
  fn ours, libm;
  /* the uniform part: sign (0 +, 1 -, 2 either), exponent fields; a second range (e_lo2 > e_hi2: none) */
  int sign;
  unsigned e_lo, e_hi;
  int sign2;
  unsigned e_lo2, e_hi2;
  const double *points; /* the branch points, each also multiplied by -1 when negate */
  int n_points;
  int negate;
  double lo, hi;        /* the inputs kept: lo <= x <= hi */
  uint64_t hash;        /* of every result, in order (results_hash) */
} fn_case;

#define LN2 0.69314718055994530942
static const double exp_points[] = {
    /* |x| = ln2 / 2 and 1.5 ln2 (high words 0x3fd62e42, 0x3ff0a2b2: where the reduction starts and
     * where k = +-1 ends), 2^-28 (0x3e300000), 2^-54 (0x3c900000) */
    0x1.62e42p-2, 0x1.0a2b2p+0, 0x1p-28, 0x1p-54,
    /* expm1: 56 ln2 (0x4043687a), the ends of k = 19 and 20 and of k = 56 (its three ways back),
     * x = ln2 - 1/4 (k = 1 with r < -1/4) */
    0x1.3687ap+5, 19.5 * LN2, 20.5 * LN2, 56.5 * LN2, LN2 - 0.25,
    /* exp: the overflow threshold, where the result turns subnormal (ln 2^-1022) and where its
     * scaling changes (k = -1021), the underflow threshold */
    0x1.62e42fefa39efp+9, -708.39641853226408, -1021.5 * LN2, -0x1.74910d52d3051p+9,
    1.0, 0.5, 2.0, 10.0, 100.0, 500.0};
static const double log_points[] = {
    /* x = 1 (f small: -2^-20 <= f < 2^-20), sqrt(2) and sqrt(2)/2 (the normalisation), the thresholds
     * of the more accurate form (mantissa 0x6147a and 0x6b851), 2 and 1/2, the ends of the doubles */
    1.0, 1.4142135623730951, 0.70710678118654757, 0x1.6147ap+0, 0x1.6b851p+0, 2.0, 0.5,
    DBL_MIN, DBL_MAX, 0x1p-1070, 0x1p-1060, 1e-300, 1e300, 1e-10, 1e10, 2.718281828459045, 10.0};
static const double log1p_points[] = {
    /* x = 0 (2^-29: 0x3e200000, 2^-54: 0x3c900000), sqrt(2) - 1 (0x3fda827a), 1 - sqrt(2)/2
     * (0xbfd2bec4), -1 and just above it, 2^53 (0x43400000), 1 + x at sqrt(2) 2^k and 2^k */
    0x1p-29, 0x1p-54, -0x1p-29, -0x1p-54, 0x1.a827ap-2, -0x1.2bec4p-2, -1.0 + 0x1p-53,
    -1.0 + 0x1p-30, -0.5, 0x1p53, 1.8284271247461903, 4.6568542494923806, 1.0, 3.0, 7.0, 1e100, DBL_MAX,
    0x1p-1070, 0.41421356237309503, -0.29289321881345248};

/* Hashes of the results, written down from this implementation on x86_64
 * (the same with gcc 12 and clang 14, -O0 and -O2; not with gcc -march=native
 * -ffp-contract=fast, whose fused operations change the results of each of
 * the four, 2 to 660 in 10^6) and to be reproduced everywhere; a change of
 * any bit of any result changes them. */
static fn_case cases[] = {
    {"exp", ball__exp, exp, 2, 0, 0x408, 2, 0x3c0, 0x408, exp_points, sizeof exp_points / sizeof *exp_points, 1,
     -800.0, 800.0, 0x8e384d686b930780ULL},
    {"expm1", ball__expm1, expm1, 2, 0, 0x408, 2, 0x3c0, 0x408, exp_points, sizeof exp_points / sizeof *exp_points,
     1, -800.0, 800.0, 0x3f7125017509694cULL},
    {"log", ball__log, log, 0, 0, 0x7fe, 0, 0x3f0, 0x40f, log_points, sizeof log_points / sizeof *log_points, 0,
     0.0, DBL_MAX, 0x3a98c164708abb2aULL},
    {"log1p", ball__log1p, log1p, 0, 0, 0x7fe, 1, 0, 0x3fe, log1p_points,
     sizeof log1p_points / sizeof *log1p_points, 0, -1.0, DBL_MAX, 0x40a93bc2e464dac3ULL},
};

/* The inputs of c, N_BITS + N_NEAR of them, seeded: half the uniform part
 * from each range, the rest near a branch point (k doubles away, k up to
 * 2^20, or up to 1e-6 relative), or near k ln2 and (k + 1/2) ln2 for
 * exp and expm1. Returns the count. */
static size_t inputs(const fn_case *c, double *x) {
  seeded_rng r = seeded_stream(2026, (uint64_t)(c - cases));
  size_t n = 0;
  int i;
  while (n < N_BITS) {
    double v = n % 2 == 0 || c->e_lo2 > c->e_hi2 ? random_double(&r, c->sign, c->e_lo, c->e_hi)
                                                 : random_double(&r, c->sign2, c->e_lo2, c->e_hi2);
    if (v >= c->lo && v <= c->hi) x[n++] = v;
  }
  for (i = 0; n < N_BITS + N_NEAR; i++) {
    double p, v;
    int kind = seeded_below(&r, 3);
    if (c->negate && kind == 2) {
      /* k ln2 or (k + 1/2) ln2, where the reduction's k changes or is exact */
      int k = seeded_below(&r, 2 * 1076) - 1076;
      p = (k + 0.5 * seeded_below(&r, 2)) * LN2;
    } else {
      p = c->points[seeded_below(&r, c->n_points)];
      if (c->negate && seeded_below(&r, 2)) p = -p;
    }
    if (kind == 0)
      v = step_doubles(p, (int64_t)seeded_below(&r, 1 << 21) - (1 << 20));
    else
      v = p * (1.0 + seeded_uniform(&r, -1e-6, 1e-6));
    if (v >= c->lo && v <= c->hi) x[n++] = v;
  }
  return n;
}

/* FNV-1a over the results' bits (a NaN as one word: its payload is the platform's). */
static uint64_t results_hash(const double *y, size_t n) {
  uint64_t h = 14695981039346656037ULL;
  size_t i;
  for (i = 0; i < n; i++) {
    uint64_t w = isnan(y[i]) ? 0x7ff8000000000000ULL : bits_of(y[i]);
    h = (h ^ w) * 1099511628211ULL;
  }
  return h;
}

static int compare_doubles(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return x < y ? -1 : x > y;
}

static double *g_x, *g_y;

static int setup(void **state) {
  (void)state;
  g_x = malloc((N_BITS + N_NEAR) * sizeof *g_x);
  g_y = malloc((N_BITS + N_NEAR) * sizeof *g_y);
  return g_x && g_y ? 0 : -1;
}
static int teardown(void **state) {
  (void)state;
  free(g_x);
  free(g_y);
  return 0;
}

/* Every result within 1 ulp of glibc's: counts printed; the hash of ours. */
static void within_one_ulp_of_glibc(const fn_case *c) {
  size_t n = inputs(c, g_x), i, equal = 0, one = 0, shown = 0;
  uint64_t h;
  assert_int_equal(n, N_BITS + N_NEAR);
  for (i = 0; i < n; i++) {
    double ours = c->ours(g_x[i]), want = c->libm(g_x[i]);
    int64_t d = ulps_apart(ours, want);
    g_y[i] = ours;
    if (d == 0)
      equal++;
    else if (d == 1)
      one++;
    else if (shown++ < 10)
      print_error("%s(%a) = %a, glibc %a (%lld ulp)\n", c->name, g_x[i], ours, want, (long long)d);
  }
  h = results_hash(g_y, n);
  print_message("%-5s %zu inputs: %zu equal to glibc's, %zu 1 ulp off, %zu more; results hash 0x%016llx\n",
                c->name, n, equal, one, n - equal - one, (unsigned long long)h);
  assert_int_equal(equal + one, n);
  if (c->hash != h) fail_msg("%s: results hash 0x%016llx, want 0x%016llx", c->name, (unsigned long long)h,
                             (unsigned long long)c->hash);
}

/* f(x) <= f(y) for x <= y: over the sorted inputs, and double by double across each branch point. */
static void monotonic(const fn_case *c) {
  size_t n = inputs(c, g_x), i;
  int p, s;
  qsort(g_x, n, sizeof *g_x, compare_doubles);
  for (i = 0; i < n; i++) g_y[i] = c->ours(g_x[i]);
  for (i = 1; i < n; i++)
    if (!(g_y[i - 1] <= g_y[i]))
      fail_msg("%s(%a) = %a > %s(%a) = %a", c->name, g_x[i - 1], g_y[i - 1], c->name, g_x[i], g_y[i]);
  for (p = 0; p < c->n_points; p++)
    for (s = 0; s <= c->negate; s++) {
      double centre = s ? -c->points[p] : c->points[p], prev = -INFINITY, x;
      int64_t k;
      for (k = -WALK; k <= WALK; k++) {
        double y;
        x = step_doubles(centre, k);
        if (!(x >= c->lo && x <= c->hi)) continue;
        y = c->ours(x);
        if (!(prev <= y)) fail_msg("%s at %a: %a after %a", c->name, x, y, prev);
        prev = y;
      }
    }
}

static void exp_within_one_ulp_of_glibc(void **state) {
  (void)state;
  within_one_ulp_of_glibc(&cases[0]);
}
static void expm1_within_one_ulp_of_glibc(void **state) {
  (void)state;
  within_one_ulp_of_glibc(&cases[1]);
}
static void log_within_one_ulp_of_glibc(void **state) {
  (void)state;
  within_one_ulp_of_glibc(&cases[2]);
}
static void log1p_within_one_ulp_of_glibc(void **state) {
  (void)state;
  within_one_ulp_of_glibc(&cases[3]);
}
static void all_four_are_monotonic(void **state) {
  int i;
  (void)state;
  for (i = 0; i < 4; i++) monotonic(&cases[i]);
}

/* The same result bits, sign included (a NaN: any NaN). */
#define assert_same(got, want) assert_same_at((got), (want), #got, __FILE__, __LINE__)
static void assert_same_at(double got, double want, const char *expr, const char *file, int line) {
  if (isnan(want) ? !isnan(got) : bits_of(got) != bits_of(want)) {
    print_error("%s = %a, want %a\n", expr, got, want);
    _fail(file, line);
  }
}

/* C99 Annex F's special values (F.9.3.1, .3, .7, .9), and the exact ones. */
static void special_values_as_annex_f_gives_them(void **state) {
  const double inf = INFINITY, nan = NAN, tiny = 0x1p-1074;
  (void)state;
  /* exp */
  assert_same(ball__exp(0.0), 1.0);
  assert_same(ball__exp(-0.0), 1.0);
  assert_same(ball__exp(inf), inf);
  assert_same(ball__exp(-inf), 0.0);
  assert_same(ball__exp(nan), nan);
  assert_same(ball__exp(-nan), nan);
  assert_same(ball__exp(710.0), inf); /* overflow */
  assert_same(ball__exp(DBL_MAX), inf);
  assert_same(ball__exp(-746.0), 0.0); /* underflow */
  assert_same(ball__exp(-DBL_MAX), 0.0);
  assert_same(ball__exp(-745.0), 0x1p-1074); /* the least subnormal: e^-745 = 4.9e-324 */
  assert_true(ball__exp(-740.0) > 0.0 && ball__exp(-740.0) < DBL_MIN);
  assert_true(ball__exp(0x1.62e42fefa39efp+9) > 0x1.fffffffffffp+1023); /* the largest x with a finite e^x */
  assert_true(ball__exp(0x1.62e42fefa39efp+9) < INFINITY);
  assert_same(ball__exp(0x1.62e42fefa39f0p+9), inf);
  assert_same(ball__exp(tiny), 1.0);
  /* expm1 */
  assert_same(ball__expm1(0.0), 0.0);
  assert_same(ball__expm1(-0.0), -0.0);
  assert_same(ball__expm1(inf), inf);
  assert_same(ball__expm1(-inf), -1.0);
  assert_same(ball__expm1(nan), nan);
  assert_same(ball__expm1(710.0), inf);
  assert_same(ball__expm1(-40.0), -1.0);
  assert_same(ball__expm1(-DBL_MAX), -1.0);
  assert_same(ball__expm1(tiny), tiny);
  assert_same(ball__expm1(-tiny), -tiny);
  assert_same(ball__expm1(0x1p-60), 0x1p-60);
  assert_same(ball__expm1(0x1.62e42fefa39f0p+9), inf);
  /* log */
  assert_same(ball__log(1.0), 0.0);
  assert_same(ball__log(0.0), -inf);
  assert_same(ball__log(-0.0), -inf);
  assert_same(ball__log(inf), inf);
  assert_same(ball__log(nan), nan);
  assert_same(ball__log(-1.0), nan);
  assert_same(ball__log(-tiny), nan);
  assert_same(ball__log(-inf), nan);
  /* log1p */
  assert_same(ball__log1p(0.0), 0.0);
  assert_same(ball__log1p(-0.0), -0.0);
  assert_same(ball__log1p(-1.0), -inf);
  assert_same(ball__log1p(inf), inf);
  assert_same(ball__log1p(nan), nan);
  assert_same(ball__log1p(-1.5), nan);
  assert_same(ball__log1p(-inf), nan);
  assert_same(ball__log1p(tiny), tiny);
  assert_same(ball__log1p(-tiny), -tiny);
  /* a NaN out is the same quiet NaN on every platform for a domain error */
  assert_true(bits_of(ball__log(-1.0)) == 0x7ff8000000000000ULL);
  assert_true(bits_of(ball__log1p(-2.0)) == 0x7ff8000000000000ULL);
}

/* Within 1 ulp of the true value (correctly rounded here, from 60 digits of
 * Python's decimal), where glibc is not the reference: e, e - 1, ln 2 and the
 * logarithms of the ends of the doubles. */
static void within_one_ulp_of_the_true_value(void **state) {
  static const struct {
    const char *what;
    fn f;
    double x, rounded;
  } cases_true[] = {
      {"exp(1) = e", ball__exp, 1.0, 0x1.5bf0a8b145769p+1},
      {"exp(-1) = 1/e", ball__exp, -1.0, 0x1.78b56362cef38p-2},
      {"exp(-745) = 4.94e-324", ball__exp, -745.0, 0x1p-1074},
      {"exp(709) = 8.22e307", ball__exp, 709.0, 0x1.d422d2be5dc9bp+1022},
      {"expm1(1) = e - 1", ball__expm1, 1.0, 0x1.b7e151628aed3p+0},
      {"expm1(-1) = 1/e - 1", ball__expm1, -1.0, -0x1.43a54e4e98864p-1},
      {"expm1(1e-10)", ball__expm1, 1e-10, 0x1.b7cdfd9dda4e3p-34},
      {"log(2) = ln 2", ball__log, 2.0, 0x1.62e42fefa39efp-1},
      {"log(e)", ball__log, 0x1.5bf0a8b145769p+1, 1.0},
      {"log(2^-1074)", ball__log, 0x1p-1074, -0x1.74385446d71c3p+9},
      {"log(DBL_MAX)", ball__log, DBL_MAX, 0x1.62e42fefa39efp+9},
      {"log(10)", ball__log, 10.0, 0x1.26bb1bbb55516p+1},
      {"log1p(1) = ln 2", ball__log1p, 1.0, 0x1.62e42fefa39efp-1},
      {"log1p(-0.5) = -ln 2", ball__log1p, -0.5, -0x1.62e42fefa39efp-1},
      {"log1p(1e-10)", ball__log1p, 1e-10, 0x1.b7cdfd9d1d693p-34},
      {"log1p(DBL_MAX)", ball__log1p, DBL_MAX, 0x1.62e42fefa39efp+9},
  };
  size_t i;
  (void)state;
  for (i = 0; i < sizeof cases_true / sizeof *cases_true; i++) {
    double got = cases_true[i].f(cases_true[i].x);
    int64_t d = ulps_apart(got, cases_true[i].rounded);
    if (d < 0 || d > 1) fail_msg("%s: %a, the true value rounded %a", cases_true[i].what, got, cases_true[i].rounded);
  }
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(special_values_as_annex_f_gives_them),
      cmocka_unit_test(within_one_ulp_of_the_true_value),
      cmocka_unit_test(exp_within_one_ulp_of_glibc),
      cmocka_unit_test(expm1_within_one_ulp_of_glibc),
      cmocka_unit_test(log_within_one_ulp_of_glibc),
      cmocka_unit_test(log1p_within_one_ulp_of_glibc),
      cmocka_unit_test(all_four_are_monotonic),
  };
  return cmocka_run_group_tests(tests, setup, teardown);
}
