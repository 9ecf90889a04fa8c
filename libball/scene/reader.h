/* Inside libball::scene: the YAML reader (reader.c) that the scene format
 * (format.c) is written in. libyaml parses; this walks its node tree,
 * converts scalars strictly, reads table-driven sections and says where a
 * value was set, so that an error points at its file, line and column. */
#ifndef BALL_SCENE_READER_H
#define BALL_SCENE_READER_H

#include <stddef.h>
#include <stdint.h>

#include <yaml.h>

#include "ball/scene.h"

#define SCENE_MAX_LOCATIONS 512
#define SCENE_PATH_SIZE 96

/* Limits checked before the work is done (docs/scenes.md, "Limits"). */
#define SCENE_MAX_BYTES (1024 * 1024) /* a scene file, bytes */
#define SCENE_MAX_DEPTH 32            /* nested mappings and lists */
#define SCENE_MAX_NODES 20000         /* scalars, mappings and lists in one file */

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

/* ---- errors and locations ---- */

void scene_copy_string(char *dst, size_t size, const char *src);
/* Records the error (first one wins is the caller's business) and returns BALL_EPARSE. */
ball_status scene_fail_at(scene_loader *L, int line, int column, const char *path, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 5, 6)))
#endif
    ;
ball_status scene_fail(scene_loader *L, const yaml_node_t *node, const char *path, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 4, 5)))
#endif
    ;
void scene_remember(scene_loader *L, const char *path, const char *display, const yaml_node_t *node);
/* The location that set path, or the one of its closest enclosing key. */
const scene_location *scene_find_location(const scene_loader *L, const char *path);
/* dst = "path.key" (or "key" at the top), cut to SCENE_PATH_SIZE. */
void scene_join(char *dst, const char *path, const char *key);

/* ---- nodes and scalars ---- */

const char *scene_text(const yaml_node_t *node);
const char *scene_node_kind(const yaml_node_t *node);
ball_status scene_get_number(scene_loader *L, const yaml_node_t *node, const char *path, double *out);
ball_status scene_get_int(scene_loader *L, const yaml_node_t *node, const char *path, int *out);
ball_status scene_get_bool(scene_loader *L, const yaml_node_t *node, const char *path, int *out);
ball_status scene_get_vec3(scene_loader *L, const yaml_node_t *node, const char *path, ball_vec3 *out);
ball_status scene_get_uint64(scene_loader *L, const yaml_node_t *node, const char *path, uint64_t *out);
/* A name out of a table of count names (names(i) for i in [0, count)). */
typedef const char *(*scene_name_fn)(int value);
ball_status scene_get_enum(scene_loader *L, const yaml_node_t *node, const char *path, scene_name_fn names,
                           int count, int *out);
/* The items of a list (what: "walls") of at most max of them. */
ball_status scene_get_list(scene_loader *L, const yaml_node_t *node, const char *path, const char *what, int max,
                           int *n);
yaml_node_t *scene_list_item(scene_loader *L, const yaml_node_t *node, int i);
/* The value of key in a mapping node, or NULL. */
yaml_node_t *scene_key_value(scene_loader *L, const yaml_node_t *node, const char *key);

/* ---- sections ---- */

/* A section (floor, racket, a wall, a script, ...) is a mapping read by one
 * loop, scene_read_section, from a table of its keys: each key says what its
 * value is and where in the section's struct it goes. Keys that need more
 * than that (the net's axis, time.fps, a script, ...) are KEY_SPECIAL and go
 * to the section's hook, in their place in the file. */
typedef enum key_kind {
  KEY_NUMBER,  /* a finite number: double */
  KEY_INT,     /* an integer: int */
  KEY_BOOL,    /* true or false: int */
  KEY_VEC3,    /* [x, y, z]: ball_vec3 */
  KEY_ENUM,    /* one of the names of key_spec.names: stored as an int */
  KEY_RANGED,  /* a number in key_spec's range, checked where it stands: double */
  KEY_UINT64,  /* an unsigned 64-bit integer: uint64_t */
  KEY_SPECIAL  /* read by the section's hook */
} key_kind;

typedef struct key_spec {
  const char *name;    /* NULL ends a table */
  key_kind kind;
  size_t offset;       /* of the field in the section's struct */
  int required;        /* must be given (in a section that requires keys) */
  scene_name_fn names; /* KEY_ENUM: the names and how many */
  int count;
  double lo, hi;       /* KEY_RANGED: the range and which ends are open (BALL_FIELD_*_OPEN) */
  unsigned open;
  const char *range;   /* KEY_RANGED: the range in words, for the error ("in [0, 1]", "> 0") */
} key_spec;

#define KEY(name, kind, type, field) {name, kind, offsetof(type, field), 0, NULL, 0, 0.0, 0.0, 0u, NULL}
#define REQUIRED_KEY(name, kind, type, field) {name, kind, offsetof(type, field), 1, NULL, 0, 0.0, 0.0, 0u, NULL}
#define SPECIAL_KEY(name, required) {name, KEY_SPECIAL, 0, required, NULL, 0, 0.0, 0.0, 0u, NULL}
#define RANGED_KEY(name, type, field, lo, hi, open, range) \
  {name, KEY_RANGED, offsetof(type, field), 0, NULL, 0, lo, hi, open, range}
#define END_OF_KEYS {NULL, KEY_SPECIAL, 0, 0, NULL, 0, 0.0, 0.0, 0u, NULL}

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

/* Checks that node is a mapping whose keys are distinct scalars, each one of
 * the section's, and (if it requires them) that no required key is missing. */
ball_status scene_check_section(scene_loader *L, const yaml_node_t *node, const char *path, const section *sec);
/* Reads the pairs of a checked section in file order into base. */
ball_status scene_read_section(scene_loader *L, const yaml_node_t *node, const char *path, const section *sec,
                               void *base, void *ctx);
/* Both. */
ball_status scene_load_section(scene_loader *L, const yaml_node_t *node, const char *path, const section *sec,
                               void *base, void *ctx);

/* ---- documents ---- */

/* Reads one YAML document of at most SCENE_MAX_BYTES (within the depth and
 * node limits, checked on libyaml's event stream before the tree is built)
 * and calls root(L, root node). A second document is an error. name is used
 * in messages. The scene comes out only on success. */
typedef ball_status (*scene_root_fn)(scene_loader *L, const yaml_node_t *root);
ball_status scene_read_document(const char *text, size_t length, const char *name, scene_loader *L,
                                scene_root_fn root);

#endif /* BALL_SCENE_READER_H */
