/* libball racket scripts: a keyframed racket swing sampled like a tracker or
 * a remote player would send it (rate, delay, jitter, loss, duplicates,
 * noise, all seeded), played as one arrival-ordered stream of samples for
 * ball_racket_push. Part of libball::scene (scene files carry scripts in
 * rackets[i].script); usable without a scene file. See docs/scenes.md,
 * "Racket scripts and network conditions". */
#ifndef BALL_SCRIPT_H
#define BALL_SCRIPT_H

#include <stddef.h>
#include <stdint.h>

#include "ball/ball.h"

#ifdef __cplusplus
extern "C" {
#endif

#define BALL_SCRIPT_MAX_KEYFRAMES 64  /* keyframes per racket script */
#define BALL_SCRIPT_MAX_PENDING 512   /* samples a player holds between taking and arrival */

/* One pose of a scripted racket. */
typedef struct ball_script_keyframe {
  double t;           /* script time, s */
  ball_vec3 center;   /* disc centre, m */
  ball_vec3 normal;   /* disc normal (unit after ball_scene_load_*; any length > 0 otherwise) */
} ball_script_keyframe;

/* A keyframed racket swing sampled like a tracker or a remote player would
 * send it: samples taken at `rate`, each arriving delay + U(0, jitter)
 * seconds later, some lost, some duplicated, with Gaussian noise; every
 * random draw comes from `seed` (docs/scenes.md, "Network conditions"). */
typedef struct ball_racket_script {
  int n_keyframes;    /* keyframes in use, [1, BALL_SCRIPT_MAX_KEYFRAMES]; 0: the racket is not scripted */
  ball_script_keyframe keyframes[BALL_SCRIPT_MAX_KEYFRAMES]; /* strictly increasing t */
  double repeat;      /* period of the pattern, s; 0: play once then hold; else > last t - first t */
  double rate;        /* samples per second, Hz, [2, 120]; sample k is taken at t = k / rate */
  double delay;       /* network delay added to every sample's arrival, s, [0, 60] */
  double jitter;      /* extra delay per sample, uniform in [0, jitter], s, [0, 0.5] */
  double loss;        /* probability a sample is dropped, [0, 1) */
  double duplicate;   /* probability a sample arrives twice (each copy jittered), [0, 1] */
  double noise;       /* Gaussian sigma added to each centre coordinate, m, >= 0 */
  double normal_noise;/* Gaussian sigma of the normal's tilt per tangent axis, rad, [0, 1] */
  uint64_t seed;      /* the same seed gives the same stream bit for bit */
} ball_racket_script;

/* No keyframes, 60 Hz, a perfect network (no delay, jitter, loss, duplicates or noise), seed 0. */
BALL_API void ball_script_default(ball_racket_script *script);

/* Checks every field of a script with keyframes; *field (if not NULL) names
 * the first bad one ("rate", "keyframes[2].t", ...). */
BALL_API ball_status ball_script_check(const ball_racket_script *script, const char **field);

/* The scripted (true, noise-free) pose at time t: the centre piecewise linear
 * between keyframes, the normal lerped and normalised; held before the first
 * and after the last keyframe, or wrapped with period `repeat` (the segment
 * from the last keyframe back to the first spans first t + repeat - last t). */
BALL_API ball_status ball_script_pose(const ball_racket_script *script, double t, ball_vec3 *center,
                                      ball_vec3 *normal);

/* A sample as it reaches the sim. */
typedef struct ball_script_sample {
  int racket;                 /* racket index */
  unsigned long index;        /* k: the sample was taken at k / rate */
  int copy;                   /* 0: the sample, 1: its duplicate */
  double arrival;             /* arrival time = sample.t + delay + jitter draw, s */
  ball_racket_sample sample;  /* what ball_racket_push gets (t = when it was taken) */
} ball_script_sample;

/* Plays the scripts of all rackets as one arrival-ordered stream. A plain
 * value: copy it to replay from the same point; no pointer to the scripts is
 * kept. */
typedef struct ball_script_player {
  int n_rackets;                                       /* [0, BALL_MAX_RACKETS] */
  ball_racket_script scripts[BALL_MAX_RACKETS];        /* copies; n_keyframes 0: silent */
  unsigned long next[BALL_MAX_RACKETS];                /* next sample index to take, per racket */
  int n_pending;                                       /* taken, not yet handed out */
  ball_script_sample pending[BALL_SCRIPT_MAX_PENDING]; /* sorted by arrival */
} ball_script_player;

/* Starts a player over n_rackets scripts (scripts[i] drives racket i). */
BALL_API ball_status ball_script_player_init(ball_script_player *player, const ball_racket_script *scripts,
                                             int n_rackets);

/* Writes to out, in arrival order (ties: racket, index, copy), up to cap
 * samples whose arrival time is <= t_now and that no earlier poll returned;
 * *n gets how many. If *n == cap, more may be waiting: poll again with the
 * same t_now. The stream depends only on the scripts, never on how often or
 * with what cap the player is polled. */
BALL_API ball_status ball_script_poll(ball_script_player *player, double t_now, ball_script_sample *out,
                                      int cap, int *n);

#ifdef __cplusplus
}
#endif

#endif /* BALL_SCRIPT_H */
