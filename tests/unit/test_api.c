/* The API a server relies on (docs/model.md, "Checked once" and "Hashes";
 * docs/benchmarks.md for why): a sim bound to a checked model, duplicate
 * samples told apart, portable hashes, the prepared flight, the prediction
 * call, and the field table the loader and the docs are made from. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "core_common.h"

/* ---- the sim owns its model ---- */

/* ball_sim_init copies the checked model: what the caller does with its own
 * model afterwards changes nothing, and ball_sim_model reads the copy. */
static void the_sim_owns_its_model_and_ignores_the_callers(void **state) {
  ball_model m;
  ball_sim sim, twin;
  ball_event ev[8], ev_twin[8];
  int f, k, n, n_twin;
  unsigned kinds = 0;
  (void)state;
  core_court_scene(&m);
  assert_ok(ball_sim_init(&sim, &m));
  assert_ok(ball_sim_init(&twin, &m));
  assert_ptr_equal(ball_sim_model(&sim), &sim.model);
  assert_null(ball_sim_model(NULL));
  assert_memory_equal(ball_sim_model(&sim), &m, sizeof m);
  /* every field a step reads, changed in the caller's copy only */
  m.gravity = 1.62;
  m.floor_damping = 0.5;
  m.net.top = 2.0;
  m.walls[0].damping = 0.1;
  m.scheme = BALL_SCHEME_SAMPLED;
  for (f = 0; f < 240; f++) {
    assert_ok(ball_step(&sim, 1.0 / 60.0, ev, 8, &n));
    assert_ok(ball_step(&twin, 1.0 / 60.0, ev_twin, 8, &n_twin));
    assert_int_equal(n, n_twin);
    if (n > 0) assert_memory_equal(ev, ev_twin, (size_t)n * sizeof ev[0]);
    for (k = 0; k < n; k++) kinds |= 1u << ev[k].kind;
  }
  assert_memory_equal(&sim, &twin, sizeof sim);
  assert_near(ball_sim_model(&sim)->gravity, 9.81, 0.0);
  /* the run met what the changed fields govern: the net, the floor, the wall */
  assert_int_equal(kinds, (1u << BALL_EVENT_NET) | (1u << BALL_EVENT_FLOOR) | (1u << BALL_EVENT_WALL));
}

static void set_model_rebinds_and_keeps_the_ball(void **state) {
  ball_model m;
  ball_sim sim, before;
  ball_state s0, s1;
  (void)state;
  core_court_scene(&m);
  assert_ok(ball_sim_init(&sim, &m));
  steps_run(&sim, 1.0 / 60.0, 30, NULL);
  assert_ok(ball_sim_state(&sim, &s0));
  m.gravity = 1.62; /* the moon, mid-flight */
  assert_ok(ball_sim_state(&sim, &s1)); /* the caller's model is not the sim's */
  assert_memory_equal(&s1, &s0, sizeof s1);
  assert_ok(ball_sim_set_model(&sim, &m));
  assert_near(ball_sim_model(&sim)->gravity, 1.62, 0.0);
  assert_ok(ball_sim_state(&sim, &s1));
  /* the ball is where it was, as fast (a new segment starts now: the new g
   * acts from now on, not over the old segment's age) */
  assert_near(s1.position.x, s0.position.x, 0.0);
  assert_near(s1.position.y, s0.position.y, 0.0);
  assert_near(s1.position.z, s0.position.z, 0.0);
  assert_near(s1.velocity.y, s0.velocity.y, 0.0);
  assert_near(s1.velocity.x, s0.velocity.x, 0.0);
  assert_near(sim.time, 0.5, 1e-12);
  /* 0.1 s later, eq 3 vertically with the moon's g from the change */
  steps_run(&sim, 1.0 / 60.0, 6, NULL);
  assert_ok(ball_sim_state(&sim, &s1));
  assert_near(s1.position.y, s0.position.y + s0.velocity.y * 0.1 - 0.5 * 1.62 * 0.01, 1e-12);
  assert_near(s1.velocity.y, s0.velocity.y - 1.62 * 0.1, 1e-12);
  /* a model under which the ball is not a valid state: refused, unchanged */
  before = sim;
  m.floor_level = 50.0;
  assert_int_equal(ball_sim_set_model(&sim, &m), BALL_ERANGE);
  assert_memory_equal(&sim, &before, sizeof sim);
  m.floor_level = 0.0;
  m.mass = -1.0;
  assert_int_equal(ball_sim_set_model(&sim, &m), BALL_ERANGE);
  assert_memory_equal(&sim, &before, sizeof sim);
  assert_int_equal(ball_sim_set_model(&sim, NULL), BALL_EINVAL);
  assert_int_equal(ball_sim_set_model(NULL, &m), BALL_EINVAL);
}

/* ball_racket_clear empties one track, as ball_sim_init leaves it, and only
 * that one; a sample older than the old holder's newest is then taken. */
static void racket_clear_empties_one_track(void **state) {
  ball_model m;
  ball_sim sim, fresh, copy;
  ball_racket_pose pose;
  int i;
  (void)state;
  core_court_scene(&m);
  m.effects |= BALL_EFFECT_RACKETS;
  m.n_rackets = 2;
  m.history = 5;
  assert_ok(ball_sim_init(&sim, &m));
  fresh = sim;
  for (i = 0; i < 3; i++) {
    assert_ok(ball_racket_push(&sim, 0, &(ball_racket_sample){1.0 + 0.1 * i, {(double)i, 1, 0}, {1, 0, 0}}));
    assert_ok(ball_racket_push(&sim, 1, &(ball_racket_sample){1.0 + 0.1 * i, {(double)i, 1, 0}, {1, 0, 0}}));
  }
  assert_ok(ball_step(&sim, 1.0 / 60.0, NULL, 0, NULL));
  copy = sim;
  assert_int_equal(ball_racket_clear(&sim, 2), BALL_EINVAL);
  assert_int_equal(ball_racket_clear(&sim, -1), BALL_EINVAL);
  assert_int_equal(ball_racket_clear(NULL, 0), BALL_EINVAL);
  assert_memory_equal(&sim, &copy, sizeof sim);
  assert_ok(ball_racket_clear(&sim, 0));
  assert_memory_equal(&sim.tracks[0], &fresh.tracks[0], sizeof sim.tracks[0]);
  assert_memory_equal(&sim.tracks[1], &copy.tracks[1], sizeof sim.tracks[1]);
  assert_int_equal(ball_racket_estimate(&sim, 0, 1.2, &pose), BALL_ENOTFOUND);
  /* a new holder's clock may be behind the old one's: its first sample counts */
  assert_ok(ball_racket_push(&sim, 0, &(ball_racket_sample){0.5, {7, 1, 0}, {1, 0, 0}}));
  assert_int_equal(sim.tracks[0].count, 1);
  assert_int_equal(ball_racket_push(&sim, 1, &(ball_racket_sample){0.5, {7, 1, 0}, {1, 0, 0}}), BALL_ESTALE);
}

static void set_model_trims_the_tracks(void **state) {
  ball_model m;
  ball_sim sim;
  int i;
  (void)state;
  core_court_scene(&m);
  m.effects |= BALL_EFFECT_RACKETS;
  m.n_rackets = 3;
  m.history = 5;
  assert_ok(ball_sim_init(&sim, &m));
  for (i = 0; i < 5; i++) {
    assert_ok(ball_racket_push(&sim, 0, &(ball_racket_sample){0.1 * i, {(double)i, 1, 0}, {1, 0, 0}}));
    assert_ok(ball_racket_push(&sim, 2, &(ball_racket_sample){0.1 * i, {(double)i, 1, 0}, {1, 0, 0}}));
  }
  assert_int_equal(sim.tracks[0].count, 5);
  m.history = 3;
  m.n_rackets = 2;
  assert_ok(ball_sim_set_model(&sim, &m));
  /* the newest three samples of racket 0 are kept, oldest first */
  assert_int_equal(sim.tracks[0].count, 3);
  assert_near(sim.tracks[0].samples[0].center.x, 2.0, 0.0);
  assert_near(sim.tracks[0].samples[2].center.x, 4.0, 0.0);
  /* racket 2 is gone */
  assert_int_equal(sim.tracks[2].count, 0);
  assert_int_equal(ball_racket_push(&sim, 2, &(ball_racket_sample){0.6, {0, 1, 0}, {1, 0, 0}}), BALL_EINVAL);
}

static void a_duplicate_sample_is_told_apart(void **state) {
  ball_model m;
  ball_sim sim, before;
  ball_racket_sample s = {0.1, {1, 1, 1}, {0, 2, 0}};
  (void)state;
  core_court_scene(&m);
  m.effects |= BALL_EFFECT_RACKETS;
  m.n_rackets = 1;
  assert_ok(ball_sim_init(&sim, &m));
  assert_ok(ball_racket_push(&sim, 0, &s));
  before = sim;
  assert_int_equal(ball_racket_push(&sim, 0, &s), BALL_EDUPLICATE);
  assert_memory_equal(&sim, &before, sizeof sim);
  s.normal.y = 4.0; /* the same after normalisation: a duplicate too */
  assert_int_equal(ball_racket_push(&sim, 0, &s), BALL_EDUPLICATE);
  s.center.x = 1.5; /* the same time with other data: stale, not a duplicate */
  assert_int_equal(ball_racket_push(&sim, 0, &s), BALL_ESTALE);
  assert_memory_equal(&sim, &before, sizeof sim);
  assert_string_not_equal(ball_strerror(BALL_EDUPLICATE), ball_strerror(BALL_ESTALE));
}

/* ---- portable hashes ---- */

/* The values below were computed by an independent implementation of the
 * definition in docs/model.md (a dozen lines of Python over the IEEE bits),
 * not by the library: any machine and any language must get them. */
#define DEFAULT_MODEL_HASH UINT64_C(0xe630a1b4dfc63305)
#define DEFAULT_SIM_HASH UINT64_C(0x0a0107916e74b5f2)

static void hashes_are_the_documented_numbers(void **state) {
  ball_model m;
  ball_sim sim;
  (void)state;
  ball_model_default(&m);
  assert_true(ball_model_hash(&m) == DEFAULT_MODEL_HASH);
  assert_ok(ball_sim_init(&sim, &m));
  assert_true(ball_sim_hash(&sim) == DEFAULT_SIM_HASH);
  assert_true(ball_model_hash(NULL) == 0 && ball_sim_hash(NULL) == 0);
}

static void the_model_hash_sees_every_field_a_step_reads(void **state) {
  int n, i;
  const ball_field *f = ball_model_fields(&n);
  ball_model base;
  uint64_t h0;
  (void)state;
  ball_model_default(&base);
  base.effects = BALL_EFFECT_ALL;
  base.n_walls = 1;
  base.walls[0] = base.net;
  base.n_rackets = 2;
  h0 = ball_model_hash(&base);
  for (i = 0; i < n; i++) {
    ball_model m = base;
    char *p = (char *)&m + f[i].offset;
    int read = !(f[i].stages & 0x80000000u) && strcmp(f[i].name, "level") != 0 &&
               strncmp(f[i].name, "initial_", 8) != 0;
    switch (f[i].type) {
      case BALL_FIELD_REAL: *(double *)p = *(double *)p * 0.5 + 0.125; break;
      case BALL_FIELD_INT:
      case BALL_FIELD_BOOL:
      case BALL_FIELD_ENUM:
      case BALL_FIELD_AXIS: *(int *)p ^= 1; break;
      case BALL_FIELD_EFFECTS: *(unsigned *)p ^= BALL_EFFECT_SOUND; break;
      case BALL_FIELD_VEC3: ((ball_vec3 *)p)->y += 1.0; break;
      case BALL_FIELD_PLANE: ((ball_plane *)p)->top += 1.0; break;
      case BALL_FIELD_PLANES: m.walls[0].lo -= 1.0; break;
      case BALL_FIELD_RACKETS: m.rackets[1].radius += 0.01; break;
      default: fail();
    }
    if (read && ball_model_hash(&m) == h0) fail_msg("changing %s does not change the hash", f[i].name);
    if (!read && ball_model_hash(&m) != h0) fail_msg("%s is not read by a step but changes the hash", f[i].name);
  }
  /* -0 and +0 alike; padding bytes are not values */
  {
    ball_model a = base, b;
    int j;
    a.floor_level = -0.0;
    assert_true(ball_model_hash(&a) == h0);
    memset(&b, 0xA5, sizeof b);
    for (j = 0; j < n; j++)
      if (f[j].type != BALL_FIELD_PLANE && f[j].type != BALL_FIELD_PLANES && f[j].type != BALL_FIELD_RACKETS) {
        size_t size = f[j].type == BALL_FIELD_REAL ? sizeof(double)
                      : f[j].type == BALL_FIELD_VEC3 ? sizeof(ball_vec3)
                                                      : sizeof(int);
        memcpy((char *)&b + f[j].offset, (char *)&base + f[j].offset, size);
      }
    b.net = base.net;
    memcpy(b.walls, base.walls, sizeof b.walls);
    memcpy(b.rackets, base.rackets, sizeof b.rackets);
    assert_true(ball_model_hash(&b) == h0);
  }
}

static void the_sim_hash_follows_the_state(void **state) {
  ball_model m;
  ball_sim a, b;
  uint64_t h;
  (void)state;
  core_court_scene(&m);
  assert_ok(ball_sim_init(&a, &m));
  b = a;
  h = ball_sim_hash(&a);
  /* the warning counters and the contact cache are not state */
  b.warnings[BALL_WARN_STALE_RACKET] = 7;
  b.next.valid = 1;
  b.next.time = 3.0;
  assert_true(ball_sim_hash(&b) == h);
  assert_ok(ball_step(&a, 1.0 / 60.0, NULL, 0, NULL));
  assert_true(ball_sim_hash(&a) != h);
  b = a;
  b.seg.v0.z = nextafter(b.seg.v0.z, 1e9); /* one ulp */
  assert_true(ball_sim_hash(&b) != ball_sim_hash(&a));
}

/* ball_sim_hash_with given the model's hash is ball_sim_hash, over random
 * scenes stepped with rackets sampled (every part of the state set); any
 * other model hash gives another sim hash. */
static void the_sim_hash_with_a_kept_model_hash_is_the_same(void **state) {
  core_rng r;
  int c, k, samples = 0;
  (void)state;
  r.s = 2026120401ULL;
  assert_true(ball_sim_hash_with(NULL, 1) == 0);
  for (c = 0; c < 200; c++) {
    ball_model m;
    ball_sim sim;
    uint64_t mh;
    ball_model d;
    ball_model_default(&d);
    core_court_scene(&m);
    m.effects |= BALL_EFFECT_RACKETS | BALL_EFFECT_SPIN;
    m.n_rackets = 2;
    m.rackets[0] = m.rackets[1] = d.rackets[0];
    m.rackets[0].partner = m.rackets[1].partner = -1;
    m.air_friction = core_uniform(&r, 0.0, 0.1);
    m.scheme = core_uniform(&r, 0.0, 1.0) < 0.5 ? BALL_SCHEME_EXACT : BALL_SCHEME_SAMPLED;
    m.initial_velocity = ball_v3(core_uniform(&r, -30, 30), core_uniform(&r, -5, 15), core_uniform(&r, -10, 10));
    m.initial_spin = ball_v3(core_uniform(&r, -3, 3), core_uniform(&r, -3, 3), core_uniform(&r, -3, 3));
    assert_ok(ball_sim_init(&sim, &m));
    mh = ball_model_hash(&sim.model);
    for (k = 0; k < 40; k++) {
      if (k % 3 == 0) {
        ball_racket_sample s = {sim.time, {core_uniform(&r, 0, 24), core_uniform(&r, 0, 2), core_uniform(&r, 0, 11)},
                                {1, 0, 0}};
        assert_ok(ball_racket_push(&sim, k % m.n_rackets, &s));
      }
      assert_ok(ball_step(&sim, core_uniform(&r, 1e-3, 0.05), NULL, 0, NULL));
      samples += sim.tracks[0].count + sim.tracks[1].count;
      assert_true(ball_sim_hash_with(&sim, mh) == ball_sim_hash(&sim));
      assert_true(ball_sim_hash_with(&sim, mh ^ 1u) != ball_sim_hash(&sim));
    }
  }
  assert_true(samples > 1000); /* the tracks were part of it */
}

/* ---- the prepared flight ---- */

static void flight_eval_is_segment_eval_to_the_bit(void **state) {
  core_rng r;
  int i;
  (void)state;
  r.s = 424242;
  for (i = 0; i < 20000; i++) {
    ball_model m;
    ball_segment seg;
    ball_flight fl;
    ball_state a, b;
    double t;
    core_model_free(&m);
    m.effects = (unsigned)(core_uniform(&r, 0.0, 128.0)) & BALL_EFFECT_ALL;
    m.air_friction = core_uniform(&r, 0.0, 1.0) < 0.2 ? 0.0 : core_uniform(&r, 1e-6, 5.0);
    m.mass = core_uniform(&r, 0.01, 2.0);
    m.spin_damping = core_uniform(&r, 0.01, 10.0);
    m.gravity = core_uniform(&r, 0.5, 30.0);
    seg = core_segment(core_uniform(&r, -10.0, 100.0),
                       ball_v3(core_uniform(&r, -20, 20), core_uniform(&r, 0, 5), core_uniform(&r, -20, 20)),
                       ball_v3(core_uniform(&r, -50, 50), core_uniform(&r, -20, 20), core_uniform(&r, -50, 50)),
                       ball_v3(core_uniform(&r, -9, 9), core_uniform(&r, -9, 9), core_uniform(&r, -9, 9)));
    seg.grounded = core_uniform(&r, 0.0, 1.0) < 0.2;
    t = seg.t0 + (core_uniform(&r, 0.0, 1.0) < 0.05 ? 0.0 : core_uniform(&r, 0.0, 30.0));
    assert_ok(ball_flight_init(&m, &seg, &fl));
    assert_ok(ball_segment_eval(&m, &seg, t, &a));
    assert_ok(ball_flight_eval(&fl, t, &b));
    assert_memory_equal(&a, &b, sizeof a);
  }
}

/* One transcendental call per evaluation gives what the textbook pair
 * -b expm1(-t/b), e^(-t/b) gives, to 1e-14 relative (the bound docs/benchmarks.md's
 * fast evaluation promises). */
static void one_expm1_gives_the_two_textbook_terms(void **state) {
  core_rng r;
  int i;
  (void)state;
  r.s = 99;
  for (i = 0; i < 100000; i++) {
    ball_model m;
    ball_segment seg = core_segment(0.0, ball_v3(0, 0, 0), ball_v3(1, 0, 0), ball_v3(0, 0, 0));
    ball_state s;
    double b, t, d_ref, f_ref;
    core_model_free(&m);
    m.mass = core_uniform(&r, 0.01, 2.0);
    m.air_friction = pow(10.0, core_uniform(&r, -8.0, 2.0));
    b = m.mass / m.air_friction;
    t = b * pow(10.0, core_uniform(&r, -12.0, 1.5));
    assert_ok(ball_segment_eval(&m, &seg, t, &s));
    d_ref = -b * expm1(-t / b);
    f_ref = exp(-t / b);
    if (!(fabs(s.position.x - d_ref) <= 1e-14 * d_ref) || !(fabs(s.velocity.x - f_ref) <= 1e-14 * f_ref))
      fail_msg("t/b = %.17g: distance %.17g vs %.17g, decay %.17g vs %.17g", t / b, s.position.x, d_ref,
               s.velocity.x, f_ref);
  }
}

static void flight_rejects_bad_input(void **state) {
  ball_model m;
  ball_segment seg = core_segment(1.0, ball_v3(0, 1, 0), ball_v3(1, 0, 0), ball_v3(0, 0, 0));
  ball_flight fl;
  ball_state s;
  (void)state;
  core_model_free(&m);
  assert_int_equal(ball_flight_init(NULL, &seg, &fl), BALL_EINVAL);
  assert_int_equal(ball_flight_init(&m, &seg, NULL), BALL_EINVAL);
  seg.v0.y = NAN;
  assert_int_equal(ball_flight_init(&m, &seg, &fl), BALL_ENONFINITE);
  seg.v0.y = 0.0;
  assert_ok(ball_flight_init(&m, &seg, &fl));
  assert_int_equal(ball_flight_eval(&fl, 0.5, &s), BALL_ERANGE); /* before t0 */
  assert_int_equal(ball_flight_eval(&fl, INFINITY, &s), BALL_ENONFINITE);
  assert_int_equal(ball_flight_eval(&fl, NAN, &s), BALL_ENONFINITE);
  assert_int_equal(ball_flight_eval(NULL, 2.0, &s), BALL_EINVAL);
  assert_int_equal(ball_flight_eval(&fl, 2.0, NULL), BALL_EINVAL);
}

/* ---- the prediction ---- */

/* A random scene without rackets (the rest as the property tests draw it,
 * simpler): floor, net, walls, drag, spin, radius, either frame rate. */
static void random_scene(core_rng *r, ball_model *m) {
  int w;
  core_court_scene(m);
  m->effects = BALL_EFFECT_ALL & ~(unsigned)BALL_EFFECT_RACKETS;
  m->radius = core_uniform(r, 0.0, 1.0) < 0.3 ? 0.0 : core_uniform(r, 0.0, 0.2);
  m->air_friction = core_uniform(r, 0.0, 1.0) < 0.2 ? 0.0 : core_uniform(r, 1e-4, 0.1);
  m->floor_damping = core_uniform(r, 0.3, 1.0);
  m->bounce_threshold = core_uniform(r, 0.0, 1.0) < 0.2 ? 0.0 : core_uniform(r, 0.0, 1.0);
  m->scheme = core_uniform(r, 0.0, 1.0) < 0.5 ? BALL_SCHEME_EXACT : BALL_SCHEME_SAMPLED;
  for (w = m->n_walls; w < 4; w++) {
    ball_plane p = {w % 2 ? 2 : 0, w % 2 ? -1.0 : -2.0, -10.0, 40.0, 0.0, 6.0, 0.8};
    assert_ok(ball_model_add_wall(m, &p));
  }
  m->initial_position = ball_v3(core_uniform(r, 0, 20), core_uniform(r, 0.5, 3.0), core_uniform(r, 0, 10));
  m->initial_velocity = ball_v3(core_uniform(r, -30, 30), core_uniform(r, -5, 15), core_uniform(r, -10, 10));
  m->initial_spin = ball_v3(core_uniform(r, -3, 3), core_uniform(r, -3, 3), core_uniform(r, -3, 3));
}

static int event_same(const ball_event *a, const ball_event *b) { return core_event_same(a, b); }

/* ball.h: ball_predict's events and end segment are ball_step's to the bit
 * (the exact scheme, no rackets), its states within BALL_PREDICT_REL_ERROR
 * of ball_step's, over 300 random scenes. */
static void predict_gives_what_exact_steps_give(void **state) {
  static ball_state states[361];
  static ball_event events[16384];
  ball_event ev[BALL_MAX_CONTACTS];
  core_rng r;
  int c, total_events = 0;
  double worst = 0.0;
  (void)state;
  r.s = 777;
  for (c = 0; c < 300; c++) {
    ball_model m;
    ball_sim sim;
    ball_prediction pr;
    double dt = core_uniform(&r, 0.0, 1.0) < 0.5 ? 1.0 / 60.0 : 1.0 / 120.0, t_end;
    int k, e = 0, n;
    random_scene(&r, &m);
    m.scheme = BALL_SCHEME_EXACT;
    assert_ok(ball_sim_init(&sim, &m));
    pr.states = states;
    pr.cap_states = 361;
    pr.events = events;
    pr.cap_events = 16384;
    /* t_end as the frames sum it (360 * dt may round above the sum, and a
     * trapped ball bounces in the sliver between them) */
    for (k = 0, t_end = 0.0; k < 360; k++) t_end += dt;
    assert_ok(ball_predict(&m, &sim.seg, 0.0, t_end, dt, &pr));
    assert_int_equal(pr.n_states, 361);
    for (k = 1; k <= 360; k++) {
      ball_state s;
      double err;
      int j;
      err = core_step_against(&sim, dt, &states[k], ev, &n, &s);
      if (!(err <= BALL_PREDICT_REL_ERROR))
        fail_msg("case %d: state %d off by %.3g of the scale (x %.17g vs %.17g)", c, k, err, states[k].position.x,
                 s.position.x);
      worst = err > worst ? err : worst;
      for (j = 0; j < n; j++, e++)
        if (e < pr.n_events && !event_same(&ev[j], &events[e]))
          fail_msg("case %d: event %d differs at frame %d", c, e, k);
    }
    /* a ball trapped between walls makes more contacts than the array holds:
     * those are counted, not lost */
    if (e != pr.n_events + pr.events_missed)
      fail_msg("case %d: %d stepped events, %d + %d predicted; warnings %lu %lu", c, e, pr.n_events,
               pr.events_missed, sim.warnings[0], sim.warnings[1]);
    assert_memory_equal(&pr.end, &sim.seg, sizeof sim.seg);
    total_events += e;
  }
  assert_true(total_events > 1000); /* the scenes do bounce */
  print_message("predicted states: at most %.3g of the scale off ball_step's (bound %g)\n", worst,
                BALL_PREDICT_REL_ERROR);
}

/* A second sim put on the first one's segment at its time (what a standby
 * server does with the newest segment it read) goes on as the first does,
 * to the bit, in both schemes over random scenes: the same events, the same
 * states. */
static void set_segment_goes_on_where_the_other_sim_is(void **state) {
  core_rng r = {2026120201ULL};
  int scene, f, k, went_on = 0;
  (void)state;
  for (scene = 0; scene < 300; scene++) {
    ball_model m;
    ball_sim a, b;
    ball_event ea[BALL_MAX_CONTACTS + 2], eb[BALL_MAX_CONTACTS + 2];
    int na, nb, frames = 1 + (int)core_uniform(&r, 0.0, 300.0);
    double dt = 1.0 / (2.0 + core_uniform(&r, 0.0, 118.0));
    random_scene(&r, &m);
    assert_ok(ball_sim_init(&a, &m));
    for (f = 0; f < frames; f++) assert_ok(ball_step(&a, dt, NULL, 0, NULL));
    /* b: another sim of the model, elsewhere in time, then set on a's segment */
    assert_ok(ball_sim_init(&b, &m));
    assert_ok(ball_step(&b, 0.37, NULL, 0, NULL));
    assert_ok(ball_sim_set_segment(&b, &a.seg, a.time));
    assert_true(b.time == a.time && memcmp(&b.seg, &a.seg, sizeof b.seg) == 0);
    assert_memory_equal(&b.prev_position, &a.prev_position, sizeof b.prev_position);
    for (f = 0; f < 240; f++) {
      ball_state sa, sb;
      assert_ok(ball_step(&a, dt, ea, BALL_MAX_CONTACTS + 2, &na));
      assert_ok(ball_step(&b, dt, eb, BALL_MAX_CONTACTS + 2, &nb));
      assert_int_equal(na, nb);
      for (k = 0; k < na; k++) assert_true(event_same(&ea[k], &eb[k]));
      went_on += na;
      assert_ok(ball_sim_state(&a, &sa));
      assert_ok(ball_sim_state(&b, &sb));
      assert_memory_equal(&sa, &sb, sizeof sa);
    }
  }
  assert_true(went_on > 300); /* the runs went on through contacts */
}

/* Bad segments and times are refused with their status, the sim unchanged. */
static void set_segment_refuses_bad_input_unchanged(void **state) {
  ball_model m;
  ball_sim sim, before;
  ball_segment good, bad;
  (void)state;
  core_court_scene(&m);
  assert_ok(ball_sim_init(&sim, &m));
  assert_ok(ball_step(&sim, 0.25, NULL, 0, NULL));
  good = core_segment(1.0, ball_v3(5.0, 1.2, 3.0), ball_v3(10.0, 2.0, 0.0), ball_v3(0.0, 0.0, 0.0));
  before = sim;
#define REFUSED(seg_expr, t, want)                                      \
  do {                                                                  \
    bad = good;                                                         \
    seg_expr;                                                           \
    assert_int_equal(ball_sim_set_segment(&sim, &bad, (t)), (want));    \
    assert_memory_equal(&sim, &before, sizeof sim);                     \
  } while (0)
  REFUSED((void)0, 0.999, BALL_ERANGE);                  /* before t0 */
  REFUSED((void)0, NAN, BALL_ENONFINITE);
  REFUSED(bad.t0 = INFINITY, 2.0, BALL_ENONFINITE);
  REFUSED(bad.v0.z = NAN, 1.5, BALL_ENONFINITE);
  REFUSED(bad.p0.x = 2e9, 1.5, BALL_ERANGE);             /* beyond BALL_MAX_COORD */
  REFUSED(bad.v0.x = 2e7, 1.5, BALL_ERANGE);             /* beyond BALL_MAX_SPEED */
  REFUSED(bad.p0.y = -0.5, 1.5, BALL_ERANGE);            /* starts under the floor */
  REFUSED((void)0, 3.0, BALL_ERANGE);                    /* under the floor by then: 1.2 + 4 - 19.6 < 0 */
  REFUSED(bad.grounded = 2, 1.5, BALL_EINVAL);
  REFUSED(bad.grounded = 1, 1.5, BALL_ERANGE);           /* not on the floor at rest vertically */
  REFUSED((bad.grounded = 1, bad.p0.y = 0.03), 1.5, BALL_ERANGE); /* on the floor, but v0.y = 2 */
#undef REFUSED
  assert_int_equal(ball_sim_set_segment(NULL, &good, 1.5), BALL_EINVAL);
  assert_int_equal(ball_sim_set_segment(&sim, NULL, 1.5), BALL_EINVAL);
  assert_memory_equal(&sim, &before, sizeof sim);
  /* a grounded ball on the floor (radius 0.03) slides on */
  bad = good;
  bad.grounded = 1;
  bad.p0.y = 0.03;
  bad.v0.y = 0.0;
  assert_ok(ball_sim_set_segment(&sim, &bad, 1.5));
  assert_near(sim.prev_position.y, 0.03, 0.0);
  /* the good one, its ball where eq 3 puts it at 1.5 s (b = 5 s) */
  assert_ok(ball_sim_set_segment(&sim, &good, 1.5));
  assert_near(sim.time, 1.5, 0.0);
  assert_near(sim.prev_position.x, 5.0 + 10.0 * 5.0 * -expm1(-0.5 / 5.0), 1e-12);
  assert_near(sim.prev_position.y, 1.2 + 2.0 * 0.5 - 0.5 * 9.81 * 0.25, 1e-12);
}

static void predict_ignores_the_scheme_and_the_rackets(void **state) {
  ball_model m, exact;
  ball_segment seg;
  ball_state a[121], b[121];
  ball_prediction pa, pb;
  (void)state;
  core_court_scene(&m);
  m.scheme = BALL_SCHEME_SAMPLED;
  m.effects |= BALL_EFFECT_RACKETS;
  m.n_rackets = 2;
  exact = m;
  exact.scheme = BALL_SCHEME_EXACT;
  exact.effects &= ~(unsigned)BALL_EFFECT_RACKETS;
  seg = core_segment(0.0, m.initial_position, m.initial_velocity, m.initial_spin);
  memset(&pa, 0, sizeof pa);
  memset(&pb, 0, sizeof pb);
  pa.states = a;
  pa.cap_states = 121;
  pb.states = b;
  pb.cap_states = 121;
  assert_ok(ball_predict(&m, &seg, 0.0, 2.0, 1.0 / 60.0, &pa));
  assert_ok(ball_predict(&exact, &seg, 0.0, 2.0, 1.0 / 60.0, &pb));
  assert_int_equal(pa.n_states, 121);
  assert_memory_equal(a, b, sizeof a);
}

static void predict_caps_and_bad_input(void **state) {
  ball_model m;
  ball_segment seg;
  ball_state st[5];
  ball_event ev[1];
  ball_prediction pr;
  (void)state;
  core_court_scene(&m);
  seg = core_segment(1.0, ball_v3(5, 3, 5), ball_v3(2, 0, 0), ball_v3(0, 0, 0));
  pr.states = st;
  pr.cap_states = 5;
  pr.events = ev;
  pr.cap_events = 1;
  /* 10 s at 2 Hz: 21 states asked, 5 written; bounces beyond the one that fits are counted */
  assert_ok(ball_predict(&m, &seg, 1.0, 11.0, 0.5, &pr));
  assert_int_equal(pr.n_states, 5);
  assert_int_equal(pr.n_events, 1);
  assert_true(pr.events_missed >= 3);
  /* before the first bounce (at 1 + sqrt(2.97 / 4.905) s): eq 3 with b = 5 s */
  assert_near(st[1].position.x, 5.0 + 2.0 * 5.0 * -expm1(-0.5 / 5.0), 1e-14);
  assert_near(st[1].position.y, 3.0 - 0.5 * 9.81 * 0.25, 1e-14);
  assert_int_equal(ball_predict(&m, &seg, 0.5, 2.0, 0.1, &pr), BALL_ERANGE); /* before the segment */
  assert_int_equal(ball_predict(&m, &seg, 2.0, 1.5, 0.1, &pr), BALL_ERANGE); /* backwards */
  assert_int_equal(ball_predict(&m, &seg, 1.0, 2.0, 0.0, &pr), BALL_ERANGE);
  assert_int_equal(ball_predict(&m, &seg, 1.0, 2.0, -0.1, &pr), BALL_ERANGE);
  assert_int_equal(ball_predict(&m, &seg, 1.0, NAN, 0.1, &pr), BALL_ENONFINITE);
  assert_int_equal(ball_predict(&m, &seg, 1.0, 2.0, INFINITY, &pr), BALL_ENONFINITE);
  pr.states = NULL;
  assert_int_equal(ball_predict(&m, &seg, 1.0, 2.0, 0.1, &pr), BALL_EINVAL);
  pr.states = st;
  m.mass = 0.0;
  assert_int_equal(ball_predict(&m, &seg, 1.0, 2.0, 0.1, &pr), BALL_ERANGE); /* checked on every call */
  m.mass = 0.057;
  assert_int_equal(ball_predict(NULL, &seg, 1.0, 2.0, 0.1, &pr), BALL_EINVAL);
  /* no arrays at all: only the end segment */
  memset(&pr, 0, sizeof pr);
  assert_ok(ball_predict(&m, &seg, 1.0, 11.0, 0.5, &pr));
  assert_int_equal(pr.n_states, 0);
  assert_true(pr.events_missed >= 4);
  assert_true(pr.end.t0 > 1.0);
}

/* ---- the field table ---- */

static void the_field_table_makes_the_defaults_and_names(void **state) {
  ball_model m, from_table;
  int n, np, nr, i, j;
  const ball_field *f = ball_model_fields(&n);
  const ball_field *pf = ball_plane_fields(&np);
  const ball_field *rf = ball_racket_fields(&nr);
  (void)state;
  ball_model_default(&m);
  memset(&from_table, 0, sizeof from_table);
  assert_true(n > 30 && np == 7 && nr == 4);
  for (i = 0; i < n; i++) {
    char *p = (char *)&from_table + f[i].offset;
    assert_non_null(f[i].name);
    assert_non_null(f[i].key);
    assert_non_null(f[i].doc);
    for (j = 0; j < i; j++) assert_string_not_equal(f[i].name, f[j].name);
    if (f[i].type == BALL_FIELD_REAL) *(double *)p = f[i].def[0];
    else if (f[i].type == BALL_FIELD_VEC3) *(ball_vec3 *)p = ball_v3(f[i].def[0], f[i].def[1], f[i].def[2]);
    else if (f[i].type == BALL_FIELD_EFFECTS) *(unsigned *)p = (unsigned)f[i].def[0];
    else if (f[i].type == BALL_FIELD_INT || f[i].type == BALL_FIELD_BOOL || f[i].type == BALL_FIELD_ENUM)
      *(int *)p = (int)f[i].def[0];
    if (f[i].type == BALL_FIELD_ENUM) {
      assert_non_null(f[i].enum_name);
      assert_string_not_equal(f[i].enum_name((int)f[i].def[0]), "unknown");
    }
  }
  for (i = 0; i < np; i++) {
    char *p = (char *)&from_table.net + pf[i].offset;
    if (pf[i].type == BALL_FIELD_REAL) *(double *)p = pf[i].def[0];
    else *(int *)p = (int)pf[i].def[0];
  }
  for (j = 0; j < BALL_MAX_RACKETS; j++)
    for (i = 0; i < nr; i++) {
      char *p = (char *)&from_table.rackets[j] + rf[i].offset;
      if (rf[i].type == BALL_FIELD_REAL) *(double *)p = rf[i].def[0];
      else if (rf[i].type == BALL_FIELD_VEC3) *(ball_vec3 *)p = ball_v3(rf[i].def[0], rf[i].def[1], rf[i].def[2]);
      else *(int *)p = (int)rf[i].def[0];
    }
  assert_memory_equal(&m, &from_table, sizeof m);
  assert_ok(ball_model_check(&m, NULL));
}

static void a_range_end_from_the_table_is_the_checks(void **state) {
  int n, i;
  const ball_field *f = ball_model_fields(&n);
  (void)state;
  /* every real field with a finite end: just inside passes, just outside fails */
  for (i = 0; i < n; i++) {
    ball_model m;
    double *p;
    if (f[i].type != BALL_FIELD_REAL) continue;
    ball_model_default(&m);
    p = (double *)((char *)&m + f[i].offset);
    if (isfinite(f[i].lo)) {
      double inside = f[i].flags & BALL_FIELD_LO_OPEN ? nextafter(f[i].lo, INFINITY) : f[i].lo;
      double outside = f[i].flags & BALL_FIELD_LO_OPEN ? f[i].lo : nextafter(f[i].lo, -INFINITY);
      const char *name = NULL;
      *p = outside;
      if (ball_model_check(&m, &name) == BALL_OK) fail_msg("%s = %.17g passes", f[i].name, outside);
      *p = inside;
      if (strcmp(f[i].name, "v_max") != 0 && strcmp(f[i].name, "floor_level") != 0 &&
          ball_model_check(&m, &name) != BALL_OK)
        fail_msg("%s = %.17g fails (%s)", f[i].name, inside, name ? name : "?");
    }
    if (isfinite(f[i].hi)) {
      double outside = f[i].flags & BALL_FIELD_HI_OPEN ? f[i].hi : nextafter(f[i].hi, INFINITY);
      *p = outside;
      if (ball_model_check(&m, NULL) == BALL_OK) fail_msg("%s = %.17g passes", f[i].name, outside);
    }
  }
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(the_sim_owns_its_model_and_ignores_the_callers),
      cmocka_unit_test(set_model_rebinds_and_keeps_the_ball),
      cmocka_unit_test(set_model_trims_the_tracks),
      cmocka_unit_test(racket_clear_empties_one_track),
      cmocka_unit_test(a_duplicate_sample_is_told_apart),
      cmocka_unit_test(hashes_are_the_documented_numbers),
      cmocka_unit_test(the_model_hash_sees_every_field_a_step_reads),
      cmocka_unit_test(the_sim_hash_follows_the_state),
      cmocka_unit_test(the_sim_hash_with_a_kept_model_hash_is_the_same),
      cmocka_unit_test(flight_eval_is_segment_eval_to_the_bit),
      cmocka_unit_test(one_expm1_gives_the_two_textbook_terms),
      cmocka_unit_test(flight_rejects_bad_input),
      cmocka_unit_test(predict_gives_what_exact_steps_give),
      cmocka_unit_test(set_segment_goes_on_where_the_other_sim_is),
      cmocka_unit_test(set_segment_refuses_bad_input_unchanged),
      cmocka_unit_test(predict_ignores_the_scheme_and_the_rackets),
      cmocka_unit_test(predict_caps_and_bad_input),
      cmocka_unit_test(the_field_table_makes_the_defaults_and_names),
      cmocka_unit_test(a_range_end_from_the_table_is_the_checks),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
