// The server's loop, free of DDS (docs/server-reference.md, "The status line";
// docs/server-design.md, "Frame clock"). One loop on one thread owns every
// match of a Host; at each wake-up it runs its phases in order:
//
//   take notes     what the DDS threads noticed: writers lost, deadlines
//                  missed, samples DDS rejected or lost (counted as drops)
//   take others    what the other servers of the domain wrote: their
//                  status (who is there, their role and room), MatchInfo
//                  and segments; a standby follows their matches with it,
//                  and a server that reads another's MatchInfo for a match
//                  it steps yields it (docs/protocol.md, "Several servers")
//   take samples   every racket sample that came in, to its match
//   take controls  every control message, to its match; a CREATE schedules
//                  the new match
//   take over      a followed match whose owner's writers lost their
//                  liveliness a grace ago, when this server is its
//                  successor: restored (Match::restore) and scheduled
//   run due hits   each match with late racket samples tests them where the
//                  ball was (lag compensation: a hit found rewinds it), and
//                  each match whose next racket hit's instant has come
//                  (Match::hit_after, from its last frame's deadline) steps
//                  to it and publishes the hit at once
//   run due frames each match whose deadline has come steps one frame and
//                  publishes what it produced; a match more than
//                  max_behind frames late (the machine stalled) skips to
//                  the present and counts the skipped frames
//   status         once a status interval: the status written, conflicts
//                  (another server announcing one of our matches) reported
//
// Deadlines are absolute (FrameClock), so errors do not add up. The network
// is reached through a ServerPort (server/dds implements it over DDS), the
// time through a Clock: the tests drive the loop with fakes of both.
#pragma once

#include <cmath>
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "cluster.h"
#include "frame_clock.h"
#include "host.h"
#include "records.h"

namespace ballsrv {

// What the network side noticed about the racket samples' writers.
struct PortNote {
  // writer_lost: a player's racket writer; server_lost: another server's
  // writers of the server topics (its liveliness lost or unmatched);
  // rejected, lost: racket samples; control_rejected, control_lost: controls;
  // door_unknown_match, door_bad_slot: racket samples, door_control: controls,
  // turned away at the reader's door (ServerPort::admit); door_malformed:
  // racket samples the door found not readable as their type
  enum Kind {
    writer_lost, deadline_missed, rejected, lost, server_lost, control_rejected, control_lost,
    door_unknown_match, door_bad_slot, door_control, door_malformed
  } kind;
  ParticipantId who{};  // writer_lost, server_lost: the participant; zeros otherwise
  uint64_t count = 1;   // samples or deadlines
};

class ServerPort {
 public:
  virtual ~ServerPort() = default;
  virtual void take_notes(std::vector<PortNote> *out) = 0;  // appends what was noticed since the last call
  virtual bool take_sample(RacketSampleIn *sample) = 0;     // false: none left; from and source_time filled in
  virtual bool take_control(ControlIn *control) = 0;        // false: none left; from filled in
  // The matches (id, player slots) whose samples and controls come in, and
  // the ids CREATEs may name (Host::create_ids): the port may turn the
  // others away before they cost it anything (a sample for another match or
  // slot, a control for another match, a CREATE outside those ids), counted
  // as door notes. Until the first call it lets everything in.
  virtual void admit(const std::vector<std::pair<uint32_t, int>> &matches, CreateIds creates) {
    (void)matches;
    (void)creates;
  }
  // MatchInfo, segments and status written by other servers (our own are
  // skipped); false: none left
  virtual bool take_other_info(MatchInfoOut *info, ParticipantId *from) = 0;
  virtual bool take_other_segment(SegmentOut *segment, ParticipantId *from) = 0;
  virtual bool take_other_status(StatusOut *status, ParticipantId *from) = 0;
  // the MatchModel of another server's match (a standby follows matches with it); false: none left
  virtual bool take_other_model(MatchModelOut *model, ParticipantId *from) = 0;
  // false: the write was refused (counted as a write failure)
  [[nodiscard]] virtual bool write(const SegmentOut &s) = 0;
  [[nodiscard]] virtual bool write(const EventOut &e) = 0;
  [[nodiscard]] virtual bool write(const StateOut &s) = 0;
  [[nodiscard]] virtual bool write(const MatchInfoOut &i) = 0;
  [[nodiscard]] virtual bool write(const StatusOut &s) = 0;
  [[nodiscard]] virtual bool write(const MatchModelOut &m) = 0;
  // Asserts the liveliness of every writer (docs/protocol.md: manual by
  // topic, lease 1 s); the loop calls it every kLivelinessPeriod. false: refused.
  virtual bool assert_liveliness() = 0;
  // A match this server no longer has: its MatchInfo and MatchModel
  // instances disposed (a late joiner is not handed them). false: refused.
  virtual bool dispose_match(uint32_t match_id) = 0;
  // Sets the ownership strength of the match writers (docs/protocol.md,
  // "Terms"); false: refused.
  virtual bool set_strength(uint32_t strength) {
    (void)strength;
    return true;
  }
};

// s: a racket hit due within this of the one the loop saw before is that
// hit found again (after a frame, or a sample that moved it a little)
constexpr double kSameHit = 1e-3;
// Samples one note of DDS may count as lost: DDS counts a gap in a writer's
// sequence numbers, which one forged datagram can make 2^31 long (a gap
// beyond this is a restart or a forgery, not that many samples).
constexpr uint64_t kMaxLostPerNote = 1000;


// The loop's settings; its place among the servers of a domain is the
// Cluster's (cluster.h: server_id, standby, claim, strength, the graces).
struct LoopSettings : ClusterSettings {
  double status_interval = 1.0;  // real s between status writes
  double info_interval = kInfoEvery;  // real s from a match's MatchInfo to the next when nothing changed
  double max_behind = 5.0;       // frames: a match further behind its deadline skips to the present
  double settle = 1.0;           // real s a claimed match waits before its first frame (startup_wait)
  double create_timeout = 30.0;  // real s a created match stands with nobody holding a slot before it goes
};

// The loop's counters: the status line, ServerStatus, the stats file (and
// the Cluster's, cluster.h).
struct LoopStats {
  StatusOut totals;             // the counters ServerStatus carries: samples, drops, controls, writes, frames, overruns
  uint64_t infos_out = 0, statuses_out = 0, models_out = 0;  // MatchInfo, ServerStatus and MatchModel written
  uint64_t skipped = 0;         // frames skipped after a stall
  uint64_t deadline_missed = 0, writers_lost = 0;
  uint64_t controls_at_door = 0;  // controls the control reader's door turned away (in controls_refused too)
  uint64_t controls_no_room = 0;  // controls over their writer's share of the inbox, or DDS had no room (in controls_refused too)
  uint64_t liveliness_failures = 0;  // liveliness assertions the port refused
  uint64_t created_expired = 0;  // created matches removed: nobody held a slot for create_timeout
  uint64_t hit_wakes = 0;        // partial frames stepped to a racket hit's instant
  Percentiles hit_late;          // real s such a step began after the hit's instant (negative: before it, by up to hit_lead)
  Percentiles hit_wake_late;     // real s such a step began after its due time, of the hits the loop knew before it
  Percentiles hit_found_late;    // real s such a step began after the hit's instant, of the hits the loop first saw after it (their samples came later)
  Percentiles frame_time;       // real s of work per wake-up, this status period
  Percentiles late;             // real s a frame started after its deadline, this status period
  Percentiles late_p99;         // each period's p99 of that, over the run
  double late_max = 0.0;        // real s, over the run
  Percentiles latency;          // real s from a hit's newest racket sample's write to its segment's, this period
  Percentiles latency_all;      // the same over the run
};

class ServerLoop {
 public:
  ServerLoop(Host &host, ServerPort &port, Clock &clock, const LoopSettings &settings);

  // Listens up to `seconds` for another server announcing one of our
  // matches: true with its MatchInfo (the domain is busy).
  bool find_owner(double seconds, const std::function<bool()> &stop, MatchInfoOut *other);
  // A standby's or claimant's start: announces this server (ServerStatus)
  // and listens `seconds` to the others (take others), so that it knows
  // them before it claims or follows.
  void listen(double seconds, const std::function<bool()> &stop);

  // Schedules every match (their frames count from now: matches of one
  // rate step together) and publishes their MatchInfo; a claimant first
  // keeps only the configured matches the claim rule gives it.
  void start();

  // Runs the phases now; true when a status period ended (status() has
  // the new status, already written). step() sleeps to next_wake() first.
  bool wake();
  bool step();
  // Steps until stop() or `duration` real s (0: no limit); calls on_status
  // with each status written, on_conflict with each MatchInfo of another
  // server for one of our matches.
  void run(double duration, const std::function<bool()> &stop,
           const std::function<void(const StatusOut &)> &on_status,
           const std::function<void(const MatchInfoOut &, const ParticipantId &)> &on_conflict);
  // The last status, written once more at the end.
  StatusOut finish();

  // Lines worth a line of the server's log: take-overs, yields, claims,
  // matches it cannot follow.
  void on_note(std::function<void(const std::string &)> fn) { on_note_ = std::move(fn); }

  // The phases, in the order step runs them (t0: mono s of the wake-up,
  // now: server s).
  void take_notes(double t0);
  void take_others();
  void admit_hosted();
  void take_samples(double now);
  void count_lost(uint64_t lost);  // seqs lost: counted in (samples_in) and dropped (docs/protocol.md)
  void take_controls(double now);
  void take_over(double t0, double now);
  void run_due_hits(double t0, double now);  // matches whose racket hit's instant has come step to it
  void run_due_frames(double t0, double now);  // those near a hit first (Match::near_hit)
  void write_due_states(double now);  // the frames' states, after the frames (hits come first)

  double next_wake() const;  // mono s
  StatusOut status_now() const;
  const StatusOut &status() const { return status_; }
  const LoopStats &stats() const { return stats_; }
  ServerReport report() const;
  double uptime() const;  // real s since start
  const Cluster &cluster() const { return cluster_; }  // the other servers of the domain, and what it follows

 private:
  struct Scheduled {
    Match *match;
    FrameClock clock;
    uint64_t k = 0;                // next frame index
    double last_frame_real = 0.0;  // server s of the newest frame's deadline
    double next_info = 0.0;        // mono s of the next periodic MatchInfo
    uint32_t revision = 0;
    uint32_t term = 1;             // the term it is stepped at (docs/protocol.md, "Terms")
    uint64_t model_written = 0;    // the model hash of the newest MatchModel written (0: none yet)
    double firm_at = 0.0;          // mono s: no frame before (a claim settling)
    double since = 0.0;            // server s: when this server began to step it
    bool taken_over = false;       // from another server
    double last_held = 0.0;        // mono s a slot was last held (for a created match's expiry)
    bool state_due = false;        // `state` is a frame's, written after the frames of the wake-up
    bool info_waits = false;       // a MatchInfo due after a hit's step, written with the next frame
    double due_seen = HUGE_VAL;    // mono s: the hit due the loop last saw (hit_due), and
    double due_seen_at = 0.0;      // when it first saw it (see_due)
    StateOut state{};
  };
  Scheduled schedule(Match *m);
  double hit_due(const Scheduled &s) const;  // mono s to step its next racket hit: the instant less hit_lead; +Inf: none
  static void see_due(Scheduled &s, double at, double t);  // the loop saw hit due `at` at mono s t
  void run_frame(Scheduled &s, double t0, double now);  // its due frame, then the hits due by then
  Scheduled *scheduled(uint32_t id);
  void other_info(const MatchInfoOut &info, const ParticipantId &from);
  void yield(uint32_t id, const MatchInfoOut &to, const ParticipantId &from);
  void raise_strength(uint32_t at_least);  // the match writers' strength, never lowered
  bool claim(const MatchConfig &config, double t0, std::string *err);
  void claim_unplaced(double t0);
  bool may_create(const ControlIn &control);
  void take_over_match(uint32_t id, double t0, double now);
  void say(const std::string &line);
  void drop_own_if_standby();
  // a frame's state is held in s (write_state), the rest written at once
  void publish(const MatchOutput &out, Scheduled &s, double now);
  void write_state(Scheduled &s);  // its frame's state, if one is due
  void publish_info(Scheduled &s);
  void info_changed(Scheduled &s);  // now, or with the next frame after a hit's step
  void close_period();  // the status written, the period's latency kept for the line
  template <class T>
  void write(const T &sample, uint64_t *written);

  Host &host_;
  ServerPort &port_;
  Clock &clock_;
  LoopSettings settings_;
  Cluster cluster_;
  uint32_t base_strength_ = 0;  // its role's (the QoS file's primary or standby profile)
  FrameClock origin_{1.0, 0.0, 0.0};
  std::vector<Scheduled> sched_;
  double start_ = 0.0, next_status_ = 0.0;
  LoopStats stats_;
  StatusOut status_;
  MatchOutput out_;
  std::vector<PortNote> notes_;
  std::vector<std::pair<uint32_t, int>> admitted_, admitted_now_;  // the port's door: (match, slots)
  bool admitted_once_ = false;
  std::function<void(const MatchInfoOut &, const ParticipantId &)> on_conflict_;
  std::function<void(const std::string &)> on_note_;
  double next_assert_ = 0.0;  // mono s of the next liveliness assertion
  double earliest_hit_ = HUGE_VAL;  // mono s of the earliest hit_due of the scheduled matches
  std::vector<char> frame_due_;     // run_due_frames': 0 none, 1 near a hit, 2 the rest
  void keep_alive(double t0);
  void expire_created(double t0);
};

// The status line: "ball-server 1: 12 s, matches 1 (1 playing), samples in ...".
std::string status_line(const StatusOut &status);

}  // namespace ballsrv
