/* Flight between collisions (eq 1-4) and prediction on a segment. */
#include "internal.h"

double ball__drag_distance(double b, double t) {
  double d, f;
  ball__drag_terms(b, isinf(b) ? 0.0 : 1.0 / b, t, &d, &f);
  return d;
}

/* eq 4: spinAirDamping = sDamp / (sDamp + t). */
double ball__spin_air_damping(const ball_model *m, double t) {
  return m->spin_damping / (m->spin_damping + t);
}

void ball__eval(const ball_model *m, const ball_segment *seg, double t, ball_state *out) {
  ball__flight fl;
  ball__flight_of(m, &fl);
  ball__eval_f(&fl, seg, t, out);
}

void ball__segment_start(ball_segment *seg, double t, ball_vec3 p0, ball_vec3 v0, ball_vec3 s0,
                         int grounded) {
  seg->t0 = t;
  seg->p0 = p0;
  seg->v0 = v0;
  seg->s0 = s0;
  seg->grounded = grounded;
}

/* The two roots r1 <= r2 of y(tau) = y, i.e. (g/2) tau^2 - v tau + (y - y0) = 0,
 * without cancellation; 0 if none. */
int ball__height_roots(double g, double y0, double v, double y, double *r1, double *r2) {
  double c = y - y0;
  double disc = v * v - 2.0 * g * c;
  double sq, q;
  if (!(disc >= 0.0)) return 0;
  sq = sqrt(disc);
  q = v >= 0.0 ? v + sq : v - sq; /* same sign as v: no cancellation */
  if (q == 0.0) {                  /* v = 0 and y = y0 */
    *r1 = *r2 = 0.0;
    return 1;
  }
  {
    double a = q / g, bb = 2.0 * c / q; /* product of the roots is 2c/g */
    *r1 = a < bb ? a : bb;
    *r2 = a < bb ? bb : a;
  }
  return 1;
}

/* tau >= tau_from with x(tau) = target along one horizontal axis; 0 if never. */
int ball__plane_tau(double b, double x0, double v, double target, double tau_from, double *tau) {
  double d = target - x0, u, t;
  if (v == 0.0) {
    if (d != 0.0) return 0;
    *tau = tau_from;
    return 1;
  }
  /* moving away from the plane never reaches it: decided on the signs, not on
   * d / v, which underflows to -0 for a ball one subnormal past a plane at
   * x = 0 and would pass "u >= 0" (docs/hard-cases.md, walls at 0) */
  if (d != 0.0 && (d > 0.0) != (v > 0.0)) return 0;
  u = d / v; /* the needed b (1 - e^(-tau/b)) */
  if (!isfinite(u)) return 0;
  if (isinf(b)) {
    t = u;
  } else {
    if (u >= b) return 0; /* drag stops the ball short of the plane */
    t = -b * ball__log1p(-u / b);
  }
  if (!(t >= tau_from)) {
    /* already past the plane, unless only rounding puts the crossing before tau_from */
    if (!(tau_from - t <= 1e-12 * (1.0 + tau_from))) return 0;
    t = tau_from;
  }
  *tau = t;
  return 1;
}

/* t and every number of seg finite: x - x is 0 for a finite x and NaN for
 * an infinite or NaN one, so one comparison of the sum decides. */
static int finite_each(const ball_segment *s, double t) {
  double z = ((t - t) + (s->t0 - s->t0)) +
             ((s->p0.x - s->p0.x) + (s->p0.y - s->p0.y) + (s->p0.z - s->p0.z)) +
             ((s->v0.x - s->v0.x) + (s->v0.y - s->v0.y) + (s->v0.z - s->v0.z)) +
             ((s->s0.x - s->s0.x) + (s->s0.y - s->s0.y) + (s->s0.z - s->s0.z));
  return z == 0.0;
}

/* The same, at half the operations on the evaluation's hot path: an
 * infinity or a NaN among the numbers makes their sum one, which no later
 * term turns finite again; a finite sum says they all are. Only a sum that
 * overflows (numbers near DBL_MAX) asks finite_each. */
static inline int finite_at(const ball_segment *s, double t) {
  double z = ((t + s->t0) + (s->p0.x + s->p0.y + s->p0.z)) + ((s->v0.x + s->v0.y + s->v0.z) + (s->s0.x + s->s0.y + s->s0.z));
  return z - z == 0.0 || finite_each(s, t);
}

static inline ball_status check_args(const ball_model *m, const ball_segment *seg, double t) {
  if (!m || !seg) return BALL_EINVAL;
  if (!finite_at(seg, t)) return BALL_ENONFINITE;
  if (t < seg->t0) return BALL_ERANGE;
  return BALL_OK;
}

ball_status ball_segment_eval(const ball_model *m, const ball_segment *seg, double t,
                              ball_state *out) {
  double b, k, d, f;
  if (!m || !seg) return BALL_EINVAL;
  /* eq 3's transcendental first, on numbers not yet checked (a NaN costs
   * nothing): the segment and the rest of the model are read after the
   * call, so that only t and b are held across it */
  ball__drag_of(m, &b, &k);
  ball__drag_terms(b, k, t - seg->t0, &d, &f);
  if (!finite_at(seg, t)) return BALL_ENONFINITE;
  if (t < seg->t0) return BALL_ERANGE;
  if (!out) return BALL_EINVAL;
  ball__state_at(m->gravity, ball__sdamp_of(m), seg, t - seg->t0, d, f, out);
  return BALL_OK;
}

ball_status ball_flight_init(const ball_model *m, const ball_segment *seg, ball_flight *out) {
  ball__flight fl;
  ball_status st = check_args(m, seg, seg ? seg->t0 : 0.0);
  if (st != BALL_OK) return st;
  if (!out) return BALL_EINVAL;
  ball__flight_of(m, &fl);
  out->seg = *seg;
  out->b = fl.b;
  out->inv_b = fl.k;
  out->gravity = fl.g;
  out->spin_damping = fl.sdamp;
  return BALL_OK;
}

ball_status ball_flight_eval(const ball_flight *fl, double t, ball_state *out) {
  if (!fl || !out) return BALL_EINVAL;
  if (!(t - t == 0.0)) return BALL_ENONFINITE;
  if (t < fl->seg.t0) return BALL_ERANGE;
  ball__eval_c(fl->b, fl->inv_b, fl->gravity, fl->spin_damping, &fl->seg, t, out);
  return BALL_OK;
}

ball_status ball_time_to_height(const ball_model *m, const ball_segment *seg, double t_from,
                                double y, double *t) {
  double r1, r2, tau_from;
  ball_status st = check_args(m, seg, t_from);
  if (st != BALL_OK) return st;
  if (!t) return BALL_EINVAL;
  if (!isfinite(y)) return BALL_ENONFINITE;
  tau_from = t_from - seg->t0;
  if (seg->grounded) {
    if (y != seg->p0.y) return BALL_ENOTFOUND;
    *t = t_from;
    return BALL_OK;
  }
  if (!ball__height_roots(m->gravity, seg->p0.y, seg->v0.y, y, &r1, &r2)) return BALL_ENOTFOUND;
  if (r1 >= tau_from) {
    *t = seg->t0 + r1;
  } else if (r2 >= tau_from) {
    *t = seg->t0 + r2;
  } else {
    return BALL_ENOTFOUND;
  }
  return BALL_OK;
}

ball_status ball_time_to_plane(const ball_model *m, const ball_segment *seg, double t_from,
                               int axis, double coord, double *t) {
  double tau;
  ball_status st = check_args(m, seg, t_from);
  if (st != BALL_OK) return st;
  if (!t || (axis != 0 && axis != 2)) return BALL_EINVAL;
  if (!isfinite(coord)) return BALL_ENONFINITE;
  if (!ball__plane_tau(ball__drag_b(m), ball_v3_axis(seg->p0, axis), ball_v3_axis(seg->v0, axis), coord,
                       t_from - seg->t0, &tau))
    return BALL_ENOTFOUND;
  *t = seg->t0 + tau;
  return BALL_OK;
}

ball_status ball_next_floor_contact(const ball_model *m, const ball_segment *seg, double t_from,
                                    double *t, ball_vec3 *point) {
  double r1, r2;
  ball_state s;
  ball_status st = check_args(m, seg, t_from);
  if (st != BALL_OK) return st;
  if (!t) return BALL_EINVAL;
  if (seg->grounded) return BALL_ENOTFOUND;
  /* the descending root: where the ball comes down through the floor */
  if (!ball__height_roots(m->gravity, seg->p0.y, seg->v0.y, ball__floor_y(m), &r1, &r2))
    return BALL_ENOTFOUND;
  if (r2 < t_from - seg->t0) return BALL_ENOTFOUND;
  *t = seg->t0 + r2;
  if (point) {
    ball__eval(m, seg, *t, &s);
    *point = s.position;
    point->y = ball__floor_y(m);
  }
  return BALL_OK;
}

ball_status ball_apex(const ball_model *m, const ball_segment *seg, double *t, ball_vec3 *point) {
  ball_state s;
  ball_status st = check_args(m, seg, seg ? seg->t0 : 0.0);
  if (st != BALL_OK) return st;
  if (!t) return BALL_EINVAL;
  *t = seg->t0;
  if (!seg->grounded && seg->v0.y > 0.0) *t = seg->t0 + seg->v0.y / m->gravity; /* eq 3: vy = 0 */
  if (point) {
    ball__eval(m, seg, *t, &s);
    *point = s.position;
  }
  return BALL_OK;
}
