// What a client received, checked against the invariants every client must
// see whatever stalls, kills, partitions and heals the servers go through
// (docs/server-tests.md, "What every client sees"): fed the lines of a
// watcher's record (`ball-watch --record`, records.h) in the order they came,
// a History says per match, and by the record line, what broke:
//   - score: a side's score in a MatchInfo's play or a POINT event went back;
//   - rally: a MatchInfo's rally count went back;
//   - revision: a MatchInfo's revision went back, or one revision came with
//     two contents (another sim time, play or segment), of one owner (a
//     newer owner's come after an older's, whatever their number);
//   - clock: the sim time of a MatchInfo or a ball state went back;
//   - segment seq / event seq: one seq of one owner came with two contents
//     (a newer owner numbers on from what it restored: its seqs are its own);
//   - continuity: the first segment a new server wrote (not a serve or a
//     racket hit: those place the ball) starts more than 1 mm from where the
//     segment in effect before it puts the ball at its t0 (the flight model of
//     the newest MatchInfo; libball's ball_segment_eval).
// Lines of an older owner than one taken before are not taken, as by every
// client (docs/protocol.md, "Terms"); they are counted.
// It counts what it checked, so that a run that checked nothing is seen.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include "records.h"

namespace ballsrv {

enum class Broken { score, rally, revision, clock, segment_seq, event_seq, continuity };
const char *broken_name(Broken b);

struct Violation {
  uint32_t match = 0;
  Broken what = Broken::score;
  long line = 0;        // the record line (1-based) that showed it
  std::string detail;   // what was seen against what came before
};

struct HistoryCounts {
  long lines = 0;          // record lines taken
  long checks = 0;         // comparisons made against what came before
  long owner_changes = 0;  // segments whose server differs from the segment's before it
  long continuity = 0;     // of those, checked for continuity (the others: a serve, a hit or no model yet)
  long old_owner = 0;      // lines of an older owner than one taken before (docs/protocol.md, "Terms"): not taken
};

class History {
 public:
  static constexpr double kContinuity = 1e-3;  // m: a new owner's ball is within this of the old one's
  static constexpr double kClockSlack = 1e-9;  // sim s a sim time may seem to go back by rounding

  // One record line (its "type": segment, event, state, match_info; the
  // others are counted and skipped). False for a line that does not read
  // as its type (err says why): a record the checker cannot read is no pass.
  bool take(const json &line, std::string *err);
  // Every line of a JSON Lines file; false with err at the first that fails.
  bool take_file(const std::string &path, std::string *err);

  const std::vector<Violation> &violations() const { return violations_; }
  const HistoryCounts &counts() const { return counts_; }
  // "match 0, line 812: score: side 1 from 2 to 1 (match_info revision 31)", one a line.
  std::string report() const;

 private:
  struct Match {
    std::array<int, 2> score{0, 0};        // the highest of the MatchInfo stream, per side
    std::array<int, 2> event_score{0, 0};  // and of the POINT events'
    uint32_t rally = 0;
    bool has_info = false;
    MatchInfoOut info;  // the newest of the highest revision
    double sim_time = 0.0;  // the ball states' newest
    bool has_clock = false;
    std::map<std::tuple<uint32_t, uint32_t, uint32_t>, SegmentOut> segments;  // by key()
    std::map<std::tuple<uint32_t, uint32_t, uint32_t>, EventOut> events;      // by key()
    uint32_t last_server = 0;                 // of the newest segment taken
    bool has_segment = false;
    uint32_t term = 0, server = 0;            // the newest owner taken
    bool has_owner = false;
  };
  bool older_owner(Match &m, uint32_t term, uint32_t server);  // counted, not taken
  // a segment's or an event's place in its match's order: by owner (term,
  // then the lower server id later), then by seq
  using Key = std::tuple<uint32_t, uint32_t, uint32_t>;
  static Key key(uint32_t term, uint32_t server, uint32_t seq);
  void take_info(Match &m, const MatchInfoOut &i);
  void take_segment(Match &m, const SegmentOut &s);
  void take_event(Match &m, const EventOut &e);
  void take_clock(Match &m, uint32_t id, double sim, const char *what);  // a ball state's
  void score_seen(Match &m, uint32_t id, const std::array<int, 2> &score, const std::string &where);
  void check_continuity(Match &m, const SegmentOut &s);
  void broke(uint32_t match, Broken what, const std::string &detail);

  std::map<uint32_t, Match> matches_;
  std::vector<Violation> violations_;
  HistoryCounts counts_;
};

}  // namespace ballsrv
