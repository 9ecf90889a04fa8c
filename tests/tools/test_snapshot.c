/* ballrender's snapshot comparison (libball/tools/snapshot.h): a frame the
 * same as its golden, one channel of one pixel one level over the tolerance
 * and exactly at it, more pixels than --max-pixels, a missing, unreadable or
 * other-size golden; the file and folder names; the line of a comparison. */
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "../unit/core_common.h"
#include "snapshot.h"

#define W 5
#define H 4
#define TOL 8

static char dir[] = "/tmp/ball_snapshot_test_XXXXXX";
static char golden[64];
static unsigned char frame[W * H * 3];

/* A golden of W x H pixels, every channel a different level; the frame a copy. */
static int setup(void **state) {
  int i;
  (void)state;
  if (!mkdtemp(dir)) return -1;
  snprintf(golden, sizeof golden, "%s/t0000.500.png", dir);
  for (i = 0; i < W * H * 3; ++i) frame[i] = (unsigned char)(40 + 3 * i);
  return ball_png_write(golden, frame, W, H) == BALL_OK ? 0 : -1;
}

static int teardown(void **state) {
  char other[64];
  (void)state;
  snprintf(other, sizeof other, "%s/t0001.000.png", dir);
  remove(other);
  remove(golden);
  return rmdir(dir);
}

static snapshot_check compare(const unsigned char *rgb, int tolerance, long max_pixels) {
  snapshot_check c;
  assert_ok(snapshot_compare(golden, rgb, W, H, tolerance, max_pixels, &c, NULL));
  return c;
}

/* The frame itself: same, 0 pixels, 0 levels, no first pixel. */
static void test_same(void **state) {
  snapshot_check c = compare(frame, TOL, 0);
  (void)state;
  assert_int_equal(c.result, SNAPSHOT_SAME);
  assert_int_equal(c.diff.differing, 0);
  assert_int_equal(c.diff.max_diff, 0);
  assert_int_equal(c.diff.first_x, -1);
  assert_int_equal(c.golden_width, W);
  assert_int_equal(c.golden_height, H);
}

/* Green of pixel (3, 2) TOL + 1 levels up differs, at that place, and the
 * diff picture marks it red; TOL levels up passes with max_diff TOL;
 * --max-pixels 1 lets the one pixel pass. */
static void test_one_level_over_the_tolerance(void **state) {
  unsigned char moved[W * H * 3], diff[W * H * 3];
  size_t at = 3 * (2 * W + 3) + 1;
  snapshot_check c;
  (void)state;
  memcpy(moved, frame, sizeof moved);
  moved[at] = (unsigned char)(frame[at] + TOL + 1);
  assert_ok(snapshot_compare(golden, moved, W, H, TOL, 0, &c, diff));
  assert_int_equal(c.result, SNAPSHOT_DIFFERS);
  assert_int_equal(c.diff.differing, 1);
  assert_int_equal(c.diff.max_diff, TOL + 1);
  assert_int_equal(c.diff.first_x, 3);
  assert_int_equal(c.diff.first_y, 2);
  assert_int_equal(diff[at - 1], 255);
  assert_int_equal(diff[at], 0);
  c = compare(moved, TOL, 1);
  assert_int_equal(c.result, SNAPSHOT_SAME);
  assert_int_equal(c.diff.differing, 1);
  moved[at] = (unsigned char)(frame[at] + TOL);
  c = compare(moved, TOL, 0);
  assert_int_equal(c.result, SNAPSHOT_SAME);
  assert_int_equal(c.diff.differing, 0);
  assert_int_equal(c.diff.max_diff, TOL);
  c = compare(moved, 0, 0);
  assert_int_equal(c.result, SNAPSHOT_DIFFERS);
}

/* No golden, a golden that is not a PNG, a golden of another size: each an
 * outcome with what it knows, not an error. Bad arguments are errors. */
static void test_missing_unreadable_other_size(void **state) {
  char other[64];
  snapshot_check c;
  FILE *f;
  (void)state;
  snprintf(other, sizeof other, "%s/t0001.000.png", dir);
  assert_ok(snapshot_compare(other, frame, W, H, TOL, 0, &c, NULL));
  assert_int_equal(c.result, SNAPSHOT_MISSING);
  f = fopen(other, "w");
  assert_non_null(f);
  fputs("not a png\n", f);
  fclose(f);
  assert_ok(snapshot_compare(other, frame, W, H, TOL, 0, &c, NULL));
  assert_int_equal(c.result, SNAPSHOT_UNREADABLE);
  assert_int_equal(c.read_status, BALL_EPARSE);
  assert_string_equal(snapshot_read_error(c.read_status), "not a PNG");
  assert_ok(ball_png_write(other, frame, H, W));
  assert_ok(snapshot_compare(other, frame, W, H, TOL, 0, &c, NULL));
  assert_int_equal(c.result, SNAPSHOT_SIZE);
  assert_int_equal(c.golden_width, H);
  assert_int_equal(c.golden_height, W);
  assert_int_equal(snapshot_compare(NULL, frame, W, H, TOL, 0, &c, NULL), BALL_EINVAL);
  assert_int_equal(snapshot_compare(golden, frame, W, H, 256, 0, &c, NULL), BALL_ERANGE);
  assert_int_equal(snapshot_compare(golden, frame, W, H, TOL, -1, &c, NULL), BALL_ERANGE);
}

static void test_names(void **state) {
  char buf[64];
  (void)state;
  assert_true(snapshot_file_name(buf, sizeof buf, "g", 0.5, NULL));
  assert_string_equal(buf, "g/t0000.500.png");
  assert_true(snapshot_file_name(buf, sizeof buf, "a/g/", 1234.25, ".diff.png"));
  assert_string_equal(buf, "a/g/t1234.250.diff.png");
  assert_false(snapshot_file_name(buf, 10, "g", 0.5, NULL));
  assert_true(snapshot_diff_dir(buf, sizeof buf, "goldens", NULL, NULL));
  assert_string_equal(buf, "goldens-diff");
  assert_true(snapshot_diff_dir(buf, sizeof buf, "ci/goldens//", NULL, NULL));
  assert_string_equal(buf, "ci/goldens-diff");
  assert_true(snapshot_diff_dir(buf, sizeof buf, "goldens", "frames", NULL));
  assert_string_equal(buf, "frames");
  assert_true(snapshot_diff_dir(buf, sizeof buf, "goldens", "frames", "fails"));
  assert_string_equal(buf, "fails");
  assert_true(snapshot_diff_dir(buf, sizeof buf, "a/.g", NULL, NULL));
  assert_string_equal(buf, "a/.g-diff");
  assert_false(snapshot_diff_dir(buf, sizeof buf, ".", NULL, NULL));
  assert_false(snapshot_diff_dir(buf, sizeof buf, "a/..", NULL, NULL));
  assert_false(snapshot_diff_dir(buf, sizeof buf, "/", NULL, NULL));
  assert_false(snapshot_diff_dir(buf, sizeof buf, "", NULL, NULL));
  assert_false(snapshot_diff_dir(buf, 8, "goldens", NULL, NULL));
  assert_string_equal(snapshot_result_name(SNAPSHOT_DIFFERS), "differs");
  assert_null(snapshot_result_name(SNAPSHOT_RESULT_COUNT));
}

/* The line: the fields of each result, and only those. */
static void test_line(void **state) {
  char *text = NULL;
  size_t size = 0;
  FILE *f = open_memstream(&text, &size);
  snapshot_check c;
  (void)state;
  assert_non_null(f);
  memset(&c, 0, sizeof c);
  c.result = SNAPSHOT_DIFFERS;
  c.diff.differing = 84;
  c.diff.max_diff = 178;
  c.diff.first_x = 159;
  c.diff.first_y = 130;
  snapshot_print(f, 5.5, "g/t0005.500.png", &c, W, H, "d/t0005.500.diff.png", "d/t0005.500.png");
  c.result = SNAPSHOT_SIZE;
  c.golden_width = 320;
  c.golden_height = 240;
  snapshot_print(f, 0.25, "g/t0000.250.png", &c, 64, 48, NULL, "d/t0000.250.png");
  c.result = SNAPSHOT_SAME;
  c.diff.differing = 0;
  c.diff.max_diff = 3;
  snapshot_print(f, 1.0, "g/t0001.000.png", &c, W, H, NULL, NULL);
  fclose(f);
  assert_string_equal(text,
                      "compare t=5.500 golden=g/t0005.500.png result=differs differing=84 max_diff=178 first=159,130 "
                      "diff=d/t0005.500.diff.png actual=d/t0005.500.png\n"
                      "compare t=0.250 golden=g/t0000.250.png result=size golden_size=320x240 size=64x48 "
                      "actual=d/t0000.250.png\n"
                      "compare t=1.000 golden=g/t0001.000.png result=same differing=0 max_diff=3\n");
  free(text);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_same),
      cmocka_unit_test(test_one_level_over_the_tolerance),
      cmocka_unit_test(test_missing_unreadable_other_size),
      cmocka_unit_test(test_names),
      cmocka_unit_test(test_line),
  };
  return cmocka_run_group_tests(tests, setup, teardown);
}
