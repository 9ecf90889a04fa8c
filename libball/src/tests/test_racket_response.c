/* Racket responses (eq 7-14), normal inversion (Fig. 9) and the frame-based
 * collision tests (sphere, Fig. 4/5 disc) against values computed by hand.
 *
 * Hand case for eq 8, 9: b = m / beta = 0.05 / 0.025 = 2 s, g = 9.81 m/s^2,
 * V_up = 4.905 m/s, so t0 = 2 V_up / g = 1 s exactly and
 *   b (1 - e^(-t0/b)) = 2 (1 - e^-0.5) = 0.78693868057473315
 *   f = 1 / 0.786938... = 1.2707470412683991
 * (30-digit arithmetic, rounded). Velocities are O(10 m/s) through a few
 * roundings: 1e-12 m/s is a deliberate, tight tolerance. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "core_common.h"
#include "../internal.h"

#define TOL 1e-12

static void assert_vec(ball_vec3 got, double x, double y, double z, double tol) {
  assert_near(got.x, x, tol);
  assert_near(got.y, y, tol);
  assert_near(got.z, z, tol);
}

static void racket_model(ball_model *m) {
  core_model_free(m);
  m->n_rackets = 2;
  m->v_min = 5.0;
  m->v_max = 40.0;
  m->spin_rack_damping = 0.8;
  m->spin_floor_damping = 0.8;
  m->effects |= BALL_EFFECT_RACKETS | BALL_EFFECT_SPIN;
}

/* ---- eq 7 ---- */

static void eq7_direction_of_racket_velocity_speed_clamped_to_v_max(void **state) {
  ball_model m;
  (void)state;
  racket_model(&m);
  /* |(30, 40, 0)| = 50 > v_max = 40: (24, 32, 0) */
  assert_vec(ball__response_racket(&m, ball_v3(30.0, 40.0, 0.0), ball_v3(1, 0, 0)), 24.0, 32.0, 0.0, TOL);
}

static void eq7_slow_racket_speed_raised_to_v_min(void **state) {
  ball_model m;
  (void)state;
  racket_model(&m);
  /* |(0.6, 0.8, 0)| = 1 < v_min = 5: (3, 4, 0) */
  assert_vec(ball__response_racket(&m, ball_v3(0.6, 0.8, 0.0), ball_v3(1, 0, 0)), 3.0, 4.0, 0.0, TOL);
  /* in range: unchanged */
  assert_vec(ball__response_racket(&m, ball_v3(0.0, 0.0, -12.0), ball_v3(1, 0, 0)), 0.0, 0.0, -12.0, TOL);
}

static void eq7_still_racket_sends_the_ball_along_the_face_normal_at_v_min(void **state) {
  ball_model m;
  (void)state;
  racket_model(&m);
  assert_vec(ball__response_racket(&m, ball_v3(0.0, 0.0, 0.0), ball_v3(-2.0, 0.0, 0.0)), -5.0, 0.0, 0.0, TOL);
}

/* ---- eq 8, 9 ---- */

static void eq8_eq9_autonomous_velocity_matches_hand_values(void **state) {
  ball_model m;
  ball_vec3 v;
  (void)state;
  racket_model(&m);
  /* from Q = (1, 1.2, 2) to the goal (13, *, 7): d1 = 12, d2 = 5 */
  v = ball__response_autonomous(&m, ball_v3(1.0, 1.2, 2.0), ball_v3(13.0, 5.0, 7.0), 4.905, 1.0);
  assert_vec(v, 12.0 * 1.2707470412683991, 4.905, 5.0 * 1.2707470412683991, TOL);
  assert_near(v.x, 15.248964495220790, TOL);
  assert_near(v.z, 6.3537352063419957, TOL);
  /* eq 9: friendlyFactor scales the whole vector */
  v = ball__response_autonomous(&m, ball_v3(1.0, 1.2, 2.0), ball_v3(13.0, 5.0, 7.0), 4.905, 0.5);
  assert_vec(v, 6.0 * 1.2707470412683991, 2.4525, 2.5 * 1.2707470412683991, TOL);
}

static void eq8_autonomous_ball_reaches_goal_at_stroke_height_after_t0(void **state) {
  ball_model m;
  ball_segment seg;
  ball_state s;
  core_rng rng = {7};
  int i;
  (void)state;
  racket_model(&m);
  /* invariant over seeded shots: with friendlyFactor 1 the flight of eq 3
   * started with the eq 9 velocity is at (goal x, Q y, goal z) at t0 */
  for (i = 0; i < 50; i++) {
    ball_vec3 q = ball_v3(core_uniform(&rng, 0, 5), core_uniform(&rng, 0.3, 2), core_uniform(&rng, 0, 10));
    ball_vec3 goal = ball_v3(core_uniform(&rng, 15, 25), 9.0, core_uniform(&rng, 0, 10));
    double v_up = core_uniform(&rng, 1.0, 8.0), t0 = 2.0 * v_up / m.gravity;
    seg = core_segment(3.0, q, ball__response_autonomous(&m, q, goal, v_up, 1.0), ball_v3(0, 0, 0));
    assert_ok(ball_segment_eval(&m, &seg, 3.0 + t0, &s));
    assert_near(s.position.x, goal.x, 1e-11);
    assert_near(s.position.y, q.y, 1e-11);
    assert_near(s.position.z, goal.z, 1e-11);
  }
  /* without drag (b infinite) the horizontal speed is dist_h / t0 */
  m.effects &= ~(unsigned)BALL_EFFECT_DRAG;
  assert_vec(ball__response_autonomous(&m, ball_v3(0, 1, 0), ball_v3(3, 1, 4), 4.905, 1.0), 3.0, 4.905, 4.0, TOL);
}

static void eq8_v_up_from_racket_is_the_racket_vertical_speed_at_least_the_minimum(void **state) {
  ball_model m;
  (void)state;
  racket_model(&m);
  m.v_up = 4.0;
  assert_near(ball__response_v_up(&m, ball_v3(3, 7, 0)), 4.0, 0.0);
  m.v_up_from_racket = 1;
  assert_near(ball__response_v_up(&m, ball_v3(3, 7, 0)), 7.0, 0.0);
  assert_near(ball__response_v_up(&m, ball_v3(3, -7, 0)), BALL__V_UP_MIN, 0.0);
  assert_true(BALL__V_UP_MIN > 0.0);
}

/* ---- eq 10 ---- */

static void eq10_mixed_velocity_matches_hand_values(void **state) {
  (void)state;
  /* Vf = (10, 4, 0), Vr = (20, 0, 2), ff = 0.8: Vf + (10, -4, 2) 0.2 = (12, 3.2, 0.4) */
  assert_vec(ball__response_mixed(ball_v3(10, 4, 0), ball_v3(20, 0, 2), 0.8), 12.0, 3.2, 0.4, TOL);
  assert_vec(ball__response_mixed(ball_v3(10, 4, 0), ball_v3(20, 0, 2), 1.0), 10.0, 4.0, 0.0, TOL);
  assert_vec(ball__response_mixed(ball_v3(10, 4, 0), ball_v3(20, 0, 2), 0.0), 20.0, 0.0, 2.0, TOL);
}

/* ---- eq 11, 12 ---- */

static void eq11_eq12_physical_response_matches_hand_values(void **state) {
  ball_model m;
  ball_vec3 v0, s0;
  (void)state;
  racket_model(&m);
  /* n = (1, 0, 0), V = (-10, -2, 0), V_racket = (5, 3, 0), no spin in:
   * V_r = (10, -2, 0), V_racketnorm = (5, 0, 0), S_racket = V_racket x n = (0, 0, -3),
   * V_spin_rack = (0 - S_racket) x n = (0, 3, 0): V0 = (15, 1, 0);
   * eq 12: S = 0.8 (0, 0, -3) = (0, 0, -2.4) */
  ball__response_physical(&m, ball_v3(-10, -2, 0), ball_v3(0, 0, 0), ball_v3(1, 0, 0), ball_v3(5, 3, 0), &v0, &s0);
  assert_vec(v0, 15.0, 1.0, 0.0, TOL);
  assert_vec(s0, 0.0, 0.0, -2.4, TOL);
  /* arriving spin (0, 0, 1): V_spin_rack = (0, 0, 4) x n = (0, 4, 0): V0 = (15, 2, 0) */
  ball__response_physical(&m, ball_v3(-10, -2, 0), ball_v3(0, 0, 1), ball_v3(1, 0, 0), ball_v3(5, 3, 0), &v0, &s0);
  assert_vec(v0, 15.0, 2.0, 0.0, TOL);
  assert_vec(s0, 0.0, 0.0, -2.4, TOL);
}

static void eq11_without_spin_effect_no_spin_term_and_no_spin_out(void **state) {
  ball_model m;
  ball_vec3 v0, s0;
  (void)state;
  racket_model(&m);
  m.effects &= ~(unsigned)BALL_EFFECT_SPIN;
  ball__response_physical(&m, ball_v3(-10, -2, 0), ball_v3(0, 0, 1), ball_v3(1, 0, 0), ball_v3(5, 3, 0), &v0, &s0);
  assert_vec(v0, 15.0, -2.0, 0.0, TOL);
  assert_vec(s0, 0.0, 0.0, 0.0, 0.0);
}

static void eq11_tilted_normal_reflection_keeps_speed_of_still_racket(void **state) {
  ball_model m;
  ball_vec3 v0, s0, n = ball_v3(0.6, 0.8, 0.0);
  (void)state;
  racket_model(&m);
  /* still racket, no spin: a mirror; V = (-3, -4, 7): n.V = -5,
   * V_r = V + 10 n = (3, 4, 7) */
  ball__response_physical(&m, ball_v3(-3, -4, 7), ball_v3(0, 0, 0), n, ball_v3(0, 0, 0), &v0, &s0);
  assert_vec(v0, 3.0, 4.0, 7.0, TOL);
}

/* ---- eq 13 ---- */

static void eq13_floor_spin_velocity_matches_hand_values(void **state) {
  ball_model m;
  (void)state;
  racket_model(&m);
  /* (Sx, Sy, Sz) x (0, 1, 0) = (-Sz, 0, Sx); times spinFloorDamping 0.8 */
  assert_vec(ball__spin_floor_velocity(&m, ball_v3(1.5, 3.0, 2.0)), -1.6, 0.0, 1.2, TOL);
  m.effects &= ~(unsigned)BALL_EFFECT_SPIN;
  assert_vec(ball__spin_floor_velocity(&m, ball_v3(1.5, 3.0, 2.0)), 0.0, 0.0, 0.0, 0.0);
}

/* ---- Fig. 9 ---- */

static void fig9_normal_inverted_toward_ball_previous_position(void **state) {
  ball_model m;
  ball_vec3 n = ball_v3(1, 0, 0), face, v0, s0;
  (void)state;
  racket_model(&m);
  assert_vec(ball__racket_face_normal(n, ball_v3(-0.5, 0.2, 0.1)), -1.0, 0.0, 0.0, 0.0);
  assert_vec(ball__racket_face_normal(n, ball_v3(0.5, -0.2, 0.1)), 1.0, 0.0, 0.0, 0.0);
  /* the back face hits like the front: a ball coming from -x moving +x at a
   * still racket whose tracked normal is +x bounces back to -x */
  face = ball__racket_face_normal(n, ball_v3(-1.0, 0.0, 0.0));
  ball__response_physical(&m, ball_v3(10, 0, 0), ball_v3(0, 0, 0), face, ball_v3(0, 0, 0), &v0, &s0);
  assert_vec(v0, -10.0, 0.0, 0.0, TOL);
  face = ball__racket_face_normal(ball_v3_scale(n, -1.0), ball_v3(-1.0, 0.0, 0.0));
  ball__response_physical(&m, ball_v3(10, 0, 0), ball_v3(0, 0, 0), face, ball_v3(0, 0, 0), &v0, &s0);
  assert_vec(v0, -10.0, 0.0, 0.0, TOL);
}

/* ---- the frame-based tests ---- */

static void sphere_test_hits_below_collision_distance_only(void **state) {
  (void)state;
  assert_true(ball__sphere_test(ball_v3(0.29, 0, 0), ball_v3(0, 0, 0), 0.3));
  assert_false(ball__sphere_test(ball_v3(0.3, 0.01, 0), ball_v3(0, 0, 0), 0.3));
}

static void fig4_disc_test_in_moving_frame_catches_racket_crossing_ball(void **state) {
  double s;
  ball_vec3 q;
  (void)state;
  /* ball 1.0 -> 0.5 along x, racket 0 -> 1.0: they cross. P' = 0.5 - 1 = -0.5,
   * the segment 1.0 -> -0.5 meets the disc at x = 0: s = 1 / 1.5, Q' = (0, 0.1, 0)
   * and Q = Q' + dR = (1, 0.1, 0). The sphere test (0.3 m) misses: |P - R| = 0.5. */
  assert_true(ball__disc_test(ball_v3(1.0, 0.1, 0), ball_v3(0.5, 0.1, 0), ball_v3(0, 0, 0), ball_v3(1, 0, 0),
                              ball_v3(1, 0, 0), 0.15, 0.0, &s, &q));
  assert_near(s, 1.0 / 1.5, TOL);
  assert_vec(q, 1.0, 0.1, 0.0, TOL);
  assert_false(ball__sphere_test(ball_v3(0.5, 0.1, 0), ball_v3(1, 0, 0), 0.3));
  /* the same frame with the racket stopping short (0 -> 0.4) is no hit */
  assert_false(ball__disc_test(ball_v3(1.0, 0.1, 0), ball_v3(0.5, 0.1, 0), ball_v3(0, 0, 0), ball_v3(0.4, 0, 0),
                               ball_v3(1, 0, 0), 0.15, 0.0, &s, &q));
}

static void fig5_disc_test_lateral_offset_against_radius_grown_by_ball(void **state) {
  double s;
  ball_vec3 q;
  (void)state;
  /* crossing 0.2 m off the axis: outside a 0.15 m disc for a point ball,
   * inside for a ball of radius 0.06 (0.15 + 0.06 = 0.21) */
  assert_false(ball__disc_test(ball_v3(1, 0.2, 0), ball_v3(-1, 0.2, 0), ball_v3(0, 0, 0), ball_v3(0, 0, 0),
                               ball_v3(1, 0, 0), 0.15, 0.0, &s, &q));
  assert_true(ball__disc_test(ball_v3(1, 0.2, 0), ball_v3(-1, 0.2, 0), ball_v3(0, 0, 0), ball_v3(0, 0, 0),
                              ball_v3(1, 0, 0), 0.15, 0.06, &s, &q));
  /* the ball surface touches the face when the centre is 0.06 m from it */
  assert_near(s, (1.0 - 0.06) / 2.0, TOL);
  assert_near(q.x, 0.06, TOL);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(eq7_direction_of_racket_velocity_speed_clamped_to_v_max),
      cmocka_unit_test(eq7_slow_racket_speed_raised_to_v_min),
      cmocka_unit_test(eq7_still_racket_sends_the_ball_along_the_face_normal_at_v_min),
      cmocka_unit_test(eq8_eq9_autonomous_velocity_matches_hand_values),
      cmocka_unit_test(eq8_autonomous_ball_reaches_goal_at_stroke_height_after_t0),
      cmocka_unit_test(eq8_v_up_from_racket_is_the_racket_vertical_speed_at_least_the_minimum),
      cmocka_unit_test(eq10_mixed_velocity_matches_hand_values),
      cmocka_unit_test(eq11_eq12_physical_response_matches_hand_values),
      cmocka_unit_test(eq11_without_spin_effect_no_spin_term_and_no_spin_out),
      cmocka_unit_test(eq11_tilted_normal_reflection_keeps_speed_of_still_racket),
      cmocka_unit_test(eq13_floor_spin_velocity_matches_hand_values),
      cmocka_unit_test(fig9_normal_inverted_toward_ball_previous_position),
      cmocka_unit_test(sphere_test_hits_below_collision_distance_only),
      cmocka_unit_test(fig4_disc_test_in_moving_frame_catches_racket_crossing_ball),
      cmocka_unit_test(fig5_disc_test_lateral_offset_against_radius_grown_by_ball),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
