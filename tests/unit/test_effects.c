/* The effect mask: a scene with an effect switched off gives bit-identical
 * results (the sim compared with memcmp after every frame, every event field
 * bit for bit) to the model without that effect, in both schemes (each test
 * once per scheme: schemes.h).
 *
 * What "the model without it" means, effect by effect:
 *   drag    (eq 2, 3) -> air friction beta = 0 (b infinite: the parabola);
 *   spin    (eq 4, 13, 14) -> a ball with zero spin: eq 4 keeps it zero,
 *           eq 13 adds 0 x n = 0 at the floor, eq 14 keeps 0;
 *   floor   (eq 5) -> there is no "no floor" parameter: a floor so far down
 *           (floor_level = -1e9 m) that the ball never reaches it;
 *   net     (Fig. 3, eq 6) -> has_net = 0;
 *   walls   -> n_walls = 0;
 *   rackets -> n_rackets = 0;
 *   sound   -> sound_threshold = +Inf (no bounce is loud enough).
 * The "off" scene keeps every parameter of the effect at a value that would
 * matter (beta > 0, a spinning ball, walls in place, ...), and for each effect
 * the full scene is checked to differ from the "off" one, so the comparison
 * is about a stage that really is skipped. */
#include <setjmp.h>
#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>

#include <cmocka.h>

#include "core_common.h"

#define FRAMES 420 /* 7 s at 60 Hz */
#define FPS 60.0

/* The tennis court with a back wall (core_court_scene), a side wall at z =
 * -0.5 and a spinning ball: the serve hits the net, comes back, bounces, hits
 * the walls and bounces on. */
static void full_scene(ball_model *m, ball_scheme scheme) {
  ball_plane side = {2, -0.5, -5.0, 30.0, 0.0, 4.0, 0.7};
  core_court_scene(m);
  m->spin_damping = 2.0;
  m->spin_floor_damping = 0.8;
  m->effects |= BALL_EFFECT_SPIN;
  m->scheme = scheme;
  assert_ok(ball_model_add_wall(m, &side));
  m->initial_velocity = ball_v3(12.0, 3.0, -0.5);
  m->initial_spin = ball_v3(0.5, 0.0, 2.0);
}

static int same_bits(const void *a, const void *b, size_t n) { return memcmp(a, b, n) == 0; }

/* Every field bit for bit (not the struct: its padding is not a value). */
static int event_same(const ball_event *a, const ball_event *b) {
  return a->kind == b->kind && a->index == b->index && a->sound == b->sound &&
         same_bits(&a->time, &b->time, sizeof a->time) &&
         same_bits(&a->point, &b->point, sizeof a->point) &&
         same_bits(&a->velocity_in, &b->velocity_in, sizeof a->velocity_in) &&
         same_bits(&a->velocity_out, &b->velocity_out, sizeof a->velocity_out) &&
         same_bits(&a->spin_out, &b->spin_out, sizeof a->spin_out) &&
         same_bits(&a->segment.t0, &b->segment.t0, sizeof a->segment.t0) &&
         same_bits(&a->segment.p0, &b->segment.p0, sizeof a->segment.p0) &&
         same_bits(&a->segment.v0, &b->segment.v0, sizeof a->segment.v0) &&
         same_bits(&a->segment.s0, &b->segment.s0, sizeof a->segment.s0) &&
         a->segment.grounded == b->segment.grounded;
}

/* The sims' state, every byte but what is not state: the model each
 * owns, and the contact cache (a model without the floor caches "no
 * contact", one with an unreachable floor a contact in 1e150 s). */
static int sims_same(const ball_sim *a, const ball_sim *b) {
  ball_sim x = *a, y = *b;
  memset(&x.next, 0, sizeof x.next);
  memset(&y.next, 0, sizeof y.next);
  return memcmp(&x, &y, offsetof(ball_sim, model)) == 0;
}

/* Steps both models side by side; returns the first frame where the sims or
 * the events differ, or -1 if none. *events counts the events of a. */
static int first_difference(const ball_model *a, const ball_model *b, int *events) {
  ball_sim sa, sb;
  ball_event ea[BALL_MAX_CONTACTS], eb[BALL_MAX_CONTACTS];
  int f, na, nb, k;
  *events = 0;
  assert_ok(ball_sim_init(&sa, a));
  assert_ok(ball_sim_init(&sb, b));
  if (!sims_same(&sa, &sb)) return 0;
  for (f = 1; f <= FRAMES; f++) {
    assert_ok(ball_step(&sa, 1.0 / FPS, ea, BALL_MAX_CONTACTS, &na));
    assert_ok(ball_step(&sb, 1.0 / FPS, eb, BALL_MAX_CONTACTS, &nb));
    *events += na;
    if (na != nb || !sims_same(&sa, &sb)) return f;
    for (k = 0; k < na; k++)
      if (!event_same(&ea[k], &eb[k])) return f;
  }
  return -1;
}

typedef void (*edit_fn)(ball_model *m);

static void drag_without(ball_model *m) { m->air_friction = 0.0; }
static void spin_without(ball_model *m) { m->initial_spin = ball_v3(0.0, 0.0, 0.0); }
static void floor_without(ball_model *m) { m->floor_level = -BALL_MAX_COORD; }
static void net_without(ball_model *m) { m->has_net = 0; }
static void walls_without(ball_model *m) { m->n_walls = 0; }
static void rackets_without(ball_model *m) { m->n_rackets = 0; }
static void sound_without(ball_model *m) { m->sound_threshold = INFINITY; }

/* The racket "off" scene has two rackets defined (that would be tested if
 * the stage ran); the others keep the full scene's parameters. */
static void rackets_defined(ball_model *m) { m->n_rackets = 2; }

static void check_effect(ball_scheme scheme, unsigned effect, edit_fn without, edit_fn off_extra, int must_matter) {
  ball_model full, off, none;
  int frame, events;
  full_scene(&full, scheme);
  off = full;
  if (off_extra) off_extra(&off);
  off.effects &= ~effect;
  none = full;
  none.effects |= effect;
  without(&none);
  frame = first_difference(&off, &none, &events);
  if (frame >= 0)
    fail_msg("%s off vs the model without it (%s scheme): differ at frame %d",
             ball_effect_name((ball_effect)effect), ball_scheme_name(scheme), frame);
  assert_true(events >= 1);
  if (must_matter && first_difference(&full, &off, &events) < 0)
    fail_msg("%s (%s scheme): the scene does not depend on it; the test would prove nothing",
             ball_effect_name((ball_effect)effect), ball_scheme_name(scheme));
}

static void effect_drag_off_is_bit_identical_to_beta_zero_eq3(void **state) {
  check_effect(test_scheme(state), BALL_EFFECT_DRAG, drag_without, NULL, 1);
}

static void effect_spin_off_is_bit_identical_to_zero_spin_eq4_eq13_eq14(void **state) {
  check_effect(test_scheme(state), BALL_EFFECT_SPIN, spin_without, NULL, 1);
}

static void effect_floor_off_is_bit_identical_to_an_unreachable_floor_eq5(void **state) {
  check_effect(test_scheme(state), BALL_EFFECT_FLOOR, floor_without, NULL, 1);
}

static void effect_net_off_is_bit_identical_to_no_net_eq6(void **state) {
  check_effect(test_scheme(state), BALL_EFFECT_NET, net_without, NULL, 1);
}

static void effect_walls_off_is_bit_identical_to_no_walls_eq6(void **state) {
  check_effect(test_scheme(state), BALL_EFFECT_WALLS, walls_without, NULL, 1);
}

/* Without racket samples the rackets cannot change the ball; this checks the
 * mask and the racket-free model agree bit for bit (the racket stage's own
 * effect is for the racket tests). */
static void effect_rackets_off_is_bit_identical_to_no_rackets(void **state) {
  check_effect(test_scheme(state), BALL_EFFECT_RACKETS, rackets_without, rackets_defined, 0);
}

static void effect_sound_off_is_bit_identical_to_infinite_sound_threshold_eq5(void **state) {
  check_effect(test_scheme(state), BALL_EFFECT_SOUND, sound_without, NULL, 1);
}

int main(void) {
  const struct CMUnitTest tests[] = {
      EACH_SCHEME(effect_drag_off_is_bit_identical_to_beta_zero_eq3),
      EACH_SCHEME(effect_spin_off_is_bit_identical_to_zero_spin_eq4_eq13_eq14),
      EACH_SCHEME(effect_floor_off_is_bit_identical_to_an_unreachable_floor_eq5),
      EACH_SCHEME(effect_net_off_is_bit_identical_to_no_net_eq6),
      EACH_SCHEME(effect_walls_off_is_bit_identical_to_no_walls_eq6),
      EACH_SCHEME(effect_rackets_off_is_bit_identical_to_no_rackets),
      EACH_SCHEME(effect_sound_off_is_bit_identical_to_infinite_sound_threshold_eq5),
  };
  return cmocka_run_group_tests(tests, NULL, NULL);
}
