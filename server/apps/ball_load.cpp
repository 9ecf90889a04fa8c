// ball-load: the load generator and benchmark (docs/server.md, "Load").
// One process plays both slots of many matches (a PlayerGroup of
// BotPlayers, one DDS participant for all) against a ball-server, and
// measures what a player sees: racket hits, and the sample-to-segment
// latency (a hit's newest racket sample written -> the hit's segment
// received). With --sweep it starts a ball-server for each match count
// itself and prints a table: matches against frame overruns and latency.
#include <sys/stat.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cinttypes>
#include <cstdio>
#include <functional>

#include "client_endpoints.h"
#include "common.h"
#include "options.h"
#include "player_group.h"
#include "process.h"

using namespace ballsrv;
using namespace ballsrv::app;

namespace {

const char *kProgram = "ball-load";
constexpr double kTick = 0.002;  // s

struct Options {
  int matches = 10;
  PlayerParams bot;        // every bot's settings (match, slot and seed are each bot's own)
  double warmup = 4.0;     // s for every slot to be joined and the rallies to start
  double duration = 10.0;  // s measured
  DdsOptions dds;
};

// Plays every slot of matches 0..n-1 for warmup + duration s; hands the
// row to `done` while the participant still lives (its teardown may be the
// one that sticks: dds::run_bounded).
bool drive(const Options &o, const std::function<void(const LoadRow &)> &done, std::string *err) {
  ball_scene scene;
  ball_scene_default(&scene);
  auto domain = dds::Domain::open(o.dds.domain, find_profile(o.dds.profile), o.dds.participant,
                                  o.dds.discovery_server, "ball-load", err);
  if (!domain) return false;
  int room = std::max(o.matches, dds::kClientRoom);
  auto port = dds::ClientEndpoints::open(*domain, {room * 2, room, room, false, true}, err);
  if (!port) return false;
  std::vector<BotPlayer> bots;
  for (int m = 0; m < o.matches; ++m)
    for (int slot = 0; slot < 2; ++slot) {
      PlayerParams p = o.bot;
      p.match = static_cast<uint32_t>(m);
      p.player = slot;
      p.seed = o.bot.seed + static_cast<uint64_t>(m * 2 + slot);
      bots.emplace_back(scene, domain->id(), p);
    }
  PlayerGroup group(std::move(bots));
  LoadRow row;
  Percentiles latency, frame_p50, frame_p99;  // the server's per-second values
  StatusOut first{}, last{};
  bool have_first = false, measuring = false;
  const double start = mono_now();
  double window_start = -1.0, window_end = 0.0, samples_before = 0.0;
  for (double next_tick = start; !stop_requested(); sleep_until(next_tick)) {
    double now = mono_now(), real = realtime_now();
    if (window_start < 0.0 && (group.all_joined() || now - start > o.warmup * 3)) {
      row.ready = group.all_joined();
      window_start = std::max(now, start + o.warmup);
      window_end = window_start + o.duration;
    } else if (window_start > 0.0 && now >= window_end) {
      break;
    }
    if (!measuring && window_start > 0.0 && now >= window_start) {
      measuring = true;
      samples_before = static_cast<double>(group.samples_written());
    }
    bool ok = group.tick(*port, now, real, [&](const SegmentOut &seg, double recv) {
      if (!measuring || seg.cause != Cause::racket || !seg.sample.valid) return;
      row.hits++;
      latency.add(recv - seg.sample.source_time);
    });
    if (!ok) {
      *err = group.error();
      return false;
    }
    StatusOut so;
    while (port->take(&so)) {
      if (!measuring) continue;
      if (!have_first) first = so;
      have_first = true;
      last = so;
      frame_p50.add(so.frame_p50);
      frame_p99.add(so.frame_p99);
    }
    next_tick += kTick;
    if (next_tick < now) next_tick = now + kTick;
  }
  row.matches = o.matches;
  row.bots = o.matches * 2;
  row.rate = o.bot.rate;
  row.seconds = mono_now() - window_start;
  row.samples_per_s = (static_cast<double>(group.samples_written()) - samples_before) / std::max(row.seconds, 1e-9);
  row.write_failures = group.write_failures();
  row.latency_p50_ms = latency.quantile(0.5) * 1e3;
  row.latency_p99_ms = latency.quantile(0.99) * 1e3;
  row.server_frames = last.frames - first.frames;
  row.server_overruns = last.overruns - first.overruns;
  row.frame_p50_ms = frame_p50.quantile(0.5) * 1e3;
  row.frame_p99_ms_median = frame_p99.quantile(0.5) * 1e3;
  row.frame_p99_ms_max = frame_p99.max() * 1e3;
  row.playing = last.playing;
  group.leave(*port);
  sleep_until(mono_now() + 0.3);  // the LEAVEs get out before the participant goes
  done(row);
  return true;
}

void print_row(const LoadRow &r) {
  double pct = r.server_frames ? 100.0 * static_cast<double>(r.server_overruns) / static_cast<double>(r.server_frames) : 0.0;
  std::printf("%8d %6d %9.0f %6" PRIu64 " %8.1f %8.1f %9" PRIu64 " %9" PRIu64 " %7.2f%% %9.3f %9.3f %9.3f%s%s\n",
              r.matches, r.bots, r.samples_per_s, r.hits, r.latency_p50_ms, r.latency_p99_ms, r.server_frames,
              r.server_overruns, pct, r.frame_p50_ms, r.frame_p99_ms_median, r.frame_p99_ms_max,
              r.ready ? "" : "  (not every slot joined)", r.write_failures ? "  (writes refused)" : "");
  std::fflush(stdout);
}

void print_header(const Options &o) {
  std::printf("bots at %g Hz, %g s measured after %g s of warm-up; latency: a hit's newest racket sample "
              "written -> its segment received; frame: the server's work per wake-up (median of its per-second "
              "p50, median and max of its per-second p99)\n",
              o.bot.rate, o.duration, o.warmup);
  const char *columns[] = {"matches", "bots", "samples/s", "hits", "lat p50", "lat p99", "frames",
                           "overruns", "overrun", "work p50", "p99 med", "p99 max"};
  const char *units[] = {"", "", "", "", "ms", "ms", "", "", "", "ms", "ms", "ms"};
  for (const char *const *row : {columns, units}) {
    std::printf("%8s %6s %9s %6s %8s %8s %9s %9s %8s %9s %9s %9s\n", row[0], row[1], row[2], row[3], row[4], row[5],
                row[6], row[7], row[8], row[9], row[10], row[11]);
  }
}

}  // namespace

int main(int argc, char **argv) {
  CLI::App cli{"ball-load: many bots in one process against ball-server; with --sweep, the load benchmark"};
  Options o;
  std::vector<int> sweep;
  std::string json_out, err;
  double frame_rate = 60.0, state_rate = 10.0;
  o.dds.domain = BALL_BENCH_DOMAIN;  // docs/server.md, "DDS domains"
  FieldOptions<PlayerParams> bot_opt;
  cli.add_option("--matches", o.matches, "matches to play (both slots of matches 0..N-1)")->capture_default_str()
      ->check(CLI::Range(1, 100000));
  bot_opt.add(cli, player_fields(), o.bot, {"rate", "seed"});
  cli.add_option("--warmup", o.warmup, "s before measuring")->capture_default_str();
  cli.add_option("--duration", o.duration, "s measured")->capture_default_str();
  cli.add_option("--sweep", sweep, "match counts: start a ball-server for each and measure")->delimiter(',');
  cli.add_option("--frame-rate", frame_rate, "with --sweep: the server's frame rate")->capture_default_str();
  cli.add_option("--state-rate", state_rate, "with --sweep: the server's ball state rate")->capture_default_str();
  cli.add_option("--json", json_out, "write the results to FILE as JSON");
  add_dds_options(cli, &o.dds);
  CLI11_PARSE(cli, argc, argv);
  bot_opt.apply(&o.bot);
  install_stop_signals();
  json all = json::array();
  bool written = true;  // every row is printed and in the JSON file as soon as it is measured
  auto record = [&](const LoadRow &r, bool last) {
    print_row(r);
    all.push_back(r);
    if (!json_out.empty()) written = write_file(json_out, all.dump(1), &err) && written;
    if (last && written) dds::set_exit_status_if_stuck(0);  // all is written (domain.h)
  };
  if (sweep.empty()) {
    print_header(o);
    if (!drive(o, [&](const LoadRow &r) { record(r, true); }, &err)) return fail(kProgram, err);
  } else {
    print_header(o);
    char dir_template[] = "/tmp/ball-load-XXXXXX";
    if (!mkdtemp(dir_template)) return fail(kProgram, "cannot make a temporary directory");
    std::string dir = dir_template;
    for (size_t i = 0; i < sweep.size() && !stop_requested(); ++i) {
      Options run = o;
      run.matches = sweep[i];
      std::vector<std::string> args = {program_dir() + "/ball-server", "--matches", std::to_string(run.matches),
                                       "--frame-rate", std::to_string(frame_rate), "--state-rate",
                                       std::to_string(state_rate), "--startup-wait", "0", "--quiet"};
      for (const std::string &a : dds_arguments(o.dds)) args.push_back(a);  // the server on our participant profile
      Process server = Process::start(args, dir + "/server.out", dir + "/server.err");
      bool ok = drive(run, [&](const LoadRow &r) { record(r, i + 1 == sweep.size()); }, &err);
      server.stop(5.0);
      if (!ok) return fail(kProgram, err);
    }
    for (const char *f : {"server.out", "server.err"}) unlink((dir + "/" + f).c_str());
    rmdir(dir.c_str());
  }
  if (!json_out.empty() && !write_file(json_out, all.dump(1), &err)) return fail(kProgram, err);  // also with no row
  return written ? 0 : fail(kProgram, err);
}
