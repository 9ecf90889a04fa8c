// Failover's room (docs/design.md, "Rooms by state"; docs/protocol.md,
// "Several servers on one domain"): what one server knows of the other
// servers of its domain and what it decides from it. A Cluster owns the
// peers heard of (their ServerStatus), the matches a standby follows (the
// owners' newest MatchInfo and segments), the owners of a claimant's
// configured matches and the claims made; it is told what the network
// brought and the time (real and monotonic s) as arguments, and returns
// decisions: refuse, yield, follow, take over, claim, leave a CREATE to
// another server. The server's loop carries them out on its host and
// reports back what came of them. Free of the match, the loop, DDS and clocks.
#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "match_config.h"
#include "placement.h"
#include "types.h"

namespace ballsrv {

// s between two assertions of a server's writers' liveliness: 4 per 1 s lease
// (docs/protocol.md, "Several servers on one domain")
constexpr double kLivelinessPeriod = 0.25;
// s: how often a standby with nothing of its own to step wakes to take
// its followed matches' samples and notes
constexpr double kFollowWake = 1.0 / 60.0;
// segments a standby keeps of each followed match, the newest by seq: the
// one in effect and those written ahead of their contact
constexpr size_t kFollowedSegments = 8;
// real s a followed MatchInfo's server_time may lie from this server's
// realtime clock: an owner writes its MatchInfo at least every kInfoEvery s,
// stamped with its newest frame's deadline, and the servers of a domain keep
// their clocks in step (NTP); a take-over maps the owner's sim clock by that stamp
constexpr double kMaxClockGap = 10.0;
// real s a standby waits for the MatchModel a followed match's MatchInfo
// names before it looks for a scene of the info's name (the two topics'
// samples come apart)
constexpr double kModelWait = 2.0;
// s a take-over held back for want of players waits once they are heard
// again: a healed cut brings the owner back too, a little after its
// players' samples (its liveliness, asserted 4 times a second)
constexpr double kPlayersSettle = 2.0;
// s: a followed match whose live owner wrote no MatchInfo of it for this
// long is no longer stepped by it, as if the owner were lost (an owner
// writes one at least every kInfoEvery s): a stranger
// that took a match with a newer term and went quiet keeps nothing.
constexpr double kOwnerSilent = 10.0;
// a server's match writers are as strong as its role plus this much per
// term of the newest match it steps (docs/protocol.md, "Terms"): above
// every role's strength, so that a newer term always outranks
constexpr uint32_t kTermStrength = 100;
// A term is a round and the low bits of its server's id (docs/protocol.md,
// "Terms"): two servers that start or take over one match in ignorance of
// each other give it two terms, and DDS, every server and every client
// rank them alike (by strength, by term).
constexpr uint32_t kTermIdBits = 8;
// The term a server of id `server_id` starts or takes over a match at
// whose highest term heard (or followed) is `heard`: the next round.
inline uint32_t next_term(uint32_t heard, uint32_t server_id) {
  return (((heard >> kTermIdBits) + 1) << kTermIdBits) | (server_id & ((1u << kTermIdBits) - 1));
}
// The writers' strength of a role's `base` at `term`, held below 2^32.
inline uint32_t term_strength(uint32_t base, uint32_t term) {
  uint64_t s = static_cast<uint64_t>(base) + static_cast<uint64_t>(kTermStrength) * term;
  return s > UINT32_MAX ? UINT32_MAX : static_cast<uint32_t>(s);
}
// other servers' ServerStatus writers a cluster keeps at most: the remote
// participants the QoS profiles allow (total_participants), so that forged
// writers cannot grow it without bound; a lost one is forgotten
constexpr size_t kMaxPeers = 4096;

// One server's place among the servers of its domain.
struct ClusterSettings {
  uint32_t server_id = 1;  // in every sample written
  bool standby = false;    // follows other servers' matches, takes one over when its owner dies
  uint32_t claim = 0;      // configured or created matches it may claim; 0: it serves its configured ones
  uint32_t strength = 20;  // its match writers' ownership strength (the QoS file's, for ServerStatus)
  // real s from the first of the owner's writers lost to the take-over: the
  // owner asserted its writers together every kLivelinessPeriod and each
  // write asserts its writer again, so a reader lets the last of them go up
  // to a period after the first; a sample written before a reader let its
  // owner's writer go is dropped by that reader (exclusive ownership)
  double takeover_grace = kLivelinessPeriod + 0.15;
  double orphan_wait = 5.0;  // real s an owner is gone before a claimant may start its match anew
};

// What a Cluster decided and counted.
struct ClusterStats {
  uint64_t others_refused = 0;     // MatchInfo and Segments of others no server writes (trust.h, kMaxClockGap)
  uint64_t conflicts = 0;          // MatchInfo of one of our matches from another server
  uint64_t takeovers = 0;          // followed matches taken over
  uint64_t takeovers_waiting = 0;  // take-overs held back: none of the match's players heard here
  uint64_t stale_terms = 0;        // another server's MatchInfo of an older owner than ours or the followed one
  uint64_t yields = 0;             // matches given up to a server that outranks this one
  uint64_t claims = 0;             // matches claimed (configured or created)
  uint64_t follow_failures = 0;    // another server's matches this one could not follow or restore
  uint64_t creates_elsewhere = 0;  // CREATEs left to another server (standby, claim rule)
  uint64_t unknown_writers = 0;    // MatchInfos held back: their writer's ServerStatus was not heard (yet)
  uint64_t unheld_let_go = 0;      // followed matches whose owner died with no slot held: not taken over
};

// Another server's match that a standby follows, or a server follows
// since it yielded it.
struct Followed {
  MatchInfoOut info;      // the owner's newest
  Segments segments;      // its newest few (kFollowedSegments; the newest may lie ahead)
  ParticipantId owner{};  // the owner's participant
  double lost_at = -1.0;  // mono s its writers lost their liveliness; -1: alive
  double heard_at = -1.0; // mono s its newest MatchInfo was heard (-1: not yet)
  bool waits_for_players = false;  // due, but none of its players heard here (counted once)
  double players_back_at = -1.0;   // mono s its players were heard again after a wait; -1: not yet
};

// The segment a standby restores an owner's match from: of the owner's
// segments, the newest in effect at sim time `target` that the owner is
// known to have stepped through: a serve or a racket hit (written at their
// instant), one the MatchInfo names, or one a later segment starting after
// it follows (the owner wrote that one once it had stepped past). A contact
// written ahead that the owner may not have reached is not: the standby
// steps it again, its events included. nullptr: none newer than the
// MatchInfo's own segment.
const SegmentOut *stepped_segment(const Segments &segments, const MatchInfoOut &info, double target);

// Where a take-over goes on from (Match::restore's arguments).
struct RestorePoint {
  MatchInfoOut info;         // the owner's newest MatchInfo
  SegmentOut segment{};      // the segment in effect at `target` (has_segment)
  bool has_segment = false;  // false: the match restarts from the info alone
  uint32_t newest_seq = 0;   // the owner's newest segment seq (one written ahead included)
  double target = 0.0;       // sim s of the frame before this server's first, on the owner's clock
};

// A take-over's restore point: on the owner's sim clock, as its clients map
// it (docs/protocol.md, "Time"), at the frame before this server's first
// (its deadline first_real, server s; frame_time s a frame), never before a
// serve or a hit the owner wrote (those are never written ahead).
RestorePoint restore_point(const Followed &f, double first_real, double frame_time);

class Cluster {
 public:
  explicit Cluster(const ClusterSettings &settings) : settings_(settings) {}

  // ---- what the network brought (the loop's "take others" phase) ----
  void hear_status(const StatusOut &status, const ParticipantId &from);
  void hear_model(const MatchModelOut &model);
  // A MatchInfo no server could have written (trust.h: usable_other_info)
  // is nobody's: counted, false.
  bool server_wrote(const MatchInfoOut &info);
  // A conflicting MatchInfo the match cannot follow (Match::can_follow): nobody's, counted.
  void refuse_other() { stats_.others_refused++; }
  enum class Heard { refused, noted, conflict, stale, unknown };
  // Another server's MatchInfo. unknown: its writer is no server heard
  // alive (no ServerStatus from its participant): nobody yields to it,
  // follows it or counts it an owner; its newest of each match waits for
  // that ServerStatus (known_infos). hosted: the host has the match (a
  // claimant's configured one before start, or one it follows); ours: this
  // server steps it. now: server s. conflict: this server must yield it
  // (DDS ranks the writer above us for every reader: the weaker of two
  // owners yields); the loop yields, then asks follow_plan.
  // our_term: the term this server steps it at (ours). conflict: a higher
  // term, or the same from a lower server id; stale: an older one (the
  // loop raises its writers above the sender's: stronger_than).
  Heard hear_info(const MatchInfoOut &info, const ParticipantId &from, bool hosted, bool ours, uint32_t our_term,
                  double now);
  // The MatchInfos held back whose writer is now a server heard alive, to
  // be heard again (the loop takes the statuses first).
  std::vector<std::pair<MatchInfoOut, ParticipantId>> known_infos();
  // The highest term of a match heard from other servers (0: none).
  uint32_t heard_term(uint32_t match_id) const;
  // A strength above the writer of participant `from` (its ServerStatus;
  // unknown: `own` + kTermStrength).
  uint32_t stronger_than(const ParticipantId &from, uint32_t own) const;
  // This server's writers' strength now (ServerStatus, the successor rule).
  void set_strength(uint32_t strength) { settings_.strength = strength; }
  enum class Follow { none, begin, update };
  // What a server does with a MatchInfo it heard: nothing (not a standby
  // and not following the match, or the MatchModel is still waited for),
  // begin following the
  // match (with *model, or a scene of the info's name when *model is
  // nullptr), or update the match it follows. t0: mono s.
  Follow follow_plan(const MatchInfoOut &info, double t0, const ball_model **model);
  // What came of follow_plan's begin or update (heard at mono s t0): the
  // line for the log, if any.
  std::string followed(const MatchInfoOut &info, const ParticipantId &from, Follow plan, bool ok,
                       const std::string &err, double t0);
  // The loop yielded a match to `from` at mono s t0; following: it follows
  // the match now (every server does, a standby or not: it takes it back
  // when that owner is lost or goes silent and no standby is there).
  void yielded(uint32_t match_id, const MatchInfoOut &to, const ParticipantId &from, bool following, double t0);
  // A segment of another server's match (ours: this server steps it: ignored).
  void hear_segment(const SegmentOut &segment, const ParticipantId &from, bool ours);
  // Another server's writers lost their liveliness at mono s t0: the line
  // for the log when it was a peer heard of (it is forgotten).
  std::string server_lost(const ParticipantId &who, double t0);

  // ---- take-overs ----
  // The followed matches whose owner was lost a grace ago (its writers'
  // liveliness, or kOwnerSilent without a MatchInfo of it), whose successor
  // (placement.h; when no standby lives, a server that yielded the match
  // takes it back) this server is, and whose players it hears
  // (hears_players(id): the side with the players decides), at mono s t0.
  std::vector<uint32_t> due_takeovers(double t0, const std::function<bool(uint32_t)> &hears_players);
  // The highest term this server would take a followed match over at whose
  // owner is lost at mono s t0 and whose successor it is (0: none), grace or
  // no grace: raised to it before its first sample, the writers' strength
  // reaches the readers by discovery during the grace.
  uint32_t coming_term(double t0) const;
  // The followed matches whose owner was lost a grace ago with no slot
  // held in its newest MatchInfo: nobody plays them, no take-over; they are
  // followed no more (the loop removes them from its host).
  std::vector<uint32_t> let_go_unheld(double t0);
  const Followed *followed(uint32_t match_id) const;
  // The take-over of match_id was done (true) or failed (false): it is
  // followed no more.
  void taken_over(uint32_t match_id, bool ok);

  // ---- claims and creates ----
  // A claimant's configured matches, candidates until the claim rule gives them to it.
  void set_candidates(std::vector<MatchConfig> candidates) { candidates_ = std::move(candidates); }
  // The candidates to claim now (mono s t0): not placed (placed(id): this
  // server has it), no owner heard of or one lost orphan_wait ago, and the
  // claim rule gives them to this server.
  std::vector<MatchConfig> claims_due(double t0, const std::function<bool(uint32_t)> &placed) const;
  void claimed();  // a claim (or a claimant's CREATE) went through: one unit of room used
  // A CREATE of a match the host does not have: this server's to create
  // (the claim rule; a standby alone never), else counted as left elsewhere.
  bool may_create(uint32_t match_id);

  // ---- what it knows ----
  ServerView own_view() const;
  std::vector<ServerView> views() const;  // the live servers heard of, and this one
  const std::map<uint32_t, Followed> &following() const { return followed_; }
  double next_wake(double t0) const;  // mono s a standby wakes by (+Inf: nothing followed)
  const ClusterStats &stats() const { return stats_; }
  const ClusterSettings &settings() const { return settings_; }
  size_t peers_known() const { return peers_.size(); }    // ServerStatus writers kept (at most kMaxPeers)
  size_t owners_known() const { return owners_.size(); }  // owners kept of a claimant's configured matches

 private:
  bool succeeds(const Followed &f, std::vector<ServerView> *servers) const;  // (views() once, when first asked)
  struct Peer {
    StatusOut status;  // its newest ServerStatus
    bool alive = true;
    uint64_t heard = 0;  // its place among the statuses heard (the oldest goes when the map is full)
  };
  uint64_t statuses_heard_ = 0;
  ClusterSettings settings_;
  ClusterStats stats_;
  std::map<ParticipantId, Peer> peers_;
  std::map<uint32_t, Followed> followed_;
  // the newest MatchModel of other servers' matches (a standby's), at most kMaxPeers matches
  std::map<uint32_t, MatchModelOut> other_models_;
  // mono s a followed match's MatchInfo first came without its MatchModel
  std::map<uint32_t, double> model_waits_;
  // a claimant's configured match -> its owner heard of, mono s it was lost (-1: alive)
  std::map<uint32_t, std::pair<ParticipantId, double>> owners_;
  std::vector<MatchConfig> candidates_;  // a claimant's configured matches not (yet) its own
  std::map<uint32_t, uint32_t> terms_;   // the highest term heard of each match, at most kMaxPeers matches
  // MatchInfos whose writer's ServerStatus was not heard: the newest of each match, at most kMaxPeers
  std::map<uint32_t, std::pair<MatchInfoOut, ParticipantId>> unknown_;
  bool knows(const ParticipantId &from) const { return peers_.count(from) > 0; }
  uint32_t claimed_ = 0;
};

}  // namespace ballsrv
