#include "watcher.h"

#include <cinttypes>
#include <cmath>
#include <cstdio>

#include "ball/vec3.h"

namespace ballsrv {

namespace {

constexpr size_t kKeepLeads = 256;     // contacts written ahead a match keeps until they happen
constexpr size_t kMaxPending = 4096;   // states waiting for a segment that never comes: counted and forgotten
constexpr double kLeadSettle = 1.0;    // sim s after a contact by which a hit that superseded it has come
constexpr double kTrailSeconds = 1.0;  // sim s of trail and of event markers
constexpr size_t kTrailPoints = 2048;
constexpr size_t kMarkers = 64;
constexpr size_t kKeepEvents = 64;     // per match, for a view

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

Watcher::Watched &Watcher::watched(uint32_t id) {
  Watched &w = matches_[id];
  if (!w.view) w.view = std::make_unique<MatchView>(id, settings_.servers, ParticipantId{});  // (it holds no slot)
  return w;
}

void Watcher::say(uint32_t match, double sim_time, const std::string &text) {
  if (settings_.log && !text.empty()) out_.log.push_back(LogLine{match, sim_time, text});
}

void Watcher::on_start(double real) {
  start_real_ = real;
  out_.records.push_back({{"type", "start"}, {"real", real}, {"fps", settings_.fps}});
}

void Watcher::on_ready(double real) {
  if (ready_) return;
  ready_ = true;
  out_.records.push_back({{"type", "ready"}, {"recv", real}});
}

void Watcher::on_info(const MatchInfoOut &info, double real) {
  if (!wanted(info.match_id)) return;
  Watched &w = watched(info.match_id);
  out_.records.push_back(record_line(info, real));  // what arrived; used only if it fits (trust.h)
  bool first = !w.view->has_info();
  MatchState before = w.view->info().state;
  std::vector<ViewEvent> given;
  if (!w.view->on_info(info, real, &given)) {
    w.tally.not_taken++;
    return;
  }
  if (w.view->counters().anew != w.anew) {
    // the sim clock went back: a server started the match anew (its seqs
    // start over too), so nothing held of the old one applies
    w.anew = w.view->counters().anew;
    say(info.match_id, info.sim_time, "match started anew by server " + std::to_string(info.server_id));
    w.pending.clear();
    w.leads.clear();
    w.trail.clear();
    w.recent.clear();
    w.next_snapshot = -1.0;
  }
  take(w, given);
  if (first || before != info.state)
    say(info.match_id, info.sim_time,
        std::string("match ") + name_of(info.state) + " (" + info.scene + ", level " +
            ball_level_name(static_cast<ball_level>(info.level)) + ", " + std::to_string(info.players) +
            " players, server " + std::to_string(info.server_id) + ")");
}

void Watcher::on_model(const MatchModelOut &model) {
  if (!wanted(model.match_id)) return;
  if (!watched(model.match_id).view->on_model(model)) watched(model.match_id).tally.not_taken++;
}

void Watcher::on_segment(const SegmentOut &seg, double real) {
  if (!wanted(seg.match_id)) return;
  Watched &w = watched(seg.match_id);
  out_.records.push_back(record_line(seg, real));  // what arrived; used only if it fits
  std::vector<ViewEvent> given;
  if (!w.view->on_segment(seg, real, &given)) {
    w.tally.not_taken++;
    return;
  }
  take(w, given);  // (the events it voids)
  if (first_segment_after_ < 0.0) first_segment_after_ = real - start_real_;
  if (seg.cause == Cause::racket && seg.sample.valid) {
    latency_.add(real - seg.sample.source_time);
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
  const MatchView &v = *w.view;
  bool contact = seg.cause == Cause::floor || seg.cause == Cause::net || seg.cause == Cause::wall;
  if (contact && v.clock().valid() && v.info().time_base > 0.0 && w.leads.size() < kKeepLeads)
    w.leads[seg.seq] = {seg.segment.t0, (seg.segment.t0 - v.clock().sim_now(real)) / v.info().time_base};
}

// The contacts whose time has passed by kLeadSettle: they happened (a hit
// that superseded one would have come by then); their leads are counted.
void Watcher::settle_leads(Watched &w, double real) {
  if (!w.view->clock().valid()) return;
  double now = w.view->clock().sim_now(real);
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

// What an event adds to the tally (sign +1), or takes off it when a
// correction voids it (-1). The counts of every kind an event counts in.
void Watcher::tally(Watched &w, const EventOut &e, int sign) {
  WatchedMatchSummary &t = w.tally;
  auto add = [sign](uint64_t &n) { n = sign > 0 ? n + 1 : n - (n > 0); };
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
    case EventKind::sound: add(t.sounds); break;
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

// What the view gave, each once and in order: the server's events tallied,
// logged and kept (for the page and the snapshots' markers), the events a
// correction voided taken off the tally, the seqs that never came counted.
void Watcher::take(Watched &w, std::vector<ViewEvent> &given) {
  for (const ViewEvent &v : given) {
    const EventOut &e = v.event;
    switch (v.note) {
      case ViewNote::none: {
        tally(w, e, +1);
        ball_event marker;
        if (settings_.snapshot_every > 0.0 && event_marker(e, &marker)) w.recent.push_back(marker);
        w.events.push_back(e);
        w.events_taken++;
        if (w.events.size() > kKeepEvents) w.events.pop_front();
        say(e.match_id, e.time, rally_line(e));
        break;
      }
      case ViewNote::voided: tally(w, e, -1); break;
      case ViewNote::gap: w.tally.events_missed += static_cast<uint64_t>(e.value); break;
      case ViewNote::server:
        say(e.match_id, e.time, "match now served by server " + std::to_string(e.server_id));
        break;
      case ViewNote::slot: break;  // (a watcher holds none)
    }
  }
  given.clear();
}

void Watcher::on_event(const EventOut &e, double real) {
  if (!wanted(e.match_id)) return;
  Watched &w = watched(e.match_id);
  out_.records.push_back(record_line(e, real));  // what arrived; given once, in order, if it fits
  std::vector<ViewEvent> given;
  uint64_t refused = w.view->counters().refused;
  w.view->on_event(e, real, &given);
  if (w.view->counters().refused != refused) w.tally.not_taken++;
  take(w, given);
}

void Watcher::on_state(const StateOut &s, double real) {
  if (!wanted(s.match_id)) return;
  Watched &w = watched(s.match_id);
  w.tally.states++;
  out_.records.push_back(record_line(s, real));
  if (!w.view->on_state(s, real)) {
    w.tally.not_taken++;
    return;
  }
  w.pending.push_back(s);
}

void Watcher::on_status(const StatusOut &s) { servers_[s.server_id] = s; }

void Watcher::not_taken(uint32_t match) {
  if (wanted(match)) watched(match).tally.not_taken++;
}

std::vector<uint32_t> Watcher::match_ids() const {
  std::vector<uint32_t> ids;
  for (const auto &kv : matches_)
    if (kv.second.view->has_info()) ids.push_back(kv.first);
  return ids;
}

bool Watcher::view(uint32_t match, WatchedView *out) const {
  auto it = matches_.find(match);
  if (it == matches_.end() || !it->second.view->has_info()) return false;
  const Watched &w = it->second;
  out->info = &w.view->info();
  out->segments = &w.view->window();
  out->model = w.view->model();
  out->events = &w.events;
  out->events_taken = w.events_taken;
  out->clock = &w.view->clock();
  out->info_real = w.view->info_local();
  return true;
}

const ball_model *Watcher::model(uint32_t match) const {
  auto it = matches_.find(match);
  return it == matches_.end() ? nullptr : it->second.view->model();
}

// each server state against the ball evaluated here from the segment it
// names (eq 3 and 4 with the match's flight model)
void Watcher::check_states() {
  for (auto &kv : matches_) {
    Watched &w = kv.second;
    const MatchView &v = *w.view;
    if (!v.has_info()) continue;
    const std::vector<KeptSegment> &window = v.window();
    size_t keep = 0;
    for (size_t i = 0; i < w.pending.size(); ++i) {
      const StateOut &st = w.pending[i];
      const KeptSegment *k = nullptr;
      for (const auto &s : window)
        if (s.segment.seq == st.segment_seq) k = &s;
      if (!k) {
        if (!window.empty() && static_cast<int32_t>(st.segment_seq - window.front().segment.seq) < 0)
          w.tally.states_unmatched++;  // too old: out of the window
        else
          w.pending[keep++] = st;  // its segment is on the way
        continue;
      }
      ball_state b;
      if (ball_segment_eval(&v.flight_model(), &k->segment.segment, st.sim_time, &b) != BALL_OK) {
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
    const MatchView &v = *w.view;
    if (!v.has_info() || !v.clock().valid()) continue;
    settle_leads(w, real);
    ViewBall vb;
    if (v.ball(real, &vb) != BALL_OK) continue;
    const double t = vb.sim_time;
    const ball_state &b = vb.state;
    w.tally.frames++;
    if (settings_.record_frames) out_.records.push_back(OwnFrame{real, kv.first, t, vb.segment->seq, b.position});
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
    due.info = v.info();
    due.has_model = v.model() != nullptr;
    if (due.has_model) due.model = *v.model();
    due.sim_time = t;
    due.ball = b.position;
    for (const auto &p : w.trail) due.trail.push_back(p.second);
    due.events.assign(w.recent.begin(), w.recent.end());
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

WatchSummary Watcher::summary(double seconds) const {
  WatchSummary s;
  s.seconds = seconds;
  s.first_segment_after = first_segment_after_;
  for (const auto &kv : matches_) {
    WatchedMatchSummary m = kv.second.tally;
    m.match = kv.first;
    const std::vector<KeptSegment> &window = kv.second.view->window();
    m.segments = window.empty() ? 0 : window.back().segment.seq;
    m.voided = kv.second.view->counters().voided;
    s.matches.push_back(m);
  }
  for (const auto &kv : servers_) s.servers.push_back(kv.second);
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

std::vector<std::string> summary_lines(const WatchSummary &s) {
  std::vector<std::string> out;
  char buf[512];
  for (const auto &m : s.matches) {
    std::snprintf(buf, sizeof buf,
                  "summary: match %u: %" PRIu64 " hits, %" PRIu64 " bounces, %" PRIu64 " serves, %" PRIu64
                  " points (score %d-%d), %" PRIu64 " pauses; desync: %" PRIu64 " of %" PRIu64
                  " ball states checked, max |error| %.3g m",
                  m.match, m.hits, m.bounces, m.serves, m.points, m.score[0], m.score[1], m.pauses, m.states_checked,
                  m.states, m.max_error);
    out.push_back(buf);
  }
  for (const auto &o : s.servers) {
    std::snprintf(buf, sizeof buf,
                  "summary: server %u: %" PRIu64 " racket samples in, %" PRIu64 " accepted, %" PRIu64
                  " idle, dropped %s, %" PRIu64 " writes refused, %" PRIu64 " frame overruns",
                  o.server_id, o.samples_in, o.samples_ok, o.samples_idle, drops_text(o.drops).c_str(),
                  o.write_failures, o.overruns);
    out.push_back(buf);
  }
  std::snprintf(buf, sizeof buf,
                "summary: sample-to-segment latency (a hit's newest racket sample written -> its segment received): "
                "p50 %.1f ms, p99 %.1f ms over %" PRIu64 " hits",
                s.latency_p50 * 1e3, s.latency_p99 * 1e3, s.latency_count);
  out.push_back(buf);
  uint64_t bounces = s.bounces_ahead + s.bounces_late;
  if (bounces > 0) {
    std::snprintf(buf, sizeof buf,
                  "summary: contacts written ahead: %" PRIu64 " of %" PRIu64
                  " received before they happen (lead p1 %.0f ms, p50 %.0f ms), %" PRIu64 " superseded by a hit",
                  s.bounces_ahead, bounces, s.bounce_lead_p1 * 1e3, s.bounce_lead_p50 * 1e3, s.bounces_superseded);
    out.push_back(buf);
  }
  if (s.untrusted > 0) {
    std::snprintf(buf, sizeof buf,
                  "summary: %" PRIu64 " server samples refused: their writer lacks the certificate of their server id",
                  s.untrusted);
    out.push_back(buf);
  }
  return out;
}

}  // namespace ballsrv
