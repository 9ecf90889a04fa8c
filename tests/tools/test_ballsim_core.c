/* ballsim's core (libball/tools/ballsim_core.h): the arguments it takes and
 * refuses with which words, the number and text forms of its lines, and a
 * run of a scene whose events are known by hand. */
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "ballsim_core.h"

/* Output captured in memory. */
typedef struct capture {
  char *text;
  size_t size;
  FILE *f;
} capture;

static void cap_open(capture *c) {
  c->text = NULL;
  c->size = 0;
  c->f = open_memstream(&c->text, &c->size);
  assert_non_null(c->f);
}

static const char *cap_text(capture *c) {
  fflush(c->f);
  return c->text ? c->text : "";
}

static void cap_close(capture *c) {
  fclose(c->f);
  free(c->text);
}

/* ballsim_parse_args on a NULL-terminated list after the program name. */
static int parse(ballsim_options *o, capture *out, capture *err, const char *const *args) {
  char *argv[16];
  int argc = 0;
  argv[argc++] = (char *)"ballsim";
  while (*args && argc < 15) argv[argc++] = (char *)*args++;
  argv[argc] = NULL;
  return ballsim_parse_args(argc, argv, o, out->f, err->f);
}

#define ARGS(...) ((const char *const[]){__VA_ARGS__, NULL})

static void refused(const char *const *args, const char *message) {
  ballsim_options o;
  capture out, err;
  cap_open(&out);
  cap_open(&err);
  assert_int_equal(parse(&o, &out, &err, args), BALLSIM_EXIT_USAGE);
  assert_string_equal(cap_text(&err), message);
  assert_string_equal(cap_text(&out), "");
  cap_close(&out);
  cap_close(&err);
}

static void bad_arguments_are_refused_in_one_line(void **state) {
  (void)state;
  refused(ARGS("--fps", "0"), "ballsim: --fps: expected a number > 0, got \"0\" (see ballsim --help)\n");
  refused(ARGS("--fps", " 5"), "ballsim: --fps: expected a number > 0, got \" 5\" (see ballsim --help)\n");
  refused(ARGS("--duration", "nan"),
          "ballsim: --duration: expected a number of seconds > 0, got \"nan\" (see ballsim --help)\n");
  refused(ARGS("--scheme", "euler"),
          "ballsim: --scheme: expected sampled or exact, got \"euler\" (see ballsim --help)\n");
  refused(ARGS("--out", "traj.txt"),
          "ballsim: --out traj.txt: cannot tell the format from the name; add --format csv|jsonl (see ballsim --help)\n");
  refused(ARGS("--format", "csv"), "ballsim: --format needs --out FILE (see ballsim --help)\n");
  refused(ARGS("a.yaml", "b.yaml"), "ballsim: more than one scene given: a.yaml and b.yaml (see ballsim --help)\n");
  refused(ARGS("--bogus=3"), "ballsim: unknown option --bogus (see ballsim --help)\n");
  refused(ARGS("--fps"), "ballsim: --fps needs a value (see ballsim --help)\n");
}

static void good_arguments_fill_the_options(void **state) {
  ballsim_options o;
  capture out, err;
  (void)state;
  cap_open(&out);
  cap_open(&err);
  assert_int_equal(parse(&o, &out, &err, ARGS("s.yaml", "--fps", "6", "--scheme", "sampled", "--out", "t.jsonl")), -1);
  assert_string_equal(o.scene_path, "s.yaml");
  assert_true(o.fps == 6.0 && o.duration == 0.0 && o.scheme == BALL_SCHEME_SAMPLED);
  assert_int_equal(o.format, BALLSIM_FORMAT_JSONL);
  /* a second call starts afresh (the scan's state is reset) */
  assert_int_equal(parse(&o, &out, &err, ARGS("--out", "t.dat", "--format", "csv", "--duration", "2.5")), -1);
  assert_null(o.scene_path);
  assert_true(o.fps == 0.0 && o.duration == 2.5 && o.scheme == -1 && o.format == BALLSIM_FORMAT_CSV);
  assert_int_equal(parse(&o, &out, &err, ARGS("--help")), 0);
  assert_non_null(strstr(cap_text(&out), "usage: ballsim [SCENE]"));
  assert_string_equal(cap_text(&err), "");
  cap_close(&out);
  cap_close(&err);
}

static void numbers_and_text_print_as_documented(void **state) {
  capture c;
  (void)state;
  cap_open(&c);
  ballsim_put_num(c.f, 2.5, 6);
  fputc(' ', c.f);
  ballsim_put_num(c.f, 0.0, 4);
  fputc(' ', c.f);
  ballsim_put_num(c.f, 0.00048828125, 6); /* 2^-11, below 1e-3: all its digits */
  fputc(' ', c.f);
  ballsim_put_num(c.f, 1e9, 6);           /* 1e9 and beyond: %.17g */
  fputc(' ', c.f);
  ballsim_put_num(c.f, -999999999.5, 1);
  fputc(' ', c.f);
  ballsim_put_text(c.f, "a\nb\tc\\d\x01\x7f");
  assert_string_equal(cap_text(&c), "2.500000 0.0000 0.00048828125 1000000000 -999999999.5 a\\nb\\tc\\\\d\\x01\\x7f");
  cap_close(&c);
}

/* A point ball dropped from 1.25 m without drag on a floor of damping 0.5:
 * it lands at t1 = sqrt(2 h / g) = 0.5048 s (g = 9.81) at 4.952 m/s and
 * leaves at 2.476 m/s. */
static const char *const drop_scene =
    "name: drop\nduration: 0.6\nradius: 0.0\nnet: none\neffects: [floor, sound]\nscheme: exact\n"
    "floor:\n  damping: 0.5\n  bounce_threshold: 0.1\n  sound_threshold: 1.0\n"
    "ball:\n  position: [0.0, 1.25, 0.0]\n  velocity: [0.0, 0.0, 0.0]\n";

static void write_file(const char *path, const char *text) {
  FILE *f = fopen(path, "w");
  assert_non_null(f);
  assert_true(fputs(text, f) >= 0);
  assert_int_equal(fclose(f), 0);
}

static void a_run_prints_the_events_and_summary_by_hand(void **state) {
  char dir[] = "/tmp/ballsim_coreXXXXXX", scene[64], traj[64], line[256];
  ballsim_options o;
  capture out, err;
  double t1 = sqrt(2.0 * 1.25 / 9.81), t;
  const char *ev;
  FILE *f;
  int rows = 0;
  (void)state;
  assert_non_null(mkdtemp(dir));
  snprintf(scene, sizeof scene, "%s/drop.yaml", dir);
  snprintf(traj, sizeof traj, "%s/t.csv", dir);
  write_file(scene, drop_scene);
  cap_open(&out);
  cap_open(&err);
  assert_int_equal(parse(&o, &out, &err, ARGS(scene, "--fps", "50", "--out", traj)), -1);
  assert_int_equal(ballsim_run(&o, out.f, err.f, NULL), BALLSIM_EXIT_OK);
  assert_string_equal(cap_text(&err), "");
  ev = strstr(cap_text(&out), "event t=");
  assert_non_null(ev);
  assert_int_equal(sscanf(ev, "event t=%lf", &t), 1);
  assert_true(fabs(t - t1) < 1e-6); /* printed to 6 decimals */
  assert_non_null(strstr(ev, " kind=floor index=0 point=0.000000,0.000000,0.000000 "));
  assert_non_null(strstr(ev, " speed_in=4.9523 speed_out=2.4761 sound=1\n"));
  assert_non_null(strstr(cap_text(&out), "scheme=exact fps=50 dt=0.02 frames=30 effects=floor,sound\n"));
  assert_non_null(strstr(cap_text(&out), "summary: frames=30 time=0.600000 events=1 floor=1 net=0 wall=0 racket=0 "
                                         "sounds=1\n"));
  /* the trajectory: a header, then t = 0 and one row a frame */
  f = fopen(traj, "r");
  assert_non_null(f);
  assert_non_null(fgets(line, sizeof line, f));
  assert_string_equal(line, "t,px,py,pz,vx,vy,vz,sx,sy,sz\n");
  while (fgets(line, sizeof line, f)) rows++;
  assert_int_equal(fclose(f), 0);
  assert_int_equal(rows, 31);
  assert_int_equal(unlink(traj), 0);
  assert_int_equal(unlink(scene), 0);
  assert_int_equal(rmdir(dir), 0);
  cap_close(&out);
  cap_close(&err);
}

static void a_stop_ends_the_run_with_130_and_a_bad_scene_with_1(void **state) {
  static volatile sig_atomic_t stop = 1;
  ballsim_options o;
  capture out, err;
  (void)state;
  cap_open(&out);
  cap_open(&err);
  assert_int_equal(parse(&o, &out, &err, ARGS("--duration", "1")), -1);
  assert_int_equal(ballsim_run(&o, out.f, err.f, &stop), BALLSIM_EXIT_INTERRUPTED);
  assert_non_null(strstr(cap_text(&out), "summary: frames=0 time=0.000000 events=0 "));
  assert_non_null(strstr(cap_text(&out), " interrupted=1\n"));
  assert_int_equal(parse(&o, &out, &err, ARGS("/nonexistent/scene.yaml")), -1);
  assert_int_equal(ballsim_run(&o, out.f, err.f, NULL), BALLSIM_EXIT_ERROR);
  assert_non_null(strstr(cap_text(&err), "/nonexistent/scene.yaml"));
  cap_close(&out);
  cap_close(&err);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(bad_arguments_are_refused_in_one_line),
      cmocka_unit_test(good_arguments_fill_the_options),
      cmocka_unit_test(numbers_and_text_print_as_documented),
      cmocka_unit_test(a_run_prints_the_events_and_summary_by_hand),
      cmocka_unit_test(a_stop_ends_the_run_with_130_and_a_bad_scene_with_1),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
