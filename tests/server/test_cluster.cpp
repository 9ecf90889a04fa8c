// Failover's room on its own (cluster.h, docs/protocol.md "Several servers
// on one domain"): what a Cluster decides from what it hears, with the time
// given as numbers: no loop, port or clock fake. The owner's MatchInfo and
// segments come from a match played offline (game.h).
#include <algorithm>
#include <cmath>
#include <random>
#include <cstring>
#include <set>

#include "check.hpp"
#include "cluster.h"
#include "game.h"

using namespace test;
using check::note;

namespace {

const ParticipantId kOwner = participant(77);
constexpr double kNow = 1.7e9;  // server s: the owner's and this server's realtime clock
constexpr double kHeardAt = 95.0;  // mono s the owner's newest MatchInfo was heard (its silence counts from there)

ClusterSettings standby_settings(uint32_t id = 2, uint32_t strength = 10) {
  ClusterSettings s;
  s.server_id = id;
  s.standby = true;
  s.strength = strength;
  return s;
}

StatusOut status_of(uint32_t id, uint32_t strength, bool standby, uint32_t claim_room = 0) {
  StatusOut st;
  st.server_id = id;
  st.strength = strength;
  st.standby = standby;
  st.claim_room = claim_room;
  return st;
}

// The owner's match after `seconds` of play, its MatchInfo as server 1 wrote it at kNow.
struct Owner {
  Game game = played(3.0);
  MatchInfoOut info() const {
    MatchInfoOut i = game.match.info();
    i.server_id = 1;
    i.server_time = kNow;
    i.revision = 9;
    return i;
  }
};

// A standby that heard the owner (server 1, strength 20) and follows its match.
Cluster following_standby(const Owner &o, ClusterSettings s = standby_settings()) {
  Cluster c(s);
  c.hear_status(status_of(1, 20, false), kOwner);
  MatchInfoOut i = o.info();
  CHECK(c.hear_info(i, kOwner, false, false, 0, kNow) == Cluster::Heard::noted);
  const ball_model *model = nullptr;
  Cluster::Follow plan = c.follow_plan(i, 0.0, &model);
  CHECK(plan == Cluster::Follow::none);  // the MatchModel may still come
  plan = c.follow_plan(i, kModelWait, &model);
  CHECK(plan == Cluster::Follow::begin && model == nullptr);
  CHECK(c.followed(i, kOwner, plan, true, "", kHeardAt).empty());
  for (const SegmentOut &seg : o.game.segments) c.hear_segment(seg, kOwner, false);
  return c;
}

}  // namespace

// every match's players heard (a standby's take-over rule)
const auto kHeard = [](uint32_t) { return true; };

// A standby follows what a live owner writes, takes nothing over while the
// owner lives, and takes the match over a grace after the owner's writers
// are lost (and not before); then it follows it no more.
TEST(a_standby_takes_over_a_grace_after_the_owner_is_lost) {
  Owner o;
  Cluster c = following_standby(o);
  CHECK_EQ(c.following().size(), 1u);
  const Followed *f = c.followed(7);
  CHECK(f && f->owner == kOwner && f->info.revision == 9u);
  CHECK_EQ(f->segments.size(), std::min(o.game.segments.size(), kFollowedSegments));
  CHECK(c.due_takeovers(100.0, kHeard).empty());
  CHECK_EQ(c.next_wake(100.0), 100.0 + kFollowWake);
  CHECK(c.server_lost(kOwner, 100.0).find("server 1") != std::string::npos);
  CHECK_EQ(c.peers_known(), 0u);  // forgotten
  const double grace = c.settings().takeover_grace;
  CHECK_EQ(c.next_wake(100.0), 100.0 + kFollowWake);
  CHECK_EQ(c.next_wake(100.0 + grace), 100.0 + grace);
  CHECK(c.due_takeovers(100.0 + grace - 1e-9, kHeard).empty());
  std::vector<uint32_t> due = c.due_takeovers(100.0 + grace, kHeard);
  CHECK(due.size() == 1u && due[0] == 7u);
  c.taken_over(7, true);
  CHECK_EQ(c.stats().takeovers, 1u);
  CHECK(c.following().empty() && c.due_takeovers(200.0, kHeard).empty());
}

// A stranger's MatchInfos (no ServerStatus of its participant) are no
// server's: 70 made-up matches are neither followed nor counted owners,
// and only the newest of each is held back (bounded). A real owner whose
// MatchInfo comes before its ServerStatus is heard again once the status
// comes. A followed match whose owner dies with no slot held is let go,
// not taken over; one with a slot held is taken over.
TEST(a_standby_adopts_only_held_matches_of_servers_it_heard) {
  Owner o;
  Cluster c(standby_settings());
  const ParticipantId stranger = participant(66);
  for (uint32_t k = 0; k < 70; ++k) {
    MatchInfoOut fake = o.info();
    fake.match_id = 100 + k;
    fake.server_id = 7;
    CHECK(c.hear_info(fake, stranger, false, false, 0, kNow) == Cluster::Heard::unknown);
  }
  CHECK_EQ(c.stats().unknown_writers, 70u);
  CHECK(c.following().empty() && c.known_infos().empty());
  CHECK_EQ(c.heard_term(100), 0u);
  // the owner's MatchInfo first, its status after
  CHECK(c.hear_info(o.info(), kOwner, false, false, 0, kNow) == Cluster::Heard::unknown);
  c.hear_status(status_of(1, 20, false), kOwner);
  auto known = c.known_infos();
  CHECK(known.size() == 1u && known[0].first.match_id == 7u && known[0].second == kOwner);
  CHECK(c.known_infos().empty());  // (given once)
  // held and unheld
  Cluster held = following_standby(o);
  Cluster unheld = following_standby(o);
  MatchInfoOut left = o.info();
  left.revision++;
  for (auto &slot : left.slots) slot.held = false;
  const ball_model *model = nullptr;
  CHECK(unheld.hear_info(left, kOwner, false, false, 0, kNow) == Cluster::Heard::noted);
  Cluster::Follow plan = unheld.follow_plan(left, 1.0, &model);
  CHECK(plan == Cluster::Follow::update);
  unheld.followed(left, kOwner, plan, true, "", kHeardAt);
  const double grace = held.settings().takeover_grace;
  for (Cluster *x : {&held, &unheld}) x->server_lost(kOwner, 100.0);
  CHECK(held.let_go_unheld(100.0 + grace).empty());
  CHECK_EQ(held.due_takeovers(100.0 + grace, kHeard).size(), 1u);
  CHECK(unheld.let_go_unheld(100.0 + grace - 1e-9).empty());
  std::vector<uint32_t> gone = unheld.let_go_unheld(100.0 + grace);
  CHECK(gone.size() == 1u && gone[0] == 7u);
  CHECK(unheld.due_takeovers(100.0 + grace, kHeard).empty());
  CHECK_EQ(unheld.stats().unheld_let_go, 1u);
}

// The side with the players decides: a standby that hears none of a lost
// owner's players takes nothing over (the owner may play on with them,
// cut off from this server alone), counts it once, and takes the match
// over once one is heard.
TEST(a_standby_takes_over_only_a_match_whose_players_it_hears) {
  Owner o;
  Cluster c = following_standby(o);
  c.server_lost(kOwner, 100.0);
  const double due = 100.0 + c.settings().takeover_grace;
  bool heard = false;
  auto hears = [&heard](uint32_t id) { return heard && id == 7u; };
  for (int k = 0; k < 5; ++k) CHECK(c.due_takeovers(due + k, hears).empty());
  CHECK_EQ(c.stats().takeovers_waiting, 1u);
  CHECK_EQ(c.following().size(), 1u);  // still followed
  heard = true;  // heard again: the owner may be back with them (a healed cut): it settles first
  CHECK(c.due_takeovers(due + 5.0, hears).empty());
  CHECK(c.due_takeovers(due + 5.0 + kPlayersSettle - 1e-9, hears).empty());
  std::vector<uint32_t> now_due = c.due_takeovers(due + 5.0 + kPlayersSettle, hears);
  CHECK(now_due.size() == 1u && now_due[0] == 7u);
  CHECK_EQ(c.stats().takeovers_waiting, 1u);
  // and an owner back within the settling takes the take-over off
  Cluster d = following_standby(o);
  d.server_lost(kOwner, 100.0);
  heard = false;
  CHECK(d.due_takeovers(due, hears).empty());
  heard = true;
  CHECK(d.due_takeovers(due + 1.0, hears).empty());
  d.followed(o.info(), kOwner, Cluster::Follow::update, true, "", due + 1.0);  // its MatchInfo: alive
  CHECK(d.due_takeovers(due + 1.0 + kPlayersSettle, hears).empty());
}

// Of two standbys, only the successor (the stronger) takes a lost owner's
// match over; the weaker waits while the stronger lives.
TEST(only_the_successor_takes_over) {
  Owner o;
  Cluster weak = following_standby(o, standby_settings(2, 10));
  Cluster strong = following_standby(o, standby_settings(3, 15));
  weak.hear_status(status_of(3, 15, true), participant(33));
  strong.hear_status(status_of(2, 10, true), participant(22));
  weak.server_lost(kOwner, 10.0);
  strong.server_lost(kOwner, 10.0);
  CHECK(weak.due_takeovers(20.0, kHeard).empty());
  CHECK_EQ(strong.due_takeovers(20.0, kHeard).size(), 1u);
  weak.server_lost(participant(33), 20.0);  // then the stronger goes too
  CHECK_EQ(weak.due_takeovers(20.0, kHeard).size(), 1u);
}

// What a standby refuses to take as another server's: a MatchInfo far from
// its clock, or one no server writes (a NaN sim time), counted; a segment
// of a participant that is not the owner is not kept.
TEST(a_standby_refuses_what_no_server_writes) {
  Owner o;
  Cluster c(standby_settings());
  MatchInfoOut far = o.info();
  far.server_time = kNow + kMaxClockGap + 1.0;
  CHECK(c.hear_info(far, kOwner, false, false, 0, kNow) == Cluster::Heard::refused);
  MatchInfoOut nan = o.info();
  nan.sim_time = NAN;
  CHECK(c.hear_info(nan, kOwner, false, false, 0, kNow) == Cluster::Heard::refused);
  CHECK_EQ(c.stats().others_refused, 2u);
  Cluster f = following_standby(o);
  size_t kept = f.followed(7)->segments.size();
  SegmentOut stranger = o.game.segments.back();
  stranger.seq += 100;
  f.hear_segment(stranger, participant(5), false);
  CHECK_EQ(f.followed(7)->segments.size(), kept);
  f.hear_segment(stranger, kOwner, true);  // one of ours: ignored
  CHECK_EQ(f.followed(7)->segments.size(), kept);
}

// Of two servers stepping one match, the newer term owns it
// (docs/protocol.md, "Terms"): another's higher term, or the same term from
// a lower id, is a conflict (this one yields); an older term is stale, and
// this server raises its writers above the sender's. The highest term heard
// of each match is kept for the next start or take-over.
TEST(terms_decide_two_owners) {
  Owner o;
  Cluster c(standby_settings(2, 10));  // server 2
  c.hear_status(status_of(1, 120, false), kOwner);
  MatchInfoOut i = o.info();  // server 1's
  CHECK_EQ(c.heard_term(7), 0u);
  i.term = 1;
  CHECK(c.hear_info(i, kOwner, true, true, 2, kNow) == Cluster::Heard::stale);
  CHECK_EQ(c.stats().stale_terms, 1u);
  CHECK_EQ(c.stronger_than(kOwner, 210), 210u);  // already above server 1's 120
  CHECK_EQ(c.stronger_than(kOwner, 100), 121u);
  CHECK_EQ(c.stronger_than(participant(99), 100), 100u + kTermStrength);  // unknown: a term's worth more
  i.term = 3;
  CHECK(c.hear_info(i, kOwner, true, true, 2, kNow) == Cluster::Heard::conflict);
  i.term = 2;  // the same term: the lower id keeps it
  CHECK(c.hear_info(i, kOwner, true, true, 2, kNow) == Cluster::Heard::conflict);
  i.server_id = 5;
  CHECK(c.hear_info(i, kOwner, true, true, 2, kNow) == Cluster::Heard::stale);
  CHECK_EQ(c.heard_term(7), 3u);
}

// A term is the next round and the server id's low bits: two servers
// that start one match in ignorance of each other give it two terms, each
// above every term heard; the writers' strength grows with the term and
// stays below 2^32.
TEST(terms_are_rounds_and_ids) {
  CHECK_EQ(next_term(0, 1), 257u);
  CHECK_EQ(next_term(0, 2), 258u);
  CHECK_EQ(next_term(258, 1), 513u);
  CHECK_EQ(next_term(257, 0x1FF), 767u);  // (the id's low 8 bits)
  std::mt19937_64 rng(38);
  for (int k = 0; k < 10000; ++k) {
    uint32_t heard = static_cast<uint32_t>(rng() % 0xFFFF0000u), a = static_cast<uint32_t>(rng()),
             b = static_cast<uint32_t>(rng());
    CHECK(next_term(heard, a) > heard);
    if ((a & 0xFF) != (b & 0xFF)) CHECK(next_term(heard, a) != next_term(heard, b));
    CHECK(term_strength(20, next_term(heard, a)) >= term_strength(10, heard));
  }
  CHECK_EQ(term_strength(20, 0xFFFFFFFFu), 0xFFFFFFFFu);
}

// A standby follows nothing of an older owner than the one it follows
// while that one lives: a primary back at its old term beside the server
// that took its match over; once the newer one is lost, it follows again.
TEST(a_standby_follows_no_older_owner) {
  Owner o;
  Cluster c(standby_settings(3, 10));  // server 3
  c.hear_status(status_of(2, 20, true), participant(2));
  MatchInfoOut newer = o.info();
  newer.server_id = 2;
  newer.term = 2;
  CHECK(c.hear_info(newer, participant(2), true, false, 0, kNow) == Cluster::Heard::noted);
  c.yielded(7, newer, participant(2), true, 0.0);  // (followed from then on)
  const ball_model *model = nullptr;
  MatchInfoOut older = o.info();  // server 1's, term 1
  older.term = 1;
  CHECK(c.follow_plan(older, 0.0, &model) == Cluster::Follow::none);
  CHECK_EQ(c.stats().stale_terms, 1u);
  newer.revision++;
  CHECK(c.follow_plan(newer, 0.0, &model) == Cluster::Follow::update);
  c.server_lost(participant(2), 1.0);
  CHECK(c.follow_plan(older, 1.0, &model) == Cluster::Follow::update);
}

// A MatchInfo of a match this server steps is a conflict: it yields, and
// a standby follows the match from then on.
TEST(a_conflict_yields_and_a_standby_follows) {
  Owner o;
  Cluster c(standby_settings());
  c.hear_status(status_of(1, 20, false), kOwner);
  MatchInfoOut i = o.info();
  CHECK(c.hear_info(i, kOwner, true, true, 0, kNow) == Cluster::Heard::conflict);
  CHECK_EQ(c.stats().conflicts, 1u);
  c.yielded(7, i, kOwner, true, 0.0);
  CHECK_EQ(c.stats().yields, 1u);
  const ball_model *model = nullptr;
  CHECK(c.follow_plan(i, 0.0, &model) == Cluster::Follow::update);
  CHECK(c.followed(7) && c.followed(7)->owner == kOwner);
}

// A server that yielded its match follows it, standby or not, and takes it
// back when no standby is there: a grace after the owner it yielded to is
// lost, or kOwnerSilent after that owner's newest MatchInfo while it lives
// and writes none (a stranger with a newer term that went quiet). A live
// standby is the successor: the server that yielded waits. A standby's
// followed match goes by the same silence.
TEST(a_server_takes_back_a_match_it_yielded) {
  Owner o;
  const ParticipantId stranger = participant(66);
  auto yielded_to_stranger = [&](bool standby_heard) {
    ClusterSettings s;
    s.server_id = 1;  // a primary: no standby
    Cluster c(s);
    c.hear_status(status_of(7, 30, false), stranger);
    if (standby_heard) c.hear_status(status_of(3, 10, true), participant(33));
    MatchInfoOut newer = o.info();
    newer.server_id = 7;
    newer.term = next_term(257, 7);
    CHECK(c.hear_info(newer, stranger, true, true, 257, kNow) == Cluster::Heard::conflict);
    c.yielded(7, newer, stranger, true, 50.0);
    const ball_model *model = nullptr;
    newer.revision++;
    CHECK(c.follow_plan(newer, 54.0, &model) == Cluster::Follow::update);  // it follows what it yielded
    c.followed(newer, stranger, Cluster::Follow::update, true, "", 54.0);
    return c;
  };
  const double grace = ClusterSettings{}.takeover_grace;
  // silent: its newest MatchInfo at 54 s
  Cluster quiet = yielded_to_stranger(false);
  CHECK(quiet.due_takeovers(54.0 + kOwnerSilent + grace - 1e-9, kHeard).empty());
  CHECK_EQ(quiet.next_wake(60.0), 60.0 + kFollowWake);
  std::vector<uint32_t> back = quiet.due_takeovers(54.0 + kOwnerSilent + grace, kHeard);
  CHECK(back.size() == 1u && back[0] == 7u);
  // lost: its writers' liveliness at 56 s
  Cluster gone = yielded_to_stranger(false);
  CHECK_EQ(gone.coming_term(56.0), 0u);  // (its owner lives)
  gone.server_lost(stranger, 56.0);
  // the term it takes the match back at, from the loss on, the grace not out: its writers'
  // strength is raised to it before its first sample
  CHECK_EQ(gone.coming_term(56.0), next_term(next_term(257, 7), 1));
  CHECK(gone.due_takeovers(56.0 + grace - 1e-9, kHeard).empty());
  CHECK_EQ(gone.due_takeovers(56.0 + grace, kHeard).size(), 1u);
  // a live standby takes it over, not the server that yielded
  Cluster beside = yielded_to_stranger(true);
  beside.server_lost(stranger, 56.0);
  CHECK(beside.due_takeovers(70.0, kHeard).empty());
  CHECK_EQ(beside.coming_term(70.0), 0u);
  CHECK_EQ(beside.following().size(), 1u);
  // a standby's followed match: silent kOwnerSilent while its owner lives
  Cluster standby = following_standby(o);
  CHECK(standby.due_takeovers(kHeardAt + kOwnerSilent + grace - 1e-9, kHeard).empty());
  CHECK_EQ(standby.due_takeovers(kHeardAt + kOwnerSilent + grace, kHeard).size(), 1u);
  CHECK_EQ(standby.peers_known(), 1u);  // (its owner still lives)
}

// A standby follows at once from a MatchModel that fits the info's hash;
// a failed follow is counted and leaves nothing followed.
TEST(a_standby_follows_from_the_wire_model) {
  Owner o;
  Cluster c(standby_settings());
  MatchInfoOut i = o.info();
  MatchModelOut m;
  m.match_id = 7;
  m.server_id = 1;
  m.model = o.game.match.model();
  m.model_hash = ball_model_hash(&m.model);
  i.model_hash = m.model_hash;
  c.hear_model(m);
  const ball_model *model = nullptr;
  CHECK(c.follow_plan(i, 0.0, &model) == Cluster::Follow::begin);
  CHECK(model != nullptr && ball_model_hash(model) == i.model_hash);
  std::string line = c.followed(i, kOwner, Cluster::Follow::begin, false, "no scene", 0.0);
  CHECK(line.find("cannot follow match 7") != std::string::npos);
  CHECK_EQ(c.stats().follow_failures, 1u);
  CHECK(c.following().empty());
}

// The restore point: a playing match's sim clock mapped to the frame before
// the standby's first, never before the owner's newest serve or hit, and
// the segment in effect there one the owner has stepped through.
TEST(the_restore_point_maps_the_owners_clock) {
  Owner o;
  Cluster c = following_standby(o);
  const Followed *f = c.followed(7);
  const double frame = 1.0 / 60.0;
  std::mt19937_64 g(5);
  for (int n = 0; n < 200; ++n) {
    double first_real = kNow + std::uniform_real_distribution<double>(0.0, 2.0)(g);
    RestorePoint p = restore_point(*f, first_real, frame);
    double mapped = f->info.sim_time + (first_real - frame - kNow) * f->info.settings.time_base;
    CHECK(p.target >= mapped - 1e-12);
    for (const auto &kv : f->segments) {
      if (kv.second.cause == Cause::serve || kv.second.cause == Cause::racket) CHECK(p.target >= kv.second.segment.t0);
      CHECK(p.newest_seq >= kv.first);
    }
    CHECK(p.has_segment);
    CHECK(p.segment.segment.t0 <= p.target);
    CHECK(p.segment.seq >= f->info.segment_seq);
  }
}

// A claimant claims a configured match only once its owner is gone
// orphan_wait, and claimants that heard each other split the unowned
// matches among them: over random domains, every match claimed once, by a
// claimant with room, and none over its room.
TEST(claimants_split_the_matches_each_claims_once) {
  std::mt19937_64 g(20261206);
  size_t claimed = 0;
  for (int n = 0; n < 300; ++n) {
    int k = 1 + static_cast<int>(g() % 4);
    std::vector<MatchConfig> configs;
    for (uint32_t id = 0; id < 1 + g() % 30; ++id) {
      MatchConfig m = default_config();
      m.id = id;
      configs.push_back(m);
    }
    std::vector<ClusterSettings> settings;
    for (int j = 0; j < k; ++j) {
      ClusterSettings s;
      s.server_id = 10 + static_cast<uint32_t>(j);
      s.claim = static_cast<uint32_t>(g() % 12);
      settings.push_back(s);
    }
    std::map<uint32_t, int> by_match;
    uint64_t room = 0;
    for (int j = 0; j < k; ++j) {
      Cluster c(settings[static_cast<size_t>(j)]);
      for (int other = 0; other < k; ++other)
        if (other != j)
          c.hear_status(status_of(settings[static_cast<size_t>(other)].server_id, 20, false,
                                  settings[static_cast<size_t>(other)].claim),
                        participant(static_cast<uint8_t>(other)));
      c.set_candidates(configs);
      std::vector<MatchConfig> mine = c.claims_due(0.0, [](uint32_t) { return false; });
      CHECK(mine.size() <= settings[static_cast<size_t>(j)].claim);
      for (const auto &m : mine) by_match[m.id]++;
      room += settings[static_cast<size_t>(j)].claim;
    }
    for (const auto &kv : by_match) CHECK_EQ(kv.second, 1);
    CHECK_EQ(by_match.size(), std::min<size_t>(configs.size(), room));
    claimed += by_match.size();
  }
  note("%zu matches claimed over 300 random domains, each once", claimed);
  CHECK(claimed > 1000);
  // an owner heard of holds its match until it is gone orphan_wait
  Owner o;
  ClusterSettings s;
  s.server_id = 3;
  s.claim = 5;
  Cluster c(s);
  MatchConfig m = default_config();
  c.set_candidates({m});
  c.hear_status(status_of(1, 20, false), kOwner);
  CHECK(c.hear_info(o.info(), kOwner, false, false, 0, kNow) == Cluster::Heard::noted);
  CHECK_EQ(c.owners_known(), 1u);
  auto none = [](uint32_t) { return false; };
  CHECK(c.claims_due(0.0, none).empty());
  c.server_lost(kOwner, 10.0);
  CHECK(c.claims_due(10.0 + s.orphan_wait - 0.01, none).empty());
  CHECK_EQ(c.claims_due(10.0 + s.orphan_wait, none).size(), 1u);
  CHECK(c.claims_due(10.0 + s.orphan_wait, [](uint32_t) { return true; }).empty());  // placed already
}

// CREATE: a server that claims nothing creates, a standby alone never, a
// claimant only what the claim rule gives it and within its room; every
// CREATE left elsewhere is counted.
TEST(creates_follow_the_claim_rule) {
  ClusterSettings plain;
  Cluster p(plain);
  CHECK(p.may_create(40));
  Cluster sb(standby_settings());
  CHECK(!sb.may_create(40));
  CHECK_EQ(sb.stats().creates_elsewhere, 1u);
  ClusterSettings s;
  s.server_id = 3;
  s.claim = 2;
  Cluster c(s);
  c.hear_status(status_of(4, 20, false, 100), participant(4));
  int mine = 0, asked = 0;
  for (uint32_t id = 100; id < 200; ++id) {
    asked++;
    std::map<uint32_t, uint32_t> rule = assign_claims({id}, c.views());
    bool ok = c.may_create(id);
    if (ok) {
      CHECK_EQ(rule[id], 3u);
      c.claimed();
      mine++;
    }
  }
  CHECK_EQ(mine, 2);  // its room
  CHECK_EQ(c.stats().creates_elsewhere, static_cast<uint64_t>(asked - mine));
  CHECK_EQ(c.own_view().claim_room, 0u);
}

// Strangers cannot grow what a Cluster keeps: at most kMaxPeers peers.
TEST(what_a_cluster_keeps_of_strangers_is_bounded) {
  Cluster c(standby_settings());
  for (uint32_t k = 0; k < kMaxPeers + 500; ++k) {
    ParticipantId who{};
    std::memcpy(who.data(), &k, sizeof k);
    c.hear_status(status_of(1000 + k, 20, false), who);
  }
  CHECK_EQ(c.peers_known(), kMaxPeers);
  CHECK_EQ(c.views().size(), kMaxPeers + 1);
}

CHECK_MAIN
