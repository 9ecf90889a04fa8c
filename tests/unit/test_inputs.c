/* Bad inputs: every call returns its status and leaves what it was given
 * bit-identical (memcmp) to before; dt = 0 is a no-op; ball_model_check names
 * the field; ball_strerror has a distinct sentence for each status. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "core_common.h"

/* A sim that has been running: a bounce behind it, mid-flight. */
static void running(ball_model *m, ball_sim *sim) {
  core_model_free(m);
  m->initial_velocity = ball_v3(3.0, 2.0, 1.0);
  assert_ok(ball_sim_init(sim, m));
  steps_run(sim, 1.0 / 60.0, 60, NULL);
  assert_true(sim->seg.t0 > 0.0); /* it has bounced */
}

/* ball_step with this dt returns want and changes neither the sim nor the events. */
static void step_rejects(ball_sim *sim, double dt, ball_status want) {
  ball_sim before;
  ball_event ev[4], ev_before[4];
  int n = 7;
  memset(ev, 0xA5, sizeof ev);
  memcpy(ev_before, ev, sizeof ev);
  memcpy(&before, sim, sizeof before);
  assert_int_equal(ball_step(sim, dt, ev, 4, &n), want);
  assert_int_equal(n, 0);
  assert_memory_equal(sim, &before, sizeof before);
  assert_memory_equal(ev, ev_before, sizeof ev);
}

static void step_bad_dt_returns_status_and_leaves_sim_unchanged(void **state) {
  ball_model m;
  ball_sim sim;
  (void)state;
  running(&m, &sim);
  step_rejects(&sim, NAN, BALL_ENONFINITE);
  step_rejects(&sim, INFINITY, BALL_ENONFINITE);
  step_rejects(&sim, -INFINITY, BALL_ENONFINITE);
  step_rejects(&sim, -1.0 / 60.0, BALL_ERANGE);
  step_rejects(&sim, -1e-300, BALL_ERANGE);
}

static void step_dt_zero_is_a_no_op(void **state) {
  ball_model m;
  ball_sim sim, before;
  ball_event ev[4];
  int n = 7;
  (void)state;
  running(&m, &sim);
  memcpy(&before, &sim, sizeof sim);
  assert_ok(ball_step(&sim, 0.0, ev, 4, &n));
  assert_int_equal(n, 0);
  assert_memory_equal(&sim, &before, sizeof sim);
  assert_ok(ball_step(&sim, -0.0, ev, 4, &n));
  assert_memory_equal(&sim, &before, sizeof sim);
}

/* A model field broken to each bad value: check names it, step and init
 * refuse it and leave the sim as it was. */
typedef struct bad_field {
  const char *field;    /* what ball_model_check must name */
  ball_status status;   /* and return */
} bad_field;

static void model_rejected(const ball_model *bad, const bad_field *want) {
  ball_model good;
  ball_sim sim, before;
  const char *field = NULL;
  running(&good, &sim);
  assert_int_equal(ball_model_check(bad, &field), want->status);
  assert_non_null(field);
  if (strncmp(field, want->field, strlen(want->field)) != 0)
    fail_msg("ball_model_check named \"%s\", want \"%s\"", field, want->field);
  memcpy(&before, &sim, sizeof sim);
  /* the only ways a model reaches a sim check it, and refuse it whole */
  assert_int_equal(ball_sim_set_model(&sim, bad), want->status);
  assert_memory_equal(&sim, &before, sizeof sim);
  assert_int_equal(ball_sim_init(&sim, bad), want->status);
  assert_memory_equal(&sim, &before, sizeof sim);
}

static void model_check_names_the_bad_field_and_sim_stays_unchanged(void **state) {
  ball_model m;
  bad_field w;
  (void)state;
#define BAD(stmt, name, st)  \
  do {                       \
    core_model_free(&m);     \
    stmt;                    \
    w.field = (name);        \
    w.status = (st);         \
    model_rejected(&m, &w);  \
  } while (0)
  BAD(m.mass = 0.0, "mass", BALL_ERANGE);
  BAD(m.mass = -1.0, "mass", BALL_ERANGE);
  BAD(m.mass = NAN, "mass", BALL_ENONFINITE);
  BAD(m.gravity = INFINITY, "gravity", BALL_ENONFINITE);
  BAD(m.air_friction = NAN, "air_friction", BALL_ENONFINITE);
  BAD(m.air_friction = -0.1, "air_friction", BALL_ERANGE);
  BAD(m.radius = -0.01, "radius", BALL_ERANGE);
  BAD(m.floor_damping = 1.0000001, "floor_damping", BALL_ERANGE);
  BAD(m.floor_damping = -0.5, "floor_damping", BALL_ERANGE);
  BAD(m.spin_floor_damping = 1.5, "spin_floor_damping", BALL_ERANGE);
  BAD(m.spin_damping = 0.0, "spin_damping", BALL_ERANGE);
  BAD(m.bounce_threshold = NAN, "bounce_threshold", BALL_ENONFINITE);
  BAD(m.sound_threshold = NAN, "sound_threshold", BALL_ENONFINITE);
  BAD((m.effects |= BALL_EFFECT_NET, m.has_net = 1, m.net.damping = 1.2), "net.damping", BALL_ERANGE);
  BAD((m.effects |= BALL_EFFECT_NET, m.has_net = 1, m.net.top = NAN), "net.top", BALL_ENONFINITE);
  BAD((m.effects |= BALL_EFFECT_WALLS, m.n_walls = 1, m.walls[0] = m.net, m.walls[0].damping = 2.0), "walls[0].damping", BALL_ERANGE);
  BAD(m.n_walls = BALL_MAX_WALLS + 1, "n_walls", BALL_ERANGE);
  BAD((m.effects |= BALL_EFFECT_WALLS, m.n_walls = 4, m.walls[0] = m.walls[1] = m.walls[2] = m.walls[3] = m.net,
       m.walls[3].lo = 20.0), "walls[3].hi", BALL_ERANGE); /* lo >= hi: hi is the one named */
  BAD((m.effects |= BALL_EFFECT_RACKETS, m.n_rackets = 2, m.rackets[1].radius = 0.0), "rackets[1].radius", BALL_ERANGE);
  BAD((m.effects |= BALL_EFFECT_RACKETS, m.n_rackets = 2, m.rackets[0].partner = 0), "rackets[0].partner", BALL_ERANGE);
  BAD((m.effects |= BALL_EFFECT_RACKETS, m.n_rackets = 1, m.rackets[0].target.z = NAN), "rackets[0].target",
      BALL_ENONFINITE);
  BAD(m.effects = BALL_EFFECT_ALL + 1u, "effects", BALL_ERANGE);
  BAD(m.scheme = BALL_SCHEME_COUNT, "scheme", BALL_ERANGE);
  BAD(m.initial_velocity.y = NAN, "initial_velocity", BALL_ENONFINITE);
  BAD(m.initial_position.y = -0.5, "initial_position", BALL_ERANGE); /* below the floor */
#undef BAD
  /* a bad wall while walls are off: check and init refuse it, a step (which
   * compares the walls with the bound model only while their effect is on,
   * so that disabled walls cost nothing) goes on unharmed */
  {
    ball_sim sim;
    const char *field = NULL;
    core_model_free(&m);
    m.n_walls = 1;
    m.walls[0] = m.net;
    assert_ok(ball_sim_init(&sim, &m));
    m.walls[0].damping = 2.0;
    assert_int_equal(ball_model_check(&m, &field), BALL_ERANGE);
    assert_string_equal(field, "walls[0].damping");
    assert_ok(ball_step(&sim, 1.0 / 60.0, NULL, 0, NULL));
  }
  /* a model that is fine says nothing */
  {
    const char *field = "untouched";
    core_model_free(&m);
    assert_ok(ball_model_check(&m, &field));
    assert_string_equal(field, "untouched");
  }
}

static void set_state_below_floor_or_nonfinite_is_rejected_unchanged(void **state) {
  ball_model m;
  ball_sim sim, before;
  ball_state st;
  (void)state;
  running(&m, &sim);
  m.radius = 0.1;
  m.floor_level = 0.2;
  assert_ok(ball_sim_set_model(&sim, &m));
  memcpy(&before, &sim, sizeof sim);
  st.position = ball_v3(0.0, 0.29, 0.0); /* centre below floor_level + radius */
  st.velocity = ball_v3(1.0, 0.0, 0.0);
  st.spin = ball_v3(0.0, 0.0, 0.0);
  assert_int_equal(ball_sim_set_state(&sim, &st), BALL_ERANGE);
  assert_memory_equal(&sim, &before, sizeof sim);
  st.position.y = 0.3;
  st.velocity.x = NAN;
  assert_int_equal(ball_sim_set_state(&sim, &st), BALL_ENONFINITE);
  st.velocity.x = 1.0;
  st.spin.z = INFINITY;
  assert_int_equal(ball_sim_set_state(&sim, &st), BALL_ENONFINITE);
  assert_memory_equal(&sim, &before, sizeof sim);
  /* on the floor exactly is fine */
  st.spin.z = 0.0;
  st.position.y = m.floor_level + m.radius;
  assert_ok(ball_sim_set_state(&sim, &st));
}

static void null_pointers_return_einval(void **state) {
  ball_model m;
  ball_sim sim, before;
  ball_state st;
  ball_segment seg;
  ball_vec3 p;
  double t;
  const char *field = NULL;
  (void)state;
  running(&m, &sim);
  memcpy(&before, &sim, sizeof sim);
  seg = sim.seg;
  assert_int_equal(ball_step(NULL, 0.01, NULL, 0, NULL), BALL_EINVAL);
  assert_int_equal(ball_step(&sim, 0.01, NULL, 4, NULL), BALL_EINVAL); /* cap without array */
  assert_int_equal(ball_step(&sim, 0.01, NULL, -1, NULL), BALL_EINVAL);
  assert_memory_equal(&sim, &before, sizeof sim);
  assert_int_equal(ball_sim_init(&sim, NULL), BALL_EINVAL);
  assert_int_equal(ball_sim_init(NULL, &m), BALL_EINVAL);
  assert_int_equal(ball_sim_set_state(&sim, NULL), BALL_EINVAL);
  assert_int_equal(ball_sim_set_state(NULL, &st), BALL_EINVAL);
  assert_int_equal(ball_sim_state(&sim, NULL), BALL_EINVAL);
  assert_int_equal(ball_sim_state(NULL, &st), BALL_EINVAL);
  assert_memory_equal(&sim, &before, sizeof sim);
  assert_int_equal(ball_model_check(NULL, &field), BALL_EINVAL);
  assert_int_equal(ball_segment_eval(&m, NULL, 1.0, &st), BALL_EINVAL);
  assert_int_equal(ball_segment_eval(&m, &seg, seg.t0, NULL), BALL_EINVAL);
  assert_int_equal(ball_time_to_height(&m, &seg, seg.t0, 0.0, NULL), BALL_EINVAL);
  assert_int_equal(ball_time_to_plane(NULL, &seg, seg.t0, 0, 1.0, &t), BALL_EINVAL);
  assert_int_equal(ball_time_to_plane(&m, &seg, seg.t0, 1, 1.0, &t), BALL_EINVAL); /* y is not a plane axis */
  assert_int_equal(ball_next_floor_contact(&m, &seg, seg.t0, NULL, &p), BALL_EINVAL);
  assert_int_equal(ball_apex(&m, NULL, &t, &p), BALL_EINVAL);
  assert_int_equal(ball_model_add_wall(&m, NULL), BALL_EINVAL);
  assert_int_equal(ball_sim_hash(NULL), 0);
}

/* Prediction with a non-finite time or a time before the segment: a status,
 * and the output untouched. */
static void prediction_rejects_nan_and_times_before_the_segment(void **state) {
  ball_model m;
  ball_segment seg;
  ball_state out, out_before;
  double t = 42.0;
  (void)state;
  core_model_free(&m);
  seg = core_segment(1.0, ball_v3(0.0, 1.0, 0.0), ball_v3(1.0, 1.0, 0.0), ball_v3(0.0, 0.0, 0.0));
  memset(&out, 0x5A, sizeof out);
  memcpy(&out_before, &out, sizeof out);
  assert_int_equal(ball_segment_eval(&m, &seg, NAN, &out), BALL_ENONFINITE);
  assert_int_equal(ball_segment_eval(&m, &seg, INFINITY, &out), BALL_ENONFINITE);
  assert_int_equal(ball_segment_eval(&m, &seg, 0.5, &out), BALL_ERANGE);
  assert_memory_equal(&out, &out_before, sizeof out);
  assert_int_equal(ball_time_to_height(&m, &seg, 1.0, NAN, &t), BALL_ENONFINITE);
  assert_int_equal(ball_time_to_plane(&m, &seg, 1.0, 0, INFINITY, &t), BALL_ENONFINITE);
  assert_int_equal(ball_time_to_height(&m, &seg, 0.0, 0.0, &t), BALL_ERANGE);
  seg.v0.x = NAN;
  assert_int_equal(ball_segment_eval(&m, &seg, 2.0, &out), BALL_ENONFINITE);
  assert_memory_equal(&out, &out_before, sizeof out);
  assert_true(t == 42.0);
}

/* A full wall list: BALL_ENOSPACE, model unchanged; a bad wall: its status. */
static void add_wall_full_or_bad_leaves_model_unchanged(void **state) {
  ball_model m, before;
  ball_plane w = {0, 5.0, 0.0, 1.0, 0.0, 1.0, 0.5};
  int i;
  (void)state;
  core_model_free(&m);
  for (i = 0; i < BALL_MAX_WALLS; i++) assert_ok(ball_model_add_wall(&m, &w));
  memcpy(&before, &m, sizeof m);
  assert_int_equal(ball_model_add_wall(&m, &w), BALL_ENOSPACE);
  assert_memory_equal(&m, &before, sizeof m);
  core_model_free(&m);
  memcpy(&before, &m, sizeof m);
  w.damping = 1.01;
  assert_int_equal(ball_model_add_wall(&m, &w), BALL_ERANGE);
  w.damping = 0.5;
  w.hi = -1.0; /* hi < lo */
  assert_int_equal(ball_model_add_wall(&m, &w), BALL_ERANGE);
  w.hi = 1.0;
  w.position = NAN;
  assert_int_equal(ball_model_add_wall(&m, &w), BALL_ENONFINITE);
  w.position = 5.0;
  w.axis = 1;
  assert_int_equal(ball_model_add_wall(&m, &w), BALL_ERANGE);
  assert_memory_equal(&m, &before, sizeof m);
}

/* A sim corrupted from outside (NaN clock): step refuses to touch it. */
static void step_on_a_corrupt_sim_is_rejected_unchanged(void **state) {
  ball_model m;
  ball_sim sim;
  (void)state;
  running(&m, &sim);
  sim.seg.v0.y = NAN;
  step_rejects(&sim, 1.0 / 60.0, BALL_ENONFINITE);
  running(&m, &sim);
  sim.time = sim.seg.t0 - 1.0; /* clock before the segment */
  step_rejects(&sim, 1.0 / 60.0, BALL_ERANGE);
}

static void strerror_gives_a_distinct_sentence_for_each_status(void **state) {
  int a, b;
  (void)state;
  for (a = 0; a < BALL_STATUS_COUNT; a++) {
    const char *s = ball_strerror((ball_status)a);
    assert_non_null(s);
    assert_true(strlen(s) > 3);
    for (b = 0; b < a; b++)
      if (strcmp(s, ball_strerror((ball_status)b)) == 0)
        fail_msg("statuses %d and %d share \"%s\"", a, b, s);
  }
  assert_non_null(ball_strerror(BALL_STATUS_COUNT));
  assert_non_null(ball_strerror((ball_status)-1));
  assert_non_null(ball_strerror((ball_status)1000));
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(step_bad_dt_returns_status_and_leaves_sim_unchanged),
      cmocka_unit_test(step_dt_zero_is_a_no_op),
      cmocka_unit_test(model_check_names_the_bad_field_and_sim_stays_unchanged),
      cmocka_unit_test(set_state_below_floor_or_nonfinite_is_rejected_unchanged),
      cmocka_unit_test(null_pointers_return_einval),
      cmocka_unit_test(prediction_rejects_nan_and_times_before_the_segment),
      cmocka_unit_test(add_wall_full_or_bad_leaves_model_unchanged),
      cmocka_unit_test(step_on_a_corrupt_sim_is_rejected_unchanged),
      cmocka_unit_test(strerror_gives_a_distinct_sentence_for_each_status),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
