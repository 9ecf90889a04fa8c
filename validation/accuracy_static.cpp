// Static obstacles: the paper's sampled scheme (Fig. 1, 3: tests at the end
// of each frame) against the exact scheme (contacts in closed form) at frame
// rates from 2 to 120 Hz: the bounces of a tennis ball (time, point, energy
// after 10 bounces) against a reference worked out here in long double, shots
// at the net (tunnelling and false hits), and the cost of a frame.
#include <cmath>

#include "accuracy.h"
#include "common.h"
#include "bench_kit.h"

namespace acc {

namespace {

const double kRates[] = {2, 6, 10, 15, 30, 60, 120};
const int kBounces = 10;

// The bounce scene: a tennis ball (b = 2.85 s, radius 0.033 m, floorDamping
// 0.75) on the floor alone, thrown from 1-2.5 m at 2-8 m/s across and 4-7 m/s
// up (seeded): 10 bounces before it slides (bounce_threshold 0.3 m/s).
void bounce_model(ball_model *m, bv::Rng &rng) {
  ball_model_default(m);
  m->radius = 0.033;
  m->has_net = 0;
  m->effects = BALL_EFFECT_DRAG | BALL_EFFECT_FLOOR;
  m->initial_position = ball_v3(0.0, rng.uniform(1.0, 2.5), 0.0);
  m->initial_velocity = ball_v3(rng.uniform(2.0, 8.0), rng.uniform(4.0, 7.0), rng.uniform(-1.0, 1.0));
}

struct Bounce {
  double t;
  ball_vec3 p, v_out;
};

// Energy per unit mass just after a bounce at p: kinetic, plus potential
// above the contact height.
double energy(const ball_model &m, ball_vec3 p, ball_vec3 v) {
  return 0.5 * ball_v3_dot(v, v) + m.gravity * (p.y - m.floor_level - m.radius);
}

// The reference bounces, in long double: eq 3 to the floor contact (the
// descending root of y0 + vy t - g t^2 / 2 = floor + r), eq 5 there, until
// a bounce leaves slower than bounce_threshold.
std::vector<Bounce> reference_bounces(const ball_model &m, int count) {
  std::vector<Bounce> out;
  long double b = (long double)m.mass / m.air_friction, g = m.gravity, t0 = 0.0L;
  long double p[3] = {m.initial_position.x, m.initial_position.y, m.initial_position.z};
  long double v[3] = {m.initial_velocity.x, m.initial_velocity.y, m.initial_velocity.z};
  long double contact = (long double)m.floor_level + m.radius;
  while ((int)out.size() < count) {
    long double tau = (v[1] + sqrtl(v[1] * v[1] + 2.0L * g * (p[1] - contact))) / g;
    long double f = expl(-tau / b), d = -b * expm1l(-tau / b);
    long double vin[3] = {v[0] * f, v[1] - g * tau, v[2] * f};
    p[0] += v[0] * d;
    p[1] = contact;
    p[2] += v[2] * d;
    t0 += tau;
    for (int i = 0; i < 3; i++) v[i] = vin[i] * m.floor_damping;  // eq 5
    v[1] = -v[1];
    if (v[1] < m.bounce_threshold) break;  // grounded: no more bounces
    out.push_back(Bounce{(double)t0, ball_v3((double)p[0], (double)p[1], (double)p[2]),
                         ball_v3((double)v[0], (double)v[1], (double)v[2])});
  }
  return out;
}

// The sim's first `count` floor bounces (or fewer in `limit` s).
std::vector<Bounce> sim_bounces(const ball_model &m, double rate, int count, double limit) {
  std::vector<Bounce> out;
  ball_sim sim;
  ball_event ev[BALL_MAX_CONTACTS];
  int n;
  ball_sim_init(&sim, &m);
  for (long k = 0; k < std::lround(limit * rate) && static_cast<int>(out.size()) < count; k++) {
    if (ball_step(&sim, 1.0 / rate, ev, BALL_MAX_CONTACTS, &n) != BALL_OK) break;
    for (int i = 0; i < n; i++)
      if (ev[i].kind == BALL_EVENT_FLOOR) out.push_back(Bounce{ev[i].time, ev[i].point, ev[i].velocity_out});
  }
  if (static_cast<int>(out.size()) > count) out.resize(count);
  return out;
}

// A shot at the net: a point ball (the paper's Fig. 3) from in front of the
// net aimed at a point of the net's plane; truth from eq 3 in long double.
struct Shot {
  ball_vec3 p0, v0;
  double t_cross;  // s: when the path meets the net's plane
  bool hits;       // the crossing is inside the net's rectangle
};

bool make_shot(const ball_model &m, bv::Rng &rng, Shot *s) {
  const ball_plane &net = m.net;
  double b = m.mass / m.air_friction, g = m.gravity;
  ball_vec3 p0 = ball_v3(rng.uniform(1.0, 10.0), rng.uniform(0.3, 2.5), rng.uniform(1.0, 10.0));
  double ya = rng.uniform(0.02, 1.6), za = rng.uniform(-1.0, 12.0), vh = rng.uniform(8.0, 60.0);
  double dx = net.position - p0.x, dz = za - p0.z, len = std::hypot(dx, dz);
  double vx = vh * dx / len, vz = vh * dz / len;
  if (dx / (vx * b) >= 0.95) return false;  // drag stops it short of the net (eq 3)
  double T = -b * std::log1p(-dx / (vx * b));
  if (T > 3.0) return false;
  // the vertical speed that passes (net.position, ya, za) at T; above the
  // floor all the way (y(t) is concave and both ends are above it)
  double vy = (ya - p0.y + 0.5 * g * T * T) / T;
  s->p0 = p0;
  s->v0 = ball_v3(vx, vy, vz);
  long double lb = b, tc = -lb * log1pl(-(long double)dx / ((long double)vx * lb)), d = -lb * expm1l(-tc / lb);
  double y = (double)((long double)p0.y + (long double)vy * tc - 0.5L * (long double)g * tc * tc);
  double z = (double)((long double)p0.z + (long double)vz * d);
  // leave out the shots that graze an edge to rounding
  if (std::fabs(y - net.top) < 1e-9 || std::fabs(z - net.lo) < 1e-9 || std::fabs(z - net.hi) < 1e-9) return false;
  s->t_cross = (double)tc;
  s->hits = y >= net.bottom && y <= net.top && z >= net.lo && z <= net.hi;
  return true;
}

// The sim's verdict: its first contact is the net.
bool sim_hits_net(ball_model m, const Shot &s, double rate) {
  ball_sim sim;
  ball_event ev[BALL_MAX_CONTACTS];
  int n;
  m.initial_position = s.p0;
  m.initial_velocity = s.v0;
  if (ball_sim_init(&sim, &m) != BALL_OK) return false;
  while (sim.time < s.t_cross + 2.0 / rate) {
    if (ball_step(&sim, 1.0 / rate, ev, BALL_MAX_CONTACTS, &n) != BALL_OK) return false;
    if (n > 0) return ev[0].kind == BALL_EVENT_NET;
  }
  return false;
}

// ns per frame of dt over the model's first `frames` frames (passes of them
// for at least min_time), the sim's start left out of the timing (it would
// weigh on the short runs of low rates).
double frame_cost(const Options &opt, const ball_model &m, double dt, long frames) {
  ball_event ev[BALL_MAX_CONTACTS];
  double spent = 0.0;
  long done = 0;
  do {
    ball_sim sim;
    ball_sim_init(&sim, &m);
    double t0 = bench_now();
    for (long k = 0; k < frames; k++) ball_step(&sim, dt, ev, BALL_MAX_CONTACTS, NULL);
    spent += bench_now() - t0;
    done += frames;
    bench_sink = sim.time;
  } while (spent < opt.min_time);
  return 1e9 * spent / static_cast<double>(done);
}

}  // namespace

void run_static(const Options &opt, Report &rep) {
  StaticResults &out = rep.statics;
  std::vector<ball_model> throws;
  std::vector<std::vector<Bounce>> refs;
  {
    bv::Rng rng(20240601, 11);
    for (int i = 0; i < opt.throws; i++) {
      ball_model bm;
      bounce_model(&bm, rng);
      throws.push_back(bm);
      refs.push_back(reference_bounces(bm, kBounces));
      if (static_cast<int>(refs.back().size()) == kBounces) out.ref_complete++;
    }
  }
  out.throws = opt.throws;

  ball_model court;
  bench_full_scene(&court);
  ball_model net_model;
  ball_model_default(&net_model);
  net_model.radius = 0.0;
  net_model.effects = BALL_EFFECT_DRAG | BALL_EFFECT_FLOOR | BALL_EFFECT_NET;
  std::vector<Shot> shots;
  {
    bv::Rng rng(20240601, 12);
    while (static_cast<int>(shots.size()) < opt.net_shots) {
      Shot s;
      if (make_shot(net_model, rng, &s)) shots.push_back(s);
    }
  }
  out.shots = static_cast<int>(shots.size());

  for (double rate : kRates)
    for (ball_scheme scheme : {BALL_SCHEME_SAMPLED, BALL_SCHEME_EXACT}) {
      StaticRow row;
      row.scheme = scheme;
      row.rate = rate;
      // every throw's first 10 bounces against its reference: the mean over
      // throws of the first bounce's error and of the worst of the 10
      int complete = 0;
      for (size_t i = 0; i < throws.size(); i++) {
        ball_model m = throws[i];
        const std::vector<Bounce> &ref = refs[i];
        m.scheme = scheme;
        std::vector<Bounce> got = sim_bounces(m, rate, kBounces, 120.0);
        if (got.size() < ref.size() || ref.size() < static_cast<size_t>(kBounces)) {
          row.short_throws++;
          continue;
        }
        double worst_dt = 0.0, worst_dp = 0.0;
        for (int k = 0; k < kBounces; k++) {
          worst_dt = std::max(worst_dt, std::fabs(got[k].t - ref[k].t));
          worst_dp = std::max(worst_dp, ball_v3_dist(got[k].p, ref[k].p));
        }
        double e = energy(m, got[kBounces - 1].p, got[kBounces - 1].v_out);
        double e_ref = energy(m, ref[kBounces - 1].p, ref[kBounces - 1].v_out);
        row.first_dt += std::fabs(got[0].t - ref[0].t);
        row.first_dp += ball_v3_dist(got[0].p, ref[0].p);
        row.max_dt += worst_dt;
        row.max_dp += worst_dp;
        row.energy_rel += std::fabs(e - e_ref) / e_ref;
        row.worst_energy_rel = std::max(row.worst_energy_rel, std::fabs(e - e_ref) / e_ref);
        complete++;
      }
      if (complete > 0) {
        row.first_dt /= complete;
        row.first_dp /= complete;
        row.max_dt /= complete;
        row.max_dp /= complete;
        row.energy_rel /= complete;
      }
      ball_model nm = net_model;
      nm.scheme = scheme;
      for (const Shot &s : shots) {
        bool hit = sim_hits_net(nm, s, rate);
        row.net_truth += s.hits;
        row.net_missed += s.hits && !hit;
        row.net_false += !s.hits && hit;
      }
      out.rows.push_back(row);
    }
  // the cost of a frame, the two schemes interleaved round by round so that a
  // disturbance of the machine hits both
  for (double rate : kRates) {
    std::vector<double> t[BALL_SCHEME_COUNT];
    for (int r = 0; r < opt.rounds; r++)
      for (int scheme = 0; scheme < BALL_SCHEME_COUNT; scheme++) {
        ball_model cm = court;
        cm.scheme = static_cast<ball_scheme>(scheme);
        t[scheme].push_back(frame_cost(opt, cm, 1.0 / rate, std::lround(7.0 * rate)));
      }
    for (StaticRow &row : out.rows)
      if (row.rate == rate) row.frame_ns = stat_of(t[row.scheme]);
  }

  FILE *d = open_data(opt, "static.dat");
  std::fprintf(d, "# ball_accuracy static obstacles: one block per scheme, one row per frame rate\n"
                  "# means over the throws: first bounce |dt| s and |dp| m, the worst |dt| and |dp| of 10\n"
                  "# bounces, |E - E_ref| / E_ref after the 10th; net shots missed and made up (%%); ns per frame\n"
                  "# rate_hz first_dt first_dp max_dt max_dp energy_rel net_missed_pct net_false_pct "
                  "frame_ns_min frame_ns_med\n");
  for (ball_scheme scheme : {BALL_SCHEME_SAMPLED, BALL_SCHEME_EXACT}) {
    std::fprintf(d, "\"%s\" rate first_dt first_dp max_dt max_dp energy missed false ns_min ns_med\n",
                 ball_scheme_name(scheme));
    for (const StaticRow &r : out.rows)
      if (r.scheme == scheme)
        std::fprintf(d, "%g %.6e %.6e %.6e %.6e %.6e %.4f %.4f %.3f %.3f\n", r.rate, std::max(r.first_dt, 1e-16),
                     std::max(r.first_dp, 1e-16), std::max(r.max_dt, 1e-16), std::max(r.max_dp, 1e-16),
                     std::max(r.energy_rel, 1e-16),
                     100.0 * r.net_missed / std::max(r.net_truth, 1),
                     100.0 * r.net_false / std::max(out.shots - r.net_truth, 1), r.frame_ns.min,
                     r.frame_ns.median);
    std::fprintf(d, "\n\n");
  }
  std::fclose(d);

  check(rep, "every throw has 10 reference bounces", out.ref_complete == out.throws,
        bv::fmt("%d of %d throws", out.ref_complete, out.throws));
  double ex_dt = 0.0, ex_dp = 0.0, ex_e = 0.0;
  int ex_missed = 0, ex_false = 0, short_throws = 0, late = 0;
  for (const StaticRow &r : out.rows) {
    if (r.scheme == BALL_SCHEME_EXACT) {
      ex_dt = std::max(ex_dt, r.max_dt);
      ex_dp = std::max(ex_dp, r.max_dp);
      ex_e = std::max(ex_e, r.worst_energy_rel);
      ex_missed += r.net_missed;
      ex_false += r.net_false;
      short_throws += r.short_throws;
    } else if (r.first_dt > 1.0 / r.rate + 1e-12) {
      late++;
    }
  }
  check(rep, "the exact scheme bounces where the reference does at every rate",
        short_throws == 0 && ex_dt < 1e-9 && ex_dp < 1e-9 && ex_e < 1e-9,
        bv::fmt("%d throws short of 10 bounces; errors up to %.1e s, %.1e m, energy %.1e", short_throws, ex_dt,
                ex_dp, ex_e));
  check(rep, "the exact scheme misses no net hit and makes none up", ex_missed == 0 && ex_false == 0,
        bv::fmt("%d missed, %d false over %d shots at each of 7 rates", ex_missed, ex_false, out.shots));
  check(rep, "the sampled scheme finds the first bounce within the frame after it", late == 0,
        bv::fmt("%d rates late by more than a frame on average", late));
  const StaticRow &first = out.rows.front();
  check(rep, "the net study has hits and misses",
        first.net_truth > out.shots / 5 && first.net_truth < out.shots * 4 / 5,
        bv::fmt("%d of %d shots meet the net", first.net_truth, out.shots));
}

}  // namespace acc
