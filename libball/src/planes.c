/* The net and the walls (Fig. 3, eq 6) for a ball with a radius: the
 * rectangle grown by the radius, that is its face, four edge cylinders and
 * four corner spheres (docs/model.md, "Ball radius, edges and corners").
 *
 * The face is found in closed form, as before (the plane's crossing by
 * inverting eq 3, then the extent). The edges and corners are the points
 * of the grown rectangle that the face's test cannot see: a ball that first
 * touches the plane above the top edge or past a side edge and then moves
 * inward, or one that only skims an edge. They are found by the search
 * below on the distance from the ball's centre to the rectangle, on the
 * analytic path (exact scheme) or on the frame's chord (sampled scheme),
 * over the time the ball is inside the grown rectangle's box (closed form
 * on each axis), before the face's contact and any contact already known.
 * The normal of an edge or corner contact points from the rectangle's
 * nearest point to the ball's centre. */
#include <string.h>

#include "internal.h"

static double clampd(double v, double lo, double hi) { return v < lo ? lo : v > hi ? hi : v; }

ball_vec3 ball__rect_nearest(const ball_plane *pl, ball_vec3 c) {
  ball_vec3 q = c;
  if (pl->axis == 0) {
    q.x = pl->position;
    q.z = clampd(c.z, pl->lo, pl->hi);
  } else {
    q.z = pl->position;
    q.x = clampd(c.x, pl->lo, pl->hi);
  }
  q.y = clampd(c.y, pl->bottom, pl->top);
  return q;
}

/* 1 when q (a nearest point) lies inside the face, off its edges: a contact
 * there is the face's, which the closed form finds. */
static int face_interior(const ball_plane *pl, ball_vec3 q) {
  double h = pl->axis == 0 ? q.z : q.x;
  return h > pl->lo && h < pl->hi && q.y > pl->bottom && q.y < pl->top;
}

/* The bound on the centre's acceleration along the path from where the
 * horizontal speed is vh: |a| <= k vh + g (eq 3; g 0 on the floor), a
 * little over for rounding; no horizontal speed, no drag's part (k is +Inf
 * where b underflows to 0). */
static double path_acc(double k, double vh, double g) { return ((vh > 0.0 ? k * vh : 0.0) + g) * (1.0 + 1e-12); }

/* ---- the search: advancement on a second-order bound ----
 *
 * d(t) = |c(t) - nearest| - r, the ball's distance to the rectangle, is the
 * distance to a convex set along the centre's path: convex in space, so
 * d'' >= -|c''| >= -A. From a time where it is d with d' = n.v (n the unit
 * normal from the nearest point), d(t + tau) >= d + d' tau - A tau^2 / 2,
 * which stays positive for tau < tau* = (d' + sqrt(d'^2 + 2 A d)) / A:
 * the search steps by tau* (rigorous: it cannot step past a contact),
 * a Newton step from the left on a chord (A = 0) or when the ball closes
 * in, and a wide step when it moves away. It stops when the distance is
 * within rounding of 0 while the ball moves in (the contact, at most a few
 * ulps of the coordinates clear of it), or at tb. A ball that starts
 * touching or overlapping and moves out is followed out in doubling steps;
 * it is in contact again only if it moves in, and a doubling step that
 * ends moving in is taken again halved, down to the least step: a long one
 * could pass over its coming clear and the contact after it. */

typedef struct rim_ctx {
  const ball_plane *pl;
  double radius;
  const ball__flight *fl; /* the exact scheme: the path on seg */
  const ball_segment *seg;
  double g;               /* the exact scheme: gravity's part of the bound (0 grounded) */
  ball_vec3 p0, p1; /* the sampled scheme: the chord p0 -> p1 */
} rim_ctx;

/* The centre and its velocity at t (time, or the chord's fraction). */
typedef void (*state_fn)(const rim_ctx *ctx, double t, ball_vec3 *c, ball_vec3 *v);

#define PLANES_MAX_STEPS 4096

static int advance(state_fn at, const rim_ctx *x, double ta, double tb, double acc, double *t_hit, ball_vec3 *q,
                   ball_vec3 *n) {
  double t = ta, out_step = 0.0, out_cap = INFINITY, t_prev = ta;
  int i;
  for (i = 0; i < PLANES_MAX_STEPS; i++) {
    ball_vec3 c, v, near, diff;
    double len, d, dp, eps, tau, disc;
    at(x, t, &c, &v);
    if (x->fl) {
      /* on the path |v_h| only falls (eq 3), so k |v_h| + g from here on
       * bounds the rest; taken when it has fallen below half the bound in
       * use (a drag that stops the ball in 1e-289 s left a bound of 1e287
       * from the window's start, and steps of 1e-144 s) */
      double a = path_acc(x->fl->k, sqrt(v.x * v.x + v.z * v.z), x->g);
      if (a < 0.5 * acc) acc = a;
    }
    near = ball__rect_nearest(x->pl, c);
    diff = ball_v3_sub(c, near);
    len = ball_v3_norm(diff);
    d = len - x->radius;
    /* the centre in the rectangle itself (a ball started in the net): no
     * normal, no way in; it is followed out */
    dp = len > 0.0 ? ball_v3_dot(diff, v) / len : 0.0;
    /* within rounding of the coordinates */
    eps = 1e-13 * (1.0 + ball_v3_max_abs(c) + x->radius);
    if (d <= eps) {
      if (dp < 0.0) {
        /* moving in, come to by a follow-out step longer than the least: the
         * ball may have come clear and back within it (a big ball along an
         * edge it started on): that step again from its start, halved */
        if (out_step > 1e-15 * (1.0 + fabs(t_prev))) {
          out_cap = 0.5 * out_step;
          out_step = 0.5 * out_cap; /* (doubled to out_cap below) */
          t = t_prev;
          continue;
        }
        *t_hit = t;
        *q = c;
        *n = len > 0.0 ? ball_v3_scale(diff, 1.0 / len) : ball_v3(0.0, 0.0, 0.0);
        return 1;
      }
      /* touching or overlapping, moving out: follow it out */
      out_step = out_step > 0.0 ? fmin(2.0 * out_step, out_cap) : 1e-15 * (1.0 + fabs(t));
      tau = out_step;
    } else {
      out_step = 0.0;
      out_cap = INFINITY;
      disc = sqrt(dp * dp + 2.0 * acc * d);
      if (dp <= 0.0)
        tau = 2.0 * d / (disc - dp); /* the root of the bound, without cancellation */
      else
        tau = acc > 0.0 ? (dp + disc) / acc : INFINITY; /* moving away on a line: for good */
    }
    /* an infinite bound (1 / b = +Inf on a moving ball: inf / inf) knows no
     * step: the smallest, and the bound again from there (V_h is 0 then) */
    if (!(tau >= 0.0)) tau = 0.0;
    if (!(t + tau <= tb)) return 0;
    if (t + tau == t) tau = 1e-15 * (1.0 + fabs(t)); /* below the clock's ulp: one ulp on */
    t_prev = t;
    t += tau;
  }
  return 0; /* a search that long does not converge: the ball skims; let it be */
}

/* ---- the exact scheme: on the analytic path ---- */

/* At tau on seg (time from its start: the search's steps, and its
 * follow-out steps of 1e-15 (1 + |tau|), stay fine on a clock whose ulp is
 * longer than the contact's time scale). */
static void path_state(const rim_ctx *x, double tau, ball_vec3 *c, ball_vec3 *v) {
  ball_state s;
  double d, f;
  ball__drag_terms(x->fl->b, x->fl->k, tau, &d, &f);
  ball__state_at(x->fl->g, x->fl->sdamp, x->seg, tau, d, f, &s);
  *c = s.position;
  *v = s.velocity;
}

/* tau at which b (1 - e^(-tau/b)) (or tau without drag) reaches d >= 0; +Inf
 * when drag stops the ball short of it (eq 3 inverted). */
static double tau_of_distance(const ball__flight *fl, double d) {
  if (!(d > 0.0)) return 0.0;
  if (fl->k == 0.0) return d;
  if (d >= fl->b) return INFINITY;
  return -fl->b * ball__log1p(-d / fl->b);
}

/* The taus at which a horizontal coordinate x0 + v D(tau) is in [lo, hi]:
 * an interval [*t0, *t1] (t1 may be +Inf); 0 if never. */
static int slab(const ball__flight *fl, double x0, double v, double lo, double hi, double *t0, double *t1) {
  if (v == 0.0) {
    *t0 = 0.0;
    *t1 = INFINITY;
    return x0 >= lo && x0 <= hi;
  }
  if (v > 0.0) {
    if (x0 > hi) return 0;
    *t0 = tau_of_distance(fl, (lo - x0) / v);
    *t1 = tau_of_distance(fl, (hi - x0) / v);
  } else {
    if (x0 < lo) return 0;
    *t0 = tau_of_distance(fl, (hi - x0) / v);
    *t1 = tau_of_distance(fl, (lo - x0) / v);
  }
  return isfinite(*t0);
}

/* The earliest time in [tau_from, tau_to] the ball's surface reaches the
 * rectangle's edges or corners while approaching it: 1 with *tau, the
 * centre *q and the contact normal *n. */
static int rim_exact(const ball_model *m, const ball__flight *fl, const ball_segment *seg, const ball_plane *pl,
                     double tau_from, double tau_to, double *tau, ball_vec3 *q, ball_vec3 *n) {
  double r = m->radius, w0 = tau_from, w1 = tau_to, w_seg, t0, t1, acc, t_hit;
  int a = pl->axis, h = a == 0 ? 2 : 0;
  rim_ctx ctx;
  ball_state s;
  /* the window: inside the slabs of the grown rectangle's bounding box */
  if (!slab(fl, ball_v3_axis(seg->p0, a), ball_v3_axis(seg->v0, a), pl->position - r, pl->position + r, &t0, &t1))
    return 0;
  w0 = fmax(w0, t0);
  w_seg = t0;
  w1 = fmin(w1, t1);
  if (!slab(fl, ball_v3_axis(seg->p0, h), ball_v3_axis(seg->v0, h), pl->lo - r, pl->hi + r, &t0, &t1)) return 0;
  w0 = fmax(w0, t0);
  w_seg = fmax(w_seg, t0);
  w1 = fmin(w1, t1);
  if (!seg->grounded) {
    /* after the descending root of y = bottom - r the ball stays below */
    double r1, r2;
    if (!ball__height_roots(fl->g, seg->p0.y, seg->v0.y, pl->bottom - r, &r1, &r2)) return 0;
    w1 = fmin(w1, r2);
  } else if (seg->p0.y < pl->bottom - r || seg->p0.y > pl->top + r) {
    return 0;
  }
  if (!isfinite(w1)) {
    /* drag holds the ball inside the box: it stops there; after the
     * remaining distance is below a femtometre nothing moves */
    double vh = sqrt(seg->v0.x * seg->v0.x + seg->v0.z * seg->v0.z);
    if (fl->k == 0.0 || !(vh > 0.0)) w1 = w0;
    else w1 = fmax(w0, fl->b * ball__log(fmax(vh * fl->b / 1e-15, 1.0)));
  }
  if (!(w0 <= w1)) return 0;
  {
    /* the ball's acceleration bounds d'' from below (the distance to a
     * convex set is convex in space): |a| <= k |v_h| + g (eq 3), |v_h| at
     * the window's start, where it is largest */
    double vh;
    ball__eval_f(fl, seg, seg->t0 + w_seg, &s);
    vh = sqrt(s.velocity.x * s.velocity.x + s.velocity.z * s.velocity.z);
    acc = path_acc(fl->k, vh, seg->grounded ? 0.0 : fl->g);
  }
  memset(&ctx, 0, sizeof ctx);
  ctx.fl = fl;
  ctx.seg = seg;
  ctx.pl = pl;
  ctx.radius = r;
  ctx.g = seg->grounded ? 0.0 : fl->g;
  /* from the segment's start, not from tau_from: the stepper asks at a
   * segment's start, ball_predict anywhere on it, and the same search gives
   * both the same contact to the bit; a contact before tau_from (a segment
   * given with one unresolved) falls back to a search from there */
  if (!advance(path_state, &ctx, w_seg, w1, acc, &t_hit, q, n)) return 0;
  if (t_hit < tau_from && !advance(path_state, &ctx, w0, w1, acc, &t_hit, q, n)) return 0;
  *tau = t_hit;
  return 1;
}

int ball__plane_contact(const ball_model *m, const ball__flight *fl, const ball_segment *seg,
                        const ball_plane *pl, double tau_from, double tau_to, double *tau, ball_vec3 *q,
                        ball_vec3 *n) {
  int a = pl->axis, face = 0;
  double v = ball_v3_axis(seg->v0, a), target, tau_face = INFINITY, tau_rim;
  ball_vec3 q_face = ball_v3(0.0, 0.0, 0.0), q_rim, n_rim;
  ball_state s;
  /* the face in closed form: the plane moved by the radius toward the ball */
  if (v != 0.0) {
    target = pl->position - (v > 0.0 ? m->radius : -m->radius);
    if (ball__plane_tau(fl->b, ball_v3_axis(seg->p0, a), v, target, tau_from, &tau_face)) {
      ball__eval_f(fl, seg, seg->t0 + tau_face, &s);
      q_face = s.position;
      /* one ulp back on the approach side: a point ball restarting exactly
       * in the plane would find the same plane again at once */
      if (a == 0)
        q_face.x = nextafter(target, v > 0.0 ? -INFINITY : INFINITY);
      else
        q_face.z = nextafter(target, v > 0.0 ? -INFINITY : INFINITY);
      face = ball__in_extent(pl, q_face);
      if (!face) tau_face = INFINITY;
    }
  }
  /* the edges and corners, before the face (a point ball has none) */
  if (m->radius > 0.0 &&
      rim_exact(m, fl, seg, pl, tau_from, fmin(tau_to, face ? tau_face : INFINITY), &tau_rim, &q_rim, &n_rim) &&
      !(face && tau_rim >= tau_face)) {
    *tau = tau_rim;
    *q = q_rim;
    *n = n_rim;
    /* near the face's inside it is the face's contact (the closed form has
     * it, unless the ball starts overlapping the face moving inward: then
     * it bounces off at once, about the plane's normal) */
    if (!face_interior(pl, ball__rect_nearest(pl, q_rim))) return 1;
    if (!face) {
      *n = ball_v3(0.0, 0.0, 0.0);
      return 1;
    }
  }
  if (!face) return 0;
  *tau = tau_face;
  *q = q_face;
  *n = ball_v3(0.0, 0.0, 0.0); /* the face: eq 6 as the paper writes it */
  return 1;
}

/* ---- the sampled scheme: on the frame's chord ---- */

static void chord_state(const rim_ctx *x, double f, ball_vec3 *c, ball_vec3 *v) {
  *c = ball_v3_lerp(x->p0, x->p1, f);
  *v = ball_v3_sub(x->p1, x->p0);
}

int ball__plane_chord(const ball_model *m, const ball_plane *pl, ball_vec3 p_old, ball_vec3 p, double *s,
                      ball_vec3 *q, ball_vec3 *n) {
  int a = pl->axis, face = 0;
  double xo = ball_v3_axis(p_old, a), x = ball_v3_axis(p, a), target, s_face = INFINITY;
  ball_vec3 q_face = ball_v3(0.0, 0.0, 0.0);
  /* Fig. 3: the segment p_old -> p against the plane moved by the radius
   * toward p_old; no crossing when it is parallel to the plane */
  if (xo != x) {
    target = pl->position - (x > xo ? m->radius : -m->radius);
    s_face = (target - xo) / (x - xo);
    if (s_face >= 0.0 && s_face <= 1.0) {
      q_face = ball_v3_lerp(p_old, p, s_face);
      if (a == 0)
        q_face.x = target;
      else
        q_face.z = target;
      face = ball__in_extent(pl, q_face);
    }
    if (!face) s_face = INFINITY;
  }
  if (m->radius > 0.0) {
    /* the edges and corners on the chord: a line, so the search's bound has
     * A = 0 and it is Newton's method from the left on a convex distance */
    rim_ctx ctx;
    double f;
    ball_vec3 c, nn;
    memset(&ctx, 0, sizeof ctx);
    ctx.p0 = p_old;
    ctx.p1 = p;
    ctx.pl = pl;
    ctx.radius = m->radius;
    if (advance(chord_state, &ctx, 0.0, face ? s_face : 1.0, 0.0, &f, &c, &nn) && !(face && f >= s_face)) {
      ball_vec3 near = ball__rect_nearest(pl, c);
      if (!face_interior(pl, near) || !face) {
        *s = f;
        *q = c;
        *n = face_interior(pl, near) ? ball_v3(0.0, 0.0, 0.0) : nn;
        return 1;
      }
    }
  }
  if (!face) return 0;
  *s = s_face;
  *q = q_face;
  *n = ball_v3(0.0, 0.0, 0.0);
  return 1;
}
