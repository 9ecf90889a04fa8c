// ball_accuracy: what accuracy costs in time (docs/accuracy.md). One program
// measures every figure of the page in one run, writes the plots' data
// (gnuplot reads them: validation/plots/*.gp) and the page itself. It uses
// libball's public API only. Timings are benchmarks, never asserted; what is
// asserted (in every run, and by the quick ctest) is the sanity of the
// accuracy numbers: a closed form exact to rounding, RK4 of order 4, the
// exact scheme missing no net hit, rates in [0, 1].
#ifndef BALL_VALIDATION_ACCURACY_H
#define BALL_VALIDATION_ACCURACY_H

#include <cstdio>
#include <string>
#include <vector>

#include "ball/ball.h"
#include "common.h"

namespace acc {

struct Options {
  bool quick = false;         // the ctest's run: tiny sample sets, one short round
  int rounds = 11;            // timing rounds: min and median
  double min_time = 0.02;     // s of wall clock per timed measurement
  int swings = 10000;         // the detection study's swings per rate
  int cost_swings = 1000;     // swings timed per rate and test
  int throws = 200;           // balls thrown to bounce 10 times, per rate and scheme
  int net_shots = 10000;      // shots at the net per rate and scheme
  int landing_swings = 2000;  // strokes per game level, response and rate
  std::string data_dir;       // the plots' data files
  std::string page;           // the markdown page ("" writes none)
  std::string scenes;         // libball/scenes (the rally scene of the whole frame)
};

using bv::Stat;  // min and median of the rounds (common.h)
using bv::stat_of;

// A sanity condition on the numbers, and whether it held.
struct Check {
  std::string what;
  bool pass;
  std::string detail;
};

// ---- Flight ----

struct FlightRow {
  std::string method;    // "libball", "Euler", "semi-implicit Euler", "RK4", "MuJoCo Euler", "MuJoCo RK4"
  std::string step;      // "1/60", "1e-3"
  double h = 0.0;        // s
  double err_path = 0.0; // m: the largest position error at the step instants over the flight
  double err_end = 0.0;  // m: the position error at the flight's end
  Stat ns_per_s;         // ns of wall clock per simulated second (a state every step)
  Stat query_ns;         // ns for one "where at T" (integrators: integrate 0..T)
};

struct FlightCase {
  std::string name;  // "2 s shot"
  double T = 0.0;    // s
  std::vector<FlightRow> rows;
};

struct FlightResults {
  double b = 0.0;  // m / beta, s
  ball_vec3 p0{}, v0{};
  std::vector<FlightCase> cases;
};

// ---- Static obstacles ----

struct StaticRow {
  ball_scheme scheme = BALL_SCHEME_EXACT;
  double rate = 0.0;             // Hz
  // the bounce throws: means over the throws with 10 bounces
  int short_throws = 0;          // throws with fewer than 10 bounces in the sim (left out)
  double first_dt = 0.0;         // s: |time error| of the first bounce
  double first_dp = 0.0;         // m: |point error| of the first bounce
  double max_dt = 0.0;           // s: the largest |time error| of the first 10 bounces
  double max_dp = 0.0;           // m: the largest |point error| of the first 10 bounces
  double energy_rel = 0.0;       // |E - E_ref| / E_ref just after the 10th bounce
  double worst_energy_rel = 0.0; // the largest of those
  // the shots at the net
  int net_truth = 0;             // shots whose path meets the net
  int net_missed = 0;            // of those, no net contact in the sim (tunnelling)
  int net_false = 0;             // net contacts the path does not have
  Stat frame_ns;                 // ns per frame of the court scene
};

struct StaticResults {
  int throws = 0;
  int ref_complete = 0;  // throws whose reference has 10 bounces
  int shots = 0;
  std::vector<StaticRow> rows;
};

// ---- Rackets ----

struct DetectRow {
  double rate = 0.0;
  int truth = 0;              // ground-truth hits (of swings)
  int found[BALL_DETECT_COUNT] = {};
  int missed[BALL_DETECT_COUNT] = {};
  int false_hits[BALL_DETECT_COUNT] = {};
  double toi_mean[BALL_DETECT_COUNT] = {};  // s: mean |t_sim - t_true| over the hits found
  double toi_max[BALL_DETECT_COUNT] = {};
  Stat frame_ns[BALL_DETECT_COUNT];         // ns per frame (push + step) with the test
  Stat base_ns;                             // the same frames without the racket stage
};

struct LandingCell {
  ball_level level = BALL_LEVEL_EASY;
  ball_response response = BALL_RESPONSE_RACKET;
  double rate = 0.0;
  int strokes = 0;
  int hits = 0;                  // strokes the level's test detected
  std::vector<double> distance;  // m, sorted: per hit, from the aim (autonomous: the partner)
};

struct RacketResults {
  int swings = 0;
  std::vector<DetectRow> detect;
  std::vector<LandingCell> landing;
};

// ---- Effects and the whole step ----

struct EffectRow {
  std::string on;       // effects on so far, "drag+spin"
  unsigned mask = 0;
  Stat ns_off;          // the full model, the rest off in the mask
  Stat ns_without;      // the model without what the rest acts on
};

struct FrameRow {
  std::string what;     // "sphere", "disc", "swept"
  Stat mean_ns;
  double median_ns = 0.0, worst_ns = 0.0;
  int hits = 0;
  long frames = 0;
};

struct StepResults {
  Stat lean_ns;                 // the yardstick (bench_kit.h)
  std::vector<EffectRow> effects;
  std::vector<FrameRow> frames; // rally_advanced.yaml, a whole frame with each test
  Stat predict_us, steps_us;
  int predict_contacts = 0;
};

struct Report {
  FlightResults flight;
  StaticResults statics;
  RacketResults rackets;
  StepResults step;
  std::vector<Check> checks;
  double seconds = 0.0;     // the run's wall clock
  std::string load_start;   // /proc/loadavg's 1-minute figure when the run began
};

// /proc/loadavg's 1-minute load average ("?" where there is none).
std::string load_average();

// The sections (accuracy_*.cpp). Each measures, adds its checks and writes
// its data files into opt.data_dir.
void run_flight(const Options &opt, Report &rep);
void run_static(const Options &opt, Report &rep);
void run_rackets(const Options &opt, Report &rep);
void run_step(const Options &opt, Report &rep);

// The page (accuracy_page.cpp).
bool write_page(const Options &opt, const Report &rep, const std::string &path);

// Shared helpers (accuracy_main.cpp).
void check(Report &rep, const std::string &what, bool pass, const std::string &detail);
FILE *open_data(const Options &opt, const std::string &name);  // exits on failure
const char *step_name(double h);  // "1/60", "1e-3"

}  // namespace acc

#endif  // BALL_VALIDATION_ACCURACY_H
