// The server loop's clocks, free of any system clock: what the loop asks of
// time (Clock: the programs use the system's, server/apps/common.h; the
// tests a fake one), the absolute frame clock and the percentiles of the
// status line (docs/server-design.md, "Frame clock").
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace ballsrv {

class Clock {
 public:
  virtual ~Clock() = default;
  virtual double mono() = 0;                 // monotonic s
  virtual double realtime() = 0;             // server s (realtime, s since 1970)
  virtual void sleep_until(double mono) = 0; // until the monotonic clock reaches it (may return early on a signal)
};

// Absolute frame deadlines D_k = D_0 + k * period on the monotonic clock; the
// realtime clock at each is R_0 + (D_k - D_0), R_0 read once at the start,
// so stamps never jump when NTP steps the wall clock during a run.
class FrameClock {
 public:
  FrameClock(double period, double d0, double r0) : period_(period), d0_(d0), r0_(r0) {}
  // deadlines that share an origin with another clock's (matches stepped together)
  FrameClock(double period, const FrameClock &origin) : period_(period), d0_(origin.d0_), r0_(origin.r0_) {}
  // the first frame index whose deadline is not before mono
  uint64_t first_at(double mono) const {
    double k = std::ceil((mono - d0_) / period_ - 1e-9);
    return k > 0.0 ? static_cast<uint64_t>(k) : 0;
  }
  double period() const { return period_; }                       // real s
  double deadline(uint64_t k) const { return d0_ + static_cast<double>(k) * period_; }  // mono s
  double realtime_at(double mono) const { return r0_ + (mono - d0_); }                 // server s
  double start() const { return d0_; }                            // mono s

 private:
  double period_, d0_, r0_;
};

// Values of one period (frame times, latencies); quantiles by selection on a
// copy. Bounded: past kCap values it keeps a uniform sample of them
// (reservoir sampling, a fixed pseudo-random sequence), so that a long run or
// a flood of hits cannot grow it without end; size() is every value added.
class Percentiles {
 public:
  static constexpr size_t kCap = 100000;
  void add(double v) {
    if (values_.size() < kCap) {
      values_.push_back(v);
    } else {
      state_ = state_ * 6364136223846793005ull + 1442695040888963407ull;  // an LCG: the same on every run
      uint64_t k = (state_ >> 11) % (added_ + 1);
      if (k < kCap) values_[k] = v;
    }
    added_++;
  }
  void clear() {
    values_.clear();
    added_ = 0;
  }
  size_t size() const { return static_cast<size_t>(added_); }
  // the value of rank round(q (n - 1)) from the smallest; 0 when empty
  double quantile(double q) const {
    if (values_.empty()) return 0.0;
    std::vector<double> v = values_;
    size_t k = static_cast<size_t>(q * static_cast<double>(v.size() - 1) + 0.5);
    std::nth_element(v.begin(), v.begin() + static_cast<long>(k), v.end());
    return v[k];
  }
  double max() const { return values_.empty() ? 0.0 : *std::max_element(values_.begin(), values_.end()); }

 private:
  std::vector<double> values_;
  uint64_t added_ = 0;
  uint64_t state_ = 0x9e3779b97f4a7c15ull;
};

}  // namespace ballsrv
