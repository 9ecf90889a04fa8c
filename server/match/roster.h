// A match's player slots (docs/design.md, "Rooms by state"): who holds
// each, whether they are there, the holders' sample streams and the checks
// a racket sample passes before it may reach the ball (docs/protocol.md,
// "Racket samples"; the order of the checks is the drop reasons' order).
// The Roster owns the slots; the match asks it and tells it what the rules
// and the sim made of a sample. Free of the sim and the rules.
#pragma once

#include <array>
#include <cstdint>

#include "ball/ball.h"
#include "court.h"
#include "match_config.h"
#include "types.h"

namespace ballsrv {

struct Slot {
  bool held = false;
  bool alive = true;         // not reported lost by DDS
  bool present = false;      // derived each frame
  ParticipantId owner{};
  double last_seen = -1e300; // real s of its newest well-formed sample
  uint32_t samples = 0;
  bool has_seq = false;
  uint32_t last_seq = 0;     // the newest accepted (or idle) sample's
  bool has_seen = false;
  uint32_t seen_seq = 0;     // the newest of the holder's samples that arrived, whatever became of it
  uint64_t missing = 0;      // bit i: seq seen_seq - 1 - i skipped and not (yet) arrived
  double seen_at = 0.0;      // sim s: seen_seq's capture time
  SampleRef ref;             // the newest accepted sample
  bool has_prev = false;     // prev_*: the newest sample that passed every check (accepted or idle)
  double prev_time = 0.0;    // sim s: its capture time
  ball_vec3 prev_center{0, 0, 0};  // m
  double asked_time_base = 0.0;    // the time base its holder asked for (0: none): a change needs every holder's
  double hit_time = -1e300;  // sim s: t0 of its racket's newest hit; a sample captured before is before_hit
  // with rewind_own_hit: its newest accepted samples, oldest first, those
  // from before its racket's last hit too (the track holds those after it)
  std::array<ball_racket_sample, BALL_MAX_HISTORY> kept{};
  int kept_n = 0;
  void keep(const ball_racket_sample &s);  // into kept, the oldest out when full
};

class Roster {
 public:
  void init(int players) { players_ = players; }
  int players() const { return players_; }
  Slot &operator[](int k) { return slots_[static_cast<size_t>(k)]; }
  const Slot &operator[](int k) const { return slots_[static_cast<size_t>(k)]; }

  bool held() const;                            // a participant holds one of the slots
  bool holds(const ParticipantId &who) const;   // `who` holds one of them
  bool all_present() const;                     // every slot held and its holder there
  // No slot held, or a holder's sample within `timeout` real s of `now`:
  // the players are on this server's side (a standby's take-over rule).
  bool hears_players(double now, double timeout) const;
  void participant_lost(const ParticipantId &who);  // DDS saw it go: absent at the next presence
  // Presence at real s now (a holder is there when alive and seen within
  // timeout s): true when a slot's presence changed; *missing: the first
  // held slot whose holder is not there (-1: none).
  bool update_presence(double now, double timeout, int *missing);

  // ---- JOIN and LEAVE ----
  // The slot a JOIN of any slot gets: the one `who` holds already, a free
  // one, or one whose holder vanished (lost, or not seen for timeout); -1: no room.
  int free_slot(const ParticipantId &who, double now, double timeout, unsigned allowed = ~0u) const;  // allowed: a bit a slot
  enum class Join { again, taken, refused };
  // again: `who` holds it already (its stream starts anew); taken: a new
  // holder (the racket's history is the caller's to clear); refused: another holds it and is there.
  Join join(int slot, const ParticipantId &who, double now, double timeout);
  bool leave(int slot, const ParticipantId &who);  // false: `who` does not hold it
  // The holders of an owner's MatchInfo (a standby follows): a slot whose
  // holder changed starts anew; returns the slots whose racket history must
  // be cleared (bit k: slot k).
  unsigned follow(const MatchInfoOut &info);
  // A holder asks for time base tb: true when every slot is held and its
  // holder asked for tb (the asks are then forgotten).
  bool ask_time_base(const ParticipantId &who, double tb);
  void fill(MatchInfoOut *info) const;  // the slots of a MatchInfo

  // ---- the holders' streams (docs/protocol.md, `lost`) ----
  // The seqs the holder's stream left behind that never arrived: a sample
  // `seq` of slot k's holder arrived (a late one fills its own gap).
  uint64_t arrived(int k, uint32_t seq, double capture);  // capture: its capture time, sim s
  uint64_t rejected(const RacketSampleIn &s);  // a sample the reader had no room for: its gap only
  void end_streams();                         // all their gaps lost (the server stops)
  uint64_t take_lost();                       // the gaps of streams that ended since the last call

  // ---- a racket sample's checks ----
  // The checks that need neither the sim nor the rules, in the drop
  // reasons' order: the slot and its holder (the stream moves on: *lost),
  // finite, a normal, within the court's box, not ahead of the sim clock
  // sim_now by more than max_sample_lead (the holder is then there), a
  // new seq, not stale, no faster than the racket may move. `accepted`:
  // it passed them.
  SampleResult check(const RacketSampleIn &s, double now, double sim_now, const MatchConfig &config,
                     const Court &court, uint64_t *lost);
  // It passed every check (accepted or idle): its seq and pose are the newest.
  void passed(int k, const RacketSampleIn &s) {
    Slot &slot = (*this)[k];
    slot.has_seq = true;
    slot.last_seq = s.seq;
    slot.has_prev = true;
    slot.prev_time = s.capture_time;
    slot.prev_center = s.center;
  }

 private:
  void end_stream(Slot &slot);  // its gaps to ended_lost_
  std::array<Slot, kMaxPlayers> slots_{};
  int players_ = 0;
  uint64_t ended_lost_ = 0;  // the gaps of ended streams, until take_lost
};

}  // namespace ballsrv
