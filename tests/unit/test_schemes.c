/* The two detection schemes: the paper's sampled tests converge to the
 * exact contacts as the frame rate grows (eq 3, eq 5), the exact scheme does
 * not depend on the frame rate (eq 3, 5, 6), and no floor or net collision
 * adds energy (eq 5, eq 6 with dampings <= 1). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "core_common.h"

/* ---- sampled -> exact ------------------------------------------------- */

#define BOUNCES 5
#define LOG_CAP 512 /* events kept of a run */

/* A ball dropped from 2 m with some horizontal speed onto the floor only
 * (fd 0.75; the 5th rebound still leaves at 6.26 * 0.75^5 = 1.5 m/s, far
 * above the 0.3 m/s threshold, in both schemes). */
static void drop_scene(ball_model *m, ball_scheme scheme) {
  core_model_free(m);
  m->floor_damping = 0.75;
  m->bounce_threshold = 0.3;
  m->scheme = scheme;
  m->initial_position = ball_v3(0.0, 2.0, 0.0);
  m->initial_velocity = ball_v3(3.0, 0.0, 1.0);
}

static void bounce_times(ball_scheme scheme, double fps, double *times) {
  static ball_event log[LOG_CAP]; /* large: not on the stack */
  ball_model m;
  ball_sim sim;
  steps_tally t;
  int k;
  drop_scene(&m, scheme);
  assert_ok(ball_sim_init(&sim, &m));
  steps_begin(&t, log, LOG_CAP);
  steps_run(&sim, 1.0 / fps, (unsigned long)(4.5 * fps), &t);
  assert_true(t.total >= BOUNCES);
  for (k = 0; k < BOUNCES; k++) {
    assert_int_equal(log[k].kind, BALL_EVENT_FLOOR);
    times[k] = log[k].time;
  }
}

/* The sampled scheme sees bounce k up to dt late (delta_k in [0, dt)), when
 * the ball is faster by g delta_k, and eq 5 bounces it from there; the
 * vertical flight after it is then longer by 2 fd (speed error) / g. With
 * e_w the error of the arriving speed (e_w0 = 0):
 *   E_0 <= dt,  E_(k+1) <= E_k + 2 fd (e_wk + g dt) / g + dt,
 *   e_w(k+1) <= fd (e_wk + g dt).
 * And E_k >= 0: a sampled bounce is never early. */
static void bounce_time_error_bound(double fd, double g, double dt, double *bound) {
  double e = dt, ew = 0.0;
  int k;
  for (k = 0; k < BOUNCES; k++) {
    bound[k] = e;
    e = e + 2.0 * fd * (ew + g * dt) / g + dt;
    ew = fd * (ew + g * dt);
  }
}

static void eq5_sampled_bounce_times_converge_to_exact_as_fps_grows(void **state) {
  const double rates[] = {15.0, 60.0, 240.0, 1000.0};
  double exact[BOUNCES], sampled[BOUNCES], bound[BOUNCES], worst_prev = INFINITY;
  size_t r;
  int k;
  (void)state;
  bounce_times(BALL_SCHEME_EXACT, 60.0, exact);
  for (r = 0; r < sizeof rates / sizeof rates[0]; r++) {
    double worst = 0.0;
    bounce_times(BALL_SCHEME_SAMPLED, rates[r], sampled);
    bounce_time_error_bound(0.75, 9.81, 1.0 / rates[r], bound);
    for (k = 0; k < BOUNCES; k++) {
      double err = sampled[k] - exact[k];
      if (!(err >= -1e-12 && err <= bound[k] + 1e-12))
        fail_msg("%g Hz bounce %d: sampled %.12g exact %.12g: error %.3g outside [0, %.3g]",
                 rates[r], k, sampled[k], exact[k], err, bound[k]);
      if (err > worst) worst = err;
    }
    print_message("sampled at %5.0f Hz: worst bounce time error %.3g s (bound %.3g s)\n", rates[r],
                  worst, bound[BOUNCES - 1]);
    assert_true(worst < worst_prev);
    worst_prev = worst;
  }
  /* at 1000 Hz the derived bound on the 5th bounce is (by hand, dt = 1 ms,
   * fd = 0.75): E = 1, 3.5, 7.125, 11.59375, 16.6953125 ms ... */
  bounce_time_error_bound(0.75, 9.81, 1e-3, bound);
  assert_near(bound[BOUNCES - 1], 16.6953125e-3, 1e-15);
  /* ... and the measured error is below it (checked above for every bounce) */
  assert_true(worst_prev <= bound[BOUNCES - 1]);
}

/* ---- exact: frame-rate independence ---------------------------------- */

/* core_court_scene (core_common.h): several floor bounces, a net hit (the
 * tennis net, damping 0.9) and a hit on a back wall at x = -1: from
 * (3, 1.5, 2) at (12, 3, 0.5) m/s the ball meets the net at y = 0.76 m, flies
 * back, bounces, hits the wall and bounces on. Radius 0.03 so the planes are
 * offset too; frame-rate independence is checked with the paper's point ball
 * as well. */

static double vdiff(ball_vec3 a, ball_vec3 b) {
  double d = fabs(a.x - b.x), dy = fabs(a.y - b.y), dz = fabs(a.z - b.z);
  return d > dy ? (d > dz ? d : dz) : (dy > dz ? dy : dz);
}

static void frame_rate_independence(double radius) {
  const double rates[] = {2.0, 6.0, 15.0, 60.0, 1000.0};
  const double duration = 6.0;
  static ball_event ref_log[LOG_CAP], log[LOG_CAP];
  ball_model m;
  ball_sim sim;
  ball_state s_ref, s;
  steps_tally ref, run;
  size_t r;
  int k;
  core_court_scene(&m);
  m.radius = radius;
  assert_ok(ball_sim_init(&sim, &m));
  steps_begin(&ref, ref_log, LOG_CAP);
  steps_run(&sim, 1.0 / rates[0], (unsigned long)(duration * rates[0]), &ref);
  assert_int_equal(sim.warnings[BALL_WARN_CONTACT_LIMIT], 0);
  assert_ok(ball_sim_state(&sim, &s_ref));
  /* the scene does what it is for */
  assert_int_equal(ref.kind[BALL_EVENT_NET], 1);
  assert_int_equal(ref.kind[BALL_EVENT_WALL], 1);
  assert_true(ref.kind[BALL_EVENT_FLOOR] >= 4);
  assert_int_equal(ref.first.kind, BALL_EVENT_NET);
  for (r = 1; r < sizeof rates / sizeof rates[0]; r++) {
    assert_ok(ball_sim_init(&sim, &m));
    steps_begin(&run, log, LOG_CAP);
    steps_run(&sim, 1.0 / rates[r], (unsigned long)(duration * rates[r] + 0.5), &run);
    if (run.total != ref.total) fail_msg("%g Hz: %d events, %g Hz: %d", rates[r], run.total, rates[0], ref.total);
    for (k = 0; k < ref.total; k++) {
      const ball_event *a = &ref_log[k], *b = &log[k];
      assert_int_equal(a->kind, b->kind);
      assert_int_equal(a->index, b->index);
      assert_int_equal(a->sound, b->sound);
      if (!(fabs(a->time - b->time) <= 1e-9 && vdiff(a->point, b->point) <= 1e-9 &&
            vdiff(a->velocity_in, b->velocity_in) <= 1e-9 &&
            vdiff(a->velocity_out, b->velocity_out) <= 1e-9))
        fail_msg("%g Hz event %d: t %.17g vs %.17g, point off by %.3g, v off by %.3g", rates[r], k,
                 b->time, a->time, vdiff(a->point, b->point),
                 vdiff(a->velocity_out, b->velocity_out));
    }
    /* the end state at t = 6 s (the clock itself sums dt: 1e-12 apart) */
    assert_ok(ball_sim_state(&sim, &s));
    assert_near(sim.time, duration, 1e-11);
    assert_true(vdiff(s.position, s_ref.position) <= 1e-9);
  }
}

static void eq3_eq5_eq6_exact_scheme_is_frame_rate_independent(void **state) {
  (void)state;
  frame_rate_independence(0.03);
}

static void eq3_eq5_eq6_exact_scheme_is_frame_rate_independent_point_ball(void **state) {
  (void)state;
  frame_rate_independence(0.0);
}

/* ---- energy ----------------------------------------------------------- */

/* m v^2 / 2 + m g y just before and just after every floor, net and wall
 * event never grows with dampings <= 1 (exact scheme, no spin): eq 5 scales
 * the speed by floorDamping at the same point, eq 6 by netDamping (no shift in
 * the exact scheme), and the bounce threshold only removes vertical speed.
 * 200 seeded random shots on the court with two walls, random dampings in
 * [0, 1], random radius; relative tolerance 1e-12 for the rounding of v^2. */
static void eq5_eq6_energy_never_increases_at_a_collision_exact(void **state) {
  core_rng rng = {12345u};
  static ball_event log[LOG_CAP];
  ball_plane side = {2, 10.97, -1.0, 25.0, 0.0, 3.0, 1.0};
  ball_plane back = {0, 23.77, -1.0, 12.0, 0.0, 3.0, 1.0};
  ball_model m;
  ball_sim sim;
  steps_tally run;
  int shot, k, events = 0, nets = 0, walls = 0;
  (void)state;
  for (shot = 0; shot < 200; shot++) {
    core_court_scene(&m);
    m.n_walls = 0;
    side.damping = core_uniform(&rng, 0.0, 1.0);
    back.damping = shot % 10 == 0 ? 1.0 : core_uniform(&rng, 0.0, 1.0);
    assert_ok(ball_model_add_wall(&m, &side));
    assert_ok(ball_model_add_wall(&m, &back));
    m.floor_damping = shot % 10 == 1 ? 1.0 : core_uniform(&rng, 0.2, 1.0);
    m.net.damping = shot % 10 == 2 ? 1.0 : core_uniform(&rng, 0.0, 1.0);
    m.radius = core_uniform(&rng, 0.0, 0.1);
    m.air_friction = shot % 3 == 0 ? 0.0 : core_uniform(&rng, 0.0, 0.05);
    m.initial_position = ball_v3(core_uniform(&rng, 0.0, 11.0), core_uniform(&rng, 0.2, 3.0),
                                 core_uniform(&rng, 0.5, 10.5));
    m.initial_velocity = ball_v3(core_uniform(&rng, -5.0, 30.0), core_uniform(&rng, -5.0, 8.0),
                                 core_uniform(&rng, -6.0, 6.0));
    assert_ok(ball_sim_init(&sim, &m));
    steps_begin(&run, log, LOG_CAP);
    steps_run(&sim, 1.0 / 30.0, 240, &run);
    for (k = 0; k < run.total; k++) {
      const ball_event *e = &log[k];
      double before = core_energy(&m, e->velocity_in, e->point.y);
      double after = core_energy(&m, e->velocity_out, e->point.y);
      if (!(after <= before * (1.0 + 1e-12) + 1e-15))
        fail_msg("shot %d event %d (kind %d at t = %.9g): energy %.17g -> %.17g", shot, k,
                 e->kind, e->time, before, after);
      events++;
      nets += e->kind == BALL_EVENT_NET;
      walls += e->kind == BALL_EVENT_WALL;
    }
  }
  print_message("energy: %d events checked (%d net, %d wall)\n", events, nets, walls);
  assert_true(events > 1000 && nets > 20 && walls > 20);
}

/* The sampled scheme (the paper's Fig. 1): the floor is found when the ball
 * is already `depth` below it, and eq 5 snaps P0 up to the floor, which adds
 * m g depth of potential energy, while the kinetic energy still drops by
 * fd^2. So E(after, on the floor) - E(before, true position) <= m g depth,
 * and depth <= |vy_in| dt (the ball crossed the floor within the frame,
 * speeding up). Checked for 100 seeded random drops and throws. */
/* Each frame's floor events against the segment the frame started on. */
typedef struct snap_check {
  const ball_model *m;
  double dt;
  int shot, events;
  double worst_gain;
  ball_segment before; /* the segment at the start of the frame */
} snap_check;

static int check_snaps(void *ctx, ball_sim *sim, const steps_tally *t, const ball_event *ev, int n) {
  snap_check *c = ctx;
  const ball_model *m = c->m;
  int k;
  (void)t;
  for (k = 0; k < n; k++) {
    ball_state truth;
    double depth, e_before, e_after;
    assert_int_equal(ev[k].kind, BALL_EVENT_FLOOR);
    assert_ok(ball_segment_eval(m, &c->before, ev[k].time, &truth));
    depth = ev[k].point.y - truth.position.y;
    assert_true(depth > 0.0 && depth <= fabs(ev[k].velocity_in.y) * c->dt * (1.0 + 1e-12));
    e_before = core_energy(m, ev[k].velocity_in, truth.position.y);
    e_after = core_energy(m, ev[k].velocity_out, ev[k].point.y);
    if (!(e_after - e_before <= m->mass * m->gravity * depth * (1.0 + 1e-9) + 1e-15))
      fail_msg("shot %d: gain %.6g J > m g depth %.6g J", c->shot, e_after - e_before,
               m->mass * m->gravity * depth);
    if (e_after - e_before > c->worst_gain) c->worst_gain = e_after - e_before;
    c->events++;
  }
  c->before = sim->seg;
  return 1;
}

static void eq5_sampled_snap_adds_at_most_m_g_depth(void **state) {
  core_rng rng = {777u};
  ball_model m;
  ball_sim sim;
  snap_check c;
  (void)state;
  memset(&c, 0, sizeof c);
  c.m = &m;
  c.dt = 1.0 / 30.0;
  for (c.shot = 0; c.shot < 100; c.shot++) {
    drop_scene(&m, BALL_SCHEME_SAMPLED);
    m.floor_damping = core_uniform(&rng, 0.2, 1.0);
    m.initial_position = ball_v3(0.0, core_uniform(&rng, 0.1, 4.0), 0.0);
    m.initial_velocity = ball_v3(core_uniform(&rng, -10.0, 10.0), core_uniform(&rng, -5.0, 8.0),
                                 core_uniform(&rng, -10.0, 10.0));
    assert_ok(ball_sim_init(&sim, &m));
    c.before = sim.seg;
    steps_each(&sim, c.dt, 150, NULL, check_snaps, &c);
  }
  print_message("sampled snap: %d bounces, worst energy gain %.3g J\n", c.events, c.worst_gain);
  assert_true(c.events > 300);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(eq5_sampled_bounce_times_converge_to_exact_as_fps_grows),
      cmocka_unit_test(eq3_eq5_eq6_exact_scheme_is_frame_rate_independent),
      cmocka_unit_test(eq3_eq5_eq6_exact_scheme_is_frame_rate_independent_point_ball),
      cmocka_unit_test(eq5_eq6_energy_never_increases_at_a_collision_exact),
      cmocka_unit_test(eq5_sampled_snap_adds_at_most_m_g_depth),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
