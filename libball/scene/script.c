/* Racket scripts: keyframed swings turned into the sample stream a tracker
 * or a remote player would send, under seeded network conditions (rate,
 * delay, jitter, loss, duplicates, noise). A client of the public API like
 * the scene loader; no dependency but libm. See docs/scenes.md. */
#include "ball/script.h"
#include "ball/vec3.h"

#include <math.h>
#include <string.h>

#define SCRIPT_MIN_RATE 2.0      /* Hz */
#define SCRIPT_MAX_RATE 120.0    /* Hz */
#define SCRIPT_MAX_DELAY 60.0    /* s */
#define SCRIPT_MAX_JITTER 0.5    /* s: keeps the samples in flight within BALL_SCRIPT_MAX_PENDING */
#define SCRIPT_MAX_NORMAL_NOISE 1.0 /* rad */
#define SCRIPT_MIN_NORMAL 1e-9   /* shortest keyframe normal accepted */
#define SCRIPT_MAX_TIME 1e9      /* s: |keyframe time| */
#define SCRIPT_MAX_NOISE 1e3     /* m: sigma of a centre's noise (a Gaussian draw stays within 10 sigma) */
#define SCRIPT_PI 3.14159265358979323846

/* ---- the random stream ---- */

/* splitmix64 (Steele, Lea, Flood 2014): one 64-bit state, one output per
 * step. Every sample seeds its own generator from (seed, racket sample
 * index), so a sample's draws do not depend on any other sample, on the
 * polling or on the other parameters. */
static uint64_t splitmix64(uint64_t *state) {
  uint64_t z = (*state += UINT64_C(0x9E3779B97F4A7C15));
  z = (z ^ (z >> 30)) * UINT64_C(0xBF58476D1CE4E5B9);
  z = (z ^ (z >> 27)) * UINT64_C(0x94D049BB133111EB);
  return z ^ (z >> 31);
}

/* Uniform in [0, 1), 53 bits. */
static double uniform(uint64_t *state) { return (double)(splitmix64(state) >> 11) * (1.0 / 9007199254740992.0); }

/* Two independent standard normals (Box-Muller). */
static void gaussian_pair(uint64_t *state, double *g0, double *g1) {
  double u1 = uniform(state), u2 = uniform(state);
  double r = sqrt(-2.0 * log1p(-u1)); /* 1 - u1 in (0, 1]: no log(0) */
  *g0 = r * cos(2.0 * SCRIPT_PI * u2);
  *g1 = r * sin(2.0 * SCRIPT_PI * u2);
}

/* ---- scripts ---- */

void ball_script_default(ball_racket_script *s) {
  if (!s) return;
  memset(s, 0, sizeof *s);
  s->rate = 60.0;
}

#define CHECK(cond, name, status) \
  do {                            \
    if (!(cond)) {                \
      if (field) *field = (name); \
      return (status);            \
    }                             \
  } while (0)
#define CHECK_FINITE(value, name) CHECK(isfinite(value), name, BALL_ENONFINITE)

/* Keyframe member names with their index, static: no buffer for *field. */
#define KF_NAMES(p) {p "t", p "center", p "normal"}
static const char *const keyframe_names[BALL_SCRIPT_MAX_KEYFRAMES][3] = {
  KF_NAMES("keyframes[0]."),
  KF_NAMES("keyframes[1]."),
  KF_NAMES("keyframes[2]."),
  KF_NAMES("keyframes[3]."),
  KF_NAMES("keyframes[4]."),
  KF_NAMES("keyframes[5]."),
  KF_NAMES("keyframes[6]."),
  KF_NAMES("keyframes[7]."),
  KF_NAMES("keyframes[8]."),
  KF_NAMES("keyframes[9]."),
  KF_NAMES("keyframes[10]."),
  KF_NAMES("keyframes[11]."),
  KF_NAMES("keyframes[12]."),
  KF_NAMES("keyframes[13]."),
  KF_NAMES("keyframes[14]."),
  KF_NAMES("keyframes[15]."),
  KF_NAMES("keyframes[16]."),
  KF_NAMES("keyframes[17]."),
  KF_NAMES("keyframes[18]."),
  KF_NAMES("keyframes[19]."),
  KF_NAMES("keyframes[20]."),
  KF_NAMES("keyframes[21]."),
  KF_NAMES("keyframes[22]."),
  KF_NAMES("keyframes[23]."),
  KF_NAMES("keyframes[24]."),
  KF_NAMES("keyframes[25]."),
  KF_NAMES("keyframes[26]."),
  KF_NAMES("keyframes[27]."),
  KF_NAMES("keyframes[28]."),
  KF_NAMES("keyframes[29]."),
  KF_NAMES("keyframes[30]."),
  KF_NAMES("keyframes[31]."),
  KF_NAMES("keyframes[32]."),
  KF_NAMES("keyframes[33]."),
  KF_NAMES("keyframes[34]."),
  KF_NAMES("keyframes[35]."),
  KF_NAMES("keyframes[36]."),
  KF_NAMES("keyframes[37]."),
  KF_NAMES("keyframes[38]."),
  KF_NAMES("keyframes[39]."),
  KF_NAMES("keyframes[40]."),
  KF_NAMES("keyframes[41]."),
  KF_NAMES("keyframes[42]."),
  KF_NAMES("keyframes[43]."),
  KF_NAMES("keyframes[44]."),
  KF_NAMES("keyframes[45]."),
  KF_NAMES("keyframes[46]."),
  KF_NAMES("keyframes[47]."),
  KF_NAMES("keyframes[48]."),
  KF_NAMES("keyframes[49]."),
  KF_NAMES("keyframes[50]."),
  KF_NAMES("keyframes[51]."),
  KF_NAMES("keyframes[52]."),
  KF_NAMES("keyframes[53]."),
  KF_NAMES("keyframes[54]."),
  KF_NAMES("keyframes[55]."),
  KF_NAMES("keyframes[56]."),
  KF_NAMES("keyframes[57]."),
  KF_NAMES("keyframes[58]."),
  KF_NAMES("keyframes[59]."),
  KF_NAMES("keyframes[60]."),
  KF_NAMES("keyframes[61]."),
  KF_NAMES("keyframes[62]."),
  KF_NAMES("keyframes[63].")};

ball_status ball_script_check(const ball_racket_script *s, const char **field) {
  int i;
  CHECK(s != NULL, "script", BALL_EINVAL);
  CHECK(s->n_keyframes >= 1 && s->n_keyframes <= BALL_SCRIPT_MAX_KEYFRAMES, "keyframes", BALL_ERANGE);
  for (i = 0; i < s->n_keyframes; ++i) {
    const ball_script_keyframe *k = &s->keyframes[i];
    const char *const *name = keyframe_names[i];
    CHECK_FINITE(k->t, name[0]);
    CHECK(fabs(k->t) <= SCRIPT_MAX_TIME, name[0], BALL_ERANGE);
    CHECK(i == 0 || k->t > s->keyframes[i - 1].t, name[0], BALL_ERANGE);
    CHECK(ball_v3_finite(k->center), name[1], BALL_ENONFINITE);
    /* inside the world the library handles, so that every pose between two
     * keyframes (and every noisy sample) is finite and a valid sample */
    CHECK(ball_v3_max_abs(k->center) <= BALL_MAX_COORD - SCRIPT_MAX_NOISE * 10.0, name[1], BALL_ERANGE);
    CHECK(ball_v3_finite(k->normal), name[2], BALL_ENONFINITE);
    CHECK(ball_v3_length(k->normal) >= SCRIPT_MIN_NORMAL, name[2], BALL_ERANGE);
  }
  CHECK_FINITE(s->repeat, "repeat");
  CHECK(s->repeat >= 0.0 && s->repeat <= 4.0 * SCRIPT_MAX_TIME, "repeat", BALL_ERANGE); /* > the longest span */
  CHECK(s->repeat == 0.0 || s->repeat > s->keyframes[s->n_keyframes - 1].t - s->keyframes[0].t, "repeat",
        BALL_ERANGE);
  CHECK_FINITE(s->rate, "rate");
  CHECK(s->rate >= SCRIPT_MIN_RATE && s->rate <= SCRIPT_MAX_RATE, "rate", BALL_ERANGE);
  CHECK_FINITE(s->delay, "delay");
  CHECK(s->delay >= 0.0 && s->delay <= SCRIPT_MAX_DELAY, "delay", BALL_ERANGE);
  CHECK_FINITE(s->jitter, "jitter");
  CHECK(s->jitter >= 0.0 && s->jitter <= SCRIPT_MAX_JITTER, "jitter", BALL_ERANGE);
  CHECK_FINITE(s->loss, "loss");
  CHECK(s->loss >= 0.0 && s->loss < 1.0, "loss", BALL_ERANGE);
  CHECK_FINITE(s->duplicate, "duplicate");
  CHECK(s->duplicate >= 0.0 && s->duplicate <= 1.0, "duplicate", BALL_ERANGE);
  CHECK_FINITE(s->noise, "noise");
  CHECK(s->noise >= 0.0 && s->noise <= SCRIPT_MAX_NOISE, "noise", BALL_ERANGE);
  CHECK_FINITE(s->normal_noise, "normal_noise");
  CHECK(s->normal_noise >= 0.0 && s->normal_noise <= SCRIPT_MAX_NORMAL_NOISE, "normal_noise", BALL_ERANGE);
  return BALL_OK;
}

/* Normalised lerp of two keyframe normals; the first one if they cancel. */
static ball_vec3 normal_lerp(ball_vec3 a, ball_vec3 b, double u) {
  ball_vec3 ua = ball_v3_unit(a), n = ball_v3_unit(ball_v3_lerp(ua, ball_v3_unit(b), u));
  return ball_v3_dot(n, n) > 0.0 ? n : ua;
}

/* The pose without argument checks. */
static void script_pose(const ball_racket_script *s, double t, ball_vec3 *center, ball_vec3 *normal) {
  const ball_script_keyframe *k = s->keyframes;
  int n = s->n_keyframes, i;
  double t_first = k[0].t, t_last = k[n - 1].t;
  if (s->repeat > 0.0 && t > t_first) {
    /* one period: the keyframes, then last -> first over the rest of it */
    double u = fmod(t - t_first, s->repeat);
    t = t_first + u;
    if (t >= t_last) {
      double gap = t_first + s->repeat - t_last;
      double w = (t - t_last) / gap;
      if (w > 1.0) w = 1.0;
      *center = ball_v3_lerp(k[n - 1].center, k[0].center, w);
      *normal = normal_lerp(k[n - 1].normal, k[0].normal, w);
      return;
    }
  }
  if (t <= t_first) {
    *center = k[0].center;
    *normal = ball_v3_unit(k[0].normal);
    return;
  }
  if (t >= t_last) {
    *center = k[n - 1].center;
    *normal = ball_v3_unit(k[n - 1].normal);
    return;
  }
  for (i = 1; i < n - 1 && k[i].t <= t; ++i) {
  }
  {
    double w = (t - k[i - 1].t) / (k[i].t - k[i - 1].t);
    *center = ball_v3_lerp(k[i - 1].center, k[i].center, w);
    *normal = normal_lerp(k[i - 1].normal, k[i].normal, w);
  }
}

ball_status ball_script_pose(const ball_racket_script *s, double t, ball_vec3 *center, ball_vec3 *normal) {
  ball_status st;
  ball_vec3 c, n;
  if (!s || !center || !normal) return BALL_EINVAL;
  if (!isfinite(t)) return BALL_ENONFINITE;
  if ((st = ball_script_check(s, NULL)) != BALL_OK) return st;
  script_pose(s, t, &c, &n);
  *center = c;
  *normal = n;
  return BALL_OK;
}

/* ---- the player ---- */

ball_status ball_script_player_init(ball_script_player *p, const ball_racket_script *scripts, int n_rackets) {
  int i;
  if (!p || (n_rackets > 0 && !scripts)) return BALL_EINVAL;
  if (n_rackets < 0 || n_rackets > BALL_MAX_RACKETS) return BALL_ERANGE;
  for (i = 0; i < n_rackets; ++i) {
    ball_status st;
    if (scripts[i].n_keyframes == 0) continue;
    if ((st = ball_script_check(&scripts[i], NULL)) != BALL_OK) return st;
  }
  memset(p, 0, sizeof *p);
  p->n_rackets = n_rackets;
  for (i = 0; i < n_rackets; ++i) p->scripts[i] = scripts[i];
  return BALL_OK;
}

static double sample_time(const ball_racket_script *s, unsigned long k) { return (double)k / s->rate; }

/* a arrives before b: by arrival, then racket, index and copy. */
static int earlier(const ball_script_sample *a, const ball_script_sample *b) {
  if (a->arrival != b->arrival) return a->arrival < b->arrival;
  if (a->racket != b->racket) return a->racket < b->racket;
  if (a->index != b->index) return a->index < b->index;
  return a->copy < b->copy;
}

static void insert_pending(ball_script_player *p, const ball_script_sample *s) {
  int i = p->n_pending;
  while (i > 0 && earlier(s, &p->pending[i - 1])) {
    p->pending[i] = p->pending[i - 1];
    --i;
  }
  p->pending[i] = *s;
  p->n_pending++;
}

/* Takes sample k of racket r: the scripted pose with noise, lost or not,
 * duplicated or not, each copy with its own jitter. The draws are always
 * made in the same order, whatever the parameters. */
static void take_sample(ball_script_player *p, int r, unsigned long k) {
  const ball_racket_script *s = &p->scripts[r];
  uint64_t seed_state = s->seed, state;
  double u_loss, u_dup, u_jit0, u_jit1, g[6];
  ball_script_sample out;
  ball_vec3 c, n, tilt;
  int i;
  state = splitmix64(&seed_state) ^ ((uint64_t)k * UINT64_C(0xD1B54A32D192ED03));
  (void)splitmix64(&state); /* one step to spread the index over all bits */
  u_loss = uniform(&state);
  u_dup = uniform(&state);
  u_jit0 = uniform(&state);
  u_jit1 = uniform(&state);
  for (i = 0; i < 6; i += 2) gaussian_pair(&state, &g[i], &g[i + 1]);

  if (u_loss < s->loss) return;
  memset(&out, 0, sizeof out);
  out.racket = r;
  out.index = k;
  out.sample.t = sample_time(s, k);
  script_pose(s, out.sample.t, &c, &n);
  out.sample.center = ball_v3_add(c, ball_v3_scale(ball_v3(g[0], g[1], g[2]), s->noise));
  /* tilt: the Gaussian's part across the normal, sigma normal_noise per axis */
  tilt = ball_v3(g[3], g[4], g[5]);
  tilt = ball_v3_add(tilt, ball_v3_scale(n, -ball_v3_dot(tilt, n)));
  out.sample.normal = s->normal_noise > 0.0 ? ball_v3_unit(ball_v3_add(n, ball_v3_scale(tilt, s->normal_noise))) : n;
  out.copy = 0;
  out.arrival = out.sample.t + s->delay + s->jitter * u_jit0;
  insert_pending(p, &out);
  if (u_dup < s->duplicate) {
    out.copy = 1;
    out.arrival = out.sample.t + s->delay + s->jitter * u_jit1;
    insert_pending(p, &out);
  }
}

/* Takes samples in the order they can first arrive (sample time + delay)
 * while that is <= t_now and there is room. Returns 1 when there was no
 * room: *bound is then the earliest arrival a sample not yet taken can have;
 * else 0 and *bound = t_now (every sample not taken arrives later). */
static int take_due(ball_script_player *p, double t_now, double *bound) {
  for (;;) {
    int r, best = -1;
    double best_t = t_now;
    for (r = 0; r < p->n_rackets; ++r) {
      const ball_racket_script *s = &p->scripts[r];
      double first;
      if (s->n_keyframes == 0) continue;
      first = sample_time(s, p->next[r]) + s->delay;
      if (first <= best_t && (best < 0 || first < best_t)) {
        best = r;
        best_t = first;
      }
    }
    *bound = best_t;
    if (best < 0) return 0;
    if (p->n_pending + 2 > BALL_SCRIPT_MAX_PENDING) return 1;
    take_sample(p, best, p->next[best]);
    p->next[best]++;
  }
}

ball_status ball_script_poll(ball_script_player *p, double t_now, ball_script_sample *out, int cap, int *n) {
  int written = 0;
  if (!p || !n || (cap > 0 && !out)) return BALL_EINVAL;
  if (cap < 0) return BALL_ERANGE;
  if (!isfinite(t_now)) return BALL_ENONFINITE;
  if (p->n_rackets < 0 || p->n_rackets > BALL_MAX_RACKETS || p->n_pending < 0 ||
      p->n_pending > BALL_SCRIPT_MAX_PENDING)
    return BALL_EINVAL;
  while (written < cap) {
    double bound;
    int stuck = take_due(p, t_now, &bound), m = 0;
    /* when stuck, a sample not yet taken may still arrive at bound itself */
    while (m < p->n_pending && written < cap &&
           (stuck ? p->pending[m].arrival < bound : p->pending[m].arrival <= bound))
      out[written++] = p->pending[m++];
    if (m == 0) break;
    memmove(&p->pending[0], &p->pending[m], (size_t)(p->n_pending - m) * sizeof p->pending[0]);
    p->n_pending -= m;
  }
  *n = written;
  return BALL_OK;
}
