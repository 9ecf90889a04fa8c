/* render_probe: the golden-image comparison, the ball finder and a pixel
 * changer of the render tests, over libball::render's PNG functions and
 * ballrender's snapshot comparison (libball/tools/snapshot.h).
 *   render_probe compare EXPECTED ACTUAL DIFF TOLERANCE MAX_PIXELS
 *     passes (exit 0) when at most MAX_PIXELS pixels have a channel more than
 *     TOLERANCE apart; else writes the diff image DIFF and exits 1.
 *   render_probe locate PNG [PX PY MAX_DISTANCE]
 *     the centroid of the ball's pixels (its yellow, any shade); with PX PY,
 *     fails (exit 1) unless it is within MAX_DISTANCE pixels of (PX, PY).
 *   render_probe poke PNG X Y CHANNEL DELTA OUT
 *     writes PNG to OUT with channel CHANNEL (0 red, 1 green, 2 blue) of
 *     pixel (X, Y) DELTA levels away: up, or down where up would pass 255. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ball/render.h"
#include "ball_pixels.h"
#include "snapshot.h"

static int read_png(const char *path, unsigned char **rgb, int *w, int *h) {
  ball_status st = ball_png_read(path, rgb, w, h);
  if (st != BALL_OK) fprintf(stderr, "render_probe: %s: %s\n", path, ball_strerror(st));
  return st == BALL_OK;
}

static int compare(char **argv) {
  unsigned char *b = NULL, *d = NULL;
  int wb, hb, tol = atoi(argv[3]), rc = 1;
  long allowed = atol(argv[4]);
  snapshot_check c;
  if (!read_png(argv[1], &b, &wb, &hb)) return 1;
  d = (unsigned char *)malloc((size_t)wb * hb * 3);
  if (!d || snapshot_compare(argv[0], b, wb, hb, tol, allowed, &c, d) != BALL_OK) goto done;
  if (c.result == SNAPSHOT_SIZE) {
    printf("FAIL %s: %dx%d, the golden %s is %dx%d\n", argv[1], wb, hb, argv[0], c.golden_width, c.golden_height);
    goto done;
  }
  if (c.result != SNAPSHOT_SAME && c.result != SNAPSHOT_DIFFERS) {
    printf("FAIL %s: the golden %s is %s\n", argv[1], argv[0],
           c.result == SNAPSHOT_MISSING ? "missing" : snapshot_read_error(c.read_status));
    goto done;
  }
  printf("%s %s: %dx%d, %ld pixels differ by more than %d (at most %ld allowed), largest difference %d",
         c.result == SNAPSHOT_DIFFERS ? "FAIL" : "ok", argv[1], wb, hb, c.diff.differing, tol, allowed,
         c.diff.max_diff);
  if (c.diff.differing > 0) printf(", first at (%ld, %ld)", c.diff.first_x, c.diff.first_y);
  if (c.result == SNAPSHOT_DIFFERS) {
    printf(", diff image %s", argv[2]);
    if (ball_png_write(argv[2], d, wb, hb) != BALL_OK) printf(" (cannot be written)");
  } else {
    rc = 0;
  }
  printf("\n");
done:
  free(b);
  free(d);
  return rc;
}

static int poke(char **argv) {
  unsigned char *a = NULL;
  int w, h, x = atoi(argv[1]), y = atoi(argv[2]), channel = atoi(argv[3]), delta = atoi(argv[4]), before, rc = 1;
  if (!read_png(argv[0], &a, &w, &h)) return 1;
  before = x >= 0 && x < w && y >= 0 && y < h && channel >= 0 && channel <= 2 ? a[3 * ((size_t)y * w + x) + channel] : -1;
  if (before < 0 || delta < 0 || (before + delta > 255 && before - delta < 0)) {
    fprintf(stderr, "render_probe: poke: no pixel (%d, %d) channel %d in %dx%d, or no room for %d levels\n", x, y,
            channel, w, h, delta);
  } else {
    unsigned char *p = a + 3 * ((size_t)y * w + x) + channel;
    *p = (unsigned char)(before + delta <= 255 ? before + delta : before - delta);
    if (ball_png_write(argv[5], a, w, h) == BALL_OK) {
      printf("poke (%d, %d) channel %d: %d -> %d\n", x, y, channel, before, *p);
      rc = 0;
    } else {
      fprintf(stderr, "render_probe: %s: cannot be written\n", argv[5]);
    }
  }
  free(a);
  return rc;
}

static int locate(int argc, char **argv) {
  unsigned char *a = NULL;
  int w, h;
  double cx, cy;
  long n;
  if (!read_png(argv[0], &a, &w, &h)) return 1;
  n = ball_centroid(a, w, h, &cx, &cy);
  free(a);
  if (n == 0) {
    printf("ball: pixels=0\n");
    return 1;
  }
  printf("ball: pixels=%ld x=%.3f y=%.3f", n, cx, cy);
  if (argc == 4) {
    double dx = cx - atof(argv[1]), dy = cy - atof(argv[2]), dist = sqrt(dx * dx + dy * dy);
    printf(" expected=%s,%s distance=%.3f max=%s %s\n", argv[1], argv[2], dist, argv[3],
           dist <= atof(argv[3]) ? "ok" : "FAIL");
    return dist <= atof(argv[3]) ? 0 : 1;
  }
  printf("\n");
  return 0;
}

int main(int argc, char **argv) {
  if (argc == 7 && strcmp(argv[1], "compare") == 0) return compare(argv + 2);
  if ((argc == 3 || argc == 6) && strcmp(argv[1], "locate") == 0) return locate(argc - 2, argv + 2);
  if (argc == 8 && strcmp(argv[1], "poke") == 0) return poke(argv + 2);
  fprintf(stderr,
          "usage: render_probe compare EXPECTED ACTUAL DIFF TOLERANCE MAX_PIXELS\n"
          "       render_probe locate PNG [PX PY MAX_DISTANCE]\n"
          "       render_probe poke PNG X Y CHANNEL DELTA OUT\n");
  return 2;
}
