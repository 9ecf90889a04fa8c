/* Long runs (docs/hard-cases.md, section 6): a ball bouncing forever in a box
 * (floor and four walls, every damping 1, no drag, exact scheme) for 1e6
 * frames at 60 Hz in CI (4.6 hours of play), 1e7 frames (46 hours) with
 * BALL_LONG=1 (./run long). Checked at every frame: the state is finite, the
 * ball is inside the box and on or above the floor, every floor event is at
 * exactly floor_level + radius (no drift of the floor level), and the energy
 * vy^2 / 2 + g (y - floor) stays within 1e-9 relative of its start (eq 5 with
 * floorDamping 1 and eq 6 with netDamping 1 conserve it; rounding alone may
 * move it). Memory: ball_sim is a fixed-size caller-owned struct and the
 * library makes no allocation call (tests/hard/no_alloc.cmake checks the
 * archive's undefined symbols with nm); here glibc's heap statistics show
 * that a run of a million steps allocates nothing either. */
#define _DEFAULT_SOURCE /* mallinfo2 (glibc) */
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#if defined(__GLIBC__) || defined(__linux__)
#include <malloc.h>
#endif

#include <cmocka.h>

#include "core_common.h"

static long frames_to_run(void) {
  const char *v = getenv("BALL_LONG");
  return v && *v && strcmp(v, "0") != 0 ? 10000000L : 1000000L;
}

/* Bytes in use on the heap, or -1 where glibc's mallinfo2 is missing. */
static long long heap_in_use(void) {
#if defined(__GLIBC__) && (__GLIBC__ > 2 || (__GLIBC__ == 2 && __GLIBC_MINOR__ >= 33))
  struct mallinfo2 mi = mallinfo2();
  return (long long)(mi.uordblks + mi.hblkhd);
#else
  return -1;
#endif
}

static void box_model(ball_model *m, ball_scheme scheme) {
  int k;
  ball_model_default(m);
  m->effects = BALL_EFFECT_FLOOR | BALL_EFFECT_WALLS | BALL_EFFECT_SOUND;
  m->scheme = scheme;
  m->radius = 0.033;
  m->floor_level = 0.25;
  m->floor_damping = 1.0;
  m->bounce_threshold = 0.3;
  for (k = 0; k < 4; k++) {
    ball_plane w;
    w.axis = k < 2 ? 0 : 2;
    w.position = k % 2 ? 10.0 : -10.0;
    w.lo = -10.0;
    w.hi = 10.0;
    w.bottom = 0.0;
    w.top = 50.0;
    w.damping = 1.0;
    assert_int_equal(ball_model_add_wall(m, &w), BALL_OK);
  }
  m->initial_position = ball_v3(0.0, 3.0, 0.0);
  m->initial_velocity = ball_v3(7.3, 4.1, -5.9);
}

static double energy(const ball_model *m, const ball_state *s) {
  return 0.5 * s->velocity.y * s->velocity.y + m->gravity * (s->position.y - m->floor_level - m->radius);
}

/* The rally that never ends: 1e6 (1e7) frames, finite, inside, no floor drift,
 * energy to 1e-9 relative, no heap growth. */
static void test_long_bouncing_run_stays_finite_on_the_floor_eq5_eq6(void **state) {
  ball_model m;
  ball_sim sim;
  ball_state st;
  ball_event ev[16];
  long f, frames = frames_to_run(), floors = 0, walls = 0;
  long long heap_before, heap_after;
  const double fy = 0.25 + 0.033, lim = 10.0 - 0.033, tol = 1e-9;
  double e0, worst = 0.0;
  (void)state;
  box_model(&m, BALL_SCHEME_EXACT);
  assert_int_equal(ball_sim_init(&sim, &m), BALL_OK);
  assert_int_equal(ball_sim_state(&sim, &st), BALL_OK);
  e0 = energy(&m, &st);
  heap_before = heap_in_use();
  for (f = 0; f < frames; f++) {
    int n, i;
    double e;
    if (ball_step(&sim, 1.0 / 60.0, ev, 16, &n) != BALL_OK) fail_msg("frame %ld: step failed", f);
    for (i = 0; i < n; i++) {
      if (ev[i].kind == BALL_EVENT_FLOOR) {
        floors++;
        if (ev[i].point.y != fy) fail_msg("frame %ld: floor event at y = %.17g", f, ev[i].point.y);
      } else {
        walls++;
      }
    }
    if (ball_sim_state(&sim, &st) != BALL_OK) fail_msg("frame %ld: no state", f);
    if (!(st.position.y >= fy - tol && fabs(st.position.x) <= lim + tol && fabs(st.position.z) <= lim + tol))
      fail_msg("frame %ld: ball outside at (%.17g, %.17g, %.17g)", f, st.position.x, st.position.y,
               st.position.z);
    e = energy(&m, &st);
    if (!isfinite(e) || !isfinite(st.position.x) || !isfinite(st.velocity.x) || !isfinite(st.velocity.z))
      fail_msg("frame %ld: non-finite state", f);
    if (fabs(e - e0) > worst) worst = fabs(e - e0);
  }
  heap_after = heap_in_use();
  print_message("%ld frames: %ld floor and %ld wall events, worst energy drift %.3g of %.6g J/kg\n",
                frames, floors, walls, worst, e0);
  assert_true(worst <= 1e-9 * e0);
  assert_true(floors > frames / 200);
  assert_int_equal(sim.warnings[BALL_WARN_CONTACT_LIMIT], 0);
  assert_int_equal(sim.frame, (unsigned long)frames);
  if (heap_before >= 0) assert_true(heap_after == heap_before);
}

/* The paper's sampled scheme over the same box (with floorDamping 0.9, since
 * its floor snap adds up to g * depth per bounce): finite, never below the
 * floor at a frame's end, never outside the walls, for 1e6 frames (1e7). */
static void test_long_sampled_run_stays_finite_and_inside_eq5(void **state) {
  ball_model m;
  ball_sim sim;
  ball_state st;
  long f, frames = frames_to_run();
  const double fy = 0.25 + 0.033, lim = 10.0 - 0.033;
  (void)state;
  box_model(&m, BALL_SCHEME_SAMPLED);
  m.floor_damping = 0.9;
  m.effects |= BALL_EFFECT_DRAG;
  m.air_friction = 0.0;
  assert_int_equal(ball_sim_init(&sim, &m), BALL_OK);
  for (f = 0; f < frames; f++) {
    if (f % 100000 == 0) {
      /* a new serve every 1e5 frames, so the ball is moving most of the run */
      ball_state s0;
      s0.position = ball_v3(0.0, 3.0, 0.0);
      s0.velocity = ball_v3(7.3 + (double)(f / 100000), 4.1, -5.9);
      s0.spin = ball_v3(0.0, 0.0, 0.0);
      assert_int_equal(ball_sim_set_state(&sim, &s0), BALL_OK);
    }
    if (ball_step(&sim, 1.0 / 60.0, NULL, 0, NULL) != BALL_OK) fail_msg("frame %ld: step failed", f);
    if (ball_sim_state(&sim, &st) != BALL_OK) fail_msg("frame %ld: no state", f);
    /* the paper's shift pushes the ball dt / 10 * |v| back from a wall: inside by construction */
    if (!(st.position.y >= fy && fabs(st.position.x) <= lim + 1e-9 && fabs(st.position.z) <= lim + 1e-9) ||
        !isfinite(st.velocity.x) || !isfinite(st.velocity.y) || !isfinite(st.velocity.z))
      fail_msg("frame %ld: ball at (%.17g, %.17g, %.17g)", f, st.position.x, st.position.y, st.position.z);
  }
}

/* The rally that never ends, with rackets: the easy level (sphere test,
 * autonomous ball, eq 8, 9) between two still rackets sending samples at
 * 10 Hz, for 1e6 frames (1e7 with BALL_LONG). V_up is chosen so that the
 * flight time t0 = 2 V_up / g (eq 8) is exactly 49 frames: every stroke
 * lands on the partner's centre at a frame, so the rally neither drifts nor
 * breaks, and every racket event must come 49 frames after the previous one,
 * alternating between the rackets, at the height of the first stroke: within
 * 1e-4 m, since the clock is a sum of frame times whose rounding (an ulp of t
 * is 4e-12 s at t = 2e4 s) moves each stroke by up to |V_up| ulp(t), about
 * 1.5e-11 m: 7e-6 m after the 2e5 strokes of the long run (seen: 1e-6 m
 * after 28,000). */
static void test_long_racket_rally_never_breaks_eq8_eq9(void **state) {
  ball_model m;
  ball_sim sim;
  ball_state st;
  ball_event ev[8];
  ball_racket_sample smp;
  long f, frames = frames_to_run(), hits = 0, last_hit = -1;
  long long heap0;
  int n, i, r, last_racket = -1;
  double stroke_y = 0.0;
  const double dt = 1.0 / 60.0;
  (void)state;
  ball_model_default(&m);
  assert_int_equal(ball_model_set_level(&m, BALL_LEVEL_EASY), BALL_OK);
  m.n_rackets = 2;
  m.rackets[0].partner = 1;
  m.rackets[1].partner = 0;
  m.v_up = 49.0 * dt * m.gravity / 2.0; /* eq 8: t0 = 2 V_up / g = 49 frames */
  m.initial_position = ball_v3(1.1, 1.0, 5.485);
  m.initial_velocity = ball_v3(0.0, 0.0, 0.0);
  assert_int_equal(ball_sim_init(&sim, &m), BALL_OK);
  heap0 = heap_in_use();
  for (f = 0; f < frames; f++) {
    if (f % 6 == 0)
      for (r = 0; r < 2; r++) {
        smp.t = sim.time;
        smp.center = r == 0 ? ball_v3(1.0, 1.0, 5.485) : ball_v3(22.77, 1.0, 5.485);
        smp.normal = ball_v3(r == 0 ? 1.0 : -1.0, 0.0, 0.0);
        if (ball_racket_push(&sim, r, &smp) != BALL_OK) fail_msg("frame %ld: sample refused", f);
      }
    if (ball_step(&sim, dt, ev, 8, &n) != BALL_OK) fail_msg("frame %ld: step failed", f);
    for (i = 0; i < n; i++) {
      if (ev[i].kind != BALL_EVENT_RACKET)
        fail_msg("frame %ld: a %d event: the rally broke", f, (int)ev[i].kind);
      if (hits == 0) stroke_y = ev[i].point.y;
      if ((hits > 0 && f - last_hit != 49) || ev[i].index == last_racket ||
          fabs(ev[i].point.y - stroke_y) > 1e-4)
        fail_msg("frame %ld: hit %ld by racket %d at y %.17g, %ld frames after the last",
                 f, hits, ev[i].index, ev[i].point.y, f - last_hit);
      last_hit = f;
      last_racket = ev[i].index;
      hits++;
    }
    if (ball_sim_state(&sim, &st) != BALL_OK || !(st.position.y >= 0.0) ||
        !isfinite(st.velocity.x) || !isfinite(st.velocity.y) || !isfinite(st.velocity.z))
      fail_msg("frame %ld: ball at (%.17g, %.17g, %.17g)", f, st.position.x, st.position.y, st.position.z);
  }
  print_message("%ld frames: %ld racket hits, stroke height %.17g m\n", frames, hits, stroke_y);
  assert_true(hits >= frames / 49 - 1);
  assert_int_equal((long)sim.warnings[BALL_WARN_STALE_RACKET], 0);
  if (heap0 >= 0) assert_int_equal(heap_in_use(), heap0);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_long_bouncing_run_stays_finite_on_the_floor_eq5_eq6),
      cmocka_unit_test(test_long_sampled_run_stays_finite_and_inside_eq5),
      cmocka_unit_test(test_long_racket_rally_never_breaks_eq8_eq9),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
