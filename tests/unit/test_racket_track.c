/* Racket tracks: samples kept (the paper's n), bad samples rejected with the
 * sim unchanged, interpolation, extrapolation (eq 15), stale tracks, and the
 * game level presets (section 4). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "core_common.h"

static void track_model(ball_model *m) {
  core_model_free(m);
  m->n_rackets = 2;
  m->history = 3;
  m->extrapolation_time = 0.05;
  m->stale_time = 0.5;
  m->effects |= BALL_EFFECT_RACKETS;
}

static ball_racket_sample sample(double t, double x, double y, double z, ball_vec3 n) {
  ball_racket_sample s;
  s.t = t;
  s.center = ball_v3(x, y, z);
  s.normal = n;
  return s;
}

/* push must fail with want and leave every byte of the sim as it was */
static void assert_rejected(ball_sim *sim, int racket, ball_racket_sample s,
                            ball_status want) {
  ball_sim before = *sim;
  assert_int_equal(ball_racket_push(sim, racket, &s), want);
  assert_memory_equal(&before, sim, sizeof before);
}

static void bad_samples_rejected_with_track_unchanged(void **state) {
  ball_model m;
  ball_sim sim;
  ball_vec3 x = ball_v3(1, 0, 0);
  (void)state;
  track_model(&m);
  assert_ok(ball_sim_init(&sim, &m));
  assert_ok(ball_racket_push(&sim, 0, &(ball_racket_sample){0.1, {1, 1, 1}, {0, 2, 0}}));
  assert_ok(ball_racket_push(&sim, 0, &(ball_racket_sample){0.2, {2, 1, 1}, {0, 1, 0}}));
  assert_rejected(&sim, 0, sample(NAN, 3, 1, 1, x), BALL_ENONFINITE);
  assert_rejected(&sim, 0, sample(INFINITY, 3, 1, 1, x), BALL_ENONFINITE);
  assert_rejected(&sim, 0, sample(0.3, 3, NAN, 1, x), BALL_ENONFINITE);
  assert_rejected(&sim, 0, sample(0.3, 3, 1, -INFINITY, x), BALL_ENONFINITE);
  assert_rejected(&sim, 0, sample(0.3, 3, 1, 1, ball_v3(NAN, 0, 0)), BALL_ENONFINITE);
  assert_rejected(&sim, 0, sample(0.3, 3, 1, 1, ball_v3(1e-10, 0, 0)), BALL_ERANGE);
  assert_rejected(&sim, 0, sample(0.3, 3, 1, 1, ball_v3(0, 0, 0)), BALL_ERANGE);
  assert_rejected(&sim, 0, sample(0.15, 3, 1, 1, x), BALL_ESTALE);  /* older than the newest */
  assert_rejected(&sim, 0, sample(0.2, 3, 1, 1, x), BALL_ESTALE);   /* same time, other data */
  assert_rejected(&sim, -1, sample(0.3, 3, 1, 1, x), BALL_EINVAL);
  assert_rejected(&sim, 2, sample(0.3, 3, 1, 1, x), BALL_EINVAL);  /* n_rackets = 2 */
  assert_rejected(&sim, 0, sample(0.2, 2, 1, 1, ball_v3(0, 1, 0)), BALL_EDUPLICATE); /* exact duplicate */
  assert_rejected(&sim, 0, sample(0.1, 1, 1, 1, ball_v3(0, 3, 0)), BALL_EDUPLICATE); /* late duplicate */
  assert_int_equal(ball_racket_push(NULL, 0, &(ball_racket_sample){0.3, {0, 0, 0}, {1, 0, 0}}), BALL_EINVAL);
  assert_int_equal(ball_racket_push(&sim, 0, NULL), BALL_EINVAL);
  assert_int_equal(sim.tracks[0].count, 2);
}

static void huge_normal_normalised_without_overflow(void **state) {
  ball_model m;
  ball_sim sim;
  ball_racket_pose p;
  (void)state;
  track_model(&m);
  assert_ok(ball_sim_init(&sim, &m));
  assert_ok(ball_racket_push(&sim, 1, &(ball_racket_sample){0.0, {0, 0, 0}, {3e300, 4e300, 0}}));
  assert_ok(ball_racket_estimate(&sim, 1, 0.0, &p));
  assert_near(p.normal.x, 0.6, 1e-15);
  assert_near(p.normal.y, 0.8, 1e-15);
}

static void history_keeps_the_newest_n_samples(void **state) {
  ball_model m;
  ball_sim sim;
  int i;
  (void)state;
  track_model(&m);
  assert_ok(ball_sim_init(&sim, &m));
  for (i = 0; i < 5; i++)
    assert_ok(ball_racket_push(&sim, 0, &(ball_racket_sample){0.1 * i, {(double)i, 0, 0}, {1, 0, 0}}));
  assert_int_equal(sim.tracks[0].count, 3);
  assert_near(sim.tracks[0].samples[0].center.x, 2.0, 0.0);
  assert_near(sim.tracks[0].samples[2].center.x, 4.0, 0.0);
  /* once dropped, a sample older than the newest is stale */
  assert_int_equal(ball_racket_push(&sim, 0, &(ball_racket_sample){0.05, {9, 0, 0}, {1, 0, 0}}), BALL_ESTALE);
}

static void estimate_interpolates_centre_nlerps_normal_velocity_from_pair(void **state) {
  ball_model m;
  ball_sim sim;
  ball_racket_pose p;
  (void)state;
  track_model(&m);
  assert_ok(ball_sim_init(&sim, &m));
  assert_ok(ball_racket_push(&sim, 0, &(ball_racket_sample){1.0, {0, 1, 0}, {1, 0, 0}}));
  assert_ok(ball_racket_push(&sim, 0, &(ball_racket_sample){1.1, {1, 1, 0}, {0, 1, 0}}));
  assert_ok(ball_racket_push(&sim, 0, &(ball_racket_sample){1.2, {1, 3, 0}, {0, 1, 0}}));
  assert_ok(ball_racket_estimate(&sim, 0, 1.05, &p));
  assert_near(p.center.x, 0.5, 1e-12);
  assert_near(p.center.y, 1.0, 1e-12);
  assert_near(p.normal.x, sqrt(0.5), 1e-15);
  assert_near(p.normal.y, sqrt(0.5), 1e-15);
  assert_near(p.velocity.x, 10.0, 1e-9);
  assert_near(p.velocity.y, 0.0, 1e-9);
  /* the second pair: velocity (0, 20, 0) */
  assert_ok(ball_racket_estimate(&sim, 0, 1.15, &p));
  assert_near(p.center.y, 2.0, 1e-12);
  assert_near(p.velocity.y, 20.0, 1e-9);
  /* before the oldest sample the oldest pose is held */
  assert_ok(ball_racket_estimate(&sim, 0, 0.9, &p));
  assert_near(p.center.x, 0.0, 0.0);
}

static void eq15_extrapolation_past_newest_sample_capped_at_extrapolation_time(void **state) {
  ball_model m;
  ball_sim sim;
  ball_racket_pose p;
  (void)state;
  track_model(&m);
  assert_ok(ball_sim_init(&sim, &m));
  assert_ok(ball_racket_push(&sim, 0, &(ball_racket_sample){0.0, {0, 1, 0}, {1, 0, 0}}));
  assert_ok(ball_racket_push(&sim, 0, &(ball_racket_sample){0.1, {1, 1, 0}, {1, 0, 0}}));
  /* eq 15: P = P_current + V_current dt with V = (10, 0, 0): 0.03 s past: x = 1.3 */
  assert_ok(ball_racket_estimate(&sim, 0, 0.13, &p));
  assert_near(p.center.x, 1.3, 1e-12);
  assert_near(p.velocity.x, 10.0, 1e-9);
  /* 0.2 s past, capped at extrapolation_time = 0.05: x = 1.5 */
  assert_ok(ball_racket_estimate(&sim, 0, 0.3, &p));
  assert_near(p.center.x, 1.5, 1e-12);
  /* extrapolation_time 0: the racket holds at its newest sample, once the
   * sim has the changed model (the caller's copy alone changes nothing) */
  m.extrapolation_time = 0.0;
  assert_ok(ball_racket_estimate(&sim, 0, 0.13, &p));
  assert_near(p.center.x, 1.3, 1e-12);
  assert_ok(ball_sim_set_model(&sim, &m));
  assert_ok(ball_racket_estimate(&sim, 0, 0.13, &p));
  assert_near(p.center.x, 1.0, 0.0);
}

static void estimate_without_samples_or_stale_fails(void **state) {
  ball_model m;
  ball_sim sim;
  ball_racket_pose p;
  (void)state;
  track_model(&m);
  assert_ok(ball_sim_init(&sim, &m));
  assert_int_equal(ball_racket_estimate(&sim, 0, 0.0, &p), BALL_ENOTFOUND);
  assert_ok(ball_racket_push(&sim, 0, &(ball_racket_sample){0.0, {0, 1, 0}, {1, 0, 0}}));
  assert_ok(ball_racket_estimate(&sim, 0, 0.5, &p)); /* stale_time 0.5: just not stale */
  assert_near(p.velocity.x, 0.0, 0.0);                    /* one sample: no velocity */
  assert_int_equal(ball_racket_estimate(&sim, 0, 0.5001, &p), BALL_ESTALE);
  assert_int_equal(ball_racket_estimate(&sim, 0, NAN, &p), BALL_ENONFINITE);
  assert_int_equal(ball_racket_estimate(&sim, 3, 0.0, &p), BALL_EINVAL);
}

static void stale_racket_does_not_collide_and_is_counted(void **state) {
  ball_model m;
  ball_sim sim;
  ball_event ev[8];
  steps_tally t;
  int n;
  (void)state;
  track_model(&m);
  m.n_rackets = 1;
  m.detect = BALL_DETECT_SPHERE;
  m.collision_distance = 0.5;
  m.effects = BALL_EFFECT_RACKETS;
  m.initial_position = ball_v3(0, 1, 0);
  assert_ok(ball_sim_init(&sim, &m));
  /* the racket sits on the ball, but its only sample is older than stale_time */
  assert_ok(ball_racket_push(&sim, 0, &(ball_racket_sample){-1.0, {0, 1, 0}, {1, 0, 0}}));
  steps_begin(&t, NULL, 0);
  steps_run(&sim, 0.01, 5, &t);
  assert_int_equal(t.total, 0);
  assert_int_equal(sim.warnings[BALL_WARN_STALE_RACKET], 5);
  /* a fresh sample: the next frame hits */
  assert_ok(ball_racket_push(&sim, 0, &(ball_racket_sample){sim.time, {0, 1, 0}, {1, 0, 0}}));
  assert_ok(ball_step(&sim, 0.01, ev, 8, &n));
  assert_int_equal(n, 1);
  assert_int_equal(ev[0].kind, BALL_EVENT_RACKET);
}

static void game_levels_set_section4_presets(void **state) {
  ball_model m;
  (void)state;
  core_model_free(&m);
  m.effects |= BALL_EFFECT_SPIN;
  assert_ok(ball_model_set_level(&m, BALL_LEVEL_EASY));
  assert_int_equal(m.detect, BALL_DETECT_SPHERE);
  assert_int_equal(m.response, BALL_RESPONSE_AUTONOMOUS);
  assert_near(m.friendly_factor, 1.0, 0.0);
  assert_int_equal(m.level, BALL_LEVEL_EASY);
  assert_true(m.effects & BALL_EFFECT_RACKETS);
  assert_false(m.effects & BALL_EFFECT_SPIN);
  assert_ok(ball_model_check(&m, NULL));
  assert_ok(ball_model_set_level(&m, BALL_LEVEL_MID));
  assert_int_equal(m.detect, BALL_DETECT_DISC);
  assert_int_equal(m.normal_mode, BALL_NORMAL_VELOCITY);
  assert_int_equal(m.response, BALL_RESPONSE_MIXED);
  assert_near(m.friendly_factor, 0.8, 0.0);
  assert_ok(ball_model_check(&m, NULL));
  assert_ok(ball_model_set_level(&m, BALL_LEVEL_ADVANCED));
  assert_int_equal(m.detect, BALL_DETECT_DISC);
  assert_int_equal(m.normal_mode, BALL_NORMAL_REAL);
  assert_int_equal(m.response, BALL_RESPONSE_PHYSICAL);
  assert_true(m.effects & BALL_EFFECT_SPIN);
  assert_ok(ball_model_check(&m, NULL));
  /* a parameter can be overridden after the preset */
  m.sleep_frames = 5;
  assert_ok(ball_model_check(&m, NULL));
  assert_int_equal(ball_model_set_level(&m, BALL_LEVEL_COUNT), BALL_ERANGE);
  assert_int_equal(ball_model_set_level(NULL, BALL_LEVEL_EASY), BALL_EINVAL);
  assert_int_equal(m.sleep_frames, 5);
}

static void racket_check_names_bad_fields(void **state) {
  ball_model m;
  const char *field = NULL;
  (void)state;
  track_model(&m);
  m.rackets[0].partner = 0; /* itself */
  assert_int_equal(ball_model_check(&m, &field), BALL_ERANGE);
  assert_string_equal(field, "rackets[0].partner");
  track_model(&m);
  m.response = BALL_RESPONSE_MIXED;
  m.friendly_factor = 1.5; /* eq 10 needs [0, 1] */
  assert_int_equal(ball_model_check(&m, &field), BALL_ERANGE);
  assert_string_equal(field, "friendly_factor");
  track_model(&m);
  m.v_max = 1.0; /* below v_min */
  assert_int_equal(ball_model_check(&m, &field), BALL_ERANGE);
  assert_string_equal(field, "v_max");
  track_model(&m);
  m.history = 1;
  assert_int_equal(ball_model_check(&m, &field), BALL_ERANGE);
  assert_string_equal(field, "history");
  track_model(&m);
  m.stale_time = NAN;
  assert_int_equal(ball_model_check(&m, &field), BALL_ENONFINITE);
  assert_string_equal(field, "stale_time");
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(bad_samples_rejected_with_track_unchanged),
      cmocka_unit_test(huge_normal_normalised_without_overflow),
      cmocka_unit_test(history_keeps_the_newest_n_samples),
      cmocka_unit_test(estimate_interpolates_centre_nlerps_normal_velocity_from_pair),
      cmocka_unit_test(eq15_extrapolation_past_newest_sample_capped_at_extrapolation_time),
      cmocka_unit_test(estimate_without_samples_or_stale_fails),
      cmocka_unit_test(stale_racket_does_not_collide_and_is_counted),
      cmocka_unit_test(game_levels_set_section4_presets),
      cmocka_unit_test(racket_check_names_bad_fields),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
