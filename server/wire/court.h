// The court a match is played on: shared by the server, the bots and the
// watchers (the wire's vocabulary). The model a match is played with, built
// from its scene, is the server's: match_model.h.
#pragma once

#include <string>

#include "ball/ball.h"
#include "types.h"

namespace ballsrv {

// A court split by a net on the plane x = net_x: side 0 is x < net_x, side 1
// the rest. Player slot i plays on side i % 2 (doubles: 0 and 2 against 1
// and 3).
struct Court {
  double net_x = 11.885;          // m
  double x_lo = 0.0, x_hi = 23.77;  // m: the court's baselines
  double z_lo = 0.0, z_hi = 10.97;  // m: its sidelines
  double floor = 0.0;             // m

  int side_of(double x) const { return x < net_x ? 0 : 1; }
  static int side_of_slot(int slot) { return slot % 2; }
  // what a spectator calls a side: "near side" (0) and "far side" (1)
  static const char *side_name(int side) { return side == 0 ? "near side" : "far side"; }
  // +1 for side 0 (the net is toward +x), -1 for side 1
  static double toward_net(int side) { return side == 0 ? 1.0 : -1.0; }
  double half_length() const { return side_length(0) > side_length(1) ? side_length(0) : side_length(1); }
  double side_length(int side) const { return side == 0 ? net_x - x_lo : x_hi - net_x; }
  double z_mid() const { return 0.5 * (z_lo + z_hi); }
  bool inside(double x, double z) const { return x >= x_lo && x <= x_hi && z >= z_lo && z <= z_hi; }
  // where a player of this slot stands waiting: 1 m inside its baseline, 1 m
  // high; doubles partners at a quarter of the width from either sideline
  ball_vec3 ready(int slot, int players) const;
  // a point on `side`'s half at `depth` (0 at the net, 1 at the baseline)
  // and lateral offset dz from the middle, at floor height
  ball_vec3 spot(int side, double depth, double dz) const;
};

// The court of a model: the net must stand on an x plane; the court spans
// x in [net_x - L, net_x + L] with L = net_x - x_lo (a court that starts at
// x_lo, 0 for libball's tennis scene) and z over the net's width.
bool court_from_model(const ball_model &model, double x_lo, Court *court, std::string *err);

// A launch velocity from `from` with vertical speed v_up whose first floor
// contact (with this model's drag; no net, no rackets) is at (x, z) of
// target: the vertical motion does not depend on drag (eq 3), so the landing
// time is fixed by v_up and the horizontal speed follows in closed form.
ball_status lob_velocity(const ball_model &model, ball_vec3 from, ball_vec3 target, double v_up,
                         ball_vec3 *velocity);

}  // namespace ballsrv
