/* When a racket's track will first meet the ball (beyond the paper): the
 * earliest frame end t at which one ball_step from the sim as it is finds a
 * hit of a racket, for a server that wakes between its frames at that
 * instant instead of finding the hit at the end of the frame that holds it.
 *
 * The racket is the stage's estimate (interpolation, eq 15 past the newest
 * sample), which is linear in t between sample times: the window is cut
 * there into pieces, each with its own speed bound. In a piece the sphere
 * and disc tests are a distance-like function c(t) of the frame end, <= 0
 * exactly when the test passes, with a bound on how fast it changes: its
 * first zero is found by contact.c's conservative advancement (rigorous
 * given the bound), then the step's own test, run at the candidate times,
 * is bisected to adjacent doubles, so the answer is the step's to the bit.
 * The swept test's hit depends on the whole frame (the disc moves from
 * R_old to R(t) over it), so its frame ends are walked by the distance at
 * the frame's end and the step's swept test run at each; docs/rackets.md,
 * "First contact", says what that finds and what it costs. */
#include <string.h>

#include "internal.h"

#define FC_PROBE_BUDGET 16384 /* distance evaluations per racket (sphere, disc), at most */
#define FC_RESTARTS 8         /* searches resumed per piece after a rounding disagreement */
#define FC_BISECT 200         /* bisection steps on the step's own test, at most (about 60 used) */
#define FC_SWEPT_MIN_STEPS 64 /* a swept piece is walked in at most 1/64 of it per frame end */
#define FC_SWEPT_POINTS 512   /* frame ends tried by the swept walk, at most */
#define FC_SCAN_ROUNDS 4      /* swept: looks back for an earlier edge, at most */

typedef struct query {
  const ball_model *m;
  const ball_sim *sim;
  ball__flight fl;
  int i;                 /* the racket */
  double t0;             /* sim->time: the frame's start */
  ball_racket_pose old;  /* R_old as the stage takes it */
  ball_vec3 a;           /* P_old - R_old */
  double k0;             /* the disc clearance's scale, m */
  int budget;            /* distance evaluations left */
  int tests;             /* the step's test run, for the cost */
} query;

/* The frame end a step of dt = t - t0 reaches: t0 + dt, as ball_step adds it. */
static double frame_end(const query *q, double t) { return q->t0 + (t - q->t0); }

/* The step's own test at frame end t. */
static int passes(query *q, double t, double *t_hit, double *key) {
  q->tests++;
  return ball__racket_test_at(q->m, &q->fl, q->sim, q->i, frame_end(q, t), t_hit, key);
}

static void pose_at(const query *q, double t, ball_racket_pose *pose) {
  ball__racket_pose(q->m, &q->sim->tracks[q->i], t, pose);
}

/* ---- the distance-like functions ---- */

/* The ball relative to the racket's centre at frame end t (*u = P - R),
 * the racket's pose *r, and a probe at t with no crossing to find. */
static ball__probe probe_start(const query *q, double t, ball_vec3 *u, ball_racket_pose *r) {
  ball_state s;
  ball__probe p;
  ball__eval_f(&q->fl, &q->sim->seg, t, &s);
  pose_at(q, t, r);
  *u = ball_v3_sub(s.position, r->center);
  p.t = t;
  p.dist = 0.0;
  p.side = 1.0;
  p.inside = 0;
  return p;
}

/* sphere (section 3): |P - R| - d_COLL, < 0 where the test passes. */
static ball__probe probe_sphere(const void *ctx, double t) {
  const query *q = (const query *)ctx;
  ball_racket_pose r;
  ball_vec3 u;
  ball__probe p = probe_start(q, t, &u, &r);
  p.dist = ball_v3_norm(u) - q->m->collision_distance;
  return p;
}

/* The disc test's normal at frame end t (the stage's). */
static ball_vec3 disc_normal(const query *q, const ball_racket_pose *now) {
  return q->m->normal_mode == BALL_NORMAL_REAL ? q->old.normal : ball__racket_test_normal(q->m, now);
}

/* Fig. 4, 5 as a function of the frame end. With a = P_old - R_old,
 * u = P' - R_old = P - R, side s = sign(a.n), e0 = s a.n - r, e1 = s u.n - r
 * (r the ball's radius, rho = r_disc + r) and L the part across n, the test
 * passes when e0 <= 0 and |L a| <= rho (touching at the start), or when
 * e0 > 0, e1 <= 0 and the crossing (e0 L u - e1 L a) / (e0 - e1) is within
 * rho of the axis: |e0 L u - e1 L a| - rho (e0 - e1) <= 0. Both as one
 * continuous function: min(max(e0, |L a| - rho), max(e1, H / k0, -e0)). */
static ball__probe probe_disc(const void *ctx, double t) {
  const query *q = (const query *)ctx;
  const ball_model *m = q->m;
  ball_racket_pose r;
  ball_vec3 n, u, la, lu;
  double d0, side, e0, e1, rho = m->rackets[q->i].radius + m->radius, h, ca, cb;
  ball__probe p = probe_start(q, t, &u, &r);
  n = disc_normal(q, &r);
  d0 = ball_v3_dot(q->a, n);
  side = d0 >= 0.0 ? 1.0 : -1.0;
  e0 = side * d0 - m->radius;
  e1 = side * ball_v3_dot(u, n) - m->radius;
  la = ball_v3_sub(q->a, ball_v3_scale(n, d0));
  lu = ball_v3_sub(u, ball_v3_scale(n, ball_v3_dot(u, n)));
  h = ball_v3_norm(ball_v3_sub(ball_v3_scale(lu, e0), ball_v3_scale(la, e1))) - rho * (e0 - e1);
  ca = fmax(e0, ball_v3_norm(la) - rho);
  cb = fmax(fmax(e1, h / q->k0), -e0);
  p.dist = fmin(ca, cb);
  return p;
}

/* Swept: the distance from the ball to the disc at the frame's end, face or
 * rim (swept.c's measure), the disc at R(t) with the test's normal then. */
static ball__probe probe_end(const void *ctx, double t) {
  const query *q = (const query *)ctx;
  const ball_model *m = q->m;
  ball_racket_pose r;
  ball_vec3 n, w;
  double d, rho, disc_r = m->rackets[q->i].radius;
  ball__probe p = probe_start(q, t, &w, &r);
  n = ball_v3_unit(ball__racket_test_normal(m, &r));
  d = ball_v3_dot(w, n);
  rho = ball_v3_norm(ball_v3_sub(w, ball_v3_scale(n, d)));
  p.dist = (rho <= disc_r ? fabs(d) : sqrt(d * d + (rho - disc_r) * (rho - disc_r))) - m->radius;
  return p;
}

/* ---- pieces: between sample times the estimate is linear ---- */

typedef struct piece {
  double a, b;   /* the frame ends searched, s */
  double v;      /* bound on the ball centre's speed, m/s */
  double vr;     /* the racket centre's speed, m/s */
  double turn;   /* bound on how fast the test's normal turns, rad/s (2 tan(angle / 2) per span) */
  double u_max;  /* bound on |P - R| over the piece, m */
} piece;

/* The piece starting at a (a sample time or the window's start), up to
 * just before the next sample time or hi. */
static void piece_at(const query *q, double a, double hi, int normal_from_pose, piece *pc) {
  const ball_racket_track *tr = &q->sim->tracks[q->i];
  const ball_model *m = q->m;
  ball_racket_pose r;
  ball_state s;
  int k;
  pc->a = a;
  pc->b = hi;
  pc->turn = 0.0;
  for (k = 0; k < tr->count; k++)
    if (tr->samples[k].t > a) {
      double end = nextafter(tr->samples[k].t, -INFINITY);
      if (end < pc->b) pc->b = end < a ? a : end;
      break;
    }
  pose_at(q, a, &r);
  pc->vr = ball_v3_norm(r.velocity); /* held poses do not move: a bound still */
  /* between two samples the pose normal turns by normalised lerp */
  if (normal_from_pose && k > 0 && k < tr->count &&
      (m->normal_mode == BALL_NORMAL_REAL || pc->vr < BALL__STILL_SPEED)) {
    ball_vec3 n0 = tr->samples[k - 1].normal, n1 = tr->samples[k].normal;
    double span = tr->samples[k].t - tr->samples[k - 1].t, c;
    if (ball_v3_dot(n0, n1) < 0.0) n1 = ball_v3_scale(n1, -1.0);
    c = ball_v3_dot(n0, n1);
    pc->turn = 2.0 * ball_v3_norm(ball_v3_cross(n0, n1)) / (1.0 + c) / span * (1.0 + 1e-9);
  }
  ball__eval_f(&q->fl, &q->sim->seg, a, &s);
  pc->v = ball_v3_norm(s.velocity) + (q->sim->seg.grounded ? 0.0 : q->fl.g * (pc->b - a));
  pc->u_max = ball_v3_norm(ball_v3_sub(s.position, r.center)) + (pc->v + pc->vr) * (pc->b - a);
}

/* The fastest the disc clearance (probe_disc) can change over the piece:
 * each term's derivative bounded by the speeds and the turn. */
static double disc_rate(const query *q, const piece *pc) {
  double v = pc->v + pc->vr, w = q->m->normal_mode == BALL_NORMAL_REAL ? 0.0 : pc->turn;
  double al = ball_v3_norm(q->a), u = pc->u_max, r = q->m->radius, rho = q->m->rackets[q->i].radius + r;
  double le0 = al * w, le1 = v + u * w, lla = 2.0 * al * w, llu = v + 2.0 * u * w;
  double lh = le0 * u + (al + r) * llu + le1 * al + (u + r) * lla + rho * (le0 + le1);
  return fmax(fmax(le1, lla), fmax(lh / q->k0, le0)) * (1.0 + 1e-9) + 1e-300;
}

/* The first frame end in (lo, hi] where the step's test passes, the test
 * false at lo (or lo = t0) and true at hi: bisection to adjacent doubles. */
static double bisect(query *q, double lo, double hi) {
  int it;
  for (it = 0; it < FC_BISECT; it++) {
    double mid = frame_end(q, lo + 0.5 * (hi - lo));
    if (!(mid > lo && mid < hi)) break;
    if (passes(q, mid, NULL, NULL))
      hi = mid;
    else
      lo = mid;
  }
  return hi;
}

/* The swept test's answer need not be monotone in the frame end where a
 * contact begins inside the frame (its search, on the disc moving from
 * R_old to R(t), changes with t): after the bisection, earlier frame ends
 * at distances growing by sqrt 2 from one ulp back to lo are tried, and an earlier
 * hit bisected again; FC_SCAN_ROUNDS times at most. */
static double first_edge(query *q, double lo, double hi) {
  double t = bisect(q, lo, hi);
  int round, k;
  for (round = 0; round < FC_SCAN_ROUNDS; round++) {
    int earlier = 0;
    for (k = 0; k < 2200; k++) {
      double te = frame_end(q, t - ldexp(t - nextafter(t, -INFINITY), k / 2) * (k % 2 ? 1.4142135623730951 : 1.0));
      if (!(te > lo)) break;
      if (passes(q, te, NULL, NULL)) {
        t = bisect(q, lo, te);
        earlier = 1;
        break;
      }
    }
    if (!earlier) break;
  }
  return t;
}

/* Sphere and disc over one piece: 1 with *t_hit, 0 if the test never passes
 * in it, -1 when the evaluation budget ran out (*t_hit: cleared so far). */
static int search_piece(query *q, const piece *pc, double *t_hit) {
  ball__contact_query cq;
  double a = pc->a;
  int restart;
  cq.probe = q->m->detect == BALL_DETECT_SPHERE ? probe_sphere : probe_disc;
  cq.ctx = q;
  cq.rate = q->m->detect == BALL_DETECT_SPHERE ? (pc->v + pc->vr) * (1.0 + 1e-9) + 1e-300 : disc_rate(q, pc);
  for (restart = 0; restart < FC_RESTARTS; restart++) {
    ball__probe hit;
    double tc, lo;
    int used = 0, found, k;
    if (q->budget <= 0) {
      *t_hit = a;
      return -1;
    }
    cq.ta = a;
    cq.tb = pc->b;
    found = ball__first_contact(&cq, &hit, &used);
    q->budget -= used;
    if (found == 0) return 0;
    if (found == 2) { /* out of evaluations: go on from where it was clear */
      a = hit.t;
      continue;
    }
    tc = frame_end(q, hit.t > q->t0 ? hit.t : nextafter(q->t0, INFINITY));
    if (passes(q, tc, NULL, NULL)) {
      lo = nextafter(tc, -INFINITY);
      /* the clearance and the test agree to rounding: the double before
       * passes only if rounding moved the edge; then the test's own edge */
      *t_hit = lo > q->t0 && passes(q, lo, NULL, NULL) ? bisect(q, q->t0, lo) : tc;
      return 1;
    }
    /* the clearance touches where the step's test does not (rounding at a
     * tangent): walk on by doubling steps until the test passes or the
     * clearance is positive again */
    lo = tc;
    for (k = 0; k < 64; k++) {
      double t2 = frame_end(q, tc + ldexp(fabs(nextafter(tc, INFINITY) - tc), k));
      if (!(t2 <= pc->b)) return 0;
      if (passes(q, t2, NULL, NULL)) {
        *t_hit = bisect(q, lo, t2);
        return 1;
      }
      lo = t2;
      q->budget--;
      if (cq.probe(q, t2).dist > 0.0) break;
    }
    a = lo;
  }
  *t_hit = a;
  return -1;
}

/* Swept over one piece: frame ends walked by the distance at the frame's
 * end (a contact that begins there comes no sooner than distance / rate)
 * and at least every 1/FC_SWEPT_MIN_STEPS of the piece, the step's test
 * run at each; the first that passes is bisected back to the last that did
 * not. When the distance at the frame's end touches first (a contact at the
 * frame's end: every contact when R_old is on the track), its zero is the
 * answer. Returns as search_piece. */
static int search_swept(query *q, const piece *pc, double *last_clear, int *points, double *t_hit) {
  double rate = (pc->v + pc->vr + pc->turn * q->m->rackets[q->i].radius) * (1.0 + 1e-9) + 1e-300;
  double min_step = (pc->b - pc->a) / FC_SWEPT_MIN_STEPS, t = pc->a;
  for (;;) {
    double te = frame_end(q, t > q->t0 ? t : nextafter(q->t0, INFINITY)), d, lo = *last_clear;
    ball__probe pe;
    if (++*points > FC_SWEPT_POINTS) return -1;
    if (passes(q, te, NULL, NULL)) {
      /* the zero of the end distance in (lo, te], if it is the edge */
      ball__probe pl = probe_end(q, lo), ph = probe_end(q, te);
      q->budget -= 2;
      if (ph.dist <= 0.0 && pl.dist > 0.0) {
        double a = lo, b = te, tr;
        int it;
        for (it = 0; it < FC_BISECT; it++) {
          double mid = a + 0.5 * (b - a);
          if (!(mid > a && mid < b)) break;
          q->budget--;
          if (probe_end(q, mid).dist <= 0.0)
            b = mid;
          else
            a = mid;
        }
        tr = frame_end(q, b);
        if (passes(q, tr, NULL, NULL) && !(nextafter(tr, -INFINITY) > lo && passes(q, nextafter(tr, -INFINITY), NULL, NULL))) {
          *t_hit = first_edge(q, lo, tr);
          return 1;
        }
      }
      *t_hit = first_edge(q, lo, te); /* a contact that begins inside the frame */
      return 1;
    }
    *last_clear = te;
    if (te >= pc->b) return 0;
    pe = probe_end(q, te);
    q->budget--;
    d = pe.dist > 0.0 ? pe.dist / rate : 0.0;
    t = te + (d > min_step ? d : min_step);
    if (!(t < pc->b) || pc->b - t < 1e-3 * min_step) t = pc->b;
  }
}

/* One racket over (t0, hi]: 1 with *t_hit, 0 if none, -1 if the budget ran
 * out (*searched: how far it got). */
static int search_racket(query *q, double hi, double *t_hit, double *searched) {
  double a = q->t0, last_clear = q->t0;
  int points = 0;
  *searched = hi;
  if (passes(q, nextafter(q->t0, INFINITY), NULL, NULL) && nextafter(q->t0, INFINITY) <= hi) {
    *t_hit = nextafter(q->t0, INFINITY); /* touching already: any step hits */
    return 1;
  }
  while (a <= hi) {
    piece pc;
    int r;
    piece_at(q, a, hi, q->m->detect != BALL_DETECT_SPHERE, &pc);
    r = q->m->detect == BALL_DETECT_SWEPT ? search_swept(q, &pc, &last_clear, &points, t_hit)
                                          : search_piece(q, &pc, t_hit);
    if (r == 1) return 1;
    if (r < 0) {
      *searched = q->m->detect == BALL_DETECT_SWEPT ? last_clear : *t_hit;
      return -1;
    }
    if (pc.b >= hi) break;
    a = nextafter(pc.b, INFINITY);
  }
  return 0;
}

/* ---- the bound: whether a racket's test can find the ball at all ---- */

/* How far the ball's centre gets from P_old over [t0, t1] on its segment
 * (eq 3), along each axis: horizontally |v0x| (d(tau1) - d(tau0)) <=
 * |v0x| (t1 - t0), drag only slows it (z alike); vertically at most the
 * larger |v_y| at the two ends (v_y is linear in tau) times t1 - t0. P_old
 * is the ball at t0: every call that moves the sim (a step, set_segment,
 * set_state, set_model) keeps it so. */
static inline ball_vec3 ball_box(const ball_sim *sim, double t1) {
  const ball_segment *seg = &sim->seg;
  double T = t1 - sim->time, vy = 0.0;
  if (!seg->grounded) {
    double g = sim->model.gravity, a = fabs(seg->v0.y - g * (sim->time - seg->t0)),
           b = fabs(seg->v0.y - g * (t1 - seg->t0));
    vy = a > b ? a : b;
  }
  return ball_v3(fabs(seg->v0.x) * T, vy * T, fabs(seg->v0.z) * T);
}

/* The same as one distance: |v0_h| T + max |v_y| T from the box's half
 * extents (the horizontal ones as a vector, drag slows both alike). */
static double ball_moves(ball_vec3 h) { return sqrt(h.x * h.x + h.z * h.z) + h.y; }

static double farther(double r, ball_vec3 c, ball_vec3 p) {
  double d = ball_v3_dist(c, p);
  return d > r ? d : r;
}

/* From the second newest sample on a racket's track is one line, R(t) =
 * R_n + V (min(t - t_n, extrapolation_time)) with V the two newest
 * samples' velocity (interpolation between them and eq 15 past the
 * newest), held after the extrapolation's end: over a window (t0, t1] that
 * starts there (nearly every look) the track is the chord from *a = R(t0)
 * to *b = R(t1), and this returns 1; 0 when the window starts earlier. */
static inline int track_chord(const ball_model *m, const ball_racket_track *tr, double t0, double t1, ball_vec3 *a,
                       ball_vec3 *b) {
  const ball_racket_sample *s = tr->samples;
  int n = tr->count;
  if (n == 1) {
    *a = *b = s[0].center;
    return 1;
  }
  if (!(t0 >= s[n - 2].t)) return 0;
  {
    ball_vec3 v = ball_v3_scale(ball_v3_sub(s[n - 1].center, s[n - 2].center), 1.0 / (s[n - 1].t - s[n - 2].t));
    double da = t0 - s[n - 1].t, db = t1 - s[n - 1].t;
    if (da > m->extrapolation_time) da = m->extrapolation_time;
    if (db > m->extrapolation_time) db = m->extrapolation_time;
    *a = ball_v3_add(s[n - 1].center, ball_v3_scale(v, da));
    *b = ball_v3_add(s[n - 1].center, ball_v3_scale(v, db));
  }
  return 1;
}

/* A sphere (centre *c, the radius returned) that holds racket i's centre at
 * every frame end in (t0, t1] as the stage estimates it, and R_old: over
 * a chord (track_chord, `line`), the chord a b; otherwise the track's
 * corners in the window, the poses at t0 and t1 and the samples between. */
static double track_sphere(const ball_model *m, const ball_sim *sim, int i, double t1, int line, ball_vec3 a,
                           ball_vec3 b, ball_vec3 *c) {
  const ball_racket_track *tr = &sim->tracks[i];
  double t0 = sim->time, r;
  int k;
  if (!line) {
    ball_racket_pose pa, pb;
    ball__racket_pose(m, tr, t0, &pa);
    ball__racket_pose(m, tr, t1, &pb);
    a = pa.center;
    b = pb.center;
  }
  *c = ball_v3_lerp(a, b, 0.5);
  r = 0.5 * ball_v3_dist(a, b);
  if (!line)
    for (k = 0; k < tr->count; k++)
      if (tr->samples[k].t > t0 && tr->samples[k].t < t1) r = farther(r, *c, tr->samples[k].center);
  return tr->has_prev ? farther(r, *c, tr->prev_pose.center) : r;
}

/* How far from a racket's centre its test can find the ball's centre: d_COLL
 * for the sphere test; for the disc test the disc grown by the ball radius
 * within the ball radius of either face, to the corner of that cylinder,
 * sqrt((r + b)^2 + b^2); the swept test's exact reach r + b is within it. */
static double test_reach(const ball_model *m, int i) {
  double r;
  if (m->detect == BALL_DETECT_SPHERE) return m->collision_distance;
  r = m->rackets[i].radius + m->radius;
  return sqrt(r * r + m->radius * m->radius);
}

/* The same without the square root, never below it: r + 2 b for the disc. */
static inline double test_reach_over(const ball_model *m, int i) {
  return m->detect == BALL_DETECT_SPHERE ? m->collision_distance : m->rackets[i].radius + 2.0 * m->radius;
}

/* One axis of boxes_apart: 1 when the racket's centre (between a and b, or
 * at q) lies farther than the reach from the ball's p +- h along it, by
 * more than rounding (a few ulps of the numbers subtracted). */
static inline int axis_apart(double p, double h, double a, double b, double q, double reach) {
  double lo = a < b ? a : b, hi = a < b ? b : a, e;
  if (q < lo) lo = q;
  if (q > hi) hi = q;
  e = lo - (p + h); /* the racket above the ball's box, or */
  if (!(e > reach)) e = (p - h) - hi; /* below it */
  e -= reach;
  return e > 0.0 && e > 1e-9 + 1e-12 * (fabs(p) + h + fabs(lo) + fabs(hi));
}

/* The cheap half of the bound, with no square root: 1 when the ball's box
 * (P_old +- h, ball_box) and the box of the racket's chord a b and R_old
 * (a again without one) lie farther apart along one axis than the test
 * reaches (the distance is at least that axis's gap; x, the court's length,
 * first); 0: ask the spheres. */
static inline int boxes_apart(ball_vec3 p, ball_vec3 h, ball_vec3 a, ball_vec3 b, ball_vec3 q, double reach) {
  return axis_apart(p.x, h.x, a.x, b.x, q.x, reach) || axis_apart(p.z, h.z, a.z, b.z, q.z, reach) ||
         axis_apart(p.y, h.y, a.y, b.y, q.y, reach);
}

/* 0 when racket i's test cannot pass in a step ending in (sim->time, t1]:
 * the ball within its box h of P_old (ball_box), the racket on its track,
 * and the two farther apart than the test reaches: first as boxes (most
 * looks end there), then as spheres, the ball within ball_moves of P_old
 * and the racket within track_sphere. The disc and swept tests measure the
 * ball (P_old to its end, or along its path) against a disc between R_old
 * and R, all within those boxes and spheres; a margin covers rounding.
 * The track has samples (count > 0: the callers' check). */
static int may_reach(const ball_sim *sim, int i, double t1, ball_vec3 h) {
  const ball_model *m = &sim->model;
  const ball_racket_track *tr = &sim->tracks[i];
  ball_vec3 a, b, c;
  double r, gap, moves;
  int line = track_chord(m, tr, sim->time, t1, &a, &b);
  if (line && boxes_apart(sim->prev_position, h, a, b, tr->has_prev ? tr->prev_pose.center : a, test_reach_over(m, i)))
    return 0;
  moves = ball_moves(h);
  r = track_sphere(m, sim, i, t1, line, a, b, &c);
  gap = ball_v3_dist(sim->prev_position, c) - r - moves - test_reach(m, i);
  if (gap > 1e-2 * (1.0 + r + moves)) return 0; /* (the margin below is smaller: BALL_MAX_COORD) */
  return !(gap > 1e-9 + 1e-12 * (ball_v3_max_abs(c) + ball_v3_max_abs(sim->prev_position) + r + moves));
}

ball_status ball_racket_may_reach(const ball_sim *sim, int racket, double t_end, int *may) {
  const ball_model *m;
  const ball_vec3 *p, *v;
  ball_vec3 h;
  double z;
  int i, lo, hi, found = 0;
  if (!sim || !may) return BALL_EINVAL;
  m = &sim->model;
  if (m->n_rackets < 0 || m->n_rackets > BALL_MAX_RACKETS || racket < -1 || racket >= m->n_rackets)
    return BALL_EINVAL;
  lo = racket < 0 ? 0 : racket;
  hi = racket < 0 ? m->n_rackets : racket + 1;
  for (i = lo; i < hi; i++)
    if (sim->tracks[i].count < 0 || sim->tracks[i].count > BALL_MAX_HISTORY) return BALL_EINVAL;
  /* all finite: their sum is (an overflowing sum asks each) */
  p = &sim->prev_position;
  v = &sim->seg.v0;
  z = (t_end + sim->time + sim->seg.t0) + (p->x + p->y + p->z) + (v->x + v->y + v->z);
  if (!(z - z == 0.0) && (!isfinite(t_end) || !isfinite(sim->time) || !ball_v3_finite(*p) ||
                          !isfinite(sim->seg.t0) || !ball_v3_finite(*v)))
    return BALL_ENONFINITE;
  if (t_end < sim->time || sim->seg.t0 > sim->time) return BALL_ERANGE;
  /* no test in the next step: the effect off, or asleep */
  if (ball__has(m, BALL_EFFECT_RACKETS) && sim->sleep <= 0 && t_end > sim->time) {
    h = ball_box(sim, t_end);
    for (i = lo; i < hi && !found; i++) {
      const ball_racket_track *tr = &sim->tracks[i];
      if (tr->count == 0 || sim->time - tr->samples[tr->count - 1].t > m->stale_time) continue;
      found = may_reach(sim, i, t_end, h);
    }
  }
  *may = found;
  return BALL_OK;
}

/* Argument checks and the window both functions share: BALL_OK with *hi
 * (the window's end; t0 when empty) and the flight, or a status. */
static ball_status prepare(const ball_sim *sim, double t_end, ball__flight *fl, double *hi) {
  ball_state s;
  if (!isfinite(t_end) || !isfinite(sim->time) || !ball_v3_finite(sim->prev_position) ||
      !isfinite(sim->seg.t0) || !ball_v3_finite(sim->seg.p0) || !ball_v3_finite(sim->seg.v0) ||
      !ball_v3_finite(sim->seg.s0))
    return BALL_ENONFINITE;
  if (t_end < sim->time || sim->seg.t0 > sim->time) return BALL_ERANGE;
  ball__flight_of(&sim->model, fl);
  /* a step the stepper would refuse (its flight overflows) */
  ball__eval_f(fl, &sim->seg, t_end, &s);
  if (!ball_v3_finite(s.position) || !ball_v3_finite(s.velocity)) return BALL_ERANGE;
  *hi = t_end > sim->time ? ball__static_window(sim, fl, t_end) : sim->time;
  return BALL_OK;
}

/* One racket, checked: as the public function, out written on OK,
 * BALL_ENOTFOUND and BALL_ESTALE. */
static ball_status first_contact(const ball_sim *sim, const ball__flight *fl, int racket, double t_end,
                                 double hi, ball_racket_contact *out, int *tests) {
  const ball_model *m = &sim->model;
  const ball_racket_track *tr = &sim->tracks[racket];
  query q;
  double t_hit = 0.0, searched = t_end, stale_end, key;
  int r;
  out->racket = racket;
  out->step_to = INFINITY;
  out->time = INFINITY;
  out->searched = t_end;
  if (tr->count < 0 || tr->count > BALL_MAX_HISTORY) return BALL_EINVAL;
  if (tr->count == 0) return BALL_ENOTFOUND; /* as ball_racket_estimate */
  if (sim->time - tr->samples[tr->count - 1].t > m->stale_time) return BALL_ESTALE;
  /* no test in the next step: the effect off, or asleep (sleep counts steps) */
  if (!ball__has(m, BALL_EFFECT_RACKETS) || sim->sleep > 0) return BALL_ENOTFOUND;
  out->searched = hi;
  /* past stale_time after the newest sample the racket does not collide */
  stale_end = tr->samples[tr->count - 1].t + m->stale_time;
  while (stale_end - tr->samples[tr->count - 1].t > m->stale_time) stale_end = nextafter(stale_end, -INFINITY);
  if (stale_end < hi) hi = stale_end;
  if (!(hi > sim->time)) return BALL_ENOTFOUND;
  if (!may_reach(sim, racket, hi, ball_box(sim, hi))) return BALL_ENOTFOUND; /* nearly every frame */
  memset(&q, 0, sizeof q);
  q.m = m;
  q.sim = sim;
  q.fl = *fl;
  q.i = racket;
  q.t0 = sim->time;
  q.budget = FC_PROBE_BUDGET;
  /* R_old as the stage takes it: the previous frame's pose, else the track at t0 */
  if (tr->has_prev) {
    q.old = tr->prev_pose;
  } else {
    ball__racket_pose(m, tr, sim->time, &q.old);
  }
  q.a = ball_v3_sub(sim->prev_position, q.old.center);
  q.k0 = 2.0 * ball_v3_norm(q.a) + m->radius + m->rackets[racket].radius + 1e-300;
  r = search_racket(&q, hi, &t_hit, &searched);
  if (tests) *tests += q.tests;
  if (r != 1) {
    if (r < 0) out->searched = searched;
    return BALL_ENOTFOUND;
  }
  ball__racket_test_at(m, fl, sim, racket, t_hit, &out->time, &key);
  out->step_to = t_hit;
  out->searched = t_hit;
  return BALL_OK;
}

ball_status ball_racket_first_contact(const ball_sim *sim, int racket, double t_end, ball_racket_contact *out) {
  ball__flight fl;
  ball_racket_contact c;
  ball_status st;
  double hi;
  if (!sim || !out) return BALL_EINVAL;
  if (racket < 0 || racket >= sim->model.n_rackets || racket >= BALL_MAX_RACKETS) return BALL_EINVAL;
  st = prepare(sim, t_end, &fl, &hi);
  if (st != BALL_OK) return st;
  st = first_contact(sim, &fl, racket, t_end, hi, &c, NULL);
  if (st == BALL_OK || st == BALL_ENOTFOUND || st == BALL_ESTALE) *out = c;
  return st;
}

ball_status ball_racket_first_contact_any(const ball_sim *sim, double t_end, ball_racket_contact *out) {
  const ball_model *m;
  ball__flight fl;
  ball_racket_contact best, c;
  ball_status st;
  double hi, searched;
  int i;
  if (!sim || !out) return BALL_EINVAL;
  m = &sim->model;
  if (m->n_rackets < 0 || m->n_rackets > BALL_MAX_RACKETS) return BALL_EINVAL;
  st = prepare(sim, t_end, &fl, &hi);
  if (st != BALL_OK) return st;
  best.racket = -1;
  best.step_to = INFINITY;
  best.time = INFINITY;
  searched = t_end;
  for (i = 0; i < m->n_rackets; i++) {
    /* a later racket need only be searched up to the best so far */
    st = first_contact(sim, &fl, i, t_end, best.racket >= 0 && best.step_to < hi ? best.step_to : hi, &c, NULL);
    if (st == BALL_OK) {
      if (c.step_to < best.step_to) best = c;
    } else if (st == BALL_ENOTFOUND || st == BALL_ESTALE) {
      if (c.searched < searched) searched = c.searched;
    } else {
      return st;
    }
  }
  if (best.racket < 0) {
    best.searched = m->n_rackets > 0 ? searched : hi;
    *out = best;
    return BALL_ENOTFOUND;
  }
  /* the step at that frame end tests every racket: the stage's key decides */
  {
    double key_best = INFINITY, key, th;
    for (i = 0; i < m->n_rackets; i++)
      if (ball__racket_test_at(m, &fl, sim, i, best.step_to, &th, &key) && key < key_best) {
        key_best = key;
        best.racket = i;
        best.time = th;
      }
  }
  best.searched = best.step_to;
  *out = best;
  return BALL_OK;
}
