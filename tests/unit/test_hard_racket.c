/* Hard cases of rackets (docs/hard-cases.md, section 5), through the public
 * API only (ball_racket_push, ball_step with BALL_EFFECT_RACKETS): a still
 * racket (the velocity normal is undefined), a racket turning fast, zero,
 * tiny, huge and NaN normals, a racket overtaking the ball from behind,
 * samples with equal timestamps, a racket inside the ball. Every detection
 * test (sphere, disc, swept) and the responses of eq 7 and eq 11 are tried. */
#include <float.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <string.h>

#include <cmocka.h>

#include "core_common.h"

#define FRAME (1.0 / 60.0)

/* One racket, no drag, no spin, floor only, the ball at (0, 1.5, 0) flying
 * +x at v m/s toward a racket near x = 1. */
static void racket_model(ball_model *m, ball_detect detect, ball_response response, double v) {
  ball_model_default(m);
  m->effects = BALL_EFFECT_FLOOR | BALL_EFFECT_RACKETS;
  m->scheme = BALL_SCHEME_EXACT;
  m->n_rackets = 1;
  m->detect = detect;
  m->normal_mode = BALL_NORMAL_REAL;
  m->response = response;
  m->initial_position = ball_v3(0.0, 1.5, 0.0);
  m->initial_velocity = ball_v3(v, 0.0, 0.0);
  m->initial_spin = ball_v3(0.0, 0.0, 0.0);
}

/* Steps frames (steps.h checks the events); checks the state is finite,
 * counts racket hits and enforces the sleep rule (hits at least
 * sleep_frames + 1 frames apart). */
typedef struct racket_run {
  int hits;
  int last_hit_frame;
  ball_event first;
  const ball_model *m;
} racket_run;

static int racket_frame(void *ctx, ball_sim *sim, const steps_tally *t, const ball_event *ev, int n) {
  racket_run *r = ctx;
  ball_state st;
  int i, f = (int)t->frames - 1;
  assert_int_equal(ball_sim_state(sim, &st), BALL_OK);
  assert_finite3(st.position);
  assert_finite3(st.velocity);
  assert_finite3(st.spin);
  for (i = 0; i < n; i++) {
    if (ev[i].kind != BALL_EVENT_RACKET) continue;
    if (r->hits == 0) r->first = ev[i];
    if (r->hits > 0 && f - r->last_hit_frame <= r->m->sleep_frames)
      fail_msg("racket hits in frames %d and %d: closer than sleep_frames %d", r->last_hit_frame, f,
               r->m->sleep_frames);
    r->hits++;
    r->last_hit_frame = f;
  }
  return 1;
}

static void step_frames(const ball_model *m, ball_sim *sim, int frames, racket_run *r) {
  steps_tally t;
  r->m = m;
  steps_begin(&t, NULL, 0);
  steps_each(sim, FRAME, (unsigned long)frames, &t, racket_frame, r);
}

static const ball_detect detects[] = {BALL_DETECT_SPHERE, BALL_DETECT_DISC, BALL_DETECT_SWEPT};

/* A still racket at x = 1 facing the ball (two samples, same pose): its
 * velocity is zero, so the velocity normal is undefined and eq 7 has no
 * direction. Real or velocity normal mode, every test: exactly one hit, and
 * eq 7 sends the ball back along the face normal at v_min = 5 m/s; eq 11
 * reflects it: V0x = -10 m/s (no racket velocity, no spin). */
static void test_still_racket_hits_once_with_defined_direction_eq7_eq11(void **state) {
  size_t d;
  int resp, mode;
  (void)state;
  for (d = 0; d < 3; d++)
    for (resp = 0; resp < 2; resp++)
      for (mode = 0; mode < 2; mode++) {
        ball_model m;
        ball_sim sim;
        racket_run r;
        ball_racket_sample s;
        memset(&r, 0, sizeof r);
        racket_model(&m, detects[d], resp ? BALL_RESPONSE_PHYSICAL : BALL_RESPONSE_RACKET, 10.0);
        m.normal_mode = mode ? BALL_NORMAL_VELOCITY : BALL_NORMAL_REAL;
        assert_int_equal(ball_sim_init(&sim, &m), BALL_OK);
        s = core_sample(-0.1, ball_v3(1.0, 1.45, 0.0), ball_v3(-1.0, 0.0, 0.0));
        assert_int_equal(ball_racket_push(&sim, 0, &s), BALL_OK);
        s.t = 0.0;
        assert_int_equal(ball_racket_push(&sim, 0, &s), BALL_OK);
        step_frames(&m, &sim, 40, &r);
        if (r.hits != 1) fail_msg("detect %d response %d mode %d: %d hits", (int)d, resp, mode, r.hits);
        if (resp == 0) {
          assert_near(r.first.velocity_out.x, -5.0, 1e-12);
          assert_near(r.first.velocity_out.y, 0.0, 1e-12);
        } else {
          assert_near(r.first.velocity_out.x, -10.0, 1e-9);
        }
      }
}

/* A racket turning fast: the normal turns by 90 degrees and by 180 degrees
 * (exactly reversed: the other face) between samples 0.05 s apart (1800 and
 * 3600 degrees per second) while the ball passes through the disc: finite,
 * at most one hit per sleep period; with the reversed normal the disc stays
 * in the plane x = 1 and the disc and swept tests reflect the ball (eq 11). */
static void test_racket_turning_fast_stays_finite_fig4(void **state) {
  static const double turns[][3] = {{0.0, 1.0, 0.0}, {1.0, 0.0, 0.0}, {0.0, 0.0, 1.0}};
  size_t d, k;
  (void)state;
  for (d = 0; d < 3; d++)
    for (k = 0; k < 3; k++) {
      ball_model m;
      ball_sim sim;
      racket_run r;
      ball_racket_sample s;
      double t;
      int i;
      memset(&r, 0, sizeof r);
      racket_model(&m, detects[d], BALL_RESPONSE_PHYSICAL, 10.0);
      m.history = 4;
      assert_int_equal(ball_sim_init(&sim, &m), BALL_OK);
      for (i = 0, t = -0.1; i < 4; i++, t += 0.05) {
        ball_vec3 n = i % 2 ? ball_v3(turns[k][0], turns[k][1], turns[k][2]) : ball_v3(-1.0, 0.0, 0.0);
        s = core_sample(t, ball_v3(1.0, 1.45, 0.0), n);
        assert_int_equal(ball_racket_push(&sim, 0, &s), BALL_OK);
      }
      step_frames(&m, &sim, 40, &r);
      /* reversed normal: the same plane x = 1, so eq 11 must send the ball back */
      if (k == 1 && d > 0) {
        assert_int_equal(r.hits, 1);
        assert_near(r.first.velocity_out.x, -10.0, 1e-9);
      }
    }
}

/* Normals that cannot be normalised are refused and change nothing: zero,
 * length below 1e-9, subnormal, NaN, Inf. Huge components (DBL_MAX) and tiny
 * but valid ones (1e-8) are normalised without overflow or underflow. */
static void test_zero_tiny_huge_and_nan_normals(void **state) {
  static const double bad_range[][3] = {
      {0.0, 0.0, 0.0}, {1e-10, 0.0, 0.0}, {4.9406564584124654e-324, 0.0, 0.0}, {-0.0, 0.0, -0.0}};
  ball_model m;
  ball_sim sim, copy;
  ball_racket_sample s;
  ball_racket_pose pose;
  size_t i;
  (void)state;
  racket_model(&m, BALL_DETECT_DISC, BALL_RESPONSE_PHYSICAL, 10.0);
  assert_int_equal(ball_sim_init(&sim, &m), BALL_OK);
  s = core_sample(0.0, ball_v3(1.0, 1.45, 0.0), ball_v3(-1.0, 0.0, 0.0));
  assert_int_equal(ball_racket_push(&sim, 0, &s), BALL_OK);
  copy = sim;
  for (i = 0; i < sizeof bad_range / sizeof bad_range[0]; i++) {
    s = core_sample(0.1, ball_v3(1.0, 1.45, 0.0), ball_v3(bad_range[i][0], bad_range[i][1], bad_range[i][2]));
    assert_int_equal(ball_racket_push(&sim, 0, &s), BALL_ERANGE);
  }
  s.normal = ball_v3(NAN, 0.0, 1.0);
  assert_int_equal(ball_racket_push(&sim, 0, &s), BALL_ENONFINITE);
  s.normal = ball_v3(0.0, INFINITY, 0.0);
  assert_int_equal(ball_racket_push(&sim, 0, &s), BALL_ENONFINITE);
  s.normal = ball_v3(0.0, 1.0, 0.0);
  s.center.y = NAN;
  assert_int_equal(ball_racket_push(&sim, 0, &s), BALL_ENONFINITE);
  assert_memory_equal(&sim, &copy, sizeof sim);
  s = core_sample(0.1, ball_v3(1.0, 1.45, 0.0), ball_v3(DBL_MAX, -DBL_MAX, DBL_MAX));
  assert_int_equal(ball_racket_push(&sim, 0, &s), BALL_OK);
  assert_int_equal(ball_racket_estimate(&sim, 0, 0.1, &pose), BALL_OK);
  assert_near(pose.normal.x, 1.0 / sqrt(3.0), 1e-15);
  assert_near(pose.normal.y, -1.0 / sqrt(3.0), 1e-15);
  s = core_sample(0.2, ball_v3(1.0, 1.45, 0.0), ball_v3(0.0, 1e-8, 0.0));
  assert_int_equal(ball_racket_push(&sim, 0, &s), BALL_OK);
  assert_int_equal(ball_racket_estimate(&sim, 0, 0.2, &pose), BALL_OK);
  assert_near(pose.normal.y, 1.0, 1e-15);
}

/* A racket overtaking the ball from behind (the paper's warning after eq 7):
 * the ball flies +x at 5 m/s, the racket comes from behind at 20 m/s. The
 * face normal is flipped toward the ball's previous position (Fig. 9: +x),
 * eq 11 gives V0x = -5 + 20 = 15 m/s: the racket is still faster and meets
 * the ball again, but never within sleep_frames of the last hit, and
 * nothing goes non-finite. With eq 7 the ball leaves at the racket's 20 m/s. */
static void test_racket_overtaking_from_behind_eq7_eq11_fig9(void **state) {
  size_t d;
  int resp;
  (void)state;
  for (d = 0; d < 3; d++)
    for (resp = 0; resp < 2; resp++) {
      ball_model m;
      ball_sim sim;
      racket_run r;
      int i;
      memset(&r, 0, sizeof r);
      racket_model(&m, detects[d], resp ? BALL_RESPONSE_PHYSICAL : BALL_RESPONSE_RACKET, 5.0);
      m.extrapolation_time = 1.0; /* eq 15: the racket keeps moving past its last sample */
      assert_int_equal(ball_sim_init(&sim, &m), BALL_OK);
      for (i = 0; i < 2; i++) {
        ball_racket_sample s =
            core_sample(-0.1 + 0.1 * i, ball_v3(-2.0 + 2.0 * i, 1.45, 0.0), ball_v3(1.0, 0.0, 0.0));
        assert_int_equal(ball_racket_push(&sim, 0, &s), BALL_OK);
      }
      step_frames(&m, &sim, 50, &r);
      if (r.hits < 1) fail_msg("detect %d response %d: the racket never caught the ball", (int)d, resp);
      assert_near(r.first.velocity_out.x, resp ? 15.0 : 20.0, 1e-9);
    }
}

/* Samples with equal timestamps: an exact duplicate is accepted and ignored
 * (the track does not change), the same time with other data is ESTALE and
 * changes nothing. Samples one ulp apart give a finite (huge) racket
 * velocity: eq 7 clamps the ball to v_max, eq 11 stays finite. */
static void test_samples_with_equal_timestamps(void **state) {
  int resp;
  (void)state;
  for (resp = 0; resp < 2; resp++) {
    ball_model m;
    ball_sim sim, copy;
    racket_run r;
    ball_racket_sample s;
    memset(&r, 0, sizeof r);
    racket_model(&m, BALL_DETECT_DISC, resp ? BALL_RESPONSE_PHYSICAL : BALL_RESPONSE_RACKET, 10.0);
    assert_int_equal(ball_sim_init(&sim, &m), BALL_OK);
    s = core_sample(0.0, ball_v3(1.0, 1.45, 0.0), ball_v3(-1.0, 0.0, 0.0));
    assert_int_equal(ball_racket_push(&sim, 0, &s), BALL_OK);
    copy = sim;
    assert_int_equal(ball_racket_push(&sim, 0, &s), BALL_EDUPLICATE);
    assert_memory_equal(&sim, &copy, sizeof sim);
    s.center.x = 0.99;
    assert_int_equal(ball_racket_push(&sim, 0, &s), BALL_ESTALE);
    assert_memory_equal(&sim, &copy, sizeof sim);
    s.t = nextafter(0.0, 1.0); /* 4.9e-324 s later: 2e321 m/s, overflows to Inf */
    s.center.x = 0.99;
    if (ball_racket_push(&sim, 0, &s) == BALL_OK) step_frames(&m, &sim, 40, &r);
    s.t = nextafter(1.0, 2.0); /* one ulp (2.2e-16 s) after a sample at 1 s: 4.5e13 m/s */
    memset(&r, 0, sizeof r);
    assert_int_equal(ball_sim_init(&sim, &m), BALL_OK);
    {
      ball_racket_sample a = core_sample(0.5, ball_v3(1.0, 1.45, 0.0), ball_v3(-1.0, 0.0, 0.0));
      ball_racket_sample b =
          core_sample(nextafter(0.5, 1.0), ball_v3(0.99, 1.45, 0.0), ball_v3(-1.0, 0.0, 0.0));
      assert_int_equal(ball_racket_push(&sim, 0, &a), BALL_OK);
      assert_int_equal(ball_racket_push(&sim, 0, &b), BALL_OK);
    }
    step_frames(&m, &sim, 40, &r);
    if (r.hits > 0 && resp == 0)
      assert_near(hypot(r.first.velocity_out.x, r.first.velocity_out.y), m.v_max, 1e-9);
  }
}

/* A racket inside the ball: ball radius 0.1 m, disc radius 0.05 m, the disc's
 * centre on the ball's centre and the ball at rest in the air or moving: no
 * division by zero, at most one hit per sleep period, and after 1 s the
 * ball has left the racket (distance of centres > ball radius). */
static void test_racket_inside_the_ball(void **state) {
  static const double speeds[] = {0.0, 3.0};
  size_t d, k;
  (void)state;
  for (d = 0; d < 3; d++)
    for (k = 0; k < 2; k++) {
      ball_model m;
      ball_sim sim;
      ball_state st;
      racket_run r;
      int i;
      memset(&r, 0, sizeof r);
      racket_model(&m, detects[d], BALL_RESPONSE_RACKET, speeds[k]);
      m.radius = 0.1;
      m.rackets[0].radius = 0.05;
      m.stale_time = 10.0;
      assert_int_equal(ball_sim_init(&sim, &m), BALL_OK);
      for (i = 0; i < 2; i++) {
        ball_racket_sample s = core_sample(-0.1 + 0.1 * i, ball_v3(0.0, 1.5, 0.0), ball_v3(0.0, 1.0, 0.0));
        assert_int_equal(ball_racket_push(&sim, 0, &s), BALL_OK);
      }
      step_frames(&m, &sim, 60, &r);
      assert_int_equal(ball_sim_state(&sim, &st), BALL_OK);
      assert_true(hypot(hypot(st.position.x, st.position.y - 1.5), st.position.z) > m.radius);
    }
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_still_racket_hits_once_with_defined_direction_eq7_eq11),
      cmocka_unit_test(test_racket_turning_fast_stays_finite_fig4),
      cmocka_unit_test(test_zero_tiny_huge_and_nan_normals),
      cmocka_unit_test(test_racket_overtaking_from_behind_eq7_eq11_fig9),
      cmocka_unit_test(test_samples_with_equal_timestamps),
      cmocka_unit_test(test_racket_inside_the_ball),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
