/* The measuring pieces of ball_bench (docs/benchmarks.md), shared with the
 * accuracy report (validation/accuracy_step.cpp, docs/accuracy.md): the
 * clock, min and median, the lean evaluation that is the yardstick between
 * machines, a scene's frames with the racket samples that arrive before each,
 * a whole frame of a rally, the 6 s prediction a bot asks for, the effects
 * scene. Public API only; C99, callable from C++. */
#ifndef BALL_BENCH_KIT_H
#define BALL_BENCH_KIT_H

#include "ball/ball.h"
#include "ball/scene.h"

#ifdef __cplusplus
extern "C" {
#endif

#define BENCH_MAX_ROUNDS 101

/* Machines differ (and a shared one drifts): the lean evaluation, measured
 * in the same run, is the yardstick. It took 7.6 ns on the machine the
 * targets of docs/benchmarks.md were set on; "@ref" figures scale a run's
 * numbers to that machine: ns * BENCH_REF_LEAN_NS / lean. */
#define BENCH_REF_LEAN_NS 7.6

/* Keeps timed work alive. */
extern volatile double bench_sink;

/* Monotonic wall clock, s. */
double bench_now(void);

typedef struct bench_stat {
  double min, median;
} bench_stat;

/* Min and median of v[0..n) (sorts v). */
bench_stat bench_stats(double *v, int n);

/* The least time between two bench_now() calls, ns (subtracted from the
 * timing of single frames). */
double bench_timer_overhead(void);

/* ---- one state on a segment (drag and spin on) ---- */

typedef struct bench_eval_result {
  bench_stat segment_eval; /* ball_segment_eval, ns */
  bench_stat flight_eval;  /* ball_flight_eval, ns */
  bench_stat lean;         /* 1/b given, one expm1, no checks: the yardstick, ns */
  bench_stat expm1;        /* one expm1: the floor, ns */
} bench_eval_result;

/* calls evaluations of each kind per round, rounds rounds (<= BENCH_MAX_ROUNDS). */
void bench_eval_run(int rounds, long calls, bench_eval_result *out);

/* ---- a scene run with its racket samples, recorded ahead ---- */

typedef struct bench_frame_samples {
  int first, count; /* into bench_run.samples */
} bench_frame_samples;

typedef struct bench_run {
  ball_scene scene;
  double dt;                        /* frame, s of sim time */
  long frames;                      /* over the scene's duration */
  bench_frame_samples *per_frame;   /* (frames) the samples that arrive before each frame */
  ball_script_sample *samples;      /* (n_samples) */
  long n_samples;
} bench_run;

/* Loads a scene file and plays its scripts once, as ballsim does, keeping
 * which samples arrive before which frame. 0 (with a message on stderr) on
 * failure. */
int bench_run_prepare(bench_run *rn, const char *path);
void bench_run_free(bench_run *rn);

/* One frame as a user runs it: the samples that arrived, then the step;
 * events[kind] counts the events. 0 if the step failed. */
int bench_frame(ball_sim *sim, const bench_run *rn, long k, int *events);

/* A whole frame of a rally scene with a test. */
typedef struct bench_rally_result {
  bench_stat mean;     /* ns per frame over whole passes of the scene */
  double frame_median; /* ns: the median frame, each frame timed alone (the best of its passes) */
  double worst;        /* ns: the slowest frame, each frame timed alone (the best of its passes) */
  int hits;            /* racket hits in one pass */
  long frames;
} bench_rally_result;

/* rounds of `passes` whole passes, then `single_passes` passes timing each
 * frame alone; the model is the scene's with `detect`. 0 if a step failed. */
int bench_rally_run(const bench_run *rn, ball_detect detect, int rounds, long passes, int single_passes,
                    bench_rally_result *out);

/* ---- the prediction a bot asks every frame ---- */

typedef struct bench_predict_result {
  bench_stat predict; /* us per ball_predict over 6 s at 120 Hz */
  bench_stat steps;   /* us per 720 ball_step of the same path */
  bench_stat expm1;   /* ns per expm1 call, measured in the same rounds (the unit of the targets) */
  int contacts;       /* contacts on the path */
} bench_predict_result;

/* The tennis serve with a back wall: the net, then bounces; calls per round. */
void bench_predict_run(int rounds, long calls, bench_predict_result *out);

/* ---- frames of a scene without rackets ---- */

/* A 7 s serve (420 frames at 60 Hz) into the net of the default court, with
 * drag, spin, floor, net, two walls and sound; no rackets. */
void bench_full_scene(ball_model *m);

/* Takes out of the model what an effect would act on, leaving the mask
 * alone: the model "without" the effect (docs/model.md, "Effects"): drag:
 * air_friction 0; spin: no initial spin; floor: the floor out of reach;
 * net: has_net 0; walls: n_walls 0; rackets: n_rackets 0; sound:
 * sound_threshold +Inf. */
void bench_without(ball_model *m, ball_effect effect);

/* ns per frame of dt over `passes` runs of `frames` frames from the model's
 * initial state. */
double bench_time_frames(const ball_model *m, long passes, long frames, double dt);

#ifdef __cplusplus
}
#endif

#endif /* BALL_BENCH_KIT_H */
