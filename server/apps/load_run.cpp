#include "load_run.h"

#include <sys/stat.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <functional>
#include <sstream>

#include "client_endpoints.h"
#include "load.h"
#include "open_client.h"
#include "player_group.h"
#include "process.h"

namespace ballsrv {
namespace app {

namespace {

const char *kProgram = "ball-load";
constexpr double kTick = 0.002;  // s between the bots' ticks

std::string read_text(const std::string &path) {
  std::ifstream f(path);
  std::stringstream s;
  s << f.rdbuf();
  return s.str();
}

// CPU and resident memory of some processes, and the loopback device's
// transmitted bytes and packets (every process's: loopback traffic is sent
// once and received once), at one instant.
struct Snapshot {
  double server_cpu = 0.0, server_rss = 0.0, bots_cpu = 0.0, bots_rss = 0.0;
  uint64_t lo_bytes = 0, lo_packets = 0;
  bool server = false, lo = false;
};

Snapshot snapshot(pid_t server, const std::vector<pid_t> &bots) {
  Snapshot s;
  double ticks = static_cast<double>(sysconf(_SC_CLK_TCK));
  auto usage = [&](pid_t pid, double *cpu, double *rss) {
    std::string dir = "/proc/" + std::to_string(pid);
    double c = 0.0, r = 0.0;
    bool ok = parse_proc_stat(read_text(dir + "/stat"), ticks, &c) && parse_proc_rss(read_text(dir + "/status"), &r);
    *cpu += c;
    *rss += r;
    return ok;
  };
  if (server > 0) s.server = usage(server, &s.server_cpu, &s.server_rss);
  for (pid_t b : bots) usage(b, &s.bots_cpu, &s.bots_rss);
  s.lo = parse_net_dev(read_text("/proc/net/dev"), "lo", &s.lo_bytes, &s.lo_packets);
  return s;
}

// The per-match figures of the two snapshots around a window of `seconds`.
void add_usage(const Snapshot &a, const Snapshot &b, double seconds, LoadRow *row) {
  double per = 1.0 / (std::max(1, row->matches) * seconds);
  if (a.server && b.server) {
    row->server_cpu_pct = 100.0 * (b.server_cpu - a.server_cpu) * per;
    row->server_rss_kib = b.server_rss / 1024.0 / std::max(1, row->matches);
  }
  row->bots_cpu_pct = 100.0 * (b.bots_cpu - a.bots_cpu) * per;
  row->bots_rss_kib = b.bots_rss / 1024.0 / std::max(1, row->matches);
  if (a.lo && b.lo) {
    row->lo_bytes = static_cast<double>(b.lo_bytes - a.lo_bytes) * per;
    row->lo_packets = static_cast<double>(b.lo_packets - a.lo_packets) * per;
  }
}

// Plays every slot of its matches over the warm-up and the window; hands
// the part to `done` while the client still lives (its teardown is the
// library's, bounded: ball_net_close), and calls at_window at the
// window's start and end. The bots play through one client of the client
// library (ball/net.h), as games do; its tap feeds the meter (load.h), which
// times the hits' segments by DDS's stamps and takes the server's statuses.
// The load's client, its tap feeding the meter; nullptr with err.
ball_net_client *open_load_client(const LoadOptions &o, LoadMeter *meter, std::string *err) {
  int room = std::max(o.first_match + o.matches, dds::kClientRoom);
  ball_net_client *client = open_client(o.dds, "ball-load", "", [&](ball_net_config *c) {
    set_link(o.bot, c);
    c->max_matches = room;
    c->ball_states = 1;  // the bots read the ball states the server writes (--state-rate): their cost is measured
    c->server_status = 1;  // (the meter's)
  }, err);
  if (client && ball_net_set_tap(client, LoadMeter::tap, meter) != BALL_OK) {
    *err = ball_net_message(client);
    ball_net_free(client);
    return nullptr;
  }
  return client;
}

// Two bots a match, each with a seed of its own.
std::vector<BotPlayer> load_bots(const LoadOptions &o) {
  std::vector<BotPlayer> bots;
  for (int m = o.first_match; m < o.first_match + o.matches; ++m)
    for (int slot = 0; slot < 2; ++slot) {
      PlayerParams p = o.bot;
      p.match = static_cast<uint32_t>(m);
      p.player = slot;
      p.seed = o.bot.seed + static_cast<uint64_t>(m * 2 + slot);
      bots.emplace_back(p);
    }
  return bots;
}

// What the bots and the meter had counted when the window began.
struct Baseline {
  uint64_t samples = 0, bytes = 0;
  PortCounts counts;
};

// The part's row and counts over the window of `seconds`.
void close_part(const LoadOptions &o, PlayerGroup &group, LoadMeter &meter, const Baseline &b, double seconds) {
  const WireSizes sizes = dds::wire_sizes();
  LoadPart &part = meter.part;
  LoadRow &row = part.row;
  row.matches = o.matches;
  row.bots = o.matches * 2;
  row.rate = o.bot.rate;
  row.seconds = seconds;
  row.samples_per_s = static_cast<double>(group.samples_written() - b.samples) / std::max(row.seconds, 1e-9);
  row.write_failures = group.write_failures();
  // the meter counted what the server wrote; the bots' writes are their client's counts
  part.counts = meter.counts() - b.counts;
  part.counts.samples_written = group.samples_written() - b.samples;
  uint64_t control_bytes = group.bytes_out() - b.bytes - part.counts.samples_written * sizes.sample;
  part.counts.controls_written = sizes.control > 0 ? control_bytes / sizes.control : 0;
}

bool drive(const LoadOptions &o, const std::function<void()> &at_window,
           const std::function<void(const LoadPart &)> &done, std::string *err) {
  LoadMeter meter(o.first_match, o.matches);
  ball_net_client *client = open_load_client(o, &meter, err);
  if (!client) return false;
  LoadPart &part = meter.part;
  bool refused = false;
  {
    PlayerGroup group(load_bots(o), client);
    const double start = mono_now();
    group.start_at(bot_starts(o.first_match, o.matches, o.bot.seed, stagger_of(o), start));
    double window_start = -1.0, window_end = 0.0;
    uint64_t samples_before = 0, bytes_before = 0;
    PortCounts counts_before;
    if (o.window_start >= 0.0) {  // the parent's window, on this process's monotonic clock
      window_start = start + (o.window_start - realtime_now());
      window_end = window_start + o.duration;
    }
    for (double next_tick = start; !stop_requested(); sleep_until(next_tick)) {
      double now = mono_now();
      if (window_start < 0.0 && (group.all_joined() || now - start > o.warmup * 3)) {
        window_start = std::max(now, start + o.warmup);
        window_end = window_start + o.duration;
      } else if (window_start > 0.0 && now >= window_end) {
        break;
      }
      if (!meter.measuring && window_start > 0.0 && now >= window_start) {
        meter.measuring = true;
        part.row.ready = group.all_joined();
        samples_before = group.samples_written();
        bytes_before = group.bytes_out();
        counts_before = meter.counts();
        if (at_window) at_window();
      }
      group.tick(now);
      if (!group.error().empty()) {
        *err = group.error();
        refused = true;
        break;
      }
      next_tick += kTick;
      if (next_tick < now) next_tick = now + kTick;
    }
    if (at_window) at_window();
    close_part(o, group, meter, Baseline{samples_before, bytes_before, counts_before}, mono_now() - window_start);
    group.leave();
  }
  sleep_until(mono_now() + 0.3);  // the LEAVEs get out before the participant goes
  if (!refused) done(part);
  ball_net_free(client);
  return !refused;
}

// The server of a point (state_rate < 0: none, the server runs elsewhere).
Process start_server(const LoadOptions &o, int matches, double state_rate, const std::string &dir) {
  if (state_rate < 0.0) return Process();
  std::vector<std::string> args = {program_dir() + "/ball-server", "--matches", std::to_string(matches),
                                   "--frame-rate", std::to_string(o.frame_rate), "--state-rate",
                                   std::to_string(state_rate), "--startup-wait", "0", "--quiet"};
  DdsOptions as_server = o.dds;  // the server on our participant profile, as a server under DDS Security
  if (!as_server.security.empty()) as_server.identity = o.server_identity;
  for (const std::string &a : dds_arguments(as_server)) args.push_back(a);
  if (o.server_priority > 0) args.insert(args.end(), {"--realtime-priority", std::to_string(o.server_priority)});
  args.insert(args.end(), o.server_args.begin(), o.server_args.end());
  return Process::start(args, dir + "/server.out", dir + "/server.err");
}

// The bots of a point in several processes (ranges of matches), sharing a
// window that starts after the warm-up: their parts, the CPU snapshots at
// the window's ends. false with err when a process left no part.
bool drive_processes(const LoadOptions &o, const std::vector<MatchRange> &ranges, const std::string &dir,
                     pid_t server, std::vector<LoadPart> *parts, Snapshot at[2], std::string *err) {
  double window = realtime_now() + o.warmup;
  std::vector<Process> procs;
  std::vector<pid_t> pids;
  for (size_t i = 0; i < ranges.size(); ++i) {
    char start[32];
    std::snprintf(start, sizeof start, "%.6f", window);
    std::string file = dir + "/part" + std::to_string(i) + ".json";
    std::vector<std::string> argv = {program_dir() + "/ball-load", "--matches", std::to_string(ranges[i].count),
                                     "--first-match", std::to_string(ranges[i].first), "--window-start", start,
                                     "--warmup", std::to_string(o.warmup), "--stagger", std::to_string(stagger_of(o)),
                                     "--duration", std::to_string(o.duration),
                                     "--rate", std::to_string(o.bot.rate), "--seed", std::to_string(o.bot.seed),
                                     "--part-json", file};
    for (const std::string &a : dds_arguments(o.dds)) argv.push_back(a);
    procs.push_back(Process::start(argv, dir + "/bots" + std::to_string(i) + ".out",
                                   dir + "/bots" + std::to_string(i) + ".err"));
    pids.push_back(procs.back().pid());
  }
  double t0 = mono_now() + (window - realtime_now());
  sleep_until(t0);
  at[0] = snapshot(server, pids);
  sleep_until(t0 + o.duration);
  at[1] = snapshot(server, pids);
  bool ok = true;
  for (size_t i = 0; i < procs.size(); ++i) {
    int status = procs[i].wait(o.duration + 30.0);
    std::string file = dir + "/part" + std::to_string(i) + ".json";
    try {
      parts->push_back(json::parse(read_text(file)).get<LoadPart>());
    } catch (const std::exception &e) {
      *err = "bot process " + std::to_string(i) + " (exit status " + std::to_string(status) +
             ") left no part: " + read_text(dir + "/bots" + std::to_string(i) + ".err");
      ok = false;
    }
    unlink(file.c_str());
    unlink((dir + "/bots" + std::to_string(i) + ".out").c_str());
    unlink((dir + "/bots" + std::to_string(i) + ".err").c_str());
  }
  return ok;
}

// One point of a sweep or the only run: its row, measured.
bool measure(const LoadOptions &o, int matches, double state_rate, LoadRow *row, std::string *err) {
  std::string dir = "/tmp/ball-load-" + std::to_string(getpid());
  mkdir(dir.c_str(), 0700);
  Process server = start_server(o, matches, state_rate, dir);
  std::vector<LoadPart> parts;
  Snapshot at[2];
  int snaps = 0;
  bool ok = true;
  auto ranges = split_matches(o.first_match, matches, o.bot_processes);
  if (ranges.size() <= 1) {
    LoadOptions one = o;
    one.matches = matches;
    ok = drive(
        one, [&] { at[std::min(snaps++, 1)] = snapshot(server.pid(), {getpid()}); },
        [&](const LoadPart &p) { parts.push_back(p); }, err);
  } else {
    ok = drive_processes(o, ranges, dir, server.pid(), &parts, at, err);
    snaps = 2;
  }
  if (server.pid() > 0) server.stop(5.0);
  for (const char *f : {"server.out", "server.err"}) unlink((dir + "/" + f).c_str());
  rmdir(dir.c_str());
  if (!ok) return false;
  *row = combine(parts, dds::wire_sizes());
  row->state_rate = state_rate;
  if (snaps >= 2) add_usage(at[0], at[1], row->seconds, row);
  return true;
}

}  // namespace

int run_load(const LoadOptions &o) {
  std::string err;
  if (o.stagger >= o.warmup && o.stagger > 0.0)
    return fail(kProgram, "--stagger must be below --warmup (every slot joins within the warm-up)");
  if (!o.part_json.empty()) {  // a bot process: its part, to the file
    bool written = false;
    bool ok = drive(o, {}, [&](const LoadPart &p) { written = write_file(o.part_json, json(p).dump(), &err); }, &err);
    return ok && written ? 0 : fail(kProgram, err);
  }
  std::printf("bots at %g Hz in %d process(es), %g s measured after %g s of warm-up; lat: a hit's newest racket "
              "sample written -> its segment received; h2w: the hit's sim time, as the server's real time -> its "
              "segment received (corrections aside); work: the server's per wake-up (median of its per-second p50 and p99); CPU in %% "
              "of one core; B/s: payload of the server's and the bots' samples, and all loopback bytes\n",
              o.bot.rate, o.bot_processes, o.duration, o.warmup);
  std::vector<int> counts = o.sweep.empty() ? std::vector<int>{o.matches} : o.sweep;
  std::vector<double> rates = o.sweep.empty() ? std::vector<double>{-1.0} : o.state_rates;
  int rounds = o.sweep.empty() ? 1 : std::max(1, o.rounds);
  std::vector<LoadRow> rows;
  bool written = true;  // every row is printed and in the JSON file as soon as it is measured
  auto save = [&](bool last) {
    auto points = summarize_points(rows);
    if (!o.json_out.empty()) {
      json j = {{"rows", rows}, {"points", json::array()}};
      for (const auto &p : points) j["points"].push_back({{"rounds", p.rounds}, {"min", p.min}, {"median", p.median}});
      written = write_file(o.json_out, j.dump(1), &err) && written;
    }
    if (!o.data_dir.empty()) {
      mkdir(o.data_dir.c_str(), 0755);
      written = write_file(o.data_dir + "/load.dat", load_plot_data(points), &err) && written;
    }
    if (last) {
      if (rounds > 1) std::printf("\n%d rounds, median and min of each figure:\n%s", rounds, load_table(points).c_str());
    }
  };
  for (int r = 0; r < rounds && !stop_requested(); ++r)
    for (double rate : rates)
      for (int n : counts) {
        if (stop_requested()) break;
        LoadRow row;
        if (!measure(o, n, rate, &row, &err)) return fail(kProgram, err);
        row.server_priority = o.server_priority;
        rows.push_back(row);
        std::printf("%s", load_table({summarize({row})}, rows.size() == 1).c_str());
        std::fflush(stdout);
        save(false);
      }
  save(true);
  return written ? 0 : fail(kProgram, err);
}

}  // namespace app
}  // namespace ballsrv
