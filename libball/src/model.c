/* The model: its field table, defaults, checks, walls, hash. */
#include <stddef.h>
#include <string.h>

#include "internal.h"

/* ---- the field table ---------------------------------------------------- */

static const char *scheme_name(int v) { return ball_scheme_name((ball_scheme)v); }
static const char *detect_name(int v) { return ball_detect_name((ball_detect)v); }
static const char *normal_name(int v) { return ball_normal_mode_name((ball_normal_mode)v); }
static const char *response_name(int v) { return ball_response_name((ball_response)v); }
static const char *level_name(int v) { return ball_level_name((ball_level)v); }

#define INF HUGE_VAL
#define LO_OPEN BALL_FIELD_LO_OPEN
#define HI_OPEN BALL_FIELD_HI_OPEN
#define INF_OK BALL_FIELD_INF_OK
#define DRAG BALL_EFFECT_DRAG
#define SPIN BALL_EFFECT_SPIN
#define FLOOR BALL_EFFECT_FLOOR
#define NET BALL_EFFECT_NET
#define WALLS BALL_EFFECT_WALLS
#define RACKETS BALL_EFFECT_RACKETS
#define SOUND BALL_EFFECT_SOUND
#define INIT 0x80000000u /* read by ball_sim_init only */

/* name, key, type, struct, lo, hi, flags, stages, default x, y, z, unit, equation, range, doc */
#define F(name, key, type, st, lo, hi, flags, stages, d0, d1, d2, unit, eq, range, doc) \
  {#name, key, BALL_FIELD_##type, offsetof(st, name), lo, hi, flags, stages, {d0, d1, d2}, unit, eq, range, doc, NULL}
#define E(name, key, st, count, stages, d0, eq, doc, fn) \
  {#name, key, BALL_FIELD_ENUM, offsetof(st, name), 0, (count) - 1, 0, stages, {d0, 0, 0}, "", eq, "", doc, fn}

static const ball_field model_fields[] = {
    F(gravity, "gravity", REAL, ball_model, BALL_MIN_GRAVITY, BALL_MAX_GRAVITY, 0, 0, 9.81, 0, 0, "m/s^2",
      "eq 1", "in [1e-6, 1e6]", "g, acts along -y"),
    F(mass, "mass", REAL, ball_model, 0, INF, LO_OPEN, DRAG, 0.057, 0, 0, "kg", "eq 2", "> 0",
      "m, the ball's mass (a tennis ball); b = mass / air_friction"),
    F(air_friction, "air_friction", REAL, ball_model, 0, INF, 0, DRAG, 0.02, 0, 0, "kg/s", "eq 2",
      ">= 0", "beta; b = m / beta = 2.85 s by default"),
    F(radius, "radius", REAL, ball_model, 0, BALL_MAX_LENGTH, 0, 0, 0, 0, 0, "m", "", "in [0, 1e6]",
      "ball radius; 0 is the paper's point ball"),
    F(spin_damping, "spin_damping", REAL, ball_model, 0, INF, LO_OPEN, SPIN, 2.0, 0, 0, "s", "eq 4",
      "> 0", "sDamp: spinAirDamping = sDamp / (sDamp + t)"),
    F(floor_level, "floor.level", REAL, ball_model, -BALL_MAX_COORD, BALL_MAX_COORD, 0, FLOOR, 0, 0, 0, "m", "eq 5",
      "in [-1e9, 1e9]",
      "the floor is the plane y = level"),
    F(floor_damping, "floor.damping", REAL, ball_model, 0, 1, 0, FLOOR, 0.75, 0, 0, "1", "eq 5",
      "in [0, 1]", "floorDamping"),
    F(bounce_threshold, "floor.bounce_threshold", REAL, ball_model, 0, INF, 0, FLOOR, 0.3, 0, 0,
      "m/s", "eq 5", ">= 0", "a bounce leaving slower than this stops: the ball slides"),
    F(sound_threshold, "floor.sound_threshold", REAL, ball_model, 0, INF, INF_OK, SOUND, 0.5, 0, 0,
      "m/s", "eq 5", ">= 0", "a faster collision makes a sound"),
    F(spin_floor_damping, "floor.spin_damping", REAL, ball_model, 0, 1, 0, FLOOR, 0.8, 0, 0, "1",
      "eq 13, 14", "in [0, 1]", "spinFloorDamping"),
    F(has_net, "net", BOOL, ball_model, 0, 1, 0, NET, 1, 0, 0, "", "Fig. 3", "",
      "1: the net is in place (`net: none` in a scene file removes it)"),
    F(net, "net", PLANE, ball_model, 0, 0, 0, NET, 0, 0, 0, "", "Fig. 3, eq 6", "",
      "the net: a tennis net by default"),
    F(n_walls, "walls", INT, ball_model, 0, BALL_MAX_WALLS, 0, WALLS, 0, 0, 0, "", "", "in [0, 16]",
      "walls in use"),
    F(walls, "walls", PLANES, ball_model, 0, 0, 0, WALLS, 0, 0, 0, "", "Fig. 3, eq 6", "",
      "walls: the net's test and response on other rectangles"),
    F(n_rackets, "rackets", INT, ball_model, 0, BALL_MAX_RACKETS, 0, RACKETS, 0, 0, 0, "", "", "in [0, 4]",
      "rackets in use"),
    F(rackets, "rackets", RACKETS, ball_model, 0, 0, 0, RACKETS, 0, 0, 0, "", "Fig. 4", "",
      "racket discs"),
    E(detect, "racket.detect", ball_model, BALL_DETECT_COUNT, RACKETS, BALL_DETECT_DISC, "Fig. 4, 5",
      "collision test (swept: beyond the paper)", detect_name),
    E(normal_mode, "racket.normal", ball_model, BALL_NORMAL_COUNT, RACKETS, BALL_NORMAL_REAL,
      "section 3", "racket normal of the disc and swept tests", normal_name),
    E(response, "racket.response", ball_model, BALL_RESPONSE_COUNT, RACKETS, BALL_RESPONSE_PHYSICAL,
      "eq 7-14", "racket response: eq 7, eq 8-9, eq 10, eq 11-14", response_name),
    F(collision_distance, "racket.collision_distance", REAL, ball_model, 0, BALL_MAX_LENGTH, LO_OPEN, RACKETS,
      0.3, 0, 0, "m", "section 3", "in (0, 1e6]", "d_COLL of the sphere test"),
    F(sleep_frames, "racket.sleep_frames", INT, ball_model, 0, 1000000, 0, RACKETS, 3, 0, 0, "frames",
      "eq 7", "in [0, 1000000]", "no racket test for this many frames after a hit"),
    F(v_min, "racket.v_min", REAL, ball_model, 0, BALL_MAX_SPEED, 0, RACKETS, 5.0, 0, 0, "m/s", "eq 7",
      "in [0, 1e7]",
      "eq 7 speed clamp, lower end"),
    F(v_max, "racket.v_max", REAL, ball_model, 0, BALL_MAX_SPEED, 0, RACKETS, 40.0, 0, 0, "m/s", "eq 7",
      "in [v_min, 1e7]", "eq 7 speed clamp, upper end; every response reads the racket speed clamped to it"),
    F(v_up, "racket.v_up", REAL, ball_model, 0, BALL_MAX_SPEED, LO_OPEN, RACKETS, 4.0, 0, 0, "m/s", "eq 8",
      "in (0, 1e7]",
      "V_up, the autonomous ball's vertical launch speed"),
    F(v_up_from_racket, "racket.v_up_from_racket", BOOL, ball_model, 0, 1, 0, RACKETS, 0, 0, 0, "",
      "eq 8", "", "true: V_up is the racket's vertical speed (at least 1 m/s)"),
    F(friendly_factor, "racket.friendly_factor", REAL, ball_model, 0, 1000.0, 0, RACKETS, 1.0, 0, 0, "1",
      "eq 9, 10", "in [0, 1000], and <= 1 with response mixed (eq 10)", "friendlyFactor"),
    F(spin_rack_damping, "racket.spin_rack_damping", REAL, ball_model, 0, 1, 0, RACKETS, 0.8, 0, 0,
      "1", "eq 12", "in [0, 1]", "spinRackDamping"),
    F(history, "racket.history", INT, ball_model, 2, BALL_MAX_HISTORY, 0, RACKETS, 3, 0, 0, "samples",
      "section 2", "in [2, 16]", "racket samples kept (the paper's n)"),
    F(extrapolation_time, "racket.extrapolation_time", REAL, ball_model, 0, 1000.0, 0, RACKETS, 0, 0, 0,
      "s", "eq 15", "in [0, 1000]", "eq 15's extrapolationTime: the most a track looks past its newest sample"),
    F(stale_time, "racket.stale_time", REAL, ball_model, 0, 1e9, LO_OPEN, RACKETS, 1.0, 0, 0, "s", "",
      "in (0, 1e9]", "a racket silent this long does not collide"),
    F(effects, "effects", EFFECTS, ball_model, 0, 0, 0, 0,
      BALL_EFFECT_DRAG | BALL_EFFECT_SPIN | BALL_EFFECT_FLOOR | BALL_EFFECT_NET | BALL_EFFECT_SOUND, 0,
      0, "", "", "", "the effects that run (ball_effect bits)"),
    E(scheme, "scheme", ball_model, BALL_SCHEME_COUNT, 0, BALL_SCHEME_EXACT, "",
      "static obstacles: the paper's per-frame tests or closed-form contact times", scheme_name),
    E(level, "level", ball_model, BALL_LEVEL_COUNT, INIT, BALL_LEVEL_CUSTOM, "section 4",
      "the game level preset the model started from (informative)", level_name),
    F(initial_position, "ball.position", VEC3, ball_model, -BALL_MAX_COORD, BALL_MAX_COORD, 0, INIT, -0.5, 2.6,
      3.0, "m", "", "each in [-1e9, 1e9]; not below the floor (y >= floor.level + radius) while floor is on",
      "where the ball starts"),
    F(initial_velocity, "ball.velocity", VEC3, ball_model, -BALL_MAX_SPEED, BALL_MAX_SPEED, 0, INIT, 24.0, 0.0,
      1.2, "m/s", "", "each in [-1e7, 1e7]", "the ball's initial velocity: a serve over the default net"),
    F(initial_spin, "ball.spin", VEC3, ball_model, -BALL_MAX_SPEED, BALL_MAX_SPEED, 0, INIT, 0, 0, 0, "m/s",
      "eq 4", "each in [-1e7, 1e7]",
      "the ball's initial spin (a tangential speed: V x n)"),
};

static const ball_field plane_fields[] = {
    F(axis, "axis", AXIS, ball_plane, 0, 2, 0, 0, 0, 0, 0, "", "Fig. 3", "x or z",
      "x: the plane x = position, spanning z in [lo, hi]; z: the plane z = position, x in [lo, hi]"),
    F(position, "position", REAL, ball_plane, -BALL_MAX_COORD, BALL_MAX_COORD, 0, 0, 11.885, 0, 0, "m", "Fig. 3",
      "in [-1e9, 1e9]", "the plane's coordinate"),
    F(lo, "lo", REAL, ball_plane, -BALL_MAX_COORD, BALL_MAX_COORD, 0, 0, 0.0, 0, 0, "m", "Fig. 3", "< hi",
      "horizontal extent along the other axis, from"),
    F(hi, "hi", REAL, ball_plane, -BALL_MAX_COORD, BALL_MAX_COORD, 0, 0, 10.97, 0, 0, "m", "Fig. 3", "> lo",
      "horizontal extent along the other axis, to"),
    F(bottom, "bottom", REAL, ball_plane, -BALL_MAX_COORD, BALL_MAX_COORD, 0, 0, 0.0, 0, 0, "m", "Fig. 3", "< top",
      "vertical extent, from"),
    F(top, "top", REAL, ball_plane, -BALL_MAX_COORD, BALL_MAX_COORD, 0, 0, 0.914, 0, 0, "m", "Fig. 3", "> bottom",
      "vertical extent, to"),
    F(damping, "damping", REAL, ball_plane, 0, 1, 0, 0, 0.2, 0, 0, "1", "eq 6", "in [0, 1]", "netDamping"),
};

static const ball_field racket_fields[] = {
    F(radius, "radius", REAL, ball_racket_def, 0, BALL_MAX_LENGTH, LO_OPEN, 0, 0.15, 0, 0, "m", "Fig. 4",
      "in (0, 1e6]",
      "r_disc"),
    F(partner, "partner", INT, ball_racket_def, -1, BALL_MAX_RACKETS - 1, 0, 0, -1, 0, 0, "", "eq 8",
      "-1 (fly to target) or the index of another racket in the list", "the racket the autonomous ball flies to; -1: to target"),
    F(target, "target", VEC3, ball_racket_def, -BALL_MAX_COORD, BALL_MAX_COORD, 0, 0, 20.0, 0.0, 5.485, "m",
      "eq 8", "each in [-1e9, 1e9]",
      "goal point when partner is -1 (its y is ignored)"),
    F(goal_reach, "goal_reach", REAL, ball_racket_def, 0, BALL_MAX_COORD, 0, 0, BALL_MAX_COORD, 0, 0, "m", "eq 8",
      "in [0, 1e9]",
      "the partner's racket as the autonomous goal, moved to within this horizontal distance of target"),
};

#define COUNT(a) ((int)(sizeof(a) / sizeof((a)[0])))
#define N_PLANE_FIELDS 7
#define N_RACKET_FIELDS 4

const ball_field *ball_model_fields(int *count) {
  if (count) *count = COUNT(model_fields);
  return model_fields;
}
const ball_field *ball_plane_fields(int *count) {
  if (count) *count = COUNT(plane_fields);
  return plane_fields;
}
const ball_field *ball_racket_fields(int *count) {
  if (count) *count = COUNT(racket_fields);
  return racket_fields;
}

/* ---- defaults ---- */

static void set_defaults(void *base, const ball_field *f, int n);

static void set_default(void *base, const ball_field *f) {
  char *p = (char *)base + f->offset;
  int i;
  switch (f->type) {
    case BALL_FIELD_REAL: *(double *)p = f->def[0]; break;
    case BALL_FIELD_INT:
    case BALL_FIELD_BOOL:
    case BALL_FIELD_AXIS: *(int *)p = (int)f->def[0]; break;
    case BALL_FIELD_ENUM: *(int *)p = (int)f->def[0]; break;
    case BALL_FIELD_EFFECTS: *(unsigned *)p = (unsigned)f->def[0]; break;
    case BALL_FIELD_VEC3: *(ball_vec3 *)p = ball_v3(f->def[0], f->def[1], f->def[2]); break;
    case BALL_FIELD_PLANE: set_defaults(p, plane_fields, COUNT(plane_fields)); break;
    case BALL_FIELD_PLANES: break; /* no walls by default */
    case BALL_FIELD_RACKETS:
      for (i = 0; i < BALL_MAX_RACKETS; i++)
        set_defaults(p + (size_t)i * sizeof(ball_racket_def), racket_fields, COUNT(racket_fields));
      break;
    case BALL_FIELD_TYPE_COUNT: break;
  }
}

static void set_defaults(void *base, const ball_field *f, int n) {
  int i;
  for (i = 0; i < n; i++) set_default(base, &f[i]);
}

void ball_model_default(ball_model *m) {
  if (!m) return;
  memset(m, 0, sizeof *m); /* padding too: the sim compares models byte for byte */
  set_defaults(m, model_fields, COUNT(model_fields));
}

/* ---- checks ---- */

/* Field names with their index, for *field: static strings, no buffer. */
#define PLANE_NAMES(p) \
  {p "axis", p "position", p "lo", p "hi", p "bottom", p "top", p "damping"}
static const char *const net_names[N_PLANE_FIELDS] = PLANE_NAMES("net.");
static const char *const wall_names[BALL_MAX_WALLS][N_PLANE_FIELDS] = {
    PLANE_NAMES("walls[0]."),  PLANE_NAMES("walls[1]."),  PLANE_NAMES("walls[2]."),
    PLANE_NAMES("walls[3]."),  PLANE_NAMES("walls[4]."),  PLANE_NAMES("walls[5]."),
    PLANE_NAMES("walls[6]."),  PLANE_NAMES("walls[7]."),  PLANE_NAMES("walls[8]."),
    PLANE_NAMES("walls[9]."),  PLANE_NAMES("walls[10]."), PLANE_NAMES("walls[11]."),
    PLANE_NAMES("walls[12]."), PLANE_NAMES("walls[13]."), PLANE_NAMES("walls[14]."),
    PLANE_NAMES("walls[15].")};
#define RACKET_NAMES(p) {p "radius", p "partner", p "target", p "goal_reach"}
static const char *const racket_names[BALL_MAX_RACKETS][N_RACKET_FIELDS] = {
    RACKET_NAMES("rackets[0]."), RACKET_NAMES("rackets[1]."), RACKET_NAMES("rackets[2]."),
    RACKET_NAMES("rackets[3].")};

static int in_range(const ball_field *f, double v) {
  if (f->flags & LO_OPEN ? !(v > f->lo) : !(v >= f->lo)) return 0;
  if (f->flags & HI_OPEN ? !(v < f->hi) : !(v <= f->hi)) return 0;
  return 1;
}

/* One scalar or vector field at base against its table entry. */
static ball_status check_value(const void *base, const ball_field *f) {
  const char *p = (const char *)base + f->offset;
  double v;
  int k;
  switch (f->type) {
    case BALL_FIELD_REAL:
      v = *(const double *)p;
      if (isnan(v) || (isinf(v) && !(f->flags & INF_OK && v > 0.0))) return BALL_ENONFINITE;
      return in_range(f, v) ? BALL_OK : BALL_ERANGE;
    case BALL_FIELD_INT:
      return in_range(f, (double)*(const int *)p) ? BALL_OK : BALL_ERANGE;
    case BALL_FIELD_BOOL:
      k = *(const int *)p;
      return k == 0 || k == 1 ? BALL_OK : BALL_ERANGE;
    case BALL_FIELD_ENUM:
      k = *(const int *)p;
      return k >= 0 && k <= (int)f->hi ? BALL_OK : BALL_ERANGE;
    case BALL_FIELD_AXIS:
      k = *(const int *)p;
      return k == 0 || k == 2 ? BALL_OK : BALL_ERANGE;
    case BALL_FIELD_EFFECTS:
      return (*(const unsigned *)p & ~(unsigned)BALL_EFFECT_ALL) == 0 ? BALL_OK : BALL_ERANGE;
    case BALL_FIELD_VEC3: {
      const ball_vec3 *w = (const ball_vec3 *)p;
      if (!ball_v3_finite(*w)) return BALL_ENONFINITE;
      return in_range(f, w->x) && in_range(f, w->y) && in_range(f, w->z) ? BALL_OK : BALL_ERANGE;
    }
    default:
      return BALL_OK; /* containers are checked member by member */
  }
}

/* Checks a plane; names[] are the names to report for its members. */
static ball_status check_plane(const ball_plane *p, const char *const *names, const char **field) {
  ball_status st;
  int i;
  for (i = 0; i < N_PLANE_FIELDS; i++) {
    st = check_value(p, &plane_fields[i]);
    CHECK(st == BALL_OK, names[i], st);
  }
  CHECK(p->lo < p->hi, names[3], BALL_ERANGE);
  CHECK(p->bottom < p->top, names[5], BALL_ERANGE);
  return BALL_OK;
}

ball_status ball_plane_check(const ball_plane *p, const char **field) {
  static const char *const bare[N_PLANE_FIELDS] = PLANE_NAMES("");
  CHECK(p != NULL, "plane", BALL_EINVAL);
  return check_plane(p, bare, field);
}

static ball_status check_rackets(const ball_model *m, const char **field) {
  ball_status st;
  int i, j;
  for (i = 0; i < m->n_rackets; i++) {
    const ball_racket_def *r = &m->rackets[i];
    for (j = 0; j < N_RACKET_FIELDS; j++) {
      st = check_value(r, &racket_fields[j]);
      CHECK(st == BALL_OK, racket_names[i][j], st);
    }
    CHECK(r->partner < m->n_rackets && r->partner != i, racket_names[i][1], BALL_ERANGE);
  }
  return BALL_OK;
}

ball_status ball_model_check(const ball_model *m, const char **field) {
  ball_status st;
  int i, j;
  CHECK(m != NULL, "model", BALL_EINVAL);
  for (i = 0; i < COUNT(model_fields); i++) {
    const ball_field *f = &model_fields[i];
    if (f->type == BALL_FIELD_PLANE) {
      st = check_plane(&m->net, net_names, field);
    } else if (f->type == BALL_FIELD_PLANES) {
      for (j = 0, st = BALL_OK; st == BALL_OK && j < m->n_walls; j++)
        st = check_plane(&m->walls[j], wall_names[j], field);
    } else if (f->type == BALL_FIELD_RACKETS) {
      st = check_rackets(m, field);
    } else {
      st = check_value(m, f);
      CHECK(st == BALL_OK, f->name, st);
    }
    if (st != BALL_OK) return st;
  }
  /* what one field's range cannot say */
  CHECK(m->v_max >= m->v_min, "v_max", BALL_ERANGE);
  CHECK(m->response != BALL_RESPONSE_MIXED || m->friendly_factor <= 1.0, "friendly_factor",
        BALL_ERANGE); /* eq 10: friendlyFactor in [0, 1] */
  if (ball__has(m, BALL_EFFECT_FLOOR))
    CHECK(m->initial_position.y >= ball__floor_y(m), "initial_position", BALL_ERANGE);
  return BALL_OK;
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

/* ---- the model's hash (portable) and the sim's binding ---- */

/* One 64-bit word into the hash: h = (h xor w) * FNV prime, then the high
 * half folded into the low one. Integer arithmetic on values, not bytes in
 * memory: the same on every machine whatever its byte order. */
uint64_t ball__hash_word(uint64_t h, uint64_t w) {
  h = (h ^ w) * 1099511628211ULL;
  return h ^ (h >> 29);
}

uint64_t ball__hash_double(uint64_t h, double v) {
  uint64_t w;
  if (v == 0.0) v = 0.0; /* -0 and +0 hash alike */
  memcpy(&w, &v, sizeof w);
  return ball__hash_word(h, w);
}

uint64_t ball__hash_vec(uint64_t h, ball_vec3 v) {
  return ball__hash_double(ball__hash_double(ball__hash_double(h, v.x), v.y), v.z);
}

static uint64_t hash_fields(uint64_t h, const void *base, const ball_field *f, int n, unsigned stages) {
  int i, j;
  for (i = 0; i < n; i++, f++) {
    const char *p = (const char *)base + f->offset;
    if (f->stages & INIT || (f->stages && !(f->stages & stages))) continue;
    switch (f->type) {
      case BALL_FIELD_REAL: h = ball__hash_double(h, *(const double *)p); break;
      case BALL_FIELD_INT:
      case BALL_FIELD_BOOL:
      case BALL_FIELD_ENUM:
      case BALL_FIELD_AXIS: h = ball__hash_word(h, (uint64_t)(int64_t) * (const int *)p); break;
      case BALL_FIELD_EFFECTS: h = ball__hash_word(h, *(const unsigned *)p); break;
      case BALL_FIELD_VEC3: h = ball__hash_vec(h, *(const ball_vec3 *)p); break;
      case BALL_FIELD_PLANE: h = hash_fields(h, p, plane_fields, COUNT(plane_fields), stages); break;
      case BALL_FIELD_PLANES: {
        const ball_model *m = (const ball_model *)base;
        for (j = 0; j < m->n_walls && j < BALL_MAX_WALLS; j++)
          h = hash_fields(h, &m->walls[j], plane_fields, COUNT(plane_fields), stages);
        break;
      }
      case BALL_FIELD_RACKETS: {
        const ball_model *m = (const ball_model *)base;
        for (j = 0; j < m->n_rackets && j < BALL_MAX_RACKETS; j++)
          h = hash_fields(h, &m->rackets[j], racket_fields, COUNT(racket_fields), stages);
        break;
      }
      case BALL_FIELD_TYPE_COUNT: break;
    }
  }
  return h;
}

uint64_t ball_model_hash(const ball_model *m) {
  if (!m) return 0;
  return hash_fields(BALL__HASH_SEED, m, model_fields, COUNT(model_fields), m->effects);
}
