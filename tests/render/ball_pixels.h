/* How the render tests find the ball in a picture: its yellow under any
 * light (red about green, little blue), which no other colour of the
 * renderer has (docs/render.md lists them). */
#ifndef BALL_TESTS_BALL_PIXELS_H
#define BALL_TESTS_BALL_PIXELS_H

static int ball_pixel(const unsigned char *p) {
  int r = p[0], g = p[1], b = p[2];
  return g >= 40 && 10 * r >= 9 * g && 10 * r <= 13 * g && 2 * b <= g;
}

/* The centroid of the ball's pixels (pixel centres at +0.5); how many. */
static long ball_centroid(const unsigned char *rgb, int w, int h, double *cx, double *cy) {
  double sx = 0.0, sy = 0.0;
  long n = 0;
  int x, y;
  for (y = 0; y < h; ++y)
    for (x = 0; x < w; ++x)
      if (ball_pixel(rgb + 3 * ((size_t)y * w + x))) {
        sx += x + 0.5;
        sy += y + 0.5;
        n++;
      }
  *cx = n ? sx / n : -1.0;
  *cy = n ? sy / n : -1.0;
  return n;
}

#endif
