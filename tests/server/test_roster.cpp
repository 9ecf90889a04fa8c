// A match's slots on their own (roster.h, docs/protocol.md "Racket
// samples" and `lost`): the holders' streams count every seq that never
// arrived exactly once, JOIN finds the slot the protocol names, and a
// sample's checks give the drop reason of the first check it fails.
#include <algorithm>
#include <random>
#include <set>

#include "check.hpp"
#include "game.h"
#include "roster.h"

using namespace test;
using check::note;

namespace {

const ParticipantId kA = participant(1), kB = participant(2);

// A roster of two slots, `a` holding slot 0.
Roster two_slots() {
  Roster r;
  r.init(2);
  CHECK(r.join(0, kA, 0.0, 1.0) == Roster::Join::taken);
  return r;
}

}  // namespace

// 3,000 random streams: seqs sent in order with random losses, delivered
// with random reordering within the late window (16 behind), duplicates,
// then the stream ended: the lost count is the number of seqs never
// delivered, whatever the order (each counted once: at the window's edge
// or at the end).
TEST(every_seq_that_never_arrived_is_counted_lost_once) {
  std::mt19937_64 g(20261206);
  uint64_t total_lost = 0;
  for (int n = 0; n < 3000; ++n) {
    Roster r = two_slots();
    uint32_t first = static_cast<uint32_t>(g());  // (wraps around 2^32 in some runs)
    int count = 2 + static_cast<int>(g() % 400);
    double loss = std::uniform_real_distribution<double>(0.0, 0.5)(g);
    std::vector<uint32_t> sent;
    sent.push_back(first);  // the first and the last arrive: the stream's ends
    for (int k = 1; k + 1 < count; ++k)
      if (std::uniform_real_distribution<double>(0.0, 1.0)(g) >= loss) sent.push_back(first + static_cast<uint32_t>(k));
    sent.push_back(first + static_cast<uint32_t>(count - 1));
    // reordered within blocks spanning at most 8 seqs (a sample arrives at
    // most 7 behind the newest: within the late window), the first first
    for (size_t k = 1; k < sent.size();) {
      size_t end = k;
      while (end < sent.size() && sent[end] - sent[k] < 8) ++end;
      if (g() % 2 == 0) std::shuffle(sent.begin() + static_cast<long>(k), sent.begin() + static_cast<long>(end), g);
      k = end;
    }
    uint64_t lost = 0;
    std::set<uint32_t> delivered;
    for (uint32_t seq : sent) {
      double capture = (seq - first) / 30.0;  // captured 30 a second
      lost += r.arrived(0, seq, capture);
      delivered.insert(seq);
      if (g() % 10 == 0) lost += r.arrived(0, seq, capture);  // a duplicate: nothing
    }
    r.end_streams();
    lost += r.take_lost();
    // reordering can put the newest before an older one: the seqs up to the newest delivered
    uint32_t newest = first;
    for (uint32_t seq : sent)
      if (static_cast<int32_t>(seq - newest) > 0) newest = seq;
    uint64_t never = static_cast<uint64_t>(newest - first) + 1 - delivered.size();
    CHECK_MSG(lost == never, "stream %d: %llu counted lost, %llu never arrived", n, (unsigned long long)lost,
              (unsigned long long)never);
    total_lost += lost;
    CHECK_EQ(r.take_lost(), 0u);
  }
  note("%llu seqs lost over 3000 random streams, each counted once", (unsigned long long)total_lost);
  CHECK(total_lost > 10000u);
}

// JOIN of any slot: the holder's own first, then a free one, then one
// whose holder vanished; a held slot whose holder is there is refused.
TEST(join_finds_the_slot_the_protocol_names) {
  Roster r = two_slots();
  CHECK_EQ(r.free_slot(kA, 0.5, 1.0), 0);  // its own
  CHECK_EQ(r.free_slot(kB, 0.5, 1.0), 1);  // a free one
  CHECK(r.join(1, kB, 0.5, 1.0) == Roster::Join::taken);
  ParticipantId c = participant(3);
  CHECK_EQ(r.free_slot(c, 0.5, 1.0), -1);  // no room
  CHECK(r.join(0, c, 0.5, 1.0) == Roster::Join::refused);
  CHECK_EQ(r.free_slot(c, 1.2, 1.0), 0);  // a's joined at 0, not seen since: vanished
  r.participant_lost(kB);
  CHECK_EQ(r.free_slot(c, 0.6, 1.0), 1);  // DDS saw b go
  CHECK(r.join(0, kA, 0.6, 1.0) == Roster::Join::again);
  CHECK(r.holds(kA) && r.holds(kB) && !r.holds(c));
  CHECK(!r.leave(0, kB));
  CHECK(r.leave(1, kB));
  CHECK(!r.holds(kB) && r.held());
  int missing = -2;
  r.update_presence(0.7, 1.0, &missing);
  CHECK(!r.all_present() && missing == -1);  // slot 1 free: not all there, none missing
}

// A standby hears a match's players when no slot is held or a holder was
// heard within the timeout (joining counts as heard, as for presence).
TEST(the_players_are_heard_within_the_timeout) {
  Roster none = two_slots();
  CHECK(none.leave(0, kA));
  CHECK(!none.held() && none.hears_players(100.0, 1.0));  // nobody to hear: nothing to decide
  Roster r = two_slots();  // a holds slot 0 since 0 s
  CHECK(r.hears_players(1.0, 1.0) && !r.hears_players(1.0 + 1e-9, 1.0));
  CHECK(r.join(1, kB, 5.0, 1.0) == Roster::Join::taken);
  CHECK(r.hears_players(5.5, 1.0) && !r.hears_players(6.5, 1.0));  // b heard at 5 s, a long gone
}

// A sample's checks, one failing at a time: the first failing check names
// the drop; one that passes them all is `accepted`, and its seq is then
// the newest (a repeat is a duplicate).
TEST(a_samples_first_failing_check_names_the_drop) {
  Game game;  // (its court and config)
  const Court &court = game.match.court();
  const MatchConfig &config = game.match.config();
  Roster r = two_slots();
  RacketSampleIn s;
  s.from = kA;
  s.player = 0;
  s.seq = 10;
  s.capture_time = 1.0;
  s.center = parked_center(court, 0);
  s.center.y = court.floor + 1.0;
  s.center.x = court.x_lo + 1.0;
  s.normal = ball_v3(1.0, 0.0, 0.0);
  uint64_t lost = 0;
  auto with = [&](auto change) {
    RacketSampleIn t = s;
    change(t);
    Roster copy = r;
    return copy.check(t, 0.1, 1.0, config, court, &lost);
  };
  CHECK(with([](RacketSampleIn &t) { t.player = 2; }) == SampleResult::bad_slot);
  CHECK(with([](RacketSampleIn &t) { t.player = 1; }) == SampleResult::not_joined);
  CHECK(with([&](RacketSampleIn &t) { t.from = kB; }) == SampleResult::not_owner);
  CHECK(with([](RacketSampleIn &t) { t.center.x = NAN; }) == SampleResult::nonfinite);
  CHECK(with([](RacketSampleIn &t) { t.normal = ball_v3(0, 0, 0); }) == SampleResult::zero_normal);
  CHECK(with([&](RacketSampleIn &t) { t.center.x = court.x_hi + 5.0; }) == SampleResult::out_of_range);
  CHECK(with([&](RacketSampleIn &t) { t.capture_time = 1.0 + config.max_sample_lead + 0.1; }) ==
        SampleResult::out_of_range);
  CHECK(with([&](RacketSampleIn &t) { t.capture_time = 1.0 - config.max_sample_age - 0.1; }) == SampleResult::stale);
  CHECK(r.check(s, 0.1, 1.0, config, court, &lost) == SampleResult::accepted);
  r.passed(0, s);
  CHECK(r.check(s, 0.2, 1.0, config, court, &lost) == SampleResult::duplicate);
  RacketSampleIn fast = s;
  fast.seq = 11;
  fast.capture_time = 1.01;
  fast.center.z += config.max_racket_speed * 0.01 + 0.5;
  CHECK(r.check(fast, 0.2, 1.0, config, court, &lost) == SampleResult::too_fast);
  RacketSampleIn back = s;
  back.seq = 9;
  CHECK(r.check(back, 0.2, 1.0, config, court, &lost) == SampleResult::out_of_order);
  CHECK_EQ(lost, 0u);
  CHECK(r[0].last_seen == 0.2);  // well formed and the holder's: it is there
}

CHECK_MAIN
