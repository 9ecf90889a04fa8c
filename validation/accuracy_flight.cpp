// Flight: position error against cost for libball's closed form (eq 3),
// three integrators written here (explicit Euler, semi-implicit Euler, RK4)
// and MuJoCo 2.2's Euler and RK4 (through the validation's twin, mujoco_ball.h),
// on the integrator sweep's shot (common.h) flown for 2 s and for 10 s.
// The reference is eq 3 in long double (64-bit mantissa), so libball's own
// rounding shows too.
#include <cmath>
#include <cstring>
#include <functional>

#include "accuracy.h"
#include "common.h"
#include "mujoco_ball.h"

namespace acc {

namespace {

volatile double g_sink;

struct Body {
  double x, y, z, vx, vy, vz;
};

// eq 1, 2: the equations of motion the integrators solve: X'' = -X' / b
// horizontally (b = m / beta), Y'' = -g vertically.
struct Ode {
  double inv_b, g;
  void accel(const Body &s, double *ax, double *ay, double *az) const {
    *ax = -s.vx * inv_b;
    *ay = -g;
    *az = -s.vz * inv_b;
  }
};

// Explicit Euler on eq 1, 2: the position moves with the old velocity.
inline void euler_step(const Ode &f, Body &s, double h) {
  double ax, ay, az;
  f.accel(s, &ax, &ay, &az);
  s.x += h * s.vx;
  s.y += h * s.vy;
  s.z += h * s.vz;
  s.vx += h * ax;
  s.vy += h * ay;
  s.vz += h * az;
}

// Semi-implicit (symplectic) Euler on eq 1, 2: the velocity first, the
// position with the new velocity (MuJoCo's Euler, without its implicit damping).
inline void semi_implicit_step(const Ode &f, Body &s, double h) {
  double ax, ay, az;
  f.accel(s, &ax, &ay, &az);
  s.vx += h * ax;
  s.vy += h * ay;
  s.vz += h * az;
  s.x += h * s.vx;
  s.y += h * s.vy;
  s.z += h * s.vz;
}

// Classical RK4 on eq 1, 2 (state: position and velocity).
inline void rk4_step(const Ode &f, Body &s, double h) {
  auto deriv = [&f](const Body &b) {
    Body d;
    d.x = b.vx;
    d.y = b.vy;
    d.z = b.vz;
    f.accel(b, &d.vx, &d.vy, &d.vz);
    return d;
  };
  auto add = [](const Body &b, const Body &d, double k) {
    return Body{b.x + k * d.x, b.y + k * d.y, b.z + k * d.z, b.vx + k * d.vx, b.vy + k * d.vy, b.vz + k * d.vz};
  };
  Body k1 = deriv(s), k2 = deriv(add(s, k1, 0.5 * h)), k3 = deriv(add(s, k2, 0.5 * h)), k4 = deriv(add(s, k3, h));
  double w = h / 6.0;
  s.x += w * (k1.x + 2.0 * k2.x + 2.0 * k3.x + k4.x);
  s.y += w * (k1.y + 2.0 * k2.y + 2.0 * k3.y + k4.y);
  s.z += w * (k1.z + 2.0 * k2.z + 2.0 * k3.z + k4.z);
  s.vx += w * (k1.vx + 2.0 * k2.vx + 2.0 * k3.vx + k4.vx);
  s.vy += w * (k1.vy + 2.0 * k2.vy + 2.0 * k3.vy + k4.vy);
  s.vz += w * (k1.vz + 2.0 * k2.vz + 2.0 * k3.vz + k4.vz);
}

// eq 3 in long double: the reference position at time t of the segment.
ball_vec3 reference(const ball_segment &seg, double b, double g, double t) {
  long double lt = t, lb = b, d = -lb * expm1l(-lt / lb);
  long double y = (long double)seg.p0.y + (long double)seg.v0.y * lt - 0.5L * (long double)g * lt * lt;
  return ball_v3((double)((long double)seg.p0.x + (long double)seg.v0.x * d), (double)y,
                 (double)((long double)seg.p0.z + (long double)seg.v0.z * d));
}

// Seconds per call of f (bv::per_call), min and median of the rounds.
Stat time_per_call(const Options &opt, const std::function<void()> &f) {
  std::vector<double> v;
  for (int r = 0; r < opt.rounds; r++) v.push_back(bv::per_call(f, opt.min_time));
  return stat_of(v);
}

Stat scaled(Stat s, double k) { return Stat{s.min * k, s.median * k}; }

using Stepper = void (*)(const Ode &, Body &, double);

void own_integrator(const Options &opt, const char *name, Stepper step, const Ode &f, const ball_segment &seg,
                    const std::vector<ball_vec3> &ref, double T, long n, FlightRow *row) {
  double h = T / static_cast<double>(n);
  Body s{seg.p0.x, seg.p0.y, seg.p0.z, seg.v0.x, seg.v0.y, seg.v0.z};
  row->method = name;
  row->err_path = 0.0;
  for (long k = 1; k <= n; k++) {
    step(f, s, h);
    row->err_path = std::max(row->err_path, ball_v3_dist(ball_v3(s.x, s.y, s.z), ref[k]));
  }
  row->err_end = ball_v3_dist(ball_v3(s.x, s.y, s.z), ref[n]);
  Stat per = time_per_call(opt, [&] {
    Body b{seg.p0.x, seg.p0.y, seg.p0.z, seg.v0.x, seg.v0.y, seg.v0.z};
    double acc = 0.0;
    for (long k = 1; k <= n; k++) {
      step(f, b, h);
      acc += b.x + b.y + b.z;  // a state every step, as a renderer reads it
    }
    g_sink = acc;
  });
  row->ns_per_s = scaled(per, 1e9 / T);
  row->query_ns = scaled(per, 1e9);
}

bool mujoco_integrator(const Options &opt, int integrator, const ball_model &m, const ball_segment &seg,
                       const std::vector<ball_vec3> &ref, double T, long n, FlightRow *row, std::string *err) {
  double h = T / static_cast<double>(n);
  bv::MjBall mj;
  if (!mj.load(m, integrator, h, err)) return false;
  row->method = integrator == mjINT_RK4 ? "MuJoCo RK4" : "MuJoCo Euler";
  row->err_path = 0.0;
  if (!mj.reset(seg.p0, seg.v0, h)) {
    *err = bv::mj_last_error();
    return false;
  }
  for (long k = 1; k <= n; k++) {
    if (!mj.step(1)) {
      *err = bv::mj_last_error();
      return false;
    }
    row->err_path = std::max(row->err_path, ball_v3_dist(mj.position(), ref[k]));
  }
  row->err_end = ball_v3_dist(mj.position(), ref[n]);
  ball_vec3 end = mj.position();
  // timed: setting the state and the n steps (a server that integrates
  // sets the state at every collision, never clears MuJoCo's arena)
  bool ok = true;
  Stat per = time_per_call(opt, [&] {
    ok = ok && mj.set_state(seg.p0, seg.v0) && mj.step(n);
    g_sink = mj.position().x;
  });
  ball_vec3 again = mj.position();
  if (!ok || std::memcmp(&end, &again, sizeof end) != 0) {
    *err = ok ? "set_state then step does not repeat reset then step" : bv::mj_last_error();
    return false;
  }
  row->ns_per_s = scaled(per, 1e9 / T);
  row->query_ns = scaled(per, 1e9);
  return true;
}

// The observed order of convergence between two rows of one method.
double order(const FlightRow &coarse, const FlightRow &fine) {
  return std::log(coarse.err_path / fine.err_path) / std::log(coarse.h / fine.h);
}

const FlightRow *find(const FlightCase &c, const std::string &method, const std::string &step) {
  for (const FlightRow &r : c.rows)
    if (r.method == method && r.step == step) return &r;
  return nullptr;
}

}  // namespace

void run_flight(const Options &opt, Report &rep) {
  ball_model m;
  ball_segment seg;
  bv::sweep_flight(&m, &seg);
  FlightResults &out = rep.flight;
  out.b = m.mass / m.air_friction;
  out.p0 = seg.p0;
  out.v0 = seg.v0;
  const Ode f{1.0 / out.b, m.gravity};
  std::vector<double> steps = {1.0 / 6, 1.0 / 10, 1.0 / 15, 1.0 / 30, 1.0 / 60, 1.0 / 120,
                               1.0 / 240, 1e-3, 1.0 / 3000, 1e-4};
  if (opt.quick) steps = {1.0 / 6, 1.0 / 10, 1.0 / 15, 1.0 / 60, 1e-3, 1e-4};
  ball_flight fl;
  ball_flight_init(&m, &seg, &fl);
  for (double T : {2.0, 10.0}) {
    FlightCase fc;
    fc.name = T == 2.0 ? "2 s shot" : "10 s flight";
    fc.T = T;
    // libball's one query at T from the segment alone (ball_segment_eval):
    // the same for every step
    Stat query = scaled(time_per_call(opt,
                                      [&] {
                                        ball_state s;
                                        double acc = 0.0;
                                        for (int j = 0; j < 1000; j++) {
                                          ball_segment_eval(&m, &seg, T - 1e-9 * (j & 7), &s);
                                          acc += s.position.x;
                                        }
                                        g_sink = acc;
                                      }),
                        1e9 / 1000.0);
    for (double h0 : steps) {
      long n = std::lround(T / h0);
      double h = T / static_cast<double>(n);
      std::vector<ball_vec3> ref(static_cast<size_t>(n) + 1);
      for (long k = 0; k <= n; k++) ref[k] = reference(seg, out.b, m.gravity, k * h);
      // libball: a state at every step instant (ball_flight_eval)
      FlightRow lib;
      lib.method = "libball";
      for (long k = 1; k <= n; k++) {
        ball_state s;
        ball_flight_eval(&fl, k * h, &s);
        lib.err_path = std::max(lib.err_path, ball_v3_dist(s.position, ref[k]));
        if (k == n) lib.err_end = ball_v3_dist(s.position, ref[n]);
      }
      Stat per = time_per_call(opt, [&] {
        ball_state s;
        double acc = 0.0;
        for (long k = 1; k <= n; k++) {
          ball_flight_eval(&fl, k * h, &s);
          acc += s.position.x + s.position.y + s.position.z;
        }
        g_sink = acc;
      });
      lib.ns_per_s = scaled(per, 1e9 / T);
      lib.query_ns = query;
      std::vector<FlightRow> rows(6);
      rows[0] = lib;
      own_integrator(opt, "Euler", euler_step, f, seg, ref, T, n, &rows[1]);
      own_integrator(opt, "semi-implicit Euler", semi_implicit_step, f, seg, ref, T, n, &rows[2]);
      own_integrator(opt, "RK4", rk4_step, f, seg, ref, T, n, &rows[3]);
      std::string err;
      if (!mujoco_integrator(opt, mjINT_EULER, m, seg, ref, T, n, &rows[4], &err) ||
          !mujoco_integrator(opt, mjINT_RK4, m, seg, ref, T, n, &rows[5], &err)) {
        check(rep, "MuJoCo integrates the flight", false, err);
        rows.resize(4);
      }
      for (FlightRow &r : rows) {
        r.h = h;
        r.step = step_name(h0);
        fc.rows.push_back(r);
      }
    }
    out.cases.push_back(fc);
  }

  // The plots' data: one block per method (step, errors, costs).
  FILE *d = open_data(opt, "flight.dat");
  std::fprintf(d, "# ball_accuracy flight: per flight and method, one row per step\n"
                  "# step_s err_path_m err_end_m ns_per_sim_s_min ns_per_sim_s_med query_ns_min query_ns_med\n");
  for (const FlightCase &fc : out.cases)
    for (const char *meth : {"libball", "Euler", "semi-implicit Euler", "RK4", "MuJoCo Euler", "MuJoCo RK4"}) {
      std::fprintf(d, "# %s\n\"%s\" step err_path err_end ns_min ns_med q_min q_med\n", fc.name.c_str(), meth);
      for (const FlightRow &r : fc.rows)
        if (r.method == meth)
          std::fprintf(d, "%.9g %.6e %.6e %.6e %.6e %.6e %.6e\n", r.h, std::max(r.err_path, 1e-16),
                       std::max(r.err_end, 1e-16), r.ns_per_s.min, r.ns_per_s.median, r.query_ns.min,
                       r.query_ns.median);
      std::fprintf(d, "\n\n");
    }
  std::fclose(d);

  // What the numbers must show.
  for (const FlightCase &fc : out.cases) {
    double worst = 0.0;
    for (const FlightRow &r : fc.rows)
      if (r.method == "libball") worst = std::max(worst, r.err_path);
    check(rep, "libball's closed form is eq 3 to rounding on the " + fc.name, worst < 1e-11,
          bv::fmt("largest position error %.2e m (bound 1e-11 m)", worst));
    const FlightRow *a = find(fc, "RK4", "1/6"), *b = find(fc, "RK4", "1/15");
    if (a && b)
      check(rep, "RK4 is of order 4 (1/6 s to 1/15 s, " + fc.name + ")",
            order(*a, *b) > 3.6 && order(*a, *b) < 4.4, bv::fmt("observed order %.2f", order(*a, *b)));
    for (const char *meth : {"Euler", "semi-implicit Euler", "MuJoCo Euler"}) {
      const FlightRow *c = find(fc, meth, "1e-3"), *e = find(fc, meth, "1e-4");
      if (c && e)
        check(rep, std::string(meth) + " is of order 1 (1e-3 s to 1e-4 s, " + fc.name + ")",
              order(*c, *e) > 0.9 && order(*c, *e) < 1.1, bv::fmt("observed order %.3f", order(*c, *e)));
    }
    const FlightRow *own = find(fc, "RK4", "1/6"), *mj = find(fc, "MuJoCo RK4", "1/6");
    if (own && mj)
      check(rep, "MuJoCo's RK4 is the RK4 written here (1/6 s, " + fc.name + ")",
            std::fabs(mj->err_path / own->err_path - 1.0) < 1e-3,
            bv::fmt("errors %.6e m and %.6e m", mj->err_path, own->err_path));
  }
}

}  // namespace acc
