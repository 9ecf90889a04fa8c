/* A full offline rally at each game level (section 4): two scripted bot
 * rackets on a tennis court, sampled at 10 Hz and fed with ball_racket_push,
 * the sim bridging the samples with eq 15 (extrapolation_time 0.1 s). The
 * ball must cross the net at least 10 times without touching it.
 *
 * The bot: after every hit, it steps a copy of the sim (rackets off) to find
 * where the ball crosses the receiver's hitting plane (time T, point X,
 * velocity V, spin S), then swings the racket linearly through X at T:
 *   easy (sphere, autonomous): any swing through X (eq 9 ignores it);
 *   mid (disc with velocity normal, mixed 0.8): the racket velocity solved
 *     from eq 10 for a lob to the partner (V_up 5.5 m/s);
 *   advanced (disc with real normal, physical with spin): the normal and
 *     racket velocity solved from eq 11 for the same lob, with a 1.5 m/s
 *     upward brush that gives the ball spin (eq 12), which then acts on the
 *     next hit (eq 11). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "core_common.h"

#define FRAME (1.0 / 60.0)
#define SAMPLE_FRAMES 6 /* 10 Hz samples */
#define X_HIT_LEFT 3.0
#define X_HIT_RIGHT 20.77
#define COURT_Z 5.485
#define READY_Y 1.0

typedef struct plan {
  int active;
  double t;                 /* T */
  ball_vec3 x, u, n;        /* hit point, racket velocity, racket normal */
} plan;

static double x_hit(int racket) { return racket == 0 ? X_HIT_LEFT : X_HIT_RIGHT; }
static ball_vec3 ready(int racket) { return ball_v3(x_hit(racket), READY_Y, COURT_Z); }
static ball_vec3 ready_normal(int racket) { return ball_v3(racket == 0 ? 1.0 : -1.0, 0, 0); }

/* eq 8, 9 by hand: from q to (goal x, q y, goal z) with v_up, times friendly. */
static ball_vec3 friendly_velocity(const ball_model *m, ball_vec3 q, ball_vec3 goal, double v_up, double friendly) {
  double b = m->mass / m->air_friction, t0 = 2.0 * v_up / m->gravity, f = 1.0 / (-b * expm1(-t0 / b));
  return ball_v3_scale(ball_v3((goal.x - q.x) * f, v_up, (goal.z - q.z) * f), friendly);
}

/* The racket's scripted pose at t: ready, approach, the swing through X at T, return. */
static void racket_pose(int racket, const plan *p, double t, ball_vec3 *c, ball_vec3 *n) {
  ball_vec3 r = ready(racket);
  *c = r;
  *n = ready_normal(racket);
  if (!p->active || t <= p->t - 0.6 || t >= p->t + 0.7) return;
  if (t < p->t - 0.25) {
    ball_vec3 from = ball_v3_sub(p->x, ball_v3_scale(p->u, 0.25)); /* where the stroke begins */
    *c = ball_v3_add(r, ball_v3_scale(ball_v3_sub(from, r), (t - (p->t - 0.6)) / 0.35));
  } else if (t <= p->t + 0.25) {
    *c = ball_v3_add(p->x, ball_v3_scale(p->u, t - p->t));
    *n = p->n;
  } else {
    ball_vec3 e = ball_v3_add(p->x, ball_v3_scale(p->u, 0.25));
    *c = ball_v3_add(e, ball_v3_scale(ball_v3_sub(r, e), (t - (p->t + 0.25)) / 0.45));
  }
}

/* Where the ball crosses the receiver's hitting plane: ball_predict over
 * 4 s at 240 Hz (static obstacles only, what a bot asks). 0 if it never gets
 * there at a hittable height. */
#define PREDICT_RATE 240
static int predict(const ball_model *m, const ball_sim *sim, int receiver, double *t, ball_state *at) {
  static ball_state states[4 * PREDICT_RATE + 1];
  ball_event events[64];
  ball_prediction pr;
  double xh = x_hit(receiver);
  int i, e = -1;
  pr.states = states;
  pr.cap_states = 4 * PREDICT_RATE + 1;
  pr.events = events;
  pr.cap_events = 64;
  assert_ok(ball_predict(m, &sim->seg, sim->time, sim->time + 4.0, 1.0 / PREDICT_RATE, &pr));
  for (i = 1; i < pr.n_states; i++) {
    const ball_segment *seg;
    double t0 = sim->time + (i - 1) * (1.0 / PREDICT_RATE), t1 = t0 + 1.0 / PREDICT_RATE;
    while (e + 1 < pr.n_events && events[e + 1].time <= t1) e++;
    if ((states[i - 1].position.x - xh) * (states[i].position.x - xh) > 0.0) continue;
    seg = e >= 0 ? &events[e].segment : &sim->seg; /* the segment in effect at the frame's end */
    if (ball_time_to_plane(m, seg, seg->t0 > t0 ? seg->t0 : t0, 0, xh, t) != BALL_OK) *t = t1;
    assert_ok(ball_segment_eval(m, seg, *t, at));
    return at->position.y > 0.1 && at->position.y < 3.0;
  }
  return 0;
}

static void make_plan(const ball_model *m, int receiver, double t, const ball_state *s, plan *p) {
  int other = 1 - receiver;
  ball_vec3 goal = ready(other), v = s->velocity;
  p->active = 1;
  p->t = t;
  p->x = s->position;
  if (m->response == BALL_RESPONSE_AUTONOMOUS) {
    /* the racket's velocity does not matter (eq 9); slower than the ball
     * leaves, so the swing does not follow it into a second hit */
    p->u = friendly_velocity(m, s->position, goal, m->v_up, 0.5);
    p->n = ball_v3_unit(p->u);
  } else if (m->response == BALL_RESPONSE_MIXED) {
    /* eq 10 solved for the racket velocity that gives a lob to the partner
     * (V_up 5.5 m/s): V_racket = (V_lob - ff V_f) / (1 - ff) */
    double ff = m->friendly_factor;
    ball_vec3 vf = friendly_velocity(m, s->position, goal, m->v_up, 1.0);
    ball_vec3 lob = friendly_velocity(m, s->position, goal, 5.5, 1.0);
    p->u = ball_v3_scale(ball_v3_sub(lob, ball_v3_scale(vf, ff)), 1.0 / (1.0 - ff));
    p->n = ball_v3_unit(p->u);
  } else {
    /* eq 11 with V_racket = s n + w, w the brush orthogonal to n:
     * V0 = V + (s - 2 n.V) n + w + S x n. Solve n for V0 = V_des (a lob to
     * the partner, V_up 5.5 m/s), then s. */
    ball_vec3 v_des = friendly_velocity(m, s->position, goal, 5.5, 1.0), w, rhs;
    ball_vec3 n = ball_v3_unit(ball_v3_sub(v_des, v));
    int it;
    double k;
    for (it = 0; it < 20; it++) {
      w = ball_v3_sub(ball_v3(0, 1.5, 0), ball_v3_scale(n, n.y * 1.5));
      rhs = ball_v3_sub(ball_v3_sub(ball_v3_sub(v_des, v), w), ball_v3_cross(s->spin, n));
      n = ball_v3_unit(rhs);
    }
    w = ball_v3_sub(ball_v3(0, 1.5, 0), ball_v3_scale(n, n.y * 1.5));
    k = ball_v3_norm(ball_v3_sub(ball_v3_sub(ball_v3_sub(v_des, v), w), ball_v3_cross(s->spin, n)));
    p->n = n;
    p->u = ball_v3_add(ball_v3_scale(n, k + 2.0 * ball_v3_dot(n, v)), w);
  }
}

/* Plays a rally at a level; returns how often the ball crossed the net. */
static int rally(ball_level level, int *hits, double *max_spin) {
  ball_model m;
  ball_sim sim;
  ball_event ev[16];
  plan plans[2];
  ball_state s, at;
  double t_hit, side_prev;
  int frame, n, k, r, crossings = 0, receiver = 1;
  ball_model_default(&m);
  assert_ok(ball_model_set_level(&m, level));
  m.radius = 0.033;
  m.n_rackets = 2;
  m.rackets[0].radius = m.rackets[1].radius = 0.2;
  m.rackets[0].partner = 1;
  m.rackets[1].partner = 0;
  m.extrapolation_time = 0.1; /* eq 15 bridges the 10 Hz samples */
  m.stale_time = 1.0;
  m.initial_position = ball_v3(X_HIT_LEFT + 1.0, READY_Y, COURT_Z); /* served in front of racket 0 */
  m.initial_velocity = friendly_velocity(&m, m.initial_position, ready(1), m.v_up, 1.0);
  assert_ok(ball_model_check(&m, NULL));
  assert_ok(ball_sim_init(&sim, &m));
  memset(plans, 0, sizeof plans);
  *hits = 0;
  *max_spin = 0.0;
  side_prev = m.initial_position.x - m.net.position;
  if (predict(&m, &sim, receiver, &t_hit, &at)) make_plan(&m, receiver, t_hit, &at, &plans[receiver]);
  for (frame = 0; frame < 60 * 40 && crossings < 12; frame++) {
    if (frame % SAMPLE_FRAMES == 0)
      for (r = 0; r < 2; r++) {
        ball_racket_sample smp;
        smp.t = sim.time;
        racket_pose(r, &plans[r], sim.time, &smp.center, &smp.normal);
        assert_ok(ball_racket_push(&sim, r, &smp));
      }
    assert_ok(ball_step(&sim, FRAME, ev, 16, &n));
    for (k = 0; k < n; k++) {
      if (ev[k].kind == BALL_EVENT_NET) return crossings; /* into the net: rally over */
      if (ev[k].kind != BALL_EVENT_RACKET) continue;
      (*hits)++;
      if (ball_v3_norm(ev[k].spin_out) > *max_spin) *max_spin = ball_v3_norm(ev[k].spin_out);
      /* the hitter's swing runs on and returns to ready; plan the receiver's */
      receiver = 1 - ev[k].index;
      if (!predict(&m, &sim, receiver, &t_hit, &at)) return crossings;
      make_plan(&m, receiver, t_hit, &at, &plans[receiver]);
    }
    assert_ok(ball_sim_state(&sim, &s));
    if ((s.position.x - m.net.position) * side_prev < 0.0) crossings++; /* over: a net contact ends the rally */
    side_prev = s.position.x - m.net.position;
  }
  return crossings;
}

static void rally_level(ball_level level) {
  int hits, crossings;
  double max_spin;
  crossings = rally(level, &hits, &max_spin);
  printf("rally %-8s: %d net crossings, %d racket hits, largest spin out %.2f m/s\n", ball_level_name(level),
         crossings, hits, max_spin);
  assert_true(crossings >= 10);
  assert_true(hits >= 9);
  if (level == BALL_LEVEL_ADVANCED)
    assert_true(max_spin > 0.5); /* the brush put spin on the ball (eq 12) */
  else
    assert_near(max_spin, 0.0, 0.0);
}

static void rally_easy_sphere_autonomous_crosses_net_10_times(void **state) {
  (void)state;
  rally_level(BALL_LEVEL_EASY);
}

static void rally_mid_disc_velocity_normal_mixed_crosses_net_10_times(void **state) {
  (void)state;
  rally_level(BALL_LEVEL_MID);
}

static void rally_advanced_disc_real_normal_physical_spin_crosses_net_10_times(void **state) {
  (void)state;
  rally_level(BALL_LEVEL_ADVANCED);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(rally_easy_sphere_autonomous_crosses_net_10_times),
      cmocka_unit_test(rally_mid_disc_velocity_normal_mixed_crosses_net_10_times),
      cmocka_unit_test(rally_advanced_disc_real_normal_physical_spin_crosses_net_10_times),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
