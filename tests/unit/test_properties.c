/* Property tests (docs/hard-cases.md, "Invariants"): seeded random scenes
 * checked against invariants that hold for every scene. CI runs a few
 * thousand cases; BALL_LONG=1 (./run long) runs 1e6 per property. A failure
 * prints the case's seed; BALL_SEED=<seed> reruns that one case alone.
 *
 * The invariants (tolerances derived in docs/hard-cases.md):
 *  P1 finite in, finite out: every accepted step leaves a finite state and
 *     finite events.
 *  P2 the ball never ends a frame below floor_level + radius (exact: by more
 *     than 1e-9 m, rounding of y0 + v t - g t^2 / 2; sampled: not at all, eq 5
 *     snaps it), nor behind a wall that spans the whole scene.
 *  P3 it never crosses the net's rectangle without a net event (exact scheme).
 *  P4 without spin and with dampings <= 1, the energy |v|^2 / 2 + g y never
 *     grows (exact; drag, eq 5 and eq 6 only remove energy); in the sampled
 *     scheme the floor snap can add g * depth, depth <= |vy_in| dt - g dt^2 / 2.
 *  P5 with spin, a floor bounce obeys |V0| <= floorDamping |V| +
 *     spinFloorDamping |S0| (eq 13: |S x n| <= |S|, eq 4: |S(t)| <= |S0|).
 *  P6 exact mode is frame-rate independent: 1/8, 1/64 and 1/1024 s frames
 *     give the same state after 4 s.
 *  P7 bad input (a NaN, Inf or out-of-range field, a bad dt or state) is
 *     refused and leaves the sim byte for byte unchanged.
 *  P8 every range ball_model_check accepts runs (below).
 *  P9 the ball's centre never crosses the net's or a wall's rectangle grown
 *     by the radius (its face, edge cylinders and corner spheres) without an
 *     event: on the analytic path between events (exact scheme), on the
 *     frame's chord up to its contact (sampled scheme). */
#include <float.h>
#include <math.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "core_common.h"

/* ---- seeded draws (kit/seeded.h: a case's seed is the generator's state) ---- */

typedef seeded_rng rng;

static double uni(rng *r, double lo, double hi) { return seeded_uniform(r, lo, hi); }
static int coin(rng *r, double p) { return uni(r, 0.0, 1.0) < p; }
static ball_vec3 uvec(rng *r, double a) { return ball_v3(uni(r, -a, a), uni(r, -a, a), uni(r, -a, a)); }
static double norm(ball_vec3 v) { return hypot(hypot(v.x, v.y), v.z); } /* no underflow at 1e-160 */
static int finite3(ball_vec3 v) { return isfinite(v.x) && isfinite(v.y) && isfinite(v.z); }

/* ---- case counts ---- */

static int long_mode(void) {
  const char *v = getenv("BALL_LONG");
  return v && *v && strcmp(v, "0") != 0;
}

/* The seeds to run: BALL_SEED alone, or base + 0 .. n - 1. */
static void seeds(uint64_t base, long ci_cases, uint64_t *first, long *count) {
  const char *one = getenv("BALL_SEED");
  if (one && *one) {
    *first = strtoull(one, NULL, 0);
    *count = 1;
    return;
  }
  *first = base;
  *count = long_mode() ? 1000000L : ci_cases;
}

#define FAIL_SEED(seed, ...)                                                     \
  do {                                                                           \
    char msg_[512];                                                              \
    snprintf(msg_, sizeof msg_, __VA_ARGS__);                                    \
    fail_msg("seed %llu (rerun: BALL_SEED=%llu): %s", (unsigned long long)(seed), \
             (unsigned long long)(seed), msg_);                                  \
  } while (0)

/* ---- random scenes ---- */

typedef struct scene_opts {
  int spin;       /* allow the SPIN effect */
  int full_walls; /* walls span the whole scene (P2 on walls) */
  int floor_only; /* no net, no walls */
  int scheme;     /* -1: either; else the ball_scheme to use */
  double radius_max; /* the largest radius drawn (0: 0.2 m) */
} scene_opts;

/* A random but valid scene: floor, net, up to four walls boxing the start,
 * random drag, radius, dampings in [0, 1], thresholds, scheme; the ball above
 * the floor, inside the walls, at up to 30 m/s. */
static void random_scene(rng *r, ball_model *m, const scene_opts *o) {
  int k;
  double x0, z0;
  ball_model_default(m);
  m->scheme = coin(r, 0.5) ? BALL_SCHEME_EXACT : BALL_SCHEME_SAMPLED;
  if (o->scheme >= 0) m->scheme = (ball_scheme)o->scheme;
  m->effects = BALL_EFFECT_FLOOR | BALL_EFFECT_SOUND;
  if (coin(r, 0.7)) m->effects |= BALL_EFFECT_DRAG;
  if (coin(r, 0.7)) m->effects |= BALL_EFFECT_NET;
  if (coin(r, 0.6)) m->effects |= BALL_EFFECT_WALLS;
  if (o->spin) m->effects |= BALL_EFFECT_SPIN;
  if (o->floor_only) m->effects &= ~(unsigned)(BALL_EFFECT_NET | BALL_EFFECT_WALLS);
  m->gravity = uni(r, 1.0, 20.0);
  m->mass = uni(r, 0.01, 1.0);
  m->air_friction = coin(r, 0.2) ? 0.0 : pow(10.0, uni(r, -6.0, 1.0));
  m->radius = coin(r, 0.3) ? 0.0 : uni(r, 0.0, o->radius_max > 0.0 ? o->radius_max : 0.2);
  m->spin_damping = uni(r, 0.1, 5.0);
  m->floor_level = uni(r, -5.0, 5.0);
  m->floor_damping = coin(r, 0.1) ? 1.0 : uni(r, 0.0, 1.0);
  m->bounce_threshold = coin(r, 0.1) ? 0.0 : uni(r, 0.0, 1.0);
  m->sound_threshold = uni(r, 0.0, 2.0);
  m->spin_floor_damping = uni(r, 0.0, 1.0);
  x0 = uni(r, -20.0, 20.0);
  z0 = uni(r, -20.0, 20.0);
  m->net.axis = coin(r, 0.5) ? 0 : 2;
  m->net.position = (m->net.axis == 0 ? x0 : z0) + uni(r, -5.0, 5.0);
  m->net.lo = (m->net.axis == 0 ? z0 : x0) + uni(r, -8.0, 0.0);
  m->net.hi = m->net.lo + uni(r, 0.5, 16.0);
  m->net.bottom = m->floor_level + (coin(r, 0.5) ? 0.0 : uni(r, -1.0, 1.0));
  m->net.top = m->net.bottom + uni(r, 0.1, 3.0);
  m->net.damping = uni(r, 0.0, 1.0);
  m->n_walls = 0;
  if (m->effects & BALL_EFFECT_WALLS)
    for (k = 0; k < 4; k++) {
      ball_plane w;
      double c = k < 2 ? x0 : z0, other = k < 2 ? z0 : x0;
      /* walls at exact coordinates a restart one ulp away can fall below
       * (docs/hard-cases.md, "walls at 0"): 0, -0, 1e-300, +-4.9e-324 */
      static const double exact[] = {0.0, -0.0, 1e-300, 4.9406564584124654e-324, -4.9406564584124654e-324};
      w.axis = k < 2 ? 0 : 2;
      w.position = c + (k % 2 ? 1.0 : -1.0) * uni(r, 1.0 + m->radius, 15.0);
      if (k % 2 == 0 && coin(r, 0.15)) {
        /* this wall at an exact coordinate, the start moved to keep its distance */
        double at = exact[seeded_below(r, 5)], shift = at - w.position;
        w.position = at;
        if (k < 2) x0 += shift; else z0 += shift;
      }
      w.lo = o->full_walls ? other - 1e4 : other + uni(r, -10.0, 0.0);
      w.hi = o->full_walls ? other + 1e4 : w.lo + uni(r, 0.5, 20.0);
      /* full walls reach far below the floor too: the sampled scheme tests the
       * chord P_old -> P (Fig. 3), which can dip below the floor in a long frame */
      w.bottom = o->full_walls ? m->floor_level - 1e6 : m->floor_level + uni(r, -1.0, 2.0);
      w.top = o->full_walls ? m->floor_level + 1e6 : w.bottom + uni(r, 0.5, 5.0);
      w.damping = coin(r, 0.2) ? 1.0 : uni(r, 0.0, 1.0);
      if (ball_model_add_wall(m, &w) != BALL_OK) fail_msg("random wall rejected");
    }
  m->initial_position = ball_v3(x0, m->floor_level + m->radius + (coin(r, 0.2) ? 0.0 : uni(r, 0.0, 5.0)), z0);
  /* not overlapping the net at the start: P3 and P9 are about crossing it.
   * The net moves away from the ball (moving the ball could put it into a
   * wall placed at 1 + r from it) */
  if (m->effects & BALL_EFFECT_NET) {
    double c = m->net.axis == 0 ? m->initial_position.x : m->initial_position.z;
    if (fabs(c - m->net.position) < m->radius + 1e-6) m->net.position = c + m->radius + 0.01;
  }
  m->initial_velocity = uvec(r, 30.0);
  m->initial_spin = o->spin ? uvec(r, 30.0) : ball_v3(0.0, 0.0, 0.0);
}

static double random_dt(rng *r) {
  switch (seeded_below(r, 4)) {
  case 0: return 1.0 / 60.0;
  case 1: return 1.0 / 2.0;
  case 2: return pow(10.0, uni(r, -4.0, 0.0));
  default: return 1.0 / 8.0;
  }
}

static double energy(const ball_model *m, const ball_state *s) {
  double v2 = s->velocity.x * s->velocity.x + s->velocity.y * s->velocity.y + s->velocity.z * s->velocity.z;
  return 0.5 * v2 + m->gravity * (s->position.y - m->floor_level - m->radius);
}

static int inside_extent(const ball_plane *p, ball_vec3 c, double tol) {
  double h = p->axis == 0 ? c.z : c.x;
  return h >= p->lo - tol && h <= p->hi + tol && c.y >= p->bottom - tol && c.y <= p->top + tol;
}

static double coord(ball_vec3 v, int axis) { return axis == 0 ? v.x : v.z; }

/* ---- P1, P2, P3, P4: one random scene over many frames ---- */

#define FRAMES 40
#define EV_CAP (BALL_MAX_CONTACTS + 2)

static void check_scene(uint64_t seed, const scene_opts *o, int check_energy) {
  rng r;
  ball_model m;
  ball_sim sim;
  ball_state prev, st;
  ball_event ev[EV_CAP];
  double dt, fy, side[BALL_MAX_WALLS];
  int f, i, n;
  r.s = seed;
  random_scene(&r, &m, o);
  dt = random_dt(&r);
  fy = m.floor_level + m.radius;
  if (ball_sim_init(&sim, &m) != BALL_OK) FAIL_SEED(seed, "a valid random scene was refused");
  if (ball_sim_state(&sim, &prev) != BALL_OK) FAIL_SEED(seed, "no state");
  for (i = 0; i < m.n_walls; i++) side[i] = coord(prev.position, m.walls[i].axis) - m.walls[i].position;
  for (f = 0; f < FRAMES; f++) {
    ball_segment seg_before = sim.seg;
    double t_prev = sim.time, e_prev = energy(&m, &prev), s_max = norm(sim.seg.s0);
    int net_event = 0;
    ball_status stt = ball_step(&sim, dt, ev, EV_CAP, &n);
    if (stt != BALL_OK) FAIL_SEED(seed, "frame %d: step refused a valid frame (%s)", f, ball_strerror(stt));
    if (ball_sim_state(&sim, &st) != BALL_OK) FAIL_SEED(seed, "frame %d: no state", f);
    /* P1 */
    if (!finite3(st.position) || !finite3(st.velocity) || !finite3(st.spin))
      FAIL_SEED(seed, "frame %d: non-finite state", f);
    for (i = 0; i < n; i++) {
      const ball_event *e = &ev[i];
      if (!isfinite(e->time) || !finite3(e->point) || !finite3(e->velocity_in) ||
          !finite3(e->velocity_out) || !finite3(e->spin_out))
        FAIL_SEED(seed, "frame %d: non-finite event %d", f, i);
      if (e->kind == BALL_EVENT_NET) net_event = 1;
      /* P5: eq 13 bound at every floor bounce (also holds, trivially, without spin) */
      if (e->kind == BALL_EVENT_FLOOR) {
        double bound = m.floor_damping * norm(e->velocity_in) + m.spin_floor_damping * s_max;
        if (!(norm(e->velocity_out) <= bound * (1.0 + 1e-12) + 1e-12))
          FAIL_SEED(seed, "frame %d: floor bounce |V0| = %.17g > %.17g (eq 13 bound)", f,
                    norm(e->velocity_out), bound);
        if (!(norm(e->spin_out) <= m.spin_floor_damping * s_max * (1.0 + 1e-12) + 1e-300))
          FAIL_SEED(seed, "frame %d: floor bounce |S0| = %.17g > %.17g (eq 14)", f, norm(e->spin_out),
                    m.spin_floor_damping * s_max);
      }
      if (e->kind != BALL_EVENT_RACKET) s_max = norm(e->spin_out) > s_max ? s_max : norm(e->spin_out);
    }
    /* P2: floor */
    if (m.scheme == BALL_SCHEME_EXACT ? !(st.position.y >= fy - 1e-9) : !(st.position.y >= fy))
      FAIL_SEED(seed, "frame %d: ball at y = %.17g below the floor %.17g", f, st.position.y, fy);
    /* P2: full walls are never crossed (the sampled scheme's dt / 10 push
     * keeps it on its side too) */
    if (o->full_walls)
      for (i = 0; i < m.n_walls; i++) {
        double d = coord(st.position, m.walls[i].axis) - m.walls[i].position;
        if (side[i] * d < 0.0 || fabs(d) < m.radius - 1e-9)
          FAIL_SEED(seed, "frame %d: ball through wall %d (%.17g -> %.17g)", f, i, side[i], d);
      }
    /* P3: exact scheme, a frame without any event: if the surface reached the
     * net plane in the frame, the centre was outside the net's rectangle then */
    if (m.scheme == BALL_SCHEME_EXACT && (m.effects & BALL_EFFECT_NET) && n == 0 && !net_event) {
      int a = m.net.axis;
      double v = coord(seg_before.v0, a), target, t_hit;
      if (v != 0.0) {
        target = m.net.position - (v > 0.0 ? m.radius : -m.radius);
        if (ball_time_to_plane(&m, &seg_before, t_prev, a, target, &t_hit) == BALL_OK && t_hit < sim.time &&
            coord(prev.position, a) != target) {
          ball_state at;
          if (ball_segment_eval(&m, &seg_before, t_hit, &at) == BALL_OK && inside_extent(&m.net, at.position, -1e-9))
            FAIL_SEED(seed, "frame %d: through the net at t = %.17g, (%.17g, %.17g, %.17g)", f, t_hit,
                      at.position.x, at.position.y, at.position.z);
        }
      }
    }
    /* P4: energy */
    if (check_energy) {
      double e = energy(&m, &st), allowed = e_prev;
      double scale = 1.0 + fabs(e_prev) + m.gravity * (fabs(st.position.y - fy) + fabs(prev.position.y - fy));
      /* sampled: every contact of a frame is at its end, where the ball is
       * below where it started by at most y_old - y_end = -vy dt - g dt^2 / 2
       * (vy: the first event's arriving vertical speed); the floor snap and
       * the restart at Q on the chord (eq 6) lift it by no more than that */
      if (m.scheme == BALL_SCHEME_SAMPLED && n > 0) {
        double drop = -ev[0].velocity_in.y * dt - 0.5 * m.gravity * dt * dt;
        if (drop > 0.0) allowed += m.gravity * drop;
      }
      if (!(e <= allowed + 1e-9 * scale))
        FAIL_SEED(seed, "frame %d: energy grew from %.17g to %.17g (allowed %.17g, %d events)", f, e_prev,
                  e, allowed, n);
    }
    prev = st;
  }
}

/* P1, P2, P3 over random scenes with spin, nets and walls (any extent). */
static void test_random_scenes_stay_finite_above_floor_and_off_the_net(void **state) {
  uint64_t first;
  long count, i;
  scene_opts o = {1, 0, 0, -1, 0.0};
  (void)state;
  seeds(1000000, 10000, &first, &count);
  for (i = 0; i < count; i++) check_scene(first + (uint64_t)i, &o, 0);
}

/* P2 on walls spanning everything: the ball stays in its box (exact scheme). */
static void test_random_exact_scenes_never_cross_a_full_wall(void **state) {
  uint64_t first;
  long count, i;
  scene_opts o = {0, 1, 0, BALL_SCHEME_EXACT, 0.0};
  (void)state;
  seeds(2000000, 10000, &first, &count);
  for (i = 0; i < count; i++) check_scene(first + (uint64_t)i, &o, 0);
}

/* P2 on walls spanning everything, sampled scheme (Fig. 3 on each wall). */
static void test_random_sampled_scenes_never_cross_a_full_wall(void **state) {
  uint64_t first;
  long count, i;
  scene_opts o = {0, 1, 0, BALL_SCHEME_SAMPLED, 0.0};
  (void)state;
  seeds(7000000, 10000, &first, &count);
  for (i = 0; i < count; i++) check_scene(first + (uint64_t)i, &o, 0);
}

/* P4: without spin, dampings <= 1: energy never grows (exact), grows by at
 * most g * depth per sampled floor snap. */
static void test_random_scenes_never_gain_energy_without_spin_eq5_eq6(void **state) {
  uint64_t first;
  long count, i;
  scene_opts o = {0, 0, 0, -1, 0.0};
  (void)state;
  seeds(3000000, 10000, &first, &count);
  for (i = 0; i < count; i++) check_scene(first + (uint64_t)i, &o, 1);
}

/* P5 is checked inside every scene above; this property runs spin scenes
 * with floor only, where every event is a floor bounce. */
static void test_random_spin_bounces_obey_the_eq13_bound(void **state) {
  uint64_t first;
  long count, i;
  scene_opts o = {1, 0, 1, -1, 0.0};
  (void)state;
  seeds(4000000, 10000, &first, &count);
  for (i = 0; i < count; i++) check_scene(first + (uint64_t)i, &o, 0);
}

/* ---- P6: frame-rate independence of the exact scheme ---- */

static void test_random_exact_scenes_are_frame_rate_independent(void **state) {
  static const double dts[] = {1.0 / 8.0, 1.0 / 64.0, 1.0 / 1024.0};
  uint64_t first;
  long count, i;
  scene_opts o = {1, 0, 0, -1, 0.0};
  (void)state;
  long skipped = 0;
  seeds(5000000, 300, &first, &count);
  if (long_mode() && !getenv("BALL_SEED")) count /= 10; /* 4096 frames a case: 1e5 cases */
  for (i = 0; i < count; i++) {
    uint64_t seed = first + (uint64_t)i;
    rng r;
    ball_model m;
    ball_state out[3];
    size_t k;
    int limited = 0;
    r.s = seed;
    random_scene(&r, &m, &o);
    m.scheme = BALL_SCHEME_EXACT;
    for (k = 0; k < 3; k++) {
      ball_sim sim;
      long f, frames = (long)(4.0 / dts[k]);
      if (ball_sim_init(&sim, &m) != BALL_OK) FAIL_SEED(seed, "scene refused");
      for (f = 0; f < frames; f++)
        if (ball_step(&sim, dts[k], NULL, 0, NULL) != BALL_OK) FAIL_SEED(seed, "step refused");
      if (sim.time != 4.0) FAIL_SEED(seed, "clock at %.17g, not 4", sim.time);
      limited |= sim.warnings[BALL_WARN_CONTACT_LIMIT] > 0;
      if (ball_sim_state(&sim, &out[k]) != BALL_OK) FAIL_SEED(seed, "no state");
    }
    /* more than BALL_MAX_CONTACTS contacts in one step (a Zeno run of
     * bounces with bounce_threshold ~ 0): the frame decides where the
     * stepper gives up, so the result may depend on it (docs/hard-cases.md) */
    if (limited) {
      skipped++;
      continue;
    }
    for (k = 1; k < 3; k++) {
      double dp = norm(ball_v3(out[k].position.x - out[0].position.x, out[k].position.y - out[0].position.y,
                           out[k].position.z - out[0].position.z));
      double dv = norm(ball_v3(out[k].velocity.x - out[0].velocity.x, out[k].velocity.y - out[0].velocity.y,
                           out[k].velocity.z - out[0].velocity.z));
      if (!(dp <= 1e-6 && dv <= 1e-6))
        FAIL_SEED(seed, "dt %g vs 1/8: positions differ by %.3g m, velocities by %.3g m/s", dts[k], dp, dv);
    }
  }
  print_message("%ld of %ld cases hit the contact limit and were not compared\n", skipped, count);
  assert_true(skipped * 10 <= count); /* the property is checked on at least 90 % of the cases */
}

/* ---- P7: bad input changes nothing ---- */

/* Breaks one random field of a valid model. */
static void break_model(rng *r, ball_model *m) {
  static const double bad[] = {NAN, INFINITY, -INFINITY, -1.0, 2.0, -1e-300};
  double v = bad[seeded_below(r, 6)];
  switch (seeded_below(r, 16)) {
  case 0: m->gravity = v > 0.0 && isfinite(v) ? -v : v; break;
  case 1: m->mass = isfinite(v) && v > 0.0 ? 0.0 : v; break;
  case 2: m->air_friction = isfinite(v) && v > 0.0 ? -v : v; break;
  case 3: m->radius = isfinite(v) && v > 0.0 ? -v : v; break;
  case 4: m->floor_damping = v == -1e-300 ? 1.5 : v; break;
  case 5: m->spin_floor_damping = v == -1e-300 ? 1.0000001 : v; break;
  case 6: m->floor_level = NAN; break;
  case 7: m->net.damping = 1.5; m->has_net = 1; break;
  case 8: m->net.hi = m->net.lo; m->has_net = 1; break;
  case 9: m->n_walls = BALL_MAX_WALLS + 1; break;
  case 10: m->scheme = (ball_scheme)7; break;
  case 11: m->effects = 1u << 12; break;
  case 12: m->spin_damping = 0.0; break;
  case 13: m->bounce_threshold = v == 2.0 ? -2.0 : v; break;
  case 14: m->has_net = 2; break;
  default: m->gravity = 0.0; break;
  }
}

static void test_bad_inputs_leave_the_sim_unchanged(void **state) {
  uint64_t first;
  long count, i;
  scene_opts o = {1, 0, 0, -1, 0.0};
  (void)state;
  seeds(6000000, 10000, &first, &count);
  for (i = 0; i < count; i++) {
    uint64_t seed = first + (uint64_t)i;
    rng r;
    ball_model m, bad;
    ball_sim sim, copy;
    ball_state s;
    ball_status st;
    ball_event ev[4];
    int n = 0;
    (void)st;
    r.s = seed;
    random_scene(&r, &m, &o);
    if (ball_sim_init(&sim, &m) != BALL_OK) FAIL_SEED(seed, "scene refused");
    steps_run(&sim, 1.0 / 60.0, 3, NULL);
    bad = m;
    break_model(&r, &bad);
    if (ball_model_check(&bad, NULL) == BALL_OK) FAIL_SEED(seed, "a broken model passed ball_model_check");
    /* the calls that hand a model to a sim refuse it and leave the sim as
     * it was; the sim's own model is untouched by the broken copy */
    copy = sim;
    if (ball_sim_init(&sim, &bad) == BALL_OK) FAIL_SEED(seed, "sim_init with a broken model was accepted");
    if (memcmp(&sim, &copy, sizeof sim) != 0) FAIL_SEED(seed, "a refused sim_init changed the sim");
    s.position = ball_v3(0.0, m.floor_level + m.radius + 1.0, 0.0);
    s.velocity = ball_v3(1.0, 1.0, 1.0);
    s.spin = ball_v3(0.0, 0.0, 0.0);
    {
      ball_sim trial = sim;
      if (ball_sim_set_state(&trial, &s) != BALL_OK && memcmp(&trial, &copy, sizeof sim) != 0)
        FAIL_SEED(seed, "a refused set_state changed the sim");
    }
    if (ball_sim_set_model(&sim, &bad) == BALL_OK) FAIL_SEED(seed, "set_model with a broken model was accepted");
    if (memcmp(&sim, &copy, sizeof sim) != 0) FAIL_SEED(seed, "a refused set_model changed the sim");
    switch (seeded_below(&r, 5)) {
    case 0: s.position.x = NAN; break;
    case 1: s.velocity.z = INFINITY; break;
    case 2: s.spin.y = -INFINITY; break;
    case 3: s.position.y = m.floor_level + m.radius - 1e-6; break;
    default: s.velocity.y = NAN; break;
    }
    if (ball_sim_set_state(&sim, &s) == BALL_OK) FAIL_SEED(seed, "a bad state was accepted");
    if (ball_step(&sim, coin(&r, 0.5) ? -uni(&r, 1e-300, 10.0) : NAN, ev, 4, &n) == BALL_OK)
      FAIL_SEED(seed, "a bad dt was accepted");
    if (memcmp(&sim, &copy, sizeof sim) != 0) FAIL_SEED(seed, "a refused call changed the sim");
  }
}

/* P8, every range that ball_model_check accepts is one the stepper handles
 * (gravity up to 9e307 was once accepted and the ball then sank). Each
 * case starts from the default court (every effect but rackets on, a net
 * and a box of four walls) and puts each real field, vector component and
 * plane coordinate at an end of its range (the field table's lo or hi, the
 * nearest double inside an open end) with probability 1/3; cases that the
 * cross-field rules refuse are drawn again. Then 240 frames of 1/60 s, 20 of
 * 1 s and 2 of 1e3 s, both schemes: every step OK, every state finite and
 * never below the floor. */
/* which: -1 the low end only, +1 the high end only, 0 either (fields whose
 * ends must keep a cross-field rule: lo < hi, bottom < top, v_min <= v_max,
 * the ball above the floor). */
static double range_end(rng *r, const ball_field *f, double value, int which) {
  int hi = which ? which > 0 : coin(r, 0.5);
  double lo_end = f->flags & BALL_FIELD_LO_OPEN ? nextafter(f->lo, INFINITY) : f->lo;
  double hi_end = f->flags & BALL_FIELD_HI_OPEN ? nextafter(f->hi, -INFINITY) : f->hi;
  if (!coin(r, 1.0 / 3.0)) return value;
  if (hi && isfinite(hi_end)) return hi_end;
  if (!hi && isfinite(lo_end)) return lo_end;
  if (isfinite(hi_end)) return hi_end;
  if (isfinite(lo_end)) return lo_end;
  return coin(r, 0.5) ? DBL_MAX : -DBL_MAX;
}

static int end_side(const char *name) {
  static const char *const low[] = {"lo", "bottom", "v_min", "floor_level"};
  static const char *const high[] = {"hi", "top", "v_max"};
  size_t i;
  for (i = 0; i < sizeof low / sizeof low[0]; i++)
    if (strcmp(name, low[i]) == 0) return -1;
  for (i = 0; i < sizeof high / sizeof high[0]; i++)
    if (strcmp(name, high[i]) == 0) return 1;
  return 0;
}

static void ends_of(rng *r, void *base, const ball_field *f, int n) {
  int i;
  for (i = 0; i < n; i++) {
    double *d = (double *)((char *)base + f[i].offset);
    if (f[i].type == BALL_FIELD_REAL) *d = range_end(r, &f[i], *d, end_side(f[i].name));
    if (f[i].type == BALL_FIELD_VEC3) {
      d[0] = range_end(r, &f[i], d[0], 0);
      /* the ball's start stays above the floor: only its high end */
      d[1] = range_end(r, &f[i], d[1], strcmp(f[i].name, "initial_position") == 0 ? 1 : 0);
      d[2] = range_end(r, &f[i], d[2], 0);
    }
  }
}

static void test_models_at_the_ends_of_their_ranges_run(void **state) {
  uint64_t first;
  long count, i, accepted = 0;
  (void)state;
  seeds(8000000, 3000, &first, &count);
  if (long_mode() && !getenv("BALL_SEED")) count /= 10; /* 524 frames a case: 1e5 cases */
  for (i = 0; i < count; i++) {
    uint64_t seed = first + (uint64_t)i;
    rng r;
    ball_model m;
    ball_sim sim;
    int n, np, nr, k, w, scheme;
    const ball_field *f = ball_model_fields(&n);
    const ball_field *pf = ball_plane_fields(&np);
    const ball_field *rf = ball_racket_fields(&nr);
    r.s = seed;
    ball_model_default(&m);
    m.effects = BALL_EFFECT_ALL & ~(unsigned)BALL_EFFECT_RACKETS;
    for (w = 0; w < 4; w++) {
      ball_plane p = {w % 2 ? 2 : 0, w < 2 ? (w ? -1.0 : 25.0) : (w == 3 ? -1.0 : 12.0), -5.0, 30.0, 0.0, 5.0, 0.8};
      p.position = w < 2 ? (w == 0 ? 25.0 : -1.0) : (w == 2 ? 12.0 : -1.0);
      if (ball_model_add_wall(&m, &p) != BALL_OK) fail_msg("wall");
    }
    ends_of(&r, &m, f, n);
    ends_of(&r, &m.net, pf, np);
    for (w = 0; w < m.n_walls; w++) ends_of(&r, &m.walls[w], pf, np);
    ends_of(&r, &m.rackets[0], rf, nr);
    if (ball_model_check(&m, NULL) != BALL_OK) continue; /* a cross-field rule: drawn again */
    accepted++;
    for (scheme = 0; scheme < BALL_SCHEME_COUNT; scheme++) {
      m.scheme = (ball_scheme)scheme;
      if (ball_sim_init(&sim, &m) != BALL_OK) FAIL_SEED(seed, "init refused a checked model");
      for (k = 0; k < 262; k++) {
        double dt = k < 240 ? 1.0 / 60.0 : k < 260 ? 1.0 : 1e3;
        ball_status st = ball_step(&sim, dt, NULL, 0, NULL);
        ball_state s;
        if (st != BALL_OK) FAIL_SEED(seed, "%s scheme, frame %d: %s", ball_scheme_name(m.scheme), k, ball_strerror(st));
        if (ball_sim_state(&sim, &s) != BALL_OK || !ball_v3_finite(s.position) || !ball_v3_finite(s.velocity))
          FAIL_SEED(seed, "frame %d: not finite", k);
        if (s.position.y < m.floor_level + m.radius - 1e-9 * (1.0 + fabs(m.floor_level) + m.radius))
          FAIL_SEED(seed, "%s scheme, frame %d: below the floor (%.17g < %.17g)", ball_scheme_name(m.scheme), k,
                    s.position.y, m.floor_level + m.radius);
      }
    }
  }
  if (accepted < count / 4) fail_msg("only %ld of %ld cases passed the model check", accepted, count);
}

/* ---- P9: no crossing of a grown rectangle without an event ---- */

/* The signed distance, within the plane, from the point c (in the plane)
 * to the rectangle: negative inside it. */
static double in_plane_distance(const ball_plane *p, ball_vec3 c) {
  double h = p->axis == 0 ? c.z : c.x;
  double dh = fmax(p->lo - h, h - p->hi), dy = fmax(p->bottom - c.y, c.y - p->top);
  if (dh <= 0.0 && dy <= 0.0) return fmax(dh, dy);
  return hypot(fmax(dh, 0.0), fmax(dy, 0.0));
}

/* The distance from c to the rectangle, in space. */
static double rect_distance(const ball_plane *p, ball_vec3 c) {
  ball_vec3 in = c;
  double d = coord(c, p->axis) - p->position, e;
  if (p->axis == 0) in.x = p->position; else in.z = p->position;
  e = in_plane_distance(p, in);
  return e <= 0.0 ? fabs(d) : hypot(d, e);
}

typedef struct planes_of {
  const ball_plane *p[BALL_MAX_WALLS + 1];
  int n;
} planes_of;

static void active_planes(const ball_model *m, planes_of *ps) {
  int i;
  ps->n = 0;
  if ((m->effects & BALL_EFFECT_NET) && m->has_net) ps->p[ps->n++] = &m->net;
  if (m->effects & BALL_EFFECT_WALLS)
    for (i = 0; i < m->n_walls; i++) ps->p[ps->n++] = &m->walls[i];
}

/* Exact scheme: the path on seg over [ta, tb] (one piece between events)
 * never has its centre in a plane within the grown rectangle, nor deeper
 * than tol inside it at 16 points along it. */
static void check_piece(uint64_t seed, int f, const ball_model *m, const planes_of *ps, const ball_segment *seg,
                        double ta, double tb, double tol) {
  int i, k;
  for (i = 0; i < ps->n; i++) {
    const ball_plane *p = ps->p[i];
    double t;
    ball_state at;
    if (ball_time_to_plane(m, seg, ta, p->axis, p->position, &t) == BALL_OK &&
        t < tb - 1e-12 * (1.0 + fabs(tb)) && ball_segment_eval(m, seg, t, &at) == BALL_OK &&
        in_plane_distance(p, at.position) < m->radius - tol)
      FAIL_SEED(seed, "frame %d: the centre crosses %s's grown rectangle at t = %.17g, (%.17g, %.17g, %.17g), "
                "%.3g m inside, no event", f, p == &m->net ? "the net" : "a wall", t, at.position.x,
                at.position.y, at.position.z, m->radius - in_plane_distance(p, at.position));
    for (k = 0; k <= 16; k++) {
      double tk = ta + (tb - ta) * k / 16.0;
      if (ball_segment_eval(m, seg, tk, &at) == BALL_OK && rect_distance(p, at.position) < m->radius - tol)
        FAIL_SEED(seed, "frame %d: the ball is %.3g m inside %s's grown rectangle at t = %.17g", f,
                  m->radius - rect_distance(p, at.position), p == &m->net ? "the net" : "a wall", tk);
    }
  }
}

/* Sampled scheme: the chord a -> b (the frame's, up to its contact) never
 * crosses a plane within its grown rectangle. */
static void check_chord(uint64_t seed, int f, const ball_model *m, const planes_of *ps, ball_vec3 a, ball_vec3 b,
                        double tol) {
  int i;
  for (i = 0; i < ps->n; i++) {
    const ball_plane *p = ps->p[i];
    double xa = coord(a, p->axis) - p->position, xb = coord(b, p->axis) - p->position;
    if ((xa < 0.0 && xb > 0.0) || (xa > 0.0 && xb < 0.0)) {
      ball_vec3 c = ball_v3_lerp(a, b, xa / (xa - xb));
      if (in_plane_distance(p, c) < m->radius - tol)
        FAIL_SEED(seed, "frame %d: the chord crosses %s's grown rectangle at (%.17g, %.17g, %.17g), no event", f,
                  p == &m->net ? "the net" : "a wall", c.x, c.y, c.z);
    }
  }
}

static void check_crossings(uint64_t seed, const scene_opts *o) {
  rng r;
  ball_model m;
  ball_sim sim;
  ball_event ev[EV_CAP];
  planes_of ps;
  double dt;
  int f, i, n;
  r.s = seed;
  random_scene(&r, &m, o);
  dt = coin(&r, 0.2) ? uni(&r, 1.0, 3.0) : random_dt(&r); /* below 1 Hz too */
  active_planes(&m, &ps);
  if (ball_sim_init(&sim, &m) != BALL_OK) FAIL_SEED(seed, "a valid random scene was refused");
  for (f = 0; f < FRAMES; f++) {
    ball_segment seg = sim.seg;
    ball_state before, end;
    double t = sim.time, tol;
    unsigned long limits = sim.warnings[BALL_WARN_CONTACT_LIMIT];
    ball_sim_state(&sim, &before);
    if (ball_step(&sim, dt, ev, EV_CAP, &n) != BALL_OK) FAIL_SEED(seed, "frame %d: step refused", f);
    tol = 1e-9 * (1.0 + ball_v3_max_abs(before.position) + norm(before.velocity) * dt);
    if (m.scheme == BALL_SCHEME_EXACT) {
      for (i = 0; i < n; i++) {
        check_piece(seed, f, &m, &ps, &seg, t, ev[i].time, tol);
        seg = ev[i].segment;
        t = ev[i].time;
      }
      /* past BALL_MAX_CONTACTS the ball stays where the last contact left
       * it for the rest of the frame (docs/model.md): no last piece */
      if (sim.warnings[BALL_WARN_CONTACT_LIMIT] == limits) check_piece(seed, f, &m, &ps, &seg, t, sim.time, tol);
    } else {
      /* the chord from the last frame's end to this one's (for a ball with
       * a radius on the floor if it fell below: where the ball is shown; a
       * point ball's is Fig. 3's), or to the first net or wall contact on it */
      ball_vec3 b;
      if (ball_segment_eval(&m, &seg, sim.time, &end) != BALL_OK) FAIL_SEED(seed, "frame %d: no end", f);
      b = end.position;
      if (m.radius > 0.0 && (m.effects & BALL_EFFECT_FLOOR) && b.y < m.floor_level + m.radius)
        b.y = m.floor_level + m.radius;
      for (i = 0; i < n; i++)
        if (ev[i].kind == BALL_EVENT_NET || ev[i].kind == BALL_EVENT_WALL) {
          b = ev[i].point;
          break;
        }
      check_chord(seed, f, &m, &ps, before.position, b, tol);
    }
  }
}

/* P9 over random scenes with a net, walls of any extent and radii up to
 * 1 m, both schemes, frames from 1e-4 s to 3 s. */
static void test_random_scenes_never_cross_a_grown_rectangle_without_an_event(void **state) {
  uint64_t first;
  long count, i;
  scene_opts o = {1, 0, 0, -1, 1.0};
  (void)state;
  seeds(9000000, 10000, &first, &count);
  for (i = 0; i < count; i++) check_crossings(first + (uint64_t)i, &o);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_random_scenes_stay_finite_above_floor_and_off_the_net),
      cmocka_unit_test(test_random_exact_scenes_never_cross_a_full_wall),
      cmocka_unit_test(test_random_sampled_scenes_never_cross_a_full_wall),
      cmocka_unit_test(test_random_scenes_never_gain_energy_without_spin_eq5_eq6),
      cmocka_unit_test(test_random_spin_bounces_obey_the_eq13_bound),
      cmocka_unit_test(test_random_exact_scenes_are_frame_rate_independent),
      cmocka_unit_test(test_bad_inputs_leave_the_sim_unchanged),
      cmocka_unit_test(test_models_at_the_ends_of_their_ranges_run),
      cmocka_unit_test(test_random_scenes_never_cross_a_grown_rectangle_without_an_event),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
