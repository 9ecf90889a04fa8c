// The history checker (tests/support/history.h) on records made here: a
// random match whose owner changes (server 1, then 2, seqs going on), the
// ball continuous by libball's closed form, scores and rallies that only go
// up, segments and events delivered twice alike. Such a history breaks
// nothing; each of the invariants broken once, at a random place, is found
// under its own name and no other.
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "ball/vec3.h"
#include "check.hpp"
#include "history.h"

using namespace ballsrv;

namespace {

// A random history of one match as a watcher records it, in order: a
// take-over by server 2 at the next term, after which the old owner, back,
// writes what it had (seqs again with other contents, an older revision,
// score and clock) now and then: `stale` counts those lines.
std::vector<json> random_history(std::mt19937_64 &rng, size_t *owner_change, long *stale = nullptr) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  ball_model model;
  ball_model_default(&model);
  std::vector<json> lines;
  MatchInfoOut info;
  info.match_id = 3;
  info.server_id = 1;
  info.term = 1;
  info.players = 2;
  info.frame_time = 1.0 / 60.0;
  info.model = model;
  SegmentOut seg;
  seg.match_id = 3;
  seg.server_id = 1;
  seg.term = 1;
  seg.seq = 1;
  seg.cause = Cause::serve;
  seg.segment.t0 = 1.0;
  seg.segment.p0 = ball_v3(1.0, 1.0, 0.5);
  seg.segment.v0 = ball_v3(10.0 + 10.0 * u(rng), 3.0 * u(rng), u(rng) - 0.5);
  uint32_t event_seq = 0;
  const int n = 20 + static_cast<int>(rng() % 20);
  const int change = 3 + static_cast<int>(rng() % static_cast<unsigned>(n - 6));
  double sim = 1.0;
  for (int k = 0; k < n; ++k) {
    if (k == change) {
      seg.server_id = info.server_id = 2;  // a take-over: the seqs, revisions and clock go on
      seg.term = info.term = 2;
      *owner_change = lines.size();
    }
    if (k > change && rng() % 3 == 0) {  // the old owner back, on what it had
      SegmentOut old_seg = seg;
      old_seg.server_id = 1;
      old_seg.term = 1;
      old_seg.segment.p0.y += 0.5;
      MatchInfoOut old_info = info;
      old_info.server_id = 1;
      old_info.term = 1;
      old_info.revision = info.revision > 5 ? info.revision - 5 : 0;
      old_info.play.score = {0, 0};
      old_info.sim_time = sim - 4.0;
      EventOut old_e;
      old_e.match_id = 3;
      old_e.server_id = 1;
      old_e.term = 1;
      old_e.seq = event_seq;
      old_e.time = sim + 0.25;
      StateOut old_st;
      old_st.match_id = 3;
      old_st.server_id = 1;
      old_st.term = 1;
      old_st.sim_time = sim - 4.0;
      for (const json &j : {record_line(old_seg, sim), record_line(old_info, sim), record_line(old_e, sim),
                            record_line(old_st, sim)})
        lines.push_back(j);
      if (stale) *stale += 4;
    }
    if (k > 0 && k != change && rng() % 3 == 0) {
      // a contact written ahead that this segment supersedes (a lower seq,
      // a later t0): never in effect, so never what the ball continues from
      SegmentOut ahead = seg;
      ahead.cause = Cause::floor;
      ahead.segment.t0 = seg.segment.t0 + 0.05 + 0.3 * u(rng);
      ahead.segment.p0.x += 5.0;
      lines.push_back(record_line(ahead, sim));
      seg.seq++;
    }
    lines.push_back(record_line(seg, sim));
    if (k > 0 && rng() % 4 == 0) lines.push_back(record_line(seg, sim));  // delivered twice
    EventOut e;
    e.match_id = 3;
    e.server_id = seg.server_id;
    e.term = seg.term;
    e.seq = ++event_seq;
    e.kind = rng() % 5 == 0 ? EventKind::point : EventKind::floor;
    e.time = seg.segment.t0;
    e.segment_seq = seg.seq;
    if (e.kind == EventKind::point) {
      info.play.score[rng() % 2]++;
      info.play.rally++;
    }
    e.score = info.play.score;
    lines.push_back(record_line(e, sim));
    for (int f = 0; f < 3; ++f) {
      StateOut st;
      st.match_id = 3;
      st.server_id = seg.server_id;
      st.term = seg.term;
      st.sim_time = sim += 0.1 * u(rng);
      lines.push_back(record_line(st, sim));
    }
    info.revision++;
    info.sim_time = sim;
    info.segment_seq = seg.seq;
    lines.push_back(record_line(info, sim));
    // the next contact: where this flight puts the ball a little later
    const double t1 = std::max(sim, seg.segment.t0) + 0.05 + 0.5 * u(rng);
    ball_state at{};
    CHECK(ball_segment_eval(&model, &seg.segment, t1, &at) == BALL_OK);
    seg.seq++;
    seg.cause = rng() % 3 == 0 ? Cause::racket : Cause::floor;
    if (k + 1 == change) seg.cause = Cause::floor;  // checked across the change
    seg.segment.t0 = t1;
    seg.segment.p0 = at.position;
    seg.segment.v0 = ball_v3(at.velocity.x, std::fabs(at.velocity.y) + 1.0, at.velocity.z);
    sim = t1;
  }
  return lines;
}

// The kinds of line of a history, and the index of each.
std::vector<size_t> lines_of(const std::vector<json> &lines, const char *type, size_t from = 0) {
  std::vector<size_t> out;
  for (size_t i = from; i < lines.size(); ++i)
    if (record_type(lines[i]) == type) out.push_back(i);
  return out;
}

History checked(const std::vector<json> &lines) {
  History h;
  std::string err;
  for (const json &j : lines) CHECK_MSG(h.take(j, &err), "%s", err.c_str());
  return h;
}

// One invariant broken in a copy of a history, at a random place after the
// first lines, by its owner of the time (a line written again by the newest
// owner: every client takes it).
std::vector<json> broken(std::mt19937_64 &rng, std::vector<json> lines, size_t change, Broken what) {
  auto pick = [&](const char *type) {
    std::vector<size_t> at;
    for (size_t i : lines_of(lines, type, 4))
      if (lines[i]["term"] == 2 || i < change) at.push_back(i);  // (not the old owner's, back)
    return at[rng() % at.size()];
  };
  auto pick_newest = [&](const char *type) {
    std::vector<size_t> at;
    for (size_t i : lines_of(lines, type, change))
      if (lines[i]["term"] == 2 && lines[i].value("kind", "") != "point") at.push_back(i);
    return at[rng() % at.size()];
  };
  auto newest = [&](json j) {
    j["server"] = 2;
    j["term"] = 2;
    return j;
  };
  switch (what) {
    case Broken::score: {
      size_t i = pick("match_info");
      json &p = lines[i]["play"]["score"];
      p[rng() % 2] = -1;
      break;
    }
    case Broken::rally: {  // a MatchInfo after the newest whose rally is one lower than the highest
      json last = newest(lines[lines_of(lines, "match_info").back()]);
      const uint32_t rally = last["play"]["rally"].get<uint32_t>();
      const uint32_t revision = last["revision"].get<uint32_t>();
      last["revision"] = revision + 1;
      last["play"]["rally"] = rally + 1;
      lines.push_back(last);
      last["revision"] = revision + 2;
      last["play"]["rally"] = rally;
      lines.push_back(last);
      break;
    }
    case Broken::revision: {  // the newest revision again, with another sim time
      json last = newest(lines[lines_of(lines, "match_info").back()]);
      last["sim_time"] = last["sim_time"].get<double>() + 0.5;
      lines.push_back(last);
      break;
    }
    case Broken::clock: {
      size_t i = pick("state");
      lines[i]["sim_time"] = lines[i]["sim_time"].get<double>() - 1.0;
      break;
    }
    case Broken::segment_seq: {  // (one of the newest owner's: a seq is its owner's)
      json again = lines[pick_newest("segment")];
      again["p0"][1] = again["p0"][1].get<double>() + 0.25;
      lines.push_back(again);
      break;
    }
    case Broken::event_seq: {  // (a floor event: its score is not the POINT events' track)
      json again = lines[pick_newest("event")];
      again["time"] = again["time"].get<double>() + 0.125;
      lines.push_back(again);
      break;
    }
    case Broken::continuity: {  // the new owner's first segment (each delivery of it) 2 mm off
      const json seq = lines[change]["seq"];
      for (size_t i : lines_of(lines, "segment"))
        if (lines[i]["seq"] == seq) lines[i]["p0"][2] = lines[i]["p0"][2].get<double>() + 2e-3;
      break;
    }
  }
  return lines;
}

}  // namespace

// The old owner's lines, back after the take-over, break everything if
// taken: taken by its term, they are counted and break nothing.
TEST(a_history_of_a_take_over_breaks_nothing) {
  std::mt19937_64 rng(20261206);
  long checks = 0, continuity = 0, stale_lines = 0, found_if_taken = 0;
  for (int k = 0; k < 200; ++k) {
    size_t change = 0;
    long stale = 0;
    std::vector<json> lines = random_history(rng, &change, &stale);
    History h = checked(lines);
    CHECK_MSG(h.violations().empty(), "history %d: %s", k, h.report().c_str());
    CHECK_EQ(h.counts().owner_changes, 1L);
    CHECK_EQ(h.counts().continuity, 1L);
    CHECK_EQ(h.counts().old_owner, stale);
    checks += h.counts().checks;
    continuity += h.counts().continuity;
    stale_lines += stale;
    if (stale == 0) continue;
    for (json &j : lines) {  // one owner to a reader without terms: the old owner's lines are taken
      j["term"] = 1;
      j["server"] = 2;
    }
    found_if_taken += !checked(lines).violations().empty();
  }
  check::note("200 histories: %ld checks, %ld owner changes checked for continuity, %ld lines of the old owner not "
              "taken, nothing broken (taken, they broke %ld histories)",
              checks, continuity, stale_lines, found_if_taken);
  CHECK(stale_lines > 200);
  CHECK(found_if_taken > 100);
}

TEST(each_invariant_broken_once_is_found_by_its_name) {
  std::mt19937_64 rng(61206);
  const Broken kinds[] = {Broken::score,       Broken::rally,     Broken::revision,  Broken::clock,
                          Broken::segment_seq, Broken::event_seq, Broken::continuity};
  int found = 0;
  for (int k = 0; k < 100; ++k) {
    size_t change = 0;
    std::vector<json> good = random_history(rng, &change);
    for (Broken what : kinds) {
      History h = checked(broken(rng, good, change, what));
      bool named = !h.violations().empty();
      for (const Violation &v : h.violations()) named = named && v.what == what && v.match == 3;
      CHECK_MSG(named, "history %d, %s broken: %s", k, broken_name(what),
                h.violations().empty() ? "nothing found" : h.report().c_str());
      found += named;
    }
  }
  check::note("%d of 700 broken histories named by what was broken", found);
}

TEST(a_line_that_does_not_read_is_no_pass) {
  History h;
  std::string err;
  json bad = json::object();
  bad["type"] = "segment";
  bad["match"] = "three";
  CHECK(!h.take(bad, &err));
  CHECK(err.find("line 1: not a segment") != std::string::npos);
  CHECK(!h.take_file("/nonexistent/watch.jsonl", &err));
  CHECK(err.find("cannot be read") != std::string::npos);
}

CHECK_MAIN
