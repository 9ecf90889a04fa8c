/* libball: the ball animation model of Noser, Stern, Stucki and Thalmann,
 * "Generic 3D Ball Animation Model for Networked Interactive VR Environments".
 * Equation numbers (eq N) and figures (Fig. N) are the paper's.
 *
 * Axes: y up, gravity (0, -g, 0), floor y = floor_level. SI units throughout.
 * The library never prints, aborts or exits, never allocates inside a step and
 * keeps no global state: every call returns a ball_status, and a call that
 * fails leaves the objects it was given exactly as they were.
 *
 * The one rule of the model and the sim (after Box2D's world definition):
 * a ball_model is a definition, checked once and copied into the sim by
 * ball_sim_init. From then on the sim owns its model: every call on a sim
 * takes the sim as its first argument and no model (ball_step,
 * ball_racket_push, ball_sim_state, ...), reads the model with
 * ball_sim_model, and changes it only with ball_sim_set_model, which checks
 * the new one. Nothing is compared or checked per frame. The stateless
 * queries (ball_segment_eval, ball_flight_*, ball_time_to_*, ball_predict,
 * ...) take the model they work with; pass ball_sim_model(sim) for a sim's. */
#ifndef BALL_BALL_H
#define BALL_BALL_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#if defined(_WIN32)
#define BALL_API
#elif defined(__GNUC__)
#define BALL_API __attribute__((visibility("default")))
#else
#define BALL_API
#endif

/* The library's version, stated here only (the build reads it from this
 * header); CHANGELOG.md says what each version changed. */
#define BALL_VERSION_MAJOR 0
#define BALL_VERSION_MINOR 2
#define BALL_VERSION_PATCH 0

#define BALL_MAX_WALLS 16     /* walls per scene, besides the net */
#define BALL_MAX_RACKETS 4    /* rackets per scene (doubles) */
#define BALL_MAX_HISTORY 16   /* racket samples a track can keep (the paper's n) */
#define BALL_MAX_CONTACTS 64  /* exact-mode contacts resolved in one step */

/* The world the library handles (docs/scenes.md, "Ranges"): every range
 * ball_model_check accepts is one the stepper computes in without overflow. */
#define BALL_MAX_COORD 1e9    /* m: |coordinate| of a position, a plane, a target, a racket sample */
#define BALL_MAX_LENGTH 1e6   /* m: a radius (of the ball, a racket, the sphere test) */
#define BALL_MAX_SPEED 1e7    /* m/s: |component| of a velocity or a spin given to the library */
#define BALL_MIN_GRAVITY 1e-6 /* m/s^2 */
#define BALL_MAX_GRAVITY 1e6  /* m/s^2 */

/* ---- status ---------------------------------------------------------- */

typedef enum ball_status {
  BALL_OK = 0,
  BALL_EINVAL,      /* a NULL pointer or an argument of the wrong kind */
  BALL_ENONFINITE,  /* NaN or Inf where a finite number is needed */
  BALL_ERANGE,      /* a finite value outside its allowed range */
  BALL_ENOTFOUND,   /* no solution: the ball never gets there */
  BALL_ESTALE,      /* a racket sample older than the newest one kept */
  BALL_ENOSPACE,    /* no room left (rackets, walls, samples) */
  BALL_EPARSE,      /* a scene file that is not valid */
  BALL_EIO,         /* a file that cannot be read */
  BALL_ENOMEM,      /* an allocation failed (scene loader only) */
  BALL_EDUPLICATE,  /* a racket sample identical to one already kept: ignored */
  /* the client library's (ball/net.h) */
  BALL_ENOMATCH,    /* a match the client does not follow, or holds no slot of */
  BALL_EAGAIN,      /* not yet: the server has not said enough (no clock, segment or model) */
  BALL_ENETWORK,    /* the network refused: a DDS entity could not be made, a write was refused */
  BALL_ECLOSED,     /* the client is closed */
  BALL_STATUS_COUNT
} ball_status;

/* A constant English sentence for a status; never NULL. */
BALL_API const char *ball_strerror(ball_status status);

/* ---- basic types ------------------------------------------------------ */

typedef struct ball_vec3 {
  double x, y, z;
} ball_vec3;

/* Effects a scene asks for; the stepper runs only those stages. */
typedef enum ball_effect {
  BALL_EFFECT_DRAG = 1u << 0,     /* air friction beta (eq 2) */
  BALL_EFFECT_SPIN = 1u << 1,     /* spin, its damping and its effect on bounces (eq 4, 11-14) */
  BALL_EFFECT_FLOOR = 1u << 2,    /* floor bounce (eq 5) */
  BALL_EFFECT_NET = 1u << 3,      /* the net (Fig. 3, eq 6) */
  BALL_EFFECT_WALLS = 1u << 4,    /* walls (Fig. 3 on other planes) */
  BALL_EFFECT_RACKETS = 1u << 5,  /* racket collisions (Fig. 4-9, eq 7-14) */
  BALL_EFFECT_SOUND = 1u << 6,    /* sound flags on events */
  BALL_EFFECT_ALL = (1u << 7) - 1u
} ball_effect;

/* How contacts with static obstacles are found. */
typedef enum ball_scheme {
  BALL_SCHEME_SAMPLED = 0,  /* the paper's per-frame tests, as written */
  BALL_SCHEME_EXACT,        /* contact times in closed form on the analytic path */
  BALL_SCHEME_COUNT
} ball_scheme;

/* A rectangle on an axis-aligned vertical plane: the net or a wall.
 * axis 0: the plane x = position, spanning z in [lo, hi];
 * axis 2: the plane z = position, spanning x in [lo, hi];
 * both span y in [bottom, top]. */
typedef struct ball_plane {
  int axis;           /* 0 (x plane) or 2 (z plane) */
  double position;    /* plane coordinate, m */
  double lo, hi;      /* horizontal extent along the other axis, m (lo < hi) */
  double bottom, top; /* vertical extent, m (bottom < top) */
  double damping;     /* netDamping of eq 6, non-dimensional, [0, 1] */
} ball_plane;

/* ---- rackets (Fig. 4-9, eq 7-15) ------------------------------------- */

typedef enum ball_detect {
  BALL_DETECT_SPHERE = 0,  /* distance to the racket centre below collision_distance */
  BALL_DETECT_DISC,        /* the paper's disc test in the racket's moving frame (Fig. 4/5) */
  BALL_DETECT_SWEPT,       /* ball against the disc moving between samples, exact time of impact */
  BALL_DETECT_COUNT
} ball_detect;

typedef enum ball_normal_mode {
  BALL_NORMAL_REAL = 0,    /* the racket's tracked orientation */
  BALL_NORMAL_VELOCITY,    /* along the racket velocity (the real normal while still) */
  BALL_NORMAL_COUNT
} ball_normal_mode;

typedef enum ball_response {
  BALL_RESPONSE_RACKET = 0,  /* eq 7: racket velocity direction, clamped speed */
  BALL_RESPONSE_AUTONOMOUS,  /* eq 8, 9: flies to the partner ("friendly" ball) */
  BALL_RESPONSE_MIXED,       /* eq 10 */
  BALL_RESPONSE_PHYSICAL,    /* eq 11-14, with spin */
  BALL_RESPONSE_COUNT
} ball_response;

typedef enum ball_level {
  BALL_LEVEL_CUSTOM = 0,
  BALL_LEVEL_EASY,      /* sphere test, autonomous, friendly factor 1 */
  BALL_LEVEL_MID,       /* disc test with velocity normal, mixed 0.8 */
  BALL_LEVEL_ADVANCED,  /* disc test with real normal, physical with spin */
  BALL_LEVEL_COUNT
} ball_level;

typedef struct ball_racket_def {
  double radius;      /* r_disc, m */
  int partner;        /* racket the autonomous ball flies to; -1: fly to target */
  ball_vec3 target;   /* goal point when partner is -1 (its y is ignored: eq 8), m */
  double goal_reach;  /* the partner's racket as the goal, but no farther than this from target
                         horizontally (a partner off the court gets a ball in it), m */
} ball_racket_def;

/* One tracker or network sample of a racket. */
typedef struct ball_racket_sample {
  double t;           /* sample time on the sim clock, s */
  ball_vec3 center;   /* disc centre, m */
  ball_vec3 normal;   /* disc normal; normalised on entry (must not be ~0) */
} ball_racket_sample;

/* What a track estimates at a time (interpolated or extrapolated, eq 15). */
typedef struct ball_racket_pose {
  ball_vec3 center;    /* m */
  ball_vec3 normal;    /* unit */
  ball_vec3 velocity;  /* m/s */
} ball_racket_pose;

/* ---- the model -------------------------------------------------------- */

typedef struct ball_model {
  /* dynamics (section 2) */
  double gravity;             /* g, m/s^2, acts along -y (> 0) */
  double mass;                /* m, kg (> 0) */
  double air_friction;        /* beta, kg/s (>= 0); b = m / beta (eq 2) */
  double radius;              /* ball radius, m (>= 0; 0 is the paper's point ball) */
  double spin_damping;        /* sDamp of eq 4, s (> 0) */
  /* floor (eq 5) */
  double floor_level;         /* m */
  double floor_damping;       /* floorDamping, [0, 1] */
  double bounce_threshold;    /* below this vertical speed after a bounce the ball slides, m/s */
  double sound_threshold;     /* above this vertical speed a bounce makes a sound, m/s */
  double spin_floor_damping;  /* spinFloorDamping of eq 13, 14, [0, 1] */
  /* net and walls (Fig. 3, eq 6) */
  int has_net;                /* 0 or 1 */
  int n_walls;                /* walls in use (walls[] below), [0, BALL_MAX_WALLS] */
  ball_plane net;             /* the net; damping is netDamping */
  /* rackets (section 3, 3.1) */
  int n_rackets;                              /* rackets in use (rackets[] below), [0, BALL_MAX_RACKETS] */
  ball_detect detect;                         /* racket collision test */
  ball_normal_mode normal_mode;               /* racket normal for the disc and swept tests */
  ball_response response;                     /* racket response */
  double collision_distance;                  /* d_COLL of the sphere test, m (> 0) */
  double v_min, v_max;                        /* eq 7 speed clamp, m/s (0 <= v_min <= v_max); every
                                                 response reads the racket speed clamped to v_max */
  double v_up;                                /* eq 8 vertical launch speed, m/s (> 0) */
  double friendly_factor;                     /* eq 9, 10, >= 0 (eq 10 uses [0, 1]) */
  double spin_rack_damping;                   /* eq 12, [0, 1] */
  double extrapolation_time;                  /* eq 15, s (>= 0) */
  double stale_time;                          /* a racket silent this long does not collide, s (> 0) */
  int sleep_frames;                           /* frames without racket tests after a hit, >= 0 */
  int v_up_from_racket;                       /* 1: V_up = the racket's vertical speed (at least 1 m/s) */
  int history;                                /* racket samples kept, the paper's n, [2, BALL_MAX_HISTORY] */
  /* what to simulate and how */
  unsigned effects;           /* ball_effect bits */
  ball_scheme scheme;         /* static obstacle detection */
  ball_level level;           /* the preset this model started from (informative) */
  /* initial state */
  ball_vec3 initial_position; /* m */
  ball_vec3 initial_velocity; /* m/s */
  ball_vec3 initial_spin;     /* m/s (the paper's spin is a tangential speed: V x n) */
  /* the obstacles in use are the first n_walls and n_rackets of these */
  ball_plane walls[BALL_MAX_WALLS];
  ball_racket_def rackets[BALL_MAX_RACKETS];
} ball_model;

/* Defaults: a tennis ball over a tennis court (23.77 m x 10.97 m, net at
 * x = 11.885 m, 0.914 m high), exact scheme, every effect but rackets. */
BALL_API void ball_model_default(ball_model *model);

/* Checks every field; on failure *field (if not NULL) names the first bad
 * one, with its index where it has one: "floor_damping", "net.lo",
 * "walls[3].lo", "rackets[1].radius". */
BALL_API ball_status ball_model_check(const ball_model *model, const char **field);

/* Applies a game level preset (section 4) over the racket fields of model. */
BALL_API ball_status ball_model_set_level(ball_model *model, ball_level level);

/* Checks one net or wall rectangle; *field names the bad member ("lo", ...). */
BALL_API ball_status ball_plane_check(const ball_plane *plane, const char **field);

/* Adds a wall; BALL_ENOSPACE when full, BALL_ERANGE/BALL_ENONFINITE on a bad plane. */
BALL_API ball_status ball_model_add_wall(ball_model *model, const ball_plane *wall);

/* Names of the enums, for files and messages ("sampled", "exact", ...). */
BALL_API const char *ball_scheme_name(ball_scheme scheme);
BALL_API const char *ball_detect_name(ball_detect detect);
BALL_API const char *ball_normal_mode_name(ball_normal_mode mode);
BALL_API const char *ball_response_name(ball_response response);
BALL_API const char *ball_level_name(ball_level level);
BALL_API const char *ball_effect_name(ball_effect effect); /* a single bit */

/* ---- the field table ---------------------------------------------------- */

/* Every field of ball_model, ball_plane and ball_racket_def once: its name,
 * its key in a scene file, its type, range, default, unit and equation.
 * ball_model_default, ball_model_check, the scene loader and the docs' key
 * table are all made from it. */
typedef enum ball_field_type {
  BALL_FIELD_REAL = 0,  /* double */
  BALL_FIELD_INT,       /* int */
  BALL_FIELD_BOOL,      /* int, 0 or 1 */
  BALL_FIELD_ENUM,      /* an enum held as int: 0 .. hi, named by ball_field.enum_name */
  BALL_FIELD_AXIS,      /* int: 0 (the plane x = position) or 2 (z = position) */
  BALL_FIELD_EFFECTS,   /* unsigned: ball_effect bits */
  BALL_FIELD_VEC3,      /* ball_vec3, every component finite */
  BALL_FIELD_PLANE,     /* a ball_plane (the net): see ball_plane_fields */
  BALL_FIELD_PLANES,    /* the walls: ball_plane[BALL_MAX_WALLS], n_walls in use */
  BALL_FIELD_RACKETS,   /* the rackets: ball_racket_def[BALL_MAX_RACKETS], n_rackets in use */
  BALL_FIELD_TYPE_COUNT
} ball_field_type;

#define BALL_FIELD_LO_OPEN 1u  /* the range excludes lo */
#define BALL_FIELD_HI_OPEN 2u  /* the range excludes hi */
#define BALL_FIELD_INF_OK 4u   /* +Inf is allowed (it is hi) */

typedef struct ball_field {
  const char *name;      /* member name: "floor_damping" */
  const char *key;       /* scene file key: "floor.damping"; relative for plane and racket members */
  ball_field_type type;
  size_t offset;         /* offsetof the member in its struct */
  double lo, hi;         /* range of REAL and INT (hi of ENUM: the last value) */
  unsigned flags;        /* BALL_FIELD_* */
  unsigned stages;       /* effect bits of the stages that read it; 0: every step reads it */
  double def[3];         /* default (vectors: x, y, z); planes: the default net's */
  const char *unit;      /* "m/s^2", "1" (non-dimensional), "" (none) */
  const char *equation;  /* "eq 5", "Fig. 3", "" */
  const char *range;     /* the range in words: "> 0", "[0, 1]" */
  const char *doc;       /* one line */
  const char *(*enum_name)(int value); /* ENUM: the value's name */
} ball_field;

/* The fields of ball_model (in the order of the docs' key table, by
 * section), of a ball_plane (net, walls) and of a ball_racket_def; *count
 * gets how many. Never NULL. */
BALL_API const ball_field *ball_model_fields(int *count);
BALL_API const ball_field *ball_plane_fields(int *count);
BALL_API const ball_field *ball_racket_fields(int *count);

/* ---- flight segments and prediction (eq 3, 4) ------------------------ */

/* A flight segment: the paper's initial state after a collision ("time reset
 * to zero"), valid from t0 until the next collision. */
typedef struct ball_segment {
  double t0;        /* sim time the segment starts, s */
  ball_vec3 p0;     /* P0, m */
  ball_vec3 v0;     /* V0, m/s */
  ball_vec3 s0;     /* S0, spin, m/s */
  int grounded;     /* 1: sliding on the floor (vertical motion stopped, eq 5 threshold) */
} ball_segment;

typedef struct ball_state {
  ball_vec3 position;  /* m */
  ball_vec3 velocity;  /* m/s */
  ball_vec3 spin;      /* m/s */
} ball_state;

/* State on a segment at sim time t >= seg->t0 (eq 3 and eq 4). */
BALL_API ball_status ball_segment_eval(const ball_model *model, const ball_segment *seg,
                                       double t, ball_state *out);

/* A segment prepared for many evaluations: the model's constants of eq 3
 * and 4 worked out once (ball_flight_init), so that ball_flight_eval costs
 * one expm1 and a few multiplications (docs/benchmarks.md). It gives what
 * ball_segment_eval gives, to the bit. */
typedef struct ball_flight {
  ball_segment seg;     /* the segment, checked finite by ball_flight_init */
  double b;             /* m / beta, s; +Inf without drag */
  double inv_b;         /* 1 / b, 1/s; 0 without drag */
  double gravity;       /* g, m/s^2 */
  double spin_damping;  /* sDamp, s; 0 without spin */
} ball_flight;

BALL_API ball_status ball_flight_init(const ball_model *model, const ball_segment *seg,
                                      ball_flight *out);

/* State at sim time t >= seg.t0 (BALL_ERANGE before, BALL_ENONFINITE for a
 * NaN or infinite t). */
BALL_API ball_status ball_flight_eval(const ball_flight *flight, double t, ball_state *out);

/* Earliest sim time >= t_from when the ball centre is at height y. */
BALL_API ball_status ball_time_to_height(const ball_model *model, const ball_segment *seg,
                                         double t_from, double y, double *t);

/* Earliest sim time >= t_from when the centre reaches the plane axis = coord
 * (axis 0: x, 2: z); BALL_ENOTFOUND if drag stops the ball short of it. */
BALL_API ball_status ball_time_to_plane(const ball_model *model, const ball_segment *seg,
                                        double t_from, int axis, double coord, double *t);

/* Next contact of the ball's surface with the floor after t_from, ignoring
 * every other obstacle: time and centre position. */
BALL_API ball_status ball_next_floor_contact(const ball_model *model, const ball_segment *seg,
                                             double t_from, double *t, ball_vec3 *point);

/* Apex of the segment: time and position of the highest point (t0 if falling). */
BALL_API ball_status ball_apex(const ball_model *model, const ball_segment *seg, double *t,
                               ball_vec3 *point);

/* ---- static geometry ---------------------------------------------------- */

/* Distance from a sphere's surface to a plane rectangle (< 0: overlapping). */
BALL_API ball_status ball_sphere_rect_distance(const ball_plane *rect, ball_vec3 center,
                                               double radius, double *distance);

/* Distance from a sphere's surface to a racket disc (< 0: overlapping). */
BALL_API ball_status ball_sphere_disc_distance(ball_vec3 disc_center, ball_vec3 disc_normal,
                                               double disc_radius, ball_vec3 center,
                                               double radius, double *distance);

/* ---- swept racket test (beyond the paper) ------------------------------ */

/* The ball moving linearly p0 -> p1 while the disc moves c0 -> c1 and turns
 * n0 -> n1 over the same interval [0, 1]. On a hit, *toi is the first time
 * of contact in [0, 1] (to 1e-12) and *point the ball centre then. */
typedef struct ball_swept_query {
  ball_vec3 p0, p1;      /* ball centre at both ends, m */
  double ball_radius;    /* m */
  ball_vec3 c0, c1;      /* disc centre at both ends, m */
  ball_vec3 n0, n1;      /* disc normal at both ends (need not be unit) */
  double disc_radius;    /* m */
} ball_swept_query;

BALL_API ball_status ball_swept_disc(const ball_swept_query *q, int *hit, double *toi,
                                     ball_vec3 *point);

/* ---- the sim ------------------------------------------------------------ */

typedef enum ball_event_kind {
  BALL_EVENT_FLOOR = 0,
  BALL_EVENT_NET,
  BALL_EVENT_WALL,
  BALL_EVENT_RACKET,
  BALL_EVENT_KIND_COUNT
} ball_event_kind;

/* The kind's name: "floor", "net", "wall", "racket" ("unknown" past the list). */
BALL_API const char *ball_event_kind_name(ball_event_kind kind);

typedef struct ball_event {
  ball_event_kind kind;
  int index;               /* wall or racket index; 0 for floor and net */
  double time;             /* sim time of the collision, s */
  ball_vec3 point;         /* ball centre at the collision (Q), m */
  ball_vec3 velocity_in;   /* velocity arriving, m/s */
  ball_vec3 velocity_out;  /* V0 of the new segment, m/s */
  ball_vec3 spin_out;      /* S0 of the new segment, m/s */
  int sound;               /* 1: the server should broadcast a sound */
  ball_segment segment;    /* the flight segment this collision starts (its p0 may be shifted
                              off Q: eq 6's dt / 10, eq 7's V0 dt, or one ulp in exact mode) */
} ball_event;

typedef enum ball_warning {
  BALL_WARN_EVENT_OVERFLOW = 0,  /* more events in a step than the caller had room for */
  BALL_WARN_CONTACT_LIMIT,       /* BALL_MAX_CONTACTS reached in one exact step */
  BALL_WARN_STALE_RACKET,        /* a racket test skipped because its track was stale */
  BALL_WARN_COUNT
} ball_warning;

typedef struct ball_racket_track {
  int count;                                    /* samples held, [0, history] */
  ball_racket_sample samples[BALL_MAX_HISTORY]; /* oldest first */
  int has_prev;                                 /* 1: prev_pose is the pose at the previous frame */
  ball_racket_pose prev_pose;                   /* for the disc and swept tests */
} ball_racket_track;

/* The next contact with a static obstacle on a segment, found in closed
 * form when the segment starts (exact scheme); a cache the sim keeps so
 * that a frame without a contact costs one comparison. */
typedef struct ball_contact {
  int valid;         /* 0: not computed yet for the current segment */
  int which;         /* -1: none ever; 0 floor, 1 net, 2 + i wall i */
  double time;       /* sim time of the contact, s (+Inf when none) */
  ball_vec3 point;   /* ball centre at the contact, m */
  ball_vec3 normal;  /* contact normal at a net's or wall's edge or corner; zero for a face */
} ball_contact;

typedef struct ball_sim {
  double time;                 /* sim clock, s */
  uint64_t frame;              /* steps taken */
  ball_segment seg;            /* the current flight segment */
  ball_contact next;           /* the next static contact on seg (exact scheme) */
  ball_vec3 prev_position;     /* ball centre at the end of the previous step (P_old), m */
  int sleep;                   /* frames left without racket tests */
  ball_racket_track tracks[BALL_MAX_RACKETS];
  unsigned long warnings[BALL_WARN_COUNT];  /* counts, never printed */
  ball_model model;            /* the sim's own checked model: read it with ball_sim_model,
                                  change it with ball_sim_set_model, never by hand */
} ball_sim;

/* A portable hash of every model field that ball_step reads (those of the
 * stages the effect mask turns on; level and initial_* are not read by a
 * step): equal on every machine for equal field values, so a server and its
 * clients can tell they run the same model. docs/model.md defines it. */
BALL_API uint64_t ball_model_hash(const ball_model *model);

/* Checks the model (ball_model_check) and starts sim with its own copy of
 * it at time 0, in the model's initial state. */
BALL_API ball_status ball_sim_init(ball_sim *sim, const ball_model *model);

/* The sim's own model (NULL for a NULL sim): what its steps run. */
BALL_API const ball_model *ball_sim_model(const ball_sim *sim);

/* Checks a changed model and makes it the sim's, keeping the ball where it
 * is and as fast, the clock and the racket tracks (a new game level
 * mid-match): a new segment starts now, under the new model. The one way to
 * change a sim's model; the check is done here, never in a step. */
BALL_API ball_status ball_sim_set_model(ball_sim *sim, const ball_model *model);

/* Sets the ball's state at the sim's current time (starts a new segment).
 * BALL_ERANGE for a position beyond BALL_MAX_COORD, a velocity or spin
 * component beyond BALL_MAX_SPEED, or a ball below the floor. */
BALL_API ball_status ball_sim_set_state(ball_sim *sim, const ball_state *state);

/* Puts the sim on a given flight segment at sim time `time` (>= seg->t0):
 * what a second server needs to go on from the newest segment another one
 * published. The clock becomes `time`, the ball is where seg puts it then
 * (also the sampled scheme's previous position), the racket tests are awake;
 * the racket tracks, the frame count and the warnings stay. Spin is dropped
 * when the model has no spin effect, as ball_sim_set_state does.
 * BALL_ENONFINITE for a NaN or infinite number; BALL_ERANGE for a time
 * before t0, a segment or a ball at `time` outside the ranges of
 * ball_sim_set_state (below the floor included), or a grounded segment
 * that is not on the floor at rest vertically; BALL_EINVAL for grounded not
 * 0 or 1. Refused, the sim is unchanged. */
BALL_API ball_status ball_sim_set_segment(ball_sim *sim, const ball_segment *seg, double time);

/* Sets how many of the next frames skip the racket tests (the pause after a
 * racket hit, section 3.1: sleep_frames of the model), as a hit leaves it:
 * what a second server restores with ball_sim_set_segment when the segment
 * it goes on from began with a racket hit a few frames ago.
 * BALL_ERANGE for frames outside [0, the model's sleep_frames]; refused, the
 * sim is unchanged. */
BALL_API ball_status ball_sim_set_sleep(ball_sim *sim, int frames);

/* The ball's state at the sim's current time. */
BALL_API ball_status ball_sim_state(const ball_sim *sim, ball_state *out);

/* Advances one frame of dt sim seconds (dt >= 0; 0 is a no-op) and writes up
 * to cap events; *n_events (may be NULL) gets how many were written. Events
 * that do not fit are counted in sim->warnings[BALL_WARN_EVENT_OVERFLOW]. */
BALL_API ball_status ball_step(ball_sim *sim, double dt, ball_event *events, int cap, int *n_events);

/* Feeds a racket sample; samples may arrive late, duplicated or out of order:
 * an exact duplicate of a kept sample is ignored with BALL_EDUPLICATE, one
 * not newer than the newest kept is rejected with BALL_ESTALE; either way
 * the sim is unchanged. */
BALL_API ball_status ball_racket_push(ball_sim *sim, int racket, const ball_racket_sample *sample);

/* Empties one racket's track (its samples and its previous pose), as
 * ball_sim_init leaves it: for a player slot that changes hands, whose new
 * holder's samples must not be joined to the old one's. BALL_EINVAL for a
 * racket the sim's model does not have. */
BALL_API ball_status ball_racket_clear(ball_sim *sim, int racket);

/* The racket's estimated pose at sim time t: interpolated between samples,
 * extrapolated (eq 15) past the newest. BALL_ENOTFOUND without samples,
 * BALL_ESTALE if the newest sample is older than stale_time. */
BALL_API ball_status ball_racket_estimate(const ball_sim *sim, int racket, double t,
                                          ball_racket_pose *out);

/* When a racket will first meet the ball (beyond the paper; docs/rackets.md,
 * "First contact"): for a server that steps at frame deadlines but wants to
 * wake between them at the instant a hit happens. */
typedef struct ball_racket_contact {
  int racket;       /* the racket the step reports; -1 from the _any query when none */
  double step_to;   /* s: the earliest frame end t: ball_step(sim, t - sim->time, ...) reports the
                       hit; +Inf when none */
  double time;      /* s: the time that step's event carries: step_to for the sphere and disc tests,
                       the time of impact (sim->time <= time <= step_to) for the swept test */
  double searched;  /* s: the search covered (sim->time, searched]: step_to on a hit; else t_end, or
                       less where a static contact or the work bound cut it (step there, ask again) */
} ball_racket_contact;

/* The earliest frame end t in (sim->time, t_end] at which ONE ball_step of
 * dt = t - sim->time, from the sim as it is, finds a hit of racket `racket`
 * with the model's detection test (sphere, disc in either normal mode,
 * swept), the racket estimated as ball_racket_estimate gives it
 * (interpolated, eq 15 past the newest sample, capped by
 * extrapolation_time): found to adjacent doubles by the step's own test, so
 * stepping to out->step_to reports that hit and stepping to any earlier
 * time does not. Other rackets are not considered (the _any query does).
 * Reads the sim only. The ball follows its current segment: if a floor,
 * net or wall contact would come first, the search ends just before it
 * (out->searched). A ball already touching gives the first double after
 * sim->time. Bounded work, no allocation (docs/rackets.md gives the cost).
 * BALL_ENOTFOUND: no hit in the window (out->searched says how far it
 * looked), also when the track has no samples, the rackets effect is off,
 * or the racket tests sleep (sim->sleep > 0 counts STEPS: the next step
 * tests nothing, however long it is; step the frames and ask again).
 * BALL_ESTALE: the track is stale at sim->time, as ball_racket_estimate.
 * out is written with these two and BALL_OK. BALL_EINVAL for NULL or a
 * racket the model does not have, BALL_ENONFINITE for a NaN or infinite
 * t_end (or sim state), BALL_ERANGE for t_end before sim->time or a step the
 * stepper would refuse; then out is unchanged. */
BALL_API ball_status ball_racket_first_contact(const ball_sim *sim, int racket, double t_end,
                                               ball_racket_contact *out);

/* The same over every racket: the earliest frame end at which one step
 * reports a racket hit, and the racket it reports (the stage's rule when
 * several pass in that step: earliest time of impact or nearest).
 * BALL_ENOTFOUND (out->racket -1) when none does. */
BALL_API ball_status ball_racket_first_contact_any(const ball_sim *sim, double t_end,
                                                   ball_racket_contact *out);

/* A cheap bound to ask before those queries: *may = 0 when racket `racket`
 * (-1: any racket) cannot be found by the model's test in a step ending in
 * (sim->time, t_end], so that ball_racket_first_contact(_any) finds no hit
 * there; 1 when it may. The ball's path over the window (from P_old, the
 * sim's prev_position, at most as fast as its segment's speeds at the
 * window's ends allow) and the racket's track (interpolated, eq 15 past the
 * newest sample, held; and R_old) are each held in a sphere; they may meet
 * only when the spheres come within the test's reach (d_COLL; the disc and
 * swept tests sqrt((r + b)^2 + b^2)). No transcendental call, no pose
 * beyond the track's corners (docs/rackets.md, "First contact"). *may = 0
 * also when the query would find nothing for other reasons (no samples, a
 * stale track, the rackets effect off, the tests asleep, an empty window).
 * BALL_EINVAL for NULL or a racket the model does not have,
 * BALL_ENONFINITE for a NaN or infinite t_end (or sim state), BALL_ERANGE
 * for t_end before sim->time; then *may is unchanged. */
BALL_API ball_status ball_racket_may_reach(const ball_sim *sim, int racket, double t_end, int *may);

/* A portable hash of the sim's state (clock, frame, segment, previous
 * position, sleep counter, racket samples, and ball_model_hash of the sim's
 * model; not the warning counters), to detect desync between peers: equal on
 * every machine for equal states (docs/model.md defines it). 0 for NULL. */
BALL_API uint64_t ball_sim_hash(const ball_sim *sim);

/* The same with the model's hash given: ball_sim_hash(sim) when model_hash
 * is ball_model_hash(&sim->model). For a caller that hashes the sim often
 * and keeps the model's hash while the model stays the same (the model's
 * hash is over half of ball_sim_hash's work). 0 for NULL. */
BALL_API uint64_t ball_sim_hash_with(const ball_sim *sim, uint64_t model_hash);

/* ---- prediction (beyond the paper) ------------------------------------- */

/* What ball_predict writes. Set the arrays and capacities, the rest is output. */
typedef struct ball_prediction {
  ball_state *states;  /* (cap_states) states at t_from + k dt, k = 0, 1, ... while <= t_end;
                          NULL with cap_states 0 for none */
  int cap_states;
  int n_states;        /* out: states written (stops at cap_states) */
  ball_event *events;  /* (cap_events) floor, net and wall contacts in (t_from, t_end], in
                          time order; NULL with cap_events 0 for none */
  int cap_events;
  int n_events;        /* out: events written */
  int events_missed;   /* out: contacts that did not fit */
  ball_segment end;    /* out: the segment in effect at t_end */
} ball_prediction;

/* How close ball_predict's states are to ball_step's (below), relative. */
#define BALL_PREDICT_REL_ERROR 1e-12

/* The ball's path from seg (in effect at t_from >= seg->t0) to t_end with
 * static obstacles only (no rackets), event-driven: contacts in closed form
 * (the exact scheme, whatever model->scheme says), then states at the fixed
 * rate 1 / dt. Gives the events and the end segment that ball_step gives at
 * frames of dt in the exact scheme, to the bit, and its states within a
 * bound: eq 3's horizontal terms are stepped from state to state by a
 * recurrence (a few multiplications instead of an expm1), re-anchored to
 * the closed form every 32 states and at every contact (docs/model.md,
 * "Prediction"). A state's height, vertical speed and spin are ball_step's
 * to the bit; along x (and z), with P0, V0, t0 the segment in effect at the
 * state's time t,
 *   |x - x_step| <= BALL_PREDICT_REL_ERROR (|P0x| + |V0x| (t - t0)),
 *   |vx - vx_step| <= BALL_PREDICT_REL_ERROR |V0x|.
 * The model is checked on every call (a bot may pass any model); no
 * allocation. */
BALL_API ball_status ball_predict(const ball_model *model, const ball_segment *seg, double t_from,
                                  double t_end, double dt, ball_prediction *out);

#ifdef __cplusplus
}
#endif

#endif /* BALL_BALL_H */
