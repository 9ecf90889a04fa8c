// A client's port without a network: what a client reads is queued by the
// test, what it writes is kept (test_client's player groups, test_spectator's
// watcher turns).
#pragma once

#include <deque>
#include <vector>

#include "port.h"

namespace test {

using namespace ballsrv;

struct FakeClientPort : ClientPort {
  std::deque<MatchInfoOut> infos;
  std::deque<SegmentOut> segments;
  std::deque<EventOut> events;
  std::deque<StateOut> states;
  std::deque<StatusOut> statuses;
  std::deque<MatchModelOut> models;
  std::deque<RacketSampleIn> rackets;  // the players' samples, as a watcher reads them
  std::vector<RacketSampleIn> samples;
  std::vector<ControlIn> controls;
  bool refuse = false;
  bool heard = true;
  bool met = false;  // some endpoint of a server matched, though not all of them yet
  template <class T>
  static bool pop(std::deque<T> &q, T *out) {
    if (q.empty()) return false;
    *out = q.front();
    q.pop_front();
    return true;
  }
  bool take(MatchInfoOut *i) override { return pop(infos, i); }
  bool take(SegmentOut *s) override { return pop(segments, s); }
  bool take(StateOut *s) override { return pop(states, s); }
  bool take(EventOut *e) override { return pop(events, e); }
  bool take(StatusOut *s) override { return pop(statuses, s); }
  bool take(MatchModelOut *m) override { return pop(models, m); }
  bool take(RacketSampleIn *s) override { return pop(rackets, s); }
  bool write(const RacketSampleIn &s) override {
    if (!refuse) samples.push_back(s);
    return !refuse;
  }
  bool write(const ControlIn &c) override {
    if (!refuse) controls.push_back(c);
    return !refuse;
  }
  bool hears_server() const override { return heard; }
  bool meets_server() const override { return heard || met; }
  WireSizes wire{};  // what sizes() says
  WireSizes sizes() const override { return wire; }
};

}  // namespace test
