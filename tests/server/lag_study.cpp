// ball_lag_study: what lag compensation is worth (docs/server-design.md, "Lag
// compensation"). Two bots rally offline (a Match stepped as the server
// loop steps it, rally.h) at 15 Hz behind a one-way delay; a swing is a
// ball that reached a bot's side: it hit it, or the point went for not
// returning it. The hit rate at each delay, with compensation off and on,
// for bots that swing ahead of the delay and for bots that swing late (as
// if there were none, as people do). A study, not a timed test: it prints
// a table and writes gnuplot's data; ./run lag-study draws the plot.
//
//   ball_lag_study [--seeds N] [--seconds S] [--own-hit] [--data FILE]
#include <CLI/CLI.hpp>
#include <cstdio>
#include <fstream>

#include "rally.h"

using namespace ballsrv;
using namespace test;

namespace {

struct Rate {
  uint64_t hits = 0, missed = 0;
  double rate() const { return hits + missed ? static_cast<double>(hits) / static_cast<double>(hits + missed) : 0.0; }
};

Rate measure(double delay, bool compensate, bool own_hit, bool plan_ahead, int seeds, double seconds) {
  Rate r;
  for (int seed = 1; seed <= seeds; ++seed) {
    MatchConfig c = default_config();
    c.level = BALL_LEVEL_MID;
    c.seed = static_cast<uint64_t>(seed);
    c.rewind_window = compensate ? 0.25 : 0.0;
    c.rewind_own_hit = own_hit;
    Net net;
    net.rate = 15.0;
    net.delay = delay;
    net.noise = 0.002;
    net.plan_ahead = plan_ahead;
    RallyResult res = play(c, net, seconds, static_cast<uint64_t>(seed));
    r.hits += res.counters.hits;  // (a hit moved is counted once: the match un-counts the one it moved)
    for (const EventOut &e : res.events)
      r.missed += e.kind == EventKind::point &&
                  (e.reason == Reason::point_double_bounce || e.reason == Reason::point_not_returned);
  }
  return r;
}

}  // namespace

int main(int argc, char **argv) {
  int seeds = 40;
  double seconds = 30.0;
  std::string data;
  bool own_hit = false;
  CLI::App cli{"ball_lag_study: hit rates behind a delay, lag compensation off and on"};
  cli.add_option("--seeds", seeds, "rallies per point (seeds 1..N)")->capture_default_str()->check(CLI::Range(1, 1000));
  cli.add_option("--seconds", seconds, "sim s of each rally")->capture_default_str()->check(CLI::Range(1.0, 600.0));
  cli.add_option("--data", data, "write gnuplot's data to FILE");
  cli.add_flag("--own-hit", own_hit, "compensation on with the match key rewind_own_hit");
  CLI11_PARSE(cli, argc, argv);
  const double delays[] = {0.0, 0.05, 0.1, 0.15, 0.25};
  std::printf("mid level, 15 Hz, %d rallies of %.0f s per point%s; hit rate = hits / (hits + balls not returned)\n",
              seeds, seconds, own_hit ? ", on: rewind_own_hit" : "");
  std::printf("%-9s %-10s %8s %8s %8s %8s\n", "delay ms", "swing", "off", "on", "swings", "on/0ms");
  std::string out = "# delay_ms ahead_off ahead_on late_off late_on (hit rates)\n";
  double base[2] = {0.0, 0.0};
  std::vector<std::array<double, 4>> rows;
  for (double d : delays) {
    std::array<double, 4> row{};
    for (int late = 0; late < 2; ++late) {
      Rate off = measure(d, false, false, late == 0, seeds, seconds),
           on = measure(d, true, own_hit, late == 0, seeds, seconds);
      if (d == 0.0) base[late] = off.rate();
      row[late * 2] = off.rate();
      row[late * 2 + 1] = on.rate();
      std::printf("%-9.0f %-10s %7.1f%% %7.1f%% %8llu %7.1f%%\n", d * 1e3, late ? "late" : "ahead", off.rate() * 100,
                  on.rate() * 100, static_cast<unsigned long long>(on.hits + on.missed),
                  base[late] > 0 ? on.rate() / base[late] * 100 : 0.0);
      std::fflush(stdout);
    }
    char line[128];
    std::snprintf(line, sizeof line, "%.0f %.4f %.4f %.4f %.4f\n", d * 1e3, row[0], row[1], row[2], row[3]);
    out += line;
  }
  if (!data.empty()) {
    std::ofstream f(data);
    f << out;
    if (!f) {
      std::fprintf(stderr, "ball_lag_study: cannot write %s\n", data.c_str());
      return 1;
    }
  }
  return 0;
}
