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

#endif /* BALL_TESTS_CORE_COMMON_H */
