// ball_bench_mujoco: libball's closed form against a MuJoCo 2.2 RK4 twin at
// equal accuracy, in one run (docs/benchmarks.md). RK4 is exact for the
// constant gravity and nearly so for the linear drag, so MuJoCo's error is
// small already at one step per frame; the accuracies asked are 1e-9 m and
// below, where libball's closed form still costs one evaluation. Not a timed test: ctest
// runs only `--smoke`.
//
// The flight: a 2 s shot with drag (eq 3), the integrator sweep's segment.
// For each accuracy E (largest position error over the flight), MuJoCo gets
// the largest RK4 step that reaches it (a whole number of steps per 60 Hz
// frame); then
//   (a) a state every 60 Hz frame: libball evaluates 120 states
//       (ball_flight_eval), MuJoCo integrates the 2 s and reads each frame;
//   (b) "where is the ball at t": libball evaluates once, MuJoCo integrates
//       from 0 to t (t spread over the flight).
// Each figure is the min and the median of several rounds.
#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "common.h"
#include "mujoco_ball.h"

namespace {

using bv::per_call;
using bv::Stat;
using bv::stat_of;

volatile double g_sink;

constexpr double kFrame = 1.0 / 60.0;  // s: states at 60 Hz ...
constexpr int kFrames = 120;           // ... over the 2 s flight

// The flight, its closed form prepared, and its states at every frame.
struct Flight {
  ball_model m;
  ball_segment seg;
  ball_flight fl;
  std::vector<ball_state> exact;
};

// MuJoCo's largest position error over the flight with n RK4 steps a frame.
double mj_error(bv::MjBall &mj, const Flight &f, int n) {
  double worst = 0.0;
  mj.reset(f.seg.p0, f.seg.v0, kFrame / n);
  for (int k = 1; k <= kFrames; k++) {
    mj.step(n);
    worst = std::max(worst, ball_v3_dist(mj.position(), f.exact[k].position));
  }
  return worst;
}

// One row: for accuracy E, the fewest RK4 steps a frame (doubling) whose
// error is at most E, then (a) and (b) timed for both, `rounds` times.
struct Row {
  int steps = 1;      // RK4 steps per frame
  double error = 0;   // MuJoCo's error with them, m
  Stat lib_a, mj_a;   // (a) s for 120 states
  Stat lib_b, mj_b;   // (b) s for one state at t
};

Row measure(bv::MjBall &mj, const Flight &f, double E, int rounds, double min_time) {
  Row row;
  row.error = mj_error(mj, f, row.steps);
  while (row.error > E && row.steps < (1 << 16)) {
    row.steps *= 2;
    row.error = mj_error(mj, f, row.steps);
  }
  const int n = row.steps;
  std::vector<double> la, ma, lb, mb;
  // the step set once; the timed loops only set the state (mj_resetData
  // clears all of mjData and would dominate a short query)
  mj.reset(f.seg.p0, f.seg.v0, kFrame / n);
  for (int r = 0; r < rounds; r++) {
    la.push_back(per_call(
        [&] {
          ball_state s;
          double acc = 0.0;
          for (int k = 1; k <= kFrames; k++) {
            ball_flight_eval(&f.fl, k * kFrame, &s);
            acc += s.position.x;
          }
          g_sink = acc;
        },
        min_time));
    ma.push_back(per_call(
        [&] {
          double acc = 0.0;
          mj.set_state(f.seg.p0, f.seg.v0);
          for (int k = 1; k <= kFrames; k++) {
            mj.step(n);
            acc += mj.position().x;
          }
          g_sink = acc;
        },
        min_time));
    int q = 0;  // t spread over the flight
    lb.push_back(per_call(
        [&] {
          ball_state s;
          q = (q + 37) % kFrames + 1;
          ball_flight_eval(&f.fl, q * kFrame, &s);
          g_sink = s.position.x;
        },
        min_time));
    q = 0;
    mb.push_back(per_call(
        [&] {
          q = (q + 37) % kFrames + 1;
          mj.set_state(f.seg.p0, f.seg.v0);
          mj.step(static_cast<long>(q) * n);
          g_sink = mj.position().x;
        },
        min_time));
  }
  row.lib_a = stat_of(la);
  row.mj_a = stat_of(ma);
  row.lib_b = stat_of(lb);
  row.mj_b = stat_of(mb);
  return row;
}

void print_header(int rounds) {
  std::printf("# ball_bench_mujoco: a 2 s flight with drag, states at 60 Hz; %d rounds\n", rounds);
  std::printf("%-10s %-9s %-10s | %-23s %-23s %-9s | %-23s %-23s %-9s\n", "accuracy", "RK4 step",
              "MuJoCo err", "(a) libball us min/med", "(a) MuJoCo us min/med", "(a) ratio",
              "(b) libball ns min/med", "(b) MuJoCo ns min/med", "(b) ratio");
}

void print_row(double E, const Row &r) {
  std::printf("%-10.0e 1/%-7d %-10.2e | %10.3f %10.3f   %10.1f %10.1f   %9.0f | %10.1f %10.1f   %10.0f %10.0f   %9.0f\n",
              E, 60 * r.steps, r.error, 1e6 * r.lib_a.min, 1e6 * r.lib_a.median, 1e6 * r.mj_a.min,
              1e6 * r.mj_a.median, r.mj_a.median / r.lib_a.median, 1e9 * r.lib_b.min, 1e9 * r.lib_b.median,
              1e9 * r.mj_b.min, 1e9 * r.mj_b.median, r.mj_b.median / r.lib_b.median);
}

}  // namespace

int main(int argc, char **argv) {
  bool smoke = false;
  int rounds = 7;
  CLI::App cli{"ball_bench_mujoco: libball against a MuJoCo 2.2 RK4 twin at equal accuracy (docs/benchmarks.md)"};
  cli.add_option("--rounds", rounds, "rounds per measurement, min and median reported")
      ->capture_default_str()
      ->check(CLI::Range(1, 101));
  cli.add_flag("--smoke", smoke, "two short rounds, to check the program runs");
  CLI11_PARSE(cli, argc, argv);
  if (smoke) rounds = 2;

  Flight f;
  bv::sweep_flight(&f.m, &f.seg);
  if (ball_flight_init(&f.m, &f.seg, &f.fl) != BALL_OK) {
    std::fprintf(stderr, "ball_bench_mujoco: the flight is not valid\n");
    return 1;
  }
  f.exact.resize(kFrames + 1);
  for (int k = 0; k <= kFrames; k++) ball_flight_eval(&f.fl, k * kFrame, &f.exact[k]);
  bv::MjBall mj;
  std::string err;
  if (!mj.load(f.m, mjINT_RK4, kFrame, &err)) {
    std::fprintf(stderr, "ball_bench_mujoco: %s\n", err.c_str());
    return 1;
  }
  print_header(rounds);
  for (double E : {1e-9, 1e-12, 1e-13}) print_row(E, measure(mj, f, E, rounds, smoke ? 0.002 : 0.05));
  std::printf("libball's own error on this flight: 0 (the closed form); MuJoCo's at each row above.\n");
  return 0;
}
