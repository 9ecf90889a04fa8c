#include "server_loop.h"

#include <cinttypes>
#include <cstdio>

namespace ballsrv {

ServerLoop::ServerLoop(Host &host, ServerPort &port, Clock &clock, const LoopSettings &settings)
    : host_(host), port_(port), clock_(clock), settings_(settings) {}

bool ServerLoop::find_owner(double seconds, const std::function<bool()> &stop, MatchInfoOut *other) {
  double until = clock_.mono() + seconds;
  ParticipantId from;
  while (clock_.mono() < until && !stop()) {
    while (port_.take_other_info(other, &from))
      if (host_.find(other->match_id)) return true;
    clock_.sleep_until(clock_.mono() + 0.05);
  }
  return false;
}

// Every match's frames count from the server's start, so matches of the
// same frame rate are stepped on the same wake-ups.
ServerLoop::Scheduled ServerLoop::schedule(Match *m) {
  Scheduled s{m, FrameClock(m->frame_time(), origin_)};
  double now = clock_.mono();
  s.k = s.clock.first_at(now);
  s.last_frame_real = s.clock.realtime_at(now);
  return s;
}

void ServerLoop::start() {
  origin_ = FrameClock(1.0, clock_.mono(), clock_.realtime());
  for (const auto &m : host_.matches()) {
    sched_.push_back(schedule(m.get()));
    publish_info(sched_.back());
  }
  start_ = clock_.mono();
  next_status_ = start_ + settings_.status_interval;
  status_ = status_now();
}

template <class T>
void ServerLoop::write(const T &sample, uint64_t *written) {
  if (port_.write(sample)) (*written)++;
  else stats_.write_failures++;
}

void ServerLoop::publish(const MatchOutput &out, Scheduled &s, double now) {
  for (SegmentOut seg : out.segments) {
    seg.server_id = settings_.server_id;
    seg.server_time = now;
    write(seg, &stats_.totals.segments_out);
    if (seg.cause == Cause::racket && seg.sample.valid && seg.sample.source_time > 0.0) {
      double lat = now - seg.sample.source_time;
      stats_.latency.add(lat);
      stats_.latency_all.add(lat);
    }
  }
  for (EventOut e : out.events) {
    e.server_id = settings_.server_id;
    e.server_time = now;
    write(e, &stats_.totals.events_out);
  }
  if (out.has_state) {
    StateOut state = out.state;
    state.server_id = settings_.server_id;
    state.server_time = s.last_frame_real;
    write(state, &stats_.totals.states_out);
  }
}

void ServerLoop::publish_info(Scheduled &s) {
  MatchInfoOut info = s.match->info();
  info.server_id = settings_.server_id;
  info.server_time = s.last_frame_real;  // sim_time holds from the newest frame's deadline
  info.revision = ++s.revision;
  write(info, &stats_.infos_out);
}

// ---- the phases ----------------------------------------------------------------

void ServerLoop::take_notes() {
  notes_.clear();
  port_.take_notes(&notes_);
  for (const auto &n : notes_) {
    switch (n.kind) {
      case PortNote::writer_lost:
        host_.on_participant_lost(n.who);
        stats_.writers_lost++;
        break;
      case PortNote::deadline_missed:
        stats_.deadline_missed += n.count;
        break;
      case PortNote::rejected:
      case PortNote::lost: {
        // refused by the reader or lost on the link: counted in and dropped, so that
        // samples_in = samples_ok + idle + every drop (docs/protocol.md)
        SampleResult why = n.kind == PortNote::rejected ? SampleResult::rejected : SampleResult::lost;
        stats_.totals.drops[static_cast<int>(why)] += n.count;
        stats_.totals.samples_in += n.count;
        break;
      }
    }
  }
}

void ServerLoop::take_samples(double now) {
  RacketSampleIn sample;
  while (port_.take_sample(&sample)) {
    stats_.totals.samples_in++;
    SampleResult r = host_.on_sample(sample, now);
    if (r == SampleResult::accepted) stats_.totals.samples_ok++;
    else if (r == SampleResult::idle) stats_.samples_idle++;
    else stats_.totals.drops[static_cast<int>(r)]++;
  }
}

void ServerLoop::take_controls(double now) {
  ControlIn control;
  while (port_.take_control(&control)) {
    stats_.totals.controls_in++;
    if (!control.valid) {
      stats_.totals.controls_refused++;
      continue;
    }
    out_.clear();
    Match *m = nullptr;
    size_t before = host_.matches().size();
    Reason r = host_.on_control(control, now, &out_, &m);
    if (r != Reason::none) stats_.totals.controls_refused++;
    if (host_.matches().size() > before) sched_.push_back(schedule(host_.matches().back().get()));  // CREATE
    if (!m) continue;
    for (auto &s : sched_)
      if (s.match == m) {
        publish(out_, s, now);
        if (out_.info_changed) publish_info(s);
      }
  }
}

void ServerLoop::run_due_frames(double t0, double now) {
  for (auto &s : sched_) {
    double d = s.clock.deadline(s.k);
    if (d > t0 + 1e-6) continue;
    // far behind (the machine stalled): skip to now rather than race
    double behind = (t0 - d) / s.clock.period();
    if (behind > settings_.max_behind) {
      uint64_t skip = static_cast<uint64_t>(behind);
      s.k += skip;
      stats_.skipped += skip;
      d = s.clock.deadline(s.k);
    }
    s.last_frame_real = s.clock.realtime_at(d);
    stats_.late.add(t0 - d);
    stats_.late_max = std::max(stats_.late_max, t0 - d);
    out_.clear();
    s.match->frame(now, &out_);
    s.k++;
    stats_.totals.frames++;
    publish(out_, s, now);
    if (out_.info_changed || t0 >= s.next_info) {
      publish_info(s);
      s.next_info = t0 + settings_.info_interval;
    }
    // an overrun: the frame was done only after the next one was due
    if (clock_.mono() > s.clock.deadline(s.k)) stats_.totals.overruns++;
  }
}

void ServerLoop::check_conflicts(const std::function<void(const MatchInfoOut &, const ParticipantId &)> &on_conflict) {
  MatchInfoOut info;
  ParticipantId from;
  while (port_.take_other_info(&info, &from))
    if (host_.find(info.match_id)) {
      stats_.conflicts++;
      if (on_conflict) on_conflict(info, from);
    }
}

double ServerLoop::next_wake() const {
  double wake = next_status_;
  for (const auto &s : sched_) wake = std::min(wake, s.clock.deadline(s.k));
  return wake;
}

bool ServerLoop::step() {
  clock_.sleep_until(next_wake());
  return wake();
}

bool ServerLoop::wake() {
  double t0 = clock_.mono();
  double now = clock_.realtime();
  take_notes();
  take_samples(now);
  take_controls(now);
  run_due_frames(t0, now);
  double t1 = clock_.mono();
  stats_.frame_time.add(t1 - t0);
  if (t1 < next_status_) return false;
  // the status phase
  check_conflicts(on_conflict_);
  close_period();
  stats_.late_p99.add(stats_.late.quantile(0.99));
  stats_.late.clear();
  stats_.frame_time.clear();
  stats_.latency.clear();
  next_status_ += settings_.status_interval;
  if (next_status_ < t1) next_status_ = t1 + settings_.status_interval;
  return true;
}

void ServerLoop::close_period() {
  status_ = status_now();
  stats_.period_latency_p50 = stats_.latency.quantile(0.5);
  stats_.period_latency_p99 = stats_.latency.quantile(0.99);
  write(status_, &stats_.statuses_out);
}

void ServerLoop::run(double duration, const std::function<bool()> &stop,
                     const std::function<void(const StatusOut &)> &on_status,
                     const std::function<void(const MatchInfoOut &, const ParticipantId &)> &on_conflict) {
  on_conflict_ = on_conflict;
  while (!stop()) {
    if (duration > 0.0 && clock_.mono() - start_ >= duration) break;
    clock_.sleep_until(next_wake());
    if (stop()) break;
    if (wake() && on_status) on_status(status_);
  }
}

StatusOut ServerLoop::finish() {
  close_period();  // the last, partial period
  return status_;
}

double ServerLoop::uptime() const { return clock_.mono() - start_; }

StatusOut ServerLoop::status_now() const {
  StatusOut o = stats_.totals;
  o.server_id = settings_.server_id;
  o.server_time = clock_.realtime();
  o.uptime = uptime();
  o.matches = static_cast<uint32_t>(host_.matches().size());
  for (const auto &m : host_.matches()) o.playing += m->state() == MatchState::playing;
  o.frame_p50 = stats_.frame_time.quantile(0.5);
  o.frame_p99 = stats_.frame_time.quantile(0.99);
  return o;
}

ServerReport ServerLoop::report() const {
  ServerReport r;
  r.status = status_;
  r.samples_idle = stats_.samples_idle;
  r.infos_out = stats_.infos_out;
  r.write_failures = stats_.write_failures;
  r.skipped_frames = stats_.skipped;
  r.late_p99_median = stats_.late_p99.quantile(0.5);
  r.late_p99_max = stats_.late_p99.max();
  r.late_max = stats_.late_max;
  r.deadline_missed = stats_.deadline_missed;
  r.writers_lost = stats_.writers_lost;
  r.conflicts = stats_.conflicts;
  r.latency_p50 = stats_.latency_all.quantile(0.5);
  r.latency_p99 = stats_.latency_all.quantile(0.99);
  r.latency_count = stats_.latency_all.size();
  for (const auto &m : host_.matches()) {
    MatchReport mr;
    mr.id = m->id();
    mr.state = m->state();
    mr.counters = m->counters();
    mr.score = m->score();
    mr.sim_time = m->sim().time;
    mr.sim_hash = ball_sim_hash(&m->sim());
    r.matches.push_back(mr);
  }
  return r;
}

std::string status_line(const StatusOut &o, const LoopStats &st) {
  char buf[1024];
  std::snprintf(buf, sizeof buf,
                "ball-server %u: %.0f s, matches %u (%u playing), samples in %" PRIu64 " ok %" PRIu64 " idle %" PRIu64
                ", drops %s, out %" PRIu64 " states %" PRIu64 " segments %" PRIu64 " events, failed writes %" PRIu64
                ", overruns %" PRIu64 ", frame p50 %.3f ms p99 %.3f ms, latency p50 %.1f ms p99 %.1f ms",
                o.server_id, o.uptime, o.matches, o.playing, o.samples_in, o.samples_ok, st.samples_idle,
                drops_text(o.drops).c_str(), o.states_out, o.segments_out, o.events_out, st.write_failures,
                o.overruns, o.frame_p50 * 1e3, o.frame_p99 * 1e3, st.period_latency_p50 * 1e3,
                st.period_latency_p99 * 1e3);
  return buf;
}

}  // namespace ballsrv
