// ball_validate: libball against MuJoCo 2.2 (flight, contacts, integrators)
// and FCL 0.7 (static verdicts, swept racket test). Exit status 0 when every
// check that ran passed.
#include <algorithm>
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include <CLI/CLI.hpp>

#include "common.h"

#ifndef BALL_VALIDATION_CSV
#define BALL_VALIDATION_CSV "integrator_sweep.csv"
#endif

int main(int argc, char **argv) {
  bv::Options opt;
  opt.csv_path = BALL_VALIDATION_CSV;
  opt.full = false;
  std::vector<std::string> only;
  bool quick = false;
  CLI::App cli{"ball_validate: libball against MuJoCo 2.2 and FCL 0.7 (docs/validation.md)"};
  auto *quick_flag = cli.add_flag("--quick", quick, "a few seconds of samples (default; what ctest runs)");
  cli.add_flag("--full", opt.full,
               "the report: 10,000 flights, 100,000 static configurations per obstacle, 10,000 swept "
               "motions per set, a timed integrator sweep")
      ->excludes(quick_flag);
  cli.add_option("--check", only, "run only this check (repeatable)")
      ->check(CLI::IsMember({"flight", "contacts", "sweep", "static", "swept"}));
  cli.add_option("--seed", opt.seed, "seed of every sample set")->capture_default_str();
  cli.add_option("--csv", opt.csv_path, "where the integrator sweep table goes")->capture_default_str();
  CLI11_PARSE(cli, argc, argv);
  if (opt.full) {
    opt.flights = 10000;
    opt.contacts = 2000;
    opt.statics = 100000;
    opt.swept = 10000;
    opt.sweep_min_time = 0.5;
  }
  struct Check {
    const char *name;
    std::function<bv::Outcome(const bv::Options &)> run;
  };
  const Check checks[] = {{"flight", bv::check_flight},
                          {"contacts", bv::check_contacts},
                          {"sweep", bv::check_sweep},
                          {"static", bv::check_static},
                          {"swept", bv::check_swept}};
  std::printf("ball_validate %s mode, seed %llu, libball %d.%d.%d\n", opt.full ? "full" : "quick",
              static_cast<unsigned long long>(opt.seed), BALL_VERSION_MAJOR, BALL_VERSION_MINOR,
              BALL_VERSION_PATCH);
  bool all = true;
  std::vector<std::pair<std::string, bool>> summary;
  for (const Check &c : checks) {
    if (!only.empty() && std::find(only.begin(), only.end(), c.name) == only.end()) continue;
    double t0 = bv::now_s();
    bv::Outcome o = c.run(opt);
    std::printf("\n== %s: %s (%.1f s)\n", o.check.c_str(), o.pass ? "PASS" : "FAIL", bv::now_s() - t0);
    for (const std::string &l : o.lines)
      if (!l.empty()) std::printf("  %s\n", l.c_str());
    std::fflush(stdout);
    summary.emplace_back(o.check, o.pass);
    all = all && o.pass;
  }
  std::printf("\n");
  for (const auto &s : summary) std::printf("%-20s %s\n", s.first.c_str(), s.second ? "PASS" : "FAIL");
  return all ? 0 : 1;
}
