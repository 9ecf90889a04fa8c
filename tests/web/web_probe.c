/* What the spectator page's tests (page_check.py) ask of libball:
 *
 *   web_probe segments N SEED
 *       N random flight models, segments and times (kit/seeded.h) with
 *       ball_segment_eval's state, one JSON array, every double to the bit
 *       (%.17g): what the page's own evaluation (libball on WebAssembly,
 *       fed as the page feeds it) is held to, bit for bit
 *
 *   web_probe shot PNG FOV EX EY EZ TX TY TZ UX UY UZ BX BY BZ [X Y Z]...
 *       a screenshot of the page's view (read with libball's PNG reader)
 *       against libball's projection (ball_camera_project) with that
 *       camera: one line for the ball at (BX, BY, BZ), its projection and
 *       the centroid of the yellow pixels (tests/render/ball_pixels.h)
 *       within 25 pixels of it, and
 *       one line per point, its projection and the brightest red of the 3 x
 *       3 pixels around it (a court line is white, the court blue)
 *
 * Exit status 0, 1 for a file or projection error, 2 for bad arguments. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ball/ball.h"
#include "ball/render.h"
#include "ball/vec3.h"
#include "ball_pixels.h"
#include "seeded.h"

static void vec(const char *name, ball_vec3 v, const char *end) {
  printf("\"%s\":[%.17g,%.17g,%.17g]%s", name, v.x, v.y, v.z, end);
}

static ball_vec3 random_vec(seeded_rng *r, double half) {
  return ball_v3(seeded_uniform(r, -half, half), seeded_uniform(r, -half, half), seeded_uniform(r, -half, half));
}

static int segments(int n, unsigned long long seed) {
  seeded_rng r = seeded_stream(seed, 1);
  int i;
  printf("[");
  for (i = 0; i < n; ++i) {
    ball_model m;
    ball_segment s;
    ball_state out;
    double t;
    ball_model_default(&m);
    m.mass = seeded_uniform(&r, 0.002, 2.0);
    m.air_friction = seeded_below(&r, 5) == 0 ? 0.0 : seeded_uniform(&r, 1e-4, 0.5);
    m.gravity = seeded_uniform(&r, 0.0, 25.0);
    m.spin_damping = seeded_uniform(&r, 0.05, 10.0);
    m.effects = (unsigned)seeded_below(&r, 128); /* every combination of the seven bits */
    memset(&s, 0, sizeof s);
    s.t0 = seeded_uniform(&r, 0.0, 1000.0);
    s.p0 = random_vec(&r, 30.0);
    s.v0 = random_vec(&r, 60.0);
    s.s0 = seeded_below(&r, 4) == 0 ? ball_v3(0.0, 0.0, 0.0) : random_vec(&r, 40.0);
    s.grounded = seeded_below(&r, 8) == 0;
    /* tau: 0, within a frame, a rally's segment, long flights (the exp branch) */
    switch (seeded_below(&r, 4)) {
      case 0: t = s.t0; break;
      case 1: t = s.t0 + seeded_uniform(&r, 0.0, 0.02); break;
      case 2: t = s.t0 + seeded_uniform(&r, 0.0, 3.0); break;
      default: t = s.t0 + seeded_uniform(&r, 0.0, 60.0); break;
    }
    if (ball_segment_eval(&m, &s, t, &out) != BALL_OK) {
      fprintf(stderr, "web_probe: ball_segment_eval refused case %d\n", i);
      return 1;
    }
    printf("%s{\"model\":{\"mass\":%.17g,\"air_friction\":%.17g,\"gravity\":%.17g,\"spin_damping\":%.17g,\"effects\":%u},",
           i ? "," : "", m.mass, m.air_friction, m.gravity, m.spin_damping, m.effects);
    printf("\"seg\":{\"t0\":%.17g,", s.t0);
    vec("p0", s.p0, ",");
    vec("v0", s.v0, ",");
    vec("s0", s.s0, ",");
    printf("\"grounded\":%s},\"t\":%.17g,", s.grounded ? "true" : "false", t);
    vec("position", out.position, ",");
    vec("velocity", out.velocity, ",");
    vec("spin", out.spin, "}");
  }
  printf("]\n");
  return 0;
}

/* The ball's yellow pixels within BALL_WINDOW pixels of (px, py), each way: their
 * centroid and how many (a trail over the green ground blends into the
 * ball's yellow elsewhere in a picture). */
#define BALL_WINDOW 25
static long ball_near(const unsigned char *rgb, int w, int h, double px, double py, double *cx, double *cy) {
  unsigned char window[3 * (2 * BALL_WINDOW + 1) * (2 * BALL_WINDOW + 1)];
  int x0 = (int)floor(px) - BALL_WINDOW, y0 = (int)floor(py) - BALL_WINDOW, x, y, side = 2 * BALL_WINDOW + 1;
  long n;
  for (y = 0; y < side; ++y)
    for (x = 0; x < side; ++x) {
      unsigned char *q = window + 3 * (y * side + x);
      int sx = x0 + x, sy = y0 + y;
      if (sx >= 0 && sy >= 0 && sx < w && sy < h) memcpy(q, rgb + 3 * ((size_t)sy * w + sx), 3);
      else memset(q, 0, 3);
    }
  n = ball_centroid(window, side, side, cx, cy);
  if (n) *cx += x0, *cy += y0;
  return n;
}

static int shot(int argc, char **argv) {
  unsigned char *rgb;
  int w, h, i;
  ball_camera cam;
  double px, py, cx, cy;
  long n;
  ball_status st;
  double v[13];
  if (argc < 16 || (argc - 16) % 3 != 0) return 2;
  for (i = 0; i < argc - 3; ++i) {
    char *end;
    double x = strtod(argv[3 + i], &end);
    if (*end || !isfinite(x)) return 2;
    if (i < 13) v[i] = x;
  }
  if ((st = ball_png_read(argv[2], &rgb, &w, &h)) != BALL_OK) {
    fprintf(stderr, "web_probe: %s: %s\n", argv[2], ball_strerror(st));
    return 1;
  }
  cam.fov = v[0];
  cam.eye = ball_v3(v[1], v[2], v[3]);
  cam.target = ball_v3(v[4], v[5], v[6]);
  cam.up = ball_v3(v[7], v[8], v[9]);
  if (ball_camera_project(&cam, w, h, ball_v3(v[10], v[11], v[12]), &px, &py, NULL) != BALL_OK) {
    free(rgb);
    return 1;
  }
  n = ball_near(rgb, w, h, px, py, &cx, &cy);
  printf("ball projected=%.3f,%.3f centroid=%.3f,%.3f pixels=%ld size=%dx%d\n", px, py, cx, cy, n, w, h);
  for (i = 16; i + 2 < argc; i += 3) {
    ball_vec3 p = ball_v3(strtod(argv[i], NULL), strtod(argv[i + 1], NULL), strtod(argv[i + 2], NULL));
    int x, y, best = -1;
    if (ball_camera_project(&cam, w, h, p, &px, &py, NULL) != BALL_OK) {
      printf("point projected=none\n");
      continue;
    }
    for (y = (int)py - 1; y <= (int)py + 1; ++y)
      for (x = (int)px - 1; x <= (int)px + 1; ++x)
        if (x >= 0 && y >= 0 && x < w && y < h && rgb[3 * ((size_t)y * w + x)] > best) best = rgb[3 * ((size_t)y * w + x)];
    printf("point projected=%.3f,%.3f max_red=%d\n", px, py, best);
  }
  free(rgb);
  return 0;
}

int main(int argc, char **argv) {
  if (argc == 4 && strcmp(argv[1], "segments") == 0) return segments(atoi(argv[2]), strtoull(argv[3], NULL, 10));
  if (argc >= 2 && strcmp(argv[1], "shot") == 0) {
    int rc = shot(argc, argv);
    if (rc != 2) return rc;
  }
  fprintf(stderr, "usage: web_probe segments N SEED | web_probe shot PNG FOV EYE(3) TARGET(3) UP(3) BALL(3) [POINT(3)]...\n");
  return 2;
}
