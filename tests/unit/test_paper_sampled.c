/* The sampled scheme is the paper as written for a point ball: an
 * independent reading of section 3 (Fig. 1 and eq 5 for the floor, Fig. 3
 * and eq 6 for the net, eq 3 for the flight between them), written here from
 * the paper alone, gives the same events, frame for frame, as ball_step over
 * random low serves into the net's foot, at 2 to 60 Hz (docs/model.md, "Two
 * schemes for static obstacles"). */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "core_common.h"

#define RUNS 12000
#define FRAMES 240
#define MAX_REF_EVENTS 512

typedef struct ref_event {
  int kind;        /* BALL_EVENT_FLOOR or BALL_EVENT_NET */
  long frame;      /* the frame that found it */
  ball_vec3 p0;    /* the new initial position */
  ball_vec3 v0;    /* the new initial velocity */
} ref_event;

/* The paper's ball: the initial state of the current flight and the time
 * since it started (t of eq 3, reset to zero at each collision). */
typedef struct ref_ball {
  ball_vec3 p0, v0;
  double t;
  int sliding;     /* vertical speed set to zero after a bounce below bounce_threshold */
} ref_ball;

/* eq 3: position and velocity t seconds into the flight; b = m / beta. */
static void ref_flight(const ball_model *m, const ref_ball *s, ball_vec3 *p, ball_vec3 *v) {
  double b = m->mass / m->air_friction, f = exp(-s->t / b), w = -b * expm1(-s->t / b);
  p->x = s->p0.x + s->v0.x * w;
  p->y = s->p0.y + s->v0.y * s->t - 0.5 * m->gravity * s->t * s->t;
  p->z = s->p0.z + s->v0.z * w;
  v->x = s->v0.x * f;
  v->y = s->v0.y - m->gravity * s->t;
  v->z = s->v0.z * f;
  if (s->sliding) {
    p->y = s->p0.y;
    v->y = 0.0;
  }
}

/* A collision: the flight restarts from s (t = 0), noted in out[*n]. */
static void ref_collision(ref_ball *s, int kind, long frame, ref_event *out, int *n) {
  s->t = 0.0;
  out[*n].kind = kind;
  out[*n].frame = frame;
  out[*n].p0 = s->p0;
  out[*n].v0 = s->v0;
  (*n)++;
}

/* One run of the paper's frame loop; returns the events. */
static int ref_run(const ball_model *m, double dt, ref_event *out) {
  ref_ball s;
  ball_vec3 p_old = m->initial_position, p, v;
  const ball_plane *net = &m->net;
  long frame;
  int n = 0;
  s.p0 = m->initial_position;
  s.v0 = m->initial_velocity;
  s.t = 0.0;
  s.sliding = 0;
  for (frame = 0; frame < FRAMES && n < MAX_REF_EVENTS; frame++) {
    s.t += dt;
    ref_flight(m, &s, &p, &v);
    /* Fig. 3: the line from P_old to P against the net plane x = net_x */
    if (p_old.x != p.x) {
      double sf = (net->position - p_old.x) / (p.x - p_old.x);
      if (sf >= 0.0 && sf <= 1.0) {
        ball_vec3 q = ball_v3_add(p_old, ball_v3_scale(ball_v3_sub(p, p_old), sf));
        if (q.z >= net->lo && q.z <= net->hi && q.y >= net->bottom && q.y <= net->top) {
          /* eq 6: x reversed, all times netDamping; restart at Q + (V0x dt / 10, 0, 0) */
          ball_vec3 v0 = ball_v3_scale(ball_v3(-v.x, v.y, v.z), net->damping);
          s.p0 = ball_v3_add(q, ball_v3(v0.x * dt / 10.0, 0.0, 0.0));
          s.v0 = v0;
          ref_collision(&s, BALL_EVENT_NET, frame, out, &n);
          ref_flight(m, &s, &p, &v);
        }
      }
    }
    /* Fig. 1, eq 5: below the floor at the frame's end */
    if (!s.sliding && p.y < m->floor_level && n < MAX_REF_EVENTS) {
      double fd = m->floor_damping;
      s.p0 = ball_v3(p.x, m->floor_level, p.z);
      s.v0 = ball_v3(v.x * fd, -v.y * fd, v.z * fd);
      /* a bounce slower than bounce_threshold stops bouncing (docs/design.md) */
      if (s.v0.y < m->bounce_threshold) {
        s.v0.y = 0.0;
        s.sliding = 1;
      }
      ref_collision(&s, BALL_EVENT_FLOOR, frame, out, &n);
      ref_flight(m, &s, &p, &v);
    }
    p_old = p;
  }
  return n;
}

/* A point ball served low at the tennis net from either side, often into
 * its foot, with drag, floor and net; sampled scheme. */
static void random_serve(core_rng *r, ball_model *m, double *dt) {
  static const double rates[] = {2.0, 6.0, 10.0, 15.0, 30.0, 60.0};
  double side = core_uniform(r, 0.0, 1.0) < 0.5 ? -1.0 : 1.0;
  core_model_free(m);
  core_tennis_net(m, core_uniform(r, 0.3, 1.0));
  m->effects = BALL_EFFECT_DRAG | BALL_EFFECT_FLOOR | BALL_EFFECT_NET;
  m->scheme = BALL_SCHEME_SAMPLED;
  m->air_friction = core_uniform(r, 0.005, 0.05);
  m->floor_damping = core_uniform(r, 0.5, 0.95);
  m->bounce_threshold = core_uniform(r, 0.1, 1.0);
  m->initial_position = ball_v3(11.885 - side * core_uniform(r, 0.5, 8.0), core_uniform(r, 0.05, 1.5),
                                core_uniform(r, 0.5, 10.5));
  m->initial_velocity = ball_v3(side * core_uniform(r, 2.0, 40.0), core_uniform(r, -6.0, 3.0),
                                core_uniform(r, -2.0, 2.0));
  *dt = 1.0 / rates[(int)core_uniform(r, 0.0, 6.0)];
}

static void sampled_point_ball_is_the_papers_fig1_fig3_eq5_eq6(void **state) {
  core_rng r = {20261202ULL};
  ref_event ref[MAX_REF_EVENTS];
  long run, differ = 0, net_events = 0, foot_frames = 0;
  (void)state;
  for (run = 0; run < RUNS; run++) {
    ball_model m;
    ball_sim sim;
    ball_event ev[4];
    double dt;
    int n_ref, k = 0, n, i, same = 1;
    long frame;
    random_serve(&r, &m, &dt);
    n_ref = ref_run(&m, dt, ref);
    assert_ok(ball_sim_init(&sim, &m));
    for (frame = 0; frame < FRAMES && same; frame++) {
      ball_state st;
      assert_ok(ball_step(&sim, dt, ev, 4, &n));
      for (i = 0; i < n && same; i++, k++) {
        same = k < n_ref && ref[k].frame == frame && (int)ev[i].kind == ref[k].kind &&
               ball_v3_dist(ev[i].segment.p0, ref[k].p0) <= 1e-9 &&
               ball_v3_dist(ev[i].segment.v0, ref[k].v0) <= 1e-9;
        if (ev[i].kind == BALL_EVENT_NET) net_events++;
      }
      /* frames whose chord to P dips below the floor (the case Fig. 3 reads
       * literally: a crossing under the floor is no net contact) */
      assert_ok(ball_sim_state(&sim, &st));
      if (n > 0 && ev[n - 1].kind == BALL_EVENT_FLOOR && fabs(st.position.x - 11.885) < 1.0) foot_frames++;
    }
    if (same && k < n_ref && ref[k].frame < FRAMES) same = 0;
    if (!same) {
      if (differ < 5)
        print_message("run %ld (dt %.4g s): libball and the paper's reading differ at event %d\n", run, dt, k);
      differ++;
    }
  }
  print_message("%d runs: %ld differ, %ld net events, %ld bounces within 1 m of the net\n", RUNS, differ,
                net_events, foot_frames);
  assert_int_equal(differ, 0);
  /* the runs reach what they are for */
  assert_true(net_events > RUNS / 4);
  assert_true(foot_frames > RUNS / 10);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(sampled_point_ball_is_the_papers_fig1_fig3_eq5_eq6),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
