// A watcher's mind, free of DDS and of drawing (docs/bots-and-watchers.md,
// "Watchers"): a client of the client library (ball/net.h) and nothing
// else. Each turn polls the client; its tap (docs/client.md, "A tap")
// brings every sample as it came, with the library's verdict on it, and
// its events come from the poll, each once and in order. The watcher
// records every line, follows every match the library lists (or the one
// asked for), keeps the tally from the events (a correction's voided ones
// taken off), checks each server ball state against the ball evaluated
// from the trusted segment it names (the desync check), evaluates its own
// ball with ball_net_ball_at at its own frame rate and says when a
// snapshot frame is due, the rackets placed by ball_net_racket. ball-watch
// prints, records and draws what it produces; the tests drive its client
// from a Match.
#pragma once

#include <array>
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "ball/net.h"
#include "frame_clock.h"
#include "records.h"

namespace ballsrv {

struct WatcherSettings {
  long match = -1;             // watch this match only; -1: every match
  double fps = 60.0;           // own frames per real s (the record's "start" line says it)
  bool log = true;             // the rally log
  bool record_frames = false;  // the own ball in the record, every frame
  double snapshot_every = 0.0; // sim s between snapshot frames, on multiples of it; 0: none
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
  MatchInfoOut info;               // the match: its scene's name and court
  bool has_model = false;          // `model` came from the wire (docs/protocol.md, "The match's model")
  ball_model model{};              // the whole model the match is stepped with: the court to draw
  double sim_time = 0.0;           // sim s
  ball_vec3 ball{0, 0, 0};         // m, the own ball
  std::vector<ball_vec3> trail;    // m, the last second of the own ball, oldest first
  std::vector<ball_event> events;  // the last second's collisions, as libball's events (markers)
  std::array<bool, kMaxPlayers> racket_drawn{};      // a racket placed for the slot (ball_net_racket)
  std::array<ball_racket_pose, kMaxPlayers> rackets{};
};

// What the calls produced since the caller last took it.
struct WatchOutput {
  std::vector<json> records;              // record lines, in order
  std::vector<LogLine> log;
  std::vector<SnapshotDue> snapshots;
  std::vector<RacketSampleIn> rackets;    // the players' racket samples the library trusted (for the page)
  void clear() {
    records.clear();
    log.clear();
    snapshots.clear();
    rackets.clear();
  }
};

// What the watcher took of one match, for a client that mirrors it (the
// spectator page, server/web/spectator.h).
struct WatchedView {
  const MatchInfoOut *info = nullptr;            // the newest trusted MatchInfo
  const std::deque<SegmentOut> *segments = nullptr;  // the trusted segments, by seq
  const ball_model *model = nullptr;             // the whole model from the wire (nullptr: not come)
  const std::deque<EventOut> *events = nullptr;  // the newest events given, oldest first
  uint64_t events_taken = 0;                     // events given so far (the deque holds the newest of them)
  std::function<double(double)> sim_at;          // the match's sim time at a local realtime s (its clock)
  bool running = false;                          // the sim clock runs (the match plays)
  double info_real = 0.0;                        // local realtime s the newest trusted MatchInfo came
};

class Watcher {
 public:
  // Over `client`, whose clock must be the local realtime clock (the
  // times given here); the watcher sets its tap. The client outlives it.
  Watcher(const WatcherSettings &settings, ball_net_client *client);
  ~Watcher();
  Watcher(const Watcher &) = delete;
  Watcher &operator=(const Watcher &) = delete;

  void on_start(double real);  // the record's "start" line
  // A turn at local realtime `real`: the client polled (its lines and
  // events taken), the matches listed followed, their models fetched, the
  // desync check of the states whose segment is known. "" or why the poll
  // failed.
  std::string turn(double real);
  // An own frame at `real`: every match's ball from the client; snapshots as they fall due.
  void frame(double real);
  // A snapshot the caller drew: its record line, and the count. `drawn`:
  // the record line's file, camera, size and rackets (real and the rest are filled in here)
  void snapshot_written(const SnapshotDue &due, const SnapshotRecord &drawn, double real);

  WatchOutput &output() { return out_; }
  WatchSummary summary(double seconds) const;
  uint64_t hits() const { return hits_; }  // racket hits in play, every match
  bool ready() const { return ready_; }
  uint64_t unreadable() const { return unreadable_; }  // tap lines that did not read as their type
  uint64_t let_go() const { return let_go_; }  // matches forgotten to make room: no server served them any more
  // The matches with a trusted MatchInfo, and what was taken of one (false: none).
  std::vector<uint32_t> match_ids() const;
  bool view(uint32_t match, WatchedView *out) const;
  // The whole model of a match from the wire; nullptr: it has not come.
  const ball_model *model(uint32_t match) const;

 private:
  struct Watched {
    bool has_info = false;
    MatchInfoOut info;                        // the newest trusted
    double info_real = 0.0;
    bool followed = false;                    // the client follows it
    bool said_refused = false;                // the log said it is not followed
    bool has_model = false;
    ball_model model{};                       // ball_net_model's, of the info's model_hash
    uint64_t model_hash = 0;                  // its hash
    std::deque<SegmentOut> segments;          // trusted, distinct seqs, by seq
    std::vector<StateOut> pending;            // trusted states whose segment has not arrived yet
    WatchedMatchSummary tally;
    std::map<uint32_t, EventOut> given;       // the newest events given, by seq (a voided one's kind)
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
  static void tap(void *user, const char *text, size_t length);
  void on_line(const json &line);
  void on_info(const json &line);
  void on_segment(const json &line);
  bool keep(Watched &w, const SegmentOut &seg);
  void on_state(const json &line);
  void on_event(const ball_net_event &e);
  void check_states();
  void fetch_model(uint32_t id, Watched &w);
  bool follow(uint32_t id);
  size_t let_go_silent();
  void tally(Watched &w, const EventOut &e, int sign);
  bool wanted(uint32_t id) const { return settings_.match < 0 || id == static_cast<uint32_t>(settings_.match); }
  Watched &watched(uint32_t id) { return matches_[id]; }
  bool sim_now(uint32_t id, double real, double *sim) const;
  void settle_leads(uint32_t id, Watched &w, double real);
  void say(uint32_t match, double sim_time, const std::string &text);

  WatcherSettings settings_;
  ball_net_client *client_;
  double real_ = 0.0;  // the turn's local realtime
  std::map<uint32_t, Watched> matches_;
  std::map<uint32_t, StatusOut> servers_;
  Percentiles latency_, latency_server_;  // a hit's newest sample written -> its segment received / written
  Percentiles bounce_lead_;               // real s from a contact's segment received to its t0 (< 0: late)
  uint64_t bounces_ahead_ = 0, bounces_late_ = 0, bounces_superseded_ = 0;
  double start_real_ = 0.0, first_segment_after_ = -1.0;
  uint64_t hits_ = 0, unreadable_ = 0, let_go_ = 0;
  bool ready_ = false;
  WatchOutput out_;
};

// The rally log's line for an event, or "" for events not worth a line.
std::string rally_line(const EventOut &e);
// The summary as ball-watch prints it at the end, one line a match, a
// server and the latency.
std::vector<std::string> summary_lines(const WatchSummary &s);

}  // namespace ballsrv
