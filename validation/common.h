// Shared pieces of the cross-checks: options, seeded sampling, summaries.
#ifndef BALL_VALIDATION_COMMON_H
#define BALL_VALIDATION_COMMON_H

#include <chrono>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "ball/ball.h"
#include "ball/vec3.h"
#include "seeded.h"

namespace bv {

// How much of each check to run; quick is for ctest, full for the report.
struct Options {
  bool full = false;
  std::uint64_t seed = 20240601;  // every sample set derives its stream from this
  int flights = 500;              // MuJoCo flight comparisons
  int contacts = 300;             // MuJoCo floor / net-plane crossings
  int statics = 5000;             // FCL static configurations per obstacle kind
  int swept = 500;                // FCL swept motions per motion set
  double sweep_min_time = 0.02;   // s of wall clock per timed sweep cell
  std::string csv_path;           // integrator sweep table (CSV)
};

// One line of the final table: a named check, its numbers and its verdict.
struct Outcome {
  std::string check;  // validate_flight, ...
  bool pass = true;
  std::vector<std::string> lines;  // human-readable findings, printed in order
};

// A seeded stream per sample set, so a set does not change when another
// grows: the draws of kit/seeded.h, the one generator of the tests and the
// benchmarks (the same numbers with every standard library).
class Rng {
 public:
  Rng(std::uint64_t seed, std::uint64_t stream) : r_(seeded_stream(seed, stream)) {}
  double uniform(double lo, double hi) { return seeded_uniform(&r_, lo, hi); }
  double log_uniform(double lo, double hi) { return std::exp(uniform(std::log(lo), std::log(hi))); }
  bool chance(double p) { return uniform(0.0, 1.0) < p; }
  ball_vec3 unit() {  // uniform on the unit sphere
    double z = uniform(-1.0, 1.0), a = uniform(0.0, 2.0 * M_PI), s = std::sqrt(1.0 - z * z);
    return ball_vec3{s * std::cos(a), s * std::sin(a), z};
  }
  ball_vec3 box(ball_vec3 lo, ball_vec3 hi) {
    return ball_vec3{uniform(lo.x, hi.x), uniform(lo.y, hi.y), uniform(lo.z, hi.z)};
  }

 private:
  seeded_rng r_;
};

// The sweep's flight (the integrator sweep and the MuJoCo benchmark): a 2 s
// shot with drag only (eq 3), from (0, 1, 3) at (15, 10, 2) m/s.
inline void sweep_flight(ball_model *m, ball_segment *seg) {
  ball_model_default(m);
  m->effects = BALL_EFFECT_DRAG;
  *seg = ball_segment{};
  seg->p0 = {0.0, 1.0, 3.0};
  seg->v0 = {15.0, 10.0, 2.0};
}

// printf into a std::string.
std::string fmt(const char *format, ...) __attribute__((format(printf, 1, 2)));

// Wall-clock seconds since an arbitrary origin.
inline double now_s() {
  using clock = std::chrono::steady_clock;
  return std::chrono::duration<double>(clock::now().time_since_epoch()).count();
}

// The min and the median of several rounds' figures.
struct Stat {
  double min = 0.0, median = 0.0;
};
Stat stat_of(std::vector<double> v);

// Seconds per call of f, over calls that last at least min_time s, made in
// batches that double (so that reading the clock costs nothing measurable).
template <class F>
double per_call(F &&f, double min_time) {
  long reps = 0, batch = 1;
  double t0 = now_s(), el;
  do {
    for (long i = 0; i < batch; i++) f();
    reps += batch;
    el = now_s() - t0;
    if (el < min_time / 16) batch *= 2;
  } while (el < min_time);
  return el / static_cast<double>(reps);
}

// The checks (mujoco_check.cpp, fcl_check.cpp).
Outcome check_flight(const Options &opt);
Outcome check_contacts(const Options &opt);
Outcome check_sweep(const Options &opt);
Outcome check_static(const Options &opt);
Outcome check_swept(const Options &opt);

}  // namespace bv

#endif  // BALL_VALIDATION_COMMON_H
