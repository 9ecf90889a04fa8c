/* libFuzzer harness: the sim fed parameter sets, steps, racket samples and
 * queries decoded from bytes (docs/hard-cases.md, "Fuzzing"). Checked on
 * every input:
 *  - nothing crashes, leaks or invokes undefined behaviour (ASan, UBSan);
 *  - a model refused by ball_model_check is refused by ball_sim_init, which
 *    then leaves the sim untouched;
 *  - every refused call (step, set_state, set_model, racket_push) leaves
 *    the sim byte for byte unchanged and reports no event;
 *  - an accepted ball_sim_set_model keeps the ball where it is, as fast;
 *  - every accepted step keeps the physical invariants of invariants.c
 *    (finite, never below the floor, never into the net or a wall, no
 *    energy gain without spin), along the frame's whole path;
 *  - ball_predict gives ball_step's events (exact scheme, no rackets) and its
 *    states within BALL_PREDICT_REL_ERROR (ball.h);
 *  - the segment queries (ball_segment_eval, ball_flight_eval,
 *    ball_time_to_height, ball_time_to_plane, ball_next_floor_contact,
 *    ball_apex) answer what the path does at the time they give;
 *  - ball_swept_disc's first contact touches, nothing earlier does, and a
 *    miss never overlaps the disc (nor crosses it, for a thin ball);
 *  - ball_sphere_rect_distance and ball_sphere_disc_distance agree with the
 *    harness's own distances; copies hash the same; racket estimates are
 *    finite with a unit normal.
 *
 * Input: a header byte, then the model, then operations until the bytes
 * run out. One input in 8 (header % 8 == 0) is "wild": a number's tag byte
 * then picks a small value, a raw 64-bit pattern (NaN, Inf, subnormal,
 * huge) or a special constant, and enums may be out of range; the others
 * decode every number into its plausible range, so that most models pass
 * ball_model_check and the invariants get exercised. An operation's byte b
 * picks b % 8: 0 a step of up to 0.1 s, 1 of up to 10 s, 2 a racket sample
 * (within 1 m of the ball), 3 set_state (b / 8 odd: set_model), 4 a swept
 * query, 5 the queries on the sim's segment, 6 a prediction compared with
 * the steps that follow (b / 8 odd: its last frame cut), 7 up to 16 frames
 * of one dt. Inputs written before the header byte existed keep their
 * meaning behind a header of 0 (corpus/sim). */
#include <float.h>
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ball/ball.h"
#include "ball/vec3.h"
#include "invariants.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

#define EV_CAP (BALL_MAX_CONTACTS + 2)
#define MAX_OPS 200
#define MAX_FRAMES 600 /* frames per input: keeps an input under a few ms */

typedef struct input {
  const uint8_t *p;
  size_t n;
  int wild; /* 1: numbers may be NaN, Inf, huge; enums out of range */
} input;

static unsigned byte(input *in) {
  if (in->n == 0) return 0;
  in->n--;
  return *in->p++;
}

static double special(unsigned k) {
  static const double v[] = {0.0, -0.0, 1.0, -1.0, 0.5, 2.0, 1e-300, 4.9406564584124654e-324,
                             DBL_MIN, DBL_MAX, -DBL_MAX, 1e300, 1e-9, 1e9, NAN, INFINITY};
  return v[k % 16];
}

/* A number: in [lo, hi] (16 bits), or, in a wild input, raw bits or special. */
static double num(input *in, double lo, double hi) {
  unsigned tag = byte(in);
  if (tag < 200 || !in->wild) {
    unsigned u = byte(in) | (byte(in) << 8);
    return lo + (hi - lo) * (double)u / 65535.0;
  }
  if (tag < 230) {
    uint64_t bits = 0;
    double d;
    int i;
    for (i = 0; i < 8; i++) bits = (bits << 8) | byte(in);
    memcpy(&d, &bits, sizeof d);
    return d;
  }
  return special(byte(in));
}

/* An enum value of count values; a wild input may give count (invalid). */
static int pick(input *in, int count) { return (int)(byte(in) % (unsigned)(in->wild ? count + 1 : count)); }

static ball_vec3 vec(input *in, double a) {
  ball_vec3 v;
  v.x = num(in, -a, a);
  v.y = num(in, -a, a);
  v.z = num(in, -a, a);
  return v;
}

static void plane(input *in, ball_plane *p) {
  p->axis = byte(in) & 1 ? 2 : 0;
  p->position = num(in, -30.0, 30.0);
  p->lo = num(in, -30.0, 30.0);
  p->hi = p->lo + num(in, 0.0, 30.0);
  p->bottom = num(in, -2.0, 2.0);
  p->top = p->bottom + num(in, 0.0, 5.0);
  p->damping = num(in, 0.0, 1.0);
}

static void decode_model(input *in, ball_model *m) {
  int i;
  ball_model_default(m);
  m->gravity = num(in, 0.1, 30.0);
  m->mass = num(in, 0.001, 5.0);
  m->air_friction = num(in, 0.0, 2.0);
  m->radius = num(in, 0.0, 0.5);
  m->spin_damping = num(in, 0.01, 10.0);
  m->floor_level = num(in, -5.0, 5.0);
  m->floor_damping = num(in, 0.0, 1.0);
  m->bounce_threshold = num(in, 0.0, 2.0);
  m->sound_threshold = num(in, 0.0, 5.0);
  m->spin_floor_damping = num(in, 0.0, 1.0);
  m->has_net = (int)(byte(in) % 3) == 0 ? 0 : 1;
  plane(in, &m->net);
  m->n_walls = (int)(byte(in) % 6);
  for (i = 0; i < m->n_walls; i++) plane(in, &m->walls[i]);
  m->n_rackets = (int)(byte(in) % (BALL_MAX_RACKETS + 1));
  for (i = 0; i < BALL_MAX_RACKETS; i++) {
    unsigned b;
    m->rackets[i].radius = num(in, 0.0, 0.5);
    b = byte(in);
    /* a plausible partner is another racket in use, or -1 (fly to target) */
    m->rackets[i].partner = in->wild ? (int)(b % (BALL_MAX_RACKETS + 1)) - 1 : (int)(b % (unsigned)(m->n_rackets + 1)) - 1;
    if (!in->wild && m->rackets[i].partner == i) m->rackets[i].partner = -1;
    m->rackets[i].target = vec(in, 30.0);
  }
  m->detect = (ball_detect)pick(in, BALL_DETECT_COUNT);
  m->normal_mode = (ball_normal_mode)(byte(in) % BALL_NORMAL_COUNT);
  m->response = (ball_response)(byte(in) % BALL_RESPONSE_COUNT);
  m->collision_distance = num(in, 0.0, 1.0);
  m->sleep_frames = (int)(byte(in) % 8);
  m->v_min = num(in, 0.0, 20.0);
  m->v_max = m->v_min + num(in, 0.0, 60.0);
  m->v_up = num(in, 0.0, 20.0);
  m->v_up_from_racket = byte(in) & 1;
  m->friendly_factor = num(in, 0.0, 1.5);
  if (!in->wild && m->response == BALL_RESPONSE_MIXED) m->friendly_factor = fmin(m->friendly_factor, 1.0); /* eq 10 */
  m->spin_rack_damping = num(in, 0.0, 1.0);
  m->history = 2 + (int)(byte(in) % (BALL_MAX_HISTORY - 1));
  m->extrapolation_time = num(in, 0.0, 0.5);
  m->stale_time = num(in, 0.01, 5.0);
  m->effects = byte(in) & BALL_EFFECT_ALL;
  m->scheme = (ball_scheme)pick(in, BALL_SCHEME_COUNT);
  m->initial_position = vec(in, 20.0);
  m->initial_position.y = m->floor_level + m->radius + num(in, 0.0, 5.0);
  m->initial_velocity = vec(in, 40.0);
  m->initial_spin = vec(in, 40.0);
}

/* ---- the sim ---- */

typedef struct run {
  input in;
  ball_model m;
  ball_sim sim;
  fz_watch watch;
  int frames; /* stepped so far */
} run;

/* FUZZ_TRACE=1: print the decoded model and every operation (to turn a
 * crashing input into a reproducer). */
static int tracing(void) {
  static int on = -1;
  if (on < 0) on = getenv("FUZZ_TRACE") != NULL;
  return on;
}

static void trace_plane(const char *name, const ball_plane *p) {
  fprintf(stderr, "  %s: axis %d position %.17g lo %.17g hi %.17g bottom %.17g top %.17g damping %.17g\n", name,
          p->axis, p->position, p->lo, p->hi, p->bottom, p->top, p->damping);
}

static void trace_model(const ball_model *m) {
  int i;
  char name[16];
  fprintf(stderr, "model: scheme %s effects 0x%x gravity %.17g mass %.17g air_friction %.17g radius %.17g\n",
          ball_scheme_name(m->scheme), m->effects, m->gravity, m->mass, m->air_friction, m->radius);
  fprintf(stderr, "  floor %.17g damping %.17g bounce_threshold %.17g spin_damping %.17g spin_floor_damping %.17g\n",
          m->floor_level, m->floor_damping, m->bounce_threshold, m->spin_damping, m->spin_floor_damping);
  if (m->has_net) trace_plane("net", &m->net);
  for (i = 0; i < m->n_walls; i++) {
    snprintf(name, sizeof name, "walls[%d]", i);
    trace_plane(name, &m->walls[i]);
  }
  fprintf(stderr, "  rackets %d; start (%.17g, %.17g, %.17g) v (%.17g, %.17g, %.17g) spin (%.17g, %.17g, %.17g)\n",
          m->n_rackets, m->initial_position.x, m->initial_position.y, m->initial_position.z, m->initial_velocity.x,
          m->initial_velocity.y, m->initial_velocity.z, m->initial_spin.x, m->initial_spin.y, m->initial_spin.z);
}

static void check_state(const run *u) {
  ball_state s;
  FZ_CHECK(ball_sim_state(&u->sim, &s) == BALL_OK, "no state");
  FZ_CHECK(fz_finite3(s.position) && fz_finite3(s.velocity) && fz_finite3(s.spin), "a state that is not finite");
}

/* One ball_step of dt with every check; 1 if it was accepted. */
static int step(run *u, double dt, ball_event *ev, int *n) {
  ball_sim copy = u->sim;
  ball_status st;
  u->frames++;
  if (tracing()) {
    ball_state now;
    if (ball_sim_state(&u->sim, &now) == BALL_OK)
      fprintf(stderr, "step %.17g at t = %.17g from (%.17g, %.17g, %.17g) v (%.17g, %.17g, %.17g)\n", dt, u->sim.time,
              now.position.x, now.position.y, now.position.z, now.velocity.x, now.velocity.y, now.velocity.z);
  }
  fz_frame_begin(&u->watch, &u->sim);
  st = ball_step(&u->sim, dt, ev, EV_CAP, n);
  if (st != BALL_OK) {
    FZ_CHECK(*n == 0 && memcmp(&u->sim, &copy, sizeof copy) == 0, "a refused step (%s) changed the sim",
             ball_strerror(st));
    return 0;
  }
  FZ_CHECK(*n >= 0 && *n <= EV_CAP, "%d events", *n);
  if (tracing()) {
    int i;
    for (i = 0; i < *n; i++)
      fprintf(stderr, "  event %d: kind %d index %d t %.17g at (%.17g, %.17g, %.17g) v_out (%.17g, %.17g, %.17g)\n", i,
              (int)ev[i].kind, ev[i].index, ev[i].time, ev[i].point.x, ev[i].point.y, ev[i].point.z,
              ev[i].velocity_out.x, ev[i].velocity_out.y, ev[i].velocity_out.z);
  }
  fz_frame_end(&u->watch, &u->sim, dt, ev, *n);
  return 1;
}

static void op_racket(run *u) {
  ball_racket_sample s;
  ball_sim copy = u->sim;
  ball_state now;
  ball_status st;
  int r = (int)(byte(&u->in) % (BALL_MAX_RACKETS + 1)) - 1;
  s.t = u->sim.time + num(&u->in, -0.2, 0.2);
  s.center = vec(&u->in, 20.0);
  s.normal = vec(&u->in, 1.0);
  /* a plausible racket is near the ball: within 1 m of it */
  if (!u->in.wild && ball_sim_state(&u->sim, &now) == BALL_OK)
    s.center = ball_v3_add(now.position, ball_v3_scale(s.center, 0.05));
  st = ball_racket_push(&u->sim, r, &s);
  if (tracing())
    fprintf(stderr, "racket %d sample t %.17g centre (%.17g, %.17g, %.17g) normal (%.17g, %.17g, %.17g): %s\n", r, s.t,
            s.center.x, s.center.y, s.center.z, s.normal.x, s.normal.y, s.normal.z, ball_strerror(st));
  if (st != BALL_OK) FZ_CHECK(memcmp(&u->sim, &copy, sizeof copy) == 0, "a refused racket push changed the sim");
}

static void op_set_state(run *u) {
  ball_state s;
  ball_sim copy = u->sim;
  ball_status st;
  s.position = vec(&u->in, 20.0);
  s.velocity = vec(&u->in, 40.0);
  s.spin = vec(&u->in, 40.0);
  /* a plausible state is above the floor */
  if (!u->in.wild) s.position.y = u->m.floor_level + u->m.radius + 0.25 * fabs(s.position.y);
  st = ball_sim_set_state(&u->sim, &s);
  if (tracing())
    fprintf(stderr, "set_state (%.17g, %.17g, %.17g) v (%.17g, %.17g, %.17g) spin (%.17g, %.17g, %.17g): %s\n",
            s.position.x, s.position.y, s.position.z, s.velocity.x, s.velocity.y, s.velocity.z, s.spin.x, s.spin.y,
            s.spin.z, ball_strerror(st));
  if (st != BALL_OK) {
    FZ_CHECK(memcmp(&u->sim, &copy, sizeof copy) == 0, "a refused set_state changed the sim");
    return;
  }
  check_state(u);
  fz_watch_start(&u->watch, &u->m, &u->sim);
}

/* A new model for the sim mid-flight (ball_sim_set_model: "keeping the
 * ball, the clock and the racket tracks"): other dynamics, dampings, scheme,
 * a game level. The ball must be where it was, as fast. */
static void op_set_model(run *u) {
  input *in = &u->in;
  static ball_model m2;
  ball_sim copy = u->sim;
  ball_state before, after;
  ball_status st;
  double tol;
  m2 = u->m;
  m2.gravity = num(in, 0.1, 30.0);
  m2.air_friction = num(in, 0.0, 2.0);
  m2.floor_damping = num(in, 0.0, 1.0);
  m2.net.damping = num(in, 0.0, 1.0);
  m2.scheme = (ball_scheme)pick(in, BALL_SCHEME_COUNT);
  m2.effects ^= byte(in) & (BALL_EFFECT_DRAG | BALL_EFFECT_SOUND);
  if (byte(in) & 1) ball_model_set_level(&m2, (ball_level)pick(in, BALL_LEVEL_COUNT));
  if (ball_sim_state(&u->sim, &before) != BALL_OK) return;
  st = ball_sim_set_model(&u->sim, &m2);
  if (tracing()) fprintf(stderr, "set_model gravity %.17g air_friction %.17g: %s\n", m2.gravity, m2.air_friction, ball_strerror(st));
  if (st != BALL_OK) {
    FZ_CHECK(memcmp(&u->sim, &copy, sizeof copy) == 0, "a refused set_model changed the sim");
    return;
  }
  u->m = m2;
  FZ_CHECK(ball_sim_state(&u->sim, &after) == BALL_OK, "no state after set_model");
  tol = 1e-9 + 1e-12 * (fz_max_abs(before.position) + ball_v3_norm(before.velocity));
  FZ_CHECK(ball_v3_dist(before.position, after.position) <= tol && ball_v3_dist(before.velocity, after.velocity) <= tol,
           "ball_sim_set_model moved the ball from (%.17g, %.17g, %.17g) at (%.17g, %.17g, %.17g) m/s to "
           "(%.17g, %.17g, %.17g) at (%.17g, %.17g, %.17g) m/s",
           before.position.x, before.position.y, before.position.z, before.velocity.x, before.velocity.y,
           before.velocity.z, after.position.x, after.position.y, after.position.z, after.velocity.x,
           after.velocity.y, after.velocity.z);
  fz_watch_start(&u->watch, &u->m, &u->sim);
}

/* ---- the swept racket test ---- */

typedef struct disc_motion {
  ball_swept_query q;
  ball_vec3 n0, n1; /* unit, n1 in n0's hemisphere (docs/rackets.md: a disc has two faces) */
} disc_motion;

/* The harness's own sphere-disc distance (face or rim). */
static double disc_distance(ball_vec3 c, ball_vec3 n, double disc_radius, ball_vec3 p, double radius, double *side) {
  ball_vec3 d = ball_v3_sub(p, c);
  double h = ball_v3_dot(d, n), rho = ball_v3_norm(ball_v3_sub(d, ball_v3_scale(n, h)));
  if (side) *side = h;
  if (rho <= disc_radius) return fabs(h) - radius;
  return hypot(rho - disc_radius, h) - radius;
}

/* At s in [0, 1]: the disc moves linearly and turns by normalised lerp. */
static double swept_distance(const disc_motion *d, double s, double *side, double *rho) {
  ball_vec3 p = ball_v3_lerp(d->q.p0, d->q.p1, s), c = ball_v3_lerp(d->q.c0, d->q.c1, s);
  ball_vec3 n = ball_v3_unit(ball_v3_lerp(d->n0, d->n1, s));
  if (rho) {
    ball_vec3 w = ball_v3_sub(p, c);
    *rho = ball_v3_norm(ball_v3_sub(w, ball_v3_scale(n, ball_v3_dot(w, n))));
  }
  return disc_distance(c, n, d->q.disc_radius, p, d->q.ball_radius, side);
}

#define SWEPT_SAMPLES 64

static void op_swept(run *u) {
  input *in = &u->in;
  disc_motion d;
  double toi = -1.0, tol, reach;
  ball_vec3 point;
  int hit = -1, j;
  d.q.p0 = vec(in, 2.0);
  d.q.p1 = ball_v3_add(d.q.p0, vec(in, 2.0));
  d.q.ball_radius = num(in, 0.0, 0.3);
  d.q.c0 = vec(in, 1.0);
  d.q.c1 = ball_v3_add(d.q.c0, vec(in, 1.0));
  d.q.n0 = vec(in, 1.0);
  d.q.n1 = vec(in, 1.0);
  d.q.disc_radius = num(in, 0.0, 0.5);
  if (ball_swept_disc(&d.q, &hit, &toi, &point) != BALL_OK) return;
  FZ_CHECK(hit == 0 || hit == 1, "ball_swept_disc: hit = %d", hit);
  if (u->in.wild) return; /* raw values: the status and finiteness are what is asserted */
  d.n0 = ball_v3_unit(d.q.n0);
  d.n1 = ball_v3_unit(d.q.n1);
  if (ball_v3_dot(d.n0, d.n1) < 0.0) d.n1 = ball_v3_scale(d.n1, -1.0);
  /* toi is exact to 1e-12 (ball.h): the distance moves by at most the
   * speed of the ball plus the disc's fastest point (a turn of at most 90
   * degrees moves the rim 2 radii per unit of s) times that */
  reach = ball_v3_dist(d.q.p0, d.q.p1) + ball_v3_dist(d.q.c0, d.q.c1) + 2.0 * d.q.disc_radius;
  tol = 1e-9 + 1e-12 * (1.0 + fz_max_abs(d.q.p0) + fz_max_abs(d.q.p1) + fz_max_abs(d.q.c0) + fz_max_abs(d.q.c1)) +
        1e-11 * reach;
  if (hit) {
    FZ_CHECK(toi >= 0.0 && toi <= 1.0 && fz_finite3(point), "ball_swept_disc: toi %.17g", toi);
    FZ_CHECK(ball_v3_dist(point, ball_v3_lerp(d.q.p0, d.q.p1, toi)) <= tol, "ball_swept_disc: the point is off the path");
    FZ_CHECK(swept_distance(&d, toi, NULL, NULL) <= tol, "ball_swept_disc: at toi %.17g the ball is %.17g from the disc",
             toi, swept_distance(&d, toi, NULL, NULL));
    for (j = 0; j < SWEPT_SAMPLES && toi > 0.0; j++) {
      double s = toi * j / SWEPT_SAMPLES;
      FZ_CHECK(swept_distance(&d, s, NULL, NULL) >= -tol, "ball_swept_disc: an earlier contact at s = %.17g (toi %.17g)",
               s, toi);
    }
    return;
  }
  for (j = 0; j <= SWEPT_SAMPLES; j++) {
    double s = (double)j / SWEPT_SAMPLES, s1 = (double)(j + 1) / SWEPT_SAMPLES, h0, h1, rho;
    FZ_CHECK(swept_distance(&d, s, &h0, NULL) >= -tol, "ball_swept_disc: a miss, but the ball overlaps the disc at s = %.17g (%.17g)",
             s, swept_distance(&d, s, NULL, NULL));
    if (j == SWEPT_SAMPLES) break;
    swept_distance(&d, s1, &h1, NULL);
    /* a thin ball through the face: the centre crosses the disc's plane
     * inside its radius; the crossing found by bisection on the side */
    if ((h0 > tol && h1 < -tol) || (h0 < -tol && h1 > tol)) {
      double a = s, b = s1, ha = h0;
      int i;
      for (i = 0; i < 60; i++) {
        double mid = 0.5 * (a + b), hm;
        swept_distance(&d, mid, &hm, NULL);
        if ((hm > 0.0) == (ha > 0.0)) {
          a = mid;
          ha = hm;
        } else {
          b = mid;
        }
      }
      swept_distance(&d, 0.5 * (a + b), NULL, &rho);
      FZ_CHECK(!(rho < d.q.disc_radius - tol), "ball_swept_disc: a miss, but the centre crosses the disc at s = %.17g",
               0.5 * (a + b));
    }
  }
}

/* ---- the segment queries on the sim's segment ---- */

static void op_queries(run *u) {
  input *in = &u->in;
  const ball_model *m = &u->m;
  const ball_segment *seg = &u->sim.seg;
  double t_from = u->sim.time, t, dt = num(in, 0.0, 10.0), y, coord, big, tol;
  double fy = m->floor_level + m->radius;
  int axis = byte(in) & 1 ? 2 : 0, k;
  ball_state now, a, b;
  ball_flight fl;
  ball_vec3 point, disc_c, disc_n;
  double disc_r, dist;
  ball_status st;
  y = num(in, -5.0, 5.0);
  coord = num(in, -5.0, 5.0);
  disc_c = vec(in, 1.0);
  disc_n = vec(in, 1.0);
  disc_r = num(in, 0.0, 0.5);
  if (ball_sim_state(&u->sim, &now) != BALL_OK) return;
  t = t_from + dt;
  /* eval and flight: the same, to the bit (ball.h) */
  st = ball_segment_eval(m, seg, t, &a);
  if (st == BALL_OK) {
    FZ_CHECK(ball_flight_init(m, seg, &fl) == BALL_OK && ball_flight_eval(&fl, t, &b) == BALL_OK,
             "ball_flight_* refused what ball_segment_eval took");
    FZ_CHECK(memcmp(&a, &b, sizeof a) == 0, "ball_flight_eval differs from ball_segment_eval at t = %.17g", t);
    if (!in->wild) FZ_CHECK(fz_finite3(a.position) && fz_finite3(a.velocity), "ball_segment_eval: not finite");
  }
  if (in->wild) return;
  /* the scale of a position on this segment within 10 s: what its rounding is relative to */
  big = 1.0 + fz_max_abs(seg->p0) + fz_max_abs(now.position) + ball_v3_norm(seg->v0) * (t - seg->t0) +
        m->gravity * (t - seg->t0) * (t - seg->t0) + fabs(fy);
  tol = 1e-9 + 1e-12 * big;
  /* time to a height: the ball is there then */
  y += now.position.y;
  st = ball_time_to_height(m, seg, t_from, y, &t);
  if (st == BALL_OK) {
    FZ_CHECK(t >= t_from && ball_segment_eval(m, seg, t, &a) == BALL_OK, "ball_time_to_height: t %.17g", t);
    big = fmax(big, 1.0 + ball_v3_norm(seg->v0) * (t - seg->t0) + m->gravity * (t - seg->t0) * (t - seg->t0));
    FZ_CHECK(fabs(a.position.y - y) <= 1e-9 + 1e-12 * big + 8.0 * fabs(a.velocity.y) * fz_ulp(t),
             "ball_time_to_height(%.17g) gives t = %.17g where y = %.17g", y, t, a.position.y);
  } else {
    ball_vec3 apex;
    double t_apex;
    FZ_CHECK(st == BALL_ENOTFOUND, "ball_time_to_height: %s", ball_strerror(st));
    FZ_CHECK(ball_apex(m, seg, &t_apex, &apex) == BALL_OK, "ball_apex refused a segment");
    /* never there: above the apex, or below and falling (or sliding at another height) */
    FZ_CHECK(seg->grounded || apex.y < y + tol || (now.position.y < y + tol && now.velocity.y <= 0.0),
             "ball_time_to_height(%.17g): not found, yet the apex is at %.17g and the ball at %.17g", y, apex.y,
             now.position.y);
  }
  /* time to a plane */
  coord += ball_v3_axis(now.position, axis);
  st = ball_time_to_plane(m, seg, t_from, axis, coord, &t);
  if (st == BALL_OK) {
    FZ_CHECK(t >= t_from && ball_segment_eval(m, seg, t, &a) == BALL_OK, "ball_time_to_plane: t %.17g", t);
    FZ_CHECK(fabs(ball_v3_axis(a.position, axis) - coord) <= tol + 8.0 * ball_v3_norm(a.velocity) * fz_ulp(t),
             "ball_time_to_plane(%d, %.17g) gives t = %.17g where the centre is at %.17g", axis, coord, t,
             ball_v3_axis(a.position, axis));
  } else {
    double v = ball_v3_axis(now.velocity, axis), gap = coord - ball_v3_axis(now.position, axis);
    double bdrag = (m->effects & BALL_EFFECT_DRAG) && m->air_friction > 0.0 ? m->mass / m->air_friction : INFINITY;
    FZ_CHECK(st == BALL_ENOTFOUND, "ball_time_to_plane: %s", ball_strerror(st));
    /* never there: still, moving away, so slow that the time overflows, or
     * drag stops it short (eq 3: it goes v b at most) */
    FZ_CHECK(v == 0.0 || gap * v < 0.0 || !isfinite(gap / v) || fabs(gap) >= fabs(v) * bdrag * (1.0 - 1e-12) - tol,
             "ball_time_to_plane(%d, %.17g): not found, yet the ball is %.17g away at %.17g m/s", axis, coord, gap, v);
  }
  /* the next floor contact */
  st = ball_next_floor_contact(m, seg, t_from, &t, &point);
  if (st == BALL_OK) {
    FZ_CHECK(t >= t_from - 4.0 * fz_ulp(t_from) && ball_segment_eval(m, seg, t, &a) == BALL_OK,
             "ball_next_floor_contact: t %.17g before %.17g", t, t_from);
    FZ_CHECK(point.y == fy && point.x == a.position.x && point.z == a.position.z,
             "ball_next_floor_contact: the point is not the ball on the floor");
    big = fmax(big, 1.0 + ball_v3_norm(seg->v0) * (t - seg->t0) + m->gravity * (t - seg->t0) * (t - seg->t0));
    FZ_CHECK(fabs(a.position.y - fy) <= 1e-9 + 1e-12 * big + 8.0 * fabs(a.velocity.y) * fz_ulp(t),
             "ball_next_floor_contact: at t = %.17g the ball is at y = %.17g, the floor at %.17g", t, a.position.y, fy);
  } else {
    FZ_CHECK(st == BALL_ENOTFOUND, "ball_next_floor_contact: %s", ball_strerror(st));
    /* gravity brings every flying ball down to a floor it is above */
    FZ_CHECK(seg->grounded || now.position.y < fy, "ball_next_floor_contact: not found for a ball in flight above it");
  }
  /* the apex */
  FZ_CHECK(ball_apex(m, seg, &t, &point) == BALL_OK && t >= seg->t0, "ball_apex");
  FZ_CHECK(ball_segment_eval(m, seg, t, &a) == BALL_OK && memcmp(&a.position, &point, sizeof point) == 0,
           "ball_apex: the point is not the ball then");
  if (!seg->grounded && seg->v0.y > 0.0)
    FZ_CHECK(fabs(a.velocity.y) <= 1e-12 * seg->v0.y + 4.0 * m->gravity * fz_ulp(t),
             "ball_apex: vertical speed %.17g at the apex", a.velocity.y);
  /* the hashes: a copy hashes the same */
  {
    static ball_sim copy;
    static ball_model mcopy;
    copy = u->sim;
    mcopy = u->m;
    FZ_CHECK(ball_sim_hash(&copy) == ball_sim_hash(&u->sim) && ball_model_hash(&mcopy) == ball_model_hash(m),
             "a copy hashes differently");
  }
  /* the rackets' estimates: finite, a unit normal */
  for (k = 0; k < m->n_rackets && (m->effects & BALL_EFFECT_RACKETS); k++) {
    ball_racket_pose pose;
    if (ball_racket_estimate(&u->sim, k, t_from, &pose) == BALL_OK)
      FZ_CHECK(fz_finite3(pose.center) && fz_finite3(pose.velocity) && fabs(ball_v3_norm(pose.normal) - 1.0) <= 1e-9,
               "ball_racket_estimate: racket %d's pose is not finite or its normal not unit", k);
  }
  /* static distances against the harness's own */
  for (k = 0; k < FZ_OBSTACLES; k++) {
    const ball_plane *p = fz_obstacle(m, k);
    double mine;
    if (!p) continue;
    FZ_CHECK(ball_sphere_rect_distance(p, now.position, m->radius, &dist) == BALL_OK, "ball_sphere_rect_distance refused");
    mine = fz_rect_distance(p, now.position) - m->radius;
    FZ_CHECK(fabs(dist - mine) <= 1e-12 * (1.0 + fabs(mine) + m->radius + fz_max_abs(now.position)),
             "ball_sphere_rect_distance %.17g, the harness's %.17g", dist, mine);
  }
  disc_c = ball_v3_add(disc_c, now.position);
  st = ball_sphere_disc_distance(disc_c, disc_n, disc_r, now.position, m->radius, &dist);
  if (st == BALL_OK) {
    double mine = disc_distance(disc_c, ball_v3_unit(disc_n), disc_r, now.position, m->radius, NULL);
    FZ_CHECK(fabs(dist - mine) <= 1e-9 * (1.0 + fabs(mine) + m->radius + disc_r),
             "ball_sphere_disc_distance %.17g, the harness's %.17g", dist, mine);
  }
}

/* ---- prediction against the stepper ---- */

#define PREDICT_MAX_FRAMES 16

/* |a - b| <= BALL_PREDICT_REL_ERROR scale, or equal to the bit (a zero or
 * an infinite scale). */
static int predict_axis_near(double a, double b, double scale) {
  return memcmp(&a, &b, sizeof a) == 0 || fabs(a - b) <= BALL_PREDICT_REL_ERROR * scale;
}

/* ball.h's bound on a state of ball_predict against ball_step's at t, seg
 * being ball_step's segment then: height, vertical speed and spin to the
 * bit, x and z within the bound. */
static int predict_near(const ball_state *p, const ball_state *s, const ball_segment *seg, double t) {
  double tau = t - seg->t0;
  return memcmp(&p->position.y, &s->position.y, sizeof p->position.y) == 0 &&
         memcmp(&p->velocity.y, &s->velocity.y, sizeof p->velocity.y) == 0 &&
         memcmp(&p->spin, &s->spin, sizeof p->spin) == 0 &&
         predict_axis_near(p->position.x, s->position.x, fabs(seg->p0.x) + fabs(seg->v0.x) * tau) &&
         predict_axis_near(p->position.z, s->position.z, fabs(seg->p0.z) + fabs(seg->v0.z) * tau) &&
         predict_axis_near(p->velocity.x, s->velocity.x, fabs(seg->v0.x)) &&
         predict_axis_near(p->velocity.z, s->velocity.z, fabs(seg->v0.z));
}

/* cut: t_end half a frame before the k-th frame's end (a last frame that is
 * cut gives no state) */
static void op_predict(run *u, int cut) {
  input *in = &u->in;
  int k = 1 + (int)(byte(in) % PREDICT_MAX_FRAMES), i, j, n, n_ev = 0, compare, grid;
  double dt = num(in, 1e-3, 0.25), t_end = u->sim.time;
  ball_state states[PREDICT_MAX_FRAMES + 1];
  ball_event pev[EV_CAP], ev[EV_CAP];
  ball_prediction pr;
  ball_status st;
  unsigned long limit = u->sim.warnings[BALL_WARN_CONTACT_LIMIT];
  for (i = 0; i < k; i++) t_end += dt; /* the clock as ball_step sums it */
  if (cut) t_end -= 0.5 * dt;
  grid = cut ? k : k + 1; /* the states ball_predict gives */
  memset(&pr, 0, sizeof pr);
  pr.states = states;
  pr.cap_states = k + 1;
  pr.events = pev;
  pr.cap_events = EV_CAP;
  st = ball_predict(&u->m, &u->sim.seg, u->sim.time, t_end, dt, &pr);
  if (st != BALL_OK) return;
  FZ_CHECK(pr.n_states >= 1 && pr.n_states <= k + 1 && pr.n_events >= 0 && pr.n_events <= EV_CAP,
           "ball_predict: %d states, %d events", pr.n_states, pr.n_events);
  for (i = 0; i < pr.n_states; i++)
    FZ_CHECK(fz_finite3(states[i].position) && fz_finite3(states[i].velocity), "ball_predict: state %d not finite", i);
  /* "the states and events that ball_step gives at frames of dt in the
   * exact scheme" (ball.h): with static obstacles only */
  compare = u->m.scheme == BALL_SCHEME_EXACT && !((u->m.effects & BALL_EFFECT_RACKETS) && u->m.n_rackets > 0) &&
            pr.n_states == grid && pr.events_missed == 0;
  for (i = 0; i + 1 < grid && u->frames < MAX_FRAMES; i++) {
    ball_state s;
    if (!step(u, dt, ev, &n)) return;
    if (!compare) continue;
    FZ_CHECK(ball_sim_state(&u->sim, &s) == BALL_OK, "no state");
    if (u->sim.warnings[BALL_WARN_CONTACT_LIMIT] != limit) return; /* the limit: where it stops depends on the frame */
    FZ_CHECK(predict_near(&states[i + 1], &s, &u->sim.seg, u->sim.time),
             "ball_predict off ball_step's state beyond BALL_PREDICT_REL_ERROR after frame %d of %.17g s: "
             "(%.17g, %.17g, %.17g) vs (%.17g, %.17g, %.17g)",
             i + 1, dt, states[i + 1].position.x, states[i + 1].position.y, states[i + 1].position.z, s.position.x,
             s.position.y, s.position.z);
    for (j = 0; j < n; j++, n_ev++)
      FZ_CHECK(n_ev < pr.n_events && pev[n_ev].kind == ev[j].kind && pev[n_ev].index == ev[j].index &&
                   pev[n_ev].time == ev[j].time,
               "ball_predict's event %d differs from ball_step's", n_ev);
  }
  if (compare && i == k && !cut) FZ_CHECK(n_ev == pr.n_events, "ball_predict: %d events, ball_step %d", pr.n_events, n_ev);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  static run u; /* about 16 kB: off the stack */
  ball_sim copy;
  ball_event ev[EV_CAP];
  int ops, n;
  u.in.p = data;
  u.in.n = size;
  u.in.wild = byte(&u.in) % 8 == 0;
  u.frames = 0;
  decode_model(&u.in, &u.m);
  if (tracing()) trace_model(&u.m);
  memset(&u.sim, 0xA5, sizeof u.sim);
  copy = u.sim;
  if (ball_model_check(&u.m, NULL) != BALL_OK) {
    FZ_CHECK(ball_sim_init(&u.sim, &u.m) != BALL_OK, "ball_sim_init took a model ball_model_check refused");
    FZ_CHECK(memcmp(&u.sim, &copy, sizeof u.sim) == 0, "a refused ball_sim_init changed the sim");
    return 0;
  }
  FZ_CHECK(ball_sim_init(&u.sim, &u.m) == BALL_OK, "ball_sim_init refused a checked model");
  check_state(&u);
  fz_watch_start(&u.watch, &u.m, &u.sim);
  for (ops = 0; ops < MAX_OPS && u.in.n > 0 && u.frames < MAX_FRAMES; ops++) {
    unsigned b = byte(&u.in), op = b % 8, variant = b / 8 % 2; /* old inputs: ops 0 to 3, variant 0 */
    int i, k;
    double dt;
    switch (op) {
    case 0:
    case 1:
      dt = op == 0 ? num(&u.in, 0.0, 0.1) : num(&u.in, 0.0, 10.0);
      step(&u, dt, ev, &n);
      break;
    case 2: op_racket(&u); break;
    case 3:
      if (variant)
        op_set_model(&u);
      else
        op_set_state(&u);
      break;
    case 4: op_swept(&u); break;
    case 5: op_queries(&u); break;
    case 6: op_predict(&u, (int)variant); break;
    default:
      /* a run of frames: the common case of a game loop */
      k = 1 + (int)(byte(&u.in) % 16);
      dt = num(&u.in, 1e-3, 1.0);
      for (i = 0; i < k && u.frames < MAX_FRAMES; i++)
        if (!step(&u, dt, ev, &n)) break;
      break;
    }
  }
  return 0;
}
