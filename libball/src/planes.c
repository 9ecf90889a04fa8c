/* The net and the walls (Fig. 3, eq 6) for a ball with a radius: the
 * rectangle grown by the radius, that is its face, four edge cylinders and
 * four corner spheres (docs/model.md, "Ball radius, edges and corners").
 *
 * The face is found in closed form, as before (the plane's crossing by
 * inverting eq 3, then the extent). The edges and corners are the points
 * of the grown rectangle that the face's test cannot see: a ball that first
 * touches the plane above the top edge or past a side edge and then moves
 * inward, or one that only skims an edge. They are found by contact.c's
 * search on the distance from the ball's centre to the rectangle, on the
 * analytic path (exact scheme) or on the frame's chord (sampled scheme),
 * over the time the ball is inside the rectangle's slab of thickness 2 r
 * (closed form), before the face's contact. The normal of an edge or corner
 * contact points from the rectangle's nearest point to the ball's centre. */
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

/* ---- the exact scheme: on the analytic path ---- */

typedef struct path_ctx {
  const ball__flight *fl;
  const ball_segment *seg;
  const ball_plane *pl;
  double radius;
} path_ctx;

static ball__probe path_probe(const void *ctx, double t) {
  const path_ctx *c = (const path_ctx *)ctx;
  ball_state s;
  ball__probe p;
  ball__eval_f(c->fl, c->seg, t, &s);
  p.t = t;
  p.dist = ball_v3_dist(s.position, ball__rect_nearest(c->pl, s.position)) - c->radius;
  p.side = 1.0; /* a thick obstacle: no crossing test */
  p.inside = 0;
  return p;
}

/* tau at which b (1 - e^(-tau/b)) (or tau without drag) reaches d >= 0; +Inf
 * when drag stops the ball short of it (eq 3 inverted). */
static double tau_of_distance(const ball__flight *fl, double d) {
  if (!(d > 0.0)) return 0.0;
  if (fl->k == 0.0) return d;
  if (d >= fl->b) return INFINITY;
  return -fl->b * log1p(-d / fl->b);
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
  double r = m->radius, w0 = tau_from, w1 = tau_to, t0, t1, vy0, vy1, rate;
  int a = pl->axis, h = a == 0 ? 2 : 0, found;
  path_ctx ctx;
  ball__contact_query cq;
  ball__probe hit, p0;
  ball_state s;
  /* the window: inside the slabs of the grown rectangle's bounding box */
  if (!slab(fl, ball_v3_axis(seg->p0, a), ball_v3_axis(seg->v0, a), pl->position - r, pl->position + r, &t0, &t1))
    return 0;
  w0 = fmax(w0, t0);
  w1 = fmin(w1, t1);
  if (!slab(fl, ball_v3_axis(seg->p0, h), ball_v3_axis(seg->v0, h), pl->lo - r, pl->hi + r, &t0, &t1)) return 0;
  w0 = fmax(w0, t0);
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
    else w1 = fmax(w0, fl->b * log(fmax(vh * fl->b / 1e-15, 1.0)));
  }
  if (!(w0 <= w1)) return 0;
  ctx.fl = fl;
  ctx.seg = seg;
  ctx.pl = pl;
  ctx.radius = r;
  p0 = path_probe(&ctx, seg->t0 + w0);
  if (p0.dist <= 0.0) {
    /* touching where the window starts: a contact as soon as it moves
     * inward (at once, or when gravity turns a ball that just bounced off
     * this edge back into it); clear of it, the search goes on from there */
    double dt = 1e-15 * (1.0 + fabs(seg->t0 + w0)), at = w0;
    for (;;) {
      ball_vec3 nq;
      ball__eval_f(fl, seg, seg->t0 + at, &s);
      nq = ball_v3_sub(s.position, ball__rect_nearest(pl, s.position));
      if (ball_v3_dot(nq, s.velocity) < 0.0) {
        *tau = at;
        *q = s.position;
        *n = ball_v3_unit(nq);
        return 1;
      }
      if (!(w0 + dt <= w1) || dt > 1e9) return 0;
      at = w0 + dt;
      p0 = path_probe(&ctx, seg->t0 + at);
      if (p0.dist > 0.0) break;
      dt *= 2.0;
    }
    w0 = at;
  }
  /* the rate: the ball's speed bounds how fast its distance changes; the
   * horizontal speed only decays, the vertical is linear in time */
  ball__eval_f(fl, seg, seg->t0 + w0, &s);
  vy0 = fabs(s.velocity.y);
  vy1 = seg->grounded ? 0.0 : fabs(seg->v0.y - fl->g * w1);
  rate = (sqrt(s.velocity.x * s.velocity.x + s.velocity.z * s.velocity.z) + fmax(vy0, vy1)) * (1.0 + 1e-9) + 1e-300;
  cq.probe = path_probe;
  cq.ctx = &ctx;
  cq.ta = seg->t0 + w0;
  cq.tb = seg->t0 + w1;
  cq.rate = rate;
  found = ball__first_contact(&cq, &hit, NULL);
  if (!found) return 0;
  ball__eval_f(fl, seg, hit.t, &s);
  *tau = hit.t - seg->t0;
  *q = s.position;
  *n = ball_v3_unit(ball_v3_sub(s.position, ball__rect_nearest(pl, s.position)));
  /* out of evaluations (2): the ball skims the rim for long. Where it was
   * last known clear it bounces if it moves toward the rim there, rather
   * than risk passing through; moving away, it is left to go */
  return found == 1 || ball_v3_dot(*n, s.velocity) < 0.0;
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

typedef struct chord_ctx {
  ball_vec3 p0, p1;
  const ball_plane *pl;
  double radius;
} chord_ctx;

static ball__probe chord_probe(const void *ctx, double s) {
  const chord_ctx *c = (const chord_ctx *)ctx;
  ball_vec3 p = ball_v3_lerp(c->p0, c->p1, s);
  ball__probe pr;
  pr.t = s;
  pr.dist = ball_v3_dist(p, ball__rect_nearest(c->pl, p)) - c->radius;
  pr.side = 1.0;
  pr.inside = 0;
  return pr;
}

int ball__plane_chord(const ball_model *m, const ball_plane *pl, ball_vec3 p_old, ball_vec3 p, double *s,
                      ball_vec3 *q, ball_vec3 *n) {
  int a = pl->axis, face = 0, found;
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
    chord_ctx ctx;
    ball__contact_query cq;
    ball__probe hit;
    double len = ball_v3_dist(p_old, p);
    ctx.p0 = p_old;
    ctx.p1 = p;
    ctx.pl = pl;
    ctx.radius = m->radius;
    cq.probe = chord_probe;
    cq.ctx = &ctx;
    cq.ta = 0.0;
    cq.tb = face ? s_face : 1.0;
    cq.rate = len * (1.0 + 1e-9) + 1e-300;
    /* a chord that starts touching and leaves (the ball just bounced off
     * this rectangle) is no contact */
    if (chord_probe(&ctx, 0.0).dist <= 0.0) {
      ball_vec3 nq = ball_v3_sub(p_old, ball__rect_nearest(pl, p_old));
      if (!(ball_v3_dot(nq, ball_v3_sub(p, p_old)) < 0.0)) cq.tb = -1.0;
    }
    found = cq.tb >= 0.0 ? ball__first_contact(&cq, &hit, NULL) : 0;
    if (found) {
      ball_vec3 c = ball_v3_lerp(p_old, p, hit.t), near = ball__rect_nearest(pl, c);
      /* out of evaluations (2): as rim_exact, a contact where the chord was
       * last known clear if it heads toward the rim there */
      if (found == 2 && !(ball_v3_dot(ball_v3_sub(c, near), ball_v3_sub(p, p_old)) < 0.0)) found = 0;
      if (found && !(face && hit.t >= s_face) && (!face_interior(pl, near) || !face)) {
        *s = hit.t;
        *q = c;
        *n = face_interior(pl, near) ? ball_v3(0.0, 0.0, 0.0) : ball_v3_unit(ball_v3_sub(c, near));
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
