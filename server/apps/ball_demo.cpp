// ball-demo: the networked demo on loopback (README, "Quick start"): one
// ball-server, two ball-bots and a ball-watch that prints the rally as it
// happens and a summary at the end. Everything it starts runs in a process
// group of its own and is stopped when the demo ends, however it ends; the
// demo fails if a process or a Fast DDS file in /dev/shm is left behind.
#include <sys/stat.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cinttypes>
#include <cstdio>
#include <fstream>

#include "common.h"
#include "options.h"
#include "player.h"
#include "process.h"
#include "records.h"

using namespace ballsrv;
using namespace ballsrv::app;

namespace {
const char *kProgram = "ball-demo";

std::string fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

// The server's end: its status, its log on a failure, its counters.
int server_summary(Process &server, const std::string &dir) {
  int rc = 0, server_rc = server.stop(5.0);
  if (server_rc != 0) {
    std::fprintf(stderr, "%s: ball-server ended with status %d; its log:\n", kProgram, server_rc);
    std::ifstream err(dir + "/server.err");
    for (std::string line; std::getline(err, line);) std::fprintf(stderr, "  %s\n", line.c_str());
    rc = 1;
  }
  try {
    std::ifstream f(dir + "/server.json");
    ServerReport r = json::parse(f).get<ServerReport>();
    uint64_t dropped = 0;
    for (int i = 0; i < kDropReasons; ++i) dropped += r.status.drops[i];
    std::printf("summary: ball-server: %" PRIu64 " frames, %" PRIu64 " overruns, %" PRIu64 " samples in, %" PRIu64
                " accepted, %" PRIu64 " idle, %" PRIu64 " dropped, %" PRIu64 " writes refused; server-side latency p50 %.1f ms, p99 "
                "%.1f ms\n",
                r.status.frames, r.status.overruns, r.status.samples_in, r.status.samples_ok,
                r.status.samples_idle, dropped, r.status.write_failures, r.latency_p50 * 1e3, r.latency_p99 * 1e3);
  } catch (const std::exception &e) {
    std::fprintf(stderr, "%s: no ball-server counters (%s): %s\n", kProgram, (dir + "/server.json").c_str(), e.what());
    rc = 1;
  }
  return rc;
}
}  // namespace

int main(int argc, char **argv) {
  CLI::App cli{"ball-demo: one ball-server, two ball-bots (seeds SEED and SEED + 1) and a ball-watch on "
               "loopback, about 20 s"};
  double duration = 20.0;
  int domain = BALL_DEMO_DOMAIN;  // docs/server.md, "DDS domains"
  std::string level = "mid", scene = "default";
  PlayerParams bots;  // the demo's bots: a little delay and noise, a miss now and then
  bots.delay = 0.02, bots.miss = 0.12, bots.noise = 0.003, bots.seed = 7;
  FieldOptions<PlayerParams> bot_opt;
  cli.add_option("--duration", duration, "s the watcher watches")->capture_default_str()->check(CLI::Range(2.0, 3600.0));
  cli.add_option("--domain", domain, "DDS domain id")->capture_default_str()->check(CLI::Range(0, kMaxDomain));
  cli.add_option("--level", level, "game level: easy, mid, advanced")->capture_default_str();
  cli.add_option("--scene", scene, "the match's scene")->capture_default_str();
  std::string secure;
  cli.add_option("--secure", secure,
                 "DDS Security: the folder of ./run certs (identities server1, watch, m0-a, m0-b; docs/security.md)");
  std::string game;
  cli.add_option("--game", game,
                 "slot 0 played by PROGRAM, a game on the client library (docs/client.md), run as PROGRAM "
                 "--domain D --match 0, instead of a ball-bot; the demo ends with it");
  int http = -1;
  cli.add_option("--http", http, "watch in a browser: the watcher serves the spectator page on PORT of 127.0.0.1 "
                                 "(0: a free port; the URL is printed)")->check(CLI::Range(0, 65535));
  bot_opt.add(cli, player_fields(), bots, {"rate", "delay", "miss", "noise", "seed"});
  CLI11_PARSE(cli, argc, argv);
  bot_opt.apply(&bots);
  if (!game.empty() && !secure.empty()) return fail(kProgram, "--game does not go with --secure (the game opens an open domain)");

  install_stop_signals();
  std::vector<std::string> shm_before = dds_shm_files();
  char dir_template[] = "/tmp/ball-demo-XXXXXX";
  if (!mkdtemp(dir_template)) return fail(kProgram, "cannot make a temporary directory");
  const std::string dir = dir_template, bin = program_dir(), dom = std::to_string(domain);
  std::printf("%s: ball-server, two ball-bots (%s level, %g Hz, %g ms delay, miss rate %g) and ball-watch on "
              "loopback, DDS domain %d%s, for %g s\n",
              kProgram, level.c_str(), bots.rate, bots.delay * 1e3, bots.miss, domain,
              secure.empty() ? "" : " under DDS Security", duration);
  // each program's identity on a secure domain (the names ./run certs makes)
  // the clients take the server topics only from server 1 holding server1's certificate
  auto as = [&](std::vector<std::string> args, const char *identity) {
    if (!secure.empty()) args.insert(args.end(), {"--secure", secure, "--identity", identity});
    if (!secure.empty() && std::string(identity) != "server1") args.insert(args.end(), {"--servers", "1=server1"});
    return args;
  };
  std::fflush(stdout);
  int rc = 0;
  {
    Process server = Process::start(as({bin + "/ball-server", "--domain", dom, "--level", level, "--scene", scene,
                                        "--server-id", "1", "--startup-wait", "0", "--duration", fmt(duration + 20.0), "--stats-json",
                                        dir + "/server.json"},
                                       "server1"),
                                    dir + "/server.log", dir + "/server.err");
    std::vector<Process> bot;
    if (!game.empty()) bot.push_back(Process::start({game, "--domain", dom, "--match", "0"}));  // its output is the demo's
    for (int i = game.empty() ? 0 : 1; i < 2; ++i)
      bot.push_back(Process::start(as({bin + "/ball-bot", "--domain", dom, "--player", std::to_string(i), "--rate",
                                       fmt(bots.rate), "--delay", fmt(bots.delay), "--miss", fmt(bots.miss), "--noise",
                                       fmt(bots.noise), "--seed", std::to_string(bots.seed + i),
                                       "--duration", fmt(duration + 15.0)},
                                      i == 0 ? "m0-a" : "m0-b"),
                                   dir + "/bot" + std::to_string(i) + ".log", dir + "/bot" + std::to_string(i) + ".err"));
    std::vector<std::string> watch_args{bin + "/ball-watch", "--domain", dom, "--duration", fmt(duration)};
    if (http >= 0) watch_args.insert(watch_args.end(), {"--http", std::to_string(http)});
    Process watch = Process::start(as(watch_args, "watch"));
    if (server.pid() <= 0 || watch.pid() <= 0 || bot[0].pid() <= 0 || bot[1].pid() <= 0) rc = 1;
    // the watcher ends the demo (or the game); a stop signal ends it early
    while (rc == 0 && watch.running() && (game.empty() || bot[0].running()) && !stop_requested()) usleep(50000);
    if (!game.empty() && !bot[0].running() && bot[0].status() != 0) {
      std::fprintf(stderr, "%s: the game %s ended with status %d\n", kProgram, game.c_str(), bot[0].status());
      rc = 1;
    }
    if (watch.running()) watch.stop();
    for (auto &b : bot) b.stop();
    if (watch.status() != 0) rc = 1;
    if (server_summary(server, dir) != 0) rc = 1;
  }  // every Process is stopped and reaped here

  std::vector<std::string> shm_after = dds_shm_files();
  if (shm_after.size() > shm_before.size()) {
    std::fprintf(stderr, "%s: Fast DDS files left in /dev/shm:", kProgram);
    for (const auto &f : shm_after) std::fprintf(stderr, " %s", f.c_str());
    std::fprintf(stderr, "\n");
    rc = 1;
  }
  for (const char *f : {"server.json", "server.log", "server.err", "bot0.log", "bot0.err", "bot1.log", "bot1.err"})
    unlink((dir + "/" + f).c_str());
  rmdir(dir.c_str());
  std::printf(rc == 0 ? "%s: done; every process stopped, nothing left in /dev/shm\n" : "%s: FAILED\n", kProgram);
  return rc;
}
