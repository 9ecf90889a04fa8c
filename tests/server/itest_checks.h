// What the networked cases of several hosts or servers ask of a run
// (itest_failover.cpp, itest_wan.cpp): a server's report, hits per match, a
// watcher's record checked with the history checker and stream by stream.
#pragma once

#include <array>
#include <map>

#include "ball/vec3.h"
#include "history.h"
#include "itest_kit.h"

namespace itest {

using check::note;

inline ServerReport report(const Env &env, const std::string &name) {
  ServerReport r;
  try {
    std::ifstream f(path(env, name + ".json"));
    r = json::parse(f).get<ServerReport>();
  } catch (const std::exception &e) {
    CHECK_MSG(false, "%s.json: %s", name.c_str(), e.what());
  }
  return r;
}

// What a watcher's record says of one match.
struct Seen {
  std::vector<SegmentOut> segments;  // as received
  std::vector<double> segment_recv;
  std::vector<MatchInfoOut> infos;
  std::vector<double> info_recv;
  std::vector<EventOut> events;
};

inline std::map<uint32_t, Seen> by_match(const std::vector<json> &lines) {
  std::map<uint32_t, Seen> m;
  for (const auto &j : lines) {
    std::string type = record_type(j);
    if (type == "segment") {
      SegmentOut s = j.get<SegmentOut>();
      m[s.match_id].segments.push_back(s);
      m[s.match_id].segment_recv.push_back(recv(j));
    } else if (type == "match_info") {
      MatchInfoOut i = j.get<MatchInfoOut>();
      m[i.match_id].infos.push_back(i);
      m[i.match_id].info_recv.push_back(recv(j));
    } else if (type == "event") {
      EventOut e = j.get<EventOut>();
      m[e.match_id].events.push_back(e);
    }
  }
  return m;
}

// racket hits in play of every match, from the record
inline std::map<uint32_t, int> hits_by_match(const std::vector<json> &lines) {
  std::map<uint32_t, int> h;
  for (const auto &j : lines)
    if (is_hit(j)) h[j.get<EventOut>().match_id]++;
  return h;
}

// Waits until every match 0..n-1 has `want` hits in play (false after `timeout` s).
inline bool rallies(Tail &t, int n, int want, double timeout) {
  double end = mono_now() + timeout;
  while (mono_now() < end) {
    t.poll();
    std::map<uint32_t, int> h = hits_by_match(t.lines);
    int ok = 0;
    for (int m = 0; m < n; ++m) ok += h[static_cast<uint32_t>(m)] >= want;
    if (ok == n) return true;
    usleep(100000);
  }
  return false;
}

// What every client must see (tests/support/history.h) over a watcher's
// whole record: scores, rallies, revisions and clocks that never go back,
// no seq with two contents, the ball continuous across a change of owner.
inline void check_history(const std::vector<json> &lines) {
  History h;
  std::string err;
  for (const json &j : lines)
    if (!h.take(j, &err)) break;
  CHECK_MSG(err.empty(), "%s", err.c_str());
  CHECK_MSG(h.violations().empty(), "%s", h.report().c_str());
  CHECK(h.counts().checks > 0);
  note("history: %ld lines, %ld checks, %ld changes of owner (%ld checked for continuity), %zu broken",
       h.counts().lines, h.counts().checks, h.counts().owner_changes, h.counts().continuity, h.violations().size());
}

// One match's stream as a client saw it: one server per segment seq, the
// seqs and the events' seqs one by one without a gap or a repeat, a serve
// only after a point, scores that never go back, and every floor or wall
// bounce where the segment before it put the ball (1 mm): no bounce lost or
// made twice. Returns the number of bounces checked.
inline int check_stream(uint32_t id, const Seen &s) {
  std::map<uint32_t, uint32_t> server_of;
  for (const auto &g : s.segments) {
    auto it = server_of.find(g.seq);
    CHECK_MSG(it == server_of.end(), "match %u: segment %u received twice (servers %u and %u)", id, g.seq,
              it == server_of.end() ? 0 : it->second, g.server_id);
    server_of[g.seq] = g.server_id;
  }
  for (size_t k = 1; k < s.segments.size(); ++k)
    CHECK_MSG(s.segments[k].seq == s.segments[k - 1].seq + 1, "match %u: segment %u after %u", id,
              s.segments[k].seq, s.segments[k - 1].seq);
  for (size_t k = 1; k < s.events.size(); ++k)
    CHECK_MSG(s.events[k].seq == s.events[k - 1].seq + 1, "match %u: event %u after %u", id, s.events[k].seq,
              s.events[k - 1].seq);
  int points = 1;  // the first serve needs none
  std::array<int, 2> score{0, 0};
  for (const auto &e : s.events) {
    if (e.kind == EventKind::point) points++;
    if (e.kind == EventKind::serve) {
      CHECK_MSG(points > 0, "match %u: a second serve (event %u) without a point", id, e.seq);
      points = 0;
    }
    CHECK_MSG(e.score[0] >= score[0] && e.score[1] >= score[1], "match %u: score %d-%d after %d-%d", id, e.score[0],
              e.score[1], score[0], score[1]);
    score = e.score;
  }
  int bounces = 0;
  if (s.infos.empty()) return 0;
  const ball_model &model = s.infos.back().model;
  for (size_t k = 1; k < s.segments.size(); ++k) {
    const SegmentOut &a = s.segments[k - 1], &b = s.segments[k];
    if (b.cause != Cause::floor && b.cause != Cause::wall) continue;
    ball_state there;
    ball_segment_eval(&model, &a.segment, b.segment.t0, &there);
    double d = ball_v3_norm(ball_v3_sub(there.position, b.segment.p0));
    CHECK_MSG(d <= 1e-3, "match %u: bounce %u is %.4f m from where segment %u put the ball", id, b.seq, d, a.seq);
    bounces++;
  }
  return bounces;
}

}  // namespace itest
