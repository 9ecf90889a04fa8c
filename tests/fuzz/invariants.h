/* The physical invariants both fuzz harnesses assert on every frame they
 * step (docs/hard-cases.md, "Fuzzing"), over libball's public API only: the
 * properties of tests/unit/test_properties.c (P1 finite, P2 floor, P3 net
 * and walls, P4 energy) for the parameter sets a fuzzer makes up, checked
 * along the whole path of a frame, not only at its end. A violated
 * invariant prints what failed and aborts (libFuzzer then saves the input).
 * invariants.c states each invariant, the region where it holds and its
 * tolerance. */
#ifndef BALL_FUZZ_INVARIANTS_H
#define BALL_FUZZ_INVARIANTS_H

#include "ball/ball.h"

#define FZ_OBSTACLES (1 + BALL_MAX_WALLS) /* the net (0) and the walls (1 + i) */

/* What the checks carry from frame to frame. */
typedef struct fz_watch {
  const ball_model *m;             /* the sim's own model (ball_sim_model) */
  ball_state prev;                 /* the ball at the end of the previous frame */
  int floor_ok;                    /* 1: P2 applies (the ball ended the last frame on or above the floor) */
  int clear[FZ_OBSTACLES];         /* 1: P3 applies to obstacle k (the ball was clear of it) */
  double dist[FZ_OBSTACLES];       /* centre to obstacle k at the previous frame's end, m */
  /* the frame being stepped (fz_frame_begin) */
  double t_prev;                   /* s */
  ball_segment seg;                /* the segment in effect when the frame starts */
  ball_vec3 p_old;                 /* sim->prev_position: the sampled scheme's chord starts there */
  unsigned long warnings[BALL_WARN_COUNT]; /* the sim's counters before the frame */
  unsigned long frames;            /* frames checked (fz_frame_end) */
} fz_watch;

/* Prints "fuzz invariant: <message>" and aborts. Built with FZ_KEEP_GOING
 * (the coverage build, fuzz_coverage.cmake) it counts instead and goes on,
 * so that an open finding does not end the run that measures coverage; the
 * count is printed at exit ("fuzz invariant: N violations"). */
void fz_fail(const char *fmt, ...)
#if defined(__GNUC__) && defined(FZ_KEEP_GOING)
    __attribute__((format(printf, 1, 2)))
#elif defined(__GNUC__)
    __attribute__((format(printf, 1, 2), noreturn))
#endif
    ;
#define FZ_CHECK(cond, ...)        \
  do {                             \
    if (!(cond)) fz_fail(__VA_ARGS__); \
  } while (0)

/* Starts watching sim: after ball_sim_init or an accepted ball_sim_set_state. */
void fz_watch_start(fz_watch *w, const ball_model *m, const ball_sim *sim);

/* Before ball_step: remembers where the frame starts. */
void fz_frame_begin(fz_watch *w, const ball_sim *sim);

/* After ball_step returned BALL_OK with n events (events[] had room for
 * more than BALL_MAX_CONTACTS): asserts the frame's invariants and moves
 * the watch on to the frame's end. */
void fz_frame_end(fz_watch *w, const ball_sim *sim, double dt, const ball_event *ev, int n);

/* The obstacle k of m if its effect is on and it is in use, else NULL. */
const ball_plane *fz_obstacle(const ball_model *m, int k);

/* Distance from c to the rectangle p (the harness's own, not libball's). */
double fz_rect_distance(const ball_plane *p, ball_vec3 c);

/* 1 when every component is finite. */
int fz_finite3(ball_vec3 v);

/* The gap from |x| to the next double up (the clock's resolution at x). */
double fz_ulp(double x);

/* The largest |component|. */
double fz_max_abs(ball_vec3 v);

#endif /* BALL_FUZZ_INVARIANTS_H */
