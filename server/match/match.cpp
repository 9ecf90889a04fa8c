#include "match.h"

#include <cmath>

#include "ball/vec3.h"
#include "rng.h"

namespace ballsrv {

namespace {

constexpr double kFarAway = 30.0;     // m beyond the court: the ball has left it
constexpr double kAheadHorizon = 10.0; // sim s: how far ahead a static contact is looked for (docs/protocol.md)
constexpr double kAheadLead = 0.5;     // real s before a foreseen contact its segment is written (docs/protocol.md)

// A decided point on the rules' state: the score, the next server, the serve
// due serve_delay after the instant t it was decided.
void settle(const Call &call, double t, double serve_delay, PlayState *p) {
  if (call.winner == 0 || call.winner == 1) p->score[static_cast<size_t>(call.winner)]++;  // (-1: a let)
  p->rally++;
  p->serving_side = static_cast<int>(p->rally % 2);
  p->serve_due = true;
  p->serve_at = t + serve_delay;
}

bool same_v3(ball_vec3 a, ball_vec3 b) { return a.x == b.x && a.y == b.y && a.z == b.z; }

bool same_segment(const ball_segment &a, const ball_segment &b) {
  return a.t0 == b.t0 && same_v3(a.p0, b.p0) && same_v3(a.v0, b.v0) && same_v3(a.s0, b.s0) &&
         a.grounded == b.grounded;
}

}  // namespace

bool Match::init(const MatchConfig &config, const ball_scene &scene, std::string *err) {
  if (!check_match_config(config, err)) return false;
  config_ = config;
  roster_.init(config.players);
  if (!court_from_model(scene.model, config.court_x_lo, &court_, err)) return false;
  ModelSetup setup;
  setup.players = config.players;
  setup.level = config.level;
  setup.extrapolation_time = config.extrapolation_time;
  setup.stale_time = config.stale_time;
  ball_model model;
  if (!build_match_model(scene, court_, setup, &model, err)) return false;
  ball_status st = ball_sim_init(&sim_, &model);  // the sim keeps its own copy
  if (st != BALL_OK) {
    *err = std::string("sim: ") + ball_strerror(st);
    return false;
  }
  model_hash_ = ball_model_hash(ball_sim_model(&sim_));
  step_events_.assign(BALL_MAX_CONTACTS + BALL_MAX_RACKETS + 8, ball_event{});
  late_from_.fill(NAN);
  // the matches of a server write their states on different frames (a phase from the
  // id), not all on the same one: a frame that wrote a state for each of 100 matches
  // held the loop for 3-6 ms and every hit that fell in it
  state_accum_ = golden_phase(config.id);
  state_ = MatchState::waiting;
  rules().serve_due = true;
  rules().serve_at = sim_.time;
  return true;
}

// ---- output helpers ------------------------------------------------------

void Match::emit(MatchOutput *out, EventKind kind, int index, double time, Reason reason, double value) {
  EventOut e;
  e.match_id = config_.id;
  e.seq = ++rules().event_seq;
  e.kind = kind;
  e.index = index;
  e.time = time;
  e.reason = reason;
  e.value = value;
  e.score = rules().score;
  e.segment_seq = current_seq_;
  out->events.push_back(e);
}

void Match::emit_segment(MatchOutput *out, Cause cause, int index, const ball_segment &seg, SampleRef ref,
                         bool sound) {
  SegmentOut s;
  s.match_id = config_.id;
  s.seq = current_seq_ = ++segment_seq_;
  s.cause = segment_cause_ = cause;
  s.cause_index = segment_cause_index_ = index;
  s.segment = seg;
  s.model_hash = model_hash_;
  s.sample = ref;
  s.sound = sound;
  s.correction = correcting_;
  out->segments.push_back(s);
  ahead_.valid = false;  // a segment written now supersedes the one written ahead (or is it, judged anew)
  took_effect(s);
}

void Match::took_effect(const SegmentOut &s) {
  history_.push_back(s);
  // what a rewind may need: the segments in effect over the window (and the one before it)
  double keep_from = sim_.time - config_.rewind_window - 1.0;
  size_t drop = 0;
  while (drop + 1 < history_.size() && (history_[drop + 1].segment.t0 < keep_from || history_.size() - drop > 64))
    ++drop;
  history_.erase(history_.begin(), history_.begin() + static_cast<long>(drop));
}

// ---- segments ahead of time (docs/protocol.md) ----------------------------

void Match::write_ahead(MatchOutput *out) {
  const ball_model &m = model();
  if (m.scheme != BALL_SCHEME_EXACT || !(m.effects & (BALL_EFFECT_FLOOR | BALL_EFFECT_NET | BALL_EFFECT_WALLS)))
    return;
  if (!ahead_.valid) {
    // from the segment's start, as the step looks for its next contact
    ball_prediction pr{};
    pr.events = &ahead_.event;
    pr.cap_events = 1;
    double t0 = sim_.seg.t0;
    if (ball_predict(&m, &sim_.seg, t0, t0 + kAheadHorizon, kAheadHorizon, &pr) != BALL_OK || pr.n_events < 1 ||
        !(ahead_.event.time > sim_.time))
      return;
    ahead_.valid = true;
    ahead_.written = false;
  }
  // written kAheadLead of real time before the contact: a racket hit
  // before then supersedes it unwritten (the bounce after the next one)
  const ball_event &ev = ahead_.event;
  if (ahead_.written || ev.time - sim_.time > kAheadLead * config_.time_base) return;
  SegmentOut s;
  s.match_id = config_.id;
  s.seq = ++segment_seq_;
  s.cause = ev.kind == BALL_EVENT_NET ? Cause::net : ev.kind == BALL_EVENT_WALL ? Cause::wall : Cause::floor;
  s.cause_index = ev.kind == BALL_EVENT_WALL ? ev.index : -1;
  s.segment = ev.segment;
  s.sound = ev.sound != 0;
  s.correction = correcting_;
  s.model_hash = model_hash_;
  s.play = judged(ev);
  out->segments.push_back(s);
  ahead_.segment = s;
  ahead_.written = true;
  counters_.ahead++;
}

bool Match::is_ahead(const ball_event &ev) const {
  const ball_event &a = ahead_.event;
  return ahead_.valid && ahead_.written && ev.kind == a.kind && ev.index == a.index && ev.time == a.time &&
         same_segment(ev.segment, a.segment);
}

Call Match::judge(Rally &r, const ball_event &ev) const {
  switch (ev.kind) {
    case BALL_EVENT_FLOOR:
      return r.on_floor(side_of_point(ev.point), court_.inside(ev.point.x, ev.point.z), ev.segment.grounded != 0);
    case BALL_EVENT_NET: return r.on_net();
    case BALL_EVENT_WALL: return r.on_wall();
    case BALL_EVENT_RACKET: return r.on_racket(Court::side_of_slot(ev.index));
    default: return Call{};
  }
}

PlayState Match::judged(const ball_event &ev) const {
  Rally r = rally_;
  uint32_t events = 1;  // the collision (its sound is its flag)
  Call call = r.live() ? judge(r, ev) : Call{};
  PlayState &p = r.state();
  if (call.decided) {
    settle(call, ev.time, config_.serve_delay, &p);
    events++;  // the point
  }
  p.event_seq += events;
  return p;
}

void Match::set_state(MatchState s, MatchOutput *out) {
  if (state_ == s) return;
  state_ = s;
  out->info_changed = true;
}

// ---- presence and the state machine -------------------------------------

bool Match::held() const { return roster_.held(); }

void Match::on_participant_lost(const ParticipantId &who) { roster_.participant_lost(who); }

void Match::update_presence(double now, MatchOutput *out) {
  int missing = -1;
  if (roster_.update_presence(now, config_.player_timeout, &missing)) out->info_changed = true;
  switch (state_) {
    case MatchState::waiting:
      if (roster_.all_present()) {
        set_state(MatchState::playing, out);
        if (left_mid_match_) emit(out, EventKind::resume, -1, sim_.time);
        left_mid_match_ = false;
      }
      break;
    case MatchState::playing:
      if (missing >= 0) {
        set_state(MatchState::paused, out);
        pause_reason_ = Reason::pause_vanished;
        pause_slot_ = missing;
        counters_.pauses++;
        emit(out, EventKind::pause, missing, sim_.time, Reason::pause_vanished);
      }
      break;
    case MatchState::paused:
      if (pause_reason_ == Reason::pause_vanished && roster_.all_present()) {
        set_state(MatchState::playing, out);
        pause_reason_ = Reason::none;
        emit(out, EventKind::resume, pause_slot_, sim_.time);
        pause_slot_ = -1;
      }
      break;
  }
}

// ---- the frame ------------------------------------------------------------

void Match::frame(double now, MatchOutput *out) {
  update_presence(now, out);
  if (state_ != MatchState::playing) {
    hit_.drop();
    return;
  }
  // the rest of the frame that hits began
  advance(std::max(0.0, frame_time() * config_.time_base - partial_), true, out);
  partial_ = 0.0;
  find_hit();
}

// ---- racket hits at their instant ----------------------------------------

void Match::find_hit() {
  hit_.none();
  const ball_model &m = model();
  if (!config_.hit_instant || state_ != MatchState::playing || following_ || rules().serve_due ||
      !(m.effects & BALL_EFFECT_RACKETS) || m.n_rackets == 0 || sim_.sleep > 0)
    return;
  const double dt = frame_time() * config_.time_base;
  hit_.look(sim_, m.n_rackets, model_hash_, sim_.time - partial_ + dt, dt, &counters_);  // to the frame's end
}

double Match::hit_after() {
  if (hit_.stale()) find_hit();
  if (!std::isfinite(hit_.next())) return HUGE_VAL;
  return (hit_.next() - (sim_.time - partial_)) / config_.time_base;
}

// ---- lag compensation -------------------------------------------------------

void Match::compensate(MatchOutput *out) {
  std::array<double, kMaxPlayers> late = late_from_;
  late_from_.fill(NAN);
  has_late_ = false;
  for (int i = 0; i < config_.players; ++i)  // at most one rewind per sample: one per slot
    if (!std::isnan(late[i])) rewind(i, late[i], out);
  find_hit();
}

void Match::rewind(int slot, double from, MatchOutput *out) {
  const double now = sim_.time;
  if (state_ != MatchState::playing || !rally_.live() || history_.empty()) return;
  LateHit found = find_late_hit(sim_, history_, slot, roster_[slot], from, lag_params(), &step_events_);
  if (found.outcome != LateHit::untested) counters_.late_tested++;
  if (found.outcome == LateHit::ruled_out) counters_.late_ruled_out++;
  if (found.outcome != LateHit::found) return;
  const double hit = found.hit, passed = found.passed, dt = frame_time() * config_.time_base;
  const SegmentOut *at = found.at;
  Aside &early = found.early;
  // the old path after the hit (and from its own hit it went back past) is not history any more
  auto gone = [&](const SegmentOut &h) { return h.segment.t0 > hit || h.segment.t0 >= passed; };
  // the rules as they were at the hit (the segment in effect then, judged)
  PlayState p = at->play;
  for (const SegmentOut &h : history_)
    if (!gone(h) && h.segment.t0 <= hit) p = h.play;
  if (!p.live) return;
  set_rules(p);
  // (the events' numbers go on)
  while (!history_.empty() && gone(history_.back())) {
    // a contact that did not happen after all is not counted (the stats
    // count what a client ends up with): in play if the rally was live after
    // the segment before it (there is one: `at` stays)
    const SegmentOut &h = history_.back();
    if (history_.size() >= 2 && history_[history_.size() - 2].play.live) {
      if (h.cause == Cause::floor) counters_.bounces--;
      if (h.cause == Cause::racket) counters_.hits--;
    }
    history_.pop_back();
  }
  if (std::isfinite(passed)) {  // its last hit is the one before, until the hit found now
    Slot &sl = roster_[slot];
    sl.hit_time = -1e300;
    for (const SegmentOut &h : history_)
      if (h.cause == Cause::racket && h.cause_index == slot) sl.hit_time = h.segment.t0;
    counters_.rewinds_past_own_hit++;
  }
  // to the hit, then on to the present: what that gives is written as corrections
  sim_ = found.then;
  correcting_ = true;
  if (std::isfinite(passed) && hit >= passed && !history_.empty()) {
    // the hit comes after the one it moves: the segment in effect before
    // that one, written again, supersedes it and voids its events
    // (docs/protocol.md, "Corrections")
    const SegmentOut b = history_.back();
    emit_segment(out, b.cause, b.cause_index, b.segment, b.sample, b.sound);
    out->segments.back().play = history_.back().play = b.play;
  }
  aside(&sim_, &early, hit);
  advance(hit - sim_.time, false, out);
  while (sim_.time < now - 1e-12) {
    double step = std::min(dt, now - sim_.time);
    aside(&sim_, &early, sim_.time + step);  // (a hit's follow-through too: its samples come after it)
    advance(step, false, out);
  }
  aside(&sim_, &early, HUGE_VAL);  // every track as it is now again
  correcting_ = false;
  counters_.rewinds++;
  out->info_changed = true;
}

// A hit ends its racket's stroke: the racket's track starts again from the
// samples captured at or after the hit (docs/server-design.md, "Lag compensation";
// a restored match's track may hold some, a live one's ahead of the sim
// clock), so that eq 15 does not carry the stroke on past the hit.
void Match::end_stroke(int k, double t_hit) {
  if (k < 0 || k >= config_.players || k >= model().n_rackets) return;
  Slot &sl = roster_[k];
  sl.hit_time = std::max(sl.hit_time, t_hit);
  const ball_racket_track tr = sim_.tracks[k];
  ball_racket_clear(&sim_, k);
  for (int i = 0; i < tr.count; ++i)  // (each was accepted after the one before it)
    if (tr.samples[i].t >= sl.hit_time) ball_racket_push(&sim_, k, &tr.samples[i]);
  hit_.moved();
}

void Match::step_to_hit(MatchOutput *out) {
  if (hit_.stale()) find_hit();
  double dt = hit_.next() - sim_.time;
  if (state_ != MatchState::playing || !(dt > 0.0) || !std::isfinite(dt)) {
    hit_.drop();
    return;
  }
  advance(dt, false, out);
  partial_ += dt;
  counters_.hit_steps++;
  find_hit();
}

void Match::advance(double dt, bool with_state, MatchOutput *out) {
  if (rules().serve_due && sim_.time >= rules().serve_at) serve(out);
  int n = 0;
  ball_status st = ball_step(&sim_, dt, step_events_.data(), static_cast<int>(step_events_.size()), &n);
  if (st != BALL_OK) {
    counters_.step_errors++;  // the sim is as it was; the frame is lost, the match goes on
    return;
  }
  counters_.frames++;
  for (int i = 0; i < n; ++i) {
    size_t first = out->segments.size();
    handle_event(step_events_[i], out);
    // each segment carries the rules' state once its collision is judged
    for (size_t k = first; k < out->segments.size(); ++k) out->segments[k].play = play();
    if (!history_.empty()) history_.back().play = play();
  }

  if (rally_.live()) {
    ball_state b;
    ball_sim_state(&sim_, &b);
    bool far = b.position.x < court_.x_lo - kFarAway || b.position.x > court_.x_hi + kFarAway ||
               b.position.z < court_.z_lo - kFarAway || b.position.z > court_.z_hi + kFarAway;
    bool still = sim_.seg.grounded && ball_v3_norm(b.velocity) < 0.05;
    apply(rally_.on_frame(far || still, sim_.time, config_.max_rally_time), sim_.time, out);
  }
  write_ahead(out);
  // a contact stepped as foreseen with none foreseen after it: only a
  // MatchInfo tells a standby that this server stepped it (docs/protocol.md;
  // the next one's segment, written later, tells it otherwise)
  if (stepped_ahead_ && !ahead_.valid) out->info_changed = true;
  stepped_ahead_ = false;

  if (!with_state) return;
  state_accum_ += config_.state_rate / config_.frame_rate;
  if (state_accum_ >= 1.0 - 1e-9) {
    state_accum_ -= 1.0;
    out->has_state = true;
    StateOut &s = out->state;
    s.match_id = config_.id;
    s.frame = sim_.frame;
    s.sim_time = sim_.time;
    s.state = state_;
    s.segment_seq = current_seq_;
    ball_sim_state(&sim_, &s.ball);
    s.sim_hash = sim_hash();
  }
}

// ---- the rules ------------------------------------------------------------

// A collision's event (and its sound's, when it makes one), numbered on.
void Match::emit_collision(const ball_event &ev, EventKind kind, int index, MatchOutput *out) {
  EventOut e;
  e.match_id = config_.id;
  e.seq = ++rules().event_seq;
  e.kind = kind;
  e.index = kind == EventKind::floor || kind == EventKind::net ? 0 : index;
  e.side = side_of_point(ev.point);
  e.in_play = rally_.live();
  e.sound = ev.sound != 0;
  e.time = ev.time;
  e.point = ev.point;
  e.velocity_in = ev.velocity_in;
  e.velocity_out = ev.velocity_out;
  e.segment_seq = current_seq_;
  e.score = rules().score;
  out->events.push_back(e);  // its sound is its flag: no EVENT_SOUND (docs/protocol.md, "Events")
}

void Match::handle_event(const ball_event &ev, MatchOutput *out) {
  Cause cause = Cause::floor;
  EventKind kind = EventKind::floor;
  int index = -1;
  SampleRef ref;
  switch (ev.kind) {
    case BALL_EVENT_FLOOR: break;
    case BALL_EVENT_NET: cause = Cause::net; kind = EventKind::net; break;
    case BALL_EVENT_WALL: cause = Cause::wall; kind = EventKind::wall; index = ev.index; break;
    case BALL_EVENT_RACKET:
      cause = Cause::racket;
      kind = EventKind::racket;
      index = ev.index;
      if (index >= 0 && index < kMaxPlayers) ref = roster_[index].ref;
      end_stroke(index, ev.segment.t0);
      break;
    case BALL_EVENT_KIND_COUNT: return;
  }
  // the contact written ahead, as foreseen: in effect now, not written again
  bool foreseen = is_ahead(ev);
  if (foreseen) {
    current_seq_ = ahead_.segment.seq;
    segment_cause_ = cause;
    segment_cause_index_ = index;
    took_effect(ahead_.segment);
  } else {
    emit_segment(out, cause, index, ev.segment, ref, ev.sound != 0);
  }
  emit_collision(ev, kind, index, out);
  if (rally_.live()) {
    if (kind == EventKind::floor) counters_.bounces++;
    if (kind == EventKind::racket) counters_.hits++;
    apply(judge(rally_, ev), ev.time, out);
  } else if (kind == EventKind::racket) {
    counters_.dead_hits++;
  }
  if (!foreseen) return;
  // judged otherwise than when it was written ahead: written again (and the
  // MatchInfo, which tells a standby it was stepped)
  PlayState now = play();
  ahead_.valid = false;
  stepped_ahead_ = true;
  if (!(now == ahead_.segment.play)) {
    emit_segment(out, cause, index, ev.segment, ref, ev.sound != 0);
    out->info_changed = true;
    counters_.ahead_corrected++;
  }
}

void Match::apply(const Call &call, double t, MatchOutput *out) {
  if (!call.decided) return;
  if (call.winner >= 0)
    counters_.points++;
  else
    counters_.lets++;
  settle(call, t, config_.serve_delay, &rules());
  emit(out, EventKind::point, -1, t, call.reason);
  out->events.back().side = call.winner;
  out->info_changed = true;
}

void Match::serve(MatchOutput *out) {
  int side = rules().serving_side;
  // singles: slot = side; doubles: the partners of a side take turns
  int slot = side;
  if (config_.players > 2 && (rules().rally / 2) % 2 == 1 && side + 2 < config_.players) slot = side + 2;
  if (side != 0 && side != 1) side = 0;  // (a restored Play is checked: play_fits)
  if (slot < 0 || slot >= config_.players) slot = 0, side = 0;
  Rng rng(config_.seed * 0x9e3779b97f4a7c15ull + rules().rally);
  ball_vec3 from = court_.ready(slot, config_.players);
  from.x += Court::toward_net(side) * 2.0;
  from.y = court_.floor + 1.0;
  double half_width = 0.5 * (court_.z_hi - court_.z_lo);
  ball_vec3 target = court_.spot(1 - side, 0.7, rng.uniform(-0.3, 0.3) * half_width);
  ball_state b{};
  b.position = from;
  if (lob_velocity(model(), from, target, config_.serve_v_up, &b.velocity) != BALL_OK)
    b.velocity = ball_v3(Court::toward_net(side) * 15.0, config_.serve_v_up, 0.0);
  if (ball_sim_set_state(&sim_, &b) != BALL_OK) {
    counters_.step_errors++;
    return;
  }
  rally_.start(side, sim_.time);
  rules().serve_due = false;
  counters_.serves++;
  emit_segment(out, Cause::serve, slot, sim_.seg, SampleRef{}, false);
  history_.back().play = play();
  emit(out, EventKind::serve, slot, sim_.time);
  EventOut &e = out->events.back();
  e.side = side;
  e.in_play = true;
  e.point = from;
  e.velocity_out = b.velocity;
  out->segments.back().play = play();
  out->info_changed = true;
}

// ---- samples --------------------------------------------------------------

void Match::end_streams() { roster_.end_streams(); }

uint64_t Match::take_lost() { return roster_.take_lost(); }

void Match::on_rejected(const RacketSampleIn &s, uint64_t *lost) {
  counters_.rejected++;
  *lost += roster_.rejected(s);
}

SampleResult Match::on_sample(const RacketSampleIn &s, double now, uint64_t *lost) {
  SampleResult checked = roster_.check(s, now, clock_now(), config_, court_, lost);
  if (checked != SampleResult::accepted) return checked;
  Slot &slot = roster_[s.player];
  if (state_ != MatchState::playing) {
    roster_.passed(s.player, s);
    return SampleResult::idle;
  }
  // captured in the past of the sim clock, within the window: tested where the ball was then
  const bool late = config_.rewind_window > 0.0 && s.capture_time < sim_.time &&
                    s.capture_time >= sim_.time - config_.rewind_window && rally_.live() && !following_;
  // of the stroke its racket's last hit ended: it cannot change the hit,
  // unless the match may go back past its own racket's hit (docs/server-design.md,
  // "Lag compensation")
  const bool past_hit = s.capture_time < slot.hit_time;
  if (past_hit && !(late && config_.rewind_own_hit)) return SampleResult::before_hit;
  // a sample identical to a kept one (BALL_EDUPLICATE) or not newer than the
  // newest kept (BALL_ESTALE) is libball's to tell; the sim stays as it was
  ball_racket_sample rs;
  rs.t = s.capture_time;
  rs.center = s.center;
  rs.normal = s.normal;
  ball_status st;
  if (past_hit) {  // not onto the track (the hit ended that stroke): kept for a rewind, checked as the track would take it
    ball_sim scratch = sim_;
    st = unended_track(&scratch, s.player, slot, &rs);
  } else {
    st = ball_racket_push(&sim_, s.player, &rs);
  }
  switch (st) {
    case BALL_OK: break;
    case BALL_EDUPLICATE: return SampleResult::duplicate;
    case BALL_ESTALE: return SampleResult::stale;
    case BALL_EINVAL: return SampleResult::bad_slot;
    default: return SampleResult::out_of_range;  // ENONFINITE/ERANGE: an implied infinite velocity
  }
  double from = slot.has_prev ? slot.prev_time : -HUGE_VAL;  // a late sample tells the track from here on
  roster_.passed(s.player, s);
  slot.samples++;
  slot.ref.valid = true;
  slot.ref.seq = s.seq;
  slot.ref.source_time = s.source_time;
  slot.ref.capture_time = s.capture_time;
  if (config_.rewind_own_hit) slot.keep(rs);
  hit_.moved();  // the track moved: the hit it meets may too (looked for once, when asked)
  if (late) {
    double &f = late_from_[s.player];
    f = std::isnan(f) ? from : std::min(f, from);
    has_late_ = true;
  }
  return SampleResult::accepted;
}

}  // namespace ballsrv
