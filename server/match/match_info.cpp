// What a match tells and takes between servers (match.h): its MatchInfo,
// and another server's match followed and restored (docs/protocol.md,
// "Several servers on one domain").
#include "match.h"

#include <algorithm>
#include <cmath>

#include "trust.h"

namespace ballsrv {

// ---- info -----------------------------------------------------------------

MatchInfoOut Match::info() const {
  MatchInfoOut i;
  i.match_id = config_.id;
  i.state = state_;
  i.scene = config_.scene_name;
  i.level = config_.level;
  i.players = config_.players;
  roster_.fill(&i);
  i.play = play();
  i.pause_reason = state_ == MatchState::paused ? pause_reason_ : Reason::none;
  i.pause_slot = state_ == MatchState::paused ? pause_slot_ : -1;
  i.segment_seq = current_seq_;
  i.segment_cause = segment_cause_;
  i.segment_cause_index = segment_cause_index_;
  i.segment = sim_.seg;
  i.frame_time = frame_time();
  i.sim_time = sim_.time;
#define BALL_PUT_SETTING(f) i.settings.f = config_.f;
  BALL_MATCH_WIRE_SETTINGS(BALL_PUT_SETTING)
#undef BALL_PUT_SETTING
  i.model_hash = model_hash_;
  i.model = model();
  i.net_x = court_.net_x;
  i.court_x[0] = court_.x_lo;
  i.court_x[1] = court_.x_hi;
  i.court_z[0] = court_.z_lo;
  i.court_z[1] = court_.z_hi;
  return i;
}

PlayState Match::play() const { return rally_.state(); }

void Match::set_rules(const PlayState &p) {
  const uint32_t seq = rules().event_seq;  // (the event numbers are the match's own: set apart)
  rules() = p;
  rules().event_seq = seq;
}

// ---- another server's match -------------------------------------------------

void Match::set_level(ball_level level, std::string *err) {
  if (level == config_.level) return;
  ball_model m = model();
  if (ball_model_set_level(&m, level) != BALL_OK || ball_sim_set_model(&sim_, &m) != BALL_OK) {
    *err = "level " + std::to_string(static_cast<int>(level)) + " does not fit the match's model";
    return;
  }
  model_hash_ = ball_model_hash(ball_sim_model(&sim_));
  config_.level = level;
}

bool Match::can_follow(const MatchInfoOut &info, std::string *err) const {
  if (info.match_id != config_.id || info.players != config_.players) {
    *err = "match " + std::to_string(info.match_id) + " with " + std::to_string(info.players) +
           " slots is not match " + std::to_string(config_.id) + " with " + std::to_string(config_.players);
    return false;
  }
  // the owner's model
  ball_model m = model();
  if (info.level != config_.level) {
    if (info.level < BALL_LEVEL_EASY || info.level > BALL_LEVEL_ADVANCED ||
        ball_model_set_level(&m, static_cast<ball_level>(info.level)) != BALL_OK) {
      *err = "level " + std::to_string(info.level) + " is not a game level";
      return false;
    }
  }
  if (info.model_hash != ball_model_hash(&m)) {
    *err = "its model (hash " + std::to_string(info.model_hash) + ") is not this server's for scene \"" +
           config_.scene_name + "\" (hash " + std::to_string(ball_model_hash(&m)) + ")";
    return false;
  }
  return true;
}

bool Match::follow(const MatchInfoOut &info, std::string *err) {
  if (!can_follow(info, err)) return false;  // (checked before anything changes)
  if (info.level != config_.level) {
    set_level(static_cast<ball_level>(info.level), err);
    if (!err->empty()) return false;
  }
  following_ = true;
  state_ = info.state;
  pause_reason_ = info.pause_reason;
  pause_slot_ = info.pause_slot;
  if (in_bounds(find_field(match_fields(), "time_base")->bounds, info.settings.time_base)) config_.time_base = info.settings.time_base;
  unsigned cleared = roster_.follow(info);  // a new holder's racket starts without the old one's history
  for (int k = 0; k < config_.players; ++k)
    if (cleared & (1u << k)) ball_racket_clear(&sim_, k);
  return true;
}

bool Match::restore(const MatchInfoOut &info, const SegmentOut *seg, uint32_t newest_seq, double target,
                    MatchOutput *out, std::string *err) {
  bool seg_newer = seg && seg->seq > info.segment_seq;
  const PlayState &p = seg_newer ? seg->play : info.play;
  const double p_at = seg_newer ? seg->segment.t0 : info.sim_time;
  // the rules' sides and counts index arrays, their times decide the serves:
  // a Play no server writes is refused before anything changes
  if (!play_fits(p, p_at)) {
    *err = "its rules' state (striker " + std::to_string(p.striker) + ", serving side " +
           std::to_string(p.serving_side) + ", bounces " + std::to_string(p.bounces) + ") is out of range";
    return false;
  }
  if (!follow(info, err)) return false;
  double dt = frame_time() * config_.time_base;
  bool hit_at_t0 = false;  // restored at the instant of a racket hit
  if (seg && !(seg->segment.t0 <= target + 1e-9)) {
    *err = "segment " + std::to_string(seg->seq) + " starts at sim time " + std::to_string(seg->segment.t0) +
           ", after the present " + std::to_string(target);
    return false;
  }
  // the info's sim time is a frame end on that segment when it came after it
  double t = seg && !seg_newer && seg->seq == info.segment_seq && info.sim_time >= seg->segment.t0
                 ? info.sim_time
                 : seg ? seg->segment.t0 : sim_.time;
  // the catch-up steps the owner's frames from t to the present: at most
  // kMaxCatchUp real s of them (a present a forged clock puts far away, or
  // +Inf, would step without end)
  bool plays = seg_newer || state_ == MatchState::playing;
  if (plays && dt > 0.0 && !(target - t <= kMaxCatchUp * config_.time_base)) {
    *err = "the present, sim time " + std::to_string(target) + ", is " + std::to_string(target - t) +
           " sim s after the segment's " + std::to_string(t) + ": more than " +
           std::to_string(static_cast<int>(kMaxCatchUp)) + " s of the owner's frames to catch up";
    return false;
  }
  if (seg && !put_on(*seg, t, &hit_at_t0, err)) return false;
  set_rules(p);
  rules().event_seq = std::max(p.event_seq, info.play.event_seq);  // a segment written ahead foresaw its own
  current_seq_ = std::max(seg ? seg->seq : 0u, info.segment_seq);
  // past every seq the owner wrote, ahead included: ours supersede its
  segment_seq_ = std::max(current_seq_, newest_seq);
  ahead_.valid = false;
  if (seg) {
    segment_cause_ = seg->cause;
    segment_cause_index_ = seg->cause_index;
  }
  // only a playing match makes segments: one newer than the info says it plays
  if (seg_newer) state_ = MatchState::playing;
  following_ = false;
  if (state_ == MatchState::playing && dt > 0.0) catch_up(info.sim_time, target, hit_at_t0, out);
  return true;
}

// The ball on the owner's segment at sim s t (a racket hit's tests asleep
// as the owner's were; *hit_at_t0: t is the hit's instant); false with err
// and the sim as it was when libball refuses it.
bool Match::put_on(const SegmentOut &seg, double t, bool *hit_at_t0, std::string *err) {
  ball_sim trial = sim_;
  ball_status st = ball_sim_set_segment(&trial, &seg.segment, t);
  if (st == BALL_OK && seg.cause == Cause::racket) {
    // the racket tests sleep after a hit (section 3.1): as many frames as
    // the owner had left at t (its frame ends since the hit's frame)
    *hit_at_t0 = t == seg.segment.t0;
    st = ball_sim_set_sleep(&trial, sleep_left(seg.segment.t0, t, frame_time() * config_.time_base, model().sleep_frames));
  }
  if (st != BALL_OK) {
    *err = "segment " + std::to_string(seg.seq) + " at sim time " + std::to_string(t) + ": " + ball_strerror(st);
    return false;
  }
  sim_ = trial;
  if (seg.cause == Cause::racket) end_stroke(seg.cause_index, seg.segment.t0);
  return true;
}

// On to the present (sim s target) as the owner went: first to the end of
// the owner's frame (its frames end at info_time + k dt while it plays
// on), the rest of the hit's frame when that is where it starts, then
// frame by frame.
void Match::catch_up(double info_time, double target, bool hit_at_t0, MatchOutput *out) {
  const double dt = frame_time() * config_.time_base;
  double end = info_time + std::ceil((sim_.time - info_time) / dt - 1e-9) * dt;
  if (end > sim_.time + 1e-12 && end <= target) {
    advance(end - sim_.time, false, out);
    if (hit_at_t0) ball_sim_set_sleep(&sim_, std::min(sim_.sleep + 1, model().sleep_frames));
  }
  // (bounded by the check above; a step that moves the clock no more ends it too)
  for (double before = -HUGE_VAL; sim_.time < target - 1e-9 && sim_.time > before;) {
    before = sim_.time;
    advance(std::min(dt, target - sim_.time), false, out);
  }
}

}  // namespace ballsrv
