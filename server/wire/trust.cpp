#include "trust.h"

#include "ball/vec3.h"
#include "fields.h"
#include "match_config.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace ballsrv {

bool ServerChoice::accepts(uint32_t server_id) const {
  return ids.empty() || std::find(ids.begin(), ids.end(), server_id) != ids.end();
}

std::vector<std::pair<uint32_t, std::string>> ServerChoice::bound() const {
  std::vector<std::pair<uint32_t, std::string>> b;
  for (size_t i = 0; i < ids.size() && i < identities.size(); ++i)
    if (!identities[i].empty()) b.emplace_back(ids[i], identities[i]);
  return b;
}

namespace {
// an identity's name: a file name in the security folder, never a path
bool identity_name(const std::string &n) {
  return !n.empty() && n[0] != '.' &&
         n.find_first_not_of("ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789-_.") == std::string::npos;
}
}  // namespace

bool ServerChoice::parse(const std::string &text, ServerChoice *out, std::string *err) {
  ServerChoice c;
  size_t i = 0;
  while (i < text.size()) {
    size_t j = text.find(',', i);
    std::string item = text.substr(i, j == std::string::npos ? std::string::npos : j - i);
    size_t eq = item.find('=');
    std::string id = item.substr(0, eq), name = eq == std::string::npos ? "" : item.substr(eq + 1);
    char *end = nullptr;
    unsigned long long v = std::strtoull(id.c_str(), &end, 10);
    if (id.empty() || id.find_first_not_of("0123456789") != std::string::npos || v > UINT32_MAX ||
        (eq != std::string::npos && !identity_name(name))) {
      *err = "servers \"" + text + "\": not a comma-separated list of server ids, each ID or ID=IDENTITY";
      return false;
    }
    c.ids.push_back(static_cast<uint32_t>(v));
    c.identities.push_back(name);
    if (j == std::string::npos) break;
    i = j + 1;
  }
  *out = c;
  return true;
}

namespace {
template <class E>
bool enum_in_range(E v) {
  return static_cast<unsigned>(v) < static_cast<unsigned>(kEnumCount<E>);  // (enum class: any int is a value)
}
bool side(int s) { return s == 0 || s == 1; }
bool sim_time(double t) { return t >= 0.0 && t <= kMaxSimTime; }
}  // namespace

bool usable_play(const PlayState &p) {
  return p.score[0] >= 0 && p.score[0] <= kMaxScore && p.score[1] >= 0 && p.score[1] <= kMaxScore &&
         side(p.serving_side) && side(p.striker) && (p.bounces == 0 || p.bounces == 1) && side(p.bounce_side) &&
         std::isfinite(p.rally_start) && std::isfinite(p.serve_at);
}

bool play_fits(const PlayState &p, double at) {
  const double serve_delay = find_field(match_fields(), "serve_delay")->bounds.hi;
  return usable_play(p) && p.rally_start <= at + 1e-6 && p.serve_at <= at + serve_delay + 1e-6;
}

bool usable_segment(const SegmentOut &s) {
  return finite_segment(s.segment) && enum_in_range(s.cause) && sim_time(s.segment.t0) &&
         play_fits(s.play, s.segment.t0);
}

bool usable_other_info(const MatchInfoOut &i) {
  return usable_info(i) && i.segment.t0 <= i.sim_time + 1e-6 && play_fits(i.play, i.sim_time);
}

bool usable_info(const MatchInfoOut &i) {
  auto finite = [](double v) { return std::isfinite(v); };
  std::string why;  // (a setting outside its range: refused like any other)
  return enum_in_range(i.state) && enum_in_range(i.pause_reason) && enum_in_range(i.segment_cause) &&
         sim_time(i.sim_time) && sim_time(i.segment.t0) && usable_play(i.play) && i.players >= 1 && i.players <= kMaxPlayers && i.level >= BALL_LEVEL_CUSTOM &&
         i.level <= BALL_LEVEL_ADVANCED && check_wire_settings(i.settings, &why) && i.frame_time > 0.0 &&
         i.frame_time <= 10.0 && finite(i.sim_time) && finite(i.server_time) && finite(i.model.gravity) &&
         finite(i.model.mass) && i.model.mass > 0.0 && finite(i.model.air_friction) && i.model.air_friction >= 0.0 &&
         finite(i.model.spin_damping) && i.model.spin_damping > 0.0 && finite(i.model.radius) &&
         i.model.radius >= 0.0 && finite(i.model.floor_level) && finite(i.model.extrapolation_time) &&
         finite(i.model.stale_time) && ball_v3_finite(i.segment.p0) && ball_v3_finite(i.segment.v0) &&
         ball_v3_finite(i.segment.s0) && finite(i.segment.t0);
}

bool finite_segment(const ball_segment &s) {
  return std::isfinite(s.t0) && ball_v3_finite(s.p0) && ball_v3_finite(s.v0) && ball_v3_finite(s.s0);
}

bool owner_before(uint32_t term_a, uint32_t server_a, uint32_t term_b, uint32_t server_b) {
  return term_a != term_b ? term_a < term_b : server_a > server_b;  // plain: terms start at 1 and only grow
}

bool segment_is_news(uint32_t seq, uint32_t newest, uint32_t info_seq) {
  if (newest == 0) return true;
  if (seq == info_seq && seq != newest) return true;
  int32_t ahead = static_cast<int32_t>(seq - newest);
  return ahead > 0 && static_cast<uint32_t>(ahead) <= kMaxSeqAhead;
}

bool segment_fits(uint32_t seq, uint32_t newest, uint32_t info_seq) {
  if (newest == 0 || seq == info_seq) return true;
  // plain differences (a stream of 2^32 segments does not happen: one that
  // wraps is forged)
  int64_t d = static_cast<int64_t>(seq) - static_cast<int64_t>(newest);
  return d >= -static_cast<int64_t>(kMaxSeqAhead) && d <= static_cast<int64_t>(kMaxSeqAhead);
}

bool usable_model(const MatchModelOut &m, uint64_t info_hash) {
  return m.model_hash == info_hash && ball_model_check(&m.model, nullptr) == BALL_OK &&
         ball_model_hash(&m.model) == m.model_hash;
}

}  // namespace ballsrv
