/* ball_bench_libm: what libball's own exp, expm1, log and log1p
 * (elementary.c) cost against glibc's, in ns per call (docs/benchmarks.md,
 * "libball's own exp, expm1, log and log1p"). A white-box benchmark beside
 * the white-box tests (it calls ball__expm1 and the others, which libball
 * does not export); ball_bench measures the public API.
 *
 * Each function over the arguments libball gives it: expm1 over [-0.72, 0]
 * (ball_bench's yardstick, eq 3 below t/b = ln 2), exp over [-11, -0.69]
 * (eq 3 beyond), log1p over (-1, 0] (eq 3 inverted: -d/b), log over [1, 1024]
 * (the rim search's stopping time). Every round times all eight loops one
 * after the other (glibc's, then libball's, function by function); every
 * number is the min and the median over the rounds of one run, and the
 * ratio compares them. Not a timed test: ctest runs only --smoke.
 *
 *   ball_bench_libm [--rounds N] [--scale X] [--smoke] */
#define _POSIX_C_SOURCE 200809L
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "../internal.h"
#include "bench_kit.h"

/* The arguments, from the loop's index i (the same 1024 in turn). */
#define ARG_EXPM1(i) (-(double)((i) & 1023) * 0.002 * 0.35) /* as bench_kit.c's time_expm1 */
#define ARG_EXP(i) (-0.69 - (double)((i) & 1023) * 0.01)
#define ARG_LOG1P(i) (-(double)((i) & 1023) * 0.00097)
#define ARG_LOG(i) (1.0 + (double)((i) & 1023))

/* One round of n calls, ns each; the results summed into *acc so that none is left out. */
#define TIMER(name, call)                              \
  static double name(long n, double *acc) {            \
    double t0 = bench_now();                           \
    long i;                                            \
    for (i = 0; i < n; i++) *acc += call;              \
    return 1e9 * (bench_now() - t0) / (double)n;       \
  }
TIMER(glibc_expm1, expm1(ARG_EXPM1(i)))
TIMER(own_expm1, ball__expm1(ARG_EXPM1(i)))
TIMER(glibc_exp, exp(ARG_EXP(i)))
TIMER(own_exp, ball__exp(ARG_EXP(i)))
TIMER(glibc_log1p, log1p(ARG_LOG1P(i)))
TIMER(own_log1p, ball__log1p(ARG_LOG1P(i)))
TIMER(glibc_log, log(ARG_LOG(i)))
TIMER(own_log, ball__log(ARG_LOG(i)))

typedef double (*timer)(long, double *);

static void usage(FILE *f) {
  fprintf(f,
          "usage: ball_bench_libm [--rounds N] [--scale X] [--smoke]\n"
          "  libball's own exp, expm1, log and log1p against glibc's, ns per call (docs/benchmarks.md)\n"
          "  --rounds N   rounds, min and median reported (default 11, at most %d)\n"
          "  --scale X    calls per round relative to the default 2,000,000 (default 1)\n"
          "  --smoke      a few calls, to check the program runs\n",
          BENCH_MAX_ROUNDS);
}

int main(int argc, char **argv) {
  static const struct option longs[] = {{"rounds", required_argument, NULL, 'r'},
                                        {"scale", required_argument, NULL, 'x'},
                                        {"smoke", no_argument, NULL, 'm'},
                                        {"help", no_argument, NULL, 'h'},
                                        {NULL, 0, NULL, 0}};
  static const struct {
    const char *name, *args;
    timer glibc, own;
  } fns[] = {{"expm1", "[-0.72, 0]", glibc_expm1, own_expm1},
             {"exp", "[-11, -0.69]", glibc_exp, own_exp},
             {"log1p", "(-1, 0]", glibc_log1p, own_log1p},
             {"log", "[1, 1024]", glibc_log, own_log}};
  double t[4][2][BENCH_MAX_ROUNDS], acc = 0.0, scale = 1.0;
  int rounds = 11, smoke = 0, opt, r, f;
  long n;
  char *end;
  while ((opt = getopt_long(argc, argv, "h", longs, NULL)) != -1) {
    switch (opt) {
    case 'r':
      rounds = (int)strtol(optarg, &end, 10);
      if (*end || rounds < 1 || rounds > BENCH_MAX_ROUNDS) {
        fprintf(stderr, "ball_bench_libm: --rounds wants 1 to %d\n", BENCH_MAX_ROUNDS);
        return 2;
      }
      break;
    case 'x':
      scale = strtod(optarg, &end);
      if (*end || !(scale > 0.0 && scale <= 100.0)) {
        fprintf(stderr, "ball_bench_libm: --scale wants a number in (0, 100]\n");
        return 2;
      }
      break;
    case 'm': smoke = 1; break;
    case 'h': usage(stdout); return 0;
    default: usage(stderr); return 2;
    }
  }
  if (optind < argc) {
    usage(stderr);
    return 2;
  }
  if (smoke) rounds = 3;
  n = smoke ? 20000 : (long)(2000000 * scale);
  if (n < 1024) n = 1024;
  for (r = 0; r < rounds; r++)
    for (f = 0; f < 4; f++) {
      t[f][0][r] = fns[f].glibc(n, &acc);
      t[f][1][r] = fns[f].own(n, &acc);
    }
  bench_sink = acc;
  printf("## libm: glibc's against libball's own (elementary.c), ns per call (%ld calls x %d rounds)%s\n", n,
         rounds, smoke ? ", smoke run" : "");
  printf("%-6s %-13s %9s %9s %9s %9s %9s %9s\n", "", "arguments", "glibc min", "glibc med", "own min", "own med",
         "own/glibc", "own/glibc");
  printf("%-6s %-13s %9s %9s %9s %9s %9s %9s\n", "", "", "", "", "", "", "min", "median");
  for (f = 0; f < 4; f++) {
    bench_stat g = bench_stats(t[f][0], rounds), o = bench_stats(t[f][1], rounds);
    printf("%-6s %-13s %9.2f %9.2f %9.2f %9.2f %9.2f %9.2f\n", fns[f].name, fns[f].args, g.min, g.median, o.min,
           o.median, o.min / g.min, o.median / g.median);
  }
  return 0;
}
