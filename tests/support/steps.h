/* The one step-and-tally loop of the C tests: step a sim N frames of dt,
 * count its events by kind (and keep them, if asked), and fail the test on
 * a status other than BALL_OK, on an event that does not fit (more in a
 * frame than STEPS_FRAME_CAP, more in the run than the log holds, or a
 * BALL_WARN_EVENT_OVERFLOW counted by the sim) and on an event that is not
 * finite. A per-frame callback checks what a test checks every frame and
 * may end the run early. Header only, C99; include after <cmocka.h>. */
#ifndef BALL_TESTS_STEPS_H
#define BALL_TESTS_STEPS_H

#include <math.h>
#include <string.h>

#include "ball/ball.h"

/* Room for one frame's events: every contact of an exact step and a hit of
 * each racket, with some to spare. */
#define STEPS_FRAME_CAP (BALL_MAX_CONTACTS + BALL_MAX_RACKETS + 4)

typedef struct steps_tally {
  unsigned long frames;            /* frames stepped */
  int total;                       /* events seen */
  int kind[BALL_EVENT_KIND_COUNT]; /* events seen, by kind */
  int sounds;                      /* events with the sound flag */
  ball_event first, last;          /* the first and the last event seen (if total > 0) */
  ball_event *log;                 /* NULL, or every event in order: log[0 .. total) */
  int log_cap;                     /* its room: one event more fails the test */
} steps_tally;

/* An empty tally; log (may be NULL) gets every event, up to log_cap. */
static inline void steps_begin(steps_tally *t, ball_event *log, int log_cap) {
  memset(t, 0, sizeof *t);
  t->log = log;
  t->log_cap = log_cap;
}

/* Called after every frame with that frame's events (t already counts
 * them); returns 0 to end the run there. */
typedef int (*steps_frame_fn)(void *ctx, ball_sim *sim, const steps_tally *t, const ball_event *ev, int n);

static inline int steps_event_finite(const ball_event *e) {
  return isfinite(e->time) && isfinite(e->point.x) && isfinite(e->point.y) && isfinite(e->point.z) &&
         isfinite(e->velocity_in.x) && isfinite(e->velocity_in.y) && isfinite(e->velocity_in.z) &&
         isfinite(e->velocity_out.x) && isfinite(e->velocity_out.y) && isfinite(e->velocity_out.z) &&
         isfinite(e->spin_out.x) && isfinite(e->spin_out.y) && isfinite(e->spin_out.z);
}

/* Steps sim up to `frames` frames of dt, tallying into t (may be NULL: just
 * the checks), calling each (may be NULL) after every frame; ends early
 * when each returns 0. Returns the frames stepped. */
static inline unsigned long steps_each(ball_sim *sim, double dt, unsigned long frames, steps_tally *t,
                                       steps_frame_fn each, void *ctx) {
  steps_tally none;
  ball_event ev[STEPS_FRAME_CAP];
  unsigned long f, overflow = sim->warnings[BALL_WARN_EVENT_OVERFLOW];
  int k, n;
  if (!t) {
    steps_begin(&none, NULL, 0);
    t = &none;
  }
  for (f = 0; f < frames; f++) {
    ball_status st = ball_step(sim, dt, ev, STEPS_FRAME_CAP, &n);
    if (st != BALL_OK)
      fail_msg("frame %lu of dt %.17g at t = %.17g: ball_step: %s", t->frames, dt, sim->time, ball_strerror(st));
    if (sim->warnings[BALL_WARN_EVENT_OVERFLOW] != overflow)
      fail_msg("frame %lu: more than %d events in one frame", t->frames, STEPS_FRAME_CAP);
    for (k = 0; k < n; k++) {
      if (!steps_event_finite(&ev[k]))
        fail_msg("frame %lu: event %d (kind %d at t = %.17g) is not finite", t->frames, t->total, (int)ev[k].kind,
                 ev[k].time);
      if (t->log) {
        if (t->total >= t->log_cap) fail_msg("frame %lu: more than %d events in the run", t->frames, t->log_cap);
        t->log[t->total] = ev[k];
      }
      if (t->total == 0) t->first = ev[k];
      t->last = ev[k];
      t->kind[ev[k].kind]++;
      t->sounds += ev[k].sound != 0;
      t->total++;
    }
    t->frames++;
    if (each && !each(ctx, sim, t, ev, n)) return f + 1;
  }
  return frames;
}

/* steps_each without a callback. */
static inline unsigned long steps_run(ball_sim *sim, double dt, unsigned long frames, steps_tally *t) {
  return steps_each(sim, dt, frames, t, NULL, NULL);
}

/* A callback: ends the run after the first frame with an event. */
static inline int steps_until_event(void *ctx, ball_sim *sim, const steps_tally *t, const ball_event *ev, int n) {
  (void)ctx;
  (void)sim;
  (void)t;
  (void)ev;
  return n == 0;
}

/* A callback: ends the run after the frame in which the ball came to rest
 * on the floor (its segment grounded). */
static inline int steps_until_grounded(void *ctx, ball_sim *sim, const steps_tally *t, const ball_event *ev, int n) {
  (void)ctx;
  (void)t;
  (void)ev;
  (void)n;
  return !sim->seg.grounded;
}

/* A box for steps_in_box: [lo, hi] coordinate by coordinate; lo = hi pins a
 * coordinate to the bit, +-INFINITY leaves it free. */
typedef struct steps_box {
  ball_vec3 lo, hi; /* m */
} steps_box;

/* The box that holds everything. */
static inline steps_box steps_anywhere(void) {
  steps_box b;
  b.lo.x = b.lo.y = b.lo.z = -INFINITY;
  b.hi.x = b.hi.y = b.hi.z = INFINITY;
  return b;
}

static inline void steps_within(const char *what, double v, double lo, double hi, unsigned long frame) {
  if (!(v >= lo && v <= hi)) fail_msg("frame %lu: %s = %.17g, outside [%.17g, %.17g]", frame, what, v, lo, hi);
}

/* A callback (ctx: a steps_box): the ball ends every frame with a finite
 * state, its centre inside the box. */
static inline int steps_in_box(void *ctx, ball_sim *sim, const steps_tally *t, const ball_event *ev, int n) {
  const steps_box *b = (const steps_box *)ctx;
  ball_state s;
  unsigned long frame = t->frames - 1;
  (void)ev;
  (void)n;
  if (ball_sim_state(sim, &s) != BALL_OK) fail_msg("frame %lu: no state", frame);
  if (!(isfinite(s.position.x) && isfinite(s.position.y) && isfinite(s.position.z) && isfinite(s.velocity.x) &&
        isfinite(s.velocity.y) && isfinite(s.velocity.z) && isfinite(s.spin.x) && isfinite(s.spin.y) &&
        isfinite(s.spin.z)))
    fail_msg("frame %lu: a state that is not finite", frame);
  steps_within("x", s.position.x, b->lo.x, b->hi.x, frame);
  steps_within("y", s.position.y, b->lo.y, b->hi.y, frame);
  steps_within("z", s.position.z, b->lo.z, b->hi.z, frame);
  return 1;
}

#endif /* BALL_TESTS_STEPS_H */
