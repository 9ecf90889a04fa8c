/* Hard cases of contacts (docs/hard-cases.md, section 4): a ball exactly on
 * the floor, starting inside the net, moving parallel to the net plane,
 * grazing the net's top and side edges, several contacts in one frame (net
 * then floor, a corner of two walls, corner and floor at once), a ball wedged
 * between a wall and the floor, the resting ball, a ball rolling into the
 * net, more contacts in a frame than BALL_MAX_CONTACTS. Gravity 8 m/s^2 and
 * speeds that are powers of two make the grazing cases exact in binary. */
#include <float.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "core_common.h"

#define AT_LEAST(a, b)                                                                    \
  do {                                                                                    \
    double a_ = (a), b_ = (b);                                                            \
    if (!(a_ >= b_)) fail_msg("%s = %.17g, expected >= %.17g", #a, a_, b_);               \
  } while (0)

#define AT_MOST(a, b)                                                                     \
  do {                                                                                    \
    double a_ = (a), b_ = (b);                                                            \
    if (!(a_ <= b_)) fail_msg("%s = %.17g, expected <= %.17g", #a, a_, b_);               \
  } while (0)

/* Floor and net, no drag, no spin, exact scheme, g = 8, the paper's point
 * ball; the default tennis net at x = 11.885, z in [0, 10.97], y in [0, 0.914]. */
static void model_of(ball_model *m, unsigned effects, double radius) {
  ball_model_default(m);
  m->effects = effects;
  m->scheme = BALL_SCHEME_EXACT;
  m->gravity = 8.0;
  m->radius = radius;
}

static void wall(ball_model *m, int axis, double position, double lo, double hi, double damping) {
  ball_plane w;
  w.axis = axis;
  w.position = position;
  w.lo = lo;
  w.hi = hi;
  w.bottom = m->floor_level;
  w.top = m->floor_level + 10.0;
  w.damping = damping;
  assert_int_equal(ball_model_add_wall(m, &w), BALL_OK);
}

static void state_of(const ball_sim *sim, ball_state *st) {
  assert_int_equal(ball_sim_state(sim, st), BALL_OK);
  assert_finite3(st->position);
  assert_finite3(st->velocity);
}

/* ---- on the floor ------------------------------------------------------- */

/* A ball placed exactly on the floor at rest (floor_level -1.5, radius 0.033):
 * at most one floor event of zero speed, then grounded (eq 5 threshold), and
 * y = floor_level + radius to the bit for 10 s, in both schemes. */
static void test_ball_at_rest_exactly_on_floor_stays_there_eq5(void **state) {
  ball_model m;
  ball_sim sim;
  steps_tally t;
  steps_box pinned = steps_anywhere();
  model_of(&m, BALL_EFFECT_FLOOR | BALL_EFFECT_NET | BALL_EFFECT_DRAG, 0.033);
  m.scheme = test_scheme(state);
  m.floor_level = -1.5;
  core_start(&m, &sim, ball_v3(3.0, -1.5 + 0.033, 4.0), ball_v3(0.0, 0.0, 0.0));
  pinned.lo.y = pinned.hi.y = -1.5 + 0.033;
  pinned.lo.x = pinned.hi.x = 3.0;
  steps_begin(&t, NULL, 0);
  steps_each(&sim, 1.0 / 60.0, 600, &t, steps_in_box, &pinned);
  AT_MOST(t.total, 1);
  if (t.total) assert_near(t.first.velocity_out.y, 0.0, 0.0);
  assert_int_equal(sim.seg.grounded, 1);
}

/* Sliding exactly on the floor at 5 m/s with drag: y stays on the floor, x
 * follows eq 3 (X0 + V0x b (1 - e^(-t/b))) and nothing bounces. The exact
 * scheme may first register a zero-speed touchdown (eq 5 at V0y = 0, which
 * also damps V0x by floorDamping): then V0x is that event's. */
static void test_ball_sliding_on_floor_follows_eq3(void **state) {
  ball_model m;
  ball_sim sim;
  ball_state st;
  steps_tally t;
  double b;
  (void)state;
  model_of(&m, BALL_EFFECT_FLOOR | BALL_EFFECT_DRAG, 0.0);
  b = m.mass / m.air_friction;
  core_start(&m, &sim, ball_v3(0.0, 0.0, 4.0), ball_v3(5.0, 0.0, 0.0));
  steps_begin(&t, NULL, 0);
  steps_run(&sim, 1.0 / 64.0, 120, &t);
  state_of(&sim, &st);
  AT_MOST(t.total, 1);
  assert_near(st.position.y, 0.0, 0.0);
  if (t.total) {
    assert_near(t.first.time, 0.0, 0.0);
    assert_near(t.first.velocity_out.x, 5.0 * m.floor_damping, 0.0);
  }
  assert_near(st.position.x, -(t.total ? t.first.velocity_out.x : 5.0) * b * expm1(-sim.time / b), 1e-12);
}

/* ---- the net plane ------------------------------------------------------ */

/* A ball whose centre starts in the net plane (inside the net), moving either
 * way or not at all: it does not get stuck in the net (no contact limit, at
 * most one net event), and after 1 s it is clear of the net (|x - net_x| >=
 * radius) or, without horizontal speed, has not moved horizontally. */
static void test_ball_starting_inside_the_net_gets_out_fig3(void **state) {
  static const double radii[] = {0.0, 0.033};
  static const double speeds[] = {3.0, -3.0, 0.0};
  size_t i, j;
  (void)state;
  for (i = 0; i < 2; i++)
    for (j = 0; j < 3; j++) {
      ball_model m;
      ball_sim sim;
      ball_state st;
      steps_tally t;
      model_of(&m, BALL_EFFECT_FLOOR | BALL_EFFECT_NET, radii[i]);
      core_start(&m, &sim, ball_v3(11.885, 0.5, 3.0), ball_v3(speeds[j], 0.0, 0.0));
      steps_begin(&t, NULL, 0);
      steps_run(&sim, 1.0 / 60.0, 60, &t);
      state_of(&sim, &st);
      AT_MOST(t.kind[BALL_EVENT_NET], 1);
      assert_int_equal(sim.warnings[BALL_WARN_CONTACT_LIMIT], 0);
      if (speeds[j] != 0.0)
        AT_LEAST(fabs(st.position.x - 11.885), radii[i]);
      else
        assert_near(st.position.x, 11.885, 0.0);
    }
}

/* Moving exactly parallel to the net plane, touching it (x = net_x - radius)
 * or in it (radius 0): no net event (Fig. 3: "line segment and net plane
 * parallel"), x unchanged to the bit, in both schemes. */
static void test_ball_parallel_to_net_plane_never_hits_it_fig3(void **state) {
  static const double radii[] = {0.0, 0.033};
  size_t i;
  for (i = 0; i < 2; i++) {
    ball_model m;
    ball_sim sim;
    ball_state st;
    steps_tally t;
    model_of(&m, BALL_EFFECT_FLOOR | BALL_EFFECT_NET | BALL_EFFECT_DRAG, radii[i]);
    m.scheme = test_scheme(state);
    core_start(&m, &sim, ball_v3(11.885 - radii[i], 0.5, 3.0), ball_v3(0.0, 2.0, 4.0));
    steps_begin(&t, NULL, 0);
    steps_run(&sim, 1.0 / 60.0, 120, &t);
    state_of(&sim, &st);
    assert_int_equal(t.kind[BALL_EVENT_NET], 0);
    assert_near(st.position.x, 11.885 - radii[i], 0.0);
    AT_LEAST(st.position.z, 5.0);
  }
}

/* A point ball from p at 8 m/s along x toward the net moved to x = 2 m
 * (m: model_of's, the net only, its top as the caller set it), in the
 * entry's scheme: the events of 32 frames of 1/64 s. */
static void toward_the_net_at_2m(void **state, ball_model *m, ball_vec3 p, steps_tally *t) {
  ball_sim sim;
  m->scheme = test_scheme(state);
  m->net.position = 2.0;
  core_start(m, &sim, p, ball_v3(8.0, 0.0, 0.0));
  steps_begin(t, NULL, 0);
  steps_run(&sim, 1.0 / 64.0, 32, t);
}

/* Grazing the top edge: launched horizontally at 8 m/s, 2 m before the net,
 * the ball crosses the plane at tau = 0.25 s after falling 8 * 0.25^2 / 2 =
 * 0.25 m (all exact in binary). Starting at top + 0.25 it crosses exactly at
 * the top edge: a hit (the extent is closed, Fig. 3); 1e-9 m higher it passes
 * over; 1e-9 m lower it hits. Frames of 1/64 s end exactly at the crossing,
 * so the sampled scheme sees the same. */
static void test_grazing_the_net_top_edge_fig3(void **state) {
  static const double offsets[] = {0.0, 1e-9, -1e-9};
  size_t i;
  for (i = 0; i < 3; i++) {
    ball_model m;
    steps_tally t;
    model_of(&m, BALL_EFFECT_NET, 0.0);
    m.net.top = 1.0;
    toward_the_net_at_2m(state, &m, ball_v3(0.0, 1.25 + offsets[i], 5.0), &t);
    assert_int_equal(t.kind[BALL_EVENT_NET], offsets[i] > 0.0 ? 0 : 1);
    if (t.total) {
      assert_near(t.first.time, 0.25, 1e-15);
      assert_near(t.first.point.y, 1.0 + offsets[i], 1e-15);
      assert_near(t.first.velocity_out.x, -8.0 * m.net.damping, 1e-15);
    }
  }
}

/* Grazing the side edges z = lo = 0 and z = hi = 10.97 of the net: exactly
 * on an edge is a hit, 1e-9 m outside it passes by (Fig. 3, closed extent). */
static void test_grazing_the_net_side_edges_fig3(void **state) {
  static const double zs[] = {0.0, -1e-9, 10.97, 10.97 + 1e-9};
  size_t i;
  for (i = 0; i < 4; i++) {
    ball_model m;
    steps_tally t;
    model_of(&m, BALL_EFFECT_NET, 0.0);
    toward_the_net_at_2m(state, &m, ball_v3(0.0, 0.75, zs[i]), &t);
    assert_int_equal(t.kind[BALL_EVENT_NET], (i % 2) ? 0 : 1);
  }
}

/* ---- several contacts in one frame -------------------------------------- */

/* Net then floor in one 0.5 s frame: 1 m before the net at 10 m/s, 0.3 m
 * high: net at tau1 = (1 - r) / 10 s (y = 0.3 - 4 tau1^2, vy = -8 tau1), the
 * whole velocity reflected in x and scaled by netDamping 0.2 (eq 6), then the
 * floor when y1 + 0.2 vy tau - 4 tau^2 = r, landing 2 tau m before the net
 * (eq 5). Events in time order. */
static void test_net_then_floor_in_one_frame_eq5_eq6(void **state) {
  static const double radii[] = {0.0, 0.033};
  size_t i;
  (void)state;
  for (i = 0; i < 2; i++) {
    ball_model m;
    ball_sim sim;
    ball_event ev[8];
    int n;
    double r = radii[i], t_net = (1.0 - r) / 10.0;
    double y1 = 0.3 - 4.0 * t_net * t_net, vy1 = -0.2 * 8.0 * t_net;
    double tau2 = (vy1 + sqrt(vy1 * vy1 + 16.0 * (y1 - r))) / 8.0; /* 4 tau^2 - vy1 tau - (y1 - r) = 0 */
    model_of(&m, BALL_EFFECT_NET | BALL_EFFECT_FLOOR, r);
    core_start(&m, &sim, ball_v3(11.885 - 1.0, 0.3, 3.0), ball_v3(10.0, 0.0, 0.0));
    assert_int_equal(ball_step(&sim, 0.5, ev, 8, &n), BALL_OK);
    assert_true(n >= 2);
    assert_int_equal(ev[0].kind, BALL_EVENT_NET);
    assert_int_equal(ev[1].kind, BALL_EVENT_FLOOR);
    assert_near(ev[0].time, t_net, 1e-15);
    assert_near(ev[0].point.y, y1, 1e-15);
    assert_near(ev[0].velocity_out.x, -2.0, 1e-15);
    assert_near(ev[0].velocity_out.y, vy1, 1e-15);
    assert_near(ev[1].time, t_net + tau2, 1e-14);
    assert_near(ev[1].point.x, 11.885 - r - 2.0 * tau2, 1e-12);
    assert_int_equal(sim.warnings[BALL_WARN_CONTACT_LIMIT], 0);
  }
}

/* Into the corner of two walls (x = 5 and z = 5) at (2, 2) m/s from 1 m away
 * on both axes: both walls at tau = 0.5 s (minus radius / 2), one event each
 * at the same time; each scales the whole velocity by its damping 0.5 (eq 6),
 * so the ball leaves with (-2, ., -2) * 0.25 and never ends a frame behind
 * either wall. Dropped from 4 tc^2 above the floor it reaches the floor at
 * the same instant: three contacts at once, and eq 5 damps all components
 * by 0.75 more: vy = 0.75 * 0.25 * 8 tc. The frame ends 0.1 s after tc,
 * before the next bounce (2 * 0.1875 * 8 tc / 8 > 0.1 s). */
static void test_corner_of_two_walls_reflects_both_axes_eq6(void **state) {
  static const double radii[] = {0.0, 0.1};
  size_t i;
  int with_floor;
  (void)state;
  for (with_floor = 0; with_floor < 2; with_floor++)
    for (i = 0; i < 2; i++) {
      ball_model m;
      ball_sim sim;
      ball_event ev[8];
      steps_box inside = steps_anywhere();
      int n, k;
      double r = radii[i], tc = (1.0 - r) / 2.0;
      model_of(&m, BALL_EFFECT_WALLS | BALL_EFFECT_FLOOR, r);
      wall(&m, 0, 5.0, -10.0, 10.0, 0.5);
      wall(&m, 2, 5.0, -10.0, 10.0, 0.5);
      /* with the floor: fall 4 tc^2 to touch it at tc */
      core_start(&m, &sim, ball_v3(4.0, r + (with_floor ? 4.0 * tc * tc : 3.0), 4.0), ball_v3(2.0, 0.0, 2.0));
      assert_int_equal(ball_step(&sim, tc + 0.1, ev, 8, &n), BALL_OK);
      assert_int_equal(n, with_floor ? 3 : 2);
      for (k = 0; k < n; k++) assert_near(ev[k].time, tc, 1e-15);
      assert_near(ev[n - 1].velocity_out.x, -0.5 * (with_floor ? 0.75 : 1.0), 1e-15);
      assert_near(ev[n - 1].velocity_out.z, -0.5 * (with_floor ? 0.75 : 1.0), 1e-15);
      if (with_floor) assert_near(ev[n - 1].velocity_out.y, 0.75 * 0.25 * 8.0 * tc, 1e-14);
      inside.hi.x = inside.hi.z = 5.0 - r;
      inside.lo.y = r;
      steps_each(&sim, 1.0 / 60.0, 120, NULL, steps_in_box, &inside);
      assert_int_equal(sim.warnings[BALL_WARN_CONTACT_LIMIT], 0);
    }
}

/* The sampled scheme (Fig. 3 per wall) with two walls crossed in one frame:
 * from (4, 3, 4.5) at (2, 0, 2) m/s, a 0.6 s frame crosses the wall z = 5
 * (index 1) at s = 0.5 / 1.2 of the chord and the wall x = 5 (index 0) at
 * s = 1 / 1.2. Whichever is handled, the ball must not end the frame, or any
 * later frame, behind either wall. */
static void test_sampled_two_walls_in_one_frame_keeps_ball_inside_fig3(void **state) {
  ball_model m;
  ball_sim sim;
  steps_box inside = steps_anywhere();
  (void)state;
  model_of(&m, BALL_EFFECT_WALLS, 0.0);
  m.scheme = BALL_SCHEME_SAMPLED;
  wall(&m, 0, 5.0, -10.0, 10.0, 1.0);
  wall(&m, 2, 5.0, -10.0, 10.0, 1.0);
  m.walls[0].bottom = m.walls[1].bottom = -1e6;
  core_start(&m, &sim, ball_v3(4.0, 3.0, 4.5), ball_v3(2.0, 0.0, 2.0));
  inside.hi.x = inside.hi.z = 5.0;
  steps_each(&sim, 0.6, 10, NULL, steps_in_box, &inside);
}

/* Wedged between a wall and the floor: a grounded ball touching the wall
 * (x = 5 - radius) pushed into it at 2 m/s bounces off once (eq 6: times
 * wall damping 0.5, and floorDamping 0.75 if a zero-speed touchdown came
 * first) and slides away on the floor; at rest in the wedge it stays put, to the bit, with no
 * event. Falling into the edge at 45 degrees it meets both at once and
 * leaves with both components reversed. Never behind the wall nor under the
 * floor. */
static void test_ball_wedged_between_wall_and_floor_eq5_eq6(void **state) {
  static const double radii[] = {0.0, 0.1};
  size_t i;
  int k;
  (void)state;
  for (i = 0; i < 2; i++)
    for (k = 0; k < 3; k++) {
      ball_model m;
      ball_sim sim;
      ball_state st;
      steps_tally t;
      steps_box inside = steps_anywhere();
      double r = radii[i];
      model_of(&m, BALL_EFFECT_WALLS | BALL_EFFECT_FLOOR, r);
      wall(&m, 0, 5.0, -10.0, 10.0, 0.5);
      if (k == 0) core_start(&m, &sim, ball_v3(5.0 - r, r, 0.0), ball_v3(2.0, 0.0, 0.0));
      if (k == 1) core_start(&m, &sim, ball_v3(5.0 - r, r, 0.0), ball_v3(0.0, 0.0, 0.0));
      if (k == 2) core_start(&m, &sim, ball_v3(4.0 - r, r + 4.0 * 0.25, 0.0), ball_v3(2.0, 0.0, 0.0));
      inside.hi.x = 5.0 - r;
      inside.lo.y = r;
      steps_begin(&t, NULL, 0);
      steps_each(&sim, 1.0 / 60.0, 120, &t, steps_in_box, &inside);
      state_of(&sim, &st);
      assert_int_equal(sim.warnings[BALL_WARN_CONTACT_LIMIT], 0);
      if (k == 0) {
        assert_int_equal(t.kind[BALL_EVENT_WALL], 1);
        assert_near(st.velocity.x, -2.0 * 0.5 * (t.kind[BALL_EVENT_FLOOR] ? 0.75 : 1.0), 0.0);
        assert_near(st.position.y, r, 0.0);
      }
      if (k == 1) {
        AT_MOST(t.total, 1); /* the zero-speed settling on the floor */
        assert_int_equal(t.kind[BALL_EVENT_WALL], 0);
        assert_near(st.position.x, 5.0 - r, 0.0);
        assert_near(st.position.y, r, 0.0);
      }
      if (k == 2) {
        assert_int_equal(t.kind[BALL_EVENT_WALL], 1);
        AT_LEAST(t.kind[BALL_EVENT_FLOOR], 1);
        assert_near(t.first.time, 0.5, 1e-15);
        AT_MOST(st.velocity.x, 0.0);
      }
    }
}

/* ---- the resting ball ---------------------------------------------------- */

/* Dropped from 1 m (g = 8): arrives at sqrt(16) = 4 m/s and leaves each bounce
 * at 0.75 times its arrival speed (eq 5): 3, 2.25, 1.6875, ... The bounce
 * that would leave below bounce_threshold = 0.3 m/s grounds the ball instead:
 * 4 * 0.75^k < 0.3 first for k = 10 (0.225), so exactly 10 floor events, the
 * k-th at time 0.5 + sum_{j<k} 2 * 4 * 0.75^j / 8. Then 10 s of nothing. */
static void test_resting_ball_stops_after_ten_bounces_eq5(void **state) {
  ball_model m;
  ball_sim sim;
  ball_state st;
  ball_event log[16];
  steps_tally t;
  int k;
  double t_expect = 0.5;
  (void)state;
  model_of(&m, BALL_EFFECT_FLOOR | BALL_EFFECT_SOUND, 0.0);
  core_start(&m, &sim, ball_v3(0.0, 1.0, 0.0), ball_v3(0.0, 0.0, 0.0));
  steps_begin(&t, log, 16);
  steps_run(&sim, 1.0 / 60.0, 60 * 20, &t);
  for (k = 0; k < t.total; k++) {
    double v_out = 4.0 * pow(0.75, k + 1);
    assert_int_equal(log[k].kind, BALL_EVENT_FLOOR);
    assert_near(log[k].time, t_expect, 1e-12);
    assert_near(log[k].velocity_out.y, v_out < 0.3 ? 0.0 : v_out, 1e-12);
    t_expect += 2.0 * v_out / 8.0;
  }
  assert_int_equal(t.total, 10);
  assert_int_equal(sim.seg.grounded, 1);
  state_of(&sim, &st);
  assert_near(st.position.y, 0.0, 0.0);
}

/* The same ball with bounce_threshold = 0, the limit the paper's threshold
 * exists for (Zeno: infinitely many bounces in 0.5 + 2 * 0.75 * 4 / 8 / 0.25
 * = 3.5 s). Whatever the stepper does about it, the ball never ends a frame
 * below the floor, stays finite, and is on the floor at rest after 10 s. */
static void test_resting_ball_with_zero_threshold_never_sinks_eq5(void **state) {
  ball_model m;
  ball_sim sim;
  ball_state st;
  steps_box above = steps_anywhere();
  model_of(&m, BALL_EFFECT_FLOOR, 0.0);
  m.scheme = test_scheme(state);
  m.bounce_threshold = 0.0;
  core_start(&m, &sim, ball_v3(0.0, 1.0, 0.0), ball_v3(0.0, 0.0, 0.0));
  above.lo.y = 0.0;
  steps_each(&sim, 1.0 / 60.0, 60 * 10, NULL, steps_in_box, &above);
  state_of(&sim, &st);
  AT_MOST(st.position.y, 0.01); /* sampled: micro-bounces of at most g dt^2 / 2 */
}

/* And a ball placed at rest on the floor with bounce_threshold = 0 stays on
 * or above it. */
static void test_ball_at_rest_with_zero_threshold_never_sinks_eq5(void **state) {
  ball_model m;
  ball_sim sim;
  steps_box above = steps_anywhere();
  (void)state;
  model_of(&m, BALL_EFFECT_FLOOR, 0.0);
  m.bounce_threshold = 0.0;
  core_start(&m, &sim, ball_v3(0.0, 0.0, 0.0), ball_v3(0.0, 0.0, 0.0));
  above.lo.y = 0.0;
  steps_each(&sim, 1.0 / 60.0, 60, NULL, steps_in_box, &above);
}

/* A ball rolling (grounded) into the net at 5 m/s with drag: one net event
 * at x = net_x - radius, leaves at -0.2 times its arrival speed (eq 6), still
 * on the floor, and slides away: never past the net, no more events. */
static void test_ball_rolling_into_the_net_bounces_once_eq6(void **state) {
  static const double radii[] = {0.0, 0.033};
  size_t i;
  (void)state;
  for (i = 0; i < 2; i++) {
    ball_model m;
    ball_sim sim;
    steps_tally t;
    steps_box rolling = steps_anywhere();
    double r = radii[i];
    model_of(&m, BALL_EFFECT_FLOOR | BALL_EFFECT_NET | BALL_EFFECT_DRAG, r);
    core_start(&m, &sim, ball_v3(10.0, r, 3.0), ball_v3(5.0, 0.0, 0.0));
    rolling.hi.x = 11.885 - r;
    rolling.lo.y = rolling.hi.y = r;
    steps_begin(&t, NULL, 0);
    steps_each(&sim, 1.0 / 60.0, 240, &t, steps_in_box, &rolling);
    assert_int_equal(t.kind[BALL_EVENT_NET], 1);
    assert_near(t.last.point.x, 11.885 - r, 1e-12);
    assert_near(t.last.velocity_out.x, -0.2 * t.last.velocity_in.x, 1e-15);
    assert_true(t.last.velocity_in.x > 0.0);
    assert_int_equal(sim.warnings[BALL_WARN_CONTACT_LIMIT], 0);
  }
}

/* The ball above the net's top edge stays above it (a callback: its
 * centre at least the radius from the edge line, less rounding). */
static int above_the_edge(void *ctx, ball_sim *sim, const steps_tally *t, const ball_event *ev, int n) {
  const ball_model *m = (const ball_model *)ctx;
  ball_state s;
  (void)t;
  (void)ev;
  (void)n;
  state_of(sim, &s);
  AT_LEAST(hypot(s.position.x - m->net.position, s.position.y - m->net.top), m->radius - 1e-9);
  return 1;
}

/* Any drag, down to a ball that it stops in 1e-289 s or at once (air
 * friction DBL_MAX: 1 / b is +Inf), on any clock:
 * dropped 0.25 m onto the net's top edge (its centre over the edge line,
 * g = 8: the surface reaches it at tau = 0.25 s, at 2 m/s), or thrown up
 * at 1 m/s from there, with a speed along the net, the ball bounces off the
 * edge (eq 6, net damping) and never sinks into it. Two findings of the fuzz harness: the
 * rim search's acceleration bound, k |v_h| at the window's start, was 1e287
 * m/s^2 for the lightest balls, and its steps of 1e-144 s ran out before the
 * contact (with 1 / b = +Inf, +Inf times a speed of 0 made it NaN, and its
 * first step off a rising ball +Inf / +Inf); and the search stepped the absolute clock, so that on a clock at
 * 1e38 s (ulp 1.7e22 s) its first step off a touching edge went past every
 * contact. Either way the ball fell through the edge. On a clock at T the
 * contact's time is T + 0.25 to the clock's ulp and its place exact as on a
 * clock at 0 (positions inside a segment are relative to its start), its
 * speeds those at the rounded time (docs/hard-cases.md, section 5). */
static void test_any_drag_on_any_clock_bounces_off_the_net_top_edge_eq6(void **state) {
  static const double masses[] = {0.057, 1e-3, 1e-12, 1e-100, 1e-250, 1.1697929883700373e-290, 1e-300};
  static const double speeds[] = {0.0, 0.3, 1.0};
  static const double clocks[] = {0.0, 1e9, 1e38};
  static const double frictions[] = {0.02, DBL_MAX};
  static const double ups[] = {0.0, 1.0};
  size_t i, j, k, l, u;
  (void)state;
  for (u = 0; u < sizeof ups / sizeof ups[0]; u++)
    for (l = 0; l < sizeof frictions / sizeof frictions[0]; l++)
      for (k = 0; k < sizeof clocks / sizeof clocks[0]; k++)
        for (i = 0; i < sizeof masses / sizeof masses[0]; i++)
          for (j = 0; j < sizeof speeds / sizeof speeds[0]; j++) {
            ball_model m;
            ball_sim sim;
            ball_segment seg;
            steps_tally t;
            const double T = clocks[k];
            model_of(&m, BALL_EFFECT_NET | BALL_EFFECT_DRAG, 0.1);
            m.mass = masses[i];
            m.air_friction = frictions[l];
            core_start(&m, &sim, ball_v3(0.0, 1.0, 0.0), ball_v3(0.0, 0.0, 0.0));
            seg = sim.seg;
            seg.t0 = T;
            seg.p0 = ball_v3(m.net.position, m.net.top + 0.1 + 0.25, 5.0);
            seg.v0 = ball_v3(0.0, ups[u], speeds[j]);
            assert_int_equal(ball_sim_set_segment(&sim, &seg, T), BALL_OK);
            steps_begin(&t, NULL, 0);
            steps_each(&sim, 1.0 / 60.0, 30, &t, above_the_edge, &m);
            if (t.kind[BALL_EVENT_NET] < 1)
              fail_msg("up %g, air friction %g, clock %g, mass %g, speed %g: no net event", ups[u], frictions[l], T,
                       masses[i], speeds[j]);
            const double ulp = nextafter(T, INFINITY) - T;
            /* 0.25 + v tau - 4 tau^2 = 0 */
            const double tau = (ups[u] + sqrt(ups[u] * ups[u] + 4.0)) / 8.0, v_in = -sqrt(ups[u] * ups[u] + 4.0);
            assert_near(t.first.time, T + tau, fmax(1e-12, 2.0 * ulp));
            /* (the search stops within 1e-13 of the coordinates' scale, 1.3e-12 m here) */
            assert_near(t.first.point.y, m.net.top + 0.1, 2e-12);
            /* the speeds at the contact's time rounded to the clock: g * 2 ulp */
            assert_near(t.first.velocity_in.y, v_in, 1e-11 + 16.0 * ulp);
            assert_near(t.first.velocity_out.y, -v_in * m.net.damping, 1e-11 + 16.0 * ulp);
          }
}

/* More contacts in one frame than BALL_MAX_CONTACTS: walls 0.05 m apart and a
 * ball at 100 m/s (33 wall contacts per 1/60 s frame, 333 per 1/6 s frame).
 * The limit is counted as a warning; the ball must still never end a frame
 * outside the two walls. */
static void test_contact_limit_keeps_ball_between_walls(void **state) {
  static const double dts[] = {1.0 / 60.0, 1.0 / 6.0};
  size_t i;
  (void)state;
  for (i = 0; i < 2; i++) {
    ball_model m;
    ball_sim sim;
    steps_box between = steps_anywhere();
    model_of(&m, BALL_EFFECT_WALLS, 0.0);
    wall(&m, 0, 0.0, -10.0, 10.0, 1.0);
    wall(&m, 0, 0.05, -10.0, 10.0, 1.0);
    m.walls[0].bottom = m.walls[1].bottom = -1e9;
    core_start(&m, &sim, ball_v3(0.025, 5.0, 0.0), ball_v3(100.0, 0.0, 0.0));
    between.lo.x = 0.0;
    between.hi.x = 0.05;
    steps_each(&sim, dts[i], 30, NULL, steps_in_box, &between);
    if (i == 1) assert_true(sim.warnings[BALL_WARN_CONTACT_LIMIT] > 0);
  }
}

/* A point ball bouncing off a wall at an exact coordinate: x = 0 or z = 0,
 * -0, 1e-300, the smallest subnormals. It restarts one ulp from the wall;
 * there a time to the plane of -tiny / v underflows to -0 and passed the
 * old "u >= 0" test, so the same wall was found again from the wrong side
 * (64 contacts a frame with damping 1; with 0.8 one bounce became 7 events
 * and the ball left at 1.95 m/s instead of 7.6). Now one event a bounce,
 * leaving at damping x the arriving speed, both schemes, both axes. */
/* A callback (ctx: a plane_side): the ball's centre never ends a frame
 * behind the wall (sim->prev_position, the paper's P_old). */
typedef struct plane_side {
  int axis;  /* 0: x, 2: z */
  double at; /* m */
} plane_side;

static int never_behind(void *ctx, ball_sim *sim, const steps_tally *t, const ball_event *ev, int n) {
  const plane_side *w = ctx;
  double c = w->axis == 0 ? sim->prev_position.x : sim->prev_position.z;
  (void)ev;
  (void)n;
  if (!(c >= w->at)) fail_msg("frame %lu: behind the wall at %.17g: %.17g", t->frames - 1, w->at, c);
  return 1;
}

static void test_point_ball_bounces_once_off_a_wall_at_an_exact_coordinate_eq6(void **state) {
  static const double at[] = {0.0, -0.0, 1e-300, 4.9406564584124654e-324, -4.9406564584124654e-324};
  int i, axis;
  for (axis = 0; axis <= 2; axis += 2)
    for (i = 0; i < 5; i++) {
      ball_model m;
      ball_sim sim;
      steps_tally t;
      ball_plane w = {axis, at[i], -100.0, 100.0, -100.0, 100.0, 0.8};
      plane_side side;
      ball_vec3 p = axis == 0 ? ball_v3(1.0, 10.0, 0.5) : ball_v3(0.5, 10.0, 1.0);
      ball_vec3 v = axis == 0 ? ball_v3(-7.6, 0.0, 0.0) : ball_v3(0.0, 0.0, -7.6);
      core_model_free(&m);
      m.air_friction = 0.0;
      m.gravity = BALL_MIN_GRAVITY; /* no fall to speak of; nothing else in the way */
      m.effects = BALL_EFFECT_WALLS;
      m.scheme = test_scheme(state);
      assert_ok(ball_model_add_wall(&m, &w));
      core_start(&m, &sim, p, v);
      side.axis = axis;
      side.at = at[i];
      steps_begin(&t, NULL, 0);
      steps_each(&sim, 1.0 / 60.0, 60, &t, never_behind, &side);
      assert_int_equal(t.total, 1);
      assert_int_equal(t.first.kind, BALL_EVENT_WALL);
      assert_near(axis == 0 ? t.first.velocity_out.x : t.first.velocity_out.z, 0.8 * 7.6, 1e-12);
      assert_int_equal(sim.warnings[BALL_WARN_CONTACT_LIMIT], 0);
    }
}

int main(void) {
  const struct CMUnitTest tests[] = {
      EACH_SCHEME(test_ball_at_rest_exactly_on_floor_stays_there_eq5),
      cmocka_unit_test(test_ball_sliding_on_floor_follows_eq3),
      cmocka_unit_test(test_ball_starting_inside_the_net_gets_out_fig3),
      EACH_SCHEME(test_ball_parallel_to_net_plane_never_hits_it_fig3),
      EACH_SCHEME(test_grazing_the_net_top_edge_fig3),
      EACH_SCHEME(test_grazing_the_net_side_edges_fig3),
      cmocka_unit_test(test_net_then_floor_in_one_frame_eq5_eq6),
      cmocka_unit_test(test_corner_of_two_walls_reflects_both_axes_eq6),
      cmocka_unit_test(test_sampled_two_walls_in_one_frame_keeps_ball_inside_fig3),
      cmocka_unit_test(test_ball_wedged_between_wall_and_floor_eq5_eq6),
      cmocka_unit_test(test_resting_ball_stops_after_ten_bounces_eq5),
      EACH_SCHEME(test_resting_ball_with_zero_threshold_never_sinks_eq5),
      cmocka_unit_test(test_ball_at_rest_with_zero_threshold_never_sinks_eq5),
      cmocka_unit_test(test_ball_rolling_into_the_net_bounces_once_eq6),
      cmocka_unit_test(test_any_drag_on_any_clock_bounces_off_the_net_top_edge_eq6),
      cmocka_unit_test(test_contact_limit_keeps_ball_between_walls),
      EACH_SCHEME(test_point_ball_bounces_once_off_a_wall_at_an_exact_coordinate_eq6),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
