// Racket hits at their instant (docs/server-design.md, "Hits at their instant";
// docs/design.md, "Rooms by state"): when, inside the frame being stepped,
// a racket first meets the ball, so that the loop steps the match to that
// instant instead of the frame's end. A HitClock is the state (the hit
// found, whether samples came since, what a bound ruled out); look() is its
// one entry point, called by the match after a frame, a hit and samples.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>

#include "ball/ball.h"
#include "types.h"

namespace ballsrv {

class HitClock {
 public:
  // The first racket contact of the sim before the frame's end `end` (sim
  // s; the next frame ends at end + frame; rackets: the model's n_rackets):
  // next() its sim s, +Inf none.
  // A bound over this frame and the next that rules every racket out
  // spares the looks after it while the ball stays on its segment, the
  // tracks take no sample and the model (model_hash) is the same. Counted
  // in counters: hit_looks, hit_looks_spared, hit_queries.
  void look(const ball_sim &sim, int rackets, uint64_t model_hash, double end, double frame,
            MatchCounters *counters);
  void none() { next_ = HUGE_VAL, stale_ = false, near_ = false; }  // nothing to look for now
  void drop() { next_ = HUGE_VAL; }    // the hit found is no more (the match stopped)
  void moved() { stale_ = true; }      // a track moved: look again when asked
  bool stale() const { return stale_; }
  double next() const { return next_; }
  // The last look could not rule out a racket before the end of the frame
  // after its own (the bound over both said maybe).
  bool near() const { return near_; }

 private:
  // A look's bound over its frame and the next said no racket can be hit
  // before `until`: it holds while the sim stays on that segment with those
  // tracks and model, awake
  struct Clear {
    double until = -HUGE_VAL;
    double t0 = 0.0;                           // the segment's start and velocity
    ball_vec3 v0{};
    std::array<double, kMaxPlayers> newest{};  // each track's newest sample time
    std::array<int, kMaxPlayers> count{};      // and its samples
    uint64_t model_hash = 0;
  };
  bool clear_holds(const ball_sim &sim, int rackets, uint64_t model_hash, double end) const;
  void keep_clear(const ball_sim &sim, int rackets, uint64_t model_hash, double until);
  double next_ = HUGE_VAL;  // sim s of the next racket hit before the frame's end
  bool stale_ = false;      // samples came since next_ was found: look again when asked
  bool near_ = false;
  Clear clear_;
};

}  // namespace ballsrv
