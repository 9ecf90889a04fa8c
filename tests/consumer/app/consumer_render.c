/* An outside program using the installed libball::render: a 64 x 48 frame
 * of the installed dropped_ball.yaml at t = 0.5 s from the side camera (the
 * ball, still falling, at y = 2 - 9.81 / 8 = 0.77375 m: eq 3), written as a
 * PNG and read back the same size, to the last byte. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <ball/render.h>

int main(int argc, char **argv) {
  static ball_scene scene;
  static ball_replay replay;
  ball_frame frame;
  ball_camera cam;
  ball_renderer *r = NULL;
  const unsigned char *rgb;
  unsigned char *back = NULL;
  int w, h, w2, h2, same;
  if (argc != 3) return 2;
  if (ball_scene_load_file(argv[1], &scene, NULL) != BALL_OK) return 1;
  if (ball_replay_init(&replay, &scene, 0.0, 1.0) != BALL_OK) return 1;
  if (ball_replay_frame(&replay, 0.5, &frame) != BALL_OK) return 1;
  if (ball_camera_from_preset(&scene.model, BALL_CAMERA_SIDE, 64.0 / 48.0, &cam) != BALL_OK) return 1;
  if (ball_renderer_create(64, 48, &r) != BALL_OK) return 1;
  if (ball_render_draw(r, &scene.model, &cam, &frame) != BALL_OK ||
      ball_render_pixels(r, &rgb, &w, &h) != BALL_OK || ball_png_write(argv[2], rgb, w, h) != BALL_OK ||
      ball_png_read(argv[2], &back, &w2, &h2) != BALL_OK) {
    ball_renderer_destroy(r);
    return 1;
  }
  same = w2 == w && h2 == h && memcmp(back, rgb, (size_t)w * (size_t)h * 3) == 0;
  printf("frame %dx%d at t=%.3f: ball at y=%.6f, png %s\n", w, h, frame.time, frame.ball.y,
         same ? "read back the same" : "differs");
  free(back);
  ball_renderer_destroy(r);
  return same ? 0 : 1;
}
