/* An outside program using the installed libball. A ball dropped from
 * 1 m falls for sqrt(2 / 9.81) = 0.451524 s before it bounces (eq 3). */
#include <stdio.h>

#include <ball/ball.h>

int main(void) {
  ball_model model;
  ball_sim sim;
  ball_event events[8];
  int i, n;
  ball_model_default(&model);
  model.has_net = 0;
  model.initial_position.x = 1.0;
  model.initial_position.y = 1.0;
  model.initial_velocity.x = 0.0;
  model.initial_velocity.z = 0.0;
  if (ball_sim_init(&sim, &model) != BALL_OK) return 1;
  for (i = 0; i < 60; i++) {
    ball_status st = ball_step(&sim, 1.0 / 60.0, events, 8, &n);
    if (st != BALL_OK) {
      fprintf(stderr, "%s\n", ball_strerror(st));
      return 1;
    }
    if (n > 0) {
      printf("bounce at t=%.6f\n", events[0].time);
      return 0;
    }
  }
  return 1;
}
