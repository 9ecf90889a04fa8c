/* The stepper: one frame of flight, static obstacles, rackets. */
#include <string.h>

#include "internal.h"

#define ORIGIN_FLOOR 0
#define ORIGIN_NET 1
#define ORIGIN_WALL(i) (2 + (i))

static void emit(ball_sim *sim, ball_event *events, int cap, int *n, const ball_event *ev) {
  if (*n < cap) {
    events[(*n)++] = *ev;
  } else {
    sim->events_dropped++;
    sim->warnings[BALL_WARN_EVENT_OVERFLOW]++;
  }
}

static int sound(const ball_model *m, double speed) {
  return ball__has(m, BALL_EFFECT_SOUND) && fabs(speed) > m->sound_threshold;
}

/* eq 5 (with eq 13, 14 when spin is on): the floor bounce at time t, ball at p. */
static void floor_bounce(const ball_model *m, ball_sim *sim, double t, ball_vec3 p,
                         const ball_state *s, ball_event *ev) {
  double fd = m->floor_damping;
  ball_vec3 v0 = v3(s->velocity.x * fd, -s->velocity.y * fd, s->velocity.z * fd);
  ball_vec3 s0 = v3(0.0, 0.0, 0.0);
  int grounded = 0;
  if (ball__has(m, BALL_EFFECT_SPIN)) {
    v0 = v3_add(v0, ball__spin_floor_velocity(m, s->spin)); /* eq 13 */
    s0 = v3_scale(s->spin, m->spin_floor_damping);         /* eq 14 */
  }
  ev->kind = BALL_EVENT_FLOOR;
  ev->index = 0;
  ev->sound = sound(m, v0.y);
  /* below the bounce threshold the ball stops bouncing and slides (DESIGN 3);
   * so does a bounce too short for the clock to resolve (threshold 0) */
  if (v0.y < m->bounce_threshold || t + 2.0 * v0.y / m->gravity == t) {
    v0.y = 0.0;
    grounded = 1;
  }
  p.y = ball__floor_y(m); /* eq 5: P0 on the floor */
  ev->time = t;
  ev->point = p;
  ev->velocity_in = s->velocity;
  ev->velocity_out = v0;
  ev->spin_out = s0;
  ball__segment_start(&sim->seg, t, p, v0, s0, grounded);
  sim->origin = ORIGIN_FLOOR;
}

/* eq 6: the net (or a wall) at time t, ball at q. shift is the paper's
 * dt / 10 push along the new normal velocity (0 in exact mode). */
static void plane_bounce(const ball_model *m, ball_sim *sim, const ball_plane *pl, int origin,
                         double t, ball_vec3 q, const ball_state *s, double shift, ball_event *ev) {
  ball_vec3 v0 = s->velocity;
  if (pl->axis == 0)
    v0.x = -v0.x;
  else
    v0.z = -v0.z;
  v0 = v3_scale(v0, pl->damping);
  ev->point = q;
  if (pl->axis == 0)
    q.x += v0.x * shift;
  else
    q.z += v0.z * shift;
  ev->kind = origin == ORIGIN_NET ? BALL_EVENT_NET : BALL_EVENT_WALL;
  ev->index = origin == ORIGIN_NET ? 0 : origin - ORIGIN_WALL(0);
  ev->time = t;
  ev->velocity_in = s->velocity;
  ev->velocity_out = v0;
  ev->spin_out = s->spin;
  ev->sound = sound(m, v3_axis(v0, pl->axis));
  ball__segment_start(&sim->seg, t, q, v0, s->spin, sim->seg.grounded);
  sim->origin = origin;
}

static int in_extent(const ball_plane *pl, ball_vec3 q) {
  double h = pl->axis == 0 ? q.z : q.x;
  return h >= pl->lo && h <= pl->hi && q.y >= pl->bottom && q.y <= pl->top;
}

static const ball_plane *plane_of(const ball_model *m, int origin) {
  return origin == ORIGIN_NET ? &m->net : &m->walls[origin - ORIGIN_WALL(0)];
}

/* ---- exact scheme: contacts in closed form on the analytic path ---- */

/* First crossing of the ball's surface with the plane rectangle in
 * [tau_from, tau_to] on seg, approaching from the side the ball is on. */
static int plane_contact(const ball_model *m, const ball_segment *seg, const ball_plane *pl,
                         double b, double tau_from, double tau_to, double *tau, ball_vec3 *q) {
  int a = pl->axis;
  double v = v3_axis(seg->v0, a), target;
  ball_state s;
  if (v == 0.0) return 0;
  target = pl->position - (v > 0.0 ? m->radius : -m->radius);
  if (!ball__plane_tau(b, v3_axis(seg->p0, a), v, target, tau_from, tau) || *tau > tau_to)
    return 0;
  ball__eval(m, seg, seg->t0 + *tau, &s);
  *q = s.position;
  /* one ulp back on the approach side: a point ball restarting exactly in
   * the plane would find the same plane again at tau = 0 (docs/hard-cases.md) */
  if (a == 0)
    q->x = nextafter(target, v > 0.0 ? -INFINITY : INFINITY);
  else
    q->z = nextafter(target, v > 0.0 ? -INFINITY : INFINITY);
  return in_extent(pl, *q);
}

static int floor_contact(const ball_model *m, const ball_segment *seg, double tau_from,
                         double tau_to, double *tau) {
  double r1, r2, y_end;
  if (seg->grounded) return 0;
  /* a response that put the ball below the floor (eq 7's restart at Q + V0 dt
   * can) while it moves down: it bounces at once instead of sinking */
  if (seg->p0.y + seg->v0.y * tau_from - 0.5 * m->gravity * tau_from * tau_from < ball__floor_y(m) &&
      seg->v0.y - m->gravity * tau_from <= 0.0) {
    *tau = tau_from;
    return 1;
  }
  if (!ball__height_roots(m->gravity, seg->p0.y, seg->v0.y, ball__floor_y(m), &r1, &r2)) return 0;
  if (r2 < tau_from) return 0;
  if (r2 > tau_to) {
    /* a root rounded just past the frame's end while y there is already below: contact now */
    y_end = seg->p0.y + seg->v0.y * tau_to - 0.5 * m->gravity * tau_to * tau_to;
    if (!(y_end < ball__floor_y(m)) || seg->v0.y - m->gravity * tau_to > 0.0) return 0;
    r2 = tau_to;
  }
  *tau = r2;
  return 1;
}

static void step_exact(const ball_model *m, ball_sim *sim, double t_from, double t_end,
                       ball_event *events, int cap, int *n) {
  double b = ball__drag_b(m);
  double t_cur = t_from;
  int contacts;
  for (contacts = 0; contacts < BALL_MAX_CONTACTS; contacts++) {
    const ball_segment *seg = &sim->seg;
    double tau_from = t_cur - seg->t0, tau_to = t_end - seg->t0, tau, best = INFINITY;
    int which = -1, i;
    ball_vec3 q, best_q = v3(0.0, 0.0, 0.0);
    ball_state s;
    ball_event ev;
    if (ball__has(m, BALL_EFFECT_FLOOR) && floor_contact(m, seg, tau_from, tau_to, &tau)) {
      best = tau;
      which = ORIGIN_FLOOR;
    }
    if (ball__has(m, BALL_EFFECT_NET) && m->has_net &&
        plane_contact(m, seg, &m->net, b, tau_from, tau_to, &tau, &q) && tau < best) {
      best = tau;
      best_q = q;
      which = ORIGIN_NET;
    }
    if (ball__has(m, BALL_EFFECT_WALLS))
      for (i = 0; i < m->n_walls; i++)
        if (plane_contact(m, seg, &m->walls[i], b, tau_from, tau_to, &tau, &q) && tau < best) {
          best = tau;
          best_q = q;
          which = ORIGIN_WALL(i);
        }
    if (which < 0) return;
    t_cur = seg->t0 + best;
    ball__eval(m, seg, t_cur, &s);
    if (which == ORIGIN_FLOOR)
      floor_bounce(m, sim, t_cur, s.position, &s, &ev);
    else
      plane_bounce(m, sim, plane_of(m, which), which, t_cur, best_q, &s, 0.0, &ev);
    emit(sim, events, cap, n, &ev);
  }
  /* Too many contacts (a ball trapped in a corner): rather than let it escape
   * through an obstacle, it stays where its last contact left it and loses
   * the rest of the frame. */
  {
    ball_segment *seg = &sim->seg;
    ball_state s;
    ball__eval(m, seg, t_cur, &s);
    ball__segment_start(seg, t_end, s.position, s.velocity, s.spin, seg->grounded);
  }
  sim->warnings[BALL_WARN_CONTACT_LIMIT]++;
}

/* ---- sampled scheme: the paper's per-frame tests (Fig. 1, Fig. 3) ---- */

/* Fig. 3: the segment p_old -> p against the plane (moved by the radius
 * toward p_old); *s is where along the segment it crosses. */
static int plane_crossing(const ball_model *m, const ball_plane *pl, ball_vec3 p_old, ball_vec3 p,
                          double *s, ball_vec3 *q) {
  int a = pl->axis;
  double xo = v3_axis(p_old, a), x = v3_axis(p, a), target;
  if (xo == x) return 0; /* segment parallel to the plane */
  target = pl->position - (x > xo ? m->radius : -m->radius);
  *s = (target - xo) / (x - xo);
  if (!(*s >= 0.0 && *s <= 1.0)) return 0;
  *q = v3_lerp(p_old, p, *s);
  if (a == 0)
    q->x = target;
  else
    q->z = target;
  return in_extent(pl, *q);
}

static void step_sampled(const ball_model *m, ball_sim *sim, double t_end, double dt,
                         ball_event *events, int cap, int *n) {
  ball_state st;
  ball_event ev;
  ball_vec3 q, best_q = v3(0.0, 0.0, 0.0);
  double s, best = INFINITY;
  int i, origin = -1;
  ball__eval(m, &sim->seg, t_end, &st);
  /* the first plane the frame's segment crosses (one plane collision a frame) */
  if (ball__has(m, BALL_EFFECT_NET) && m->has_net &&
      plane_crossing(m, &m->net, sim->prev_position, st.position, &s, &q)) {
    best = s;
    best_q = q;
    origin = ORIGIN_NET;
  }
  if (ball__has(m, BALL_EFFECT_WALLS))
    for (i = 0; i < m->n_walls; i++)
      if (plane_crossing(m, &m->walls[i], sim->prev_position, st.position, &s, &q) && s < best) {
        best = s;
        best_q = q;
        origin = ORIGIN_WALL(i);
      }
  if (origin >= 0) {
    /* eq 6: velocity now, restart at Q pushed dt / 10 along the new velocity */
    plane_bounce(m, sim, plane_of(m, origin), origin, t_end, best_q, &st, dt / 10.0, &ev);
    emit(sim, events, cap, n, &ev);
    ball__eval(m, &sim->seg, t_end, &st);
  }
/* Fig. 1, eq 5: below the floor at the end of the frame */
  if (ball__has(m, BALL_EFFECT_FLOOR) && !sim->seg.grounded && st.position.y < ball__floor_y(m)) {
    floor_bounce(m, sim, t_end, st.position, &st, &ev);
    emit(sim, events, cap, n, &ev);
  }
}

/* ---- public ---- */

static int segment_finite(const ball_segment *seg) {
  return isfinite(seg->t0) && v3_finite(seg->p0) && v3_finite(seg->v0) && v3_finite(seg->s0);
}

static ball_status check_state(const ball_model *m, const ball_state *state) {
  if (!v3_finite(state->position) || !v3_finite(state->velocity) || !v3_finite(state->spin))
    return BALL_ENONFINITE;
  if (ball__has(m, BALL_EFFECT_FLOOR) && state->position.y < ball__floor_y(m)) return BALL_ERANGE;
  return BALL_OK;
}

static void start_state(const ball_model *m, ball_sim *sim, const ball_state *state) {
  ball_vec3 spin = ball__has(m, BALL_EFFECT_SPIN) ? state->spin : v3(0.0, 0.0, 0.0);
  ball__segment_start(&sim->seg, sim->time, state->position, state->velocity, spin, 0);
  sim->prev_position = state->position;
  sim->origin = -1;
}

ball_status ball_sim_init(const ball_model *m, ball_sim *sim) {
  ball_state st0;
  ball_status st;
  int r;
  if (!m || !sim) return BALL_EINVAL;
  st = ball_model_check(m, NULL);
  if (st != BALL_OK) return st;
  memset(sim, 0, sizeof *sim);
  sim->last_racket = -1;
  for (r = 0; r < BALL_MAX_RACKETS; r++) sim->tracks[r].count = 0;
  st0.position = m->initial_position;
  st0.velocity = m->initial_velocity;
  st0.spin = m->initial_spin;
  start_state(m, sim, &st0);
  return BALL_OK;
}

ball_status ball_sim_set_state(const ball_model *m, ball_sim *sim, const ball_state *state) {
  ball_status st;
  if (!m || !sim || !state) return BALL_EINVAL;
  st = ball_model_check(m, NULL);
  if (st != BALL_OK) return st;
  st = check_state(m, state);
  if (st != BALL_OK) return st;
  start_state(m, sim, state);
  return BALL_OK;
}

ball_status ball_sim_state(const ball_model *m, const ball_sim *sim, ball_state *out) {
  if (!m || !sim || !out) return BALL_EINVAL;
  if (!isfinite(sim->time) || !segment_finite(&sim->seg)) return BALL_ENONFINITE;
  if (sim->time < sim->seg.t0) return BALL_ERANGE;
  ball__eval(m, &sim->seg, sim->time, out);
  return BALL_OK;
}

/* What a step changes besides the clock, kept to undo a refused frame (the
 * track samples are not touched by a step, so the whole sim is not copied). */
typedef struct step_undo {
  ball_segment seg;
  int origin, sleep, last_racket;
  unsigned long warnings[BALL_WARN_COUNT], events_dropped;
  int has_prev[BALL_MAX_RACKETS];
  ball_racket_pose prev_pose[BALL_MAX_RACKETS];
} step_undo;

static void undo_save(step_undo *u, const ball_sim *sim) {
  int r;
  u->seg = sim->seg;
  u->origin = sim->origin;
  u->sleep = sim->sleep;
  u->last_racket = sim->last_racket;
  memcpy(u->warnings, sim->warnings, sizeof u->warnings);
  u->events_dropped = sim->events_dropped;
  for (r = 0; r < BALL_MAX_RACKETS; r++) {
    u->has_prev[r] = sim->tracks[r].has_prev;
    u->prev_pose[r] = sim->tracks[r].prev_pose;
  }
}

static void undo_restore(const step_undo *u, ball_sim *sim, double t) {
  int r;
  sim->time = t;
  sim->seg = u->seg;
  sim->origin = u->origin;
  sim->sleep = u->sleep;
  sim->last_racket = u->last_racket;
  memcpy(sim->warnings, u->warnings, sizeof u->warnings);
  sim->events_dropped = u->events_dropped;
  for (r = 0; r < BALL_MAX_RACKETS; r++) {
    sim->tracks[r].has_prev = u->has_prev[r];
    sim->tracks[r].prev_pose = u->prev_pose[r];
  }
}

static int events_finite(const ball_event *ev, int n) {
  int i;
  for (i = 0; i < n; i++)
    if (!isfinite(ev[i].time) || !v3_finite(ev[i].point) || !v3_finite(ev[i].velocity_in) ||
        !v3_finite(ev[i].velocity_out) || !v3_finite(ev[i].spin_out))
      return 0;
  return 1;
}

ball_status ball_step(const ball_model *m, ball_sim *sim, double dt, ball_event *events, int cap,
                      int *n_events) {
  ball_status st;
  double t_prev, t_end;
  int n = 0;
  ball_state s;
  step_undo undo;
  if (n_events) *n_events = 0;
  if (!m || !sim || cap < 0 || (cap > 0 && !events)) return BALL_EINVAL;
  if (!isfinite(dt)) return BALL_ENONFINITE;
  if (dt < 0.0) return BALL_ERANGE;
  st = ball__model_check_stages(m, m->effects, NULL);
  if (st != BALL_OK) return st;
  if (!isfinite(sim->time) || !segment_finite(&sim->seg) || !v3_finite(sim->prev_position))
    return BALL_ENONFINITE;
  t_prev = sim->time;
  t_end = t_prev + dt;
  if (!isfinite(t_end) || sim->seg.t0 > t_prev) return BALL_ERANGE;
  if (dt == 0.0) return BALL_OK;
  /* a frame whose flight would overflow is refused before anything changes */
  ball__eval(m, &sim->seg, t_end, &s);
  if (!v3_finite(s.position) || !v3_finite(s.velocity) || !v3_finite(s.spin)) return BALL_ERANGE;
  undo_save(&undo, sim);

  if (m->scheme == BALL_SCHEME_EXACT)
    step_exact(m, sim, t_prev, t_end, events, cap, &n);
  else
    step_sampled(m, sim, t_end, dt, events, cap, &n);
  sim->time = t_end;

  if (ball__has(m, BALL_EFFECT_RACKETS) && m->n_rackets > 0) {
    ball_event ev;
    if (ball__racket_stage(m, sim, t_prev, dt, &ev)) {
      sim->origin = 2 + BALL_MAX_WALLS + ev.index;
      emit(sim, events, cap, &n, &ev);
      /* the rest of the frame on the new path (a swept hit lands inside it) */
      if (m->scheme == BALL_SCHEME_EXACT && ev.time < t_end)
        step_exact(m, sim, ev.time, t_end, events, cap, &n);
    }
  }
  ball__eval(m, &sim->seg, t_end, &s);
  /* a response that overflowed (speeds near DBL_MAX): refuse the frame and
   * give the sim back as it was */
  if (!segment_finite(&sim->seg) || !v3_finite(s.position) || !v3_finite(s.velocity) ||
      !v3_finite(s.spin) || !events_finite(events, n)) {
    undo_restore(&undo, sim, t_prev);
    return BALL_ERANGE;
  }
  sim->prev_position = s.position;
  sim->frame++;
  if (n_events) *n_events = n;
  return BALL_OK;
}

/* FNV-1a over the state that decides the ball's future. */
static unsigned long long hash_bytes(unsigned long long h, const void *data, size_t len) {
  const unsigned char *p = (const unsigned char *)data;
  size_t i;
  for (i = 0; i < len; i++) {
    h ^= p[i];
    h *= 1099511628211ULL;
  }
  return h;
}

static unsigned long long hash_double(unsigned long long h, double v) {
  if (v == 0.0) v = 0.0; /* -0 and +0 hash alike */
  return hash_bytes(h, &v, sizeof v);
}

static unsigned long long hash_vec(unsigned long long h, ball_vec3 v) {
  return hash_double(hash_double(hash_double(h, v.x), v.y), v.z);
}

unsigned long long ball_sim_hash(const ball_sim *sim) {
  unsigned long long h = 14695981039346656037ULL;
  long ints[4];
  int r, i;
  if (!sim) return 0;
  h = hash_double(h, sim->time);
  h = hash_double(h, sim->seg.t0);
  h = hash_vec(h, sim->seg.p0);
  h = hash_vec(h, sim->seg.v0);
  h = hash_vec(h, sim->seg.s0);
  h = hash_vec(h, sim->prev_position);
  ints[0] = sim->seg.grounded;
  ints[1] = sim->sleep;
  ints[2] = sim->last_racket;
  ints[3] = (long)sim->frame;
  h = hash_bytes(h, ints, sizeof ints);
  for (r = 0; r < BALL_MAX_RACKETS; r++) {
    const ball_racket_track *tr = &sim->tracks[r];
    h = hash_bytes(h, &tr->count, sizeof tr->count);
    for (i = 0; i < tr->count && i < BALL_MAX_HISTORY; i++) {
      h = hash_double(h, tr->samples[i].t);
      h = hash_vec(h, tr->samples[i].center);
      h = hash_vec(h, tr->samples[i].normal);
    }
  }
  return h;
}
