#include "watcher.h"

#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <algorithm>

#include "ball/vec3.h"

namespace ballsrv {

namespace {

constexpr size_t kKeepLeads = 256;     // contacts written ahead a match keeps until they happen
constexpr size_t kMaxWatched = 16384;  // matches known before the silent ones are let go
constexpr size_t kMaxPending = 4096;   // states waiting for a segment that never comes: counted and forgotten
constexpr double kLeadSettle = 1.0;    // sim s after a contact by which a hit that superseded it has come
constexpr double kTrailSeconds = 1.0;  // sim s of trail and of event markers
constexpr size_t kTrailPoints = 2048;
constexpr size_t kMarkers = 64;
constexpr size_t kKeepEvents = 64;     // per match, for a view
constexpr size_t kKeepSegments = 256;  // trusted segments a match keeps (the desync check, the page)
constexpr size_t kKeepGiven = 1024;    // events given a match remembers (a correction voids recent ones)

std::string point_text(ball_vec3 p) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "(%.2f, %.2f, %.2f)", p.x, p.y, p.z);
  return buf;
}

// a collision as libball's event, for the snapshot's markers
bool event_marker(const EventOut &e, ball_event *out) {
  ball_event ev{};
  switch (e.kind) {
    case EventKind::floor: ev.kind = BALL_EVENT_FLOOR; break;
    case EventKind::net: ev.kind = BALL_EVENT_NET; break;
    case EventKind::wall: ev.kind = BALL_EVENT_WALL; break;
    case EventKind::racket: ev.kind = BALL_EVENT_RACKET; break;
    default: return false;
  }
  ev.index = e.index;
  ev.time = e.time;
  ev.point = e.point;
  ev.velocity_in = e.velocity_in;
  ev.velocity_out = e.velocity_out;
  *out = ev;
  return true;
}

}  // namespace

std::string rally_line(const EventOut &e) {
  char buf[256];
  const char *side = e.side == 0 ? "near" : "far";
  switch (e.kind) {
    case EventKind::serve:
      std::snprintf(buf, sizeof buf, "serve by player %d (%s side), score %d-%d", e.index, side, e.score[0],
                    e.score[1]);
      break;
    case EventKind::floor:
      std::snprintf(buf, sizeof buf, "  bounce on the %s side at %s%s%s", side, point_text(e.point).c_str(),
                    e.sound ? ", sound" : "", e.in_play ? "" : " (dead ball)");
      break;
    case EventKind::net: std::snprintf(buf, sizeof buf, "  net at %s", point_text(e.point).c_str()); break;
    case EventKind::wall: std::snprintf(buf, sizeof buf, "  wall %d at %s", e.index, point_text(e.point).c_str()); break;
    case EventKind::racket:
      std::snprintf(buf, sizeof buf, "  hit by player %d at %s, %.1f m/s%s", e.index, point_text(e.point).c_str(),
                    ball_v3_norm(e.velocity_out), e.in_play ? "" : " (dead ball)");
      break;
    case EventKind::point:
      if (e.side < 0) std::snprintf(buf, sizeof buf, "let (%s): replayed", name_of(e.reason));
      else
        std::snprintf(buf, sizeof buf, "point to the %s side (%s), score %d-%d", side, name_of(e.reason), e.score[0],
                      e.score[1]);
      break;
    case EventKind::pause: std::snprintf(buf, sizeof buf, "pause: player %d %s", e.index, name_of(e.reason)); break;
    case EventKind::resume: std::snprintf(buf, sizeof buf, "resume"); break;
    case EventKind::join: std::snprintf(buf, sizeof buf, "player %d joined", e.index); break;
    case EventKind::leave: std::snprintf(buf, sizeof buf, "player %d left", e.index); break;
    case EventKind::level:
      std::snprintf(buf, sizeof buf, "level %s", ball_level_name(static_cast<ball_level>(static_cast<int>(e.value))));
      break;
    case EventKind::time_base: std::snprintf(buf, sizeof buf, "time base %.2f", e.value); break;
    default: return "";
  }
  return buf;
}

Watcher::Watcher(const WatcherSettings &settings, ball_net_client *client) : settings_(settings), client_(client) {
  ball_net_set_tap(client_, &Watcher::tap, this);
}

Watcher::~Watcher() { ball_net_set_tap(client_, nullptr, nullptr); }

void Watcher::say(uint32_t match, double sim_time, const std::string &text) {
  if (settings_.log && !text.empty()) out_.log.push_back(LogLine{match, sim_time, text});
}

void Watcher::on_start(double real) {
  start_real_ = real;
  out_.records.push_back({{"type", "start"}, {"real", real}, {"fps", settings_.fps}});
}

std::string Watcher::turn(double real) {
  real_ = real;
  ball_net_event events[64];
  int n = 0;
  do {
    if (ball_net_poll(client_, events, 64, &n) != BALL_OK) return ball_net_message(client_);
    for (int i = 0; i < n; ++i) on_event(events[i]);
  } while (n == 64);
  std::vector<uint32_t> fresh;
  for (auto &kv : matches_)
    if (kv.second.has_info && !kv.second.followed) fresh.push_back(kv.first);
  for (uint32_t id : fresh)
    if (!follow(id)) break;  // (no room: none of the rest has any either)
  if (matches_.size() > kMaxWatched) let_go_silent();  // (what untrusted lines named)
  for (auto &kv : matches_)
    if (kv.second.followed) fetch_model(kv.first, kv.second);
  check_states();
  return "";
}

// Follows a match with a trusted MatchInfo; false when the client has no
// room (its max_matches) even after the matches no server serves any more
// were let go (it is tried again next turn). A match refused for another
// reason is not tried again: its samples stay untrusted and counted.
bool Watcher::follow(uint32_t id) {
  ball_status st = ball_net_watch(client_, id);
  if (st == BALL_ENOSPACE && let_go_silent() > 0) st = ball_net_watch(client_, id);
  auto it = matches_.find(id);
  if (it == matches_.end()) return true;  // (let go itself: silent)
  Watched &w = it->second;
  w.followed = st != BALL_ENOSPACE;
  if (st != BALL_OK && !w.said_refused) say(id, w.info.sim_time, std::string("not followed: ") + ball_net_message(client_));
  w.said_refused = st != BALL_OK;
  return st != BALL_ENOSPACE;
}

// Every match no server serves any more (the client lists it no more)
// let go: the client unwatches it, the watcher forgets it. A stranger's
// made-up matches, each heard once, go 10 s after; a match whose server
// died goes only when the room is needed. How many went.
size_t Watcher::let_go_silent() {
  std::vector<uint32_t> silent;
  ball_net_match m;
  for (const auto &kv : matches_)
    if (ball_net_match_info(client_, kv.first, &m) != BALL_OK) silent.push_back(kv.first);
  for (uint32_t id : silent) {
    if (matches_[id].followed) ball_net_unwatch(client_, id);
    matches_.erase(id);
  }
  let_go_ += silent.size();
  return silent.size();
}

// The whole model of the match's newest info, once the client has it.
void Watcher::fetch_model(uint32_t id, Watched &w) {
  if (w.has_model && w.model_hash == w.info.model_hash) return;  // (every turn: no hash of the model here)
  ball_model m;
  if (ball_net_model(client_, id, &m) != BALL_OK) return;
  const uint64_t hash = ball_model_hash(&m);
  if (hash != w.info.model_hash) return;
  w.model = m;
  w.model_hash = hash;
  w.has_model = true;
}

// One line of the tap: recorded as it came; what the library trusted is used.
void Watcher::tap(void *user, const char *text, size_t length) {
  auto *w = static_cast<Watcher *>(user);
  json line = json::parse(text, text + length, nullptr, false);
  if (!line.is_object()) {
    w->unreadable_++;
    return;
  }
  try {
    w->on_line(line);
  } catch (const std::exception &) {  // (numbers a type cannot hold, a NaN as null: recorded, counted, not used)
    w->unreadable_++;
    auto m = line.find("match");
    if (m == line.end() || !m->is_number_unsigned() || !w->wanted(m->get<uint32_t>())) return;
    w->watched(m->get<uint32_t>()).tally.not_taken++;
    const std::string type = record_type(line);
    if (type != "match_info" && type != "segment" && type != "event" && type != "state") return;
    for (const char *key : {"trusted", "sent", "anew", "kept"}) line.erase(key);
    line["recv"] = w->real_;
    w->out_.records.push_back(line);
  }
}

void Watcher::on_line(const json &line) {
  const std::string type = record_type(line);
  if (type == "ready") {
    if (!ready_) out_.records.push_back({{"type", "ready"}, {"recv", real_}});
    ready_ = true;
    return;
  }
  if (type == "renewed") {  // (the client started anew: docs/deploy.md, "Limits")
    out_.records.push_back({{"type", "renewed"}, {"recv", real_}});
    return;
  }
  if (type == "server_status") {
    StatusOut s = line.get<StatusOut>();
    servers_[s.server_id] = s;
    return;
  }
  auto m = line.find("match");
  if (m == line.end() || !m->is_number_unsigned() || !wanted(m->get<uint32_t>())) return;
  if (type == "match_model") return;  // (the model itself: ball_net_model, once the info names it)
  const bool trusted = line.value("trusted", false);
  if (type == "racket_sample") {
    if (trusted) out_.rackets.push_back(line.get<RacketSampleIn>());
    return;
  }
  if (type == "match_info") {
    on_info(line);
  } else if (type == "segment") {
    on_segment(line);
  } else if (type == "state") {
    on_state(line);
  } else if (type == "event") {
    out_.records.push_back(record_line(line.get<EventOut>(), real_));  // (given by the poll, each once, in order)
    Watched &w = watched(m->get<uint32_t>());
    if (!trusted && w.followed) w.tally.not_taken++;
  }
}

void Watcher::on_info(const json &line) {
  const MatchInfoOut info = line.get<MatchInfoOut>();
  out_.records.push_back(record_line(info, real_));  // what arrived; used only if trusted
  Watched &w = watched(info.match_id);
  if (!line.value("trusted", false)) {
    w.tally.not_taken++;
    return;
  }
  bool first = !w.has_info;
  MatchState before = w.info.state;
  if (line.value("anew", false)) {
    // the sim clock went back: a server started the match anew (its seqs
    // start over too), so nothing held of the old one applies
    say(info.match_id, info.sim_time, "match started anew by server " + std::to_string(info.server_id));
    w.segments.clear();
    w.pending.clear();
    w.leads.clear();
    w.trail.clear();
    w.recent.clear();
    w.next_snapshot = -1.0;
  }
  w.info = info;
  w.info_real = real_;
  w.has_info = true;
  if (info.segment_seq > 0) keep(w, current_segment(info));  // the segment in effect, as the client's match has it
  if (first || before != info.state)
    say(info.match_id, info.sim_time,
        std::string("match ") + name_of(info.state) + " (" + info.scene + ", level " +
            ball_level_name(static_cast<ball_level>(info.level)) + ", " + std::to_string(info.players) +
            " players, server " + std::to_string(info.server_id) + ")");
}

// A trusted segment kept, by seq (a late joiner gets older ones after the
// one in effect); false: held already.
bool Watcher::keep(Watched &w, const SegmentOut &seg) {
  for (const auto &s : w.segments)
    if (s.seq == seg.seq) return false;
  auto at = std::find_if(w.segments.begin(), w.segments.end(),
                         [&seg](const SegmentOut &x) { return static_cast<int32_t>(seg.seq - x.seq) < 0; });
  w.segments.insert(at, seg);
  while (w.segments.size() > kKeepSegments) w.segments.pop_front();
  return true;
}

void Watcher::on_segment(const json &line) {
  const SegmentOut seg = line.get<SegmentOut>();
  const bool kept = line.value("kept", false);  // (recorded when it came, before the match was followed)
  if (!kept) out_.records.push_back(record_line(seg, real_));  // what arrived; used only if trusted
  Watched &w = watched(seg.match_id);
  if (!line.value("trusted", false)) {
    if (w.followed) w.tally.not_taken++;  // (before: the client kept it for when it follows)
    return;
  }
  if (!keep(w, seg)) return;  // (the same segment again)
  if (first_segment_after_ < 0.0) first_segment_after_ = real_ - start_real_;
  if (seg.cause == Cause::racket && seg.sample.valid) {
    latency_.add(real_ - seg.sample.source_time);
    latency_server_.add(seg.server_time - seg.sample.source_time);
  }
  // contacts written ahead: a later seq that starts no later supersedes them
  for (auto it = w.leads.begin(); it != w.leads.end();) {
    if (it->first < seg.seq && it->second.first >= seg.segment.t0) {
      bounces_superseded_++;
      it = w.leads.erase(it);
    } else {
      ++it;
    }
  }
  double sim = 0.0;
  bool contact = seg.cause == Cause::floor || seg.cause == Cause::net || seg.cause == Cause::wall;
  if (contact && w.has_info && w.info.settings.time_base > 0.0 && w.leads.size() < kKeepLeads &&
      sim_now(seg.match_id, real_, &sim))
    w.leads[seg.seq] = {seg.segment.t0, (seg.segment.t0 - sim) / w.info.settings.time_base};
}

void Watcher::on_state(const json &line) {
  const StateOut s = line.get<StateOut>();
  out_.records.push_back(record_line(s, real_));
  Watched &w = watched(s.match_id);
  w.tally.states++;
  if (!line.value("trusted", false)) {
    if (w.followed) w.tally.not_taken++;
    return;
  }
  w.pending.push_back(s);
}

bool Watcher::sim_now(uint32_t id, double real, double *sim) const {
  return ball_net_sim_time(client_, id, real, sim) == BALL_OK;
}

// The contacts whose time has passed by kLeadSettle: they happened (a hit
// that superseded one would have come by then); their leads are counted.
void Watcher::settle_leads(uint32_t id, Watched &w, double real) {
  double now = 0.0;
  if (!sim_now(id, real, &now)) return;
  for (auto it = w.leads.begin(); it != w.leads.end();) {
    if (it->second.first > now - kLeadSettle) {
      ++it;
      continue;
    }
    bounce_lead_.add(it->second.second);
    (it->second.second > 0.0 ? bounces_ahead_ : bounces_late_)++;
    it = w.leads.erase(it);
  }
}

// An event the poll gave, each once and in order (the library's own
// included: a correction's void, a gap, a change of server): tallied,
// logged and kept (for the page and the snapshots' markers).
void Watcher::on_event(const ball_net_event &e) {
  if (!wanted(e.match)) return;
  Watched &w = watched(e.match);
  switch (e.kind) {
    case BALL_NET_EVENT_VOIDED: {
      auto it = w.given.find(static_cast<uint32_t>(e.value));
      if (it != w.given.end()) {
        tally(w, it->second, -1);
        w.given.erase(it);
      }
      w.tally.voided++;
      return;
    }
    case BALL_NET_EVENT_GAP: w.tally.events_missed += static_cast<uint64_t>(e.value); return;
    case BALL_NET_EVENT_SERVER:
      say(e.match, e.time, "match now served by server " + std::to_string(e.server));
      return;
    case BALL_NET_EVENT_SLOT: return;  // (a watcher holds none)
    case BALL_NET_EVENT_SOUND: return;  // (its collision's flag, counted with it)
    default: break;
  }
  if (static_cast<int>(e.kind) < 0 || e.kind >= BALL_NET_EVENT_SERVER) return;
  EventOut ev;
  ev.match_id = e.match;
  ev.server_id = e.server;
  ev.seq = e.seq;
  ev.kind = static_cast<EventKind>(e.kind);
  ev.index = e.index;
  ev.side = e.side;
  ev.in_play = e.in_play != 0;
  ev.sound = e.sound != 0;
  ev.time = e.time;
  ev.point = e.point;
  ev.velocity_in = e.velocity_in;
  ev.velocity_out = e.velocity_out;
  ev.reason = static_cast<Reason>(e.reason);
  ev.score = {e.score[0], e.score[1]};
  ev.value = e.value;
  tally(w, ev, +1);
  w.given[ev.seq] = ev;
  while (w.given.size() > kKeepGiven) w.given.erase(w.given.begin());
  ball_event marker;
  if (settings_.snapshot_every > 0.0 && event_marker(ev, &marker)) w.recent.push_back(marker);
  w.events.push_back(ev);
  w.events_taken++;
  if (w.events.size() > kKeepEvents) w.events.pop_front();
  say(ev.match_id, ev.time, rally_line(ev));
}

std::vector<uint32_t> Watcher::match_ids() const {
  std::vector<uint32_t> ids;
  for (const auto &kv : matches_)
    if (kv.second.has_info) ids.push_back(kv.first);
  return ids;
}

bool Watcher::view(uint32_t match, WatchedView *out) const {
  auto it = matches_.find(match);
  if (it == matches_.end() || !it->second.has_info) return false;
  const Watched &w = it->second;
  out->info = &w.info;
  out->segments = &w.segments;
  out->model = w.has_model ? &w.model : nullptr;
  out->events = &w.events;
  out->events_taken = w.events_taken;
  out->sim_at = [this, match, &w](double real) {
    double sim = w.info.sim_time;
    sim_now(match, real, &sim);
    return sim;
  };
  out->running = w.info.state == MatchState::playing;
  out->info_real = w.info_real;
  return true;
}

const ball_model *Watcher::model(uint32_t match) const {
  auto it = matches_.find(match);
  return it == matches_.end() || !it->second.has_model ? nullptr : &it->second.model;
}

// each server state against the ball evaluated here from the trusted
// segment it names (eq 3 and 4 with the match's flight model)
void Watcher::check_states() {
  for (auto &kv : matches_) {
    Watched &w = kv.second;
    if (!w.has_info) continue;
    size_t keep = 0;
    const uint32_t oldest = w.segments.empty() ? 0 : w.segments.front().seq;
    for (size_t i = 0; i < w.pending.size(); ++i) {
      const StateOut &st = w.pending[i];
      const SegmentOut *k = nullptr;
      for (const auto &s : w.segments)
        if (s.seq == st.segment_seq) k = &s;
      if (!k) {
        if (!w.segments.empty() && static_cast<int32_t>(st.segment_seq - oldest) < 0)
          w.tally.states_unmatched++;  // too old: out of the window
        else
          w.pending[keep++] = st;  // its segment is on the way
        continue;
      }
      ball_state b;
      if (ball_segment_eval(&w.info.model, &k->segment, st.sim_time, &b) != BALL_OK) {
        w.tally.states_unmatched++;
        continue;
      }
      w.tally.max_error = std::fmax(w.tally.max_error, ball_v3_max_diff(b.position, st.ball.position));
      w.tally.states_checked++;
    }
    w.pending.resize(keep);
    if (w.pending.size() > kMaxPending) {  // segments that never come
      w.tally.states_unmatched += w.pending.size();
      w.pending.clear();
    }
  }
}

void Watcher::frame(double real) {
  const double every = settings_.snapshot_every;
  for (auto &kv : matches_) {
    Watched &w = kv.second;
    if (!w.has_info || !w.followed) continue;
    settle_leads(kv.first, w, real);
    ball_net_ball vb;
    if (ball_net_ball_at(client_, kv.first, real, &vb) != BALL_OK) continue;
    const double t = vb.sim_time;
    const ball_state &b = vb.state;
    w.tally.frames++;
    if (settings_.record_frames) out_.records.push_back(OwnFrame{real, kv.first, t, vb.segment, b.position});
    if (every <= 0.0) continue;
    // the last second of the ball and of its collisions, then a frame
    // every `every` sim seconds, on multiples of it
    if (!w.trail.empty() && t < w.trail.back().first) w.trail.clear();  // the clock went back
    w.trail.emplace_back(t, b.position);
    while (w.trail.size() > kTrailPoints || (!w.trail.empty() && w.trail.front().first < t - kTrailSeconds))
      w.trail.pop_front();
    while (!w.recent.empty() && (w.recent.front().time < t - kTrailSeconds || w.recent.size() > kMarkers))
      w.recent.pop_front();
    if (w.next_snapshot < 0.0) w.next_snapshot = std::ceil(t / every) * every;
    if (t < w.next_snapshot) continue;
    SnapshotDue due;
    due.match = kv.first;
    due.info = w.info;
    due.has_model = w.has_model;
    if (due.has_model) due.model = w.model;
    due.sim_time = t;
    due.ball = b.position;
    for (const auto &p : w.trail) due.trail.push_back(p.second);
    due.events.assign(w.recent.begin(), w.recent.end());
    for (int i = 0; i < std::min(w.info.players, kMaxPlayers); ++i)  // (with the config's rackets)
      due.racket_drawn[i] = ball_net_racket(client_, kv.first, i, real, &due.rackets[i]) == BALL_OK;
    out_.snapshots.push_back(std::move(due));
    w.next_snapshot = (std::floor(t / every) + 1.0) * every;
  }
}

void Watcher::snapshot_written(const SnapshotDue &due, const SnapshotRecord &drawn, double real) {
  watched(due.match).tally.snapshots++;
  SnapshotRecord r = drawn;
  r.real = real;
  r.match = due.match;
  r.sim_time = due.sim_time;
  r.position = due.ball;
  out_.records.push_back(r);
}

// What an event adds to the tally (sign +1), or takes off it when a
// correction voids it (-1). The counts of every kind an event counts in.
void Watcher::tally(Watched &w, const EventOut &e, int sign) {
  WatchedMatchSummary &t = w.tally;
  auto add = [sign](uint64_t &n) { n = sign > 0 ? n + 1 : n - (n > 0); };
  if (is_collision(e.kind) && e.sound) add(t.sounds);  // the paper's sound event (docs/protocol.md, "Events")
  switch (e.kind) {
    case EventKind::racket:
      add(e.in_play ? t.hits : t.dead_hits);
      if (e.in_play) add(hits_);
      break;
    case EventKind::floor:
      if (e.in_play) add(t.bounces);
      break;
    case EventKind::net: add(t.nets); break;
    case EventKind::wall: add(t.walls); break;
    case EventKind::serve: add(t.serves); break;
    case EventKind::point:
      add(e.side < 0 ? t.lets : t.points);
      if (sign > 0) t.score = e.score;
      break;
    case EventKind::pause: add(t.pauses); break;
    case EventKind::resume: add(t.resumes); break;
    case EventKind::refused: add(t.refused); break;
    default: break;
  }
}

WatchSummary Watcher::summary(double seconds) const {
  WatchSummary s;
  s.seconds = seconds;
  s.first_segment_after = first_segment_after_;
  for (const auto &kv : matches_) {
    WatchedMatchSummary m = kv.second.tally;
    m.match = kv.first;
    m.segments = kv.second.segments.empty() ? 0 : kv.second.segments.back().seq;
    s.matches.push_back(m);
  }
  for (const auto &kv : servers_) s.servers.push_back(kv.second);
  ball_net_status st;  // (the client's count, the same in every match's status)
  for (const auto &kv : matches_)
    if (kv.second.followed && ball_net_status_of(client_, kv.first, &st) == BALL_OK) {
      s.untrusted = st.untrusted;
      break;
    }
  s.latency_p50 = latency_.quantile(0.5);
  s.latency_p99 = latency_.quantile(0.99);
  s.latency_server_p50 = latency_server_.quantile(0.5);
  s.latency_server_p99 = latency_server_.quantile(0.99);
  s.latency_count = latency_.size();
  s.bounces_ahead = bounces_ahead_;
  s.bounces_late = bounces_late_;
  s.bounces_superseded = bounces_superseded_;
  s.bounce_lead_p1 = bounce_lead_.quantile(0.01);
  s.bounce_lead_p50 = bounce_lead_.quantile(0.5);
  return s;
}

}  // namespace ballsrv
