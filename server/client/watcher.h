// A watcher's mind, free of DDS and of drawing (docs/server.md,
// "Watchers"): fed with what the server says (on_info, on_model,
// on_segment, on_event, on_state, on_status) and ticked at its own frame
// rate (frame), it records every sample as it arrived (records.h) and
// takes each match through the client library's view of it (MatchView:
// the trust rules, the sim clock, the segment window, a match started
// anew, corrections): from what the view took it keeps the tally, checks
// each server ball state against the ball evaluated from the segment it
// names (the desync check), evaluates its own ball from the segment in
// effect and says when a snapshot frame is due. ball-watch prints, records
// and draws what it produces; the tests feed it from a Match.
#pragma once

#include <cstdint>
#include <deque>
#include <map>
#include <string>
#include <vector>

#include <memory>

#include "frame_clock.h"
#include "match_view.h"
#include "records.h"

namespace ballsrv {

struct WatcherSettings {
  long match = -1;             // watch this match only; -1: every match
  double fps = 60.0;           // own frames per real s (the record's "start" line says it)
  bool log = true;             // the rally log
  bool record_frames = false;  // the own ball in the record, every frame
  double snapshot_every = 0.0; // sim s between snapshot frames, on multiples of it; 0: none
  ServerChoice servers;        // the servers whose samples it uses (recorded all the same)
};

// One line of the rally log.
struct LogLine {
  uint32_t match;
  double sim_time;  // sim s of what it tells
  std::string text; // "serve by player 0 (near side), score 0-0"
};

// A snapshot frame due: what to draw (the caller draws it and then calls
// Watcher::snapshot_written).
struct SnapshotDue {
  uint32_t match = 0;
  MatchInfoOut info;               // the match: its scene's name and flight model
  bool has_model = false;          // `model` came from the wire (docs/protocol.md, "The match's model")
  ball_model model{};              // the whole model the match is stepped with: the court to draw
  double sim_time = 0.0;           // sim s
  ball_vec3 ball{0, 0, 0};         // m, the own ball
  std::vector<ball_vec3> trail;    // m, the last second of the own ball, oldest first
  std::vector<ball_event> events;  // the last second's collisions, as libball's events (markers)
};

// What the calls produced since the caller last took it.
struct WatchOutput {
  std::vector<json> records;  // record lines, in order
  std::vector<LogLine> log;
  std::vector<SnapshotDue> snapshots;
  void clear() {
    records.clear();
    log.clear();
    snapshots.clear();
  }
};

// What the watcher took of one match, for a client that mirrors it (the
// spectator page, server/web/spectator.h).
struct WatchedView {
  const MatchInfoOut *info = nullptr;      // the newest usable MatchInfo
  const std::vector<KeptSegment> *segments = nullptr;  // the segments taken, by seq (the view's window)
  const ball_model *model = nullptr;       // the whole model from the wire (nullptr: not come)
  const std::deque<EventOut> *events = nullptr;  // the newest events taken, oldest first
  uint64_t events_taken = 0;               // events taken so far (the deque holds the newest of them)
  const SimClock *clock = nullptr;         // the estimate of the match's sim clock
  double info_real = 0.0;                  // local realtime s the newest usable MatchInfo came
};

class Watcher {
 public:
  explicit Watcher(const WatcherSettings &settings) : settings_(settings) {}

  void on_start(double real);  // the record's "start" line
  void on_ready(double real);  // a server's writers reach us: the "ready" line (once)
  // `real`: the local realtime clock at reception, s
  void on_info(const MatchInfoOut &info, double real);
  void on_model(const MatchModelOut &model);
  void on_segment(const SegmentOut &segment, double real);
  void on_event(const EventOut &event, double real);
  void on_state(const StateOut &state, double real);
  void on_status(const StatusOut &status);
  // A sample of `match` that did not read as its type (counted as not taken).
  void not_taken(uint32_t match);
  // The desync check of every state received whose segment is known now.
  void check_states();
  // An own frame at local realtime `real`: every match's ball from its
  // newest segment at the estimated sim time; snapshots as they fall due.
  void frame(double real);
  // A snapshot the caller drew to `file`: its record line, and the count.
  // `drawn`: the record line's file, camera, size and rackets (real and the rest are filled in here)
  void snapshot_written(const SnapshotDue &due, const SnapshotRecord &drawn, double real);

  WatchOutput &output() { return out_; }
  WatchSummary summary(double seconds) const;
  uint64_t hits() const { return hits_; }  // racket hits in play, every match
  bool ready() const { return ready_; }
  // The matches with a usable MatchInfo, and what was taken of one (false: none).
  std::vector<uint32_t> match_ids() const;
  bool view(uint32_t match, WatchedView *out) const;
  // The whole model of a match from the wire; nullptr: it has not come.
  const ball_model *model(uint32_t match) const;

 private:
  struct Watched {
    std::unique_ptr<MatchView> view;          // the client library's view of the match
    std::vector<StateOut> pending;            // states whose segment has not arrived yet
    WatchedMatchSummary tally;
    uint64_t anew = 0;                        // the view's starts anew seen
    // the last second of the own ball and of the collisions, the next snapshot's sim time
    std::deque<std::pair<double, ball_vec3>> trail;
    std::deque<ball_event> recent;
    std::deque<EventOut> events;  // the newest events given
    uint64_t events_taken = 0;
    double next_snapshot = -1.0;
    // floor, net and wall segments received, not yet happened or superseded:
    // seq -> (t0 sim s, lead at reception real s)
    std::map<uint32_t, std::pair<double, double>> leads;
  };
  void tally(Watched &w, const EventOut &e, int sign);
  void take(Watched &w, std::vector<ViewEvent> &given);  // what the view gave: tallied, logged, kept
  bool wanted(uint32_t id) const { return settings_.match < 0 || id == static_cast<uint32_t>(settings_.match); }
  Watched &watched(uint32_t id);
  void settle_leads(Watched &w, double real);
  void say(uint32_t match, double sim_time, const std::string &text);

  WatcherSettings settings_;
  std::map<uint32_t, Watched> matches_;
  std::map<uint32_t, StatusOut> servers_;
  Percentiles latency_, latency_server_;  // a hit's newest sample written -> its segment received / written
  Percentiles bounce_lead_;               // real s from a contact's segment received to its t0 (< 0: late)
  uint64_t bounces_ahead_ = 0, bounces_late_ = 0, bounces_superseded_ = 0;
  double start_real_ = 0.0, first_segment_after_ = -1.0;
  uint64_t hits_ = 0;
  bool ready_ = false;
  WatchOutput out_;
};

// The rally log's line for an event, or "" for events not worth a line.
std::string rally_line(const EventOut &e);
// The summary as ball-watch prints it at the end, one line a match, a
// server and the latency.
std::vector<std::string> summary_lines(const WatchSummary &s);

}  // namespace ballsrv
