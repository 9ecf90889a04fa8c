/* Ball-racket responses (section 3.1, eq 7-14). Pure functions of the
 * arriving ball, the racket and the model; racket.c picks one and starts the
 * new flight segment. docs/rackets.md explains each reading. */
#include "internal.h"

/* Below this speed a racket counts as still: eq 7 has no direction then. */
#define STILL_SPEED 1e-3 /* m/s */

/* Fig. 9: the racket normal inverted when the ball's previous position lies
 * behind it (dP_old . n < 0), so either face of the racket can hit. */
ball_vec3 ball__racket_face_normal(ball_vec3 n, ball_vec3 rel_old) {
  return ball_v3_dot(rel_old, n) < 0.0 ? ball_v3_scale(n, -1.0) : n;
}

/* eq 7: along the racket velocity, speed clamped to [v_min, v_max]. A still
 * racket has no direction: the ball leaves along fallback (the face normal)
 * at v_min. */
ball_vec3 ball__response_racket(const ball_model *m, ball_vec3 v_racket, ball_vec3 fallback) {
  double speed = ball_v3_norm(v_racket);
  ball_vec3 dir;
  if (speed < STILL_SPEED) {
    double fl = ball_v3_norm(fallback);
    dir = fl > 0.0 ? ball_v3_scale(fallback, 1.0 / fl) : ball_v3(0.0, 1.0, 0.0);
    speed = 0.0;
  } else {
    dir = ball_v3_scale(v_racket, 1.0 / speed);
  }
  if (speed < m->v_min) speed = m->v_min;
  if (speed > m->v_max) speed = m->v_max;
  return ball_v3_scale(dir, speed);
}

/* eq 8: V_up, given or matched to the racket's vertical speed; the racket's
 * speed is clamped to at least BALL__V_UP_MIN so that t0 = 2 V_up / g > 0. */
double ball__response_v_up(const ball_model *m, ball_vec3 v_racket) {
  if (!m->v_up_from_racket) return m->v_up;
  return v_racket.y > BALL__V_UP_MIN ? v_racket.y : BALL__V_UP_MIN;
}

/* eq 8, 9: the "friendly" ball from q to the goal's (x, z) at q's height:
 * t0 = 2 V_up / g, horizontal speed dist_h / (b (1 - e^(-t0/b))) (the paper's
 * "V0y" there is a typo, docs/design.md R7), everything times friendlyFactor. */
ball_vec3 ball__response_autonomous(const ball_model *m, ball_vec3 q, ball_vec3 goal, double v_up,
                                    double friendly) {
  double t0 = 2.0 * v_up / m->gravity;                       /* eq 8 */
  double f = 1.0 / ball__drag_distance(ball__drag_b(m), t0); /* eq 9: f = 1 / (b (1 - e^(-t0/b))) */
  double d1 = goal.x - q.x, d2 = goal.z - q.z;
  return ball_v3_scale(ball_v3(d1 * f, v_up, d2 * f), friendly); /* eq 9 */
}

/* eq 10: V0 = V_friendly + (V_racket - V_friendly) (1 - friendlyFactor). */
ball_vec3 ball__response_mixed(ball_vec3 v_friendly, ball_vec3 v_racket, double friendly) {
  return ball_v3_add(v_friendly, ball_v3_scale(ball_v3_sub(v_racket, v_friendly), 1.0 - friendly));
}

/* eq 11, 12: reflection about the (face) normal, plus the racket's normal
 * velocity, plus the spin term; spin_in is the arriving ball's spin with the
 * air damping of eq 4 already applied (spinAirDamping S_ball_old). Without
 * the SPIN effect the spin term is left out and the ball leaves without spin. */
void ball__response_physical(const ball_model *m, ball_vec3 v, ball_vec3 spin_in, ball_vec3 n,
                             ball_vec3 v_racket, ball_vec3 *v0, ball_vec3 *s0) {
  ball_vec3 v_r = ball_v3_sub(v, ball_v3_scale(n, 2.0 * ball_v3_dot(n, v))); /* eq 11: V_r */
  ball_vec3 v_rn = ball_v3_scale(n, ball_v3_dot(n, v_racket));          /* eq 11: V_racketnorm */
  *v0 = ball_v3_add(v_r, v_rn);
  *s0 = ball_v3(0.0, 0.0, 0.0);
  if (ball__has(m, BALL_EFFECT_SPIN)) {
    ball_vec3 s_racket = ball_v3_cross(v_racket, n);                           /* eq 11: S_racket */
    ball_vec3 v_spin = ball_v3_cross(ball_v3_sub(spin_in, s_racket), n);            /* eq 11: V_spin_rack */
    *v0 = ball_v3_add(*v0, v_spin);                                            /* eq 11: V0 */
    *s0 = ball_v3_scale(s_racket, m->spin_rack_damping);                       /* eq 12 */
  }
}

/* eq 13: V_spin_floor = spinFloorDamping (spinAirDamping S_ball) x n with the
 * floor normal n = (0, 1, 0); zero without the SPIN effect. */
ball_vec3 ball__spin_floor_velocity(const ball_model *m, ball_vec3 spin_air_damped) {
  if (!ball__has(m, BALL_EFFECT_SPIN)) return ball_v3(0.0, 0.0, 0.0);
  return ball_v3_scale(ball_v3_cross(spin_air_damped, ball_v3(0.0, 1.0, 0.0)), m->spin_floor_damping);
}
