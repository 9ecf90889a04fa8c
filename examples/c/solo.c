/* The game loop of the library alone, no server (docs/game-loop.md): two
 * rackets, one on each side of a tennis net, each a tracker's pose pushed
 * 10 times a second, hit the ball back and forth; the sim steps 60 frames a
 * second. Each racket's tracker reads the racket on the ball while the ball
 * comes towards it low and deep in its half, as a player's would.
 *
 *   solo [--seconds S]
 *
 * Prints every hit and bounce; exit status 0 when both rackets hit. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <ball/ball.h>
#include <ball/vec3.h>

int main(int argc, char **argv) {
  const double frame = 1.0 / 60.0, sample_every = 0.1; /* 60 frames, 10 racket samples a second */
  double seconds = 10.0, next_sample = 0.0;
  ball_model model;
  ball_sim sim;
  ball_event events[16];
  int hits[2] = {0, 0}, n, i, k;
  ball_status st;

  if (argc == 3 && strcmp(argv[1], "--seconds") == 0) seconds = atof(argv[2]);
  ball_model_default(&model);               /* a tennis court, its net at x = 11.885 m */
  model.n_rackets = 2;                      /* racket 0 on the near side, 1 beyond the net */
  model.rackets[0].radius = model.rackets[1].radius = 0.15;
  model.rackets[0].partner = 1;             /* the easy level's ball flies to the partner's racket (eq 8, 9) */
  model.rackets[1].partner = 0;
  model.rackets[0].target = ball_v3(17.8, 0.0, 5.5); /* but lands in the middle of the partner's half, */
  model.rackets[1].target = ball_v3(5.9, 0.0, 5.5);
  model.rackets[0].goal_reach = model.rackets[1].goal_reach = 2.0; /* within 2 m of it */
  if (ball_model_set_level(&model, BALL_LEVEL_EASY) != BALL_OK) return 1; /* turns the rackets effect on */
  model.extrapolation_time = sample_every;  /* eq 15 carries a pose over the gap to the next sample */
  model.stale_time = 1.0;
  model.initial_position = ball_v3(1.0, 1.2, 5.0);
  model.initial_velocity = ball_v3(14.0, 5.0, 0.0); /* a lob over the net */
  st = ball_sim_init(&sim, &model);
  if (st != BALL_OK) {
    const char *field = NULL;
    ball_model_check(&model, &field);
    fprintf(stderr, "solo: %s: %s\n", field ? field : "model", ball_strerror(st));
    return 1;
  }
  while (sim.time < seconds) {
    if (sim.time >= next_sample) { /* the trackers' samples: a player's racket goes to the ball */
      ball_state next;
      ball_sim_state(&sim, &next);
      for (k = 0; k < 2; k++) {
        ball_racket_sample s;
        /* coming towards it, deep in its half (5 m from the net) and low (1.5 m): the racket meets
           it; else it waits behind its baseline */
        double from_net = k == 0 ? model.net.position - next.position.x : next.position.x - model.net.position;
        int mine = from_net > 5.0 && (next.velocity.x < 0.0) == (k == 0) && next.position.y < 1.5;
        s.t = sim.time;
        s.center = mine ? next.position : ball_v3(k == 0 ? 0.0 : 23.77, 1.0, 5.5);
        s.normal = ball_v3(k == 0 ? 1.0 : -1.0, 0.0, 0.0);
        st = ball_racket_push(&sim, k, &s);
        if (st != BALL_OK && st != BALL_EDUPLICATE) fprintf(stderr, "solo: push: %s\n", ball_strerror(st));
      }
      next_sample += sample_every;
    }
    st = ball_step(&sim, frame, events, 16, &n);
    if (st != BALL_OK) {
      fprintf(stderr, "solo: step: %s\n", ball_strerror(st));
      return 1;
    }
    for (i = 0; i < n; i++) {
      const ball_event *e = &events[i];
      if (e->kind == BALL_EVENT_RACKET) hits[e->index]++;
      printf("solo: t %6.3f %s%s at (%.2f, %.2f, %.2f)\n", e->time, ball_event_kind_name(e->kind),
             e->kind == BALL_EVENT_RACKET ? (e->index == 0 ? " 0" : " 1") : "", e->point.x, e->point.y, e->point.z);
    }
  }
  printf("solo: %.0f s: %d hits by racket 0, %d by racket 1\n", seconds, hits[0], hits[1]);
  return hits[0] > 0 && hits[1] > 0 ? 0 : 1;
}
