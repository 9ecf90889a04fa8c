#include "spectator.h"

#include <cmath>
#include <cstdio>

#include "ball/render.h"
#include "court.h"
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

json rgb_json(const ball_rgb &c) { return json::array({c.r, c.g, c.b}); }

// libball's palette (ball_render_palette), by the names of ball_palette
json palette_json() {
  ball_palette p;
  ball_render_palette(&p);
  json rackets = json::array(), markers = json::object();
  for (const ball_rgb &c : p.rackets) rackets.push_back(rgb_json(c));
  for (int k = 0; k < BALL_EVENT_KIND_COUNT; ++k) markers[ball_event_kind_name(static_cast<ball_event_kind>(k))] = rgb_json(p.markers[k]);
  return {{"sky", rgb_json(p.sky)},         {"ground", rgb_json(p.ground)},       {"court", rgb_json(p.court)},
          {"line", rgb_json(p.line)},       {"grid", rgb_json(p.grid)},           {"net", rgb_json(p.net)},
          {"wall", rgb_json(p.wall)},       {"wall_edge", rgb_json(p.wall_edge)}, {"ball", rgb_json(p.ball)},
          {"trail", rgb_json(p.trail)},     {"rackets", rackets},                 {"markers", markers},
          {"net_alpha", p.net_alpha},       {"tape_alpha", p.tape_alpha},         {"wall_alpha", p.wall_alpha},
          {"shadow_alpha", p.shadow_alpha}};
}

// A struct's fields by libball's field table (ball_model_fields and the
// plane and racket tables), by name: what the page copies into the
// module's ball_model the same way (ballwasm.js). JSON has no infinity: an
// infinite real (sound_threshold may be +Inf) is written "Infinity", as
// JavaScript's Number() reads it.
json fields_json(const ball_field *fields, int count, const unsigned char *base, int n_walls, int n_rackets);

json real_json(double v) { return std::isfinite(v) ? json(v) : json(v > 0 ? "Infinity" : v < 0 ? "-Infinity" : "NaN"); }

json field_json(const ball_field &f, const unsigned char *at, int n_walls, int n_rackets) {
  int plane_count = 0, racket_count = 0;
  const ball_field *plane = ball_plane_fields(&plane_count), *racket = ball_racket_fields(&racket_count);
  switch (f.type) {
    case BALL_FIELD_REAL: return real_json(*reinterpret_cast<const double *>(at));
    case BALL_FIELD_INT:
    case BALL_FIELD_ENUM:
    case BALL_FIELD_AXIS: return *reinterpret_cast<const int *>(at);
    case BALL_FIELD_BOOL: return *reinterpret_cast<const int *>(at) != 0;
    case BALL_FIELD_EFFECTS: return *reinterpret_cast<const unsigned *>(at);
    case BALL_FIELD_VEC3: {
      const ball_vec3 &v = *reinterpret_cast<const ball_vec3 *>(at);
      return json::array({real_json(v.x), real_json(v.y), real_json(v.z)});
    }
    case BALL_FIELD_PLANE: return fields_json(plane, plane_count, at, 0, 0);
    case BALL_FIELD_PLANES: {
      json a = json::array();
      for (int i = 0; i < n_walls; ++i) a.push_back(fields_json(plane, plane_count, at + i * sizeof(ball_plane), 0, 0));
      return a;
    }
    case BALL_FIELD_RACKETS: {
      json a = json::array();
      for (int i = 0; i < n_rackets; ++i)
        a.push_back(fields_json(racket, racket_count, at + i * sizeof(ball_racket_def), 0, 0));
      return a;
    }
    case BALL_FIELD_TYPE_COUNT: break;
  }
  return nullptr;
}

json fields_json(const ball_field *fields, int count, const unsigned char *base, int n_walls, int n_rackets) {
  json j = json::object();
  for (int i = 0; i < count; ++i) j[fields[i].name] = field_json(fields[i], base + fields[i].offset, n_walls, n_rackets);
  return j;
}

json model_json(const ball_model &m) {
  int count = 0;
  const ball_field *fields = ball_model_fields(&count);
  return fields_json(fields, count, reinterpret_cast<const unsigned char *>(&m), m.n_walls, m.n_rackets);
}

// 64 bits as 16 hex digits: a JSON number would lose bits in JavaScript's doubles
std::string hex64(uint64_t v) {
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(v));
  return text;
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
  // the court the match's rules judge (MatchInfo's court_x, court_z), else the one its net implies
  const double judged[4] = {info.court_x[0], info.court_z[0], info.court_x[1], info.court_z[1]};
  ball_floor_layout f;
  bool own = ball_floor_layout_court(&court, judged, &f) == BALL_OK;
  if (!own) ball_floor_layout_of(&court, &f);
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
    ball_status st = own ? ball_camera_from_preset_court(&court, judged, preset, aspect, &c)
                         : ball_camera_from_preset(&court, preset, aspect, &c);
    if (st == BALL_OK) cameras[ball_camera_preset_name(preset)] = camera_json(c);
  }
  json j = {{"type", "court"},   {"match", match},     {"scene", info.scene},     {"radius", court.radius},
            {"floor", floor},    {"walls", walls},     {"rackets", rackets},      {"cameras", cameras},
            {"aspect", aspect},  {"trail", kTrailSeconds}, {"palette", palette_json()},
            {"model", model_json(court)}, {"model_hash", hex64(ball_model_hash(&court))}};
  j["net"] = court.has_net ? plane_json(court.net) : json(nullptr);
  j["judged"] = own ? json(judged) : json(nullptr);
  return j.dump();
}

std::string info_message(uint32_t match, const MatchInfoOut &info, bool live, double real) {
  json sides = json::array();
  for (int side = 0; side < 2; ++side) {
    json slots = json::array();
    for (int i = 0; i < std::min(std::max(info.players, 0), kMaxPlayers); ++i)
      if (Court::side_of_slot(i) == side) slots.push_back(i);
    sides.push_back({{"name", Court::side_name(side)}, {"slots", slots}});
  }
  return json{{"type", "info"},
              {"match", match},
              {"live", live},
              {"real", real},
              {"model_hash", hex64(info.model_hash)},
              {"level_name", ball_level_name(static_cast<ball_level>(info.level))},
              {"sides", sides},
              {"info", info}}
      .dump();
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
  Mirror &m = matches_[id];
  mirror_court(id, v, &m);
  bool live = real - v.info_real < settings_.silence;
  mirror_info(id, v, live, &m);
  // segments: the watcher's, from the newest page_segments; anew when it dropped ours (a match started anew)
  const std::deque<SegmentOut> &segs = *v.segments;
  std::pair<uint32_t, size_t> watched{segs.empty() ? 0 : segs.back().seq, segs.size()};
  if (watched != m.watched) mirror_segments(id, segs, &m);
  m.watched = watched;
  mirror_events(id, v, &m);
  mirror_clock(id, v, live, real, &m);
}

// The court, again when the match changed scene or model: the court the
// server judges, from the match's model on the wire, else a scene of its name.
void Spectator::mirror_court(uint32_t id, const WatchedView &v, Mirror *m) {
  const MatchInfoOut &info = *v.info;
  std::array<double, 4> judged{info.court_x[0], info.court_z[0], info.court_x[1], info.court_z[1]};
  if (!m->court.empty() && m->scene == info.scene && m->model_hash == info.model_hash &&
      m->court_from_wire == (v.model != nullptr) && m->judged == judged)
    return;
  m->court = court_message(id, info, v.model ? *v.model : court_(info), settings_.aspect);
  m->court_from_wire = v.model != nullptr;
  m->scene = info.scene;
  m->model_hash = info.model_hash;
  m->judged = judged;
  send(m->court);
}

// The match's info, when its server, revision or liveness changed; a new
// holder's racket starts anew, on its own clock.
void Spectator::mirror_info(uint32_t id, const WatchedView &v, bool live, Mirror *m) {
  const MatchInfoOut &info = *v.info;
  if (!m->info.empty() && m->server == info.server_id && m->revision == info.revision && m->live == live) return;
  m->server = info.server_id;
  m->revision = info.revision;
  m->players = std::min(std::max(info.players, 0), kMaxPlayers);
  for (int i = 0; i < kMaxPlayers; ++i) {
    if (m->owners[i] != info.slots[i].owner || m->info.empty()) {
      m->rackets[i].clear();
      m->racket_t[i] = -INFINITY;
    }
    m->owners[i] = info.slots[i].owner;
  }
  m->info = info_message(id, info, live, v.info_real);
  send(m->info);
}

// The events taken since the last update (those the watcher still holds).
void Spectator::mirror_events(uint32_t id, const WatchedView &v, Mirror *m) {
  uint64_t fresh = v.events_taken - m->events_sent;
  size_t n = static_cast<size_t>(std::min<uint64_t>(fresh, v.events->size()));
  for (size_t i = v.events->size() - n; i < v.events->size(); ++i) {
    const EventOut &e = (*v.events)[i];
    if (!drawable(e)) {
      not_drawable_++;
      continue;
    }
    std::string text = json{{"type", "event"}, {"match", id}, {"event", e}, {"text", rally_line(e)}}.dump();
    m->events.push_back(text);
    send(text);
  }
  m->events_sent = v.events_taken;
  while (m->events.size() > settings_.page_events) m->events.pop_front();
}

// The clock: the watcher's estimate while the server is heard; the ball
// held still from when it went silent (at the latest, its newest MatchInfo
// and the period the owner writes one in) until a server serves the match again.
void Spectator::mirror_clock(uint32_t id, const WatchedView &v, bool live, double real, Mirror *m) {
  if (live != m->live && !live) m->frozen = v.sim_at(std::min(real, v.info_real + kInfoEvery));
  if (live == m->live && real - m->clock_real < settings_.clock_every) return;
  double sim = live ? v.sim_at(real) : m->frozen;
  m->clock = json{{"type", "clock"},     {"match", id},
                  {"sim_time", sim},     {"real", real},
                  {"time_base", v.info->settings.time_base}, {"running", live && v.running},
                  {"live", live}}.dump();
  m->clock_real = real;
  m->live = live;
  send(m->clock);
}

// The watcher's newest page_segments segments the page has not got; all of
// them anew when the watcher dropped ours (a match started anew).
void Spectator::mirror_segments(uint32_t id, const std::deque<SegmentOut> &segs, Mirror *m) {
  auto held = [&segs](uint32_t seq) {
    for (const auto &k : segs)
      if (k.seq == seq) return true;
    return false;
  };
  // anew when the view dropped ours: a match started anew (its seqs start over)
  if (!m->segments.empty() && !segs.empty() && !held(m->segments.rbegin()->first) &&
      static_cast<int32_t>(segs.back().seq - m->segments.rbegin()->first) < 0) {
    m->segments.clear();
    send(json{{"type", "reset"}, {"match", id}}.dump());
  }
  size_t from = segs.size() > settings_.page_segments ? segs.size() - settings_.page_segments : 0;
  for (size_t i = from; i < segs.size(); ++i) {
    const SegmentOut &s = segs[i];
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
