#include "match_model.h"

#include <algorithm>
#include <cstring>

namespace ballsrv {

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
