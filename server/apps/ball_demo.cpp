// ball-demo: the networked demo on loopback (README, "Quick start"): one
// ball-server, two ball-bots and a ball-watch that prints the rally as it
// happens and a summary at the end; with --failover a standby server too,
// and the primary killed (kill -9) halfway: the standby takes the match
// over and the rally goes on (docs/server.md, "Several servers and
// failover"). Everything it starts runs in a process group of its own and
// is stopped when the demo ends, however it ends; the demo fails if a
// process or a Fast DDS file in /dev/shm is left behind.
#include <sys/stat.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cinttypes>
#include <csignal>
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

// A server's end (name: "server" or "standby", its files' names): its
// status, its log on a failure, its counters; *takeovers: the matches it took over.
int server_summary(Process &server, const std::string &dir, const std::string &name, uint64_t *takeovers) {
  int rc = 0, server_rc = server.stop(5.0);
  if (server_rc != 0) {
    std::fprintf(stderr, "%s: ball-server (%s) ended with status %d; its log:\n", kProgram, name.c_str(), server_rc);
    std::ifstream err(dir + "/" + name + ".err");
    for (std::string line; std::getline(err, line);) std::fprintf(stderr, "  %s\n", line.c_str());
    rc = 1;
  }
  try {
    std::ifstream f(dir + "/" + name + ".json");
    ServerReport r = json::parse(f).get<ServerReport>();
    *takeovers = r.takeovers;
    uint64_t dropped = 0;
    for (int i = 0; i < kDropReasons; ++i) dropped += r.status.drops[i];
    std::printf("summary: ball-server%s: %" PRIu64 " frames, %" PRIu64 " overruns, %" PRIu64 " samples in, %" PRIu64
                " accepted, %" PRIu64 " idle, %" PRIu64 " dropped, %" PRIu64 " writes refused; server-side latency p50 %.1f ms, p99 "
                "%.1f ms\n",
                name == "standby" ? " (standby)" : "", r.status.frames, r.status.overruns, r.status.samples_in, r.status.samples_ok,
                r.status.samples_idle, dropped, r.status.write_failures, r.latency_p50 * 1e3, r.latency_p99 * 1e3);
  } catch (const std::exception &e) {
    std::fprintf(stderr, "%s: no ball-server counters (%s): %s\n", kProgram, (dir + "/" + name + ".json").c_str(),
                 e.what());
    rc = 1;
  }
  return rc;
}

// What the demo plays (its command line).
struct Demo {
  double duration = 20.0;
  int domain = BALL_DEMO_DOMAIN;  // docs/server-reference.md, "DDS domains"
  std::string level = "mid", scene = "default", secure, game;
  int http = -1;
  bool failover = false;
  PlayerParams bots;  // the demo's bots: a little delay and noise, a miss now and then
  Demo() { bots.delay = 0.02, bots.miss = 0.12, bots.noise = 0.003, bots.seed = 7; }
};

// The processes of a demo, stopped and reaped when it goes.
struct Cast {
  Process server, standby, watch;
  std::vector<Process> bot;
};

// Each program's identity on a secure domain (the names ./run certs makes):
// the clients take the server topics only from the servers holding their certificates.
std::vector<std::string> as(const Demo &d, std::vector<std::string> args, const std::string &identity) {
  if (d.secure.empty()) return args;
  args.insert(args.end(), {"--secure", d.secure, "--identity", identity});
  if (identity.rfind("server", 0) != 0)
    args.insert(args.end(), {"--servers", d.failover ? "1=server1,2=server2" : "1=server1"});
  return args;
}

Process start_server(const Demo &d, const std::string &bin, const std::string &dir, const std::string &name, int id) {
  std::vector<std::string> args{bin + "/ball-server", "--domain", std::to_string(d.domain), "--level", d.level,
                                "--scene", d.scene, "--server-id", std::to_string(id), "--startup-wait",
                                id == 1 ? "0" : "0.5", "--duration", fmt(d.duration + 20.0), "--stats-json",
                                dir + "/" + name + ".json"};
  if (id != 1) args.push_back("--standby");
  return Process::start(as(d, args, "server" + std::to_string(id)), dir + "/" + name + ".log", dir + "/" + name + ".err");
}

void start_cast(const Demo &d, const std::string &dir, Cast *c) {
  const std::string bin = program_dir(), dom = std::to_string(d.domain);
  c->server = start_server(d, bin, dir, "server", 1);
  if (d.failover) c->standby = start_server(d, bin, dir, "standby", 2);
  if (!d.game.empty()) c->bot.push_back(Process::start({d.game, "--domain", dom, "--match", "0"}));  // its output is the demo's
  for (int i = d.game.empty() ? 0 : 1; i < 2; ++i) {
    const std::string n = std::to_string(i);
    c->bot.push_back(Process::start(as(d, {bin + "/ball-bot", "--domain", dom, "--player", n, "--rate", fmt(d.bots.rate),
                                           "--delay", fmt(d.bots.delay), "--miss", fmt(d.bots.miss), "--noise",
                                           fmt(d.bots.noise), "--seed", std::to_string(d.bots.seed + i),
                                           "--duration", fmt(d.duration + 15.0)},
                                       i == 0 ? "m0-a" : "m0-b"),
                                    dir + "/bot" + n + ".log", dir + "/bot" + n + ".err"));
  }
  std::vector<std::string> watch_args{bin + "/ball-watch", "--domain", dom, "--duration", fmt(d.duration)};
  if (d.http >= 0) watch_args.insert(watch_args.end(), {"--http", std::to_string(d.http)});
  c->watch = Process::start(as(d, watch_args, "watch"));
}

// Runs the demo until the watcher (or the game) ends or a stop signal; with
// --failover the primary is killed halfway. 0: every program did its part.
int play(const Demo &d, const std::string &dir) {
  Cast c;
  start_cast(d, dir, &c);
  int rc = 0;
  if (c.server.pid() <= 0 || c.watch.pid() <= 0 || c.bot[0].pid() <= 0 || c.bot[1].pid() <= 0 ||
      (d.failover && c.standby.pid() <= 0))
    rc = 1;
  const double kill_at = realtime_now() + 0.5 * d.duration;
  bool killed = false;
  while (rc == 0 && c.watch.running() && (d.game.empty() || c.bot[0].running()) && !stop_requested()) {
    if (d.failover && !killed && realtime_now() >= kill_at) {
      c.server.signal(SIGKILL);
      killed = true;
      std::printf("%s: the primary killed (kill -9) at %.0f s; the standby takes its match over\n", kProgram,
                  0.5 * d.duration);
      std::fflush(stdout);
    }
    usleep(50000);
  }
  if (!d.game.empty() && !c.bot[0].running() && c.bot[0].status() != 0) {
    std::fprintf(stderr, "%s: the game %s ended with status %d\n", kProgram, d.game.c_str(), c.bot[0].status());
    rc = 1;
  }
  if (c.watch.running()) c.watch.stop();
  for (auto &b : c.bot) b.stop();
  if (c.watch.status() != 0) rc = 1;
  uint64_t takeovers = 0;
  if (!killed && server_summary(c.server, dir, "server", &takeovers) != 0) rc = 1;
  if (d.failover && server_summary(c.standby, dir, "standby", &takeovers) != 0) rc = 1;
  if (killed) {
    std::printf("summary: the standby took %" PRIu64 " match%s over\n", takeovers, takeovers == 1 ? "" : "es");
    if (takeovers == 0) rc = 1;
  }
  return rc;
}

// The demo's folder and /dev/shm as they were: 0 when nothing is left behind.
int clean_up(const std::string &dir, const std::vector<std::string> &shm_before) {
  int rc = 0;
  std::vector<std::string> shm_after = dds_shm_files();
  if (shm_after.size() > shm_before.size()) {
    std::fprintf(stderr, "%s: Fast DDS files left in /dev/shm:", kProgram);
    for (const auto &f : shm_after) std::fprintf(stderr, " %s", f.c_str());
    std::fprintf(stderr, "\n");
    rc = 1;
  }
  for (const char *name : {"server", "standby", "bot0", "bot1"})
    for (const char *ext : {".json", ".log", ".err"}) unlink((dir + "/" + name + ext).c_str());
  rmdir(dir.c_str());
  return rc;
}

}  // namespace

int main(int argc, char **argv) {
  CLI::App cli{"ball-demo: one ball-server, two ball-bots (seeds SEED and SEED + 1) and a ball-watch on "
               "loopback, about 20 s"};
  Demo d;
  FieldOptions<PlayerParams> bot_opt;
  cli.add_option("--duration", d.duration, "s the watcher watches")->capture_default_str()->check(CLI::Range(2.0, 3600.0));
  cli.add_option("--domain", d.domain, "DDS domain id")->capture_default_str()->check(CLI::Range(0, kMaxDomain));
  cli.add_option("--level", d.level, "game level: easy, mid, advanced")->capture_default_str();
  cli.add_option("--scene", d.scene, "the match's scene")->capture_default_str();
  cli.add_option("--secure", d.secure,
                 "DDS Security: the folder of ./run certs (identities server1, server2, watch, m0-a, m0-b; "
                 "docs/security.md)");
  cli.add_option("--game", d.game,
                 "slot 0 played by PROGRAM, a game on the client library (docs/client.md), run as PROGRAM "
                 "--domain D --match 0, instead of a ball-bot; the demo ends with it");
  cli.add_option("--http", d.http, "watch in a browser: the watcher serves the spectator page on PORT of 127.0.0.1 "
                                   "(0: a free port; the URL is printed)")->check(CLI::Range(0, 65535));
  cli.add_flag("--failover", d.failover,
               "a standby server (server 2) too; the primary is killed (kill -9) halfway and the standby takes its "
               "match over (docs/server.md, \"Several servers and failover\")");
  bot_opt.add(cli, player_fields(), d.bots, {"rate", "delay", "miss", "noise", "seed"});
  CLI11_PARSE(cli, argc, argv);
  bot_opt.apply(&d.bots);
  if (!d.game.empty() && !d.secure.empty()) return fail(kProgram, "--game does not go with --secure (the game opens an open domain)");

  install_stop_signals();
  std::vector<std::string> shm_before = dds_shm_files();
  char dir_template[] = "/tmp/ball-demo-XXXXXX";
  if (!mkdtemp(dir_template)) return fail(kProgram, "cannot make a temporary directory");
  std::printf("%s: ball-server%s, two ball-bots (%s level, %g Hz, %g ms delay, miss rate %g) and ball-watch on "
              "loopback, DDS domain %d%s, for %g s\n",
              kProgram, d.failover ? " and a standby" : "", d.level.c_str(), d.bots.rate, d.bots.delay * 1e3,
              d.bots.miss, d.domain, d.secure.empty() ? "" : " under DDS Security", d.duration);
  std::fflush(stdout);
  int rc = play(d, dir_template);  // every Process is stopped and reaped when it returns
  if (clean_up(dir_template, shm_before) != 0) rc = 1;
  std::printf(rc == 0 ? "%s: done; every process stopped, nothing left in /dev/shm\n" : "%s: FAILED\n", kProgram);
  return rc;
}
