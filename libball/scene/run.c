/* A scene played frame by frame, as ballsim and ballrender play it
 * (ball/scene.h, "running a scene"). */
#include "ball/scene.h"

#include <math.h>
#include <string.h>

#define RUN_SAMPLE_CAP 64
/* The sim clock adds dt up frame by frame; a sample taken on the frame clock
 * must not come a frame late by rounding. */
#define RUN_ARRIVAL_SLACK 1e-9 /* s */

ball_status ball_scene_run_init(ball_scene_run *run, const ball_scene *scene) {
  ball_scene_run fresh;
  ball_status st;
  if (!run || !scene) return BALL_EINVAL;
  memset(&fresh, 0, sizeof fresh);
  fresh.dt = scene->frame_time * scene->time_base;
  if (!(fresh.dt > 0.0) || !isfinite(fresh.dt)) return BALL_ERANGE;
  if ((st = ball_sim_init(&fresh.sim, &scene->model)) != BALL_OK) return st;
  if ((st = ball_script_player_init(&fresh.player, scene->scripts, scene->model.n_rackets)) != BALL_OK) return st;
  *run = fresh;
  return BALL_OK;
}

/* Every sample that has arrived by t_now goes to ball_racket_push. */
static ball_status feed_samples(ball_scene_run *run, double t_now) {
  ball_script_sample samples[RUN_SAMPLE_CAP];
  int n, i;
  ball_status st;
  do {
    if ((st = ball_script_poll(&run->player, t_now, samples, RUN_SAMPLE_CAP, &n)) != BALL_OK) return st;
    for (i = 0; i < n; ++i) {
      /* rejected samples are normal under jitter: count them and go on */
      st = ball_racket_push(&run->sim, samples[i].racket, &samples[i].sample);
      run->arrived++;
      if (st == BALL_OK) run->accepted++;
      else if (st == BALL_EDUPLICATE) run->duplicate++; /* a copy of a kept sample: ignored */
      else if (st == BALL_ESTALE) run->stale++;
      else run->invalid++;
    }
  } while (n == RUN_SAMPLE_CAP);
  return BALL_OK;
}

ball_status ball_scene_run_step(ball_scene_run *run, ball_event *events, int cap, int *n_events) {
  ball_status st;
  if (!run) return BALL_EINVAL;
  if ((st = feed_samples(run, run->sim.time + run->dt + RUN_ARRIVAL_SLACK)) != BALL_OK) return st;
  return ball_step(&run->sim, run->dt, events, cap, n_events);
}
