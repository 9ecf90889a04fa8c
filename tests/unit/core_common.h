/* Helpers shared by the unit tests: tolerance assertions that print both
 * numbers, vector arithmetic, the base scenes (a ball in free space, the
 * tennis net, the court with a back wall), starting a sim; with them the
 * kit's seeded generator, tests/support's stepping loop (steps.h) and its
 * for-each-scheme driver (schemes.h). Include after <cmocka.h>. */
#ifndef BALL_TESTS_CORE_COMMON_H
#define BALL_TESTS_CORE_COMMON_H

#include <math.h>
#include <stdio.h>
#include <string.h>

#include "ball/ball.h"
#include "ball/vec3.h"
#include "schemes.h"
#include "seeded.h"
#include "steps.h"

/* |got - want| <= tol, with both expressions and numbers in the failure
 * message. A NaN on either side fails. */
#define assert_near(got, want, tol) \
  core_assert_near((got), (want), (tol), #got, #want, __FILE__, __LINE__)

static inline void core_assert_near(double got, double want, double tol, const char *got_expr,
                                    const char *want_expr, const char *file, int line) {
  if (!(fabs(got - want) <= tol)) {
    print_error("%s = %.17g, want %s = %.17g +- %.3g (off by %.3g)\n", got_expr, got, want_expr,
                want, tol, fabs(got - want));
    _fail(file, line);
  }
}

/* Relative version: |got - want| <= rel * |want|. */
#define assert_rel(got, want, rel) \
  core_assert_near((got), (want), (rel) * fabs(want), #got, #want, __FILE__, __LINE__)

/* Every component of a ball_vec3 is finite. */
#define assert_finite3(v) assert_true(isfinite((v).x) && isfinite((v).y) && isfinite((v).z))

#define assert_ok(call) assert_int_equal((call), BALL_OK)

/* A point ball in free space: no obstacles, no spin, no sound, drag with
 * b = m / beta = 2 s, floor at 0, exact scheme. Tests switch on what they need. */
static inline void core_model_free(ball_model *m) {
  ball_model_default(m);
  m->mass = 0.05;
  m->air_friction = 0.025; /* b = 2 s */
  m->radius = 0.0;
  m->has_net = 0;
  m->n_walls = 0;
  m->n_rackets = 0;
  m->effects = BALL_EFFECT_DRAG | BALL_EFFECT_FLOOR;
  m->scheme = BALL_SCHEME_EXACT;
  m->initial_position.x = 0.0;
  m->initial_position.y = 1.0;
  m->initial_position.z = 0.0;
  m->initial_velocity.x = 0.0;
  m->initial_velocity.y = 0.0;
  m->initial_velocity.z = 0.0;
  m->initial_spin.x = 0.0;
  m->initial_spin.y = 0.0;
  m->initial_spin.z = 0.0;
}

/* The default tennis net (x = 11.885 m, z in [0, 10.97] m, y in [0, 0.914] m)
 * with the given netDamping, switched on in the model (not in the effects). */
static inline void core_tennis_net(ball_model *m, double damping) {
  m->has_net = 1;
  m->net.axis = 0;
  m->net.position = 11.885;
  m->net.lo = 0.0;
  m->net.hi = 10.97;
  m->net.bottom = 0.0;
  m->net.top = 0.914;
  m->net.damping = damping;
}

/* The tennis court with a back wall at x = -1 (damping 0.8), drag with b =
 * 5 s, radius 0.03 m, floorDamping 0.8, netDamping 0.9: the serve from
 * (3, 1.5, 2) m at (12, 3, 0.5) m/s hits the net at y = 0.76 m, flies back,
 * bounces, hits the wall and bounces on. Exact scheme, no spin. */
static inline void core_court_scene(ball_model *m) {
  ball_plane back = {0, -1.0, -5.0, 15.0, 0.0, 4.0, 0.8};
  core_model_free(m);
  m->air_friction = 0.01; /* b = 5 s */
  m->radius = 0.03;
  m->floor_damping = 0.8;
  m->bounce_threshold = 0.3;
  m->sound_threshold = 0.5;
  core_tennis_net(m, 0.9);
  m->effects = BALL_EFFECT_DRAG | BALL_EFFECT_FLOOR | BALL_EFFECT_NET | BALL_EFFECT_WALLS |
               BALL_EFFECT_SOUND;
  assert_ok(ball_model_add_wall(m, &back));
  m->initial_position = ball_v3(3.0, 1.5, 2.0);
  m->initial_velocity = ball_v3(12.0, 3.0, 0.5);
}

/* Starts sim at time 0 with the ball at p moving at v, no spin (the model's
 * initial state). */
static inline void core_start(ball_model *m, ball_sim *sim, ball_vec3 p, ball_vec3 v) {
  m->initial_position = p;
  m->initial_velocity = v;
  m->initial_spin = ball_v3(0.0, 0.0, 0.0);
  assert_ok(ball_sim_init(sim, m));
}

static inline ball_racket_sample core_sample(double t, ball_vec3 c, ball_vec3 n) {
  ball_racket_sample s;
  s.t = t;
  s.center = c;
  s.normal = n;
  return s;
}

static inline ball_segment core_segment(double t0, ball_vec3 p0, ball_vec3 v0, ball_vec3 s0) {
  ball_segment seg;
  memset(&seg, 0, sizeof seg);
  seg.t0 = t0;
  seg.p0 = p0;
  seg.v0 = v0;
  seg.s0 = s0;
  seg.grounded = 0;
  return seg;
}

/* Kinetic plus potential energy: m v^2 / 2 + m g y. */
static inline double core_energy(const ball_model *m, ball_vec3 v, double y) {
  return 0.5 * m->mass * (v.x * v.x + v.y * v.y + v.z * v.z) + m->mass * m->gravity * y;
}

/* Seeded random shots: kit/seeded.h's generator. */
typedef seeded_rng core_rng;
static inline double core_uniform(core_rng *r, double lo, double hi) { return seeded_uniform(r, lo, hi); }

/* How far a state of ball_predict is from ball_step's at time t, seg being
 * the segment ball_step had in effect then, in units of ball.h's bound: the
 * largest over x and z of |dx| / (|P0x| + |V0x| (t - t0)) and
 * |dvx| / |V0x| (0 for numbers equal to the bit, +Inf for any difference
 * where the scale is 0); +Inf when the height, the vertical speed or the
 * spin differ at all (ball.h promises those to the bit). */
static inline double core_predict_error_axis(double got, double want, double scale) {
  if (memcmp(&got, &want, sizeof got) == 0) return 0.0;
  if (!(scale > 0.0)) return INFINITY;
  return fabs(got - want) / scale;
}
static inline double core_predict_error(const ball_state *got, const ball_state *want, const ball_segment *seg,
                                        double t) {
  double tau = t - seg->t0, e, worst = 0.0;
  if (memcmp(&got->position.y, &want->position.y, sizeof got->position.y) != 0 ||
      memcmp(&got->velocity.y, &want->velocity.y, sizeof got->velocity.y) != 0 ||
      memcmp(&got->spin, &want->spin, sizeof got->spin) != 0)
    return INFINITY;
  e = core_predict_error_axis(got->position.x, want->position.x, fabs(seg->p0.x) + fabs(seg->v0.x) * tau);
  worst = e > worst ? e : worst;
  e = core_predict_error_axis(got->position.z, want->position.z, fabs(seg->p0.z) + fabs(seg->v0.z) * tau);
  worst = e > worst ? e : worst;
  e = core_predict_error_axis(got->velocity.x, want->velocity.x, fabs(seg->v0.x));
  worst = e > worst ? e : worst;
  e = core_predict_error_axis(got->velocity.z, want->velocity.z, fabs(seg->v0.z));
  return e > worst ? e : worst;
}

/* One frame of dt of the sim against a prediction's state at its end: the
 * sim stepped (its events into ev, BALL_MAX_CONTACTS of room, their count
 * into *n, its state into *stepped), and core_predict_error of the
 * prediction against it. */
static inline double core_step_against(ball_sim *sim, double dt, const ball_state *predicted, ball_event *ev,
                                       int *n, ball_state *stepped) {
  assert_ok(ball_step(sim, dt, ev, BALL_MAX_CONTACTS, n));
  assert_ok(ball_sim_state(sim, stepped));
  return core_predict_error(predicted, stepped, &sim->seg, sim->time);
}

/* Every field of two events equal to the bit. */
static inline int core_event_same(const ball_event *a, const ball_event *b) {
  return a->kind == b->kind && a->index == b->index && a->sound == b->sound &&
         memcmp(&a->time, &b->time, sizeof a->time) == 0 && memcmp(&a->point, &b->point, sizeof a->point) == 0 &&
         memcmp(&a->velocity_in, &b->velocity_in, sizeof a->velocity_in) == 0 &&
         memcmp(&a->velocity_out, &b->velocity_out, sizeof a->velocity_out) == 0 &&
         memcmp(&a->spin_out, &b->spin_out, sizeof a->spin_out) == 0 &&
         memcmp(&a->segment.t0, &b->segment.t0, sizeof a->segment.t0) == 0 &&
         memcmp(&a->segment.p0, &b->segment.p0, sizeof a->segment.p0) == 0 &&
         memcmp(&a->segment.v0, &b->segment.v0, sizeof a->segment.v0) == 0 &&
         memcmp(&a->segment.s0, &b->segment.s0, sizeof a->segment.s0) == 0 &&
         a->segment.grounded == b->segment.grounded;
}

#endif /* BALL_TESTS_CORE_COMMON_H */
