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

#include "accuracy.h"
#include "common.h"

namespace acc {

namespace {
std::string g_data_dir;
}

Stat stat_of(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  size_t n = v.size();
  if (n == 0) return Stat{};
  return Stat{v[0], n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2])};
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

namespace {

void usage(FILE *f) {
  std::fprintf(f,
               "usage: ball_accuracy [--quick] [--rounds N] [--data DIR] [--page FILE] [--scenes DIR]\n"
               "                     [--only SECTION]...\n"
               "  what accuracy costs in time (docs/accuracy.md): flight, static obstacles,\n"
               "  rackets, effects and the whole step, measured in one run\n"
               "  --quick        tiny sample sets and short timings (the ctest's sanity run)\n"
               "  --rounds N     timing rounds, min and median reported (default 11)\n"
               "  --data DIR     where the plots' data files go (default .; created)\n"
               "  --page FILE    write the markdown page there (default: none)\n"
               "  --scenes DIR   the example scenes (default libball/scenes)\n"
               "  --only NAME    flight, static, rackets or step (repeatable; the page needs all)\n");
}

}  // namespace

int main(int argc, char **argv) {
  acc::Options opt;
  opt.data_dir = ".";
  opt.scenes = "libball/scenes";
  std::vector<std::string> only;
  for (int i = 1; i < argc; i++) {
    std::string a = argv[i];
    if (a == "--quick") {
      opt.quick = true;
    } else if (a == "--rounds" && i + 1 < argc) {
      opt.rounds = std::atoi(argv[++i]);
      if (opt.rounds < 1 || opt.rounds > 101) {
        std::fprintf(stderr, "ball_accuracy: --rounds wants 1 to 101\n");
        return 2;
      }
    } else if (a == "--data" && i + 1 < argc) {
      opt.data_dir = argv[++i];
    } else if (a == "--page" && i + 1 < argc) {
      opt.page = argv[++i];
    } else if (a == "--scenes" && i + 1 < argc) {
      opt.scenes = argv[++i];
    } else if (a == "--only" && i + 1 < argc) {
      only.push_back(argv[++i]);
    } else if (a == "--help" || a == "-h") {
      usage(stdout);
      return 0;
    } else {
      usage(stderr);
      return 2;
    }
  }
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
  for (const std::string &name : only)
    if (std::none_of(std::begin(sections), std::end(sections), [&](const Section &s) { return name == s.name; })) {
      std::fprintf(stderr, "ball_accuracy: unknown section '%s'\n", name.c_str());
      return 2;
    }
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
