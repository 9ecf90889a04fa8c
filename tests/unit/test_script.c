/* Racket scripts (docs/scenes.md, "Network conditions"): keyframe
 * interpolation by hand, and the sample stream of ball_script_player: the
 * same seed gives the same stream bit for bit whatever the polling, loss,
 * duplicates, delay, jitter and noise behave as stated (binomial and sample
 * variance bounds given at each check), and bad script fields in a scene
 * file are rejected with their line and field. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <math.h>

#include <cmocka.h>

#include "ball/scene.h"
#include "core_common.h"

#define MAX_STREAM 12000

/* Both streams are static: a player is about 50 kB. */
static ball_script_player player_a, player_b;
static ball_script_sample stream_a[MAX_STREAM], stream_b[MAX_STREAM];

/* Keyframe i of s: the racket at center facing normal at time t. */
static void keyframe(ball_racket_script *s, int i, double t, ball_vec3 center, ball_vec3 normal) {
  s->keyframes[i].t = t;
  s->keyframes[i].center = center;
  s->keyframes[i].normal = normal;
}

/* A still racket at (1, 2, 3) facing +x, with the given network. */
static void still_script(ball_racket_script *s, double rate) {
  ball_script_default(s);
  s->n_keyframes = 1;
  keyframe(s, 0, 0.0, ball_v3(1.0, 2.0, 3.0), ball_v3(1.0, 0.0, 0.0));
  s->rate = rate;
}

/* A swing: (0, 1, 0) -> (2, 1.5, 0.5) over [0.2, 0.6], the normal turning. */
static void swing_script(ball_racket_script *s) {
  ball_script_default(s);
  s->n_keyframes = 2;
  keyframe(s, 0, 0.2, ball_v3(0.0, 1.0, 0.0), ball_v3(1.0, 0.0, 0.0));
  keyframe(s, 1, 0.6, ball_v3(2.0, 1.5, 0.5), ball_v3(0.0, 1.0, 0.0));
  s->repeat = 1.0;
}

/* Polls a fresh player over scripts from t = step to t_end in steps of
 * step with the given cap, looping while the cap is filled. */
static int collect(ball_script_player *p, const ball_racket_script *scripts, int n_rackets, double t_end,
                   double step, int cap, ball_script_sample *out) {
  int total = 0, k;
  assert_int_equal(ball_script_player_init(p, scripts, n_rackets), BALL_OK);
  for (k = 1;; ++k) {
    double t = k * step < t_end ? k * step : t_end;
    int n;
    do {
      assert_true(total + cap <= MAX_STREAM);
      assert_int_equal(ball_script_poll(p, t, out + total, cap, &n), BALL_OK);
      total += n;
    } while (n == cap);
    if (t >= t_end) break;
  }
  return total;
}

static int same_sample(const ball_script_sample *a, const ball_script_sample *b) {
  return a->racket == b->racket && a->index == b->index && a->copy == b->copy && a->arrival == b->arrival &&
         a->sample.t == b->sample.t && a->sample.center.x == b->sample.center.x &&
         a->sample.center.y == b->sample.center.y && a->sample.center.z == b->sample.center.z &&
         a->sample.normal.x == b->sample.normal.x && a->sample.normal.y == b->sample.normal.y &&
         a->sample.normal.z == b->sample.normal.z;
}

/* ---- keyframes ---- */

static void keyframes_interpolate_linearly_and_hold_outside(void **state) {
  ball_racket_script s;
  ball_vec3 c, n;
  (void)state;
  ball_script_default(&s);
  s.n_keyframes = 3;
  keyframe(&s, 0, 0.0, ball_v3(0.0, 0.0, 0.0), ball_v3(1.0, 0.0, 0.0));
  keyframe(&s, 1, 1.0, ball_v3(2.0, 4.0, -2.0), ball_v3(0.0, 3.0, 0.0)); /* any length: normalised */
  keyframe(&s, 2, 3.0, ball_v3(2.0, 0.0, 0.0), ball_v3(0.0, 1.0, 0.0));
  /* t = 0.25: a quarter of the way, centre (0.5, 1, -0.5); normal
   * (0.75, 0.25, 0) / |.| = (3, 1, 0) / sqrt(10) */
  assert_int_equal(ball_script_pose(&s, 0.25, &c, &n), BALL_OK);
  assert_near(c.x, 0.5, 1e-15);
  assert_near(c.y, 1.0, 1e-15);
  assert_near(c.z, -0.5, 1e-15);
  assert_near(n.x, 3.0 / sqrt(10.0), 1e-15);
  assert_near(n.y, 1.0 / sqrt(10.0), 1e-15);
  assert_near(n.z, 0.0, 1e-15);
  /* t = 2: half way from keyframe 1 to 2: (2, 2, -1), normal (0, 1, 0) */
  assert_int_equal(ball_script_pose(&s, 2.0, &c, &n), BALL_OK);
  assert_near(c.x, 2.0, 1e-15);
  assert_near(c.y, 2.0, 1e-15);
  assert_near(c.z, -1.0, 1e-15);
  assert_near(n.y, 1.0, 1e-15);
  /* before the first keyframe and after the last: held */
  assert_int_equal(ball_script_pose(&s, -5.0, &c, &n), BALL_OK);
  assert_true(c.x == 0.0 && c.y == 0.0 && c.z == 0.0 && n.x == 1.0);
  assert_int_equal(ball_script_pose(&s, 100.0, &c, &n), BALL_OK);
  assert_true(c.x == 2.0 && c.y == 0.0 && c.z == 0.0 && n.y == 1.0);
}

static void repeat_wraps_from_last_keyframe_back_to_first(void **state) {
  ball_racket_script s;
  ball_vec3 c, n, c2, n2;
  (void)state;
  ball_script_default(&s);
  s.n_keyframes = 3;
  keyframe(&s, 0, 0.0, ball_v3(0.0, 0.0, 0.0), ball_v3(1.0, 0.0, 0.0));
  keyframe(&s, 1, 1.0, ball_v3(2.0, 4.0, -2.0), ball_v3(0.0, 1.0, 0.0));
  keyframe(&s, 2, 3.0, ball_v3(2.0, 0.0, 0.0), ball_v3(0.0, 1.0, 0.0));
  s.repeat = 4.0; /* span 3 s, then 1 s from keyframe 2 back to keyframe 0 */
  /* t = 3.5: half way from (2, 0, 0) back to (0, 0, 0): (1, 0, 0); normal
   * (0.5, 0.5, 0) / |.| */
  assert_int_equal(ball_script_pose(&s, 3.5, &c, &n), BALL_OK);
  assert_near(c.x, 1.0, 1e-15);
  assert_near(c.y, 0.0, 1e-15);
  assert_near(n.x, sqrt(0.5), 1e-15);
  assert_near(n.y, sqrt(0.5), 1e-15);
  /* t = 4.25 and 8.25 are t = 0.25 again: (0.5, 1, -0.5) */
  assert_int_equal(ball_script_pose(&s, 4.25, &c, &n), BALL_OK);
  assert_near(c.x, 0.5, 1e-14);
  assert_near(c.y, 1.0, 1e-14);
  assert_near(c.z, -0.5, 1e-14);
  assert_int_equal(ball_script_pose(&s, 8.25, &c2, &n2), BALL_OK);
  assert_near(c2.y, 1.0, 1e-14);
  assert_near(n2.x, n.x, 1e-14);
  /* a repeat not longer than the span is rejected */
  s.repeat = 3.0;
  assert_int_equal(ball_script_pose(&s, 0.5, &c, &n), BALL_ERANGE);
}

static void noise_free_samples_are_the_scripted_pose_at_k_over_rate(void **state) {
  ball_racket_script s;
  int n, i;
  (void)state;
  swing_script(&s);
  s.rate = 30.0;
  n = collect(&player_a, &s, 1, 3.0, 1.0 / 60.0, 64, stream_a);
  assert_int_equal(n, 91); /* k = 0 .. 90: t = k / 30 <= 3 */
  for (i = 0; i < n; ++i) {
    const ball_script_sample *x = &stream_a[i];
    ball_vec3 c, nn;
    assert_int_equal(x->index, (unsigned long)i);
    assert_true(x->sample.t == (double)i / 30.0);
    assert_true(x->arrival == x->sample.t); /* no delay, no jitter */
    assert_int_equal(ball_script_pose(&s, x->sample.t, &c, &nn), BALL_OK);
    assert_true(c.x == x->sample.center.x && c.y == x->sample.center.y && c.z == x->sample.center.z);
    assert_true(nn.x == x->sample.normal.x && nn.y == x->sample.normal.y && nn.z == x->sample.normal.z);
  }
}

/* ---- determinism ---- */

static void network_script(ball_racket_script *s, uint64_t seed) {
  swing_script(s);
  s->rate = 60.0;
  s->delay = 0.05;
  s->jitter = 0.08;
  s->loss = 0.2;
  s->duplicate = 0.2;
  s->noise = 0.01;
  s->normal_noise = 0.05;
  s->seed = seed;
}

static void same_seed_gives_the_same_stream_whatever_the_polling(void **state) {
  ball_racket_script s[2];
  int na, nb, i;
  (void)state;
  network_script(&s[0], 42);
  network_script(&s[1], 43);
  /* frame by frame at 60 Hz with room for 64, against 0.37 s steps, 3 at a time */
  na = collect(&player_a, s, 2, 20.0, 1.0 / 60.0, 64, stream_a);
  nb = collect(&player_b, s, 2, 20.0, 0.37, 3, stream_b);
  assert_int_equal(na, nb);
  assert_true(na > 1500); /* 2 x 1200 taken, 20 % lost, 20 % doubled: about 2300 */
  for (i = 0; i < na; ++i) assert_true(same_sample(&stream_a[i], &stream_b[i]));
  /* and one poll at 20 s: more samples are due than the player holds
   * (BALL_SCRIPT_MAX_PENDING), so it takes and hands out in turns */
  nb = collect(&player_b, s, 2, 20.0, 20.0, 64, stream_b);
  assert_int_equal(na, nb);
  for (i = 0; i < na; ++i) assert_true(same_sample(&stream_a[i], &stream_b[i]));
  /* arrival order, the tie break included */
  for (i = 1; i < na; ++i) assert_true(stream_a[i].arrival >= stream_a[i - 1].arrival);
}

static void another_seed_gives_another_stream(void **state) {
  ball_racket_script s;
  int na, nb, i, j, equal_centres = 0;
  (void)state;
  network_script(&s, 42);
  na = collect(&player_a, &s, 1, 10.0, 1.0 / 60.0, 64, stream_a);
  s.seed = 4242;
  nb = collect(&player_b, &s, 1, 10.0, 1.0 / 60.0, 64, stream_b);
  /* with 1 cm of noise two seeds never give the same centre for a sample */
  for (i = 0; i < na; ++i)
    for (j = 0; j < nb; ++j)
      if (stream_a[i].index == stream_b[j].index && stream_a[i].sample.center.x == stream_b[j].sample.center.x)
        equal_centres++;
  assert_int_equal(equal_centres, 0);
}

/* ---- loss, duplicates ---- */

static void loss_one_half_drops_about_half(void **state) {
  ball_racket_script s;
  uint64_t seed;
  (void)state;
  still_script(&s, 100.0);
  s.loss = 0.5;
  for (seed = 1; seed <= 5; ++seed) {
    int n;
    s.seed = seed;
    /* 2000 samples taken (k = 0 .. 1999, t <= 19.99 s); the number kept is
     * Binomial(2000, 0.5): mean 1000, sd sqrt(2000 / 4) = 22.4; bound 5 sd */
    n = collect(&player_a, &s, 1, 19.995, 0.5, 256, stream_a);
    if (n < 888 || n > 1112) fail_msg("seed %lu: %d of 2000 samples kept", (unsigned long)seed, n);
  }
  s.loss = 0.0;
  assert_int_equal(collect(&player_a, &s, 1, 19.995, 0.5, 256, stream_a), 2000);
}

static void duplicates_are_exact_copies_about_as_often_as_asked(void **state) {
  ball_racket_script s;
  int n, i, copies = 0, originals = 0;
  (void)state;
  still_script(&s, 100.0);
  s.duplicate = 0.3;
  s.noise = 0.01;
  s.jitter = 0.05;
  s.seed = 9;
  /* every sample taken by t = 20 s (k = 0 .. 2000) has arrived by 20.05 s */
  n = collect(&player_a, &s, 1, 20.05, 0.5, 256, stream_a);
  for (i = 0; i < n; ++i) {
    int j;
    if (stream_a[i].index > 2000) continue;
    if (!stream_a[i].copy) {
      originals++;
      continue;
    }
    copies++;
    for (j = 0; j < n; ++j)
      if (stream_a[j].index == stream_a[i].index && !stream_a[j].copy) break;
    assert_true(j < n);
    assert_true(memcmp(&stream_a[j].sample, &stream_a[i].sample, sizeof stream_a[i].sample) == 0);
    assert_true(stream_a[j].arrival != stream_a[i].arrival); /* each copy has its own jitter */
  }
  assert_int_equal(originals, 2001);
  /* copies ~ Binomial(2001, 0.3): mean 600.3, sd 20.5; bound 5 sd */
  assert_true(copies >= 498 && copies <= 703);
}

/* ---- delay, jitter ---- */

static void delay_shifts_every_arrival_by_exactly_the_delay(void **state) {
  ball_racket_script s;
  int na, nb, i;
  (void)state;
  network_script(&s, 7);
  s.delay = 0.0;
  na = collect(&player_a, &s, 1, 30.0, 1.0 / 60.0, 64, stream_a);
  s.delay = 0.25;
  nb = collect(&player_b, &s, 1, 30.25, 1.0 / 60.0, 64, stream_b);
  assert_int_equal(na, nb);
  for (i = 0; i < na; ++i) {
    /* the same sample, noise and all, 0.25 s later (to the rounding of one
     * addition at t <= 30 s: 1e-12 s) */
    assert_int_equal(stream_a[i].index, stream_b[i].index);
    assert_int_equal(stream_a[i].copy, stream_b[i].copy);
    assert_true(memcmp(&stream_a[i].sample, &stream_b[i].sample, sizeof stream_a[i].sample) == 0);
    assert_near(stream_b[i].arrival - stream_a[i].arrival, 0.25, 1e-12);
  }
  /* without jitter, arrival = t + delay */
  s.jitter = 0.0;
  nb = collect(&player_b, &s, 1, 10.0, 1.0 / 60.0, 64, stream_b);
  for (i = 0; i < nb; ++i) assert_near(stream_b[i].arrival - stream_b[i].sample.t, 0.25, 1e-12);
}

static void jitter_delivers_out_of_order_within_its_bounds(void **state) {
  ball_racket_script s;
  int n, i, inverted = 0;
  static unsigned long arrival_rank[MAX_STREAM];
  (void)state;
  still_script(&s, 60.0);
  s.delay = 0.03;
  s.jitter = 0.1;
  s.seed = 11;
  /* by 10.13 s every sample taken by 10 s (k = 0 .. 600) has arrived, and
   * some later ones */
  n = collect(&player_a, &s, 1, 10.0 + 0.13, 1.0 / 60.0, 64, stream_a);
  for (i = 0; i <= 600; ++i) arrival_rank[i] = MAX_STREAM;
  for (i = 0; i < n; ++i) {
    double lag = stream_a[i].arrival - stream_a[i].sample.t;
    assert_true(lag >= 0.03 - 1e-12 && lag <= 0.13 + 1e-12);
    if (i > 0) assert_true(stream_a[i].arrival >= stream_a[i - 1].arrival);
    if (stream_a[i].index <= 600) arrival_rank[stream_a[i].index] = (unsigned long)i;
  }
  for (i = 0; i <= 600; ++i) assert_true(arrival_rank[i] < MAX_STREAM);
  /* sample k + 1 arrives before sample k when U(k+1) - U(k) < -(1/60) / 0.1
   * = -1/6: probability (5/6)^2 / 2 = 0.347, so about 208 of 600 pairs; the
   * pairs overlap, so allow a wide band: [150, 270] */
  for (i = 0; i < 600; ++i)
    if (arrival_rank[i + 1] < arrival_rank[i]) inverted++;
  assert_true(inverted >= 150 && inverted <= 270);
  /* and none at all without jitter */
  s.jitter = 0.0;
  n = collect(&player_a, &s, 1, 10.0, 1.0 / 60.0, 64, stream_a);
  for (i = 1; i < n; ++i) assert_true(stream_a[i].sample.t > stream_a[i - 1].sample.t);
}

/* ---- noise ---- */

static void noise_has_the_stated_sigma(void **state) {
  ball_racket_script s;
  int n, i;
  double sum = 0.0, sum2 = 0.0, nsum2 = 0.0, m, sd, nsd;
  (void)state;
  still_script(&s, 100.0);
  s.noise = 0.01;
  s.normal_noise = 0.05;
  s.seed = 3;
  n = collect(&player_a, &s, 1, 39.995, 0.5, 256, stream_a);
  assert_int_equal(n, 4000);
  for (i = 0; i < n; ++i) {
    const ball_racket_sample *x = &stream_a[i].sample;
    double d[3], r;
    int j;
    d[0] = x->center.x - 1.0;
    d[1] = x->center.y - 2.0;
    d[2] = x->center.z - 3.0;
    for (j = 0; j < 3; ++j) {
      sum += d[j];
      sum2 += d[j] * d[j];
    }
    /* the normal (1, 0, 0) tilted by sigma g across it: y / x = sigma g_y */
    assert_near(x->normal.x * x->normal.x + x->normal.y * x->normal.y + x->normal.z * x->normal.z, 1.0, 1e-12);
    r = x->normal.y / x->normal.x;
    nsum2 += r * r;
  }
  /* 12000 centre deviations: the mean within 4 sd of the mean
   * (4 * 0.01 / sqrt(12000) = 3.7e-4 m), the sd within 4 % (the relative sd
   * of a sample sd is 1 / sqrt(2 N) = 0.65 %: 6 sd) */
  m = sum / (3.0 * n);
  sd = sqrt(sum2 / (3.0 * n) - m * m);
  assert_true(fabs(m) < 3.7e-4);
  assert_near(sd, 0.01, 0.04 * 0.01);
  /* 4000 tilts: relative sd of the sd 1.1 %; bound 5 % */
  nsd = sqrt(nsum2 / n);
  assert_near(nsd, 0.05, 0.05 * 0.05);
}

/* ---- arguments ---- */

static void bad_scripts_and_polls_are_rejected(void **state) {
  ball_racket_script s;
  ball_script_sample out[4];
  const char *field = NULL;
  int n = -1;
  (void)state;
  still_script(&s, 60.0);
  assert_int_equal(ball_script_check(&s, &field), BALL_OK);
  s.rate = 121.0;
  assert_int_equal(ball_script_check(&s, &field), BALL_ERANGE);
  assert_string_equal(field, "rate");
  assert_int_equal(ball_script_player_init(&player_a, &s, 1), BALL_ERANGE);
  still_script(&s, 60.0);
  s.delay = NAN;
  assert_int_equal(ball_script_check(&s, &field), BALL_ENONFINITE);
  assert_string_equal(field, "delay");
  still_script(&s, 60.0);
  s.keyframes[0].normal = ball_v3(0.0, 0.0, 0.0);
  assert_int_equal(ball_script_check(&s, &field), BALL_ERANGE);
  assert_string_equal(field, "keyframes[0].normal");
  /* keyframes far out once gave infinite poses; the world's limits hold */
  still_script(&s, 60.0);
  s.keyframes[0].center.x = 1e308;
  assert_int_equal(ball_script_check(&s, &field), BALL_ERANGE);
  assert_string_equal(field, "keyframes[0].center");
  still_script(&s, 60.0);
  s.keyframes[0].t = -2e9;
  assert_int_equal(ball_script_check(&s, &field), BALL_ERANGE);
  assert_string_equal(field, "keyframes[0].t");
  still_script(&s, 60.0);
  s.noise = 1e308;
  assert_int_equal(ball_script_check(&s, &field), BALL_ERANGE);
  assert_string_equal(field, "noise");
  still_script(&s, 60.0);
  s.loss = 1.0;
  assert_int_equal(ball_script_check(&s, &field), BALL_ERANGE);
  assert_string_equal(field, "loss");
  still_script(&s, 60.0);
  assert_int_equal(ball_script_player_init(&player_a, &s, BALL_MAX_RACKETS + 1), BALL_ERANGE);
  assert_int_equal(ball_script_player_init(&player_a, &s, 1), BALL_OK);
  assert_int_equal(ball_script_poll(&player_a, NAN, out, 4, &n), BALL_ENONFINITE);
  assert_int_equal(ball_script_poll(NULL, 1.0, out, 4, &n), BALL_EINVAL);
  assert_int_equal(ball_script_poll(&player_a, 1.0, out, -1, &n), BALL_ERANGE);
  assert_int_equal(ball_script_poll(&player_a, 1.0, out, 0, &n), BALL_OK);
  assert_int_equal(n, 0);
  /* a racket without keyframes is silent */
  s.n_keyframes = 0;
  assert_int_equal(ball_script_player_init(&player_a, &s, 1), BALL_OK);
  assert_int_equal(ball_script_poll(&player_a, 5.0, out, 4, &n), BALL_OK);
  assert_int_equal(n, 0);
}

/* ---- scene files ---- */

static void script_keys_land_in_the_scene(void **state) {
  static const char text[] =
      "rackets:\n"
      "  - radius: 0.2\n"
      "  - script:\n"
      "      keyframes:\n"
      "        - {t: 0.5, center: [1, 2, 3], normal: [0, 0, 2]}\n"
      "        - {t: 1.5, center: [4, 5, 6], normal: [3, 4, 0]}\n"
      "      repeat: 2.5\n"
      "      rate: 6\n"
      "      delay: 0.1\n"
      "      jitter: 0.02\n"
      "      loss: 0.1\n"
      "      duplicate: 0.05\n"
      "      noise: 0.003\n"
      "      normal_noise: 0.01\n"
      "      seed: 18446744073709551615\n";
  static ball_scene scene;
  ball_scene_error err;
  const ball_racket_script *s;
  (void)state;
  assert_int_equal(ball_scene_load_string(text, strlen(text), "mem.yaml", &scene, &err), BALL_OK);
  assert_int_equal(scene.scripts[0].n_keyframes, 0);
  s = &scene.scripts[1];
  assert_int_equal(s->n_keyframes, 2);
  assert_true(s->keyframes[1].t == 1.5 && s->keyframes[1].center.z == 6.0);
  assert_true(s->keyframes[0].normal.z == 1.0);                                /* normalised */
  assert_near(s->keyframes[1].normal.x, 0.6, 1e-16);
  assert_near(s->keyframes[1].normal.y, 0.8, 1e-16);
  assert_true(s->repeat == 2.5 && s->rate == 6.0 && s->delay == 0.1 && s->jitter == 0.02);
  assert_true(s->loss == 0.1 && s->duplicate == 0.05 && s->noise == 0.003 && s->normal_noise == 0.01);
  assert_true(s->seed == UINT64_C(18446744073709551615));
}

/* text must fail at line:column with field. */
static void expect_script_error(const char *text, int line, int column, const char *field, const char *words) {
  static ball_scene scene;
  ball_scene_error err;
  ball_status st = ball_scene_load_string(text, strlen(text), "mem.yaml", &scene, &err);
  if (st != BALL_EPARSE || err.line != line || err.column != column || strcmp(err.field, field) != 0 ||
      !strstr(err.message, words))
    fail_msg("status %d at %d:%d field \"%s\": %s; expected %d:%d %s (%s)", (int)st, err.line, err.column, err.field,
             err.message, line, column, field, words);
}

#define HEAD "rackets:\n  - script:\n      keyframes:\n        - {t: 0, center: [1, 1, 5], normal: [1, 0, 0]}\n"

static void bad_script_fields_are_rejected_with_line_and_field(void **state) {
  static char many[8192];
  size_t used;
  int i;
  (void)state;
  expect_script_error(HEAD "      rate: 1\n", 5, 13, "rackets[0].script.rate", "must be in [2, 120] Hz");
  expect_script_error(HEAD "      rate: 120.5\n", 5, 13, "rackets[0].script.rate", "must be in [2, 120] Hz");
  expect_script_error(HEAD "      loss: 1\n", 5, 13, "rackets[0].script.loss", "must be in [0, 1)");
  expect_script_error(HEAD "      duplicate: -0.1\n", 5, 18, "rackets[0].script.duplicate", "must be in [0, 1]");
  expect_script_error(HEAD "      jitter: 0.6\n", 5, 15, "rackets[0].script.jitter", "must be in [0, 0.5] s");
  expect_script_error(HEAD "      delay: -1\n", 5, 14, "rackets[0].script.delay", "must be in [0, 60] s");
  expect_script_error(HEAD "      noise: .nan\n", 5, 14, "rackets[0].script.noise", "finite");
  expect_script_error(HEAD "      normal_noise: 2\n", 5, 21, "rackets[0].script.normal_noise", "in [0, 1] rad");
  expect_script_error(HEAD "      seed: -1\n", 5, 13, "rackets[0].script.seed", "expected an integer");
  expect_script_error(HEAD "      seed: 1.5\n", 5, 13, "rackets[0].script.seed", "expected an integer");
  expect_script_error(HEAD "      seed: 18446744073709551616\n", 5, 13, "rackets[0].script.seed", "out of range");
  expect_script_error(HEAD "        - {t: 1, center: [2, 1, 5], normal: [1, 0, 0]}\n      repeat: 0.5\n", 6, 15,
                      "rackets[0].script.repeat", "must be 0 or > the keyframes' span (1 s)");
  expect_script_error(HEAD "      jiter: 0.1\n", 5, 7, "rackets[0].script.jiter", "unknown key");
  expect_script_error(HEAD "        - {t: 0, center: [2, 1, 5], normal: [1, 0, 0]}\n", 5, 15,
                      "rackets[0].script.keyframes[1].t", "must increase strictly");
  expect_script_error(HEAD "        - {t: 1, center: [2, 1, 5], normal: [0, 0, 0]}\n", 5, 45,
                      "rackets[0].script.keyframes[1].normal", "must not be (nearly) zero");
  expect_script_error(HEAD "        - {t: 1, center: [2, 1]}\n", 5, 11, "rackets[0].script.keyframes[1].normal",
                      "missing required key");
  expect_script_error("rackets:\n  - {}\n  - script:\n      rate: 30\n", 4, 7, "rackets[1].script.keyframes",
                      "missing required key");
  expect_script_error("rackets:\n  - script: {keyframes: []}\n", 2, 25, "rackets[0].script.keyframes",
                      "at least one keyframe");
  /* 65 keyframes: one too many */
  used = (size_t)snprintf(many, sizeof many, "rackets:\n  - script:\n      keyframes:\n");
  for (i = 0; i < 65; ++i)
    used += (size_t)snprintf(many + used, sizeof many - used, "        - {t: %d, center: [0, 1, 0], normal: [1, 0, 0]}\n", i);
  expect_script_error(many, 4, 9, "rackets[0].script.keyframes", "65 keyframes given, at most 64");
}

static void example_scenes_with_scripts_load(void **state) {
  static const char *const files[] = {"rally_easy.yaml", "rally_mid.yaml", "rally_advanced.yaml",
                                      "serve.yaml",      "smash_6hz.yaml", "drop_shot.yaml"};
  static const int rackets[] = {2, 2, 2, 1, 1, 1};
  static ball_scene scene;
  const char *dir = getenv("BALL_SCENES");
  size_t i;
  (void)state;
  for (i = 0; i < sizeof files / sizeof files[0]; ++i) {
    char path[1024];
    ball_scene_error err;
    int r;
    snprintf(path, sizeof path, "%s/%s", dir && *dir ? dir : "libball/scenes", files[i]);
    if (ball_scene_load_file(path, &scene, &err) != BALL_OK) fail_msg("%s: %s", files[i], err.message);
    assert_int_equal(scene.model.n_rackets, rackets[i]);
    assert_true(scene.model.effects & BALL_EFFECT_RACKETS);
    for (r = 0; r < rackets[i]; ++r) {
      const char *field = NULL;
      assert_true(scene.scripts[r].n_keyframes >= 1);
      assert_int_equal(ball_script_check(&scene.scripts[r], &field), BALL_OK);
    }
  }
}

/* Every script ball_script_check accepts gives finite poses and
 * samples ball_racket_push takes: keyframes at the limits, the largest
 * noise, the longest repeat (the example was keyframes at +-1e308, which
 * gave 600 infinite samples). */
static void scripts_at_the_limits_give_finite_valid_samples(void **state) {
  static ball_script_player player;
  ball_racket_script s;
  ball_script_sample out[64];
  ball_model m;
  ball_sim sim;
  const double c = 1e9 - 1e4;
  int n, i, k, pushed = 0;
  (void)state;
  ball_script_default(&s);
  s.n_keyframes = 2;
  s.keyframes[0].t = -1e9;
  s.keyframes[0].center = ball_v3(-c, c, -c);
  s.keyframes[0].normal = ball_v3(1, 0, 0);
  s.keyframes[1].t = 1e9;
  s.keyframes[1].center = ball_v3(c, -c, c);
  s.keyframes[1].normal = ball_v3(0, 1, 0);
  s.noise = 1e3;
  s.normal_noise = 1.0;
  s.repeat = 2e9 + 1.0;
  s.rate = 120.0;
  assert_int_equal(ball_script_check(&s, NULL), BALL_OK);
  ball_model_default(&m);
  m.effects |= BALL_EFFECT_RACKETS;
  m.n_rackets = 1;
  assert_ok(ball_sim_init(&sim, &m));
  assert_ok(ball_script_player_init(&player, &s, 1));
  for (k = 1; k <= 60; k++) {
    assert_ok(ball_script_poll(&player, k / 60.0, out, 64, &n));
    for (i = 0; i < n; i++) {
      ball_status st;
      assert_true(ball_v3_finite(out[i].sample.center) && ball_v3_finite(out[i].sample.normal));
      st = ball_racket_push(&sim, 0, &out[i].sample);
      assert_true(st == BALL_OK || st == BALL_ESTALE || st == BALL_EDUPLICATE);
      pushed += st == BALL_OK;
    }
  }
  assert_true(pushed > 50);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      cmocka_unit_test(keyframes_interpolate_linearly_and_hold_outside),
      cmocka_unit_test(repeat_wraps_from_last_keyframe_back_to_first),
      cmocka_unit_test(noise_free_samples_are_the_scripted_pose_at_k_over_rate),
      cmocka_unit_test(same_seed_gives_the_same_stream_whatever_the_polling),
      cmocka_unit_test(another_seed_gives_another_stream),
      cmocka_unit_test(loss_one_half_drops_about_half),
      cmocka_unit_test(duplicates_are_exact_copies_about_as_often_as_asked),
      cmocka_unit_test(delay_shifts_every_arrival_by_exactly_the_delay),
      cmocka_unit_test(jitter_delivers_out_of_order_within_its_bounds),
      cmocka_unit_test(noise_has_the_stated_sigma),
      cmocka_unit_test(bad_scripts_and_polls_are_rejected),
      cmocka_unit_test(scripts_at_the_limits_give_finite_valid_samples),
      cmocka_unit_test(script_keys_land_in_the_scene),
      cmocka_unit_test(bad_script_fields_are_rejected_with_line_and_field),
      cmocka_unit_test(example_scenes_with_scripts_load),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
