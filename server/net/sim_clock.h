// A client's estimate of a match's sim clock (docs/protocol.md, "Time").
//
// The server states, in every BallState and MatchInfo, the sim time at a
// server time (its realtime clock at the frame's deadline) and the time base.
// A client records when it received each pair on its own realtime clock; the
// smallest (local - server) difference over a window is the clock offset
// plus the smallest one-way latency, the usual minimum filter (NTP). Then
//   server_now = local_now - offset
//   sim_now    = sim_time + (server_now - server_time) * time_base   (playing)
//              = sim_time                                          (otherwise)
// On one host, or with NTP/PTP-synchronised clocks, the offset is the
// latency alone: a fraction of a millisecond on loopback.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>

namespace ballsrv {

class SimClock {
 public:
  // A (sim_time, server_time) pair received at local realtime `local_now`.
  // false (and counted in rejected()) for a pair that does not fit: a
  // number that is not finite, a time base outside [0.05, 20], or, once
  // the clock runs, an offset more than kMaxJump above the clock's own or
  // kMaxFresher below it (a forged pair must not move the clock; a fresher
  // pair lies below, by up to the age of the clock's first: the MatchInfo a
  // late joiner gets first may be 4 s old); kConfirm such pairs in a row that
  // agree with each other are a new clock (a server on another host) and
  // the estimate starts anew from them. A pair whose offset fits is taken
  // only if its sim time fits too: within kMaxJump (times the time base)
  // of what the clock gives at its server time, unless rebase() was called
  // (a new owner's clock may be another).
  bool observe(double sim_time, double server_time, double time_base, bool running, double local_now) {
    double offset = local_now - server_time;
    if (!std::isfinite(sim_time) || !std::isfinite(offset) || !(time_base >= 0.05 && time_base <= 20.0)) {
      rejected_++;
      return false;
    }
    if (valid_ && (offset - this->offset() > kMaxJump || this->offset() - offset > kMaxFresher)) {
      rejected_++;
      bool agrees = outliers_ > 0 && std::fabs(offset - outlier_offset_) <= kMaxJump;
      outliers_ = agrees ? outliers_ + 1 : 1;
      outlier_offset_ = offset;
      if (outliers_ < kConfirm) return false;
      next_ = 0;  // a new clock: the window starts over
      valid_ = false;
    }
    outliers_ = 0;
    if (valid_ && !rebase_ &&
        !(std::fabs(sim_time - sim_at_server(server_time)) <= kMaxJump * std::fmax(1.0, time_base_))) {
      rejected_++;  // a forged sim time under a fitting offset moves nothing
      return false;
    }
    rebase_ = false;
    offsets_[next_ % kWindow] = offset;
    next_++;
    best_ = offsets_[0];  // the minimum kept, for every reading of the clock
    for (size_t i = 1, n = next_ < kWindow ? next_ : kWindow; i < n; ++i)
      if (offsets_[i] < best_) best_ = offsets_[i];
    // the newest anchor wins when it is at least as recent (pairs can arrive out of order)
    if (!valid_ || server_time >= server_time_) {
      sim_time_ = sim_time;
      server_time_ = server_time;
      time_base_ = time_base;
      running_ = running;
    }
    valid_ = true;
    return true;
  }

  bool valid() const { return valid_; }
  // The next pair that fits by its offset sets the sim clock, wherever it is.
  void rebase() { rebase_ = true; }
  // The sim time the clock gives at server time t.
  double sim_at_server(double t) const { return running_ ? sim_time_ + (t - server_time_) * time_base_ : sim_time_; }

  double offset() const { return best_; }
  // How far one pair's offset strays above the minimum: the median of the
  // window's offsets less their minimum (s; 0 without pairs).
  double spread() const {
    size_t n = next_ < kWindow ? next_ : kWindow;
    if (n == 0) return 0.0;
    std::array<double, kWindow> sorted;
    std::copy(offsets_, offsets_ + n, sorted.begin());
    std::nth_element(sorted.begin(), sorted.begin() + n / 2, sorted.begin() + n);
    return sorted[n / 2] - best_;
  }

  double server_now(double local_now) const { return local_now - offset(); }

  double sim_now(double local_now) const {
    if (!valid_) return 0.0;
    if (!running_) return sim_time_;
    double ahead = server_now(local_now) - server_time_;
    if (ahead < 0.0) ahead = 0.0;
    return sim_time_ + ahead * time_base_;
  }

  // The local time at which the sim clock reads `sim` (while it runs; else
  // the present reading's: local_now). The inverse of sim_now.
  double local_at(double sim, double local_now) const {
    if (!valid_ || !running_) return local_now;
    return server_time_ + (sim - sim_time_) / time_base_ + offset();
  }

  bool running() const { return running_; }
  double time_base() const { return time_base_; }
  unsigned long rejected() const { return rejected_; }  // pairs that did not fit

  static constexpr double kMaxJump = 2.0;     // s: an offset this far above the clock's is not its
  static constexpr double kMaxFresher = 5.0;  // s: nor one this far below (docs/protocol.md, "Clients that trust no one")
  static constexpr int kConfirm = 10;      // pairs in a row that make a new clock (a burst of forged ones must be long)

 private:
  static constexpr size_t kWindow = 128;  // pairs: about 2 s of 60 Hz states
  unsigned long rejected_ = 0;
  int outliers_ = 0;            // pairs in a row that did not fit
  double outlier_offset_ = 0.0; // the newest of them
  double offsets_[kWindow] = {0};
  double best_ = 0.0;  // their minimum
  size_t next_ = 0;
  bool valid_ = false;
  bool rebase_ = false;
  bool running_ = false;
  double sim_time_ = 0.0, server_time_ = 0.0, time_base_ = 1.0;
};

}  // namespace ballsrv
