// ball-watch: an observer (docs/server.md, "Watchers"). It prints the rally
// as it happens, records everything it receives to JSON Lines on request,
// evaluates the ball from the segments at its own frame rate (eq 3 on the
// client, with the flight model MatchInfo carries) and checks that ball
// against the server's ball states: the desync check. With --snapshots it
// also writes PNG frames of each match (libball::render, headless OSMesa)
// every S sim seconds, as ballrender does for a scene. One loop, one thread.
#include <CLI/CLI.hpp>
#include <cerrno>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <deque>
#include <fstream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <sys/stat.h>

#include "ball/render.h"
#include "ball/vec3.h"
#include "common.h"
#include "domain.h"
#include "sim_clock.h"

using namespace ballsrv;
using namespace ballsrv::app;
using json = nlohmann::json;

namespace {

const char *kProgram = "ball-watch";
constexpr size_t kKeepSegments = 256;  // per match, for states that arrive late

json vec(ball_vec3 v) { return json::array({v.x, v.y, v.z}); }

// What the watcher knows of one match.
struct Watched {
  MatchInfoOut info;
  bool has_info = false;
  SimClock clock;
  std::map<uint32_t, SegmentOut> segments;  // by seq
  std::vector<StateOut> pending;            // states whose segment has not arrived yet
  // the rally
  uint64_t hits = 0, dead_hits = 0, bounces = 0, nets = 0, walls = 0, sounds = 0, serves = 0, points = 0;
  uint64_t pauses = 0, resumes = 0, lets = 0, refused = 0;
  uint32_t last_event_seq = 0;
  uint64_t events_missed = 0;
  std::array<int, 2> score{0, 0};
  // the desync check
  uint64_t states = 0, checked = 0, unmatched = 0;
  double max_error = 0.0;
  uint64_t frames = 0;  // own frames evaluated
  // snapshots: the court to draw, the last second of the own ball and of
  // the collision events, the next sim time to draw
  bool has_court = false;
  ball_model court{};
  std::deque<std::pair<double, ball_vec3>> trail;
  std::deque<ball_event> recent;
  double next_snapshot = -1.0;
  uint64_t snapshots = 0;
};

// Snapshot frames of live matches (docs/server.md, "Snapshot frames").
struct Snapshots {
  std::string dir;
  double every = 0.5;  // sim s
  std::string camera = "side";
  int width = 640, height = 480;
  ball_renderer *renderer = nullptr;
  ~Snapshots() { ball_renderer_destroy(renderer); }
};

constexpr double kTrailSeconds = 1.0;    // sim s of trail and of event markers
constexpr size_t kTrailPoints = 2048;

// The model a match's frames are drawn with: its scene's court (net, walls,
// racket discs), if the watcher finds the scene by name, else libball's
// default court, with the flight fields the match announced (radius,
// floor: where the ball is drawn).
ball_model court_model(const MatchInfoOut &info) {
  ball_scene scene;
  std::string err;
  if (!load_scene(info.scene, &scene, &err)) ball_scene_default(&scene);
  ball_model m = scene.model;
  m.radius = info.model.radius;
  m.floor_level = info.model.floor_level;
  m.gravity = info.model.gravity;
  return m;
}

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

// Draws match id at sim time t, the ball at b, into the snapshot folder:
// "" and the file's path, or an error.
std::string snapshot(Snapshots &sn, uint32_t id, Watched &w, double t, ball_vec3 b, std::string *file) {
  if (!sn.renderer && ball_renderer_create(sn.width, sn.height, &sn.renderer) != BALL_OK)
    return "cannot create an OSMesa renderer";
  if (!w.has_court) {
    w.court = court_model(w.info);
    w.has_court = true;
  }
  ball_camera cam;
  ball_camera_preset preset = BALL_CAMERA_SIDE;
  for (int i = 0; i < BALL_CAMERA_PRESET_COUNT; ++i)
    if (sn.camera == ball_camera_preset_name(static_cast<ball_camera_preset>(i)))
      preset = static_cast<ball_camera_preset>(i);
  if (ball_camera_from_preset(&w.court, preset, static_cast<double>(sn.width) / sn.height, &cam) != BALL_OK)
    return "no camera for match " + std::to_string(id);
  std::vector<ball_vec3> trail;
  for (const auto &p : w.trail) trail.push_back(p.second);
  std::vector<ball_event> events(w.recent.begin(), w.recent.end());
  ball_frame f{};
  f.time = t;
  f.ball = b;
  f.n_rackets = 0;  // a watcher does not read the players' samples
  f.n_trail = static_cast<int>(trail.size());
  f.trail = trail.data();
  f.n_events = static_cast<int>(events.size());
  f.events = events.data();
  if (ball_render_draw(sn.renderer, &w.court, &cam, &f) != BALL_OK) return "cannot draw match " + std::to_string(id);
  const unsigned char *rgb;
  int width, height;
  ball_render_pixels(sn.renderer, &rgb, &width, &height);
  char name[64];
  std::snprintf(name, sizeof name, "/m%u_t%08.3f.png", id, t);
  *file = sn.dir + name;
  if (ball_png_write(file->c_str(), rgb, width, height) != BALL_OK)
    return "cannot write " + *file + ": " + std::strerror(errno);
  return "";
}

std::string point_text(ball_vec3 p) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "(%.2f, %.2f, %.2f)", p.x, p.y, p.z);
  return buf;
}

// One line of the rally log, or "" for events not worth a line.
std::string rally_line(const EventOut &e, const Watched &w) {
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
    case EventKind::net:
      std::snprintf(buf, sizeof buf, "  net at %s", point_text(e.point).c_str());
      break;
    case EventKind::wall:
      std::snprintf(buf, sizeof buf, "  wall %d at %s", e.index, point_text(e.point).c_str());
      break;
    case EventKind::racket:
      std::snprintf(buf, sizeof buf, "  hit by player %d at %s, %.1f m/s%s", e.index, point_text(e.point).c_str(),
                    ball_v3_norm(e.velocity_out), e.in_play ? "" : " (dead ball)");
      break;
    case EventKind::point:
      if (e.side < 0) std::snprintf(buf, sizeof buf, "let (%s): replayed", name_of(e.reason));
      else
        std::snprintf(buf, sizeof buf, "point to the %s side (%s), score %d-%d", e.side == 0 ? "near" : "far",
                      name_of(e.reason), e.score[0], e.score[1]);
      break;
    case EventKind::pause:
      std::snprintf(buf, sizeof buf, "pause: player %d %s", e.index, name_of(e.reason));
      break;
    case EventKind::resume:
      std::snprintf(buf, sizeof buf, "resume");
      break;
    case EventKind::join:
      std::snprintf(buf, sizeof buf, "player %d joined", e.index);
      break;
    case EventKind::leave:
      std::snprintf(buf, sizeof buf, "player %d left", e.index);
      break;
    case EventKind::level:
      std::snprintf(buf, sizeof buf, "level %s", ball_level_name(static_cast<ball_level>(static_cast<int>(e.value))));
      break;
    case EventKind::time_base:
      std::snprintf(buf, sizeof buf, "time base %.2f", e.value);
      break;
    default:
      return "";
  }
  (void)w;
  return buf;
}

// The segment in effect at sim time t: the newest with t0 <= t.
const SegmentOut *segment_at(const Watched &w, double t) {
  const SegmentOut *best = nullptr;
  for (auto it = w.segments.rbegin(); it != w.segments.rend(); ++it)
    if (it->second.segment.t0 <= t) {
      best = &it->second;
      break;
    }
  return best;
}

}  // namespace

int main(int argc, char **argv) {
  CLI::App cli{"ball-watch: watch ball-server's matches: the rally log, a JSON Lines record, the ball\n"
               "evaluated from segments and checked against the server's ball states"};
  long match_filter = -1;
  double fps = 60.0, duration = 0.0;
  std::string record, summary_json;
  bool quiet = false, frames_in_record = false, no_log = false;
  long until_hits = 0;
  DdsOptions dds_opt;
  cli.add_option("--match", match_filter, "watch this match only (default: all)");
  cli.add_option("--fps", fps, "frames per second of the watcher's own ball")->capture_default_str()->check(CLI::Range(1.0, 1000.0));
  cli.add_option("--duration", duration, "stop after S real seconds (0: until SIGINT/SIGTERM)")->check(CLI::Range(0.0, 1e9));
  cli.add_option("--until-hits", until_hits, "stop once this many racket hits were seen in play")->check(CLI::Range(0L, 1000000L));
  cli.add_option("--record", record, "write everything received to FILE as JSON Lines (one object a line)");
  cli.add_flag("--record-frames", frames_in_record, "with --record: also the watcher's own ball, every frame");
  cli.add_option("--summary-json", summary_json, "write the summary to FILE as JSON at exit");
  cli.add_flag("--no-log", no_log, "no rally log, only the summary");
  cli.add_flag("--quiet,-q", quiet, "print nothing but errors");
  Snapshots snap;
  std::string size_text;
  cli.add_option("--snapshots", snap.dir, "write PNG frames of each match to DIR (m<match>_t<sim time>.png)");
  cli.add_option("--snapshot-every", snap.every, "with --snapshots: sim seconds between frames")
      ->capture_default_str()
      ->check(CLI::Range(0.01, 3600.0));
  std::vector<std::string> cameras;
  for (int i = 0; i < BALL_CAMERA_PRESET_COUNT; ++i)
    cameras.push_back(ball_camera_preset_name(static_cast<ball_camera_preset>(i)));
  cli.add_option("--camera", snap.camera, "with --snapshots: the camera")
      ->capture_default_str()
      ->check(CLI::IsMember(cameras));
  cli.add_option("--size", size_text, "with --snapshots: WxH pixels, each in [16, 2048] (default 640x480)");
  add_dds_options(cli, &dds_opt);
  CLI11_PARSE(cli, argc, argv);
  if (!size_text.empty()) {
    char x = 0, extra = 0;
    if (std::sscanf(size_text.c_str(), "%d%c%d%c", &snap.width, &x, &snap.height, &extra) != 3 || x != 'x' ||
        snap.width < BALL_RENDER_MIN_SIZE || snap.width > BALL_RENDER_MAX_SIZE || snap.height < BALL_RENDER_MIN_SIZE ||
        snap.height > BALL_RENDER_MAX_SIZE)
      return fail(kProgram, "--size: want WxH, each in [" + std::to_string(BALL_RENDER_MIN_SIZE) + ", " +
                                std::to_string(BALL_RENDER_MAX_SIZE) + "], got \"" + size_text + "\"");
  }
  if (!snap.dir.empty()) {
    struct stat st {};
    if (::stat(snap.dir.c_str(), &st) != 0 && ::mkdir(snap.dir.c_str(), 0777) != 0)
      return fail(kProgram, "--snapshots: cannot create " + snap.dir + ": " + std::strerror(errno));
    if (::stat(snap.dir.c_str(), &st) != 0 || !S_ISDIR(st.st_mode))
      return fail(kProgram, "--snapshots: " + snap.dir + " is not a folder");
  }

  std::string err;
  install_stop_signals();
  auto domain = dds::Domain::open(dds_opt.domain, find_profile(dds_opt.profile), dds_opt.participant,
                                  "ball-watch", &err);
  if (!domain) return fail(kProgram, err);
  const int room = dds::kClientRoom;
  auto segments = domain->reader<SegmentOut>(dds::kSegmentTopic, dds::kSegmentProfile, {room}, &err);
  auto events = domain->reader<EventOut>(dds::kEventTopic, dds::kEventProfile, {room}, &err);
  auto states = domain->reader<StateOut>(dds::kStateTopic, dds::kStateProfile, {room}, &err);
  auto infos = domain->reader<MatchInfoOut>(dds::kInfoTopic, dds::kInfoProfile, {room}, &err);
  auto status = domain->reader<StatusOut>(dds::kStatusTopic, dds::kStatusProfile, {16}, &err);
  if (!segments.valid() || !events.valid() || !states.valid() || !infos.valid() || !status.valid())
    return fail(kProgram, err);

  std::ofstream rec;
  if (!record.empty()) {
    rec.open(record, std::ios::trunc);
    if (!rec) return fail(kProgram, "cannot write " + record);
  }
  bool unflushed = false;
  auto log = [&](const json &j) {
    if (!rec) return;
    rec << j.dump() << "\n";
    unflushed = true;
  };

  std::map<uint32_t, Watched> matches;
  std::map<uint32_t, StatusOut> servers;
  Percentiles latency, latency_server;  // sample write -> segment received / written
  const double start = mono_now(), start_real = realtime_now();
  auto wanted = [&](uint32_t id) { return match_filter < 0 || id == static_cast<uint32_t>(match_filter); };
  auto say = [&](uint32_t id, double sim_t, const std::string &line) {
    if (quiet || no_log || line.empty()) return;
    std::printf("[%6.2f s] match %u, t %7.3f: %s\n", mono_now() - start, id, sim_t, line.c_str());
    std::fflush(stdout);
  };
  uint64_t hits_total = 0;
  double first_segment_delay = -1.0;
  log({{"type", "start"}, {"real", start_real}, {"fps", fps}});

  double next_frame = start;
  bool ready = false;
  while (!stop_requested()) {
    double now = mono_now();
    if (duration > 0.0 && now - start >= duration) break;
    if (until_hits > 0 && hits_total >= static_cast<uint64_t>(until_hits)) break;
    double real = realtime_now();
    dds::SampleMeta meta;
    // "ready": a server's segments, events and match info reach us from now on
    // (events are not kept for late joiners: what came before is not seen)
    if (!ready && segments.matched() > 0 && events.matched() > 0 && infos.matched() > 0) {
      ready = true;
      log({{"type", "ready"}, {"recv", real}});
    }

    MatchInfoOut info;
    while (infos.take(&info, &meta)) {
      if (!wanted(info.match_id)) continue;
      Watched &w = matches[info.match_id];
      bool first = !w.has_info;
      MatchState before = w.info.state;
      w.info = info;
      w.has_info = true;
      w.clock.observe(info.sim_time, info.server_time, info.time_base, info.state == MatchState::playing, real);
      if (first || before != info.state)
        say(info.match_id, info.sim_time,
            std::string("match ") + name_of(info.state) + " (" + info.scene + ", level " +
                ball_level_name(static_cast<ball_level>(info.level)) + ", " + std::to_string(info.players) +
                " players, server " + std::to_string(info.server_id) + ")");
      log({{"type", "match_info"}, {"recv", real}, {"match", info.match_id}, {"server", info.server_id},
           {"revision", info.revision}, {"state", name_of(info.state)}, {"scene", info.scene},
           {"level", info.level}, {"players", info.players}, {"score", {info.score[0], info.score[1]}},
           {"sim_time", info.sim_time}, {"server_time", info.server_time}, {"time_base", info.time_base},
           {"player_timeout", info.player_timeout}, {"model_hash", info.model_hash},
           {"segment_seq", info.segment_seq}});
    }

    SegmentOut seg;
    while (segments.take(&seg, &meta)) {
      if (!wanted(seg.match_id)) continue;
      Watched &w = matches[seg.match_id];
      if (first_segment_delay < 0.0) first_segment_delay = now - start;
      w.segments[seg.seq] = seg;
      while (w.segments.size() > kKeepSegments) w.segments.erase(w.segments.begin());
      if (seg.cause == Cause::racket && seg.sample.valid) {
        latency.add(real - seg.sample.source_time);
        latency_server.add(seg.server_time - seg.sample.source_time);
      }
      log({{"type", "segment"}, {"recv", real}, {"match", seg.match_id}, {"server", seg.server_id}, {"seq", seg.seq},
           {"cause", name_of(seg.cause)}, {"index", seg.cause_index}, {"t0", seg.segment.t0},
           {"p0", vec(seg.segment.p0)}, {"v0", vec(seg.segment.v0)}, {"s0", vec(seg.segment.s0)},
           {"grounded", seg.segment.grounded != 0}, {"server_time", seg.server_time}, {"model_hash", seg.model_hash},
           {"sample_seq", seg.sample.seq}, {"sample_source_time", seg.sample.source_time}});
    }

    EventOut e;
    while (events.take(&e, &meta)) {
      if (!wanted(e.match_id)) continue;
      Watched &w = matches[e.match_id];
      if (w.last_event_seq && e.seq > w.last_event_seq + 1) w.events_missed += e.seq - w.last_event_seq - 1;
      if (e.seq > w.last_event_seq) w.last_event_seq = e.seq;
      switch (e.kind) {
        case EventKind::racket: (e.in_play ? w.hits : w.dead_hits)++; hits_total += e.in_play; break;
        case EventKind::floor: w.bounces += e.in_play; break;
        case EventKind::net: w.nets++; break;
        case EventKind::wall: w.walls++; break;
        case EventKind::sound: w.sounds++; break;
        case EventKind::serve: w.serves++; break;
        case EventKind::point: (e.side < 0 ? w.lets : w.points)++; w.score = e.score; break;
        case EventKind::pause: w.pauses++; break;
        case EventKind::resume: w.resumes++; break;
        case EventKind::refused: w.refused++; break;
        default: break;
      }
      ball_event marker;
      if (!snap.dir.empty() && event_marker(e, &marker)) w.recent.push_back(marker);
      say(e.match_id, e.time, rally_line(e, w));
      log({{"type", "event"}, {"recv", real}, {"match", e.match_id}, {"server", e.server_id}, {"seq", e.seq},
           {"kind", name_of(e.kind)}, {"index", e.index}, {"side", e.side}, {"in_play", e.in_play},
           {"sound", e.sound}, {"time", e.time}, {"server_time", e.server_time}, {"point", vec(e.point)},
           {"velocity_in", vec(e.velocity_in)}, {"velocity_out", vec(e.velocity_out)},
           {"segment_seq", e.segment_seq}, {"reason", name_of(e.reason)},
           {"score", {e.score[0], e.score[1]}}, {"value", e.value}});
    }

    StateOut s;
    while (states.take(&s, &meta)) {
      if (!wanted(s.match_id)) continue;
      Watched &w = matches[s.match_id];
      w.states++;
      w.clock.observe(s.sim_time, s.server_time, w.info.time_base, s.state == MatchState::playing, real);
      w.pending.push_back(s);
      log({{"type", "state"}, {"recv", real}, {"match", s.match_id}, {"frame", s.frame}, {"sim_time", s.sim_time},
           {"server_time", s.server_time}, {"segment_seq", s.segment_seq}, {"position", vec(s.ball.position)},
           {"velocity", vec(s.ball.velocity)}, {"spin", vec(s.ball.spin)}, {"sim_hash", s.sim_hash}});
    }

    StatusOut so;
    while (status.take(&so, nullptr)) servers[so.server_id] = so;

    // the desync check: each server state against the ball evaluated here
    // from the segment it names (eq 3 and 4 with MatchInfo's flight model)
    for (auto &kv : matches) {
      Watched &w = kv.second;
      if (!w.has_info) continue;
      size_t keep = 0;
      for (size_t i = 0; i < w.pending.size(); ++i) {
        const StateOut &st = w.pending[i];
        auto it = w.segments.find(st.segment_seq);
        if (it == w.segments.end()) {
          if (!w.segments.empty() && st.segment_seq < w.segments.begin()->first) w.unmatched++;  // too old
          else w.pending[keep++] = st;  // its segment is on the way
          continue;
        }
        ball_state b;
        if (ball_segment_eval(&w.info.model, &it->second.segment, st.sim_time, &b) != BALL_OK) {
          w.unmatched++;
          continue;
        }
        double e1 = ball_v3_max_diff(b.position, st.ball.position);
        if (e1 > w.max_error) w.max_error = e1;
        w.checked++;
      }
      w.pending.resize(keep);
      if (w.pending.size() > 4096) {  // segments that never come: count and forget
        w.unmatched += w.pending.size();
        w.pending.clear();
      }
    }

    // the watcher's own ball, at its own frame rate
    if (now >= next_frame) {
      for (auto &kv : matches) {
        Watched &w = kv.second;
        if (!w.has_info || !w.clock.valid()) continue;
        double t = w.clock.sim_now(real);
        const SegmentOut *sg = segment_at(w, t);
        if (!sg) continue;
        ball_state b;
        if (ball_segment_eval(&w.info.model, &sg->segment, t, &b) != BALL_OK) continue;
        w.frames++;
        if (frames_in_record)
          log({{"type", "frame"}, {"real", real}, {"match", kv.first}, {"sim_time", t}, {"segment_seq", sg->seq},
               {"position", vec(b.position)}});
        if (!snap.dir.empty()) {
          // the last second of the ball and of its collisions, then a frame
          // every `every` sim seconds, on multiples of it
          if (!w.trail.empty() && t < w.trail.back().first) w.trail.clear();  // the clock went back
          w.trail.emplace_back(t, b.position);
          while (w.trail.size() > kTrailPoints || (!w.trail.empty() && w.trail.front().first < t - kTrailSeconds))
            w.trail.pop_front();
          while (!w.recent.empty() && (w.recent.front().time < t - kTrailSeconds || w.recent.size() > 64))
            w.recent.pop_front();
          if (w.next_snapshot < 0.0) w.next_snapshot = std::ceil(t / snap.every) * snap.every;
          if (t >= w.next_snapshot) {
            std::string file, why = snapshot(snap, kv.first, w, t, b.position, &file);
            if (!why.empty()) return fail(kProgram, why);
            w.snapshots++;
            log({{"type", "snapshot"}, {"real", real}, {"match", kv.first}, {"sim_time", t}, {"file", file},
                 {"position", vec(b.position)}, {"camera", snap.camera}, {"size", {snap.width, snap.height}}});
            w.next_snapshot = (std::floor(t / snap.every) + 1.0) * snap.every;
          }
        }
      }
      next_frame += 1.0 / fps;
      if (next_frame < now) next_frame = now + 1.0 / fps;
    }
    if (unflushed) {  // a reader can follow the record as it grows
      rec.flush();
      unflushed = false;
    }
    sleep_until(std::min(next_frame, mono_now() + 0.002));
  }

  // the summary
  json sum;
  sum["seconds"] = mono_now() - start;
  sum["first_segment_after"] = first_segment_delay;
  json ms = json::array();
  for (auto &kv : matches) {
    const Watched &w = kv.second;
    ms.push_back({{"match", kv.first}, {"hits", w.hits}, {"dead_hits", w.dead_hits}, {"bounces", w.bounces},
                  {"nets", w.nets}, {"serves", w.serves}, {"points", w.points}, {"lets", w.lets},
                  {"score", {w.score[0], w.score[1]}}, {"pauses", w.pauses}, {"resumes", w.resumes},
                  {"events_missed", w.events_missed}, {"states", w.states}, {"states_checked", w.checked},
                  {"states_unmatched", w.unmatched}, {"max_error", w.max_error}, {"frames", w.frames},
                  {"snapshots", w.snapshots},
                  {"segments", w.segments.empty() ? 0 : w.segments.rbegin()->first}});
  }
  sum["matches"] = ms;
  json sv = json::array();
  for (auto &kv : servers) {
    const StatusOut &o = kv.second;
    json drops = json::object();
    uint64_t dropped = 0;
    for (int i = 0; i < kDropReasons; ++i) {
      dropped += o.drops[i];
      if (o.drops[i]) drops[name_of(static_cast<SampleResult>(i))] = o.drops[i];
    }
    sv.push_back({{"server", o.server_id}, {"samples_in", o.samples_in}, {"samples_ok", o.samples_ok},
                  {"dropped", dropped}, {"drops", drops}, {"overruns", o.overruns}, {"frames", o.frames}});
  }
  sum["servers"] = sv;
  sum["latency_p50"] = latency.quantile(0.5);
  sum["latency_p99"] = latency.quantile(0.99);
  sum["latency_server_p50"] = latency_server.quantile(0.5);
  sum["latency_server_p99"] = latency_server.quantile(0.99);
  sum["latency_count"] = latency.size();
  log({{"type", "summary"}, {"summary", sum}});
  if (!quiet) {
    for (auto &kv : matches) {
      const Watched &w = kv.second;
      std::printf("summary: match %u: %" PRIu64 " hits, %" PRIu64 " bounces, %" PRIu64 " serves, %" PRIu64
                  " points (score %d-%d), %" PRIu64 " pauses; desync: %" PRIu64 " of %" PRIu64
                  " ball states checked, max |error| %.3g m\n",
                  kv.first, w.hits, w.bounces, w.serves, w.points, w.score[0], w.score[1], w.pauses, w.checked,
                  w.states, w.max_error);
    }
    for (auto &kv : servers) {
      const StatusOut &o = kv.second;
      std::printf("summary: server %u: %" PRIu64 " racket samples in, %" PRIu64 " accepted, dropped %s, %" PRIu64
                  " frame overruns\n",
                  o.server_id, o.samples_in, o.samples_ok, drops_text(o.drops).c_str(), o.overruns);
    }
    std::printf("summary: sample-to-segment latency (a hit's newest racket sample written -> its segment "
                "received): p50 %.1f ms, p99 %.1f ms over %zu hits\n",
                latency.quantile(0.5) * 1e3, latency.quantile(0.99) * 1e3, latency.size());
  }
  if (!summary_json.empty()) std::ofstream(summary_json) << sum.dump(1) << "\n";
  if (rec.is_open()) rec.close();
  dds::set_exit_status_if_stuck(0);  // all is written: a stuck DDS teardown still ends well (domain.h)
  return 0;
}
