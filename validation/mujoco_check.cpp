// libball's closed form (eq 3) and exact contacts against MuJoCo integrating
// the same ODEs (eq 1, 2).
#include <algorithm>
#include <cstdio>
#include <fstream>

#include "common.h"
#include "mujoco_ball.h"

namespace bv {

namespace {

// Tolerances, chosen on purpose (docs/validation.md explains them).
constexpr double kFlightPosTol = 1e-9;   // m
constexpr double kFlightVelTol = 1e-9;   // m/s
constexpr double kContactTimeTol = 1e-9; // s
constexpr double kContactPosTol = 1e-9;  // m

// RK4 steps for a flight. RK4 is exact for constant gravity (eq 1), so the
// step only has to resolve the exponential of eq 2. Per step RK4 keeps
// e^(-z) to z^5/120 (z = h/b); over a flight that leaves a velocity error of
// at most V z^4 / (120 e) and a position error of at most V b z^4 / 120. The
// step takes the largest z that keeps both under kTruncBudget for
// V = 80 m/s (z = 4.5e-3 at b = 0.05 s, 2.9e-3 at b = 2 s), at most 10 ms.
// Every step also rounds: 10^4 steps of a 100 m/s fall cost about 1e-10 m/s,
// which is why the step is no smaller and grows once the drag is spent:
// phase 1 is the first 40 b (after which V e^(-t/b) < 1e-15 m/s), phase 2
// the rest at 10 ms.
constexpr double kTruncBudget = 1e-10;  // m and m/s
constexpr double kVmax = 80.0;          // m/s
constexpr double kStepMax = 0.01;       // s
constexpr double kDragLife = 40.0;      // b

struct Phase {
  long n;    // steps
  double h;  // s
};

// The two phases covering [0, T] exactly.
void flight_phases(const ball_model &m, double T, Phase ph[2]) {
  double b = m.air_friction > 0.0 ? m.mass / m.air_friction : INFINITY;
  double z = std::min(std::pow(120.0 * kTruncBudget / (kVmax * b), 0.25),
                      std::pow(120.0 * M_E * kTruncBudget / kVmax, 0.25));
  double h1 = std::min(kStepMax, z * b);
  double t1 = h1 < kStepMax ? std::min(T, kDragLife * b) : T;
  ph[0].n = std::max(1L, static_cast<long>(std::ceil(t1 / h1)));
  ph[0].h = t1 / static_cast<double>(ph[0].n);
  ph[1].n = T > t1 ? std::max(1L, static_cast<long>(std::ceil((T - t1) / kStepMax))) : 0;
  ph[1].h = ph[1].n ? (T - t1) / static_cast<double>(ph[1].n) : 0.0;
}

// A random ball: mass from a table-tennis ball to a basketball, beta = 0 in
// one case of ten, otherwise b = m / beta from 0.05 s (strong drag) to 1000 s.
ball_model random_model(Rng &rng) {
  ball_model m;
  ball_model_default(&m);
  m.mass = rng.log_uniform(0.0027, 0.62);
  m.air_friction = rng.chance(0.1) ? 0.0 : m.mass / rng.log_uniform(0.05, 1000.0);
  m.effects = BALL_EFFECT_DRAG;
  return m;
}

double dist(ball_vec3 a, ball_vec3 b) { return ball_v3_norm(ball_v3_sub(a, b)); }

// Cubic Hermite interpolation between two MuJoCo states h apart, s in [0, 1].
ball_vec3 hermite(ball_vec3 p0, ball_vec3 v0, ball_vec3 p1, ball_vec3 v1, double h, double s) {
  double s2 = s * s, s3 = s2 * s;
  double h00 = 2 * s3 - 3 * s2 + 1, h10 = s3 - 2 * s2 + s, h01 = -2 * s3 + 3 * s2, h11 = s3 - s2;
  return ball_v3_add(ball_v3_add(ball_v3_scale(p0, h00), ball_v3_scale(v0, h10 * h)), ball_v3_add(ball_v3_scale(p1, h01), ball_v3_scale(v1, h11 * h)));
}

double axis_of(ball_vec3 p, int axis) { return axis == 0 ? p.x : axis == 1 ? p.y : p.z; }

// Where in [0, 1] the Hermite curve crosses coord along axis (the ends
// bracket it); bisection to the last bit.
double hermite_root(ball_vec3 p0, ball_vec3 v0, ball_vec3 p1, ball_vec3 v1, double h, int axis,
                    double coord) {
  double lo = 0.0, hi = 1.0;
  double flo = axis_of(p0, axis) - coord;
  for (int i = 0; i < 200; i++) {
    double mid = 0.5 * (lo + hi);
    if (mid <= lo || mid >= hi) break;
    double f = axis_of(hermite(p0, v0, p1, v1, h, mid), axis) - coord;
    if ((f > 0) == (flo > 0) && f != 0.0) {
      lo = mid;
      flo = f;
    } else {
      hi = mid;
    }
  }
  return 0.5 * (lo + hi);
}

std::string vec(ball_vec3 v) { return fmt("(%.17g, %.17g, %.17g)", v.x, v.y, v.z); }

}  // namespace

Outcome check_flight(const Options &opt) {
  Outcome out;
  out.check = "validate_flight";
  if (!mj_handlers_selftest()) {
    out.pass = false;
    out.lines.push_back("a MuJoCo error did not come back through the handler: " + mj_last_error());
    return out;
  }
  Rng rng(opt.seed, 1);
  MjBall mj;
  double max_dp = 0, max_dv = 0, max_rel_dp = 0;
  long steps = 0;
  int worst = -1;
  std::string worst_case;
  double t_start = now_s();
  for (int i = 0; i < opt.flights; i++) {
    ball_model m = random_model(rng);
    ball_segment seg{};
    seg.t0 = rng.uniform(0.0, 50.0);
    seg.p0 = rng.box({-5, 0, -2}, {30, 3, 13});
    seg.v0 = ball_v3_scale(rng.unit(), rng.uniform(0.0, 80.0));
    double T = rng.uniform(0.01, 10.0);
    const char *field = nullptr;
    if (ball_model_check(&m, &field) != BALL_OK) {
      out.pass = false;
      out.lines.push_back(fmt("flight %d: ball_model_check rejects %s", i, field ? field : "?"));
      continue;
    }
    Phase ph[2];
    flight_phases(m, T, ph);
    std::string err;
    if (!mj.load(m, mjINT_RK4, ph[0].h, &err) || !mj.reset(seg.p0, seg.v0, ph[0].h) || !mj.step(ph[0].n) ||
        !mj.set_step(ph[1].h) || !mj.step(ph[1].n)) {
      out.pass = false;
      out.lines.push_back(fmt("flight %d: MuJoCo failed: %s %s", i, err.c_str(), mj_last_error().c_str()));
      continue;
    }
    steps += ph[0].n + ph[1].n;
    ball_state s;
    ball_status st = ball_segment_eval(&m, &seg, seg.t0 + T, &s);
    if (st != BALL_OK) {
      out.pass = false;
      out.lines.push_back(fmt("flight %d: ball_segment_eval: %s", i, ball_strerror(st)));
      continue;
    }
    double dp = dist(s.position, mj.position()), dv = dist(s.velocity, mj.velocity());
    double scale_p = std::max(1.0, ball_v3_norm(s.position));
    max_rel_dp = std::max(max_rel_dp, dp / scale_p);
    if (dp > max_dp || dv > max_dv) {
      if (dp > max_dp) worst = i;
      max_dp = std::max(max_dp, dp);
      max_dv = std::max(max_dv, dv);
    }
    if (dp > kFlightPosTol || dv > kFlightVelTol || !std::isfinite(dp) || !std::isfinite(dv)) {
      out.pass = false;
      out.lines.push_back(fmt(
          "flight %d beyond tolerance: mass %.17g beta %.17g t0 %.17g T %.17g p0 %s v0 %s: libball p %s v "
          "%s, MuJoCo p %s v %s (|dp| %.3g m, |dv| %.3g m/s)",
          i, m.mass, m.air_friction, seg.t0, T, vec(seg.p0).c_str(), vec(seg.v0).c_str(),
          vec(s.position).c_str(), vec(s.velocity).c_str(), vec(mj.position()).c_str(),
          vec(mj.velocity()).c_str(), dp, dv));
    }
    if (i == worst)
      worst_case = fmt("worst position case: flight %d, b %.4g s, |V0| %.4g m/s, T %.4g s, phase-1 step %.3g s", i,
                       m.air_friction > 0 ? m.mass / m.air_friction : INFINITY, ball_v3_norm(seg.v0), T, ph[0].h);
  }
  out.lines.insert(out.lines.begin(),
                   {fmt("%d flights (speeds 0-80 m/s, b 0.05-1000 s or no drag, 0.01-10 s), MuJoCo RK4, "
                        "h = min(z b, %.0f ms) with RK4's error bound under %.0e for the first %.0f b, then %.0f ms "
                        "(%ld steps, %.1f s)",
                        opt.flights, kStepMax * 1e3, kTruncBudget, kDragLife, kStepMax * 1e3, steps,
                        now_s() - t_start),
                    fmt("max |position difference| %.3e m (tolerance %.0e m), relative %.3e", max_dp,
                        kFlightPosTol, max_rel_dp),
                    fmt("max |velocity difference| %.3e m/s (tolerance %.0e m/s)", max_dv, kFlightVelTol),
                    worst_case});
  return out;
}

Outcome check_contacts(const Options &opt) {
  Outcome out;
  out.check = "validate_contacts";
  Rng rng(opt.seed, 2);
  MjBall mj;
  const double window = 10.0;  // s of MuJoCo trajectory per case
  double max_floor_dt = 0, max_floor_dp = 0, max_net_dt = 0, max_net_dp = 0;
  int n_floor = 0, n_net = 0, n_net_none = 0, n_net_edge = 0;
  double t_start = now_s();
  for (int i = 0; i < opt.contacts; i++) {
    ball_model m = random_model(rng);
    m.effects = BALL_EFFECT_DRAG | BALL_EFFECT_FLOOR | BALL_EFFECT_NET;
    m.radius = rng.chance(0.2) ? 0.0 : rng.uniform(0.0, 0.2);
    m.floor_level = rng.uniform(-1.0, 1.0);
    m.net.position = rng.uniform(5.0, 15.0);
    double floor_y = m.floor_level + m.radius;
    const double net_x = m.net.position;
    ball_segment seg{};
    seg.t0 = rng.uniform(0.0, 50.0);
    seg.p0 = {rng.uniform(0.0, 24.0), floor_y + rng.uniform(0.01, 4.0), rng.uniform(-2.0, 13.0)};
    if (std::fabs(seg.p0.x - net_x) < 1e-3) seg.p0.x += 0.01;
    seg.v0 = ball_v3_scale(rng.unit(), rng.uniform(0.5, 80.0));
    // most cases head for the net plane
    if (rng.chance(0.8) && (net_x - seg.p0.x) * seg.v0.x < 0) seg.v0.x = -seg.v0.x;
    const char *field = nullptr;
    if (ball_model_check(&m, &field) != BALL_OK) {
      out.pass = false;
      out.lines.push_back(fmt("case %d: ball_model_check rejects %s", i, field ? field : "?"));
      continue;
    }
    Phase ph[2];
    flight_phases(m, window, ph);
    std::string err;
    if (!mj.load(m, mjINT_RK4, ph[0].h, &err) || !mj.reset(seg.p0, seg.v0, ph[0].h)) {
      out.pass = false;
      out.lines.push_back(fmt("case %d: MuJoCo failed: %s %s", i, err.c_str(), mj_last_error().c_str()));
      continue;
    }
    bool floor_found = false, net_found = false, failed = false;
    double floor_t = 0, net_t = 0;
    ball_vec3 floor_p{}, net_p{};
    ball_vec3 p = mj.position(), v = mj.velocity();
    long n = ph[0].n + ph[1].n;
    double tk = 0.0;  // MuJoCo's time at p, v
    for (long k = 0; k < n && !(floor_found && net_found); k++) {
      double h = k < ph[0].n ? ph[0].h : ph[1].h;
      if ((k == ph[0].n && !mj.set_step(h)) || !mj.step(1)) {
        failed = true;
        break;
      }
      ball_vec3 p1 = mj.position(), v1 = mj.velocity();
      if (!floor_found && p.y > floor_y && p1.y <= floor_y) {
        double s = hermite_root(p, v, p1, v1, h, 1, floor_y);
        floor_found = true;
        floor_t = tk + s * h;
        floor_p = hermite(p, v, p1, v1, h, s);
      }
      double a = p.x - net_x, b = p1.x - net_x;
      if (!net_found && (b == 0.0 || (a > 0) != (b > 0))) {
        double s = hermite_root(p, v, p1, v1, h, 0, net_x);
        net_found = true;
        net_t = tk + s * h;
        net_p = hermite(p, v, p1, v1, h, s);
      }
      p = p1;
      v = v1;
      tk = k < ph[0].n ? static_cast<double>(k + 1) * ph[0].h
                       : ph[0].n * ph[0].h + static_cast<double>(k + 1 - ph[0].n) * ph[1].h;
    }
    if (failed) {
      out.pass = false;
      out.lines.push_back(fmt("case %d: MuJoCo failed: %s", i, mj_last_error().c_str()));
      continue;
    }
    // floor: eq 1 gives a descending crossing within 10 s for every case here
    double t_lib;
    ball_vec3 p_lib;
    ball_status st = ball_next_floor_contact(&m, &seg, seg.t0, &t_lib, &p_lib);
    if (st == BALL_OK && t_lib - seg.t0 <= window && floor_found) {
      double dt = std::fabs((t_lib - seg.t0) - floor_t), dp = dist(p_lib, floor_p);
      n_floor++;
      max_floor_dt = std::max(max_floor_dt, dt);
      max_floor_dp = std::max(max_floor_dp, dp);
      if (dt > kContactTimeTol || dp > kContactPosTol) {
        out.pass = false;
        out.lines.push_back(fmt("case %d floor contact differs: libball t %.17g p %s, MuJoCo t %.17g p %s (p0 %s v0 "
                                "%s, b %.17g, floor %.17g)",
                                i, t_lib - seg.t0, vec(p_lib).c_str(), floor_t, vec(floor_p).c_str(),
                                vec(seg.p0).c_str(), vec(seg.v0).c_str(), m.mass / m.air_friction, floor_y));
      }
    } else if (st == BALL_OK && t_lib - seg.t0 > window && !floor_found) {
      // both agree: no floor crossing inside the window
    } else if (!(st == BALL_OK && std::fabs(t_lib - seg.t0 - window) < 1e-6)) {
      out.pass = false;
      out.lines.push_back(fmt("case %d floor: libball %s (t %.17g), MuJoCo %s (t %.17g); p0 %s v0 %s", i,
                              ball_strerror(st), st == BALL_OK ? t_lib - seg.t0 : NAN,
                              floor_found ? "found" : "none", floor_t, vec(seg.p0).c_str(), vec(seg.v0).c_str()));
    }
    // net plane x = net_x (the centre crossing it; eq 3 inverted)
    st = ball_time_to_plane(&m, &seg, seg.t0, 0, net_x, &t_lib);
    bool lib_in = st == BALL_OK && t_lib - seg.t0 <= window;
    if (st == BALL_OK && std::fabs(t_lib - seg.t0 - window) < 1e-6) {
      n_net_edge++;  // at the end of the window: either answer is right
    } else if (lib_in && net_found) {
      ball_state s;
      ball_segment_eval(&m, &seg, t_lib, &s);
      double dt = std::fabs((t_lib - seg.t0) - net_t), dp = dist(s.position, net_p);
      n_net++;
      max_net_dt = std::max(max_net_dt, dt);
      max_net_dp = std::max(max_net_dp, dp);
      if (dt > kContactTimeTol || dp > kContactPosTol) {
        out.pass = false;
        out.lines.push_back(fmt("case %d net-plane crossing differs: libball t %.17g p %s, MuJoCo t %.17g p %s "
                                "(p0 %s v0 %s, mass %.17g beta %.17g)",
                                i, t_lib - seg.t0, vec(s.position).c_str(), net_t, vec(net_p).c_str(),
                                vec(seg.p0).c_str(), vec(seg.v0).c_str(), m.mass, m.air_friction));
      }
    } else if (!lib_in && !net_found && (st == BALL_OK || st == BALL_ENOTFOUND)) {
      n_net_none++;
    } else {
      out.pass = false;
      out.lines.push_back(fmt("case %d net plane: libball %s (t %.17g), MuJoCo %s (t %.17g); p0 %s v0 %s mass "
                              "%.17g beta %.17g",
                              i, ball_strerror(st), st == BALL_OK ? t_lib - seg.t0 : NAN,
                              net_found ? "found" : "none", net_t, vec(seg.p0).c_str(), vec(seg.v0).c_str(),
                              m.mass, m.air_friction));
    }
  }
  out.lines.insert(
      out.lines.begin(),
      {fmt("%d cases, MuJoCo RK4 trajectory (h as for flights), crossings by cubic Hermite "
           "interpolation of the two states around them (%.1f s)",
           opt.contacts, now_s() - t_start),
       fmt("floor (ball_next_floor_contact): %d contacts, max |dt| %.3e s, max |dp| %.3e m (tolerances %.0e s, "
           "%.0e m)",
           n_floor, max_floor_dt, max_floor_dp, kContactTimeTol, kContactPosTol),
       fmt("net plane (ball_time_to_plane): %d crossings, max |dt| %.3e s, max |dp| %.3e m; %d never reach it "
           "in 10 s (both agree), %d at the window's end",
           n_net, max_net_dt, max_net_dp, n_net_none, n_net_edge)});
  return out;
}

// Euler and RK4 at the frame steps a renderer uses, against the closed form:
// the accuracy-vs-time data. One fixed lob (tennis ball, default drag).
Outcome check_sweep(const Options &opt) {
  Outcome out;
  out.check = "validate_sweep";
  ball_model m;
  ball_segment seg;
  bv::sweep_flight(&m, &seg);
  const double T = 2.0;  // s: a whole number of every step below
  const double steps[] = {1.0 / 6, 1.0 / 10, 1.0 / 15, 1.0 / 30, 1.0 / 60, 1.0 / 120, 1e-3, 1e-4};
  const char *step_names[] = {"1/6", "1/10", "1/15", "1/30", "1/60", "1/120", "1e-3", "1e-4"};
  ball_state exact;
  ball_segment_eval(&m, &seg, T, &exact);

  struct Row {
    std::string integrator, step_name;
    double h, pos_err, vel_err, mj_cost, lib_cost, jump_cost;
  };
  std::vector<Row> rows;
  volatile double sink = 0;
  // libball's cost for one closed-form evaluation, far from any step: the
  // same for every row, measured once (a jump straight to T).
  int jumps = 0;
  const double jump_cost = bv::per_call(
      [&] {
        ball_state s;
        ball_segment_eval(&m, &seg, T * (0.5 + 0.5 * (jumps++ & 1)), &s);
        sink = sink + s.position.x;
      },
      opt.sweep_min_time);
  for (int integ : {mjINT_EULER, mjINT_RK4}) {
    MjBall mj;
    std::string err;
    if (!mj.load(m, integ, steps[0], &err)) {
      out.pass = false;
      out.lines.push_back("MuJoCo load failed: " + err);
      return out;
    }
    for (size_t j = 0; j < sizeof steps / sizeof steps[0]; j++) {
      double h = steps[j];
      long n = std::lround(T / h);
      h = T / static_cast<double>(n);
      if (!mj.reset(seg.p0, seg.v0, h) || !mj.step(n)) {
        out.pass = false;
        out.lines.push_back("MuJoCo failed: " + mj_last_error());
        return out;
      }
      Row r;
      r.integrator = integ == mjINT_RK4 ? "RK4" : "Euler";
      r.step_name = step_names[j];
      r.h = h;
      r.pos_err = dist(mj.position(), exact.position);
      r.vel_err = dist(mj.velocity(), exact.velocity);
      // wall clock per simulated second: MuJoCo stepping at h ...
      r.mj_cost = bv::per_call(
                      [&] {
                        mj.reset(seg.p0, seg.v0, h);
                        mj.step(n);
                        sink = sink + mj.position().x;
                      },
                      opt.sweep_min_time) /
                  T;
      // ... and libball evaluating the closed form at the same instants
      r.lib_cost = bv::per_call(
                       [&] {
                         for (long k = 1; k <= n; k++) {
                           ball_state s;
                           ball_segment_eval(&m, &seg, static_cast<double>(k) * h, &s);
                           sink = sink + s.position.x;
                         }
                       },
                       opt.sweep_min_time) /
                   T;
      r.jump_cost = jump_cost;
      rows.push_back(r);
    }
  }
  out.lines.push_back(fmt("lob P0 %s V0 %s, b = %.4g s, T = %.0f s; cost = wall clock per simulated second; "
                          "libball evaluates eq 3 at every step instant",
                          vec(seg.p0).c_str(), vec(seg.v0).c_str(), m.mass / m.air_friction, T));
  out.lines.push_back(fmt("%-6s %-6s %12s %12s %12s %12s %10s", "integ", "step", "pos err m", "vel err m/s",
                          "MuJoCo s/s", "libball s/s", "ratio"));
  for (const Row &r : rows)
    out.lines.push_back(fmt("%-6s %-6s %12.3e %12.3e %12.3e %12.3e %10.1f", r.integrator.c_str(),
                            r.step_name.c_str(), r.pos_err, r.vel_err, r.mj_cost, r.lib_cost,
                            r.mj_cost / r.lib_cost));
  out.lines.push_back(fmt("libball jump to any t (one evaluation): %.3e s", jump_cost));
  if (!opt.csv_path.empty()) {
    std::ofstream csv(opt.csv_path);
    csv << "integrator,step_s,step_name,position_error_m,velocity_error_mps,mujoco_s_per_sim_s,"
           "libball_s_per_sim_s,cost_ratio,libball_single_eval_s\n";
    for (const Row &r : rows)
      csv << fmt("%s,%.17g,%s,%.6e,%.6e,%.6e,%.6e,%.4g,%.6e\n", r.integrator.c_str(), r.h, r.step_name.c_str(),
                 r.pos_err, r.vel_err, r.mj_cost, r.lib_cost, r.mj_cost / r.lib_cost, r.jump_cost);
    if (!csv) {
      out.pass = false;
      out.lines.push_back("cannot write " + opt.csv_path);
    } else {
      out.lines.push_back("table written to " + opt.csv_path);
    }
  }
  // What the table must show: Euler first order (error / 10 from 1e-3 to
  // 1e-4 s, within 20 %), RK4 far better than Euler at each step, RK4 at
  // 1e-3 s inside the flight tolerance.
  const size_t ns = sizeof steps / sizeof steps[0];
  double e3 = rows[ns - 2].pos_err, e4 = rows[ns - 1].pos_err;
  if (!(e3 / e4 > 8.0 && e3 / e4 < 12.0)) {
    out.pass = false;
    out.lines.push_back(fmt("Euler is not first order: error %.3e at 1e-3 s, %.3e at 1e-4 s", e3, e4));
  }
  for (size_t j = 0; j < ns; j++)
    if (!(rows[ns + j].pos_err < 1e-3 * rows[j].pos_err) && rows[ns + j].pos_err > kFlightPosTol) {
      out.pass = false;
      out.lines.push_back(fmt("RK4 not far better than Euler at step %s: %.3e vs %.3e", step_names[j],
                              rows[ns + j].pos_err, rows[j].pos_err));
    }
  if (!(rows[2 * ns - 2].pos_err < kFlightPosTol)) {
    out.pass = false;
    out.lines.push_back(fmt("RK4 at 1e-3 s misses the closed form by %.3e m", rows[2 * ns - 2].pos_err));
  }
  if (sink == 12345.678) out.lines.push_back("");  // keeps the timed work alive
  return out;
}

}  // namespace bv
