// Rackets: the sphere, disc and swept tests on the detection study's seeded
// swings (kit/swings.h) at sample rates from 2 to 120 Hz (hit rate,
// false hits, time of impact, cost), and the four responses at each game
// level: how far the ball lands from where the player aimed (from the
// partner, for the autonomous ball).
#include <algorithm>
#include <cmath>

#include "accuracy.h"
#include "bench_kit.h"
#include "common.h"
#include "swings.h"

namespace acc {

namespace {

const double kRates[] = {2, 6, 10, 15, 30, 60, 120};

// ---- detection ----

// ns per frame (push + step) over the swings' frames, the sim's start left out.
double swing_frame_cost(const ball_model &m, const std::vector<swing> &swings, double overhead) {
  double spent = 0.0;
  long frames = 0;
  for (const swing &sw : swings) {
    ball_sim sim;
    ball_state st;
    ball_event ev[8];
    st.position = sw.seg.p0;
    st.velocity = sw.seg.v0;
    st.spin = sw.seg.s0;
    ball_sim_init(&sim, &m);
    ball_sim_set_state(&sim, &st);
    ball_racket_push(&sim, 0, &sw.s[0]);
    double t0 = bench_now();
    for (int k = 1; k < sw.n; k++) {
      ball_racket_push(&sim, 0, &sw.s[k]);
      ball_step(&sim, sw.s[k].t - sim.time, ev, 8, NULL);
    }
    spent += bench_now() - t0 - overhead;
    frames += sw.n - 1;
    bench_sink = sim.time;
  }
  return 1e9 * spent / static_cast<double>(frames);
}

void detection(const Options &opt, Report &rep) {
  RacketResults &out = rep.rackets;
  out.swings = opt.swings;
  ball_model m[BALL_DETECT_COUNT];
  for (int d = 0; d < BALL_DETECT_COUNT; d++) swing_model(&m[d], static_cast<ball_detect>(d));
  ball_model base = m[BALL_DETECT_DISC];
  base.effects &= ~static_cast<unsigned>(BALL_EFFECT_RACKETS);
  bool sims_ok = true;
  for (double rate : kRates) {
    DetectRow row;
    row.rate = rate;
    seeded_rng rng = {20240601ULL};  // the same swings at every rate, sampled differently
    std::vector<swing> timed;
    for (int i = 0; i < opt.swings; i++) {
      swing sw;
      double closest, root, t_sim = -1.0;
      swing_make(&m[0], &rng, 1.0 / rate, &sw);
      double t_true = swing_ground_truth(&m[0], &sw, &closest, &root);
      if (t_true >= 0) row.truth++;
      for (int d = 0; d < BALL_DETECT_COUNT; d++) {
        if (swing_simulate(&m[d], &sw, &t_sim, NULL) != BALL_OK) sims_ok = false;
        if (t_true >= 0 && t_sim >= 0) {
          double e = std::fabs(t_sim - root);
          row.found[d]++;
          row.toi_mean[d] += e;
          row.toi_max[d] = std::max(row.toi_max[d], e);
        }
        if (t_true >= 0 && t_sim < 0) row.missed[d]++;
        if (t_true < 0 && t_sim >= 0) row.false_hits[d]++;
      }
      if (i < opt.cost_swings) timed.push_back(sw);
    }
    for (int d = 0; d < BALL_DETECT_COUNT; d++)
      if (row.found[d]) row.toi_mean[d] /= row.found[d];
    // the frames with each test and without a racket stage, interleaved
    // round by round so that a disturbance of the machine hits all four
    std::vector<double> t[BALL_DETECT_COUNT + 1];
    double overhead = 1e-9 * bench_timer_overhead();
    for (int r = 0; r < opt.rounds; r++) {
      for (int d = 0; d < BALL_DETECT_COUNT; d++) t[d].push_back(swing_frame_cost(m[d], timed, overhead));
      t[BALL_DETECT_COUNT].push_back(swing_frame_cost(base, timed, overhead));
    }
    for (int d = 0; d < BALL_DETECT_COUNT; d++) row.frame_ns[d] = stat_of(t[d]);
    row.base_ns = stat_of(t[BALL_DETECT_COUNT]);
    out.detect.push_back(row);
  }

  FILE *f = open_data(opt, "detect.dat");
  std::fprintf(f, "# ball_accuracy racket tests: one block per test, one row per sample rate (= frame rate)\n"
                  "# rate_hz hit_pct false_per_1000_swings toi_mean_s toi_max_s frame_ns_min frame_ns_med "
                  "test_ns (the least frame minus the least frame without a racket stage)\n");
  for (int d = 0; d < BALL_DETECT_COUNT; d++) {
    std::fprintf(f, "\"%s\" rate hit false toi_mean toi_max ns_min ns_med test_ns\n",
                 ball_detect_name(static_cast<ball_detect>(d)));
    for (const DetectRow &r : out.detect)
      std::fprintf(f, "%g %.4f %.4f %.6e %.6e %.2f %.2f %.2f\n", r.rate, 100.0 * r.found[d] / std::max(r.truth, 1),
                   1000.0 * r.false_hits[d] / out.swings, std::max(r.toi_mean[d], 1e-16),
                   std::max(r.toi_max[d], 1e-16), r.frame_ns[d].min, r.frame_ns[d].median,
                   r.frame_ns[d].min - r.base_ns.min);
    std::fprintf(f, "\n\n");
  }
  std::fclose(f);

  check(rep, "every swing runs through ball_step", sims_ok, sims_ok ? "all BALL_OK" : "a step failed");
  int swept_missed = 0, bad_rate = 0;
  double swept_toi = 0.0;
  for (const DetectRow &r : out.detect) {
    swept_missed += r.missed[BALL_DETECT_SWEPT];
    swept_toi = std::max(swept_toi, r.toi_max[BALL_DETECT_SWEPT]);
    for (int d = 0; d < BALL_DETECT_COUNT; d++) {
      double hit = static_cast<double>(r.found[d]) / std::max(r.truth, 1);
      bad_rate += !(hit >= 0.0 && hit <= 1.0) || r.found[d] + r.missed[d] != r.truth;
    }
  }
  check(rep, "hit rates are in [0, 1] and found + missed = the ground truth's hits", bad_rate == 0,
        bv::fmt("%d bad cells", bad_rate));
  check(rep, "the swept test finds every ground-truth hit at every rate", swept_missed == 0,
        bv::fmt("%d missed over %d swings at 7 rates", swept_missed, out.swings));
  check(rep, "the swept test's time of impact is the ground truth's to 1e-9 s", swept_toi < 1e-9,
        bv::fmt("largest |error| %.1e s", swept_toi));
  const DetectRow &lo = out.detect.front(), &hi = out.detect.back();
  check(rep, "the sphere test misses more at 2 Hz than at 120 Hz",
        lo.missed[BALL_DETECT_SPHERE] * hi.truth > hi.missed[BALL_DETECT_SPHERE] * lo.truth,
        bv::fmt("missed %d of %d at 2 Hz, %d of %d at 120 Hz", lo.missed[BALL_DETECT_SPHERE], lo.truth,
                hi.missed[BALL_DETECT_SPHERE], hi.truth));
}

// ---- the responses at each game level ----

const double kLandingRates[] = {10, 60};
const ball_vec3 kPartner = {21.0, 1.0, 5.485};  // the partner's racket, at rest
const double kContactX = 2.5;                   // where the player meets the ball, m

// One stroke: the incoming ball, where the player meets it, what the player
// aims at, and the player's errors (seeded; the same for every response).
struct Stroke {
  ball_segment seg;     // the incoming ball from t = 0 (no spin)
  double t;             // s: when it reaches the contact point (any phase of the frames)
  ball_vec3 x, v_in;    // the planned contact point and the ball's velocity there
  ball_vec3 aim;        // the point on the floor the player aims at
  double v_up;          // the aimed shot's vertical launch speed (clears the net by 0.3 m)
  double delay;         // s: the racket passes its point late (or early)
  ball_vec3 offset;     // m: off the face's centre (projected into the face's plane)
  double speed_err;     // relative error of the racket speed
  ball_vec3 turn, tilt; // random unit directions for the swing's and the face's angle errors
  double turn_deg, tilt_deg;
  double accel;         // m/s^2 along the swing (speeding up or slowing down)
  unsigned long long noise;  // the tracker noise's seed
};

ball_vec3 perp_unit(ball_vec3 n, ball_vec3 r) {
  return ball_v3_unit(ball_v3_sub(r, ball_v3_scale(n, ball_v3_dot(r, n))));
}

// eq 3 horizontally: the distance b (1 - e^(-t/b)) covered per m/s of speed.
double reach(double b, double t) { return -b * std::expm1(-t / b); }

// The launch from x that lands (ball centre at the radius) at the aim with
// vertical speed v_up, eq 3 solved for the horizontal speed.
ball_vec3 aimed_launch(const ball_model &m, ball_vec3 x, ball_vec3 aim, double v_up) {
  double b = m.mass / m.air_friction, g = m.gravity;
  double t_f = (v_up + std::sqrt(v_up * v_up + 2.0 * g * (x.y - m.radius))) / g;
  double dx = aim.x - x.x, dz = aim.z - x.z, d = std::hypot(dx, dz), vh = d / reach(b, t_f);
  return ball_v3(vh * dx / d, v_up, vh * dz / d);
}

// Height of that launch where it passes the net's plane.
double height_at_net(const ball_model &m, ball_vec3 x, ball_vec3 v) {
  double b = m.mass / m.air_friction, g = m.gravity, k = (m.net.position - x.x) / (v.x * b);
  if (k >= 1.0) return -1.0;
  double t = -b * std::log1p(-k);
  return x.y + v.y * t - 0.5 * g * t * t;
}

Stroke make_stroke(const ball_model &m, bv::Rng &rng) {
  Stroke s;
  double b = m.mass / m.air_friction, g = m.gravity, tc = rng.uniform(0.4, 0.5);
  s.t = tc;
  s.x = ball_v3(kContactX, rng.uniform(0.8, 1.3), rng.uniform(2.0, 9.0));
  s.v_in = ball_v3(-rng.uniform(12.0, 25.0), rng.uniform(-3.0, 1.0), rng.uniform(-2.0, 2.0));
  // the segment from t = 0 that is at x with v_in at tc (eq 3)
  ball_vec3 v0 = ball_v3(s.v_in.x * std::exp(tc / b), s.v_in.y + g * tc, s.v_in.z * std::exp(tc / b));
  double d = reach(b, tc);
  s.seg = ball_segment{};
  s.seg.p0 = ball_v3(s.x.x - v0.x * d, s.x.y - (v0.y * tc - 0.5 * g * tc * tc), s.x.z - v0.z * d);
  s.seg.v0 = v0;
  s.aim = ball_v3(rng.uniform(15.0, 22.0), m.radius, rng.uniform(1.5, 9.5));
  s.v_up = rng.uniform(3.0, 5.0);
  while (height_at_net(m, s.x, aimed_launch(m, s.x, s.aim, s.v_up)) < m.net.top + m.radius + 0.3) s.v_up += 0.25;
  s.delay = rng.uniform(-0.01, 0.01);
  s.offset = ball_v3_scale(rng.unit(), 0.06 * std::sqrt(rng.uniform(0.0, 1.0)));
  s.speed_err = rng.uniform(-0.05, 0.05);
  s.turn = rng.unit();
  s.tilt = rng.unit();
  s.turn_deg = rng.uniform(0.0, 3.0);
  s.tilt_deg = rng.uniform(0.0, 3.0);
  s.accel = rng.uniform(-10.0, 10.0);
  s.noise = static_cast<unsigned long long>(rng.uniform(1.0, 1e15));
  return s;
}

// eq 8, 9 with friendlyFactor 1: from q to the partner at q's height.
ball_vec3 friendly_launch(const ball_model &m, ball_vec3 q) {
  double b = m.mass / m.air_friction, t0 = 2.0 * m.v_up / m.gravity, f = 1.0 / reach(b, t0);
  return ball_v3((kPartner.x - q.x) * f, m.v_up, (kPartner.z - q.z) * f);
}

// The racket velocity and normal that give the aimed launch with each
// response, for a player who knows the response (no errors yet).
void plan(const ball_model &m, const Stroke &s, ball_vec3 *u, ball_vec3 *n) {
  ball_vec3 want = aimed_launch(m, s.x, s.aim, s.v_up);
  switch (m.response) {
    case BALL_RESPONSE_MIXED: {
      // eq 10 solved for the racket: V_racket = (V0 - ff V_f) / (1 - ff)
      double ff = m.friendly_factor;
      *u = ball_v3_scale(ball_v3_sub(want, ball_v3_scale(friendly_launch(m, s.x), ff)), 1.0 / (1.0 - ff));
      *n = ball_v3_unit(*u);
      break;
    }
    case BALL_RESPONSE_PHYSICAL: {
      // eq 11 with V_racket along n (no brush, so no spin: S_racket = V_racket x n = 0):
      // V0 = V + (n.V_racket - 2 n.V) n, so n = unit(V0 - V)
      ball_vec3 dv = ball_v3_sub(want, s.v_in);
      *n = ball_v3_unit(dv);
      *u = ball_v3_scale(*n, ball_v3_norm(dv) + 2.0 * ball_v3_dot(*n, s.v_in));
      break;
    }
    default:  // eq 7 follows the racket; the autonomous ball ignores it (eq 9)
      *u = want;
      *n = ball_v3_unit(want);
      break;
  }
}

// The racket's path with the player's errors: it passes x + offset at
// the contact time + delay with velocity u (turned and scaled), accelerating along it,
// its face tilted.
struct Swing {
  ball_vec3 c, u, a, n;
  double t;
  ball_vec3 at(double time) const {
    double w = time - t;
    return ball_v3_add(ball_v3_add(c, ball_v3_scale(u, w)), ball_v3_scale(a, 0.5 * w * w));
  }
};

Swing with_errors(const Stroke &s, ball_vec3 u, ball_vec3 n) {
  const double deg = M_PI / 180.0;
  Swing w;
  ball_vec3 du = ball_v3_unit(u);
  double speed = ball_v3_norm(u) * (1.0 + s.speed_err);
  w.u = ball_v3_scale(ball_v3_unit(ball_v3_add(du, ball_v3_scale(perp_unit(du, s.turn), std::tan(s.turn_deg * deg)))),
                      speed);
  w.n = ball_v3_unit(ball_v3_add(n, ball_v3_scale(perp_unit(n, s.tilt), std::tan(s.tilt_deg * deg))));
  w.a = ball_v3_scale(du, s.accel);
  w.c = ball_v3_add(s.x, ball_v3_sub(s.offset, ball_v3_scale(n, ball_v3_dot(s.offset, n))));
  w.t = s.t + s.delay;
  return w;
}

// What became of a stroke.
struct Outcome {
  bool hit = false;
  double distance = INFINITY;  // m: the landing from the aim (autonomous: the ball from the partner)
  double across = 0.0;         // m: autonomous only: the horizontal part of that distance
};

// One stroke through ball_step at `rate` (samples of both rackets every
// frame, 2 mm of tracker noise).
Outcome play(const ball_model &step_m, const ball_model &court, const Stroke &s, double rate, bool *ok) {
  Outcome out;
  ball_vec3 u, n;
  plan(step_m, s, &u, &n);
  Swing w = with_errors(s, u, n);
  ball_sim sim;
  ball_state st;
  ball_event ev[8];
  int n_ev;
  seeded_rng noise = {s.noise};
  st.position = s.seg.p0;
  st.velocity = s.seg.v0;
  st.spin = ball_v3(0.0, 0.0, 0.0);
  *ok = ball_sim_init(&sim, &step_m) == BALL_OK && ball_sim_set_state(&sim, &st) == BALL_OK;
  const double dt = 1.0 / rate;
  for (long k = 0; *ok && k * dt <= s.t + 0.3; k++) {
    double t = k * dt;
    ball_racket_sample player, partner;
    player.t = partner.t = t;
    player.center = ball_v3_add(w.at(t), swing_rnd3(&noise, -0.002, 0.002));
    player.normal = w.n;
    partner.center = kPartner;
    partner.normal = ball_v3(-1.0, 0.0, 0.0);
    *ok = ball_racket_push(&sim, 0, &player) == BALL_OK &&
          ball_racket_push(&sim, 1, &partner) == BALL_OK;
    if (!*ok || k == 0) continue;
    *ok = ball_step(&sim, t - sim.time, ev, 8, &n_ev) == BALL_OK;
    for (int i = 0; *ok && i < n_ev; i++) {
      if (ev[i].kind != BALL_EVENT_RACKET) continue;
      // where it comes down: on the court (net and floor) from the hit on
      ball_event path[16];
      ball_prediction pr;
      pr.states = nullptr;
      pr.cap_states = 0;
      pr.events = path;
      pr.cap_events = 16;
      ball_state at;
      out.hit = true;
      if (step_m.response == BALL_RESPONSE_AUTONOMOUS) {
        // eq 8: at the partner after t0 = 2 V_up / g, at the stroke's height
        double t_goal = ev[i].time + 2.0 * step_m.v_up / step_m.gravity;
        *ok = ball_predict(&court, &ev[i].segment, ev[i].time, t_goal, 0.01, &pr) == BALL_OK &&
              ball_segment_eval(&court, &pr.end, t_goal, &at) == BALL_OK;
        out.distance = ball_v3_dist(at.position, kPartner);
        out.across = std::hypot(at.position.x - kPartner.x, at.position.z - kPartner.z);
        return out;
      }
      *ok = ball_predict(&court, &ev[i].segment, ev[i].time, ev[i].time + 6.0, 0.01, &pr) == BALL_OK;
      for (int j = 0; j < pr.n_events; j++)
        if (path[j].kind == BALL_EVENT_FLOOR) {
          out.distance = std::hypot(path[j].point.x - s.aim.x, path[j].point.z - s.aim.z);
          break;
        }
      return out;
    }
  }
  return out;
}

void landing(const Options &opt, Report &rep) {
  RacketResults &out = rep.rackets;
  bool ok_all = true;
  double auto_across = 0.0;
  for (double rate : kLandingRates)
    for (ball_level level : {BALL_LEVEL_EASY, BALL_LEVEL_MID, BALL_LEVEL_ADVANCED})
      for (ball_response resp :
           {BALL_RESPONSE_RACKET, BALL_RESPONSE_AUTONOMOUS, BALL_RESPONSE_MIXED, BALL_RESPONSE_PHYSICAL}) {
        // the level's preset, then the response swapped in (mixed with the
        // paper's friendlyFactor 0.8, autonomous with 1); a tennis ball on
        // the default court, the player's racket and the partner's
        ball_model court;
        ball_model_default(&court);
        ball_model_set_level(&court, level);
        court.response = resp;
        court.friendly_factor = resp == BALL_RESPONSE_MIXED ? 0.8 : 1.0;
        court.radius = 0.033;
        court.n_rackets = 2;
        court.rackets[0].radius = court.rackets[1].radius = 0.15;
        court.rackets[0].partner = 1;
        court.rackets[1].partner = 0;
        // the stroke is stepped with the rackets only (the incoming ball
        // starts beyond the net); the landing is found on the court
        ball_model step_m = court;
        step_m.effects &= ~static_cast<unsigned>(BALL_EFFECT_FLOOR | BALL_EFFECT_NET | BALL_EFFECT_SOUND);
        LandingCell cell;
        cell.level = level;
        cell.response = resp;
        cell.rate = rate;
        bv::Rng rng(20240601, 21);  // the same strokes in every cell
        for (int i = 0; i < opt.landing_swings; i++) {
          Stroke s = make_stroke(court, rng);
          bool ok;
          Outcome o = play(step_m, court, s, rate, &ok);
          ok_all = ok_all && ok;
          cell.strokes++;
          if (o.hit) {
            cell.hits++;
            cell.distance.push_back(o.distance);
            auto_across = std::max(auto_across, o.across);
          }
        }
        std::sort(cell.distance.begin(), cell.distance.end());
        out.landing.push_back(cell);
      }

  FILE *f = open_data(opt, "landing.dat");
  std::fprintf(f, "# ball_accuracy landing: one block per rate, level and response (in that order of\n"
                  "# nesting: rates 10, 60 Hz; easy, mid, advanced; racket, autonomous, mixed, physical):\n"
                  "# distance from the aim (autonomous: from the partner) in m, and the share of the hits\n"
                  "# that land at least that close\n");
  for (const LandingCell &c : out.landing) {
    std::fprintf(f, "\"%s\" distance share\n", ball_response_name(c.response));
    std::fprintf(f, "%.6e 0\n", 1e-3);
    for (size_t k = 0; k < c.distance.size(); k++)
      if (std::isfinite(c.distance[k]))
        std::fprintf(f, "%.6e %.6f\n", std::max(c.distance[k], 1e-3), (k + 1.0) / c.distance.size());
    std::fprintf(f, "\n\n");
  }
  std::fclose(f);

  check(rep, "every stroke runs through ball_step and ball_predict", ok_all, ok_all ? "all BALL_OK" : "a call failed");
  int bad = 0;
  for (const LandingCell &c : out.landing) bad += c.hits > c.strokes || static_cast<int>(c.distance.size()) != c.hits;
  check(rep, "hit counts are within the strokes", bad == 0, bv::fmt("%d bad cells", bad));
  // eq 8, 9 put the ball over the partner's racket after t0, at the stroke's height
  check(rep, "the autonomous ball arrives above or below the partner's racket (eq 8, 9)", auto_across < 1e-9,
        bv::fmt("largest horizontal miss %.1e m", auto_across));
}

}  // namespace

void run_rackets(const Options &opt, Report &rep) {
  detection(opt, rep);
  landing(opt, rep);
}

}  // namespace acc
