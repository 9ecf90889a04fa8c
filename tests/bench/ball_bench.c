/* ball_bench: what users run, in nanoseconds (docs/benchmarks.md).
 *
 *   eval     ball_segment_eval and ball_flight_eval with drag and spin, against
 *            one bare expm1 (the targets' unit)
 *   rally    a whole frame (the racket samples that arrived, pushed, then
 *            ball_step) of each rally scene with the sphere, disc and swept
 *            tests: median and worst frame, and the mean of the best round
 *   predict  ball_predict: 6 s of a bouncing ball at 120 Hz (what a bot asks
 *            every frame), against stepping the same 720 frames and in expm1
 *            calls timed in the same rounds
 *   walls    a frame in a box of 0..16 walls: the cost of one wall
 *   rackets  a frame with 0..4 rackets that get samples: the cost of one racket
 *   effects  each effect on, off in the mask, and removed from the model
 *   contact  ball_racket_first_contact over 0.3 s from sims caught before a
 *            stroke (kit/swings.h at 10 Hz), per test, against one expm1
 *
 * Every number is the min and the median over several rounds of one run on
 * one machine; ratios compare numbers of the same run. Not a timed test:
 * ctest runs only `ball_bench --smoke`, which checks the program works.
 *
 *   ball_bench [--rounds N] [--scale X] [--smoke] [--only SECTION] [--scenes DIR] */
#define _POSIX_C_SOURCE 200809L
#include <getopt.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ball/ball.h"
#include "ball/scene.h"
#include "ball/vec3.h"
#include "bench_kit.h"
#include "swings.h"

#define MAX_ROUNDS BENCH_MAX_ROUNDS

typedef struct opts {
  int rounds;       /* rounds per measurement */
  double scale;     /* work per round, relative */
  int smoke;        /* a few iterations, no meaning in the numbers */
  const char *only; /* one section, or NULL */
  const char *scenes;
} opts;

static int rounds_of(const opts *o) { return o->smoke ? 3 : o->rounds; }
static long work(const opts *o, long n) {
  long w = o->smoke ? n / 100 : (long)(n * o->scale);
  return w < 10 ? 10 : w;
}

static int section(const opts *o, const char *name) { return !o->only || strcmp(o->only, name) == 0; }

/* the lean evaluation of this run (bench_kit.h: the yardstick) */
static double g_lean_ns = BENCH_REF_LEAN_NS;
static double g_expm1_ns = 0.0; /* one expm1 of this run (eval) */
static double at_ref(double ns) { return ns * BENCH_REF_LEAN_NS / g_lean_ns; }

/* ---- eval ---- */

static void bench_eval(const opts *o) {
  bench_eval_result e;
  long n = work(o, 2000000);
  int R = rounds_of(o);
  bench_stat a, b, c, d;
  bench_eval_run(R, n, &e);
  a = e.segment_eval;
  b = e.expm1;
  c = e.lean;
  d = e.flight_eval;
  printf("\n## eval: one state on a segment, drag and spin on (%ld calls x %d rounds)\n", n, R);
  printf("%-28s %9s %9s\n", "", "min ns", "median ns");
  printf("%-28s %9.2f %9.2f\n", "ball_segment_eval", a.min, a.median);
  printf("%-28s %9.2f %9.2f\n", "ball_flight_eval", d.min, d.median);
  g_lean_ns = c.median;
  g_expm1_ns = b.median;
  printf("%-28s %9.2f %9.2f\n", "lean (1/b given, no checks)", c.min, c.median);
  printf("%-28s %9.2f %9.2f\n", "one expm1 (the floor)", b.min, b.median);
  printf("%-28s %9.2f %9.2f\n", "segment_eval / lean", a.min / c.min, a.median / c.median);
  printf("%-28s %9.2f %9.2f\n", "flight_eval / lean", d.min / c.min, d.median / c.median);
  printf("%-28s %9.2f %9.2f\n", "segment_eval / expm1", a.min / b.min, a.median / b.median);
  printf("%-28s %9.2f %9.2f\n", "flight_eval / expm1", d.min / b.min, d.median / b.median);
  printf("%-28s %9.2f %9.2f\n", "ball_segment_eval @ref", at_ref(a.min), at_ref(a.median));
  printf("%-28s %9.2f %9.2f\n", "ball_flight_eval @ref", at_ref(d.min), at_ref(d.median));
}

/* ---- rally ---- */

static void bench_rally(const opts *o) {
  static const char *const scenes[] = {"rally_easy.yaml", "rally_mid.yaml", "rally_advanced.yaml"};
  static const ball_detect detects[] = {BALL_DETECT_SPHERE, BALL_DETECT_DISC, BALL_DETECT_SWEPT};
  double overhead = bench_timer_overhead();
  int R = rounds_of(o), si, di;
  printf("\n## rally: a whole frame (samples pushed + ball_step) of each rally scene\n");
  printf("timer overhead %.1f ns (subtracted from single frames); %d rounds\n", overhead, R);
  printf("%-20s %-7s %7s %5s %6s %9s %9s %9s %9s %9s %9s\n", "scene", "detect", "frames", "hits", "pushes",
         "mean min", "mean med", "frame med", "worst", "med@ref", "worst@ref");
  for (si = 0; si < 3; si++) {
    bench_run rn;
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", o->scenes, scenes[si]);
    if (!bench_run_prepare(&rn, path)) {
      fprintf(stderr, "ball_bench: cannot prepare %s\n", path);
      exit(1);
    }
    for (di = 0; di < 3; di++) {
      bench_rally_result ra;
      if (!bench_rally_run(&rn, detects[di], R, work(o, 40), o->smoke ? 2 : 15, &ra)) exit(1);
      printf("%-20s %-7s %7ld %5d %6ld %9.1f %9.1f %9.1f %9.1f %9.1f %9.1f\n", scenes[si],
             ball_detect_name(detects[di]), ra.frames, ra.hits, rn.n_samples, ra.mean.min, ra.mean.median,
             ra.frame_median, ra.worst, at_ref(ra.frame_median), at_ref(ra.worst));
    }
    bench_run_free(&rn);
  }
}

/* ---- predict ---- */

static void bench_predict(const opts *o) {
  bench_predict_result p;
  long n = work(o, 2000);
  int R = rounds_of(o);
  bench_stat a, b;
  bench_predict_run(R, n, &p);
  a = p.predict;
  b = p.steps;
  printf("\n## predict: 6 s at 120 Hz (721 states, %d contacts), %ld calls x %d rounds\n", p.contacts, n, R);
  printf("%-28s %9s %9s\n", "", "min us", "median us");
  printf("%-28s %9.2f %9.2f\n", "ball_predict", a.min, a.median);
  printf("%-28s %9.2f %9.2f\n", "720 x ball_step", b.min, b.median);
  printf("%-28s %9.3f %9.3f\n", "predict / steps", a.min / b.min, a.median / b.median);
  printf("%-28s %9.2f %9.2f\n", "ball_predict @ref", at_ref(a.min), at_ref(a.median));
  printf("%-28s %9.2f %9.2f\n", "one expm1 (ns)", p.expm1.min, p.expm1.median);
  printf("%-28s %9.0f %9.0f\n", "predict / expm1", 1e3 * a.min / p.expm1.min, 1e3 * a.median / p.expm1.median);
}

/* ---- walls and rackets: cost per obstacle ---- */

/* A ball bouncing in a 10 m box (4 walls) plus n - 4 far walls (n >= 4), or
 * only the first n box walls; 600 frames a pass. */
static void wall_scene(ball_model *m, int n) {
  int i;
  ball_model_default(m);
  m->has_net = 0;
  m->radius = 0.03;
  m->floor_damping = 1.0;
  m->effects = BALL_EFFECT_DRAG | BALL_EFFECT_FLOOR | BALL_EFFECT_WALLS;
  m->initial_position = ball_v3(5.0, 1.0, 5.0);
  m->initial_velocity = ball_v3(7.0, 3.0, 5.0);
  for (i = 0; i < n; i++) {
    ball_plane w = {i % 2 ? 2 : 0, i < 4 ? (i / 2 ? 10.0 : 0.0) : 100.0 + i, -1.0, 11.0, 0.0, 5.0, 1.0};
    ball_model_add_wall(m, &w);
  }
}

static void bench_walls(const opts *o) {
  int R = rounds_of(o), r, n;
  long passes = work(o, 200);
  double first = 0.0, last = 0.0;
  printf("\n## walls: a frame of a ball bouncing in a box, n walls (4 box walls, the rest far away)\n");
  printf("%-6s %9s %9s\n", "walls", "min ns", "median ns");
  for (n = 0; n <= BALL_MAX_WALLS; n += n < 4 ? 4 : 4) {
    ball_model m;
    double t[MAX_ROUNDS];
    bench_stat s;
    wall_scene(&m, n);
    for (r = 0; r < R; r++) t[r] = bench_time_frames(&m, passes, 600, 1.0 / 60.0);
    s = bench_stats(t, R);
    printf("%-6d %9.1f %9.1f\n", n, s.min, s.median);
    if (n == 4) first = s.median;
    last = s.median;
  }
  printf("cost of one far wall: %.2f ns (median, (16 walls - 4 walls) / 12)\n", (last - first) / 12.0);
}

static void bench_rackets(const opts *o) {
  bench_run rn;
  char path[1024];
  int R = rounds_of(o), n, r, d;
  snprintf(path, sizeof path, "%s/%s", o->scenes, "rally_advanced.yaml");
  if (!bench_run_prepare(&rn, path)) exit(1);
  printf("\n## rackets: rally_advanced with its 2 scripted rackets plus far rackets that get the same "
         "samples moved 50 m away\n");
  printf("%-7s %-7s %9s %9s\n", "rackets", "detect", "min ns", "median ns");
  for (d = BALL_DETECT_DISC; d <= BALL_DETECT_SWEPT; d++)
    for (n = 2; n <= BALL_MAX_RACKETS; n++) {
      ball_model m = rn.scene.model;
      ball_sim sim;
      double t[MAX_ROUNDS];
      long passes = work(o, 40), p, k;
      bench_stat s;
      int events[BALL_EVENT_KIND_COUNT];
      m.detect = (ball_detect)d;
      m.n_rackets = n;
      for (r = 0; r < R; r++) {
        double t0 = bench_now();
        for (p = 0; p < passes; p++) {
          ball_sim_init(&sim, &m);
          for (k = 0; k < rn.frames; k++) {
            const ball_script_sample *s0 = rn.samples + rn.per_frame[k].first;
            int i, j;
            for (i = 0; i < rn.per_frame[k].count; i++)
              for (j = s0[i].racket; j < n; j += 2) {
                ball_racket_sample far = s0[i].sample;
                if (j >= 2) far.center.z += 50.0;
                ball_racket_push(&sim, j, &far);
              }
            ball_step(&sim, rn.dt, NULL, 0, NULL);
          }
        }
        t[r] = 1e9 * (bench_now() - t0) / (double)(passes * rn.frames);
      }
      (void)events;
      s = bench_stats(t, R);
      printf("%-7d %-7s %9.1f %9.1f\n", n, ball_detect_name((ball_detect)d), s.min, s.median);
    }
  bench_run_free(&rn);
}

/* ---- effects: on, off, and the model without it ---- */

static void bench_effects(const opts *o) {
  static const ball_effect cases[] = {BALL_EFFECT_DRAG,  BALL_EFFECT_SPIN,    BALL_EFFECT_FLOOR, BALL_EFFECT_NET,
                                       BALL_EFFECT_WALLS, BALL_EFFECT_RACKETS, BALL_EFFECT_SOUND};
  int R = rounds_of(o), i, r, j;
  long passes = work(o, 100);
  printf("\n## effects: a 7 s serve (420 frames) with each effect on, off in the mask, removed from "
         "the model (ns per frame, min of interleaved rounds: the least disturbed)\n");
  printf("%-8s %9s %9s %10s %8s %11s\n", "effect", "on", "off", "without", "off/on", "off/without");
  for (i = 0; i < (int)(sizeof cases / sizeof cases[0]); i++) {
    ball_model v[3];
    double t[3][MAX_ROUNDS];
    bench_stat s[3];
    bench_full_scene(&v[0]);
    if (cases[i] == BALL_EFFECT_RACKETS) {
      v[0].effects |= BALL_EFFECT_RACKETS; /* two rackets that get no samples */
      v[0].n_rackets = 2;
    }
    v[1] = v[0];
    v[1].effects &= ~(unsigned)cases[i];
    v[2] = v[0];
    bench_without(&v[2], cases[i]);
    for (r = 0; r < R; r++)
      for (j = 0; j < 3; j++) t[j][r] = bench_time_frames(&v[j], passes, 420, 1.0 / 60.0); /* interleaved */
    for (j = 0; j < 3; j++) s[j] = bench_stats(t[j], R);
    printf("%-8s %9.1f %9.1f %10.1f %8.3f %11.3f\n", ball_effect_name(cases[i]), s[0].min,
           s[1].min, s[2].min, s[1].min / s[0].min, s[1].min / s[2].min);
  }
}

/* ---- contact: when a racket will first meet the ball ---- */

#define CONTACT_SIMS 64

static void bench_contact(const opts *o) {
  static const ball_detect detects[] = {BALL_DETECT_SPHERE, BALL_DETECT_DISC, BALL_DETECT_SWEPT};
  static ball_sim sims[CONTACT_SIMS];
  int R = rounds_of(o), d, r, k;
  long passes = work(o, 20);
  printf("\n## contact: ball_racket_first_contact over 0.3 s, %d sims caught 0.1-0.3 s before a stroke "
         "(10 Hz swings), %ld passes x %d rounds\n", CONTACT_SIMS, passes, R);
  printf("%-7s %5s %9s %9s %12s\n", "detect", "hits", "min ns", "median ns", "median/expm1");
  for (d = 0; d < 3; d++) {
    seeded_rng rng = seeded_stream(4242, (uint64_t)d);
    double t[MAX_ROUNDS];
    bench_stat s;
    int hits = 0;
    for (k = 0; k < CONTACT_SIMS; k++) {
      ball_model m;
      swing sw;
      ball_state st;
      double t_catch;
      int j;
      swing_model(&m, detects[d]);
      m.extrapolation_time = 0.1;
      swing_make(&m, &rng, 0.1, &sw);
      t_catch = seeded_uniform(&rng, 0.3, 0.5);
      st.position = sw.seg.p0;
      st.velocity = sw.seg.v0;
      st.spin = sw.seg.s0;
      ball_sim_init(&sims[k], &m);
      ball_sim_set_state(&sims[k], &st);
      for (j = 0; j < sw.n && sw.s[j].t <= t_catch; j++) {
        ball_racket_push(&sims[k], 0, &sw.s[j]);
        ball_step(&sims[k], sw.s[j].t - sims[k].time, NULL, 0, NULL);
      }
    }
    for (r = 0; r < R; r++) {
      double t0 = bench_now();
      long p;
      hits = 0;
      for (p = 0; p < passes; p++)
        for (k = 0; k < CONTACT_SIMS; k++) {
          ball_racket_contact c;
          hits += ball_racket_first_contact(&sims[k], 0, sims[k].time + 0.3, &c) == BALL_OK;
        }
      t[r] = 1e9 * (bench_now() - t0) / (double)(passes * CONTACT_SIMS);
    }
    s = bench_stats(t, R);
    printf("%-7s %5d %9.1f %9.1f %12.1f\n", ball_detect_name(detects[d]), hits / (int)passes, s.min, s.median,
           s.median / g_expm1_ns);
  }
}

static void usage(FILE *f) {
  fprintf(f,
          "usage: ball_bench [--rounds N] [--scale X] [--smoke] [--only SECTION] [--scenes DIR]\n"
          "  sections: eval, rally, predict, walls, rackets, effects, contact (docs/benchmarks.md)\n"
          "  --rounds N   rounds per measurement, min and median reported (default 11, at most %d)\n"
          "  --scale X    work per round relative to the default (default 1)\n"
          "  --smoke      a few iterations of everything, to check the program runs\n"
          "  --scenes DIR the example scenes (default: $BALL_SCENES or libball/scenes)\n",
          MAX_ROUNDS);
}

int main(int argc, char **argv) {
  opts o;
  int i;
  o.rounds = 11;
  o.scale = 1.0;
  o.smoke = 0;
  o.only = NULL;
  o.scenes = getenv("BALL_SCENES") ? getenv("BALL_SCENES") : "libball/scenes";
  {
    static const struct option longs[] = {{"rounds", required_argument, NULL, 'r'},
                                          {"scale", required_argument, NULL, 'x'},
                                          {"only", required_argument, NULL, 'o'},
                                          {"scenes", required_argument, NULL, 's'},
                                          {"smoke", no_argument, NULL, 'm'},
                                          {"help", no_argument, NULL, 'h'},
                                          {NULL, 0, NULL, 0}};
    char *end;
    while ((i = getopt_long(argc, argv, "h", longs, NULL)) != -1) {
      switch (i) {
      case 'r':
        o.rounds = (int)strtol(optarg, &end, 10);
        if (*end || o.rounds < 1 || o.rounds > MAX_ROUNDS) {
          fprintf(stderr, "ball_bench: --rounds wants 1 to %d\n", MAX_ROUNDS);
          return 2;
        }
        break;
      case 'x':
        o.scale = strtod(optarg, &end);
        if (*end || !(o.scale > 0.0 && o.scale <= 100.0)) {
          fprintf(stderr, "ball_bench: --scale wants a number in (0, 100]\n");
          return 2;
        }
        break;
      case 'o': o.only = optarg; break;
      case 's': o.scenes = optarg; break;
      case 'm': o.smoke = 1; break;
      case 'h': usage(stdout); return 0;
      default: usage(stderr); return 2;
      }
    }
    if (optind < argc) {
      usage(stderr);
      return 2;
    }
  }
  printf("# ball_bench: %s, %d rounds, scale %g\n", o.smoke ? "smoke run" : "benchmark", rounds_of(&o), o.scale);
  bench_eval(&o); /* always: it measures the yardstick */
  if (section(&o, "rally")) bench_rally(&o);
  if (section(&o, "predict")) bench_predict(&o);
  if (section(&o, "walls")) bench_walls(&o);
  if (section(&o, "rackets")) bench_rackets(&o);
  if (section(&o, "effects")) bench_effects(&o);
  if (section(&o, "contact")) bench_contact(&o);
  return 0;
}
