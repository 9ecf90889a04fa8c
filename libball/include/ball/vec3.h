/* libball: small vector helpers over ball_vec3, for the library and its
 * users (tools, validation, the server, bots): one copy instead of one per
 * program. Header only, C99 and C++; no state, no checks (a NaN in gives a
 * NaN out). */
#ifndef BALL_VEC3_H
#define BALL_VEC3_H

#include <math.h>

#include "ball/ball.h"

#ifdef __cplusplus
extern "C" {
#endif

static inline ball_vec3 ball_v3(double x, double y, double z) {
  ball_vec3 r;
  r.x = x;
  r.y = y;
  r.z = z;
  return r;
}
static inline ball_vec3 ball_v3_add(ball_vec3 a, ball_vec3 b) { return ball_v3(a.x + b.x, a.y + b.y, a.z + b.z); }
static inline ball_vec3 ball_v3_sub(ball_vec3 a, ball_vec3 b) { return ball_v3(a.x - b.x, a.y - b.y, a.z - b.z); }
static inline ball_vec3 ball_v3_scale(ball_vec3 a, double s) { return ball_v3(a.x * s, a.y * s, a.z * s); }
static inline double ball_v3_dot(ball_vec3 a, ball_vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static inline ball_vec3 ball_v3_cross(ball_vec3 a, ball_vec3 b) {
  return ball_v3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
static inline double ball_v3_norm(ball_vec3 a) { return sqrt(ball_v3_dot(a, a)); }
static inline double ball_v3_dist(ball_vec3 a, ball_vec3 b) { return ball_v3_norm(ball_v3_sub(a, b)); }
/* the largest |component| (finite input) */
static inline double ball_v3_max_abs(ball_vec3 a) {
  double x = fabs(a.x), y = fabs(a.y), z = fabs(a.z), m = x > y ? x : y;
  return m > z ? m : z;
}
/* |a| without overflow or underflow: scaled by the largest component first
 * (|(3e300, 4e300, 0)| = 5e300, not +Inf) */
static inline double ball_v3_length(ball_vec3 a) {
  double s = ball_v3_max_abs(a);
  if (!(s > 0.0) || isinf(s)) return s > 0.0 ? s : 0.0;
  a = ball_v3_scale(a, 1.0 / s);
  return s * sqrt(ball_v3_dot(a, a));
}
/* a / |a| without overflow (scaled first, as ball_v3_length); the zero
 * vector stays zero */
static inline ball_vec3 ball_v3_unit(ball_vec3 a) {
  double s = ball_v3_max_abs(a);
  double n;
  if (!(s > 0.0)) return ball_v3(0.0, 0.0, 0.0);
  a = ball_v3_scale(a, 1.0 / s);
  n = sqrt(ball_v3_dot(a, a));
  return ball_v3(a.x / n, a.y / n, a.z / n); /* divided, not scaled by 1 / n: to half an ulp */
}
/* every component finite: x - x is 0 for a finite x and NaN for an infinite
 * or NaN one, so one comparison decides, without a branch per component
 * (as isfinite, this needs IEEE arithmetic: no -ffinite-math-only) */
static inline int ball_v3_finite(ball_vec3 a) { return (a.x - a.x) + (a.y - a.y) + (a.z - a.z) == 0.0; }
/* a + (b - a) u */
static inline ball_vec3 ball_v3_lerp(ball_vec3 a, ball_vec3 b, double u) {
  return ball_v3(a.x + (b.x - a.x) * u, a.y + (b.y - a.y) * u, a.z + (b.z - a.z) * u);
}
/* component 0 (x), 1 (y) or 2 (z) */
static inline double ball_v3_axis(ball_vec3 a, int axis) { return axis == 0 ? a.x : axis == 1 ? a.y : a.z; }
/* largest absolute component difference */
static inline double ball_v3_max_diff(ball_vec3 a, ball_vec3 b) {
  return ball_v3_max_abs(ball_v3_sub(a, b));
}

#ifdef __cplusplus
}
#endif

#endif /* BALL_VEC3_H */
