/* ball_racket_first_contact and _any: the earliest frame end at which one
 * ball_step from the sim as it is reports a racket hit, against stepping.
 * Seeded swings (kit/swings.h) at 10 Hz under each game level preset and
 * the swept test in both normal modes, each sim caught at a random time
 * before, during or after the stroke, sometimes with a newer sample than
 * its last frame saw (R_old off the new track). For every answer: one step
 * to it reports the hit at the time the query says, one step to the double
 * before (and to 1 ns before) reports none, and a reference by single
 * steps on a grid of frame ends, bisected, finds the same frame end. */
#include <float.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "core_common.h"
#include "swings.h"

#define WINDOW 0.3      /* s searched from the sim's time */
#define GRID 1500       /* reference frame ends over the window */
#define CASES 200       /* swings per configuration */
#define AGREE 1e-12     /* s: query against stepping */

typedef struct config {
  const char *name;
  ball_level level;   /* the preset the model starts from */
  int swept;          /* 1: the preset's normal mode with the swept test */
} config;

static const config configs[] = {
    {"easy (sphere)", BALL_LEVEL_EASY, 0},
    {"mid (disc, velocity normal)", BALL_LEVEL_MID, 0},
    {"advanced (disc, real normal)", BALL_LEVEL_ADVANCED, 0},
    {"swept, real normal", BALL_LEVEL_ADVANCED, 1},
    {"swept, velocity normal", BALL_LEVEL_MID, 1},
};

static void config_model(ball_model *m, const config *c, seeded_rng *r) {
  swing_model(m, BALL_DETECT_DISC);
  assert_ok(ball_model_set_level(m, c->level));
  if (c->swept) m->detect = BALL_DETECT_SWEPT;
  m->extrapolation_time = 0.1; /* eq 15 bridges the 10 Hz gap */
  m->stale_time = 1.0;
  m->history = 3;
  m->scheme = seeded_uniform(r, 0, 1) < 0.5 ? BALL_SCHEME_EXACT : BALL_SCHEME_SAMPLED;
  if (seeded_uniform(r, 0, 1) < 0.5) m->effects |= BALL_EFFECT_FLOOR; /* a floor the search must know of */
  m->floor_level = -10.0; /* below the swing's start (eq 3 run back from the stroke) */
}

/* A seeded case of configuration c: its model and a swing at 10 Hz. */
static void case_of(const config *c, seeded_rng *r, ball_model *m, swing *sw) {
  config_model(m, c, r);
  swing_make(m, r, 0.1, sw);
}

/* One step of a copy to frame end t: 1 if it reports a hit of `racket`
 * (-1: any racket), its racket and time in *which, *time. */
static int step_hits(const ball_sim *sim, double t, int racket, int *which, double *time) {
  ball_sim copy = *sim;
  ball_event ev[STEPS_FRAME_CAP];
  int n, k;
  assert_ok(ball_step(&copy, t - sim->time, ev, STEPS_FRAME_CAP, &n));
  for (k = 0; k < n; k++)
    if (ev[k].kind == BALL_EVENT_RACKET && (racket < 0 || ev[k].index == racket)) {
      if (which) *which = ev[k].index;
      if (time) *time = ev[k].time;
      return 1;
    }
  return 0;
}

/* The first frame end in (lo, hi] where one step hits, hi hitting:
 * bisection on single steps; then, since the swept test's answer need not
 * be monotone in the frame end (a contact that begins inside the frame),
 * earlier frame ends 1e-15 s, 2e-15 s, ... back are tried and an earlier
 * hit bisected again. */
static double reference_edge(const ball_sim *sim, int racket, double lo, double hi) {
  double t0 = sim->time, d;
  int again = 1;
  while (again) {
    again = 0;
    for (;;) {
      double mid = t0 + ((lo + 0.5 * (hi - lo)) - t0);
      if (!(mid > lo && mid < hi)) break;
      if (step_hits(sim, mid, racket, NULL, NULL))
        hi = mid;
      else
        lo = mid;
    }
    for (d = 1e-15; hi - d > lo; d *= 1.7)
      if (step_hits(sim, hi - d, racket, NULL, NULL)) {
        hi = t0 + ((hi - d) - t0);
        again = 1;
        break;
      }
  }
  return hi;
}

/* The reference: single steps to GRID frame ends over (t0, until], the
 * first that hits bisected back (single steps again) to adjacent doubles;
 * -1 if none. */
static double reference(const ball_sim *sim, double until, int racket) {
  double t0 = sim->time, lo = t0, hi = -1.0;
  int j;
  for (j = 1; j <= GRID; j++) {
    double t = t0 + (until - t0) * j / GRID;
    if (j == GRID) t = until;
    if (t <= t0) continue;
    if (step_hits(sim, t, racket, NULL, NULL)) {
      hi = t;
      break;
    }
    lo = t;
  }
  if (hi < 0.0) return -1.0;
  return reference_edge(sim, racket, lo, hi);
}

/* A sim on swing sw caught at time t_catch: the samples up to it pushed,
 * a frame stepped at each, the last frame cut at t_catch; with `newer`, the
 * next sample too (time past t_catch: R_old is then off the new track).
 * Returns 0 if the catch missed (the run was refused). */
static void catch_sim(const ball_model *m, const swing *sw, double t_catch, int newer, ball_sim *sim) {
  ball_state st;
  ball_event ev[STEPS_FRAME_CAP];
  int k, n;
  st.position = sw->seg.p0;
  st.velocity = sw->seg.v0;
  st.spin = sw->seg.s0;
  assert_ok(ball_sim_init(sim, m));
  assert_ok(ball_sim_set_state(sim, &st));
  assert_ok(ball_racket_push(sim, 0, &sw->s[0]));
  for (k = 1; k < sw->n && sw->s[k].t <= t_catch; k++) {
    assert_ok(ball_racket_push(sim, 0, &sw->s[k]));
    assert_ok(ball_step(sim, sw->s[k].t - sim->time, ev, STEPS_FRAME_CAP, &n));
  }
  if (t_catch > sim->time) assert_ok(ball_step(sim, t_catch - sim->time, ev, STEPS_FRAME_CAP, &n));
  if (newer && k < sw->n) assert_ok(ball_racket_push(sim, 0, &sw->s[k]));
}

/* What every answer must satisfy against stepping; returns |query - reference|. */
static double check_answer(const ball_sim *sim, ball_status st, const ball_racket_contact *c, int racket,
                           int *grid_missed) {
  double ref, t_ev = 0.0;
  int which = -1;
  if (st == BALL_OK) {
    double before = nextafter(c->step_to, -INFINITY);
    assert_true(c->step_to > sim->time && c->step_to <= sim->time + WINDOW);
    assert_true(c->searched == c->step_to);
    /* (a) one step to it reports the hit, at the query's time */
    assert_true(step_hits(sim, c->step_to, racket, &which, &t_ev));
    assert_int_equal(which, c->racket);
    assert_near(t_ev, c->time, AGREE);
    if (sim->model.detect != BALL_DETECT_SWEPT) assert_near(c->time, c->step_to, AGREE);
    assert_true(c->time >= sim->time - AGREE && c->time <= c->step_to + AGREE);
    /* (b) one step to any earlier frame end reports none */
    if (before > sim->time) assert_false(step_hits(sim, before, racket, NULL, NULL));
    if (c->step_to - 1e-9 > sim->time)
      assert_false(step_hits(sim, c->step_to - 1e-9, racket, NULL, NULL));
  } else {
    assert_int_equal(st, BALL_ENOTFOUND);
    assert_true(c->searched >= sim->time && c->searched <= sim->time + WINDOW);
    assert_true(isinf(c->step_to));
  }
  /* (c) the reference over what the query searched */
  ref = reference(sim, st == BALL_OK ? sim->time + WINDOW : c->searched, racket);
  if (st == BALL_OK && ref >= 0.0 && ref > c->searched) ref = -1.0; /* past a static contact */
  if (st != BALL_OK) {
    if (ref >= 0.0 && ref <= c->searched)
      fail_msg("query: none through %.17g; stepping: a hit at %.17g (t0 %.17g)", c->searched, ref, sim->time);
    return 0.0;
  }
  if (ref < 0.0 || ref > c->step_to + AGREE) {
    /* the query found a hit the grid stepped over: (a) and (b) vouch for it */
    (*grid_missed)++;
    return 0.0;
  }
  if (!(fabs(ref - c->step_to) <= AGREE))
    fail_msg("query %.17g, stepping %.17g (off by %.3g s; t0 %.17g)", c->step_to, ref, fabs(ref - c->step_to),
             sim->time);
  return fabs(ref - c->step_to);
}

static void first_contact_is_where_one_step_first_hits(void **state) {
  size_t ci;
  (void)state;
  for (ci = 0; ci < sizeof configs / sizeof configs[0]; ci++) {
    seeded_rng r = seeded_stream(20261202, ci);
    int k, found = 0, none = 0, asleep = 0, missed = 0, tests = 0;
    double worst = 0.0;
    for (k = 0; k < CASES; k++) {
      ball_model m;
      swing sw;
      ball_sim sim, before;
      ball_racket_contact c;
      ball_status st;
      uint64_t h;
      double t_catch;
      int newer;
      case_of(&configs[ci], &r, &m, &sw);
      t_catch = seeded_uniform(&r, 0.3, 0.7);
      newer = seeded_uniform(&r, 0, 1) < 0.5;
      catch_sim(&m, &sw, t_catch, newer, &sim);
      before = sim;
      h = ball_sim_hash(&sim);
      st = ball_racket_first_contact(&sim, 0, sim.time + WINDOW, &c);
      /* read only */
      assert_memory_equal(&sim, &before, sizeof sim);
      assert_true(ball_sim_hash(&sim) == h);
      if (sim.sleep > 0) { /* caught just after a hit: the next step tests nothing */
        assert_int_equal(st, BALL_ENOTFOUND);
        assert_true(c.searched == sim.time + WINDOW);
        asleep++;
        continue;
      }
      worst = fmax(worst, check_answer(&sim, st, &c, 0, &missed));
      found += st == BALL_OK;
      none += st != BALL_OK;
      tests++;
    }
    print_message("%-30s %3d found, %3d none, %2d asleep, %d the grid stepped over; worst |query - stepping| "
                  "%.3g s\n", configs[ci].name, found, none, asleep, missed, worst);
    /* the cases must exercise both answers */
    assert_true(found >= CASES / 10);
    assert_true(none >= 3);
    assert_true(missed <= tests / 20);
  }
}

/* Two rackets: the second gets the first's samples moved by a random
 * offset; the _any query gives the frame end and the racket the step
 * reports. */
static void any_racket_is_what_the_step_reports(void **state) {
  size_t ci;
  (void)state;
  for (ci = 0; ci < sizeof configs / sizeof configs[0]; ci++) {
    seeded_rng r = seeded_stream(77, ci);
    int k, found = 0, seconds = 0, missed = 0;
    for (k = 0; k < CASES; k++) {
      ball_model m;
      swing sw;
      ball_sim sim, before;
      ball_racket_contact c, one;
      ball_status st;
      ball_vec3 off = swing_rnd3(&r, -0.3, 0.3);
      int j;
      case_of(&configs[ci], &r, &m, &sw);
      m.n_rackets = 2;
      m.rackets[1] = m.rackets[0];
      catch_sim(&m, &sw, seeded_uniform(&r, 0.25, 0.7), 0, &sim);
      for (j = 0; j < sw.n && sw.s[j].t <= sim.time; j++) {
        ball_racket_sample s = sw.s[j];
        s.center = ball_v3_add(s.center, off);
        assert_ok(ball_racket_push(&sim, 1, &s));
      }
      if (sim.sleep > 0) continue;
      before = sim;
      st = ball_racket_first_contact_any(&sim, sim.time + WINDOW, &c);
      assert_memory_equal(&sim, &before, sizeof sim);
      check_answer(&sim, st, &c, -1, &missed);
      if (st != BALL_OK) {
        assert_int_equal(c.racket, -1);
        continue;
      }
      found++;
      seconds += c.racket == 1;
      /* never later than either racket's own first contact */
      for (j = 0; j < 2; j++)
        if (ball_racket_first_contact(&sim, j, sim.time + WINDOW, &one) == BALL_OK)
          assert_true(c.step_to <= one.step_to);
    }
    print_message("%-30s %3d found, %2d of them racket 1\n", configs[ci].name, found, seconds);
    assert_true(found >= CASES / 40);
    assert_true(seconds > 0);
    assert_true(missed <= found / 10 + 1);
  }
}

/* When swing sw's ball comes closest to its racket's centre (2 ms grid). */
static double closest(const ball_model *m, const swing *sw) {
  double best = INFINITY, at = 0.5;
  int j;
  for (j = 1; j < sw->n; j++) {
    double t;
    for (t = sw->s[j - 1].t; t < sw->s[j].t; t += 0.002) {
      ball_state st;
      double u = (t - sw->s[j - 1].t) / (sw->s[j].t - sw->s[j - 1].t), d;
      assert_ok(ball_segment_eval(m, &sw->seg, t, &st));
      d = ball_v3_dist(st.position, ball_v3_lerp(sw->s[j - 1].center, sw->s[j].center, u));
      if (d < best) {
        best = d;
        at = t;
      }
    }
  }
  return at;
}

/* A case of c whose racket is moved off the ball's path by up to twice the
 * test's reach (*off; many pass near its edge); returns the reach. */
static double near_swing(const config *c, seeded_rng *r, ball_model *m, swing *sw, ball_vec3 *off) {
  double reach;
  int j;
  case_of(c, r, m, sw);
  reach = m->detect == BALL_DETECT_SPHERE ? m->collision_distance : hypot(m->rackets[0].radius + m->radius, m->radius);
  *off = ball_v3_scale(ball_v3_unit(swing_rnd3(r, -1.0, 1.0)), seeded_uniform(r, 0.0, 2.0 * reach));
  for (j = 0; j < sw->n; j++) sw->s[j].center = ball_v3_add(sw->s[j].center, *off);
  return reach;
}

/* ball_racket_may_reach never says 0 where a step finds a hit: swings with
 * their racket moved off the ball's path by up to twice the test's reach
 * (many pass near its edge), caught up to 60 ms before the closest
 * approach. The truth is stepping alone: single steps to 200 frame ends
 * over 100 ms, the first that hits bisected to the first frame end t_hit
 * that does. The bound is asked where it is tightest, over (t0, t_hit] (the
 * hit at the window's very end), and over random windows; wherever a step
 * in the window hits, it must say 1. It must also spare a fair share of
 * the windows without a hit (near as these swings come). */
static void the_bound_never_hides_a_hit(void **state) {
  size_t ci;
  (void)state;
  for (ci = 0; ci < sizeof configs / sizeof configs[0]; ci++) {
    seeded_rng r = seeded_stream(91, ci);
    int k, hits = 0, edge = 0, misses = 0, spared = 0;
    for (k = 0; k < 300; k++) {
      ball_model m;
      swing sw;
      ball_sim sim, before;
      ball_vec3 off;
      double t_end, t_hit = INFINITY, lo, reach;
      int j, may = -1;
      reach = near_swing(&configs[ci], &r, &m, &sw, &off);
      catch_sim(&m, &sw, closest(&m, &sw) - seeded_uniform(&r, 0.0, 0.06), k % 2, &sim);
      if (sim.sleep > 0) continue;
      for (j = 1, lo = sim.time; j <= 200; j++) {
        double t = sim.time + 0.1 * j / 200;
        if (step_hits(&sim, t, -1, NULL, NULL)) {
          t_hit = reference_edge(&sim, -1, lo, t);
          break;
        }
        lo = t;
      }
      before = sim;
      if (isfinite(t_hit)) {
        assert_ok(ball_racket_may_reach(&sim, -1, t_hit, &may));
        if (!may) fail_msg("a step hits at %.17g, the bound said no (t0 %.17g)", t_hit, sim.time);
        assert_ok(ball_racket_may_reach(&sim, 0, t_hit, &may)); /* racket 0 alone: the same */
        assert_int_equal(may, 1);
        hits++;
        edge += ball_v3_norm(off) > 0.8 * reach;
      }
      t_end = sim.time + (k % 2 ? seeded_uniform(&r, 0.0005, 0.005) : seeded_uniform(&r, 0.005, 0.1));
      assert_ok(ball_racket_may_reach(&sim, -1, t_end, &may));
      assert_memory_equal(&sim, &before, sizeof sim);
      if (t_end >= t_hit && !may) fail_msg("a step hits at %.17g, the bound said no through %.17g", t_hit, t_end);
      if (t_end < t_hit) {
        misses++;
        spared += !may;
      }
    }
    print_message("%-30s %3d hits (%d with the racket moved 0.8-2 reaches off), the bound spared %d of %d windows "
                  "without one\n",
                  configs[ci].name, hits, edge, spared, misses);
    assert_true(hits >= 50);
    assert_true(edge >= 10);
    assert_true(spared * 4 >= misses);
  }
}

/* What a server rests on when it spares looks over several frames (the
 * next look after a no over two frames, a late sample ruled out over its
 * whole window): the bound's no over (t0, t_end] holds for every walk of
 * frames through the window, not only one step, while the ball stays on its
 * segment (each frame's P_old and R_old lie on the path and the track the
 * bound held). Swings as above, windows of 5 to 150 ms, walked in frames of
 * 1/240 to 1/30 s; the walk ends at a static contact. */
static void the_bound_covers_every_walk_of_frames(void **state) {
  size_t ci;
  (void)state;
  for (ci = 0; ci < sizeof configs / sizeof configs[0]; ci++) {
    seeded_rng r = seeded_stream(97, ci);
    int k, hits = 0, spared = 0, near = 0, frames = 0;
    for (k = 0; k < 300; k++) {
      ball_model m;
      swing sw;
      ball_sim sim, walk;
      ball_vec3 off;
      ball_event ev[STEPS_FRAME_CAP];
      double t_end, reach;
      int j, n, may = -1, hit = 0, stop = 0;
      reach = near_swing(&configs[ci], &r, &m, &sw, &off);
      catch_sim(&m, &sw, closest(&m, &sw) - seeded_uniform(&r, 0.0, 0.15), k % 2, &sim);
      if (sim.sleep > 0) continue;
      t_end = sim.time + seeded_uniform(&r, 0.005, 0.15);
      assert_ok(ball_racket_may_reach(&sim, -1, t_end, &may));
      walk = sim;
      while (walk.time < t_end && !hit && !stop) {
        double end = walk.time + seeded_uniform(&r, 1.0 / 240, 1.0 / 30);
        if (end > t_end) end = t_end;
        assert_ok(ball_step(&walk, end - walk.time, ev, STEPS_FRAME_CAP, &n));
        frames++;
        for (j = 0; j < n; j++) {
          if (ev[j].kind == BALL_EVENT_RACKET) hit = 1;
          else stop = 1; /* (a static contact: another segment) */
        }
      }
      if (hit && !may) fail_msg("a walk of frames hits before %.17g, the bound said no from %.17g", t_end, sim.time);
      hits += hit;
      if (!may) {
        spared++;
        near += ball_v3_norm(off) < reach;
      }
    }
    print_message("%-30s %3d walks hit; the bound ruled out %d (%d with the racket's path within a reach of the "
                  "ball's), %d frames walked\n", configs[ci].name, hits, spared, near, frames);
    assert_true(hits >= 25);
    assert_true(spared >= 50);
    assert_true(near >= 10);
  }
}

/* At the edge, by hand: a ball at its apex moving at v straight at a racket
 * held still (one sample). Over T the spheres let the ball come |v_h| T +
 * max |v_y| T = (v + g T) T nearer; centres 1e-7 m nearer than the test's
 * reach plus that may be hit, 1e-7 m farther not. The disc and swept tests
 * reach the corner of the disc test's cylinder, sqrt((r + b)^2 + b^2).
 * Along an axis (x, z) the boxes decide where they are tighter: the ball
 * comes v T nearer along it, the test reaches d_COLL, or r + 2 b for a disc
 * (the corner without the square root). */
static void the_bound_at_the_tests_reach(void **state) {
  const ball_detect detects[] = {BALL_DETECT_SPHERE, BALL_DETECT_DISC, BALL_DETECT_SWEPT};
  const double speeds[] = {0.0, 12.0};
  const double dirs[][2] = {{0.6, 0.8}, {1.0, 0.0}, {0.0, -1.0}}; /* (x, z) */
  size_t di, vi, ui;
  (void)state;
  for (di = 0; di < 3; di++)
    for (vi = 0; vi < 2; vi++)
      for (ui = 0; ui < 3; ui++) {
      const double T = 0.01, r = SWING_DISC_R, b = SWING_BALL_R, v = speeds[vi];
      double reach, d, side;
      ball_model m;
      swing_model(&m, detects[di]);
      m.collision_distance = 0.2;
      reach = detects[di] == BALL_DETECT_SPHERE ? 0.2 : sqrt((r + b) * (r + b) + b * b);
      for (side = -1.0; side <= 1.0; side += 2.0) {
        ball_sim sim;
        const double ux = dirs[ui][0], uz = dirs[ui][1];
        ball_state st = {{1.0, 2.0, 3.0}, {ux * v, 0, uz * v}, {0, 0, 0}};
        int may = -1;
        double edge = reach + (v + m.gravity * T) * T;
        if (ux == 0.0 || uz == 0.0) {
          double boxes = (detects[di] == BALL_DETECT_SPHERE ? 0.2 : r + 2.0 * b) + v * T;
          if (boxes < edge) edge = boxes;
        }
        d = edge + side * 1e-7;
        assert_ok(ball_sim_init(&sim, &m));
        assert_ok(ball_sim_set_state(&sim, &st));
        assert_ok(
            ball_racket_push(&sim, 0, &(ball_racket_sample){0.0, {1.0 + d * ux, 2.0, 3.0 + d * uz}, {1, 0, 0}}));
        assert_ok(ball_racket_may_reach(&sim, 0, T, &may));
        assert_int_equal(may, side < 0.0);
      }
    }
}

/* Its bad input, and the cases where the query finds nothing anyway. */
static void the_bound_refuses_bad_input(void **state) {
  ball_model m;
  ball_sim sim, before;
  int may = 7;
  (void)state;
  swing_model(&m, BALL_DETECT_DISC);
  assert_ok(ball_sim_init(&sim, &m));
  assert_ok(ball_racket_may_reach(&sim, -1, 1.0, &may));
  assert_int_equal(may, 0); /* no samples */
  assert_ok(ball_racket_push(&sim, 0, &(ball_racket_sample){0.0, {0.0, 1.0, 0.0}, {1, 0, 0}}));
  assert_ok(ball_racket_may_reach(&sim, -1, 0.1, &may));
  assert_int_equal(may, 1); /* the racket where the ball is */
  assert_ok(ball_racket_may_reach(&sim, -1, 0.0, &may));
  assert_int_equal(may, 0); /* an empty window */
  before = sim;
  may = 7;
  assert_int_equal(ball_racket_may_reach(NULL, -1, 1.0, &may), BALL_EINVAL);
  assert_int_equal(ball_racket_may_reach(&sim, -1, 1.0, NULL), BALL_EINVAL);
  assert_int_equal(ball_racket_may_reach(&sim, -2, 1.0, &may), BALL_EINVAL);
  assert_int_equal(ball_racket_may_reach(&sim, 1, 1.0, &may), BALL_EINVAL); /* n_rackets is 1 */
  assert_int_equal(ball_racket_may_reach(&sim, 0, NAN, &may), BALL_ENONFINITE);
  assert_int_equal(ball_racket_may_reach(&sim, 0, INFINITY, &may), BALL_ENONFINITE);
  assert_int_equal(ball_racket_may_reach(&sim, 0, -1e-9, &may), BALL_ERANGE);
  sim.tracks[0].count = BALL_MAX_HISTORY + 1; /* a track written by hand */
  assert_int_equal(ball_racket_may_reach(&sim, -1, 0.1, &may), BALL_EINVAL);
  sim.tracks[0].count = before.tracks[0].count;
  sim.prev_position.x = sim.prev_position.y = DBL_MAX; /* a sum that overflows asks each number: all finite */
  assert_ok(ball_racket_may_reach(&sim, -1, 0.1, &may));
  assert_int_equal(may, 0);
  sim.prev_position.y = NAN;
  may = 7;
  assert_int_equal(ball_racket_may_reach(&sim, -1, 0.1, &may), BALL_ENONFINITE);
  sim.prev_position = before.prev_position;
  assert_int_equal(may, 7);
  assert_memory_equal(&sim, &before, sizeof sim);
  /* asleep or the effect off: no test in the next step */
  sim.sleep = 1;
  assert_ok(ball_racket_may_reach(&sim, -1, 0.1, &may));
  assert_int_equal(may, 0);
  sim.sleep = 0;
  m.effects &= ~BALL_EFFECT_RACKETS;
  assert_ok(ball_sim_set_model(&sim, &m));
  assert_ok(ball_racket_may_reach(&sim, -1, 0.1, &may));
  assert_int_equal(may, 0);
}

/* A racket 5 m away: nothing in the window, searched through t_end. */
static void no_hit_when_the_racket_stays_away(void **state) {
  size_t ci;
  (void)state;
  for (ci = 0; ci < sizeof configs / sizeof configs[0]; ci++) {
    seeded_rng r = seeded_stream(5, ci);
    int k;
    for (k = 0; k < 20; k++) {
      ball_model m;
      swing sw;
      ball_sim sim;
      ball_racket_contact c;
      int j;
      case_of(&configs[ci], &r, &m, &sw);
      for (j = 0; j < sw.n; j++) sw.s[j].center.z += 5.0;
      catch_sim(&m, &sw, seeded_uniform(&r, 0.25, 0.8), k % 2, &sim);
      assert_int_equal(ball_racket_first_contact(&sim, 0, sim.time + WINDOW, &c), BALL_ENOTFOUND);
      assert_true(c.searched == sim.time + WINDOW);
      assert_true(isinf(c.step_to) && c.racket == 0);
      assert_true(reference(&sim, sim.time + WINDOW, 0) < 0.0);
    }
  }
}

/* A ball falling onto the floor under a racket it reaches only after the
 * bounce: the search stops just before the bounce, in both schemes, and
 * stepping there and asking again finds the hit. */
static void search_stops_before_a_static_contact(void **state) {
  int scheme;
  (void)state;
  for (scheme = 0; scheme < BALL_SCHEME_COUNT; scheme++) {
    ball_model m;
    ball_sim sim;
    ball_racket_contact c;
    ball_event ev[STEPS_FRAME_CAP];
    double t_floor = sqrt(2.0 * 1.0 / 9.81); /* from 1 m, no drag vertically */
    int n;
    swing_model(&m, BALL_DETECT_SPHERE);
    assert_ok(ball_model_set_level(&m, BALL_LEVEL_EASY));
    m.effects |= BALL_EFFECT_FLOOR;
    m.radius = 0.0;
    m.floor_level = 0.0;
    m.floor_damping = 0.9;
    m.scheme = (ball_scheme)scheme;
    m.initial_position = ball_v3(0, 1, 0);
    m.initial_velocity = ball_v3(0, 0, 0);
    assert_ok(ball_sim_init(&sim, &m));
    /* a racket 2 m aside until the bounce, then coming over the rising
     * ball: it reaches it (d_COLL 0.3 m) near t = 0.97 s, after the bounce */
    assert_ok(ball_racket_push(&sim, 0, &(ball_racket_sample){0.0, {2.0, 0.5, 0}, {1, 0, 0}}));
    assert_ok(ball_racket_push(&sim, 0, &(ball_racket_sample){0.45, {2.0, 0.5, 0}, {1, 0, 0}}));
    assert_ok(ball_racket_push(&sim, 0, &(ball_racket_sample){1.0, {0.0, 0.5, 0}, {1, 0, 0}}));
    assert_int_equal(ball_racket_first_contact(&sim, 0, 1.0, &c), BALL_ENOTFOUND);
    assert_near(c.searched, t_floor, 1e-12);
    /* no step to a time in (0, searched] meets the floor */
    {
      ball_sim copy = sim;
      assert_ok(ball_step(&copy, c.searched, ev, STEPS_FRAME_CAP, &n));
      assert_int_equal(n, 0);
    }
    /* the server steps there (the bounce comes in its next step) and asks again */
    assert_ok(ball_step(&sim, c.searched - sim.time, ev, STEPS_FRAME_CAP, &n));
    assert_ok(ball_step(&sim, 1e-6, ev, STEPS_FRAME_CAP, &n));
    assert_int_equal(n, 1);
    assert_int_equal(ev[0].kind, BALL_EVENT_FLOOR);
    assert_ok(ball_racket_first_contact(&sim, 0, 2.0, &c));
    assert_true(step_hits(&sim, c.step_to, 0, NULL, NULL));
    assert_false(step_hits(&sim, nextafter(c.step_to, -INFINITY), 0, NULL, NULL));
  }
}

/* Sleep counts steps: after a hit, every query answers BALL_ENOTFOUND
 * until sleep_frames steps (of any length) have been taken. */
static void sleep_counts_steps_not_seconds(void **state) {
  ball_model m;
  ball_sim sim;
  ball_racket_contact c;
  ball_event ev[STEPS_FRAME_CAP];
  int n, f;
  (void)state;
  swing_model(&m, BALL_DETECT_SPHERE);
  assert_ok(ball_model_set_level(&m, BALL_LEVEL_EASY));
  m.collision_distance = 1.0;
  m.response = BALL_RESPONSE_RACKET;
  m.v_min = 0.5;
  m.initial_position = ball_v3(0, 1, 0);
  assert_ok(ball_sim_init(&sim, &m));
  assert_ok(ball_racket_push(&sim, 0, &(ball_racket_sample){0.0, {0.3, 1, 0}, {1, 0, 0}}));
  /* touching already: the first double after 0 */
  assert_ok(ball_racket_first_contact(&sim, 0, 1.0, &c));
  assert_true(c.step_to == nextafter(0.0, 1.0));
  assert_ok(ball_step(&sim, 0.05, ev, STEPS_FRAME_CAP, &n));
  assert_int_equal(n, 1);
  for (f = 0; f < m.sleep_frames; f++) {
    assert_int_equal(sim.sleep, m.sleep_frames - f);
    assert_int_equal(ball_racket_first_contact(&sim, 0, sim.time + 10.0, &c), BALL_ENOTFOUND);
    assert_true(c.searched == sim.time + 10.0);
    assert_ok(ball_step(&sim, f == 0 ? 1e-6 : 0.02 * f, ev, STEPS_FRAME_CAP, &n)); /* irregular frames */
    assert_int_equal(n, 0);
  }
  assert_int_equal(sim.sleep, 0);
  assert_ok(ball_racket_first_contact(&sim, 0, sim.time + 10.0, &c));
  assert_true(step_hits(&sim, c.step_to, 0, NULL, NULL));
}

/* Bad input: a status, out and the sim unchanged. */
static void bad_input_changes_nothing(void **state) {
  ball_model m;
  ball_sim sim, before;
  ball_racket_contact c, sentinel;
  (void)state;
  swing_model(&m, BALL_DETECT_DISC);
  assert_ok(ball_sim_init(&sim, &m));
  assert_int_equal(ball_racket_first_contact(&sim, 0, 1.0, &c), BALL_ENOTFOUND); /* no samples */
  assert_ok(ball_racket_push(&sim, 0, &(ball_racket_sample){0.0, {0.3, 1, 0}, {1, 0, 0}}));
  assert_ok(ball_step(&sim, 0.5, NULL, 0, NULL));
  memset(&sentinel, 0x5a, sizeof sentinel);
  c = sentinel;
  before = sim;
  assert_int_equal(ball_racket_first_contact(NULL, 0, 1.0, &c), BALL_EINVAL);
  assert_int_equal(ball_racket_first_contact(&sim, 0, 1.0, NULL), BALL_EINVAL);
  assert_int_equal(ball_racket_first_contact(&sim, -1, 1.0, &c), BALL_EINVAL);
  assert_int_equal(ball_racket_first_contact(&sim, 1, 1.0, &c), BALL_EINVAL); /* n_rackets is 1 */
  assert_int_equal(ball_racket_first_contact(&sim, BALL_MAX_RACKETS, 1.0, &c), BALL_EINVAL);
  assert_int_equal(ball_racket_first_contact(&sim, 0, NAN, &c), BALL_ENONFINITE);
  assert_int_equal(ball_racket_first_contact(&sim, 0, INFINITY, &c), BALL_ENONFINITE);
  assert_int_equal(ball_racket_first_contact(&sim, 0, -INFINITY, &c), BALL_ENONFINITE);
  assert_int_equal(ball_racket_first_contact(&sim, 0, 0.25, &c), BALL_ERANGE); /* before sim->time */
  assert_int_equal(ball_racket_first_contact(&sim, 0, nextafter(0.5, 0.0), &c), BALL_ERANGE);
  assert_int_equal(ball_racket_first_contact_any(NULL, 1.0, &c), BALL_EINVAL);
  assert_int_equal(ball_racket_first_contact_any(&sim, 1.0, NULL), BALL_EINVAL);
  assert_int_equal(ball_racket_first_contact_any(&sim, NAN, &c), BALL_ENONFINITE);
  assert_int_equal(ball_racket_first_contact_any(&sim, 0.1, &c), BALL_ERANGE);
  assert_memory_equal(&c, &sentinel, sizeof c);
  assert_memory_equal(&sim, &before, sizeof sim);
  /* an empty window: nothing to find */
  assert_int_equal(ball_racket_first_contact(&sim, 0, 0.5, &c), BALL_ENOTFOUND);
  assert_true(c.searched == 0.5);
  /* stale at sim->time, as ball_racket_estimate: BALL_ESTALE */
  assert_ok(ball_step(&sim, m.stale_time + 1.0, NULL, 0, NULL));
  before = sim;
  assert_int_equal(ball_racket_first_contact(&sim, 0, sim.time + 1.0, &c), BALL_ESTALE);
  assert_int_equal(ball_racket_estimate(&sim, 0, sim.time, &(ball_racket_pose){{0, 0, 0}, {0, 0, 0}, {0, 0, 0}}),
                   BALL_ESTALE);
  assert_memory_equal(&sim, &before, sizeof sim);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(first_contact_is_where_one_step_first_hits),
      cmocka_unit_test(any_racket_is_what_the_step_reports),
      cmocka_unit_test(no_hit_when_the_racket_stays_away),
      cmocka_unit_test(search_stops_before_a_static_contact),
      cmocka_unit_test(sleep_counts_steps_not_seconds),
      cmocka_unit_test(bad_input_changes_nothing),
      cmocka_unit_test(the_bound_never_hides_a_hit),
      cmocka_unit_test(the_bound_covers_every_walk_of_frames),
      cmocka_unit_test(the_bound_at_the_tests_reach),
      cmocka_unit_test(the_bound_refuses_bad_input),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
