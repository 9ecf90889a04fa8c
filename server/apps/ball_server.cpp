// ball-server: many matches in one process over Fast DDS (docs/server.md).
// One loop on one thread owns every match: at each match's absolute frame
// deadline it takes the racket samples and control messages that arrived,
// steps the match, and publishes segments, events, ball states and match
// info; once a second it prints the status line.
#include <CLI/CLI.hpp>
#include <cinttypes>
#include <cstdio>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>

#include "common.h"
#include "config.h"
#include "domain.h"
#include "host.h"

using namespace ballsrv;
using namespace ballsrv::app;

namespace {

const char *kProgram = "ball-server";

// The loop's counters, printed as the status line and published as ServerStatus.
struct Stats {
  uint64_t samples_in = 0, samples_ok = 0, samples_idle = 0;
  std::array<uint64_t, kDropSlots> drops{};
  uint64_t controls_in = 0, controls_refused = 0;
  uint64_t states_out = 0, segments_out = 0, events_out = 0, infos_out = 0;
  uint64_t frames = 0, overruns = 0, skipped = 0;
  uint64_t deadline_missed = 0, writers_lost = 0;
  uint64_t conflicts = 0;   // MatchInfo of one of our matches from another participant
  Percentiles frame_time;   // s of work per wake-up, this status period
  Percentiles late;         // s a frame started after its deadline, this status period
  Percentiles late_p99;     // each period's p99 of that, over the run
  double late_max = 0.0;    // s, over the run
  Percentiles latency;      // s from a racket sample's write to its segment's, this period
  Percentiles latency_all;  // the same over the run
};

// A match with its schedule.
struct Scheduled {
  Match *match;
  FrameClock clock;
  uint64_t k = 0;               // next frame index
  double last_frame_real = 0.0; // realtime of the newest frame's deadline
  double next_info = 0.0;       // mono s of the next periodic MatchInfo
  uint32_t revision = 0;
};

// Every match's frames count from the server's start, so matches of the
// same frame rate are stepped on the same wake-ups.
Scheduled scheduled(Match *m, const FrameClock &origin) {
  Scheduled s{m, FrameClock(m->frame_time(), origin)};
  double now = mono_now();
  s.k = s.clock.first_at(now);
  s.last_frame_real = s.clock.realtime_at(now);
  return s;
}

struct Writers {
  dds::Writer<SegmentOut> segments;
  dds::Writer<EventOut> events;
  dds::Writer<StateOut> states;
  dds::Writer<MatchInfoOut> infos;
  dds::Writer<StatusOut> status;
};

void publish(const MatchOutput &out, Scheduled &s, uint32_t server_id, double now_real, Writers &w, Stats &st) {
  for (SegmentOut seg : out.segments) {
    seg.server_id = server_id;
    seg.server_time = now_real;
    w.segments.write(seg);
    st.segments_out++;
    if (seg.cause == Cause::racket && seg.sample.valid && seg.sample.source_time > 0.0) {
      double lat = now_real - seg.sample.source_time;
      st.latency.add(lat);
      st.latency_all.add(lat);
    }
  }
  for (EventOut e : out.events) {
    e.server_id = server_id;
    e.server_time = now_real;
    w.events.write(e);
    st.events_out++;
  }
  if (out.has_state) {
    StateOut state = out.state;
    state.server_id = server_id;
    state.server_time = s.last_frame_real;
    w.states.write(state);
    st.states_out++;
  }
}

void publish_info(Scheduled &s, uint32_t server_id, Writers &w, Stats &st) {
  MatchInfoOut info = s.match->info();
  info.server_id = server_id;
  info.server_time = s.last_frame_real;  // sim_time holds from the newest frame's deadline
  info.revision = ++s.revision;
  w.infos.write(info);
  st.infos_out++;
}

StatusOut status_of(const Stats &st, const Host &host, uint32_t server_id, double uptime) {
  StatusOut o;
  o.server_id = server_id;
  o.server_time = realtime_now();
  o.uptime = uptime;
  o.matches = static_cast<uint32_t>(host.matches().size());
  for (const auto &m : host.matches()) o.playing += m->state() == MatchState::playing;
  o.samples_in = st.samples_in;
  o.samples_ok = st.samples_ok;
  o.drops = st.drops;
  o.controls_in = st.controls_in;
  o.controls_refused = st.controls_refused;
  o.states_out = st.states_out;
  o.segments_out = st.segments_out;
  o.events_out = st.events_out;
  o.frames = st.frames;
  o.overruns = st.overruns;
  o.frame_p50 = st.frame_time.quantile(0.5);
  o.frame_p99 = st.frame_time.quantile(0.99);
  return o;
}

void print_status(const StatusOut &o, const Stats &st) {
  std::printf("%s %u: %.0f s, matches %u (%u playing), samples in %" PRIu64 " ok %" PRIu64 " idle %" PRIu64
              ", drops %s, out %" PRIu64 " states %" PRIu64 " segments %" PRIu64
              " events, overruns %" PRIu64 ", frame p50 %.3f ms p99 %.3f ms, latency p50 %.1f ms p99 %.1f ms\n",
              kProgram, o.server_id, o.uptime, o.matches, o.playing, o.samples_in, o.samples_ok, st.samples_idle,
              drops_text(o.drops).c_str(), o.states_out, o.segments_out, o.events_out, o.overruns,
              o.frame_p50 * 1e3, o.frame_p99 * 1e3,
              st.latency.quantile(0.5) * 1e3, st.latency.quantile(0.99) * 1e3);
  std::fflush(stdout);
}

bool write_stats_json(const std::string &path, const StatusOut &o, const Stats &st, const Host &host) {
  nlohmann::json j;
  j["server_id"] = o.server_id;
  j["uptime"] = o.uptime;
  j["samples_in"] = o.samples_in;
  j["samples_ok"] = o.samples_ok;
  j["samples_idle"] = st.samples_idle;
  nlohmann::json drops = nlohmann::json::object();
  for (int i = 0; i < kDropReasons; ++i) drops[name_of(static_cast<SampleResult>(i))] = o.drops[i];
  j["drops"] = drops;
  j["controls_in"] = o.controls_in;
  j["controls_refused"] = o.controls_refused;
  j["states_out"] = o.states_out;
  j["segments_out"] = o.segments_out;
  j["events_out"] = o.events_out;
  j["frames"] = o.frames;
  j["overruns"] = o.overruns;
  j["skipped_frames"] = st.skipped;
  // the absolute frame clock: how late frames start (each status period's p99, then its median and max)
  j["late_p99_median"] = st.late_p99.quantile(0.5);
  j["late_p99_max"] = st.late_p99.max();
  j["late_max"] = st.late_max;
  j["deadline_missed"] = st.deadline_missed;
  j["writers_lost"] = st.writers_lost;
  j["conflicts"] = st.conflicts;
  j["latency_p50"] = st.latency_all.quantile(0.5);
  j["latency_p99"] = st.latency_all.quantile(0.99);
  j["latency_count"] = st.latency_all.size();
  nlohmann::json matches = nlohmann::json::array();
  for (const auto &m : host.matches()) {
    const MatchCounters &c = m->counters();
    matches.push_back({{"id", m->id()}, {"state", name_of(m->state())}, {"frames", c.frames},
                       {"hits", c.hits}, {"bounces", c.bounces}, {"points", c.points}, {"serves", c.serves},
                       {"pauses", c.pauses}, {"lets", c.lets}, {"score", {m->score()[0], m->score()[1]}},
                       {"sim_time", m->sim().time}, {"sim_hash", ball_sim_hash(&m->sim())}});
  }
  j["matches"] = matches;
  std::ofstream f(path);
  f << j.dump(1) << "\n";
  return static_cast<bool>(f);
}

}  // namespace

int main(int argc, char **argv) {
  CLI::App cli{"ball-server: a ball server hosting many matches over Fast DDS (docs/server.md).\n"
               "Command-line settings override the config file's defaults; without a\n"
               "config file or --matches it hosts one match on the default tennis scene."};
  std::string stats_json;
  double duration = 0.0;
  bool quiet = false;
  ServerOptions opt;
  opt.add(cli);
  cli.add_option("--duration", duration, "stop after S real seconds (0: run until SIGINT/SIGTERM)")
      ->check(CLI::Range(0.0, 1e9));
  cli.add_option("--stats-json", stats_json, "write the final counters to FILE as JSON");
  cli.add_flag("--quiet,-q", quiet, "no status line");
  CLI11_PARSE(cli, argc, argv);
  if (!opt.keys.empty()) {
    std::fputs(keys_table(opt.keys).c_str(), stdout);
    return 0;
  }

  ServerConfig config;
  std::string err;
  if (!opt.config_file.empty() && !load_config_file(opt.config_file, &config, &err)) return fail(kProgram, err);
  if (!opt.apply(&config, &err)) return fail(kProgram, err);

  // every scene is read before DDS is touched: a bad config fails fast
  std::map<std::string, ball_scene> catalogue;
  for (const auto &c : config.catalogue)
    if (!load_scene(c.second, &catalogue[c.first], &err)) return fail(kProgram, "catalogue \"" + c.first + "\": " + err);
  std::vector<ball_scene> scenes(config.matches.size());
  for (size_t i = 0; i < config.matches.size(); ++i)
    if (!load_scene(config.matches[i].scene, &scenes[i], &err)) return fail(kProgram, err);

  install_stop_signals();
  std::string profile = find_profile(config.profile);
  auto domain = dds::Domain::open(config.domain, profile, config.participant,
                                  "ball-server " + std::to_string(config.server_id), &err);
  if (!domain) return fail(kProgram, err);
  // the player timeout is the deadline the racket samples reader requests
  double deadline = domain->reader_deadline(dds::kRacketProfile);
  if (deadline > 0.0) config.defaults.player_timeout = deadline;

  Host host(config.max_matches, config.allow_create, config.defaults);
  for (const auto &c : catalogue)
    if (!host.add_scene(c.first, c.second, &err)) return fail(kProgram, err);
  for (size_t i = 0; i < config.matches.size(); ++i) {
    MatchEntry &e = config.matches[i];
    const ball_scene &sc = scenes[i];
    if (deadline > 0.0) e.config.player_timeout = deadline;
    if (e.scene != "default" && !sc.name[0]) e.config.scene_name = e.scene.substr(0, kNameLen - 1);
    else e.config.scene_name = sc.name[0] ? sc.name : "tennis";
    if (!host.add_match(e.config, sc, &err))
      return fail(kProgram, "match " + std::to_string(e.config.id) + " (" + e.scene + "): " + err);
  }

  // endpoints sized for max_matches x players (DESIGN.md 6: 10 instances by default)
  int match_room = static_cast<int>(config.max_matches);
  int sample_room = match_room * std::max(1, host.max_players()) + 64;  // + room for junk keys
  Writers w;
  w.segments = domain->writer<SegmentOut>(dds::kSegmentTopic, dds::kSegmentProfile, {match_room}, &err);
  if (w.segments.valid()) w.events = domain->writer<EventOut>(dds::kEventTopic, dds::kEventProfile, {match_room}, &err);
  if (w.events.valid()) w.states = domain->writer<StateOut>(dds::kStateTopic, dds::kStateProfile, {match_room}, &err);
  if (w.states.valid()) w.infos = domain->writer<MatchInfoOut>(dds::kInfoTopic, dds::kInfoProfile, {match_room}, &err);
  if (w.infos.valid()) w.status = domain->writer<StatusOut>(dds::kStatusTopic, dds::kStatusProfile, {1}, &err);
  auto samples = domain->reader<RacketSampleIn>(dds::kRacketTopic, dds::kRacketProfile, {sample_room}, &err);
  auto controls = domain->reader<ControlIn>(dds::kControlTopic, dds::kControlProfile, {match_room + 64}, &err);
  auto others = domain->reader<MatchInfoOut>(dds::kInfoTopic, dds::kInfoProfile, {match_room + 64}, &err);
  if (!w.status.valid() || !samples.valid() || !controls.valid() || !others.valid()) return fail(kProgram, err);

  Stats st;
  // another server already serving one of our matches makes the domain busy
  if (config.startup_wait > 0.0) {
    double until = mono_now() + config.startup_wait;
    while (mono_now() < until && !stop_requested()) {
      MatchInfoOut info;
      dds::SampleMeta meta;
      while (others.take(&info, &meta)) {
        if (meta.from != domain->id() && host.find(info.match_id))
          return fail(kProgram, "domain " + std::to_string(config.domain) + " is busy: match " +
                                    std::to_string(info.match_id) + " is served by server " +
                                    std::to_string(info.server_id));
      }
      sleep_until(mono_now() + 0.05);
    }
  }
  // later conflicts (another server started without looking) are reported once a second
  auto check_conflicts = [&]() {
    MatchInfoOut info;
    dds::SampleMeta meta;
    while (others.take(&info, &meta))
      if (meta.from != domain->id() && host.find(info.match_id)) {
        st.conflicts++;
        std::fprintf(stderr, "%s %u: warning: match %u is also served by server %u (participant %s)\n", kProgram,
                     config.server_id, info.match_id, info.server_id, hex(meta.from).c_str());
      }
  };

  std::vector<Scheduled> sched;
  const FrameClock origin(1.0);
  for (const auto &m : host.matches()) {
    sched.push_back(scheduled(m.get(), origin));
    publish_info(sched.back(), config.server_id, w, st);
  }
  if (!quiet)
    std::printf("%s %u: %zu matches on domain %d (profile %s, participant %s), player timeout %.2f s, room for %u matches\n",
                kProgram, config.server_id, host.matches().size(), config.domain, profile.c_str(),
                hex(domain->id()).c_str(), config.defaults.player_timeout, config.max_matches);
  std::fflush(stdout);

  const double start = mono_now();
  double next_status = start + config.status_interval;
  std::vector<dds::StatusNote> notes;
  MatchOutput out;
  while (!stop_requested()) {
    if (duration > 0.0 && mono_now() - start >= duration) break;
    double wake = next_status;
    for (const auto &s : sched) wake = std::min(wake, s.clock.deadline(s.k));
    sleep_until(wake);
    if (stop_requested()) break;
    double t0 = mono_now();
    double now_real = realtime_now();

    // what the DDS threads saw: writers gone or not alive any more
    notes.clear();
    samples.drain_status(&notes);
    for (const auto &n : notes) {
      if (n.kind == dds::StatusNote::writer_lost) {
        host.on_participant_lost(n.who);
        st.writers_lost++;
      } else if (n.kind == dds::StatusNote::deadline_missed) {
        st.deadline_missed += static_cast<uint64_t>(n.count);
      } else if (n.kind == dds::StatusNote::rejected || n.kind == dds::StatusNote::samples_lost) {
        // refused by the reader or lost on the link: counted in and dropped, so that
        // samples_in = samples_ok + idle + every drop (docs/protocol.md)
        SampleResult why = n.kind == dds::StatusNote::rejected ? SampleResult::rejected : SampleResult::lost;
        st.drops[static_cast<int>(why)] += static_cast<uint64_t>(n.count);
        st.samples_in += static_cast<uint64_t>(n.count);
      }
    }
    // every racket sample that came in
    RacketSampleIn sample;
    dds::SampleMeta meta;
    while (samples.take(&sample, &meta)) {
      sample.from = meta.from;
      sample.source_time = meta.source_time;
      st.samples_in++;
      SampleResult r = host.on_sample(sample, now_real);
      if (r == SampleResult::accepted) st.samples_ok++;
      else if (r == SampleResult::idle) st.samples_idle++;
      else st.drops[static_cast<int>(r)]++;
    }
    // control messages
    ControlIn control;
    while (controls.take(&control, &meta)) {
      control.from = meta.from;
      st.controls_in++;
      if (!control.valid) {
        st.controls_refused++;
        continue;
      }
      out.clear();
      Match *m = nullptr;
      size_t before = host.matches().size();
      Reason r = host.on_control(control, now_real, &out, &m);
      if (r != Reason::none) st.controls_refused++;
      if (host.matches().size() > before) sched.push_back(scheduled(host.matches().back().get(), origin));  // CREATE
      if (!m) continue;
      for (auto &s : sched)
        if (s.match == m) {
          publish(out, s, config.server_id, now_real, w, st);
          if (out.info_changed) publish_info(s, config.server_id, w, st);
        }
    }
    // the frames that are due
    for (auto &s : sched) {
      double d = s.clock.deadline(s.k);
      if (d > t0 + 1e-6) continue;
      // more than 5 frames behind (the machine stalled): skip to now rather than race
      double behind = (t0 - d) / s.clock.period();
      if (behind > 5.0) {
        uint64_t skip = static_cast<uint64_t>(behind);
        s.k += skip;
        st.skipped += skip;
        d = s.clock.deadline(s.k);
      }
      s.last_frame_real = s.clock.realtime_at(d);
      st.late.add(t0 - d);
      st.late_max = std::max(st.late_max, t0 - d);
      out.clear();
      s.match->frame(now_real, &out);
      s.k++;
      st.frames++;
      publish(out, s, config.server_id, now_real, w, st);
      if (out.info_changed || t0 >= s.next_info) {
        publish_info(s, config.server_id, w, st);
        s.next_info = t0 + 1.0;
      }
      // an overrun: the frame was done only after the next one was due
      if (mono_now() > s.clock.deadline(s.k)) st.overruns++;
    }
    double t1 = mono_now();
    st.frame_time.add(t1 - t0);
    if (t1 >= next_status) {
      check_conflicts();
      StatusOut o = status_of(st, host, config.server_id, t1 - start);
      w.status.write(o);
      if (!quiet) print_status(o, st);
      st.frame_time.clear();
      st.latency.clear();
      st.late_p99.add(st.late.quantile(0.99));
      st.late.clear();
      next_status += config.status_interval;
      if (next_status < t1) next_status = t1 + config.status_interval;
    }
  }

  StatusOut o = status_of(st, host, config.server_id, mono_now() - start);
  w.status.write(o);
  if (!quiet) {
    print_status(o, st);
    std::printf("%s %u: stopped\n", kProgram, config.server_id);
  }
  if (!stats_json.empty() && !write_stats_json(stats_json, o, st, host))
    return fail(kProgram, "cannot write " + stats_json);
  dds::set_exit_status_if_stuck(0);  // all is written: a stuck DDS teardown still ends well (domain.h)
  return 0;  // the Domain deletes every entity, in reverse order, as it goes
}
