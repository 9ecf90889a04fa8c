/* Internal helpers shared by libball's sources; not installed. */
#ifndef BALL_INTERNAL_H
#define BALL_INTERNAL_H

#include <math.h>
#include <string.h>

#include "ball/ball.h"
#include "ball/vec3.h"

/* For the check functions: on a failed condition, name the field in *field
 * (if the caller asked) and return the status. */
#define CHECK(cond, name, status) \
  do {                            \
    if (!(cond)) {                \
      if (field) *field = (name); \
      return (status);            \
    }                             \
  } while (0)
#define CHECK_FINITE(value, name) CHECK(isfinite(value), name, BALL_ENONFINITE)

static inline int ball__has(const ball_model *m, unsigned effect) { return (m->effects & effect) != 0; }

/* ---- elementary functions (elementary.c) ---- */

/* e^x, e^x - 1, ln x, ln(1 + x): fdlibm's algorithms in portable C99, the
 * same bits on every platform (libm's differ between C libraries and, with
 * glibc, between CPUs); within 1 ulp. No errno, no flags. */
double ball__exp(double x);
double ball__expm1(double x);
double ball__log(double x);
double ball__log1p(double x);

/* ---- flight (flight.c) ---- */

/* b = m / beta, or +Inf when drag is off or beta = 0. */
static inline double ball__drag_b(const ball_model *m) {
  if (!ball__has(m, BALL_EFFECT_DRAG) || m->air_friction == 0.0) return INFINITY;
  return m->mass / m->air_friction; /* eq 2: b = m / beta; may overflow to +Inf */
}
/* b (1 - e^(-t/b)) without cancellation; t when b is infinite (eq 3). */
double ball__drag_distance(double b, double t);
/* sDamp / (sDamp + t) (eq 4), 1 when spin is off. */
double ball__spin_air_damping(const ball_model *m, double t);
/* What an evaluation needs of the model, worked out once per step or
 * prediction instead of once per evaluation (two divisions saved each). */
typedef struct ball__flight {
  double b;      /* m / beta, +Inf without drag */
  double k;      /* 1 / b, 0 without drag */
  double g;      /* gravity */
  double sdamp;  /* sDamp of eq 4; 0 without spin */
} ball__flight;
/* b and k = 1/b of a model (eq 2): +Inf and 0 without drag. */
static inline void ball__drag_of(const ball_model *m, double *b, double *k) {
  if (!ball__has(m, BALL_EFFECT_DRAG) || m->air_friction == 0.0) {
    *b = INFINITY;
    *k = 0.0;
  } else {
    /* k first: an evaluation waits for it (expm1(-t k)), for b only at its end */
    *k = m->air_friction / m->mass;
    *b = m->mass / m->air_friction; /* eq 2: b = m / beta; may overflow to +Inf */
    if (isinf(*b)) *k = 0.0;
  }
}
static inline double ball__sdamp_of(const ball_model *m) {
  return ball__has(m, BALL_EFFECT_SPIN) ? m->spin_damping : 0.0;
}
static inline void ball__flight_of(const ball_model *m, ball__flight *f) {
  ball__drag_of(m, &f->b, &f->k);
  f->g = m->gravity;
  f->sdamp = ball__sdamp_of(m);
}

/* eq 3 for both horizontal terms at once: *d = b (1 - e^(-t/b)) and
 * *f = e^(-t/b), from one transcendental call (libball's own, elementary.c:
 * the same bits on every platform). For t/b < ln 2, expm1 gives
 * both without cancellation (f = 1 + expm1 >= 1/2 is exact to an ulp);
 * beyond, f = e^(-t/b) <= 1/2 and 1 - f is as exact. k = 1/b, 0 for no drag. */
static inline void ball__drag_terms(double b, double k, double t, double *d, double *f) {
  double x;
  if (t == 0.0 || k == 0.0) {
    *d = t;
    *f = 1.0;
    return;
  }
  x = t * k;
  if (x < 0.69314718055994531) {
    double e = ball__expm1(-x);
    *d = -b * e;
    *f = 1.0 + e;
  } else {
    *f = ball__exp(-x);
    *d = b * (1.0 - *f);
  }
}

/* 1 when each of v's numbers is +0 or -0: by their bits (a NaN is not
 * zero), one test instead of three comparisons. */
static inline int ball__zero3(const ball_vec3 *v) {
  uint64_t x, y, z;
  memcpy(&x, &v->x, sizeof x);
  memcpy(&y, &v->y, sizeof y);
  memcpy(&z, &v->z, sizeof z);
  return ((x | y | z) << 1) == 0;
}

/* eq 3 and eq 4 at tau = t - t0 on seg, from the drag terms d, f of
 * ball__drag_terms at tau; g gravity, sdamp sDamp (0: no spin). No checks. */
static inline void ball__state_at(double g, double sdamp, const ball_segment *seg, double tau, double d,
                                  double f, ball_state *out) {
  /* eq 3: horizontal with drag, vertical under gravity alone */
  out->position.x = seg->p0.x + seg->v0.x * d;
  out->position.z = seg->p0.z + seg->v0.z * d;
  out->velocity.x = seg->v0.x * f;
  out->velocity.z = seg->v0.z * f;
  if (seg->grounded) {
    out->position.y = seg->p0.y;
    out->velocity.y = 0.0;
  } else {
    out->position.y = seg->p0.y + seg->v0.y * tau - 0.5 * g * tau * tau;
    out->velocity.y = seg->v0.y - g * tau;
  }
  if (sdamp != 0.0 && !ball__zero3(&seg->s0))
    out->spin = ball_v3_scale(seg->s0, sdamp / (sdamp + tau)); /* eq 4 */
  else
    out->spin = ball_v3(0.0, 0.0, 0.0);
}

/* State at sim time t on seg, no argument checks (eq 3, 4), from the
 * constants b, k = 1/b, g, sDamp (0: no spin). Inline: it is the hot path
 * of a step, a prediction, the swept test and ball_flight_eval. The
 * transcendental call comes first, before anything of seg but t0 is read:
 * nothing else is live across it (no registers to save and restore). */
static inline void ball__eval_c(double b, double k, double g, double sdamp, const ball_segment *seg,
                                double t, ball_state *out) {
  double tau = t - seg->t0, d, f;
  ball__drag_terms(b, k, tau, &d, &f);
  ball__state_at(g, sdamp, seg, tau, d, f, out);
}

static inline void ball__eval_f(const ball__flight *fl, const ball_segment *seg, double t,
                                ball_state *out) {
  ball__eval_c(fl->b, fl->k, fl->g, fl->sdamp, seg, t, out);
}
/* The same, working the constants out of the model. */
void ball__eval(const ball_model *m, const ball_segment *seg, double t, ball_state *out);
/* Starts a new segment at time t. */
void ball__segment_start(ball_segment *seg, double t, ball_vec3 p0, ball_vec3 v0, ball_vec3 s0, int grounded);
/* Roots r1 <= r2 of y0 + v tau - g tau^2 / 2 = y; 0 if the height is never reached. */
int ball__height_roots(double g, double y0, double v, double y, double *r1, double *r2);
/* tau >= tau_from where x0 + v b (1 - e^(-tau/b)) = target; 0 if never. */
int ball__plane_tau(double b, double x0, double v, double target, double tau_from, double *tau);
/* The effective floor height for the ball centre: floor_level + radius. */
static inline double ball__floor_y(const ball_model *m) { return m->floor_level + m->radius; }

/* ---- the net and the walls (planes.c) ---- */

/* q within the rectangle's extent (closed: its edges count). */
static inline int ball__in_extent(const ball_plane *pl, ball_vec3 q) {
  double h = pl->axis == 0 ? q.z : q.x;
  return h >= pl->lo && h <= pl->hi && q.y >= pl->bottom && q.y <= pl->top;
}
/* The point of pl's rectangle nearest to c. */
ball_vec3 ball__rect_nearest(const ball_plane *pl, ball_vec3 c);
/* The first contact of the ball (the model's radius) with the rectangle
 * grown by the radius at tau in [tau_from, tau_to] on seg (tau_to: a
 * contact already known, +Inf if none; the edges are not searched past it),
 * approaching it: 1 with
 * *tau, the centre *q (for the face one ulp back on the approach side) and
 * the contact normal *n (zero for the face, else from the nearest point). */
int ball__plane_contact(const ball_model *m, const ball__flight *fl, const ball_segment *seg,
                        const ball_plane *pl, double tau_from, double tau_to, double *tau, ball_vec3 *q,
                        ball_vec3 *n);
/* The same on the chord p_old -> p (the sampled scheme): *s in [0, 1]. */
int ball__plane_chord(const ball_model *m, const ball_plane *pl, ball_vec3 p_old, ball_vec3 p, double *s,
                      ball_vec3 *q, ball_vec3 *n);

/* ---- rackets (racket.c, response.c) ---- */

/* Racket stage of a step, run after the static obstacles when the RACKETS
 * effect is on. The frame goes from t_prev (ball centre then:
 * sim->prev_position) to t = sim->time (ball on sim->seg, *s_end its state
 * then). Handles the sleep
 * counter, the detection mode and the response; on a hit it starts a new
 * segment in sim->seg, writes *ev and returns 1; otherwise returns 0.
 * Updates each track's prev_pose for the next frame. */
int ball__racket_stage(const ball_model *m, const ball__flight *fl, ball_sim *sim, double t_prev,
                       double dt, const ball_state *s_end, ball_event *ev);

/* eq 13: velocity added at a floor bounce by the air-damped spin, normal (0, 1, 0):
 * spinFloorDamping (spinAirDamping S_ball) x n. Implemented in response.c. */
ball_vec3 ball__spin_floor_velocity(const ball_model *m, ball_vec3 spin_air_damped);

/* ---- model (model.c) ---- */

/* The hash's start value (FNV-1a's offset basis). */
#define BALL__HASH_SEED 14695981039346656037ULL
/* One 64-bit word, a double (by its bits, -0 as +0), a vector into a hash. */
uint64_t ball__hash_word(uint64_t h, uint64_t w);
uint64_t ball__hash_double(uint64_t h, double v);
uint64_t ball__hash_vec(uint64_t h, ball_vec3 v);

/* Racket tests and responses, exposed for the unit tests (racket.c, response.c). */

/* Lowest V_up of eq 8 when it is matched to the racket's vertical speed, m/s. */
#define BALL__V_UP_MIN 1.0
/* Fig. 9: n, inverted if the ball's previous position rel_old (relative to the racket) is behind it. */
ball_vec3 ball__racket_face_normal(ball_vec3 n, ball_vec3 rel_old);
/* eq 7: V0 along v_racket, speed clamped to [v_min, v_max]; along fallback at v_min when still. */
ball_vec3 ball__response_racket(const ball_model *m, ball_vec3 v_racket, ball_vec3 fallback);
/* eq 8: V_up, model->v_up or the racket's vertical speed (>= BALL__V_UP_MIN). */
double ball__response_v_up(const ball_model *m, ball_vec3 v_racket);
/* eq 8, 9: V0 flying from q to the goal's (x, z) at q's height, times friendly. */
ball_vec3 ball__response_autonomous(const ball_model *m, ball_vec3 q, ball_vec3 goal, double v_up,
                                    double friendly);
/* eq 10: the friendly velocity mixed with the racket velocity. */
ball_vec3 ball__response_mixed(ball_vec3 v_friendly, ball_vec3 v_racket, double friendly);
/* eq 11, 12: V0 and S0 after a physical hit; n is the face normal (Fig. 9),
 * spin_in the arriving spin with eq 4 applied. */
void ball__response_physical(const ball_model *m, ball_vec3 v, ball_vec3 spin_in, ball_vec3 n,
                             ball_vec3 v_racket, ball_vec3 *v0, ball_vec3 *s0);
/* The sphere test: |p - r| < d_coll. */
int ball__sphere_test(ball_vec3 p, ball_vec3 r, double d_coll);
/* Fig. 4, 5: p_old -> p' = p - (r - r_old) against the disc (r_old, unit n,
 * disc_radius) grown by ball_radius; *s in [0, 1] along the segment, *q the
 * ball centre at contact carried to the racket's current pose. */
int ball__disc_test(ball_vec3 p_old, ball_vec3 p, ball_vec3 r_old, ball_vec3 r, ball_vec3 n,
                    double disc_radius, double ball_radius, double *s, ball_vec3 *q);
/* Below this speed the racket counts as still: the velocity normal mode falls
 * back to the real normal. */
#define BALL__STILL_SPEED 1e-3 /* m/s */
/* The normal the disc (velocity mode) and swept tests read from a pose: the
 * real one, or the velocity's direction (the real one while still). */
ball_vec3 ball__racket_test_normal(const ball_model *m, const ball_racket_pose *pose);
/* The racket stage's test of racket i alone, for one step from sim->time to
 * t on sim->seg with no static contact in between (the tracks, the previous
 * pose and position as the stage reads them; the sleep counter not read):
 * 1 on a hit, with the time the step's event would carry and the stage's
 * key (earliest / nearest wins); 0 otherwise. */
int ball__racket_test_at(const ball_model *m, const ball__flight *fl, const ball_sim *sim, int i, double t,
                         double *t_hit, double *key);
/* The end of the window a racket query may search from sim->time: the
 * largest time <= t_end such that no step from sim to a time in
 * (sim->time, it] meets the floor, the net or a wall (step.c). Exact scheme:
 * just before the next contact (sim->next, or found as a step finds it);
 * sampled: just before the centre falls below the floor or comes within the
 * ball's radius of a net's or wall's plane (a bound: the chord test may meet
 * the rectangle later or never). sim->time when the window is empty. */
double ball__static_window(const ball_sim *sim, const ball__flight *fl, double t_end);
/* A track's pose at t without checks (interpolation, eq 15 past the newest). */
void ball__racket_pose(const ball_model *m, const ball_racket_track *tr, double t,
                       ball_racket_pose *out);

/* ---- the first contact search (contact.c) ---- */

/* The distance between the ball and an obstacle at a time. */
typedef struct ball__probe {
  double t;     /* s */
  double dist;  /* ball surface to the obstacle, m (<= 0: touching) */
  double side;  /* signed distance of the centre to a thin obstacle's plane, for the crossing
                   test; the same value everywhere for an obstacle that has no crossing */
  int inside;   /* 1: here the centre is within the thin obstacle (a crossing counts) */
} ball__probe;
typedef ball__probe (*ball__probe_fn)(const void *ctx, double t);

typedef struct ball__contact_query {
  ball__probe_fn probe;
  const void *ctx;
  double ta, tb; /* the interval searched, s */
  double rate;   /* L: the fastest |d dist / dt| can be over it, m/s (> 0) */
} ball__contact_query;

/* The first time in [ta, tb] the distance is <= 0 (or the centre crosses a
 * thin obstacle inside it): 1 with *hit the first touching probe (its side:
 * the last clear one's); 0 if none. Rigorous given the rate; at most
 * 2048 evaluations. When they run out before [ta, tb] is cleared (a ball
 * skimming an obstacle for long): 2 with *hit the last clear probe, which
 * a caller that must not let the ball through treats as the contact.
 * *probes_used (may be NULL) gets how many it made. */
int ball__first_contact(const ball__contact_query *q, ball__probe *hit, int *probes_used);

/* The swept test over [ta, tb] (swept.c). The ball follows seg (analytic,
 * when flight is not NULL) or moves linearly p0 -> p1; the disc moves linearly
 * c0 -> c1 and turns n0 -> n1 (normalised lerp) over [tc0, tc1]. */
typedef struct ball__swept_motion {
  const ball__flight *flight; /* NULL: linear ball motion */
  const ball_segment *seg;  /* the ball's segment (flight not NULL) */
  double ta, tb;            /* interval searched, s */
  ball_vec3 p0, p1;         /* ball centre at ta and tb (linear motion), m */
  double ball_radius;       /* m */
  double tc0, tc1;          /* times of the two disc poses, s */
  ball_vec3 c0, c1;         /* disc centre, m */
  ball_vec3 n0, n1;         /* disc normal (need not be unit) */
  double disc_radius;       /* m */
  int *probes_used;         /* NULL, or where the search counts its distance evaluations */
} ball__swept_motion;
/* First contact (distance to the disc, face or rim, <= the ball radius) in
 * [ta, tb]; 1 with *t_hit, the ball centre then and the face normal toward
 * the side the ball came from; 0 if none. Callers run the early reject
 * ball__swept_cannot_touch first (it needs p0, p1: the ball at ta and tb). */
int ball__swept_toi(const ball__swept_motion *mo, double *t_hit, ball_vec3 *center,
                    ball_vec3 *face_normal);
/* 1 when no contact is possible over the interval (bounding spheres of the
 * ball's path and the disc's: the early reject ball__swept_toi starts with). */
int ball__swept_cannot_touch(const ball__swept_motion *mo);

#endif /* BALL_INTERNAL_H */
