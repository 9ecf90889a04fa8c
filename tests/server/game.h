// An offline game for the server's tests: a Match on libball's default
// tennis scene, stepped frame by frame with real time = sim time, players
// that are fake participants, and every output kept for the checks.
#pragma once

#include <string>
#include <vector>

#include "ball/scene.h"
#include "ball/vec3.h"
#include "match.h"

namespace test {

using namespace ballsrv;

inline ParticipantId participant(uint8_t n) {
  ParticipantId id{};
  id[0] = n;
  id[11] = 0xAB;
  return id;
}

// Where a test parks a player's racket: behind its own baseline and off the
// side of the court, out of the ball's way but inside the racket margin.
inline ball_vec3 parked_center(const Court &c, int slot) {
  double x = Court::side_of_slot(slot) == 0 ? c.x_lo - 4.0 : c.x_hi + 4.0;
  return ball_v3(x, 1.0, c.z_lo - 4.0 - 0.5 * slot);
}

inline MatchConfig default_config() {
  MatchConfig c;
  c.id = 7;
  c.level = BALL_LEVEL_EASY;
  return c;
}

struct Game {
  Match match;
  MatchOutput out;
  double now = 1000.0;  // real s; presence only
  std::vector<EventOut> events;
  std::vector<SegmentOut> segments;
  std::vector<StateOut> states;
  uint32_t seq[kMaxPlayers] = {0, 0, 0, 0};
  ParticipantId owner[kMaxPlayers] = {};
  bool park[kMaxPlayers] = {false, false, false, false};
  double sent_at[kMaxPlayers] = {0, 0, 0, 0};  // real s of each slot's newest parked sample
  std::string err;
  int frames = 0;

  explicit Game(const MatchConfig &config = default_config()) {
    ball_scene scene;
    ball_scene_default(&scene);
    ok = match.init(config, scene, &err);
  }
  bool ok = false;

  Reason control(ControlKind kind, ParticipantId who, int player = -1, double value = 0.0) {
    ControlIn c;
    c.match_id = match.id();
    c.kind = kind;
    c.player = player;
    c.from = who;
    c.level = static_cast<int>(value);
    c.time_base = value;
    out.clear();
    Reason r = match.on_control(c, now, &out);
    keep();
    return r;
  }

  // joins `slot` as `who` and keeps its racket parked off the court
  Reason join(int slot, ParticipantId who) {
    Reason r = control(ControlKind::join, who, slot);
    if (r == Reason::none && slot >= 0 && slot < kMaxPlayers) {
      owner[slot] = who;
      park[slot] = true;
    }
    return r;
  }

  RacketSampleIn parked_sample(int slot) {
    RacketSampleIn s;
    s.match_id = match.id();
    s.player = slot;
    s.seq = ++seq[slot];
    s.capture_time = match.sim().time;
    s.center = parked_center(match.court(), slot);
    s.normal = ball_v3(1, 0, 0);
    s.from = owner[slot];
    return s;
  }

  // stamped as a server writes them: its id and the match's term
  uint32_t server_id = 1, term = 1;
  template <class T> void stamp(std::vector<T> *to, const std::vector<T> &from) {
    for (T x : from) {
      x.server_id = server_id;
      x.term = term;
      to->push_back(x);
    }
  }
  void keep() {
    stamp(&events, out.events);
    stamp(&segments, out.segments);
    if (out.has_state) {
      states.push_back(out.state);
      states.back().server_id = server_id;
      states.back().term = term;
    }
  }

  // runs frames for `seconds` of real time; parked players send 10 samples a second
  void run(double seconds) {
    int n = static_cast<int>(seconds * match.config().frame_rate + 0.5);
    for (int k = 0; k < n; ++k) {
      if (frames % 6 == 0)
        for (int i = 0; i < kMaxPlayers; ++i)
          if (park[i]) {
            match.on_sample(parked_sample(i), now);
            sent_at[i] = now;
          }
      out.clear();
      match.frame(now, &out);
      keep();
      now += match.frame_time();
      frames++;
    }
  }

  int count(EventKind kind) const {
    int n = 0;
    for (const auto &e : events) n += e.kind == kind;
    return n;
  }
  const EventOut *first(EventKind kind, size_t from = 0) const {
    for (size_t i = from; i < events.size(); ++i)
      if (events[i].kind == kind) return &events[i];
    return nullptr;
  }
};

// a game with both slots joined and parked: nothing hits, serves and double bounces
inline Game played(double seconds) {
  Game g;
  g.join(0, participant(1));
  g.join(1, participant(2));
  g.run(seconds);
  return g;
}

}  // namespace test
