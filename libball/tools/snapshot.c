/* Snapshot regression (snapshot.h): a frame against its golden PNG, the
 * names of the files, the line of a comparison. docs/render.md, "Snapshot
 * regression of your own scenes". */
#define _POSIX_C_SOURCE 200809L

#include "snapshot.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

const char *snapshot_result_name(snapshot_result result) {
  static const char *const names[SNAPSHOT_RESULT_COUNT] = {"same", "differs", "missing", "size", "unreadable"};
  return (int)result >= 0 && result < SNAPSHOT_RESULT_COUNT ? names[result] : NULL;
}

const char *snapshot_read_error(ball_status read_status) {
  switch (read_status) {
    case BALL_OK: return "read";
    case BALL_EPARSE: return "not a PNG";
    case BALL_ERANGE: return "larger than 65536 pixels a side";
    case BALL_ENOMEM: return "out of memory";
    default: return "cannot be read";
  }
}

ball_status snapshot_compare(const char *golden_path, const unsigned char *rgb, int width, int height, int tolerance,
                             long max_pixels, snapshot_check *out, unsigned char *diff_rgb) {
  struct stat sb;
  unsigned char *golden = NULL;
  ball_status st;
  if (!golden_path || !rgb || !out) return BALL_EINVAL;
  if (width < 1 || height < 1 || tolerance < 0 || tolerance > 255 || max_pixels < 0) return BALL_ERANGE;
  memset(out, 0, sizeof *out);
  out->diff.first_x = out->diff.first_y = -1;
  /* missing is the one failure a user fixes with --update: tell it apart */
  if (stat(golden_path, &sb) != 0 && errno == ENOENT) {
    out->result = SNAPSHOT_MISSING;
    return BALL_OK;
  }
  st = ball_png_read(golden_path, &golden, &out->golden_width, &out->golden_height);
  if (st == BALL_ENOMEM) return st;
  if (st != BALL_OK) {
    out->result = SNAPSHOT_UNREADABLE;
    out->read_status = st;
    out->golden_width = out->golden_height = 0;
    return BALL_OK;
  }
  if (out->golden_width != width || out->golden_height != height) {
    out->result = SNAPSHOT_SIZE;
    free(golden);
    return BALL_OK;
  }
  st = ball_image_compare(golden, rgb, width, height, tolerance, &out->diff, diff_rgb);
  free(golden);
  if (st != BALL_OK) return st;
  out->result = out->diff.differing > max_pixels ? SNAPSHOT_DIFFERS : SNAPSHOT_SAME;
  return BALL_OK;
}

int snapshot_file_name(char *buf, size_t n, const char *dir, double t, const char *suffix) {
  size_t d = strlen(dir);
  int len = snprintf(buf, n, "%s%st%08.3f%s", dir, d > 0 && dir[d - 1] == '/' ? "" : "/", t, suffix ? suffix : ".png");
  return len >= 0 && (size_t)len < n;
}

int snapshot_diff_dir(char *buf, size_t n, const char *golden_dir, const char *out_dir, const char *diff_dir) {
  size_t len;
  const char *base;
  int written;
  if (diff_dir || out_dir) {
    written = snprintf(buf, n, "%s", diff_dir ? diff_dir : out_dir);
    return written >= 0 && (size_t)written < n;
  }
  len = strlen(golden_dir);
  while (len > 0 && golden_dir[len - 1] == '/') --len;
  base = golden_dir + len; /* the last name of the path */
  while (base > golden_dir && base[-1] != '/') --base;
  if (len == 0 || (golden_dir + len - base == 1 && base[0] == '.') ||
      (golden_dir + len - base == 2 && base[0] == '.' && base[1] == '.'))
    return 0;
  written = snprintf(buf, n, "%.*s-diff", (int)len, golden_dir);
  return written >= 0 && (size_t)written < n;
}

void snapshot_print(FILE *out, double t, const char *golden_path, const snapshot_check *check, int width, int height,
                    const char *diff_path, const char *actual_path) {
  fprintf(out, "compare t=%.3f golden=%s result=%s", t, golden_path, snapshot_result_name(check->result));
  if (check->result == SNAPSHOT_SIZE)
    fprintf(out, " golden_size=%dx%d size=%dx%d", check->golden_width, check->golden_height, width, height);
  if (check->result == SNAPSHOT_SAME || check->result == SNAPSHOT_DIFFERS) {
    fprintf(out, " differing=%ld max_diff=%d", check->diff.differing, check->diff.max_diff);
    if (check->diff.differing > 0) fprintf(out, " first=%ld,%ld", check->diff.first_x, check->diff.first_y);
  }
  if (diff_path) fprintf(out, " diff=%s", diff_path);
  if (actual_path) fprintf(out, " actual=%s", actual_path);
  fputc('\n', out);
}
