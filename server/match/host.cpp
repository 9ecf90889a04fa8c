#include "host.h"

namespace ballsrv {

Host::Host(size_t max_matches, bool allow_create, MatchConfig create_template)
    : max_matches_(max_matches), allow_create_(allow_create), template_(std::move(create_template)) {}

bool Host::add_scene(const std::string &name, const ball_scene &scene, std::string *err) {
  if (name.empty() || name.size() >= static_cast<size_t>(kNameLen)) {
    *err = "scene name \"" + name + "\": must be 1 to 31 bytes";
    return false;
  }
  scenes_[name] = scene;
  return true;
}

bool Host::add_match(const MatchConfig &config, const ball_scene &scene, std::string *err) {
  if (by_id_.count(config.id)) {
    *err = "match id " + std::to_string(config.id) + " is used twice";
    return false;
  }
  if (matches_.size() >= max_matches_) {
    *err = "more matches than max_matches (" + std::to_string(max_matches_) + ")";
    return false;
  }
  auto m = std::make_unique<Match>();
  if (!m->init(config, scene, err)) return false;
  by_id_[config.id] = m.get();
  matches_.push_back(std::move(m));
  return true;
}

Match *Host::find(uint32_t id) {
  auto it = by_id_.find(id);
  return it == by_id_.end() ? nullptr : it->second;
}

int Host::max_players() const {
  int n = allow_create_ ? kMaxPlayers : 0;
  for (const auto &m : matches_)
    if (m->config().players > n) n = m->config().players;
  return n;
}

SampleResult Host::on_sample(const RacketSampleIn &sample, double now) {
  Match *m = find(sample.match_id);
  if (!m) return SampleResult::unknown_match;
  return m->on_sample(sample, now);
}

Reason Host::on_control(const ControlIn &c, double now, MatchOutput *out, Match **match) {
  *match = find(c.match_id);
  if (c.kind != ControlKind::create) {
    if (!*match) return Reason::refused_bad_value;
    return (*match)->on_control(c, now, out);
  }
  if (*match) return (*match)->on_control(c, now, out);  // refused there: it exists
  auto scene = scenes_.find(c.scene);
  if (!allow_create_ || matches_.size() >= max_matches_) return Reason::refused_no_room;
  const Bounds &players = find_field(match_fields(), "players")->bounds;
  if (scene == scenes_.end() || c.players < players.ilo || c.players > players.ihi || c.level < 0 ||
      c.level > BALL_LEVEL_ADVANCED)
    return Reason::refused_bad_value;
  MatchConfig config = template_;
  config.id = c.match_id;
  config.scene_name = c.scene;
  config.players = c.players;
  config.level = static_cast<ball_level>(c.level);
  std::string err;
  if (!add_match(config, scene->second, &err)) return Reason::refused_bad_value;
  *match = find(c.match_id);
  out->info_changed = true;
  return Reason::none;
}

void Host::on_participant_lost(const ParticipantId &who) {
  for (auto &m : matches_) m->on_participant_lost(who);
}

}  // namespace ballsrv
