/* The floor: eq 5 bounce, the bounce and sound thresholds (docs/design.md
 * R4: below bounce_threshold the ball stops bouncing and slides), spin at the floor
 * (eq 13, 14), and the resting ball.
 *
 * Hand case (the same as test_flight.c): b = 2 s, g = 9.81 m/s^2,
 * P0 = (1, 2, -1) m, V0 = (4, 3, -2) m/s, floorDamping 0.75. The floor is hit
 * at t = (3 + sqrt(9 + 4 g)) / g = 1.0138126546049068 s where
 * f = e^(-t/2) = 0.60235619216984279, so eq 5 gives
 *   V0' = (4 f 0.75, -(3 - g t) 0.75, -2 f 0.75)
 *       = (1.8070685765095284, 5.2091266062556015, -0.90353428825476419).
 * Tolerance 1e-12 (values O(10), a few roundings each). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "core_common.h"

#define TOL 1e-12

static void hand_model(ball_model *m) {
  core_model_free(m);
  m->floor_damping = 0.75;
  m->bounce_threshold = 0.3;
  m->sound_threshold = 0.5;
  m->effects |= BALL_EFFECT_SOUND;
  m->initial_position = ball_v3(1.0, 2.0, -1.0);
  m->initial_velocity = ball_v3(4.0, 3.0, -2.0);
}

/* Steps until the first frame with an event; returns it (fails unless
 * that frame has exactly one, within 10 s). */
static ball_event first_event(const ball_model *m, ball_sim *sim, double dt) {
  steps_tally t;
  assert_ok(ball_sim_init(sim, m));
  steps_begin(&t, NULL, 0);
  steps_each(sim, dt, (unsigned long)(10.0 / dt), &t, steps_until_event, NULL);
  assert_int_equal(t.total, 1);
  return t.first;
}

/* A callback (ctx: the model): the ball ends the frame resting or sliding
 * on the floor: no event, y exactly floor_level + radius, vy exactly 0,
 * the rest finite. */
static int on_the_floor(void *ctx, ball_sim *sim, const steps_tally *t, const ball_event *ev, int n) {
  const ball_model *m = ctx;
  const double floor_y = m->floor_level + m->radius;
  unsigned long f = t->frames - 1;
  ball_state s;
  (void)ev;
  if (n != 0) fail_msg("frame %lu on the floor: %d events", f, n);
  assert_ok(ball_sim_state(sim, &s));
  if (!(s.position.y == floor_y && s.velocity.y == 0.0 && isfinite(s.position.x) && isfinite(s.position.z) &&
        isfinite(s.velocity.x) && isfinite(s.velocity.z)))
    fail_msg("frame %lu on the floor: y = %.17g (floor %.17g), vy = %g", f, s.position.y, floor_y, s.velocity.y);
  return 1;
}

static void eq5_exact_bounce_velocity_damped_flipped_and_drag_decayed(void **state) {
  ball_model m;
  ball_sim sim;
  ball_event ev;
  (void)state;
  hand_model(&m);
  ev = first_event(&m, &sim, 1.0 / 60.0);
  assert_int_equal(ev.kind, BALL_EVENT_FLOOR);
  assert_near(ev.time, 1.0138126546049068, TOL);
  /* arriving: eq 3 velocity at the contact */
  assert_near(ev.velocity_in.x, 2.4094247686793712, TOL);
  assert_near(ev.velocity_in.y, -6.9455021416741353, TOL);
  assert_near(ev.velocity_in.z, -1.2047123843396856, TOL);
  /* eq 5: V0 = (Vx f fd, -(V0y - g t) fd, Vz f fd) */
  assert_near(ev.velocity_out.x, 1.8070685765095284, TOL);
  assert_near(ev.velocity_out.y, 5.2091266062556015, TOL);
  assert_near(ev.velocity_out.z, -0.90353428825476419, TOL);
  /* eq 5: P0 = (Px, floor_level, Pz) */
  assert_true(ev.point.y == 0.0);
  assert_near(ev.point.x, 4.1811504626412577, TOL);
  assert_near(ev.point.z, -2.5905752313206288, TOL);
  /* the new segment starts there, then (t reset to zero) */
  assert_true(sim.seg.t0 == ev.time);
  assert_true(memcmp(&sim.seg.p0, &ev.point, sizeof ev.point) == 0);
  assert_true(memcmp(&sim.seg.v0, &ev.velocity_out, sizeof ev.velocity_out) == 0);
  assert_int_equal(sim.seg.grounded, 0);
  /* 5.2 m/s > sound_threshold 0.5 */
  assert_int_equal(ev.sound, 1);
}

/* The paper's sampled test (Fig. 1): at dt = 0.1 s the ball is first below
 * the floor at the end of frame 11, t = 1.1 s, y = 5.3 - 4.905 * 1.21 =
 * -0.63505 m; eq 5 snaps P0 to the floor and uses the velocity then:
 * vy = 3 - 9.81 * 1.1 = -7.791 -> 5.84325 m/s. */
static void eq5_sampled_bounce_snaps_p0_to_floor_level(void **state) {
  ball_model m;
  ball_sim sim;
  ball_event ev;
  (void)state;
  hand_model(&m);
  m.scheme = BALL_SCHEME_SAMPLED;
  ev = first_event(&m, &sim, 0.1);
  assert_int_equal(ev.kind, BALL_EVENT_FLOOR);
  assert_int_equal(sim.frame, 11);
  assert_near(ev.time, 1.1, 1e-14);
  assert_true(ev.point.y == 0.0);
  assert_near(ev.point.x, 4.3844015169561064, TOL);
  assert_near(ev.point.z, -2.6922007584780532, TOL);
  assert_near(ev.velocity_in.y, -7.791, TOL);
  assert_near(ev.velocity_out.x, 1.7308494311414601, TOL);
  assert_near(ev.velocity_out.y, 5.84325, TOL);
  assert_near(ev.velocity_out.z, -0.86542471557073004, TOL);
}

/* Floor level and radius: the centre bounces at floor_level + radius. */
static void eq5_radius_puts_the_contact_at_floor_level_plus_radius(void **state) {
  ball_model m;
  ball_sim sim;
  ball_event ev;
  (void)state;
  hand_model(&m);
  m.floor_level = -0.5;
  m.radius = 0.1;
  /* the centre falls from 2 to -0.4: 2.4 + 3 t - 4.905 t^2 = 0 -> t = 1.0692346802020758 */
  ev = first_event(&m, &sim, 1.0 / 60.0);
  assert_true(ev.point.y == -0.5 + 0.1);
  assert_near(ev.time, 1.0692346802020758, TOL);
  m.scheme = BALL_SCHEME_SAMPLED;
  ev = first_event(&m, &sim, 0.25);
  assert_true(ev.point.y == -0.5 + 0.1);
}

/* Drop from h = 0.4905 m: impact after sqrt(0.1) s at 3.1021943846251801
 * m/s, out at 0.75 * that = 2.3266457884688851 m/s. Thresholds either side. */
static void drop_model(ball_model *m, double bounce_threshold, double sound_threshold) {
  hand_model(m);
  m->initial_position = ball_v3(0.0, 0.4905, 0.0);
  m->initial_velocity = ball_v3(1.5, 0.0, 0.0);
  m->bounce_threshold = bounce_threshold;
  m->sound_threshold = sound_threshold;
}

static void eq5_above_bounce_threshold_bounces_below_it_slides(void **state) {
  ball_model m;
  ball_sim sim;
  ball_event ev;
  ball_state s;
  (void)state;
  drop_model(&m, 2.3, 0.5); /* 2.3267 > 2.3: bounces */
  ev = first_event(&m, &sim, 1.0 / 60.0);
  assert_near(ev.time, 0.31622776601683793, TOL);
  assert_near(ev.velocity_out.y, 2.3266457884688851, TOL);
  assert_int_equal(sim.seg.grounded, 0);

  drop_model(&m, 2.4, 0.5); /* 2.3267 < 2.4: stops bouncing, slides */
  ev = first_event(&m, &sim, 1.0 / 60.0);
  assert_true(ev.velocity_out.y == 0.0);
  assert_int_equal(sim.seg.grounded, 1);
  /* sliding: y exactly the floor, vy 0, x by eq 3 from the contact (drag only) */
  assert_true(m.floor_level + m.radius == 0.0);
  steps_each(&sim, 1.0 / 60.0, 600, NULL, on_the_floor, &m);
  assert_ok(ball_sim_state(&sim, &s));
  {
    double tau = sim.time - ev.time;
    assert_near(s.position.x, ev.point.x + ev.velocity_out.x * 2.0 * (1.0 - exp(-tau / 2.0)), TOL);
    assert_near(s.velocity.x, ev.velocity_out.x * exp(-tau / 2.0), TOL);
  }
}

/* Sound: V0y above sound_threshold makes a sound, below does not; off with
 * the SOUND effect. */
static void eq5_sound_flag_above_sound_threshold_not_below(void **state) {
  ball_model m;
  ball_sim sim;
  ball_event ev;
  (void)state;
  drop_model(&m, 0.3, 2.3);
  ev = first_event(&m, &sim, 1.0 / 60.0);
  assert_int_equal(ev.sound, 1);
  drop_model(&m, 0.3, 2.4);
  ev = first_event(&m, &sim, 1.0 / 60.0);
  assert_int_equal(ev.sound, 0);
  drop_model(&m, 0.3, 2.3);
  m.effects &= ~(unsigned)BALL_EFFECT_SOUND;
  ev = first_event(&m, &sim, 1.0 / 60.0);
  assert_int_equal(ev.sound, 0);
}

/* eq 13, 14 at the floor (spin on): drop from 0.4905 m with S0 = (1, 0, 2),
 * no horizontal speed, sDamp = 2 s, spinFloorDamping 0.8. At the contact
 * (t = sqrt(0.1)) eq 4 gives S = S0 k, k = 2 / (2 + sqrt(0.1)) =
 * 0.86347294050418568; eq 13 adds 0.8 (S x (0, 1, 0)) = 0.8 k (-2, 0, 1) to
 * the velocity; eq 14 leaves the spin 0.8 S. */
static void eq13_eq14_spin_at_the_floor_adds_velocity_and_damps_spin(void **state) {
  ball_model m;
  ball_sim sim;
  ball_event ev;
  (void)state;
  drop_model(&m, 0.3, 0.5);
  m.initial_velocity = ball_v3(0.0, 0.0, 0.0);
  m.effects |= BALL_EFFECT_SPIN;
  m.spin_damping = 2.0;
  m.spin_floor_damping = 0.8;
  m.initial_spin = ball_v3(1.0, 0.0, 2.0);
  ev = first_event(&m, &sim, 1.0 / 60.0);
  assert_near(ev.velocity_out.x, -1.3815567048066971, TOL);
  assert_near(ev.velocity_out.y, 2.3266457884688851, TOL);
  assert_near(ev.velocity_out.z, 0.69077835240334854, TOL);
  assert_near(ev.spin_out.x, 0.69077835240334854, TOL);
  assert_true(ev.spin_out.y == 0.0);
  assert_near(ev.spin_out.z, 1.3815567048066971, TOL);
  assert_true(memcmp(&sim.seg.s0, &ev.spin_out, sizeof ev.spin_out) == 0);
}

/* Frames of a resting-ball run: exactly at floor_level + radius, finite,
 * no event. */
static void assert_rests(const ball_model *m, ball_sim *sim, double dt, unsigned long frames) {
  steps_each(sim, dt, frames, NULL, on_the_floor, (void *)m);
}

/* The resting ball, exact scheme: dropped from 2 m onto a floor at 0.25 m
 * (radius 0.05), it hits at v = sqrt(2 g 1.7) = 5.7755...; the k-th bounce
 * leaves at v fd^k. The ball stops at the first k with v fd^k <
 * bounce_threshold, counted here independently (fd 0.75, threshold 0.3:
 * v fd^10 = 0.325 > 0.3 > v fd^11 = 0.244: n = 11, not a close call). Then
 * 1e6 frames at 60 Hz on the floor. */
static void eq5_dropped_ball_comes_to_rest_after_derived_bounce_count_exact(void **state) {
  ball_model m;
  ball_sim sim;
  steps_tally t;
  double v, speed;
  int expected = 0;
  (void)state;
  hand_model(&m);
  m.floor_level = 0.25;
  m.radius = 0.05;
  m.initial_position = ball_v3(0.0, 2.0, 0.0);
  m.initial_velocity = ball_v3(0.5, 0.0, 0.0);
  v = sqrt(2.0 * m.gravity * (2.0 - 0.3));
  for (speed = v * m.floor_damping, expected = 1; speed >= m.bounce_threshold; expected++)
    speed *= m.floor_damping;
  assert_int_equal(expected, 11);
  assert_ok(ball_sim_init(&sim, &m));
  steps_begin(&t, NULL, 0);
  steps_each(&sim, 1.0 / 60.0, 60 * 20, &t, steps_until_grounded, NULL);
  assert_int_equal(sim.seg.grounded, 1);
  assert_int_equal(t.kind[BALL_EVENT_FLOOR], t.total);
  assert_int_equal(t.kind[BALL_EVENT_FLOOR], expected);
  assert_rests(&m, &sim, 1.0 / 60.0, 1000000UL);
}

/* The resting ball, sampled scheme (the paper's): each bounce is detected up
 * to dt late, when the ball is already faster by up to g dt, so the k-th
 * rebound speed u_k <= fd (u_(k-1) + g dt), which tends to at most
 * u* = fd g dt / (1 - fd) = 0.4905 m/s at 60 Hz. With bounce_threshold 0.6 >
 * u* the ball must stop; the count lies between the exact count (u_k >= the
 * exact speed) and the count of the upper recursion. Both derived here. */
static void eq5_dropped_ball_comes_to_rest_within_derived_bounds_sampled(void **state) {
  const double dt = 1.0 / 60.0;
  ball_model m;
  ball_sim sim;
  steps_tally t;
  double v, speed;
  int lo, hi;
  (void)state;
  hand_model(&m);
  m.scheme = BALL_SCHEME_SAMPLED;
  m.bounce_threshold = 0.6;
  m.initial_position = ball_v3(0.0, 2.0, 0.0);
  v = sqrt(2.0 * m.gravity * 2.0);
  assert_true(m.bounce_threshold > m.floor_damping * m.gravity * dt / (1.0 - m.floor_damping));
  for (speed = v * m.floor_damping, lo = 1; speed >= m.bounce_threshold; lo++)
    speed *= m.floor_damping;
  for (speed = m.floor_damping * (v + m.gravity * dt), hi = 1; speed >= m.bounce_threshold; hi++)
    speed = m.floor_damping * (speed + m.gravity * dt);
  assert_ok(ball_sim_init(&sim, &m));
  steps_begin(&t, NULL, 0);
  steps_each(&sim, dt, 60 * 30, &t, steps_until_grounded, NULL);
  assert_int_equal(sim.seg.grounded, 1);
  if (t.kind[BALL_EVENT_FLOOR] < lo || t.kind[BALL_EVENT_FLOOR] > hi)
    fail_msg("sampled: %d floor events, derived bounds [%d, %d]", t.kind[BALL_EVENT_FLOOR], lo, hi);
  assert_rests(&m, &sim, dt, 1000000UL);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(eq5_exact_bounce_velocity_damped_flipped_and_drag_decayed),
      cmocka_unit_test(eq5_sampled_bounce_snaps_p0_to_floor_level),
      cmocka_unit_test(eq5_radius_puts_the_contact_at_floor_level_plus_radius),
      cmocka_unit_test(eq5_above_bounce_threshold_bounces_below_it_slides),
      cmocka_unit_test(eq5_sound_flag_above_sound_threshold_not_below),
      cmocka_unit_test(eq13_eq14_spin_at_the_floor_adds_velocity_and_damps_spin),
      cmocka_unit_test(eq5_dropped_ball_comes_to_rest_after_derived_bounce_count_exact),
      cmocka_unit_test(eq5_dropped_ball_comes_to_rest_within_derived_bounds_sampled),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
