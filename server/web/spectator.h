// The spectator page's core (docs/bots-and-watchers.md, "The spectator page"), free of
// DDS and of HTTP: it mirrors what a Watcher took (every match's court,
// MatchInfo, segments, events and sim clock) and the players' racket samples
// into the page's messages, JSON texts numbered in order. A page opened now
// gets snapshot(), then every message after it. The page evaluates the ball
// itself from the segments (docs/protocol.md). Not thread-safe: the web
// server (web_server.h) calls it under its lock.
#pragma once

#include <array>
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "ball/ball.h"
#include "watcher.h"

namespace ballsrv {

struct SpectatorSettings {
  double aspect = 4.0 / 3.0;    // width / height of the page's view (its camera presets are placed for it)
  double clock_every = 0.1;     // real s between two clock messages of a match
  double silence = 10.0;        // real s without a MatchInfo after which a match's server is gone (docs/protocol.md, "Time")
  size_t keep_messages = 4096;  // messages a late reader can still catch up with
  size_t page_segments = 32;    // segments of a match a page is given at once
  size_t page_events = 32;      // events of a match a page is given at once
};

struct PageMessage {
  uint64_t id = 0;   // 1, 2, ... in order
  std::string text;  // one JSON object
};

class Spectator {
 public:
  // court: a match's model for its court (net, walls, rackets), from its MatchInfo
  Spectator(const SpectatorSettings &settings, std::function<ball_model(const MatchInfoOut &)> court)
      : settings_(settings), court_(std::move(court)) {}

  // Brings the page's view in line with what `w` took, at local realtime `real`.
  void update(const Watcher &w, double real);
  // A racket sample its slot's holder wrote (the client library trusted it): passed
  // on unless it is within 1/120 s of the slot's newest passed on (a page
  // needs no more). false: not passed on (counted in racket_dropped).
  bool on_racket(const RacketSampleIn &s);

  // What a page opened now is given first: every match as it stands.
  std::vector<std::string> snapshot() const;
  // The messages after `after` (at most `max`); false when some of them
  // are no longer kept (the reader then starts over from a snapshot).
  bool since(uint64_t after, size_t max, std::vector<PageMessage> *out) const;
  uint64_t newest() const { return next_id_ - 1; }
  uint64_t racket_dropped() const { return racket_dropped_; }
  // events the watcher took whose numbers are not all finite: not passed on
  uint64_t not_drawable() const { return not_drawable_; }

 private:
  struct Mirror {
    std::string court;                   // the court message
    bool court_from_wire = false;        // ... drawn from the match's model on the wire
    std::string scene;                   // ... of this scene and model hash
    uint64_t model_hash = 0;
    std::array<double, 4> judged{};      // ... and court (MatchInfo's court_x, court_z)
    uint32_t server = 0;
    uint32_t revision = 0;
    std::string info;                    // the newest info message
    std::map<uint32_t, std::string> segments;  // the segment messages sent, by seq
    std::pair<uint32_t, size_t> watched{0, 0};  // the watcher's newest seq and count when last looked at
    std::deque<std::string> events;      // the newest event messages
    uint64_t events_sent = 0;
    std::array<std::deque<std::string>, kMaxPlayers> rackets;  // the newest racket messages per slot
    std::array<double, kMaxPlayers> racket_t{};                 // capture time of the newest passed on
    std::array<ParticipantId, kMaxPlayers> owners{};
    int players = 0;
    std::string clock;                   // the newest clock message
    double clock_real = -1.0;
    bool live = false;
    double frozen = 0.0;                 // sim s the ball stands at while the server is gone
  };
  void send(std::string text);
  void mirror(uint32_t id, const WatchedView &v, double real);
  void mirror_segments(uint32_t id, const std::deque<SegmentOut> &segs, Mirror *m);
  void mirror_court(uint32_t id, const WatchedView &v, Mirror *m);
  void mirror_info(uint32_t id, const WatchedView &v, bool live, Mirror *m);
  void mirror_events(uint32_t id, const WatchedView &v, Mirror *m);
  void mirror_clock(uint32_t id, const WatchedView &v, bool live, double real, Mirror *m);

  SpectatorSettings settings_;
  std::function<ball_model(const MatchInfoOut &)> court_;
  std::map<uint32_t, Mirror> matches_;
  std::deque<PageMessage> sent_;
  uint64_t next_id_ = 1;
  uint64_t racket_dropped_ = 0, not_drawable_ = 0;
};

// The court message of a match, JSON: its floor as libball's renderer lays
// it out around the court the match's rules judge (MatchInfo's court_x and
// court_z: ball_floor_layout_court), the net, walls, racket radii, the
// camera presets for `aspect`, libball's palette (ball_render_palette), and
// the whole model (`court`) by libball's field table with its
// ball_model_hash in hex, for the page's WebAssembly module.
std::string court_message(uint32_t match, const MatchInfoOut &info, const ball_model &court, double aspect);
// The info message of a match: the MatchInfo, whether its server is heard,
// the local realtime it came (`real`: the page's module takes it at that
// time, as the watcher did), its model hash in hex, libball's name of its
// level (ball_level_name) and the slots of each side with the side's name.
std::string info_message(uint32_t match, const MatchInfoOut &info, bool live, double real);

}  // namespace ballsrv
