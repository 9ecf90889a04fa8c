/* Static distance queries (checked against FCL in validation/). */
#include "internal.h"

static double clamp(double v, double lo, double hi) { return v < lo ? lo : v > hi ? hi : v; }

ball_status ball_sphere_rect_distance(const ball_plane *rect, ball_vec3 c, double radius,
                                      double *distance) {
  ball_status st;
  double h, hc, yc, dn, dh, dy;
  if (!rect || !distance) return BALL_EINVAL;
  if (!ball_v3_finite(c) || !isfinite(radius)) return BALL_ENONFINITE;
  if (radius < 0.0) return BALL_ERANGE;
  st = ball_plane_check(rect, NULL);
  if (st != BALL_OK) return st;
  h = rect->axis == 0 ? c.z : c.x; /* in-plane horizontal coordinate */
  hc = clamp(h, rect->lo, rect->hi);
  yc = clamp(c.y, rect->bottom, rect->top);
  dn = ball_v3_axis(c, rect->axis) - rect->position;
  dh = h - hc;
  dy = c.y - yc;
  *distance = sqrt(dn * dn + dh * dh + dy * dy) - radius;
  return BALL_OK;
}

ball_status ball_sphere_disc_distance(ball_vec3 disc_center, ball_vec3 disc_normal,
                                      double disc_radius, ball_vec3 c, double radius,
                                      double *distance) {
  double len, h, rho;
  ball_vec3 n, d, radial;
  if (!distance) return BALL_EINVAL;
  if (!ball_v3_finite(disc_center) || !ball_v3_finite(disc_normal) || !ball_v3_finite(c) ||
      !isfinite(disc_radius) || !isfinite(radius))
    return BALL_ENONFINITE;
  if (disc_radius < 0.0 || radius < 0.0) return BALL_ERANGE;
  len = ball_v3_norm(disc_normal);
  if (!(len > 1e-12)) return BALL_ERANGE;
  n = ball_v3_scale(disc_normal, 1.0 / len);
  d = ball_v3_sub(c, disc_center);
  h = ball_v3_dot(d, n);
  radial = ball_v3_sub(d, ball_v3_scale(n, h));
  rho = ball_v3_norm(radial);
  if (rho <= disc_radius)
    *distance = fabs(h) - radius;
  else
    *distance = sqrt((rho - disc_radius) * (rho - disc_radius) + h * h) - radius;
  return BALL_OK;
}
