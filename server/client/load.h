// The load benchmark's core, free of DDS (docs/server-reference.md, "Load"): how
// ball-load splits the matches over its bot processes, what each process
// measures (a LoadPart, records.h) and how the parts of one run and the
// rounds of one point become the report; the meter of the samples the bots'
// client takes (from its tap), the payload bytes of those counts,
// the real instant of a sim time (hit-to-wire), and the few /proc figures
// (CPU, resident memory, loopback bytes) the report reads.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "port.h"
#include "records.h"

namespace ballsrv {

// Matches [first, first + count) played by one bot process.
struct MatchRange {
  int first = 0, count = 0;
};
// `count` matches from `first`, in k consecutive ranges whose sizes differ by
// at most one (the larger first); k is clamped to [1, count] (no empty range).
std::vector<MatchRange> split_matches(int first, int count, int k);

// The server instant (server s) at which sim time `sim` fell, by the
// (sim_time, server_time) pair and time base of a match's MatchInfo
// (docs/protocol.md, "Time"); valid while the match plays on from that pair.
double server_time_of(const MatchInfoOut &info, double sim);

// When each bot of a load begins (s, in bot order, two a match: ball-load's
// stagger): match m's both at start plus a draw in [0, stagger) from the
// seed and m alone, so that a match begins alike however the matches are
// split over processes.
std::vector<double> bot_starts(int first_match, int matches, uint64_t seed, double stagger, double start);

// ball-load's meter: the lines of the bots' client's tap (ball_net_set_tap,
// docs/client.md "A tap") counted by type, the newest MatchInfo of each
// match (for server_time_of), and, while `measuring`, the timings of the
// racket segments of this process's matches [first, first + count) by
// their DDS stamps (another process's matches are that one's to count)
// and the server's statuses, into `part`.
class LoadMeter {
 public:
  LoadMeter(int first_match, int matches) : first_(first_match), count_(matches) {}
  void line(const char *text, size_t length);
  // ball_net_tap's shape, `user` a LoadMeter
  static void tap(void *user, const char *text, size_t length) { static_cast<LoadMeter *>(user)->line(text, length); }

  bool measuring = false;
  LoadPart part;
  const PortCounts &counts() const { return counts_; }  // server samples taken, by type (writes: the client's)
  const MatchInfoOut *info(uint32_t match) const;      // nullptr: none taken yet
  uint64_t unreadable() const { return unreadable_; }

 private:
  static std::string type_of(const char *text, size_t length);
  void segment(const SegmentOut &seg, double recv, double sent);
  void status(const StatusOut &so);
  int first_, count_;
  PortCounts counts_;
  std::map<uint32_t, MatchInfoOut> infos_;
  bool have_first_ = false;
  uint64_t unreadable_ = 0;
};

// Payload bytes of the server's samples among `c` (taken), and of the
// client's own (written). RTPS, UDP and IP headers, heartbeats,
// acknowledgements, resends and discovery are not in them.
uint64_t server_payload(const PortCounts &c, const WireSizes &s);
uint64_t client_payload(const PortCounts &c, const WireSizes &s);
// Payload bytes per second the server wrote between two of its statuses
// (a the earlier): its own counts of segments, events and ball states,
// over the statuses' server_time between them; -1 when they are not two.
// (A bot reads no events, so what a client port takes leaves them out.)
double server_written_per_s(const StatusOut &a, const StatusOut &b, const WireSizes &s);
PortCounts operator-(const PortCounts &a, const PortCounts &b);

// /proc figures of one process and of the loopback device.
struct ProcUsage {
  double cpu = 0.0;  // s of CPU, user + system, since it started
  double rss = 0.0;  // bytes resident now
};
// From the texts of /proc/PID/stat and /proc/PID/status (ticks: the
// clock ticks per second); false when a text lacks its field.
bool parse_proc_stat(const std::string &stat, double ticks, double *cpu);
bool parse_proc_rss(const std::string &status, double *rss);
// The transmitted bytes and packets of `device` in a /proc/net/dev text.
bool parse_net_dev(const std::string &text, const std::string &device, uint64_t *bytes, uint64_t *packets);

// The figures of one run (one point, one round) from its parts: counts
// summed over the bot processes, hits and latencies pooled, the server's
// figures (its status, the payload of its samples) from the part that
// heard the most status periods. `seconds` is the window measured.
LoadRow combine(const std::vector<LoadPart> &parts, const WireSizes &sizes);

// Several rounds of one point as one row each: every number of the
// rounds' rows, its minimum and its median (of an even count, the lower
// middle value); the rows must be of one point.
struct LoadPoint {
  LoadRow min, median;
  int rounds = 0;
};
LoadPoint summarize(const std::vector<LoadRow> &rounds);
// The rows grouped by point (matches, state rate), in first-seen order.
std::vector<LoadPoint> summarize_points(const std::vector<LoadRow> &rows);

// The report: a table (a line a point; of several rounds two, the median
// and the min), with its two header lines or without, and gnuplot's data
// (one line a point, the medians, then the minimum overrun rate).
std::string load_table(const std::vector<LoadPoint> &points, bool header = true);
std::string load_plot_data(const std::vector<LoadPoint> &points);

}  // namespace ballsrv
