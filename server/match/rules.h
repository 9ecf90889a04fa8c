// The point rules, tennis-like and free of geometry (docs/server.md, "Match
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

class Rally {
 public:
  void start(int serving_side, double t) {
    live_ = true;
    striker_ = serving_side;
    bounces_ = 0;
    net_ = false;
    started_ = t;
  }
  bool live() const { return live_; }
  int striker() const { return striker_; }
  int bounces() const { return bounces_; }
  int bounce_side() const { return bounce_side_; }
  bool net() const { return net_; }
  double started() const { return started_; }
  // Puts the rally where another server's left it (PlayState's fields).
  void restore(bool live, int striker, int bounces, int bounce_side, bool net, double started) {
    live_ = live;
    striker_ = striker;
    bounces_ = bounces;
    bounce_side_ = bounce_side;
    net_ = net;
    started_ = started;
  }

  Call on_racket(int side) {
    striker_ = side;
    bounces_ = 0;
    net_ = false;
    return Call{};
  }
  Call on_net() {
    net_ = true;
    return Call{};
  }
  // a bounce on `side`; inside: within the court; grounded: it rolls on from there
  Call on_floor(int side, bool inside, bool grounded) {
    if (bounces_ == 0) {
      if (side == striker_) return end(other(), net_ ? Reason::point_net : Reason::point_own_side);
      if (!inside) return end(other(), Reason::point_out);
      bounces_ = 1;
      bounce_side_ = side;
      if (grounded) return end(striker_, Reason::point_not_returned);
      return Call{};
    }
    return end(striker_, side == bounce_side_ ? Reason::point_double_bounce : Reason::point_not_returned);
  }
  Call on_wall() { return bounces_ == 0 ? end(other(), Reason::point_out) : end(striker_, Reason::point_not_returned); }
  // each frame: `gone` when the ball has left the court area for good or lies still
  Call on_frame(bool gone, double t, double max_time) {
    if (gone) return on_wall();
    if (t - started_ > max_time) return end(-1, Reason::point_let);
    return Call{};
  }

 private:
  int other() const { return 1 - striker_; }
  Call end(int winner, Reason why) {
    live_ = false;
    return Call{true, winner, why};
  }
  bool live_ = false;
  int striker_ = 0;
  int bounces_ = 0;
  int bounce_side_ = 0;
  bool net_ = false;
  double started_ = 0.0;
};

}  // namespace ballsrv
