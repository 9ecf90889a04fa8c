/* ball_bench: nanoseconds per ball_step for one scene with each effect on,
 * switched off in the mask, and removed from the model instead (the "model
 * without it" of tests/unit/test_effects.c). It shows that a disabled effect
 * costs nothing measurable: "off / without" should be 1 within the noise.
 * All ratios come from one run on one machine; see docs/benchmarks.md.
 *
 *   ball_bench [--seconds S] [--scheme exact|sampled] [--smoke]
 *
 * --smoke runs a few thousand steps per case (a ctest that checks the program
 * works; it asserts nothing about time). */
#define _POSIX_C_SOURCE 199309L

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "ball/ball.h"

#define FPS 60.0
#define RESTART_FRAMES 420 /* 7 s of play, then the serve again */

static ball_vec3 vec(double x, double y, double z) {
  ball_vec3 r;
  r.x = x;
  r.y = y;
  r.z = z;
  return r;
}

/* The scene of test_effects.c: a serve into the net, back to the walls,
 * bounces, a spinning ball; every effect but rackets on. */
static void full_scene(ball_model *m, ball_scheme scheme) {
  ball_plane back = {0, -1.0, -5.0, 15.0, 0.0, 4.0, 0.8};
  ball_plane side = {2, -0.5, -5.0, 30.0, 0.0, 4.0, 0.7};
  ball_model_default(m);
  m->mass = 0.05;
  m->air_friction = 0.01;
  m->radius = 0.03;
  m->floor_damping = 0.8;
  m->net.damping = 0.9;
  m->effects = BALL_EFFECT_DRAG | BALL_EFFECT_SPIN | BALL_EFFECT_FLOOR | BALL_EFFECT_NET |
               BALL_EFFECT_WALLS | BALL_EFFECT_SOUND;
  m->scheme = scheme;
  ball_model_add_wall(m, &back);
  ball_model_add_wall(m, &side);
  m->initial_position = vec(3.0, 1.5, 2.0);
  m->initial_velocity = vec(12.0, 3.0, -0.5);
  m->initial_spin = vec(0.5, 0.0, 2.0);
}

typedef struct effect_case {
  unsigned bit;
  void (*without)(ball_model *m); /* the model without the effect */
} effect_case;

static void drag_without(ball_model *m) { m->air_friction = 0.0; }
static void spin_without(ball_model *m) { m->initial_spin = vec(0.0, 0.0, 0.0); }
static void floor_without(ball_model *m) { m->floor_level = -1e300; }
static void net_without(ball_model *m) { m->has_net = 0; }
static void walls_without(ball_model *m) { m->n_walls = 0; }
static void rackets_without(ball_model *m) { m->n_rackets = 0; }
static void sound_without(ball_model *m) { m->sound_threshold = INFINITY; }

static double now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static volatile double sink;

/* ns per step over `steps` steps of m (the serve restarted every 7 s). */
static double time_steps(const ball_model *m, long steps) {
  ball_sim sim;
  ball_event ev[BALL_MAX_CONTACTS];
  double t0, t1, acc = 0.0;
  long i;
  int n;
  if (ball_sim_init(m, &sim) != BALL_OK) return NAN;
  t0 = now();
  for (i = 0; i < steps; i++) {
    if (sim.frame == RESTART_FRAMES) ball_sim_init(m, &sim);
    if (ball_step(m, &sim, 1.0 / FPS, ev, BALL_MAX_CONTACTS, &n) != BALL_OK) return NAN;
    acc += sim.prev_position.x;
  }
  t1 = now();
  sink = acc;
  return 1e9 * (t1 - t0) / (double)steps;
}

/* Best of `rounds` interleaved timings of three models (min: the least
 * disturbed run; interleaving spreads frequency drift over all three). */
static void time_three(const ball_model *a, const ball_model *b, const ball_model *c, long steps,
                       int rounds, double out[3]) {
  int r;
  out[0] = out[1] = out[2] = INFINITY;
  for (r = 0; r < rounds; r++) {
    double ta = time_steps(a, steps), tb = time_steps(b, steps), tc = time_steps(c, steps);
    if (ta < out[0]) out[0] = ta;
    if (tb < out[1]) out[1] = tb;
    if (tc < out[2]) out[2] = tc;
  }
}

static void usage(FILE *f) {
  fprintf(f,
          "usage: ball_bench [--seconds S] [--scheme exact|sampled] [--smoke]\n"
          "  ns per ball_step with each effect on, off in the mask, and removed from the\n"
          "  model; 'off/without' near 1 means a disabled effect costs nothing.\n"
          "  --seconds S  rough total running time (default 4)\n"
          "  --scheme     static obstacle detection (default exact)\n"
          "  --smoke      a few thousand steps per case, to check the program runs\n");
}

int main(int argc, char **argv) {
  static const effect_case cases[] = {
      {BALL_EFFECT_DRAG, drag_without},   {BALL_EFFECT_SPIN, spin_without},
      {BALL_EFFECT_FLOOR, floor_without}, {BALL_EFFECT_NET, net_without},
      {BALL_EFFECT_WALLS, walls_without}, {BALL_EFFECT_RACKETS, rackets_without},
      {BALL_EFFECT_SOUND, sound_without},
  };
  const int n_cases = (int)(sizeof cases / sizeof cases[0]);
  const int rounds = 21;
  double seconds = 4.0;
  ball_scheme scheme = BALL_SCHEME_EXACT;
  long steps;
  int i, smoke = 0;
  for (i = 1; i < argc; i++) {
    if (!strcmp(argv[i], "--seconds") && i + 1 < argc) {
      seconds = strtod(argv[++i], NULL);
      if (!(seconds > 0.0 && seconds < 3600.0)) {
        fprintf(stderr, "ball_bench: --seconds wants a number in (0, 3600)\n");
        return 2;
      }
    } else if (!strcmp(argv[i], "--scheme") && i + 1 < argc) {
      i++;
      if (!strcmp(argv[i], "exact"))
        scheme = BALL_SCHEME_EXACT;
      else if (!strcmp(argv[i], "sampled"))
        scheme = BALL_SCHEME_SAMPLED;
      else {
        fprintf(stderr, "ball_bench: unknown scheme '%s'\n", argv[i]);
        return 2;
      }
    } else if (!strcmp(argv[i], "--smoke")) {
      smoke = 1;
    } else if (!strcmp(argv[i], "--help") || !strcmp(argv[i], "-h")) {
      usage(stdout);
      return 0;
    } else {
      usage(stderr);
      return 2;
    }
  }
  {
    /* calibrate: steps per timing so the whole run takes about `seconds` */
    ball_model m;
    double ns;
    full_scene(&m, scheme);
    if (ball_model_check(&m, NULL) != BALL_OK) {
      fprintf(stderr, "ball_bench: the bench scene is not valid\n");
      return 1;
    }
    ns = time_steps(&m, 20000);
    if (!(ns > 0.0)) ns = 100.0;
    steps = smoke ? 2000 : (long)(seconds * 1e9 / (ns * 3.0 * rounds * n_cases));
    if (steps < 2000) steps = 2000;
    printf("ball_bench: scheme %s, %ld steps x %d rounds per case (best round kept), %.0f Hz\n",
           ball_scheme_name(scheme), steps, rounds, FPS);
  }
  printf("%-8s %10s %10s %10s %9s %12s\n", "effect", "on ns", "off ns", "without ns", "off/on",
         "off/without");
  for (i = 0; i < n_cases; i++) {
    ball_model on, off, without;
    double t[3];
    full_scene(&on, scheme);
    if (cases[i].bit == BALL_EFFECT_RACKETS) {
      /* two rackets with no samples yet: the stage runs and finds nothing */
      on.effects |= BALL_EFFECT_RACKETS;
      on.n_rackets = 2;
    }
    off = on;
    off.effects &= ~cases[i].bit;
    without = on;
    cases[i].without(&without);
    time_three(&on, &off, &without, steps, rounds, t);
    if (!(isfinite(t[0]) && isfinite(t[1]) && isfinite(t[2]))) {
      fprintf(stderr, "ball_bench: a step failed (%s)\n", ball_effect_name((ball_effect)cases[i].bit));
      return 1;
    }
    printf("%-8s %10.1f %10.1f %10.1f %9.3f %12.3f\n", ball_effect_name((ball_effect)cases[i].bit),
           t[0], t[1], t[2], t[1] / t[0], t[1] / t[2]);
  }
  return 0;
}
