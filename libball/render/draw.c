/* The renderer: fixed-function OpenGL 1.x into memory through OSMesa.
 * Why fixed-function: the picture is simple (quads, discs, a sphere, lines),
 * llvmpipe runs it the same with any thread count, and only libOSMesa is
 * linked: no libGL, no EGL, no GLU (the matrices are view.h's, so the
 * projection the tests use is the one drawn with). Each picture is drawn at
 * twice the size and averaged down 2 x 2 (OSMesa has no multisampling). */
#include <GL/osmesa.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "view.h"

#define SUPERSAMPLE 2
#define MIN_BALL_PIXELS 2.0   /* least ball radius, output pixels */
#define MIN_MARKER_PIXELS 5.0 /* least marker radius, output pixels */
#define MARKER_RADIUS 0.25    /* m */
#define PI 3.14159265358979323846

struct ball_renderer {
  OSMesaContext ctx;
  int width, height;        /* output, pixels */
  int big_w, big_h;         /* drawn, pixels (SUPERSAMPLE times the output) */
  unsigned char *big;       /* big_w * big_h * 4, RGBA, rows bottom first */
  unsigned char *rgb;       /* width * height * 3, rows top first */
};

ball_status ball_renderer_create(int width, int height, ball_renderer **out) {
  ball_renderer *r;
  if (!out) return BALL_EINVAL;
  if (width < BALL_RENDER_MIN_SIZE || width > BALL_RENDER_MAX_SIZE || height < BALL_RENDER_MIN_SIZE ||
      height > BALL_RENDER_MAX_SIZE)
    return BALL_ERANGE;
  r = (ball_renderer *)calloc(1, sizeof *r);
  if (!r) return BALL_ENOMEM;
  r->width = width;
  r->height = height;
  r->big_w = width * SUPERSAMPLE;
  r->big_h = height * SUPERSAMPLE;
  r->big = (unsigned char *)calloc((size_t)r->big_w * r->big_h, 4);
  r->rgb = (unsigned char *)calloc((size_t)width * height, 3);
  /* RGBA, a 24-bit depth buffer, no stencil, no accumulation buffer */
  r->ctx = OSMesaCreateContextExt(OSMESA_RGBA, 24, 0, 0, NULL);
  if (!r->big || !r->rgb || !r->ctx) {
    ball_renderer_destroy(r);
    return BALL_ENOMEM;
  }
  *out = r;
  return BALL_OK;
}

void ball_renderer_destroy(ball_renderer *r) {
  if (!r) return;
  if (r->ctx) {
    /* release it first: a context destroyed while current keeps its framebuffer */
    if (OSMesaGetCurrentContext() == r->ctx) OSMesaMakeCurrent(NULL, NULL, GL_UNSIGNED_BYTE, 0, 0);
    OSMesaDestroyContext(r->ctx);
  }
  free(r->big);
  free(r->rgb);
  free(r);
}

ball_status ball_render_pixels(const ball_renderer *r, const unsigned char **rgb, int *width, int *height) {
  if (!r || !rgb) return BALL_EINVAL;
  *rgb = r->rgb;
  if (width) *width = r->width;
  if (height) *height = r->height;
  return BALL_OK;
}

/* ---- geometry ---------------------------------------------------------- */

static ball_vec3 unit(ball_vec3 v) {
  double n = sqrt(ball_v3_dot(v, v));
  return n > 0.0 ? ball_v3(v.x / n, v.y / n, v.z / n) : ball_v3(0.0, 1.0, 0.0);
}

/* Two unit vectors across n. */
static void basis(ball_vec3 n, ball_vec3 *u, ball_vec3 *w) {
  ball_vec3 a = fabs(n.y) < 0.9 ? ball_v3(0.0, 1.0, 0.0) : ball_v3(1.0, 0.0, 0.0);
  *u = unit(ball_v3_cross(n, a));
  *w = ball_v3_cross(n, *u);
}

static void colour(ball_rgb c, float alpha) { glColor4f(c.r, c.g, c.b, alpha); }
static void vertex(ball_vec3 p) { glVertex3d(p.x, p.y, p.z); }

/* An axis-aligned rectangle on the floor plane, at height y. */
static void floor_rect(double x0, double z0, double x1, double z1, double y) {
  glNormal3d(0.0, 1.0, 0.0);
  glBegin(GL_QUADS);
  glVertex3d(x0, y, z0);
  glVertex3d(x0, y, z1);
  glVertex3d(x1, y, z1);
  glVertex3d(x1, y, z0);
  glEnd();
}

/* A net or wall rectangle; its normal along the plane's axis. */
static void plane_rect(const ball_plane *p, double bottom, double top) {
  glBegin(GL_QUADS);
  if (p->axis == 0) {
    glNormal3d(1.0, 0.0, 0.0);
    glVertex3d(p->position, bottom, p->lo);
    glVertex3d(p->position, bottom, p->hi);
    glVertex3d(p->position, top, p->hi);
    glVertex3d(p->position, top, p->lo);
  } else {
    glNormal3d(0.0, 0.0, 1.0);
    glVertex3d(p->lo, bottom, p->position);
    glVertex3d(p->hi, bottom, p->position);
    glVertex3d(p->hi, top, p->position);
    glVertex3d(p->lo, top, p->position);
  }
  glEnd();
}

/* The rectangle's edges (seen edge-on, a plane would not show). */
static void plane_outline(const ball_plane *p) {
  glBegin(GL_LINE_LOOP);
  if (p->axis == 0) {
    glVertex3d(p->position, p->bottom, p->lo);
    glVertex3d(p->position, p->bottom, p->hi);
    glVertex3d(p->position, p->top, p->hi);
    glVertex3d(p->position, p->top, p->lo);
  } else {
    glVertex3d(p->lo, p->bottom, p->position);
    glVertex3d(p->hi, p->bottom, p->position);
    glVertex3d(p->hi, p->top, p->position);
    glVertex3d(p->lo, p->top, p->position);
  }
  glEnd();
}

static void disc(ball_vec3 c, ball_vec3 n, double radius, int filled) {
  ball_vec3 u, w;
  int i, segs = 48;
  basis(n, &u, &w);
  glNormal3d(n.x, n.y, n.z);
  glBegin(filled ? GL_TRIANGLE_FAN : GL_LINE_LOOP);
  if (filled) vertex(c);
  for (i = 0; i <= segs - (filled ? 0 : 1); ++i) {
    double a = 2.0 * PI * (i % segs) / segs;
    vertex(ball_v3(c.x + radius * (cos(a) * u.x + sin(a) * w.x), c.y + radius * (cos(a) * u.y + sin(a) * w.y),
              c.z + radius * (cos(a) * u.z + sin(a) * w.z)));
  }
  glEnd();
}

static void sphere(ball_vec3 c, double radius) {
  int i, j, stacks = 16, slices = 24;
  for (i = 0; i < stacks; ++i) {
    double t0 = PI * i / stacks - 0.5 * PI, t1 = PI * (i + 1) / stacks - 0.5 * PI;
    glBegin(GL_QUAD_STRIP);
    for (j = 0; j <= slices; ++j) {
      double p = 2.0 * PI * (j % slices) / slices;
      ball_vec3 n0 = ball_v3(cos(t1) * cos(p), sin(t1), cos(t1) * sin(p));
      ball_vec3 n1 = ball_v3(cos(t0) * cos(p), sin(t0), cos(t0) * sin(p));
      /* lower ring first: counter-clockwise seen from outside, so the
       * outside is the front face that two-sided lighting lights */
      glNormal3d(n1.x, n1.y, n1.z);
      glVertex3d(c.x + radius * n1.x, c.y + radius * n1.y, c.z + radius * n1.z);
      glNormal3d(n0.x, n0.y, n0.z);
      glVertex3d(c.x + radius * n0.x, c.y + radius * n0.y, c.z + radius * n0.z);
    }
    glEnd();
  }
}

/* The world size of `pixels` output pixels at point p. */
static double world_size(const ball_camera *cam, int height, ball_vec3 p, double pixels) {
  ball_vec3 d = ball_v3(p.x - cam->eye.x, p.y - cam->eye.y, p.z - cam->eye.z);
  return pixels * 2.0 * sqrt(ball_v3_dot(d, d)) * tan(0.5 * cam->fov * PI / 180.0) / height;
}

/* ---- the picture -------------------------------------------------------- */

static void draw_floor(const ball_model *m, const ball_palette *pal) {
  ball_floor_layout f;
  int i;
  ball_floor_layout_of(m, &f);
  colour(pal->ground, 1.0f);
  floor_rect(f.ground[0], f.ground[1], f.ground[2], f.ground[3], f.level);
  if (f.has_court) {
    colour(pal->court, 1.0f);
    floor_rect(f.court[0], f.court[1], f.court[2], f.court[3], f.level);
    colour(pal->line, 1.0f);
    for (i = 0; i < f.n_lines; ++i) floor_rect(f.lines[i][0], f.lines[i][1], f.lines[i][2], f.lines[i][3], f.level);
  } else {
    double g, h = 0.5 * f.grid_width;
    colour(pal->grid, 1.0f);
    for (g = ceil(f.ground[0]); g <= f.ground[2]; g += f.grid_step) floor_rect(g - h, f.ground[1], g + h, f.ground[3], f.level);
    for (g = ceil(f.ground[1]); g <= f.ground[3]; g += f.grid_step) floor_rect(f.ground[0], g - h, f.ground[2], g + h, f.level);
  }
}

/* The frame's 2x2 blocks averaged into the output, top row first. */
static void downsample(ball_renderer *r) {
  int x, y, c;
  for (y = 0; y < r->height; ++y) {
    const unsigned char *row0 = r->big + (size_t)(r->big_h - 1 - 2 * y) * r->big_w * 4;
    const unsigned char *row1 = row0 - (size_t)r->big_w * 4;
    unsigned char *dst = r->rgb + (size_t)y * r->width * 3;
    for (x = 0; x < r->width; ++x)
      for (c = 0; c < 3; ++c)
        dst[3 * x + c] = (unsigned char)((row0[8 * x + c] + row0[8 * x + 4 + c] + row1[8 * x + c] +
                                          row1[8 * x + 4 + c] + 2) / 4);
  }
}

static ball_status check_frame(const ball_model *m, const ball_camera *cam, const ball_frame *f) {
  int i;
  if (!ball_v3_finite(cam->eye) || !ball_v3_finite(cam->target) || !ball_v3_finite(cam->up) || !isfinite(cam->fov) || !ball_v3_finite(f->ball))
    return BALL_ENONFINITE;
  if (!(cam->fov >= 1.0 && cam->fov <= 179.0)) return BALL_ERANGE;
  if (f->n_rackets < 0 || f->n_rackets > m->n_rackets || f->n_trail < 0 || f->n_events < 0) return BALL_ERANGE;
  if ((f->n_trail > 0 && !f->trail) || (f->n_events > 0 && !f->events)) return BALL_EINVAL;
  for (i = 0; i < f->n_rackets; ++i) {
    if (!f->rackets[i].visible) continue;
    if (!ball_v3_finite(f->rackets[i].center) || !ball_v3_finite(f->rackets[i].normal)) return BALL_ENONFINITE;
    if (!(ball_v3_dot(f->rackets[i].normal, f->rackets[i].normal) > 0.0)) return BALL_ERANGE;
  }
  for (i = 0; i < f->n_trail; ++i)
    if (!ball_v3_finite(f->trail[i])) return BALL_ENONFINITE;
  for (i = 0; i < f->n_events; ++i) {
    if ((unsigned)f->events[i].kind >= BALL_EVENT_KIND_COUNT) return BALL_ERANGE;
    if (!ball_v3_finite(f->events[i].point)) return BALL_ENONFINITE;
  }
  return BALL_OK;
}

static void draw_marker(const ball_model *m, const ball_palette *pal, const ball_camera *cam, int height,
                        const ball_event *e) {
  double r = world_size(cam, height, e->point, MIN_MARKER_PIXELS);
  ball_vec3 n = ball_v3(0.0, 1.0, 0.0), p = e->point;
  if (r < MARKER_RADIUS) r = MARKER_RADIUS;
  colour(pal->markers[e->kind], 1.0f);
  if (e->kind == BALL_EVENT_RACKET) {
    glBegin(GL_LINES);
    glVertex3d(p.x - r, p.y, p.z);
    glVertex3d(p.x + r, p.y, p.z);
    glVertex3d(p.x, p.y - r, p.z);
    glVertex3d(p.x, p.y + r, p.z);
    glVertex3d(p.x, p.y, p.z - r);
    glVertex3d(p.x, p.y, p.z + r);
    glEnd();
    return;
  }
  if (e->kind == BALL_EVENT_FLOOR) {
    p.y = m->floor_level + 0.01;
  } else {
    const ball_plane *pl = e->kind == BALL_EVENT_NET ? &m->net
                           : (e->index >= 0 && e->index < m->n_walls) ? &m->walls[e->index] : NULL;
    n = (pl && pl->axis == 2) ? ball_v3(0.0, 0.0, 1.0) : ball_v3(1.0, 0.0, 0.0);
  }
  disc(p, n, r, 0);
}

ball_status ball_render_draw(ball_renderer *r, const ball_model *m, const ball_camera *cam, const ball_frame *f) {
  static const GLfloat light_dir[4] = {0.35f, 1.0f, 0.55f, 0.0f};
  static const GLfloat light_diffuse[4] = {0.75f, 0.75f, 0.75f, 1.0f};
  static const GLfloat light_ambient[4] = {0.0f, 0.0f, 0.0f, 1.0f};
  static const GLfloat scene_ambient[4] = {0.40f, 0.40f, 0.40f, 1.0f};
  double view[16], proj[16], ball_r;
  ball_palette pal;
  ball_status st;
  int i;

  if (!r || !m || !cam || !f) return BALL_EINVAL;
  if ((st = check_frame(m, cam, f)) != BALL_OK) return st;
  if (!view_matrix(cam, view)) return BALL_ERANGE;
  view_projection(cam, (double)r->width / r->height, proj);
  if (!OSMesaMakeCurrent(r->ctx, r->big, GL_UNSIGNED_BYTE, r->big_w, r->big_h)) return BALL_ENOMEM;
  ball_render_palette(&pal);

  glViewport(0, 0, r->big_w, r->big_h);
  glClearColor(pal.sky.r, pal.sky.g, pal.sky.b, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glMatrixMode(GL_PROJECTION);
  glLoadMatrixd(proj);
  glMatrixMode(GL_MODELVIEW);
  glLoadMatrixd(view);

  glShadeModel(GL_SMOOTH);
  glEnable(GL_NORMALIZE);
  glLightModelfv(GL_LIGHT_MODEL_AMBIENT, scene_ambient);
  glLightModeli(GL_LIGHT_MODEL_TWO_SIDE, GL_TRUE);
  glLightfv(GL_LIGHT0, GL_POSITION, light_dir); /* with the view loaded: fixed in the world */
  glLightfv(GL_LIGHT0, GL_DIFFUSE, light_diffuse);
  glLightfv(GL_LIGHT0, GL_AMBIENT, light_ambient);
  glEnable(GL_LIGHT0);
  glColorMaterial(GL_FRONT_AND_BACK, GL_AMBIENT_AND_DIFFUSE);
  glEnable(GL_COLOR_MATERIAL);
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  glDisable(GL_CULL_FACE);

  /* The floor and what lies on it, painted in order without the depth test:
   * the camera is above the floor and everything else stands on it, so it
   * covers the floor wherever the two overlap (and nothing z-fights). */
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_LIGHTING);
  draw_floor(m, &pal);
  ball_r = world_size(cam, r->height, f->ball, MIN_BALL_PIXELS);
  if (ball_r < m->radius) ball_r = m->radius;
  glEnable(GL_BLEND);
  colour(pal.net, pal.shadow_alpha); /* the shadow: straight below the ball, softer when it flies high */
  disc(ball_v3(f->ball.x, m->floor_level, f->ball.z), ball_v3(0.0, 1.0, 0.0), ball_r, 1);
  glDisable(GL_BLEND);

  /* The solid things, lit, with the depth test. */
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glEnable(GL_LIGHTING);
  for (i = 0; i < f->n_rackets; ++i) {
    const ball_render_racket *k = &f->rackets[i];
    if (!k->visible) continue;
    colour(pal.rackets[i], 1.0f);
    disc(k->center, unit(k->normal), m->rackets[i].radius, 1);
  }
  colour(pal.ball, 1.0f);
  sphere(f->ball, ball_r);

  /* Lines: racket rims, the trail, the markers. */
  glDisable(GL_LIGHTING);
  glLineWidth((GLfloat)SUPERSAMPLE * 1.5f);
  for (i = 0; i < f->n_rackets; ++i) {
    const ball_render_racket *k = &f->rackets[i];
    if (!k->visible) continue;
    colour(pal.net, 1.0f);
    disc(k->center, unit(k->normal), m->rackets[i].radius, 0);
  }
  if (f->n_trail > 1) {
    colour(pal.trail, 1.0f);
    glBegin(GL_LINE_STRIP);
    for (i = 0; i < f->n_trail; ++i) vertex(f->trail[i]);
    glEnd();
  }
  for (i = 0; i < f->n_events; ++i) draw_marker(m, &pal, cam, r->height, &f->events[i]);
  colour(pal.wall_edge, 1.0f);
  for (i = 0; i < m->n_walls; ++i) plane_outline(&m->walls[i]);
  if (m->has_net) {
    colour(pal.line, 1.0f);
    plane_outline(&m->net);
  }

  /* Last, the see-through net and walls, without writing depth. */
  glEnable(GL_LIGHTING);
  glEnable(GL_BLEND);
  glDepthMask(GL_FALSE);
  for (i = 0; i < m->n_walls; ++i) {
    colour(pal.wall, pal.wall_alpha);
    plane_rect(&m->walls[i], m->walls[i].bottom, m->walls[i].top);
  }
  if (m->has_net) {
    double tape = 0.06 * (m->net.top - m->net.bottom);
    colour(pal.net, pal.net_alpha);
    plane_rect(&m->net, m->net.bottom, m->net.top - tape);
    colour(pal.line, pal.tape_alpha);
    plane_rect(&m->net, m->net.top - tape, m->net.top);
  }
  glDepthMask(GL_TRUE);
  glDisable(GL_BLEND);
  glFinish();
  downsample(r);
  return BALL_OK;
}
