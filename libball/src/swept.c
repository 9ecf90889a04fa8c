/* Swept racket test (beyond the paper): the ball, a sphere, against the racket
 * disc moving and turning over one frame; the first time of contact.
 *
 * The contact test is the exact distance from the ball centre to the disc
 * (face and rim: the disc grown by the ball radius is a rounded slab), so a
 * ball that hits the rim edge is found like one that hits the face. The
 * search walks the frame in sub-steps fine enough for the relative motion
 * (a quarter of the smaller of the two radii per sub-step, at most
 * SWEPT_MAX_STEPS). In each sub-step a contact is caught three ways:
 *   - the distance is <= 0 at the end of the sub-step;
 *   - the signed distance of the centre to the disc plane changes sign and the
 *     crossing point lies within the disc (a thin or point ball tunnelling);
 *   - a graze: when the sub-step comes close, the minimum of the distance
 *     inside it (golden-section search) is <= 0.
 * The contact time is then refined by bisection to below 1e-13 of the frame. */
#include "internal.h"

#define SWEPT_MIN_STEPS 16
#define SWEPT_MAX_STEPS 8192
#define SWEPT_MIN_GRAIN 1e-4 /* m: sub-step length floor for tiny radii */
#define SWEPT_BISECT 80      /* halvings: 2^-80 of a sub-step */
#define SWEPT_GOLDEN 60      /* golden-section iterations for a graze */

/* The frame's motion at time t. */
static void pose_at(const ball__swept_motion *mo, double t, ball_vec3 *ball, ball_vec3 *c,
                    ball_vec3 *n) {
  double span = mo->tc1 - mo->tc0;
  double u = span > 0.0 ? (t - mo->tc0) / span : 1.0;
  ball_vec3 nn;
  double len;
  if (mo->flight) {
    ball_state s;
    ball__eval_f(mo->flight, mo->seg, t, &s);
    *ball = s.position;
  } else {
    double w = mo->tb > mo->ta ? (t - mo->ta) / (mo->tb - mo->ta) : 1.0;
    *ball = ball_v3_lerp(mo->p0, mo->p1, w);
  }
  *c = ball_v3_lerp(mo->c0, mo->c1, u);
  nn = ball_v3_lerp(mo->n0, mo->n1, u); /* normalised lerp; n1 is in n0's hemisphere */
  len = ball_v3_norm(nn);
  *n = ball_v3_scale(nn, 1.0 / len);
}

typedef struct probe {
  double t;
  double dist;   /* ball surface to disc, m (< 0: overlapping) */
  double side;   /* signed distance of the centre to the disc plane, m */
  double radial; /* distance of the centre from the disc axis, m */
} probe;

static probe probe_at(const ball__swept_motion *mo, double t) {
  ball_vec3 p, c, n, w;
  probe pr;
  double rho, d;
  pose_at(mo, t, &p, &c, &n);
  w = ball_v3_sub(p, c);
  d = ball_v3_dot(w, n);
  rho = ball_v3_norm(ball_v3_sub(w, ball_v3_scale(n, d)));
  pr.t = t;
  pr.side = d;
  pr.radial = rho;
  if (rho <= mo->disc_radius)
    pr.dist = fabs(d) - mo->ball_radius;
  else
    pr.dist = hypot(d, rho - mo->disc_radius) - mo->ball_radius;
  return pr;
}

/* First contact in [a, b] where a is clear (dist > 0) and b touches:
 * bisection on "touching". */
static probe refine(const ball__swept_motion *mo, probe a, probe b) {
  int i;
  for (i = 0; i < SWEPT_BISECT && b.t - a.t > 0.0; i++) {
    double tm = 0.5 * (a.t + b.t);
    probe m;
    if (tm <= a.t || tm >= b.t) break;
    m = probe_at(mo, tm);
    if (m.dist <= 0.0)
      b = m;
    else
      a = m;
  }
  b.side = a.side; /* the side the ball came from, for the face normal */
  return b;
}

/* The plane crossing between a and b (sides of opposite signs), by bisection. */
static probe crossing(const ball__swept_motion *mo, probe a, probe b) {
  int i;
  for (i = 0; i < SWEPT_BISECT; i++) {
    double tm = 0.5 * (a.t + b.t);
    probe m;
    if (tm <= a.t || tm >= b.t) break;
    m = probe_at(mo, tm);
    if ((m.side > 0.0) == (a.side > 0.0))
      a = m;
    else
      b = m;
  }
  return b;
}

/* Minimum of dist over [a, b] (golden section; the distance is unimodal over
 * a sub-step short against both radii). */
static probe graze(const ball__swept_motion *mo, probe a, probe b) {
  const double g = 0.6180339887498949;
  double lo = a.t, hi = b.t;
  probe x1 = probe_at(mo, hi - g * (hi - lo)), x2 = probe_at(mo, lo + g * (hi - lo));
  probe best = a.dist < b.dist ? a : b;
  int i;
  for (i = 0; i < SWEPT_GOLDEN; i++) {
    if (x1.dist <= 0.0 || x2.dist <= 0.0) break;
    if (x1.dist < x2.dist) {
      hi = x2.t;
      x2 = x1;
      x1 = probe_at(mo, hi - g * (hi - lo));
    } else {
      lo = x1.t;
      x1 = x2;
      x2 = probe_at(mo, lo + g * (hi - lo));
    }
  }
  if (x1.dist < best.dist) best = x1;
  if (x2.dist < best.dist) best = x2;
  return best;
}

/* An upper bound of how far the ball moves relative to the disc over the
 * interval, from a few chords of each motion. */
static double motion_bound(const ball__swept_motion *mo, double ang) {
  ball_vec3 p, c, n, p_prev, c_prev, n_prev;
  double len = 0.0;
  int i;
  const int k = 8;
  pose_at(mo, mo->ta, &p_prev, &c_prev, &n_prev);
  for (i = 1; i <= k; i++) {
    pose_at(mo, mo->ta + (mo->tb - mo->ta) * i / k, &p, &c, &n);
    len += ball_v3_norm(ball_v3_sub(p, p_prev)) + ball_v3_norm(ball_v3_sub(c, c_prev));
    p_prev = p;
    c_prev = c;
  }
  /* chords undercut curves: a margin, plus the rim sweeping by the turn */
  return 1.5 * len + ang * (mo->disc_radius + mo->ball_radius) + 1e-12;
}

/* Early reject, before any probe: a contact needs the ball centre within
 * ball_radius + disc_radius of the disc centre (the disc lies inside that
 * sphere whatever its normal). Relative to the disc centre, which moves
 * linearly, the ball follows the chord between its ends within `sag`: for
 * the analytic path the chord's largest deviation is (tb - ta)^2 / 8 times
 * the largest acceleration, g vertically and |v_h| / b horizontally (eq 3's
 * second derivatives, largest at ta since drag only slows the ball). So if
 * the chord of the relative motion stays farther than the radii plus sag
 * from the origin, no contact can happen: the exact search is skipped, and
 * where a contact is possible it runs exactly as before. */
int ball__swept_cannot_touch(const ball__swept_motion *mo) {
  ball_vec3 pa, pb, ra, d;
  double sag = 0.0, reach, u, dd, h = mo->tb - mo->ta;
  double span = mo->tc1 - mo->tc0;
  double ua = span > 0.0 ? (mo->ta - mo->tc0) / span : 1.0, ub = span > 0.0 ? (mo->tb - mo->tc0) / span : 1.0;
  if (mo->flight) {
    ball_state sa, sb;
    /* |v_h| at the segment's start bounds it everywhere on the segment */
    double vh = sqrt(mo->seg->v0.x * mo->seg->v0.x + mo->seg->v0.z * mo->seg->v0.z);
    ball__eval_f(mo->flight, mo->seg, mo->ta, &sa);
    ball__eval_f(mo->flight, mo->seg, mo->tb, &sb);
    pa = sa.position;
    pb = sb.position;
    sag = 0.125 * h * h * ((mo->seg->grounded ? 0.0 : mo->flight->g) + vh * mo->flight->k);
  } else {
    pa = mo->p0;
    pb = mo->p1;
  }
  ra = ball_v3_sub(pa, ball_v3_lerp(mo->c0, mo->c1, ua));
  d = ball_v3_sub(ball_v3_sub(pb, ball_v3_lerp(mo->c0, mo->c1, ub)), ra);
  dd = ball_v3_dot(d, d);
  u = dd > 0.0 ? -ball_v3_dot(ra, d) / dd : 0.0;
  u = u < 0.0 ? 0.0 : u > 1.0 ? 1.0 : u;
  reach = (mo->ball_radius + mo->disc_radius + sag) * (1.0 + 1e-9) + 1e-12;
  return ball_v3_norm(ball_v3_add(ra, ball_v3_scale(d, u))) > reach;
}

int ball__swept_toi(const ball__swept_motion *mo_in, double *t_hit, ball_vec3 *center,
                    ball_vec3 *face_normal) {
  ball__swept_motion mo = *mo_in;
  double l0 = ball_v3_norm(mo.n0), l1 = ball_v3_norm(mo.n1), grain, bound, ang, step;
  ball_vec3 p, c, n;
  probe a, b, hit;
  int steps, i, found = 0;
  if (!(l0 > 0.0) || !(l1 > 0.0) || !(mo.tb >= mo.ta)) return 0;
  if (ball__swept_cannot_touch(&mo)) return 0;
  mo.n0 = ball_v3_scale(mo.n0, 1.0 / l0);
  mo.n1 = ball_v3_scale(mo.n1, 1.0 / l1);
  if (ball_v3_dot(mo.n0, mo.n1) < 0.0) mo.n1 = ball_v3_scale(mo.n1, -1.0); /* a disc has two faces */
  ang = acos(fmin(1.0, fmax(-1.0, ball_v3_dot(mo.n0, mo.n1))));
  grain = 0.25 * fmin(mo.ball_radius > 0.0 ? mo.ball_radius : mo.disc_radius, mo.disc_radius);
  if (grain < SWEPT_MIN_GRAIN) grain = SWEPT_MIN_GRAIN;
  bound = motion_bound(&mo, ang);
  steps = (int)fmin((double)SWEPT_MAX_STEPS, ceil(bound / grain));
  if (steps < SWEPT_MIN_STEPS) steps = SWEPT_MIN_STEPS;
  step = bound / steps; /* relative motion per sub-step, m */

  a = probe_at(&mo, mo.ta);
  hit = a;
  if (a.dist <= 0.0) {
    found = 1; /* touching at the start: contact at once (FCL's convention) */
  }
  for (i = 1; i <= steps && !found; i++) {
    double tb = i == steps ? mo.tb : mo.ta + (mo.tb - mo.ta) * i / steps;
    b = probe_at(&mo, tb);
    if (b.dist <= 0.0) {
      hit = refine(&mo, a, b);
      found = 1;
    } else if ((a.side > 0.0) != (b.side > 0.0) && a.side != 0.0) {
      probe x = crossing(&mo, a, b);
      if (x.radial <= mo.disc_radius) {
        /* the centre passes through the disc: contact at or before x */
        x.dist = fmin(x.dist, 0.0);
        hit = refine(&mo, a, x);
        found = 1;
      }
    }
    if (!found && fmin(a.dist, b.dist) < step) {
      probe g = graze(&mo, a, b);
      if (g.dist <= 0.0) {
        hit = refine(&mo, a, g);
        found = 1;
      }
    }
    a = b;
  }
  if (!found) return 0;
  pose_at(&mo, hit.t, &p, &c, &n);
  *t_hit = hit.t;
  *center = p;
  if (face_normal) {
    /* the face the ball arrived on (Fig. 9); the start position if undecided */
    double side = hit.side != 0.0 ? hit.side : ball_v3_dot(ball_v3_sub(p, c), n);
    if (side == 0.0) {
      ball_vec3 p0, c0, n0;
      pose_at(&mo, mo.ta, &p0, &c0, &n0);
      side = ball_v3_dot(ball_v3_sub(p0, c0), n0);
    }
    *face_normal = side < 0.0 ? ball_v3_scale(n, -1.0) : n;
  }
  return 1;
}

ball_status ball_swept_disc(const ball_swept_query *q, int *hit, double *toi, ball_vec3 *point) {
  ball__swept_motion mo;
  double t;
  ball_vec3 c;
  if (!q || !hit) return BALL_EINVAL;
  if (!ball_v3_finite(q->p0) || !ball_v3_finite(q->p1) || !ball_v3_finite(q->c0) || !ball_v3_finite(q->c1) ||
      !ball_v3_finite(q->n0) || !ball_v3_finite(q->n1) || !isfinite(q->ball_radius) ||
      !isfinite(q->disc_radius))
    return BALL_ENONFINITE;
  if (q->ball_radius < 0.0 || q->disc_radius < 0.0) return BALL_ERANGE;
  if (!(ball_v3_norm(q->n0) >= 1e-9) || !(ball_v3_norm(q->n1) >= 1e-9)) return BALL_ERANGE;
  mo.flight = NULL;
  mo.seg = NULL;
  mo.ta = 0.0;
  mo.tb = 1.0;
  mo.p0 = q->p0;
  mo.p1 = q->p1;
  mo.ball_radius = q->ball_radius;
  mo.tc0 = 0.0;
  mo.tc1 = 1.0;
  mo.c0 = q->c0;
  mo.c1 = q->c1;
  mo.n0 = q->n0;
  mo.n1 = q->n1;
  mo.disc_radius = q->disc_radius;
  *hit = ball__swept_toi(&mo, &t, &c, NULL);
  if (*hit) {
    if (toi) *toi = t;
    if (point) *point = c;
  }
  return BALL_OK;
}
