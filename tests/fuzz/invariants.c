/* The frame invariants of the fuzz harnesses (invariants.h), on libball's
 * public API only.
 *
 * Each frame ball_step accepts is checked for:
 *  P1 finite: the state, the free flight to the frame's end and every event
 *     (time, point, velocities, spin, segment) are finite; event kinds and
 *     indices are valid; exact-scheme events lie in [t_prev, t_end] in time
 *     order, sampled ones at t_end (Fig. 3 tests at the frame's end).
 *  P2 floor (FLOOR on): the ball never goes below floor_level + radius.
 *     Exact scheme: along the whole path, by at most tol. Sampled scheme: at
 *     the frame's end, not at all (eq 5 snaps it). Every floor event is at
 *     y = floor_level + radius exactly.
 *  P3 net and walls (an obstacle whose effect is on): a ball clear of a
 *     rectangle (its centre at least radius - tol from it) stays clear:
 *     exact scheme: along the path rebuilt from the events (each event's
 *     segment from its time on), sampled at 17 times per piece, plus the
 *     time the centre crosses the rectangle's plane (it must be outside the
 *     rectangle then) and the time the surface reaches it (then the centre
 *     is outside the face, or the ball does not move on into it); a restart
 *     never jumps (event point = path = new segment's p0, within tol).
 *     Sampled scheme: the paper's Fig. 3 tests the chord between frame ends
 *     (ending on the floor when the free end is below it, where eq 5 shows
 *     the ball), and the frame's end may be pushed off the contact (eq 6's
 *     dt / 10, horizontally along the contact normal); so what is asserted
 *     is that the chord P_old -> Q (Q: the first plane event's point, else
 *     the free end on the floor) and the push Q -> restart never come
 *     nearer than radius - tol to a rectangle the ball was clear of, nor
 *     cross its plane inside it. Every net or wall event's point is within
 *     radius + tol of its rectangle (the ball touches what it hits).
 *  P4 energy, without spin (SPIN off, or no spin on the frame's segment):
 *     every event leaves no faster than it arrived, and E = |v|^2 / 2 +
 *     g (y - floor) does not grow. Exact scheme: by at most tol_e. Sampled
 *     scheme: by at most g times the height the frame's end was moved up
 *     above the free end: the chord's point Q is at most as high as the
 *     higher frame end, the push along an edge normal lifts it by what the
 *     event's segment says, the floor snap to the floor (the m g depth of
 *     docs/hard-cases.md, generalised).
 * Not asserted in a frame with a racket event: eq 7 restarts the ball at
 * Q + V0 dt (below the floor or inside a wall, by design), and a racket
 * adds energy and spin; after it, P2 and P4 wait until the ball is back
 * above the floor (below it, moving down, the exact scheme bounces it at
 * once: eq 5 lifts it to the floor) and P3 until it is clear of a rectangle
 * again (also where such a lift lands it: the lift is a jump by design). The exact scheme's
 * path is not rebuilt in a frame that hit BALL_MAX_CONTACTS (the ball is
 * then held where its last contact left it).
 *
 * Tolerances. Positions are sums of terms up to L = 1 + radius + the largest
 * coordinate in the frame + |v| dt + g dt^2, rounded to a few ulps each: 1e-12 L
 * is 4,500 ulps of L, so only a defect, never rounding, fails; contact times
 * are rounded to the absolute clock, so every event may move the ball by
 * |v| ulp(t): 8 (events + 1) |v| ulp(t_end), and the path at an event's
 * time (not its place) by the fall within that rounding, 8 (events + 1) g
 * ulp(t_end)^2 (on a clock at 1e38 s a whole fall is one tick); 1e-9 m
 * absolute. Energy: 1e-9
 * relative to |v|^2 + g L, plus g tol and |v| g times the clock's rounding.
 * A real defect (a ball through a net, a lift of a ulp-free millimetre) is
 * far above these in every plausible scene. */
#include "invariants.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>

#include "ball/vec3.h"

#define PIECE_SAMPLES 16   /* intervals a path piece is sampled at (17 times) */
#define GOLDEN_STEPS 90    /* golden-section steps on a chord: 0.618^90 = 1.6e-19 of it */

#ifdef FZ_KEEP_GOING
static unsigned long violations;
static void report_violations(void) { fprintf(stderr, "fuzz invariant: %lu violations\n", violations); }
#endif

void fz_fail(const char *fmt, ...) {
  va_list ap;
#ifdef FZ_KEEP_GOING
  if (violations++ == 0) atexit(report_violations);
  if (violations > 10) return; /* the first ten are printed */
#endif
  va_start(ap, fmt);
  fputs("fuzz invariant: ", stderr);
  vfprintf(stderr, fmt, ap);
  fputc('\n', stderr);
  va_end(ap);
#ifndef FZ_KEEP_GOING
  abort();
#endif
}

int fz_finite3(ball_vec3 v) { return isfinite(v.x) && isfinite(v.y) && isfinite(v.z); }

double fz_max_abs(ball_vec3 v) { return fmax(fabs(v.x), fmax(fabs(v.y), fabs(v.z))); }

const ball_plane *fz_obstacle(const ball_model *m, int k) {
  if (k == 0) return (m->effects & BALL_EFFECT_NET) && m->has_net ? &m->net : NULL;
  return (m->effects & BALL_EFFECT_WALLS) && k - 1 < m->n_walls ? &m->walls[k - 1] : NULL;
}

/* signed distance of c from p's plane */
static double side(const ball_plane *p, ball_vec3 c) { return (p->axis == 0 ? c.x : c.z) - p->position; }

double fz_rect_distance(const ball_plane *p, ball_vec3 c) {
  double h = p->axis == 0 ? c.z : c.x;
  double dh = h < p->lo ? p->lo - h : h > p->hi ? h - p->hi : 0.0;
  double dy = c.y < p->bottom ? p->bottom - c.y : c.y > p->top ? c.y - p->top : 0.0;
  return hypot(hypot(side(p, c), dh), dy);
}

/* c's projection lies inside p's face by more than tol (off every edge) */
static int in_face(const ball_plane *p, ball_vec3 c, double tol) {
  double h = p->axis == 0 ? c.z : c.x;
  return h > p->lo + tol && h < p->hi - tol && c.y > p->bottom + tol && c.y < p->top - tol;
}

static double energy(const ball_model *m, const ball_state *s) {
  return 0.5 * ball_v3_dot(s->velocity, s->velocity) + m->gravity * (s->position.y - (m->floor_level + m->radius));
}

double fz_ulp(double x) {
  x = fabs(x);
  return nextafter(x, INFINITY) - x;
}

/* a b, 0 when either is 0 (an infinite tolerance term times a zero speed
 * is no term, not NaN) */
static double mul(double a, double b) { return a == 0.0 || b == 0.0 ? 0.0 : a * b; }

static void seg_finite(const ball_segment *s, const char *what, int i) {
  FZ_CHECK(isfinite(s->t0) && fz_finite3(s->p0) && fz_finite3(s->v0) && fz_finite3(s->s0),
           "%s %d: a segment that is not finite", what, i);
}

/* What a frame is checked with. */
typedef struct frame {
  fz_watch *w;
  double t_end, tol, fy;
  int floor;   /* P2 applies in this frame */
} frame;

/* The ball at t on seg (t >= seg->t0). */
static ball_vec3 at(const frame *f, const ball_segment *seg, double t, ball_state *out) {
  ball_state s;
  FZ_CHECK(ball_segment_eval(f->w->m, seg, t, &s) == BALL_OK, "ball_segment_eval refused t = %.17g on its segment", t);
  FZ_CHECK(fz_finite3(s.position) && fz_finite3(s.velocity), "the path is not finite at t = %.17g", t);
  if (out) *out = s;
  return s.position;
}

/* P2 and P3 at one point of the path. */
static void check_point(const frame *f, ball_vec3 c, double t, const char *where) {
  const fz_watch *w = f->w;
  double r = w->m->radius;
  int k;
  if (f->floor)
    FZ_CHECK(c.y >= fmin(f->fy, w->prev.position.y) - f->tol,
             "%s: below the floor at t = %.17g: y = %.17g < %.17g (tol %.3g)", where, t, c.y, f->fy, f->tol);
  for (k = 0; k < FZ_OBSTACLES; k++) {
    const ball_plane *p = fz_obstacle(w->m, k);
    double d;
    if (!p || !w->clear[k]) continue;
    d = fz_rect_distance(p, c);
    FZ_CHECK(d >= fmin(r, w->dist[k]) - f->tol,
             "%s: inside obstacle %d (%s) at t = %.17g: centre (%.17g, %.17g, %.17g) %.17g from it, radius %.17g "
             "(tol %.3g)",
             where, k, k ? "wall" : "net", t, c.x, c.y, c.z, d, r, f->tol);
  }
}

/* The exact scheme: one piece [ta, tb] of the path on seg. */
static void check_piece(const frame *f, const ball_segment *seg, double ta, double tb) {
  const fz_watch *w = f->w;
  const ball_model *m = w->m;
  double r = m->radius;
  ball_vec3 pa, pb;
  int j, k;
  FZ_CHECK(ta <= tb, "events out of time order: %.17g after %.17g", ta, tb);
  for (j = 0; j <= PIECE_SAMPLES; j++) {
    double t = j == PIECE_SAMPLES ? tb : ta + (tb - ta) * ((double)j / PIECE_SAMPLES);
    ball_vec3 c = at(f, seg, t, NULL);
    check_point(f, c, t, "exact path");
    if (j == 0) pa = c;
    if (j == PIECE_SAMPLES) pb = c;
  }
  for (k = 0; k < FZ_OBSTACLES; k++) {
    const ball_plane *p = fz_obstacle(m, k);
    double sa, sb, tc;
    if (!p || !w->clear[k]) continue;
    sa = side(p, pa);
    sb = side(p, pb);
    /* eq 3's horizontal motion is monotonic: the centre crosses a plane at
     * most once in a piece; it must be outside the rectangle then */
    if ((sa > f->tol && sb < -f->tol) || (sa < -f->tol && sb > f->tol)) {
      ball_vec3 c;
      FZ_CHECK(ball_time_to_plane(m, seg, ta, p->axis, p->position, &tc) == BALL_OK,
               "obstacle %d: the centre crossed its plane in [%.17g, %.17g] but ball_time_to_plane finds no time", k,
               ta, tb);
      c = at(f, seg, fmin(tc, tb), NULL);
      FZ_CHECK(!in_face(p, c, f->tol) && fz_rect_distance(p, c) >= fmin(r, w->dist[k]) - f->tol,
               "through obstacle %d (%s) at t = %.17g without an event: centre (%.17g, %.17g, %.17g)", k,
               k ? "wall" : "net", tc, c.x, c.y, c.z);
    }
    /* the surface reaches the plane: if the centre is then in front of the
     * face, that is a contact, and the ball must not move on into it */
    if (r > 0.0 && fabs(sa) > r + f->tol &&
        ball_time_to_plane(m, seg, ta, p->axis, p->position + copysign(r, sa), &tc) == BALL_OK && tc < tb) {
      ball_vec3 c = at(f, seg, tc, NULL);
      FZ_CHECK(!in_face(p, c, f->tol) || fabs(side(p, c) - sb) <= f->tol || (sb > 0.0) != (sa > 0.0),
               "into the face of obstacle %d (%s) at t = %.17g without an event: centre (%.17g, %.17g, %.17g), "
               "%.17g from the plane at the piece's end t = %.17g",
               k, k ? "wall" : "net", tc, c.x, c.y, c.z, sb, tb);
    }
  }
}

/* The distance from the chord a -> b to p, at its nearest: the distance from
 * a point moving on a line to a convex set is convex, so golden-section
 * search finds the minimum. */
static double chord_distance(const ball_plane *p, ball_vec3 a, ball_vec3 b, ball_vec3 *nearest) {
  const double g = 0.6180339887498949;
  double lo = 0.0, hi = 1.0, x1 = hi - g, x2 = g;
  double f1 = fz_rect_distance(p, ball_v3_lerp(a, b, x1)), f2 = fz_rect_distance(p, ball_v3_lerp(a, b, x2));
  double best, fa = fz_rect_distance(p, a), fb = fz_rect_distance(p, b);
  int i;
  for (i = 0; i < GOLDEN_STEPS; i++) {
    if (f1 <= f2) {
      hi = x2;
      x2 = x1;
      f2 = f1;
      x1 = hi - g * (hi - lo);
      f1 = fz_rect_distance(p, ball_v3_lerp(a, b, x1));
    } else {
      lo = x1;
      x1 = x2;
      f1 = f2;
      x2 = lo + g * (hi - lo);
      f2 = fz_rect_distance(p, ball_v3_lerp(a, b, x2));
    }
  }
  best = fmin(f1, f2);
  *nearest = ball_v3_lerp(a, b, f1 <= f2 ? x1 : x2);
  if (fa < best) {
    best = fa;
    *nearest = a;
  }
  if (fb < best) {
    best = fb;
    *nearest = b;
  }
  return best;
}

/* The sampled scheme: the chord a -> b (a piece of what Fig. 3 tests); the
 * distance to obstacle `near` (-1: none) is not asserted, only that the
 * chord does not cross it. */
static void check_chord(const frame *f, ball_vec3 a, ball_vec3 b, const char *what, int near) {
  const fz_watch *w = f->w;
  double r = w->m->radius;
  int k;
  for (k = 0; k < FZ_OBSTACLES; k++) {
    const ball_plane *p = fz_obstacle(w->m, k);
    double d, sa, sb;
    ball_vec3 c;
    if (!p || !w->clear[k]) continue;
    d = chord_distance(p, a, b, &c);
    FZ_CHECK(k == near || d >= fmin(r, w->dist[k]) - f->tol,
             "sampled %s (%.17g, %.17g, %.17g) -> (%.17g, %.17g, %.17g) comes %.17g near obstacle %d (%s) at "
             "(%.17g, %.17g, %.17g), radius %.17g, without an event",
             what, a.x, a.y, a.z, b.x, b.y, b.z, d, k, k ? "wall" : "net", c.x, c.y, c.z, r);
    sa = side(p, a);
    sb = side(p, b);
    if ((sa > f->tol && sb < -f->tol) || (sa < -f->tol && sb > f->tol)) {
      c = ball_v3_lerp(a, b, sa / (sa - sb));
      FZ_CHECK(!in_face(p, c, f->tol), "sampled %s crosses obstacle %d (%s) at (%.17g, %.17g, %.17g) without an event",
               what, k, k ? "wall" : "net", c.x, c.y, c.z);
    }
  }
}

/* The obstacles the ball is clear of at c, for the next frame. */
static void update_clear(fz_watch *w, ball_vec3 c, double tol) {
  int k;
  for (k = 0; k < FZ_OBSTACLES; k++) {
    const ball_plane *p = fz_obstacle(w->m, k);
    w->dist[k] = p ? fz_rect_distance(p, c) : INFINITY;
    w->clear[k] = p && w->dist[k] >= w->m->radius - tol;
  }
}

void fz_watch_start(fz_watch *w, const ball_model *m, const ball_sim *sim) {
  double fy = m->floor_level + m->radius;
  w->m = m;
  w->frames = 0;
  FZ_CHECK(ball_sim_state(sim, &w->prev) == BALL_OK, "no state after init or set_state");
  FZ_CHECK(fz_finite3(w->prev.position) && fz_finite3(w->prev.velocity) && fz_finite3(w->prev.spin),
           "a state that is not finite after init or set_state");
  /* init and set_state refuse a ball below the floor */
  w->floor_ok = (m->effects & BALL_EFFECT_FLOOR) != 0;
  if (w->floor_ok) FZ_CHECK(w->prev.position.y >= fy, "a start below the floor was accepted");
  update_clear(w, w->prev.position, 1e-9 + 1e-12 * (1.0 + m->radius + fz_max_abs(w->prev.position)));
}

void fz_frame_begin(fz_watch *w, const ball_sim *sim) {
  int i;
  w->t_prev = sim->time;
  w->seg = sim->seg;
  w->p_old = sim->prev_position;
  for (i = 0; i < BALL_WARN_COUNT; i++) w->warnings[i] = sim->warnings[i];
}

void fz_frame_end(fz_watch *w, const ball_sim *sim, double dt, const ball_event *ev, int n) {
  const ball_model *m = w->m;
  int exact = m->scheme == BALL_SCHEME_EXACT, racket = 0, plane_ev = -1, floor_ev = 0, i, k;
  int limited = sim->warnings[BALL_WARN_CONTACT_LIMIT] != w->warnings[BALL_WARN_CONTACT_LIMIT];
  int overflow = sim->warnings[BALL_WARN_EVENT_OVERFLOW] != w->warnings[BALL_WARN_EVENT_OVERFLOW];
  int spinless = !(m->effects & BALL_EFFECT_SPIN) || (w->seg.s0.x == 0.0 && w->seg.s0.y == 0.0 && w->seg.s0.z == 0.0);
  double t_end = sim->time, r = m->radius, g = m->gravity, pmax, vmax, big, tol_e;
  ball_state end, free_end;
  frame f;
  w->frames++;
  f.w = w;
  f.t_end = t_end;
  f.fy = m->floor_level + m->radius;
  /* P1 */
  FZ_CHECK(ball_sim_state(sim, &end) == BALL_OK, "no state after an accepted step");
  FZ_CHECK(fz_finite3(end.position) && fz_finite3(end.velocity) && fz_finite3(end.spin),
           "a state that is not finite after an accepted step");
  FZ_CHECK(n >= 0 && !overflow, "%d events, or more than the harness had room for", n);
  FZ_CHECK(sim->time >= w->t_prev, "the clock went back");
  FZ_CHECK(ball_segment_eval(m, &w->seg, t_end, &free_end) == BALL_OK && fz_finite3(free_end.position) &&
               fz_finite3(free_end.velocity),
           "the frame's free flight is not finite, yet the step was accepted");
  pmax = fmax(fz_max_abs(w->prev.position), fmax(fz_max_abs(end.position), fz_max_abs(free_end.position)));
  vmax = fmax(ball_v3_norm(w->prev.velocity), fmax(ball_v3_norm(end.velocity), ball_v3_norm(free_end.velocity)));
  for (i = 0; i < n; i++) {
    const ball_event *e = &ev[i];
    FZ_CHECK((unsigned)e->kind < BALL_EVENT_KIND_COUNT, "event %d: kind %d", i, (int)e->kind);
    FZ_CHECK(isfinite(e->time) && fz_finite3(e->point) && fz_finite3(e->velocity_in) && fz_finite3(e->velocity_out) &&
                 fz_finite3(e->spin_out),
             "event %d: not finite", i);
    seg_finite(&e->segment, "event", i);
    FZ_CHECK(e->time >= w->t_prev && e->time <= t_end, "event %d at %.17g outside the frame [%.17g, %.17g]", i,
             e->time, w->t_prev, t_end);
    switch (e->kind) {
    case BALL_EVENT_RACKET:
      racket = 1;
      FZ_CHECK(e->index >= 0 && e->index < m->n_rackets, "racket event %d: index %d", i, e->index);
      break;
    case BALL_EVENT_FLOOR:
      floor_ev = 1;
      FZ_CHECK(m->effects & BALL_EFFECT_FLOOR, "a floor event with the floor off");
      FZ_CHECK(e->index == 0, "floor event %d: index %d", i, e->index);
      break;
    default:
      if (plane_ev < 0) plane_ev = i;
      FZ_CHECK(fz_obstacle(m, e->kind == BALL_EVENT_NET ? 0 : 1 + e->index) != NULL &&
                   (e->kind == BALL_EVENT_NET ? e->index == 0 : e->index >= 0),
               "event %d: kind %d index %d is no obstacle in use", i, (int)e->kind, e->index);
    }
    FZ_CHECK(e->segment.t0 == e->time, "event %d: its segment starts at %.17g, not at its time %.17g", i,
             e->segment.t0, e->time);
    pmax = fmax(pmax, fmax(fz_max_abs(e->point), fz_max_abs(e->segment.p0)));
    vmax = fmax(vmax, fmax(ball_v3_norm(e->velocity_in), ball_v3_norm(e->velocity_out)));
  }
  for (k = 0; k < FZ_OBSTACLES; k++) {
    const ball_plane *p = fz_obstacle(m, k);
    if (p)
      pmax = fmax(pmax, fmax(fabs(p->position), fmax(fmax(fabs(p->lo), fabs(p->hi)),
                                                     fmax(fabs(p->bottom), fabs(p->top)))));
  }
  pmax = fmax(pmax, fabs(m->floor_level));
  big = 1.0 + r + pmax + mul(vmax, dt) + g * dt * dt;
  f.tol = 1e-9 + 1e-12 * big + 8.0 * (n + 1) * mul(vmax, fz_ulp(t_end));
  tol_e = 1e-9 * (1.0 + vmax * vmax + g * big) + g * f.tol + 8.0 * (n + 1) * g * mul(vmax, fz_ulp(t_end));
  f.floor = w->floor_ok && !racket;

  if (!racket) {
    for (i = 0; i < n; i++) {
      const ball_event *e = &ev[i];
      if (!exact) FZ_CHECK(e->time == t_end, "sampled event %d at %.17g, not at the frame's end %.17g", i, e->time, t_end);
      if (exact && i > 0) FZ_CHECK(e->time >= ev[i - 1].time, "event %d before event %d", i, i - 1);
      if (e->kind == BALL_EVENT_FLOOR) {
        FZ_CHECK(e->point.y == f.fy, "floor event %d at y = %.17g, not on the floor %.17g", i, e->point.y, f.fy);
      } else {
        const ball_plane *p = fz_obstacle(m, e->kind == BALL_EVENT_NET ? 0 : 1 + e->index);
        double d = fz_rect_distance(p, e->point);
        FZ_CHECK(d <= r + f.tol, "%s event %d at (%.17g, %.17g, %.17g): %.17g from the rectangle, radius %.17g",
                 e->kind == BALL_EVENT_NET ? "net" : "wall", i, e->point.x, e->point.y, e->point.z, d, r);
      }
      if (spinless)
        FZ_CHECK(ball_v3_norm(e->velocity_out) <= ball_v3_norm(e->velocity_in) * (1.0 + 1e-12) + 1e-300,
                 "event %d (kind %d) leaves at %.17g m/s, faster than it came (%.17g)", i, (int)e->kind,
                 ball_v3_norm(e->velocity_out), ball_v3_norm(e->velocity_in));
    }
    /* P2 at the frame's end */
    if (f.floor) {
      if (exact)
        check_point(&f, end.position, t_end, "frame end");
      else
        FZ_CHECK(end.position.y >= f.fy, "sampled: below the floor at the frame's end: y = %.17g < %.17g",
                 end.position.y, f.fy);
    }
    /* P3 */
    if (exact) {
      if (!limited) {
        /* the path: w->seg until the first event, each event's segment until the next */
        const ball_segment *sg = &w->seg;
        double ta = w->t_prev;
        for (i = 0; i <= n; i++) {
          double tb = i < n ? ev[i].time : t_end;
          check_piece(&f, sg, ta, tb);
          if (i < n) {
            ball_vec3 c = at(&f, sg, tb, NULL), q = ev[i].point;
            /* a ball a racket left below the floor bounces at once: eq 5
             * puts it on the floor, a jump up (step.c, floor_contact) */
            int lifted = ev[i].kind == BALL_EVENT_FLOOR && !f.floor && c.y < q.y;
            if (lifted) q.y = c.y;
            /* (the path at the event's time, which the clock rounds: also
             * the fall gravity makes within that rounding, from rest) */
            double jump = f.tol + 8.0 * (n + 1) * g * fz_ulp(t_end) * fz_ulp(t_end);
            ball_vec3 p0 = ev[i].point;
            /* a ball coming to rest on an edge under the floor (a racket left
             * it below) is held at the floor, as eq 5 lifts a falling one
             * (step.c, plane_bounce) */
            if (ev[i].kind != BALL_EVENT_FLOOR && (m->effects & BALL_EFFECT_FLOOR) && ev[i].segment.grounded &&
                p0.y < f.fy) {
              p0.y = f.fy;
              lifted = 1;
            }
            FZ_CHECK(ball_v3_dist(c, q) <= jump && ball_v3_dist(ev[i].segment.p0, p0) <= f.tol,
                     "event %d: the ball jumps from (%.17g, %.17g, %.17g) to the event point (%.17g, %.17g, %.17g) "
                     "and restarts at (%.17g, %.17g, %.17g)",
                     i, c.x, c.y, c.z, ev[i].point.x, ev[i].point.y, ev[i].point.z, ev[i].segment.p0.x,
                     ev[i].segment.p0.y, ev[i].segment.p0.z);
            /* a jump by design, as a racket's: P3 holds for the rectangles
             * the ball is clear of where it lands */
            if (lifted) update_clear(w, ev[i].segment.p0, f.tol);
            sg = &ev[i].segment;
            ta = tb;
          }
        }
        FZ_CHECK(sg->t0 == sim->seg.t0 && sg->grounded == sim->seg.grounded &&
                     ball_v3_dist(sg->p0, sim->seg.p0) == 0.0 && ball_v3_dist(sg->v0, sim->seg.v0) == 0.0,
                 "the last event's segment is not the sim's");
      } else {
        /* a ball a racket left below the floor is lifted to it by its floor
         * events here too (a jump by design, as above): P3 holds for the
         * rectangles it is clear of where the last lift left it */
        for (i = 0; i < n && !f.floor; i++)
          if (ev[i].kind == BALL_EVENT_FLOOR) update_clear(w, ev[i].segment.p0, f.tol);
        check_point(&f, end.position, t_end, "frame end after the contact limit");
      }
    } else {
      /* a ball with a radius: the chord ends where the ball is shown, on
       * the floor if it fell below it; a point ball's is Fig. 3's, to the
       * free end (docs/model.md, "Ball radius, edges and corners") */
      ball_vec3 q = plane_ev >= 0 ? ev[plane_ev].point : free_end.position;
      if (plane_ev < 0 && m->radius > 0.0 && (m->effects & BALL_EFFECT_FLOOR) && q.y < f.fy) q.y = f.fy;
      FZ_CHECK(ball_v3_dist(w->p_old, w->prev.position) == 0.0,
               "sampled: prev_position is not the previous frame's end");
      /* a frame that starts below the floor (a racket's restart left the
       * ball there, eq 7) tests Fig. 3's chord from where the ball cannot
       * be: from under the floor it may pass beneath a low edge or meet the
       * net's face on its way up, and the frame's end shows the ball on the
       * floor. A jump by design, as the restart itself: P3 holds again for
       * the rectangles the ball is clear of where this frame leaves it */
      if (!(m->radius > 0.0 && (m->effects & BALL_EFFECT_FLOOR) && w->p_old.y < f.fy))
        check_chord(&f, w->p_old, q, "chord", -1);
      /* the push off the contact (eq 6's dt / 10, horizontal, along the
       * contact normal, away from the rectangle: a velocity already leaving
       * an edge is not reversed) comes no nearer to any rectangle */
      if (plane_ev >= 0) check_chord(&f, q, ev[plane_ev].segment.p0, "push", -1);
    }
    /* P4 (not while a racket's restart has left the ball below the floor:
     * the floor lifts it) */
    if (spinless && (f.floor || !(m->effects & BALL_EFFECT_FLOOR))) {
      double e0 = energy(m, &w->prev), e1 = energy(m, &end), allowed = e0;
      if (!exact) {
        double y_top = fmax(w->prev.position.y, free_end.position.y);
        for (i = 0; i < n; i++)
          if (ev[i].kind != BALL_EVENT_FLOOR) y_top += fmax(0.0, ev[i].segment.p0.y - ev[i].point.y);
        if (floor_ev) y_top = fmax(y_top, f.fy);
        allowed += g * fmax(0.0, y_top - free_end.position.y);
      }
      FZ_CHECK(e1 <= allowed + tol_e,
               "%s scheme: energy grew from %.17g to %.17g (allowed %.17g, tol %.3g), %d events, dt %.17g",
               exact ? "exact" : "sampled", e0, e1, allowed, tol_e, n, dt);
    }
  }
  /* on to the frame's end */
  w->prev = end;
  if (m->effects & BALL_EFFECT_FLOOR) w->floor_ok = w->floor_ok ? (f.floor || end.position.y >= f.fy) : end.position.y >= f.fy;
  update_clear(w, end.position, f.tol);
}
