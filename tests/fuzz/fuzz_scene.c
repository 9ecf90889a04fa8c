/* libFuzzer harness: the scene loader on arbitrary bytes, then the scene
 * played (docs/hard-cases.md, "Fuzzing"). Whatever the bytes,
 * ball_scene_load_string must not crash, leak or invoke undefined behaviour
 * (ASan, UBSan); a refused scene leaves the output untouched and an error
 * whose strings are terminated. An accepted scene:
 *  - holds a model that passes ball_model_check and scripts that pass
 *    ball_script_check, whose poses (ball_script_pose) are finite with a
 *    unit normal;
 *  - plays its racket scripts (ball_script_player_init, ball_script_poll
 *    with a small cap) as one stream in arrival order (ties: racket, index,
 *    copy), each sample arriving no earlier than it was taken and no later
 *    than the poll's time, with finite poses;
 *  - runs through ball_scene_run_step, as ballsim runs it, in its own
 *    scheme and in the other one (so both the exact and the sampled stepper
 *    see every scene), every frame keeping the invariants of invariants.c
 *    (finite, floor, net and walls, energy). */
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "ball/ball.h"
#include "ball/scene.h"
#include "ball/script.h"
#include "ball/vec3.h"
#include "invariants.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

#define RUN_FRAMES 90       /* frames played per scheme */
#define POLL_CAP 3          /* small: exercises "poll again with the same t_now" */
#define POLL_MAX 2000       /* samples polled per scene, at most */
#define EV_CAP (BALL_MAX_CONTACTS + 2)

static int terminated(const char *s, size_t cap) { return memchr(s, '\0', cap) != NULL; }

static void check_pose(const ball_racket_script *s, int racket, double t) {
  ball_vec3 c, n;
  FZ_CHECK(ball_script_pose(s, t, &c, &n) == BALL_OK, "racket %d: ball_script_pose refused t = %.17g", racket, t);
  FZ_CHECK(fz_finite3(c) && fz_finite3(n) && fabs(ball_v3_norm(n) - 1.0) <= 1e-9,
           "racket %d: the pose at t = %.17g is not finite or its normal not unit", racket, t);
}

/* The scripted poses: finite, normal of unit length, before, at and between
 * the keyframes and after them. */
static void check_script(const ball_racket_script *s, int racket) {
  int k, last = s->n_keyframes - 1;
  FZ_CHECK(ball_script_check(s, NULL) == BALL_OK, "racket %d: a loaded script fails ball_script_check", racket);
  check_pose(s, racket, s->keyframes[0].t - 1.0);
  for (k = 0; k <= last; k++) {
    check_pose(s, racket, s->keyframes[k].t);
    if (k < last) check_pose(s, racket, 0.5 * (s->keyframes[k].t + s->keyframes[k + 1].t));
  }
  check_pose(s, racket, s->keyframes[last].t + (s->repeat > 0.0 ? 0.5 * s->repeat : 1.0));
}

/* The samples in arrival order, as ball_script_poll promises. */
static void check_stream(const ball_scene *scene, double t_last) {
  static ball_script_player player;
  ball_script_sample out[POLL_CAP];
  double t_now, step = t_last / 16.0, last_arrival = -INFINITY;
  int last_racket = -1, total = 0, i, n;
  unsigned long last_index = 0;
  FZ_CHECK(ball_script_player_init(&player, scene->scripts, scene->model.n_rackets) == BALL_OK,
           "ball_script_player_init refused a loaded scene's scripts");
  for (t_now = 0.0; total < POLL_MAX; t_now += step) {
    do {
      FZ_CHECK(ball_script_poll(&player, t_now, out, POLL_CAP, &n) == BALL_OK && n >= 0 && n <= POLL_CAP,
               "ball_script_poll at %.17g", t_now);
      for (i = 0; i < n; i++, total++) {
        const ball_script_sample *s = &out[i];
        FZ_CHECK(s->racket >= 0 && s->racket < scene->model.n_rackets && scene->scripts[s->racket].n_keyframes > 0,
                 "a sample of racket %d, which has no script", s->racket);
        FZ_CHECK(s->arrival <= t_now && s->arrival >= s->sample.t, "a sample arriving at %.17g polled at %.17g",
                 s->arrival, t_now);
        FZ_CHECK(isfinite(s->sample.t) && fz_finite3(s->sample.center) && fz_finite3(s->sample.normal),
                 "a sample that is not finite");
        FZ_CHECK(s->arrival > last_arrival ||
                     (s->arrival == last_arrival &&
                      (s->racket > last_racket || (s->racket == last_racket && s->index >= last_index))),
                 "samples out of arrival order");
        last_arrival = s->arrival;
        last_racket = s->racket;
        last_index = s->index;
      }
    } while (n == POLL_CAP && total < POLL_MAX);
    if (!(step > 0.0) || t_now >= t_last) break;
  }
}

/* The scene played as ballsim plays it, every frame checked. */
static void play(const ball_scene *scene) {
  static ball_scene_run run;
  fz_watch w;
  ball_event ev[EV_CAP];
  int f, n;
  if (ball_scene_run_init(&run, scene) != BALL_OK) return; /* a frame time that overflows */
  fz_watch_start(&w, &scene->model, &run.sim);
  for (f = 0; f < RUN_FRAMES; f++) {
    fz_frame_begin(&w, &run.sim);
    /* a frame that would overflow is refused, not wrong */
    if (ball_scene_run_step(&run, ev, EV_CAP, &n) != BALL_OK) break;
    fz_frame_end(&w, &run.sim, run.dt, ev, n);
  }
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  static ball_scene scene, copy, other;
  ball_scene_error err;
  ball_status st;
  char line[1024];
  int r, any_script = 0;
  memset(&scene, 0xA5, sizeof scene);
  copy = scene;
  memset(&err, 0x5A, sizeof err);
  st = ball_scene_load_string((const char *)data, size, "fuzz", &scene, &err);
  FZ_CHECK((unsigned)st < BALL_STATUS_COUNT, "status %d", (int)st);
  if (st != BALL_OK) {
    FZ_CHECK(memcmp(&scene, &copy, sizeof scene) == 0, "a refused scene changed the output");
    FZ_CHECK(terminated(err.file, sizeof err.file) && terminated(err.field, sizeof err.field) &&
                 terminated(err.message, sizeof err.message),
             "an error string that is not terminated");
    ball_scene_error_format(&err, line, sizeof line);
    FZ_CHECK(terminated(line, sizeof line), "a formatted error that is not terminated");
    return 0;
  }
  FZ_CHECK(terminated(scene.name, sizeof scene.name), "a name that is not terminated");
  FZ_CHECK(ball_model_check(&scene.model, NULL) == BALL_OK, "a loaded model fails ball_model_check");
  for (r = 0; r < scene.model.n_rackets; r++)
    if (scene.scripts[r].n_keyframes > 0) {
      check_script(&scene.scripts[r], r);
      any_script = 1;
    }
  if (any_script) check_stream(&scene, RUN_FRAMES * scene.frame_time * scene.time_base);
  play(&scene);
  /* the same scene in the other scheme */
  other = scene;
  other.model.scheme = scene.model.scheme == BALL_SCHEME_EXACT ? BALL_SCHEME_SAMPLED : BALL_SCHEME_EXACT;
  play(&other);
  return 0;
}
