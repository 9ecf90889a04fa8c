// One match as a client sees it (docs/protocol.md; docs/client.md): the
// core of the client library, free of DDS. It takes the server's samples
// of the match as they come (MatchInfo, MatchModel, segments, events, ball
// states) by the rules of "Clients that trust no one", keeps the match's
// sim clock, one window of segments with one rule for a match started
// anew, the corrections and the events they void, and answers where the
// ball is at any time of the caller's clock from the segment in effect.
// Every client of the project is fed through one: the library's C API,
// the bots, the watcher and the page (compiled to WebAssembly).
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <vector>

#include "sim_clock.h"
#include "trust.h"
#include "types.h"

namespace ballsrv {

// What a view tells its owner besides the server's own events.
enum class ViewNote {
  none,    // a server's event (EventOut as it came)
  server,  // the match's server changed: event.server_id the new one
  slot,    // this client's slot event.index: event.value 1 taken, 0 lost
  voided,  // a correction took back an event given before: event is that event
  gap,     // events never came: event.value how many seqs were skipped
};

struct ViewEvent {
  ViewNote note = ViewNote::none;
  EventOut event;  // the server's event (voided: the event taken back); for another note, match_id,
                   // time and the fields the note names
};

// A segment kept, with its flight prepared for evaluation (ball_flight).
struct KeptSegment {
  SegmentOut segment;
  ball_flight flight{};
  bool ready = false;  // flight prepared (ball_flight_init took it)
};

struct ViewCounters {
  uint64_t segments = 0;  // segments taken
  uint64_t events = 0;    // server events given
  uint64_t refused = 0;   // samples not taken (trust.h): another server's, out of range, a clock pair or seq that does not fit
  uint64_t lost = 0;      // event seqs skipped
  uint64_t late = 0;      // segments taken after their t0 on the caller's clock
  uint64_t voided = 0;    // events a correction took back (given or not)
  uint64_t anew = 0;      // times the match was started anew
  uint64_t old_owner = 0; // samples of an older owner than the one taken (docs/protocol.md, "Terms")
  uint64_t replaced = 0;  // events given that a newer owner's other event of their seq replaced (each voided)
};

// The ball as a view answers it.
struct ViewBall {
  ball_state state{};        // position m, velocity m/s, spin m/s
  double sim_time = 0.0;     // sim s
  const SegmentOut *segment = nullptr;  // the segment in effect
};

class MatchView {
 public:
  static constexpr size_t kWindow = 16;          // segments kept: the one in effect, those written ahead, a trail's past
  static constexpr double kAnew = 1.0;           // sim s: a MatchInfo this far behind the newest is a match started anew
  static constexpr double kVoidableFor = 5.0;    // sim s an event given stays where a correction may void it
  static constexpr size_t kCorrections = 16;     // the newest corrections, which may void events still to come
  // s of the caller's clock: an owner of whom nothing came this long is
  // forgotten, and any owner's samples are taken again (a match served
  // anew after its servers were gone; an owner writes a MatchInfo at
  // least every 4 s and its writers live for a 1 s lease: docs/protocol.md, "Time")
  static constexpr double kForgetOwner = 10.0;
  // s of the caller's clock: the owner's samples come from the participant
  // that wrote the newest taken; another participant's of the same owner
  // (a stranger copying its server id and term) are refused while that one
  // was heard this long ago at most (more than the 4 s between MatchInfos;
  // a server restarted under its old term is taken after it).
  static constexpr double kOwnerWriter = 5.0;

  // `servers`: whose samples it takes; `me`: this client's participant (its slot)
  MatchView(uint32_t id, const ServerChoice &servers, const ParticipantId &me);
  // the client's participant from now on (a client started anew: ClientCore::renewed)
  void set_me(const ParticipantId &me) { me_ = me; }

  // What the server said; `local` is the caller's clock at its reception.
  // false: refused (counted). Notes and events for the caller go to `out`.
  bool on_info(const MatchInfoOut &info, double local, std::vector<ViewEvent> *out);
  bool on_model(const MatchModelOut &model);
  bool on_segment(const SegmentOut &segment, double local, std::vector<ViewEvent> *out);
  bool on_event(const EventOut &event, double local, std::vector<ViewEvent> *out);
  bool on_state(const StateOut &state, double local);
  // a one-way delay seen (s): a sample's reception less its source time
  void on_delay(double seconds);

  uint32_t id() const { return id_; }
  // the owner taken: its term and server (0, 0: none yet)
  uint32_t term() const { return has_owner_ ? term_ : 0; }
  bool has_info() const { return has_info_; }
  const MatchInfoOut &info() const { return info_; }  // the newest usable
  double info_local() const { return info_local_; }   // the caller's clock at its reception
  const SimClock &clock() const { return clock_; }
  // the whole model from the wire (docs/protocol.md, "The match's model"); nullptr until it came
  const ball_model *model() const { return has_model_ ? &model_.model : nullptr; }
  // the flight model: the whole model's, else MatchInfo's flight fields
  const ball_model &flight_model() const { return has_model_ ? model_.model : info_.model; }
  bool holds(int slot) const { return slot >= 0 && slot < kMaxPlayers && (mine_ >> slot & 1u); }  // this client's
  int slot() const;  // the lowest slot this client holds, -1: none
  const std::vector<KeptSegment> &window() const { return window_; }  // by (owner, seq), oldest first
  const ViewCounters &counters() const { return counters_; }
  double delay() const;  // s: the median of the recent delays (0: none)

  // The segment in effect at sim time t: of those kept, the latest by
  // (owner, seq) whose t0 is not after t; nullptr: none.
  const KeptSegment *in_effect(double sim) const {
    for (auto it = window_.rbegin(); it != window_.rend(); ++it)
      if (it->segment.segment.t0 <= sim) return &*it;
    return nullptr;
  }
  // The segment in effect at `local` of the caller's clock and that sim
  // time: what ball() evaluates (nullptr: no clock, or no segment in
  // effect yet). The library's ball query, kept to a few comparisons.
  const KeptSegment *at(double local, double *sim) const {
    if (!clock_.valid()) return nullptr;
    *sim = clock_.sim_now(local);
    const KeptSegment *k = in_effect(*sim);
    return k && k->ready ? k : nullptr;
  }
  // The ball at `local` of the caller's clock. BALL_EAGAIN: no clock or
  // no segment in effect yet; BALL_ENONFINITE: a NaN or infinite time.
  ball_status ball(double local, ViewBall *out) const;
  // The path ahead from the segment in effect at `local` (ball_predict).
  // BALL_EAGAIN: no whole model, clock or segment yet.
  ball_status predict(double local, double horizon, double dt, ball_prediction *out) const;

 private:
  void start_anew();
  // docs/protocol.md, "Terms": whether a sample of (term, server) may be
  // taken at `local`; taking one makes its owner the held one (true: an
  // older one, the match started anew)
  // and its writer's participant `from` (zeros: unknown, any)
  bool owner_fits(uint32_t term, uint32_t server, const ParticipantId &from, double local);  // (counts what it refuses)
  bool take_owner(uint32_t term, uint32_t server, const ParticipantId &from, double local);
  bool keep(const SegmentOut &s);  // false: held already
  void prepare(KeptSegment *k) const;
  void void_given(const SegmentOut &correction, std::vector<ViewEvent> *out);
  bool voided_before(const EventOut &e) const;
  void give(const EventOut &e, std::vector<ViewEvent> *out);
  bool replace_given(const EventOut &e, std::vector<ViewEvent> *out);
  ViewEvent note(ViewNote n, double time) const;

  uint32_t id_;
  ServerChoice servers_;
  ParticipantId me_;
  MatchInfoOut info_;
  bool has_info_ = false;
  double info_local_ = 0.0;
  SimClock clock_;
  MatchModelOut model_;
  bool has_model_ = false;
  std::vector<MatchModelOut> models_;  // models not (yet) named by a MatchInfo: the newest few
  uint64_t flight_hash_ = 0;           // the model hash the window's flights were prepared with
  std::vector<KeptSegment> window_;
  uint32_t term_ = 0, owner_ = 0;      // the owner taken: term, server id
  bool has_owner_ = false;
  double owner_local_ = 0.0;           // the caller's clock at its newest sample taken
  ParticipantId owner_from_{};         // the participant that wrote it (zeros: unknown)
  uint32_t last_event_ = 0;            // the newest event seq given
  bool any_event_ = false;
  std::deque<EventOut> given_;         // voidable events given, the last kVoidableFor sim s
  std::deque<EventOut> recent_;        // the newest kGivenKept events given, any kind
  std::deque<std::pair<uint32_t, double>> corrections_;  // (seq, t0) of the newest corrections
  unsigned mine_ = 0;  // the slots this client holds, a bit each
  std::vector<double> delays_;         // the newest one-way delays, a ring
  size_t next_delay_ = 0;
  ViewCounters counters_;
};

// The segment in effect on a view, handed on once each time it changes: a
// segment written ahead when its t0 has come, never one a racket hit
// superseded (what a bot's brain plays).
class EffectFeed {
 public:
  // The segment in effect at sim time `sim` if it was not handed on yet; nullptr otherwise.
  const SegmentOut *due(const MatchView &view, double sim) {
    const KeptSegment *k = view.in_effect(sim);
    if (!k || (any_ && k->segment.seq == seq_)) return nullptr;
    seq_ = k->segment.seq;
    any_ = true;
    return &k->segment;
  }

 private:
  uint32_t seq_ = 0;
  bool any_ = false;
};

// The events a correction (a segment with `correction` set) voids
// (docs/protocol.md, "Corrections"): a collision's or a point's, written
// before it (its segment older, serial arithmetic) for a later time.
bool voids(uint32_t correction_seq, double t0, const EventOut &e);
// Two events of one seq that say the same: kind, index, side, in play, time,
// reason and score (not segment_seq: a new owner numbers its segments on).
bool same_event(const EventOut &a, const EventOut &b);

}  // namespace ballsrv
