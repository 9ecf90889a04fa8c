// ball_accuracy: what accuracy costs in time, measured in one run
// (docs/accuracy.md; `./run accuracy` runs it, then gnuplot). Exit status 0
// only when every sanity check on the numbers held.
#include <sys/stat.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include <CLI/CLI.hpp>

#include "accuracy.h"
#include "common.h"

namespace acc {

namespace {
std::string g_data_dir;
}

void check(Report &rep, const std::string &what, bool pass, const std::string &detail) {
  rep.checks.push_back(Check{what, pass, detail});
  std::printf("  check %s: %s (%s)\n", pass ? "ok  " : "FAIL", what.c_str(), detail.c_str());
}

FILE *open_data(const Options &opt, const std::string &name) {
  std::string path = opt.data_dir + "/" + name;
  FILE *f = std::fopen(path.c_str(), "w");
  if (!f) {
    std::fprintf(stderr, "ball_accuracy: cannot write %s: %s\n", path.c_str(), std::strerror(errno));
    std::exit(2);
  }
  return f;
}

std::string load_average() {
  char buf[64] = "?";
  if (FILE *f = std::fopen("/proc/loadavg", "r")) {
    if (std::fscanf(f, "%63s", buf) != 1) std::strcpy(buf, "?");
    std::fclose(f);
  }
  return buf;
}

const char *step_name(double h) {
  static const struct {
    double h;
    const char *name;
  } names[] = {{1.0 / 2, "1/2"},     {1.0 / 6, "1/6"},     {1.0 / 10, "1/10"},   {1.0 / 15, "1/15"},
               {1.0 / 30, "1/30"},   {1.0 / 60, "1/60"},   {1.0 / 120, "1/120"}, {1.0 / 240, "1/240"},
               {1e-3, "1e-3"},       {1.0 / 3000, "1/3000"}, {1e-4, "1e-4"}};
  for (const auto &n : names)
    if (std::fabs(h - n.h) < 1e-12 * n.h) return n.name;
  return "?";
}

}  // namespace acc

int main(int argc, char **argv) {
  acc::Options opt;
  opt.data_dir = ".";
  opt.scenes = "libball/scenes";
  std::vector<std::string> only;
  CLI::App cli{"ball_accuracy: what accuracy costs in time (docs/accuracy.md): flight, static obstacles,\n"
               "rackets, effects and the whole step, measured in one run"};
  cli.add_flag("--quick", opt.quick, "tiny sample sets and short timings (the ctest's sanity run)");
  cli.add_option("--rounds", opt.rounds, "timing rounds, min and median reported")
      ->capture_default_str()
      ->check(CLI::Range(1, 101));
  cli.add_option("--data", opt.data_dir, "where the plots' data files go (created)")->capture_default_str();
  cli.add_option("--page", opt.page, "write the markdown page there (default: none)");
  cli.add_option("--scenes", opt.scenes, "the example scenes")->capture_default_str();
  cli.add_option("--only", only, "this section only (repeatable; the page needs all)")
      ->check(CLI::IsMember({"flight", "static", "rackets", "step"}));
  CLI11_PARSE(cli, argc, argv);
  if (opt.quick) {
    opt.rounds = 1;
    opt.min_time = 0.0;
    opt.swings = 400;
    opt.cost_swings = 20;
    opt.throws = 20;
    opt.net_shots = 400;
    opt.landing_swings = 60;
  }
  if (mkdir(opt.data_dir.c_str(), 0777) != 0 && errno != EEXIST) {
    std::fprintf(stderr, "ball_accuracy: cannot create %s: %s\n", opt.data_dir.c_str(), std::strerror(errno));
    return 2;
  }
  struct Section {
    const char *name;
    void (*run)(const acc::Options &, acc::Report &);
  };
  const Section sections[] = {{"flight", acc::run_flight},
                              {"static", acc::run_static},
                              {"rackets", acc::run_rackets},
                              {"step", acc::run_step}};
  if (!opt.page.empty() && !only.empty()) {
    std::fprintf(stderr, "ball_accuracy: --page needs every section\n");
    return 2;
  }
  std::printf("ball_accuracy %s, %d rounds, libball %d.%d.%d\n", opt.quick ? "quick" : "full", opt.rounds,
              BALL_VERSION_MAJOR, BALL_VERSION_MINOR, BALL_VERSION_PATCH);
  acc::Report rep;
  rep.load_start = acc::load_average();
  double t_start = bv::now_s();
  for (const Section &s : sections) {
    if (!only.empty() && std::find(only.begin(), only.end(), s.name) == only.end()) continue;
    double t0 = bv::now_s();
    std::printf("\n== %s\n", s.name);
    std::fflush(stdout);
    s.run(opt, rep);
    std::printf("   (%.1f s)\n", bv::now_s() - t0);
    std::fflush(stdout);
  }
  rep.seconds = bv::now_s() - t_start;
  int failed = 0;
  for (const acc::Check &c : rep.checks) failed += !c.pass;
  std::printf("\n%zu checks, %d failed; %.1f s\n", rep.checks.size(), failed, rep.seconds);
  if (!opt.page.empty()) {
    if (!acc::write_page(opt, rep, opt.page)) return 2;
    std::printf("page written to %s\n", opt.page.c_str());
  }
  return failed ? 1 : 0;
}
