/* Scene files (docs/scenes.md): every example loads, every key lands in its
 * model field, bad files are rejected with the file, line, column and field,
 * and a failed load leaves the scene as it was. */
#include <errno.h>
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <cmocka.h>

#include "ball/ball.h"
#include "ball/scene.h"

static const char *scenes_dir(void) {
  const char *d = getenv("BALL_SCENES");
  return d && *d ? d : "libball/scenes";
}

static ball_status load_example(const char *file, ball_scene *scene, ball_scene_error *err) {
  char path[1024];
  snprintf(path, sizeof path, "%s/%s", scenes_dir(), file);
  return ball_scene_load_file(path, scene, err);
}

static ball_status load_text(const char *text, ball_scene *scene, ball_scene_error *err) {
  return ball_scene_load_string(text, strlen(text), "mem.yaml", scene, err);
}

static void assert_vec(ball_vec3 v, double x, double y, double z) {
  assert_true(v.x == x);
  assert_true(v.y == y);
  assert_true(v.z == z);
}

/* Exactly equal, field by field (the struct has padding, so no memcmp). */
static void assert_plane_equal(const ball_plane *a, const ball_plane *b) {
  assert_int_equal(a->axis, b->axis);
  assert_true(a->position == b->position && a->lo == b->lo && a->hi == b->hi);
  assert_true(a->bottom == b->bottom && a->top == b->top && a->damping == b->damping);
}

static void assert_model_equal(const ball_model *a, const ball_model *b) {
  int i;
  assert_true(a->gravity == b->gravity && a->mass == b->mass && a->air_friction == b->air_friction);
  assert_true(a->radius == b->radius && a->spin_damping == b->spin_damping);
  assert_true(a->floor_level == b->floor_level && a->floor_damping == b->floor_damping);
  assert_true(a->bounce_threshold == b->bounce_threshold && a->sound_threshold == b->sound_threshold);
  assert_true(a->spin_floor_damping == b->spin_floor_damping);
  assert_int_equal(a->has_net, b->has_net);
  assert_plane_equal(&a->net, &b->net);
  assert_int_equal(a->n_walls, b->n_walls);
  for (i = 0; i < a->n_walls; ++i) assert_plane_equal(&a->walls[i], &b->walls[i]);
  assert_int_equal(a->n_rackets, b->n_rackets);
  for (i = 0; i < a->n_rackets; ++i) {
    assert_true(a->rackets[i].radius == b->rackets[i].radius);
    assert_int_equal(a->rackets[i].partner, b->rackets[i].partner);
    assert_vec(a->rackets[i].target, b->rackets[i].target.x, b->rackets[i].target.y, b->rackets[i].target.z);
  }
  assert_int_equal(a->detect, b->detect);
  assert_int_equal(a->normal_mode, b->normal_mode);
  assert_int_equal(a->response, b->response);
  assert_true(a->collision_distance == b->collision_distance);
  assert_int_equal(a->sleep_frames, b->sleep_frames);
  assert_true(a->v_min == b->v_min && a->v_max == b->v_max && a->v_up == b->v_up);
  assert_int_equal(a->v_up_from_racket, b->v_up_from_racket);
  assert_true(a->friendly_factor == b->friendly_factor && a->spin_rack_damping == b->spin_rack_damping);
  assert_int_equal(a->history, b->history);
  assert_true(a->extrapolation_time == b->extrapolation_time && a->stale_time == b->stale_time);
  assert_int_equal(a->effects, b->effects);
  assert_int_equal(a->scheme, b->scheme);
  assert_int_equal(a->level, b->level);
  assert_vec(a->initial_position, b->initial_position.x, b->initial_position.y, b->initial_position.z);
  assert_vec(a->initial_velocity, b->initial_velocity.x, b->initial_velocity.y, b->initial_velocity.z);
  assert_vec(a->initial_spin, b->initial_spin.x, b->initial_spin.y, b->initial_spin.z);
}

/* Loads text that must fail; checks status, line, column (0: not checked) and field. */
static void assert_rejected(const char *text, int line, int column, const char *field) {
  ball_scene scene;
  ball_scene_error err;
  ball_status st;
  memset(&scene, 0, sizeof scene);
  st = load_text(text, &scene, &err);
  if (st != BALL_EPARSE || err.line != line || (column && err.column != column) || strcmp(err.field, field) != 0)
    print_error("text:\n%s\ngot status %d at %d:%d field \"%s\": %s\n", text, (int)st, err.line, err.column,
                err.field, err.message);
  assert_int_equal(st, BALL_EPARSE);
  assert_string_equal(err.file, "mem.yaml");
  assert_int_equal(err.line, line);
  if (column) assert_int_equal(err.column, column);
  assert_string_equal(err.field, field);
  assert_true(err.message[0] != '\0');
}

static void every_example_scene_loads_and_passes_the_model_check(void **state) {
  static const char *const files[] = {"tennis.yaml", "football_wall.yaml", "dropped_ball.yaml", "darts.yaml",
                                      "juggling.yaml"};
  static const char *const names[] = {"tennis", "football_wall", "dropped_ball", "darts", "juggling"};
  size_t i;
  (void)state;
  for (i = 0; i < sizeof files / sizeof files[0]; ++i) {
    ball_scene scene;
    ball_scene_error err;
    ball_status st = load_example(files[i], &scene, &err);
    if (st != BALL_OK) print_error("%s:%d:%d: %s: %s\n", err.file, err.line, err.column, err.field, err.message);
    assert_int_equal(st, BALL_OK);
    assert_string_equal(scene.name, names[i]);
    assert_true(scene.duration > 0.0);
    assert_int_equal(ball_model_check(&scene.model, NULL), BALL_OK);
  }
}

static void tennis_yaml_is_the_builtin_default_scene(void **state) {
  ball_scene file, builtin;
  ball_model def;
  (void)state;
  assert_int_equal(load_example("tennis.yaml", &file, NULL), BALL_OK);
  ball_scene_default(&builtin);
  assert_string_equal(file.name, builtin.name);
  assert_true(file.duration == builtin.duration);
  assert_model_equal(&file.model, &builtin.model);
  /* and the built-in scene is ball_model_default itself */
  ball_model_default(&def);
  assert_model_equal(&builtin.model, &def);
}

static void example_scenes_state_their_effects_exactly(void **state) {
  ball_scene s;
  (void)state;
  assert_int_equal(load_example("juggling.yaml", &s, NULL), BALL_OK);
  assert_int_equal(s.model.effects, BALL_EFFECT_FLOOR | BALL_EFFECT_SOUND); /* drag-free */
  assert_int_equal(s.model.has_net, 0);
  assert_int_equal(load_example("darts.yaml", &s, NULL), BALL_OK);
  assert_int_equal(s.model.effects & BALL_EFFECT_SPIN, 0u); /* a dart does not spin */
  assert_int_equal(s.model.n_walls, 1);
  assert_true(s.model.walls[0].damping == 0.0);
  assert_int_equal(load_example("football_wall.yaml", &s, NULL), BALL_OK);
  assert_int_equal(s.model.n_walls, 1);
  assert_true(s.model.walls[0].bottom == 0.0); /* bottom omitted: the floor level */
}

/* Every key, each with a value unlike its default. */
static const char every_key[] =
    "name: all keys\n"
    "duration: 7.5\n"
    "gravity: 9.5\n"
    "mass: 0.45\n"
    "air_friction: 0.125\n"
    "radius: 0.11\n"
    "spin_damping: 3.5\n"
    "floor: {level: 0.25, damping: 0.5, bounce_threshold: 0.2, sound_threshold: 0.75, spin_damping: 0.6}\n"
    "net: {axis: z, position: 4.0, lo: -1.0, hi: 2.0, bottom: 0.25, top: 1.5, damping: 0.3}\n"
    "walls:\n"
    "  - {axis: x, position: 20.0, lo: -5.0, hi: 5.0, bottom: 0.5, top: 3.0, damping: 0.4}\n"
    "  - {axis: z, position: -6.0, lo: 0.0, hi: 20.0, top: 2.0}\n"
    "rackets:\n"
    "  - {radius: 0.2, partner: 1, target: [1.0, 2.0, 3.0]}\n"
    "  - {radius: 0.125}\n"
    "racket:\n"
    "  detect: swept\n"
    "  normal: velocity\n"
    "  response: mixed\n"
    "  collision_distance: 0.4\n"
    "  sleep_frames: 5\n"
    "  v_min: 2.0\n"
    "  v_max: 30.0\n"
    "  v_up: 3.5\n"
    "  v_up_from_racket: true\n"
    "  friendly_factor: 0.7\n"
    "  spin_rack_damping: 0.5\n"
    "  history: 5\n"
    "  extrapolation_time: 0.05\n"
    "  stale_time: 2.0\n"
    "time: {frame_time: 0.04, time_base: 0.5}\n"
    "effects: [drag, walls, rackets]\n"
    "scheme: sampled\n"
    "ball:\n"
    "  position: [1.0, 2.0, 3.0]\n"
    "  velocity: [-4.0, 5.0, -6.0]\n"
    "  spin: [0.5, -0.25, 0.125]\n";

static void every_key_lands_in_its_model_field(void **state) {
  ball_scene s;
  ball_scene_error err;
  ball_model def;
  const ball_model *m = &s.model;
  ball_status st;
  (void)state;
  ball_model_default(&def);
  st = load_text(every_key, &s, &err);
  if (st != BALL_OK) print_error("%d:%d %s: %s\n", err.line, err.column, err.field, err.message);
  assert_int_equal(st, BALL_OK);
  assert_string_equal(s.name, "all keys");
  assert_true(s.duration == 7.5);
  assert_true(m->gravity == 9.5 && m->mass == 0.45 && m->air_friction == 0.125);
  assert_true(m->radius == 0.11 && m->spin_damping == 3.5);
  assert_true(m->floor_level == 0.25 && m->floor_damping == 0.5 && m->bounce_threshold == 0.2);
  assert_true(m->sound_threshold == 0.75 && m->spin_floor_damping == 0.6);
  assert_int_equal(m->has_net, 1);
  assert_int_equal(m->net.axis, 2);
  assert_true(m->net.position == 4.0 && m->net.lo == -1.0 && m->net.hi == 2.0);
  assert_true(m->net.bottom == 0.25 && m->net.top == 1.5 && m->net.damping == 0.3);
  assert_int_equal(m->n_walls, 2);
  assert_int_equal(m->walls[0].axis, 0);
  assert_true(m->walls[0].position == 20.0 && m->walls[0].lo == -5.0 && m->walls[0].hi == 5.0);
  assert_true(m->walls[0].bottom == 0.5 && m->walls[0].top == 3.0 && m->walls[0].damping == 0.4);
  assert_int_equal(m->walls[1].axis, 2);
  assert_true(m->walls[1].position == -6.0 && m->walls[1].lo == 0.0 && m->walls[1].hi == 20.0);
  assert_true(m->walls[1].bottom == 0.25);                /* default: the floor level set above */
  assert_true(m->walls[1].damping == def.net.damping);    /* default: the default net damping */
  assert_int_equal(m->n_rackets, 2);
  assert_true(m->rackets[0].radius == 0.2);
  assert_int_equal(m->rackets[0].partner, 1);
  assert_vec(m->rackets[0].target, 1.0, 2.0, 3.0);
  assert_true(m->rackets[1].radius == 0.125);
  assert_int_equal(m->rackets[1].partner, def.rackets[1].partner);
  assert_vec(m->rackets[1].target, def.rackets[1].target.x, def.rackets[1].target.y, def.rackets[1].target.z);
  assert_int_equal(m->detect, BALL_DETECT_SWEPT);
  assert_int_equal(m->normal_mode, BALL_NORMAL_VELOCITY);
  assert_int_equal(m->response, BALL_RESPONSE_MIXED);
  assert_true(m->collision_distance == 0.4);
  assert_int_equal(m->sleep_frames, 5);
  assert_true(m->v_min == 2.0 && m->v_max == 30.0 && m->v_up == 3.5);
  assert_int_equal(m->v_up_from_racket, 1);
  assert_true(m->friendly_factor == 0.7 && m->spin_rack_damping == 0.5);
  assert_int_equal(m->history, 5);
  assert_true(m->extrapolation_time == 0.05 && m->stale_time == 2.0);
  assert_true(s.frame_time == 0.04 && s.time_base == 0.5);
  assert_int_equal(m->effects, BALL_EFFECT_DRAG | BALL_EFFECT_WALLS | BALL_EFFECT_RACKETS);
  assert_int_equal(m->scheme, BALL_SCHEME_SAMPLED);
  assert_int_equal(m->level, BALL_LEVEL_CUSTOM);
  assert_vec(m->initial_position, 1.0, 2.0, 3.0);
  assert_vec(m->initial_velocity, -4.0, 5.0, -6.0);
  assert_vec(m->initial_spin, 0.5, -0.25, 0.125);
}

static void missing_keys_keep_the_defaults(void **state) {
  ball_scene s;
  ball_model def;
  (void)state;
  ball_model_default(&def);
  assert_int_equal(load_text("mass: 0.5\n", &s, NULL), BALL_OK);
  assert_true(s.model.mass == 0.5);
  s.model.mass = def.mass;
  assert_model_equal(&s.model, &def);
  assert_true(s.duration == 10.0); /* documented default run length */
  assert_string_equal(s.name, "");
}

static void fps_sets_the_frame_time_and_none_removes_the_net(void **state) {
  ball_scene s;
  (void)state;
  assert_int_equal(load_text("time: {fps: 8}\nnet: none\neffects: []\n", &s, NULL), BALL_OK);
  assert_true(s.frame_time == 0.125);
  assert_int_equal(s.model.has_net, 0);
  assert_int_equal(s.model.effects, 0u);
}

static void level_preset_applies_first_then_keys_override_it(void **state) {
  ball_scene s, ref;
  ball_model preset;
  (void)state;
  ball_model_default(&preset);
  assert_int_equal(ball_model_set_level(&preset, BALL_LEVEL_MID), BALL_OK);
  /* level comes after the override in the file: the override still wins */
  assert_int_equal(load_text("racket: {friendly_factor: 0.5, detect: sphere}\nlevel: mid\n", &s, NULL), BALL_OK);
  assert_true(s.model.friendly_factor == 0.5);
  assert_int_equal(s.model.detect, BALL_DETECT_SPHERE);
  assert_int_equal(s.model.normal_mode, preset.normal_mode);
  assert_int_equal(s.model.response, preset.response);
  assert_int_equal(s.model.level, BALL_LEVEL_MID);
  /* the same keys in the other order give the same model */
  assert_int_equal(load_text("level: mid\nracket: {detect: sphere, friendly_factor: 0.5}\n", &ref, NULL), BALL_OK);
  assert_model_equal(&s.model, &ref.model);
  /* a level switches racket collisions on; an effects list, in any place, has the last word */
  assert_true((s.model.effects & BALL_EFFECT_RACKETS) != 0);
  assert_int_equal(load_text("effects: [floor]\nlevel: advanced\n", &ref, NULL), BALL_OK);
  assert_int_equal(ref.model.effects, BALL_EFFECT_FLOOR);
  /* the level alone is the preset */
  assert_int_equal(load_text("level: mid\n", &s, NULL), BALL_OK);
  assert_model_equal(&s.model, &preset);
}

static void unknown_keys_are_rejected_with_line_and_field(void **state) {
  (void)state;
  assert_rejected("mass: 0.1\nmas: 0.2\n", 2, 1, "mas");
  assert_rejected("floor:\n  damping: 0.5\n  dampign: 0.4\n", 3, 3, "floor.dampign");
  assert_rejected("walls:\n  - {axis: x, position: 1, lo: 0, hi: 1, top: 1}\n  - {axis: x, position: 2, lo: 0, hi: 1, "
                  "top: 1, colour: red}\n",
                  3, 50, "walls[1].colour");
  assert_rejected("effects: [drag, wind]\n", 1, 17, "effects[1]");
  assert_rejected("mass: 0.1\nmass: 0.2\n", 2, 1, "mass");  /* a key given twice */
  assert_rejected("walls:\n  - {position: 2, lo: 0, hi: 1, top: 1}\n", 2, 5, "walls[0].axis"); /* required */
}

static void wrong_types_are_rejected_with_line_and_field(void **state) {
  (void)state;
  assert_rejected("mass: heavy\n", 1, 7, "mass");
  assert_rejected("mass: \"0.1\"\n", 1, 7, "mass");         /* a string, not a number */
  assert_rejected("mass: 0.1kg\n", 1, 7, "mass");           /* not fully a number */
  assert_rejected("gravity: .inf\n", 1, 10, "gravity");     /* non-finite */
  assert_rejected("gravity: nan\n", 1, 10, "gravity");
  assert_rejected("gravity: 1e999\n", 1, 10, "gravity");    /* overflows to Inf */
  assert_rejected("floor: 0.5\n", 1, 8, "floor");           /* a number, not a mapping */
  assert_rejected("ball:\n  position: [1, 2]\n", 2, 13, "ball.position");  /* wrong length */
  assert_rejected("ball:\n  velocity: [1, x, 3]\n", 2, 17, "ball.velocity[1]");
  assert_rejected("racket:\n  sleep_frames: 2.5\n", 2, 17, "racket.sleep_frames");  /* not an integer */
  assert_rejected("racket:\n  v_up_from_racket: 1\n", 2, 21, "racket.v_up_from_racket");
  assert_rejected("scheme: analytic\n", 1, 9, "scheme");
  assert_rejected("walls: {axis: x}\n", 1, 8, "walls");
  assert_rejected("time: {fps: 60, frame_time: 0.1}\n", 1, 17, "time");  /* both */
}

static void out_of_range_values_are_rejected_where_they_were_set(void **state) {
  (void)state;
  assert_rejected("mass: 0.1\nfloor:\n  damping: 1.5\n", 3, 12, "floor.damping");
  assert_rejected("mass: -1\n", 1, 7, "mass");
  assert_rejected("time:\n  fps: 0\n", 2, 8, "time.fps");
  assert_rejected("time:\n  frame_time: -0.1\n", 2, 15, "time.frame_time");
  assert_rejected("net:\n  top: -1\n", 2, 8, "net.top");
  assert_rejected("walls:\n  - {axis: x, position: 1, lo: 0, hi: 1, top: 1}\n"
                  "  - {axis: x, position: 2, lo: 0, hi: 1, top: 1, damping: 2}\n",
                  3, 59, "walls[1].damping");
  assert_rejected("rackets:\n  - {radius: 0.2}\n  - {radius: -1}\n", 3, 14, "rackets[1].radius");
  assert_rejected("rackets:\n  - {radius: 0.2}\n  - {partner: 1}\n", 3, 15, "rackets[1].partner"); /* itself */
  assert_rejected("level: mid\nracket:\n  friendly_factor: 1.5\n", 3, 20, "racket.friendly_factor"); /* eq 10 */
  assert_rejected("ball:\n  position: [0, -1, 0]\n", 2, 13, "ball.position");  /* below the floor */
  assert_rejected("duration: 0\n", 1, 11, "duration");
}

static void bad_yaml_syntax_is_rejected_with_its_line(void **state) {
  (void)state;
  /* the third line is indented into the middle of the second */
  assert_rejected("mass: 0.1\nfloor:\n  damping: 0.5\n   level: 0\n", 4, 9, "");
  assert_rejected("ball:\n  position: [1, 2, 3\nmass: 1\n", 3, 5, "");  /* unclosed flow list */
  assert_rejected("", 1, 1, "");                                       /* empty scene */
  assert_rejected("mass: 0.1\n---\nmass: 0.2\n", 3, 1, "");            /* two documents */
}

static void a_failed_load_leaves_the_scene_unchanged(void **state) {
  ball_scene s, before;
  ball_scene_error err;
  (void)state;
  assert_int_equal(load_example("football_wall.yaml", &s, NULL), BALL_OK);
  before = s;
  /* valid keys first (they would change mass, floor and walls), then a bad one */
  assert_int_equal(load_text("mass: 9\nfloor: {damping: 0.1}\nwalls: []\nball: {spin: [1, 2]}\n", &s, &err),
                   BALL_EPARSE);
  assert_int_equal(err.line, 4);
  assert_string_equal(s.name, before.name);
  assert_true(s.duration == before.duration);
  assert_model_equal(&s.model, &before.model);
  /* the same for a range error found by the model check at the end */
  assert_int_equal(load_text("mass: 9\nfloor: {damping: 1.1}\n", &s, &err), BALL_EPARSE);
  assert_model_equal(&s.model, &before.model);
}

static void errors_format_as_file_line_column_field_message(void **state) {
  ball_scene s;
  ball_scene_error err;
  char text[600];
  (void)state;
  assert_int_equal(load_text("floor:\n  damping: 1.5\n", &s, &err), BALL_EPARSE);
  ball_scene_error_format(&err, text, sizeof text);
  assert_int_equal(strncmp(text, "mem.yaml:2:12: floor.damping: ", 30), 0);
  assert_int_equal(ball_scene_load_file("no/such/scene.yaml", &s, &err), BALL_EIO);
  assert_string_equal(err.file, "no/such/scene.yaml");
  assert_int_equal(err.line, 0);
}

/* The loader's limits (docs/scenes.md, "Limits"), checked before the work:
 * a file over 1 MiB, nesting deeper than 32, more than 20,000 values. Each
 * is refused at once with its reason, and a file within them loads. */
static void limits_are_checked_before_the_work(void **state) {
  static char big[1100000];
  ball_scene s;
  ball_scene_error err;
  size_t i, n = 0;
  (void)state;
  /* 100,000 levels of nesting: refused at level 33, not after building the tree */
  for (i = 0; i < 100000; i++) big[n++] = '[';
  big[n] = '\0';
  assert_int_equal(ball_scene_load_string(big, n, "deep.yaml", &s, &err), BALL_EPARSE);
  assert_non_null(strstr(err.message, "deeper than 32"));
  assert_int_equal(err.column, 33);
  /* 32 levels (the top mapping, ball, 30 lists) are fine for the reader; the
   * format then rejects the list */
  n = 0;
  n += (size_t)sprintf(big + n, "ball:\n  position: ");
  for (i = 0; i < 30; i++) big[n++] = '[';
  for (i = 0; i < 30; i++) big[n++] = ']';
  big[n] = '\0';
  assert_int_equal(ball_scene_load_string(big, n, "deep.yaml", &s, &err), BALL_EPARSE);
  assert_null(strstr(err.message, "deeper"));
  /* over 1 MiB */
  memset(big, ' ', sizeof big - 1);
  big[sizeof big - 1] = '\0';
  memcpy(big, "mass: 0.1\n", 10);
  assert_int_equal(ball_scene_load_string(big, sizeof big - 1, "big.yaml", &s, &err), BALL_EPARSE);
  assert_non_null(strstr(err.message, "larger than 1048576 bytes"));
  /* 30,000 values in a list, well under a megabyte */
  n = (size_t)sprintf(big, "effects: [");
  for (i = 0; i < 30000; i++) n += (size_t)sprintf(big + n, "0,");
  n += (size_t)sprintf(big + n, "0]\n");
  assert_int_equal(ball_scene_load_string(big, n, "many.yaml", &s, &err), BALL_EPARSE);
  assert_non_null(strstr(err.message, "more than 20000 values"));
}

/* A directory is "Is a directory", not a YAML syntax error; a number is
 * decimal: hexadecimal (which strtod would take), inf and nan are refused. */
static void a_directory_and_hex_numbers_are_refused_clearly(void **state) {
  ball_scene s;
  ball_scene_error err;
  const char *dir = getenv("BALL_SCENES");
  (void)state;
  assert_int_equal(ball_scene_load_file(dir && *dir ? dir : "libball/scenes", &s, &err), BALL_EIO);
  assert_string_equal(err.message, strerror(EISDIR));
  assert_rejected("mass: 0x10\n", 1, 7, "mass");
  assert_rejected("mass: 0x1p-3\n", 1, 7, "mass");
  assert_rejected("mass: -0X2\n", 1, 7, "mass");
  assert_rejected("mass: inf\n", 1, 7, "mass");
  assert_int_equal(load_text("mass: .5\nradius: -.0\ngravity: +9.5e0\n", &s, NULL), BALL_OK);
  assert_true(s.model.mass == 0.5 && s.model.gravity == 9.5);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(every_example_scene_loads_and_passes_the_model_check),
      cmocka_unit_test(tennis_yaml_is_the_builtin_default_scene),
      cmocka_unit_test(example_scenes_state_their_effects_exactly),
      cmocka_unit_test(every_key_lands_in_its_model_field),
      cmocka_unit_test(missing_keys_keep_the_defaults),
      cmocka_unit_test(fps_sets_the_frame_time_and_none_removes_the_net),
      cmocka_unit_test(limits_are_checked_before_the_work),
      cmocka_unit_test(a_directory_and_hex_numbers_are_refused_clearly),
      cmocka_unit_test(level_preset_applies_first_then_keys_override_it),
      cmocka_unit_test(unknown_keys_are_rejected_with_line_and_field),
      cmocka_unit_test(wrong_types_are_rejected_with_line_and_field),
      cmocka_unit_test(out_of_range_values_are_rejected_where_they_were_set),
      cmocka_unit_test(bad_yaml_syntax_is_rejected_with_its_line),
      cmocka_unit_test(a_failed_load_leaves_the_scene_unchanged),
      cmocka_unit_test(errors_format_as_file_line_column_field_message),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
