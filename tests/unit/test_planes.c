/* The net and the walls: Fig. 3 (the segment test and its extents), eq 6
 * (the reflection, netDamping on the whole velocity, the dt / 10 shift along
 * the NEW x velocity in the sampled scheme, no shift in the exact scheme:
 * docs/design.md R5), walls on x and z planes, and the ball radius moving the contact
 * plane toward the approaching ball.
 *
 * Hand case: the default tennis net (x = 11.885 m, z in [0, 10.97] m, top
 * 0.914 m, netDamping 0.2), b = 2 s, P0 = (10, 0.5, 5) m, V0 = (8, 2, 1) m/s.
 * The plane needs b (1 - e^(-t/b)) = 1.885 / 8 = 0.235625, so
 * e^(-t/b) = 1 - 0.235625 / 2 = 0.8821875 exactly, t = -2 ln 0.8821875 =
 * 0.25070132106865718 s, y = 0.69311773968609384 m, z = 5.235625 m,
 * vy = 2 - g t = -0.45937995968352691 m/s. eq 6: V0' = 0.2 (-8 f, vy, 1 f) =
 * (-1.4115, -0.091875991936705383, 0.1764375). Tolerance 1e-12 (values O(10)). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "core_common.h"

#define TOL 1e-12

static void net_model(ball_model *m) {
  core_model_free(m);
  core_tennis_net(m, 0.2);
  m->effects |= BALL_EFFECT_NET | BALL_EFFECT_WALLS;
  m->initial_position = ball_v3(10.0, 0.5, 5.0);
  m->initial_velocity = ball_v3(8.0, 2.0, 1.0);
}

/* Runs `frames` frames and returns how many events; the first in *first. */
static int run_events(const ball_model *m, ball_sim *sim, double dt, int frames, ball_event *first) {
  steps_tally t;
  assert_ok(ball_sim_init(sim, m));
  steps_begin(&t, NULL, 0);
  steps_run(sim, dt, (unsigned long)frames, &t);
  if (t.total > 0 && first) *first = t.first;
  return t.total;
}

static void eq6_exact_net_reflection_matches_hand_values(void **state) {
  ball_model m;
  ball_sim sim;
  ball_event ev;
  (void)state;
  net_model(&m);
  /* one hit in 0.5 s (the floor comes at 0.62 s): reflected once, not again
   * at the same instant by the plane it is leaving */
  assert_int_equal(run_events(&m, &sim, 1.0 / 60.0, 30, &ev), 1);
  assert_int_equal(sim.warnings[BALL_WARN_CONTACT_LIMIT], 0);
  assert_int_equal(ev.kind, BALL_EVENT_NET);
  assert_int_equal(ev.index, 0);
  assert_near(ev.time, 0.25070132106865718, TOL);
  /* no eq 6 shift in the exact scheme: Q is on the plane (to rounding) */
  assert_near(ev.point.x, 11.885, TOL);
  assert_near(ev.point.y, 0.69311773968609384, TOL);
  assert_near(ev.point.z, 5.235625, TOL);
  assert_near(ev.velocity_in.x, 8.0 * 0.8821875, TOL);
  assert_near(ev.velocity_in.y, -0.45937995968352691, TOL);
  assert_near(ev.velocity_out.x, -1.4115, TOL);
  assert_near(ev.velocity_out.y, -0.091875991936705383, TOL);
  assert_near(ev.velocity_out.z, 0.1764375, TOL);
  /* the ball then stays on its own side */
  {
    ball_state s;
    int f;
    double x_prev = 11.885;
    for (f = 0; f < 120; f++) {
      assert_ok(ball_step(&sim, 1.0 / 60.0, NULL, 0, NULL));
      assert_ok(ball_sim_state(&sim, &s));
      assert_true(s.position.x < x_prev); /* moving away at -1.4115 f(t) m/s */
      x_prev = s.position.x;
    }
  }
}

/* Fig. 3 at dt = 0.1 s: P_old at t = 0.2 (x = 11.5226...), P at t = 0.3
 * (x = 12.2287...), s = 0.51326092534024094, Q = P_old + s (P - P_old) =
 * (11.885, 0.68057494312835410, 5.235625). eq 6 with the velocity at the end
 * of the frame, f = e^-0.15: V0' = 0.2 (-8 f, 2 - 0.3 g, f) =
 * (-1.3771327622800925, -0.1886, 0.17214159528501156); P0 = Q + (V0x' dt / 10,
 * 0, 0): x = 11.885 - 0.013771... = 11.871228672377199, back on the side the
 * ball came from. */
static void eq6_sampled_net_hit_shifts_dt_over_10_along_new_velocity(void **state) {
  ball_model m;
  ball_sim sim;
  ball_event ev;
  (void)state;
  net_model(&m);
  m.scheme = BALL_SCHEME_SAMPLED;
  assert_true(run_events(&m, &sim, 0.1, 3, &ev) == 1);
  assert_int_equal(ev.kind, BALL_EVENT_NET);
  assert_near(ev.time, 0.3, 1e-15);
  assert_near(ev.velocity_out.x, -1.3771327622800925, TOL);
  assert_near(ev.velocity_out.y, -0.1886, TOL);
  assert_near(ev.velocity_out.z, 0.17214159528501156, TOL);
  /* the event reports Q (ball.h: "ball centre at the collision (Q)"), the
   * segment restarts at the shifted P0 */
  assert_near(ev.point.x, 11.885, TOL);
  assert_near(ev.point.y, 0.68057494312835410, TOL);
  assert_near(ev.point.z, 5.235625, TOL);
  assert_near(sim.seg.p0.x, 11.871228672377199, TOL);
  assert_true(sim.seg.p0.y == ev.point.y && sim.seg.p0.z == ev.point.z);
  assert_true(sim.seg.p0.x < 11.885);
  assert_true(sim.seg.t0 == ev.time);
  /* the same from the far side: the shift lands the ball beyond the net */
  m.initial_position = ball_v3(13.77, 0.5, 5.0);
  m.initial_velocity = ball_v3(-8.0, 2.0, 1.0);
  assert_true(run_events(&m, &sim, 0.1, 3, &ev) == 1);
  assert_true(ev.velocity_out.x > 0.0);
  assert_near(ev.point.x, 11.885, TOL);
  assert_near(sim.seg.p0.x - 11.885, ev.velocity_out.x * 0.1 / 10.0, 1e-14);
  assert_true(sim.seg.p0.x > 11.885);
}

/* Fig. 3 extents: beside the net (z > net_z) or above its top: no event. */
static void fig3_ball_beside_or_above_the_net_passes(void **state) {
  ball_model m;
  ball_sim sim;
  ball_event ev;
  ball_state s;
  net_model(&m);
  m.scheme = test_scheme(state);
  /* beside: z = 11 + 0.236 at the net, outside [0, 10.97] */
  m.initial_position = ball_v3(10.0, 0.5, 11.0);
  assert_int_equal(run_events(&m, &sim, 1.0 / 60.0, 30, &ev), 0);
  assert_ok(ball_sim_state(&sim, &s));
  assert_true(s.position.x > 11.885);
  /* on the other side of z = 0 */
  m.initial_position = ball_v3(10.0, 0.5, -0.5);
  m.initial_velocity = ball_v3(8.0, 2.0, -1.0);
  assert_int_equal(run_events(&m, &sim, 1.0 / 60.0, 30, &ev), 0);
  /* above: y at the net = 1.0 + 0.193 > 0.914 */
  m.initial_position = ball_v3(10.0, 1.0, 5.0);
  m.initial_velocity = ball_v3(8.0, 2.0, 1.0);
  assert_int_equal(run_events(&m, &sim, 1.0 / 60.0, 30, &ev), 0);
  assert_ok(ball_sim_state(&sim, &s));
  assert_true(s.position.x > 11.885);
  /* just under the top: a hit */
  m.initial_position = ball_v3(10.0, 0.7, 5.0);
  assert_true(run_events(&m, &sim, 1.0 / 60.0, 30, &ev) >= 1);
  assert_int_equal(ev.kind, BALL_EVENT_NET);
}

/* Walls on a z plane and an x plane (Fig. 3 on other planes, eq 6 with the
 * wall's damping 0.5). Both cases need b (1 - e^(-t/b)) = 0.5 (f = 0.75):
 * t = 2 ln(4/3) = 0.57536414490356185 s, y = 1 + 2 t - g t^2 / 2 =
 * 0.52695796403194675 m, vy = -3.6443222615039418 m/s. */
static void eq6_walls_on_z_and_x_planes_reflect_the_normal_component(void **state) {
  ball_model m;
  ball_sim sim;
  ball_event ev;
  ball_plane zwall = {2, 3.0, -5.0, 5.0, 0.0, 3.0, 0.5};
  ball_plane xwall = {0, -2.0, -1.0, 1.0, 0.0, 3.0, 0.5};
  (void)state;
  core_model_free(&m);
  m.effects |= BALL_EFFECT_WALLS;
  assert_ok(ball_model_add_wall(&m, &xwall));
  assert_ok(ball_model_add_wall(&m, &zwall));
  m.initial_position = ball_v3(0.0, 1.0, 0.0);
  m.initial_velocity = ball_v3(1.0, 2.0, 6.0);
  /* one hit in 0.67 s (the floor comes at 0.78 s) */
  assert_int_equal(run_events(&m, &sim, 1.0 / 60.0, 40, &ev), 1);
  assert_int_equal(ev.kind, BALL_EVENT_WALL);
  assert_int_equal(ev.index, 1);
  assert_near(ev.time, 0.57536414490356185, TOL);
  assert_near(ev.point.x, 0.5, TOL);
  assert_near(ev.point.y, 0.52695796403194675, TOL);
  assert_near(ev.point.z, 3.0, TOL);
  assert_near(ev.velocity_out.x, 0.75 * 0.5, TOL);
  assert_near(ev.velocity_out.y, -3.6443222615039418 * 0.5, TOL);
  assert_near(ev.velocity_out.z, -4.5 * 0.5, TOL);

  m.initial_velocity = ball_v3(-4.0, 2.0, 0.0);
  assert_int_equal(run_events(&m, &sim, 1.0 / 60.0, 40, &ev), 1);
  assert_int_equal(ev.kind, BALL_EVENT_WALL);
  assert_int_equal(ev.index, 0);
  assert_near(ev.time, 0.57536414490356185, TOL);
  assert_near(ev.point.x, -2.0, TOL);
  assert_near(ev.velocity_out.x, 3.0 * 0.5, TOL);
  assert_near(ev.velocity_out.y, -3.6443222615039418 * 0.5, TOL);
  assert_true(ev.velocity_out.z == 0.0);

  /* the sampled scheme finds the same walls (at the end of the frame) */
  m.scheme = BALL_SCHEME_SAMPLED;
  assert_true(run_events(&m, &sim, 1.0 / 60.0, 40, &ev) >= 1);
  assert_int_equal(ev.kind, BALL_EVENT_WALL);
  assert_int_equal(ev.index, 0);
  assert_true(ev.time >= 0.57536414490356185 && ev.time < 0.57536414490356185 + 1.0 / 60.0);
  assert_near(ev.point.x, -2.0, TOL);
  assert_true(sim.seg.p0.x > -2.0);
}

/* A ball of radius 0.1 touches the net when its centre is 0.1 m before the
 * plane, on whichever side it comes from: from x0 = 10 it needs
 * 2 (1 - e^(-t/2)) = 1.785 / 8: t = 0.23658195427363626 s. */
static void fig3_radius_moves_the_contact_plane_toward_the_ball(void **state) {
  ball_model m;
  ball_sim sim;
  ball_event ev;
  ball_plane zwall = {2, 3.0, -5.0, 5.0, 0.0, 3.0, 0.5};
  const ball_scheme scheme = test_scheme(state);
  net_model(&m);
  m.radius = 0.1;
  m.scheme = scheme;
  assert_true(run_events(&m, &sim, 1.0 / 60.0, 30, &ev) >= 1);
  assert_int_equal(ev.kind, BALL_EVENT_NET);
  assert_near(ev.point.x, 11.885 - 0.1, TOL);
  if (scheme == BALL_SCHEME_EXACT) assert_near(ev.time, 0.23658195427363626, TOL);
  m.initial_position = ball_v3(13.77, 0.5, 5.0);
  m.initial_velocity = ball_v3(-8.0, 2.0, 1.0);
  assert_true(run_events(&m, &sim, 1.0 / 60.0, 30, &ev) >= 1);
  assert_int_equal(ev.kind, BALL_EVENT_NET);
  assert_near(ev.point.x, 11.885 + 0.1, TOL);
  /* a z wall approached along +z: the centre stops at z = 3 - 0.1 */
  core_model_free(&m);
  m.radius = 0.1;
  m.scheme = scheme;
  m.effects |= BALL_EFFECT_WALLS;
  assert_ok(ball_model_add_wall(&m, &zwall));
  m.initial_position = ball_v3(0.0, 1.0, 0.0);
  m.initial_velocity = ball_v3(1.0, 2.0, 6.0);
  assert_true(run_events(&m, &sim, 1.0 / 60.0, 40, &ev) >= 1);
  assert_int_equal(ev.kind, BALL_EVENT_WALL);
  assert_near(ev.point.z, 2.9, TOL);
}

/* A big ball (r = 0.3 m) started overlapping the net's top edge (its
 * centre 0.2 m from the plane, 0.0374 m above the top: 0.203 m from the
 * edge), moving up off it and along it, comes clear after 0.15 s, its top
 * 7.5 mm clear at 0.2 s, and comes back onto the edge before 0.25 s. The
 * search follows a ball out of an overlap in doubling steps; one from
 * 0.141 s to 0.281 s passed over the whole time it was clear, and the
 * contact was found at 0.281 s with the centre 0.284 m from the edge, 16 mm
 * inside. Exact scheme: the first contact is where the path (bisected
 * through ball_segment_eval) first comes back to r from the edge. */
static double edge_gap(const ball_model *m, const ball_segment *seg, double t) {
  ball_state s;
  assert_ok(ball_segment_eval(m, seg, t, &s));
  return hypot(s.position.x - 11.885, s.position.y - 0.914) - m->radius;
}

static void a_ball_started_on_the_nets_edge_meets_it_again_where_it_touches(void **state) {
  ball_model m;
  ball_sim sim;
  ball_event ev;
  ball_segment seg;
  double lo, hi, dy_touch = sqrt(0.3 * 0.3 - 0.2 * 0.2), vy;
  int k;
  (void)state;
  net_model(&m);
  m.radius = 0.3;
  vy = 0.2 * m.gravity; /* the top at 0.2 s */
  m.initial_position = ball_v3(11.885 - 0.2, 0.914 + dy_touch + 0.01 - vy * vy / (2.0 * m.gravity), 8.0);
  m.initial_velocity = ball_v3(0.0, vy, -3.0);
  assert_ok(ball_sim_init(&sim, &m));
  seg = sim.seg;
  assert_true(edge_gap(&m, &seg, 0.0) < -0.09); /* overlapping at the start */
  assert_true(edge_gap(&m, &seg, 0.2) > 0.007); /* clear at the top */
  /* the truth: the gap's root after the top (it falls from there) */
  lo = 0.2;
  hi = 0.3;
  assert_true(edge_gap(&m, &seg, hi) < 0.0);
  for (k = 0; k < 200 && hi - lo > 1e-15; k++) {
    double mid = 0.5 * (lo + hi);
    if (edge_gap(&m, &seg, mid) > 0.0) lo = mid;
    else hi = mid;
  }
  assert_true(run_events(&m, &sim, 1.0 / 60.0, 18, &ev) >= 1);
  assert_int_equal(ev.kind, BALL_EVENT_NET);
  assert_near(ev.time, lo, 1e-9);
  assert_near(hypot(ev.point.x - 11.885, ev.point.y - 0.914), m.radius, 1e-9);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(eq6_exact_net_reflection_matches_hand_values),
      cmocka_unit_test(eq6_sampled_net_hit_shifts_dt_over_10_along_new_velocity),
      EACH_SCHEME(fig3_ball_beside_or_above_the_net_passes),
      cmocka_unit_test(eq6_walls_on_z_and_x_planes_reflect_the_normal_component),
      EACH_SCHEME(fig3_radius_moves_the_contact_plane_toward_the_ball),
      cmocka_unit_test(a_ball_started_on_the_nets_edge_meets_it_again_where_it_touches),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
