// The watcher's summary as ball-watch prints it (watcher.h, summary_lines).
#include <cinttypes>
#include <cstdio>

#include "watcher.h"

namespace ballsrv {

std::vector<std::string> summary_lines(const WatchSummary &s) {
  std::vector<std::string> out;
  char buf[512];
  for (const auto &m : s.matches) {
    std::snprintf(buf, sizeof buf,
                  "summary: match %u: %" PRIu64 " hits, %" PRIu64 " bounces, %" PRIu64 " serves, %" PRIu64
                  " points (score %d-%d), %" PRIu64 " pauses; desync: %" PRIu64 " of %" PRIu64
                  " ball states checked, max |error| %.3g m",
                  m.match, m.hits, m.bounces, m.serves, m.points, m.score[0], m.score[1], m.pauses, m.states_checked,
                  m.states, m.max_error);
    out.push_back(buf);
  }
  for (const auto &o : s.servers) {
    std::snprintf(buf, sizeof buf,
                  "summary: server %u: %" PRIu64 " racket samples in, %" PRIu64 " accepted, %" PRIu64
                  " idle, dropped %s, %" PRIu64 " writes refused, %" PRIu64 " frame overruns",
                  o.server_id, o.samples_in, o.samples_ok, o.samples_idle, drops_text(o.drops).c_str(),
                  o.write_failures, o.overruns);
    out.push_back(buf);
  }
  std::snprintf(buf, sizeof buf,
                "summary: sample-to-segment latency (a hit's newest racket sample written -> its segment received): "
                "p50 %.1f ms, p99 %.1f ms over %" PRIu64 " hits",
                s.latency_p50 * 1e3, s.latency_p99 * 1e3, s.latency_count);
  out.push_back(buf);
  uint64_t bounces = s.bounces_ahead + s.bounces_late;
  if (bounces > 0) {
    std::snprintf(buf, sizeof buf,
                  "summary: contacts written ahead: %" PRIu64 " of %" PRIu64
                  " received before they happen (lead p1 %.0f ms, p50 %.0f ms), %" PRIu64 " superseded by a hit",
                  s.bounces_ahead, bounces, s.bounce_lead_p1 * 1e3, s.bounce_lead_p50 * 1e3, s.bounces_superseded);
    out.push_back(buf);
  }
  if (s.untrusted > 0) {
    std::snprintf(buf, sizeof buf,
                  "summary: %" PRIu64 " server samples refused: their writer lacks the certificate of their server id",
                  s.untrusted);
    out.push_back(buf);
  }
  return out;
}

}  // namespace ballsrv
