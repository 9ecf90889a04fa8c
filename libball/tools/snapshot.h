/* Snapshot regression: a rendered frame against its golden PNG. ballrender's
 * --compare and the project's own golden tests (render_probe compare) decide
 * with this one function, apart from the process so that tests can drive it
 * (docs/render.md, "Snapshot regression of your own scenes"). Public API of
 * libball::render only; prints only where it is handed a stream. */
#ifndef BALL_TOOLS_SNAPSHOT_H
#define BALL_TOOLS_SNAPSHOT_H

#include <stddef.h>
#include <stdio.h>

#include "ball/render.h"

typedef enum snapshot_result {
  SNAPSHOT_SAME = 0,   /* at most max_pixels pixels differ by more than the tolerance */
  SNAPSHOT_DIFFERS,    /* more than max_pixels do */
  SNAPSHOT_MISSING,    /* no golden file */
  SNAPSHOT_SIZE,       /* the golden has another size */
  SNAPSHOT_UNREADABLE, /* a golden file that cannot be read as a PNG */
  SNAPSHOT_RESULT_COUNT
} snapshot_result;

/* What one comparison found. */
typedef struct snapshot_check {
  snapshot_result result;
  int golden_width, golden_height; /* pixels; 0 when missing or unreadable */
  ball_status read_status;         /* ball_png_read's, BALL_OK unless unreadable */
  ball_image_diff diff;            /* same and differs: ball_image_compare's counts */
} snapshot_check;

/* "same", "differs", "missing", "size", "unreadable"; NULL out of range. */
const char *snapshot_result_name(snapshot_result result);

/* Compares the frame rgb (width x height, rows top first) with the golden
 * PNG at golden_path: a pixel differs when one of its channels is more than
 * tolerance ([0, 255]) apart, and the frame differs when more than
 * max_pixels (>= 0) pixels do. diff_rgb (width * height * 3 bytes, may be
 * NULL) gets ball_image_compare's picture of the differences when the sizes
 * match. Returns BALL_OK with the outcome in *out (a missing, unreadable or
 * other-size golden is an outcome, not an error); BALL_EINVAL, BALL_ERANGE
 * for bad arguments, BALL_ENOMEM. */
ball_status snapshot_compare(const char *golden_path, const unsigned char *rgb, int width, int height, int tolerance,
                             long max_pixels, snapshot_check *out, unsigned char *diff_rgb);

/* Why a golden is unreadable, in words ("not a PNG", ...). */
const char *snapshot_read_error(ball_status read_status);

/* DIR/tSSSS.mmm.png (one slash after DIR), or with suffix ".diff.png" the
 * diff image's name; the time in seconds with milliseconds. Returns 0 if it
 * does not fit in n. */
int snapshot_file_name(char *buf, size_t n, const char *dir, double t, const char *suffix);

/* The folder for the frames that fail and their diff images: diff_dir if
 * given, else out_dir if given, else GOLDEN_DIR-diff beside golden_dir (its
 * trailing slashes dropped). Returns 0 if it does not fit in n, or if
 * golden_dir has no name to add "-diff" to ("", ".", "..", "/", or ending in
 * "/." or "/.."). */
int snapshot_diff_dir(char *buf, size_t n, const char *golden_dir, const char *out_dir, const char *diff_dir);

/* The line of one comparison:
 *   compare t=T golden=PATH result=R [golden_size=WxH size=WxH]
 *           [differing=N max_diff=M [first=X,Y]] [diff=PATH] [actual=PATH]
 * diff_path and actual_path may be NULL (not written). */
void snapshot_print(FILE *out, double t, const char *golden_path, const snapshot_check *check, int width, int height,
                    const char *diff_path, const char *actual_path);

#endif
