// A fake clock that sleeps exactly (and stalls on request) and a fake
// server port that takes queued input, records every write and makes each
// wake-up's work take a chosen time: the server loop without a network or a
// clock (test_server_loop, test_placement).
#pragma once

#include <deque>
#include <map>
#include <string>
#include <vector>

#include "server_loop.h"

namespace test {

using namespace ballsrv;

constexpr double kStart = 100.0;       // mono s when the loop starts
constexpr double kRealOffset = 1.7e9;  // realtime = mono + this

struct FakeClock : Clock {
  double now = kStart;
  int sleeps = 0;
  std::map<int, double> oversleep;  // by sleep index: s the machine stalls past the wake-up
  double per_read = 0.0;            // s each reading takes: work in proportion to the loop's
  double mono() override {
    double t = now;
    now += per_read;
    return t;
  }
  double realtime() override { return now + kRealOffset; }
  void sleep_until(double t) override {
    if (t > now) now = t;
    auto it = oversleep.find(sleeps++);
    if (it != oversleep.end()) now += it->second;
  }
};

struct FakePort : ServerPort {
  FakeClock *clock = nullptr;
  std::map<int, double> work;  // by wake-up index: s its phases take (0 unless said)
  int wakes = 0;
  bool refuse = false;
  std::deque<RacketSampleIn> samples;
  std::deque<ControlIn> controls;
  std::vector<PortNote> notes;
  std::deque<std::pair<MatchInfoOut, ParticipantId>> others;
  std::deque<std::pair<SegmentOut, ParticipantId>> other_segments;
  std::deque<std::pair<StatusOut, ParticipantId>> other_status;
  std::deque<std::pair<MatchModelOut, ParticipantId>> other_models;
  std::vector<SegmentOut> segments;
  std::vector<EventOut> events;
  std::vector<StateOut> states;
  std::vector<MatchInfoOut> infos;
  std::vector<StatusOut> statuses;
  std::vector<MatchModelOut> models;

  void take_notes(std::vector<PortNote> *out) override {  // the first phase of every wake-up
    auto it = work.find(wakes++);
    if (it != work.end()) clock->now += it->second;
    out->insert(out->end(), notes.begin(), notes.end());
    notes.clear();
  }
  std::vector<std::vector<std::pair<uint32_t, int>>> admitted;  // every admit call's matches
  std::vector<CreateIds> admitted_creates;                        // and the ids CREATEs may name
  void admit(const std::vector<std::pair<uint32_t, int>> &m, CreateIds creates) override {
    admitted.push_back(m);
    admitted_creates.push_back(creates);
  }
  bool take_sample(RacketSampleIn *s) override { return pop(samples, s); }
  bool take_control(ControlIn *c) override { return pop(controls, c); }
  bool take_other_info(MatchInfoOut *info, ParticipantId *from) override { return pop_from(others, info, from); }
  bool take_other_segment(SegmentOut *s, ParticipantId *from) override { return pop_from(other_segments, s, from); }
  bool take_other_status(StatusOut *s, ParticipantId *from) override { return pop_from(other_status, s, from); }
  bool take_other_model(MatchModelOut *m, ParticipantId *from) override { return pop_from(other_models, m, from); }
  template <class T>
  static bool pop_from(std::deque<std::pair<T, ParticipantId>> &q, T *out, ParticipantId *from) {
    if (q.empty()) return false;
    *out = q.front().first;
    *from = q.front().second;
    q.pop_front();
    return true;
  }
  std::string written;  // what was written, in order: s(egment), e(vent), b(all state)
  std::vector<double> segment_mono;  // the clock's mono s at each segment's write
  bool write(const SegmentOut &s) override {
    if (!keep(segments, s)) return false;
    segment_mono.push_back(clock->now);
    written += 's';
    return true;
  }
  bool write(const EventOut &e) override { return keep(events, e) && (written += 'e', true); }
  bool write(const StateOut &s) override { return keep(states, s) && (written += 'b', true); }
  std::vector<double> info_mono;  // the clock's mono s at each MatchInfo's write
  bool write(const MatchInfoOut &i) override {
    if (!keep(infos, i)) return false;
    info_mono.push_back(clock->now);
    return true;
  }
  bool write(const StatusOut &s) override { return keep(statuses, s); }
  bool write(const MatchModelOut &m) override { return keep(models, m); }
  int asserted = 0;
  bool assert_liveliness() override {
    asserted++;
    return !refuse;
  }
  std::vector<uint32_t> disposed;
  bool dispose_match(uint32_t match_id) override {
    disposed.push_back(match_id);
    return !refuse;
  }

  template <class T>
  static bool pop(std::deque<T> &q, T *out) {
    if (q.empty()) return false;
    *out = q.front();
    q.pop_front();
    return true;
  }
  template <class T>
  bool keep(std::vector<T> &v, const T &x) {
    if (refuse) return false;
    v.push_back(x);
    return true;
  }
};

}  // namespace test
