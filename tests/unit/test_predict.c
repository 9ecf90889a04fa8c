/* ball_predict against ball_step over long horizons (ball.h): the events and
 * the end segment to the bit, the states within BALL_PREDICT_REL_ERROR of
 * the scale of the segment in effect. Random segments with and without
 * drag and spin, on a clock far from 0 (where a frame's rounding is
 * large), and the models of every example scene. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>

#include <cmocka.h>

#include "ball/scene.h"
#include "core_common.h"

#define MAX_STATES 14401 /* 60 s at 240 Hz */
#define EVENT_CAP 4096

static ball_state g_states[MAX_STATES];
static ball_event g_events[EVENT_CAP];

typedef struct tally {
  double worst;  /* the largest error, in units of the scale */
  long states;   /* states compared */
  long events;   /* events compared */
  long anchors;  /* states off ball_step's by more than nothing: recurrence states */
} tally;

/* Predicts from the sim's segment at its time over n frames of dt, steps a
 * copy of the sim the same frames (exact scheme, no rackets) and compares. */
static void predict_against_steps(const ball_model *m, const ball_sim *start, double dt, int n, tally *ta,
                                  const char *what) {
  ball_sim sim = *start;
  ball_prediction pr;
  ball_event ev[BALL_MAX_CONTACTS];
  double t_end = sim.time;
  int k, e = 0, ne;
  assert_true(n + 1 <= MAX_STATES);
  for (k = 0; k < n; k++) t_end += dt; /* the clock as ball_step sums it */
  memset(&pr, 0, sizeof pr);
  pr.states = g_states;
  pr.cap_states = n + 1;
  pr.events = g_events;
  pr.cap_events = EVENT_CAP;
  assert_ok(ball_predict(m, &sim.seg, sim.time, t_end, dt, &pr));
  assert_int_equal(pr.n_states, n + 1);
  for (k = 1; k <= n; k++) {
    ball_state s;
    double err;
    int j;
    err = core_step_against(&sim, dt, &g_states[k], ev, &ne, &s);
    if (!(err <= BALL_PREDICT_REL_ERROR))
      fail_msg("%s: state %d of %d (dt %.17g, t %.17g) off by %.3g of the scale: x %.17g vs %.17g, vx %.17g vs "
               "%.17g", what, k, n, dt, sim.time, err, g_states[k].position.x, s.position.x, g_states[k].velocity.x,
               s.velocity.x);
    if (err > ta->worst) ta->worst = err;
    if (memcmp(&g_states[k], &s, sizeof s) != 0) ta->anchors++;
    for (j = 0; j < ne; j++, e++) {
      if (e >= pr.n_events) fail_msg("%s: ball_step's event %d at frame %d, %d predicted", what, e, k, pr.n_events);
      if (!core_event_same(&ev[j], &g_events[e])) fail_msg("%s: event %d differs at frame %d", what, e, k);
    }
  }
  if (e != pr.n_events || pr.events_missed != 0)
    fail_msg("%s: %d stepped events, %d + %d predicted", what, e, pr.n_events, pr.events_missed);
  assert_memory_equal(&pr.end, &sim.seg, sizeof sim.seg);
  ta->states += n;
  ta->events += e;
}

/* A random model: the court (floor, net, back wall) or free space, drag
 * from none to b = 0.05 s, spin on or off. */
static void random_model(core_rng *r, ball_model *m, int obstacles) {
  if (obstacles) {
    core_court_scene(m);
    m->effects |= BALL_EFFECT_SPIN;
    m->radius = core_uniform(r, 0.0, 0.1);
    m->floor_damping = core_uniform(r, 0.5, 1.0);
  } else {
    core_model_free(m);
    m->effects &= ~(unsigned)BALL_EFFECT_FLOOR;
    m->effects |= BALL_EFFECT_SPIN;
  }
  m->mass = core_uniform(r, 0.01, 1.0);
  m->air_friction = core_uniform(r, 0.0, 1.0) < 0.2 ? 0.0 : m->mass / exp(core_uniform(r, log(0.05), log(1e4)));
  if (core_uniform(r, 0.0, 1.0) < 0.2) m->effects &= ~(unsigned)BALL_EFFECT_DRAG;
  if (core_uniform(r, 0.0, 1.0) < 0.3) m->effects &= ~(unsigned)BALL_EFFECT_SPIN;
  m->spin_damping = core_uniform(r, 0.1, 10.0);
}

/* Random segments on a random clock (0 to 1e6 s: the larger the clock, the
 * larger the rounding of each t + dt), 20 to 60 s ahead at 30 to 240 Hz. */
static void predict_random_segments_within_bound(void **state) {
  core_rng r = {20261203ULL};
  tally ta = {0.0, 0, 0, 0};
  int c;
  (void)state;
  for (c = 0; c < 120; c++) {
    ball_model m;
    ball_sim sim;
    ball_segment seg;
    char what[64];
    int obstacles = c % 2;
    double hz = core_uniform(&r, 30.0, 240.0), dt = 1.0 / hz, t0;
    int n = (int)(core_uniform(&r, 20.0, 60.0) * hz);
    random_model(&r, &m, obstacles);
    t0 = core_uniform(&r, 0.0, 1.0) < 0.3 ? 0.0 : exp(core_uniform(&r, 0.0, log(1e6)));
    seg = core_segment(t0, ball_v3(core_uniform(&r, 0.5, 20.0), core_uniform(&r, 0.5, 3.0), core_uniform(&r, 0.5, 10.0)),
                       ball_v3(core_uniform(&r, -40.0, 40.0), core_uniform(&r, -5.0, 20.0), core_uniform(&r, -15.0, 15.0)),
                       ball_v3(core_uniform(&r, -3.0, 3.0), core_uniform(&r, -3.0, 3.0), core_uniform(&r, -3.0, 3.0)));
    if (!(m.effects & BALL_EFFECT_SPIN)) seg.s0 = ball_v3(0.0, 0.0, 0.0);
    assert_ok(ball_sim_init(&sim, &m));
    assert_ok(ball_sim_set_segment(&sim, &seg, t0));
    snprintf(what, sizeof what, "case %d", c);
    predict_against_steps(&m, &sim, dt, n, &ta, what);
  }
  assert_true(ta.events > 1000);            /* the court's cases bounce */
  assert_true(ta.anchors > ta.states / 2);  /* most states are the recurrence's, not the closed form's */
  print_message("%ld states, %ld events: at most %.3g of the scale off ball_step's (bound %g)\n", ta.states,
                ta.events, ta.worst, BALL_PREDICT_REL_ERROR);
}

/* The models of every example scene (rackets taken out, the exact scheme),
 * from their initial state: 60 s at their frame rate and at 240 Hz. */
static void predict_scene_models_within_bound(void **state) {
  static const char *const files[] = {"darts.yaml",     "drop_shot.yaml",      "dropped_ball.yaml",
                                      "football_wall.yaml", "juggling.yaml",   "rally_advanced.yaml",
                                      "rally_easy.yaml", "rally_mid.yaml",      "serve.yaml",
                                      "smash_6hz.yaml",  "tennis.yaml"};
  const char *dir = getenv("BALL_SCENES");
  tally ta = {0.0, 0, 0, 0};
  size_t i;
  (void)state;
  if (!dir) dir = "libball/scenes";
  for (i = 0; i < sizeof files / sizeof files[0]; i++) {
    static ball_scene scene;
    ball_scene_error err;
    ball_sim sim;
    char path[1024];
    int rate;
    snprintf(path, sizeof path, "%s/%s", dir, files[i]);
    if (ball_scene_load_file(path, &scene, &err) != BALL_OK) fail_msg("cannot load %s", path);
    scene.model.effects &= ~(unsigned)BALL_EFFECT_RACKETS;
    scene.model.scheme = BALL_SCHEME_EXACT;
    assert_ok(ball_sim_init(&sim, &scene.model));
    for (rate = 0; rate < 2; rate++) {
      double dt = rate == 0 ? scene.frame_time * scene.time_base : 1.0 / 240.0;
      int n = (int)(60.0 / dt);
      if (n + 1 > MAX_STATES) n = MAX_STATES - 1;
      predict_against_steps(&scene.model, &sim, dt, n, &ta, files[i]);
    }
  }
  assert_true(ta.events > 100);
  print_message("%ld states, %ld events: at most %.3g of the scale off ball_step's (bound %g)\n", ta.states,
                ta.events, ta.worst, BALL_PREDICT_REL_ERROR);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(predict_random_segments_within_bound),
      cmocka_unit_test(predict_scene_models_within_bound),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
