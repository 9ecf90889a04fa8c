// What the server loop counts (server_loop.h): the notes of the network
// side, the seqs lost, the status and the report.
#include "server_loop.h"

#include <algorithm>
#include <cinttypes>
#include <cstdio>

namespace ballsrv {

void ServerLoop::take_notes(double t0) {
  notes_.clear();
  port_.take_notes(&notes_);
  for (const auto &n : notes_) {
    switch (n.kind) {
      case PortNote::server_lost: {
        std::string line = cluster_.server_lost(n.who, t0);
        if (!line.empty()) say(line);
        break;
      }
      case PortNote::writer_lost:
        host_.on_participant_lost(n.who);
        stats_.writers_lost++;
        break;
      case PortNote::deadline_missed:
        stats_.deadline_missed += n.count;
        break;
      case PortNote::rejected:
        // refused by the reader past its room for rejected samples: counted in and dropped,
        // so that samples_in = samples_ok + idle + every drop (docs/protocol.md)
        stats_.totals.drops[static_cast<int>(SampleResult::rejected)] += n.count;
        stats_.totals.samples_in += n.count;
        break;
      case PortNote::lost:
        // DDS's own count of a writer's sequence gaps: kept apart, since `lost` comes from the
        // holders' own seqs (take_samples), and one forged datagram makes a gap of 2^31
        stats_.totals.dds_lost += std::min(n.count, kMaxLostPerNote);
        break;
      case PortNote::door_unknown_match:
      case PortNote::door_bad_slot:
      case PortNote::door_malformed: {
        // turned away at the door: not readable, or the first two checks of a sample (docs/protocol.md)
        SampleResult why = n.kind == PortNote::door_bad_slot      ? SampleResult::bad_slot
                           : n.kind == PortNote::door_malformed ? SampleResult::malformed
                                                                : SampleResult::unknown_match;
        stats_.totals.drops[static_cast<int>(why)] += n.count;
        stats_.totals.samples_in += n.count;
        break;
      }
      case PortNote::door_control:
      case PortNote::control_rejected:
      case PortNote::control_lost: {
        // controls DDS refused or lost: in, and refused, like a malformed one
        uint64_t count = n.kind == PortNote::control_lost ? std::min(n.count, kMaxLostPerNote) : n.count;
        stats_.totals.controls_in += count;
        stats_.totals.controls_refused += count;
        if (n.kind == PortNote::door_control) stats_.controls_at_door += count;
        if (n.kind == PortNote::control_rejected) stats_.controls_no_room += count;
        break;
      }
    }
  }
}

void ServerLoop::count_lost(uint64_t lost) {
  stats_.totals.drops[static_cast<int>(SampleResult::lost)] += lost;
  stats_.totals.samples_in += lost;
}

double ServerLoop::uptime() const { return clock_.mono() - start_; }

StatusOut ServerLoop::status_now() const {
  StatusOut o = stats_.totals;
  o.server_id = settings_.server_id;
  o.server_time = clock_.realtime();
  o.uptime = uptime();
  o.frame_p50 = stats_.frame_time.quantile(0.5);
  o.frame_p99 = stats_.frame_time.quantile(0.99);
  o.latency_p50 = stats_.latency.quantile(0.5);
  o.latency_p99 = stats_.latency.quantile(0.99);
  o.matches = static_cast<uint32_t>(sched_.size());
  o.playing = 0;
  for (const auto &s : sched_) o.playing += s.match->state() == MatchState::playing;
  o.max_matches = static_cast<uint32_t>(host_.max_matches());
  o.following = static_cast<uint32_t>(cluster_.following().size());
  o.claim_room = cluster_.own_view().claim_room;
  o.standby = settings_.standby;
  o.strength = cluster_.settings().strength;
  return o;
}

ServerReport ServerLoop::report() const {
  ServerReport r;
  r.status = status_;
  r.infos_out = stats_.infos_out;
  r.skipped_frames = stats_.skipped;
  r.late_p99_median = stats_.late_p99.quantile(0.5);
  r.late_p99_max = stats_.late_p99.max();
  r.late_max = stats_.late_max;
  r.deadline_missed = stats_.deadline_missed;
  r.writers_lost = stats_.writers_lost;
  r.controls_at_door = stats_.controls_at_door;
  r.controls_no_room = stats_.controls_no_room;
  const ClusterStats &c = cluster_.stats();
  r.creates_elsewhere = c.creates_elsewhere;
  r.others_refused = c.others_refused;
  r.conflicts = c.conflicts;
  r.takeovers = c.takeovers;
  r.takeovers_waiting = c.takeovers_waiting;
  r.stale_terms = c.stale_terms;
  r.unknown_writers = c.unknown_writers;
  r.unheld_let_go = c.unheld_let_go;
  r.yields = c.yields;
  r.claims = c.claims;
  r.follow_failures = c.follow_failures;
  r.created_expired = stats_.created_expired;
  r.following = static_cast<uint32_t>(cluster_.following().size());
  r.latency_p50 = stats_.latency_all.quantile(0.5);
  r.latency_p99 = stats_.latency_all.quantile(0.99);
  r.latency_count = stats_.latency_all.size();
  r.hit_wakes = stats_.hit_wakes;
  r.hit_late_p50 = stats_.hit_late.quantile(0.5);
  r.hit_late_p99 = stats_.hit_late.quantile(0.99);
  r.hit_known = stats_.hit_wake_late.size();
  r.hit_wake_late_p99 = stats_.hit_wake_late.quantile(0.99);
  r.hit_found_after = stats_.hit_found_late.size();
  r.hit_found_late_p50 = stats_.hit_found_late.quantile(0.5);
  r.hit_found_late_p99 = stats_.hit_found_late.quantile(0.99);
  for (const auto &sc : sched_) {
    const Match *m = sc.match;
    MatchReport mr;
    mr.since = sc.since;
    mr.taken_over = sc.taken_over;
    mr.id = m->id();
    mr.state = m->state();
    mr.counters = m->counters();
    mr.score = m->score();
    mr.sim_time = m->sim().time;
    mr.sim_hash = m->sim_hash();
    r.matches.push_back(mr);
  }
  return r;
}

std::string status_line(const StatusOut &o) {
  char buf[1024];
  std::snprintf(buf, sizeof buf,
                "ball-server %u: %.0f s, matches %u (%u playing), samples in %" PRIu64 " ok %" PRIu64 " idle %" PRIu64
                ", drops %s, out %" PRIu64 " states %" PRIu64 " segments %" PRIu64 " events, failed writes %" PRIu64
                ", overruns %" PRIu64 ", frame p50 %.3f ms p99 %.3f ms, latency p50 %.1f ms p99 %.1f ms",
                o.server_id, o.uptime, o.matches, o.playing, o.samples_in, o.samples_ok, o.samples_idle,
                drops_text(o.drops).c_str(), o.states_out, o.segments_out, o.events_out, o.write_failures,
                o.overruns, o.frame_p50 * 1e3, o.frame_p99 * 1e3, o.latency_p50 * 1e3, o.latency_p99 * 1e3);
  return buf;
}

}  // namespace ballsrv
