/* libFuzzer harness: the scene loader on arbitrary bytes (docs/hard-cases.md).
 * Whatever the bytes, ball_scene_load_string must not crash, leak or invoke
 * undefined behaviour (ASan, UBSan); a refused scene leaves the output
 * untouched and an error whose strings are terminated; an accepted scene
 * holds a model that passes ball_model_check and steps with finite results. */
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "ball/ball.h"
#include "ball/scene.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static void check(int ok) {
  if (!ok) abort();
}

static int terminated(const char *s, size_t cap) { return memchr(s, '\0', cap) != NULL; }

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  ball_scene scene, copy;
  ball_scene_error err;
  ball_status st;
  char line[1024];
  memset(&scene, 0xA5, sizeof scene);
  copy = scene;
  memset(&err, 0x5A, sizeof err);
  st = ball_scene_load_string((const char *)data, size, "fuzz", &scene, &err);
  check((unsigned)st < BALL_STATUS_COUNT);
  if (st != BALL_OK) {
    check(memcmp(&scene, &copy, sizeof scene) == 0);
    check(terminated(err.file, sizeof err.file) && terminated(err.field, sizeof err.field) &&
          terminated(err.message, sizeof err.message));
    ball_scene_error_format(&err, line, sizeof line);
    check(terminated(line, sizeof line));
    return 0;
  }
  check(terminated(scene.name, sizeof scene.name));
  check(ball_model_check(&scene.model, NULL) == BALL_OK);
  {
    ball_sim sim;
    ball_state s;
    ball_event ev[8];
    int f, n;
    check(ball_sim_init(&scene.model, &sim) == BALL_OK);
    for (f = 0; f < 30; f++) {
      st = ball_step(&scene.model, &sim, scene.frame_time * scene.time_base, ev, 8, &n);
      if (st != BALL_OK) break; /* e.g. a frame that would overflow: refused, not wrong */
      check(ball_sim_state(&scene.model, &sim, &s) == BALL_OK);
      check(isfinite(s.position.x) && isfinite(s.position.y) && isfinite(s.position.z));
      check(isfinite(s.velocity.x) && isfinite(s.velocity.y) && isfinite(s.velocity.z));
    }
  }
  return 0;
}
