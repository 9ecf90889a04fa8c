/* The swept racket test (beyond the paper): time of impact of a ball against
 * a moving, turning disc, against cases solvable by hand. ball_swept_disc
 * promises the time on [0, 1] to 1e-12; the stepper's variant (the ball on
 * its analytic flight) to 1e-9 s. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "core_common.h"
#include "../internal.h"

#define TOI_TOL 1e-12

static ball_swept_query query(ball_vec3 p0, ball_vec3 p1, double r, ball_vec3 c0, ball_vec3 c1, ball_vec3 n0,
                              ball_vec3 n1, double disc_r) {
  ball_swept_query q;
  q.p0 = p0;
  q.p1 = p1;
  q.ball_radius = r;
  q.c0 = c0;
  q.c1 = c1;
  q.n0 = n0;
  q.n1 = n1;
  q.disc_radius = disc_r;
  return q;
}

static void swept_ball_straight_at_still_disc_toi_by_hand(void **state) {
  ball_vec3 o = ball_v3(0, 0, 0), x = ball_v3(1, 0, 0), pt;
  ball_swept_query q = query(ball_v3(2, 0.05, 0), ball_v3(-2, 0.05, 0), 0.1, o, o, x, x, 0.15);
  double toi = -1;
  int hit = 0;
  (void)state;
  /* surface at the face when x = 0.1: toi = (2 - 0.1) / 4 = 0.475 */
  assert_ok(ball_swept_disc(&q, &hit, &toi, &pt));
  assert_int_equal(hit, 1);
  assert_near(toi, 0.475, TOI_TOL);
  assert_near(pt.x, 0.1, 4 * TOI_TOL);
  assert_near(pt.y, 0.05, 0.0);
}

static void swept_point_ball_passes_through_disc_toi_by_hand(void **state) {
  ball_vec3 o = ball_v3(0, 0, 0), x = ball_v3(1, 0, 0);
  ball_swept_query q = query(ball_v3(1, 0.05, 0), ball_v3(-3, 0.05, 0), 0.0, o, o, x, x, 0.15);
  double toi = -1;
  int hit = 0;
  (void)state;
  /* a point ball (the paper's) crosses the plane at x = 0: toi = 1 / 4 */
  assert_ok(ball_swept_disc(&q, &hit, &toi, NULL));
  assert_int_equal(hit, 1);
  assert_near(toi, 0.25, TOI_TOL);
  /* beside the disc (0.2 m off its axis): no hit */
  q.p0.y = q.p1.y = 0.2;
  assert_ok(ball_swept_disc(&q, &hit, &toi, NULL));
  assert_int_equal(hit, 0);
}

static void swept_racket_overtaking_ball_from_behind_toi_by_hand(void **state) {
  ball_vec3 x = ball_v3(1, 0, 0);
  /* ball 0.5 -> 1.5 (1 m per frame), racket 0 -> 3 behind it: the gap
   * 0.5 - 0.05 closes at 2 per frame: toi = 0.225; at the frame's end the
   * racket is 1.5 m ahead of the ball, so the sphere test sees nothing */
  ball_swept_query q = query(ball_v3(0.5, 0, 0), ball_v3(1.5, 0, 0), 0.05, ball_v3(0, 0, 0), ball_v3(3, 0, 0), x, x,
                             0.15);
  double toi = -1;
  int hit = 0;
  ball_vec3 pt;
  (void)state;
  assert_ok(ball_swept_disc(&q, &hit, &toi, &pt));
  assert_int_equal(hit, 1);
  assert_near(toi, 0.225, TOI_TOL);
  assert_near(pt.x, 0.725, 4 * TOI_TOL);
  assert_false(ball__sphere_test(q.p1, q.c1, 0.3));
}

static void swept_turning_disc_toi_by_hand(void **state) {
  /* a still ball at (0, 0.1, 0), radius 0.02; the disc at the origin turns
   * from normal (0, 1, 0) to (1, 0, 0) (normalised lerp: n = (u, 1-u, 0)/|.|),
   * bringing its plane onto the ball. Contact when
   * 0.1 (1-u) / sqrt(u^2 + (1-u)^2) = 0.02, i.e. sqrt(24) (1-u) = u:
   * u = sqrt(24) / (1 + sqrt(24)); the centre is then 0.098 m off the axis, on the face. */
  ball_vec3 p = ball_v3(0, 0.1, 0), o = ball_v3(0, 0, 0);
  ball_swept_query q = query(p, p, 0.02, o, o, ball_v3(0, 1, 0), ball_v3(1, 0, 0), 0.15);
  double toi = -1, want = sqrt(24.0) / (1.0 + sqrt(24.0));
  int hit = 0;
  (void)state;
  assert_ok(ball_swept_disc(&q, &hit, &toi, NULL));
  assert_int_equal(hit, 1);
  assert_near(toi, want, TOI_TOL);
  /* a normal given with the opposite sign is the same disc */
  q.n0 = ball_v3(0, -1, 0);
  q.n1 = ball_v3(-1, 0, 0);
  assert_ok(ball_swept_disc(&q, &hit, &toi, NULL));
  assert_int_equal(hit, 1);
  assert_near(toi, want, TOI_TOL);
  /* turning only 5.7 degrees it stays clear: the ball is 0.1 / sqrt(1.01) > 0.02 from the plane */
  q.n1 = ball_v3(-0.1, -1, 0);
  assert_ok(ball_swept_disc(&q, &hit, &toi, NULL));
  assert_int_equal(hit, 0);
}

static void swept_ball_hits_the_rim_edge_on(void **state) {
  /* the disc lies in the plane x = 0; the ball moves along -y inside that
   * plane and meets the rim when y = 0.15 + 0.05: toi = (0.5 - 0.2) / 1 */
  ball_vec3 o = ball_v3(0, 0, 0), x = ball_v3(1, 0, 0);
  ball_swept_query q = query(ball_v3(0, 0.5, 0), ball_v3(0, -0.5, 0), 0.05, o, o, x, x, 0.15);
  double toi = -1;
  int hit = 0;
  (void)state;
  assert_ok(ball_swept_disc(&q, &hit, &toi, NULL));
  assert_int_equal(hit, 1);
  assert_near(toi, 0.3, TOI_TOL);
}

static void swept_shallow_rim_graze_found_between_substeps(void **state) {
  /* the ball passes the rim at (0.03, 0.17, z), z: -1 -> 1. Its least distance
   * to the disc is hypot(0.03, 0.02) = 0.0360555 m; with radius 0.0362 it
   * overlaps for only |z| < 0.003. First contact (30 digits):
   * z = -sqrt((0.15 + sqrt(r^2 - 0.03^2))^2 - 0.17^2), toi = (z + 1) / 2 */
  ball_vec3 o = ball_v3(0, 0, 0), x = ball_v3(1, 0, 0);
  ball_swept_query q = query(ball_v3(0.03, 0.17, -1), ball_v3(0.03, 0.17, 1), 0.0362, o, o, x, x, 0.15);
  double toi = -1;
  int hit = 0;
  (void)state;
  assert_ok(ball_swept_disc(&q, &hit, &toi, NULL));
  assert_int_equal(hit, 1);
  assert_near(toi, 0.495303308264565559, 1e-10); /* the root is flat: dist' ~ 0 there */
  /* 0.0005 m thinner, no contact */
  q.ball_radius = 0.0355;
  assert_ok(ball_swept_disc(&q, &hit, &toi, NULL));
  assert_int_equal(hit, 0);
}

static void swept_touching_at_start_is_contact_at_zero(void **state) {
  ball_vec3 o = ball_v3(0, 0, 0), x = ball_v3(1, 0, 0);
  ball_swept_query q = query(ball_v3(0.01, 0, 0), ball_v3(1, 0, 0), 0.05, o, o, x, x, 0.15);
  double toi = -1;
  int hit = 0;
  (void)state;
  assert_ok(ball_swept_disc(&q, &hit, &toi, NULL));
  assert_int_equal(hit, 1);
  assert_near(toi, 0.0, 0.0);
}

static void swept_rejects_bad_queries(void **state) {
  ball_vec3 o = ball_v3(0, 0, 0), x = ball_v3(1, 0, 0);
  ball_swept_query q = query(ball_v3(1, 0, 0), ball_v3(-1, 0, 0), 0.05, o, o, x, x, 0.15), bad;
  double toi = 42;
  int hit = 7;
  (void)state;
  bad = q;
  bad.p1.x = NAN;
  assert_int_equal(ball_swept_disc(&bad, &hit, &toi, NULL), BALL_ENONFINITE);
  bad = q;
  bad.n1 = ball_v3(1e-12, 0, 0);
  assert_int_equal(ball_swept_disc(&bad, &hit, &toi, NULL), BALL_ERANGE);
  bad = q;
  bad.ball_radius = -0.1;
  assert_int_equal(ball_swept_disc(&bad, &hit, &toi, NULL), BALL_ERANGE);
  assert_int_equal(ball_swept_disc(NULL, &hit, &toi, NULL), BALL_EINVAL);
  assert_int_equal(ball_swept_disc(&q, NULL, &toi, NULL), BALL_EINVAL);
  assert_near(toi, 42.0, 0.0);
}

static void swept_analytic_flight_ball_dropped_on_still_disc_toi_to_1e9(void **state) {
  /* the stepper's variant: the ball falls from rest at y = 1 on eq 3's
   * path onto a horizontal disc at the origin; its surface (radius 0.02)
   * touches when 1 - g t^2 / 2 = 0.02: t = sqrt(0.98 / 4.905) = 0.44698559976987065 s */
  ball_model m;
  ball__flight fl;
  ball_segment seg = core_segment(10.0, ball_v3(0, 1, 0), ball_v3(0, 0, 0), ball_v3(0, 0, 0));
  ball__swept_motion mo;
  double t = 0;
  ball_vec3 c, face;
  (void)state;
  core_model_free(&m);
  ball__flight_of(&m, &fl);
  mo.flight = &fl;
  mo.seg = &seg;
  mo.probes_used = NULL;
  mo.ta = 10.0;
  mo.tb = 10.5;
  mo.p0 = seg.p0;
  mo.p1 = seg.p0;
  mo.ball_radius = 0.02;
  mo.tc0 = 10.0;
  mo.tc1 = 10.5;
  mo.c0 = mo.c1 = ball_v3(0, 0, 0);
  mo.n0 = mo.n1 = ball_v3(0, -1, 0); /* tracked upside down: the face turns to the ball */
  mo.disc_radius = 0.15;
  assert_int_equal(ball__swept_toi(&mo, &t, &c, &face), 1);
  assert_near(t, 10.0 + 0.44698559976987065, 1e-9);
  assert_near(c.y, 0.02, 1e-8);
  assert_near(face.y, 1.0, 0.0);
  /* the same disc rising at 1 m/s meets it earlier:
   * 1 - g t^2 / 2 = 0.02 + t  ->  t = (-1 + sqrt(1 + 2 g 0.98)) / g */
  mo.c1 = ball_v3(0, 0.5, 0);
  assert_int_equal(ball__swept_toi(&mo, &t, &c, &face), 1);
  assert_near(t, 10.0 + (-1.0 + sqrt(1.0 + 2.0 * 9.81 * 0.98)) / 9.81, 1e-9);
}

/* ball_swept_disc once took 32 ms in one call on extreme but finite inputs
 * (docs/hard-cases.md, "The catalogue"). The search's work is bounded: at most 2048 distance evaluations
 * (plus the root refinements' share of the budget), whatever the input. */
static void swept_work_is_bounded_on_extreme_inputs(void **state) {
  static const double big[] = {1e-300, 1e-9, 1.0, 1e9, 1e150, 1e300};
  core_rng r;
  int i, worst = 0;
  (void)state;
  r.s = 31337;
  for (i = 0; i < 3000; i++) {
    ball__swept_motion mo;
    double t, s = big[(int)core_uniform(&r, 0.0, 6.0) % 6], rb = big[(int)core_uniform(&r, 0.0, 6.0) % 6];
    ball_vec3 c, face;
    int used = 0;
    memset(&mo, 0, sizeof mo);
    mo.ta = 0.0;
    mo.tb = 1.0;
    mo.tc0 = 0.0;
    mo.tc1 = 1.0;
    mo.p0 = ball_v3(core_uniform(&r, -s, s), core_uniform(&r, -s, s), core_uniform(&r, -s, s));
    mo.p1 = ball_v3(core_uniform(&r, -s, s), core_uniform(&r, -s, s), core_uniform(&r, -s, s));
    mo.c0 = ball_v3(core_uniform(&r, -s, s), core_uniform(&r, -s, s), core_uniform(&r, -s, s));
    mo.c1 = ball_v3(core_uniform(&r, -s, s), core_uniform(&r, -s, s), core_uniform(&r, -s, s));
    mo.n0 = ball_v3(core_uniform(&r, -1, 1), core_uniform(&r, -1, 1), 1.0);
    mo.n1 = ball_v3(core_uniform(&r, -1, 1), 1.0, core_uniform(&r, -1, 1));
    mo.ball_radius = core_uniform(&r, 0.0, 1.0) < 0.3 ? 0.0 : rb * 1e-3;
    mo.disc_radius = rb;
    mo.probes_used = &used;
    (void)ball__swept_toi(&mo, &t, &c, &face);
    assert_true(used <= 2048);
    if (used > worst) worst = used;
  }
  assert_true(worst > 16); /* the inputs did make the search work */
}

/* The early reject never rejects a motion that touches: for random motions
 * (the analytic flight with drag and linear ones) it rejects, the distance
 * sampled densely over the interval stays above the ball's radius. */
static void swept_early_reject_is_sound(void **state) {
  core_rng r;
  int i, rejected = 0, kept = 0;
  (void)state;
  r.s = 4242;
  for (i = 0; i < 4000; i++) {
    ball_model m;
    ball__flight fl;
    ball_segment seg;
    ball__swept_motion mo;
    ball_state sa, sb;
    int k;
    core_model_free(&m);
    m.air_friction = core_uniform(&r, 0.0, 1.0) < 0.3 ? 0.0 : core_uniform(&r, 0.001, 1.0);
    ball__flight_of(&m, &fl);
    seg = core_segment(0.0, ball_v3(0, 1, 0),
                       ball_v3(core_uniform(&r, -30, 30), core_uniform(&r, -10, 10), core_uniform(&r, -30, 30)),
                       ball_v3(0, 0, 0));
    memset(&mo, 0, sizeof mo);
    mo.flight = core_uniform(&r, 0.0, 1.0) < 0.7 ? &fl : NULL;
    mo.seg = &seg;
    mo.ta = core_uniform(&r, 0.0, 0.5);
    mo.tb = mo.ta + core_uniform(&r, 0.0, 0.5);
    ball__eval_f(&fl, &seg, mo.ta, &sa);
    ball__eval_f(&fl, &seg, mo.tb, &sb);
    mo.p0 = sa.position;
    mo.p1 = sb.position;
    mo.tc0 = mo.ta - core_uniform(&r, 0.0, 0.1);
    mo.tc1 = mo.tb;
    mo.c0 = ball_v3_add(sa.position, ball_v3(core_uniform(&r, -2, 2), core_uniform(&r, -2, 2), core_uniform(&r, -2, 2)));
    mo.c1 = ball_v3_add(sb.position, ball_v3(core_uniform(&r, -2, 2), core_uniform(&r, -2, 2), core_uniform(&r, -2, 2)));
    mo.n0 = mo.n1 = ball_v3(1, 0, 0);
    mo.ball_radius = core_uniform(&r, 0.0, 0.2);
    mo.disc_radius = core_uniform(&r, 0.05, 0.5);
    if (!ball__swept_cannot_touch(&mo)) {
      kept++;
      continue;
    }
    rejected++;
    for (k = 0; k <= 2000; k++) {
      double t = mo.ta + (mo.tb - mo.ta) * k / 2000.0, span = mo.tc1 - mo.tc0;
      ball_vec3 p = mo.flight ? (ball__eval_f(&fl, &seg, t, &sa), sa.position)
                              : ball_v3_lerp(mo.p0, mo.p1, mo.tb > mo.ta ? (t - mo.ta) / (mo.tb - mo.ta) : 1.0);
      ball_vec3 c = ball_v3_lerp(mo.c0, mo.c1, (t - mo.tc0) / span);
      /* the disc lies inside the sphere of its radius about its centre */
      if (!(ball_v3_dist(p, c) > mo.ball_radius + mo.disc_radius))
        fail_msg("motion %d rejected but within reach at t = %.17g", i, t);
    }
  }
  assert_true(rejected > 500 && kept > 500);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(swept_ball_straight_at_still_disc_toi_by_hand),
      cmocka_unit_test(swept_point_ball_passes_through_disc_toi_by_hand),
      cmocka_unit_test(swept_racket_overtaking_ball_from_behind_toi_by_hand),
      cmocka_unit_test(swept_turning_disc_toi_by_hand),
      cmocka_unit_test(swept_ball_hits_the_rim_edge_on),
      cmocka_unit_test(swept_shallow_rim_graze_found_between_substeps),
      cmocka_unit_test(swept_touching_at_start_is_contact_at_zero),
      cmocka_unit_test(swept_rejects_bad_queries),
      cmocka_unit_test(swept_analytic_flight_ball_dropped_on_still_disc_toi_to_1e9),
      cmocka_unit_test(swept_work_is_bounded_on_extreme_inputs),
      cmocka_unit_test(swept_early_reject_is_sound),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
