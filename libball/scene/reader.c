/* The YAML reader of libball::scene (reader.h). libyaml does the parsing
 * (yaml_parser_load builds the node tree with line and column marks); this
 * file only walks the tree, converts scalars strictly, reads table-driven
 * sections and enforces the limits. The scene format is in format.c. */
#include "reader.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* ---- errors and locations ----------------------------------------------- */

void scene_copy_string(char *dst, size_t size, const char *src) {
  size_t n;
  if (size == 0) return;
  if (!src) src = "";
  n = strlen(src);
  if (n >= size) n = size - 1;
  memcpy(dst, src, n);
  dst[n] = '\0';
}

static ball_status fail_va(scene_loader *L, int line, int column, const char *path, const char *fmt,
                           va_list ap) {
  L->err.line = line;
  L->err.column = column;
  scene_copy_string(L->err.field, sizeof L->err.field, path);
  vsnprintf(L->err.message, sizeof L->err.message, fmt, ap);
  return BALL_EPARSE;
}

ball_status scene_fail_at(scene_loader *L, int line, int column, const char *path, const char *fmt, ...) {
  va_list ap;
  ball_status st;
  va_start(ap, fmt);
  st = fail_va(L, line, column, path, fmt, ap);
  va_end(ap);
  return st;
}

ball_status scene_fail(scene_loader *L, const yaml_node_t *node, const char *path, const char *fmt, ...) {
  va_list ap;
  ball_status st;
  va_start(ap, fmt);
  st = fail_va(L, node ? (int)node->start_mark.line + 1 : 0, node ? (int)node->start_mark.column + 1 : 0, path,
               fmt, ap);
  va_end(ap);
  return st;
}

void scene_remember(scene_loader *L, const char *path, const char *display, const yaml_node_t *node) {
  scene_location *loc;
  if (L->n_locations >= SCENE_MAX_LOCATIONS || !node) return;
  loc = &L->locations[L->n_locations++];
  scene_copy_string(loc->path, sizeof loc->path, path);
  scene_copy_string(loc->display, sizeof loc->display, display ? display : path);
  loc->line = (int)node->start_mark.line + 1;
  loc->column = (int)node->start_mark.column + 1;
}

static int prefix_of(const char *prefix, const char *s) {
  size_t n = strlen(prefix);
  return strncmp(prefix, s, n) == 0 && (s[n] == '\0' || s[n] == '.' || s[n] == '[');
}

const scene_location *scene_find_location(const scene_loader *L, const char *path) {
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

void scene_join(char *dst, const char *path, const char *key) {
  size_t n;
  scene_copy_string(dst, SCENE_PATH_SIZE, path);
  n = strlen(dst);
  if (*path && n + 1 < SCENE_PATH_SIZE) dst[n++] = '.';
  scene_copy_string(dst + n, SCENE_PATH_SIZE - n, key);
}

/* ---- scalars ------------------------------------------------------------ */

const char *scene_text(const yaml_node_t *node) { return (const char *)node->data.scalar.value; }

const char *scene_node_kind(const yaml_node_t *node) {
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

/* Decimal only: strtod also reads hexadecimal ("0x1p3") and the words inf
 * and nan, which a scene does not take (docs/scenes.md). */
static int decimal_number_text(const char *t) {
  if (*t == '+' || *t == '-') ++t;
  if (t[0] == '0' && (t[1] == 'x' || t[1] == 'X')) return 0;
  return (*t >= '0' && *t <= '9') || *t == '.';
}

/* A number: a plain decimal scalar that strtod consumes entirely, finite. */
ball_status scene_get_number(scene_loader *L, const yaml_node_t *node, const char *path, double *out) {
  const char *text;
  char *end;
  double v;
  if (node->type != YAML_SCALAR_NODE)
    return scene_fail(L, node, path, "expected a number, got %s", scene_node_kind(node));
  text = scene_text(node);
  if (!is_plain_scalar(node)) return scene_fail(L, node, path, "expected a number, got the string \"%s\"", text);
  if (node->data.scalar.length == 0) return scene_fail(L, node, path, "expected a number, got nothing");
  {
    const char *t = (*text == '+' || *text == '-') ? text + 1 : text;
    if (ascii_casecmp(t, ".inf") == 0 || ascii_casecmp(t, ".nan") == 0)
      return scene_fail(L, node, path, "expected a finite number, got %s", text);
  }
  if (!decimal_number_text(text))
    return scene_fail(L, node, path, "expected a decimal number, got \"%s\"", text);
  errno = 0;
  v = strtod(text, &end);
  if (end == text || *end != '\0' || (size_t)(end - text) != node->data.scalar.length)
    return scene_fail(L, node, path, "expected a number, got \"%s\"", text);
  if (!isfinite(v) || (errno == ERANGE && fabs(v) > 1.0))
    return scene_fail(L, node, path, "expected a finite number, got %s", text);
  *out = v;
  return BALL_OK;
}

ball_status scene_get_int(scene_loader *L, const yaml_node_t *node, const char *path, int *out) {
  const char *text;
  char *end;
  long v;
  if (node->type != YAML_SCALAR_NODE)
    return scene_fail(L, node, path, "expected an integer, got %s", scene_node_kind(node));
  text = scene_text(node);
  if (!is_plain_scalar(node)) return scene_fail(L, node, path, "expected an integer, got the string \"%s\"", text);
  errno = 0;
  v = strtol(text, &end, 10);
  if (node->data.scalar.length == 0 || end == text || *end != '\0' ||
      (size_t)(end - text) != node->data.scalar.length)
    return scene_fail(L, node, path, "expected an integer, got \"%s\"", text);
  if (errno == ERANGE || v < INT_MIN || v > INT_MAX) return scene_fail(L, node, path, "integer %s is out of range", text);
  *out = (int)v;
  return BALL_OK;
}

ball_status scene_get_bool(scene_loader *L, const yaml_node_t *node, const char *path, int *out) {
  if (is_plain_scalar(node)) {
    if (strcmp(scene_text(node), "true") == 0) {
      *out = 1;
      return BALL_OK;
    }
    if (strcmp(scene_text(node), "false") == 0) {
      *out = 0;
      return BALL_OK;
    }
  }
  if (node->type != YAML_SCALAR_NODE)
    return scene_fail(L, node, path, "expected true or false, got %s", scene_node_kind(node));
  return scene_fail(L, node, path, "expected true or false, got \"%s\"", scene_text(node));
}

/* A list of three numbers. */
ball_status scene_get_vec3(scene_loader *L, const yaml_node_t *node, const char *path, ball_vec3 *out) {
  double c[3];
  int i, n;
  ball_status st;
  char sub[SCENE_PATH_SIZE];
  if (node->type != YAML_SEQUENCE_NODE)
    return scene_fail(L, node, path, "expected a list of 3 numbers [x, y, z], got %s", scene_node_kind(node));
  n = (int)(node->data.sequence.items.top - node->data.sequence.items.start);
  if (n != 3)
    return scene_fail(L, node, path, "expected a list of 3 numbers [x, y, z], got %d item%s", n, n == 1 ? "" : "s");
  for (i = 0; i < 3; ++i) {
    yaml_node_t *item = yaml_document_get_node(L->doc, node->data.sequence.items.start[i]);
    snprintf(sub, sizeof sub, "%.80s[%d]", path, i);
    if ((st = scene_get_number(L, item, sub, &c[i])) != BALL_OK) return st;
  }
  out->x = c[0];
  out->y = c[1];
  out->z = c[2];
  return BALL_OK;
}

/* An unsigned 64-bit integer (a seed): plain decimal digits, in range. */
ball_status scene_get_uint64(scene_loader *L, const yaml_node_t *node, const char *path, uint64_t *out) {
  const char *text, *c;
  char *end;
  unsigned long long v;
  if (node->type != YAML_SCALAR_NODE)
    return scene_fail(L, node, path, "expected an integer, got %s", scene_node_kind(node));
  text = scene_text(node);
  if (!is_plain_scalar(node)) return scene_fail(L, node, path, "expected an integer, got the string \"%s\"", text);
  if (node->data.scalar.length == 0) return scene_fail(L, node, path, "expected an integer, got nothing");
  for (c = text; *c; ++c)
    if (*c < '0' || *c > '9')
      return scene_fail(L, node, path, "expected an integer in [0, 18446744073709551615], got \"%s\"", text);
  errno = 0;
  v = strtoull(text, &end, 10);
  if (errno == ERANGE || *end != '\0' || v > (unsigned long long)UINT64_MAX)
    return scene_fail(L, node, path, "integer %s is out of range [0, 18446744073709551615]", text);
  *out = (uint64_t)v;
  return BALL_OK;
}

/* A number in [lo, hi] (open ends per `open`); read and checked where it stands. */
static ball_status get_ranged(scene_loader *L, const yaml_node_t *node, const char *path, const key_spec *spec,
                              double *out) {
  double v;
  ball_status st = scene_get_number(L, node, path, &v);
  if (st != BALL_OK) return st;
  if ((spec->open & BALL_FIELD_LO_OPEN ? !(v > spec->lo) : !(v >= spec->lo)) ||
      (spec->open & BALL_FIELD_HI_OPEN ? !(v < spec->hi) : !(v <= spec->hi)))
    return scene_fail(L, node, path, "out of range: must be %s, got %s", spec->range, scene_text(node));
  *out = v;
  return BALL_OK;
}

ball_status scene_get_enum(scene_loader *L, const yaml_node_t *node, const char *path, scene_name_fn names,
                           int count, int *out) {
  char choices[160];
  size_t used = 0;
  int i;
  if (node->type == YAML_SCALAR_NODE) {
    for (i = 0; i < count; ++i) {
      if (strcmp(scene_text(node), names(i)) == 0) {
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
  if (node->type != YAML_SCALAR_NODE)
    return scene_fail(L, node, path, "expected one of %s, got %s", choices, scene_node_kind(node));
  return scene_fail(L, node, path, "expected one of %s, got \"%s\"", choices, scene_text(node));
}

ball_status scene_get_list(scene_loader *L, const yaml_node_t *node, const char *path, const char *what, int max,
                           int *n) {
  if (node->type != YAML_SEQUENCE_NODE)
    return scene_fail(L, node, path, "expected a list of %s, got %s", what, scene_node_kind(node));
  *n = (int)(node->data.sequence.items.top - node->data.sequence.items.start);
  if (*n > max) return scene_fail(L, node, path, "%d %s given, at most %d allowed", *n, what, max);
  return BALL_OK;
}

yaml_node_t *scene_list_item(scene_loader *L, const yaml_node_t *node, int i) {
  return yaml_document_get_node(L->doc, node->data.sequence.items.start[i]);
}

static const char *pair_key(scene_loader *L, const yaml_node_pair_t *p) {
  return scene_text(yaml_document_get_node(L->doc, p->key));
}

yaml_node_t *scene_key_value(scene_loader *L, const yaml_node_t *node, const char *key) {
  yaml_node_pair_t *p;
  for (p = node->data.mapping.pairs.start; p < node->data.mapping.pairs.top; ++p)
    if (strcmp(pair_key(L, p), key) == 0) return yaml_document_get_node(L->doc, p->value);
  return NULL;
}

/* ---- sections ------------------------------------------------------------ */

static const key_spec *find_key(const key_spec *keys, const char *name) {
  for (; keys->name; ++keys)
    if (strcmp(keys->name, name) == 0) return keys;
  return NULL;
}

ball_status scene_check_section(scene_loader *L, const yaml_node_t *node, const char *path, const section *sec) {
  yaml_node_pair_t *p, *q;
  const key_spec *r;
  if (node->type != YAML_MAPPING_NODE)
    return scene_fail(L, node, path, "expected a mapping (key: value lines), got %s", scene_node_kind(node));
  for (p = node->data.mapping.pairs.start; p < node->data.mapping.pairs.top; ++p) {
    yaml_node_t *key = yaml_document_get_node(L->doc, p->key);
    char sub[SCENE_PATH_SIZE];
    if (key->type != YAML_SCALAR_NODE)
      return scene_fail(L, key, path, "a key must be a plain name, got %s", scene_node_kind(key));
    scene_join(sub, path, scene_text(key));
    if (!find_key(sec->keys, scene_text(key))) return scene_fail(L, key, sub, "unknown key \"%s\"", scene_text(key));
    for (q = node->data.mapping.pairs.start; q < p; ++q) {
      yaml_node_t *prev = yaml_document_get_node(L->doc, q->key);
      if (strcmp(scene_text(prev), scene_text(key)) == 0)
        return scene_fail(L, key, sub, "key given twice (first on line %d)", (int)prev->start_mark.line + 1);
    }
  }
  for (r = sec->keys; sec->require && r->name; ++r) {
    if (r->required && !scene_key_value(L, node, r->name)) {
      char sub[SCENE_PATH_SIZE];
      scene_join(sub, path, r->name);
      return scene_fail(L, node, sub, "missing required key \"%s\"", r->name);
    }
  }
  return BALL_OK;
}

/* Reads value into base's field that spec names. */
static ball_status read_key(scene_loader *L, const key_spec *spec, const yaml_node_t *value, const char *path,
                            void *base) {
  void *field = (char *)base + spec->offset;
  switch (spec->kind) {
    case KEY_NUMBER: return scene_get_number(L, value, path, (double *)field);
    case KEY_INT: return scene_get_int(L, value, path, (int *)field);
    case KEY_BOOL: return scene_get_bool(L, value, path, (int *)field);
    case KEY_VEC3: return scene_get_vec3(L, value, path, (ball_vec3 *)field);
    case KEY_UINT64: return scene_get_uint64(L, value, path, (uint64_t *)field);
    case KEY_RANGED: return get_ranged(L, value, path, spec, (double *)field);
    case KEY_ENUM: return scene_get_enum(L, value, path, spec->names, spec->count, (int *)field);
    case KEY_SPECIAL: break;
  }
  return BALL_EINVAL; /* not reached: KEY_SPECIAL keys go to the hook */
}

ball_status scene_read_section(scene_loader *L, const yaml_node_t *node, const char *path, const section *sec,
                               void *base, void *ctx) {
  yaml_node_pair_t *p;
  for (p = node->data.mapping.pairs.start; p < node->data.mapping.pairs.top; ++p) {
    yaml_node_t *key = yaml_document_get_node(L->doc, p->key);
    yaml_node_t *value = yaml_document_get_node(L->doc, p->value);
    const key_spec *spec = find_key(sec->keys, scene_text(key));
    char sub[SCENE_PATH_SIZE];
    ball_status st;
    scene_join(sub, path, scene_text(key));
    if (spec->kind == KEY_SPECIAL) {
      st = sec->hook(L, key, value, sub, base, ctx);
    } else {
      st = read_key(L, spec, value, sub, base);
      if (st == BALL_OK && sec->record) scene_remember(L, sub, NULL, value);
    }
    if (st != BALL_OK) return st;
  }
  return BALL_OK;
}

ball_status scene_load_section(scene_loader *L, const yaml_node_t *node, const char *path, const section *sec,
                               void *base, void *ctx) {
  ball_status st = scene_check_section(L, node, path, sec);
  return st != BALL_OK ? st : scene_read_section(L, node, path, sec, base, ctx);
}

/* ---- documents ------------------------------------------------------------ */

static ball_status syntax_error(scene_loader *L, const yaml_parser_t *parser) {
  const char *problem = parser->problem ? parser->problem : "cannot be parsed";
  if (parser->error == YAML_MEMORY_ERROR) {
    scene_fail_at(L, 0, 0, "", "out of memory");
    return BALL_ENOMEM;
  }
  if (parser->error == YAML_READER_ERROR)
    return scene_fail_at(L, 0, 0, "", "YAML syntax: %s (at byte %lu)", problem, (unsigned long)parser->problem_offset);
  if (parser->context)
    return scene_fail_at(L, (int)parser->problem_mark.line + 1, (int)parser->problem_mark.column + 1, "",
                         "YAML syntax: %s %s (line %d)", problem, parser->context, (int)parser->context_mark.line + 1);
  return scene_fail_at(L, (int)parser->problem_mark.line + 1, (int)parser->problem_mark.column + 1, "",
                       "YAML syntax: %s", problem);
}

/* The limits, on libyaml's event stream, before any tree is built: a deep
 * or huge file is refused after SCENE_MAX_DEPTH or SCENE_MAX_NODES events
 * instead of after the whole tree has been built (libyaml's tree loader is
 * slow on deep nesting: 100,000 levels took 31 s). */
static ball_status check_limits(scene_loader *L, const char *text, size_t length) {
  yaml_parser_t parser;
  yaml_event_t ev;
  ball_status st = BALL_OK;
  int depth = 0, nodes = 0, done = 0;
  if (!yaml_parser_initialize(&parser)) return scene_fail_at(L, 0, 0, "", "out of memory"), BALL_ENOMEM;
  yaml_parser_set_input_string(&parser, (const unsigned char *)text, length);
  while (!done && st == BALL_OK) {
    if (!yaml_parser_parse(&parser, &ev)) {
      st = syntax_error(L, &parser);
      break;
    }
    switch (ev.type) {
      case YAML_MAPPING_START_EVENT:
      case YAML_SEQUENCE_START_EVENT:
      case YAML_SCALAR_EVENT:
      case YAML_ALIAS_EVENT:
        if ((ev.type == YAML_MAPPING_START_EVENT || ev.type == YAML_SEQUENCE_START_EVENT) &&
            ++depth > SCENE_MAX_DEPTH)
          st = scene_fail_at(L, (int)ev.start_mark.line + 1, (int)ev.start_mark.column + 1, "",
                             "nested deeper than %d levels (the limit)", SCENE_MAX_DEPTH);
        else if (++nodes > SCENE_MAX_NODES)
          st = scene_fail_at(L, (int)ev.start_mark.line + 1, (int)ev.start_mark.column + 1, "",
                             "more than %d values (the limit)", SCENE_MAX_NODES);
        break;
      case YAML_MAPPING_END_EVENT:
      case YAML_SEQUENCE_END_EVENT: --depth; break;
      case YAML_STREAM_END_EVENT: done = 1; break;
      default: break;
    }
    yaml_event_delete(&ev);
  }
  yaml_parser_delete(&parser);
  return st;
}

ball_status scene_read_document(const char *text, size_t length, const char *name, scene_loader *L,
                                scene_root_fn root_fn) {
  yaml_parser_t parser;
  yaml_document_t doc;
  yaml_node_t *root;
  ball_status st;
  scene_copy_string(L->err.file, sizeof L->err.file, name);
  if (length > SCENE_MAX_BYTES)
    return scene_fail_at(L, 0, 0, "", "larger than %d bytes (the limit)", SCENE_MAX_BYTES);
  if ((st = check_limits(L, text, length)) != BALL_OK) return st;
  if (!yaml_parser_initialize(&parser)) return scene_fail_at(L, 0, 0, "", "out of memory"), BALL_ENOMEM;
  yaml_parser_set_input_string(&parser, (const unsigned char *)text, length);
  if (!yaml_parser_load(&parser, &doc)) {
    st = syntax_error(L, &parser);
  } else {
    L->doc = &doc;
    root = yaml_document_get_root_node(&doc);
    st = root ? root_fn(L, root) : scene_fail_at(L, 1, 1, "", "the scene is empty (expected a mapping of keys)");
    if (st == BALL_OK) {
      /* A scene is one YAML document; a second one is a mistake. */
      yaml_document_t next;
      if (!yaml_parser_load(&parser, &next)) {
        st = syntax_error(L, &parser);
      } else {
        yaml_node_t *extra = yaml_document_get_root_node(&next);
        if (extra) st = scene_fail(L, extra, "", "a scene file holds one YAML document; found a second one");
        yaml_document_delete(&next);
      }
    }
    yaml_document_delete(&doc);
    L->doc = NULL;
  }
  yaml_parser_delete(&parser);
  return st;
}
