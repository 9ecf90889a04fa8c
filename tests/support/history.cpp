#include "history.h"

#include <cmath>
#include <fstream>

#include "trust.h"

namespace ballsrv {

namespace {

bool same_vec(const ball_vec3 &a, const ball_vec3 &b) { return a.x == b.x && a.y == b.y && a.z == b.z; }

bool same_flight(const ball_segment &a, const ball_segment &b) {
  return a.t0 == b.t0 && same_vec(a.p0, b.p0) && same_vec(a.v0, b.v0) && same_vec(a.s0, b.s0) &&
         a.grounded == b.grounded;
}

// What a seq names, without what a reader or a second delivery may change.
bool same_segment(const SegmentOut &a, const SegmentOut &b) {
  return same_flight(a.segment, b.segment) && a.cause == b.cause && a.cause_index == b.cause_index &&
         a.correction == b.correction;
}

bool same_event(const EventOut &a, const EventOut &b) {
  return a.kind == b.kind && a.time == b.time && a.index == b.index && a.side == b.side && a.score == b.score &&
         a.segment_seq == b.segment_seq && a.reason == b.reason;
}

std::string number(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.9g", v);
  return buf;
}

}  // namespace

const char *broken_name(Broken b) {
  switch (b) {
    case Broken::score: return "score";
    case Broken::rally: return "rally";
    case Broken::revision: return "revision";
    case Broken::clock: return "clock";
    case Broken::segment_seq: return "segment seq";
    case Broken::event_seq: return "event seq";
    case Broken::continuity: return "continuity";
  }
  return "?";
}

void History::broke(uint32_t match, Broken what, const std::string &detail) {
  violations_.push_back(Violation{match, what, counts_.lines, detail});
}

// docs/protocol.md, "Terms": a client takes nothing of an older owner than
// one it took; the record holds what arrived, the checks what was taken.
bool History::older_owner(Match &m, uint32_t term, uint32_t server) {
  if (m.has_owner && owner_before(term, server, m.term, m.server)) {
    counts_.old_owner++;
    return true;
  }
  m.has_owner = true;
  m.term = term;
  m.server = server;
  return false;
}

bool History::take(const json &line, std::string *err) {
  counts_.lines++;
  const std::string type = record_type(line);
  try {
    if (type == "match_info") {
      MatchInfoOut i = line.get<MatchInfoOut>();
      Match &m = matches_[i.match_id];
      if (!older_owner(m, i.term, i.server_id)) take_info(m, i);
    } else if (type == "segment") {
      SegmentOut s = line.get<SegmentOut>();
      Match &m = matches_[s.match_id];
      if (!older_owner(m, s.term, s.server_id)) take_segment(m, s);
    } else if (type == "event") {
      EventOut e = line.get<EventOut>();
      Match &m = matches_[e.match_id];
      if (!older_owner(m, e.term, e.server_id)) take_event(m, e);
    } else if (type == "state") {
      StateOut s = line.get<StateOut>();
      Match &m = matches_[s.match_id];
      if (!older_owner(m, s.term, s.server_id)) take_clock(m, s.match_id, s.sim_time, "state");
    }
  } catch (const std::exception &e) {
    *err = "line " + std::to_string(counts_.lines) + ": not a " + type + ": " + e.what();
    return false;
  }
  return true;
}

bool History::take_file(const std::string &path, std::string *err) {
  std::ifstream in(path);
  if (!in) {
    *err = path + ": cannot be read";
    return false;
  }
  std::string text;
  while (std::getline(in, text)) {
    if (text.empty()) continue;
    json j = json::parse(text, nullptr, false);
    if (j.is_discarded()) {
      *err = path + ":" + std::to_string(counts_.lines + 1) + ": not JSON";
      return false;
    }
    if (!take(j, err)) return false;
  }
  return true;
}

void History::take_clock(Match &m, uint32_t id, double sim, const char *what) {
  // (a MatchInfo and a ball state travel on two topics: each its own clock
  // here, a state's kept apart in has_clock/sim_time, an info's in info)
  counts_.checks++;
  if (m.has_clock && sim < m.sim_time - kClockSlack)
    broke(id, Broken::clock, std::string(what) + " sim time " + number(sim) + " after " + number(m.sim_time));
  if (!m.has_clock || sim > m.sim_time) m.sim_time = sim;
  m.has_clock = true;
}

void History::score_seen(Match &m, uint32_t id, const std::array<int, 2> &score, const std::string &where) {
  for (int side = 0; side < 2; ++side) {
    counts_.checks++;
    if (score[side] < m.score[side])
      broke(id, Broken::score,
            "side " + std::to_string(side) + " from " + std::to_string(m.score[side]) + " to " +
                std::to_string(score[side]) + " (" + where + ")");
    m.score[side] = std::max(m.score[side], score[side]);
  }
}

void History::take_info(Match &m, const MatchInfoOut &i) {
  const std::string where = "match_info revision " + std::to_string(i.revision);
  if (m.has_info) {
    const MatchInfoOut &was = m.info;
    counts_.checks += 3;
    // (a newer owner's revisions come after the older's, whatever their number:
    // each side of a partition may have written the next one)
    const bool newer = i.term != was.term || i.server_id != was.server_id;
    if (!newer && i.revision < was.revision)
      broke(i.match_id, Broken::revision, std::to_string(i.revision) + " after " + std::to_string(was.revision));
    else if (!newer && i.revision == was.revision &&
             !(i.sim_time == was.sim_time && i.play == was.play && i.segment_seq == was.segment_seq))
      broke(i.match_id, Broken::revision, std::to_string(i.revision) + " came with two contents");
    if (i.sim_time < was.sim_time - kClockSlack)
      broke(i.match_id, Broken::clock, "match_info sim time " + number(i.sim_time) + " after " + number(was.sim_time));
    if (i.play.rally < m.rally)
      broke(i.match_id, Broken::rally,
            std::to_string(i.play.rally) + " after " + std::to_string(m.rally) + " (" + where + ")");
  }
  // (scores and rallies of the MatchInfo stream; a POINT event's are kept
  // with the events: the two topics may arrive in either order)
  score_seen(m, i.match_id, i.play.score, where);
  m.rally = std::max(m.rally, i.play.rally);
  if (!m.has_info || i.revision >= m.info.revision || i.term != m.info.term || i.server_id != m.info.server_id)
    m.info = i;
  m.has_info = true;
}

History::Key History::key(uint32_t term, uint32_t server, uint32_t seq) { return {term, UINT32_MAX - server, seq}; }

void History::take_segment(Match &m, const SegmentOut &s) {
  auto it = m.segments.find(key(s.term, s.server_id, s.seq));
  if (it != m.segments.end()) {
    counts_.checks++;
    if (!same_segment(it->second, s))
      broke(s.match_id, Broken::segment_seq,
            std::to_string(s.seq) + " came with two contents (servers " + std::to_string(it->second.server_id) +
                " and " + std::to_string(s.server_id) + ", t0 " + number(it->second.segment.t0) + " and " +
                number(s.segment.t0) + ")");
    return;
  }
  if (m.has_segment && s.server_id != m.last_server) {
    counts_.owner_changes++;
    check_continuity(m, s);
  }
  m.segments[key(s.term, s.server_id, s.seq)] = s;
  m.last_server = s.server_id;
  m.has_segment = true;
}

void History::check_continuity(Match &m, const SegmentOut &s) {
  if (s.cause == Cause::serve || s.cause == Cause::racket || !m.has_info) return;
  // the segment in effect at s's t0 before it: of those before it by
  // (owner, seq), the last whose t0 is not after it (docs/protocol.md,
  // "Segments", "Terms"; one of a later t0 but an earlier seq is superseded)
  const SegmentOut *before = nullptr;
  for (const auto &kv : m.segments)  // (by key: owner, then seq)
    if (kv.first < key(s.term, s.server_id, s.seq) && kv.second.segment.t0 <= s.segment.t0) before = &kv.second;
  if (!before) return;
  ball_model model = m.info.model;
  ball_state at{};
  if (ball_segment_eval(&model, &before->segment, s.segment.t0, &at) != BALL_OK) return;
  counts_.continuity++;
  counts_.checks++;
  const double dx = at.position.x - s.segment.p0.x, dy = at.position.y - s.segment.p0.y,
               dz = at.position.z - s.segment.p0.z;
  const double gap = std::sqrt(dx * dx + dy * dy + dz * dz);
  if (!(gap <= kContinuity))
    broke(s.match_id, Broken::continuity,
          "segment " + std::to_string(s.seq) + " of server " + std::to_string(s.server_id) + " starts " +
              number(gap) + " m from segment " + std::to_string(before->seq) + " of server " +
              std::to_string(before->server_id) + " at t0 " + number(s.segment.t0));
}

void History::take_event(Match &m, const EventOut &e) {
  auto it = m.events.find(key(e.term, e.server_id, e.seq));
  if (it != m.events.end()) {
    counts_.checks++;
    if (!same_event(it->second, e))
      broke(e.match_id, Broken::event_seq, std::to_string(e.seq) + " came with two contents");
    return;
  }
  m.events[key(e.term, e.server_id, e.seq)] = e;
  if (e.kind != EventKind::point) return;
  // the POINT events' own track: each at least the score of every point before it
  std::array<int, 2> &best = m.event_score;
  for (int side = 0; side < 2; ++side) {
    counts_.checks++;
    if (e.score[side] < best[side])
      broke(e.match_id, Broken::score,
            "side " + std::to_string(side) + " from " + std::to_string(best[side]) + " to " +
                std::to_string(e.score[side]) + " (point event " + std::to_string(e.seq) + ")");
    best[side] = std::max(best[side], e.score[side]);
  }
}

std::string History::report() const {
  std::string out;
  for (const Violation &v : violations_)
    out += "match " + std::to_string(v.match) + ", line " + std::to_string(v.line) + ": " + broken_name(v.what) +
           ": " + v.detail + "\n";
  return out;
}

}  // namespace ballsrv
