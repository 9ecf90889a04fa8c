/* A scene replayed to chosen times (ball/render.h, "frames from a scene"). */
#include <math.h>
#include <string.h>

#include "ball/render.h"

#define TIME_SLACK 1e-9 /* s: a frame ending this close after t counts as at t */
#define EVENT_CAP (BALL_MAX_CONTACTS + BALL_MAX_RACKETS + 8)

static void keep_position(ball_replay *r) {
  int i = (r->trail_start + r->n_trail) % BALL_REPLAY_MAX_TRAIL;
  ball_state s;
  if (ball_segment_eval(&r->scene.model, &r->run.sim.seg, r->run.sim.time, &s) != BALL_OK) return;
  if (r->n_trail == BALL_REPLAY_MAX_TRAIL) r->trail_start = (r->trail_start + 1) % BALL_REPLAY_MAX_TRAIL;
  else r->n_trail++;
  r->trail_points[i] = s.position;
  r->trail_times[i] = r->run.sim.time;
}

static void keep_event(ball_replay *r, const ball_event *e) {
  int i = (r->event_start + r->n_events) % BALL_REPLAY_MAX_EVENTS;
  if (r->n_events == BALL_REPLAY_MAX_EVENTS) r->event_start = (r->event_start + 1) % BALL_REPLAY_MAX_EVENTS;
  else r->n_events++;
  r->events[i] = *e;
}

ball_status ball_replay_init(ball_replay *r, const ball_scene *scene, double trail, double markers) {
  ball_status st;
  if (!r || !scene) return BALL_EINVAL;
  if (!isfinite(trail) || !isfinite(markers)) return BALL_ENONFINITE;
  if (!(trail >= 0.0 && trail <= 60.0) || !(markers >= 0.0 && markers <= 60.0)) return BALL_ERANGE;
  if ((st = ball_model_check(&scene->model, NULL)) != BALL_OK) return st;
  memset(r, 0, sizeof *r);
  r->scene = *scene;
  r->trail = trail;
  r->markers = markers;
  if ((st = ball_scene_run_init(&r->run, &r->scene)) != BALL_OK) return st;
  keep_position(r);
  return BALL_OK;
}

ball_status ball_replay_frame(ball_replay *r, double t, ball_frame *f) {
  const ball_model *m;
  ball_event events[EVENT_CAP];
  ball_state s;
  ball_status st;
  double te;
  int i, n;
  if (!r || !f) return BALL_EINVAL;
  if (!isfinite(t)) return BALL_ENONFINITE;
  m = &r->scene.model;
  if (t < r->run.sim.time - TIME_SLACK) return BALL_ERANGE;
  while (r->run.sim.time + r->run.dt <= t + TIME_SLACK) {
    if ((st = ball_scene_run_step(&r->run, events, EVENT_CAP, &n)) != BALL_OK) return st;
    for (i = 0; i < n; ++i) keep_event(r, &events[i]);
    keep_position(r);
  }
  /* on the current segment; at a frame's time (to TIME_SLACK) the frame's own state */
  te = t > r->run.sim.time + TIME_SLACK ? t : r->run.sim.time;
  if ((st = ball_segment_eval(m, &r->run.sim.seg, te, &s)) != BALL_OK) return st;
  memset(f, 0, sizeof *f);
  f->time = t;
  f->ball = s.position;
  f->n_rackets = m->n_rackets;
  for (i = 0; i < m->n_rackets; ++i) {
    ball_racket_pose pose;
    if (ball_racket_estimate(&r->run.sim, i, t, &pose) != BALL_OK) continue;
    f->rackets[i].visible = 1;
    f->rackets[i].center = pose.center;
    f->rackets[i].normal = pose.normal;
  }
  if (r->trail > 0.0) {
    for (i = 0; i < r->n_trail; ++i) {
      int k = (r->trail_start + i) % BALL_REPLAY_MAX_TRAIL;
      if (r->trail_times[k] >= t - r->trail - TIME_SLACK) r->frame_trail[f->n_trail++] = r->trail_points[k];
    }
    r->frame_trail[f->n_trail++] = s.position;
    f->trail = r->frame_trail;
  }
  if (r->markers > 0.0) {
    for (i = 0; i < r->n_events; ++i) {
      const ball_event *e = &r->events[(r->event_start + i) % BALL_REPLAY_MAX_EVENTS];
      if (e->time >= t - r->markers - TIME_SLACK && e->time <= t + TIME_SLACK) r->frame_events[f->n_events++] = *e;
    }
    f->events = r->frame_events;
  }
  return BALL_OK;
}
