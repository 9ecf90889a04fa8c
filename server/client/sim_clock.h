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

#include <cstddef>

namespace ballsrv {

class SimClock {
 public:
  // A (sim_time, server_time) pair received at local realtime `local_now`.
  void observe(double sim_time, double server_time, double time_base, bool running, double local_now) {
    double offset = local_now - server_time;
    offsets_[next_ % kWindow] = offset;
    next_++;
    // the newest anchor wins when it is at least as recent (pairs can arrive out of order)
    if (!valid_ || server_time >= server_time_) {
      sim_time_ = sim_time;
      server_time_ = server_time;
      time_base_ = time_base;
      running_ = running;
    }
    valid_ = true;
  }

  bool valid() const { return valid_; }

  double offset() const {
    size_t n = next_ < kWindow ? next_ : kWindow;
    double best = offsets_[0];
    for (size_t i = 1; i < n; ++i)
      if (offsets_[i] < best) best = offsets_[i];
    return best;
  }

  double server_now(double local_now) const { return local_now - offset(); }

  double sim_now(double local_now) const {
    if (!valid_) return 0.0;
    if (!running_) return sim_time_;
    double ahead = server_now(local_now) - server_time_;
    if (ahead < 0.0) ahead = 0.0;
    return sim_time_ + ahead * time_base_;
  }

  bool running() const { return running_; }
  double time_base() const { return time_base_; }

 private:
  static constexpr size_t kWindow = 128;  // pairs: about 2 s of 60 Hz states
  double offsets_[kWindow] = {0};
  size_t next_ = 0;
  bool valid_ = false;
  bool running_ = false;
  double sim_time_ = 0.0, server_time_ = 0.0, time_base_ = 1.0;
};

}  // namespace ballsrv
