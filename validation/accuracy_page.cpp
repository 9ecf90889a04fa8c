// docs/accuracy.md, written from one run's numbers: every figure and every
// claim of the page comes from the Report, so that rerunning `./run accuracy`
// rewrites the page and its plots together.
#include <sys/utsname.h>
#include <unistd.h>

#include <cmath>
#include <ctime>
#include <fstream>
#include <sstream>

#include "accuracy.h"
#include "bench_kit.h"
#include "common.h"

namespace acc {

namespace {

using bv::fmt;

// ---- numbers in words ----

std::string sci(double x) {
  if (x == 0.0) return "0";
  if (!std::isfinite(x)) return "-";
  return fmt("%.1e", x);
}

std::string ns(double t) {  // a duration given in ns
  if (!std::isfinite(t)) return "-";
  if (t < 10.0) return fmt("%.1f ns", t);
  if (t < 1e3) return fmt("%.0f ns", t);
  if (t < 1e4) return fmt("%.2f us", t / 1e3);
  if (t < 1e6) return fmt("%.0f us", t / 1e3);
  if (t < 1e9) return fmt("%.1f ms", t / 1e6);
  return fmt("%.2f s", t / 1e9);
}

std::string seconds(double t) {  // a time given in s
  if (!std::isfinite(t)) return "-";
  if (t == 0.0) return "0 s";
  if (t < 1e-6) return sci(t) + " s";
  return ns(1e9 * t);
}

std::string metres(double m) {
  if (!std::isfinite(m)) return "-";
  if (m == 0.0) return "0 m";
  if (m < 1e-3) return sci(m) + " m";
  if (m < 0.1) return fmt("%.1f cm", m * 100.0);
  return fmt("%.2f m", m);
}

std::string times(double r) {  // a ratio
  if (!std::isfinite(r)) return "-";
  if (r < 10.0) return fmt("%.1f", r);
  if (r < 1e5) return fmt("%.0f", r);
  return sci(r);
}

std::string pct(double num, double den) { return den > 0 ? fmt("%.1f %%", 100.0 * num / den) : "-"; }

std::string minmed(const Stat &s) { return ns(s.min) + " / " + ns(s.median); }

// ---- lookups ----

const FlightRow *flight_row(const Report &r, double T, const std::string &method, const std::string &step) {
  for (const FlightCase &c : r.flight.cases)
    if (c.T == T)
      for (const FlightRow &row : c.rows)
        if (row.method == method && row.step == step) return &row;
  return nullptr;
}

double flight_err(const Report &r, double T, const std::string &method, const std::string &step) {
  const FlightRow *row = flight_row(r, T, method, step);
  return row ? row->err_path : NAN;
}

double flight_cost(const Report &r, double T, const std::string &method, const std::string &step) {
  const FlightRow *row = flight_row(r, T, method, step);
  return row ? row->ns_per_s.median : NAN;
}

double flight_query(const Report &r, double T, const std::string &method, const std::string &step) {
  const FlightRow *row = flight_row(r, T, method, step);
  return row ? row->query_ns.median : NAN;
}

const StaticRow *static_row(const Report &r, ball_scheme s, double rate) {
  for (const StaticRow &row : r.statics.rows)
    if (row.scheme == s && row.rate == rate) return &row;
  return nullptr;
}

const DetectRow *detect_row(const Report &r, double rate) {
  for (const DetectRow &row : r.rackets.detect)
    if (row.rate == rate) return &row;
  return nullptr;
}

double hit_pct(const DetectRow *d, int test) {
  return d && d->truth ? 100.0 * d->found[test] / d->truth : NAN;
}

const LandingCell *landing_cell(const Report &r, double rate, ball_level level, ball_response resp) {
  for (const LandingCell &c : r.rackets.landing)
    if (c.rate == rate && c.level == level && c.response == resp) return &c;
  return nullptr;
}

double quantile(const LandingCell *c, double q) {
  if (!c || c->distance.empty()) return NAN;
  size_t i = static_cast<size_t>(q * (c->distance.size() - 1) + 0.5);
  return c->distance[i];
}

const FrameRow *frame_row(const Report &r, const std::string &what) {
  for (const FrameRow &f : r.step.frames)
    if (f.what == what) return &f;
  return nullptr;
}

// ---- the machine ----

std::string machine() {
  std::string cpu = "unknown CPU";
  std::ifstream in("/proc/cpuinfo");
  for (std::string line; std::getline(in, line);)
    if (line.rfind("model name", 0) == 0) {
      cpu = line.substr(line.find(':') + 2);
      break;
    }
  struct utsname u;
  std::string os = uname(&u) == 0 ? std::string(u.sysname) + " " + u.release : "unknown OS";
  std::string distro;
  std::ifstream rel("/etc/os-release");
  for (std::string line; std::getline(rel, line);)
    if (line.rfind("PRETTY_NAME=", 0) == 0) distro = line.substr(13, line.size() - 14) + ", ";
  return fmt("%s, %ld cores, %s%s, g++ %s", cpu.c_str(), sysconf(_SC_NPROCESSORS_ONLN), distro.c_str(), os.c_str(),
             __VERSION__);
}

std::string today() {
  char buf[32];
  std::time_t t = std::time(nullptr);
  std::strftime(buf, sizeof buf, "%Y-%m-%d", std::gmtime(&t));
  return buf;
}

// ---- sections ----

void choosing(std::ostream &o, const Report &r) {
  const double ev = flight_cost(r, 2.0, "libball", "1/60") / 60.0;  // ns per state
  const StaticRow *sa60 = static_row(r, BALL_SCHEME_SAMPLED, 60), *ex60 = static_row(r, BALL_SCHEME_EXACT, 60);
  const StaticRow *sa15 = static_row(r, BALL_SCHEME_SAMPLED, 15), *sa2 = static_row(r, BALL_SCHEME_SAMPLED, 2);
  const FrameRow *swept = frame_row(r, "swept"), *disc = frame_row(r, "disc");
  o << "## Choosing\n\n"
       "Read off the measured tables below (this run). Racket figures are at the racket **sample** rate (the "
       "study steps one frame per sample); flight and obstacle figures at the **frame** rate. Costs are for the "
       "ball of one match, per frame.\n\n";
  o << "- **Flight: the closed form, always.** A state costs " << ns(ev) << " (`ball_flight_eval`; one "
    << "\"where at t\" from a segment, `ball_segment_eval`, " << ns(flight_query(r, 2.0, "libball", "1/60"))
    << ") and is exact to rounding (" << metres(flight_err(r, 2.0, "libball", "1e-4")) << " over 2 s, "
    << metres(flight_err(r, 10.0, "libball", "1e-4")) << " over 10 s). At a 60 Hz step Euler is off by "
    << metres(flight_err(r, 2.0, "Euler", "1/60")) << " after 2 s and RK4 by "
    << metres(flight_err(r, 2.0, "RK4", "1/60")) << "; MuJoCo's RK4 costs "
    << times(flight_cost(r, 2.0, "MuJoCo RK4", "1/60") / flight_cost(r, 2.0, "libball", "1/60"))
    << " times the closed form per simulated second at that step, and a query at t = 2 s "
    << times(flight_query(r, 2.0, "MuJoCo RK4", "1/60") / flight_query(r, 2.0, "libball", "1/60"))
    << " times.\n";
  if (sa60 && ex60 && sa15 && sa2)
    o << "- **Static obstacles: the exact scheme**, at every frame rate: bounces where the reference puts them "
      << "(to " << sci(std::max(ex60->max_dt, 1e-16)) << " s), no net hit missed or made up, and a frame costs "
      << ns(ex60->frame_ns.min) << " against the sampled scheme's " << ns(sa60->frame_ns.min) << " at 60 Hz. The "
      << "sampled scheme (the paper's) is there to compare: at 15 Hz its first bounce is off by "
      << ns(1e9 * sa15->first_dt) << " and " << metres(sa15->first_dp) << " on average, and at 2 Hz it lets "
      << pct(sa2->net_missed, sa2->net_truth) << " of the net hits through.\n";
  o << "- **Racket test: swept, unless the budget says no.** It finds every hit at every sample rate, at the "
       "exact time of impact. Its cost is the frames where a racket is near: the detection study's frames cost "
       "it "
    << ns(detect_row(r, 60) ? detect_row(r, 60)->frame_ns[BALL_DETECT_SWEPT].min : NAN) << " at 60 Hz and "
    << ns(detect_row(r, 2) ? detect_row(r, 2)->frame_ns[BALL_DETECT_SWEPT].min : NAN)
    << " at 2 Hz (long frames, long searches); a whole frame of the advanced rally costs "
    << ns(swept ? swept->median_ns : NAN) << " (median) and " << ns(swept ? swept->worst_ns : NAN)
    << " at worst. Where that worst frame does not fit, the disc test ("
    << ns(disc ? disc->worst_ns : NAN) << " at worst) finds "
    << fmt("%.0f %%", hit_pct(detect_row(r, 60), BALL_DETECT_DISC)) << " of the hits at 60 Hz, "
    << fmt("%.0f %%", hit_pct(detect_row(r, 10), BALL_DETECT_DISC)) << " at 10 Hz, "
    << fmt("%.0f %%", hit_pct(detect_row(r, 2), BALL_DETECT_DISC)) << " at 2 Hz, and reports hits the "
    << "geometry does not have; the sphere test finds "
    << fmt("%.0f %%", hit_pct(detect_row(r, 10), BALL_DETECT_SPHERE)) << " at 10 Hz (a d_COLL of r_disc + r).\n";
  const LandingCell *a10 = landing_cell(r, 10, BALL_LEVEL_EASY, BALL_RESPONSE_AUTONOMOUS);
  const LandingCell *m60 = landing_cell(r, 60, BALL_LEVEL_MID, BALL_RESPONSE_MIXED);
  const LandingCell *k60 = landing_cell(r, 60, BALL_LEVEL_ADVANCED, BALL_RESPONSE_RACKET);
  const LandingCell *k10 = landing_cell(r, 10, BALL_LEVEL_ADVANCED, BALL_RESPONSE_RACKET);
  const LandingCell *p60 = landing_cell(r, 60, BALL_LEVEL_ADVANCED, BALL_RESPONSE_PHYSICAL);
  o << "- **Response: by what the players should control.** The autonomous ball (eq 8, 9) arrives at the "
       "partner's racket whatever the stroke, off only by the stroke's height (median "
    << metres(quantile(a10, 0.5)) << "); mixed 0.8 (eq 10) lands within " << metres(quantile(m60, 0.5))
    << " of the aim (median, mid level, 60 Hz), but only for a player who swings five times the correction; "
       "eq 7 follows the racket: "
    << metres(quantile(k60, 0.5)) << " at 60 Hz, " << metres(quantile(k10, 0.5))
    << " at 10 Hz (it restarts the ball V0 dt ahead); the physical response (eq 11) reflects about the "
       "face, so it about doubles the face's angle error: "
    << metres(quantile(p60, 0.5)) << " at 60 Hz with 3 degrees of face error.\n\n";

  // example setups, each choice made by the rules above from the numbers
  struct Setup {
    double frame, samples, budget_ns;
    ball_level level;
    const char *who;
  } setups[] = {{120, 60, 5000, BALL_LEVEL_ADVANCED, "VR headsets on a fast network"},
                {60, 15, 1000, BALL_LEVEL_MID, "desktop clients, an ordinary network"},
                {15, 6, 300, BALL_LEVEL_EASY, "the paper's slow network"},
                {60, 10, 200, BALL_LEVEL_MID, "a server with many matches on one core"}};
  o << "| setup | frame rate | racket samples | budget per frame | scheme | racket test | response "
       "(level) | what it buys (this run) |\n|---|---|---|---|---|---|---|---|\n";
  for (const Setup &s : setups) {
    const DetectRow *d = detect_row(r, s.samples);
    const StaticRow *ex = static_row(r, BALL_SCHEME_EXACT, s.frame);
    if (!d || !ex || !swept) continue;
    // swept when its worst rally frame fits the budget, or its mean frame at
    // this sample rate does (then the worst frames overrun now and then)
    bool swept_fits = swept->worst_ns <= s.budget_ns, swept_mean = d->frame_ns[BALL_DETECT_SWEPT].min <= s.budget_ns;
    int test = swept_fits || swept_mean ? BALL_DETECT_SWEPT : BALL_DETECT_DISC;
    ball_response resp = s.level == BALL_LEVEL_ADVANCED ? BALL_RESPONSE_PHYSICAL
                         : s.level == BALL_LEVEL_MID    ? BALL_RESPONSE_MIXED
                                                        : BALL_RESPONSE_AUTONOMOUS;
    double lrate = s.samples >= 30 ? 60 : 10;
    const LandingCell *lc = landing_cell(r, lrate, s.level, resp);
    std::string buys = fmt("bounces exact; %s of the hits found", fmt("%.0f %%", hit_pct(d, test)).c_str());
    buys += test == BALL_DETECT_SWEPT ? ", time of impact to " + seconds(d->toi_max[test])
                                      : fmt(", %.0f false per 1000 swings, hit time up to %s late",
                                            1000.0 * d->false_hits[test] / r.rackets.swings,
                                            seconds(d->toi_max[test]).c_str());
    if (test == BALL_DETECT_SWEPT && !swept_fits)
      buys += fmt(" (worst frames %s: over budget)", ns(swept->worst_ns).c_str());
    if (lc)
      buys += fmt("; lands %s from the %s (median, %g Hz)", metres(quantile(lc, 0.5)).c_str(),
                  resp == BALL_RESPONSE_AUTONOMOUS ? "partner" : "aim", lrate);
    o << "| " << s.who << " | " << s.frame << " Hz | " << s.samples << " Hz | " << ns(s.budget_ns) << " | exact | "
      << ball_detect_name(static_cast<ball_detect>(test)) << " | " << ball_response_name(resp) << " ("
      << ball_level_name(s.level) << ") | " << buys << " |\n";
  }
  o << "\n";
}

void flight(std::ostream &o, const Report &r) {
  const FlightResults &f = r.flight;
  o << "## Flight\n\n"
    << fmt("The integrator sweep's shot (docs/validation.md): a tennis ball (b = m / beta = %.2f s) from "
           "(%g, %g, %g) m at (%g, %g, %g) m/s, drag only, flown for 2 s and, with no floor, for 10 s. The "
           "reference is eq 3 in long double (64-bit mantissa), so libball's own rounding shows. The error is "
           "the largest distance from the reference at the step instants over the flight; the cost is wall "
           "clock per simulated second with a state at every step (libball: `ball_flight_eval` at those "
           "instants), and for one query \"where is the ball at T\" (libball: one `ball_segment_eval`; an "
           "integrator steps from 0 to T). The integrators: explicit Euler, semi-implicit Euler and RK4 written "
           "for the comparison (validation/accuracy_flight.cpp, on eq 1, 2), MuJoCo 2.2's Euler (semi-implicit, "
           "damping implicit) and RK4 on the validation's twin model (validation/mujoco_ball.h; the state set "
           "once, then the steps).\n\n",
           f.b, f.p0.x, f.p0.y, f.p0.z, f.v0.x, f.v0.y, f.v0.z);
  o << "![Flight: error against cost per simulated second](img/accuracy/flight.png)\n\n"
    << "![Flight: error against the cost of one query](img/accuracy/flight_query.png)\n\n"
    << "*(In the plots an error below 1e-16 m, or of exactly 0, is drawn at 1e-16 m.)*\n\n";
  const char *methods[] = {"libball", "Euler", "semi-implicit Euler", "RK4", "MuJoCo Euler", "MuJoCo RK4"};
  for (const FlightCase &c : f.cases) {
    o << "**" << c.name << "**: largest position error (m) / wall clock per simulated second (median)\n\n"
      << "| step (s) |";
    for (const char *m : methods) o << " " << m << " |";
    o << "\n|---|";
    for (size_t i = 0; i < sizeof methods / sizeof methods[0]; i++) o << "---|";
    o << "\n";
    std::vector<std::string> steps;
    for (const FlightRow &row : c.rows)
      if (row.method == "libball") steps.push_back(row.step);
    for (const std::string &st : steps) {
      o << "| " << st << " |";
      for (const char *m : methods) {
        const FlightRow *row = flight_row(r, c.T, m, st);
        o << " " << (row ? sci(row->err_path) + " / " + ns(row->ns_per_s.median) : "-") << " |";
      }
      o << "\n";
    }
    o << "\n";
  }
  // one query
  o << "One query at T (median): libball " << ns(flight_query(r, 2.0, "libball", "1/60")) << " (2 s), "
    << ns(flight_query(r, 10.0, "libball", "1/60")) << " (10 s); RK4 integrating to T at 1/60 s "
    << ns(flight_query(r, 2.0, "RK4", "1/60")) << " and " << ns(flight_query(r, 10.0, "RK4", "1/60"))
    << "; MuJoCo's RK4 at 1e-3 s " << ns(flight_query(r, 2.0, "MuJoCo RK4", "1e-3")) << " and "
    << ns(flight_query(r, 10.0, "MuJoCo RK4", "1e-3")) << ".\n\n";
  // whether RK4 at its best is still short of the closed form at its worst, flight by flight
  double lib60 = flight_cost(r, 2.0, "libball", "1/60");
  bool rk4_short = true;
  for (const FlightCase &c : f.cases) {
    double rk4_best = INFINITY, lib_worst = 0.0;
    for (const FlightRow &row : c.rows) {
      if (row.method == "RK4") rk4_best = std::min(rk4_best, row.err_path);
      if (row.method == "libball") lib_worst = std::max(lib_worst, row.err_path);
    }
    rk4_short = rk4_short && rk4_best > lib_worst;
  }
  o << "What it shows:\n\n"
    << "- **The closed form is exact at any rate**: " << metres(flight_err(r, 2.0, "libball", "1e-4"))
    << " over 2 s, " << metres(flight_err(r, 10.0, "libball", "1e-4"))
    << " over 10 s (rounding: the 10 s flight falls a few hundred metres), for " << ns(lib60 / 60.0)
    << " a state.\n"
    << "- **Euler, either kind, is first order**: off by " << metres(flight_err(r, 2.0, "Euler", "1/60"))
    << " after 2 s at 1/60 s and still " << metres(flight_err(r, 2.0, "Euler", "1e-4"))
    << " at 1e-4 s; over 10 s " << metres(flight_err(r, 10.0, "Euler", "1/60")) << " at 1/60 s.\n"
    << "- **RK4 is fourth order until rounding stops it**: " << metres(flight_err(r, 2.0, "RK4", "1/6"))
    << " at 1/6 s, " << metres(flight_err(r, 2.0, "RK4", "1/60")) << " at 1/60 s, then no better than "
    << metres(flight_err(r, 2.0, "RK4", "1e-3")) << " (2 s); over 10 s the rounding of 100,000 steps grows "
    << "it back to " << metres(flight_err(r, 10.0, "RK4", "1e-4")) << " at 1e-4 s. A step costs "
    << times(flight_cost(r, 2.0, "RK4", "1/60") / lib60) << " times a closed-form state (at 1/60 s)"
    << (rk4_short ? "; at no step does it reach the closed form's accuracy" : "") << ".\n"
    << "- **MuJoCo's RK4 is the same RK4** (its errors are the ones written here to 0.1 %, a check below) "
    << "at " << times(flight_cost(r, 2.0, "MuJoCo RK4", "1/60") / flight_cost(r, 2.0, "RK4", "1/60"))
    << " times the cost per step: a general engine's step (mj_step with its stages) for a ball.\n"
    << "- **A query is where the closed form wins outright**: one evaluation, against "
    << times(flight_query(r, 2.0, "RK4", "1/60") / flight_query(r, 2.0, "libball", "1/60"))
    << " times as long for RK4 at 1/60 s to reach t = 2 s, and "
    << times(flight_query(r, 10.0, "MuJoCo RK4", "1e-3") / flight_query(r, 10.0, "libball", "1/60"))
    << " times for MuJoCo's RK4 at 1e-3 s to reach t = 10 s.\n\n";
}

void statics(std::ostream &o, const Report &r) {
  const StaticResults &s = r.statics;
  o << "## Static obstacles\n\n"
    << fmt("The paper's **sampled** scheme (Fig. 1, 3: the floor and the frame's chord tested at the end of each "
           "frame, the response there) against the **exact** scheme (contacts in closed form on the path), at "
           "frame rates from 2 to 120 Hz:\n\n"
           "- *bounces*: %d seeded throws of a tennis ball (radius 0.033 m, floorDamping 0.75, b = 2.85 s) from "
           "1-2.5 m, 2-8 m/s across and 4-7 m/s up, on the floor alone; each sim's first 10 floor events against "
           "a reference computed here in long double (eq 3 to the contact, eq 5 there). Errors are means over "
           "the throws: the first bounce, and the worst of the 10; the energy (kinetic and potential above the "
           "contact height) just after the 10th bounce, relative;\n"
           "- *net*: %d seeded shots of a point ball (Fig. 3's) from 1-10 m in front of the tennis net at "
           "8-60 m/s, aimed at points of the net's plane from 0.02 to 1.6 m high and from z = -1 to 12 m: the "
           "truth (eq 3 in long double) is whether the path crosses inside the net; a sim's verdict is whether "
           "its first contact is the net; shots grazing an edge to 1e-9 m are left out;\n"
           "- *cost*: ns per frame of ball_bench's court scene (a 7 s serve with drag, spin, floor, net, two "
           "walls and sound), min and median of the rounds.\n\n",
           s.throws, s.shots);
  o << "![Static obstacles: errors, net hits and cost against frame rate](img/accuracy/static.png)\n\n"
    << "*(In the plots an error below 1e-16, or of exactly 0, is drawn at 1e-16.)*\n\n"
    << "| rate | scheme | 1st bounce: time / point error | worst of 10: time / point error | energy error "
       "after 10 | net hits missed | net hits made up | ns per frame (min / median) |\n"
       "|---|---|---|---|---|---|---|---|\n";
  for (const StaticRow &row : s.rows)
    o << "| " << row.rate << " Hz | " << ball_scheme_name(row.scheme) << " | " << sci(row.first_dt) << " s / "
      << sci(row.first_dp) << " m | " << sci(row.max_dt) << " s / " << sci(row.max_dp) << " m | "
      << (row.short_throws ? fmt("(%d throws short)", row.short_throws) : fmt("%.2g", row.energy_rel)) << " | "
      << row.net_missed << " of " << row.net_truth << " | " << row.net_false << " of " << s.shots - row.net_truth
      << " | " << minmed(row.frame_ns) << " |\n";
  const StaticRow *sa2 = static_row(r, BALL_SCHEME_SAMPLED, 2), *sa120 = static_row(r, BALL_SCHEME_SAMPLED, 120);
  const StaticRow *sa60 = static_row(r, BALL_SCHEME_SAMPLED, 60), *ex60 = static_row(r, BALL_SCHEME_EXACT, 60);
  const StaticRow *ex2 = static_row(r, BALL_SCHEME_EXACT, 2), *sa15 = static_row(r, BALL_SCHEME_SAMPLED, 15);
  if (!sa2 || !sa120 || !sa60 || !ex60 || !ex2 || !sa15) return;
  // the lowest rate from which on the sampled scheme gets every shot right
  int first_clean = 0;
  bool exact_cheaper = true;
  for (const StaticRow &row : s.rows) {
    if (row.scheme != BALL_SCHEME_SAMPLED) {
      exact_cheaper = exact_cheaper && row.frame_ns.min < static_row(r, BALL_SCHEME_SAMPLED, row.rate)->frame_ns.min;
      continue;
    }
    if (row.net_missed == 0 && row.net_false == 0) {
      if (!first_clean) first_clean = static_cast<int>(row.rate);
    } else {
      first_clean = 0;
    }
  }
  o << "\nWhat it shows:\n\n"
    << "- **The exact scheme does not depend on the frame rate**: the same bounces at 2 and 120 Hz, to "
    << sci(std::max(ex2->max_dt, ex60->max_dt)) << " s and " << sci(std::max(ex2->max_dp, ex60->max_dp))
    << " m of the reference, the energy to " << sci(ex60->worst_energy_rel)
    << ", and not one net hit missed or made up.\n"
    << "- **The sampled scheme is late by up to a frame at every bounce** (" << ns(1e9 * sa15->first_dt)
    << " on average at 15 Hz, " << ns(1e9 * sa120->first_dt)
    << " at 120 Hz), and it reflects the ball where it found it, below the floor: the bounce gains the "
       "energy of that depth, and the errors add up bounce after bounce (worst of 10: "
    << ns(1e9 * sa60->max_dt) << " and " << metres(sa60->max_dp) << " at 60 Hz; the energy after 10 bounces "
    << fmt("%.0f %%", 100.0 * sa60->energy_rel) << " off at 60 Hz, " << fmt("%.0f %%", 100.0 * sa120->energy_rel)
    << " at 120 Hz).\n"
    << "- **Tunnelling**: at 2 Hz the sampled scheme lets " << pct(sa2->net_missed, sa2->net_truth)
    << " of the net hits through (the frame's chord passes under the net, through the floor) and makes up "
    << pct(sa2->net_false, s.shots - sa2->net_truth) << " of the misses (the chord cuts the net under a ball "
    << "that flies over it); "
    << (first_clean ? fmt("from %d Hz on it neither misses nor makes up any", first_clean)
                    : std::string("even at 120 Hz a few are wrong"))
    << ".\n"
    << "- **Cost**: " << (exact_cheaper ? "exact is the cheaper at every rate, " : "")
    << ns(ex60->frame_ns.min) << " a frame against " << ns(sa60->frame_ns.min) << " at 60 Hz, "
    << ns(ex2->frame_ns.min) << " against " << ns(sa2->frame_ns.min)
    << " at 2 Hz: the sampled scheme tests the net and every wall against each frame's chord, the exact one "
       "compares the clock with the next contact it worked out when the segment began (and resolves every "
       "contact of a long frame).\n\n";
}

void rackets(std::ostream &o, const Report &r) {
  const RacketResults &k = r.rackets;
  o << "## Rackets\n\n### The tests against the sample rate\n\n"
    << fmt("docs/rackets.md's detection study, grown: %d seeded swings (kit/swings.h: a tennis ball at "
           "10-30 m/s, a disc of r = 0.15 m swinging at 5-30 m/s, accelerating up to 30 m/s^2, turning up to "
           "6 rad/s; one in five overtaking a slow ball), the racket sampled at 2 to 120 Hz and one frame "
           "stepped per sample, through `ball_step` with each test (d_COLL = r_disc + r for the sphere test). "
           "The ground truth is the same motions sampled every 2e-5 s, its contact refined by bisection. The "
           "hit rate is the share of the ground truth's hits a test finds; false hits are hits the ground truth "
           "does not have; the time-of-impact error is against the refined contact; the cost is a frame (push "
           "and step) over the swings' frames, min of interleaved rounds, and the test's share of it (the "
           "frame less the same frame without a racket stage).\n\n",
           k.swings);
  o << "![Rackets: hit rate, time of impact and cost against the sample rate](img/accuracy/rackets.png)\n\n"
    << "| rate | ground-truth hits | sphere: hit rate / false / time error | disc: hit rate / false / time error "
       "| swept: hit rate / false / time error | ns per frame (the test's share): sphere / disc / swept; no "
       "racket stage |\n"
       "|---|---|---|---|---|---|\n";
  for (const DetectRow &d : k.detect) {
    o << "| " << d.rate << " Hz | " << d.truth << " |";
    for (int t = 0; t < BALL_DETECT_COUNT; t++)
      o << " " << fmt("%.1f %%", hit_pct(&d, t)) << " / " << d.false_hits[t] << " / " << seconds(d.toi_mean[t])
        << " |";
    o << " " << fmt("%.0f (%.0f) / %.0f (%.0f) / %.0f (%.0f); %.0f", d.frame_ns[0].min,
                    d.frame_ns[0].min - d.base_ns.min, d.frame_ns[1].min, d.frame_ns[1].min - d.base_ns.min,
                    d.frame_ns[2].min, d.frame_ns[2].min - d.base_ns.min, d.base_ns.min)
      << " |\n";
  }
  const DetectRow *d2 = detect_row(r, 2), *d10 = detect_row(r, 10), *d120 = detect_row(r, 120);
  if (d2 && d10 && d120)
    o << "\nWhat it shows:\n\n"
      << "- **swept** finds every hit at every rate, none that is not there, at the contact time to "
      << sci(std::max(d2->toi_max[2], d120->toi_max[2])) << " s. It pays at low rates, where a frame is long "
      << "and the search covers it: " << ns(d2->frame_ns[2].min) << " a frame at 2 Hz, "
      << ns(d120->frame_ns[2].min) << " at 120 Hz.\n"
      << "- **disc** (the paper's Fig. 4, 5) finds " << fmt("%.0f %%", hit_pct(d2, 1)) << " at 2 Hz, "
      << fmt("%.0f %%", hit_pct(d10, 1)) << " at 10 Hz, " << fmt("%.0f %%", hit_pct(d120, 1))
      << " at 120 Hz: it sees the racket's motion over a frame as one straight shift and its normal at one "
         "instant, and it reports "
      << d10->false_hits[1] << " hits per " << k.swings << " swings at 10 Hz that the geometry does not have; "
      << "its hit time is the frame's end (" << ns(1e9 * d10->toi_mean[1]) << " late on average at 10 Hz).\n"
      << "- **sphere** (the paper's distance test) misses what moves more than d_COLL in a frame: "
      << fmt("%.0f %%", hit_pct(d10, 0)) << " found at 10 Hz, " << fmt("%.0f %%", hit_pct(d120, 0))
      << " at 120 Hz; it is meant for slow, generous play (the easy level's d_COLL is 0.3 m).\n\n";

  o << "### Where the ball lands: the four responses at each game level\n\n"
       "A player returns balls that come at 12-25 m/s to a contact point 2.5 m from the baseline, 0.8-1.3 m "
       "high, aiming at a random point of the far court (x from 15 to 22 m). The player knows the response and "
       "swings what would put the ball on the aim: eq 7 follows the racket, so the racket moves as the shot; "
       "eq 10 is solved for the racket (five times the shot's difference from the friendly ball: sometimes a "
       "swing backwards, which the tests then often miss); eq 11 is solved for the face's normal and speed "
       "(no brush, so no spin); the autonomous ball ignores the swing. The player errs as players do: 10 ms of "
       "timing, up to 6 cm off the face's centre, 5 % of speed, 3 degrees of swing direction and 3 degrees of "
       "face angle, +-10 m/s^2 of acceleration through the stroke, 2 mm of tracker noise. Each level's preset "
       "(test, normal, spin) with the response swapped in (mixed with friendlyFactor 0.8, autonomous with 1); "
       "racket samples and frames at 10 and 60 Hz. The distance is from the aim to the first bounce on the "
       "court (net and floor on), or, for the autonomous ball, from the partner's racket to the ball when eq 8 "
       "puts it there (after t0 = 2 V_up / g, at the stroke's height).\n\n"
    << "![Landing: distance from the aim, by level, response and rate](img/accuracy/landing.png)\n\n";
  o << "| level | response | 10 Hz: hits / median / 90 % | 60 Hz: hits / median / 90 % |\n|---|---|---|---|\n";
  for (ball_level lv : {BALL_LEVEL_EASY, BALL_LEVEL_MID, BALL_LEVEL_ADVANCED})
    for (ball_response rs :
         {BALL_RESPONSE_RACKET, BALL_RESPONSE_AUTONOMOUS, BALL_RESPONSE_MIXED, BALL_RESPONSE_PHYSICAL}) {
      o << "| " << ball_level_name(lv) << " | " << ball_response_name(rs) << " |";
      for (double rate : {10.0, 60.0}) {
        const LandingCell *c = landing_cell(r, rate, lv, rs);
        if (!c) {
          o << " - |";
          continue;
        }
        o << " " << pct(c->hits, c->strokes) << " / " << metres(quantile(c, 0.5)) << " / "
          << metres(quantile(c, 0.9)) << " |";
      }
      o << "\n";
    }
  const LandingCell *e10 = landing_cell(r, 10, BALL_LEVEL_EASY, BALL_RESPONSE_AUTONOMOUS);
  const LandingCell *e60 = landing_cell(r, 60, BALL_LEVEL_EASY, BALL_RESPONSE_AUTONOMOUS);
  const LandingCell *k10 = landing_cell(r, 10, BALL_LEVEL_ADVANCED, BALL_RESPONSE_RACKET);
  const LandingCell *k60 = landing_cell(r, 60, BALL_LEVEL_ADVANCED, BALL_RESPONSE_RACKET);
  const LandingCell *pm = landing_cell(r, 60, BALL_LEVEL_MID, BALL_RESPONSE_PHYSICAL);
  const LandingCell *pa = landing_cell(r, 60, BALL_LEVEL_ADVANCED, BALL_RESPONSE_PHYSICAL);
  const LandingCell *mm = landing_cell(r, 60, BALL_LEVEL_MID, BALL_RESPONSE_MIXED);
  if (e10 && e60 && k10 && k60 && pm && pa && mm)
    o << "\nWhat it shows:\n\n"
      << "- **autonomous**: the ball is over the partner's racket every time (horizontally to rounding, a check "
         "below); what is left is eq 8's goal height, the stroke's, against the racket's: median "
      << metres(quantile(e60, 0.5)) << ". The easy level's sphere test finds only " << pct(e10->hits, e10->strokes)
      << " of these strokes at 10 Hz (" << pct(e60->hits, e60->strokes) << " at 60 Hz): fast balls pass d_COLL "
      << "between two frames.\n"
      << "- **racket (eq 7)** carries the swing's errors and restarts the ball V0 dt ahead of the contact: median "
      << metres(quantile(k60, 0.5)) << " at 60 Hz, " << metres(quantile(k10, 0.5)) << " at 10 Hz (advanced).\n"
      << "- **mixed 0.8 (eq 10)**: median " << metres(quantile(mm, 0.5)) << " (mid, 60 Hz): the racket's "
      << "errors count a fifth. The price is the swing, five times the correction; "
      << pct(mm->strokes - mm->hits, mm->strokes) << " of those swings miss the ball.\n"
      << "- **physical (eq 11)** reflects about the face: 3 degrees of face error turn the reflected part of "
      << "the shot by 6, median "
      << metres(quantile(pa, 0.5)) << " with the tracked normal (advanced), " << metres(quantile(pm, 0.5))
      << " with the velocity normal (mid), where the face is wherever the racket's estimated velocity points.\n\n";
}

void step(std::ostream &o, const Report &r) {
  const StepResults &s = r.step;
  auto at_ref = [&](double x) { return x * BENCH_REF_LEAN_NS / s.lean_ns.median; };
  o << "## Effects and the whole step\n\n"
       "ball_bench's court scene (a 7 s serve at 60 Hz: drag, spin, floor, net, two walls, sound) with two "
       "rackets standing clear of the ball, tracked every frame while the rackets effect is on. The effects are "
       "switched on one by one; at each stage the full model with the effects still off cleared from the mask "
       "is timed against the model without what they act on (no drag, no spin, the floor out of reach, no net, "
       "no walls, no rackets, no sound threshold: docs/model.md, \"Effects\"). Both give the same path to the "
       "bit (a check below); min and median of interleaved rounds.\n\n"
       "![Effects: cost per frame as effects are switched on](img/accuracy/effects.png)\n\n"
       "| effects on | the rest off in the mask | the rest removed from the model | ratio (min) | this "
       "effect's cost (min) |\n|---|---|---|---|---|\n";
  double lo = 1e9, hi = 0.0;
  for (size_t i = 0; i < s.effects.size(); i++) {
    const EffectRow &e = s.effects[i];
    double ratio = e.ns_off.min / e.ns_without.min;
    lo = std::min(lo, ratio);
    hi = std::max(hi, ratio);
    o << "| " << e.on << " | " << minmed(e.ns_off) << " | " << minmed(e.ns_without) << " | " << fmt("%.3f", ratio)
      << " | " << (i == 0 ? ns(e.ns_off.min) + " (a bare frame)" : ns(e.ns_off.min - s.effects[i - 1].ns_off.min))
      << " |\n";
  }
  o << "\nOff in the mask against removed from the model: " << fmt("%.2f to %.2f", lo, hi)
    << (lo >= 0.9 && hi <= 1.1 ? ", within this run's noise: a scene pays only for the effects it uses (a "
                                 "disabled effect costs nothing measurable)."
                               : ": beyond 10 %, more than this run's noise should explain; rerun on a quieter "
                                 "machine before reading anything into it.")
    << " The rackets stage includes the two `ball_racket_push` calls a frame.\n\n";
  const FrameRow *sw = frame_row(r, "swept");
  o << "**A whole frame** (ball_bench's rally: `rally_advanced.yaml`, ball, floor, net, two rackets with their "
       "scripted samples pushed as they arrive, physical response; `ball_step` with each test) and **the 6 s "
       "prediction at 120 Hz a bot asks every frame** (`ball_predict`, the serve with its contacts). "
    << fmt("This run's lean evaluation (the yardstick, docs/benchmarks.md) took %.1f ns (median), so `@ref` = "
           "ns x %.2f scales to the machine docs/benchmarks.md's targets were set on. The last column says "
           "whether this one run met a target; whether libball meets it is judged in "
           "[benchmarks.md](benchmarks.md#targets), over pinned runs.\n\n",
           s.lean_ns.median, BENCH_REF_LEAN_NS / s.lean_ns.median)
    << "| figure | this run | @ref | target (docs/benchmarks.md) | met in this run |\n|---|---|---|---|---|\n";
  for (const FrameRow &f : s.frames)
    o << "| rally frame, " << f.what << " test: median frame (mean of whole passes, min / median) | "
      << ns(f.median_ns) << " (" << minmed(f.mean_ns) << ") | " << ns(at_ref(f.median_ns)) << " | <= 100 ns | "
      << (at_ref(f.median_ns) <= 100.0 ? "yes" : fmt("no: %.2f x the target", at_ref(f.median_ns) / 100.0))
      << " |\n";
  if (sw)
    o << "| rally frame, swept test, worst frame | " << ns(sw->worst_ns) << " | " << ns(at_ref(sw->worst_ns))
      << " | <= 2 us | "
      << (at_ref(sw->worst_ns) <= 2000.0 ? "yes" : fmt("no: %.1f x the target", at_ref(sw->worst_ns) / 2000.0))
      << " |\n";
  o << "| `ball_predict`, 6 s at 120 Hz (" << s.predict_contacts << " contacts), min / median | "
    << minmed(Stat{1e3 * s.predict_us.min, 1e3 * s.predict_us.median}) << " | " << ns(at_ref(1e3 * s.predict_us.median))
    << " | <= 5 us | "
    << (at_ref(1e3 * s.predict_us.median) <= 5000.0
            ? "yes"
            : fmt("no: %.1f x the target", at_ref(1e3 * s.predict_us.median) / 5000.0))
    << " |\n"
    << "| 720 `ball_step` of the same path, min / median | "
    << minmed(Stat{1e3 * s.steps_us.min, 1e3 * s.steps_us.median})
    << " | " << ns(at_ref(1e3 * s.steps_us.median)) << " | | |\n\n";
  o << "Where the time goes: docs/benchmarks.md (a swept frame near a racket is a search along the path; the "
       "prediction is one `expm1` per state). Its figures come from a quieter run of the same programs; on a "
       "loaded machine the single-frame figures suffer most.\n\n";
}

void made(std::ostream &o, const Report &r) {
  int failed = 0;
  for (const Check &c : r.checks) failed += !c.pass;
  o << "## How this page is made\n\n"
       "`./run accuracy` builds `ball_accuracy` (validation/accuracy_*.cpp; it measures with ball_bench's "
       "pieces, kit/bench_kit.h, and the detection study's swings, kit/swings.h; libball's "
       "public API only), runs it, which writes the plots' data to build/accuracy/ and this page, then runs "
       "the gnuplot scripts in validation/plots/ into docs/img/accuracy/. Nothing on the page is written by "
       "hand: change the program and rerun. "
    << fmt("This run's measurements took %.0f s. ", r.seconds)
    << "`ctest --test-dir build --no-tests=error -L accuracy` runs the program in its quick mode (tiny sets, one short round), which asserts "
       "nothing about time and every check below.\n\n"
    << fmt("Sanity checks of this run (%zu, %d failed):\n\n", r.checks.size(), failed);
  for (const Check &c : r.checks)
    o << "- " << (c.pass ? "ok" : "**FAILED**") << ": " << c.what << " (" << c.detail << ")\n";
  o << "\n";
}

}  // namespace

bool write_page(const Options &opt, const Report &rep, const std::string &path) {
  std::ostringstream o;
  o << "# What accuracy costs in time\n\n"
    << "*Generated by `./run accuracy`: do not edit, rerun (\"How this page is made\", at the end).*\n\n"
    << "One run on " << today() << ": " << machine()
    << fmt(", -O2; load average %s at the start, %s at the end (the machine is shared). Timings are the min and "
           "the median of %d rounds; every ratio compares numbers of this run.\n\n",
           rep.load_start.c_str(), load_average().c_str(), opt.rounds);
  choosing(o, rep);
  flight(o, rep);
  statics(o, rep);
  rackets(o, rep);
  step(o, rep);
  made(o, rep);
  std::ofstream f(path);
  f << o.str();
  if (!f) {
    std::fprintf(stderr, "ball_accuracy: cannot write %s\n", path.c_str());
    return false;
  }
  return true;
}

}  // namespace acc
