#include "server_loop.h"

#include "trust.h"

#include <cinttypes>
#include <algorithm>
#include <cmath>
#include <cstdio>

namespace ballsrv {

ServerLoop::ServerLoop(Host &host, ServerPort &port, Clock &clock, const LoopSettings &settings)
    : host_(host), port_(port), clock_(clock), settings_(settings), cluster_(settings),
      base_strength_(settings.strength) {}

bool ServerLoop::find_owner(double seconds, const std::function<bool()> &stop, MatchInfoOut *other) {
  double until = clock_.mono() + seconds;
  ParticipantId from;
  while (clock_.mono() < until && !stop()) {
    while (port_.take_other_info(other, &from)) {
      if (cluster_.server_wrote(*other) && host_.find(other->match_id)) return true;
    }
    clock_.sleep_until(clock_.mono() + 0.05);
  }
  return false;
}

void ServerLoop::drop_own_if_standby() {
  if (!settings_.standby || settings_.claim > 0) return;
  // a standby alone steps nothing of its own: its configured matches only name scenes
  std::vector<uint32_t> own;
  for (const auto &m : host_.matches())
    if (!m->following()) own.push_back(m->id());
  for (uint32_t id : own) host_.remove(id);
}

// A match created on request, or taken over from a server gone, that nobody
// held a slot of for create_timeout goes: a stranger's CREATEs (or made-up
// matches) must not fill max_matches (or squat an id) for good.
void ServerLoop::expire_created(double t0) {
  for (auto it = sched_.begin(); it != sched_.end();) {
    Match *m = it->match;
    if (m->held()) it->last_held = t0;
    bool expires = host_.creator(m->id()) != ParticipantId{} || it->taken_over;
    if (!expires || t0 - it->last_held < settings_.create_timeout) {
      ++it;
      continue;
    }
    uint32_t id = m->id();
    bool taken_over = it->taken_over;
    if (!port_.dispose_match(id)) stats_.totals.write_failures++;
    it = sched_.erase(it);
    host_.remove(id);
    stats_.created_expired++;
    say("removed match " + std::to_string(id) + (taken_over ? ": taken over" : ": created") +
        ", and nobody held a slot for " +
        std::to_string(static_cast<int>(settings_.create_timeout)) + " s");
  }
}

void ServerLoop::keep_alive(double t0) {
  if (t0 < next_assert_) return;
  if (!port_.assert_liveliness()) stats_.liveliness_failures++;
  next_assert_ = t0 + kLivelinessPeriod;
}

void ServerLoop::listen(double seconds, const std::function<bool()> &stop) {
  if (start_ == 0.0) start_ = clock_.mono();
  drop_own_if_standby();
  write(status_now(), &stats_.statuses_out);  // so that the others know this one
  double until = clock_.mono() + seconds;
  while (clock_.mono() < until && !stop()) {
    double t0 = clock_.mono();
    keep_alive(t0);
    take_notes(t0);
    take_others();
    clock_.sleep_until(clock_.mono() + 0.05);
  }
}

// Every match's frames count from the server's start, so matches of the
// same frame rate are stepped on the same wake-ups.
ServerLoop::Scheduled ServerLoop::schedule(Match *m) {
  Scheduled s{m, FrameClock(m->frame_time(), origin_)};
  double now = clock_.mono();
  s.k = s.clock.first_at(now);
  s.last_frame_real = s.clock.realtime_at(now);
  s.since = clock_.realtime();
  s.last_held = now;
  // the periodic MatchInfo of many matches spread over the interval (by the
  // golden ratio of their ids), not all in one wake-up: 1000 at once took
  // 10-20 ms, and every frame of that wake-up overran, 1 in 60
  s.next_info = now + settings_.info_interval * std::fmod(static_cast<double>(m->id()) * 0.6180339887498949, 1.0);
  // the round after any term of it heard (docs/protocol.md, "Terms"); its
  // writers outrank every older term's
  s.term = next_term(cluster_.heard_term(m->id()), settings_.server_id);
  raise_strength(term_strength(base_strength_, s.term));
  return s;
}

void ServerLoop::raise_strength(uint32_t at_least) {
  if (at_least <= cluster_.settings().strength) return;
  if (!port_.set_strength(at_least)) {
    say("cannot raise the match writers' strength to " + std::to_string(at_least));
    return;
  }
  cluster_.set_strength(at_least);
}

ServerLoop::Scheduled *ServerLoop::scheduled(uint32_t id) {
  for (auto &s : sched_)
    if (s.match->id() == id) return &s;
  return nullptr;
}

void ServerLoop::say(const std::string &line) {
  if (on_note_) on_note_(line);
}

void ServerLoop::start() {
  origin_ = FrameClock(1.0, clock_.mono(), clock_.realtime());
  drop_own_if_standby();
  if (settings_.claim > 0) {
    // a claimant's configured matches are candidates: it steps those the claim rule gives it
    std::vector<MatchConfig> candidates;
    for (const auto &m : host_.matches())
      if (!m->following()) candidates.push_back(m->config());
    for (const auto &c : candidates) host_.remove(c.id);
    cluster_.set_candidates(std::move(candidates));
    claim_unplaced(clock_.mono());
  }
  for (const auto &m : host_.matches()) {
    if (m->following() || scheduled(m->id())) continue;
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
  else stats_.totals.write_failures++;
}

void ServerLoop::publish(const MatchOutput &out, Scheduled &s, double now) {
  for (SegmentOut seg : out.segments) {
    seg.server_id = settings_.server_id;
    seg.term = s.term;
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
    e.term = s.term;
    e.server_time = now;
    write(e, &stats_.totals.events_out);
  }
  if (out.has_state) {  // states are the bulk of a frame's writes: they wait for the hits
    write_state(s);       // (an older one first: one state per frame, in order)
    s.state = out.state;
    s.state.server_id = settings_.server_id;
    s.state.term = s.term;
    s.state.server_time = s.last_frame_real;
    s.state_due = true;
  }
}

void ServerLoop::write_state(Scheduled &s) {
  if (!s.state_due) return;
  s.state_due = false;
  write(s.state, &stats_.totals.states_out);
}

void ServerLoop::write_due_states(double now) {
  for (auto &s : sched_) {
    if (!s.state_due) continue;  // (a hit's wake-up has none: no clock read per match)
    write_state(s);
    if (clock_.mono() >= earliest_hit_) run_due_hits(clock_.mono(), now);
  }
}

// A match stepped to a hit since its frame has a sim clock past the frame's
// server_time: its MatchInfo waits for the frame's end, so that every
// (sim_time, server_time) pair is a frame's (docs/protocol.md, "Time").
void ServerLoop::info_changed(Scheduled &s) {
  if (s.match->frame_stepped() > 0.0)
    s.info_waits = true;
  else
    publish_info(s);
}

void ServerLoop::publish_info(Scheduled &s) {
  s.info_waits = false;
  MatchInfoOut info = s.match->info();
  info.server_id = settings_.server_id;
  info.term = s.term;
  info.server_time = s.last_frame_real;  // sim_time holds from the newest frame's deadline
  info.revision = ++s.revision;
  write(info, &stats_.infos_out);
  // the whole model, when the server starts serving the match and when it changes (docs/protocol.md)
  if (info.model_hash != s.model_written) {
    MatchModelOut m;
    m.match_id = info.match_id;
    m.server_id = settings_.server_id;
    m.model_hash = info.model_hash;
    m.model = s.match->model();
    if (port_.write(m)) {
      stats_.models_out++;
      s.model_written = info.model_hash;
    } else {
      stats_.totals.write_failures++;  // (written again with the next MatchInfo)
    }
  }
}

// ---- the phases ----------------------------------------------------------------

// The port lets in only the samples and controls of the matches the host
// has (its own and those it follows), told again whenever they change.
void ServerLoop::admit_hosted() {
  admitted_now_.clear();
  for (const auto &m : host_.matches()) admitted_now_.emplace_back(m->id(), m->config().players);
  if (admitted_once_ && admitted_now_ == admitted_) return;
  admitted_.swap(admitted_now_);
  admitted_once_ = true;
  port_.admit(admitted_, host_.create_ids());
}

void ServerLoop::take_samples(double now) {
  RacketSampleIn sample;
  while (port_.take_sample(&sample)) {
    stats_.totals.samples_in++;
    // the seqs a holder's stream skipped never arrived: counted in and lost (docs/protocol.md)
    uint64_t lost = 0;
    SampleResult r = SampleResult::not_permitted;
    if (sample.rejected) {
      r = SampleResult::rejected;
      if (sample.permitted) host_.on_rejected(sample, &lost);
    } else if (sample.permitted) {
      r = host_.on_sample(sample, now, &lost);
    }
    if (r == SampleResult::accepted) stats_.totals.samples_ok++;
    else if (r == SampleResult::idle) stats_.totals.samples_idle++;
    else stats_.totals.drops[static_cast<int>(r)]++;
    count_lost(lost);
  }
}

void ServerLoop::take_controls(double now) {
  ControlIn control;
  while (port_.take_control(&control)) {
    stats_.totals.controls_in++;
    if (control.rejected) {  // over its writer's share of the inbox (server_endpoints.cpp)
      stats_.totals.controls_refused++;
      stats_.controls_no_room++;
      continue;
    }
    if (!control.valid || !control.permitted) {
      stats_.totals.controls_refused++;
      continue;
    }
    if (!may_create(control)) {  // another server's to create (the claim rule, a standby): nothing here
      stats_.totals.controls_refused++;
      continue;
    }
    out_.clear();
    Match *m = nullptr;
    size_t before = host_.matches().size();
    Reason r = host_.on_control(control, now, &out_, &m);
    if (r != Reason::none) stats_.totals.controls_refused++;
    if (host_.matches().size() > before) {  // CREATE
      sched_.push_back(schedule(host_.matches().back().get()));
      if (settings_.claim > 0) {
        sched_.back().firm_at = clock_.mono() + settings_.settle;
        cluster_.claimed();
      }
    }
    if (!m) continue;
    for (auto &s : sched_)
      if (s.match == m) {
        publish(out_, s, now);
        if (out_.info_changed) info_changed(s);
      }
  }
}

void ServerLoop::run_due_frames(double t0, double now) {
  // the matches a racket may hit in the frame after this one first: a hit
  // early in that frame is found at this deadline, not after every other
  // match's frame (docs/server-design.md, "Hits at their instant")
  frame_due_.assign(sched_.size(), 0);
  for (size_t i = 0; i < sched_.size(); ++i)
    if (sched_[i].clock.deadline(sched_[i].k) <= t0 + 1e-6) frame_due_[i] = sched_[i].match->near_hit() ? 1 : 2;
  for (char pass : {1, 2})
    for (size_t i = 0; i < sched_.size(); ++i)
      if (frame_due_[i] == pass) run_frame(sched_[i], t0, now);
}

void ServerLoop::run_frame(Scheduled &s, double t0, double now) {
  double d = s.clock.deadline(s.k);
  if (t0 < s.firm_at) {  // a claim settling: nothing moves yet
    s.k = s.clock.first_at(t0 + 1e-6);
    return;
  }
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
  if (out_.info_changed || s.info_waits || t0 >= s.next_info) {
    publish_info(s);
    s.next_info = t0 + settings_.info_interval;
  }
  // an overrun: the frame was done only after the next one was due
  double t = clock_.mono();
  if (t > s.clock.deadline(s.k)) stats_.totals.overruns++;
  // a hit whose instant came while the frames of many matches were done
  // waits for one match's frame, not for all of them
  double due = hit_due(s);
  see_due(s, due, t);
  earliest_hit_ = std::min(earliest_hit_, due);
  if (t >= earliest_hit_) run_due_hits(t, now);
}


double ServerLoop::hit_due(const Scheduled &s) const {
  return s.k == 0 ? HUGE_VAL : s.clock.deadline(s.k - 1) + s.match->hit_after() - s.match->config().hit_lead;
}

// A hit due within kSameHit of the one seen before is known since then.
void ServerLoop::see_due(Scheduled &s, double at, double t) {
  if (std::fabs(at - s.due_seen) <= kSameHit) return;
  s.due_seen = at;
  s.due_seen_at = t;
}

void ServerLoop::run_due_hits(double t0, double now) {
  earliest_hit_ = HUGE_VAL;
  for (auto &s : sched_) {
    if (s.match->has_late()) {  // late samples: a hit found where the ball was rewinds the match
      MatchOutput out;
      s.match->compensate(&out);
      publish(out, s, now);
      if (out.info_changed) info_changed(s);
    }
    double at = hit_due(s);
    see_due(s, at, t0);
    if (at <= t0 + 1e-6 && t0 >= s.firm_at) {
      MatchOutput out;  // (out_ may hold a frame's output being published)
      write_state(s);   // the state of its frame before the hit
      s.match->step_to_hit(&out);
      publish(out, s, now);
      if (out.info_changed) info_changed(s);
      stats_.hit_wakes++;
      const double lead = s.match->config().hit_lead;
      stats_.hit_late.add(t0 - (at + lead));
      // why late: the wake-up (the loop knew the hit before it was due), or
      // its samples (first seen after its instant); else found within the lead
      if (s.due_seen_at < at) stats_.hit_wake_late.add(t0 - at);
      else if (s.due_seen_at > at + lead) stats_.hit_found_late.add(t0 - (at + lead));
      at = hit_due(s);
      see_due(s, at, t0);
    }
    earliest_hit_ = std::min(earliest_hit_, at);
  }
}

double ServerLoop::next_wake() const {
  double wake = next_status_;
  bool often = false;  // frames come often enough to assert the liveliness on time
  for (const auto &s : sched_) {
    wake = std::min({wake, s.clock.deadline(s.k), hit_due(s)});
    often = often || s.clock.period() <= kLivelinessPeriod;
  }
  if (!often) wake = std::min(wake, next_assert_);
  return std::min(wake, cluster_.next_wake(clock_.mono()));  // a standby's followed matches
}

bool ServerLoop::step() {
  clock_.sleep_until(next_wake());
  return wake();
}

bool ServerLoop::wake() {
  double t0 = clock_.mono();
  double now = clock_.realtime();
  keep_alive(t0);
  take_notes(t0);
  take_others();
  for (const auto &f : cluster_.following()) {  // the owner's sim clock, for the samples' checks
    const MatchInfoOut &i = f.second.info;
    Match *m = host_.find(f.first);
    if (m) m->follow_clock(i.sim_time + (i.state == MatchState::playing ? (now - i.server_time) * i.settings.time_base : 0.0));
  }
  admit_hosted();
  take_samples(now);
  take_controls(now);
  take_over(t0, now);
  run_due_hits(t0, now);  // (also finds the earliest hit after the samples moved the tracks)
  run_due_frames(t0, now);
  write_due_states(now);
  count_lost(host_.take_lost());  // the gaps of streams that ended (controls, yields, take-overs)
  double t1 = clock_.mono();
  stats_.frame_time.add(t1 - t0);
  if (t1 < next_status_) return false;
  // the status phase
  if (settings_.claim > 0) claim_unplaced(t1);
  expire_created(t1);
  count_lost(host_.take_lost());
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
  host_.end_streams();  // their gaps still open: lost
  count_lost(host_.take_lost());
  close_period();  // the last, partial period
  return status_;
}

}  // namespace ballsrv
