/* libball scene files: YAML text -> ball_model (and, for ballsim and tests,
 * the run settings and racket scripts). Built on libyaml; not part of the
 * core library, which depends on libm only. See docs/scenes.md. */
#ifndef BALL_SCENE_H
#define BALL_SCENE_H

#include <stddef.h>
#include <stdint.h>

#include "ball/ball.h"
#include "ball/script.h"

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

/* ---- the render section (read here, drawn by libball::render) ------------ */

#define BALL_SCENE_MAX_CAMERAS 8  /* explicit cameras per scene */

/* A pinhole camera: where it stands, what it looks at, which way is up. */
typedef struct ball_camera {
  ball_vec3 eye;     /* m */
  ball_vec3 target;  /* m; not the eye */
  ball_vec3 up;      /* any length > 0, not along target - eye */
  double fov;        /* vertical field of view, degrees, [1, 179] */
} ball_camera;

typedef struct ball_scene_camera {
  char name[32];      /* letters, digits, '_' and '-'; distinct within a scene */
  ball_camera camera;
} ball_scene_camera;

/* What ballrender draws unless told otherwise; ballsim ignores it. */
typedef struct ball_scene_render {
  double trail;       /* s of recent ball positions drawn as a trail, [0, 60]; 0: none */
  double markers;     /* s an event marker stays after its event, [0, 60]; 0: none */
  int n_cameras;      /* [0, BALL_SCENE_MAX_CAMERAS] */
  ball_scene_camera cameras[BALL_SCENE_MAX_CAMERAS];
} ball_scene_render;

/* ---- scenes ----------------------------------------------------------------- */

/* A loaded scene: the model plus what a headless run needs. */
typedef struct ball_scene {
  char name[64];        /* scene name ("name:" key, else empty) */
  ball_model model;     /* every parameter, checked with ball_model_check */
  double duration;      /* default run length for ballsim, s */
  double frame_time;    /* real seconds per frame, s (> 0; time.frame_time or 1 / time.fps) */
  double time_base;     /* sim seconds per real second (> 0): a frame advances the sim by
                           frame_time * time_base (section 4's time base) */
  ball_racket_script scripts[BALL_MAX_RACKETS]; /* rackets[i].script; n_keyframes 0: none */
  ball_scene_render render;  /* the render section (docs/render.md); trail 0, markers 1 s, no cameras by default */
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

/* ---- running a scene ------------------------------------------------------- */

/* A scene played frame by frame the way ballsim plays it: each frame first
 * hands every scripted racket sample that has arrived by the end of the frame
 * to ball_racket_push (rejections are counted, not errors: they are normal
 * under jitter), then calls ball_step with dt = frame_time * time_base. Every
 * tool that replays a scene (ballsim, ballrender) steps it through here, so
 * they agree frame for frame. A plain value, about 60 kB: copy it to branch
 * off a replay. */
typedef struct ball_scene_run {
  ball_sim sim;                /* the ball; sim.time is the clock */
  ball_script_player player;   /* the rackets' scripted samples */
  double dt;                   /* sim seconds per frame, s */
  unsigned long arrived;       /* racket samples handed to ball_racket_push */
  unsigned long accepted;      /* ... kept (newer than the newest kept) */
  unsigned long duplicate;     /* ... exact copies of a kept sample, ignored */
  unsigned long stale;         /* ... older than the newest kept (BALL_ESTALE) */
  unsigned long invalid;       /* ... refused for another reason */
} ball_scene_run;

/* Starts a run of scene (its model must pass ball_model_check) at time 0. */
BALL_API ball_status ball_scene_run_init(ball_scene_run *run, const ball_scene *scene);

/* One frame: samples, then ball_step on the run's sim (which owns the
 * scene's model). Events as ball_step writes them. */
BALL_API ball_status ball_scene_run_step(ball_scene_run *run, ball_event *events, int cap, int *n_events);

#ifdef __cplusplus
}
#endif

#endif /* BALL_SCENE_H */
