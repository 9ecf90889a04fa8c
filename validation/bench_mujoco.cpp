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

using bv::now_s;

volatile double g_sink;

struct Stat {
  double min, median;
};

Stat stat(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  size_t n = v.size();
  return {v[0], n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2])};
}

// Seconds per call of f, over enough calls to last min_time.
template <class F>
double per_call(F &&f, double min_time) {
  long reps = 0;
  double t0 = now_s(), el;
  do {
    f();
    reps++;
    el = now_s() - t0;
  } while (el < min_time);
  return el / static_cast<double>(reps);
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
  const double min_time = smoke ? 0.002 : 0.05;
  const double frame = 1.0 / 60.0; // 120 frames: the 2 s flight
  const int frames = 120;

  ball_model m;
  ball_segment seg;
  bv::sweep_flight(&m, &seg);
  ball_flight fl;
  if (ball_flight_init(&m, &seg, &fl) != BALL_OK) {
    std::fprintf(stderr, "ball_bench_mujoco: the flight is not valid\n");
    return 1;
  }
  std::vector<ball_state> exact(frames + 1);
  for (int k = 0; k <= frames; k++) ball_flight_eval(&fl, k * frame, &exact[k]);

  bv::MjBall mj;
  std::string err;
  if (!mj.load(m, mjINT_RK4, frame, &err)) {
    std::fprintf(stderr, "ball_bench_mujoco: %s\n", err.c_str());
    return 1;
  }
  // MuJoCo's error over the flight with n RK4 steps per frame.
  auto mj_error = [&](int n) {
    double worst = 0.0;
    mj.reset(seg.p0, seg.v0, frame / n);
    for (int k = 1; k <= frames; k++) {
      mj.step(n);
      worst = std::max(worst, ball_v3_dist(mj.position(), exact[k].position));
    }
    return worst;
  };

  std::printf("# ball_bench_mujoco: a 2 s flight with drag, states at 60 Hz; %d rounds\n", rounds);
  std::printf("%-10s %-9s %-10s | %-23s %-23s %-9s | %-23s %-23s %-9s\n", "accuracy", "RK4 step",
              "MuJoCo err", "(a) libball us min/med", "(a) MuJoCo us min/med", "(a) ratio",
              "(b) libball ns min/med", "(b) MuJoCo ns min/med", "(b) ratio");
  for (double E : {1e-9, 1e-12, 1e-13}) {
    int n = 1;
    double e = mj_error(n);
    while (e > E && n < (1 << 16)) {
      n *= 2;
      e = mj_error(n);
    }
    double h = frame / n;
    std::vector<double> la, ma, lb, mb;
    // the step set once; the timed loops only set the state (mj_resetData
    // clears all of mjData and would dominate a short query)
    mj.reset(seg.p0, seg.v0, h);
    for (int r = 0; r < rounds; r++) {
      // (a) a state every frame
      la.push_back(per_call(
          [&] {
            ball_state s;
            double acc = 0.0;
            for (int k = 1; k <= frames; k++) {
              ball_flight_eval(&fl, k * frame, &s);
              acc += s.position.x;
            }
            g_sink = acc;
          },
          min_time));
      ma.push_back(per_call(
          [&] {
            double acc = 0.0;
            mj.set_state(seg.p0, seg.v0);
            for (int k = 1; k <= frames; k++) {
              mj.step(n);
              acc += mj.position().x;
            }
            g_sink = acc;
          },
          min_time));
      // (b) one query at t, t spread over the flight
      int q = 0;
      lb.push_back(per_call(
                       [&] {
                         ball_state s;
                         double acc = 0.0;
                         for (int j = 0; j < 1000; j++) {
                           q = (q + 37) % frames + 1;
                           ball_flight_eval(&fl, q * frame, &s);
                           acc += s.position.x;
                         }
                         g_sink = acc;
                       },
                       min_time) /
                   1000.0);
      q = 0;
      mb.push_back(per_call(
          [&] {
            q = (q + 37) % frames + 1;
            mj.set_state(seg.p0, seg.v0);
            mj.step(static_cast<long>(q) * n);
            g_sink = mj.position().x;
          },
          min_time));
    }
    Stat sla = stat(la), sma = stat(ma), slb = stat(lb), smb = stat(mb);
    std::printf("%-10.0e 1/%-7d %-10.2e | %10.3f %10.3f   %10.1f %10.1f   %9.0f | %10.1f %10.1f   %10.0f %10.0f   %9.0f\n",
                E, 60 * n, e, 1e6 * sla.min, 1e6 * sla.median, 1e6 * sma.min, 1e6 * sma.median,
                sma.median / sla.median, 1e9 * slb.min, 1e9 * slb.median, 1e9 * smb.min,
                1e9 * smb.median, smb.median / slb.median);
  }
  std::printf("libball's own error on this flight: 0 (the closed form); MuJoCo's at each row above.\n");
  return 0;
}
