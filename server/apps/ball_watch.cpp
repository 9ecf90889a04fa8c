// ball-watch: an observer (docs/server.md, "Watchers"). It prints the rally
// as it happens, records everything it receives to JSON Lines on request,
// evaluates the ball from the segments at its own frame rate (eq 3 on the
// client, with the flight model MatchInfo carries) and checks that ball
// against the server's ball states: the desync check. One loop, one thread.
#include <CLI/CLI.hpp>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>

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
};

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
      if (e.side < 0) std::snprintf(buf, sizeof buf, "let (%s): replayed", reason_name(e.reason));
      else
        std::snprintf(buf, sizeof buf, "point to the %s side (%s), score %d-%d", e.side == 0 ? "near" : "far",
                      reason_name(e.reason), e.score[0], e.score[1]);
      break;
    case EventKind::pause:
      std::snprintf(buf, sizeof buf, "pause: player %d %s", e.index, reason_name(e.reason));
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
  add_dds_options(cli, &dds_opt);
  CLI11_PARSE(cli, argc, argv);

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
            std::string("match ") + state_name(info.state) + " (" + info.scene + ", level " +
                ball_level_name(static_cast<ball_level>(info.level)) + ", " + std::to_string(info.players) +
                " players, server " + std::to_string(info.server_id) + ")");
      log({{"type", "match_info"}, {"recv", real}, {"match", info.match_id}, {"server", info.server_id},
           {"revision", info.revision}, {"state", state_name(info.state)}, {"scene", info.scene},
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
           {"cause", cause_name(seg.cause)}, {"index", seg.cause_index}, {"t0", seg.segment.t0},
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
      say(e.match_id, e.time, rally_line(e, w));
      log({{"type", "event"}, {"recv", real}, {"match", e.match_id}, {"server", e.server_id}, {"seq", e.seq},
           {"kind", event_name(e.kind)}, {"index", e.index}, {"side", e.side}, {"in_play", e.in_play},
           {"sound", e.sound}, {"time", e.time}, {"server_time", e.server_time}, {"point", vec(e.point)},
           {"velocity_in", vec(e.velocity_in)}, {"velocity_out", vec(e.velocity_out)},
           {"segment_seq", e.segment_seq}, {"reason", reason_name(e.reason)},
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
      if (o.drops[i]) drops[drop_name(static_cast<SampleResult>(i))] = o.drops[i];
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
  return 0;
}
