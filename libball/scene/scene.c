/* Scene files: YAML text -> ball_scene. libyaml does the parsing
 * (yaml_parser_load builds the node tree with line and column marks); this
 * file only walks the tree, converts scalars strictly and checks the result
 * with ball_model_check. The format is documented in docs/scenes.md. */
#include "ball/scene.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <yaml.h>

#define SCENE_MAX_LOCATIONS 512
#define SCENE_PATH_SIZE 96
#define SCENE_DEFAULT_DURATION 10.0

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

/* ---- mappings ------------------------------------------------------------ */

/* Checks that node is a mapping whose keys are distinct scalars, each one of
 * the allowed names (a NULL-terminated list). */
static ball_status check_mapping(scene_loader *L, const yaml_node_t *node, const char *path,
                                 const char *const *allowed) {
  yaml_node_pair_t *p, *q;
  if (node->type != YAML_MAPPING_NODE)
    return fail(L, node, path, "expected a mapping (key: value lines), got %s", node_kind(node));
  for (p = node->data.mapping.pairs.start; p < node->data.mapping.pairs.top; ++p) {
    yaml_node_t *key = yaml_document_get_node(L->doc, p->key);
    const char *const *a;
    char sub[SCENE_PATH_SIZE];
    if (key->type != YAML_SCALAR_NODE) return fail(L, key, path, "a key must be a plain name, got %s", node_kind(key));
    join(sub, path, scalar_text(key));
    for (a = allowed; *a; ++a)
      if (strcmp(*a, scalar_text(key)) == 0) break;
    if (!*a) return fail(L, key, sub, "unknown key \"%s\"", scalar_text(key));
    for (q = node->data.mapping.pairs.start; q < p; ++q) {
      yaml_node_t *prev = yaml_document_get_node(L->doc, q->key);
      if (strcmp(scalar_text(prev), scalar_text(key)) == 0)
        return fail(L, key, sub, "key given twice (first on line %d)", (int)prev->start_mark.line + 1);
    }
  }
  return BALL_OK;
}

static const char *pair_key(scene_loader *L, const yaml_node_pair_t *p) {
  return scalar_text(yaml_document_get_node(L->doc, p->key));
}

static yaml_node_t *pair_value(scene_loader *L, const yaml_node_pair_t *p) {
  return yaml_document_get_node(L->doc, p->value);
}

/* Reads one numeric key of a mapping into *dst, recording where it was set. */
static ball_status set_number(scene_loader *L, const yaml_node_t *value, const char *path, double *dst) {
  ball_status st = get_number(L, value, path, dst);
  if (st == BALL_OK) remember(L, path, NULL, value);
  return st;
}

/* ---- sections ------------------------------------------------------------ */

static ball_status load_floor(scene_loader *L, const yaml_node_t *node) {
  static const char *const keys[] = {"level", "damping", "bounce_threshold", "sound_threshold",
                                     "spin_damping", NULL};
  ball_model *m = &L->scene.model;
  yaml_node_pair_t *p;
  ball_status st;
  if ((st = check_mapping(L, node, "floor", keys)) != BALL_OK) return st;
  for (p = node->data.mapping.pairs.start; p < node->data.mapping.pairs.top; ++p) {
    const char *k = pair_key(L, p);
    yaml_node_t *v = pair_value(L, p);
    char path[SCENE_PATH_SIZE];
    double *dst = NULL;
    join(path, "floor", k);
    if (strcmp(k, "level") == 0) dst = &m->floor_level;
    else if (strcmp(k, "damping") == 0) dst = &m->floor_damping;
    else if (strcmp(k, "bounce_threshold") == 0) dst = &m->bounce_threshold;
    else if (strcmp(k, "sound_threshold") == 0) dst = &m->sound_threshold;
    else dst = &m->spin_floor_damping;
    if ((st = set_number(L, v, path, dst)) != BALL_OK) return st;
  }
  return BALL_OK;
}

/* A net or a wall: keys of ball_plane. *bottom_set tells whether "bottom"
 * was given (a wall without it stands on the floor). */
static ball_status load_plane(scene_loader *L, const yaml_node_t *node, const char *path, ball_plane *pl,
                              int require_all, int *bottom_set) {
  static const char *const keys[] = {"axis", "position", "lo", "hi", "bottom", "top", "damping", NULL};
  static const char *const required[] = {"axis", "position", "lo", "hi", "top", NULL};
  static const char *const axes[] = {"x", "z"};
  yaml_node_pair_t *p;
  ball_status st;
  const char *const *r;
  if ((st = check_mapping(L, node, path, keys)) != BALL_OK) return st;
  if (require_all) {
    for (r = required; *r; ++r) {
      int found = 0;
      for (p = node->data.mapping.pairs.start; p < node->data.mapping.pairs.top; ++p)
        if (strcmp(pair_key(L, p), *r) == 0) found = 1;
      if (!found) {
        char sub[SCENE_PATH_SIZE];
        join(sub, path, *r);
        return fail(L, node, sub, "missing required key \"%s\"", *r);
      }
    }
  }
  *bottom_set = 0;
  for (p = node->data.mapping.pairs.start; p < node->data.mapping.pairs.top; ++p) {
    const char *k = pair_key(L, p);
    yaml_node_t *v = pair_value(L, p);
    char sub[SCENE_PATH_SIZE];
    join(sub, path, k);
    if (strcmp(k, "axis") == 0) {
      if (v->type == YAML_SCALAR_NODE && strcmp(scalar_text(v), axes[0]) == 0) pl->axis = 0;
      else if (v->type == YAML_SCALAR_NODE && strcmp(scalar_text(v), axes[1]) == 0) pl->axis = 2;
      else if (v->type == YAML_SCALAR_NODE) return fail(L, v, sub, "expected x or z, got \"%s\"", scalar_text(v));
      else return fail(L, v, sub, "expected x or z, got %s", node_kind(v));
      remember(L, sub, NULL, v);
      continue;
    }
    if (strcmp(k, "position") == 0) st = set_number(L, v, sub, &pl->position);
    else if (strcmp(k, "lo") == 0) st = set_number(L, v, sub, &pl->lo);
    else if (strcmp(k, "hi") == 0) st = set_number(L, v, sub, &pl->hi);
    else if (strcmp(k, "top") == 0) st = set_number(L, v, sub, &pl->top);
    else if (strcmp(k, "damping") == 0) st = set_number(L, v, sub, &pl->damping);
    else {
      st = set_number(L, v, sub, &pl->bottom);
      *bottom_set = 1;
    }
    if (st != BALL_OK) return st;
  }
  return BALL_OK;
}

static ball_status load_net(scene_loader *L, const yaml_node_t *node) {
  int bottom_set;
  ball_status st;
  if (node->type == YAML_SCALAR_NODE && strcmp(scalar_text(node), "none") == 0) {
    L->scene.model.has_net = 0;
    return BALL_OK;
  }
  if (node->type == YAML_SCALAR_NODE)
    return fail(L, node, "net", "expected a mapping or none, got \"%s\"", scalar_text(node));
  if ((st = load_plane(L, node, "net", &L->scene.model.net, 0, &bottom_set)) != BALL_OK) return st;
  L->scene.model.has_net = 1;
  return BALL_OK;
}

static ball_status load_walls(scene_loader *L, const yaml_node_t *node, double default_damping) {
  ball_model *m = &L->scene.model;
  int i, n;
  ball_status st;
  if (node->type != YAML_SEQUENCE_NODE) return fail(L, node, "walls", "expected a list of walls, got %s", node_kind(node));
  n = (int)(node->data.sequence.items.top - node->data.sequence.items.start);
  if (n > BALL_MAX_WALLS) return fail(L, node, "walls", "%d walls given, at most %d allowed", n, BALL_MAX_WALLS);
  for (i = 0; i < n; ++i) {
    yaml_node_t *item = yaml_document_get_node(L->doc, node->data.sequence.items.start[i]);
    char path[SCENE_PATH_SIZE];
    ball_plane *w = &m->walls[i];
    snprintf(path, sizeof path, "walls[%d]", i);
    remember(L, path, NULL, item);
    memset(w, 0, sizeof *w);
    w->damping = default_damping;
    if ((st = load_plane(L, item, path, w, 1, &L->wall_bottom_set[i])) != BALL_OK) return st;
  }
  m->n_walls = n;
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

/* Whether mapping node has key. */
static int has_key(scene_loader *L, const yaml_node_t *node, const char *key) {
  yaml_node_pair_t *p;
  for (p = node->data.mapping.pairs.start; p < node->data.mapping.pairs.top; ++p)
    if (strcmp(pair_key(L, p), key) == 0) return 1;
  return 0;
}

/* Fails on the first of the required keys (NULL-terminated) node lacks. */
static ball_status require_keys(scene_loader *L, const yaml_node_t *node, const char *path,
                                const char *const *required) {
  for (; *required; ++required) {
    if (!has_key(L, node, *required)) {
      char sub[SCENE_PATH_SIZE];
      join(sub, path, *required);
      return fail(L, node, sub, "missing required key \"%s\"", *required);
    }
  }
  return BALL_OK;
}

static ball_status load_keyframes(scene_loader *L, const yaml_node_t *node, const char *path,
                                  ball_racket_script *s) {
  static const char *const keys[] = {"t", "center", "normal", NULL};
  int i, n;
  ball_status st;
  if (node->type != YAML_SEQUENCE_NODE)
    return fail(L, node, path, "expected a list of keyframes {t, center, normal}, got %s", node_kind(node));
  n = (int)(node->data.sequence.items.top - node->data.sequence.items.start);
  if (n < 1) return fail(L, node, path, "expected at least one keyframe");
  if (n > BALL_SCRIPT_MAX_KEYFRAMES)
    return fail(L, node, path, "%d keyframes given, at most %d allowed", n, BALL_SCRIPT_MAX_KEYFRAMES);
  for (i = 0; i < n; ++i) {
    yaml_node_t *item = yaml_document_get_node(L->doc, node->data.sequence.items.start[i]);
    ball_script_keyframe *k = &s->keyframes[i];
    yaml_node_pair_t *p;
    char kpath[SCENE_PATH_SIZE];
    snprintf(kpath, sizeof kpath, "%.80s[%d]", path, i);
    if ((st = check_mapping(L, item, kpath, keys)) != BALL_OK) return st;
    if ((st = require_keys(L, item, kpath, keys)) != BALL_OK) return st;
    for (p = item->data.mapping.pairs.start; p < item->data.mapping.pairs.top; ++p) {
      const char *key = pair_key(L, p);
      yaml_node_t *v = pair_value(L, p);
      char sub[SCENE_PATH_SIZE];
      join(sub, kpath, key);
      if (strcmp(key, "t") == 0) {
        if ((st = get_number(L, v, sub, &k->t)) != BALL_OK) return st;
        if (i > 0 && !(k->t > s->keyframes[i - 1].t))
          return fail(L, v, sub, "out of range: keyframe times must increase strictly, got %s after %.17g",
                      scalar_text(v), s->keyframes[i - 1].t);
      } else if (strcmp(key, "center") == 0) {
        if ((st = get_vec3(L, v, sub, &k->center)) != BALL_OK) return st;
      } else {
        ball_vec3 u;
        double big, w;
        if ((st = get_vec3(L, v, sub, &u)) != BALL_OK) return st;
        /* normalise without overflow: scale by the largest component first */
        big = fmax(fabs(u.x), fmax(fabs(u.y), fabs(u.z)));
        if (big > 0.0) {
          u.x /= big;
          u.y /= big;
          u.z /= big;
        }
        w = sqrt(u.x * u.x + u.y * u.y + u.z * u.z);
        if (!(big * w >= 1e-9)) return fail(L, v, sub, "out of range: a normal must not be (nearly) zero");
        k->normal.x = u.x / w;
        k->normal.y = u.y / w;
        k->normal.z = u.z / w;
      }
    }
  }
  s->n_keyframes = n;
  return BALL_OK;
}

/* rackets[i].script: keyframes and network conditions (docs/scenes.md). */
static ball_status load_script(scene_loader *L, const yaml_node_t *node, const char *path, ball_racket_script *s) {
  static const char *const keys[] = {"keyframes", "repeat", "rate", "delay", "jitter", "loss", "duplicate",
                                     "noise", "normal_noise", "seed", NULL};
  static const char *const required[] = {"keyframes", NULL};
  const yaml_node_t *repeat_node = NULL;
  yaml_node_pair_t *p;
  ball_status st;
  const char *field = NULL;
  ball_script_default(s);
  if ((st = check_mapping(L, node, path, keys)) != BALL_OK) return st;
  if ((st = require_keys(L, node, path, required)) != BALL_OK) return st;
  for (p = node->data.mapping.pairs.start; p < node->data.mapping.pairs.top; ++p) {
    const char *k = pair_key(L, p);
    yaml_node_t *v = pair_value(L, p);
    char sub[SCENE_PATH_SIZE];
    join(sub, path, k);
    if (strcmp(k, "keyframes") == 0) st = load_keyframes(L, v, sub, s);
    else if (strcmp(k, "repeat") == 0) {
      st = get_ranged(L, v, sub, 0.0, HUGE_VAL, 0, ">= 0 (0: no repeat)", &s->repeat);
      repeat_node = v;
    } else if (strcmp(k, "rate") == 0) st = get_ranged(L, v, sub, 2.0, 120.0, 0, "in [2, 120] Hz", &s->rate);
    else if (strcmp(k, "delay") == 0) st = get_ranged(L, v, sub, 0.0, 60.0, 0, "in [0, 60] s", &s->delay);
    else if (strcmp(k, "jitter") == 0) st = get_ranged(L, v, sub, 0.0, 0.5, 0, "in [0, 0.5] s", &s->jitter);
    else if (strcmp(k, "loss") == 0) st = get_ranged(L, v, sub, 0.0, 1.0, 1, "in [0, 1)", &s->loss);
    else if (strcmp(k, "duplicate") == 0) st = get_ranged(L, v, sub, 0.0, 1.0, 0, "in [0, 1]", &s->duplicate);
    else if (strcmp(k, "noise") == 0) st = get_ranged(L, v, sub, 0.0, HUGE_VAL, 0, ">= 0 m", &s->noise);
    else if (strcmp(k, "normal_noise") == 0)
      st = get_ranged(L, v, sub, 0.0, 1.0, 0, "in [0, 1] rad", &s->normal_noise);
    else st = get_uint64(L, v, sub, &s->seed);
    if (st != BALL_OK) return st;
  }
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

static ball_status load_rackets(scene_loader *L, const yaml_node_t *node, const ball_model *defaults) {
  static const char *const keys[] = {"radius", "partner", "target", "script", NULL};
  ball_model *m = &L->scene.model;
  int i, n;
  ball_status st;
  if (node->type != YAML_SEQUENCE_NODE) return fail(L, node, "rackets", "expected a list of rackets, got %s", node_kind(node));
  n = (int)(node->data.sequence.items.top - node->data.sequence.items.start);
  if (n > BALL_MAX_RACKETS) return fail(L, node, "rackets", "%d rackets given, at most %d allowed", n, BALL_MAX_RACKETS);
  for (i = 0; i < n; ++i) {
    yaml_node_t *item = yaml_document_get_node(L->doc, node->data.sequence.items.start[i]);
    ball_racket_def *r = &m->rackets[i];
    yaml_node_pair_t *p;
    char path[SCENE_PATH_SIZE];
    snprintf(path, sizeof path, "rackets[%d]", i);
    remember(L, path, NULL, item);
    *r = defaults->rackets[i];
    if ((st = check_mapping(L, item, path, keys)) != BALL_OK) return st;
    for (p = item->data.mapping.pairs.start; p < item->data.mapping.pairs.top; ++p) {
      const char *k = pair_key(L, p);
      yaml_node_t *v = pair_value(L, p);
      char sub[SCENE_PATH_SIZE];
      join(sub, path, k);
      if (strcmp(k, "radius") == 0) st = set_number(L, v, sub, &r->radius);
      else if (strcmp(k, "partner") == 0) st = get_int(L, v, sub, &r->partner);
      else if (strcmp(k, "script") == 0) st = load_script(L, v, sub, &L->scene.scripts[i]);
      else st = get_vec3(L, v, sub, &r->target);
      if (st != BALL_OK) return st;
      remember(L, sub, NULL, v);
    }
  }
  m->n_rackets = n;
  return BALL_OK;
}

static ball_status load_racket(scene_loader *L, const yaml_node_t *node) {
  static const char *const keys[] = {"detect", "normal", "response", "collision_distance", "sleep_frames",
                                     "v_min", "v_max", "v_up", "v_up_from_racket", "friendly_factor",
                                     "spin_rack_damping", "history", "extrapolation_time", "stale_time",
                                     NULL};
  ball_model *m = &L->scene.model;
  yaml_node_pair_t *p;
  ball_status st;
  if ((st = check_mapping(L, node, "racket", keys)) != BALL_OK) return st;
  for (p = node->data.mapping.pairs.start; p < node->data.mapping.pairs.top; ++p) {
    const char *k = pair_key(L, p);
    yaml_node_t *v = pair_value(L, p);
    char path[SCENE_PATH_SIZE];
    int e;
    join(path, "racket", k);
    if (strcmp(k, "detect") == 0) {
      if ((st = get_enum(L, v, path, detect_name, BALL_DETECT_COUNT, &e)) == BALL_OK) m->detect = (ball_detect)e;
    } else if (strcmp(k, "normal") == 0) {
      if ((st = get_enum(L, v, path, normal_name, BALL_NORMAL_COUNT, &e)) == BALL_OK) m->normal_mode = (ball_normal_mode)e;
    } else if (strcmp(k, "response") == 0) {
      if ((st = get_enum(L, v, path, response_name, BALL_RESPONSE_COUNT, &e)) == BALL_OK) m->response = (ball_response)e;
    } else if (strcmp(k, "sleep_frames") == 0) {
      st = get_int(L, v, path, &m->sleep_frames);
    } else if (strcmp(k, "history") == 0) {
      st = get_int(L, v, path, &m->history);
    } else if (strcmp(k, "v_up_from_racket") == 0) {
      st = get_bool(L, v, path, &m->v_up_from_racket);
    } else {
      double *dst;
      if (strcmp(k, "collision_distance") == 0) dst = &m->collision_distance;
      else if (strcmp(k, "v_min") == 0) dst = &m->v_min;
      else if (strcmp(k, "v_max") == 0) dst = &m->v_max;
      else if (strcmp(k, "v_up") == 0) dst = &m->v_up;
      else if (strcmp(k, "friendly_factor") == 0) dst = &m->friendly_factor;
      else if (strcmp(k, "spin_rack_damping") == 0) dst = &m->spin_rack_damping;
      else if (strcmp(k, "extrapolation_time") == 0) dst = &m->extrapolation_time;
      else dst = &m->stale_time;
      st = get_number(L, v, path, dst);
    }
    if (st != BALL_OK) return st;
    remember(L, path, NULL, v);
  }
  return BALL_OK;
}

static ball_status load_time(scene_loader *L, const yaml_node_t *node) {
  static const char *const keys[] = {"frame_time", "fps", "time_base", NULL};
  ball_model *m = &L->scene.model;
  yaml_node_pair_t *p;
  ball_status st;
  const yaml_node_t *frame_node = NULL;
  if ((st = check_mapping(L, node, "time", keys)) != BALL_OK) return st;
  for (p = node->data.mapping.pairs.start; p < node->data.mapping.pairs.top; ++p) {
    const char *k = pair_key(L, p);
    yaml_node_t *v = pair_value(L, p);
    if (strcmp(k, "time_base") == 0) {
      if ((st = set_number(L, v, "time.time_base", &m->time_base)) != BALL_OK) return st;
    } else if (frame_node) {
      return fail(L, yaml_document_get_node(L->doc, p->key), "time", "give frame_time or fps, not both");
    } else if (strcmp(k, "frame_time") == 0) {
      frame_node = v;
      if ((st = set_number(L, v, "time.frame_time", &m->frame_time)) != BALL_OK) return st;
    } else {
      double fps;
      frame_node = v;
      if ((st = get_number(L, v, "time.fps", &fps)) != BALL_OK) return st;
      if (!(fps > 0.0)) return fail(L, v, "time.fps", "must be > 0, got %s", scalar_text(v));
      m->frame_time = 1.0 / fps;
      remember(L, "time.frame_time", "time.fps", v);
    }
  }
  return BALL_OK;
}

static ball_status load_effects(scene_loader *L, const yaml_node_t *node) {
  unsigned mask = 0;
  int i, n;
  if (node->type != YAML_SEQUENCE_NODE)
    return fail(L, node, "effects", "expected a list of effect names, got %s", node_kind(node));
  n = (int)(node->data.sequence.items.top - node->data.sequence.items.start);
  for (i = 0; i < n; ++i) {
    yaml_node_t *item = yaml_document_get_node(L->doc, node->data.sequence.items.start[i]);
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

static ball_status load_ball(scene_loader *L, const yaml_node_t *node) {
  static const char *const keys[] = {"position", "velocity", "spin", NULL};
  ball_model *m = &L->scene.model;
  yaml_node_pair_t *p;
  ball_status st;
  if ((st = check_mapping(L, node, "ball", keys)) != BALL_OK) return st;
  for (p = node->data.mapping.pairs.start; p < node->data.mapping.pairs.top; ++p) {
    const char *k = pair_key(L, p);
    yaml_node_t *v = pair_value(L, p);
    char path[SCENE_PATH_SIZE];
    ball_vec3 *dst = strcmp(k, "position") == 0   ? &m->initial_position
                     : strcmp(k, "velocity") == 0 ? &m->initial_velocity
                                                  : &m->initial_spin;
    join(path, "ball", k);
    if ((st = get_vec3(L, v, path, dst)) != BALL_OK) return st;
    remember(L, path, NULL, v);
  }
  return BALL_OK;
}

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
    {"frame_time", "time.frame_time"},
    {"time_base", "time.time_base"},
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
    {"time.frame_time", "must be > 0"},
    {"time.fps", "must be > 0 (and 1 / fps finite)"},
    {"time.time_base", "must be > 0"},
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

static ball_status load_root(scene_loader *L, const yaml_node_t *root) {
  static const char *const keys[] = {"name", "duration", "gravity", "mass", "air_friction", "radius",
                                     "spin_damping", "floor", "net", "walls", "rackets", "racket",
                                     "level", "time", "effects", "scheme", "ball", NULL};
  ball_model defaults;
  ball_model *m = &L->scene.model;
  yaml_node_pair_t *p;
  ball_status st;
  const char *field = NULL;
  int i;

  ball_model_default(&defaults);
  if (root->type == YAML_SCALAR_NODE && root->data.scalar.length == 0)
    return fail(L, root, "", "the scene is empty (expected a mapping of keys)");
  if ((st = check_mapping(L, root, "", keys)) != BALL_OK) return st;
  remember(L, "", NULL, root);

  /* The level preset goes first, whatever its place in the file, so every
   * racket key can override it. */
  for (p = root->data.mapping.pairs.start; p < root->data.mapping.pairs.top; ++p) {
    if (strcmp(pair_key(L, p), "level") == 0) {
      yaml_node_t *v = pair_value(L, p);
      int level;
      if ((st = get_enum(L, v, "level", level_name, BALL_LEVEL_COUNT, &level)) != BALL_OK) return st;
      if (ball_model_set_level(m, (ball_level)level) != BALL_OK)
        return fail(L, v, "level", "the library rejected level \"%s\"", scalar_text(v));
      remember(L, "level", NULL, v);
    }
  }

  for (p = root->data.mapping.pairs.start; p < root->data.mapping.pairs.top; ++p) {
    const char *k = pair_key(L, p);
    yaml_node_t *v = pair_value(L, p);
    if (strcmp(k, "level") == 0) continue;
    if (strcmp(k, "name") == 0) {
      if (v->type != YAML_SCALAR_NODE) return fail(L, v, "name", "expected a string, got %s", node_kind(v));
      if (v->data.scalar.length >= sizeof L->scene.name)
        return fail(L, v, "name", "longer than %d characters", (int)sizeof L->scene.name - 1);
      copy_string(L->scene.name, sizeof L->scene.name, scalar_text(v));
      continue;
    }
    if (strcmp(k, "duration") == 0) {
      if ((st = get_number(L, v, "duration", &L->scene.duration)) != BALL_OK) return st;
      if (!(L->scene.duration > 0.0)) return fail(L, v, "duration", "must be > 0, got %s", scalar_text(v));
      continue;
    }
    if (strcmp(k, "gravity") == 0) st = set_number(L, v, k, &m->gravity);
    else if (strcmp(k, "mass") == 0) st = set_number(L, v, k, &m->mass);
    else if (strcmp(k, "air_friction") == 0) st = set_number(L, v, k, &m->air_friction);
    else if (strcmp(k, "radius") == 0) st = set_number(L, v, k, &m->radius);
    else if (strcmp(k, "spin_damping") == 0) st = set_number(L, v, k, &m->spin_damping);
    else if (strcmp(k, "floor") == 0) st = load_floor(L, v);
    else if (strcmp(k, "net") == 0) st = load_net(L, v);
    else if (strcmp(k, "walls") == 0) st = load_walls(L, v, defaults.net.damping);
    else if (strcmp(k, "rackets") == 0) st = load_rackets(L, v, &defaults);
    else if (strcmp(k, "racket") == 0) st = load_racket(L, v);
    else if (strcmp(k, "time") == 0) st = load_time(L, v);
    else if (strcmp(k, "effects") == 0) st = load_effects(L, v);
    else if (strcmp(k, "ball") == 0) st = load_ball(L, v);
    else {
      int e;
      st = get_enum(L, v, "scheme", scheme_name, BALL_SCHEME_COUNT, &e);
      if (st == BALL_OK) m->scheme = (ball_scheme)e;
    }
    if (st != BALL_OK) return st;
    if (v->type != YAML_SCALAR_NODE) remember(L, k, NULL, v);
  }

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
