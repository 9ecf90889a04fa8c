/* The scene format (docs/scenes.md) in the YAML reader's terms (reader.h).
 * The model's keys are not listed here: every section of model fields
 * (the top level, floor, racket, ball, a net or wall, a racket) is made
 * from libball's field table (ball_model_fields and friends): its keys, the
 * type and range of each, and the words of an error. This file holds what
 * the table cannot say: the sections of the file, the keys that are not
 * model fields (name, duration, time, scripts, render), the net's `none`,
 * the level read first, and mapping ball_model_check's field back to the
 * line that set it. */
#include "reader.h"
#include "ball/vec3.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define SCENE_DEFAULT_DURATION 10.0
#define SCENE_DEFAULT_FRAME_TIME (1.0 / 60.0)
#define SCENE_DEFAULT_MARKERS 1.0 /* s */
#define TABLE_KEYS 40             /* keys of one section made from the field table, at most */

/* ---- sections made from the field table ---------------------------------- */

typedef struct table_section {
  key_spec keys[TABLE_KEYS + 1];
  section sec;
} table_section;

/* A key of the scene format for a table field (its key after the section's
 * prefix), or 0 for a field that is not read as a plain key. */
static int key_of(const ball_field *f, key_spec *k, const char *name) {
  memset(k, 0, sizeof *k);
  k->name = name;
  k->offset = f->offset;
  switch (f->type) {
    case BALL_FIELD_REAL:
      k->kind = KEY_RANGED;
      k->lo = f->lo;
      k->hi = f->hi;
      k->open = f->flags & (BALL_FIELD_LO_OPEN | BALL_FIELD_HI_OPEN);
      k->range = f->range;
      return 1;
    case BALL_FIELD_INT: k->kind = KEY_INT; return 1;
    case BALL_FIELD_BOOL: k->kind = KEY_BOOL; return 1;
    case BALL_FIELD_VEC3: k->kind = KEY_VEC3; return 1;
    case BALL_FIELD_ENUM:
      k->kind = KEY_ENUM;
      k->names = f->enum_name;
      k->count = (int)f->hi + 1;
      return 1;
    default: return 0; /* axis, effects, containers: special keys */
  }
}

/* The section of table fields whose key starts with prefix ("floor.", or ""
 * for the top level's plain keys), then the extra (special) keys. */
static void make_section(table_section *ts, const ball_field *f, int n, const char *prefix, const key_spec *extra,
                         key_hook hook, int require) {
  size_t len = strlen(prefix);
  int i, j, k = 0;
  /* the special keys first: they win over a table field of the same key
   * (has_net, n_walls, n_rackets are given by the net, walls and rackets
   * sections, not as numbers) */
  for (; extra && extra->name && k < TABLE_KEYS; extra++) ts->keys[k++] = *extra;
  for (i = 0; i < n && k < TABLE_KEYS; i++) {
    const char *name = f[i].key + len;
    int dup = 0;
    if (strncmp(f[i].key, prefix, len) != 0 || (!*prefix && strchr(f[i].key, '.'))) continue;
    for (j = 0; j < k; j++) dup |= strcmp(ts->keys[j].name, name) == 0;
    if (!dup && key_of(&f[i], &ts->keys[k], name)) k++;
  }
  memset(&ts->keys[k], 0, sizeof ts->keys[k]); /* END_OF_KEYS */
  ts->keys[k].kind = KEY_SPECIAL;
  ts->sec.keys = ts->keys;
  ts->sec.hook = hook;
  ts->sec.require = require;
  ts->sec.record = 1;
}

/* The scene's loader: the reader's state and the sections made for it. */
typedef struct scene_format {
  scene_loader L; /* first: a scene_loader * is a scene_format * */
  ball_model defaults;
  table_section root, floor, racket, ball, net, wall, racket_def;
} scene_format;

static scene_format *format_of(scene_loader *L) { return (scene_format *)L; }

/* ---- net and walls -------------------------------------------------------- */

/* A plane's axis: x or z (stored as 0 or 2). */
static ball_status plane_axis(scene_loader *L, const yaml_node_t *key, const yaml_node_t *v, const char *path,
                              void *base, void *ctx) {
  ball_plane *pl = (ball_plane *)base;
  (void)key;
  (void)ctx;
  if (v->type == YAML_SCALAR_NODE && strcmp(scene_text(v), "x") == 0) pl->axis = 0;
  else if (v->type == YAML_SCALAR_NODE && strcmp(scene_text(v), "z") == 0) pl->axis = 2;
  else if (v->type == YAML_SCALAR_NODE) return scene_fail(L, v, path, "expected x or z, got \"%s\"", scene_text(v));
  else return scene_fail(L, v, path, "expected x or z, got %s", scene_node_kind(v));
  scene_remember(L, path, NULL, v);
  return BALL_OK;
}

/* A wall must give these; without "bottom" it stands on the floor and
 * without "damping" it has the default net's. */
static const key_spec plane_extra[] = {SPECIAL_KEY("axis", 1), END_OF_KEYS};
static const char *const wall_required[] = {"axis", "position", "lo", "hi", "top"};

static ball_status load_net(scene_loader *L, const yaml_node_t *node) {
  ball_status st;
  if (node->type == YAML_SCALAR_NODE && strcmp(scene_text(node), "none") == 0) {
    L->scene.model.has_net = 0;
    return BALL_OK;
  }
  if (node->type == YAML_SCALAR_NODE)
    return scene_fail(L, node, "net", "expected a mapping or none, got \"%s\"", scene_text(node));
  if ((st = scene_load_section(L, node, "net", &format_of(L)->net.sec, &L->scene.model.net, NULL)) != BALL_OK)
    return st;
  L->scene.model.has_net = 1;
  return BALL_OK;
}

static ball_status load_walls(scene_loader *L, const yaml_node_t *node) {
  scene_format *F = format_of(L);
  ball_model *m = &L->scene.model;
  int i, n;
  ball_status st;
  if ((st = scene_get_list(L, node, "walls", "walls", BALL_MAX_WALLS, &n)) != BALL_OK) return st;
  for (i = 0; i < n; ++i) {
    yaml_node_t *item = scene_list_item(L, node, i);
    char path[SCENE_PATH_SIZE];
    ball_plane *w = &m->walls[i];
    snprintf(path, sizeof path, "walls[%d]", i);
    scene_remember(L, path, NULL, item);
    memset(w, 0, sizeof *w);
    w->damping = F->defaults.net.damping;
    if ((st = scene_load_section(L, item, path, &F->wall.sec, w, NULL)) != BALL_OK) return st;
    L->wall_bottom_set[i] = scene_key_value(L, item, "bottom") != NULL;
  }
  m->n_walls = n;
  return BALL_OK;
}

/* ---- rackets and their scripts ------------------------------------------- */

/* A keyframe's t (strictly after the one before) or normal (made unit). */
static ball_status keyframe_key(scene_loader *L, const yaml_node_t *key, const yaml_node_t *v, const char *path,
                                void *base, void *ctx) {
  ball_script_keyframe *k = (ball_script_keyframe *)base;
  const ball_racket_script *s = (const ball_racket_script *)ctx;
  ball_status st;
  if (strcmp(scene_text(key), "t") == 0) {
    if ((st = scene_get_number(L, v, path, &k->t)) != BALL_OK) return st;
    if (k > s->keyframes && !(k->t > k[-1].t))
      return scene_fail(L, v, path, "out of range: keyframe times must increase strictly, got %s after %.17g",
                        scene_text(v), k[-1].t);
  } else {
    ball_vec3 u;
    if ((st = scene_get_vec3(L, v, path, &u)) != BALL_OK) return st;
    if (!(ball_v3_length(u) >= 1e-9))
      return scene_fail(L, v, path, "out of range: a normal must not be (nearly) zero");
    k->normal = ball_v3_unit(u);
  }
  return BALL_OK;
}

static const key_spec keyframe_keys[] = {
    SPECIAL_KEY("t", 1),
    REQUIRED_KEY("center", KEY_VEC3, ball_script_keyframe, center),
    SPECIAL_KEY("normal", 1),
    END_OF_KEYS,
};
static const section keyframe_section = {keyframe_keys, keyframe_key, 1, 0};

static ball_status load_keyframes(scene_loader *L, const yaml_node_t *node, const char *path, ball_racket_script *s) {
  int i, n;
  ball_status st;
  if (node->type != YAML_SEQUENCE_NODE)
    return scene_fail(L, node, path, "expected a list of keyframes {t, center, normal}, got %s", scene_node_kind(node));
  n = (int)(node->data.sequence.items.top - node->data.sequence.items.start);
  if (n < 1) return scene_fail(L, node, path, "expected at least one keyframe");
  if (n > BALL_SCRIPT_MAX_KEYFRAMES)
    return scene_fail(L, node, path, "%d keyframes given, at most %d allowed", n, BALL_SCRIPT_MAX_KEYFRAMES);
  for (i = 0; i < n; ++i) {
    char kpath[SCENE_PATH_SIZE];
    snprintf(kpath, sizeof kpath, "%.80s[%d]", path, i);
    if ((st = scene_load_section(L, scene_list_item(L, node, i), kpath, &keyframe_section, &s->keyframes[i], s)) !=
        BALL_OK)
      return st;
  }
  s->n_keyframes = n;
  return BALL_OK;
}

static ball_status script_keyframes(scene_loader *L, const yaml_node_t *key, const yaml_node_t *v, const char *path,
                                    void *base, void *ctx) {
  (void)key;
  (void)ctx;
  return load_keyframes(L, v, path, (ball_racket_script *)base);
}

/* rackets[i].script: keyframes and network conditions (docs/scenes.md). */
static const key_spec script_keys[] = {
    SPECIAL_KEY("keyframes", 1),
    RANGED_KEY("repeat", ball_racket_script, repeat, 0.0, 4e9, 0u, "in [0, 4e9] s (0: no repeat)"),
    RANGED_KEY("rate", ball_racket_script, rate, 2.0, 120.0, 0u, "in [2, 120] Hz"),
    RANGED_KEY("delay", ball_racket_script, delay, 0.0, 60.0, 0u, "in [0, 60] s"),
    RANGED_KEY("jitter", ball_racket_script, jitter, 0.0, 0.5, 0u, "in [0, 0.5] s"),
    RANGED_KEY("loss", ball_racket_script, loss, 0.0, 1.0, BALL_FIELD_HI_OPEN, "in [0, 1)"),
    RANGED_KEY("duplicate", ball_racket_script, duplicate, 0.0, 1.0, 0u, "in [0, 1]"),
    RANGED_KEY("noise", ball_racket_script, noise, 0.0, 1e3, 0u, "in [0, 1000] m"),
    RANGED_KEY("normal_noise", ball_racket_script, normal_noise, 0.0, 1.0, 0u, "in [0, 1] rad"),
    KEY("seed", KEY_UINT64, ball_racket_script, seed),
    END_OF_KEYS,
};
static const section script_section = {script_keys, script_keyframes, 1, 0};

static ball_status load_script(scene_loader *L, const yaml_node_t *node, const char *path, ball_racket_script *s) {
  const yaml_node_t *repeat_node;
  ball_status st;
  const char *field = NULL;
  ball_script_default(s);
  if ((st = scene_load_section(L, node, path, &script_section, s, NULL)) != BALL_OK) return st;
  repeat_node = scene_key_value(L, node, "repeat");
  if (repeat_node && s->repeat != 0.0 && !(s->repeat > s->keyframes[s->n_keyframes - 1].t - s->keyframes[0].t)) {
    char sub[SCENE_PATH_SIZE];
    scene_join(sub, path, "repeat");
    return scene_fail(L, repeat_node, sub, "out of range: must be 0 or > the keyframes' span (%.17g s), got %s",
                      s->keyframes[s->n_keyframes - 1].t - s->keyframes[0].t, scene_text(repeat_node));
  }
  /* the reader checked every field where it stands; this is the library's word */
  if ((st = ball_script_check(s, &field)) != BALL_OK)
    return scene_fail(L, node, path, "rejected by ball_script_check: %s: %s", field ? field : "?", ball_strerror(st));
  return BALL_OK;
}

/* rackets[i].script goes to L->scene.scripts[i] (ctx). */
static ball_status racket_script(scene_loader *L, const yaml_node_t *key, const yaml_node_t *v, const char *path,
                                 void *base, void *ctx) {
  ball_status st = load_script(L, v, path, (ball_racket_script *)ctx);
  (void)key;
  (void)base;
  if (st == BALL_OK) scene_remember(L, path, NULL, v);
  return st;
}

static const key_spec racket_def_extra[] = {SPECIAL_KEY("script", 0), END_OF_KEYS};

static ball_status load_rackets(scene_loader *L, const yaml_node_t *node) {
  scene_format *F = format_of(L);
  ball_model *m = &L->scene.model;
  int i, n;
  ball_status st;
  if ((st = scene_get_list(L, node, "rackets", "rackets", BALL_MAX_RACKETS, &n)) != BALL_OK) return st;
  for (i = 0; i < n; ++i) {
    yaml_node_t *item = scene_list_item(L, node, i);
    ball_racket_def *r = &m->rackets[i];
    char path[SCENE_PATH_SIZE];
    snprintf(path, sizeof path, "rackets[%d]", i);
    scene_remember(L, path, NULL, item);
    *r = F->defaults.rackets[i];
    if ((st = scene_load_section(L, item, path, &F->racket_def.sec, r, &L->scene.scripts[i])) != BALL_OK) return st;
  }
  m->n_rackets = n;
  return BALL_OK;
}

/* ---- time, effects, render ------------------------------------------------ */

/* time.frame_time or time.fps (one of them; ctx: the one seen so far). */
static ball_status time_frame(scene_loader *L, const yaml_node_t *key, const yaml_node_t *v, const char *path,
                              void *base, void *ctx) {
  ball_scene *sc = (ball_scene *)base;
  const yaml_node_t **frame_node = (const yaml_node_t **)ctx;
  ball_status st;
  double x;
  if (*frame_node) return scene_fail(L, key, "time", "give frame_time or fps, not both");
  *frame_node = v;
  if ((st = scene_get_number(L, v, path, &x)) != BALL_OK) return st;
  if (strcmp(scene_text(key), "frame_time") == 0) {
    if (!(x > 0.0)) return scene_fail(L, v, path, "out of range: must be > 0, got %s", scene_text(v));
    sc->frame_time = x;
  } else {
    if (!(x > 0.0) || !isfinite(1.0 / x))
      return scene_fail(L, v, path, "out of range: must be > 0 (and 1 / fps finite), got %s", scene_text(v));
    sc->frame_time = 1.0 / x;
  }
  return BALL_OK;
}

static const key_spec time_keys[] = {
    SPECIAL_KEY("frame_time", 0),
    SPECIAL_KEY("fps", 0),
    RANGED_KEY("time_base", ball_scene, time_base, 0.0, HUGE_VAL, BALL_FIELD_LO_OPEN, "> 0"),
    END_OF_KEYS,
};
static const section time_section = {time_keys, time_frame, 0, 0};

static ball_status load_effects(scene_loader *L, const yaml_node_t *node) {
  unsigned mask = 0;
  int i, n;
  ball_status st;
  if ((st = scene_get_list(L, node, "effects", "effect names", 7, &n)) != BALL_OK) return st;
  for (i = 0; i < n; ++i) {
    yaml_node_t *item = scene_list_item(L, node, i);
    char path[SCENE_PATH_SIZE];
    unsigned bit;
    snprintf(path, sizeof path, "effects[%d]", i);
    for (bit = 1u; bit & BALL_EFFECT_ALL; bit <<= 1) {
      if (item->type == YAML_SCALAR_NODE && strcmp(scene_text(item), ball_effect_name((ball_effect)bit)) == 0) break;
    }
    if (!(bit & BALL_EFFECT_ALL)) {
      if (item->type != YAML_SCALAR_NODE)
        return scene_fail(L, item, path, "expected an effect name, got %s", scene_node_kind(item));
      return scene_fail(L, item, path, "unknown effect \"%s\" (drag, spin, floor, net, walls, rackets or sound)",
                        scene_text(item));
    }
    if (mask & bit) return scene_fail(L, item, path, "effect \"%s\" listed twice", scene_text(item));
    mask |= bit;
  }
  L->scene.model.effects = mask;
  scene_remember(L, "effects", NULL, node);
  return BALL_OK;
}

/* A camera's name: distinct from the cameras before it (ctx: the section). */
static ball_status camera_name(scene_loader *L, const yaml_node_t *key, const yaml_node_t *v, const char *path,
                               void *base, void *ctx) {
  ball_scene_camera *c = (ball_scene_camera *)base;
  const ball_scene_render *r = (const ball_scene_render *)ctx;
  const char *text, *ch;
  int i;
  (void)key;
  if (v->type != YAML_SCALAR_NODE || v->data.scalar.length == 0)
    return scene_fail(L, v, path, "expected a name, got %s", scene_node_kind(v));
  text = scene_text(v);
  if (v->data.scalar.length >= sizeof c->name)
    return scene_fail(L, v, path, "longer than %d characters", (int)sizeof c->name - 1);
  for (ch = text; *ch; ++ch)
    if (!((*ch >= 'a' && *ch <= 'z') || (*ch >= 'A' && *ch <= 'Z') || (*ch >= '0' && *ch <= '9') || *ch == '_' ||
          *ch == '-'))
      return scene_fail(L, v, path, "\"%s\": a name takes letters, digits, '_' and '-' only", text);
  for (i = 0; r->cameras + i < c; ++i)
    if (strcmp(r->cameras[i].name, text) == 0) return scene_fail(L, v, path, "camera \"%s\" named twice", text);
  scene_copy_string(c->name, sizeof c->name, text);
  return BALL_OK;
}

static const key_spec camera_keys[] = {
    SPECIAL_KEY("name", 1),
    REQUIRED_KEY("eye", KEY_VEC3, ball_scene_camera, camera.eye),
    REQUIRED_KEY("target", KEY_VEC3, ball_scene_camera, camera.target),
    KEY("up", KEY_VEC3, ball_scene_camera, camera.up),
    RANGED_KEY("fov", ball_scene_camera, camera.fov, 1.0, 179.0, 0u, "in [1, 179] degrees"),
    END_OF_KEYS,
};
static const section camera_section = {camera_keys, camera_name, 1, 0};

static ball_status load_cameras(scene_loader *L, const yaml_node_t *node, const char *path, ball_scene_render *r) {
  int i, n;
  ball_status st;
  if ((st = scene_get_list(L, node, path, "cameras", BALL_SCENE_MAX_CAMERAS, &n)) != BALL_OK) return st;
  for (i = 0; i < n; ++i) {
    ball_scene_camera *c = &r->cameras[i];
    yaml_node_t *item = scene_list_item(L, node, i);
    char sub[SCENE_PATH_SIZE];
    ball_vec3 d;
    double dd, du, cross;
    snprintf(sub, sizeof sub, "%.80s[%d]", path, i);
    memset(c, 0, sizeof *c);
    c->camera.up.y = 1.0;
    c->camera.fov = 45.0;
    if ((st = scene_load_section(L, item, sub, &camera_section, c, r)) != BALL_OK) return st;
    d = ball_v3_sub(c->camera.target, c->camera.eye);
    dd = ball_v3_dot(d, d);
    du = ball_v3_dot(c->camera.up, c->camera.up);
    if (!(dd > 1e-12) || !isfinite(dd)) return scene_fail(L, item, sub, "target must be away from eye");
    /* |d x up|^2 = |d|^2 |up|^2 - (d . up)^2: the up vector must not lie along d */
    cross = dd * du - ball_v3_dot(d, c->camera.up) * ball_v3_dot(d, c->camera.up);
    if (!(du > 0.0) || !isfinite(du) || !(cross > 1e-6 * dd * du))
      return scene_fail(L, item, sub, "up must not be zero or along target - eye");
  }
  r->n_cameras = n;
  return BALL_OK;
}

static ball_status render_cameras(scene_loader *L, const yaml_node_t *key, const yaml_node_t *v, const char *path,
                                  void *base, void *ctx) {
  (void)key;
  (void)ctx;
  return load_cameras(L, v, path, (ball_scene_render *)base);
}

static const key_spec render_keys[] = {
    RANGED_KEY("trail", ball_scene_render, trail, 0.0, 60.0, 0u, "in [0, 60] s"),
    RANGED_KEY("markers", ball_scene_render, markers, 0.0, 60.0, 0u, "in [0, 60] s"),
    SPECIAL_KEY("cameras", 0),
    END_OF_KEYS,
};
static const section render_section = {render_keys, render_cameras, 0, 0};

/* ---- ball_model_check's field -> the line that set it --------------------- */

/* The table entry of a field name as ball_model_check gives it ("v_max",
 * "net.lo", "walls[3].hi", "rackets[1].partner"); *path gets its scene path. */
static const ball_field *field_entry(const char *name, char *path) {
  int n, i;
  const ball_field *f;
  const char *dot = strchr(name, '.');
  if (dot) {
    /* a net, wall or racket member: the same path in the file */
    int is_racket = strncmp(name, "rackets[", 8) == 0;
    f = is_racket ? ball_racket_fields(&n) : ball_plane_fields(&n);
    scene_copy_string(path, SCENE_PATH_SIZE, name);
    for (i = 0; i < n; i++)
      if (strcmp(f[i].key, dot + 1) == 0) return &f[i];
    return NULL;
  }
  f = ball_model_fields(&n);
  for (i = 0; i < n; i++)
    if (strcmp(f[i].name, name) == 0) {
      scene_copy_string(path, SCENE_PATH_SIZE, f[i].key);
      return &f[i];
    }
  scene_copy_string(path, SCENE_PATH_SIZE, name);
  return NULL;
}

static ball_status model_error(scene_loader *L, ball_status st, const char *field) {
  char path[SCENE_PATH_SIZE];
  const ball_field *f = field_entry(field ? field : "", path);
  const scene_location *loc = scene_find_location(L, path);
  const char *range = f && f->range && *f->range ? f->range : NULL;
  if (loc && strcmp(loc->path, path) == 0) {
    /* the key that set the value: report it as written (time.fps, ...) */
    if (range) return scene_fail_at(L, loc->line, loc->column, loc->display, "out of range: must be %s", range);
    return scene_fail_at(L, loc->line, loc->column, loc->display, "out of range: %s", ball_strerror(st));
  }
  {
    char where[SCENE_PATH_SIZE + 40];
    if (loc && *loc->path) snprintf(where, sizeof where, "the default or set in \"%s\"", loc->display);
    else snprintf(where, sizeof where, "the default");
    if (range)
      return scene_fail_at(L, loc ? loc->line : 0, loc ? loc->column : 0, path, "out of range (%s): must be %s",
                           where, range);
    return scene_fail_at(L, loc ? loc->line : 0, loc ? loc->column : 0, path, "out of range (%s): %s", where,
                         ball_strerror(st));
  }
}

/* ---- the document --------------------------------------------------------- */

/* The top-level keys that are not plain fields: name, duration and the
 * sections (level is read first, by load_root). */
static ball_status root_key(scene_loader *L, const yaml_node_t *key, const yaml_node_t *v, const char *path,
                            void *base, void *ctx) {
  scene_format *F = format_of(L);
  const char *k = scene_text(key);
  const yaml_node_t *frame_node = NULL;
  ball_status st;
  (void)ctx;
  if (strcmp(k, "level") == 0) return BALL_OK;
  if (strcmp(k, "name") == 0) {
    if (v->type != YAML_SCALAR_NODE) return scene_fail(L, v, "name", "expected a string, got %s", scene_node_kind(v));
    if (v->data.scalar.length >= sizeof L->scene.name)
      return scene_fail(L, v, "name", "longer than %d characters", (int)sizeof L->scene.name - 1);
    scene_copy_string(L->scene.name, sizeof L->scene.name, scene_text(v));
    return BALL_OK;
  }
  if (strcmp(k, "duration") == 0) {
    if ((st = scene_get_number(L, v, "duration", &L->scene.duration)) != BALL_OK) return st;
    if (!(L->scene.duration > 0.0)) return scene_fail(L, v, "duration", "must be > 0, got %s", scene_text(v));
    return BALL_OK;
  }
  if (strcmp(k, "floor") == 0) st = scene_load_section(L, v, path, &F->floor.sec, base, NULL);
  else if (strcmp(k, "net") == 0) st = load_net(L, v);
  else if (strcmp(k, "walls") == 0) st = load_walls(L, v);
  else if (strcmp(k, "rackets") == 0) st = load_rackets(L, v);
  else if (strcmp(k, "racket") == 0) st = scene_load_section(L, v, path, &F->racket.sec, base, NULL);
  else if (strcmp(k, "time") == 0) st = scene_load_section(L, v, path, &time_section, &L->scene, &frame_node);
  else if (strcmp(k, "effects") == 0) st = load_effects(L, v);
  else if (strcmp(k, "render") == 0) st = scene_load_section(L, v, path, &render_section, &L->scene.render, NULL);
  else st = scene_load_section(L, v, path, &F->ball.sec, base, NULL);
  if (st != BALL_OK) return st;
  if (v->type != YAML_SCALAR_NODE) scene_remember(L, k, NULL, v);
  return BALL_OK;
}

/* The sections that are not plain fields of the top level. */
static const key_spec root_extra[] = {
    SPECIAL_KEY("name", 0),   SPECIAL_KEY("duration", 0), SPECIAL_KEY("floor", 0), SPECIAL_KEY("net", 0),
    SPECIAL_KEY("walls", 0),  SPECIAL_KEY("rackets", 0),  SPECIAL_KEY("racket", 0), SPECIAL_KEY("level", 0),
    SPECIAL_KEY("time", 0),   SPECIAL_KEY("effects", 0),  SPECIAL_KEY("ball", 0),  SPECIAL_KEY("render", 0),
    END_OF_KEYS,
};

static const char *level_name(int v) { return ball_level_name((ball_level)v); }

static ball_status load_root(scene_loader *L, const yaml_node_t *root) {
  scene_format *F = format_of(L);
  ball_model *m = &L->scene.model;
  yaml_node_t *v;
  ball_status st;
  const char *field = NULL;
  int i;

  if (root->type == YAML_SCALAR_NODE && root->data.scalar.length == 0)
    return scene_fail(L, root, "", "the scene is empty (expected a mapping of keys)");
  if ((st = scene_check_section(L, root, "", &F->root.sec)) != BALL_OK) return st;
  scene_remember(L, "", NULL, root);

  /* The level preset goes first, whatever its place in the file, so every
   * racket key can override it. */
  if ((v = scene_key_value(L, root, "level")) != NULL) {
    int level;
    if ((st = scene_get_enum(L, v, "level", level_name, BALL_LEVEL_COUNT, &level)) != BALL_OK) return st;
    if (ball_model_set_level(m, (ball_level)level) != BALL_OK)
      return scene_fail(L, v, "level", "the library rejected level \"%s\"", scene_text(v));
    scene_remember(L, "level", NULL, v);
  }

  if ((st = scene_read_section(L, root, "", &F->root.sec, m, NULL)) != BALL_OK) return st;

  /* A wall without "bottom" stands on the floor. */
  for (i = 0; i < m->n_walls; ++i)
    if (!L->wall_bottom_set[i]) m->walls[i].bottom = m->floor_level;

  /* what a single key cannot say (v_max >= v_min, lo < hi, a partner in the
   * list, the ball above the floor, ...): the library's check, pointed back
   * at the line that set the field (its name carries the index) */
  st = ball_model_check(m, &field);
  if (st != BALL_OK) return model_error(L, st, field);
  return BALL_OK;
}

/* The format's sections, made from the field table. */
static void make_format(scene_format *F) {
  int n, np, nr, i;
  const ball_field *f = ball_model_fields(&n);
  const ball_field *pf = ball_plane_fields(&np);
  const ball_field *rf = ball_racket_fields(&nr);
  ball_model_default(&F->defaults);
  make_section(&F->root, f, n, "", root_extra, root_key, 0);
  make_section(&F->floor, f, n, "floor.", NULL, NULL, 0);
  make_section(&F->racket, f, n, "racket.", NULL, NULL, 0);
  make_section(&F->ball, f, n, "ball.", NULL, NULL, 0);
  make_section(&F->net, pf, np, "", plane_extra, plane_axis, 0);
  make_section(&F->wall, pf, np, "", plane_extra, plane_axis, 1);
  for (i = 0; F->wall.keys[i].name; i++) {
    size_t j;
    for (j = 0; j < sizeof wall_required / sizeof wall_required[0]; j++)
      if (strcmp(F->wall.keys[i].name, wall_required[j]) == 0) F->wall.keys[i].required = 1;
  }
  make_section(&F->racket_def, rf, nr, "", racket_def_extra, racket_script, 0);
}

static void scene_start(ball_scene *sc) {
  memset(sc, 0, sizeof *sc);
  ball_model_default(&sc->model);
  sc->duration = SCENE_DEFAULT_DURATION;
  sc->frame_time = SCENE_DEFAULT_FRAME_TIME;
  sc->time_base = 1.0;
  sc->render.markers = SCENE_DEFAULT_MARKERS;
}

static void set_error(ball_scene_error *err, const char *file, const char *message) {
  if (!err) return;
  memset(err, 0, sizeof *err);
  scene_copy_string(err->file, sizeof err->file, file);
  scene_copy_string(err->message, sizeof err->message, message);
}

ball_status ball_scene_load_string(const char *text, size_t length, const char *name, ball_scene *scene,
                                   ball_scene_error *err) {
  scene_format *F;
  ball_status st;
  if (!name) name = "<string>";
  if (!text || !scene) {
    set_error(err, name, "no text or no scene given");
    return BALL_EINVAL;
  }
  F = (scene_format *)calloc(1, sizeof *F);
  if (!F) {
    set_error(err, name, "out of memory");
    return BALL_ENOMEM;
  }
  make_format(F);
  scene_start(&F->L.scene);
  st = scene_read_document(text, length, name, &F->L, load_root);
  if (st == BALL_OK) *scene = F->L.scene;
  if (err) {
    if (st == BALL_OK) memset(err, 0, sizeof *err);
    else *err = F->L.err;
  }
  free(F);
  return st;
}

ball_status ball_scene_load_file(const char *path, ball_scene *scene, ball_scene_error *err) {
  FILE *f;
  char *text;
  size_t n = 0;
  ball_status st;
  if (!path || !scene) {
    set_error(err, path ? path : "", "no file name or no scene given");
    return BALL_EINVAL;
  }
  f = fopen(path, "rb");
  if (!f) {
    set_error(err, path, strerror(errno));
    return BALL_EIO;
  }
  /* read it whole, at most the limit and one byte more (a pipe or an
   * endless stream stops there), then parse the text */
  text = (char *)malloc(SCENE_MAX_BYTES + 1);
  if (!text) {
    fclose(f);
    set_error(err, path, "out of memory");
    return BALL_ENOMEM;
  }
  errno = 0;
  n = fread(text, 1, SCENE_MAX_BYTES + 1, f);
  if (ferror(f)) {
    /* a directory reads as an error (EISDIR): say so, not "YAML syntax" */
    set_error(err, path, errno ? strerror(errno) : "read error");
    free(text);
    fclose(f);
    return BALL_EIO;
  }
  fclose(f);
  st = ball_scene_load_string(text, n, path, scene, err);
  free(text);
  return st;
}

void ball_scene_default(ball_scene *scene) {
  if (!scene) return;
  scene_start(scene);
  scene_copy_string(scene->name, sizeof scene->name, "tennis");
  /* the default model is the tennis court with a serve that clears the net */
  scene->duration = 3.0;
}

void ball_scene_error_format(const ball_scene_error *err, char *buf, size_t size) {
  if (!buf || size == 0) return;
  if (!err) {
    scene_copy_string(buf, size, "");
    return;
  }
  if (err->line > 0 && err->field[0])
    snprintf(buf, size, "%s:%d:%d: %s: %s", err->file, err->line, err->column, err->field, err->message);
  else if (err->line > 0)
    snprintf(buf, size, "%s:%d:%d: %s", err->file, err->line, err->column, err->message);
  else if (err->field[0])
    snprintf(buf, size, "%s: %s: %s", err->file, err->field, err->message);
  else
    snprintf(buf, size, "%s: %s", err->file, err->message);
}
