/* Flight (eq 3), spin damping in air (eq 4) and the prediction functions,
 * against values computed by hand (30-digit arithmetic, rounded to 17).
 *
 * The hand case: b = m / beta = 0.05 / 0.025 = 2 s, g = 9.81 m/s^2,
 * P0 = (1, 2, -1) m, V0 = (4, 3, -2) m/s, one second of flight:
 *   e^(-t/b) = e^-0.5 = 0.60653065971263342
 *   b (1 - e^(-t/b)) = 2 (1 - e^-0.5) = 0.78693868057473315
 *   x = 1 + 4 * 0.786938... = 4.1477547222989326, z = -1 - 2 * 0.786938... = -2.5738773611494663
 *   y = 2 + 3 - 9.81 / 2 = 0.095, vx = 4 e^-0.5, vy = 3 - 9.81, vz = -2 e^-0.5.
 * Positions are O(10 m) and each goes through a handful of roundings, so
 * 1e-12 m (about 1000 ulps) is a deliberate, still tight tolerance. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "core_common.h"

#define TOL 1e-12

static ball_segment hand_segment(double t0) {
  return core_segment(t0, ball_v3(1.0, 2.0, -1.0), ball_v3(4.0, 3.0, -2.0), ball_v3(0.0, 0.0, 5.0));
}

static void eq3_position_and_velocity_match_hand_values_b2_t1(void **state) {
  ball_model m;
  ball_segment seg = hand_segment(0.0);
  ball_state s;
  (void)state;
  core_model_free(&m);
  assert_ok(ball_segment_eval(&m, &seg, 1.0, &s));
  assert_near(s.position.x, 4.1477547222989326, TOL);
  assert_near(s.position.y, 0.095, TOL);
  assert_near(s.position.z, -2.5738773611494663, TOL);
  assert_near(s.velocity.x, 2.4261226388505337, TOL);
  assert_near(s.velocity.y, 3.0 - 9.81, TOL);
  assert_near(s.velocity.z, -1.2130613194252668, TOL);
}

/* The paper resets time to zero at each collision: eval uses t - t0. */
static void eq3_uses_time_since_segment_start(void **state) {
  ball_model m;
  ball_segment seg = hand_segment(10.0);
  ball_state s;
  (void)state;
  core_model_free(&m);
  assert_ok(ball_segment_eval(&m, &seg, 11.0, &s));
  assert_near(s.position.x, 4.1477547222989326, TOL);
  assert_near(s.position.y, 0.095, TOL);
  assert_near(s.velocity.x, 2.4261226388505337, TOL);
  /* at t0 itself the segment's own P0 and V0, exactly */
  assert_ok(ball_segment_eval(&m, &seg, 10.0, &s));
  assert_true(s.position.x == 1.0 && s.position.y == 2.0 && s.position.z == -1.0);
  assert_true(s.velocity.x == 4.0 && s.velocity.y == 3.0 && s.velocity.z == -2.0);
}

/* beta = 0 (b infinite): exactly the drag-free parabola, bit for bit. */
static void eq3_beta_zero_is_exactly_the_parabola(void **state) {
  ball_model m;
  ball_segment seg = hand_segment(0.0);
  ball_state s;
  const double ts[] = {0.7, 1.0, 3.25, 1e3, 1e9};
  size_t i;
  (void)state;
  core_model_free(&m);
  m.air_friction = 0.0;
  for (i = 0; i < sizeof ts / sizeof ts[0]; i++) {
    double t = ts[i];
    assert_ok(ball_segment_eval(&m, &seg, t, &s));
    assert_true(s.position.x == 1.0 + 4.0 * t);
    assert_true(s.position.z == -1.0 + -2.0 * t);
    assert_true(s.position.y == 2.0 + 3.0 * t - 0.5 * 9.81 * t * t);
    assert_true(s.velocity.x == 4.0 && s.velocity.z == -2.0);
    assert_true(s.velocity.y == 3.0 - 9.81 * t);
  }
  /* the drag effect switched off gives the same parabola with beta > 0 */
  core_model_free(&m);
  m.effects &= ~(unsigned)BALL_EFFECT_DRAG;
  assert_ok(ball_segment_eval(&m, &seg, 0.7, &s));
  assert_true(s.position.x == 1.0 + 4.0 * 0.7 && s.velocity.x == 4.0);
}

/* b = 1e12 s: b (1 - e^(-t/b)) computed naively loses ~1e-4 relative
 * (1 - e^-1e-12 cancels); the series t - t^2/(2b) + t^3/(6b^2) - ... is the
 * truth. Tolerance: 4 ulps at t = 1 and 1e-15 relative at t = 1e9. */
static void eq3_huge_b_has_no_cancellation_matches_series(void **state) {
  ball_model m;
  ball_segment seg = core_segment(0.0, ball_v3(0.0, 0.0, 0.0), ball_v3(1.0, 0.0, 0.0),
                                  ball_v3(0.0, 0.0, 0.0));
  ball_state s;
  double b = 1e12, t, series;
  (void)state;
  core_model_free(&m);
  m.mass = 1.0;
  m.air_friction = 1e-12;
  m.effects = BALL_EFFECT_DRAG; /* free flight, no floor */
  t = 1.0;
  series = t - t * t / (2.0 * b) + t * t * t / (6.0 * b * b);
  assert_ok(ball_segment_eval(&m, &seg, t, &s));
  assert_near(s.position.x, series, 4.0 * 2.2e-16);
  assert_true(s.position.x < 1.0); /* the drag is there, not rounded away */
  t = 1e9;                         /* t / b = 1e-3: 999500166.62500833 */
  series = t - t * t / (2.0 * b) + t * t * t / (6.0 * b * b) - t * t * t * t / (24.0 * b * b * b) +
           pow(t, 5.0) / (120.0 * pow(b, 4.0));
  assert_ok(ball_segment_eval(&m, &seg, t, &s));
  assert_rel(s.position.x, 999500166.62500833, 1e-15);
  assert_rel(s.position.x, series, 1e-15);
  assert_rel(s.velocity.x, exp(-1e-3), 1e-15);
}

/* b = 1e-12 s: the ball stops dead after ~b; the distance is b (1 - e^(-t/b)). */
static void eq3_tiny_b_stops_at_v0_times_b(void **state) {
  ball_model m;
  ball_segment seg = core_segment(0.0, ball_v3(1.0, 0.0, 0.0), ball_v3(1e6, 0.0, 0.0),
                                  ball_v3(0.0, 0.0, 0.0));
  ball_state s;
  (void)state;
  core_model_free(&m);
  m.mass = 1.0;
  m.air_friction = 1e12;
  m.effects = BALL_EFFECT_DRAG;
  /* t = b: 1e6 * 1e-12 * (1 - e^-1) = 6.3212055882855768e-7 */
  assert_ok(ball_segment_eval(&m, &seg, 1e-12, &s));
  assert_near(s.position.x, 1.0 + 6.3212055882855768e-7, 1e-15);
  assert_near(s.velocity.x, 1e6 * 0.36787944117144233, 1e-9);
  /* t = 1 s = 1e12 b: all of the distance v0 b = 1e-6 m, no speed left */
  assert_ok(ball_segment_eval(&m, &seg, 1.0, &s));
  assert_near(s.position.x, 1.0 + 1e-6, 1e-15);
  assert_true(s.velocity.x == 0.0);
}

/* Finite everywhere: t from 1e-12 to 1e9 s, b from 1e-12 s to infinite. */
static void eq3_state_is_finite_for_every_t_up_to_1e9(void **state) {
  const double betas[] = {0.0, 1e-12, 0.025, 1.0, 1e12};
  ball_model m;
  ball_segment seg = hand_segment(0.0);
  ball_state s;
  size_t i;
  int k;
  (void)state;
  core_model_free(&m);
  m.effects = BALL_EFFECT_DRAG | BALL_EFFECT_SPIN;
  m.mass = 1.0;
  for (i = 0; i < sizeof betas / sizeof betas[0]; i++) {
    m.air_friction = betas[i];
    for (k = -120; k <= 90; k++) {
      double t = pow(10.0, k / 10.0);
      assert_ok(ball_segment_eval(&m, &seg, t, &s));
      assert_true(isfinite(s.position.x) && isfinite(s.position.y) && isfinite(s.position.z));
      assert_true(isfinite(s.velocity.x) && isfinite(s.velocity.y) && isfinite(s.velocity.z));
      assert_true(isfinite(s.spin.x) && isfinite(s.spin.y) && isfinite(s.spin.z));
    }
  }
  /* t = 1e9 with b = 1 s: the horizontal distance is exactly v0 b; y is the parabola */
  m.air_friction = 1.0;
  assert_ok(ball_segment_eval(&m, &seg, 1e9, &s));
  assert_near(s.position.x, 1.0 + 4.0, TOL);
  assert_rel(s.position.y, 2.0 + 3e9 - 0.5 * 9.81 * 1e18, 1e-15);
}

/* eq 4: S(t) = S0 sDamp / (sDamp + t): sDamp = 2 s, t = 1 s gives S0 * 2/3. */
static void eq4_spin_air_damping_sdamp2_t1_is_two_thirds(void **state) {
  ball_model m;
  ball_segment seg = hand_segment(0.0);
  ball_state s;
  (void)state;
  core_model_free(&m);
  m.effects |= BALL_EFFECT_SPIN;
  m.spin_damping = 2.0;
  assert_ok(ball_segment_eval(&m, &seg, 1.0, &s));
  assert_near(s.spin.z, 5.0 * 2.0 / 3.0, 1e-15);
  assert_true(s.spin.x == 0.0 && s.spin.y == 0.0);
  /* t = 6 s: 2 / 8 = 1/4 */
  assert_ok(ball_segment_eval(&m, &seg, 6.0, &s));
  assert_near(s.spin.z, 1.25, 1e-15);
  /* the flight itself does not depend on spin (the paper's spin acts at collisions) */
  assert_near(s.position.x, 1.0 + 4.0 * 2.0 * (1.0 - exp(-3.0)), TOL);
}

/* Time to the floor height 0: 2 + 3 t - 4.905 t^2 = 0 -> t = 1.0138126546049068. */
static void eq3_time_to_height_matches_quadratic_roots(void **state) {
  ball_model m;
  ball_segment seg = hand_segment(0.0);
  double t;
  (void)state;
  core_model_free(&m);
  assert_ok(ball_time_to_height(&m, &seg, 0.0, 0.0, &t));
  assert_near(t, 1.0138126546049068, TOL);
  /* y = 2.3 twice: rising at 0.12592732513941599, falling at 0.48569346996761765 */
  assert_ok(ball_time_to_height(&m, &seg, 0.0, 2.3, &t));
  assert_near(t, 0.12592732513941599, TOL);
  assert_ok(ball_time_to_height(&m, &seg, 0.2, 2.3, &t));
  assert_near(t, 0.48569346996761765, TOL);
  /* above the apex (2.4587 m): never */
  t = -1.0;
  assert_int_equal(ball_time_to_height(&m, &seg, 0.0, 2.5, &t), BALL_ENOTFOUND);
  assert_true(t == -1.0);
  /* both crossings already past */
  assert_int_equal(ball_time_to_height(&m, &seg, 0.6, 2.3, &t), BALL_ENOTFOUND);
  /* a later segment start shifts the answer by t0 */
  seg.t0 = 5.0;
  assert_ok(ball_time_to_height(&m, &seg, 5.0, 0.0, &t));
  assert_near(t, 5.0 + 1.0138126546049068, TOL);
}

/* Plane x = 3 from x0 = 1 at 4 m/s, b = 2 s: 2 (1 - e^(-t/2)) = 0.5 ->
 * t = 2 ln(4/3) = 0.57536414490356185; reach limit x0 + v0 b = 9 m. */
static void eq3_time_to_plane_inverts_the_exponential(void **state) {
  ball_model m;
  ball_segment seg = hand_segment(0.0);
  double t = -1.0;
  (void)state;
  core_model_free(&m);
  assert_ok(ball_time_to_plane(&m, &seg, 0.0, 0, 3.0, &t));
  assert_near(t, 0.57536414490356185, TOL);
  /* z plane: z0 = -1 at -2 m/s to z = -2 is the same distance fraction */
  assert_ok(ball_time_to_plane(&m, &seg, 0.0, 2, -2.0, &t));
  assert_near(t, 0.57536414490356185, TOL);
  /* x = 8.99, just short of the 9 m limit: t = -2 ln(1 - 7.99 / 8) = 13.369223455335855 */
  assert_ok(ball_time_to_plane(&m, &seg, 0.0, 0, 8.99, &t));
  assert_near(t, 13.369223455335855, 1e-9);
  /* drag stops the ball short of x = 9.5 (and of x = 9, reached only at t = inf) */
  t = -1.0;
  assert_int_equal(ball_time_to_plane(&m, &seg, 0.0, 0, 9.5, &t), BALL_ENOTFOUND);
  assert_int_equal(ball_time_to_plane(&m, &seg, 0.0, 0, 9.0, &t), BALL_ENOTFOUND);
  /* behind the ball */
  assert_int_equal(ball_time_to_plane(&m, &seg, 0.0, 0, 0.5, &t), BALL_ENOTFOUND);
  assert_true(t == -1.0);
  /* without drag: exactly distance / speed */
  m.air_friction = 0.0;
  assert_ok(ball_time_to_plane(&m, &seg, 0.0, 0, 3.0, &t));
  assert_true(t == 0.5);
  assert_ok(ball_time_to_plane(&m, &seg, 0.0, 0, 9.5, &t));
  assert_true(t == 2.125);
}

/* Next floor contact: t = 1.0138126546049068, x = 1 + 8 (1 - e^(-t/2)). */
static void eq3_next_floor_contact_time_and_point(void **state) {
  ball_model m;
  ball_segment seg = hand_segment(0.0);
  double t;
  ball_vec3 p;
  (void)state;
  core_model_free(&m);
  assert_ok(ball_next_floor_contact(&m, &seg, 0.0, &t, &p));
  assert_near(t, 1.0138126546049068, TOL);
  assert_near(p.x, 4.1811504626412577, TOL);
  assert_true(p.y == 0.0);
  assert_near(p.z, -2.5905752313206288, TOL);
  /* radius 0.1: the centre meets the floor at y = 0.1: 1.9 + 3 t - 4.905 t^2 = 0 */
  m.radius = 0.1;
  assert_ok(ball_next_floor_contact(&m, &seg, 0.0, &t, &p));
  assert_near(t, 0.99926539692475310, TOL);
  assert_true(p.y == 0.1);
  /* floor level 0.5 and radius 0.1: centre at 0.6 */
  m.floor_level = 0.5;
  assert_ok(ball_next_floor_contact(&m, &seg, 0.0, &t, &p));
  assert_true(p.y == 0.6);
  /* a sliding (grounded) ball has no next contact */
  seg.grounded = 1;
  assert_int_equal(ball_next_floor_contact(&m, &seg, 0.0, &t, &p), BALL_ENOTFOUND);
}

/* Apex: vy = 0 at t = 3 / 9.81 = 0.30581039755351682, y = 2 + 9 / 19.62. */
static void eq3_apex_of_a_rising_and_a_falling_segment(void **state) {
  ball_model m;
  ball_segment seg = hand_segment(0.0);
  double t;
  ball_vec3 p;
  (void)state;
  core_model_free(&m);
  assert_ok(ball_apex(&m, &seg, &t, &p));
  assert_near(t, 0.30581039755351682, TOL);
  assert_near(p.y, 2.4587155963302752, TOL);
  assert_near(p.x, 2.1343113806802726, TOL);
  /* a falling segment's apex is its start */
  seg.v0.y = -1.0;
  seg.t0 = 4.0;
  assert_ok(ball_apex(&m, &seg, &t, &p));
  assert_true(t == 4.0);
  assert_true(p.x == 1.0 && p.y == 2.0 && p.z == -1.0);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(eq3_position_and_velocity_match_hand_values_b2_t1),
      cmocka_unit_test(eq3_uses_time_since_segment_start),
      cmocka_unit_test(eq3_beta_zero_is_exactly_the_parabola),
      cmocka_unit_test(eq3_huge_b_has_no_cancellation_matches_series),
      cmocka_unit_test(eq3_tiny_b_stops_at_v0_times_b),
      cmocka_unit_test(eq3_state_is_finite_for_every_t_up_to_1e9),
      cmocka_unit_test(eq4_spin_air_damping_sdamp2_t1_is_two_thirds),
      cmocka_unit_test(eq3_time_to_height_matches_quadratic_roots),
      cmocka_unit_test(eq3_time_to_plane_inverts_the_exponential),
      cmocka_unit_test(eq3_next_floor_contact_time_and_point),
      cmocka_unit_test(eq3_apex_of_a_rising_and_a_falling_segment),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
