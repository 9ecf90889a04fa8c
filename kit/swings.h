/* Seeded racket swings for the detection studies: the one of docs/rackets.md
 * (tests/unit/test_racket_detection.c) and the one of docs/accuracy.md
 * (validation/accuracy_rackets.cpp). A tennis ball meets a disc racket that
 * swings, accelerates and turns; the racket is sampled at a rate (one sample a
 * frame); the ground truth is the same motions the sim sees (the ball on its
 * analytic flight, the racket linear between its samples with a
 * normalised-lerp normal) sampled every SWING_GT_STEP seconds. Public API
 * only; header only, C99 and C++. */
#ifndef BALL_KIT_SWINGS_H
#define BALL_KIT_SWINGS_H

#include <math.h>
#include <string.h>

#include "ball/ball.h"
#include "ball/vec3.h"
#include "seeded.h"

#define SWING_GT_STEP 2e-5       /* s: at <= 60 m/s relative speed, 1.2 mm */
#define SWING_GT_RESOLUTION 1e-4 /* m: a graze shallower than this may slip between GT samples */
#define SWING_RUN_TIME 1.2       /* s per swing */
#define SWING_MAX_SAMPLES 160    /* one a frame over SWING_RUN_TIME at 120 Hz, and some */
#define SWING_BALL_R 0.033       /* m: a tennis ball */
#define SWING_DISC_R 0.15        /* m: r_disc */

typedef struct swing {
  ball_segment seg;                        /* the ball, from t = 0 */
  int n;                                   /* racket samples, one per frame from t = 0 */
  ball_racket_sample s[SWING_MAX_SAMPLES];
} swing;

static inline ball_vec3 swing_rnd3(seeded_rng *r, double lo, double hi) {
  double x = seeded_uniform(r, lo, hi), y = seeded_uniform(r, lo, hi);
  return ball_v3(x, y, seeded_uniform(r, lo, hi));
}

/* The study's model: a tennis ball in free space (b = m / beta = 2 s), one
 * racket of radius SWING_DISC_R, the physical response, the given test with
 * the real normal, d_COLL = r_disc + ball radius. */
static inline void swing_model(ball_model *m, ball_detect detect) {
  ball_model_default(m);
  m->mass = 0.05;
  m->air_friction = 0.025; /* b = 2 s */
  m->has_net = 0;
  m->n_walls = 0;
  m->scheme = BALL_SCHEME_EXACT;
  m->initial_position = ball_v3(0.0, 1.0, 0.0);
  m->initial_velocity = ball_v3(0.0, 0.0, 0.0);
  m->initial_spin = ball_v3(0.0, 0.0, 0.0);
  m->effects = BALL_EFFECT_DRAG | BALL_EFFECT_RACKETS;
  m->radius = SWING_BALL_R;
  m->n_rackets = 1;
  m->rackets[0].radius = SWING_DISC_R;
  m->detect = detect;
  m->normal_mode = BALL_NORMAL_REAL;
  m->collision_distance = SWING_DISC_R + SWING_BALL_R;
  m->response = BALL_RESPONSE_PHYSICAL;
  m->history = 3;
  m->extrapolation_time = 0.0;
  m->stale_time = 10.0;
}

/* A swing sampled every dt: the ball passes the point X at time tc with
 * velocity vb (10-30 m/s); the racket passes X + offset at tc + delay with
 * velocity vr (5-30 m/s), accelerating (up to 30 m/s^2), its normal turning
 * (up to 6 rad/s). One swing in five is a racket overtaking a slow ball from
 * behind. The same rng state gives the same motion at every dt. */
static inline void swing_make(const ball_model *m, seeded_rng *r, double dt, swing *sw) {
  const double b = m->mass / m->air_friction, g = m->gravity;
  double tc = seeded_uniform(r, 0.5, 0.8), delay = seeded_uniform(r, -0.03, 0.03);
  int overtake = seeded_uniform(r, 0, 1) < 0.2, k;
  ball_vec3 x = ball_v3(0, 1, 0), vb, v0, vr, acc, offset, n_c, spin;
  if (overtake) {
    vb = ball_v3(seeded_uniform(r, 1, 5), seeded_uniform(r, -2, 2), seeded_uniform(r, -1, 1));
    vr = ball_v3(seeded_uniform(r, 10, 30), seeded_uniform(r, -3, 3), seeded_uniform(r, -3, 3));
  } else {
    vb = ball_v3(-seeded_uniform(r, 10, 30), seeded_uniform(r, -3, 3), seeded_uniform(r, -2, 2));
    vr = ball_v3(seeded_uniform(r, 5, 30), seeded_uniform(r, -5, 5), seeded_uniform(r, -5, 5));
  }
  acc = swing_rnd3(r, -30, 30);
  offset = swing_rnd3(r, -0.25, 0.25);
  n_c = ball_v3_unit(ball_v3_add(ball_v3(1, 0, 0), swing_rnd3(r, -0.5, 0.5)));
  spin = swing_rnd3(r, -6, 6); /* how fast the normal turns, 1/s */
  /* the ball's segment from t = 0 that has velocity vb at X at time tc (eq 3) */
  v0 = ball_v3(vb.x * exp(tc / b), vb.y + g * tc, vb.z * exp(tc / b));
  {
    double d = -b * expm1(-tc / b);
    memset(&sw->seg, 0, sizeof sw->seg);
    sw->seg.p0 = ball_v3(x.x - v0.x * d, x.y - (v0.y * tc - 0.5 * g * tc * tc), x.z - v0.z * d);
    sw->seg.v0 = v0;
  }
  sw->n = 0;
  for (k = 0; k * dt <= SWING_RUN_TIME + 1e-9 && k < SWING_MAX_SAMPLES; k++) {
    double t = k * dt, u = t - tc - delay;
    ball_racket_sample *s = &sw->s[sw->n++];
    s->t = t;
    s->center = ball_v3_add(ball_v3_add(ball_v3_add(x, offset), ball_v3_scale(vr, u)), ball_v3_scale(acc, 0.5 * u * u));
    s->normal = ball_v3_unit(ball_v3_add(n_c, ball_v3_scale(spin, u)));
  }
}

/* ---- ground truth: the same motions, finely sampled ---- */

/* Distance from the ball's surface to the disc (face or rim). */
static inline double swing_disc_distance(ball_vec3 p, ball_vec3 c, ball_vec3 n) {
  ball_vec3 w = ball_v3_sub(p, c);
  double d = ball_v3_dot(w, n), rho = ball_v3_norm(ball_v3_sub(w, ball_v3_scale(n, d)));
  return (rho <= SWING_DISC_R ? fabs(d) : hypot(d, rho - SWING_DISC_R)) - SWING_BALL_R;
}

/* The distance at fraction u of the frame between samples a and b (nb: b's
 * normal turned into a's hemisphere), the ball at sim time t. */
static inline double swing_distance_at(const ball_model *m, const swing *sw, const ball_racket_sample *a,
                                       const ball_racket_sample *b, ball_vec3 nb, double t, double u) {
  ball_state s;
  ball_segment_eval(m, &sw->seg, t, &s);
  return swing_disc_distance(s.position, ball_v3_lerp(a->center, b->center, u),
                             ball_v3_unit(ball_v3_lerp(a->normal, nb, u)));
}

/* The first ground-truth sample time at which the ball touches the disc, or
 * -1; *closest gets the least distance seen before it (exact as to whether it
 * is below SWING_GT_RESOLUTION), *root (may be NULL) the contact time refined
 * by bisection between that sample and the one before (-1 without a hit).
 *
 * Every sample of the dense grid counts, but samples the distance cannot
 * reach within SWING_GT_RESOLUTION are skipped: the distance changes at most
 * as fast as the ball's speed plus the disc's fastest point (its centre's
 * speed plus the rim's speed from the normal's turn), so a sample d above
 * the resolution vouches for the next (d - resolution) / (bound * step)
 * samples. The result is the dense grid's, at a fraction of its cost. */
static inline double swing_ground_truth(const ball_model *m, const swing *sw, double *closest, double *root) {
  int k;
  *closest = INFINITY;
  if (root) *root = -1.0;
  for (k = 1; k < sw->n; k++) {
    const ball_racket_sample *a = &sw->s[k - 1], *bs = &sw->s[k];
    ball_vec3 nb = ball_v3_dot(a->normal, bs->normal) < 0 ? ball_v3_scale(bs->normal, -1) : bs->normal;
    ball_state s0, s1;
    double span = bs->t - a->t, h, v_ball, v_disc, turn, bound;
    int i, steps;
    /* skip frames where the ball stays far from both poses' reach */
    ball_segment_eval(m, &sw->seg, a->t, &s0);
    ball_segment_eval(m, &sw->seg, bs->t, &s1);
    if (ball_v3_norm(ball_v3_sub(s0.position, a->center)) + ball_v3_norm(ball_v3_sub(s1.position, bs->center)) >
        ball_v3_norm(ball_v3_sub(s1.position, s0.position)) + ball_v3_norm(ball_v3_sub(bs->center, a->center)) +
            4.0 * (SWING_DISC_R + SWING_BALL_R))
      continue;
    steps = (int)ceil(span / SWING_GT_STEP);
    h = span / steps;
    /* the rate bound over this frame: the horizontal speed only decays (eq 3),
     * the vertical one is linear in t; the nlerp normal turns at most at
     * |nb - na| / (span |na + (nb - na) u|), and |na + (nb - na) u|^2 >=
     * (1 + na.nb) / 2 for unit na, nb */
    v_ball = hypot(s0.velocity.x, s0.velocity.z) +
             (fabs(s0.velocity.y) > fabs(s1.velocity.y) ? fabs(s0.velocity.y) : fabs(s1.velocity.y));
    v_disc = ball_v3_norm(ball_v3_sub(bs->center, a->center)) / span;
    turn = ball_v3_norm(ball_v3_sub(nb, a->normal)) / (span * sqrt(0.5 * (1.0 + ball_v3_dot(a->normal, nb))));
    bound = v_ball + v_disc + turn * SWING_DISC_R;
    for (i = 0; i <= steps;) {
      double t = a->t + span * i / steps, dist = swing_distance_at(m, sw, a, bs, nb, t, (t - a->t) / span);
      long skip;
      if (dist < *closest) *closest = dist;
      if (dist <= 0.0) {
        if (root && i == 0) *root = t;
        if (root && i > 0) {
          double lo = a->t + span * (i - 1) / steps, hi = t;
          int it;
          for (it = 0; it < 80 && hi - lo > 1e-15; it++) {
            double mid = 0.5 * (lo + hi);
            if (swing_distance_at(m, sw, a, bs, nb, mid, (mid - a->t) / span) <= 0.0)
              hi = mid;
            else
              lo = mid;
          }
          *root = hi;
        }
        return t;
      }
      skip = dist > SWING_GT_RESOLUTION ? (long)floor(0.99 * (dist - SWING_GT_RESOLUTION) / (bound * h)) : 0;
      if (skip > steps - i) skip = steps - i;
      /* land on the last sample of the frame rather than past it */
      i += skip > 1 ? (int)skip : 1;
    }
  }
  return -1.0;
}

/* One run through ball_step: the samples pushed as they come, a frame from
 * each sample to the next; *t_hit gets the first racket event's time, or -1.
 * *frames (may be NULL) gets the frames stepped. */
static inline ball_status swing_simulate(const ball_model *m, const swing *sw, double *t_hit, int *frames) {
  ball_sim sim;
  ball_state st;
  ball_event ev[8];
  ball_status rc;
  int k, n;
  *t_hit = -1.0;
  if (frames) *frames = 0;
  st.position = sw->seg.p0;
  st.velocity = sw->seg.v0;
  st.spin = sw->seg.s0;
  if ((rc = ball_sim_init(&sim, m)) != BALL_OK || (rc = ball_sim_set_state(&sim, &st)) != BALL_OK ||
      (rc = ball_racket_push(&sim, 0, &sw->s[0])) != BALL_OK)
    return rc;
  for (k = 1; k < sw->n; k++) {
    if ((rc = ball_racket_push(&sim, 0, &sw->s[k])) != BALL_OK) return rc;
    if ((rc = ball_step(&sim, sw->s[k].t - sim.time, ev, 8, &n)) != BALL_OK) return rc;
    if (frames) (*frames)++;
    if (n > 0) {
      *t_hit = ev[0].time;
      return BALL_OK;
    }
  }
  return BALL_OK;
}

#endif /* BALL_KIT_SWINGS_H */
