/* libball::render: the ball drawn where the camera projects it, the camera
 * presets framing the court, rackets drawn oriented and moving the picture
 * when they move, markers where their events are, the same picture every
 * time, the comparison failing for a ball a few centimetres off, PNG files,
 * the scene replay agreeing with the scene run frame for frame, the render
 * section of scene files, and bad arguments refused. */
#define _POSIX_C_SOURCE 200809L
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <unistd.h>

#include <cmocka.h>

#include "../unit/core_common.h"
#include "ball/render.h"
#include "ball_pixels.h"

#define PI 3.14159265358979323846
#define W 320
#define H 240
/* BALL_GOLDEN_TOLERANCE and BALL_GOLDEN_MAX_PIXELS: the golden frames'
 * comparison (tests/render/golden_cases.cmake, docs/render.md "Tolerance"),
 * given by the build */

static ball_renderer *renderer;
static ball_replay replay_a; /* about 200 kB each: static */
static ball_scene_run run_b;
static ball_scene scene_a;

static int setup(void **state) {
  (void)state;
  return ball_renderer_create(W, H, &renderer) == BALL_OK ? 0 : -1;
}

static int teardown(void **state) {
  (void)state;
  ball_renderer_destroy(renderer);
  return 0;
}

/* A ball of radius 0.1 m over an empty floor. */
static void plain_model(ball_model *m) {
  core_model_free(m);
  m->radius = 0.1;
}

/* 3 m in front of a point 1 m up, looking at it along -z. */
static ball_camera close_camera(void) {
  ball_camera c;
  c.eye = ball_v3(0.0, 1.0, 3.0);
  c.target = ball_v3(0.0, 1.0, 0.0);
  c.up = ball_v3(0.0, 1.0, 0.0);
  c.fov = 40.0;
  return c;
}

static ball_frame ball_only(ball_vec3 p) {
  ball_frame f;
  memset(&f, 0, sizeof f);
  f.ball = p;
  return f;
}

static const unsigned char *draw(const ball_model *m, const ball_camera *c, const ball_frame *f) {
  const unsigned char *rgb;
  int w, h;
  assert_ok(ball_render_draw(renderer, m, c, f));
  assert_ok(ball_render_pixels(renderer, &rgb, &w, &h));
  assert_int_equal(w, W);
  assert_int_equal(h, H);
  return rgb;
}

static void load_scene(const char *name, ball_scene *scene) {
  char path[1024];
  const char *dir = getenv("BALL_SCENES");
  ball_scene_error err;
  snprintf(path, sizeof path, "%s/%s", dir ? dir : "libball/scenes", name);
  if (ball_scene_load_file(path, scene, &err) != BALL_OK) {
    char text[600];
    ball_scene_error_format(&err, text, sizeof text);
    print_error("%s\n", text);
    fail();
  }
}

/* The camera's target is the image's centre; x runs right, y up is up in
 * the picture; a point behind the camera has no pixel. */
static void test_projection_axes(void **state) {
  ball_camera c = close_camera();
  double px, py, depth;
  (void)state;
  assert_ok(ball_camera_project(&c, W, H, c.target, &px, &py, &depth));
  assert_near(px, W / 2.0, 1e-9);
  assert_near(py, H / 2.0, 1e-9);
  assert_near(depth, 3.0, 1e-12);
  /* 0.5 m right at 3 m with a 40 degree vertical view: 0.5 / (3 tan 20) * H / 2 pixels */
  assert_ok(ball_camera_project(&c, W, H, ball_v3(0.5, 1.0, 0.0), &px, &py, NULL));
  assert_near(px, W / 2.0 + 0.5 / (3.0 * tan(20.0 * PI / 180.0)) * H / 2.0, 1e-9);
  assert_ok(ball_camera_project(&c, W, H, ball_v3(0.0, 1.5, 0.0), &px, &py, NULL));
  assert_true(py < H / 2.0 - 30.0);
  assert_int_equal(ball_camera_project(&c, W, H, ball_v3(0.0, 1.0, 4.0), &px, &py, NULL), BALL_ERANGE);
}

/* The ball's pixels are centred where ball_camera_project puts its centre,
 * within 0.5 pixel, at 25 places over the picture. */
static void test_ball_drawn_where_projected(void **state) {
  ball_model m;
  ball_camera c = close_camera();
  int i, j;
  (void)state;
  plain_model(&m);
  for (i = -2; i <= 2; ++i) {
    for (j = -2; j <= 2; ++j) {
      ball_vec3 p = ball_v3(0.4 * i, 1.0 + 0.25 * j, 0.1 * (i + j));
      ball_frame f = ball_only(p);
      const unsigned char *rgb = draw(&m, &c, &f);
      double px, py, cx, cy;
      long n;
      assert_ok(ball_camera_project(&c, W, H, p, &px, &py, NULL));
      n = ball_centroid(rgb, W, H, &cx, &cy);
      assert_true(n > 100); /* radius 0.1 m at about 3 m: 10 pixels */
      assert_near(cx, px, 0.5);
      assert_near(cy, py, 0.5);
    }
  }
}

/* A point ball far away still shows: at least 3 pixels, centred to a pixel. */
static void test_point_ball_visible(void **state) {
  ball_model m;
  ball_camera c;
  ball_frame f;
  double px, py, cx, cy;
  long n;
  (void)state;
  ball_model_default(&m); /* radius 0: the paper's point ball */
  assert_ok(ball_camera_from_preset(&m, BALL_CAMERA_SIDE, (double)W / H, &c));
  f = ball_only(ball_v3(16.0, 1.5, 5.0));
  n = ball_centroid(draw(&m, &c, &f), W, H, &cx, &cy);
  assert_ok(ball_camera_project(&c, W, H, f.ball, &px, &py, NULL));
  assert_true(n >= 3);
  assert_near(cx, px, 1.0);
  assert_near(cy, py, 1.0);
}

/* Each preset frames the court: its four corners and the net's top inside
 * the picture; side and top run the long axis left to right; behind0 sees
 * the near baseline lower in the picture than the far one. */
static void test_presets_frame_the_court(void **state) {
  ball_model m;
  int k, i;
  (void)state;
  ball_model_default(&m);
  for (k = 0; k < BALL_CAMERA_PRESET_COUNT; ++k) {
    ball_camera c;
    double px[4], py[4];
    assert_non_null(ball_camera_preset_name((ball_camera_preset)k));
    assert_ok(ball_camera_from_preset(&m, (ball_camera_preset)k, (double)W / H, &c));
    for (i = 0; i < 4; ++i) {
      ball_vec3 corner = ball_v3(i & 1 ? 23.77 : 0.0, 0.0, i & 2 ? 10.97 : 0.0);
      assert_ok(ball_camera_project(&c, W, H, corner, &px[i], &py[i], NULL));
      assert_true(px[i] >= 0.0 && px[i] <= W && py[i] >= 0.0 && py[i] <= H);
    }
    if (k == BALL_CAMERA_SIDE || k == BALL_CAMERA_TOP) {
      assert_true(px[1] > px[0] + 0.5 * W); /* x = 23.77 well right of x = 0 */
    }
    if (k == BALL_CAMERA_BEHIND0) assert_true(py[0] > py[1]); /* x = 0 nearer: lower */
    if (k == BALL_CAMERA_BEHIND1) assert_true(py[1] > py[0]);
  }
  assert_null(ball_camera_preset_name(BALL_CAMERA_PRESET_COUNT));
}

/* The floor layout is what is drawn: the default court's lines where a
 * tennis court has them (the baseline at x = 0, the service lines 6.40 m
 * from the net), each line's middle white from the top camera and the court
 * between two lines blue; a model without a net gets the 1 m grid. */
static void test_floor_layout_drawn(void **state) {
  ball_model m;
  ball_camera c;
  ball_floor_layout f;
  ball_frame fr = ball_only(ball_v3(-50.0, 0.5, -50.0)); /* the ball off the picture */
  const unsigned char *rgb;
  int i, found_baseline = 0, found_service = 0;
  (void)state;
  ball_model_default(&m);
  assert_int_equal(ball_floor_layout_of(NULL, &f), BALL_EINVAL);
  assert_ok(ball_floor_layout_of(&m, &f));
  assert_int_equal(f.has_court, 1);
  assert_int_equal(f.n_lines, 7);
  assert_near(f.level, m.floor_level, 0.0);
  for (i = 0; i < f.n_lines; ++i) {
    double xm = 0.5 * (f.lines[i][0] + f.lines[i][2]);
    if (fabs(xm - 0.04) < 1e-12) found_baseline = 1; /* 0.08 m wide, inside the court */
    if (fabs(xm - (m.net.position - 6.40 * (23.77 / 2.0) / 11.885)) < 1e-9) found_service = 1;
  }
  assert_true(found_baseline && found_service);
  assert_ok(ball_camera_from_preset(&m, BALL_CAMERA_TOP, (double)W / H, &c));
  rgb = draw(&m, &c, &fr);
  for (i = 0; i < f.n_lines; ++i) {
    ball_vec3 mid = ball_v3(0.5 * (f.lines[i][0] + f.lines[i][2]), f.level, 0.5 * (f.lines[i][1] + f.lines[i][3]));
    double px, py;
    const unsigned char *p;
    assert_ok(ball_camera_project(&c, W, H, mid, &px, &py, NULL));
    p = rgb + 3 * ((size_t)py * W + (size_t)px);
    assert_true(p[0] > 100); /* the line's white, under a pixel wide: at least half of it over the court's 56 red */
  }
  {
    double px, py;
    const unsigned char *p;
    assert_ok(ball_camera_project(&c, W, H, ball_v3(3.0, f.level, 3.0), &px, &py, NULL));
    p = rgb + 3 * ((size_t)py * W + (size_t)px);
    assert_true(p[2] > p[0] + 60); /* the court's blue */
  }
  m.has_net = 0;
  assert_ok(ball_floor_layout_of(&m, &f));
  assert_int_equal(f.has_court, 0);
  assert_int_equal(f.n_lines, 0);
  assert_near(f.grid_step, 1.0, 0.0);
  assert_true(f.ground[0] < f.ground[2] && f.ground[1] < f.ground[3]);
}

/* A court given instead of the net's (a ball server judges its own:
 * MatchInfo's court_x, court_z): the default court given is the net's to
 * 1e-9 m; an 18 m court (court_x_lo 2.885 on the tennis net) gets its
 * baselines 0.04 m inside its ends, service lines 6.40 / 11.885 of each half
 * from the net, and every preset holds its corners; a court larger than the
 * net's (44 m) grows the ground and stays in the picture of each preset,
 * where the net's own presets lose it; bad courts refused. */
static void test_floor_layout_court(void **state) {
  ball_model m;
  ball_floor_layout f, g;
  ball_camera c;
  const double tennis[4] = {0.0, 0.0, 23.77, 10.97}, short_court[4] = {2.885, 0.0, 20.885, 10.97};
  const double big[4] = {-10.0, -3.0, 33.77, 13.97};
  double bad[4] = {0.0, 0.0, 23.77, 10.97};
  int i, k, kept = 0;
  (void)state;
  ball_model_default(&m);
  assert_ok(ball_floor_layout_of(&m, &f));
  assert_ok(ball_floor_layout_court(&m, tennis, &g));
  assert_int_equal(g.n_lines, f.n_lines);
  for (i = 0; i < 4; ++i) assert_near(g.ground[i], f.ground[i], 0.0);
  for (i = 0; i < 4 * f.n_lines; ++i) assert_near(g.lines[i / 4][i % 4], f.lines[i / 4][i % 4], 1e-9);
  assert_ok(ball_floor_layout_court(&m, short_court, &g));
  assert_int_equal(g.n_lines, 7);
  for (i = 0; i < 4; ++i) assert_near(g.court[i], short_court[i], 0.0);
  {
    int baseline_lo = 0, baseline_hi = 0, service = 0;
    for (i = 0; i < g.n_lines; ++i) {
      double xm = 0.5 * (g.lines[i][0] + g.lines[i][2]), len = g.lines[i][3] - g.lines[i][1];
      if (len < 1.0) continue; /* the lines along x */
      baseline_lo += fabs(xm - 2.925) < 1e-12;
      baseline_hi += fabs(xm - 20.845) < 1e-12;
      service += fabs(fabs(xm - m.net.position) - 9.0 * 6.40 / 11.885) < 1e-12;
    }
    assert_int_equal(baseline_lo, 1);
    assert_int_equal(baseline_hi, 1);
    assert_int_equal(service, 2);
  }
  assert_ok(ball_floor_layout_court(&m, big, &g));
  assert_true(g.ground[0] <= -12.0 && g.ground[2] >= 35.77 && g.ground[1] <= -5.0 && g.ground[3] >= 15.97);
  for (k = 0; k < BALL_CAMERA_PRESET_COUNT; ++k) {
    ball_camera n;
    int inside = 1;
    assert_ok(ball_camera_from_preset_court(&m, big, (ball_camera_preset)k, (double)W / H, &c));
    assert_ok(ball_camera_from_preset(&m, (ball_camera_preset)k, (double)W / H, &n));
    for (i = 0; i < 4; ++i) {
      double px, py;
      ball_vec3 corner = ball_v3(big[i & 1 ? 2 : 0], 0.0, big[i & 2 ? 3 : 1]);
      assert_ok(ball_camera_project(&c, W, H, corner, &px, &py, NULL));
      assert_true(px >= 0.0 && px <= W && py >= 0.0 && py <= H);
      if (ball_camera_project(&n, W, H, corner, &px, &py, NULL) != BALL_OK || px < 0.0 || px > W || py < 0.0 || py > H)
        inside = 0;
    }
    kept += inside;
  }
  assert_true(kept < BALL_CAMERA_PRESET_COUNT); /* the net's own presets lose a corner of it */
  assert_int_equal(ball_floor_layout_court(NULL, tennis, &g), BALL_EINVAL);
  assert_int_equal(ball_floor_layout_court(&m, NULL, &g), BALL_EINVAL);
  assert_int_equal(ball_camera_from_preset_court(&m, NULL, BALL_CAMERA_SIDE, 1.0, &c), BALL_EINVAL);
  bad[2] = 0.0;
  assert_int_equal(ball_floor_layout_court(&m, bad, &g), BALL_ERANGE);
  assert_int_equal(ball_camera_from_preset_court(&m, bad, BALL_CAMERA_SIDE, 1.0, &c), BALL_ERANGE);
  bad[2] = NAN;
  assert_int_equal(ball_floor_layout_court(&m, bad, &g), BALL_ENONFINITE);
  bad[2] = 2e9;
  assert_int_equal(ball_floor_layout_court(&m, bad, &g), BALL_ERANGE);
}

/* The palette is what is drawn: from the top camera, with the lights off for
 * the floor, the sky, the ground and the court are ball_render_palette's
 * colours to one level of 255; the racket colours differ from each other and
 * from the ball's yellow, which the tests find the ball by. */
static void test_palette_drawn(void **state) {
  ball_model m;
  ball_camera c;
  ball_palette p;
  ball_floor_layout f;
  ball_frame fr = ball_only(ball_v3(-50.0, 0.5, -50.0));
  const unsigned char *rgb;
  const ball_rgb *want[3];
  double where[3][2];
  int i, j;
  (void)state;
  assert_int_equal(ball_render_palette(NULL), BALL_EINVAL);
  assert_ok(ball_render_palette(&p));
  ball_model_default(&m);
  assert_ok(ball_floor_layout_of(&m, &f));
  assert_ok(ball_camera_from_preset(&m, BALL_CAMERA_SIDE, (double)W / H, &c));
  rgb = draw(&m, &c, &fr);
  want[0] = &p.sky, where[0][0] = 2.0, where[0][1] = 2.0; /* the top-left corner: sky */
  want[1] = &p.court;
  want[2] = &p.ground;
  assert_ok(ball_camera_project(&c, W, H, ball_v3(3.0, f.level, 3.0), &where[1][0], &where[1][1], NULL));
  assert_ok(ball_camera_project(&c, W, H, ball_v3(f.ground[0] + 0.5, f.level, 0.5 * (f.ground[1] + f.ground[3])),
                                &where[2][0], &where[2][1], NULL));
  for (i = 0; i < 3; ++i) {
    const unsigned char *px = rgb + 3 * ((size_t)where[i][1] * W + (size_t)where[i][0]);
    float c3[3];
    c3[0] = want[i]->r, c3[1] = want[i]->g, c3[2] = want[i]->b;
    for (j = 0; j < 3; ++j) assert_true(fabs(px[j] - 255.0 * c3[j]) <= 1.0);
  }
  for (i = 0; i < BALL_MAX_RACKETS; ++i) {
    assert_true(fabs(p.rackets[i].r - p.ball.r) + fabs(p.rackets[i].g - p.ball.g) + fabs(p.rackets[i].b - p.ball.b) > 0.3);
    for (j = 0; j < i; ++j)
      assert_true(fabs(p.rackets[i].r - p.rackets[j].r) + fabs(p.rackets[i].g - p.rackets[j].g) +
                      fabs(p.rackets[i].b - p.rackets[j].b) > 0.3);
  }
}

/* Cameras by name: presets, the scene's own first; unknown names refused. */
static void test_camera_find(void **state) {
  ball_scene s;
  ball_camera a, b;
  (void)state;
  ball_scene_default(&s);
  assert_ok(ball_camera_find(&s, "top", 4.0 / 3.0, &a));
  assert_ok(ball_camera_from_preset(&s.model, BALL_CAMERA_TOP, 4.0 / 3.0, &b));
  assert_memory_equal(&a, &b, sizeof a);
  assert_int_equal(ball_camera_find(&s, "front", 4.0 / 3.0, &a), BALL_ENOTFOUND);
  s.render.n_cameras = 1;
  strcpy(s.render.cameras[0].name, "top");
  s.render.cameras[0].camera = close_camera();
  assert_ok(ball_camera_find(&s, "top", 4.0 / 3.0, &a));
  assert_near(a.eye.z, 3.0, 0.0);
}

/* A racket disc facing the camera covers pi r^2 of its colour (to 10 %); the
 * same disc edge-on covers almost none. Racket 0 is red. */
static void test_racket_oriented(void **state) {
  ball_model m;
  ball_camera c = close_camera();
  ball_frame f;
  long facing = 0, edge_on = 0;
  double pixel = 2.0 * 3.0 * tan(20.0 * PI / 180.0) / H, r_px;
  int k, i;
  (void)state;
  plain_model(&m);
  m.n_rackets = 1;
  m.rackets[0].radius = 0.15;
  r_px = 0.15 / pixel;
  for (k = 0; k < 2; ++k) {
    const unsigned char *rgb;
    f = ball_only(ball_v3(0.0, 3.0, -20.0)); /* the ball out of the way */
    f.n_rackets = 1;
    f.rackets[0].visible = 1;
    f.rackets[0].center = ball_v3(0.0, 1.0, 0.0);
    f.rackets[0].normal = k == 0 ? ball_v3(0.0, 0.0, 2.0) : ball_v3(1.0, 0.0, 0.0);
    rgb = draw(&m, &c, &f);
    for (i = 0; i < W * H; ++i)
      if (racket_pixel(0, rgb + 3 * i)) ++*(k == 0 ? &facing : &edge_on);
  }
  assert_near((double)facing, PI * r_px * r_px, 0.1 * PI * r_px * r_px);
  assert_true(edge_on < 0.05 * facing);
}

/* Rackets move the picture: racket 0 (red) and racket 1 (blue), each facing
 * the camera 2.8 m away, cover pi r^2 of their own colour (to 10 %, none of
 * the other's) centred within 0.5 pixel of where ball_camera_project puts
 * their centres; the same pose again gives 0 differing pixels; the centre
 * 5 cm to the side (5.9 pixels here) changes more pixels than a golden
 * frame may differ in (about 570), by more than the goldens' tolerance, and
 * moves the racket's pixels as far as the projection moves, to 0.5 pixel. */
static void test_racket_moved_changes_the_frame(void **state) {
  static unsigned char before[W * H * 3];
  ball_model m;
  ball_camera c = close_camera();
  double r_px = 0.15 / (2.0 * 2.8 * tan(20.0 * PI / 180.0) / H); /* at 2.8 m: 17.7 pixels */
  int k;
  (void)state;
  plain_model(&m);
  m.n_rackets = 2;
  m.rackets[0].radius = m.rackets[1].radius = 0.15;
  for (k = 0; k < 2; ++k) {
    ball_frame f = ball_only(ball_v3(0.0, 3.0, -20.0)); /* the ball out of the way */
    ball_image_diff d;
    double px, py, px2, py2, cx, cy, cx2, cy2;
    long n;
    f.n_rackets = 2;
    f.rackets[k].visible = 1;
    f.rackets[k].center = ball_v3(k == 0 ? -0.4 : 0.3, 1.1, 0.2);
    f.rackets[k].normal = ball_v3(0.0, 0.0, 1.0);
    memcpy(before, draw(&m, &c, &f), sizeof before);
    assert_ok(ball_camera_project(&c, W, H, f.rackets[k].center, &px, &py, NULL));
    n = colour_centroid(before, W, H, k, &cx, &cy);
    assert_near((double)n, PI * r_px * r_px, 0.1 * PI * r_px * r_px);
    assert_near(cx, px, 0.5);
    assert_near(cy, py, 0.5);
    assert_int_equal(colour_centroid(before, W, H, 1 - k, &cx2, &cy2), 0);

    assert_ok(ball_image_compare(before, draw(&m, &c, &f), W, H, BALL_GOLDEN_TOLERANCE, &d, NULL));
    assert_int_equal(d.differing, 0);

    f.rackets[k].center.x += 0.05;
    assert_ok(ball_image_compare(before, draw(&m, &c, &f), W, H, BALL_GOLDEN_TOLERANCE, &d, NULL));
    print_message("racket %d moved 5 cm: %ld pixels differ by more than %d, largest difference %d\n", k, d.differing,
                  BALL_GOLDEN_TOLERANCE, d.max_diff);
    assert_true(d.differing > BALL_GOLDEN_MAX_PIXELS);
    assert_true(d.max_diff > BALL_GOLDEN_TOLERANCE);
    assert_ok(ball_camera_project(&c, W, H, f.rackets[k].center, &px2, &py2, NULL));
    assert_true(px2 - px > 5.0); /* visible from the camera: across its view */
    colour_centroid(draw(&m, &c, &f), W, H, k, &cx2, &cy2);
    assert_near(cx2 - cx, px2 - px, 0.5);
    assert_near(cy2 - cy, 0.0, 0.5);
  }
}

/* An event's marker changes pixels only near the event's point. */
static void test_markers_at_events(void **state) {
  ball_model m;
  ball_camera c = close_camera();
  static unsigned char before[W * H * 3];
  int kind;
  (void)state;
  plain_model(&m);
  m.has_net = 1;
  m.net.axis = 0;
  m.net.position = 5.0; /* out of the picture */
  m.net.lo = 0.0;
  m.net.hi = 1.0;
  m.net.bottom = 0.0;
  m.net.top = 1.0;
  for (kind = 0; kind < BALL_EVENT_KIND_COUNT; ++kind) {
    ball_frame f = ball_only(ball_v3(0.0, 3.0, -20.0));
    ball_event e;
    const unsigned char *rgb;
    double px, py;
    long changed = 0, far = 0;
    int x, y;
    memcpy(before, draw(&m, &c, &f), sizeof before);
    memset(&e, 0, sizeof e);
    e.kind = (ball_event_kind)kind;
    e.point = ball_v3(0.3, 1.2, 0.0);
    f.n_events = 1;
    f.events = &e;
    rgb = draw(&m, &c, &f);
    assert_ok(ball_camera_project(&c, W, H, e.point, &px, &py, NULL));
    for (y = 0; y < H; ++y)
      for (x = 0; x < W; ++x) {
        size_t i = 3 * ((size_t)y * W + x);
        if (memcmp(rgb + i, before + i, 3) == 0) continue;
        changed++;
        /* marker radius 0.25 m = 21 pixels here; a floor marker lies on the floor below */
        if (kind != BALL_EVENT_FLOOR && hypot(x + 0.5 - px, y + 0.5 - py) > 30.0) far++;
      }
    assert_true(changed > 20);
    assert_int_equal(far, 0);
  }
}

/* The same frame twice, with other frames between, gives the same bytes. */
static void test_same_picture_every_time(void **state) {
  static unsigned char first[W * H * 3];
  ball_model m;
  ball_camera c;
  ball_frame f, g;
  ball_vec3 trail[3];
  (void)state;
  ball_model_default(&m);
  assert_ok(ball_camera_from_preset(&m, BALL_CAMERA_BEHIND0, (double)W / H, &c));
  f = ball_only(ball_v3(8.0, 1.0, 4.0));
  trail[0] = ball_v3(4.0, 1.0, 4.0);
  trail[1] = ball_v3(6.0, 1.5, 4.0);
  trail[2] = f.ball;
  f.n_trail = 3;
  f.trail = trail;
  memcpy(first, draw(&m, &c, &f), sizeof first);
  g = ball_only(ball_v3(15.0, 0.5, 2.0));
  draw(&m, &c, &g);
  assert_memory_equal(draw(&m, &c, &f), first, sizeof first);
}

/* The comparison: identical pictures pass with 0 differing pixels; a ball
 * 3 cm off (3.5 pixels here) differs in far more pixels than the goldens
 * allow (BALL_GOLDEN_MAX_PIXELS, 20), by far more than their tolerance
 * (BALL_GOLDEN_TOLERANCE, 8); the diff image marks them red. */
static void test_compare_catches_a_few_centimetres(void **state) {
  static unsigned char a[W * H * 3], diff[W * H * 3];
  ball_model m;
  ball_camera c = close_camera();
  ball_frame f;
  ball_image_diff d;
  long red = 0;
  int i;
  (void)state;
  plain_model(&m);
  f = ball_only(ball_v3(0.0, 1.0, 0.0));
  memcpy(a, draw(&m, &c, &f), sizeof a);
  assert_ok(ball_image_compare(a, draw(&m, &c, &f), W, H, BALL_GOLDEN_TOLERANCE, &d, diff));
  assert_int_equal(d.differing, 0);
  assert_int_equal(d.max_diff, 0);
  assert_int_equal(d.first_x, -1);
  f.ball.x += 0.03;
  assert_ok(ball_image_compare(a, draw(&m, &c, &f), W, H, BALL_GOLDEN_TOLERANCE, &d, diff));
  assert_true(d.differing > 100);
  assert_true(d.max_diff > 100);
  assert_true(d.first_x >= 0 && d.first_y >= 0);
  for (i = 0; i < W * H; ++i)
    if (diff[3 * i] == 255 && diff[3 * i + 1] == 0 && diff[3 * i + 2] == 0) red++;
  assert_int_equal(red, d.differing);
  assert_int_equal(ball_image_compare(a, a, W, H, 256, &d, NULL), BALL_ERANGE);
}

/* PNG: what is written is read back bit for bit; a file that is not a PNG,
 * a missing file and a folder that does not exist are reported. */
static void test_png_round_trip(void **state) {
  static unsigned char img[37 * 23 * 3];
  unsigned char *back = NULL;
  char path[] = "/tmp/ball_render_test_XXXXXX";
  int fd, w, h, i;
  (void)state;
  for (i = 0; i < (int)sizeof img; ++i) img[i] = (unsigned char)(i * 7 + i / 3);
  fd = mkstemp(path);
  assert_true(fd >= 0);
  close(fd);
  assert_ok(ball_png_write(path, img, 37, 23));
  assert_ok(ball_png_read(path, &back, &w, &h));
  assert_int_equal(w, 37);
  assert_int_equal(h, 23);
  assert_memory_equal(back, img, sizeof img);
  free(back);
  {
    FILE *f = fopen(path, "wb");
    assert_non_null(f);
    fputs("not a png\n", f);
    fclose(f);
  }
  assert_int_equal(ball_png_read(path, &back, &w, &h), BALL_EPARSE);
  remove(path);
  assert_int_equal(ball_png_read(path, &back, &w, &h), BALL_EIO);
  assert_int_equal(ball_png_write("/nonexistent-folder/x.png", img, 37, 23), BALL_EIO);
}

/* The replay is the scene run: at frame times its ball is the run's ball to
 * the bit, the rackets are drawn where the sim estimates them, and time does
 * not go back. */
static void test_replay_is_the_scene_run(void **state) {
  ball_frame f;
  int k, next = 0;
  (void)state;
  load_scene("rally_mid.yaml", &scene_a);
  assert_ok(ball_replay_init(&replay_a, &scene_a, 0.5, 1.0));
  assert_ok(ball_scene_run_init(&run_b, &scene_a));
  for (k = 0; k <= 120; ++k) {
    ball_state s;
    if (k % 15 != 0) continue;
    while (next < k) {
      assert_ok(ball_scene_run_step(&run_b, NULL, 0, NULL));
      next++;
    }
    assert_ok(ball_replay_frame(&replay_a, k / 60.0, &f));
    assert_ok(ball_sim_state(&run_b.sim, &s));
    assert_memory_equal(&f.ball, &s.position, sizeof s.position);
    assert_int_equal(f.n_rackets, 2);
    if (k > 0) {
      ball_racket_pose pose;
      assert_ok(ball_racket_estimate(&run_b.sim, 0, k / 60.0, &pose));
      assert_int_equal(f.rackets[0].visible, 1);
      assert_memory_equal(&f.rackets[0].center, &pose.center, sizeof pose.center);
    }
  }
  assert_int_equal(ball_replay_frame(&replay_a, 1.0, &f), BALL_ERANGE);
}

/* Trail and markers: the serve bounces at t = 0.728 s. At t = 1 s with a
 * 0.5 s trail: the frames at 0.5 .. 1 s (31 of them at 60 Hz) plus the ball
 * now; one floor marker within 1 s. At 1.8 s the bounce is older than 1 s. */
static void test_replay_trail_and_markers(void **state) {
  ball_frame f;
  (void)state;
  ball_scene_default(&scene_a);
  assert_ok(ball_replay_init(&replay_a, &scene_a, 0.5, 1.0));
  assert_ok(ball_replay_frame(&replay_a, 1.0, &f));
  assert_int_equal(f.n_trail, 32);
  assert_memory_equal(&f.trail[31], &f.ball, sizeof f.ball);
  assert_true(f.trail[0].x < f.trail[30].x);
  assert_int_equal(f.n_events, 1);
  assert_int_equal(f.events[0].kind, BALL_EVENT_FLOOR);
  assert_near(f.events[0].time, 0.728, 1e-3);
  assert_ok(ball_replay_frame(&replay_a, 1.8, &f));
  assert_int_equal(f.n_events, 0);
  assert_ok(ball_replay_init(&replay_a, &scene_a, 0.0, 0.0));
  assert_ok(ball_replay_frame(&replay_a, 1.0, &f));
  assert_int_equal(f.n_trail, 0);
  assert_int_equal(f.n_events, 0);
  assert_int_equal(ball_replay_init(&replay_a, &scene_a, 61.0, 0.0), BALL_ERANGE);
}

/* The render section of a scene file: cameras with defaults (up y, 45
 * degrees), trail and markers; mistakes located like every scene error. */
static void test_scene_render_section(void **state) {
  static const char good[] =
      "render:\n"
      "  trail: 2\n"
      "  cameras:\n"
      "    - {name: a, eye: [0, 2, 5], target: [0, 1, 0]}\n"
      "    - {name: b-2, eye: [0, 9, 0], target: [0, 0, 0], up: [1, 0, 0], fov: 30}\n";
  static const struct {
    const char *text, *error;
  } bad[] = {
      {"render: {cameras: [{name: a, eye: [0, 2, 5], target: [0, 2, 5]}]}",
       "t:1:20: render.cameras[0]: target must be away from eye"},
      {"render: {cameras: [{name: a, eye: [0, 9, 0], target: [0, 0, 0]}]}",
       "t:1:20: render.cameras[0]: up must not be zero or along target - eye"},
      {"render: {cameras: [{name: a, eye: [0, 2, 5], target: [0, 0, 0]}, {name: a, eye: [0, 2, 5], target: [0, 0, 0]}]}",
       "t:1:73: render.cameras[1].name: camera \"a\" named twice"},
      {"render: {cameras: [{name: 'a b', eye: [0, 2, 5], target: [0, 0, 0]}]}",
       "t:1:27: render.cameras[0].name: \"a b\": a name takes letters, digits, '_' and '-' only"},
      {"render: {cameras: [{eye: [0, 2, 5], target: [0, 0, 0]}]}",
       "t:1:20: render.cameras[0].name: missing required key \"name\""},
      {"render: {markers: -1}", "t:1:19: render.markers: out of range: must be in [0, 60] s, got -1"},
      {"render: {zoom: 2}", "t:1:10: render.zoom: unknown key \"zoom\""},
  };
  ball_scene_error err;
  char text[600];
  size_t i;
  (void)state;
  assert_ok(ball_scene_load_string(good, sizeof good - 1, "t", &scene_a, &err));
  assert_near(scene_a.render.trail, 2.0, 0.0);
  assert_near(scene_a.render.markers, 1.0, 0.0);
  assert_int_equal(scene_a.render.n_cameras, 2);
  assert_string_equal(scene_a.render.cameras[1].name, "b-2");
  assert_near(scene_a.render.cameras[0].camera.fov, 45.0, 0.0);
  assert_near(scene_a.render.cameras[0].camera.up.y, 1.0, 0.0);
  assert_near(scene_a.render.cameras[1].camera.up.x, 1.0, 0.0);
  for (i = 0; i < sizeof bad / sizeof bad[0]; ++i) {
    assert_int_equal(ball_scene_load_string(bad[i].text, strlen(bad[i].text), "t", &scene_a, &err), BALL_EPARSE);
    ball_scene_error_format(&err, text, sizeof text);
    assert_string_equal(text, bad[i].error);
  }
}

/* Bad arguments are refused and leave the last picture as it was. */
static void test_bad_arguments(void **state) {
  static unsigned char last[W * H * 3];
  ball_renderer *r = NULL;
  ball_model m;
  ball_camera c = close_camera();
  ball_frame f;
  const unsigned char *rgb;
  (void)state;
  plain_model(&m);
  assert_int_equal(ball_renderer_create(BALL_RENDER_MIN_SIZE - 1, 100, &r), BALL_ERANGE);
  assert_int_equal(ball_renderer_create(100, BALL_RENDER_MAX_SIZE + 1, &r), BALL_ERANGE);
  assert_null(r);
  ball_renderer_destroy(NULL);
  f = ball_only(ball_v3(0.0, 1.0, 0.0));
  memcpy(last, draw(&m, &c, &f), sizeof last);
  f.ball.x = NAN;
  assert_int_equal(ball_render_draw(renderer, &m, &c, &f), BALL_ENONFINITE);
  f.ball.x = 0.3;
  f.n_rackets = 1; /* the model has none */
  assert_int_equal(ball_render_draw(renderer, &m, &c, &f), BALL_ERANGE);
  f.n_rackets = 0;
  f.n_trail = 2; /* and no points */
  assert_int_equal(ball_render_draw(renderer, &m, &c, &f), BALL_EINVAL);
  f.n_trail = 0;
  c.fov = 0.5;
  assert_int_equal(ball_render_draw(renderer, &m, &c, &f), BALL_ERANGE);
  c = close_camera();
  c.target = c.eye;
  assert_int_equal(ball_render_draw(renderer, &m, &c, &f), BALL_ERANGE);
  assert_int_equal(ball_render_draw(renderer, &m, NULL, &f), BALL_EINVAL);
  assert_ok(ball_render_pixels(renderer, &rgb, NULL, NULL));
  assert_memory_equal(rgb, last, sizeof last);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(test_projection_axes),
      cmocka_unit_test(test_ball_drawn_where_projected),
      cmocka_unit_test(test_point_ball_visible),
      cmocka_unit_test(test_presets_frame_the_court),
      cmocka_unit_test(test_floor_layout_drawn),
      cmocka_unit_test(test_floor_layout_court),
      cmocka_unit_test(test_palette_drawn),
      cmocka_unit_test(test_camera_find),
      cmocka_unit_test(test_racket_oriented),
      cmocka_unit_test(test_racket_moved_changes_the_frame),
      cmocka_unit_test(test_markers_at_events),
      cmocka_unit_test(test_same_picture_every_time),
      cmocka_unit_test(test_compare_catches_a_few_centimetres),
      cmocka_unit_test(test_png_round_trip),
      cmocka_unit_test(test_replay_is_the_scene_run),
      cmocka_unit_test(test_replay_trail_and_markers),
      cmocka_unit_test(test_scene_render_section),
      cmocka_unit_test(test_bad_arguments),
  };
  return cmocka_run_group_tests(tests, setup, teardown);
}
