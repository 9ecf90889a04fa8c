/* Scene files: YAML text -> ball_scene. libyaml does the parsing
 * (yaml_parser_load builds the node tree with line and column marks); this
 * file only walks the tree, converts scalars strictly and checks the result
 * with ball_model_check. The format is documented in docs/scenes.md. */
#include "ball/scene.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <yaml.h>

#define SCENE_MAX_LOCATIONS 512
#define SCENE_PATH_SIZE 96
#define SCENE_DEFAULT_DURATION 10.0
#define SCENE_DEFAULT_FRAME_TIME (1.0 / 60.0)

/* Where a scene path was set in the file: used to point an error found later
 * (by ball_model_check) at the line that set the value. */
typedef struct scene_location {
  char path[SCENE_PATH_SIZE];     /* scene path as looked up, e.g. "time.frame_time" */
  char display[SCENE_PATH_SIZE];  /* scene path as reported, e.g. "time.fps" */
  int line, column;               /* 1-based */
} scene_location;

typedef struct scene_loader {
  yaml_document_t *doc;
  ball_scene scene;                 /* the scene being built; copied out on success */
  ball_scene_error err;             /* the first error */
  int wall_bottom_set[BALL_MAX_WALLS];
  int n_locations;
  scene_location locations[SCENE_MAX_LOCATIONS];
} scene_loader;

/* ---- errors ------------------------------------------------------------ */

static void copy_string(char *dst, size_t size, const char *src) {
  size_t n;
  if (size == 0) return;
  if (!src) src = "";
  n = strlen(src);
  if (n >= size) n = size - 1;
  memcpy(dst, src, n);
  dst[n] = '\0';
}

static ball_status fail_at(scene_loader *L, int line, int column, const char *path, const char *fmt,
                           ...) {
  va_list ap;
  L->err.line = line;
  L->err.column = column;
  copy_string(L->err.field, sizeof L->err.field, path);
  va_start(ap, fmt);
  vsnprintf(L->err.message, sizeof L->err.message, fmt, ap);
  va_end(ap);
  return BALL_EPARSE;
}

static ball_status fail(scene_loader *L, const yaml_node_t *node, const char *path, const char *fmt,
                        ...) {
  va_list ap;
  L->err.line = node ? (int)node->start_mark.line + 1 : 0;
  L->err.column = node ? (int)node->start_mark.column + 1 : 0;
  copy_string(L->err.field, sizeof L->err.field, path);
  va_start(ap, fmt);
  vsnprintf(L->err.message, sizeof L->err.message, fmt, ap);
  va_end(ap);
  return BALL_EPARSE;
}

static void remember(scene_loader *L, const char *path, const char *display, const yaml_node_t *node) {
  scene_location *loc;
  if (L->n_locations >= SCENE_MAX_LOCATIONS || !node) return;
  loc = &L->locations[L->n_locations++];
  copy_string(loc->path, sizeof loc->path, path);
  copy_string(loc->display, sizeof loc->display, display ? display : path);
  loc->line = (int)node->start_mark.line + 1;
  loc->column = (int)node->start_mark.column + 1;
}

/* ---- scalars ------------------------------------------------------------ */

static const char *scalar_text(const yaml_node_t *node) {
  return (const char *)node->data.scalar.value;
}

static const char *node_kind(const yaml_node_t *node) {
  switch (node->type) {
    case YAML_SCALAR_NODE: return node->data.scalar.length == 0 ? "nothing" : "a scalar";
    case YAML_SEQUENCE_NODE: return "a list";
    case YAML_MAPPING_NODE: return "a mapping";
    case YAML_NO_NODE: break;
  }
  return "nothing";
}

static int is_plain_scalar(const yaml_node_t *node) {
  return node->type == YAML_SCALAR_NODE && node->data.scalar.style == YAML_PLAIN_SCALAR_STYLE;
}

static int ascii_casecmp(const char *a, const char *b) {
  for (;; ++a, ++b) {
    int ca = (unsigned char)*a, cb = (unsigned char)*b;
    if (ca >= 'A' && ca <= 'Z') ca += 'a' - 'A';
    if (cb >= 'A' && cb <= 'Z') cb += 'a' - 'A';
    if (ca != cb) return ca - cb;
    if (ca == 0) return 0;
  }
}

/* A number: a plain scalar that strtod consumes entirely, finite. */
static ball_status get_number(scene_loader *L, const yaml_node_t *node, const char *path, double *out) {
  const char *text;
  char *end;
  double v;
  if (node->type != YAML_SCALAR_NODE) return fail(L, node, path, "expected a number, got %s", node_kind(node));
  text = scalar_text(node);
  if (!is_plain_scalar(node)) return fail(L, node, path, "expected a number, got the string \"%s\"", text);
  if (node->data.scalar.length == 0) return fail(L, node, path, "expected a number, got nothing");
  {
    const char *t = (*text == '+' || *text == '-') ? text + 1 : text;
    if (ascii_casecmp(t, ".inf") == 0 || ascii_casecmp(t, ".nan") == 0)
      return fail(L, node, path, "expected a finite number, got %s", text);
  }
  errno = 0;
  v = strtod(text, &end);
  if (end == text || *end != '\0' || (size_t)(end - text) != node->data.scalar.length)
    return fail(L, node, path, "expected a number, got \"%s\"", text);
  if (!isfinite(v) || (errno == ERANGE && fabs(v) > 1.0))
    return fail(L, node, path, "expected a finite number, got %s", text);
  *out = v;
  return BALL_OK;
}

static ball_status get_int(scene_loader *L, const yaml_node_t *node, const char *path, int *out) {
  const char *text;
  char *end;
  long v;
  if (node->type != YAML_SCALAR_NODE) return fail(L, node, path, "expected an integer, got %s", node_kind(node));
  text = scalar_text(node);
  if (!is_plain_scalar(node)) return fail(L, node, path, "expected an integer, got the string \"%s\"", text);
  errno = 0;
  v = strtol(text, &end, 10);
  if (node->data.scalar.length == 0 || end == text || *end != '\0' ||
      (size_t)(end - text) != node->data.scalar.length)
    return fail(L, node, path, "expected an integer, got \"%s\"", text);
  if (errno == ERANGE || v < INT_MIN || v > INT_MAX)
    return fail(L, node, path, "integer %s is out of range", text);
  *out = (int)v;
  return BALL_OK;
}

static ball_status get_bool(scene_loader *L, const yaml_node_t *node, const char *path, int *out) {
  if (is_plain_scalar(node)) {
    if (strcmp(scalar_text(node), "true") == 0) { *out = 1; return BALL_OK; }
    if (strcmp(scalar_text(node), "false") == 0) { *out = 0; return BALL_OK; }
  }
  if (node->type != YAML_SCALAR_NODE) return fail(L, node, path, "expected true or false, got %s", node_kind(node));
  return fail(L, node, path, "expected true or false, got \"%s\"", scalar_text(node));
}

/* A list of three numbers. */
static ball_status get_vec3(scene_loader *L, const yaml_node_t *node, const char *path, ball_vec3 *out) {
  double c[3];
  int i, n;
  ball_status st;
  char sub[SCENE_PATH_SIZE];
  if (node->type != YAML_SEQUENCE_NODE)
    return fail(L, node, path, "expected a list of 3 numbers [x, y, z], got %s", node_kind(node));
  n = (int)(node->data.sequence.items.top - node->data.sequence.items.start);
  if (n != 3) return fail(L, node, path, "expected a list of 3 numbers [x, y, z], got %d item%s", n, n == 1 ? "" : "s");
  for (i = 0; i < 3; ++i) {
    yaml_node_t *item = yaml_document_get_node(L->doc, node->data.sequence.items.start[i]);
    snprintf(sub, sizeof sub, "%s[%d]", path, i);
    if ((st = get_number(L, item, sub, &c[i])) != BALL_OK) return st;
  }
  out->x = c[0];
  out->y = c[1];
  out->z = c[2];
  return BALL_OK;
}

/* An unsigned 64-bit integer (a seed): plain decimal digits, in range. */
static ball_status get_uint64(scene_loader *L, const yaml_node_t *node, const char *path, uint64_t *out) {
  const char *text, *c;
  char *end;
  unsigned long long v;
  if (node->type != YAML_SCALAR_NODE) return fail(L, node, path, "expected an integer, got %s", node_kind(node));
  text = scalar_text(node);
  if (!is_plain_scalar(node)) return fail(L, node, path, "expected an integer, got the string \"%s\"", text);
  if (node->data.scalar.length == 0) return fail(L, node, path, "expected an integer, got nothing");
  for (c = text; *c; ++c)
    if (*c < '0' || *c > '9')
      return fail(L, node, path, "expected an integer in [0, 18446744073709551615], got \"%s\"", text);
  errno = 0;
  v = strtoull(text, &end, 10);
  if (errno == ERANGE || *end != '\0' || v > (unsigned long long)UINT64_MAX)
    return fail(L, node, path, "integer %s is out of range [0, 18446744073709551615]", text);
  *out = (uint64_t)v;
  return BALL_OK;
}

/* A number in [lo, hi] (hi_open: [lo, hi)); read and checked where it stands. */
static ball_status get_ranged(scene_loader *L, const yaml_node_t *node, const char *path, double lo, double hi,
                              int hi_open, const char *range, double *out) {
  double v;
  ball_status st = get_number(L, node, path, &v);
  if (st != BALL_OK) return st;
  if (!(v >= lo) || (hi_open ? !(v < hi) : !(v <= hi)))
    return fail(L, node, path, "out of range: must be %s, got %s", range, scalar_text(node));
  *out = v;
  return BALL_OK;
}

/* A name out of a table of names (given by the library's own name functions). */
typedef const char *(*name_fn)(int value);

static const char *scheme_name(int v) { return ball_scheme_name((ball_scheme)v); }
static const char *detect_name(int v) { return ball_detect_name((ball_detect)v); }
static const char *normal_name(int v) { return ball_normal_mode_name((ball_normal_mode)v); }
static const char *response_name(int v) { return ball_response_name((ball_response)v); }
static const char *level_name(int v) { return ball_level_name((ball_level)v); }

static ball_status get_enum(scene_loader *L, const yaml_node_t *node, const char *path, name_fn names,
                            int count, int *out) {
  char choices[160];
  size_t used = 0;
  int i;
  if (node->type == YAML_SCALAR_NODE) {
    for (i = 0; i < count; ++i) {
      if (strcmp(scalar_text(node), names(i)) == 0) {
        *out = i;
        return BALL_OK;
      }
    }
  }
  choices[0] = '\0';
  for (i = 0; i < count && used < sizeof choices; ++i) {
    int w = snprintf(choices + used, sizeof choices - used, "%s%s", i ? (i + 1 == count ? " or " : ", ") : "",
                     names(i));
    if (w < 0) break;
    used += (size_t)w;
  }
  if (node->type != YAML_SCALAR_NODE) return fail(L, node, path, "expected one of %s, got %s", choices, node_kind(node));
  return fail(L, node, path, "expected one of %s, got \"%s\"", choices, scalar_text(node));
}

/* dst = "path.key" (or "key" at the top), cut to SCENE_PATH_SIZE. */
static void join(char *dst, const char *path, const char *key) {
  size_t n;
  copy_string(dst, SCENE_PATH_SIZE, path);
  n = strlen(dst);
  if (*path && n + 1 < SCENE_PATH_SIZE) dst[n++] = '.';
  copy_string(dst + n, SCENE_PATH_SIZE - n, key);
}


/* ---- sections ------------------------------------------------------------ */

/* A section (floor, racket, a wall, a script, ...) is a mapping read by one
 * loop, read_section, from a table of its keys: each key says what its value
 * is and where in the section's struct it goes. Keys that need more than
 * that (the net's axis, time.fps, a script, ...) are KEY_SPECIAL and go to
 * the section's hook, in their place in the file. */
typedef enum key_kind {
  KEY_NUMBER,  /* a finite number: double */
  KEY_INT,     /* an integer: int */
  KEY_BOOL,    /* true or false: int */
  KEY_VEC3,    /* [x, y, z]: ball_vec3 */
  KEY_ENUM,    /* one of the names of key_spec.names: stored by key_spec.put */
  KEY_RANGED,  /* a number in key_spec's range, checked where it stands: double */
  KEY_UINT64,  /* an unsigned 64-bit integer: uint64_t */
  KEY_SPECIAL  /* read by the section's hook */
} key_kind;

typedef struct key_spec {
  const char *name;                  /* NULL ends a table */
  key_kind kind;
  size_t offset;                     /* of the field in the section's struct */
  int required;                      /* must be given (in a section that requires keys) */
  name_fn names;                     /* KEY_ENUM: the names, how many, and how to store one */
  int count;
  void (*put)(void *field, int value);
  double lo, hi;                     /* KEY_RANGED: [lo, hi], or [lo, hi) with hi_open */
  int hi_open;
  const char *range;                 /* KEY_RANGED: the range in words, for the error */
} key_spec;

#define KEY(name, kind, type, field) {name, kind, offsetof(type, field), 0, NULL, 0, NULL, 0.0, 0.0, 0, NULL}
#define REQUIRED_KEY(name, kind, type, field) \
  {name, kind, offsetof(type, field), 1, NULL, 0, NULL, 0.0, 0.0, 0, NULL}
#define SPECIAL_KEY(name, required) {name, KEY_SPECIAL, 0, required, NULL, 0, NULL, 0.0, 0.0, 0, NULL}
#define ENUM_KEY(name, type, field, names, count, put) \
  {name, KEY_ENUM, offsetof(type, field), 0, names, count, put, 0.0, 0.0, 0, NULL}
#define RANGED_KEY(name, type, field, lo, hi, hi_open, range) \
  {name, KEY_RANGED, offsetof(type, field), 0, NULL, 0, NULL, lo, hi, hi_open, range}
#define END_OF_KEYS {NULL, KEY_SPECIAL, 0, 0, NULL, 0, NULL, 0.0, 0.0, 0, NULL}

static void put_scheme(void *field, int v) { *(ball_scheme *)field = (ball_scheme)v; }
static void put_detect(void *field, int v) { *(ball_detect *)field = (ball_detect)v; }
static void put_normal(void *field, int v) { *(ball_normal_mode *)field = (ball_normal_mode)v; }
static void put_response(void *field, int v) { *(ball_response *)field = (ball_response)v; }

/* Reads a KEY_SPECIAL key (key: its key node) of the section that fills
 * base; ctx is what the section's caller passed along. */
typedef ball_status (*key_hook)(scene_loader *L, const yaml_node_t *key, const yaml_node_t *value,
                                const char *path, void *base, void *ctx);

typedef struct section {
  const key_spec *keys;
  key_hook hook;  /* NULL when no key is KEY_SPECIAL */
  int require;    /* fail on a missing required key */
  int record;     /* remember where each key was set (model keys: for ball_model_check's errors) */
} section;

static const key_spec *find_key(const key_spec *keys, const char *name) {
  for (; keys->name; ++keys)
    if (strcmp(keys->name, name) == 0) return keys;
  return NULL;
}

static const char *pair_key(scene_loader *L, const yaml_node_pair_t *p) {
  return scalar_text(yaml_document_get_node(L->doc, p->key));
}

/* The value of key in mapping node, or NULL. */
static yaml_node_t *key_value(scene_loader *L, const yaml_node_t *node, const char *key) {
  yaml_node_pair_t *p;
  for (p = node->data.mapping.pairs.start; p < node->data.mapping.pairs.top; ++p)
    if (strcmp(pair_key(L, p), key) == 0) return yaml_document_get_node(L->doc, p->value);
  return NULL;
}

/* Checks that node is a mapping whose keys are distinct scalars, each one of
 * the section's, and (if it requires them) that no required key is missing. */
static ball_status check_section(scene_loader *L, const yaml_node_t *node, const char *path, const section *sec) {
  yaml_node_pair_t *p, *q;
  const key_spec *r;
  if (node->type != YAML_MAPPING_NODE)
    return fail(L, node, path, "expected a mapping (key: value lines), got %s", node_kind(node));
  for (p = node->data.mapping.pairs.start; p < node->data.mapping.pairs.top; ++p) {
    yaml_node_t *key = yaml_document_get_node(L->doc, p->key);
    char sub[SCENE_PATH_SIZE];
    if (key->type != YAML_SCALAR_NODE) return fail(L, key, path, "a key must be a plain name, got %s", node_kind(key));
    join(sub, path, scalar_text(key));
    if (!find_key(sec->keys, scalar_text(key))) return fail(L, key, sub, "unknown key \"%s\"", scalar_text(key));
    for (q = node->data.mapping.pairs.start; q < p; ++q) {
      yaml_node_t *prev = yaml_document_get_node(L->doc, q->key);
      if (strcmp(scalar_text(prev), scalar_text(key)) == 0)
        return fail(L, key, sub, "key given twice (first on line %d)", (int)prev->start_mark.line + 1);
    }
  }
  for (r = sec->keys; sec->require && r->name; ++r) {
    if (r->required && !key_value(L, node, r->name)) {
      char sub[SCENE_PATH_SIZE];
      join(sub, path, r->name);
      return fail(L, node, sub, "missing required key \"%s\"", r->name);
    }
  }
  return BALL_OK;
}

/* Reads value into base's field that spec names. */
static ball_status read_key(scene_loader *L, const key_spec *spec, const yaml_node_t *value, const char *path,
                            void *base) {
  void *field = (char *)base + spec->offset;
  ball_status st;
  int e;
  switch (spec->kind) {
    case KEY_NUMBER: return get_number(L, value, path, field);
    case KEY_INT: return get_int(L, value, path, field);
    case KEY_BOOL: return get_bool(L, value, path, field);
    case KEY_VEC3: return get_vec3(L, value, path, field);
    case KEY_UINT64: return get_uint64(L, value, path, field);
    case KEY_RANGED:
      return get_ranged(L, value, path, spec->lo, spec->hi, spec->hi_open, spec->range, field);
    case KEY_ENUM:
      if ((st = get_enum(L, value, path, spec->names, spec->count, &e)) == BALL_OK) spec->put(field, e);
      return st;
    case KEY_SPECIAL: break;
  }
  return BALL_EINVAL; /* not reached: KEY_SPECIAL keys go to the hook */
}

/* Reads the pairs of a checked section in file order into base. */
static ball_status read_section(scene_loader *L, const yaml_node_t *node, const char *path, const section *sec,
                                void *base, void *ctx) {
  yaml_node_pair_t *p;
  for (p = node->data.mapping.pairs.start; p < node->data.mapping.pairs.top; ++p) {
    yaml_node_t *key = yaml_document_get_node(L->doc, p->key);
    yaml_node_t *value = yaml_document_get_node(L->doc, p->value);
    const key_spec *spec = find_key(sec->keys, scalar_text(key));
    char sub[SCENE_PATH_SIZE];
    ball_status st;
    join(sub, path, scalar_text(key));
    if (spec->kind == KEY_SPECIAL) {
      st = sec->hook(L, key, value, sub, base, ctx);
    } else {
      st = read_key(L, spec, value, sub, base);
      if (st == BALL_OK && sec->record) remember(L, sub, NULL, value);
    }
    if (st != BALL_OK) return st;
  }
  return BALL_OK;
}

static ball_status load_section(scene_loader *L, const yaml_node_t *node, const char *path, const section *sec,
                                void *base, void *ctx) {
  ball_status st = check_section(L, node, path, sec);
  return st != BALL_OK ? st : read_section(L, node, path, sec, base, ctx);
}

/* The items of a list (what: "walls") of at most max of them. */
static ball_status get_list(scene_loader *L, const yaml_node_t *node, const char *path, const char *what, int max,
                            int *n) {
  if (node->type != YAML_SEQUENCE_NODE) return fail(L, node, path, "expected a list of %s, got %s", what, node_kind(node));
  *n = (int)(node->data.sequence.items.top - node->data.sequence.items.start);
  if (*n > max) return fail(L, node, path, "%d %s given, at most %d allowed", *n, what, max);
  return BALL_OK;
}

static yaml_node_t *list_item(scene_loader *L, const yaml_node_t *node, int i) {
  return yaml_document_get_node(L->doc, node->data.sequence.items.start[i]);
}

/* ---- floor, net and walls -------------------------------------------------- */

static const key_spec floor_keys[] = {
    KEY("level", KEY_NUMBER, ball_model, floor_level),
    KEY("damping", KEY_NUMBER, ball_model, floor_damping),
    KEY("bounce_threshold", KEY_NUMBER, ball_model, bounce_threshold),
    KEY("sound_threshold", KEY_NUMBER, ball_model, sound_threshold),
    KEY("spin_damping", KEY_NUMBER, ball_model, spin_floor_damping),
    END_OF_KEYS,
};
static const section floor_section = {floor_keys, NULL, 0, 1};

/* A plane's axis: x or z (stored as 0 or 2). */
static ball_status plane_axis(scene_loader *L, const yaml_node_t *key, const yaml_node_t *v, const char *path,
                              void *base, void *ctx) {
  ball_plane *pl = (ball_plane *)base;
  (void)key;
  (void)ctx;
  if (v->type == YAML_SCALAR_NODE && strcmp(scalar_text(v), "x") == 0) pl->axis = 0;
  else if (v->type == YAML_SCALAR_NODE && strcmp(scalar_text(v), "z") == 0) pl->axis = 2;
  else if (v->type == YAML_SCALAR_NODE) return fail(L, v, path, "expected x or z, got \"%s\"", scalar_text(v));
  else return fail(L, v, path, "expected x or z, got %s", node_kind(v));
  remember(L, path, NULL, v);
  return BALL_OK;
}

/* A net or a wall: keys of ball_plane. A wall must give the required ones;
 * without "bottom" it stands on the floor (load_root). */
static const key_spec plane_keys[] = {
    SPECIAL_KEY("axis", 1),
    REQUIRED_KEY("position", KEY_NUMBER, ball_plane, position),
    REQUIRED_KEY("lo", KEY_NUMBER, ball_plane, lo),
    REQUIRED_KEY("hi", KEY_NUMBER, ball_plane, hi),
    KEY("bottom", KEY_NUMBER, ball_plane, bottom),
    REQUIRED_KEY("top", KEY_NUMBER, ball_plane, top),
    KEY("damping", KEY_NUMBER, ball_plane, damping),
    END_OF_KEYS,
};
static const section net_section = {plane_keys, plane_axis, 0, 1};
static const section wall_section = {plane_keys, plane_axis, 1, 1};

static ball_status load_net(scene_loader *L, const yaml_node_t *node) {
  ball_status st;
  if (node->type == YAML_SCALAR_NODE && strcmp(scalar_text(node), "none") == 0) {
    L->scene.model.has_net = 0;
    return BALL_OK;
  }
  if (node->type == YAML_SCALAR_NODE)
    return fail(L, node, "net", "expected a mapping or none, got \"%s\"", scalar_text(node));
  if ((st = load_section(L, node, "net", &net_section, &L->scene.model.net, NULL)) != BALL_OK) return st;
  L->scene.model.has_net = 1;
  return BALL_OK;
}

static ball_status load_walls(scene_loader *L, const yaml_node_t *node, double default_damping) {
  ball_model *m = &L->scene.model;
  int i, n;
  ball_status st;
  if ((st = get_list(L, node, "walls", "walls", BALL_MAX_WALLS, &n)) != BALL_OK) return st;
  for (i = 0; i < n; ++i) {
    yaml_node_t *item = list_item(L, node, i);
    char path[SCENE_PATH_SIZE];
    ball_plane *w = &m->walls[i];
    snprintf(path, sizeof path, "walls[%d]", i);
    remember(L, path, NULL, item);
    memset(w, 0, sizeof *w);
    w->damping = default_damping;
    if ((st = load_section(L, item, path, &wall_section, w, NULL)) != BALL_OK) return st;
    L->wall_bottom_set[i] = key_value(L, item, "bottom") != NULL;
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
  if (strcmp(scalar_text(key), "t") == 0) {
    if ((st = get_number(L, v, path, &k->t)) != BALL_OK) return st;
    if (k > s->keyframes && !(k->t > k[-1].t))
      return fail(L, v, path, "out of range: keyframe times must increase strictly, got %s after %.17g",
                  scalar_text(v), k[-1].t);
  } else {
    ball_vec3 u;
    double big, w;
    if ((st = get_vec3(L, v, path, &u)) != BALL_OK) return st;
    /* normalise without overflow: scale by the largest component first */
    big = fmax(fabs(u.x), fmax(fabs(u.y), fabs(u.z)));
    if (big > 0.0) {
      u.x /= big;
      u.y /= big;
      u.z /= big;
    }
    w = sqrt(u.x * u.x + u.y * u.y + u.z * u.z);
    if (!(big * w >= 1e-9)) return fail(L, v, path, "out of range: a normal must not be (nearly) zero");
    k->normal.x = u.x / w;
    k->normal.y = u.y / w;
    k->normal.z = u.z / w;
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

static ball_status load_keyframes(scene_loader *L, const yaml_node_t *node, const char *path,
                                  ball_racket_script *s) {
  int i, n;
  ball_status st;
  if (node->type != YAML_SEQUENCE_NODE)
    return fail(L, node, path, "expected a list of keyframes {t, center, normal}, got %s", node_kind(node));
  n = (int)(node->data.sequence.items.top - node->data.sequence.items.start);
  if (n < 1) return fail(L, node, path, "expected at least one keyframe");
  if (n > BALL_SCRIPT_MAX_KEYFRAMES)
    return fail(L, node, path, "%d keyframes given, at most %d allowed", n, BALL_SCRIPT_MAX_KEYFRAMES);
  for (i = 0; i < n; ++i) {
    char kpath[SCENE_PATH_SIZE];
    snprintf(kpath, sizeof kpath, "%.80s[%d]", path, i);
    if ((st = load_section(L, list_item(L, node, i), kpath, &keyframe_section, &s->keyframes[i], s)) != BALL_OK)
      return st;
  }
  s->n_keyframes = n;
  return BALL_OK;
}

static ball_status script_keyframes(scene_loader *L, const yaml_node_t *key, const yaml_node_t *v,
                                    const char *path, void *base, void *ctx) {
  (void)key;
  (void)ctx;
  return load_keyframes(L, v, path, (ball_racket_script *)base);
}

/* rackets[i].script: keyframes and network conditions (docs/scenes.md). */
static const key_spec script_keys[] = {
    SPECIAL_KEY("keyframes", 1),
    RANGED_KEY("repeat", ball_racket_script, repeat, 0.0, HUGE_VAL, 0, ">= 0 (0: no repeat)"),
    RANGED_KEY("rate", ball_racket_script, rate, 2.0, 120.0, 0, "in [2, 120] Hz"),
    RANGED_KEY("delay", ball_racket_script, delay, 0.0, 60.0, 0, "in [0, 60] s"),
    RANGED_KEY("jitter", ball_racket_script, jitter, 0.0, 0.5, 0, "in [0, 0.5] s"),
    RANGED_KEY("loss", ball_racket_script, loss, 0.0, 1.0, 1, "in [0, 1)"),
    RANGED_KEY("duplicate", ball_racket_script, duplicate, 0.0, 1.0, 0, "in [0, 1]"),
    RANGED_KEY("noise", ball_racket_script, noise, 0.0, HUGE_VAL, 0, ">= 0 m"),
    RANGED_KEY("normal_noise", ball_racket_script, normal_noise, 0.0, 1.0, 0, "in [0, 1] rad"),
    KEY("seed", KEY_UINT64, ball_racket_script, seed),
    END_OF_KEYS,
};
static const section script_section = {script_keys, script_keyframes, 1, 0};

static ball_status load_script(scene_loader *L, const yaml_node_t *node, const char *path, ball_racket_script *s) {
  const yaml_node_t *repeat_node;
  ball_status st;
  const char *field = NULL;
  ball_script_default(s);
  if ((st = load_section(L, node, path, &script_section, s, NULL)) != BALL_OK) return st;
  repeat_node = key_value(L, node, "repeat");
  if (repeat_node && s->repeat != 0.0 &&
      !(s->repeat > s->keyframes[s->n_keyframes - 1].t - s->keyframes[0].t)) {
    char sub[SCENE_PATH_SIZE];
    join(sub, path, "repeat");
    return fail(L, repeat_node, sub, "out of range: must be 0 or > the keyframes' span (%.17g s), got %s",
                s->keyframes[s->n_keyframes - 1].t - s->keyframes[0].t, scalar_text(repeat_node));
  }
  /* the reader checked every field where it stands; this is the library's word */
  if ((st = ball_script_check(s, &field)) != BALL_OK)
    return fail(L, node, path, "rejected by ball_script_check: %s: %s", field ? field : "?", ball_strerror(st));
  return BALL_OK;
}

/* rackets[i].script goes to L->scene.scripts[i] (ctx). */
static ball_status racket_script(scene_loader *L, const yaml_node_t *key, const yaml_node_t *v, const char *path,
                                 void *base, void *ctx) {
  ball_status st = load_script(L, v, path, (ball_racket_script *)ctx);
  (void)key;
  (void)base;
  if (st == BALL_OK) remember(L, path, NULL, v);
  return st;
}

static const key_spec rackets_keys[] = {
    KEY("radius", KEY_NUMBER, ball_racket_def, radius),
    KEY("partner", KEY_INT, ball_racket_def, partner),
    KEY("target", KEY_VEC3, ball_racket_def, target),
    SPECIAL_KEY("script", 0),
    END_OF_KEYS,
};
static const section rackets_section = {rackets_keys, racket_script, 0, 1};

static ball_status load_rackets(scene_loader *L, const yaml_node_t *node, const ball_model *defaults) {
  ball_model *m = &L->scene.model;
  int i, n;
  ball_status st;
  if ((st = get_list(L, node, "rackets", "rackets", BALL_MAX_RACKETS, &n)) != BALL_OK) return st;
  for (i = 0; i < n; ++i) {
    yaml_node_t *item = list_item(L, node, i);
    ball_racket_def *r = &m->rackets[i];
    char path[SCENE_PATH_SIZE];
    snprintf(path, sizeof path, "rackets[%d]", i);
    remember(L, path, NULL, item);
    *r = defaults->rackets[i];
    if ((st = load_section(L, item, path, &rackets_section, r, &L->scene.scripts[i])) != BALL_OK) return st;
  }
  m->n_rackets = n;
  return BALL_OK;
}

static const key_spec racket_keys[] = {
    ENUM_KEY("detect", ball_model, detect, detect_name, BALL_DETECT_COUNT, put_detect),
    ENUM_KEY("normal", ball_model, normal_mode, normal_name, BALL_NORMAL_COUNT, put_normal),
    ENUM_KEY("response", ball_model, response, response_name, BALL_RESPONSE_COUNT, put_response),
    KEY("collision_distance", KEY_NUMBER, ball_model, collision_distance),
    KEY("sleep_frames", KEY_INT, ball_model, sleep_frames),
    KEY("v_min", KEY_NUMBER, ball_model, v_min),
    KEY("v_max", KEY_NUMBER, ball_model, v_max),
    KEY("v_up", KEY_NUMBER, ball_model, v_up),
    KEY("v_up_from_racket", KEY_BOOL, ball_model, v_up_from_racket),
    KEY("friendly_factor", KEY_NUMBER, ball_model, friendly_factor),
    KEY("spin_rack_damping", KEY_NUMBER, ball_model, spin_rack_damping),
    KEY("history", KEY_INT, ball_model, history),
    KEY("extrapolation_time", KEY_NUMBER, ball_model, extrapolation_time),
    KEY("stale_time", KEY_NUMBER, ball_model, stale_time),
    END_OF_KEYS,
};
static const section racket_section = {racket_keys, NULL, 0, 1};

/* ---- time, effects and the ball -------------------------------------------- */

/* time.frame_time or time.fps (one of them; ctx: the one seen so far). */
static ball_status time_frame(scene_loader *L, const yaml_node_t *key, const yaml_node_t *v, const char *path,
                              void *base, void *ctx) {
  ball_scene *sc = (ball_scene *)base;
  const yaml_node_t **frame_node = (const yaml_node_t **)ctx;
  ball_status st;
  double x;
  if (*frame_node) return fail(L, key, "time", "give frame_time or fps, not both");
  *frame_node = v;
  if ((st = get_number(L, v, path, &x)) != BALL_OK) return st;
  if (strcmp(scalar_text(key), "frame_time") == 0) {
    if (!(x > 0.0)) return fail(L, v, path, "out of range: must be > 0, got %s", scalar_text(v));
    sc->frame_time = x;
  } else {
    if (!(x > 0.0) || !isfinite(1.0 / x))
      return fail(L, v, path, "out of range: must be > 0 (and 1 / fps finite), got %s", scalar_text(v));
    sc->frame_time = 1.0 / x;
  }
  return BALL_OK;
}

static const key_spec time_keys[] = {
    SPECIAL_KEY("frame_time", 0),
    SPECIAL_KEY("fps", 0),
    RANGED_KEY("time_base", ball_scene, time_base, 4.9406564584124654e-324, HUGE_VAL, 0, "> 0"),
    END_OF_KEYS,
};
static const section time_section = {time_keys, time_frame, 0, 0};

static ball_status load_effects(scene_loader *L, const yaml_node_t *node) {
  unsigned mask = 0;
  int i, n;
  ball_status st;
  if ((st = get_list(L, node, "effects", "effect names", INT_MAX, &n)) != BALL_OK) return st;
  for (i = 0; i < n; ++i) {
    yaml_node_t *item = list_item(L, node, i);
    char path[SCENE_PATH_SIZE];
    unsigned bit;
    snprintf(path, sizeof path, "effects[%d]", i);
    for (bit = 1u; bit & BALL_EFFECT_ALL; bit <<= 1) {
      if (item->type == YAML_SCALAR_NODE && strcmp(scalar_text(item), ball_effect_name((ball_effect)bit)) == 0)
        break;
    }
    if (!(bit & BALL_EFFECT_ALL)) {
      if (item->type != YAML_SCALAR_NODE) return fail(L, item, path, "expected an effect name, got %s", node_kind(item));
      return fail(L, item, path,
                  "unknown effect \"%s\" (drag, spin, floor, net, walls, rackets or sound)", scalar_text(item));
    }
    if (mask & bit) return fail(L, item, path, "effect \"%s\" listed twice", scalar_text(item));
    mask |= bit;
  }
  L->scene.model.effects = mask;
  remember(L, "effects", NULL, node);
  return BALL_OK;
}

static const key_spec ball_keys[] = {
    KEY("position", KEY_VEC3, ball_model, initial_position),
    KEY("velocity", KEY_VEC3, ball_model, initial_velocity),
    KEY("spin", KEY_VEC3, ball_model, initial_spin),
    END_OF_KEYS,
};
static const section ball_section = {ball_keys, NULL, 0, 1};

/* ---- the render section (docs/render.md) ---------------------------------- */

#define SCENE_DEFAULT_MARKERS 1.0 /* s */

/* A camera's name: distinct from the cameras before it (ctx: the section). */
static ball_status camera_name(scene_loader *L, const yaml_node_t *key, const yaml_node_t *v, const char *path,
                               void *base, void *ctx) {
  ball_scene_camera *c = (ball_scene_camera *)base;
  const ball_scene_render *r = (const ball_scene_render *)ctx;
  const char *text, *ch;
  int i;
  (void)key;
  if (v->type != YAML_SCALAR_NODE || v->data.scalar.length == 0)
    return fail(L, v, path, "expected a name, got %s", node_kind(v));
  text = scalar_text(v);
  if (v->data.scalar.length >= sizeof c->name)
    return fail(L, v, path, "longer than %d characters", (int)sizeof c->name - 1);
  for (ch = text; *ch; ++ch)
    if (!((*ch >= 'a' && *ch <= 'z') || (*ch >= 'A' && *ch <= 'Z') || (*ch >= '0' && *ch <= '9') || *ch == '_' ||
          *ch == '-'))
      return fail(L, v, path, "\"%s\": a name takes letters, digits, '_' and '-' only", text);
  for (i = 0; r->cameras + i < c; ++i)
    if (strcmp(r->cameras[i].name, text) == 0) return fail(L, v, path, "camera \"%s\" named twice", text);
  copy_string(c->name, sizeof c->name, text);
  return BALL_OK;
}

static const key_spec camera_keys[] = {
    SPECIAL_KEY("name", 1),
    REQUIRED_KEY("eye", KEY_VEC3, ball_scene_camera, camera.eye),
    REQUIRED_KEY("target", KEY_VEC3, ball_scene_camera, camera.target),
    KEY("up", KEY_VEC3, ball_scene_camera, camera.up),
    RANGED_KEY("fov", ball_scene_camera, camera.fov, 1.0, 179.0, 0, "in [1, 179] degrees"),
    END_OF_KEYS,
};
static const section camera_section = {camera_keys, camera_name, 1, 0};

static double dot3(ball_vec3 a, ball_vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }

static ball_status load_cameras(scene_loader *L, const yaml_node_t *node, const char *path, ball_scene_render *r) {
  int i, n;
  ball_status st;
  if ((st = get_list(L, node, path, "cameras", BALL_SCENE_MAX_CAMERAS, &n)) != BALL_OK) return st;
  for (i = 0; i < n; ++i) {
    ball_scene_camera *c = &r->cameras[i];
    yaml_node_t *item = list_item(L, node, i);
    char sub[SCENE_PATH_SIZE];
    ball_vec3 d;
    double dd, du, cross;
    snprintf(sub, sizeof sub, "%s[%d]", path, i);
    memset(c, 0, sizeof *c);
    c->camera.up.y = 1.0;
    c->camera.fov = 45.0;
    if ((st = load_section(L, item, sub, &camera_section, c, r)) != BALL_OK) return st;
    d.x = c->camera.target.x - c->camera.eye.x;
    d.y = c->camera.target.y - c->camera.eye.y;
    d.z = c->camera.target.z - c->camera.eye.z;
    dd = dot3(d, d);
    du = dot3(c->camera.up, c->camera.up);
    if (!(dd > 1e-12) || !isfinite(dd)) return fail(L, item, sub, "target must be away from eye");
    /* |d x up|^2 = |d|^2 |up|^2 - (d . up)^2: the up vector must not lie along d */
    cross = dd * du - dot3(d, c->camera.up) * dot3(d, c->camera.up);
    if (!(du > 0.0) || !isfinite(du) || !(cross > 1e-6 * dd * du))
      return fail(L, item, sub, "up must not be zero or along target - eye");
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
    RANGED_KEY("trail", ball_scene_render, trail, 0.0, 60.0, 0, "in [0, 60] s"),
    RANGED_KEY("markers", ball_scene_render, markers, 0.0, 60.0, 0, "in [0, 60] s"),
    SPECIAL_KEY("cameras", 0),
    END_OF_KEYS,
};
static const section render_section = {render_keys, render_cameras, 0, 0};

/* ---- mapping ball_model_check's field names back to scene keys ---------- */

/* Model field (or prefix) -> scene path (or prefix). Fields not listed have
 * the same name in the scene (gravity, mass, net.*, walls[i].*, ...). */
static const char *const field_to_scene[][2] = {
    {"floor_level", "floor.level"},
    {"floor_damping", "floor.damping"},
    {"bounce_threshold", "floor.bounce_threshold"},
    {"sound_threshold", "floor.sound_threshold"},
    {"spin_floor_damping", "floor.spin_damping"},
    {"has_net", "net"},
    {"n_walls", "walls"},
    {"n_rackets", "rackets"},
    {"detect", "racket.detect"},
    {"normal_mode", "racket.normal"},
    {"response", "racket.response"},
    {"collision_distance", "racket.collision_distance"},
    {"sleep_frames", "racket.sleep_frames"},
    {"v_min", "racket.v_min"},
    {"v_max", "racket.v_max"},
    {"v_up", "racket.v_up"},
    {"v_up_from_racket", "racket.v_up_from_racket"},
    {"friendly_factor", "racket.friendly_factor"},
    {"spin_rack_damping", "racket.spin_rack_damping"},
    {"history", "racket.history"},
    {"extrapolation_time", "racket.extrapolation_time"},
    {"stale_time", "racket.stale_time"},
    {"initial_position", "ball.position"},
    {"initial_velocity", "ball.velocity"},
    {"initial_spin", "ball.spin"},
};

static int prefix_of(const char *prefix, const char *s) {
  size_t n = strlen(prefix);
  return strncmp(prefix, s, n) == 0 && (s[n] == '\0' || s[n] == '.' || s[n] == '[');
}

static void scene_path_of(const char *field, char *out) {
  size_t i;
  for (i = 0; i < sizeof field_to_scene / sizeof field_to_scene[0]; ++i) {
    if (prefix_of(field_to_scene[i][0], field)) {
      snprintf(out, SCENE_PATH_SIZE, "%s%s", field_to_scene[i][1], field + strlen(field_to_scene[i][0]));
      return;
    }
  }
  copy_string(out, SCENE_PATH_SIZE, field);
}

/* What ball_model_check wants of a key (indices stripped: walls[].hi);
 * keys not listed get the library's generic sentence. */
static const char *const range_hints[][2] = {
    {"gravity", "must be > 0"},
    {"mass", "must be > 0"},
    {"air_friction", "must be >= 0"},
    {"radius", "must be >= 0"},
    {"spin_damping", "must be > 0"},
    {"floor.damping", "must be in [0, 1]"},
    {"floor.bounce_threshold", "must be >= 0"},
    {"floor.sound_threshold", "must be >= 0"},
    {"floor.spin_damping", "must be in [0, 1]"},
    {"net.hi", "must be > lo"},
    {"net.top", "must be > bottom"},
    {"net.damping", "must be in [0, 1]"},
    {"walls[].hi", "must be > lo"},
    {"walls[].top", "must be > bottom"},
    {"walls[].damping", "must be in [0, 1]"},
    {"rackets[].radius", "must be > 0"},
    {"rackets[].partner", "must be -1 (fly to target) or the index of another racket in the list"},
    {"racket.collision_distance", "must be > 0"},
    {"racket.sleep_frames", "must be >= 0"},
    {"racket.v_min", "must be >= 0"},
    {"racket.v_max", "must be >= racket.v_min"},
    {"racket.v_up", "must be > 0"},
    {"racket.friendly_factor", "must be >= 0, and <= 1 with response mixed (eq 10)"},
    {"racket.spin_rack_damping", "must be in [0, 1]"},
    {"racket.history", "must be in [2, 16]"},
    {"racket.extrapolation_time", "must be >= 0"},
    {"racket.stale_time", "must be > 0"},
    {"ball.position", "must not start below the floor (y >= floor.level + radius) while the floor effect is on"},
};

static const char *range_hint(const char *path) {
  char bare[SCENE_PATH_SIZE];
  size_t i = 0, j = 0;
  /* "walls[3].hi" -> "walls[].hi" */
  while (path[i] && j + 1 < sizeof bare) {
    bare[j++] = path[i];
    if (path[i++] == '[')
      while (path[i] >= '0' && path[i] <= '9') ++i;
  }
  bare[j] = '\0';
  for (i = 0; i < sizeof range_hints / sizeof range_hints[0]; ++i)
    if (strcmp(range_hints[i][0], bare) == 0) return range_hints[i][1];
  return NULL;
}

/* The location that set path, or the one of its closest enclosing key. */
static const scene_location *find_location(const scene_loader *L, const char *path) {
  const scene_location *best = NULL;
  size_t best_len = 0;
  int i;
  for (i = 0; i < L->n_locations; ++i) {
    const scene_location *loc = &L->locations[i];
    size_t n = strlen(loc->path);
    if (prefix_of(loc->path, path) && (!best || n >= best_len)) {
      best = loc;
      best_len = n;
    }
  }
  return best;
}

/* ---- the document --------------------------------------------------------- */


/* The top-level keys that are not plain fields: name, duration and the
 * sections (level is read first, by load_root). ctx: the default model. */
static ball_status root_key(scene_loader *L, const yaml_node_t *key, const yaml_node_t *v, const char *path,
                            void *base, void *ctx) {
  const ball_model *defaults = (const ball_model *)ctx;
  const char *k = scalar_text(key);
  const yaml_node_t *frame_node = NULL;
  ball_status st;
  if (strcmp(k, "level") == 0) return BALL_OK;
  if (strcmp(k, "name") == 0) {
    if (v->type != YAML_SCALAR_NODE) return fail(L, v, "name", "expected a string, got %s", node_kind(v));
    if (v->data.scalar.length >= sizeof L->scene.name)
      return fail(L, v, "name", "longer than %d characters", (int)sizeof L->scene.name - 1);
    copy_string(L->scene.name, sizeof L->scene.name, scalar_text(v));
    return BALL_OK;
  }
  if (strcmp(k, "duration") == 0) {
    if ((st = get_number(L, v, "duration", &L->scene.duration)) != BALL_OK) return st;
    if (!(L->scene.duration > 0.0)) return fail(L, v, "duration", "must be > 0, got %s", scalar_text(v));
    return BALL_OK;
  }
  if (strcmp(k, "floor") == 0) st = load_section(L, v, path, &floor_section, base, NULL);
  else if (strcmp(k, "net") == 0) st = load_net(L, v);
  else if (strcmp(k, "walls") == 0) st = load_walls(L, v, defaults->net.damping);
  else if (strcmp(k, "rackets") == 0) st = load_rackets(L, v, defaults);
  else if (strcmp(k, "racket") == 0) st = load_section(L, v, path, &racket_section, base, NULL);
  else if (strcmp(k, "time") == 0) st = load_section(L, v, path, &time_section, &L->scene, &frame_node);
  else if (strcmp(k, "effects") == 0) st = load_effects(L, v);
  else if (strcmp(k, "render") == 0) st = load_section(L, v, path, &render_section, &L->scene.render, NULL);
  else st = load_section(L, v, path, &ball_section, base, NULL);
  if (st != BALL_OK) return st;
  if (v->type != YAML_SCALAR_NODE) remember(L, k, NULL, v);
  return BALL_OK;
}

static const key_spec root_keys[] = {
    SPECIAL_KEY("name", 0),
    SPECIAL_KEY("duration", 0),
    KEY("gravity", KEY_NUMBER, ball_model, gravity),
    KEY("mass", KEY_NUMBER, ball_model, mass),
    KEY("air_friction", KEY_NUMBER, ball_model, air_friction),
    KEY("radius", KEY_NUMBER, ball_model, radius),
    KEY("spin_damping", KEY_NUMBER, ball_model, spin_damping),
    SPECIAL_KEY("floor", 0),
    SPECIAL_KEY("net", 0),
    SPECIAL_KEY("walls", 0),
    SPECIAL_KEY("rackets", 0),
    SPECIAL_KEY("racket", 0),
    SPECIAL_KEY("level", 0),
    SPECIAL_KEY("time", 0),
    SPECIAL_KEY("effects", 0),
    ENUM_KEY("scheme", ball_model, scheme, scheme_name, BALL_SCHEME_COUNT, put_scheme),
    SPECIAL_KEY("ball", 0),
    SPECIAL_KEY("render", 0),
    END_OF_KEYS,
};
static const section root_section = {root_keys, root_key, 0, 1};

static ball_status load_root(scene_loader *L, const yaml_node_t *root) {
  ball_model defaults;
  ball_model *m = &L->scene.model;
  yaml_node_t *v;
  ball_status st;
  const char *field = NULL;
  int i;

  ball_model_default(&defaults);
  if (root->type == YAML_SCALAR_NODE && root->data.scalar.length == 0)
    return fail(L, root, "", "the scene is empty (expected a mapping of keys)");
  if ((st = check_section(L, root, "", &root_section)) != BALL_OK) return st;
  remember(L, "", NULL, root);

  /* The level preset goes first, whatever its place in the file, so every
   * racket key can override it. */
  if ((v = key_value(L, root, "level")) != NULL) {
    int level;
    if ((st = get_enum(L, v, "level", level_name, BALL_LEVEL_COUNT, &level)) != BALL_OK) return st;
    if (ball_model_set_level(m, (ball_level)level) != BALL_OK)
      return fail(L, v, "level", "the library rejected level \"%s\"", scalar_text(v));
    remember(L, "level", NULL, v);
  }

  if ((st = read_section(L, root, "", &root_section, m, &defaults)) != BALL_OK) return st;

  /* A wall without "bottom" stands on the floor. */
  for (i = 0; i < m->n_walls; ++i)
    if (!L->wall_bottom_set[i]) m->walls[i].bottom = m->floor_level;

  st = ball_model_check(m, &field);
  if (st != BALL_OK) {
    char path[SCENE_PATH_SIZE];
    const scene_location *loc;
    scene_path_of(field ? field : "", path);
    if (strncmp(path, "rackets.", 8) == 0) {
      /* the library names the key but not the racket: find the first one
       * that still fails when every other racket is a default one */
      ball_model probe;
      ball_model def;
      const char *probe_field = NULL;
      int j;
      ball_model_default(&def);
      for (i = 0; i < m->n_rackets; ++i) {
        probe = *m;
        for (j = 0; j < m->n_rackets; ++j)
          if (j != i) probe.rackets[j] = def.rackets[j];
        if (ball_model_check(&probe, &probe_field) != BALL_OK && probe_field && strcmp(probe_field, field) == 0) {
          char rest[SCENE_PATH_SIZE];
          copy_string(rest, sizeof rest, path + 8);
          snprintf(path, sizeof path, "rackets[%d].%.32s", i, rest);
          break;
        }
      }
    }
    if (strcmp(path, "walls") == 0) {
      /* name the wall and its key */
      for (i = 0; i < m->n_walls; ++i) {
        const char *sub = NULL;
        if (ball_plane_check(&m->walls[i], &sub) != BALL_OK) {
          snprintf(path, sizeof path, "walls[%d].%s", i, sub ? sub : "");
          break;
        }
      }
    }
    loc = find_location(L, path);
    if (loc && strcmp(loc->path, path) == 0) {
      /* the key that set the value: report it as written (time.fps, ...) */
      const char *hint = range_hint(loc->display);
      return fail_at(L, loc->line, loc->column, loc->display, "out of range: %s",
                     hint ? hint : ball_strerror(st));
    }
    {
      const char *hint = range_hint(path);
      char where[SCENE_PATH_SIZE + 40];
      if (loc && *loc->path) snprintf(where, sizeof where, "the default or set in \"%s\"", loc->display);
      else snprintf(where, sizeof where, "the default");
      return fail_at(L, loc ? loc->line : 0, loc ? loc->column : 0, path, "out of range (%s): %s", where,
                     hint ? hint : ball_strerror(st));
    }
  }
  return BALL_OK;
}

static ball_status load_parser(yaml_parser_t *parser, const char *name, ball_scene *scene,
                               ball_scene_error *err) {
  scene_loader *L;
  yaml_document_t doc;
  yaml_node_t *root;
  ball_status st = BALL_OK;

  L = (scene_loader *)calloc(1, sizeof *L);
  if (!L) {
    if (err) {
      memset(err, 0, sizeof *err);
      copy_string(err->file, sizeof err->file, name);
      copy_string(err->message, sizeof err->message, "out of memory");
    }
    return BALL_ENOMEM;
  }
  copy_string(L->err.file, sizeof L->err.file, name);
  ball_model_default(&L->scene.model);
  L->scene.duration = SCENE_DEFAULT_DURATION;
  L->scene.frame_time = SCENE_DEFAULT_FRAME_TIME;
  L->scene.time_base = 1.0;
  L->scene.render.markers = SCENE_DEFAULT_MARKERS;

  if (!yaml_parser_load(parser, &doc)) {
    const char *problem = parser->problem ? parser->problem : "cannot be parsed";
    if (parser->error == YAML_MEMORY_ERROR) {
      st = BALL_ENOMEM;
      fail_at(L, 0, 0, "", "out of memory");
    } else if (parser->error == YAML_READER_ERROR) {
      st = fail_at(L, 0, 0, "", "YAML syntax: %s (at byte %lu)", problem, (unsigned long)parser->problem_offset);
    } else if (parser->context) {
      st = fail_at(L, (int)parser->problem_mark.line + 1, (int)parser->problem_mark.column + 1, "",
                   "YAML syntax: %s %s (line %d)", problem, parser->context, (int)parser->context_mark.line + 1);
    } else {
      st = fail_at(L, (int)parser->problem_mark.line + 1, (int)parser->problem_mark.column + 1, "",
                   "YAML syntax: %s", problem);
    }
  } else {
    L->doc = &doc;
    root = yaml_document_get_root_node(&doc);
    if (!root) {
      st = fail_at(L, 1, 1, "", "the scene is empty (expected a mapping of keys)");
    } else {
      st = load_root(L, root);
    }
    if (st == BALL_OK) {
      /* A scene is one YAML document; a second one is a mistake. */
      yaml_document_t next;
      if (!yaml_parser_load(parser, &next)) {
        st = fail_at(L, (int)parser->problem_mark.line + 1, (int)parser->problem_mark.column + 1, "",
                     "YAML syntax: %s", parser->problem ? parser->problem : "cannot be parsed");
      } else {
        yaml_node_t *extra = yaml_document_get_root_node(&next);
        if (extra) st = fail(L, extra, "", "a scene file holds one YAML document; found a second one");
        yaml_document_delete(&next);
      }
    }
    yaml_document_delete(&doc);
  }

  if (st == BALL_OK) *scene = L->scene;
  if (err) {
    if (st == BALL_OK) memset(err, 0, sizeof *err);
    else *err = L->err;
  }
  free(L);
  return st;
}

ball_status ball_scene_load_string(const char *text, size_t length, const char *name, ball_scene *scene,
                                   ball_scene_error *err) {
  yaml_parser_t parser;
  ball_status st;
  if (!name) name = "<string>";
  if (!text || !scene) {
    if (err) {
      memset(err, 0, sizeof *err);
      copy_string(err->file, sizeof err->file, name);
      copy_string(err->message, sizeof err->message, "no text or no scene given");
    }
    return BALL_EINVAL;
  }
  if (!yaml_parser_initialize(&parser)) {
    if (err) {
      memset(err, 0, sizeof *err);
      copy_string(err->file, sizeof err->file, name);
      copy_string(err->message, sizeof err->message, "out of memory");
    }
    return BALL_ENOMEM;
  }
  yaml_parser_set_input_string(&parser, (const unsigned char *)text, length);
  st = load_parser(&parser, name, scene, err);
  yaml_parser_delete(&parser);
  return st;
}

ball_status ball_scene_load_file(const char *path, ball_scene *scene, ball_scene_error *err) {
  yaml_parser_t parser;
  FILE *f;
  ball_status st;
  if (!path || !scene) {
    if (err) {
      memset(err, 0, sizeof *err);
      copy_string(err->file, sizeof err->file, path ? path : "");
      copy_string(err->message, sizeof err->message, "no file name or no scene given");
    }
    return BALL_EINVAL;
  }
  f = fopen(path, "rb");
  if (!f) {
    if (err) {
      memset(err, 0, sizeof *err);
      copy_string(err->file, sizeof err->file, path);
      copy_string(err->message, sizeof err->message, strerror(errno));
    }
    return BALL_EIO;
  }
  if (!yaml_parser_initialize(&parser)) {
    fclose(f);
    if (err) {
      memset(err, 0, sizeof *err);
      copy_string(err->file, sizeof err->file, path);
      copy_string(err->message, sizeof err->message, "out of memory");
    }
    return BALL_ENOMEM;
  }
  yaml_parser_set_input_file(&parser, f);
  st = load_parser(&parser, path, scene, err);
  yaml_parser_delete(&parser);
  if (ferror(f) && st == BALL_OK) st = BALL_EIO;
  fclose(f);
  return st;
}

void ball_scene_default(ball_scene *scene) {
  if (!scene) return;
  memset(scene, 0, sizeof *scene);
  copy_string(scene->name, sizeof scene->name, "tennis");
  /* The default model is the tennis court with a serve that clears the net. */
  ball_model_default(&scene->model);
  scene->duration = 3.0;
  scene->frame_time = SCENE_DEFAULT_FRAME_TIME;
  scene->time_base = 1.0;
  scene->render.markers = SCENE_DEFAULT_MARKERS;
}

void ball_scene_error_format(const ball_scene_error *err, char *buf, size_t size) {
  if (!buf || size == 0) return;
  if (!err) {
    copy_string(buf, size, "");
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
