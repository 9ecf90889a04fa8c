/* How the render tests find things in a picture by their colours, which
 * docs/render.md lists ("What is drawn"): the ball by its yellow under any
 * light (red about green, little blue), which no other colour of the
 * renderer has; a racket by its index colour. */
#ifndef BALL_TESTS_BALL_PIXELS_H
#define BALL_TESTS_BALL_PIXELS_H

static inline int ball_pixel(const unsigned char *p) {
  int r = p[0], g = p[1], b = p[2];
  return g >= 40 && 10 * r >= 9 * g && 10 * r <= 13 * g && 2 * b <= g;
}

/* Racket 0 red, racket 1 blue, lit: ambient and diffuse light scale the
 * colour, so its channels keep their ratios; the dark rim and the edges,
 * mixed with what is behind, are not counted. */
static inline int racket_pixel(int index, const unsigned char *p) {
  if (index == 0) return p[0] > 100 && p[0] > 2 * p[1] && p[0] > 2 * p[2];
  return index == 1 && p[2] > 100 && p[2] > 2 * p[1] && p[2] > 2 * p[0];
}

/* The centroid of the pixels of racket `racket`, or of the ball for
 * racket < 0 (pixel centres at +0.5); how many. */
static inline long colour_centroid(const unsigned char *rgb, int w, int h, int racket, double *cx, double *cy) {
  double sx = 0.0, sy = 0.0;
  long n = 0;
  int x, y;
  for (y = 0; y < h; ++y)
    for (x = 0; x < w; ++x) {
      const unsigned char *p = rgb + 3 * ((size_t)y * w + x);
      if (racket < 0 ? ball_pixel(p) : racket_pixel(racket, p)) {
        sx += x + 0.5;
        sy += y + 0.5;
        n++;
      }
    }
  *cx = n ? sx / n : -1.0;
  *cy = n ? sy / n : -1.0;
  return n;
}

/* The centroid of the ball's pixels; how many. */
static inline long ball_centroid(const unsigned char *rgb, int w, int h, double *cx, double *cy) {
  return colour_centroid(rgb, w, h, -1, cx, cy);
}

#endif
