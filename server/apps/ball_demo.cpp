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
#include <nlohmann/json.hpp>

#include "common.h"
#include "process.h"

using namespace ballsrv;
using namespace ballsrv::app;

namespace {
const char *kProgram = "ball-demo";

std::string fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}
}  // namespace

int main(int argc, char **argv) {
  CLI::App cli{"ball-demo: one ball-server, two ball-bots and a ball-watch on loopback, about 20 s"};
  double duration = 20.0, rate = 30.0, delay = 0.02, miss = 0.12, noise = 0.003;
  int domain = 42;
  long seed = 7;
  std::string level = "mid", scene = "default";
  cli.add_option("--duration", duration, "s the watcher watches")->capture_default_str()->check(CLI::Range(2.0, 3600.0));
  cli.add_option("--domain", domain, "DDS domain id")->capture_default_str()->check(CLI::Range(0, 232));
  cli.add_option("--level", level, "game level: easy, mid, advanced")->capture_default_str();
  cli.add_option("--scene", scene, "the match's scene")->capture_default_str();
  cli.add_option("--rate", rate, "the bots' sample rate, Hz")->capture_default_str()->check(CLI::Range(2.0, 120.0));
  cli.add_option("--delay", delay, "s the bots' samples are delayed")->capture_default_str()->check(CLI::Range(0.0, 1.0));
  cli.add_option("--miss", miss, "the bots' miss rate (their skill)")->capture_default_str()->check(CLI::Range(0.0, 1.0));
  cli.add_option("--seed", seed, "the bots' seeds are SEED and SEED + 1")->capture_default_str();
  cli.add_option("--noise", noise, "m of tracker noise on the bots' rackets")->capture_default_str()->check(CLI::Range(0.0, 1.0));
  CLI11_PARSE(cli, argc, argv);

  install_stop_signals();
  std::vector<std::string> shm_before = dds_shm_files();
  char dir_template[] = "/tmp/ball-demo-XXXXXX";
  if (!mkdtemp(dir_template)) return fail(kProgram, "cannot make a temporary directory");
  const std::string dir = dir_template;
  const std::string bin = program_dir();
  const std::string dom = std::to_string(domain);
  const std::string server_json = dir + "/server.json";

  std::printf("%s: ball-server, two ball-bots (%s level, %g Hz, %g ms delay, miss rate %g) and ball-watch on "
              "loopback, DDS domain %d, for %g s\n",
              kProgram, level.c_str(), rate, delay * 1e3, miss, domain, duration);
  std::fflush(stdout);
  int rc = 0;
  {
    Process server = Process::start({bin + "/ball-server", "--domain", dom, "--level", level, "--scene", scene,
                                     "--startup-wait", "0", "--duration", fmt(duration + 20.0), "--stats-json",
                                     server_json},
                                    dir + "/server.log", dir + "/server.err");
    std::vector<Process> bots;
    for (int i = 0; i < 2; ++i)
      bots.push_back(Process::start({bin + "/ball-bot", "--domain", dom, "--player", std::to_string(i), "--rate",
                                     fmt(rate), "--delay", fmt(delay), "--miss", fmt(miss), "--noise", fmt(noise),
                                     "--seed", std::to_string(seed + i), "--scene", scene, "--duration",
                                     fmt(duration + 15.0)},
                                    dir + "/bot" + std::to_string(i) + ".log", dir + "/bot" + std::to_string(i) + ".err"));
    Process watch = Process::start({bin + "/ball-watch", "--domain", dom, "--duration", fmt(duration)});
    if (server.pid() <= 0 || watch.pid() <= 0 || bots[0].pid() <= 0 || bots[1].pid() <= 0) rc = 1;
    // the watcher ends the demo; a stop signal ends it early
    while (rc == 0 && watch.running() && !stop_requested()) usleep(50000);
    if (watch.running()) watch.stop();
    for (auto &b : bots) b.stop();
    int server_rc = server.stop(5.0);
    if (watch.status() != 0) rc = 1;
    if (server_rc != 0) {
      std::fprintf(stderr, "%s: ball-server ended with status %d; its log:\n", kProgram, server_rc);
      std::ifstream err(dir + "/server.err");
      std::string line;
      while (std::getline(err, line)) std::fprintf(stderr, "  %s\n", line.c_str());
      rc = 1;
    }
    std::ifstream f(server_json);
    if (f) {
      nlohmann::json j = nlohmann::json::parse(f, nullptr, false);
      if (!j.is_discarded()) {
        uint64_t dropped = 0;
        for (auto &kv : j["drops"].items()) dropped += kv.value().get<uint64_t>();
        std::printf("summary: ball-server: %" PRIu64 " frames, %" PRIu64 " overruns, %" PRIu64
                    " samples in, %" PRIu64 " accepted, %" PRIu64 " dropped; server-side latency p50 %.1f ms, "
                    "p99 %.1f ms\n",
                    j["frames"].get<uint64_t>(), j["overruns"].get<uint64_t>(), j["samples_in"].get<uint64_t>(),
                    j["samples_ok"].get<uint64_t>(), dropped, j["latency_p50"].get<double>() * 1e3,
                    j["latency_p99"].get<double>() * 1e3);
      }
    }
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
  if (rc == 0) std::printf("%s: done; every process stopped, nothing left in /dev/shm\n", kProgram);
  else std::printf("%s: FAILED\n", kProgram);
  return rc;
}
