// The point rules, tennis-like and free of geometry (docs/server-design.md, "Match
// rules"). A rally starts with a serve, which counts as a stroke of the
// serving side; after every stroke the ball must first come down inside the
// other side's court, and once it has bounced there the other side must
// strike it before it bounces again:
//
//   first bounce after a stroke on the striker's own side   -> striker loses (own_side, or net
//                                                               if it touched the net on the way)
//   first bounce outside the other side's court, or a wall  -> striker loses (out)
//   before any bounce
//   second bounce (on the receiver's side)                  -> striker wins (double_bounce)
//   after bouncing in: a wall, a bounce on the striker's    -> striker wins (not_returned)
//   side, the ball rolling, or leaving the court area
//   a rally longer than the match's limit                   -> let: replayed, nobody scores
//
// Strokes are legal anywhere and before the bounce (volleys); a racket hit
// ends nothing by itself.
#pragma once

#include "types.h"

namespace ballsrv {

struct Call {
  bool decided = false;
  int winner = -1;  // side, -1: a let
  Reason reason = Reason::none;
};

// The rules' state, stored here once: the rally's (who struck last, the
// bounces since, the net) and the match's (the score, the serve due, the
// newest event's seq), as PlayState carries it on the wire.
class Rally {
 public:
  void start(int serving_side, double t) {
    s_.live = true;
    s_.striker = serving_side;
    s_.bounces = 0;
    s_.net = false;
    s_.rally_start = t;
  }
  bool live() const { return s_.live; }
  int striker() const { return s_.striker; }
  int bounces() const { return s_.bounces; }
  int bounce_side() const { return s_.bounce_side; }
  bool net() const { return s_.net; }
  double started() const { return s_.rally_start; }
  PlayState &state() { return s_; }
  const PlayState &state() const { return s_; }

  Call on_racket(int side) {
    s_.striker = side;
    s_.bounces = 0;
    s_.net = false;
    return Call{};
  }
  Call on_net() {
    s_.net = true;
    return Call{};
  }
  // a bounce on `side`; inside: within the court; grounded: it rolls on from there
  Call on_floor(int side, bool inside, bool grounded) {
    if (s_.bounces == 0) {
      if (side == s_.striker) return end(other(), s_.net ? Reason::point_net : Reason::point_own_side);
      if (!inside) return end(other(), Reason::point_out);
      s_.bounces = 1;
      s_.bounce_side = side;
      if (grounded) return end(s_.striker, Reason::point_not_returned);
      return Call{};
    }
    return end(s_.striker, side == s_.bounce_side ? Reason::point_double_bounce : Reason::point_not_returned);
  }
  Call on_wall() { return s_.bounces == 0 ? end(other(), Reason::point_out) : end(s_.striker, Reason::point_not_returned); }
  // each frame: `gone` when the ball has left the court area for good or lies still
  Call on_frame(bool gone, double t, double max_time) {
    if (gone) return on_wall();
    if (t - s_.rally_start > max_time) return end(-1, Reason::point_let);
    return Call{};
  }

 private:
  int other() const { return 1 - s_.striker; }
  Call end(int winner, Reason why) {
    s_.live = false;
    return Call{true, winner, why};
  }
  PlayState s_;
};

}  // namespace ballsrv
