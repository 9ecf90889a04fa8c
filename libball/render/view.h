/* Inside libball::render: the arena a model spans (for the presets and the
 * floor) and the camera matrices (for the drawing and ball_camera_project). */
#ifndef BALL_RENDER_VIEW_H
#define BALL_RENDER_VIEW_H

#include <math.h>

#include "ball/render.h"
#include "ball/vec3.h"

#define VIEW_NEAR 0.2   /* near clipping plane, m */
#define VIEW_FAR 400.0  /* far clipping plane, m */

/* The floor area a model's scene uses, and its court. */
typedef struct view_arena {
  double lo[2], hi[2];  /* floor rectangle, x and z, whole m (court and obstacles plus a margin) */
  int long_axis;        /* 0: x, 1: z; the axis across the net, else the longer side */
  double height;        /* the highest thing to keep in view (net, walls, ball start), m */
  int has_court;        /* 1: a net: court lines around it */
  double court_lo[2], court_hi[2];  /* the court: a tennis court scaled to the net's width, m */
} view_arena;

void view_arena_of(const ball_model *model, view_arena *arena);

/* Column-major 4x4 matrices, as glLoadMatrixd takes them. 0 for a camera
 * whose target is its eye or whose up is along the view. */
int view_matrix(const ball_camera *cam, double m[16]);
void view_projection(const ball_camera *cam, double aspect, double m[16]);

#endif
