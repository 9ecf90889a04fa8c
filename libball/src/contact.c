/* The first contact of a moving ball with an obstacle, given the distance
 * between them as a function of time (internal.h): the swept racket test's
 * search. (The net's and walls' edges use planes.c's own search: their
 * distance is convex in space, which allows a second-order bound.)
 *
 * It rests on one bound: L, the fastest the distance can change. From a
 * time where the ball is d clear, no contact can come sooner than d / L, so
 * the search advances by that much (conservative advancement, as FCL does),
 * and by at least 1/BALL__CONTACT_MIN_STEPS of the interval when it is
 * close. Each step from a to b catches a contact three ways:
 *   - the distance is <= 0 at b;
 *   - the probe's `side` changes sign and the crossing point is `inside`
 *     (a thin or point ball through a zero-thickness disc);
 *   - a graze: the distance may dip below 0 between a and b (it cannot when
 *     (d_a + d_b - L (b - a)) / 2 > 0); then the step is halved, earliest
 *     half first, until that bound clears it or a touching time is found.
 * The contact time is then refined (regula falsi with Illinois steps and a
 * bisection every third step) until the clear and the touching time are
 * adjacent doubles. The whole search makes at most BALL__CONTACT_MAX_PROBES
 * evaluations; out of them, it says so and where the ball was last clear. */
#include "internal.h"

#define BALL__CONTACT_MIN_STEPS 64   /* a step near the obstacle is at most 1/64 of the interval */
#define BALL__CONTACT_MAX_PROBES 2048 /* distance evaluations per search, at most */
#define BALL__CONTACT_REFINE 200     /* refinement iterations, at most (about 15 are used) */
#define BALL__CONTACT_GRAZE_DEPTH 48 /* halvings of a step in a graze search */

typedef struct search {
  const ball__contact_query *q;
  int probes; /* left in the budget */
} search;

static ball__probe probe_at(search *se, double t) {
  ball__probe p;
  se->probes--;
  p = se->q->probe(se->q->ctx, t);
  p.t = t;
  return p;
}

typedef double (*probe_value)(const ball__probe *p);
static double value_dist(const ball__probe *p) { return p->dist; }
static double value_side(const ball__probe *p) { return p->side; }

/* The root between a and b of f, where f(a) and f(b) have opposite signs
 * ("a's side" is f > 0 for a distance, the sign of f(a) for a side): regula
 * falsi with Illinois steps, and a bisection every third step, until a and
 * b are adjacent doubles. Returns the end on b's side. */
static ball__probe root(search *se, ball__probe a, ball__probe b, probe_value f, int a_pos) {
  double fa = f(&a), fb = f(&b);
  int i, last = 0;
  for (i = 0; i < BALL__CONTACT_REFINE && se->probes > 0; i++) {
    double tm = 0.5 * (a.t + b.t);
    ball__probe m;
    int m_on_a;
    if (tm <= a.t || tm >= b.t) break; /* adjacent: done */
    if (i % 3 != 2 && fa != fb) {
      double ts = a.t + (b.t - a.t) * (fa / (fa - fb));
      if (ts > a.t && ts < b.t) tm = ts;
    }
    m = probe_at(se, tm);
    m_on_a = a_pos ? f(&m) > 0.0 : (f(&m) > 0.0) == (fa > 0.0);
    if (m_on_a) {
      a = m;
      fa = f(&m);
      if (last == 1) fb *= 0.5; /* Illinois: the stuck end weighs half */
      last = 1;
    } else {
      b = m;
      fb = f(&m);
      if (last == -1) fa *= 0.5;
      last = -1;
    }
  }
  return b;
}

/* First contact in (a, b] where a is clear and b touches. */
static ball__probe refine(search *se, ball__probe a, ball__probe b) {
  ball__probe hit = root(se, a, b, value_dist, 1);
  hit.side = a.side; /* the side the ball came from */
  return hit;
}

/* A contact inside (a, b) though both are clear. Earliest first. */
static int graze(search *se, ball__probe a, ball__probe b, int depth, ball__probe *hit) {
  ball__probe m;
  if ((a.side > 0.0) != (b.side > 0.0) && a.side != 0.0) {
    ball__probe x = root(se, a, b, value_side, 0);
    if (x.inside) {
      /* the centre passes through the obstacle: contact at or before x */
      x.dist = fmin(x.dist, 0.0);
      *hit = refine(se, a, x);
      return 1;
    }
  }
  if (0.5 * (a.dist + b.dist - se->q->rate * (b.t - a.t)) > 0.0) return 0; /* cannot dip to 0 */
  if (depth >= BALL__CONTACT_GRAZE_DEPTH || se->probes <= 0) return 0;
  m = probe_at(se, 0.5 * (a.t + b.t));
  if (!(m.t > a.t && m.t < b.t)) return 0;
  if (m.dist <= 0.0) {
    *hit = refine(se, a, m);
    return 1;
  }
  return graze(se, a, m, depth + 1, hit) || graze(se, m, b, depth + 1, hit);
}

int ball__first_contact(const ball__contact_query *q, ball__probe *hit, int *probes_used) {
  search se;
  ball__probe a, b;
  int found = 0;
  double min_step = (q->tb - q->ta) / BALL__CONTACT_MIN_STEPS;
  se.q = q;
  se.probes = BALL__CONTACT_MAX_PROBES;
  a = probe_at(&se, q->ta);
  *hit = a;
  if (a.dist <= 0.0) found = 1; /* touching at the start: contact at once */
  while (!found && a.t < q->tb && se.probes > 0) {
    /* no contact can come sooner than dist / L: advance by that, at least a step */
    double tb = a.t + fmax(a.dist / q->rate, min_step);
    if (!(tb < q->tb) || q->tb - tb < 1e-3 * min_step) tb = q->tb;
    b = probe_at(&se, tb);
    if (b.dist <= 0.0) {
      *hit = refine(&se, a, b);
      found = 1;
    } else {
      found = graze(&se, a, b, 0, hit);
    }
    a = b;
  }
  if (probes_used) *probes_used = BALL__CONTACT_MAX_PROBES - se.probes;
  if (!found && a.t < q->tb && se.probes <= 0) {
    *hit = a; /* out of evaluations: the last time known clear */
    return 2;
  }
  return found;
}
