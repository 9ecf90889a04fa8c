/* Cameras: presets placed from the model, lookup by name, projection. */
#include <math.h>
#include <string.h>

#include "view.h"

#define MARGIN 2.0             /* m of floor around the court and the obstacles */
#define MIN_HALF_SIZE 3.0      /* m: the floor is at least 6 m each way */
#define COURT_RATIO (23.77 / 10.97)  /* a doubles tennis court: length / width */
#define LINE_WIDTH 0.08       /* court lines, m */
#define GRID_STEP 1.0         /* the grid without a court, m */
#define GRID_WIDTH 0.025      /* its lines, m */
#define PI 3.14159265358979323846

static const char *const preset_names[BALL_CAMERA_PRESET_COUNT] = {"side", "top", "behind0", "behind1"};

const char *ball_camera_preset_name(ball_camera_preset preset) {
  if ((unsigned)preset >= BALL_CAMERA_PRESET_COUNT) return NULL;
  return preset_names[preset];
}

static void grow(view_arena *a, double x, double z) {
  if (x < a->lo[0]) a->lo[0] = x;
  if (x > a->hi[0]) a->hi[0] = x;
  if (z < a->lo[1]) a->lo[1] = z;
  if (z > a->hi[1]) a->hi[1] = z;
}

/* x and z extent of a net or wall rectangle */
static void grow_plane(view_arena *a, const ball_plane *p) {
  if (p->axis == 0) {
    grow(a, p->position, p->lo);
    grow(a, p->position, p->hi);
  } else {
    grow(a, p->lo, p->position);
    grow(a, p->hi, p->position);
  }
  if (p->top > a->height) a->height = p->top;
}

/* The arena around court ({x0, z0, x1, z1}), or around the court a net implies (NULL). */
static void arena(const ball_model *m, const double *court, view_arena *a) {
  int i;
  memset(a, 0, sizeof *a);
  a->lo[0] = a->hi[0] = m->initial_position.x;
  a->lo[1] = a->hi[1] = m->initial_position.z;
  a->height = m->initial_position.y > 2.0 ? m->initial_position.y : 2.0;
  if (court) {
    a->has_court = 1;
    a->court_lo[0] = court[0], a->court_lo[1] = court[1];
    a->court_hi[0] = court[2], a->court_hi[1] = court[3];
    grow(a, court[0], court[1]);
    grow(a, court[2], court[3]);
    /* the long axis: the one the net cuts, else the court's longer side */
    a->long_axis = m->has_net ? (m->net.axis == 0 ? 0 : 1) : (court[3] - court[1] > court[2] - court[0] ? 1 : 0);
    if (m->has_net) grow_plane(a, &m->net);
  } else if (m->has_net) {
    /* the net spans the court's width; the court is a tennis court of that width */
    const ball_plane *n = &m->net;
    int across = n->axis == 0 ? 0 : 1; /* the axis the net's plane cuts */
    double half_len = 0.5 * (n->hi - n->lo) * COURT_RATIO;
    a->has_court = 1;
    a->court_lo[across] = n->position - half_len;
    a->court_hi[across] = n->position + half_len;
    a->court_lo[1 - across] = n->lo;
    a->court_hi[1 - across] = n->hi;
    grow(a, a->court_lo[0], a->court_lo[1]);
    grow(a, a->court_hi[0], a->court_hi[1]);
    grow_plane(a, n);
    a->long_axis = across;
  }
  for (i = 0; i < m->n_walls; ++i) grow_plane(a, &m->walls[i]);
  for (i = 0; i < m->n_rackets; ++i)
    if (m->rackets[i].partner < 0) grow(a, m->rackets[i].target.x, m->rackets[i].target.z);
  /* whole metres, so that a small change of the scene (the ball's start a
   * few centimetres off) keeps the floor and the preset cameras where they are */
  for (i = 0; i < 2; ++i) {
    double c = floor(0.5 * (a->lo[i] + a->hi[i]) + 0.5);
    a->lo[i] = floor(a->lo[i] - MARGIN);
    a->hi[i] = ceil(a->hi[i] + MARGIN);
    if (a->lo[i] > c - MIN_HALF_SIZE) a->lo[i] = c - MIN_HALF_SIZE;
    if (a->hi[i] < c + MIN_HALF_SIZE) a->hi[i] = c + MIN_HALF_SIZE;
  }
  if (!a->has_court) a->long_axis = (a->hi[1] - a->lo[1]) > (a->hi[0] - a->lo[0]) ? 1 : 0;
}

void view_arena_of(const ball_model *m, view_arena *a) { arena(m, NULL, a); }

/* A court given by a caller: finite, not empty, within BALL_MAX_COORD. */
static ball_status check_court(const double court[4]) {
  int i;
  for (i = 0; i < 4; ++i) {
    if (!isfinite(court[i])) return BALL_ENONFINITE;
    if (fabs(court[i]) > BALL_MAX_COORD) return BALL_ERANGE;
  }
  return court[0] < court[2] && court[1] < court[3] ? BALL_OK : BALL_ERANGE;
}

/* A line from (a0, b) to (a1, b) along axis (0: x, 1: z), w wide, as a floor rectangle. */
static void floor_line(ball_floor_layout *f, int axis, double a0, double a1, double b, double w) {
  double *r = f->lines[f->n_lines++];
  if (axis == 0) {
    r[0] = a0, r[1] = b - 0.5 * w, r[2] = a1, r[3] = b + 0.5 * w;
  } else {
    r[0] = b - 0.5 * w, r[1] = a0, r[2] = b + 0.5 * w, r[3] = a1;
  }
}

/* The floor of arena a (docs/render.md, "What is drawn"). */
static void layout_of(const ball_model *m, const view_arena *a, ball_floor_layout *out) {
  ball_floor_layout f;
  memset(&f, 0, sizeof f);
  f.level = m->floor_level;
  f.ground[0] = a->lo[0], f.ground[1] = a->lo[1], f.ground[2] = a->hi[0], f.ground[3] = a->hi[1];
  f.grid_step = GRID_STEP;
  f.grid_width = GRID_WIDTH;
  if (a->has_court) {
    /* a tennis court on the court: the outer lines and, with a net across
     * it, the service lines 6.40 m of 11.885 m of each half from the net and
     * the centre line between them */
    int L = a->long_axis, W = 1 - L;
    double lw = LINE_WIDTH;
    f.has_court = 1;
    f.court[0] = a->court_lo[0], f.court[1] = a->court_lo[1], f.court[2] = a->court_hi[0], f.court[3] = a->court_hi[1];
    floor_line(&f, L, a->court_lo[L], a->court_hi[L], a->court_lo[W] + 0.5 * lw, lw);
    floor_line(&f, L, a->court_lo[L], a->court_hi[L], a->court_hi[W] - 0.5 * lw, lw);
    floor_line(&f, W, a->court_lo[W], a->court_hi[W], a->court_lo[L] + 0.5 * lw, lw);
    floor_line(&f, W, a->court_lo[W], a->court_hi[W], a->court_hi[L] - 0.5 * lw, lw);
    if (m->has_net && (m->net.axis == 0 ? 0 : 1) == L && m->net.position > a->court_lo[L] &&
        m->net.position < a->court_hi[L]) {
      double net = m->net.position, mid = 0.5 * (a->court_lo[W] + a->court_hi[W]);
      double service_lo = (net - a->court_lo[L]) * 6.40 / 11.885, service_hi = (a->court_hi[L] - net) * 6.40 / 11.885;
      floor_line(&f, W, a->court_lo[W], a->court_hi[W], net - service_lo, lw);
      floor_line(&f, W, a->court_lo[W], a->court_hi[W], net + service_hi, lw);
      floor_line(&f, L, net - service_lo, net + service_hi, mid, lw);
    }
  }
  *out = f;
}

ball_status ball_floor_layout_of(const ball_model *m, ball_floor_layout *out) {
  view_arena a;
  if (!m || !out) return BALL_EINVAL;
  view_arena_of(m, &a);
  layout_of(m, &a, out);
  return BALL_OK;
}

ball_status ball_floor_layout_court(const ball_model *m, const double court[4], ball_floor_layout *out) {
  view_arena a;
  ball_status st;
  if (!m || !court || !out) return BALL_EINVAL;
  if ((st = check_court(court)) != BALL_OK) return st;
  arena(m, court, &a);
  layout_of(m, &a, out);
  return BALL_OK;
}

/* Preset `preset` framing arena a for an image of that aspect (checked by the caller). */
static void preset_of(const ball_model *model, const view_arena *a, ball_camera_preset preset, double aspect,
                      ball_camera *out) {
  ball_vec3 along, side_dir, centre, up = ball_v3(0.0, 1.0, 0.0);
  double len, wid, tan_v, tan_h, d;
  ball_camera c;
  along = a->long_axis == 0 ? ball_v3(1.0, 0.0, 0.0) : ball_v3(0.0, 0.0, 1.0);
  /* the side camera's view direction: with up y, the long axis runs left to right */
  side_dir = ball_v3_cross(up, along);
  len = a->hi[a->long_axis] - a->lo[a->long_axis];
  wid = a->hi[1 - a->long_axis] - a->lo[1 - a->long_axis];
  centre = ball_v3(0.5 * (a->lo[0] + a->hi[0]), model->floor_level, 0.5 * (a->lo[1] + a->hi[1]));
  memset(&c, 0, sizeof c);
  c.up = up;
  switch (preset) {
    case BALL_CAMERA_SIDE: {
      double elev = 28.0 * PI / 180.0;
      c.fov = 40.0;
      tan_v = tan(0.5 * c.fov * PI / 180.0);
      tan_h = tan_v * aspect;
      /* the length across the image, the height of the scene above it */
      d = 0.5 * len / tan_h;
      if (0.6 * a->height / tan_v > d) d = 0.6 * a->height / tan_v;
      d += 0.5 * wid;
      c.target = ball_v3_add(centre, ball_v3(0.0, 0.3 * a->height, 0.0));
      c.eye = ball_v3_add(c.target, ball_v3_add(ball_v3_scale(side_dir, -d * cos(elev)), ball_v3(0.0, d * sin(elev), 0.0)));
      break;
    }
    case BALL_CAMERA_TOP:
      c.fov = 40.0;
      tan_v = tan(0.5 * c.fov * PI / 180.0);
      tan_h = tan_v * aspect;
      d = 0.5 * len / tan_h;
      if (0.5 * wid / tan_v > d) d = 0.5 * wid / tan_v;
      c.target = centre;
      c.eye = ball_v3_add(centre, ball_v3(0.0, d, 0.0));
      c.up = ball_v3_cross(up, along); /* so that the long axis runs left to right */
      break;
    case BALL_CAMERA_BEHIND0:
    case BALL_CAMERA_BEHIND1: {
      double sgn = preset == BALL_CAMERA_BEHIND0 ? 1.0 : -1.0;
      c.fov = 50.0;
      c.target = ball_v3_add(centre, ball_v3(0.0, 0.3, 0.0));
      c.eye = ball_v3_add(centre, ball_v3_add(ball_v3_scale(along, -sgn * 0.75 * len), ball_v3(0.0, 0.3 * len + 1.0, 0.0)));
      break;
    }
    case BALL_CAMERA_PRESET_COUNT: break;
  }
  *out = c;
}

static ball_status check_preset(ball_camera_preset preset, double aspect) {
  if (!isfinite(aspect)) return BALL_ENONFINITE;
  if (!(aspect > 0.0)) return BALL_ERANGE;
  return (unsigned)preset < BALL_CAMERA_PRESET_COUNT ? BALL_OK : BALL_ERANGE;
}

ball_status ball_camera_from_preset(const ball_model *model, ball_camera_preset preset, double aspect,
                                    ball_camera *out) {
  view_arena a;
  ball_status st;
  if (!model || !out) return BALL_EINVAL;
  if ((st = check_preset(preset, aspect)) != BALL_OK) return st;
  view_arena_of(model, &a);
  preset_of(model, &a, preset, aspect, out);
  return BALL_OK;
}

ball_status ball_camera_from_preset_court(const ball_model *model, const double court[4], ball_camera_preset preset,
                                          double aspect, ball_camera *out) {
  view_arena a;
  ball_status st;
  if (!model || !court || !out) return BALL_EINVAL;
  if ((st = check_preset(preset, aspect)) != BALL_OK || (st = check_court(court)) != BALL_OK) return st;
  arena(model, court, &a);
  preset_of(model, &a, preset, aspect, out);
  return BALL_OK;
}

ball_status ball_camera_find(const ball_scene *scene, const char *name, double aspect, ball_camera *out) {
  int i;
  if (!scene || !name || !out) return BALL_EINVAL;
  for (i = 0; i < scene->render.n_cameras && i < BALL_SCENE_MAX_CAMERAS; ++i) {
    if (strcmp(scene->render.cameras[i].name, name) == 0) {
      *out = scene->render.cameras[i].camera;
      return BALL_OK;
    }
  }
  for (i = 0; i < BALL_CAMERA_PRESET_COUNT; ++i)
    if (strcmp(preset_names[i], name) == 0)
      return ball_camera_from_preset(&scene->model, (ball_camera_preset)i, aspect, out);
  return BALL_ENOTFOUND;
}

static ball_vec3 unit_or_flag(ball_vec3 v, int *ok) {
  double n = sqrt(ball_v3_dot(v, v));
  if (!(n > 1e-12) || !isfinite(n)) {
    *ok = 0;
    return v;
  }
  return ball_v3_scale(v, 1.0 / n);
}

int view_matrix(const ball_camera *cam, double m[16]) {
  int ok = 1;
  ball_vec3 f = unit_or_flag(ball_v3(cam->target.x - cam->eye.x, cam->target.y - cam->eye.y, cam->target.z - cam->eye.z), &ok);
  ball_vec3 s = unit_or_flag(ball_v3_cross(f, unit_or_flag(cam->up, &ok)), &ok);
  ball_vec3 u = ball_v3_cross(s, f);
  if (!ok) return 0;
  /* rows s, u, -f; translation -R eye (column-major) */
  m[0] = s.x; m[4] = s.y; m[8] = s.z; m[12] = -ball_v3_dot(s, cam->eye);
  m[1] = u.x; m[5] = u.y; m[9] = u.z; m[13] = -ball_v3_dot(u, cam->eye);
  m[2] = -f.x; m[6] = -f.y; m[10] = -f.z; m[14] = ball_v3_dot(f, cam->eye);
  m[3] = 0.0; m[7] = 0.0; m[11] = 0.0; m[15] = 1.0;
  return 1;
}

void view_projection(const ball_camera *cam, double aspect, double m[16]) {
  double f = 1.0 / tan(0.5 * cam->fov * PI / 180.0);
  memset(m, 0, 16 * sizeof m[0]);
  m[0] = f / aspect;
  m[5] = f;
  m[10] = (VIEW_FAR + VIEW_NEAR) / (VIEW_NEAR - VIEW_FAR);
  m[11] = -1.0;
  m[14] = 2.0 * VIEW_FAR * VIEW_NEAR / (VIEW_NEAR - VIEW_FAR);
}

ball_status ball_camera_project(const ball_camera *cam, int width, int height, ball_vec3 p, double *px, double *py,
                                double *depth) {
  double v[16], pr[16], e[4], clip[4];
  int i;
  if (!cam || !px || !py) return BALL_EINVAL;
  if (!ball_v3_finite(cam->eye) || !ball_v3_finite(cam->target) || !ball_v3_finite(cam->up) || !isfinite(cam->fov) || !ball_v3_finite(p))
    return BALL_ENONFINITE;
  if (width < 1 || height < 1 || !(cam->fov >= 1.0 && cam->fov <= 179.0)) return BALL_ERANGE;
  if (!view_matrix(cam, v)) return BALL_ERANGE;
  view_projection(cam, (double)width / height, pr);
  for (i = 0; i < 4; ++i) e[i] = v[i] * p.x + v[4 + i] * p.y + v[8 + i] * p.z + v[12 + i];
  if (!(-e[2] > 0.0)) return BALL_ERANGE;
  for (i = 0; i < 4; ++i) clip[i] = pr[i] * e[0] + pr[4 + i] * e[1] + pr[8 + i] * e[2] + pr[12 + i] * e[3];
  *px = 0.5 * (clip[0] / clip[3] + 1.0) * width;
  *py = (1.0 - 0.5 * (clip[1] / clip[3] + 1.0)) * height;
  if (depth) *depth = -e[2];
  return BALL_OK;
}
