/* The model: defaults, checks, walls. */
#include <string.h>

#include "internal.h"

void ball_model_default(ball_model *m) {
  int i;
  if (!m) return;
  memset(m, 0, sizeof *m);
  m->gravity = 9.81;
  m->mass = 0.057;          /* tennis ball */
  m->air_friction = 0.02;   /* b = m / beta = 2.85 s */
  m->radius = 0.0;          /* the paper's point ball */
  m->spin_damping = 2.0;
  m->floor_level = 0.0;
  m->floor_damping = 0.75;
  m->bounce_threshold = 0.3;
  m->sound_threshold = 0.5;
  m->spin_floor_damping = 0.8;
  /* tennis court: baseline at x = 0, 23.77 m long, 10.97 m wide (doubles) */
  m->has_net = 1;
  m->net.axis = 0;
  m->net.position = 11.885;
  m->net.lo = 0.0;
  m->net.hi = 10.97;
  m->net.bottom = 0.0;
  m->net.top = 0.914;
  m->net.damping = 0.2;
  m->n_walls = 0;
  m->n_rackets = 0;
  for (i = 0; i < BALL_MAX_RACKETS; i++) {
    m->rackets[i].radius = 0.15;
    m->rackets[i].partner = -1;
    m->rackets[i].target = v3(20.0, 0.0, 5.485);
  }
  m->detect = BALL_DETECT_DISC;
  m->normal_mode = BALL_NORMAL_REAL;
  m->response = BALL_RESPONSE_PHYSICAL;
  m->collision_distance = 0.3;
  m->sleep_frames = 3;
  m->v_min = 5.0;
  m->v_max = 40.0;
  m->v_up = 4.0;
  m->v_up_from_racket = 0;
  m->friendly_factor = 1.0;
  m->spin_rack_damping = 0.8;
  m->history = 3;
  m->extrapolation_time = 0.0;
  m->stale_time = 1.0;
  m->frame_time = 1.0 / 60.0;
  m->time_base = 1.0;
  m->effects = BALL_EFFECT_DRAG | BALL_EFFECT_SPIN | BALL_EFFECT_FLOOR | BALL_EFFECT_NET |
               BALL_EFFECT_SOUND;
  m->scheme = BALL_SCHEME_EXACT;
  m->level = BALL_LEVEL_CUSTOM;
  /* a serve from behind the baseline that clears the net */
  m->initial_position = v3(-0.5, 2.6, 3.0);
  m->initial_velocity = v3(24.0, 0.0, 1.2);
  m->initial_spin = v3(0.0, 0.0, 0.0);
}

#define CHECK_UNIT(value, name) \
  CHECK_FINITE(value, name);    \
  CHECK((value) >= 0.0 && (value) <= 1.0, name, BALL_ERANGE)

ball_status ball_plane_check(const ball_plane *p, const char **field) {
  CHECK(p != NULL, "plane", BALL_EINVAL);
  CHECK(p->axis == 0 || p->axis == 2, "axis", BALL_ERANGE);
  CHECK_FINITE(p->position, "position");
  CHECK_FINITE(p->lo, "lo");
  CHECK_FINITE(p->hi, "hi");
  CHECK_FINITE(p->bottom, "bottom");
  CHECK_FINITE(p->top, "top");
  CHECK(p->lo < p->hi, "hi", BALL_ERANGE);
  CHECK(p->bottom < p->top, "top", BALL_ERANGE);
  CHECK_UNIT(p->damping, "damping");
  return BALL_OK;
}

/* "lo" -> "net.lo": static names, so *field needs no buffer. */
static const char *net_field(const char *sub) {
  static const char *const names[][2] = {{"axis", "net.axis"}, {"position", "net.position"},
                                         {"lo", "net.lo"},     {"hi", "net.hi"},
                                         {"bottom", "net.bottom"}, {"top", "net.top"},
                                         {"damping", "net.damping"}};
  size_t i;
  for (i = 0; i < sizeof names / sizeof names[0]; i++)
    if (!strcmp(sub, names[i][0])) return names[i][1];
  return "net";
}

static ball_status check_vec(ball_vec3 v, const char *name, const char **field) {
  CHECK(v3_finite(v), name, BALL_ENONFINITE);
  return BALL_OK;
}

/* Checks the fields every stage reads, and those of the stages in `stages`
 * (effect bits): the stepper checks only what it will use, so a disabled
 * effect costs nothing. */
ball_status ball__model_check_stages(const ball_model *m, unsigned stages, const char **field) {
  ball_status st;
  const char *sub = NULL;
  int i;
  CHECK(m != NULL, "model", BALL_EINVAL);
  CHECK_FINITE(m->gravity, "gravity");
  CHECK(m->gravity > 0.0, "gravity", BALL_ERANGE);
  CHECK_FINITE(m->mass, "mass");
  CHECK(m->mass > 0.0, "mass", BALL_ERANGE);
  CHECK_FINITE(m->air_friction, "air_friction");
  CHECK(m->air_friction >= 0.0, "air_friction", BALL_ERANGE);
  CHECK_FINITE(m->radius, "radius");
  CHECK(m->radius >= 0.0, "radius", BALL_ERANGE);
  CHECK_FINITE(m->spin_damping, "spin_damping");
  CHECK(m->spin_damping > 0.0, "spin_damping", BALL_ERANGE);
  CHECK_FINITE(m->floor_level, "floor_level");
  CHECK_UNIT(m->floor_damping, "floor_damping");
  CHECK_FINITE(m->bounce_threshold, "bounce_threshold");
  CHECK(m->bounce_threshold >= 0.0, "bounce_threshold", BALL_ERANGE);
  CHECK(!isnan(m->sound_threshold), "sound_threshold", BALL_ENONFINITE);
  CHECK(m->sound_threshold >= 0.0, "sound_threshold", BALL_ERANGE);
  CHECK_UNIT(m->spin_floor_damping, "spin_floor_damping");
  CHECK(m->has_net == 0 || m->has_net == 1, "has_net", BALL_ERANGE);
  if (m->has_net && (stages & BALL_EFFECT_NET)) {
    st = ball_plane_check(&m->net, &sub);
    if (st != BALL_OK) {
      if (field) *field = net_field(sub);
      return st;
    }
  }
  CHECK(m->n_walls >= 0 && m->n_walls <= BALL_MAX_WALLS, "n_walls", BALL_ERANGE);
  for (i = 0; (stages & BALL_EFFECT_WALLS) && i < m->n_walls; i++) {
    st = ball_plane_check(&m->walls[i], &sub);
    CHECK(st == BALL_OK, "walls", st);
  }
  if (stages & BALL_EFFECT_RACKETS) {
    st = ball__racket_check(m, field);
    if (st != BALL_OK) return st;
  }
  CHECK_FINITE(m->frame_time, "frame_time");
  CHECK(m->frame_time > 0.0, "frame_time", BALL_ERANGE);
  CHECK_FINITE(m->time_base, "time_base");
  CHECK(m->time_base > 0.0, "time_base", BALL_ERANGE);
  CHECK((m->effects & ~(unsigned)BALL_EFFECT_ALL) == 0, "effects", BALL_ERANGE);
  CHECK((unsigned)m->scheme < BALL_SCHEME_COUNT, "scheme", BALL_ERANGE);
  CHECK((unsigned)m->level < BALL_LEVEL_COUNT, "level", BALL_ERANGE);
  st = check_vec(m->initial_position, "initial_position", field);
  if (st != BALL_OK) return st;
  st = check_vec(m->initial_velocity, "initial_velocity", field);
  if (st != BALL_OK) return st;
  st = check_vec(m->initial_spin, "initial_spin", field);
  if (st != BALL_OK) return st;
  if (ball__has(m, BALL_EFFECT_FLOOR))
    CHECK(m->initial_position.y >= ball__floor_y(m), "initial_position", BALL_ERANGE);
  return BALL_OK;
}

ball_status ball_model_check(const ball_model *m, const char **field) {
  return ball__model_check_stages(m, BALL_EFFECT_ALL, field);
}

ball_status ball_model_add_wall(ball_model *m, const ball_plane *wall) {
  ball_status st;
  if (!m || !wall) return BALL_EINVAL;
  st = ball_plane_check(wall, NULL);
  if (st != BALL_OK) return st;
  if (m->n_walls < 0 || m->n_walls >= BALL_MAX_WALLS) return BALL_ENOSPACE;
  m->walls[m->n_walls++] = *wall;
  return BALL_OK;
}
