// The players' rackets as a watcher sees them (docs/server.md, "The
// spectator page"), free of DDS: racket samples read from the players'
// topic, taken only from the holder of their slot as the newest MatchInfo
// names it, kept on one libball track per slot, so a frame shows each
// racket where its track puts it (ball_racket_estimate: interpolated
// between samples, eq 15 past the newest, capped by extrapolation_time).
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <memory>

#include "ball/ball.h"
#include "match_rackets.h"
#include "watcher.h"

namespace ballsrv {

class RacketTracks {
 public:
  // court: a match's model (its rackets and flight fields), from its MatchInfo
  explicit RacketTracks(std::function<ball_model(const MatchInfoOut &)> court) : court_(std::move(court)) {}

  // A sample from the players' topic. Taken when the match's newest usable
  // MatchInfo (w) names its writer as the slot's holder and libball's track
  // takes it (finite, newer than the newest kept); false: dropped, counted.
  bool take(const RacketSampleIn &s, const Watcher &w);
  // Slot `slot`'s racket at sim time t; false: none to draw (no sample, stale).
  bool pose(uint32_t match, int slot, double t, ball_racket_pose *out) const;
  uint64_t taken() const { return taken_; }
  uint64_t dropped() const { return dropped_; }

 private:
  std::function<ball_model(const MatchInfoOut &)> court_;
  std::map<uint32_t, MatchRackets> matches_;
  uint64_t taken_ = 0, dropped_ = 0;
};

}  // namespace ballsrv
