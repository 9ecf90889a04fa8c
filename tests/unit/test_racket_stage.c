/* The racket stage inside ball_step: sleep frames (section 3.1), the event a
 * hit emits, eq 7's restart point, and the swept test's time of impact inside
 * a frame at 6 Hz where the frame-based tests see the hit late or not at all. */
#include <limits.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "core_common.h"

static void still_racket_model(ball_model *m, int sleep_frames) {
  core_model_free(m);
  m->effects = BALL_EFFECT_RACKETS; /* no drag, no floor: the ball just falls */
  m->n_rackets = 1;
  m->detect = BALL_DETECT_SPHERE;
  m->collision_distance = 1.0;
  m->response = BALL_RESPONSE_RACKET;
  m->v_min = 0.5;
  m->v_max = 40.0;
  m->sleep_frames = sleep_frames;
  m->stale_time = 10.0;
  m->initial_position = ball_v3(0, 1, 0);
}

/* A callback (ctx: the hit frames so far): a frame's events are one
 * racket hit or none; records the 1-based frame of each hit. */
static int record_hit(void *ctx, ball_sim *sim, const steps_tally *t, const ball_event *ev, int n) {
  int *which = ctx;
  (void)sim;
  if (n > 0) {
    assert_int_equal(n, 1);
    assert_int_equal(ev[0].kind, BALL_EVENT_RACKET);
    which[t->total - 1] = (int)t->frames;
  }
  return 1;
}

/* Frames (1-based) in which a racket event came, over `frames` steps of dt. */
static int hit_frames(const ball_model *m, double dt, int frames, int *which, ball_event *first) {
  ball_sim sim;
  steps_tally t;
  assert_ok(ball_sim_init(&sim, m));
  assert_ok(ball_racket_push(&sim, 0, &(ball_racket_sample){0.0, {0.3, 1, 0}, {1, 0, 0}}));
  steps_begin(&t, NULL, 0);
  steps_each(&sim, dt, (unsigned long)frames, &t, record_hit, which);
  if (t.total > 0 && first) *first = t.first;
  return t.total;
}

static void sleep_frames_prevent_double_hit_of_one_stroke(void **state) {
  ball_model m;
  int which[32], n;
  (void)state;
  /* the ball stays within the 1 m collision distance of the still racket for
   * the whole run (eq 7 sends it off at v_min = 0.5 m/s): every frame would
   * hit. With 3 sleep frames the hits come every 4th frame: 1, 5, 9. */
  still_racket_model(&m, 3);
  n = hit_frames(&m, 0.01, 12, which, NULL);
  assert_int_equal(n, 3);
  assert_int_equal(which[0], 1);
  assert_int_equal(which[1], 5);
  assert_int_equal(which[2], 9);
  still_racket_model(&m, 0);
  n = hit_frames(&m, 0.01, 12, which, NULL);
  assert_int_equal(n, 12);
}

/* ball_sim_set_sleep leaves the racket tests asleep for exactly the frames
 * it is given, as a hit does (a second server restoring a sim just after a
 * hit); a count outside [0, sleep_frames] is refused, the sim unchanged. */
static void set_sleep_skips_exactly_the_frames_given(void **state) {
  ball_model m;
  ball_sim sim, before;
  int k, f, n;
  (void)state;
  still_racket_model(&m, 3);
  for (k = 0; k <= 3; k++) {
    assert_ok(ball_sim_init(&sim, &m));
    assert_ok(ball_racket_push(&sim, 0, &(ball_racket_sample){0.0, {0.3, 1, 0}, {1, 0, 0}}));
    assert_ok(ball_sim_set_sleep(&sim, k));
    assert_int_equal(sim.sleep, k);
    /* every frame would hit (see above): the first hit is frame k + 1 */
    for (f = 1; f <= k + 1; f++) {
      ball_event ev[4];
      assert_ok(ball_step(&sim, 0.01, ev, 4, &n));
      assert_int_equal(n, f == k + 1 ? 1 : 0);
    }
  }
  assert_ok(ball_sim_init(&sim, &m));
  before = sim;
  assert_int_equal(ball_sim_set_sleep(&sim, -1), BALL_ERANGE);
  assert_int_equal(ball_sim_set_sleep(&sim, 4), BALL_ERANGE); /* more than sleep_frames */
  assert_int_equal(ball_sim_set_sleep(&sim, INT_MAX), BALL_ERANGE);
  assert_memory_equal(&sim, &before, sizeof sim);
  assert_int_equal(ball_sim_set_sleep(NULL, 1), BALL_EINVAL);
}

/* eq 8, 9 with a partner: the autonomous ball flies to the partner's
 * racket; with goal_reach, to the point within that horizontal distance of
 * the racket's target nearest it (a partner parked off the court gets a
 * ball in the court). The direction of V0's horizontal part is the goal's. */
static void autonomous_goal_stays_within_reach_of_target(void **state) {
  int k;
  (void)state;
  for (k = 0; k < 3; k++) {
    ball_model m;
    ball_sim sim;
    ball_event ev[4];
    int n;
    double reach = k == 0 ? BALL_MAX_COORD : k == 1 ? 5.0 : 50.0;
    ball_vec3 partner = ball_v3(20.0, 1.0, 40.0), target = ball_v3(17.0, 0.0, 5.0), goal;
    still_racket_model(&m, 3);
    m.n_rackets = 2;
    m.response = BALL_RESPONSE_AUTONOMOUS;
    m.friendly_factor = 1.0;
    m.rackets[0].partner = 1;
    m.rackets[0].target = target;
    m.rackets[0].goal_reach = reach;
    m.rackets[1].partner = 0;
    assert_ok(ball_sim_init(&sim, &m));
    assert_ok(ball_racket_push(&sim, 0, &(ball_racket_sample){0.0, {0.3, 1, 0}, {1, 0, 0}}));
    assert_ok(ball_racket_push(&sim, 1, &(ball_racket_sample){0.0, partner, {1, 0, 0}}));
    assert_ok(ball_step(&sim, 0.01, ev, 4, &n));
    assert_int_equal(n, 1);
    assert_int_equal(ev[0].kind, BALL_EVENT_RACKET);
    if (k == 1) { /* |partner - target| = 35.13 m: moved to 5 m from target, toward the partner */
      double d = sqrt(3.0 * 3.0 + 35.0 * 35.0);
      goal = ball_v3(17.0 + 3.0 * 5.0 / d, 0.0, 5.0 + 35.0 * 5.0 / d);
    } else { /* within reach: the partner's racket itself, as the paper has it */
      goal = partner;
    }
    assert_near(ev[0].velocity_out.z / ev[0].velocity_out.x, (goal.z - ev[0].point.z) / (goal.x - ev[0].point.x), 1e-12);
  }
}

static void eq7_hit_event_fields_and_restart_at_q_plus_v0_dt(void **state) {
  ball_model m;
  ball_sim sim;
  ball_event ev[4];
  ball_state s;
  int n;
  (void)state;
  still_racket_model(&m, 3);
  m.effects |= BALL_EFFECT_SOUND;
  m.sound_threshold = 0.4;
  assert_ok(ball_sim_init(&sim, &m));
  assert_ok(ball_racket_push(&sim, 0, &(ball_racket_sample){0.0, {0.3, 1, 0}, {1, 0, 0}}));
  assert_ok(ball_step(&sim, 0.01, ev, 4, &n));
  assert_int_equal(n, 1);
  assert_int_equal(ev[0].kind, BALL_EVENT_RACKET);
  assert_int_equal(ev[0].index, 0);
  assert_near(ev[0].time, 0.01, 1e-15);
  /* Q: the ball position at t = 0.01 (sphere test), falling from rest */
  assert_near(ev[0].point.y, 1.0 - 0.5 * 9.81 * 1e-4, 1e-12);
  assert_near(ev[0].velocity_in.y, -0.0981, 1e-12);
  /* still racket: along the face toward the ball's side (-x) at v_min */
  assert_near(ev[0].velocity_out.x, -0.5, 1e-12);
  assert_near(ev[0].velocity_out.y, 0.0, 0.0);
  assert_int_equal(ev[0].sound, 1); /* 0.5 m/s > 0.4 */
  assert_int_equal(ev[0].index, 0);
  assert_int_equal(sim.sleep, 3);
  /* eq 7: P0 = Q + V0 dt */
  assert_near(sim.seg.p0.x, ev[0].point.x - 0.5 * 0.01, 1e-15);
  assert_near(sim.seg.t0, 0.01, 1e-15);
  assert_ok(ball_sim_state(&sim, &s));
  assert_near(s.position.x, -0.005, 1e-15);
}

/* The ball flies +x at 2 m/s; the racket (normal +x) comes from behind at
 * 20 m/s, sampled at 6 Hz. Without drag x_ball = 2 t and x_racket = -4 + 20 t:
 * the surfaces (ball radius 0.033) touch when 2 t + 4 - 20 t = 0.033,
 * t = 3.967 / 18 = 0.22038888... s, inside the second frame [1/6, 2/6]. */
static int overtake_at(ball_detect detect, ball_response response, double speed, double v_max, ball_event *hit) {
  ball_model m;
  ball_sim sim;
  ball_event ev[4];
  int f, n;
  const double dt = 1.0 / 6.0;
  core_model_free(&m);
  m.effects = BALL_EFFECT_RACKETS;
  m.radius = 0.033;
  m.n_rackets = 1;
  m.rackets[0].radius = 0.15;
  m.detect = detect;
  m.collision_distance = 0.183;
  m.response = response;
  m.v_min = 0.0;
  m.v_max = v_max;
  m.friendly_factor = 0.5; /* mixed: half the racket's own velocity (eq 10) */
  m.stale_time = 10.0;
  m.initial_position = ball_v3(0, 1, 0);
  m.initial_velocity = ball_v3(2, 0, 0);
  assert_ok(ball_sim_init(&sim, &m));
  for (f = 0; f <= 3; f++) {
    double t = f * dt;
    /* the racket follows the ball's height at the sample times */
    ball_racket_sample s = {t, {-4.0 + speed * t, 1.0 - 0.5 * 9.81 * t * t, 0}, {1, 0, 0}};
    assert_ok(ball_racket_push(&sim, 0, &s));
    if (f == 0) continue;
    assert_ok(ball_step(&sim, dt, ev, 4, &n));
    if (n > 0) {
      *hit = ev[0];
      return f;
    }
  }
  return 0;
}

static int overtake(ball_detect detect, ball_event *hit) {
  return overtake_at(detect, BALL_RESPONSE_PHYSICAL, 20.0, 40.0, hit);
}

static void swept_finds_overtaking_racket_inside_6hz_frame(void **state) {
  ball_event ev;
  (void)state;
  assert_int_equal(overtake(BALL_DETECT_SWEPT, &ev), 2);
  assert_near(ev.time, 3.967 / 18.0, 1e-9);
  assert_near(ev.point.x, 2.0 * 3.967 / 18.0, 1e-8);
  /* eq 11 with the face toward the ball (+x): -2 + n . V_racket = -2 + 20 */
  assert_near(ev.velocity_in.x, 2.0, 1e-12);
  assert_near(ev.velocity_out.x, 18.0, 1e-9);
  /* the disc test sees it at the frame's end; the sphere test not at all */
  assert_int_equal(overtake(BALL_DETECT_DISC, &ev), 2);
  assert_near(ev.time, 2.0 / 6.0, 1e-15);
  assert_int_equal(overtake(BALL_DETECT_SPHERE, &ev), 0);
}

/* The physical response reads the racket velocity with its speed clamped to
 * v_max: racket speeds along +x from 10 to 1e5 m/s (log-uniform, fixed seed)
 * against v_max 30 m/s. Eq 11 with n = +x: V0.x = -2 + n . V_racket. The
 * racket also falls with the ball (about 2 m/s down at the hit), so below
 * 25 m/s V0.x = -2 + speed as without a clamp, from 40 m/s up the clamped
 * velocity is within 1 % of v_max along x, and never beyond it. */
static void physical_response_clamps_racket_speed_to_v_max(void **state) {
  uint64_t seed = 12345;
  int k, fast = 0, slow = 0;
  (void)state;
  for (k = 0; k < 40; k++) {
    ball_event ev;
    double speed;
    seed = seed * 6364136223846793005ULL + 1442695040888963407ULL;
    speed = 10.0 * pow(1e4, (double)(seed >> 11) / 9007199254740992.0);
    assert_int_not_equal(overtake_at(BALL_DETECT_SWEPT, BALL_RESPONSE_PHYSICAL, speed, 30.0, &ev), 0);
    assert_true(ev.velocity_out.x <= -2.0 + 30.0 + 1e-9);
    if (speed < 25.0) {
      assert_near(ev.velocity_out.x, -2.0 + speed, 1e-9 * speed);
      slow++;
    } else if (speed > 40.0) {
      assert_true(ev.velocity_out.x >= -2.0 + 30.0 * 0.99);
      fast++;
    }
  }
  assert_true(fast >= 20 && slow >= 5); /* the draws cover both sides */
}

/* The mixed response (eq 10) reads it clamped too: a racket at 1e4 or 1e5
 * m/s sends the ball off as one at v_max does (to within the racket's fall,
 * which is the same for all three), not at thousands of m/s. */
static void mixed_response_clamps_racket_speed_to_v_max(void **state) {
  ball_event a, b, c;
  (void)state;
  assert_int_not_equal(overtake_at(BALL_DETECT_SWEPT, BALL_RESPONSE_MIXED, 1e5, 30.0, &a), 0);
  assert_int_not_equal(overtake_at(BALL_DETECT_SWEPT, BALL_RESPONSE_MIXED, 1e4, 30.0, &b), 0);
  assert_int_not_equal(overtake_at(BALL_DETECT_SWEPT, BALL_RESPONSE_MIXED, 300.0, 30.0, &c), 0);
  assert_true(ball_v3_norm(a.velocity_out) < 100.0);
  assert_true(ball_v3_norm(ball_v3_sub(a.velocity_out, b.velocity_out)) < 0.1);
  assert_true(ball_v3_norm(ball_v3_sub(a.velocity_out, c.velocity_out)) < 0.5);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(sleep_frames_prevent_double_hit_of_one_stroke),
      cmocka_unit_test(set_sleep_skips_exactly_the_frames_given),
      cmocka_unit_test(autonomous_goal_stays_within_reach_of_target),
      cmocka_unit_test(eq7_hit_event_fields_and_restart_at_q_plus_v0_dt),
      cmocka_unit_test(swept_finds_overtaking_racket_inside_6hz_frame),
      cmocka_unit_test(physical_response_clamps_racket_speed_to_v_max),
      cmocka_unit_test(mixed_response_clamps_racket_speed_to_v_max),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
