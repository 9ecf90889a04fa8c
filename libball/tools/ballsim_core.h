/* ballsim's core: its arguments, its run and its output lines, apart from
 * the process (signals, the terminal), so that tests can drive it with
 * memory streams (docs/scenes.md, "ballsim"). Public API of libball only. */
#ifndef BALL_TOOLS_BALLSIM_CORE_H
#define BALL_TOOLS_BALLSIM_CORE_H

#include <signal.h>
#include <stdio.h>

#include "ball/ball.h"

typedef enum ballsim_format { BALLSIM_FORMAT_NONE = 0, BALLSIM_FORMAT_CSV, BALLSIM_FORMAT_JSONL } ballsim_format;

typedef struct ballsim_options {
  const char *scene_path;  /* NULL: the built-in tennis scene */
  double fps;              /* frames per second; 0: the scene's frame time */
  double duration;         /* sim s; 0: the scene's duration */
  int scheme;              /* a ball_scheme; -1: the scene's */
  const char *out_path;    /* the trajectory file; NULL: none */
  ballsim_format format;   /* of out_path */
  int keys;                /* 1: print the scene key table and stop */
  int progress;            /* 1: show progress on err during a long run (set by the shell) */
} ballsim_options;

/* Exit statuses (ballsim --help). */
#define BALLSIM_EXIT_OK 0
#define BALLSIM_EXIT_ERROR 1
#define BALLSIM_EXIT_USAGE 2
#define BALLSIM_EXIT_INTERRUPTED 130

/* Reads argv into *o. Returns -1 to go on, or the exit status: 0 after
 * --help (printed on out), BALLSIM_EXIT_USAGE after an error (one line on
 * err: "ballsim: MESSAGE (see ballsim --help)"). */
int ballsim_parse_args(int argc, char **argv, ballsim_options *o, FILE *out, FILE *err);

/* The model keys of a scene file as the Markdown table of docs/scenes.md. */
int ballsim_print_keys(FILE *out);

/* Runs the scene as *o says: the scene line, one line per event and the
 * summary on out, errors on err, the trajectory to o->out_path. Stops after
 * the frame in hand once *stop is set (NULL: never). Returns the exit
 * status. */
int ballsim_run(const ballsim_options *o, FILE *out, FILE *err, const volatile sig_atomic_t *stop);

/* Text from a scene (its name, a file name) with control characters and
 * the backslash escaped, so that nothing in a scene can start a line of its
 * own or drive the terminal. */
void ballsim_put_text(FILE *f, const char *s);

/* A number for the text lines: fixed point with `digits` decimals between
 * 1e-3 and 1e9 (and 0), %.17g beyond. */
void ballsim_put_num(FILE *f, double v, int digits);

#endif
