/* libball scene files: YAML text -> ball_model (and, for ballsim and tests,
 * the run settings and racket scripts). Built on libyaml; not part of the
 * core library, which depends on libm only. See docs/scenes.md. */
#ifndef BALL_SCENE_H
#define BALL_SCENE_H

#include <stddef.h>

#include "ball/ball.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Where and why a scene was rejected. */
typedef struct ball_scene_error {
  char file[256];     /* file name (or the name given to ball_scene_load_string) */
  int line;           /* 1-based line of the offending node, 0 if none */
  int column;         /* 1-based column, 0 if none */
  char field[128];    /* dotted path of the field, e.g. "walls[1].damping" */
  char message[256];  /* what is wrong */
} ball_scene_error;

/* A loaded scene: the model plus what a headless run needs. */
typedef struct ball_scene {
  char name[64];        /* scene name ("name:" key, else empty) */
  ball_model model;     /* every parameter, checked with ball_model_check */
  double duration;      /* default run length for ballsim, s */
} ball_scene;

/* Loads a scene file. On failure the scene is left unchanged and err (if not
 * NULL) says where: "file:line:column: field: message". */
BALL_API ball_status ball_scene_load_file(const char *path, ball_scene *scene,
                                          ball_scene_error *err);

/* The same from text in memory; name is used in error messages. */
BALL_API ball_status ball_scene_load_string(const char *text, size_t length, const char *name,
                                            ball_scene *scene, ball_scene_error *err);

/* The built-in scene ballsim runs without a scene file: ball_model_default
 * (a tennis court) plus a serve, 3 s long; libball/scenes/tennis.yaml spells
 * out the same scene. */
BALL_API void ball_scene_default(ball_scene *scene);

/* Formats err as "file:line:column: field: message" into buf. */
BALL_API void ball_scene_error_format(const ball_scene_error *err, char *buf, size_t size);

#ifdef __cplusplus
}
#endif

#endif /* BALL_SCENE_H */
