// A match: one libball sim, its player slots and its rules, free of DDS.
// Frames, samples and control messages go in; segments, events, ball states
// and match info come out (docs/server-design.md, "Match rules").
//
// Time: the sim clock (sim s) advances by frame_time * time_base per frame
// while the match plays and stands still otherwise. `now` arguments are the
// server's realtime clock (s); they decide presence only, never the ball.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "ball/ball.h"
#include "ball/scene.h"
#include "court.h"
#include "match_model.h"
#include "hit_clock.h"
#include "lag.h"
#include "match_config.h"
#include "roster.h"
#include "rules.h"
#include "types.h"

namespace ballsrv {

// What one call produced. The vectors keep their capacity between frames.
struct MatchOutput {
  std::vector<SegmentOut> segments;
  std::vector<EventOut> events;
  bool has_state = false;
  StateOut state;
  bool info_changed = false;
  void clear() {
    segments.clear();
    events.clear();
    has_state = false;
    info_changed = false;
  }
};


// real s of the owner's frames a restore steps at most to the present
// (docs/protocol.md, "Several servers on one domain"): an owner's frames
// since its newest segment and MatchInfo, a few seconds; a present further
// away is a forged clock's
constexpr double kMaxCatchUp = 60.0;

class Match {
 public:
  // Builds the model (build_match_model) and the court; false with err.
  bool init(const MatchConfig &config, const ball_scene &scene, std::string *err);
  // Which participant may hold which slot (docs/security.md, "Slots bound to
  // identities"): a JOIN of a slot the rule refuses is REFUSED_NOT_PLAYER,
  // free or vanished; none: anyone may hold any.
  void set_slot_rule(std::function<bool(int slot, const ParticipantId &who)> rule) { slot_rule_ = std::move(rule); }

  // One frame at real time `now`: presence, the state machine, the serve,
  // the step and the rules.
  void frame(double now, MatchOutput *out);

  // A racket sample; never changes the ball. `now` is when it arrived. A
  // sample of a slot's holder also moves the holder's stream on: *lost (if
  // given) gets the seqs it left behind that never arrived, a late one
  // fills its gap instead (docs/protocol.md, `lost`).
  SampleResult on_sample(const RacketSampleIn &sample, double now, uint64_t *lost = nullptr);
  // A sample the reader had no room for (RacketSampleIn::rejected): it
  // only moves its holder's stream on, so that it is not counted lost too.
  void on_rejected(const RacketSampleIn &sample, uint64_t *lost);
  // The gaps of streams that ended (a JOIN anew, a LEAVE, a new holder, a
  // followed owner's slots) since the last call: lost. end_streams() ends
  // them all (the server stops).
  uint64_t take_lost();
  void end_streams();

  // Racket hits at their instant (docs/server-design.md, "Hits at their instant"):
  // the real s after the last frame's deadline at which the first contact
  // of a racket's track with the ball comes (ball_racket_first_contact_any),
  // when it comes before the next frame's end; +Inf: none. Found again after
  // every frame and hit, and when asked after samples came (once for all of them).
  double hit_after();
  // The last look could not rule out a racket hit before the end of the
  // frame after its own (the bound over both said maybe): the loop runs the
  // frames of such matches first at a deadline, so that a hit early in the
  // next frame is found before its instant, not after other matches' frames.
  bool near_hit() const { return hit_.near(); }
  // sim s of the current frame already stepped to hits (0 at a frame's end)
  double frame_stepped() const { return partial_; }
  // Steps the match to that instant (a partial frame, no ball state): the
  // level's own test finds the hit then; the next frame steps the rest.
  void step_to_hit(MatchOutput *out);

  // Lag compensation (docs/server-design.md, "Lag compensation"): accepted racket
  // samples captured in the past of the sim clock wait here; compensate
  // tests each against the ball where it was (at most rewind_window back,
  // never before the last hit or serve, never once the point is decided)
  // and on a hit goes back to it, applies the response and steps on to the
  // present: its segments come out marked as corrections.
  bool has_late() const { return has_late_; }
  void compensate(MatchOutput *out);

  // A control message; refusals come out as a REFUSED event and the reason.
  Reason on_control(const ControlIn &control, double now, MatchOutput *out);

  // DDS saw the participant go (liveliness lost, writer gone): its slots
  // count as vanished at the next frame.
  void on_participant_lost(const ParticipantId &who);

  // ---- another server's match (docs/protocol.md, "Several servers") ------
  // A standby follows a match another server steps: it takes the owner's
  // MatchInfo (slots, state, level, time base; never the ball) and the
  // racket samples, checked against the owner's sim clock as a client maps
  // it, so that its racket tracks and the slots' presence are warm. It is
  // never stepped while it follows. false with err when the info does not
  // fit this match (another id, slot count or model).
  bool follow(const MatchInfoOut &info, std::string *err);
  // Whether follow(info) would take it, changing nothing (false with err).
  bool can_follow(const MatchInfoOut &info, std::string *err) const;
  void follow_clock(double sim_now) { follow_time_ = sim_now; }
  bool following() const { return following_; }
  // Whether this server hears the match's players at real s `now` (Roster::hears_players, the player timeout).
  bool hears_players(double now) const { return roster_.hears_players(now, config_.player_timeout); }
  bool held() const;  // a participant holds one of its slots

  // Goes on from the owner's newest segment (nullptr: none yet) and
  // MatchInfo: the ball on the segment (at the info's sim time when the info
  // came after it, else at its t0, the racket tests asleep after a hit as
  // they were), the rules' state and the segment and event numbers from
  // the newer of the two, then steps on in frames to the sim time `target`
  // (the bounces and hits of the gap go to out with their own times), and
  // stops following. false with err (and the match still following) when
  // the segment cannot be the sim's (ball_sim_set_segment refused it).
  // newest_seq: the highest segment seq the owner wrote (one written ahead
  // of its contact included), which this server's segments go on from.
  bool restore(const MatchInfoOut &info, const SegmentOut *segment, uint32_t newest_seq, double target, MatchOutput *out,
               std::string *err);
  PlayState play() const;  // the rules' state now

  MatchInfoOut info() const;
  uint32_t id() const { return config_.id; }
  MatchState state() const { return state_; }
  const MatchConfig &config() const { return config_; }
  const ball_model &model() const { return *ball_sim_model(&sim_); }  // the sim's own
  const ball_sim &sim() const { return sim_; }
  // ball_sim_hash of the sim, with the model's hash kept as the model changes
  uint64_t sim_hash() const { return ball_sim_hash_with(&sim_, model_hash_); }
  const Court &court() const { return court_; }
  const MatchCounters &counters() const { return counters_; }
  double frame_time() const { return 1.0 / config_.frame_rate; }
  std::array<int, 2> score() const { return rally_.state().score; }

 private:
  // The segment of the next static contact, written before the contact
  // (docs/protocol.md, "Segments ahead of time").
  struct Ahead {
    bool valid = false;    // a contact foreseen
    bool written = false;  // its segment written (kAheadLead before it)
    ball_event event{};    // the contact as libball predicts it
    SegmentOut segment;    // as written
  };

  void write_ahead(MatchOutput *out);
  bool is_ahead(const ball_event &ev) const;  // ev is the contact written ahead, to the bit
  PlayState judged(const ball_event &ev) const;  // the rules' state once ev is judged, nothing changed
  Call judge(Rally &rally, const ball_event &ev) const;  // what the rules make of a collision
  PlayState &rules() { return rally_.state(); }
  void set_rules(const PlayState &p);  // the rules' state as p says (not the event numbers)
  void emit(MatchOutput *out, EventKind kind, int index, double time, Reason reason = Reason::none,
            double value = 0.0);
  // a segment starts now (sound: its collision makes the paper's sound)
  void emit_segment(MatchOutput *out, Cause cause, int index, const ball_segment &seg, SampleRef ref, bool sound);
  void handle_event(const ball_event &ev, MatchOutput *out);
  void emit_collision(const ball_event &ev, EventKind kind, int index, MatchOutput *out);
  void apply(const Call &call, double t, MatchOutput *out);  // a point decided at sim s t
  void serve(MatchOutput *out);
  void update_presence(double now, MatchOutput *out);
  void advance(double dt, bool with_state, MatchOutput *out);  // a frame's sim part: serve, step, rules
  double clock_now() const { return following_ ? follow_time_ : sim_.time; }  // sim s the sample checks use
  void set_level(ball_level level, std::string *err);
  bool put_on(const SegmentOut &seg, double t, bool *hit_at_t0, std::string *err);  // restore's ball
  void catch_up(double info_time, double target, bool hit_at_t0, MatchOutput *out);  // restore's frames
  void find_hit();  // the hit clock looks again, from the tracks as they are (when the rules allow a hit)
  void took_effect(const SegmentOut &s);  // a segment is in effect now: into the history
  // Lag compensation (docs/server-design.md, "Lag compensation"): the late hit of
  // slot `slot`'s racket since sim s `from`, if any (find_late_hit, which
  // changes nothing), then the match taken back to it and on to the present.
  void rewind(int slot, double from, MatchOutput *out);
  void end_stroke(int slot, double t_hit);  // its racket hit at t_hit: its track from then on only
  LagParams lag_params() const {
    return {config_.rewind_window, config_.rewind_own_hit, frame_time() * config_.time_base};
  }
  void set_state(MatchState s, MatchOutput *out);
  Reason refuse(const ControlIn &c, Reason why, MatchOutput *out);
  Reason on_join(const ControlIn &c, double now, MatchOutput *out);
  Reason on_leave(const ControlIn &c, MatchOutput *out);
  Reason on_player_control(const ControlIn &c, MatchOutput *out);  // SERVE, LEVEL, PAUSE, RESUME, TIME_BASE of a holder
  int side_of_point(ball_vec3 p) const { return court_.side_of(p.x); }

  std::function<bool(int, const ParticipantId &)> slot_rule_;
  MatchConfig config_;
  ball_sim sim_{};
  uint64_t model_hash_ = 0;  // ball_model_hash of the sim's model, kept as the model changes
  Court court_;
  Roster roster_;  // the slots, their holders and streams
  MatchState state_ = MatchState::waiting;
  Reason pause_reason_ = Reason::none;
  int pause_slot_ = -1;
  bool left_mid_match_ = false;  // a LEAVE stopped a match that had started
  Rally rally_;  // the rules' state (the score, the serve due, the event seqs): play() is its copy
  uint32_t segment_seq_ = 0;  // the newest segment written (one ahead included)
  uint32_t current_seq_ = 0;  // the segment in effect: the sim's
  Ahead ahead_;
  bool stepped_ahead_ = false;  // this frame stepped a contact written ahead
  HitClock hit_;  // the next racket hit before the frame's end (find_hit)
  double partial_ = 0.0;        // sim s of the current frame already stepped to hits
  std::vector<SegmentOut> history_;  // the segments in effect over the rewind window, oldest first (play: judged)
  // per slot, the capture time of the sample before its first late one
  // waiting (-Inf: none before it; NaN: none waiting): the late samples of
  // a slot are tested together, so a flood of them costs one test a wake-up
  std::array<double, kMaxPlayers> late_from_{};
  bool has_late_ = false;
  bool correcting_ = false;     // segments written now are corrections
  Cause segment_cause_ = Cause::serve;  // what started the current segment
  int segment_cause_index_ = -1;
  uint64_t ended_lost_ = 0;  // the gaps of ended streams, until take_lost
  double state_accum_ = 0.0; // fraction of a ball state owed (state_rate / frame_rate per frame)
  MatchCounters counters_;
  std::vector<ball_event> step_events_;
  bool following_ = false;   // another server steps it: never stepped here
  double follow_time_ = 0.0; // sim s: the owner's sim clock while following
};

}  // namespace ballsrv
