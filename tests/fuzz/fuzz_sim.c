/* libFuzzer harness: the sim fed arbitrary parameter sets and racket samples
 * decoded from bytes (docs/hard-cases.md). Checked on every input:
 *  - nothing crashes, leaks or invokes undefined behaviour (ASan, UBSan);
 *  - a model refused by ball_model_check is refused by ball_sim_init, which
 *    then leaves the sim untouched;
 *  - every refused call (step, set_state, racket_push) leaves the sim byte
 *    for byte unchanged and reports no event;
 *  - finite stays finite: after every accepted call the ball's state and
 *    the events are finite.
 * Numbers are decoded so that most are plausible and some are extreme: a tag
 * byte picks a small value, a raw 64-bit pattern (NaN, Inf, subnormal, huge)
 * or a special constant. */
#include <float.h>
#include <math.h>
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "ball/ball.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

typedef struct input {
  const uint8_t *p;
  size_t n;
} input;

static void check(int ok) {
  if (!ok) abort();
}

static unsigned byte(input *in) {
  if (in->n == 0) return 0;
  in->n--;
  return *in->p++;
}

static double special(unsigned k) {
  static const double v[] = {0.0, -0.0, 1.0, -1.0, 0.5, 2.0, 1e-300, 4.9406564584124654e-324,
                             DBL_MIN, DBL_MAX, -DBL_MAX, 1e300, 1e-9, 1e9, NAN, INFINITY};
  return v[k % 16];
}

/* A number: small (in [lo, hi], 16 bits), raw bits, or special. */
static double num(input *in, double lo, double hi) {
  unsigned tag = byte(in);
  if (tag < 200) {
    unsigned u = byte(in) | (byte(in) << 8);
    return lo + (hi - lo) * (double)u / 65535.0;
  }
  if (tag < 230) {
    uint64_t bits = 0;
    double d;
    int i;
    for (i = 0; i < 8; i++) bits = (bits << 8) | byte(in);
    memcpy(&d, &bits, sizeof d);
    return d;
  }
  return special(byte(in));
}

static ball_vec3 vec(input *in, double a) {
  ball_vec3 v;
  v.x = num(in, -a, a);
  v.y = num(in, -a, a);
  v.z = num(in, -a, a);
  return v;
}

static int finite3(ball_vec3 v) { return isfinite(v.x) && isfinite(v.y) && isfinite(v.z); }

static void plane(input *in, ball_plane *p) {
  p->axis = byte(in) & 1 ? 2 : 0;
  p->position = num(in, -30.0, 30.0);
  p->lo = num(in, -30.0, 30.0);
  p->hi = p->lo + num(in, 0.0, 30.0);
  p->bottom = num(in, -2.0, 2.0);
  p->top = p->bottom + num(in, 0.0, 5.0);
  p->damping = num(in, 0.0, 1.0);
}

static void decode_model(input *in, ball_model *m) {
  int i;
  ball_model_default(m);
  m->gravity = num(in, 0.1, 30.0);
  m->mass = num(in, 0.001, 5.0);
  m->air_friction = num(in, 0.0, 2.0);
  m->radius = num(in, 0.0, 0.5);
  m->spin_damping = num(in, 0.01, 10.0);
  m->floor_level = num(in, -5.0, 5.0);
  m->floor_damping = num(in, 0.0, 1.0);
  m->bounce_threshold = num(in, 0.0, 2.0);
  m->sound_threshold = num(in, 0.0, 5.0);
  m->spin_floor_damping = num(in, 0.0, 1.0);
  m->has_net = (int)(byte(in) % 3) == 0 ? 0 : 1;
  plane(in, &m->net);
  m->n_walls = (int)(byte(in) % 6);
  for (i = 0; i < m->n_walls; i++) plane(in, &m->walls[i]);
  m->n_rackets = (int)(byte(in) % (BALL_MAX_RACKETS + 1));
  for (i = 0; i < BALL_MAX_RACKETS; i++) {
    m->rackets[i].radius = num(in, 0.0, 0.5);
    m->rackets[i].partner = (int)(byte(in) % (BALL_MAX_RACKETS + 1)) - 1;
    m->rackets[i].target = vec(in, 30.0);
  }
  m->detect = (ball_detect)(byte(in) % (BALL_DETECT_COUNT + 1));
  m->normal_mode = (ball_normal_mode)(byte(in) % BALL_NORMAL_COUNT);
  m->response = (ball_response)(byte(in) % BALL_RESPONSE_COUNT);
  m->collision_distance = num(in, 0.0, 1.0);
  m->sleep_frames = (int)(byte(in) % 8);
  m->v_min = num(in, 0.0, 20.0);
  m->v_max = m->v_min + num(in, 0.0, 60.0);
  m->v_up = num(in, 0.0, 20.0);
  m->v_up_from_racket = byte(in) & 1;
  m->friendly_factor = num(in, 0.0, 1.5);
  m->spin_rack_damping = num(in, 0.0, 1.0);
  m->history = 2 + (int)(byte(in) % (BALL_MAX_HISTORY - 1));
  m->extrapolation_time = num(in, 0.0, 0.5);
  m->stale_time = num(in, 0.01, 5.0);
  m->effects = byte(in) & BALL_EFFECT_ALL;
  m->scheme = (ball_scheme)(byte(in) % (BALL_SCHEME_COUNT + 1));
  m->initial_position = vec(in, 20.0);
  m->initial_position.y = m->floor_level + m->radius + num(in, 0.0, 5.0);
  m->initial_velocity = vec(in, 40.0);
  m->initial_spin = vec(in, 40.0);
}

static void check_state(const ball_model *m, const ball_sim *sim) {
  ball_state s;
  check(ball_sim_state(m, sim, &s) == BALL_OK);
  check(finite3(s.position) && finite3(s.velocity) && finite3(s.spin));
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  input in;
  ball_model m;
  ball_sim sim, copy;
  ball_event ev[BALL_MAX_CONTACTS + 2];
  ball_status st;
  int ops;
  in.p = data;
  in.n = size;
  decode_model(&in, &m);
  memset(&sim, 0xA5, sizeof sim);
  copy = sim;
  if (ball_model_check(&m, NULL) != BALL_OK) {
    check(ball_sim_init(&m, &sim) != BALL_OK);
    check(memcmp(&sim, &copy, sizeof sim) == 0);
    return 0;
  }
  check(ball_sim_init(&m, &sim) == BALL_OK);
  check_state(&m, &sim);
  for (ops = 0; ops < 200 && in.n > 0; ops++) {
    unsigned op = byte(&in) % 4;
    int n = -1, i;
    copy = sim;
    if (op <= 1) {
      double dt = op == 0 ? num(&in, 0.0, 0.1) : num(&in, 0.0, 10.0);
      st = ball_step(&m, &sim, dt, ev, BALL_MAX_CONTACTS + 2, &n);
      if (st != BALL_OK) {
        check(n == 0 && memcmp(&sim, &copy, sizeof sim) == 0);
        continue;
      }
      check(n >= 0 && n <= BALL_MAX_CONTACTS + 2);
      for (i = 0; i < n; i++)
        check(isfinite(ev[i].time) && finite3(ev[i].point) && finite3(ev[i].velocity_in) &&
              finite3(ev[i].velocity_out) && finite3(ev[i].spin_out));
      check_state(&m, &sim);
    } else if (op == 2) {
      ball_racket_sample s;
      int r = (int)(byte(&in) % (BALL_MAX_RACKETS + 1)) - 1;
      s.t = sim.time + num(&in, -0.2, 0.2);
      s.center = vec(&in, 20.0);
      s.normal = vec(&in, 1.0);
      st = ball_racket_push(&m, &sim, r, &s);
      if (st != BALL_OK) check(memcmp(&sim, &copy, sizeof sim) == 0);
    } else {
      ball_state s;
      s.position = vec(&in, 20.0);
      s.velocity = vec(&in, 40.0);
      s.spin = vec(&in, 40.0);
      st = ball_sim_set_state(&m, &sim, &s);
      if (st != BALL_OK)
        check(memcmp(&sim, &copy, sizeof sim) == 0);
      else
        check_state(&m, &sim);
    }
  }
  return 0;
}
