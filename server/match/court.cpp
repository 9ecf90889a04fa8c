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

// The default racket radius, from libball's field table (no number repeated here).
static double default_racket_radius() {
  int n = 0;
  const ball_field *fields = ball_racket_fields(&n);
  for (int i = 0; i < n; ++i)
    if (std::strcmp(fields[i].name, "radius") == 0) return fields[i].def[0];
  return 0.15;
}

bool build_match_model(const ball_scene &scene, const Court &court, const ModelSetup &setup,
                       ball_model *out, std::string *err) {
  ball_model m = scene.model;
  if (setup.players < 1 || setup.players > kMaxPlayers) {
    *err = "players must be in [1, " + std::to_string(kMaxPlayers) + "]";
    return false;
  }
  if (setup.level != BALL_LEVEL_CUSTOM) {
    ball_status st = ball_model_set_level(&m, setup.level);
    if (st != BALL_OK) {
      *err = std::string("level: ") + ball_strerror(st);
      return false;
    }
  }
  for (int i = m.n_rackets; i < setup.players; ++i) {
    ball_racket_def &r = m.rackets[i];
    r.radius = default_racket_radius();
    int partner = i ^ 1;  // the slot facing this one across the net
    r.partner = partner < setup.players ? partner : -1;
    r.target = court.ready(partner, setup.players);
    r.target.y = 0.0;
  }
  if (m.n_rackets < setup.players) m.n_rackets = setup.players;
  // a racket added above may name a partner the scene's own rackets lack
  for (int i = 0; i < m.n_rackets; ++i)
    if (m.rackets[i].partner >= m.n_rackets) m.rackets[i].partner = -1;
  // the autonomous ball (eq 8, 9) flies to the partner's racket, but lands
  // in the partner's half of the court: the goal, where the ball comes back
  // to the stroke's height, within half the radius of the circle inscribed
  // in that half (it lands a couple of metres beyond the goal); a partner
  // who parks its racket off the court must not win the point
  for (int i = 0; i < setup.players; ++i) {
    ball_racket_def &r = m.rackets[i];
    if (r.partner < 0) continue;
    int side = Court::side_of_slot(r.partner);
    r.target = court.spot(side, 0.5, 0.0);
    r.goal_reach = 0.5 * std::min(0.5 * court.side_length(side), 0.5 * (court.z_hi - court.z_lo));
  }
  m.effects |= BALL_EFFECT_RACKETS;
  if (setup.extrapolation_time >= 0.0) m.extrapolation_time = setup.extrapolation_time;
  if (setup.stale_time >= 0.0) m.stale_time = setup.stale_time;
  const char *field = nullptr;
  ball_status st = ball_model_check(&m, &field);
  if (st != BALL_OK) {
    *err = std::string(field ? field : "model") + ": " + ball_strerror(st);
    return false;
  }
  *out = m;
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

bool match_model_of(const ball_scene &scene, const MatchInfoOut &info, ball_model *model, Court *court,
                    std::string *err) {
  ModelSetup setup;
  setup.players = info.players;
  setup.level = static_cast<ball_level>(info.level);
  setup.extrapolation_time = info.model.extrapolation_time;
  setup.stale_time = info.model.stale_time;
  return court_from_model(scene.model, info.court_x[0], court, err) && build_match_model(scene, *court, setup, model, err);
}

}  // namespace ballsrv
