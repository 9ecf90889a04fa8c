/* The stepper: one frame of flight, static obstacles, rackets; and the
 * prediction, which shares the exact scheme's contact code. */
#include <string.h>

#include "internal.h"

#define WHICH_NONE -1
#define WHICH_FLOOR 0
#define WHICH_NET 1
#define WHICH_WALL(i) (2 + (i))

/* Where events go: the caller's array; what does not fit is counted. */
typedef struct sink {
  ball_event *events;
  int cap;
  int n;
  unsigned long *missed;
} sink;

static void emit(sink *k, const ball_event *ev) {
  if (k->n < k->cap)
    k->events[k->n++] = *ev;
  else
    (*k->missed)++;
}

static int sound(const ball_model *m, double speed) {
  return ball__has(m, BALL_EFFECT_SOUND) && fabs(speed) > m->sound_threshold;
}

/* eq 5 (with eq 13, 14 when spin is on): the floor bounce at time t, ball at p. */
static void floor_bounce(const ball_model *m, ball_segment *seg, double t, ball_vec3 p,
                         const ball_state *s, ball_event *ev) {
  double fd = m->floor_damping;
  ball_vec3 v0 = ball_v3(s->velocity.x * fd, -s->velocity.y * fd, s->velocity.z * fd);
  ball_vec3 s0 = ball_v3(0.0, 0.0, 0.0);
  int grounded = 0;
  if (ball__has(m, BALL_EFFECT_SPIN)) {
    v0 = ball_v3_add(v0, ball__spin_floor_velocity(m, s->spin)); /* eq 13 */
    s0 = ball_v3_scale(s->spin, m->spin_floor_damping);         /* eq 14 */
  }
  ev->kind = BALL_EVENT_FLOOR;
  ev->index = 0;
  ev->sound = sound(m, v0.y);
  /* below the bounce threshold the ball stops bouncing and slides (docs/design.md R4);
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
  ball__segment_start(seg, t, p, v0, s0, grounded);
  ev->segment = *seg;
}

/* eq 6: the velocity after the net (or a wall): the normal component
 * reversed, all times netDamping. n is the contact normal of an edge or a
 * corner (the grown rectangle's); zero for the face, where the reversal is
 * the plane's axis exactly as the paper writes it. */
static ball_vec3 plane_reflect(const ball_plane *pl, ball_vec3 n, ball_vec3 v) {
  if (n.x == 0.0 && n.y == 0.0 && n.z == 0.0) {
    if (pl->axis == 0)
      v.x = -v.x;
    else
      v.z = -v.z;
  } else if (ball_v3_dot(v, n) < 0.0) {
    /* only a velocity into the edge turns: the sampled scheme finds the
     * contact on the frame's chord but responds with the velocity at the
     * frame's end (eq 6), which gravity may already have turned away from
     * an edge's slanted normal; reversing that would send the ball in */
    v = ball_v3_sub(v, ball_v3_scale(n, 2.0 * ball_v3_dot(v, n)));
  }
  return ball_v3_scale(v, pl->damping);
}

/* The unit normal a contact's response turns about: n, or the axis. */
static ball_vec3 plane_normal(const ball_plane *pl, ball_vec3 n) {
  if (n.x != 0.0 || n.y != 0.0 || n.z != 0.0) return n;
  return pl->axis == 0 ? ball_v3(1.0, 0.0, 0.0) : ball_v3(0.0, 0.0, 1.0);
}

/* eq 6 at time t: the event at the centre q, the new segment from r with
 * v0 (plane_reflect's) and the arriving spin. n is the unit normal the
 * response turned about; rim: an edge's or corner's contact. */
static void plane_bounce(const ball_model *m, ball_segment *seg, int which, ball_vec3 n, int rim, double t,
                         ball_vec3 q, ball_vec3 r, const ball_state *s, ball_vec3 v0, ball_event *ev) {
  /* a grounded ball stays on the floor unless an edge sends it up or down */
  int grounded = seg->grounded && v0.y == 0.0;
  if (rim && n.y > 0.0 && ball_v3_dot(v0, n) < m->bounce_threshold) {
    /* on a top edge, too slow to bounce off it (the floor's threshold, eq 5):
     * the ball comes to rest there, balanced, instead of bouncing ever
     * smaller within one instant (docs/model.md) */
    v0 = ball_v3(0.0, 0.0, 0.0);
    r = q;
    /* a sampled frame may find the edge at a chord point under the floor: the
     * floor holds the resting ball, as it holds a grounded one */
    if (ball__has(m, BALL_EFFECT_FLOOR) && r.y < ball__floor_y(m)) r.y = ball__floor_y(m);
    grounded = 1;
  }
  ev->kind = which == WHICH_NET ? BALL_EVENT_NET : BALL_EVENT_WALL;
  ev->index = which == WHICH_NET ? 0 : which - WHICH_WALL(0);
  ev->time = t;
  ev->point = q;
  ev->velocity_in = s->velocity;
  ev->velocity_out = v0;
  ev->spin_out = s->spin;
  ev->sound = sound(m, ball_v3_dot(v0, n));
  ball__segment_start(seg, t, r, v0, s->spin, grounded);
  ev->segment = *seg;
}

static const ball_plane *plane_of(const ball_model *m, int which) {
  return which == WHICH_NET ? &m->net : &m->walls[which - WHICH_WALL(0)];
}

/* ---- exact scheme: contacts in closed form on the analytic path ---- */

static double height(const ball_model *m, const ball_segment *seg, double tau) {
  return seg->p0.y + seg->v0.y * tau - 0.5 * m->gravity * tau * tau;
}

/* The descending floor contact at tau >= tau_from. */
static int floor_contact(const ball_model *m, const ball_segment *seg, double tau_from, double *tau) {
  double r1, r2;
  if (seg->grounded) return 0;
  /* a response that put the ball below the floor (eq 7's restart at Q + V0 dt
   * can) while it moves down: it bounces at once instead of sinking */
  if (height(m, seg, tau_from) < ball__floor_y(m) && seg->v0.y - m->gravity * tau_from <= 0.0) {
    *tau = tau_from;
    return 1;
  }
  if (!ball__height_roots(m->gravity, seg->p0.y, seg->v0.y, ball__floor_y(m), &r1, &r2)) return 0;
  if (r2 < tau_from) return 0;
  *tau = r2;
  return 1;
}

/* The earliest static contact on seg at or after t_from: into *c. */
static void find_next(const ball_model *m, const ball__flight *fl, const ball_segment *seg,
                      double t_from, ball_contact *c) {
  double tau_from = t_from - seg->t0, tau, best = INFINITY;
  ball_vec3 q, n, best_q = ball_v3(0.0, 0.0, 0.0), best_n = ball_v3(0.0, 0.0, 0.0);
  int i, which = WHICH_NONE;
  if (ball__has(m, BALL_EFFECT_FLOOR) && floor_contact(m, seg, tau_from, &tau)) {
    best = tau;
    which = WHICH_FLOOR;
  }
  if (ball__has(m, BALL_EFFECT_NET) && m->has_net &&
      ball__plane_contact(m, fl, seg, &m->net, tau_from, best, &tau, &q, &n) && tau < best) {
    best = tau;
    best_q = q;
    best_n = n;
    which = WHICH_NET;
  }
  if (ball__has(m, BALL_EFFECT_WALLS))
    for (i = 0; i < m->n_walls; i++)
      if (ball__plane_contact(m, fl, seg, &m->walls[i], tau_from, best, &tau, &q, &n) && tau < best) {
        best = tau;
        best_q = q;
        best_n = n;
        which = WHICH_WALL(i);
      }
  c->valid = 1;
  c->which = which;
  c->time = which == WHICH_NONE ? INFINITY : seg->t0 + best;
  c->point = best_q;
  c->normal = best_n;
}

/* The contact c on seg: its response starts the next segment. */
static void resolve(const ball_model *m, const ball__flight *fl, ball_segment *seg,
                    const ball_contact *c, ball_event *ev) {
  ball_state s;
  ball__eval_f(fl, seg, c->time, &s);
  if (c->which == WHICH_FLOOR) {
    floor_bounce(m, seg, c->time, s.position, &s, ev);
  } else {
    const ball_plane *pl = plane_of(m, c->which);
    int rim = ball_v3_norm(c->normal) > 0.0;
    /* an edge's or corner's centre is the search's, at the contact's tau:
     * the clock rounds c->time (by 1.2e-7 s at 1e9 s), and the path there
     * may already be inside the edge (where a ball too slow to bounce rests) */
    plane_bounce(m, seg, c->which, plane_normal(pl, c->normal), rim, c->time, rim ? c->point : s.position, c->point,
                 &s, plane_reflect(pl, c->normal, s.velocity), ev);
  }
}

/* The exact scheme over (t_from, t_end] on seg, next being seg's cached next
 * contact (computed here when not valid): every contact in time order, up to
 * BALL_MAX_CONTACTS; *end gets the state at t_end. Returns the contacts
 * resolved, or -1 when the limit was reached. */
static int exact_advance(const ball_model *m, const ball__flight *fl, ball_segment *seg,
                         ball_contact *next, double t_from, double t_end, sink *k, ball_state *end) {
  int contacts;
  double t_cur = t_from;
  for (contacts = 0; contacts < BALL_MAX_CONTACTS; contacts++) {
    ball_event ev;
    if (!next->valid) find_next(m, fl, seg, t_cur, next);
    if (!(next->time <= t_end)) {
      ball__eval_f(fl, seg, t_end, end);
      /* a floor root rounded just past the frame's end while the ball there
       * is already below the floor: the contact is now */
      if (!(next->which == WHICH_FLOOR && end->position.y < ball__floor_y(m) && end->velocity.y <= 0.0))
        return contacts;
      next->time = t_end;
    }
    t_cur = next->time;
    resolve(m, fl, seg, next, &ev);
    emit(k, &ev);
    next->valid = 0;
  }
  /* Too many contacts (a ball trapped in a corner): rather than let it escape
   * through an obstacle, it stays where its last contact left it and loses
   * the rest of the frame. */
  ball__eval_f(fl, seg, t_cur, end);
  ball__segment_start(seg, t_end, end->position, end->velocity, end->spin, seg->grounded);
  next->valid = 0;
  ball__eval_f(fl, seg, t_end, end);
  return -1;
}

/* ---- sampled scheme: the paper's per-frame tests (Fig. 1, Fig. 3) ---- */

/* The first plane (net or wall, but not `skip`) the segment from p0 to p1
 * touches, at the fraction *s along it; WHICH_NONE if none. */
static int first_plane_on(const ball_model *m, ball_vec3 p0, ball_vec3 p1, int skip, double *s, ball_vec3 *q,
                          ball_vec3 *n) {
  double f, best = INFINITY;
  ball_vec3 qq, nn;
  int i, which = WHICH_NONE;
  if (ball__has(m, BALL_EFFECT_NET) && m->has_net && skip != WHICH_NET &&
      ball__plane_chord(m, &m->net, p0, p1, &f, &qq, &nn)) {
    best = f;
    *q = qq;
    *n = nn;
    which = WHICH_NET;
  }
  if (ball__has(m, BALL_EFFECT_WALLS))
    for (i = 0; i < m->n_walls; i++)
      if (skip != WHICH_WALL(i) && ball__plane_chord(m, &m->walls[i], p0, p1, &f, &qq, &nn) && f < best) {
        best = f;
        *q = qq;
        *n = nn;
        which = WHICH_WALL(i);
      }
  *s = best;
  return which;
}

/* One sampled frame ending at t_end, *st the state there (updated on a
 * collision). Returns the collisions. */
static int step_sampled(const ball_model *m, const ball__flight *fl, ball_sim *sim, double t_end,
                        double dt, sink *k, ball_state *st) {
  ball_event ev;
  ball_vec3 q = ball_v3(0.0, 0.0, 0.0), nrm = ball_v3(0.0, 0.0, 0.0);
  double s;
  int which, n = 0;
  ball_vec3 p_end = st->position;
  /* the first plane the frame's segment touches (one plane collision a
   * frame). A point ball's segment is Fig. 3's, P_old -> P, exactly. A ball
   * with a radius has edges to meet (docs/model.md, "Ball radius, edges and
   * corners"): its segment ends where the ball is shown, on the floor if it
   * fell below (Fig. 1's snap), since under a low edge a chord that dips
   * below the floor would pass where the ball cannot be, and the snap would
   * then lift the ball into the edge */
  if (m->radius > 0.0 && ball__has(m, BALL_EFFECT_FLOOR) && p_end.y < ball__floor_y(m)) p_end.y = ball__floor_y(m);
  which = first_plane_on(m, sim->prev_position, p_end, WHICH_NONE, &s, &q, &nrm);
  if (which != WHICH_NONE) {
    /* eq 6: velocity now, restart at Q pushed dt / 10 along the new normal
     * velocity, horizontally as the paper's (V0x dt / 10, 0, 0): a lift off
     * a top edge would add potential energy; with long frames that push can
     * be metres, so it stops short of any other plane it would reach (the
     * paper's push keeps the ball out of the net, never through a wall
     * behind it) */
    const ball_plane *pl = plane_of(m, which);
    ball_vec3 un = plane_normal(pl, nrm), v0 = plane_reflect(pl, nrm, st->velocity), r, qs, ns, push;
    double f;
    push = ball_v3_scale(un, ball_v3_dot(v0, un) * dt / 10.0);
    push.y = 0.0;
    r = ball_v3_add(q, push);
    if (first_plane_on(m, q, r, which, &f, &qs, &ns) != WHICH_NONE && f <= 1.0) r = ball_v3_lerp(q, r, 0.5 * f);
    plane_bounce(m, &sim->seg, which, un, ball_v3_norm(nrm) > 0.0, t_end, q, r, st, v0, &ev);
    emit(k, &ev);
    ball__eval_f(fl, &sim->seg, t_end, st);
    n++;
  }
  /* Fig. 1, eq 5: below the floor at the end of the frame */
  if (ball__has(m, BALL_EFFECT_FLOOR) && !sim->seg.grounded && st->position.y < ball__floor_y(m)) {
    floor_bounce(m, &sim->seg, t_end, st->position, st, &ev);
    emit(k, &ev);
    ball__eval_f(fl, &sim->seg, t_end, st);
    n++;
  }
  return n;
}

/* ---- the sim ---- */

static int segment_finite(const ball_segment *seg) {
  return isfinite(seg->t0) && ball_v3_finite(seg->p0) && ball_v3_finite(seg->v0) &&
         ball_v3_finite(seg->s0);
}

static int state_finite_each(const ball_state *s) {
  return ball_v3_finite(s->position) && ball_v3_finite(s->velocity) && ball_v3_finite(s->spin);
}

/* Every number of s finite: their sum is (an infinity or a NaN stays in
 * it); only a sum that overflows asks each (a check per state of a
 * prediction, at half the operations). */
static inline int state_finite(const ball_state *s) {
  double z = (s->position.x + s->position.y + s->position.z) + (s->velocity.x + s->velocity.y + s->velocity.z) +
             (s->spin.x + s->spin.y + s->spin.z);
  return z - z == 0.0 || state_finite_each(s);
}

static ball_status check_state(const ball_model *m, const ball_state *state) {
  if (!state_finite(state)) return BALL_ENONFINITE;
  if (ball_v3_max_abs(state->position) > BALL_MAX_COORD || ball_v3_max_abs(state->velocity) > BALL_MAX_SPEED ||
      ball_v3_max_abs(state->spin) > BALL_MAX_SPEED)
    return BALL_ERANGE;
  if (ball__has(m, BALL_EFFECT_FLOOR) && state->position.y < ball__floor_y(m)) return BALL_ERANGE;
  return BALL_OK;
}

static void start_state(const ball_model *m, ball_sim *sim, const ball_state *state) {
  ball_vec3 spin = ball__has(m, BALL_EFFECT_SPIN) ? state->spin : ball_v3(0.0, 0.0, 0.0);
  ball__segment_start(&sim->seg, sim->time, state->position, state->velocity, spin, 0);
  sim->next.valid = 0;
  sim->prev_position = state->position;
}

ball_status ball_sim_init(ball_sim *sim, const ball_model *m) {
  ball_state st0;
  ball_status st;
  if (!m || !sim) return BALL_EINVAL;
  st = ball_model_check(m, NULL);
  if (st != BALL_OK) return st;
  memset(sim, 0, sizeof *sim);
  sim->model = *m;
  st0.position = m->initial_position;
  st0.velocity = m->initial_velocity;
  st0.spin = m->initial_spin;
  start_state(m, sim, &st0);
  return BALL_OK;
}

const ball_model *ball_sim_model(const ball_sim *sim) { return sim ? &sim->model : NULL; }

ball_status ball_sim_set_model(ball_sim *sim, const ball_model *m) {
  ball_status st;
  ball_state now;
  int r;
  if (!m || !sim) return BALL_EINVAL;
  st = ball_model_check(m, NULL);
  if (st != BALL_OK) return st;
  if (!isfinite(sim->time) || !segment_finite(&sim->seg)) return BALL_ENONFINITE;
  if (sim->time < sim->seg.t0) return BALL_ERANGE;
  /* the ball where it is now (by the model it flew under) must be a valid
   * state of the new model, which takes over from now: a new segment starts
   * here, so new drag, gravity or spin damping act from this time on, not
   * over the segment's past */
  ball__eval(&sim->model, &sim->seg, sim->time, &now);
  st = check_state(m, &now);
  if (st != BALL_OK) return st;
  {
    int grounded = sim->seg.grounded && ball__has(m, BALL_EFFECT_FLOOR) && now.position.y == ball__floor_y(m);
    ball_vec3 spin = ball__has(m, BALL_EFFECT_SPIN) ? now.spin : ball_v3(0.0, 0.0, 0.0);
    if (grounded) now.velocity.y = 0.0;
    sim->model = *m;
    ball__segment_start(&sim->seg, sim->time, now.position, now.velocity, spin, grounded);
  }
  sim->next.valid = 0;
  for (r = 0; r < BALL_MAX_RACKETS; r++) {
    ball_racket_track *tr = &sim->tracks[r];
    if (r >= m->n_rackets) {
      memset(tr, 0, sizeof *tr);
    } else if (tr->count > m->history) {
      /* keep the newest samples that fit the new history */
      memmove(tr->samples, tr->samples + (tr->count - m->history),
              (size_t)m->history * sizeof tr->samples[0]);
      tr->count = m->history;
    }
  }
  return BALL_OK;
}

ball_status ball_sim_set_state(ball_sim *sim, const ball_state *state) {
  ball_status st;
  if (!sim || !state) return BALL_EINVAL;
  st = check_state(&sim->model, state);
  if (st != BALL_OK) return st;
  start_state(&sim->model, sim, state);
  return BALL_OK;
}

ball_status ball_sim_set_segment(ball_sim *sim, const ball_segment *seg, double time) {
  const ball_model *m;
  ball_state start, now;
  ball_status st;
  if (!sim || !seg) return BALL_EINVAL;
  m = &sim->model;
  if (!isfinite(time) || !segment_finite(seg)) return BALL_ENONFINITE;
  if (seg->grounded != 0 && seg->grounded != 1) return BALL_EINVAL;
  if (time < seg->t0 || ball_v3_max_abs(seg->p0) > BALL_MAX_COORD) return BALL_ERANGE;
  start.position = seg->p0;
  start.velocity = seg->v0;
  start.spin = seg->s0;
  if ((st = check_state(m, &start)) != BALL_OK) return st;
  /* a grounded ball slides on the floor: there, with no vertical speed */
  if (seg->grounded && (!ball__has(m, BALL_EFFECT_FLOOR) || seg->p0.y != ball__floor_y(m) || seg->v0.y != 0.0))
    return BALL_ERANGE;
  ball__eval(m, seg, time, &now);
  if ((st = check_state(m, &now)) != BALL_OK) return st;
  sim->time = time;
  sim->seg = *seg;
  if (!ball__has(m, BALL_EFFECT_SPIN)) sim->seg.s0 = ball_v3(0.0, 0.0, 0.0);
  sim->next.valid = 0;
  sim->prev_position = now.position;
  sim->sleep = 0;
  return BALL_OK;
}

ball_status ball_sim_set_sleep(ball_sim *sim, int frames) {
  if (!sim) return BALL_EINVAL;
  if (frames < 0 || frames > sim->model.sleep_frames) return BALL_ERANGE;
  sim->sleep = frames; /* section 3.1: no racket tests for these frames */
  return BALL_OK;
}

ball_status ball_sim_state(const ball_sim *sim, ball_state *out) {
  if (!sim || !out) return BALL_EINVAL;
  if (!isfinite(sim->time) || !segment_finite(&sim->seg)) return BALL_ENONFINITE;
  if (sim->time < sim->seg.t0) return BALL_ERANGE;
  ball__eval(&sim->model, &sim->seg, sim->time, out);
  return BALL_OK;
}

/* What a step changes besides the clock, kept to undo a refused frame (the
 * track samples are not touched by a step, so the whole sim is not copied;
 * of the tracks only the prev poses of the rackets the stage tests). */
typedef struct step_undo {
  ball_segment seg;
  ball_contact next;
  int sleep, n_tracks;
  unsigned long warnings[BALL_WARN_COUNT];
  int has_prev[BALL_MAX_RACKETS];
  ball_racket_pose prev_pose[BALL_MAX_RACKETS];
} step_undo;

static void undo_save(step_undo *u, const ball_sim *sim) {
  int r;
  u->seg = sim->seg;
  u->next = sim->next;
  u->sleep = sim->sleep;
  memcpy(u->warnings, sim->warnings, sizeof u->warnings);
  u->n_tracks = sim->model.effects & BALL_EFFECT_RACKETS ? sim->model.n_rackets : 0;
  for (r = 0; r < u->n_tracks; r++) {
    u->has_prev[r] = sim->tracks[r].has_prev;
    u->prev_pose[r] = sim->tracks[r].prev_pose;
  }
}

static void undo_restore(const step_undo *u, ball_sim *sim, double t) {
  int r;
  sim->time = t;
  sim->seg = u->seg;
  sim->next = u->next;
  sim->sleep = u->sleep;
  memcpy(sim->warnings, u->warnings, sizeof u->warnings);
  for (r = 0; r < u->n_tracks; r++) {
    sim->tracks[r].has_prev = u->has_prev[r];
    sim->tracks[r].prev_pose = u->prev_pose[r];
  }
}

static int events_finite(const ball_event *ev, int n) {
  int i;
  for (i = 0; i < n; i++)
    if (!isfinite(ev[i].time) || !ball_v3_finite(ev[i].point) || !ball_v3_finite(ev[i].velocity_in) ||
        !ball_v3_finite(ev[i].velocity_out) || !ball_v3_finite(ev[i].spin_out) ||
        !segment_finite(&ev[i].segment))
      return 0;
  return 1;
}

ball_status ball_step(ball_sim *sim, double dt, ball_event *events, int cap, int *n_events) {
  const ball_model *m;
  double t_prev, t_end;
  int changed = 0;
  ball_state s;
  ball__flight fl;
  step_undo undo;
  sink k;
  if (n_events) *n_events = 0;
  if (!sim || cap < 0 || (cap > 0 && !events)) return BALL_EINVAL;
  if (!isfinite(dt)) return BALL_ENONFINITE;
  if (dt < 0.0) return BALL_ERANGE;
  m = &sim->model; /* checked when the sim got it (ball_sim_init, ball_sim_set_model) */
  if (!isfinite(sim->time) || !segment_finite(&sim->seg) || !ball_v3_finite(sim->prev_position))
    return BALL_ENONFINITE;
  t_prev = sim->time;
  t_end = t_prev + dt;
  if (!isfinite(t_end) || sim->seg.t0 > t_prev) return BALL_ERANGE;
  if (dt == 0.0) return BALL_OK;
  /* a frame whose flight would overflow is refused before anything changes */
  ball__flight_of(m, &fl);
  ball__eval_f(&fl, &sim->seg, t_end, &s);
  if (!state_finite(&s)) return BALL_ERANGE;
  undo_save(&undo, sim);
  k.events = events;
  k.cap = cap;
  k.n = 0;
  k.missed = &sim->warnings[BALL_WARN_EVENT_OVERFLOW];

  if (m->scheme == BALL_SCHEME_EXACT) {
    int c = exact_advance(m, &fl, &sim->seg, &sim->next, t_prev, t_end, &k, &s);
    if (c < 0) sim->warnings[BALL_WARN_CONTACT_LIMIT]++;
    changed = c != 0;
  } else {
    changed = step_sampled(m, &fl, sim, t_end, dt, &k, &s) > 0;
  }
  sim->time = t_end;

  if (ball__has(m, BALL_EFFECT_RACKETS) && m->n_rackets > 0) {
    ball_event ev;
    if (ball__racket_stage(m, &fl, sim, t_prev, dt, &s, &ev)) {
      emit(&k, &ev);
      changed = 1;
      sim->next.valid = 0;
      /* the rest of the frame on the new path (a swept hit lands inside it) */
      if (m->scheme == BALL_SCHEME_EXACT && ev.time < t_end) {
        if (exact_advance(m, &fl, &sim->seg, &sim->next, ev.time, t_end, &k, &s) < 0)
          sim->warnings[BALL_WARN_CONTACT_LIMIT]++;
      } else {
        ball__eval_f(&fl, &sim->seg, t_end, &s);
      }
    }
  }
  /* a response that overflowed (speeds near DBL_MAX): refuse the frame and
   * give the sim back as it was */
  if (changed && (!segment_finite(&sim->seg) || !state_finite(&s) || !events_finite(events, k.n))) {
    undo_restore(&undo, sim, t_prev);
    return BALL_ERANGE;
  }
  sim->prev_position = s.position;
  sim->frame++;
  if (n_events) *n_events = k.n;
  return BALL_OK;
}

/* ---- the window of a racket query (internal.h) ---- */

/* The latest time in (lo, hi] where `below` is false, `below` being true at
 * hi and false from lo up to some point (a ball sinking through the floor):
 * bisection to adjacent doubles. */
static double last_above(const ball_model *m, const ball__flight *fl, const ball_segment *seg, double lo,
                         double hi, int need_falling) {
  int it;
  for (it = 0; it < 200; it++) {
    double mid = lo + 0.5 * (hi - lo);
    ball_state s;
    if (!(mid > lo && mid < hi)) break;
    ball__eval_f(fl, seg, mid, &s);
    if (s.position.y < ball__floor_y(m) && (!need_falling || s.velocity.y <= 0.0))
      hi = mid;
    else
      lo = mid;
  }
  return lo;
}

double ball__static_window(const ball_sim *sim, const ball__flight *fl, double t_end) {
  const ball_model *m = &sim->model;
  const ball_segment *seg = &sim->seg;
  double t0 = sim->time, hi = t_end;
  ball_state s;
  if (m->scheme == BALL_SCHEME_EXACT) {
    ball_contact c = sim->next;
    if (!c.valid) find_next(m, fl, seg, t0, &c); /* what the step would find, not kept */
    if (c.time <= hi) hi = nextafter(c.time, -INFINITY);
    if (!(hi > t0)) return t0;
    /* exact_advance's rule: a floor root rounded past the frame's end with
     * the ball already below the floor there is a contact now */
    ball__eval_f(fl, seg, hi, &s);
    if (c.which == WHICH_FLOOR && s.position.y < ball__floor_y(m) && s.velocity.y <= 0.0)
      hi = last_above(m, fl, seg, t0, hi, 1);
    return hi;
  }
  /* sampled: the floor below the centre at the frame's end (Fig. 1) */
  if (ball__has(m, BALL_EFFECT_FLOOR) && !seg->grounded) {
    double r1, r2;
    if (ball__height_roots(m->gravity, seg->p0.y, seg->v0.y, ball__floor_y(m), &r1, &r2) && seg->t0 + r2 <= hi)
      hi = seg->t0 + r2;
    ball__eval_f(fl, seg, hi, &s);
    if (s.position.y < ball__floor_y(m)) hi = last_above(m, fl, seg, t0, hi, 0);
  }
  /* a net's or wall's plane: the chord P_old -> P covers the coordinates
   * between its ends, which move one way (drag never turns the ball), so it
   * cannot reach the rectangle grown by r before the centre comes within r
   * of the plane */
  {
    int i, n = ball__has(m, BALL_EFFECT_WALLS) ? m->n_walls : 0;
    int net = ball__has(m, BALL_EFFECT_NET) && m->has_net;
    for (i = net ? -1 : 0; i < n; i++) {
      const ball_plane *pl = i < 0 ? &m->net : &m->walls[i];
      double x = ball_v3_axis(sim->prev_position, pl->axis), d = pl->position - x, tau;
      if (fabs(d) <= m->radius) return t0; /* at the plane already: nothing is searched */
      if (ball__plane_tau(fl->b, ball_v3_axis(seg->p0, pl->axis), ball_v3_axis(seg->v0, pl->axis),
                          d > 0.0 ? pl->position - m->radius : pl->position + m->radius, t0 - seg->t0, &tau) &&
          seg->t0 + tau <= hi)
        hi = nextafter(seg->t0 + tau, -INFINITY);
    }
  }
  return hi > t0 ? hi : t0;
}

/* ---- prediction ---- */

/* States between two re-anchorings of the recurrence to the closed form
 * (docs/model.md, "Prediction": the error bound and its proof). */
#define MARCH_ANCHOR 32
/* Above this |delta / b| the first-order correction of a frame's rounding
 * (march_state) would err by more than an ulp: re-anchor instead. */
#define MARCH_DELTA_MAX 1e-8

/* The drag terms of eq 3 stepped at the prediction's fixed rate. With
 * D(tau) = b (1 - e^(-tau/b)) and F(tau) = e^(-tau/b), eq 3 gives
 *   F(tau + h) = F(tau) F(h),   D(tau + h) = D(tau) + F(tau) D(h),
 * so each state costs a few multiplications instead of an expm1. h is the
 * frame the clock really advanced, dt - delta with delta the rounding of
 * t + dt (exact, by TwoSum): F(h) = F(dt) (1 + delta / b) and
 * D(h) = D(dt) - F(dt) delta to first order, exact to an ulp while
 * |delta / b| <= MARCH_DELTA_MAX. */
typedef struct march {
  double fdt, ddt; /* F(dt), D(dt) */
  double f, d;     /* F, D at the last state's tau on the segment */
  double sdamp;    /* sDamp for eq 4 on the segment; 0 also when its spin is zero (a test less a state) */
  int left;        /* states before the next anchor; 0: anchor at the next one */
} march;

/* The state at t_next = t + dt (as the clock sums it) on seg, the last
 * state having been at t: by the recurrence, or the closed form (eq 3) when
 * an anchor is due. Height, vertical speed and spin are always the closed
 * form's (ball__state_at), to the bit. */
static inline void march_state(const ball__flight *fl, const ball_segment *seg, march *mr, double t, double dt,
                        double t_next, ball_state *s) {
  double tau = t_next - seg->t0;
  if (fl->k != 0.0 && mr->left > 0) {
    /* t + dt = t_next + err exactly (Fast2Sum while |t| >= dt, else
     * TwoSum); the frame is h = dt - err */
    double bb = t_next - t, err = dt - bb, de;
    if (!(fabs(t) >= dt)) err = (t - (t_next - bb)) + err;
    de = err * fl->k;
    if (fabs(de) <= MARCH_DELTA_MAX) {
      double fh = mr->fdt + mr->fdt * de, dh = mr->ddt - mr->fdt * err;
      mr->d += mr->f * dh; /* eq 3: D(tau + h) = D(tau) + F(tau) D(h) */
      mr->f *= fh;         /* eq 3: F(tau + h) = F(tau) F(h) */
      mr->left--;
      ball__state_at(fl->g, mr->sdamp, seg, tau, mr->d, mr->f, s);
      return;
    }
  }
  ball__drag_terms(fl->b, fl->k, tau, &mr->d, &mr->f);
  mr->left = MARCH_ANCHOR;
  mr->sdamp = ball__zero3(&seg->s0) ? 0.0 : fl->sdamp;
  ball__state_at(fl->g, mr->sdamp, seg, tau, mr->d, mr->f, s);
}

ball_status ball_predict(const ball_model *m, const ball_segment *seg_in, double t_from,
                         double t_end, double dt, ball_prediction *out) {
  ball_segment seg;
  ball_contact next;
  ball_state s;
  ball_status st;
  ball__flight fl;
  march mr;
  unsigned long missed = 0;
  sink k;
  double t;
  if (!m || !seg_in || !out) return BALL_EINVAL;
  if ((out->cap_states > 0 && !out->states) || (out->cap_events > 0 && !out->events) ||
      out->cap_states < 0 || out->cap_events < 0)
    return BALL_EINVAL;
  if (!isfinite(t_from) || !isfinite(t_end) || !isfinite(dt) || !segment_finite(seg_in))
    return BALL_ENONFINITE;
  if (!(dt > 0.0) || t_end < t_from || t_from < seg_in->t0) return BALL_ERANGE;
  st = ball_model_check(m, NULL);
  if (st != BALL_OK) return st;
  seg = *seg_in;
  next.valid = 0;
  k.events = out->events;
  k.cap = out->cap_events;
  k.n = 0;
  k.missed = &missed;
  out->n_states = 0;
  t = t_from;
  ball__flight_of(m, &fl);
  ball__drag_terms(fl.b, fl.k, dt, &mr.ddt, &mr.fdt); /* eq 3 over one frame */
  mr.left = 0;
  march_state(&fl, &seg, &mr, t, 0.0, t, &s); /* an anchor: the closed form at t_from */
  if (!state_finite(&s)) return BALL_ERANGE;
  if (out->cap_states > 0) out->states[out->n_states++] = s;
  /* frames of dt as ball_step takes them (the clock summed, not k dt), the
   * last one cut at t_end */
  while (t < t_end) {
    double t_next = t + dt;
    ball_state *at = &s; /* the state is written where it is kept, when it is */
    if (!(t_next <= t_end)) t_next = t_end; /* the cut frame: no state kept */
    else if (out->n_states < out->cap_states) at = &out->states[out->n_states];
    if (t_next == t) break; /* dt below the clock's resolution */
    /* most frames have no contact: the cached next one is later, and the
     * ball is not below the floor by rounding (exact_advance's last rule,
     * which reads the height and the vertical speed: march_state gives
     * those to the bit) */
    if (!next.valid) find_next(m, &fl, &seg, t, &next);
    march_state(&fl, &seg, &mr, t, dt, t_next, at);
    if (!(next.time > t_next) ||
        (next.which == WHICH_FLOOR && at->position.y < ball__floor_y(m) && at->velocity.y <= 0.0)) {
      exact_advance(m, &fl, &seg, &next, t, t_next, &k, at);
      if (!segment_finite(&seg)) return BALL_ERANGE;
      mr.left = 0; /* a new segment (or a contact at its end): the next state anchors */
    } else if (!state_finite(at)) {
      ball__eval_f(&fl, &seg, t_next, at); /* an overflow is decided by the closed form, as ball_step does */
      mr.left = 0;
    }
    if (!state_finite(at)) return BALL_ERANGE;
    if (at != &s) out->n_states++;
    t = t_next;
  }
  out->n_events = k.n;
  out->events_missed = (int)missed;
  out->end = seg;
  return BALL_OK;
}

/* ---- hash ---- */

uint64_t ball_sim_hash(const ball_sim *sim) {
  return sim ? ball_sim_hash_with(sim, ball_model_hash(&sim->model)) : 0;
}

uint64_t ball_sim_hash_with(const ball_sim *sim, uint64_t model_hash) {
  uint64_t h = BALL__HASH_SEED;
  int r, i;
  if (!sim) return 0;
  h = ball__hash_double(h, sim->time);
  h = ball__hash_word(h, sim->frame);
  h = ball__hash_double(h, sim->seg.t0);
  h = ball__hash_vec(h, sim->seg.p0);
  h = ball__hash_vec(h, sim->seg.v0);
  h = ball__hash_vec(h, sim->seg.s0);
  h = ball__hash_word(h, (uint64_t)(int64_t)sim->seg.grounded);
  h = ball__hash_vec(h, sim->prev_position);
  h = ball__hash_word(h, (uint64_t)(int64_t)sim->sleep);
  for (r = 0; r < BALL_MAX_RACKETS; r++) {
    const ball_racket_track *tr = &sim->tracks[r];
    h = ball__hash_word(h, (uint64_t)(int64_t)tr->count);
    for (i = 0; i < tr->count && i < BALL_MAX_HISTORY; i++) {
      h = ball__hash_double(h, tr->samples[i].t);
      h = ball__hash_vec(h, tr->samples[i].center);
      h = ball__hash_vec(h, tr->samples[i].normal);
    }
  }
  return ball__hash_word(h, model_hash);
}
