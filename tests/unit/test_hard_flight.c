/* Hard cases of flight and time (docs/hard-cases.md, sections 1-3): air
 * friction beta = 0 / tiny / huge, sim times up to 1e9 s, frame times from
 * 1e-9 s to 10 s and 0, speeds 0 / 1e-300 / subnormal / 1e6 m/s, positions
 * up to 1e7 m. Each test asserts numbers computed by hand or an invariant. */
#include <float.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "core_common.h"

/* A model with only the effects asked for, the exact scheme, a point ball. */
static void plain_model(ball_model *m, unsigned effects) {
  ball_model_default(m);
  m->effects = effects;
  m->scheme = BALL_SCHEME_EXACT;
}

static ball_segment segment(ball_vec3 p0, ball_vec3 v0) {
  return core_segment(0.0, p0, v0, ball_v3(0.0, 0.0, 0.0));
}

/* Restarts the ball at p moving at v at the sim's current time. */
static void restart(ball_sim *sim, ball_vec3 p, ball_vec3 v) {
  ball_state st;
  st.position = p;
  st.velocity = v;
  st.spin = ball_v3(0.0, 0.0, 0.0);
  assert_int_equal(ball_sim_set_state(sim, &st), BALL_OK);
}

static void state_of(const ball_sim *sim, ball_state *st) {
  assert_int_equal(ball_sim_state(sim, st), BALL_OK);
  assert_finite3(st->position);
  assert_finite3(st->velocity);
  assert_finite3(st->spin);
}

/* ---- beta ------------------------------------------------------------- */

/* eq 3 with b infinite: x = X0 + V0x t exactly; the plane time is distance / speed. */
static void test_beta_zero_gives_straight_line_eq3(void **state) {
  ball_model m;
  ball_segment s = segment(ball_v3(1.0, 2.0, 3.0), ball_v3(4.0, 5.0, 6.0));
  ball_state out;
  double t;
  (void)state;
  plain_model(&m, BALL_EFFECT_DRAG);
  m.air_friction = 0.0;
  assert_int_equal(ball_segment_eval(&m, &s, 2.0, &out), BALL_OK);
  assert_near(out.position.x, 9.0, 0.0);
  assert_near(out.position.z, 15.0, 0.0);
  assert_near(out.velocity.x, 4.0, 0.0);
  assert_near(out.position.y, 2.0 + 10.0 - 0.5 * 9.81 * 4.0, 1e-15);
  assert_int_equal(ball_time_to_plane(&m, &s, 0.0, 0, 21.0, &t), BALL_OK);
  assert_near(t, 5.0, 0.0);
}

/* eq 3 with b = m / beta ~ 5.7e298 (beta = 1e-300): 1 - e^(-t/b) cancels to 0
 * if computed naively; -b expm1(-t/b) must give t to the last bit or so. A
 * subnormal beta makes b overflow to +Inf: the same straight line. */
static void test_beta_tiny_matches_no_drag_without_cancellation_eq3(void **state) {
  static const double betas[] = {1e-300, 4.9406564584124654e-324, 1e-18};
  ball_model m;
  ball_segment s = segment(ball_v3(1.0, 2.0, 3.0), ball_v3(4.0, 5.0, 6.0));
  ball_state out;
  size_t i;
  (void)state;
  plain_model(&m, BALL_EFFECT_DRAG);
  for (i = 0; i < sizeof betas / sizeof betas[0]; i++) {
    double t;
    m.air_friction = betas[i];
    assert_int_equal(ball_model_check(&m, NULL), BALL_OK);
    assert_int_equal(ball_segment_eval(&m, &s, 2.0, &out), BALL_OK);
    /* b >= 5.7e16: the drag term t^2 / (2b) is below 4e-17 m: x = 9 to 1e-14 */
    assert_near(out.position.x, 9.0, 1e-14);
    assert_near(out.position.z, 15.0, 1e-14);
    assert_near(out.velocity.x, 4.0, 1e-15);
    assert_int_equal(ball_time_to_plane(&m, &s, 0.0, 0, 21.0, &t), BALL_OK);
    assert_near(t, 5.0, 1e-13);
  }
}

/* eq 3 with b -> 0 (beta = 1e300, beta = DBL_MAX, and mass subnormal so that
 * b underflows to exactly 0): the ball stops at once, x moves by V0x b at
 * most, the horizontal velocity is 0, and a plane 1 m ahead is never reached. */
static void test_beta_huge_stops_ball_at_once_eq3(void **state) {
  ball_model m;
  ball_segment s = segment(ball_v3(1.0, 2.0, 3.0), ball_v3(4.0, 5.0, 6.0));
  ball_state out;
  double t;
  int k;
  (void)state;
  plain_model(&m, BALL_EFFECT_DRAG);
  for (k = 0; k < 3; k++) {
    if (k == 0) m.air_friction = 1e300;
    if (k == 1) m.air_friction = DBL_MAX;
    if (k == 2) {
      m.air_friction = 1e10;
      m.mass = 4.9406564584124654e-324; /* b = m / beta = 0 exactly */
    }
    assert_int_equal(ball_segment_eval(&m, &s, 1.0, &out), BALL_OK);
    assert_finite3(out.position);
    assert_finite3(out.velocity);
    assert_near(out.position.x, 1.0, 1e-299);
    assert_near(out.position.z, 3.0, 1e-299);
    assert_near(out.velocity.x, 0.0, 0.0);
    assert_near(out.position.y, 2.0 + 5.0 - 0.5 * 9.81, 1e-15); /* vertical: no drag (eq 1) */
    assert_int_equal(ball_segment_eval(&m, &s, 0.0, &out), BALL_OK);
    assert_near(out.velocity.x, 4.0, 0.0); /* t = 0: V0 itself, no 0 / 0 */
    assert_int_equal(ball_time_to_plane(&m, &s, 0.0, 0, 2.0, &t), BALL_ENOTFOUND);
  }
}

/* A sim with beta huge: a ball thrown at the net drops straight down where it
 * is: one floor event at x0, no net event. */
static void test_beta_huge_ball_drops_in_place(void **state) {
  ball_model m;
  ball_sim sim;
  ball_event log[64];
  steps_tally t;
  int i;
  (void)state;
  plain_model(&m, BALL_EFFECT_DRAG | BALL_EFFECT_FLOOR | BALL_EFFECT_NET);
  m.air_friction = 1e300;
  core_start(&m, &sim, ball_v3(11.0, 0.5, 3.0), ball_v3(30.0, 0.0, 0.0));
  steps_begin(&t, log, 64);
  steps_run(&sim, 1.0 / 60.0, 60, &t);
  for (i = 0; i < t.total; i++) {
    assert_int_equal(log[i].kind, BALL_EVENT_FLOOR);
    assert_near(log[i].point.x, 11.0, 1e-12);
  }
  assert_true(t.kind[BALL_EVENT_FLOOR] >= 1);
}

/* ---- time ------------------------------------------------------------- */

/* eq 3 and eq 4 at t = 1e9 s: the horizontal part reaches its limit X0 + V0x b,
 * the vertical part is -4.9e18 m, spin is S0 sDamp / (sDamp + t): all finite. */
static void test_time_1e9_on_a_segment_is_finite_eq3_eq4(void **state) {
  ball_model m;
  ball_segment s = segment(ball_v3(1.0, 2.0, 3.0), ball_v3(4.0, 5.0, 6.0));
  ball_state out;
  double b, t;
  (void)state;
  plain_model(&m, BALL_EFFECT_DRAG | BALL_EFFECT_SPIN);
  s.s0 = ball_v3(10.0, 0.0, 0.0);
  b = m.mass / m.air_friction;
  assert_int_equal(ball_segment_eval(&m, &s, 1e9, &out), BALL_OK);
  assert_finite3(out.position);
  assert_finite3(out.velocity);
  assert_near(out.position.x, 1.0 + 4.0 * b, 1e-12);
  assert_near(out.position.z, 3.0 + 6.0 * b, 1e-12);
  assert_near(out.velocity.x, 0.0, 0.0);
  assert_near(out.position.y, 2.0 + 5e9 - 0.5 * 9.81 * 1e18, 1e3); /* 1e3 m of 4.9e18: 2e-16 relative */
  assert_near(out.spin.x, 10.0 * 2.0 / (2.0 + 1e9), 1e-20);
  /* the plane the ball would need 1e9 s for is beyond its drag limit */
  assert_int_equal(ball_time_to_plane(&m, &s, 1e9, 0, 1.0 + 5.0 * b, &t), BALL_ENOTFOUND);
}

/* One exact step of 1e9 s of the default serve: every bounce resolved, the
 * ball ends at rest on the floor exactly where 600 frames of 1/60 s and one
 * step of the remaining time put it (eq 5: frame-rate independence). After
 * that, frames at 1/60 s on a clock at 1e9 s (ulp 1.2e-7 s) give no events
 * and the ball stays exactly on the floor. */
static void test_step_of_1e9_seconds_matches_small_frames_eq5(void **state) {
  ball_model m;
  ball_sim a, b;
  ball_state sa, sb;
  ball_event ev[BALL_MAX_CONTACTS];
  steps_tally t;
  int n;
  (void)state;
  ball_model_default(&m);
  assert_int_equal(ball_sim_init(&a, &m), BALL_OK);
  assert_int_equal(ball_sim_init(&b, &m), BALL_OK);
  assert_int_equal(ball_step(&a, 1e9, ev, BALL_MAX_CONTACTS, &n), BALL_OK);
  assert_true(n >= 3);
  assert_int_equal(a.warnings[BALL_WARN_CONTACT_LIMIT], 0);
  steps_run(&b, 1.0 / 60.0, 600, NULL);
  assert_int_equal(ball_step(&b, 1e9 - b.time, NULL, 0, NULL), BALL_OK);
  state_of(&a, &sa);
  state_of(&b, &sb);
  assert_int_equal(a.seg.grounded, 1);
  assert_near(sa.position.y, m.floor_level + m.radius, 0.0);
  assert_near(sa.position.x, sb.position.x, 1e-9);
  assert_near(sa.position.z, sb.position.z, 1e-9);
  assert_near(sa.velocity.x, 0.0, 0.0);
  steps_begin(&t, NULL, 0);
  steps_run(&a, 1.0 / 60.0, 600, &t);
  assert_int_equal(t.total, 0);
  state_of(&a, &sa);
  assert_near(sa.position.y, m.floor_level + m.radius, 0.0);
  assert_near(a.time, 1e9 + 10.0, 600 * 1.2e-7); /* each frame rounds to the clock's ulp */
}

/* A drop of 1 m started on a clock at 1e9 s: segments are relative to their
 * start (the paper's "time reset to zero"), so the landing point is exact and
 * the landing time (and with it the landing speed) is off by the clock's ulp
 * (1.2e-7 s) only. */
static void test_drop_on_a_clock_at_1e9_seconds_lands_exactly_eq3(void **state) {
  ball_model m;
  ball_sim sim;
  steps_tally t;
  (void)state;
  plain_model(&m, BALL_EFFECT_FLOOR);
  assert_int_equal(ball_sim_init(&sim, &m), BALL_OK);
  assert_int_equal(ball_step(&sim, 1e9, NULL, 0, NULL), BALL_OK);
  restart(&sim, ball_v3(2.0, 1.0, 3.0), ball_v3(0.0, 0.0, 0.0));
  steps_begin(&t, NULL, 0);
  steps_each(&sim, 1.0 / 60.0, 60, &t, steps_until_event, NULL);
  assert_true(t.total > 0);
  assert_near(t.first.time, 1e9 + sqrt(2.0 / 9.81), 2.4e-7);
  assert_near(t.first.point.x, 2.0, 0.0);
  assert_near(t.first.point.y, 0.0, 0.0);
  /* the contact time is rounded to the clock (ulp 1.2e-7 s) before the
   * velocity is evaluated: g * 2 ulp = 2.4e-6 m/s */
  assert_near(t.first.velocity_in.y, -sqrt(2.0 * 9.81), 2.4e-6);
}

/* ---- frame time ------------------------------------------------------- */

/* dt = 1e-9 s across a bounce: 4000 frames of 1e-9 s and one frame of 4e-6 s
 * give the same event and end state as the closed form: contact when
 * 1e-6 - tau - 4.905 tau^2 = 0, then V0y = 0.75 |vy| (eq 5). */
static void test_dt_of_1e_minus_9_seconds_resolves_a_bounce_like_one_frame_eq5(void **state) {
  ball_model m;
  ball_sim a, b;
  ball_state sa, sb;
  ball_event ev[4];
  steps_tally t;
  int n;
  double tc, vin, y_end;
  (void)state;
  plain_model(&m, BALL_EFFECT_FLOOR);
  m.bounce_threshold = 0.1;
  core_start(&m, &a, ball_v3(0.0, 1e-6, 0.0), ball_v3(0.0, -1.0, 0.0));
  core_start(&m, &b, ball_v3(0.0, 1e-6, 0.0), ball_v3(0.0, -1.0, 0.0));
  tc = (-1.0 + sqrt(1.0 + 2.0 * 9.81 * 1e-6)) / 9.81; /* ~9.99990e-7 s */
  vin = -1.0 - 9.81 * tc;
  steps_begin(&t, NULL, 0);
  steps_run(&a, 1e-9, 4000, &t);
  assert_int_equal(t.total, 1);
  assert_near(t.first.time, tc, 1e-15);
  assert_near(t.first.velocity_out.y, -0.75 * vin, 1e-12);
  assert_int_equal(ball_step(&b, 4000 * 1e-9, ev, 4, &n), BALL_OK);
  assert_int_equal(n, 1);
  assert_near(ev[0].time, tc, 1e-15);
  state_of(&a, &sa);
  state_of(&b, &sb);
  y_end = -0.75 * vin * (4e-6 - tc) - 0.5 * 9.81 * (4e-6 - tc) * (4e-6 - tc);
  assert_near(sa.position.y, y_end, 1e-15);
  assert_near(sb.position.y, y_end, 1e-15);
  assert_near(sa.velocity.y, sb.velocity.y, 1e-12);
}

/* dt = 10 s in the exact scheme: the default serve (drag, spin, floor, net)
 * ends where 600 frames of 1/60 s put it, to 1e-9 m. */
static void test_dt_10_seconds_exact_matches_64_hz(void **state) {
  ball_model m;
  ball_sim a, b;
  ball_state sa, sb;
  (void)state;
  ball_model_default(&m);
  m.initial_spin = ball_v3(0.0, 0.0, -20.0);
  assert_int_equal(ball_sim_init(&a, &m), BALL_OK);
  assert_int_equal(ball_sim_init(&b, &m), BALL_OK);
  assert_int_equal(ball_step(&a, 10.0, NULL, 0, NULL), BALL_OK);
  steps_run(&b, 1.0 / 64.0, 640, NULL);
  assert_true(b.time == 10.0);
  state_of(&a, &sa);
  state_of(&b, &sb);
  assert_near(sa.position.x, sb.position.x, 1e-9);
  assert_near(sa.position.y, sb.position.y, 1e-9);
  assert_near(sa.position.z, sb.position.z, 1e-9);
  assert_near(sa.velocity.x, sb.velocity.x, 1e-9);
}

/* dt = 10 s in the sampled scheme (the paper's Fig. 1 test): the ball is 490 m
 * below the floor at the frame's end; it is snapped to the floor (eq 5) and
 * leaves with V0y = 0.75 * 98.1 m/s: finite, never below the floor. */
static void test_dt_10_seconds_sampled_snaps_to_floor_eq5(void **state) {
  ball_model m;
  ball_sim sim;
  ball_event ev[4];
  steps_box above = steps_anywhere();
  int n;
  (void)state;
  plain_model(&m, BALL_EFFECT_FLOOR);
  m.scheme = BALL_SCHEME_SAMPLED;
  m.bounce_threshold = 0.0;
  core_start(&m, &sim, ball_v3(0.0, 0.0, 0.0), ball_v3(1.0, 0.0, 0.0));
  assert_int_equal(ball_step(&sim, 10.0, ev, 4, &n), BALL_OK);
  assert_int_equal(n, 1);
  assert_near(ev[0].velocity_in.y, -98.1, 1e-12);
  assert_near(ev[0].velocity_out.y, 0.75 * 98.1, 1e-12);
  assert_near(ev[0].point.y, 0.0, 0.0);
  above.lo.y = 0.0;
  steps_each(&sim, 10.0, 100, NULL, steps_in_box, &above);
}

/* dt = 0 and dt = -0: a no-op, byte for byte, no events. */
static void test_dt_zero_leaves_sim_unchanged(void **state) {
  ball_model m;
  ball_sim sim, copy;
  ball_event ev[4];
  int n = 7;
  (void)state;
  ball_model_default(&m);
  assert_int_equal(ball_sim_init(&sim, &m), BALL_OK);
  assert_int_equal(ball_step(&sim, 0.3, NULL, 0, NULL), BALL_OK);
  copy = sim;
  assert_int_equal(ball_step(&sim, 0.0, ev, 4, &n), BALL_OK);
  assert_int_equal(n, 0);
  assert_memory_equal(&sim, &copy, sizeof sim);
  assert_int_equal(ball_step(&sim, -0.0, ev, 4, &n), BALL_OK);
  assert_memory_equal(&sim, &copy, sizeof sim);
}

/* Bad frame times are rejected with their status and change nothing. */
static void test_bad_dt_is_rejected_and_changes_nothing(void **state) {
  static const double bad[] = {-1e-300, -4.9406564584124654e-324, -1.0, -DBL_MAX};
  ball_model m;
  ball_sim sim, copy;
  size_t i;
  (void)state;
  ball_model_default(&m);
  assert_int_equal(ball_sim_init(&sim, &m), BALL_OK);
  copy = sim;
  assert_int_equal(ball_step(&sim, NAN, NULL, 0, NULL), BALL_ENONFINITE);
  assert_int_equal(ball_step(&sim, INFINITY, NULL, 0, NULL), BALL_ENONFINITE);
  assert_int_equal(ball_step(&sim, -INFINITY, NULL, 0, NULL), BALL_ENONFINITE);
  for (i = 0; i < sizeof bad / sizeof bad[0]; i++)
    assert_int_equal(ball_step(&sim, bad[i], NULL, 0, NULL), BALL_ERANGE);
  assert_memory_equal(&sim, &copy, sizeof sim);
}

/* A subnormal dt: on a clock at 0 it advances the clock by 4.9e-324 s; on a
 * clock at 1 s it is absorbed. Either way the frame counts and nothing else
 * moves. */
static void test_subnormal_dt_is_harmless(void **state) {
  ball_model m;
  ball_sim sim;
  ball_state before, after;
  (void)state;
  ball_model_default(&m);
  assert_int_equal(ball_sim_init(&sim, &m), BALL_OK);
  state_of(&sim, &before);
  assert_int_equal(ball_step(&sim, 4.9406564584124654e-324, NULL, 0, NULL), BALL_OK);
  assert_true(sim.time > 0.0 && sim.time < 1e-300);
  state_of(&sim, &after);
  assert_near(after.position.x, before.position.x, 1e-300);
  assert_int_equal(ball_step(&sim, 1.0 - sim.time, NULL, 0, NULL), BALL_OK);
  state_of(&sim, &before);
  assert_int_equal(ball_step(&sim, 4.9406564584124654e-324, NULL, 0, NULL), BALL_OK);
  state_of(&sim, &after);
  assert_memory_equal(&before, &after, sizeof before);
  assert_int_equal(sim.frame, 3);
}

/* A frame so long that the free fall overflows (no floor: y = -g t^2 / 2 =
 * -Inf at t = 1e200 s): the step either refuses it (status, sim unchanged) or
 * ends with a finite state. It must not accept it and leave -Inf behind. */
static void test_overflowing_frame_is_refused_or_finite(void **state) {
  ball_model m;
  ball_sim sim, copy;
  ball_status st;
  ball_state out;
  (void)state;
  plain_model(&m, BALL_EFFECT_DRAG);
  assert_int_equal(ball_sim_init(&sim, &m), BALL_OK);
  copy = sim;
  st = ball_step(&sim, 1e200, NULL, 0, NULL);
  if (st == BALL_OK) {
    state_of(&sim, &out);
    assert_finite3(sim.prev_position);
  } else {
    assert_memory_equal(&sim, &copy, sizeof sim);
  }
}

/* A bounce that overflowed (found by fuzz_sim): velocity and spin near
 * DBL_MAX; eq 5 damps the velocity by 0.75 but eq 13 adds 0.8 * S x n, so
 * V0z = 0.75 * (-DBL_MAX) + 0.8 * (-DBL_MAX) = -Inf. Such a state is outside
 * the world the library handles now (BALL_MAX_SPEED): ball_sim_set_state
 * refuses it with BALL_ERANGE and the sim is byte for byte as it was. At the
 * limit itself the same shot bounces normally, finite; and the step's own
 * guard (a response that overflows refuses the frame) stays for states a
 * very long flight could reach. */
static void test_overflowing_bounce_is_refused_unchanged_eq5_eq13(void **state) {
  ball_model m;
  ball_sim sim, copy;
  ball_state s0;
  ball_event ev[8];
  int n = 7;
  (void)state;
  ball_model_default(&m);
  assert_int_equal(ball_sim_init(&sim, &m), BALL_OK);
  s0.position = ball_v3(0.0, 1e-4, 3.0);
  s0.velocity = ball_v3(0.0, -DBL_MAX, -DBL_MAX);
  s0.spin = ball_v3(-DBL_MAX, 0.0, 0.0);
  copy = sim;
  assert_int_equal(ball_sim_set_state(&sim, &s0), BALL_ERANGE);
  assert_memory_equal(&sim, &copy, sizeof sim);
  s0.velocity = ball_v3(0.0, -BALL_MAX_SPEED, nextafter(-BALL_MAX_SPEED, -INFINITY));
  assert_int_equal(ball_sim_set_state(&sim, &s0), BALL_ERANGE);
  /* at the limit: bounces, finite, eq 5 and eq 13 by hand */
  s0.velocity = ball_v3(0.0, -BALL_MAX_SPEED, -BALL_MAX_SPEED);
  s0.spin = ball_v3(-BALL_MAX_SPEED, 0.0, 0.0);
  assert_int_equal(ball_sim_set_state(&sim, &s0), BALL_OK);
  assert_int_equal(ball_step(&sim, 1e-9, ev, 8, &n), BALL_OK);
  assert_int_equal(n, 1);
  assert_true(isfinite(ev[0].velocity_out.z) && ev[0].velocity_out.z < -1e7);
  assert_near(ev[0].velocity_out.y, 0.75 * ev[0].velocity_in.y * -1.0, 1e-6 * 1e7);
}

/* ---- speeds ----------------------------------------------------------- */

/* Speed 0: a dropped ball falls straight, x and z exactly unchanged, and hits
 * the floor after sqrt(2 h / g) (eq 3, eq 5). */
static void test_speed_zero_drops_straight_eq3(void **state) {
  ball_model m;
  ball_sim sim;
  ball_event ev[4];
  int n;
  (void)state;
  ball_model_default(&m);
  core_start(&m, &sim, ball_v3(3.0, 2.0, 4.0), ball_v3(0.0, 0.0, 0.0));
  assert_int_equal(ball_step(&sim, 1.0, ev, 4, &n), BALL_OK);
  assert_true(n >= 1);
  assert_near(ev[0].time, sqrt(4.0 / 9.81), 1e-15);
  assert_near(ev[0].point.x, 3.0, 0.0);
  assert_near(ev[0].point.z, 4.0, 0.0);
}

/* Speeds 1e-300 and 4.9e-324 (subnormal) toward a net 0.885 m away: drag
 * stops the ball after V0x b (~1e-300 m): no net event, nothing non-finite;
 * without drag the crossing would take 1e300 s or more, beyond any frame. */
static void test_speed_1e300_and_subnormal_never_reach_the_net_eq3(void **state) {
  static const double speeds[] = {1e-300, 4.9406564584124654e-324};
  ball_model m;
  size_t i;
  int drag;
  (void)state;
  for (drag = 0; drag < 2; drag++)
    for (i = 0; i < sizeof speeds / sizeof speeds[0]; i++) {
      ball_sim sim;
      ball_state st;
      steps_tally t;
      plain_model(&m, BALL_EFFECT_NET | BALL_EFFECT_FLOOR | (drag ? BALL_EFFECT_DRAG : 0u));
      core_start(&m, &sim, ball_v3(11.0, 0.0, 3.0), ball_v3(speeds[i], 0.0, speeds[i]));
      steps_begin(&t, NULL, 0);
      steps_run(&sim, 1.0 / 60.0, 120, &t);
      steps_run(&sim, 1e6, 1, &t);
      assert_int_equal(t.kind[BALL_EVENT_FLOOR], t.total); /* settling */
      state_of(&sim, &st);
      assert_near(st.position.x, 11.0, 1e-290);
      assert_true(st.velocity.x >= 0.0);
    }
}

/* 1e6 m/s at a net 0.885 m ahead: the exact scheme finds the contact at
 * tau = -b log(1 - u / b), u = 0.885 / 1e6 (eq 3 inverted); the sampled
 * scheme (a segment test, Fig. 3) catches it in a 16 km frame. Both end the
 * frame on the near side. */
static void test_speed_1e6_does_not_tunnel_through_the_net_fig3(void **state) {
  ball_model m;
  ball_sim sim;
  ball_event log[64];
  steps_tally t;
  steps_box near_side = steps_anywhere();
  int i;
  ball_model_default(&m);
  m.scheme = test_scheme(state);
  m.radius = 0.033;
  core_start(&m, &sim, ball_v3(11.0, 0.5, 3.0), ball_v3(1e6, 0.0, 0.0));
  near_side.hi.x = 11.885 - 0.033 + 1e-9;
  steps_begin(&t, log, 64);
  steps_each(&sim, 1.0 / 60.0, 30, &t, steps_in_box, &near_side);
  assert_int_equal(t.kind[BALL_EVENT_NET], 1);
  for (i = 0; i < t.total; i++)
    if (log[i].kind == BALL_EVENT_NET && m.scheme == BALL_SCHEME_EXACT) {
      double b = m.mass / m.air_friction, u = (11.885 - 0.033 - 11.0) / 1e6;
      assert_near(log[i].time, -b * log1p(-u / b), 1e-15);
      assert_near(log[i].velocity_out.x, -0.2 * 1e6 * (1.0 - u / b), 1e-3);
    }
}

/* 1e6 m/s straight up: apex 1e12 / (2 g) = 5.1e10 m, back on the floor after
 * 2e6 / g = 203873.6 s arriving at -1e6 m/s (eq 3, eq 5). */
static void test_speed_1e6_upward_returns_eq3(void **state) {
  ball_model m;
  ball_sim sim;
  ball_event ev[4];
  double t_apex;
  ball_vec3 apex;
  int n;
  (void)state;
  plain_model(&m, BALL_EFFECT_FLOOR);
  core_start(&m, &sim, ball_v3(0.0, 0.0, 0.0), ball_v3(0.0, 1e6, 0.0));
  assert_int_equal(ball_apex(&m, &sim.seg, &t_apex, &apex), BALL_OK);
  assert_near(apex.y, 1e12 / (2.0 * 9.81), 1e-4);
  assert_int_equal(ball_step(&sim, 3e5, ev, 4, &n), BALL_OK);
  assert_int_equal(n, 1);
  assert_near(ev[0].time, 2e6 / 9.81, 1e-9);
  assert_near(ev[0].velocity_in.y, -1e6, 1e-6);
  assert_near(ev[0].velocity_out.y, 0.75e6, 1e-6);
}

/* ---- positions -------------------------------------------------------- */

/* A box 2 m wide at x = z = 1e7 m, floor at y = 1e7 m (ulp 1.9e-9 m), no
 * drag, all dampings 1: 100 s at 60 Hz, the ball never ends a frame outside
 * the box or below the floor by more than 1e-8 m (a few ulps), and the
 * energy vy^2 / 2 + g y is kept to 1e-6 relative of its kinetic part. */
static void test_positions_at_1e7_metres_stay_in_their_box(void **state) {
  const double c = 1e7, r = 0.1, tol = 1e-8;
  ball_model m;
  ball_plane w;
  ball_sim sim;
  ball_state st;
  int f, events = 0, n, k;
  double e0 = 0.0;
  (void)state;
  plain_model(&m, BALL_EFFECT_FLOOR | BALL_EFFECT_WALLS);
  m.radius = r;
  m.floor_level = c;
  m.floor_damping = 1.0;
  m.bounce_threshold = 0.0;
  for (k = 0; k < 4; k++) {
    w.axis = k < 2 ? 0 : 2;
    w.position = c + (k % 2 ? 1.0 : -1.0);
    w.lo = c - 2.0;
    w.hi = c + 2.0;
    w.bottom = c - 1.0;
    w.top = c + 100.0;
    w.damping = 1.0;
    assert_int_equal(ball_model_add_wall(&m, &w), BALL_OK);
  }
  core_start(&m, &sim, ball_v3(c, c + 1.0, c), ball_v3(3.0, 0.0, 2.5));
  for (f = 0; f < 6000; f++) {
    ball_event ev[16];
    assert_int_equal(ball_step(&sim, 1.0 / 60.0, ev, 16, &n), BALL_OK);
    events += n;
    state_of(&sim, &st);
    assert_true(st.position.x >= c - 1.0 + r - tol && st.position.x <= c + 1.0 - r + tol);
    assert_true(st.position.z >= c - 1.0 + r - tol && st.position.z <= c + 1.0 - r + tol);
    assert_true(st.position.y >= c + r - tol);
    if (f == 0) e0 = 0.5 * st.velocity.y * st.velocity.y + 9.81 * (st.position.y - c);
    assert_near(0.5 * st.velocity.y * st.velocity.y + 9.81 * (st.position.y - c), e0, 1e-6 * e0);
  }
  assert_true(events > 100);
  assert_int_equal(sim.warnings[BALL_WARN_CONTACT_LIMIT], 0);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_beta_zero_gives_straight_line_eq3),
      cmocka_unit_test(test_beta_tiny_matches_no_drag_without_cancellation_eq3),
      cmocka_unit_test(test_beta_huge_stops_ball_at_once_eq3),
      cmocka_unit_test(test_beta_huge_ball_drops_in_place),
      cmocka_unit_test(test_time_1e9_on_a_segment_is_finite_eq3_eq4),
      cmocka_unit_test(test_step_of_1e9_seconds_matches_small_frames_eq5),
      cmocka_unit_test(test_drop_on_a_clock_at_1e9_seconds_lands_exactly_eq3),
      cmocka_unit_test(test_dt_of_1e_minus_9_seconds_resolves_a_bounce_like_one_frame_eq5),
      cmocka_unit_test(test_dt_10_seconds_exact_matches_64_hz),
      cmocka_unit_test(test_dt_10_seconds_sampled_snaps_to_floor_eq5),
      cmocka_unit_test(test_dt_zero_leaves_sim_unchanged),
      cmocka_unit_test(test_bad_dt_is_rejected_and_changes_nothing),
      cmocka_unit_test(test_subnormal_dt_is_harmless),
      cmocka_unit_test(test_overflowing_frame_is_refused_or_finite),
      cmocka_unit_test(test_overflowing_bounce_is_refused_unchanged_eq5_eq13),
      cmocka_unit_test(test_speed_zero_drops_straight_eq3),
      cmocka_unit_test(test_speed_1e300_and_subnormal_never_reach_the_net_eq3),
      EACH_SCHEME(test_speed_1e6_does_not_tunnel_through_the_net_fig3),
      cmocka_unit_test(test_speed_1e6_upward_returns_eq3),
      cmocka_unit_test(test_positions_at_1e7_metres_stay_in_their_box),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
