// ball-server: many matches in one process over Fast DDS (docs/server.md):
// the config (config.h) read before DDS is touched, then one ServerLoop
// (server_loop.h) on this thread over the DDS port, printing the status
// line once a status interval.
#include <CLI/CLI.hpp>
#include <cstdio>

#include "common.h"
#include "config.h"
#include "domain.h"
#include "server_endpoints.h"

using namespace ballsrv;
using namespace ballsrv::app;

namespace {
const char *kProgram = "ball-server";

// How this run ends and what it prints.
struct Run {
  double duration = 0.0;   // real s (0: until SIGINT/SIGTERM)
  std::string stats_json;  // the final counters' file ("": none)
  bool quiet = false;      // no status line
};

// Before the loop starts: a standby or a claimant listens to the others; a
// primary makes sure no server steps one of its matches. "" or why not.
std::string settle(ServerLoop &loop, const ServerConfig &config) {
  MatchInfoOut other;
  if (config.standby || config.claim > 0) {
    loop.listen(config.startup_wait, stop_requested);  // knows the others before it follows or claims
  } else if (config.startup_wait > 0.0 && loop.find_owner(config.startup_wait, stop_requested, &other)) {
    return "domain " + std::to_string(config.domain) + " is busy: match " + std::to_string(other.match_id) +
           " is served by server " + std::to_string(other.server_id) +
           " (start this one with --standby to follow it)";
  }
  return "";
}

// The loop until the run ends, its status lines and warnings printed.
void run_loop(ServerLoop &loop, const ServerConfig &config, const Run &run) {
  auto print = [&](const StatusOut &o) {
    if (run.quiet) return;
    std::printf("%s\n", status_line(o).c_str());
    std::fflush(stdout);
  };
  // another server that outranks this one for one of its matches: it yields it (protocol.md)
  auto conflict = [&](const MatchInfoOut &info, const ParticipantId &from) {
    std::fprintf(stderr, "%s %u: warning: match %u is also served by server %u (participant %s), which outranks this one\n",
                 kProgram, config.server_id, info.match_id, info.server_id, hex(from).c_str());
  };
  loop.run(run.duration, stop_requested, print, conflict);
  print(loop.finish());
}

// The server over DDS, from its config: 0, or fail's status with why.
int serve(ServerConfig &config, const ServerScenes &scenes, const Run &run) {
  std::string err;
  std::string profile = find_profile(config.profile);
  auto domain = dds::Domain::open(config.domain, profile, config.participant,
                                  {config.discovery_server, config.tcp_peers, config.tcp_listen, config.tcp_public},
                                  "ball-server " + std::to_string(config.server_id), &err,
                                  {config.security, config.identity, config.tls});
  if (!domain) return fail(kProgram, err);
  // the player timeout is the liveliness lease the racket samples reader requests
  auto host = make_host(&config, scenes, domain->reader_lease(dds::kRacketProfile), &err);
  if (!host) return fail(kProgram, err);
  // a primary's writers outrank a standby's (docs/protocol.md, "Several servers on one domain")
  const char *role = config.standby ? dds::kStandbyProfile : dds::kPrimaryProfile;
  auto port = dds::ServerEndpoints::open(*domain, static_cast<int>(config.max_matches), host->max_players(),
                                         host->create_ids().count, role, config.standby, &err);
  if (!port) return fail(kProgram, err);

  SystemClock clock;
  ServerLoop loop(*host, *port, clock, loop_settings(config, domain->writer_strength(role)));
  loop.on_note([&](const std::string &line) {
    std::printf("%s %u: %s\n", kProgram, config.server_id, line.c_str());
    std::fflush(stdout);
  });
  err = settle(loop, config);
  if (!err.empty()) return fail(kProgram, err);
  // the loop's thread alone, after DDS started its own: a server that cannot keep up must not
  // starve the host's other programs (docs/server-reference.md, "Load")
  if (config.realtime_priority > 0 && !set_realtime_priority(config.realtime_priority, &err)) return fail(kProgram, err);
  loop.start();
  if (!run.quiet)
    std::printf("%s %u: %u matches, following %u, on domain %d (profile %s, participant %s), player timeout %.2f s, "
                "room for %u matches\n",
                kProgram, config.server_id, loop.status_now().matches, loop.status_now().following, config.domain,
                profile.c_str(), hex(domain->id()).c_str(), config.defaults.player_timeout, config.max_matches);
  std::fflush(stdout);
  run_loop(loop, config, run);
  if (!run.quiet) std::printf("%s %u: stopped\n", kProgram, config.server_id);
  if (!run.stats_json.empty() && !write_file(run.stats_json, json(loop.report()).dump(1), &err))
    return fail(kProgram, err);
  dds::set_exit_status_if_stuck(0);  // all is written: a stuck DDS teardown still ends well (domain.h)
  return 0;  // the Domain deletes every entity, in reverse order, as it goes
}

}  // namespace

int main(int argc, char **argv) {
  CLI::App cli{"ball-server: a ball server hosting many matches over Fast DDS (docs/server.md).\n"
               "Command-line settings override the config file's defaults; without a\n"
               "config file or --matches it hosts one match on the default tennis scene."};
  ServerOptions opt;
  opt.add(cli);
  Run run;
  cli.add_option("--duration", run.duration, "stop after S real seconds (0: run until SIGINT/SIGTERM)")
      ->check(CLI::Range(0.0, 1e9));
  cli.add_option("--stats-json", run.stats_json, "write the final counters to FILE as JSON");
  cli.add_flag("--quiet,-q", run.quiet, "no status line");
  CLI11_PARSE(cli, argc, argv);
  if (!opt.keys.empty()) return std::fputs(keys_table(opt.keys).c_str(), stdout) < 0;

  ServerConfig config;
  ServerScenes scenes;
  std::string err;
  if (!opt.config_file.empty() && !load_config_file(opt.config_file, &config, &err)) return fail(kProgram, err);
  if (!opt.apply(&config, &err) || !load_scenes(config, &scenes, &err)) return fail(kProgram, err);
  install_stop_signals();
  return serve(config, scenes, run);
}
