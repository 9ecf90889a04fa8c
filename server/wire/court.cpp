#include "court.h"

#include <algorithm>

#include <cmath>
#include <cstring>

#include "ball/vec3.h"
#include "types.h"

namespace ballsrv {

ball_vec3 Court::ready(int slot, int players) const {
  int side = side_of_slot(slot);
  double x = side == 0 ? x_lo + 1.0 : x_hi - 1.0;
  double z = z_mid();
  if (players > 2) z = slot / 2 == 0 ? z_lo + 0.25 * (z_hi - z_lo) : z_lo + 0.75 * (z_hi - z_lo);
  return ball_v3(x, floor + 1.0, z);
}

ball_vec3 Court::spot(int side, double depth, double dz) const {
  double x = net_x - toward_net(side) * depth * side_length(side);
  return ball_v3(x, floor, z_mid() + dz);
}

bool court_from_model(const ball_model &model, double x_lo, Court *court, std::string *err) {
  if (!model.has_net || model.net.axis != 0) {
    *err = "the match rules need a net on an x plane (net.axis: x)";
    return false;
  }
  double length = model.net.position - x_lo;
  if (!(length > 0.0)) {
    *err = "the court must start before the net (x_lo < net.position)";
    return false;
  }
  court->net_x = model.net.position;
  court->x_lo = x_lo;
  court->x_hi = model.net.position + length;
  court->z_lo = model.net.lo;
  court->z_hi = model.net.hi;
  court->floor = model.floor_level;
  return true;
}

ball_status lob_velocity(const ball_model &model, ball_vec3 from, ball_vec3 target, double v_up,
                         ball_vec3 *velocity) {
  if (!ball_v3_finite(from) || !ball_v3_finite(target) || !std::isfinite(v_up)) return BALL_ENONFINITE;
  ball_vec3 d = ball_v3(target.x - from.x, 0.0, target.z - from.z);
  double dist = ball_v3_norm(d);
  if (!(dist > 1e-9)) return BALL_ERANGE;
  d = ball_v3_scale(d, 1.0 / dist);
  // unit horizontal speed: how far does the ball get before it lands?
  ball_segment seg{};
  seg.t0 = 0.0;
  seg.p0 = from;
  seg.v0 = ball_v3(d.x, v_up, d.z);
  double t_land = 0.0;
  ball_vec3 land;
  ball_status st = ball_next_floor_contact(&model, &seg, 0.0, &t_land, &land);
  if (st != BALL_OK) return st;
  double reach = ball_v3_dist(ball_v3(land.x, 0.0, land.z), ball_v3(from.x, 0.0, from.z));
  if (!(reach > 1e-12)) return BALL_ERANGE;
  double speed = dist / reach;
  *velocity = ball_v3(d.x * speed, v_up, d.z * speed);
  return BALL_OK;
}

}  // namespace ballsrv
