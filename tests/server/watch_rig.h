// A Watcher without a network (test_watcher, test_spectator): its client
// of the client library over a port the test fills (FakeNet); each on_*
// puts a sample on the port and runs the watcher's turn at local realtime
// `real`, as ball-watch's loop does; the client's clock is that time.
#pragma once

#include "check.hpp"
#include "fake_net_client.h"
#include "game.h"
#include "watcher.h"

namespace test {

struct WatchRig {
  // `more` sets the client's config (the servers it takes)
  explicit WatchRig(const WatcherSettings &s = WatcherSettings{}, void (*more)(ball_net_config *) = nullptr)
      : net(participant(99), more), w(s, net.client) {}

  void turn(double real) {
    net.now = real;
    std::string err = w.turn(real);
    CHECK_MSG(err.empty(), "the watcher's turn: %s", err.c_str());
  }
  void on_info(const MatchInfoOut &i, double real) { put(net.port.infos, i, real); }
  void on_segment(const SegmentOut &s, double real) { put(net.port.segments, s, real); }
  void on_event(const EventOut &e, double real) { put(net.port.events, e, real); }
  void on_state(const StateOut &s, double real) { put(net.port.states, s, real); }
  void on_status(const StatusOut &s, double real) { put(net.port.statuses, s, real); }
  // a sample on the port, then a turn
  template <class T>
  void put(std::deque<T> &queue, const T &sample, double real) {
    queue.push_back(sample);
    turn(real);
  }
  void frame(double real) {
    net.now = real;
    w.frame(real);
  }
  // the watcher's own, as the tests call them
  void on_start(double real) { w.on_start(real); }
  void check_states() {}  // (every turn checks them)
  WatchOutput &output() { return w.output(); }
  WatchSummary summary(double seconds) const { return w.summary(seconds); }
  void snapshot_written(const SnapshotDue &due, const SnapshotRecord &drawn, double real) {
    w.snapshot_written(due, drawn, real);
  }

  FakeNet net;
  Watcher w;
};

}  // namespace test
