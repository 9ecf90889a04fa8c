// ball-load's shell over DDS and processes (docs/server-reference.md, "Load"): plays
// both slots of a range of matches from one process, or starts bot
// processes that do, and with a sweep starts a ball-server for each point;
// measures the server's and the bots' CPU and memory and the loopback
// device's bytes from /proc around the window; the figures' core is
// server/client/load.h.
#pragma once

#include <string>
#include <vector>

#include "common.h"
#include "player.h"

namespace ballsrv {
namespace app {

struct LoadOptions {
  int matches = 10;          // matches to play: first_match .. first_match + matches - 1
  int first_match = 0;
  PlayerParams bot;          // every bot's settings (match, slot and seed are each bot's own)
  double warmup = 4.0;       // s for every slot to be joined and the rallies to start
  // s: each match's bots begin at a seeded random instant this long after the start at most (below
  // the warm-up), as the matches of a server do; 0: all at once, and the rallies play in lockstep;
  // < 0: a quarter of the warm-up
  double stagger = -1.0;
  double duration = 10.0;    // s measured
  double window_start = -1;  // server s the window starts (a bot process's, from ball-load); < 0: after the warm-up
  int bot_processes = 1;     // 1: this process plays every slot
  std::vector<int> sweep;    // match counts: a ball-server started for each
  std::vector<double> state_rates{10.0};  // Hz, with a sweep: each point at each rate
  double frame_rate = 60.0;  // Hz, with a sweep
  int server_priority = 0;   // with a sweep: the servers' --realtime-priority (0: the normal scheduler)
  std::vector<std::string> server_args;  // with a sweep: more arguments for every ball-server it starts
  int rounds = 1;            // with a sweep: every point measured this many times, interleaved
  std::string json_out;      // the rows and points as JSON
  std::string data_dir;      // gnuplot's data (load.dat)
  std::string part_json;     // a bot process's part (LoadPart) to this file, nothing printed
  DdsOptions dds;            // under DDS Security its --identity must be granted every match/* (`load`)
  std::string server_identity = "server1";  // with a sweep under DDS Security: the ball-server's identity
};

// The stagger in s that the options mean (LoadOptions::stagger).
inline double stagger_of(const LoadOptions &o) { return o.stagger < 0.0 ? o.warmup / 4.0 : o.stagger; }

// Runs what the options say; the exit status.
int run_load(const LoadOptions &o);

}  // namespace app
}  // namespace ballsrv
