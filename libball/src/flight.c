/* Flight between collisions (eq 1-4) and prediction on a segment. */
#include "internal.h"

double ball__drag_b(const ball_model *m) {
  if (!ball__has(m, BALL_EFFECT_DRAG) || m->air_friction == 0.0) return INFINITY;
  return m->mass / m->air_friction; /* eq 2: b = m / beta; may overflow to +Inf */
}

/* eq 3: b (1 - e^(-t/b)) as -b expm1(-t/b): no cancellation for b >> t. */
double ball__drag_distance(double b, double t) {
  if (t == 0.0) return 0.0;
  if (isinf(b)) return t;
  return -b * expm1(-t / b);
}

/* eq 3: e^(-t/b). */
double ball__drag_decay(double b, double t) {
  if (t == 0.0 || isinf(b)) return 1.0;
  return exp(-t / b);
}

/* eq 4: spinAirDamping = sDamp / (sDamp + t). */
double ball__spin_air_damping(const ball_model *m, double t) {
  return m->spin_damping / (m->spin_damping + t);
}

void ball__eval(const ball_model *m, const ball_segment *seg, double t, ball_state *out) {
  double tau = t - seg->t0;
  double b = ball__drag_b(m);
  double d = ball__drag_distance(b, tau);
  double f = ball__drag_decay(b, tau);
  /* eq 3: horizontal with drag, vertical under gravity alone */
  out->position.x = seg->p0.x + seg->v0.x * d;
  out->position.z = seg->p0.z + seg->v0.z * d;
  out->velocity.x = seg->v0.x * f;
  out->velocity.z = seg->v0.z * f;
  if (seg->grounded) {
    out->position.y = seg->p0.y;
    out->velocity.y = 0.0;
  } else {
    out->position.y = seg->p0.y + seg->v0.y * tau - 0.5 * m->gravity * tau * tau;
    out->velocity.y = seg->v0.y - m->gravity * tau;
  }
  if (ball__has(m, BALL_EFFECT_SPIN))
    out->spin = v3_scale(seg->s0, ball__spin_air_damping(m, tau));
  else
    out->spin = v3(0.0, 0.0, 0.0);
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
  double u, t;
  if (v == 0.0) {
    if (x0 != target) return 0;
    *tau = tau_from;
    return 1;
  }
  u = (target - x0) / v; /* the needed b (1 - e^(-tau/b)) */
  if (!(u >= 0.0) || !isfinite(u)) return 0;
  if (isinf(b)) {
    t = u;
  } else {
    if (u >= b) return 0; /* drag stops the ball short of the plane */
    t = -b * log1p(-u / b);
  }
  if (!(t >= tau_from)) {
    /* already past the plane, unless only rounding puts the crossing before tau_from */
    if (!(tau_from - t <= 1e-12 * (1.0 + tau_from))) return 0;
    t = tau_from;
  }
  *tau = t;
  return 1;
}

static ball_status check_args(const ball_model *m, const ball_segment *seg, double t) {
  if (!m || !seg) return BALL_EINVAL;
  if (!isfinite(t) || !isfinite(seg->t0) || !v3_finite(seg->p0) || !v3_finite(seg->v0) ||
      !v3_finite(seg->s0))
    return BALL_ENONFINITE;
  if (t < seg->t0) return BALL_ERANGE;
  return BALL_OK;
}

ball_status ball_segment_eval(const ball_model *m, const ball_segment *seg, double t,
                              ball_state *out) {
  ball_status st = check_args(m, seg, t);
  if (st != BALL_OK) return st;
  if (!out) return BALL_EINVAL;
  ball__eval(m, seg, t, out);
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
  if (!ball__plane_tau(ball__drag_b(m), v3_axis(seg->p0, axis), v3_axis(seg->v0, axis), coord,
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
