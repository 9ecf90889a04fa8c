// ball-load: the load generator and benchmark (docs/server-reference.md, "Load").
// Plays both slots of many matches (PlayerGroups of BotPlayers, one DDS
// participant a process, in one process or --bot-processes) against a
// ball-server and measures what a player sees: racket hits, the
// sample-to-segment and the hit-to-wire latency. With --sweep it starts a
// ball-server for each point (match count x state rate) itself, measures
// every point --rounds times and prints the table (server/apps/load_run.h).
#include <CLI/CLI.hpp>

#include "load_run.h"
#include "options.h"

using namespace ballsrv;
using namespace ballsrv::app;

int main(int argc, char **argv) {
  CLI::App cli{"ball-load: many bots against ball-server; with --sweep, the load benchmark"};
  LoadOptions o;
  o.dds.domain = BALL_BENCH_DOMAIN;  // docs/server-reference.md, "DDS domains"
  FieldOptions<PlayerParams> bot_opt;
  cli.add_option("--matches", o.matches, "matches to play (both slots of each)")->capture_default_str()
      ->check(CLI::Range(1, 100000));
  cli.add_option("--first-match", o.first_match, "the first match's id")->capture_default_str()
      ->check(CLI::Range(0, 100000));
  bot_opt.add(cli, player_fields(), o.bot, {"rate", "seed"});
  cli.add_option("--warmup", o.warmup, "s before measuring")->capture_default_str();
  cli.add_option("--stagger", o.stagger,
                 "s: each match's bots begin at a random instant within this of the start (0: all at once; "
                 "default: a quarter of --warmup)")
      ->check(CLI::Range(0.0, 60.0));
  cli.add_option("--duration", o.duration, "s measured")->capture_default_str();
  cli.add_option("--bot-processes", o.bot_processes, "processes the bots are split over")->capture_default_str()
      ->check(CLI::Range(1, 64));
  cli.add_option("--sweep", o.sweep, "match counts: start a ball-server for each and measure")->delimiter(',');
  cli.add_option("--frame-rate", o.frame_rate, "with --sweep: the server's frame rate")->capture_default_str();
  cli.add_option("--server-priority", o.server_priority,
                 "with --sweep: the servers' --realtime-priority (SCHED_FIFO; root); 0: the normal scheduler")
      ->check(CLI::Range(0, 99))
      ->capture_default_str();
  cli.add_option("--server-args", o.server_args,
                 "with --sweep: more arguments for every ball-server, comma-separated (--hit-instant,false)")
      ->delimiter(',')->allow_extra_args(false);
  cli.add_option("--state-rate", o.state_rates, "with --sweep: the server's ball state rates, each a point")
      ->delimiter(',')->capture_default_str();
  cli.add_option("--rounds", o.rounds, "with --sweep: times every point is measured (interleaved)")
      ->capture_default_str()->check(CLI::Range(1, 100));
  cli.add_option("--json", o.json_out, "write the rows and points to FILE as JSON");
  cli.add_option("--data", o.data_dir, "write gnuplot's data (load.dat) into DIR");
  cli.add_option("--window-start", o.window_start, "(a bot process's) server s at which measuring starts");
  cli.add_option("--part-json", o.part_json, "(a bot process's) write what it measured to FILE, print nothing");
  cli.add_option("--server-identity", o.server_identity,
                 "with --sweep and --secure: the identity of the ball-server it starts")->capture_default_str();
  add_dds_options(cli, &o.dds);
  CLI11_PARSE(cli, argc, argv);
  bot_opt.apply(&o.bot);
  install_stop_signals();
  return run_load(o);
}
