// What the thin mains share: the stop flag (the one global), clocks, the
// absolute frame clock, percentiles, finding the QoS profile file, command
// line pieces and printing.
#pragma once

#include <cmath>
#include <csignal>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "ball/scene.h"
#include "types.h"

namespace CLI {
class App;
}

namespace ballsrv {
namespace app {

// SIGINT and SIGTERM set the stop flag; loops poll stop_requested().
void install_stop_signals();
bool stop_requested();

double realtime_now();  // CLOCK_REALTIME, s since 1970
double mono_now();      // CLOCK_MONOTONIC, s
// Sleeps until CLOCK_MONOTONIC reaches t (absolute: no drift); returns early on a signal.
void sleep_until(double t);

// Absolute frame deadlines D_k = D_0 + k * period on the monotonic clock; the
// realtime clock at each is R_0 + (D_k - D_0), R_0 read once at the start,
// so stamps never jump when NTP steps the wall clock during a run.
class FrameClock {
 public:
  explicit FrameClock(double period) : period_(period), d0_(mono_now()), r0_(realtime_now()) {}
  // deadlines that share an origin with another clock's (matches stepped together)
  FrameClock(double period, const FrameClock &origin) : period_(period), d0_(origin.d0_), r0_(origin.r0_) {}
  // the first frame index whose deadline is not before mono
  uint64_t first_at(double mono) const {
    double k = std::ceil((mono - d0_) / period_ - 1e-9);
    return k > 0.0 ? static_cast<uint64_t>(k) : 0;
  }
  double period() const { return period_; }
  double deadline(uint64_t k) const { return d0_ + static_cast<double>(k) * period_; }
  double realtime_at(double mono) const { return r0_ + (mono - d0_); }
  double start() const { return d0_; }

 private:
  double period_, d0_, r0_;
};

// Values of one period (frame times, latencies); quantiles by sorting a copy.
class Percentiles {
 public:
  void add(double v) { values_.push_back(v); }
  void clear() { values_.clear(); }
  size_t size() const { return values_.size(); }
  double quantile(double q) const;  // 0 when empty
  double max() const;

 private:
  std::vector<double> values_;
};

// The QoS profile file: `given`, else $BALL_QOS_PROFILE, else the one
// installed beside the program (../share/libball/ball_qos.xml), else the
// build tree's server/qos/ball_qos.xml.
std::string find_profile(const std::string &given);
// libball's example scenes, for names like "rally_mid"
std::string scenes_dir();
// The directory of the running program (ball-demo finds ball-server beside it).
std::string program_dir();

// The DDS options every program has: domain, profile file, participant profile.
struct DdsOptions {
  int domain = 0;
  std::string profile;
  std::string participant = "loopback";
};
void add_dds_options(CLI::App &app, DdsOptions *o);

bool parse_level(const std::string &text, ball_level *out);  // easy, mid, advanced, custom
// Loads a scene: "" or "default" is ball_scene_default, a name without a
// slash is libball's scenes/NAME.yaml, else a file. false with the loader's
// "file:line:column: field: message" in err.
bool load_scene(const std::string &what, ball_scene *scene, std::string *err);

// Drop counters as words: "12 (stale 10, duplicate 2)", or "0".
std::string drops_text(const std::array<uint64_t, kDropSlots> &drops);

// "name: message" to stderr, and the exit status 1
int fail(const char *program, const std::string &message);

}  // namespace app
}  // namespace ballsrv
