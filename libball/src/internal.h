/* Internal helpers shared by libball's sources; not installed. */
#ifndef BALL_INTERNAL_H
#define BALL_INTERNAL_H

#include <math.h>

#include "ball/ball.h"

/* ---- vectors ---- */
static inline ball_vec3 v3(double x, double y, double z) {
  ball_vec3 r;
  r.x = x; r.y = y; r.z = z;
  return r;
}
static inline ball_vec3 v3_add(ball_vec3 a, ball_vec3 b) { return v3(a.x + b.x, a.y + b.y, a.z + b.z); }
static inline ball_vec3 v3_sub(ball_vec3 a, ball_vec3 b) { return v3(a.x - b.x, a.y - b.y, a.z - b.z); }
static inline ball_vec3 v3_scale(ball_vec3 a, double s) { return v3(a.x * s, a.y * s, a.z * s); }
static inline double v3_dot(ball_vec3 a, ball_vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
static inline ball_vec3 v3_cross(ball_vec3 a, ball_vec3 b) {
  return v3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
static inline double v3_norm(ball_vec3 a) { return sqrt(v3_dot(a, a)); }
static inline int v3_finite(ball_vec3 a) { return isfinite(a.x) && isfinite(a.y) && isfinite(a.z); }
static inline ball_vec3 v3_lerp(ball_vec3 a, ball_vec3 b, double u) {
  return v3(a.x + (b.x - a.x) * u, a.y + (b.y - a.y) * u, a.z + (b.z - a.z) * u);
}
static inline double v3_axis(ball_vec3 a, int axis) { return axis == 0 ? a.x : axis == 1 ? a.y : a.z; }

static inline int ball__has(const ball_model *m, unsigned effect) { return (m->effects & effect) != 0; }

/* ---- flight (flight.c) ---- */

/* b = m / beta, or +Inf when drag is off or beta = 0. */
double ball__drag_b(const ball_model *m);
/* b (1 - e^(-t/b)), computed as -b expm1(-t/b); t when b is infinite (eq 3). */
double ball__drag_distance(double b, double t);
/* e^(-t/b), 1 when b is infinite (eq 3). */
double ball__drag_decay(double b, double t);
/* sDamp / (sDamp + t) (eq 4), 1 when spin is off. */
double ball__spin_air_damping(const ball_model *m, double t);
/* State at sim time t on seg, no argument checks (eq 3, 4). */
void ball__eval(const ball_model *m, const ball_segment *seg, double t, ball_state *out);
/* Starts a new segment at time t. */
void ball__segment_start(ball_segment *seg, double t, ball_vec3 p0, ball_vec3 v0, ball_vec3 s0, int grounded);
/* Roots r1 <= r2 of y0 + v tau - g tau^2 / 2 = y; 0 if the height is never reached. */
int ball__height_roots(double g, double y0, double v, double y, double *r1, double *r2);
/* tau >= tau_from where x0 + v b (1 - e^(-tau/b)) = target; 0 if never. */
int ball__plane_tau(double b, double x0, double v, double target, double tau_from, double *tau);
/* The effective floor height for the ball centre: floor_level + radius. */
static inline double ball__floor_y(const ball_model *m) { return m->floor_level + m->radius; }

/* ---- rackets (racket.c, response.c) ---- */

/* Racket stage of a step, run after the static obstacles when the RACKETS
 * effect is on. The frame goes from t_prev (ball centre then:
 * sim->prev_position) to t = sim->time (ball on sim->seg). Handles the sleep
 * counter, the detection mode and the response; on a hit it starts a new
 * segment in sim->seg, writes *ev and returns 1; otherwise returns 0.
 * Updates each track's prev_pose for the next frame. */
int ball__racket_stage(const ball_model *m, ball_sim *sim, double t_prev, double dt, ball_event *ev);

/* eq 13: velocity added at a floor bounce by the air-damped spin, normal (0, 1, 0):
 * spinFloorDamping (spinAirDamping S_ball) x n. Implemented in response.c. */
ball_vec3 ball__spin_floor_velocity(const ball_model *m, ball_vec3 spin_air_damped);

/* Checks the racket fields of a model; *field names the bad one. */
ball_status ball__racket_check(const ball_model *m, const char **field);

#endif /* BALL_INTERNAL_H */
