#include "spectator.h"

#include <cmath>

#include "ball/render.h"
#include "records.h"

namespace ballsrv {

namespace {

constexpr double kMinSampleGap = 1.0 / 120.0;  // sim s: racket samples closer than this to the newest are not passed on
constexpr size_t kPageRackets = 4;             // racket samples per slot a page is given at once
constexpr double kTrailSeconds = 1.0;          // sim s of trail and of markers the page draws

json plane_json(const ball_plane &p) {
  return {{"axis", p.axis}, {"position", p.position}, {"lo", p.lo}, {"hi", p.hi}, {"bottom", p.bottom}, {"top", p.top}};
}

json camera_json(const ball_camera &c) {
  return {{"eye", c.eye}, {"target", c.target}, {"up", c.up}, {"fov", c.fov}};
}

bool finite3(const ball_vec3 &v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// An event a page can show: JSON has no NaN or infinity (nlohmann writes
// null), and a forged event must not stop the page. (The watcher takes no
// segment that is not finite: trust.h.)
bool drawable(const EventOut &e) {
  return std::isfinite(e.time) && finite3(e.point) && finite3(e.velocity_in) && finite3(e.velocity_out) &&
         std::isfinite(e.value);
}

}  // namespace

std::string court_message(uint32_t match, const MatchInfoOut &info, const ball_model &court, double aspect) {
  ball_floor_layout f;
  ball_floor_layout_of(&court, &f);
  json floor = {{"level", f.level},
                {"ground", f.ground},
                {"has_court", f.has_court != 0},
                {"court", f.court},
                {"lines", json::array()},
                {"grid_step", f.grid_step},
                {"grid_width", f.grid_width}};
  for (int i = 0; i < f.n_lines; ++i) floor["lines"].push_back(f.lines[i]);
  json walls = json::array();
  for (int i = 0; i < court.n_walls; ++i) walls.push_back(plane_json(court.walls[i]));
  json rackets = json::array();
  for (int i = 0; i < court.n_rackets; ++i) rackets.push_back({{"radius", court.rackets[i].radius}});
  json cameras = json::object();
  for (int k = 0; k < BALL_CAMERA_PRESET_COUNT; ++k) {
    ball_camera c;
    auto preset = static_cast<ball_camera_preset>(k);
    if (ball_camera_from_preset(&court, preset, aspect, &c) == BALL_OK) cameras[ball_camera_preset_name(preset)] = camera_json(c);
  }
  json j = {{"type", "court"},   {"match", match},     {"scene", info.scene},     {"radius", court.radius},
            {"floor", floor},    {"walls", walls},     {"rackets", rackets},      {"cameras", cameras},
            {"aspect", aspect},  {"trail", kTrailSeconds}};
  j["net"] = court.has_net ? plane_json(court.net) : json(nullptr);
  return j.dump();
}

void Spectator::send(std::string text) {
  sent_.push_back(PageMessage{next_id_++, std::move(text)});
  while (sent_.size() > settings_.keep_messages) sent_.pop_front();
}

void Spectator::update(const Watcher &w, double real) {
  for (uint32_t id : w.match_ids()) {
    WatchedView v;
    if (w.view(id, &v)) mirror(id, v, real);
  }
}

void Spectator::mirror(uint32_t id, const WatchedView &v, double real) {
  const MatchInfoOut &info = *v.info;
  Mirror &m = matches_[id];
  // the court, again when the match changed scene or model
  if (m.court.empty() || m.scene != info.scene || m.model_hash != info.model_hash || m.court_from_wire != (v.model != nullptr)) {
    // the court the server judges: the match's model from the wire, else a scene of its name
    m.court = court_message(id, info, v.model ? *v.model : court_(info), settings_.aspect);
    m.court_from_wire = v.model != nullptr;
    m.scene = info.scene;
    m.model_hash = info.model_hash;
    send(m.court);
  }
  bool live = real - v.info_real < settings_.silence;
  if (m.info.empty() || m.server != info.server_id || m.revision != info.revision || m.live != live) {
    m.server = info.server_id;
    m.revision = info.revision;
    m.players = std::min(std::max(info.players, 0), kMaxPlayers);
    for (int i = 0; i < kMaxPlayers; ++i) {
      if (m.owners[i] != info.slots[i].owner || m.info.empty()) {  // a new holder, on its own clock
        m.rackets[i].clear();
        m.racket_t[i] = -INFINITY;
      }
      m.owners[i] = info.slots[i].owner;
    }
    m.info = json{{"type", "info"}, {"match", id}, {"live", live}, {"info", info}}.dump();
    send(m.info);
  }
  // segments: the watcher's, from the newest page_segments; anew when it dropped ours (a match started anew)
  const std::vector<KeptSegment> &segs = *v.segments;
  std::pair<uint32_t, size_t> watched{segs.empty() ? 0 : segs.back().segment.seq, segs.size()};
  if (watched != m.watched) mirror_segments(id, segs, &m);
  m.watched = watched;
  // events taken since the last update (those the watcher still holds)
  uint64_t fresh = v.events_taken - m.events_sent;
  size_t n = static_cast<size_t>(std::min<uint64_t>(fresh, v.events->size()));
  for (size_t i = v.events->size() - n; i < v.events->size(); ++i) {
    const EventOut &e = (*v.events)[i];
    if (!drawable(e)) {
      not_drawable_++;
      continue;
    }
    std::string text = json{{"type", "event"}, {"match", id}, {"event", e}, {"text", rally_line(e)}}.dump();
    m.events.push_back(text);
    send(text);
  }
  m.events_sent = v.events_taken;
  while (m.events.size() > settings_.page_events) m.events.pop_front();
  // the clock: the watcher's estimate while the server is heard; the ball
  // held still from when it went silent until a server serves the match again
  if (live != m.live && !live) m.frozen = v.clock->sim_now(std::min(real, v.info_real + 1.0));
  if (live != m.live || real - m.clock_real >= settings_.clock_every) {
    double sim = live ? v.clock->sim_now(real) : m.frozen;
    m.clock = json{{"type", "clock"},     {"match", id},
                   {"sim_time", sim},     {"real", real},
                   {"time_base", info.time_base}, {"running", live && v.clock->running()},
                   {"live", live}}.dump();
    m.clock_real = real;
    m.live = live;
    send(m.clock);
  }
}

// The watcher's newest page_segments segments the page has not got; all of
// them anew when the watcher dropped ours (a match started anew).
void Spectator::mirror_segments(uint32_t id, const std::vector<KeptSegment> &segs, Mirror *m) {
  auto held = [&segs](uint32_t seq) {
    for (const auto &k : segs)
      if (k.segment.seq == seq) return true;
    return false;
  };
  // anew when the view dropped ours: a match started anew (its seqs start over)
  if (!m->segments.empty() && !segs.empty() && !held(m->segments.rbegin()->first) &&
      static_cast<int32_t>(segs.back().segment.seq - m->segments.rbegin()->first) < 0) {
    m->segments.clear();
    send(json{{"type", "reset"}, {"match", id}}.dump());
  }
  size_t from = segs.size() > settings_.page_segments ? segs.size() - settings_.page_segments : 0;
  for (size_t i = from; i < segs.size(); ++i) {
    const SegmentOut &s = segs[i].segment;
    if (m->segments.count(s.seq)) continue;
    std::string text = json{{"type", "segment"}, {"match", id}, {"segment", s}}.dump();
    m->segments[s.seq] = text;
    send(text);
  }
  while (m->segments.size() > settings_.page_segments) m->segments.erase(m->segments.begin());
}

bool Spectator::on_racket(const RacketSampleIn &s) {
  auto it = matches_.find(s.match_id);
  bool fits = it != matches_.end() && s.player >= 0 && s.player < it->second.players && std::isfinite(s.capture_time) &&
              finite3(s.center) && finite3(s.normal) && s.capture_time >= it->second.racket_t[s.player] + kMinSampleGap;
  if (!fits) {
    racket_dropped_++;
    return false;
  }
  std::string text = json{{"type", "racket"}, {"match", s.match_id}, {"player", s.player}, {"seq", s.seq},
                          {"t", s.capture_time}, {"center", s.center}, {"normal", s.normal}}.dump();
  std::deque<std::string> &kept = it->second.rackets[s.player];
  it->second.racket_t[s.player] = s.capture_time;
  kept.push_back(text);
  while (kept.size() > kPageRackets) kept.pop_front();
  send(text);
  return true;
}

std::vector<std::string> Spectator::snapshot() const {
  std::vector<std::string> out;
  out.push_back(json{{"type", "hello"}, {"newest", newest()}}.dump());
  for (const auto &kv : matches_) {
    const Mirror &m = kv.second;
    out.push_back(m.court);
    out.push_back(m.info);
    for (const auto &s : m.segments) out.push_back(s.second);
    for (const auto &e : m.events) out.push_back(e);
    for (const auto &slot : m.rackets)
      for (const auto &r : slot) out.push_back(r);
    if (!m.clock.empty()) out.push_back(m.clock);
  }
  return out;
}

bool Spectator::since(uint64_t after, size_t max, std::vector<PageMessage> *out) const {
  out->clear();
  if (sent_.empty() || after >= sent_.back().id) return true;
  if (after + 1 < sent_.front().id) return false;
  for (size_t i = after + 1 - sent_.front().id; i < sent_.size() && out->size() < max; ++i) out->push_back(sent_[i]);
  return true;
}

}  // namespace ballsrv
