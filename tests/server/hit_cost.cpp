// ball_hit_cost: what hits at their instant cost the server's matches
// (docs/server-design.md, "Hits at their instant"). Two bots rally offline (a Match
// stepped as the server loop steps it, rally.h) at the three levels, the
// match frame-locked or at the instant; ./run hit-cost runs it under
// callgrind, which counts the instructions of the calls the loop makes into
// the match (the same on every run), and prints them per match second.
//
//   ball_hit_cost --hit-instant BOOL [--seeds N] [--seconds S]
#include <CLI/CLI.hpp>
#include <cstdio>

#include "rally.h"

using namespace ballsrv;
using namespace test;

int main(int argc, char **argv) {
  CLI::App app{"ball_hit_cost: offline rallies, frame-locked or hits at their instant, for callgrind"};
  bool instant = true;
  int seeds = 4;
  double seconds = 30.0;
  double rate = 30.0;
  app.add_option("--hit-instant", instant, "step to a racket hit's instant (true) or find hits at frame ends (false)")
      ->required();
  app.add_option("--seeds", seeds, "rallies per level")->check(CLI::Range(1, 100));
  app.add_option("--seconds", seconds, "sim s per rally")->check(CLI::Range(1.0, 600.0));
  app.add_option("--rate", rate, "racket samples per s (ball-load's bots: 30)")->check(CLI::Range(2.0, 120.0));
  CLI11_PARSE(app, argc, argv);
  uint64_t hits = 0, wakes = 0, looks = 0, spared = 0, queries = 0, frames = 0;
  for (int level = BALL_LEVEL_EASY; level <= BALL_LEVEL_ADVANCED; ++level)
    for (int seed = 1; seed <= seeds; ++seed) {
      MatchConfig c = default_config();
      c.level = static_cast<ball_level>(level);
      c.seed = static_cast<uint64_t>(seed);
      c.hit_instant = instant;
      Net net;  // the players' rate, as in ball-load
      net.rate = rate;
      net.noise = 0.002;
      RallyResult r = play(c, net, seconds, static_cast<uint64_t>(seed));
      hits += r.counters.hits;
      wakes += r.counters.hit_steps;
      looks += r.counters.hit_looks;
      spared += r.counters.hit_looks_spared;
      queries += r.counters.hit_queries;
      frames += static_cast<uint64_t>(seconds * c.frame_rate);
    }
  double match_s = 3.0 * seeds * seconds;
  std::printf("hit_instant %s: %.0f match s, %llu frames, %llu hits, %llu hit steps (%.2f/s), %llu looks, "
              "%llu spared, %llu queries (%.2f/s)\n",
              instant ? "true" : "false", match_s, (unsigned long long)frames, (unsigned long long)hits,
              (unsigned long long)wakes, static_cast<double>(wakes) / match_s, (unsigned long long)looks,
              (unsigned long long)spared, (unsigned long long)queries, static_cast<double>(queries) / match_s);
  return 0;
}
