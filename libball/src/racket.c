/* Rackets (section 2, 3, 4): sampled tracks, estimation (eq 15), the three
 * collision tests (Fig. 4, 5), the racket stage of a step and the game
 * levels. docs/rackets.md and docs/game-levels.md explain the choices. */
#include <string.h>

#include "internal.h"

/* ---- tracks ---- */

static ball_vec3 nlerp(ball_vec3 a, ball_vec3 b, double u) {
  ball_vec3 n;
  double len;
  if (ball_v3_dot(a, b) < 0.0) b = ball_v3_scale(b, -1.0); /* a disc has two faces */
  n = ball_v3_lerp(a, b, u);
  len = ball_v3_norm(n);
  return len > 0.0 ? ball_v3_scale(n, 1.0 / len) : a;
}

/* Interpolation between the two samples around t (linear centre, nlerp
 * normal, the pair's finite difference as velocity); before the oldest the
 * oldest pose is held; past the newest, eq 15. */
void ball__racket_pose(const ball_model *m, const ball_racket_track *tr, double t,
                       ball_racket_pose *out) {
  int n = tr->count, k;
  const ball_racket_sample *s = tr->samples;
  const ball_racket_sample *a, *b;
  if (n == 1) {
    out->center = s[0].center;
    out->normal = s[0].normal;
    out->velocity = ball_v3(0.0, 0.0, 0.0);
    return;
  }
  if (t >= s[n - 1].t) {
    /* eq 15: P = P_current + V_current * extrapolationTime, where the time
     * past the newest sample is the delay being compensated, capped at
     * extrapolation_time (0: the racket holds at its newest sample). */
    double dx = t - s[n - 1].t;
    a = &s[n - 2];
    b = &s[n - 1];
    out->velocity = ball_v3_scale(ball_v3_sub(b->center, a->center), 1.0 / (b->t - a->t));
    if (dx > m->extrapolation_time) dx = m->extrapolation_time;
    out->center = ball_v3_add(b->center, ball_v3_scale(out->velocity, dx));
    out->normal = b->normal;
    return;
  }
  if (t <= s[0].t) {
    a = &s[0];
    b = &s[1];
    out->velocity = ball_v3_scale(ball_v3_sub(b->center, a->center), 1.0 / (b->t - a->t));
    out->center = a->center;
    out->normal = a->normal;
    return;
  }
  for (k = n - 2; k > 0 && s[k].t > t; k--) {
  }
  a = &s[k];
  b = &s[k + 1];
  {
    double u = (t - a->t) / (b->t - a->t);
    out->center = ball_v3_lerp(a->center, b->center, u);
    out->normal = nlerp(a->normal, b->normal, u);
    out->velocity = ball_v3_scale(ball_v3_sub(b->center, a->center), 1.0 / (b->t - a->t));
  }
}

static int history_of(const ball_model *m) {
  return m->history < 2 ? 2 : m->history > BALL_MAX_HISTORY ? BALL_MAX_HISTORY : m->history;
}

static int same_sample(const ball_racket_sample *a, const ball_racket_sample *b) {
  return a->t == b->t && a->center.x == b->center.x && a->center.y == b->center.y &&
         a->center.z == b->center.z && a->normal.x == b->normal.x && a->normal.y == b->normal.y &&
         a->normal.z == b->normal.z;
}

ball_status ball_racket_clear(ball_sim *sim, int racket) {
  if (!sim) return BALL_EINVAL;
  if (racket < 0 || racket >= sim->model.n_rackets || racket >= BALL_MAX_RACKETS) return BALL_EINVAL;
  memset(&sim->tracks[racket], 0, sizeof sim->tracks[racket]);
  return BALL_OK;
}
ball_status ball_racket_push(ball_sim *sim, int racket, const ball_racket_sample *sample) {
  const ball_model *m;
  ball_racket_track *tr;
  ball_racket_sample s;
  double scale, len;
  int i, keep;
  if (!sim || !sample) return BALL_EINVAL;
  m = &sim->model;
  if (racket < 0 || racket >= m->n_rackets || racket >= BALL_MAX_RACKETS) return BALL_EINVAL;
  if (!(sample->t - sample->t == 0.0) || !ball_v3_finite(sample->center) || !ball_v3_finite(sample->normal))
    return BALL_ENONFINITE;
  if (ball_v3_max_abs(sample->center) > BALL_MAX_COORD) return BALL_ERANGE; /* outside the world */
  /* normalised without overflow: scaled by the largest component first */
  scale = ball_v3_max_abs(sample->normal);
  if (!(scale > 0.0)) return BALL_ERANGE;
  s = *sample;
  s.normal = ball_v3_scale(sample->normal, 1.0 / scale);
  len = sqrt(ball_v3_dot(s.normal, s.normal));
  if (!(len * scale >= 1e-9)) return BALL_ERANGE;
  s.normal = ball_v3_scale(s.normal, 1.0 / len);
  tr = &sim->tracks[racket];
  if (tr->count < 0 || tr->count > BALL_MAX_HISTORY) return BALL_EINVAL;
  for (i = 0; i < tr->count; i++)
    if (same_sample(&tr->samples[i], &s)) return BALL_EDUPLICATE; /* nothing new */
  /* not strictly newer (older, or the same time with other data): the first
   * sample for a time wins, so a replayed or reordered stream gives one track */
  if (tr->count > 0 && !(s.t > tr->samples[tr->count - 1].t)) return BALL_ESTALE;
  /* the velocity this sample implies must be a number: samples a subnormal
   * time apart would make it infinite and poison the ball's velocity */
  if (tr->count > 0) {
    const ball_racket_sample *last = &tr->samples[tr->count - 1];
    if (!ball_v3_finite(ball_v3_scale(ball_v3_sub(s.center, last->center), 1.0 / (s.t - last->t))))
      return BALL_ERANGE;
  }
  keep = history_of(m);
  while (tr->count >= keep) {
    memmove(&tr->samples[0], &tr->samples[1], (size_t)(tr->count - 1) * sizeof s);
    tr->count--;
  }
  tr->samples[tr->count++] = s;
  return BALL_OK;
}

/* ball_racket_estimate without the argument and binding checks. */
static ball_status estimate(const ball_model *m, const ball_sim *sim, int racket, double t,
                            ball_racket_pose *out) {
  const ball_racket_track *tr = &sim->tracks[racket];
  if (tr->count < 0 || tr->count > BALL_MAX_HISTORY) return BALL_EINVAL;
  if (tr->count == 0) return BALL_ENOTFOUND;
  if (t - tr->samples[tr->count - 1].t > m->stale_time) return BALL_ESTALE;
  ball__racket_pose(m, tr, t, out);
  return BALL_OK;
}

ball_status ball_racket_estimate(const ball_sim *sim, int racket, double t, ball_racket_pose *out) {
  if (!sim || !out) return BALL_EINVAL;
  if (racket < 0 || racket >= sim->model.n_rackets || racket >= BALL_MAX_RACKETS) return BALL_EINVAL;
  if (!isfinite(t)) return BALL_ENONFINITE;
  return estimate(&sim->model, sim, racket, t, out);
}

/* ---- the collision tests ---- */

/* The paper's simple test: the ball closer to the racket centre than d_COLL. */
int ball__sphere_test(ball_vec3 p, ball_vec3 r, double d_coll) {
  return ball_v3_norm(ball_v3_sub(p, r)) < d_coll;
}

/* Fig. 4, 5 in the racket's moving frame: P' = P - (R - R_old), the segment
 * P_old -> P' against the disc at R_old. A ball with a radius touches the face
 * when its centre enters the slab |d| <= ball_radius; the disc is grown to a
 * cylinder of radius disc_radius + ball_radius (exact on the face, slightly
 * generous at the rim corners; the swept test is exact there). */
int ball__disc_test(ball_vec3 p_old, ball_vec3 p, ball_vec3 r_old, ball_vec3 r, ball_vec3 n,
                    double disc_radius, double ball_radius, double *s_out, ball_vec3 *q) {
  ball_vec3 dr = ball_v3_sub(r, r_old);
  ball_vec3 p_rel = ball_v3_sub(p, dr); /* P' */
  double d0 = ball_v3_dot(ball_v3_sub(p_old, r_old), n);
  double d1 = ball_v3_dot(ball_v3_sub(p_rel, r_old), n);
  double side = d0 >= 0.0 ? 1.0 : -1.0;
  double e0 = side * d0 - ball_radius, e1 = side * d1 - ball_radius, s;
  ball_vec3 qr, w;
  if (e0 <= 0.0) {
    s = 0.0; /* already touching the face at the frame start */
  } else {
    if (e1 > 0.0) return 0; /* stays in front of the face */
    s = e0 / (e0 - e1);
  }
  qr = ball_v3_lerp(p_old, p_rel, s); /* Q' in the racket's frame */
  w = ball_v3_sub(qr, r_old);
  if (ball_v3_norm(ball_v3_sub(w, ball_v3_scale(n, ball_v3_dot(w, n)))) > disc_radius + ball_radius) return 0;
  if (s_out) *s_out = s;
  if (q) *q = ball_v3_add(qr, dr);
  return 1;
}

/* Section 4's game levels; docs/game-levels.md lists every value. */
ball_status ball_model_set_level(ball_model *m, ball_level level) {
  if (!m) return BALL_EINVAL;
  if ((unsigned)level >= BALL_LEVEL_COUNT) return BALL_ERANGE;
  m->level = level;
  if (level == BALL_LEVEL_CUSTOM) return BALL_OK;
  /* shared by the three levels */
  m->effects |= BALL_EFFECT_RACKETS;
  m->sleep_frames = 3;
  m->v_min = 5.0;
  m->v_max = 40.0;
  m->v_up = 4.0;
  m->v_up_from_racket = 0;
  m->spin_rack_damping = 0.8;
  m->collision_distance = 0.3;
  switch (level) {
    case BALL_LEVEL_EASY: /* distance test, autonomous ball, friendlyFactor 1 */
      m->detect = BALL_DETECT_SPHERE;
      m->normal_mode = BALL_NORMAL_REAL;
      m->response = BALL_RESPONSE_AUTONOMOUS;
      m->friendly_factor = 1.0;
      m->effects &= ~(unsigned)BALL_EFFECT_SPIN;
      break;
    case BALL_LEVEL_MID: /* disc test with the velocity normal, mixed 0.8 */
      m->detect = BALL_DETECT_DISC;
      m->normal_mode = BALL_NORMAL_VELOCITY;
      m->response = BALL_RESPONSE_MIXED;
      m->friendly_factor = 0.8;
      m->effects &= ~(unsigned)BALL_EFFECT_SPIN;
      break;
    default: /* advanced: disc test with the real normal, physical with spin */
      m->detect = BALL_DETECT_DISC;
      m->normal_mode = BALL_NORMAL_REAL;
      m->response = BALL_RESPONSE_PHYSICAL;
      m->friendly_factor = 1.0;
      m->effects |= BALL_EFFECT_SPIN;
      break;
  }
  return BALL_OK;
}

/* ---- the racket stage of a step ---- */

typedef struct racket_hit {
  double key;          /* earliest / nearest wins */
  double t;            /* hit time, s */
  ball_vec3 q;         /* ball centre at the hit (Q), m */
  ball_vec3 face;      /* racket normal facing the ball's side (Fig. 9) */
  const ball_racket_pose *pose; /* the racket's pose now */
} racket_hit;

/* The normal the disc and swept tests use: the real one, or the velocity's
 * direction (the real one while the racket is still). */
ball_vec3 ball__racket_test_normal(const ball_model *m, const ball_racket_pose *pose) {
  double sp = ball_v3_norm(pose->velocity);
  if (m->normal_mode == BALL_NORMAL_VELOCITY && sp >= BALL__STILL_SPEED)
    return ball_v3_scale(pose->velocity, 1.0 / sp);
  return pose->normal;
}

/* Racket i's test over the frame (t_prev, t] (the sim's previous position
 * and segment; the ball at t: *s_end). */
static int test_racket(const ball_model *m, const ball__flight *fl, const ball_sim *sim, int i,
                       double t_prev, double t, const ball_state *s_end, const ball_racket_pose *old,
                       const ball_racket_pose *now, racket_hit *h) {
  const ball_state *s = s_end;
  h->pose = now;
  if (m->detect == BALL_DETECT_SPHERE) {
    if (!ball__sphere_test(s->position, now->center, m->collision_distance)) return 0;
    h->key = ball_v3_norm(ball_v3_sub(s->position, now->center));
    h->t = t;
    h->q = s->position; /* the paper: the ball position is the collision point */
    h->face = ball__racket_face_normal(ball__racket_test_normal(m, now),
                                       ball_v3_sub(sim->prev_position, old->center));
    return 1;
  }
  if (m->detect == BALL_DETECT_DISC) {
    double sfrac;
    /* the disc at R_old with its normal then, or along the racket's velocity now */
    ball_vec3 n = m->normal_mode == BALL_NORMAL_REAL ? old->normal : ball__racket_test_normal(m, now);
    if (!ball__disc_test(sim->prev_position, s->position, old->center, now->center, n,
                         m->rackets[i].radius, m->radius, &sfrac, &h->q))
      return 0;
    h->key = sfrac;
    h->t = t; /* the frame-based test: the hit is at the frame's time */
    h->face = ball__racket_face_normal(n, ball_v3_sub(sim->prev_position, old->center));
    return 1;
  }
  {
    /* swept: the ball on its segment, the disc moving linearly between the
     * two poses; from the segment's start if a static contact began it inside
     * this frame (the path before it is no longer known) */
    ball__swept_motion mo;
    double th;
    mo.flight = fl;
    mo.seg = &sim->seg;
    mo.probes_used = NULL;
    mo.ta = sim->seg.t0 > t_prev ? sim->seg.t0 : t_prev;
    mo.tb = t;
    mo.p0 = sim->prev_position;
    mo.p1 = s->position;
    mo.ball_radius = m->radius;
    mo.tc0 = t_prev;
    mo.tc1 = t;
    mo.c0 = old->center;
    mo.c1 = now->center;
    mo.disc_radius = m->rackets[i].radius;
    if (mo.ta > mo.tb) return 0;
    if (mo.ta > t_prev) { /* the segment began in this frame: the ball at its start */
      ball_state at;
      ball__eval_f(fl, mo.seg, mo.ta, &at);
      mo.p0 = at.position;
    }
    /* far from each other (nearly every frame): no probe at all */
    if (ball__swept_cannot_touch(&mo)) return 0;
    mo.n0 = ball__racket_test_normal(m, old);
    mo.n1 = ball__racket_test_normal(m, now);
    if (!ball__swept_toi(&mo, &th, &h->q, &h->face)) return 0;
    h->key = th;
    h->t = th;
    return 1;
  }
}

/* The response (section 3.1) to a hit by racket i: the new segment and the event. */
static void respond(const ball_model *m, const ball__flight *fl, ball_sim *sim, int i, double dt,
                    const racket_hit *h, ball_event *ev) {
  ball_state in;
  ball_vec3 v0, s0 = ball_v3(0.0, 0.0, 0.0), p0 = h->q;
  const ball_racket_pose *pose = h->pose;
  /* the racket velocity every response reads, its speed at most v_max (eq 7's
   * clamp): a racket is a body, however fast its samples imply it moved
   * (docs/rackets.md, "Racket speed") */
  double speed = ball_v3_norm(pose->velocity);
  ball_vec3 v_racket = speed > m->v_max ? ball_v3_scale(pose->velocity, m->v_max / speed) : pose->velocity;
  ball__eval_f(fl, &sim->seg, h->t, &in);
  if (m->response == BALL_RESPONSE_RACKET) {
    v0 = ball__response_racket(m, v_racket, h->face); /* eq 7 */
    p0 = ball_v3_add(h->q, ball_v3_scale(v0, dt));                    /* eq 7: P = Q + V0 dt */
  } else if (m->response == BALL_RESPONSE_PHYSICAL) {
    ball__response_physical(m, in.velocity, in.spin, h->face, v_racket, &v0, &s0);
  } else {
    /* eq 8, 9: the goal is the partner's racket (its estimated centre now) or
     * the racket's target point when there is no partner or it has no pose */
    ball_vec3 goal = m->rackets[i].target;
    ball_racket_pose pp;
    int partner = m->rackets[i].partner;
    double v_up = ball__response_v_up(m, v_racket);
    if (partner >= 0 && estimate(m, sim, partner, h->t, &pp) == BALL_OK) {
      /* the partner's racket, within goal_reach of target horizontally */
      double dx = pp.center.x - goal.x, dz = pp.center.z - goal.z, d = sqrt(dx * dx + dz * dz);
      double k = m->rackets[i].goal_reach / d;
      goal = d > m->rackets[i].goal_reach ? ball_v3(goal.x + dx * k, pp.center.y, goal.z + dz * k) : pp.center;
    }
    if (m->response == BALL_RESPONSE_AUTONOMOUS) {
      v0 = ball__response_autonomous(m, h->q, goal, v_up, m->friendly_factor);
    } else {
      ball_vec3 vf = ball__response_autonomous(m, h->q, goal, v_up, 1.0);
      v0 = ball__response_mixed(vf, v_racket, m->friendly_factor); /* eq 10 */
    }
  }
  ball__segment_start(&sim->seg, h->t, p0, v0, s0, 0);
  sim->next.valid = 0;
  sim->sleep = m->sleep_frames;
  ev->kind = BALL_EVENT_RACKET;
  ev->index = i;
  ev->time = h->t;
  ev->point = h->q;
  ev->velocity_in = in.velocity;
  ev->velocity_out = v0;
  ev->spin_out = s0;
  ev->sound = ball__has(m, BALL_EFFECT_SOUND) && ball_v3_norm(v0) > m->sound_threshold;
  ev->segment = sim->seg;
}

int ball__racket_stage(const ball_model *m, const ball__flight *fl, ball_sim *sim, double t_prev,
                       double dt, const ball_state *s_end, ball_event *ev) {
  ball_racket_pose now[BALL_MAX_RACKETS];
  racket_hit hits[BALL_MAX_RACKETS];
  int ok[BALL_MAX_RACKETS];
  int i, best = -1, hit = 0;
  double t = sim->time;
  for (i = 0; i < m->n_rackets; i++) {
    ball_status st = estimate(m, sim, i, t, &now[i]);
    ok[i] = st == BALL_OK ? 1 : st == BALL_ESTALE ? -1 : 0;
    if (ok[i] > 0 && !(ball_v3_finite(now[i].center) && ball_v3_finite(now[i].velocity))) ok[i] = 0;
  }
  if (sim->sleep > 0) {
    sim->sleep--; /* no racket tests for sleep_frames frames after a hit */
  } else {
    for (i = 0; i < m->n_rackets; i++) {
      ball_racket_pose estimated;
      const ball_racket_pose *old = &now[i];
      const ball_racket_track *tr = &sim->tracks[i];
      if (ok[i] < 0) sim->warnings[BALL_WARN_STALE_RACKET]++; /* stale: does not collide */
      if (ok[i] <= 0) continue;
      /* R_old: the pose the sim used at the previous frame; else the track
       * re-estimated at t_prev; else the racket counts as still */
      if (tr->has_prev)
        old = &tr->prev_pose;
      else if (estimate(m, sim, i, t_prev, &estimated) == BALL_OK)
        old = &estimated;
      if (test_racket(m, fl, sim, i, t_prev, t, s_end, old, &now[i], &hits[i]) &&
          (best < 0 || hits[i].key < hits[best].key))
        best = i;
    }
    if (best >= 0) {
      respond(m, fl, sim, best, dt, &hits[best], ev);
      hit = 1;
    }
  }
  for (i = 0; i < m->n_rackets; i++) {
    sim->tracks[i].has_prev = ok[i] > 0;
    if (ok[i] > 0) sim->tracks[i].prev_pose = now[i];
  }
  return hit;
}

int ball__racket_test_at(const ball_model *m, const ball__flight *fl, const ball_sim *sim, int i, double t,
                         double *t_hit, double *key) {
  ball_racket_pose now, estimated;
  const ball_racket_pose *old = &now;
  const ball_racket_track *tr = &sim->tracks[i];
  ball_state s;
  racket_hit h;
  /* what ball__racket_stage does for racket i with t_prev = sim->time */
  if (estimate(m, sim, i, t, &now) != BALL_OK || !(ball_v3_finite(now.center) && ball_v3_finite(now.velocity)))
    return 0;
  if (tr->has_prev)
    old = &tr->prev_pose;
  else if (estimate(m, sim, i, sim->time, &estimated) == BALL_OK)
    old = &estimated;
  ball__eval_f(fl, &sim->seg, t, &s);
  if (!test_racket(m, fl, sim, i, sim->time, t, &s, old, &now, &h)) return 0;
  if (t_hit) *t_hit = h.t;
  if (key) *key = h.key;
  return 1;
}
