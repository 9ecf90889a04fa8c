/* render_probe: the golden-image comparison and the ball finder of the
 * render tests, over libball::render's PNG functions and ballrender's
 * snapshot comparison (libball/tools/snapshot.h).
 *   render_probe compare EXPECTED ACTUAL DIFF TOLERANCE MAX_PIXELS
 *     passes (exit 0) when at most MAX_PIXELS pixels have a channel more than
 *     TOLERANCE apart; else writes the diff image DIFF and exits 1.
 *   render_probe locate PNG [PX PY MAX_DISTANCE]
 *     the centroid of the ball's pixels (its yellow, any shade); with PX PY,
 *     fails (exit 1) unless it is within MAX_DISTANCE pixels of (PX, PY). */
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
  fprintf(stderr,
          "usage: render_probe compare EXPECTED ACTUAL DIFF TOLERANCE MAX_PIXELS\n"
          "       render_probe locate PNG [PX PY MAX_DISTANCE]\n");
  return 2;
}
