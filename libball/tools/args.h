/* Argument helpers shared by the tools (ballsim, ballrender): a usage error
 * in the tools' one format, and strict numbers. Define TOOL_NAME before
 * including. */
#ifndef BALL_TOOLS_ARGS_H
#define BALL_TOOLS_ARGS_H

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>

#include "ball/scene.h"

#define EXIT_USAGE 2

/* "TOOL: message (see TOOL --help)" on err; returns EXIT_USAGE. */
static inline int tool_usage_error(FILE *err, const char *fmt, ...) {
  va_list ap;
  fprintf(err, "%s: ", TOOL_NAME);
  va_start(ap, fmt);
  vfprintf(err, fmt, ap);
  va_end(ap);
  fprintf(err, " (see %s --help)\n", TOOL_NAME);
  return EXIT_USAGE;
}
#define usage_error(...) tool_usage_error(stderr, __VA_ARGS__)

/* A finite number, the whole text consumed. strtod would skip leading
 * blanks: a strict number starts with a sign, a digit or a point. */
static inline int parse_number(const char *text, double *out) {
  char *end;
  double v;
  if (!text || !(*text == '-' || *text == '+' || *text == '.' || (*text >= '0' && *text <= '9'))) return 0;
  errno = 0;
  v = strtod(text, &end);
  if (end == text || *end != '\0' || errno == ERANGE || !isfinite(v)) return 0;
  *out = v;
  return 1;
}

/* A whole number in [lo, hi], the whole text consumed: digits after an
 * optional sign, nothing else (no blanks, no exponent). */
static inline int parse_integer(const char *text, long lo, long hi, long *out) {
  char *end;
  long v;
  if (!text || !(*text == '-' || *text == '+' || (*text >= '0' && *text <= '9'))) return 0;
  errno = 0;
  v = strtol(text, &end, 10);
  if (end == text || *end != '\0' || errno == ERANGE || v < lo || v > hi) return 0;
  *out = v;
  return 1;
}

/* Loads a scene file; on failure prints "file:line:column: field: message"
 * to out and returns 0. */
static inline int load_scene_to(FILE *out, const char *path, ball_scene *scene) {
  ball_scene_error err;
  char text[1024];
  if (ball_scene_load_file(path, scene, &err) == BALL_OK) return 1;
  ball_scene_error_format(&err, text, sizeof text);
  fprintf(out, "%s\n", text);
  return 0;
}
#define load_scene(path, scene) load_scene_to(stderr, (path), (scene))

#endif
