/* Swept racket test (beyond the paper): the ball, a sphere, against the racket
 * disc moving and turning over one frame; the first time of contact.
 *
 * The contact test is the exact distance from the ball centre to the disc
 * (face and rim: the disc grown by the ball radius is a rounded slab), so a
 * ball that hits the rim edge is found like one that hits the face; a thin
 * or point ball through the face is a crossing of the disc's plane inside
 * it. The search is contact.c's, on a rate bound of the ball's speed plus
 * the speed of the disc's fastest point (rate_bound); before it, the early
 * reject by bounding spheres (ball__swept_cannot_touch) skips nearly every
 * frame of a rally. */
#include "internal.h"


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

/* The distance from the ball (the motion's sphere) to the disc at time t:
 * the face or the rim, whichever is nearer. */
static ball__probe disc_probe(const void *ctx, double t) {
  const ball__swept_motion *mo = (const ball__swept_motion *)ctx;
  ball_vec3 p, c, n, w;
  ball__probe pr;
  double rho, d;
  pose_at(mo, t, &p, &c, &n);
  w = ball_v3_sub(p, c);
  d = ball_v3_dot(w, n);
  rho = ball_v3_norm(ball_v3_sub(w, ball_v3_scale(n, d)));
  pr.t = t;
  pr.side = d;
  pr.inside = rho <= mo->disc_radius;
  if (pr.inside)
    pr.dist = fabs(d) - mo->ball_radius;
  else
    pr.dist = sqrt(d * d + (rho - mo->disc_radius) * (rho - mo->disc_radius)) - mo->ball_radius;
  return pr;
}

/* L: the fastest the ball centre's distance to the disc can change, m/s:
 * the ball's speed (at most its speed at ta plus g for every second, drag
 * only slowing it) plus the disc centre's speed plus the rim's speed from
 * the turn (a normalised lerp through an angle a turns at most 2 tan(a/2)
 * per unit of its parameter). */
static double rate_bound(const ball__swept_motion *mo, const ball_state *at_a) {
  double span = mo->tc1 - mo->tc0, h = mo->tb - mo->ta, c_rate = 0.0, turn = 0.0, v;
  double cosang = ball_v3_dot(mo->n0, mo->n1);
  if (mo->flight)
    v = ball_v3_norm(at_a->velocity) + (mo->seg->grounded ? 0.0 : mo->flight->g * h);
  else
    v = h > 0.0 ? ball_v3_norm(ball_v3_sub(mo->p1, mo->p0)) / h : 0.0;
  if (span > 0.0) {
    /* tan(a/2) = sin a / (1 + cos a) = |n0 x n1| / (1 + n0.n1), n0.n1 >= 0 */
    turn = 2.0 * ball_v3_norm(ball_v3_cross(mo->n0, mo->n1)) / (1.0 + cosang) / span;
    c_rate = ball_v3_norm(ball_v3_sub(mo->c1, mo->c0)) / span;
  }
  return (v + c_rate + turn * mo->disc_radius) * (1.0 + 1e-9) + 1e-300;
}

/* Early reject, before any probe: a contact needs the ball centre within
 * ball_radius + disc_radius of the disc centre (the disc lies inside that
 * sphere whatever its normal). Relative to the disc centre, which moves
 * linearly, the ball follows the chord between its ends within `sag`: for
 * the analytic path the chord's largest deviation is (tb - ta)^2 / 8 times
 * the largest acceleration, g vertically and |v_h| / b horizontally (eq 3's
 * second derivatives, largest at the segment's start since drag only slows
 * the ball). So if the chord of the relative motion stays farther than the
 * radii plus sag from the origin, no contact can happen and the search is
 * skipped. The ball's ends are mo->p0, mo->p1 (the caller knows them). */
int ball__swept_cannot_touch(const ball__swept_motion *mo) {
  ball_vec3 ra, d;
  double sag = 0.0, reach, u, dd, h = mo->tb - mo->ta;
  double span = mo->tc1 - mo->tc0;
  double ua = span > 0.0 ? (mo->ta - mo->tc0) / span : 1.0, ub = span > 0.0 ? (mo->tb - mo->tc0) / span : 1.0;
  if (mo->flight) {
    double vh = sqrt(mo->seg->v0.x * mo->seg->v0.x + mo->seg->v0.z * mo->seg->v0.z);
    sag = 0.125 * h * h * ((mo->seg->grounded ? 0.0 : mo->flight->g) + vh * mo->flight->k);
  }
  ra = ball_v3_sub(mo->p0, ball_v3_lerp(mo->c0, mo->c1, ua));
  d = ball_v3_sub(ball_v3_sub(mo->p1, ball_v3_lerp(mo->c0, mo->c1, ub)), ra);
  dd = ball_v3_dot(d, d);
  u = dd > 0.0 ? -ball_v3_dot(ra, d) / dd : 0.0;
  u = u < 0.0 ? 0.0 : u > 1.0 ? 1.0 : u;
  reach = (mo->ball_radius + mo->disc_radius + sag) * (1.0 + 1e-9) + 1e-12;
  return ball_v3_norm(ball_v3_add(ra, ball_v3_scale(d, u))) > reach;
}

int ball__swept_toi(const ball__swept_motion *mo_in, double *t_hit, ball_vec3 *center,
                    ball_vec3 *face_normal) {
  ball__swept_motion mo = *mo_in;
  double l0 = ball_v3_norm(mo.n0), l1 = ball_v3_norm(mo.n1);
  ball_vec3 p, c, n;
  ball_state at_a;
  ball__probe hit;
  ball__contact_query q;
  if (!(l0 > 0.0) || !(l1 > 0.0) || !(mo.tb >= mo.ta)) return 0;
  mo.n0 = ball_v3_scale(mo.n0, 1.0 / l0);
  mo.n1 = ball_v3_scale(mo.n1, 1.0 / l1);
  if (ball_v3_dot(mo.n0, mo.n1) < 0.0) mo.n1 = ball_v3_scale(mo.n1, -1.0); /* a disc has two faces */
  if (mo.flight) ball__eval_f(mo.flight, mo.seg, mo.ta, &at_a);
  q.probe = disc_probe;
  q.ctx = &mo;
  q.ta = mo.ta;
  q.tb = mo.tb;
  q.rate = rate_bound(&mo, &at_a);
  /* out of evaluations (2) is no hit: a racket that skims the ball that
   * long is not a stroke */
  if (ball__first_contact(&q, &hit, mo.probes_used) != 1) return 0;
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
  if (!(ball_v3_length(q->n0) >= 1e-9) || !(ball_v3_length(q->n1) >= 1e-9)) return BALL_ERANGE;
  mo.flight = NULL;
  mo.seg = NULL;
  mo.probes_used = NULL;
  mo.ta = 0.0;
  mo.tb = 1.0;
  mo.p0 = q->p0;
  mo.p1 = q->p1;
  mo.ball_radius = q->ball_radius;
  mo.tc0 = 0.0;
  mo.tc1 = 1.0;
  mo.c0 = q->c0;
  mo.c1 = q->c1;
  mo.n0 = ball_v3_unit(q->n0);
  mo.n1 = ball_v3_unit(q->n1);
  mo.disc_radius = q->disc_radius;
  *hit = !ball__swept_cannot_touch(&mo) && ball__swept_toi(&mo, &t, &c, NULL);
  if (*hit) {
    if (toi) *toi = t;
    if (point) *point = c;
  }
  return BALL_OK;
}
