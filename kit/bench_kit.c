/* The measuring pieces of ball_bench, shared with the accuracy report
 * (bench_kit.h says what each is). */
#define _POSIX_C_SOURCE 199309L

#include "bench_kit.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "ball/vec3.h"

#define SAMPLE_CAP 64
#define ARRIVAL_SLACK 1e-9 /* s; as ballsim */

volatile double bench_sink;

double bench_now(void) {
  struct timespec ts;
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int cmp_double(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return x < y ? -1 : x > y;
}

bench_stat bench_stats(double *v, int n) {
  bench_stat s;
  qsort(v, (size_t)n, sizeof *v, cmp_double);
  s.min = v[0];
  s.median = n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
  return s;
}

double bench_timer_overhead(void) {
  double best = INFINITY;
  int i;
  for (i = 0; i < 1000; i++) {
    double a = bench_now(), b = bench_now();
    if (b - a < best) best = b - a;
  }
  return 1e9 * best;
}

/* ---- eval ---- */

/* The lean evaluation (the yardstick): 1/b and b worked out beforehand, one expm1,
 * no argument checks: what an evaluation costs at the least (eq 3, 4). */
__attribute__((noinline)) static void lean_eval(const ball_segment *seg, double k, double b, double g, double sd,
                                                double t, ball_state *out) {
  double tau = t - seg->t0, e = expm1(-tau * k), d = -b * e, f = 1.0 + e, a = sd / (sd + tau);
  out->position = ball_v3(seg->p0.x + seg->v0.x * d, seg->p0.y + seg->v0.y * tau - 0.5 * g * tau * tau,
                          seg->p0.z + seg->v0.z * d);
  out->velocity = ball_v3(seg->v0.x * f, seg->v0.y - g * tau, seg->v0.z * f);
  out->spin = ball_v3_scale(seg->s0, a);
}

/* One round of n expm1 calls, ns each: the floor of an evaluation, and the
 * unit docs/benchmarks.md's targets are stated in. */
static double time_expm1(long n, double *acc) {
  double t0 = bench_now();
  long i;
  for (i = 0; i < n; i++) *acc += expm1(-(double)(i & 1023) * 0.002 * 0.35);
  return 1e9 * (bench_now() - t0) / (double)n;
}

void bench_eval_run(int rounds, long n, bench_eval_result *out) {
  ball_model m;
  ball_segment seg;
  ball_state s;
  double t_eval[BENCH_MAX_ROUNDS], t_exp[BENCH_MAX_ROUNDS], t_lean[BENCH_MAX_ROUNDS], t_fl[BENCH_MAX_ROUNDS];
  double acc = 0.0, k, bb;
  ball_flight fl;
  long i;
  int r;
  ball_model_default(&m); /* drag and spin on */
  seg.t0 = 0.0;
  seg.p0 = ball_v3(0.0, 1.0, 0.0);
  seg.v0 = ball_v3(20.0, 3.0, 1.0);
  seg.s0 = ball_v3(1.0, 2.0, 3.0);
  seg.grounded = 0;
  k = m.air_friction / m.mass;
  bb = m.mass / m.air_friction;
  ball_flight_init(&m, &seg, &fl);
  for (r = 0; r < rounds; r++) {
    double t0 = bench_now(), t1, t2, t3, t4;
    for (i = 0; i < n; i++) {
      ball_segment_eval(&m, &seg, (double)(i & 1023) * 0.002, &s);
      acc += s.position.x;
    }
    t1 = bench_now();
    for (i = 0; i < n; i++) {
      lean_eval(&seg, k, bb, m.gravity, m.spin_damping, (double)(i & 1023) * 0.002, &s);
      acc += s.position.x;
    }
    t2 = bench_now();
    t_exp[r] = time_expm1(n, &acc);
    t3 = bench_now();
    for (i = 0; i < n; i++) {
      ball_flight_eval(&fl, (double)(i & 1023) * 0.002, &s);
      acc += s.position.x;
    }
    t4 = bench_now();
    t_fl[r] = 1e9 * (t4 - t3) / (double)n;
    t_eval[r] = 1e9 * (t1 - t0) / (double)n;
    t_lean[r] = 1e9 * (t2 - t1) / (double)n;
  }
  bench_sink = acc;
  out->segment_eval = bench_stats(t_eval, rounds);
  out->expm1 = bench_stats(t_exp, rounds);
  out->lean = bench_stats(t_lean, rounds);
  out->flight_eval = bench_stats(t_fl, rounds);
}

/* ---- a scene run with its racket samples, recorded ahead ---- */

static int run_record(bench_run *rn) {
  static ball_script_player player;
  ball_script_sample buf[SAMPLE_CAP];
  long k, cap = 1024;
  double t = 0.0;
  rn->dt = rn->scene.frame_time * rn->scene.time_base;
  rn->frames = (long)ceil(rn->scene.duration / rn->dt * (1.0 - 1e-12));
  rn->per_frame = (bench_frame_samples *)calloc((size_t)rn->frames, sizeof *rn->per_frame);
  rn->samples = (ball_script_sample *)malloc((size_t)cap * sizeof *rn->samples);
  rn->n_samples = 0;
  if (!rn->per_frame || !rn->samples) return 0;
  if (ball_script_player_init(&player, rn->scene.scripts, rn->scene.model.n_rackets) != BALL_OK) return 0;
  for (k = 0; k < rn->frames; k++) {
    int n, i;
    rn->per_frame[k].first = (int)rn->n_samples;
    do {
      if (ball_script_poll(&player, t + rn->dt + ARRIVAL_SLACK, buf, SAMPLE_CAP, &n) != BALL_OK) return 0;
      for (i = 0; i < n; i++) {
        if (rn->n_samples == cap) {
          ball_script_sample *more;
          cap *= 2;
          more = (ball_script_sample *)realloc(rn->samples, (size_t)cap * sizeof *more);
          if (!more) return 0;
          rn->samples = more;
        }
        rn->samples[rn->n_samples++] = buf[i];
      }
    } while (n == SAMPLE_CAP);
    rn->per_frame[k].count = (int)rn->n_samples - rn->per_frame[k].first;
    t += rn->dt;
  }
  return 1;
}

int bench_run_prepare(bench_run *rn, const char *path) {
  ball_scene_error err;
  rn->per_frame = NULL;
  rn->samples = NULL;
  if (ball_scene_load_file(path, &rn->scene, &err) != BALL_OK) {
    char text[600];
    ball_scene_error_format(&err, text, sizeof text);
    fprintf(stderr, "%s\n", text);
    return 0;
  }
  if (!run_record(rn)) {
    fprintf(stderr, "%s: cannot record the racket samples\n", path);
    bench_run_free(rn);
    return 0;
  }
  return 1;
}

void bench_run_free(bench_run *rn) {
  free(rn->per_frame);
  free(rn->samples);
  rn->per_frame = NULL;
  rn->samples = NULL;
}

int bench_frame(ball_sim *sim, const bench_run *rn, long k, int *events) {
  ball_event ev[BALL_MAX_CONTACTS + BALL_MAX_RACKETS];
  const ball_script_sample *s = rn->samples + rn->per_frame[k].first;
  int i, n;
  for (i = 0; i < rn->per_frame[k].count; i++) ball_racket_push(sim, s[i].racket, &s[i].sample);
  if (ball_step(sim, rn->dt, ev, BALL_MAX_CONTACTS + BALL_MAX_RACKETS, &n) != BALL_OK) return 0;
  for (i = 0; i < n; i++) events[ev[i].kind]++;
  return 1;
}

int bench_rally_run(const bench_run *rn, ball_detect detect, int rounds, long passes, int single_passes,
                    bench_rally_result *out) {
  ball_model m = rn->scene.model;
  ball_sim sim;
  double mean[BENCH_MAX_ROUNDS], overhead = bench_timer_overhead(), *per;
  int events[BALL_EVENT_KIND_COUNT], r;
  long k, p;
  per = (double *)malloc((size_t)rn->frames * sizeof *per);
  if (!per) return 0;
  m.detect = detect;
  for (r = 0; r < rounds; r++) {
    double t0, t1;
    t0 = bench_now();
    for (p = 0; p < passes; p++) {
      ball_sim_init(&sim, &m);
      for (k = 0; k < rn->frames; k++)
        if (!bench_frame(&sim, rn, k, events)) {
          free(per);
          return 0;
        }
    }
    t1 = bench_now();
    mean[r] = 1e9 * (t1 - t0) / (double)(passes * rn->frames);
  }
  /* single frames, timed one by one: the median and the worst, over
   * several passes (the worst of each frame's best run) */
  for (k = 0; k < rn->frames; k++) per[k] = INFINITY;
  for (p = 0; p < single_passes; p++) {
    ball_sim_init(&sim, &m);
    for (k = 0; k < rn->frames; k++) {
      double t0 = bench_now(), t1;
      bench_frame(&sim, rn, k, events);
      t1 = bench_now();
      if (1e9 * (t1 - t0) - overhead < per[k]) per[k] = 1e9 * (t1 - t0) - overhead;
    }
  }
  memset(events, 0, sizeof events);
  ball_sim_init(&sim, &m);
  for (k = 0; k < rn->frames; k++) bench_frame(&sim, rn, k, events);
  out->worst = 0.0;
  for (k = 0; k < rn->frames; k++) out->worst = per[k] > out->worst ? per[k] : out->worst;
  out->frame_median = bench_stats(per, (int)rn->frames).median;
  out->mean = bench_stats(mean, rounds);
  out->hits = events[BALL_EVENT_RACKET];
  out->frames = rn->frames;
  free(per);
  return 1;
}

/* ---- predict ---- */

void bench_predict_run(int rounds, long n, bench_predict_result *out) {
  static ball_state states[721];
  ball_event events[256];
  ball_model m;
  ball_sim sim;
  ball_segment seg;
  ball_prediction pr;
  double t_pred[BENCH_MAX_ROUNDS], t_step[BENCH_MAX_ROUNDS], t_exp[BENCH_MAX_ROUNDS];
  double acc = 0.0;
  long i;
  int r, k;
  ball_model_default(&m); /* the tennis serve: the net, then bounces */
  m.effects |= BALL_EFFECT_WALLS;
  {
    ball_plane back = {0, 25.0, -5.0, 15.0, 0.0, 4.0, 0.8};
    ball_model_add_wall(&m, &back);
  }
  m.initial_velocity = ball_v3(20.0, 4.0, 1.0);
  ball_sim_init(&sim, &m);
  seg = sim.seg;
  pr.states = states;
  pr.cap_states = 721;
  pr.events = events;
  pr.cap_events = 256;
  for (r = 0; r < rounds; r++) {
    double t0 = bench_now(), t1, t2;
    for (i = 0; i < n; i++) ball_predict(&m, &seg, 0.0, 6.0, 1.0 / 120.0, &pr);
    t1 = bench_now();
    for (i = 0; i < n; i++) {
      ball_sim_init(&sim, &m);
      for (k = 0; k < 720; k++) ball_step(&sim, 1.0 / 120.0, events, 256, NULL);
    }
    t2 = bench_now();
    t_pred[r] = 1e6 * (t1 - t0) / (double)n;
    t_step[r] = 1e6 * (t2 - t1) / (double)n;
    t_exp[r] = time_expm1(n * 720, &acc);
  }
  bench_sink = states[720].position.x + sim.time + acc;
  out->expm1 = bench_stats(t_exp, rounds);
  out->predict = bench_stats(t_pred, rounds);
  out->steps = bench_stats(t_step, rounds);
  out->contacts = pr.n_events;
}

/* ---- frames of a scene without rackets ---- */

void bench_full_scene(ball_model *m) {
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
  ball_model_add_wall(m, &back);
  ball_model_add_wall(m, &side);
  m->initial_position = ball_v3(3.0, 1.5, 2.0);
  m->initial_velocity = ball_v3(12.0, 3.0, -0.5);
  m->initial_spin = ball_v3(0.5, 0.0, 2.0);
}

void bench_without(ball_model *m, ball_effect effect) {
  switch (effect) {
    case BALL_EFFECT_DRAG: m->air_friction = 0.0; break;
    case BALL_EFFECT_SPIN: m->initial_spin = ball_v3(0.0, 0.0, 0.0); break;
    case BALL_EFFECT_FLOOR: m->floor_level = -BALL_MAX_COORD; break;
    case BALL_EFFECT_NET: m->has_net = 0; break;
    case BALL_EFFECT_WALLS: m->n_walls = 0; break;
    case BALL_EFFECT_RACKETS: m->n_rackets = 0; break;
    case BALL_EFFECT_SOUND: m->sound_threshold = INFINITY; break;
    default: break;
  }
}

double bench_time_frames(const ball_model *m, long passes, long frames, double dt) {
  ball_sim sim;
  ball_event ev[BALL_MAX_CONTACTS];
  double t0 = bench_now();
  long p, k;
  for (p = 0; p < passes; p++) {
    ball_sim_init(&sim, m);
    for (k = 0; k < frames; k++) ball_step(&sim, dt, ev, BALL_MAX_CONTACTS, NULL);
  }
  bench_sink = sim.time;
  return 1e9 * (bench_now() - t0) / (double)(passes * frames);
}
