/* A ball with a radius against the net and the walls as rectangles grown by
 * the radius: the face, four edge cylinders, four corner spheres
 * (docs/design.md R15; docs/model.md, "Ball radius, edges and corners").
 * The cases: that section's example, a ball drifting onto the top edge, a
 * side edge, a corner, a graze that passes, both schemes; the response about the contact normal by hand; the
 * sampled scheme's dt / 10 push in frames of seconds; and after every
 * contact the ball never inside the grown rectangle. */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "core_common.h"

/* The distance from c to the rectangle pl (its nearest point). */
static double rect_distance(const ball_plane *pl, ball_vec3 c) {
  double d;
  assert_ok(ball_sphere_rect_distance(pl, c, 0.0, &d));
  return d;
}

/* What run_net checks after each frame, and the net events it keeps. */
typedef struct net_watch {
  const ball_model *m;
  double dt;
  ball_segment before; /* the segment at the start of the frame */
  double t0;           /* the time at the start of the frame, s */
  ball_event *out;
  int cap, got;
} net_watch;

static int watch_net(void *ctx, ball_sim *sim, const steps_tally *t, const ball_event *ev, int n) {
  net_watch *w = ctx;
  const ball_model *m = w->m;
  const double tol = 1e-9;
  unsigned long f = t->frames - 1;
  ball_state s;
  int i;
  for (i = 0; i < n; i++)
    if (ev[i].kind == BALL_EVENT_NET) {
      if (w->got < w->cap) w->out[w->got] = ev[i];
      w->got++;
    }
  assert_ok(ball_sim_state(sim, &s));
  if (rect_distance(&m->net, s.position) < m->radius - tol)
    fail_msg("frame %lu: inside the grown net (%.17g < r = %.17g)", f, rect_distance(&m->net, s.position),
             m->radius);
  if (m->scheme == BALL_SCHEME_EXACT && n == 0) {
    int k;
    for (k = 1; k <= 16; k++) {
      ball_state p;
      assert_ok(ball_segment_eval(m, &w->before, w->t0 + w->dt * k / 16.0, &p));
      if (rect_distance(&m->net, p.position) < m->radius - tol)
        fail_msg("frame %lu: the path went into the grown net without an event", f);
    }
  }
  w->before = sim->seg;
  w->t0 = sim->time;
  return 1;
}

/* Steps frames of dt; returns the net events (up to cap) and checks that
 * the ball never ends a frame inside the net grown by its radius, nor (in
 * the exact scheme) anywhere on the frame's path when the frame had no net
 * event (16 points of the segment). */
static int run_net(const ball_model *m, ball_sim *sim, int frames, double dt, ball_event *out, int cap) {
  net_watch w;
  w.m = m;
  w.dt = dt;
  w.before = sim->seg;
  w.t0 = sim->time;
  w.out = out;
  w.cap = cap;
  w.got = 0;
  steps_each(sim, dt, (unsigned long)frames, NULL, watch_net, &w);
  return w.got;
}

static void net_model(ball_model *m, ball_scheme scheme, double radius) {
  ball_model_default(m);
  m->effects = BALL_EFFECT_FLOOR | BALL_EFFECT_NET;
  m->scheme = scheme;
  m->radius = radius;
}

/* The response about n, by hand: v0 = netDamping (v - 2 (v . n) n). */
static void assert_reflected_about(const ball_event *e, const ball_plane *net, double r) {
  ball_vec3 q, n;
  double d;
  /* the contact normal from the nearest point of the net to the centre, at
   * the radius (1e-9: the root is refined to adjacent doubles in time) */
  assert_ok(ball_sphere_rect_distance(net, e->point, 0.0, &d));
  assert_near(d, r, 1e-9);
  q = e->point;
  q.x = net->position;
  if (q.y > net->top) q.y = net->top;
  if (q.z > net->hi) q.z = net->hi;
  if (q.z < net->lo) q.z = net->lo;
  n = ball_v3_unit(ball_v3_sub(e->point, q));
  {
    double vn = ball_v3_dot(e->velocity_in, n);
    ball_vec3 want = ball_v3_scale(ball_v3_sub(e->velocity_in, ball_v3_scale(n, 2.0 * vn)), net->damping);
    assert_near(e->velocity_out.x, want.x, 1e-12);
    assert_near(e->velocity_out.y, want.y, 1e-12);
    assert_near(e->velocity_out.z, want.z, 1e-12);
    assert_true(vn < 0.0); /* it was arriving */
  }
}

/* The example of docs/model.md, "Ball radius, edges and corners": a 0.1 m ball at (11.735, 2.0, 5.0) drifting at
 * (0.3, 0, 0) onto the default net. It reaches the net's plane (x = 11.785)
 * at 1.86 m, above the top: the face test saw nothing, and it fell through.
 * Now it meets the top edge's cylinder when
 * (11.735 + 0.3 t - 11.885)^2 + (2 - g t^2 / 2 - 0.914)^2 = 0.1^2, near
 * t = 0.449 s, and bounces up about that normal. */
static void test_ball_drifting_onto_the_top_edge_bounces_off_it(void **state) {
  const ball_scheme scheme = test_scheme(state);
  ball_model m;
  ball_sim sim;
  ball_event ev[8];
  int n;
  net_model(&m, scheme, 0.1);
  core_start(&m, &sim, ball_v3(11.735, 2.0, 5.0), ball_v3(0.3, 0.0, 0.0));
  n = run_net(&m, &sim, 600, 1.0 / 60.0, ev, 8);
  assert_true(n >= 1);
  if (scheme == BALL_SCHEME_EXACT) {
    double t = ev[0].time, x = 11.735 + 0.3 * t, y = 2.0 - 0.5 * 9.81 * t * t;
    /* on the cylinder: the root of the equation above */
    assert_near(sqrt((x - 11.885) * (x - 11.885) + (y - 0.914) * (y - 0.914)), 0.1, 1e-12);
    assert_true(t > 0.448 && t < 0.45);
    assert_reflected_about(&ev[0], &m.net, 0.1);
    assert_true(ev[0].velocity_out.y > 0.0); /* up and off the edge */
  } else {
    /* the sampled scheme: on the frame's chord, at the frame's end */
    double d;
    assert_ok(ball_sphere_rect_distance(&m.net, ev[0].point, 0.0, &d));
    assert_near(d, 0.1, 1e-9);
  }
}

/* Past a side edge: the ball comes in at z = hi + 0.05 (beside the net, but
 * within its radius 0.1 of the edge) at the height of the net's middle. The
 * face test passes it by; the vertical edge's cylinder
 * (x - 11.885)^2 + (z - 10.97)^2 = 0.01 meets it at x = 11.885 - sqrt(0.0075). */
static void test_ball_passing_a_side_edge_within_its_radius_hits_it(void **state) {
  const ball_scheme scheme = test_scheme(state);
  ball_model m;
  ball_sim sim;
  ball_event ev[8];
  int n;
  net_model(&m, scheme, 0.1);
  m.effects = BALL_EFFECT_NET; /* no floor, no fall to speak of */
  m.gravity = BALL_MIN_GRAVITY;
  core_start(&m, &sim, ball_v3(10.0, 0.5, 10.97 + 0.05), ball_v3(4.0, 0.0, 0.0));
  n = run_net(&m, &sim, 120, 1.0 / 240.0, ev, 8);
  assert_int_equal(n, 1);
  if (scheme == BALL_SCHEME_EXACT) {
    assert_near(ev[0].point.x, 11.885 - sqrt(0.0075), 1e-9);
    assert_reflected_about(&ev[0], &m.net, 0.1);
    /* the normal (-sqrt(0.75), 0, 0.5): v_out = 0.2 (4 - 2 (4)(0.75), 0, -2 (-2 sqrt(0.75))(0.5) ...) */
    assert_near(ev[0].velocity_out.x, 0.2 * (4.0 - 2.0 * 4.0 * 0.75), 1e-6);
    assert_near(ev[0].velocity_out.z, 0.2 * (2.0 * 4.0 * sqrt(0.75) * 0.5), 1e-6);
  }
}

/* Toward the top corner (x = 11.885, y = 0.914, z = 10.97) along the
 * diagonal: the corner's sphere, the normal along (-1, 1, 1) / sqrt(3). */
static void test_ball_at_a_corner_reflects_about_the_corner_normal(void **state) {
  ball_model m;
  ball_sim sim;
  ball_event ev[8];
  double a = 0.1 / sqrt(3.0);
  int n;
  (void)state;
  net_model(&m, BALL_SCHEME_EXACT, 0.1);
  m.effects = BALL_EFFECT_NET;
  m.gravity = BALL_MIN_GRAVITY;
  /* from 1 m away along (-1, 1, 1), moving back along (1, -1, -1) */
  core_start(&m, &sim, ball_v3(11.885 - 1.0, 0.914 + 1.0, 10.97 + 1.0), ball_v3(2.0, -2.0, -2.0));
  n = run_net(&m, &sim, 240, 1.0 / 240.0, ev, 8);
  assert_int_equal(n, 1);
  assert_near(ev[0].point.x, 11.885 - a, 1e-6);
  assert_near(ev[0].point.y, 0.914 + a, 1e-6);
  assert_near(ev[0].point.z, 10.97 + a, 1e-6);
  /* head-on: straight back, times 0.2 */
  assert_near(ev[0].velocity_out.x, -0.4, 1e-5);
  assert_near(ev[0].velocity_out.y, 0.4, 1e-5);
  assert_near(ev[0].velocity_out.z, 0.4, 1e-5);
}

/* A graze that passes: beside the side edge by more than the radius (1e-6
 * m more) nothing happens; by 1e-6 m less, a contact. */
static void test_a_graze_just_outside_the_radius_passes(void **state) {
  static const double off[] = {1e-6, -1e-6};
  int i;
  for (i = 0; i < 2; i++) {
    ball_model m;
    ball_sim sim;
    ball_event ev[8];
    net_model(&m, test_scheme(state), 0.1);
    m.effects = BALL_EFFECT_NET;
    m.gravity = BALL_MIN_GRAVITY;
    core_start(&m, &sim, ball_v3(10.0, 0.5, 10.97 + 0.1 + off[i]), ball_v3(4.0, 0.0, 0.0));
    assert_int_equal(run_net(&m, &sim, 120, 1.0 / 240.0, ev, 8), i == 0 ? 0 : 1);
  }
}

/* The point ball has no edges: exactly the paper's Fig. 3 (the grazing tests
 * of test_hard_contacts.c hold it to the bit). From the same start it
 * reaches the net's plane x = 11.885 at t = 0.5 s, at y = 2 - g / 8 = 0.77375
 * m, below the top: the face, as before. */
static void test_the_point_ball_keeps_fig3(void **state) {
  ball_model m;
  ball_sim sim;
  ball_event ev[8];
  (void)state;
  net_model(&m, BALL_SCHEME_EXACT, 0.0);
  core_start(&m, &sim, ball_v3(11.735, 2.0, 5.0), ball_v3(0.3, 0.0, 0.0));
  assert_int_equal(run_net(&m, &sim, 60, 1.0 / 60.0, ev, 8), 1);
  assert_near(ev[0].time, 0.5, 1e-12);
  assert_near(ev[0].point.y, 2.0 - 9.81 / 8.0, 1e-12);
  assert_near(ev[0].velocity_out.x, -0.3 * 0.2, 0.0);
}

/* The sampled scheme in frames of 2 s: the paper's dt / 10 push after a
 * wall is 6 m at 30 m/s, more than the 4 m box; it stops short of the wall
 * behind, so the ball stays in the box (25 random scenes tunnelled before). */
static void test_the_sampled_push_stops_short_of_the_next_wall(void **state) {
  ball_model m;
  ball_sim sim;
  ball_plane w0 = {0, 0.0, -1e4, 1e4, -1e6, 1e6, 1.0}, w1 = {0, 4.0, -1e4, 1e4, -1e6, 1e6, 1.0};
  int f;
  (void)state;
  ball_model_default(&m);
  m.effects = BALL_EFFECT_WALLS;
  m.scheme = BALL_SCHEME_SAMPLED;
  m.gravity = BALL_MIN_GRAVITY;
  m.radius = 0.05;
  assert_ok(ball_model_add_wall(&m, &w0));
  assert_ok(ball_model_add_wall(&m, &w1));
  core_start(&m, &sim, ball_v3(2.0, 1.0, 0.0), ball_v3(30.0, 0.0, 0.0));
  for (f = 0; f < 50; f++) {
    assert_ok(ball_step(&sim, 2.0, NULL, 0, NULL));
    if (!(sim.prev_position.x > 0.0 && sim.prev_position.x < 4.0))
      fail_msg("frame %d: out of the box at x = %.17g", f, sim.prev_position.x);
  }
}

int main(void) {
  const struct CMUnitTest tests[] = {
      EACH_SCHEME(test_ball_drifting_onto_the_top_edge_bounces_off_it),
      EACH_SCHEME(test_ball_passing_a_side_edge_within_its_radius_hits_it),
      cmocka_unit_test(test_ball_at_a_corner_reflects_about_the_corner_normal),
      EACH_SCHEME(test_a_graze_just_outside_the_radius_passes),
      cmocka_unit_test(test_the_point_ball_keeps_fig3),
      cmocka_unit_test(test_the_sampled_push_stops_short_of_the_next_wall),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
