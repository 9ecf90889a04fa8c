// ball-load: the load generator and benchmark (docs/server.md, "Load").
// One process plays both slots of many matches (BotPlayer each, one DDS
// participant for all) against a ball-server, and measures what a player
// sees: racket hits, and the sample-to-segment latency (a hit's newest
// racket sample written -> the hit's segment received). With --sweep it
// starts a ball-server for each match count itself and prints a table:
// matches against frame overruns and latency.
#include <sys/stat.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cinttypes>
#include <cstdio>
#include <fstream>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>

#include "common.h"
#include "domain.h"
#include "player.h"
#include "process.h"

using namespace ballsrv;
using namespace ballsrv::app;
using json = nlohmann::json;

namespace {

const char *kProgram = "ball-load";
constexpr double kTick = 0.002;  // s

struct Options {
  int matches = 10;
  double rate = 30.0;
  double warmup = 4.0;    // s for every slot to be joined and the rallies to start
  double duration = 10.0; // s measured
  uint64_t seed = 1;
  DdsOptions dds;
};

struct Result {
  int matches = 0;
  bool ready = false;         // every slot joined within the warm-up
  double seconds = 0.0;
  uint64_t samples = 0, hits = 0;
  Percentiles latency;
  uint64_t frames = 0, overruns = 0;  // the server's, over the window
  Percentiles frame_p50, frame_p99;   // the server's per-second values
  uint32_t playing = 0;
};

// Plays every slot of matches 0..n-1 for warmup + duration s; hands the
// result to `done` while the participant still lives (its teardown may be
// the one that sticks: dds::run_bounded).
bool drive(const Options &o, const std::function<void(const Result &)> &done, std::string *err) {
  Result result;
  Result *r = &result;
  ball_scene scene;
  ball_scene_default(&scene);
  auto domain = dds::Domain::open(o.dds.domain, find_profile(o.dds.profile), o.dds.participant, "ball-load", err);
  if (!domain) return false;
  int room = std::max(o.matches, dds::kClientRoom);
  auto samples = domain->writer<RacketSampleIn>(dds::kRacketTopic, dds::kRacketProfile, {room * 2}, err);
  auto controls = domain->writer<ControlIn>(dds::kControlTopic, dds::kControlProfile, {room}, err);
  auto segments = domain->reader<SegmentOut>(dds::kSegmentTopic, dds::kSegmentProfile, {room}, err);
  auto infos = domain->reader<MatchInfoOut>(dds::kInfoTopic, dds::kInfoProfile, {room}, err);
  auto states = domain->reader<StateOut>(dds::kStateTopic, dds::kStateProfile, {room}, err);
  auto status = domain->reader<StatusOut>(dds::kStatusTopic, dds::kStatusProfile, {4}, err);
  if (!samples.valid() || !controls.valid() || !segments.valid() || !infos.valid() || !states.valid() ||
      !status.valid())
    return false;
  std::vector<BotPlayer> bots;
  bots.reserve(static_cast<size_t>(o.matches) * 2);
  std::map<uint32_t, std::vector<BotPlayer *>> by_match;
  for (int m = 0; m < o.matches; ++m)
    for (int slot = 0; slot < 2; ++slot) {
      PlayerParams p;
      p.match = static_cast<uint32_t>(m);
      p.player = slot;
      p.rate = o.rate;
      p.seed = o.seed + static_cast<uint64_t>(m * 2 + slot);
      bots.emplace_back(scene, domain->id(), p);
    }
  for (size_t i = 0; i < bots.size(); ++i) by_match[static_cast<uint32_t>(i / 2)].push_back(&bots[i]);

  std::vector<RacketSampleIn> out_samples;
  std::vector<ControlIn> out_controls;
  const double start = mono_now();
  double window_start = -1.0, window_end = 0.0, next_tick = start;
  StatusOut first{}, last{};
  bool have_first = false;
  while (!stop_requested()) {
    double now = mono_now(), real = realtime_now();
    if (window_start < 0.0) {
      bool all = true;
      for (auto &b : bots) all = all && b.joined();
      if (all || now - start > o.warmup * 3) {
        r->ready = all;
        window_start = std::max(now, start + o.warmup);
        window_end = window_start + o.duration;
      }
    } else if (now >= window_end) {
      break;
    }
    bool measuring = window_start > 0.0 && now >= window_start;
    MatchInfoOut info;
    while (infos.take(&info, nullptr)) {
      auto it = by_match.find(info.match_id);
      if (it == by_match.end()) continue;
      for (BotPlayer *b : it->second)
        if (!b->on_info(info, real)) {
          *err = b->error();
          return false;
        }
    }
    StateOut st;
    while (states.take(&st, nullptr)) {
      auto it = by_match.find(st.match_id);
      if (it != by_match.end())
        for (BotPlayer *b : it->second) b->on_state(st, real);
    }
    SegmentOut seg;
    while (segments.take(&seg, nullptr)) {
      auto it = by_match.find(seg.match_id);
      if (it == by_match.end()) continue;
      for (BotPlayer *b : it->second) b->on_segment(seg, real);
      if (measuring && seg.cause == Cause::racket && seg.sample.valid) {
        r->hits++;
        r->latency.add(real - seg.sample.source_time);
      }
    }
    StatusOut so;
    while (status.take(&so, nullptr)) {
      if (!measuring) continue;
      if (!have_first) {
        first = so;
        have_first = true;
      }
      last = so;
      r->frame_p50.add(so.frame_p50);
      r->frame_p99.add(so.frame_p99);
    }
    out_samples.clear();
    out_controls.clear();
    for (auto &b : bots) b.tick(now, real, &out_samples, &out_controls);
    for (const auto &c : out_controls) controls.write(c);
    for (const auto &s : out_samples) samples.write(s);
    if (measuring) r->samples += out_samples.size();
    next_tick += kTick;
    if (next_tick < now) next_tick = now + kTick;
    sleep_until(next_tick);
  }
  r->matches = o.matches;
  r->seconds = mono_now() - window_start;
  r->frames = last.frames - first.frames;
  r->overruns = last.overruns - first.overruns;
  r->playing = last.playing;
  for (auto &b : bots) {
    ControlIn bye;
    if (b.leave(&bye)) controls.write(bye);
  }
  sleep_until(mono_now() + 0.3);  // the LEAVEs get out before the participant goes
  done(result);
  return true;
}

json to_json(const Result &r, const Options &o) {
  return {{"matches", r.matches},
          {"bots", r.matches * 2},
          {"rate", o.rate},
          {"ready", r.ready},
          {"seconds", r.seconds},
          {"samples_per_s", r.samples / std::max(r.seconds, 1e-9)},
          {"hits", r.hits},
          {"latency_p50_ms", r.latency.quantile(0.5) * 1e3},
          {"latency_p99_ms", r.latency.quantile(0.99) * 1e3},
          {"server_frames", r.frames},
          {"server_overruns", r.overruns},
          {"frame_p50_ms", r.frame_p50.quantile(0.5) * 1e3},
          {"frame_p99_ms_median", r.frame_p99.quantile(0.5) * 1e3},
          {"frame_p99_ms_max", r.frame_p99.max() * 1e3},
          {"playing", r.playing}};
}

void print_row(const Result &r) {
  double overrun_pct = r.frames ? 100.0 * static_cast<double>(r.overruns) / static_cast<double>(r.frames) : 0.0;
  std::printf("%8d %6d %9.0f %6" PRIu64 " %8.1f %8.1f %9" PRIu64 " %9" PRIu64 " %7.2f%% %9.3f %9.3f %9.3f%s\n",
              r.matches, r.matches * 2, r.samples / std::max(r.seconds, 1e-9), r.hits, r.latency.quantile(0.5) * 1e3,
              r.latency.quantile(0.99) * 1e3, r.frames, r.overruns, overrun_pct, r.frame_p50.quantile(0.5) * 1e3,
              r.frame_p99.quantile(0.5) * 1e3, r.frame_p99.max() * 1e3, r.ready ? "" : "  (not every slot joined)");
  std::fflush(stdout);
}

void print_header(const Options &o) {
  std::printf("bots at %g Hz, %g s measured after %g s of warm-up; latency: a hit's newest racket sample "
              "written -> its segment received; frame: the server's work per wake-up (median of its per-second "
              "p50, median and max of its per-second p99)\n",
              o.rate, o.duration, o.warmup);
  std::printf("%8s %6s %9s %6s %8s %8s %9s %9s %8s %9s %9s %9s\n", "matches", "bots", "samples/s", "hits",
              "lat p50", "lat p99", "frames", "overruns", "overrun", "work p50", "p99 med", "p99 max");
  std::printf("%8s %6s %9s %6s %8s %8s %9s %9s %8s %9s %9s %9s\n", "", "", "", "", "ms", "ms", "", "", "", "ms",
              "ms", "ms");
}

}  // namespace

int main(int argc, char **argv) {
  CLI::App cli{"ball-load: many bots in one process against ball-server; with --sweep, the load benchmark"};
  Options o;
  std::vector<int> sweep;
  std::string json_out;
  double frame_rate = 60.0, state_rate = 10.0;
  cli.add_option("--matches", o.matches, "matches to play (both slots of matches 0..N-1)")->capture_default_str()
      ->check(CLI::Range(1, 100000));
  cli.add_option("--rate", o.rate, "each bot's sample rate, Hz")->capture_default_str()->check(CLI::Range(2.0, 120.0));
  cli.add_option("--warmup", o.warmup, "s before measuring")->capture_default_str();
  cli.add_option("--duration", o.duration, "s measured")->capture_default_str();
  cli.add_option("--seed", o.seed, "seed of the bots")->capture_default_str();
  cli.add_option("--sweep", sweep, "match counts: start a ball-server for each and measure")->delimiter(',');
  cli.add_option("--frame-rate", frame_rate, "with --sweep: the server's frame rate")->capture_default_str();
  cli.add_option("--state-rate", state_rate, "with --sweep: the server's ball state rate")->capture_default_str();
  cli.add_option("--json", json_out, "write the results to FILE as JSON");
  add_dds_options(cli, &o.dds);
  CLI11_PARSE(cli, argc, argv);
  install_stop_signals();
  std::string err;
  json all = json::array();
  // every row is printed and in the JSON file as soon as it is measured
  auto record = [&](const Result &r, const Options &run, bool last) {
    print_row(r);
    all.push_back(to_json(r, run));
    if (!json_out.empty()) std::ofstream(json_out) << all.dump(1) << "\n";
    if (last) dds::set_exit_status_if_stuck(0);  // all is written (domain.h)
  };
  if (sweep.empty()) {
    auto done = [&](const Result &r) {
      print_header(o);
      record(r, o, true);
    };
    if (!drive(o, done, &err)) return fail(kProgram, err);
  } else {
    print_header(o);
    char dir_template[] = "/tmp/ball-load-XXXXXX";
    if (!mkdtemp(dir_template)) return fail(kProgram, "cannot make a temporary directory");
    std::string dir = dir_template;
    for (size_t i = 0; i < sweep.size(); ++i) {
      int n = sweep[i];
      if (stop_requested()) break;
      Options run = o;
      run.matches = n;
      Process server = Process::start({program_dir() + "/ball-server", "--domain", std::to_string(o.dds.domain),
                                       "--matches", std::to_string(n), "--frame-rate", std::to_string(frame_rate),
                                       "--state-rate", std::to_string(state_rate), "--startup-wait", "0", "--quiet",
                                       "--stats-json", dir + "/server.json"},
                                      dir + "/server.out", dir + "/server.err");
      bool ok = drive(run, [&](const Result &r) { record(r, run, i + 1 == sweep.size()); }, &err);
      server.stop(5.0);
      if (!ok) return fail(kProgram, err);
    }
    for (const char *f : {"server.json", "server.out", "server.err"}) unlink((dir + "/" + f).c_str());
    rmdir(dir.c_str());
  }
  if (!json_out.empty()) std::ofstream(json_out) << all.dump(1) << "\n";  // also when no row was measured
  return 0;
}
