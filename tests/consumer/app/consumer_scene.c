/* An outside program using the installed libball::scene: the installed
 * dropped_ball.yaml (a ball of radius 0.12 m dropped from 2 m, no vertical
 * drag: eq 3) played as ballsim plays it; its centre meets the floor at
 * y = 0.12 m after sqrt(2 * 1.88 / 9.81) = 0.619098 s. */
#include <stdio.h>

#include <ball/scene.h>

int main(int argc, char **argv) {
  static ball_scene scene;
  static ball_scene_run run;
  ball_scene_error err;
  ball_event events[8];
  int i, n;
  if (argc != 2) return 2;
  if (ball_scene_load_file(argv[1], &scene, &err) != BALL_OK) {
    char text[768];
    ball_scene_error_format(&err, text, sizeof text);
    fprintf(stderr, "%s\n", text);
    return 1;
  }
  if (ball_scene_run_init(&run, &scene) != BALL_OK) return 1;
  for (i = 0; i < 600; i++) {
    if (ball_scene_run_step(&run, events, 8, &n) != BALL_OK) return 1;
    if (n > 0) {
      printf("%s: bounce at t=%.6f y=%.6f\n", scene.name, events[0].time, events[0].point.y);
      return 0;
    }
  }
  return 1;
}
