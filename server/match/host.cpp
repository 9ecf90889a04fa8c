#include "host.h"

#include <algorithm>

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

const ball_scene *Host::scene(const std::string &name, std::string *err) {
  auto it = scenes_.find(name);
  if (it != scenes_.end()) return &it->second;
  ball_scene sc;
  if (!source_ || name.empty() || name.size() >= static_cast<size_t>(kNameLen) || !source_(name, &sc, err)) {
    if (err->empty()) *err = "no scene \"" + name + "\" on this server";
    return nullptr;
  }
  return &(scenes_[name] = sc);
}

Match *Host::follow(const MatchInfoOut &info, const ball_model *model, std::string *err) {
  if (find(info.match_id)) {
    *err = "match " + std::to_string(info.match_id) + " is here already";
    return nullptr;
  }
  // the owner's model from the wire needs no scene file: the match is built
  // over it as over a scene's (build_match_model gives that model back)
  ball_scene from_wire;
  const ball_scene *sc = &from_wire;
  if (model) {
    ball_scene_default(&from_wire);
    from_wire.model = *model;
  } else {
    sc = scene(info.scene, err);
    if (!sc) return nullptr;
  }
  MatchConfig c = template_;
  c.id = info.match_id;
  c.scene_name = info.scene;
  c.players = info.players;
  c.level = static_cast<ball_level>(info.level);
  c.frame_rate = info.frame_time > 0.0 ? 1.0 / info.frame_time : 0.0;
#define BALL_GET_SETTING(f) c.f = info.settings.f;
  BALL_MATCH_WIRE_SETTINGS(BALL_GET_SETTING)
#undef BALL_GET_SETTING
  c.extrapolation_time = info.model.extrapolation_time;
  c.stale_time = info.model.stale_time;
  c.court_x_lo = info.court_x[0];
  if (info.level < BALL_LEVEL_CUSTOM || info.level > BALL_LEVEL_ADVANCED) {
    *err = "level " + std::to_string(info.level) + " is not a game level";
    return nullptr;
  }
  // (a model from the wire is not a scene of this server's: it joins no catalogue)
  if (!(model ? insert_match(c, *sc, err) : add_match(c, *sc, err))) return nullptr;
  Match *m = find(c.id);
  if (!m->follow(info, err)) {
    remove(c.id);
    return nullptr;
  }
  return m;
}

ParticipantId Host::creator(uint32_t id) const {
  auto it = creators_.find(id);
  return it == creators_.end() ? ParticipantId{} : it->second.from;
}

void Host::remove(uint32_t id) {
  if (Match *m = find(id)) {
    m->end_streams();
    removed_lost_ += m->take_lost();
  }
  by_id_.erase(id);
  creators_.erase(id);
  matches_.erase(std::remove_if(matches_.begin(), matches_.end(),
                                [id](const std::unique_ptr<Match> &m) { return m->id() == id; }),
                 matches_.end());
}

bool Host::add_match(const MatchConfig &config, const ball_scene &scene, std::string *err) {
  if (!insert_match(config, scene, err)) return false;
  scenes_.emplace(config.scene_name, scene);  // a standby may follow it by that name
  return true;
}

bool Host::insert_match(const MatchConfig &config, const ball_scene &scene, std::string *err) {
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
  apply_slot_rule(*m);
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

SampleResult Host::on_sample(const RacketSampleIn &sample, double now, uint64_t *lost) {
  Match *m = find(sample.match_id);
  if (!m) return SampleResult::unknown_match;
  return m->on_sample(sample, now, lost);
}

void Host::on_rejected(const RacketSampleIn &sample, uint64_t *lost) {
  if (Match *m = find(sample.match_id)) m->on_rejected(sample, lost);
}

uint64_t Host::take_lost() {
  uint64_t n = removed_lost_;
  removed_lost_ = 0;
  for (auto &m : matches_) n += m->take_lost();
  return n;
}

void Host::end_streams() {
  for (auto &m : matches_) m->end_streams();
}

void Host::set_slot_rule(std::function<bool(uint32_t, int, const ParticipantId &)> rule) {
  slot_rule_ = std::move(rule);
  for (auto &m : matches_) apply_slot_rule(*m);
}

void Host::apply_slot_rule(Match &m) const {
  if (!slot_rule_) return m.set_slot_rule(nullptr);
  m.set_slot_rule([rule = slot_rule_, id = m.id()](int k, const ParticipantId &who) { return rule(id, k, who); });
}

Reason Host::on_control(const ControlIn &c, double now, MatchOutput *out, Match **match) {
  *match = find(c.match_id);
  if (*match && (*match)->following()) {  // its owner's to answer
    *match = nullptr;
    return Reason::none;
  }
  if (c.kind != ControlKind::create) {
    if (!*match) return Reason::refused_bad_value;
    return (*match)->on_control(c, now, out);
  }
  if (*match) return (*match)->on_control(c, now, out);  // refused there: it exists
  auto scene = scenes_.find(c.scene);
  if (!allow_create_ || matches_.size() >= max_matches_) return Reason::refused_no_room;
  if (!create_ids().has(c.match_id)) return Reason::refused_bad_value;
  if (share_taken(c)) return Reason::refused_no_room;
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
  creators_[c.match_id] = {c.from, c.host};
  *match = find(c.match_id);
  out->info_changed = true;
  return Reason::none;
}

bool Host::share_taken(const ControlIn &c) const {
  // the bytes of a GUID prefix that name its origin: a process's first 8; an
  // identity's first 6 (PKI-DH's flag bit and 47 bits of its subject: certificate.h)
  const size_t n = origin_ == Origin::process ? 8 : 6;
  auto same_origin = [&](const ParticipantId &p) { return std::equal(p.begin(), p.begin() + n, c.from.begin()); };
  const bool known_host = c.host != HostAddress{};
  uint32_t by_origin = 0, by_host = 0;
  for (const auto &kv : creators_) {
    by_origin += same_origin(kv.second.from);
    by_host += known_host && kv.second.host == c.host;
  }
  return by_origin >= max_creates_ || by_host >= max_creates_per_host_;
}

void Host::on_participant_lost(const ParticipantId &who) {
  for (auto &m : matches_) m->on_participant_lost(who);
}

}  // namespace ballsrv
