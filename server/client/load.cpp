#include "load.h"

#include <algorithm>
#include <cstdio>
#include <sstream>

#include "frame_clock.h"
#include "rng.h"

namespace ballsrv {

std::vector<MatchRange> split_matches(int first, int count, int k) {
  std::vector<MatchRange> out;
  if (count <= 0) return out;
  k = std::max(1, std::min(k, count));
  int at = first;
  for (int i = 0; i < k; ++i) {
    int n = count / k + (i < count % k ? 1 : 0);
    out.push_back({at, n});
    at += n;
  }
  return out;
}

double server_time_of(const MatchInfoOut &info, double sim) {
  return info.server_time + (sim - info.sim_time) / info.settings.time_base;
}

std::vector<double> bot_starts(int first_match, int matches, uint64_t seed, double stagger, double start) {
  std::vector<double> out;
  for (int m = first_match; m < first_match + matches; ++m) {
    Rng rng(seed * 0x9e3779b97f4a7c15ull + static_cast<uint64_t>(m));
    double at = start + stagger * rng.uniform();
    out.insert(out.end(), {at, at});
  }
  return out;
}

// The "type" of a tap line, read off its text: the ball states and events,
// most of the lines, are only counted, and are not parsed for that ("": none).
std::string LoadMeter::type_of(const char *text, size_t length) {
  static const std::string key = "\"type\":\"";
  const char *end = text + length;
  const char *at = std::search(text, end, key.begin(), key.end());
  if (at == end) return "";
  at += key.size();
  const char *close = std::find(at, end, '"');
  return close == end ? "" : std::string(at, close);
}

void LoadMeter::line(const char *text, size_t length) {
  const std::string type = type_of(text, length);
  if (type == "state" || type == "event") {
    (type == "state" ? counts_.states : counts_.events)++;
    return;
  }
  json j = json::parse(text, text + length, nullptr, false);
  if (!j.is_object() || record_type(j) != type) {
    unreadable_++;
    return;
  }
  try {
    if (type == "match_info") {
      MatchInfoOut info = j.get<MatchInfoOut>();
      counts_.infos++;
      infos_[info.match_id] = info;
    } else if (type == "segment") {
      counts_.segments++;
      segment(j.get<SegmentOut>(), j.at("recv").get<double>(), j.value("sent", 0.0));
    } else if (type == "server_status") {
      counts_.statuses++;
      status(j.get<StatusOut>());
    }
  } catch (const std::exception &) {
    unreadable_++;
  }
}

// a hit's segment: newest sample written -> received, and the hit's sim
// time as the server's real instant -> written -> received (`sent`: the
// segment's DDS source timestamp, 0 unknown)
void LoadMeter::segment(const SegmentOut &seg, double recv, double sent) {
  const bool ours = seg.match_id >= static_cast<uint32_t>(first_) &&
                    seg.match_id < static_cast<uint32_t>(first_ + count_);
  if (!measuring || !ours || seg.cause != Cause::racket || !seg.sample.valid) return;
  part.latency.push_back(recv - seg.sample.source_time);
  const MatchInfoOut *i = info(seg.match_id);
  // (a MatchInfo without its clock pair maps nothing: no figure rather than a wrong one;
  // a correction's t0 lies back by its late sample's trip: lag compensation's, not a hit's way out)
  if (!i || i->settings.time_base <= 0.0 || i->server_time <= 0.0 || seg.correction) return;
  double hit = server_time_of(*i, seg.segment.t0);
  part.hit_to_wire.push_back(recv - hit);
  if (sent > 0.0) {  // its two parts, where DDS said both
    part.hit_to_write.push_back(sent - hit);
    part.delivery.push_back(recv - sent);
  }
}

void LoadMeter::status(const StatusOut &so) {
  if (!measuring) return;
  if (!have_first_) part.first = so;
  have_first_ = true;
  part.last = so;
  part.frame_p50.push_back(so.frame_p50);
  part.frame_p99.push_back(so.frame_p99);
}

const MatchInfoOut *LoadMeter::info(uint32_t match) const {
  auto it = infos_.find(match);
  return it == infos_.end() ? nullptr : &it->second;
}

uint64_t server_payload(const PortCounts &c, const WireSizes &s) {
  return c.infos * s.info + c.segments * s.segment + c.states * s.state + c.events * s.event + c.statuses * s.status;
}

uint64_t client_payload(const PortCounts &c, const WireSizes &s) {
  return c.samples_written * s.sample + c.controls_written * s.control;
}

double server_written_per_s(const StatusOut &a, const StatusOut &b, const WireSizes &s) {
  double span = b.server_time - a.server_time;
  if (!(span > 0.0) || b.segments_out < a.segments_out || b.events_out < a.events_out || b.states_out < a.states_out)
    return -1.0;
  uint64_t bytes = (b.segments_out - a.segments_out) * s.segment + (b.events_out - a.events_out) * s.event +
                   (b.states_out - a.states_out) * s.state;
  return static_cast<double>(bytes) / span;
}

PortCounts operator-(const PortCounts &a, const PortCounts &b) {
  return {a.infos - b.infos,       a.segments - b.segments, a.states - b.states,
          a.events - b.events,     a.statuses - b.statuses, a.samples_written - b.samples_written,
          a.controls_written - b.controls_written};
}

// ---- /proc ---------------------------------------------------------------------

bool parse_proc_stat(const std::string &stat, double ticks, double *cpu) {
  // "pid (comm) state ppid ...": comm may hold spaces and parentheses, so
  // count the fields from the last ')'; utime and stime are fields 14, 15
  size_t close = stat.rfind(')');
  if (close == std::string::npos || ticks <= 0.0) return false;
  std::istringstream in(stat.substr(close + 1));
  std::string field;
  double utime = 0.0, stime = 0.0;
  for (int i = 3; i <= 15; ++i) {
    if (!(in >> field)) return false;
    if (i == 14) utime = std::stod(field);
    if (i == 15) stime = std::stod(field);
  }
  *cpu = (utime + stime) / ticks;
  return true;
}

bool parse_proc_rss(const std::string &status, double *rss) {
  std::istringstream in(status);
  std::string line;
  while (std::getline(in, line)) {
    if (line.compare(0, 6, "VmRSS:") != 0) continue;
    std::istringstream f(line.substr(6));
    double kib = 0.0;
    std::string unit;
    if (!(f >> kib >> unit) || unit != "kB") return false;
    *rss = kib * 1024.0;
    return true;
  }
  return false;
}

bool parse_net_dev(const std::string &text, const std::string &device, uint64_t *bytes, uint64_t *packets) {
  // "  lo: rx_bytes rx_packets errs drop fifo frame compressed multicast tx_bytes tx_packets ..."
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    size_t colon = line.find(':');
    if (colon == std::string::npos) continue;
    std::string name = line.substr(0, colon);
    name.erase(0, name.find_first_not_of(' '));
    if (name != device) continue;
    std::istringstream f(line.substr(colon + 1));
    uint64_t v[10];
    for (auto &x : v)
      if (!(f >> x)) return false;
    *bytes = v[8];
    *packets = v[9];
    return true;
  }
  return false;
}

// ---- the report ----------------------------------------------------------------

// The server's side of a row, from the part that read its status the
// longest: frames, overruns, frame times, and the bytes it wrote a match.
static void add_server(const LoadPart &server, const WireSizes &sizes, double seconds, LoadRow *out) {
  LoadRow &row = *out;
  Percentiles p50, p99;
  for (double v : server.frame_p50) p50.add(v);
  for (double v : server.frame_p99) p99.add(v);
  row.server_frames = server.last.frames - server.first.frames;
  row.server_overruns = server.last.overruns - server.first.overruns;
  row.overrun_pct = row.server_frames ? 100.0 * static_cast<double>(row.server_overruns) /
                                            static_cast<double>(row.server_frames)
                                      : 0.0;
  row.frame_p50_ms = p50.quantile(0.5) * 1e3;
  row.frame_p99_ms_median = p99.quantile(0.5) * 1e3;
  row.frame_p99_ms_max = p99.max() * 1e3;
  row.playing = server.last.playing;
  // what the server wrote: segments, events and ball states by its own
  // counts; MatchInfos and statuses, which it does not count there, as one
  // bot process took them (every process reads every match's)
  double per = row.matches > 0 && seconds > 0.0 ? 1.0 / (row.matches * seconds) : 0.0;
  double counted = server_written_per_s(server.first, server.last, sizes);
  PortCounts heard;
  heard.infos = server.counts.infos;
  heard.statuses = server.counts.statuses;
  if (counted >= 0.0 && row.matches > 0)
    row.server_bytes = counted / row.matches + static_cast<double>(server_payload(heard, sizes)) * per;
}

LoadRow combine(const std::vector<LoadPart> &parts, const WireSizes &sizes) {
  LoadRow row;
  if (parts.empty()) return row;
  row = parts[0].row;
  row.matches = row.bots = 0;
  row.samples_per_s = 0.0;
  row.write_failures = 0;
  row.ready = true;
  row.bot_processes = static_cast<int>(parts.size());
  Percentiles latency, h2w, h2write, delivery;
  const LoadPart *server = &parts[0];
  double seconds = 0.0;
  uint64_t written = 0;
  for (const auto &p : parts) {
    row.matches += p.row.matches;
    row.bots += p.row.bots;
    row.samples_per_s += p.row.samples_per_s;
    row.write_failures += p.row.write_failures;
    row.ready = row.ready && p.row.ready;
    seconds = std::max(seconds, p.row.seconds);
    written += client_payload(p.counts, sizes);
    for (double v : p.latency) latency.add(v);
    for (double v : p.hit_to_wire) h2w.add(v);
    for (double v : p.hit_to_write) h2write.add(v);
    for (double v : p.delivery) delivery.add(v);
    if (p.frame_p50.size() > server->frame_p50.size()) server = &p;
  }
  row.seconds = seconds;
  row.hits = latency.size();
  row.latency_p50_ms = latency.quantile(0.5) * 1e3;
  row.latency_p99_ms = latency.quantile(0.99) * 1e3;
  row.hit_to_wire_p50_ms = h2w.quantile(0.5) * 1e3;
  row.hit_to_wire_p99_ms = h2w.quantile(0.99) * 1e3;
  row.hit_to_write_p50_ms = h2write.quantile(0.5) * 1e3;
  row.hit_to_write_p99_ms = h2write.quantile(0.99) * 1e3;
  row.delivery_p50_ms = delivery.quantile(0.5) * 1e3;
  row.delivery_p99_ms = delivery.quantile(0.99) * 1e3;
  add_server(*server, sizes, seconds, &row);
  row.bots_bytes = static_cast<double>(written) * (row.matches > 0 && seconds > 0.0 ? 1.0 / (row.matches * seconds) : 0.0);
  return row;
}


LoadPoint summarize(const std::vector<LoadRow> &rounds) {
  LoadPoint p;
  p.rounds = static_cast<int>(rounds.size());
  if (rounds.empty()) return p;
  json lo = rounds[0], mid = rounds[0];
  for (auto it = lo.begin(); it != lo.end(); ++it) {
    const std::string &key = it.key();
    if (it->is_boolean()) {
      bool all = true;
      for (const auto &r : rounds) all = all && json(r)[key].get<bool>();
      lo[key] = mid[key] = all;
    } else if (it->is_number()) {
      std::vector<json> v;
      for (const auto &r : rounds) v.push_back(json(r)[key]);
      std::sort(v.begin(), v.end(), [](const json &a, const json &b) { return a.get<double>() < b.get<double>(); });
      lo[key] = v.front();
      mid[key] = v[(v.size() - 1) / 2];
    }
  }
  p.min = lo.get<LoadRow>();
  p.median = mid.get<LoadRow>();
  return p;
}

std::vector<LoadPoint> summarize_points(const std::vector<LoadRow> &rows) {
  std::vector<std::vector<LoadRow>> groups;
  for (const auto &r : rows) {
    auto g = std::find_if(groups.begin(), groups.end(), [&](const std::vector<LoadRow> &x) {
      return x[0].matches == r.matches && x[0].state_rate == r.state_rate && x[0].server_priority == r.server_priority;
    });
    if (g == groups.end()) groups.push_back({r});
    else g->push_back(r);
  }
  std::vector<LoadPoint> out;
  for (const auto &g : groups) out.push_back(summarize(g));
  return out;
}

namespace {

std::string fmt(const char *f, double v) {
  if (v < 0.0) return "-";
  char buf[32];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

}  // namespace

std::string load_table(const std::vector<LoadPoint> &points, bool header) {
  std::string out;
  char line[512];
  const char *head =
      "%7s %6s %4s %4s %5s %6s %8s %8s %7s %7s %7s %7s %7s %7s %7s %7s %7s %7s %7s %7s %7s %8s %8s\n";
  std::snprintf(line, sizeof line, head, "matches", "states", "prio", "proc", "round", "hits", "samp/s", "overrun",
                "work50", "work99", "lat50", "lat99", "h2w50", "h2w99", "h2s99", "s2r99", "srvCPU", "srvRSS", "botCPU", "botRSS",
                "srv B/s", "bot B/s", "lo B/s");
  if (header) out += line;
  std::snprintf(line, sizeof line, head, "", "Hz", "", "", "", "", "", "%", "ms", "ms", "ms", "ms", "ms", "ms", "ms",
                "ms", "%/match", "KiB/m", "%/match", "KiB/m", "/match", "/match", "/match");
  if (header) out += line;
  for (const auto &p : points)
    for (int which = 0; which < (p.rounds > 1 ? 2 : 1); ++which) {
      const LoadRow &r = which == 0 ? p.median : p.min;
      std::snprintf(line, sizeof line,
                    "%7d %6s %4s %4d %5s %6llu %8.0f %7.2f%% %7.3f %7.3f %7.1f %7.1f %7.1f %7.1f %7.1f %7.1f %7s %7s %7s %7s "
                    "%7s %8s %8s%s\n",
                    r.matches, fmt("%.0f", r.state_rate).c_str(),
                    r.server_priority > 0 ? ("F" + std::to_string(r.server_priority)).c_str() : "-", r.bot_processes,
                    p.rounds == 1 ? "1" : which == 0 ? "med" : "min",
                    static_cast<unsigned long long>(r.hits), r.samples_per_s, r.overrun_pct, r.frame_p50_ms,
                    r.frame_p99_ms_median, r.latency_p50_ms, r.latency_p99_ms, r.hit_to_wire_p50_ms,
                    r.hit_to_wire_p99_ms, r.hit_to_write_p99_ms, r.delivery_p99_ms, fmt("%.3f", r.server_cpu_pct).c_str(),
                    fmt("%.1f", r.server_rss_kib).c_str(), fmt("%.3f", r.bots_cpu_pct).c_str(),
                    fmt("%.1f", r.bots_rss_kib).c_str(), fmt("%.0f", r.server_bytes).c_str(),
                    fmt("%.0f", r.bots_bytes).c_str(), fmt("%.0f", r.lo_bytes).c_str(),
                    r.ready ? "" : "  (not every slot joined)");
      out += line;
    }
  return out;
}

std::string load_plot_data(const std::vector<LoadPoint> &points) {
  std::string out =
      "# matches state_rate overrun_pct work_p50_ms work_p99_ms latency_p50_ms latency_p99_ms h2w_p50_ms h2w_p99_ms "
      "server_cpu_pct server_rss_kib bots_cpu_pct server_bytes bots_bytes lo_bytes overrun_pct_min (medians; per "
      "match)\n";
  char line[512];
  for (const auto &p : points) {
    const LoadRow &r = p.median;
    std::snprintf(line, sizeof line, "%d %g %.4f %.4f %.4f %.3f %.3f %.3f %.3f %.5f %.3f %.5f %.2f %.2f %.2f %.4f\n",
                  r.matches, r.state_rate, r.overrun_pct, r.frame_p50_ms, r.frame_p99_ms_median, r.latency_p50_ms,
                  r.latency_p99_ms, r.hit_to_wire_p50_ms, r.hit_to_wire_p99_ms, r.server_cpu_pct, r.server_rss_kib,
                  r.bots_cpu_pct, r.server_bytes, r.bots_bytes, r.lo_bytes, p.min.overrun_pct);
    out += line;
  }
  return out;
}

}  // namespace ballsrv
