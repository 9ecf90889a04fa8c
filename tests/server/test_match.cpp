// The match without a network: serve, point rules, player slots, presence,
// pause and resume, control messages, sample validation, the host.
#include <random>
#include <cmath>
#include <set>

#include "ball/vec3.h"
#include "check.hpp"
#include "seeded.h"
#include "game.h"
#include "host.h"

using namespace test;

namespace {

const ParticipantId A = participant(1);
const ParticipantId B = participant(2);
const ParticipantId C = participant(3);

// a game with both slots joined and parked
Game two_players(const MatchConfig &config = default_config()) {
  Game g(config);
  g.join(0, A);
  g.join(1, B);
  return g;
}

// indices of the serves in g.events
std::vector<size_t> serves(const Game &g) {
  std::vector<size_t> out;
  for (size_t i = 0; i < g.events.size(); ++i)
    if (g.events[i].kind == EventKind::serve) out.push_back(i);
  return out;
}

}  // namespace

TEST(lob_velocity_lands_on_target) {
  ball_scene scene;
  ball_scene_default(&scene);
  // with drag: the first floor contact is where it was asked to be
  ball_vec3 from = ball_v3(3.0, 1.0, 5.0), target = ball_v3(20.0, 0.0, 7.0), v;
  CHECK_EQ(lob_velocity(scene.model, from, target, 4.0, &v), BALL_OK);
  CHECK_NEAR(v.y, 4.0, 0.0);
  ball_segment seg{};
  seg.p0 = from;
  seg.v0 = v;
  double t;
  ball_vec3 land;
  CHECK_EQ(ball_next_floor_contact(&scene.model, &seg, 0.0, &t, &land), BALL_OK);
  CHECK_NEAR(land.x, 20.0, 1e-9);
  CHECK_NEAR(land.z, 7.0, 1e-9);
  CHECK_EQ(lob_velocity(scene.model, from, from, 4.0, &v), BALL_ERANGE);
}

TEST(waits_for_its_players) {
  Game g;
  CHECK(g.ok);
  g.join(0, A);
  g.run(2.0);
  CHECK(g.match.state() == MatchState::waiting);
  CHECK_EQ(g.match.sim().time, 0.0);  // nothing moves
  CHECK_EQ(g.count(EventKind::serve), 0);
  g.join(1, B);
  g.run(0.1);
  CHECK(g.match.state() == MatchState::playing);
  CHECK_EQ(g.count(EventKind::serve), 1);
  CHECK_EQ(g.segments.front().cause, Cause::serve);
  CHECK_EQ(g.segments.front().seq, 1u);
}

TEST(serve_lands_in_then_double_bounce) {
  Game g = two_players();
  g.run(5.0);
  auto s = serves(g);
  CHECK(!s.empty());
  const EventOut &serve = g.events[s[0]];
  CHECK_EQ(serve.index, 0);
  CHECK_EQ(serve.side, 0);
  // nothing hits the parked rackets: serve, two bounces on side 1, the point to side 0
  const EventOut *b1 = g.first(EventKind::floor);
  CHECK(b1 != nullptr);
  CHECK_EQ(b1->side, 1);
  CHECK(g.match.court().inside(b1->point.x, b1->point.z));
  CHECK(b1->in_play);
  CHECK(b1->sound);
  CHECK_EQ(g.count(EventKind::net), 0);  // the serve clears the net
  const EventOut *p = g.first(EventKind::point);
  CHECK(p != nullptr);
  CHECK_EQ(p->side, 0);
  CHECK(p->reason == Reason::point_double_bounce);
  CHECK_EQ(p->score[0], 1);
  CHECK_EQ(p->score[1], 0);
  // every collision starts the segment it names
  for (const auto &e : g.events)
    if (e.kind == EventKind::floor) CHECK(e.segment_seq >= 2u);
  // the paper's sound event is a loud bounce's flag: none is written apart (docs/protocol.md, "Events")
  int loud = 0;
  for (const auto &e : g.events) loud += (e.kind == EventKind::floor && e.sound);
  CHECK(loud > 0);
  CHECK_EQ(g.count(EventKind::sound), 0);
}

TEST(serves_alternate_and_land_in) {
  Game g = two_players();
  g.run(60.0);
  auto s = serves(g);
  CHECK(s.size() >= 10);
  std::set<double> zs;
  for (size_t k = 0; k < s.size(); ++k) {
    const EventOut &serve = g.events[s[k]];
    CHECK_EQ(serve.side, static_cast<int>(k % 2));  // sides take turns
    zs.insert(serve.velocity_out.z);
    const EventOut *b = g.first(EventKind::floor, s[k]);
    if (!b) continue;
    CHECK_EQ(b->side, 1 - serve.side);
    CHECK(g.match.court().inside(b->point.x, b->point.z));
  }
  CHECK(zs.size() >= s.size() - 1);  // placed differently each time
  // nobody returns: every point goes to the server, by double bounce
  auto score = g.match.score();
  CHECK_EQ(score[0] + score[1], g.count(EventKind::point));
  for (const auto &e : g.events)
    if (e.kind == EventKind::point) CHECK(e.reason == Reason::point_double_bounce);
  CHECK_EQ(g.match.counters().hits, 0u);
}

TEST(rules_table) {
  // one line per rule of rules.h
  Rally r;
  r.start(0, 0.0);
  Call c = r.on_floor(0, true, false);
  CHECK(c.decided && c.winner == 1 && c.reason == Reason::point_own_side);
  r.start(0, 0.0);
  r.on_net();
  c = r.on_floor(0, true, false);
  CHECK(c.decided && c.winner == 1 && c.reason == Reason::point_net);
  r.start(0, 0.0);
  c = r.on_floor(1, false, false);
  CHECK(c.decided && c.winner == 1 && c.reason == Reason::point_out);
  r.start(0, 0.0);
  c = r.on_wall();
  CHECK(c.decided && c.winner == 1 && c.reason == Reason::point_out);
  r.start(0, 0.0);
  CHECK(!r.on_floor(1, true, false).decided);
  c = r.on_floor(1, true, false);
  CHECK(c.decided && c.winner == 0 && c.reason == Reason::point_double_bounce);
  r.start(0, 0.0);
  r.on_floor(1, true, false);
  c = r.on_wall();
  CHECK(c.decided && c.winner == 0 && c.reason == Reason::point_not_returned);
  r.start(0, 0.0);
  c = r.on_floor(1, true, true);  // bounced in and rolls
  CHECK(c.decided && c.winner == 0 && c.reason == Reason::point_not_returned);
  // a return resets the count: side 1 strikes after the bounce, its ball lands in on side 0
  r.start(0, 0.0);
  r.on_floor(1, true, false);
  r.on_racket(1);
  CHECK(!r.on_floor(0, true, false).decided);
  c = r.on_floor(0, true, false);
  CHECK(c.decided && c.winner == 1 && c.reason == Reason::point_double_bounce);
  // a volley is legal
  r.start(0, 0.0);
  r.on_racket(1);
  c = r.on_floor(1, true, false);
  CHECK(c.decided && c.winner == 0 && c.reason == Reason::point_own_side);
  r.start(0, 0.0);
  c = r.on_frame(false, 61.0, 60.0);
  CHECK(c.decided && c.winner == -1 && c.reason == Reason::point_let);
  r.start(0, 0.0);
  c = r.on_frame(true, 1.0, 60.0);
  CHECK(c.decided && c.winner == 1 && c.reason == Reason::point_out);
}

TEST(samples_dropped_by_reason_leave_the_ball_alone) {
  Game g = two_players();
  g.run(1.0);
  ball_sim before = g.match.sim();
  uint64_t hash = ball_sim_hash(&before);
  RacketSampleIn good = g.parked_sample(0);
  CHECK(g.match.on_sample(good, g.now) == SampleResult::accepted);
  hash = ball_sim_hash(&g.match.sim());
  auto with = [&](auto edit) {
    RacketSampleIn s = g.parked_sample(0);
    g.seq[0]--;  // the parked stream's next seq stays the same
    edit(s);
    return g.match.on_sample(s, g.now);
  };
  double nan = std::nan("");
  CHECK(with([&](RacketSampleIn &s) { s.player = 5; }) == SampleResult::bad_slot);
  CHECK(with([&](RacketSampleIn &s) { s.player = -1; }) == SampleResult::bad_slot);
  CHECK(with([&](RacketSampleIn &s) { s.from = C; }) == SampleResult::not_owner);
  CHECK(with([&](RacketSampleIn &s) { s.center.y = nan; }) == SampleResult::nonfinite);
  CHECK(with([&](RacketSampleIn &s) { s.normal.z = INFINITY; }) == SampleResult::nonfinite);
  CHECK(with([&](RacketSampleIn &s) { s.capture_time = nan; }) == SampleResult::nonfinite);
  CHECK(with([&](RacketSampleIn &s) { s.normal = ball_v3(0, 1e-9, 0); }) == SampleResult::zero_normal);
  CHECK(with([&](RacketSampleIn &s) { s.normal = ball_v3(0, 1e7, 0); }) == SampleResult::out_of_range);
  CHECK(with([&](RacketSampleIn &s) { s.center.y = 1e4; }) == SampleResult::out_of_range);
  CHECK(with([&](RacketSampleIn &s) { s.center.x = -1e3; }) == SampleResult::out_of_range);
  CHECK(with([&](RacketSampleIn &s) { s.capture_time += 10.0; }) == SampleResult::out_of_range);
  CHECK(g.match.on_sample(good, g.now) == SampleResult::duplicate);
  CHECK(with([&](RacketSampleIn &s) { s.seq = good.seq - 1; }) == SampleResult::out_of_order);
  CHECK(with([&](RacketSampleIn &s) { s.capture_time -= 30.0; }) == SampleResult::stale);
  // a new seq but not newer than the newest kept: libball says stale
  CHECK(with([&](RacketSampleIn &s) { s.capture_time = good.capture_time; s.center.x += 1.0; }) ==
        SampleResult::stale);
  // a new seq, identical pose and time: libball's duplicate (its normal is
  // compared after normalising, so twice the normal is the same pose)
  CHECK(with([&](RacketSampleIn &s) { s.capture_time = good.capture_time; s.center = good.center; }) ==
        SampleResult::duplicate);
  CHECK(with([&](RacketSampleIn &s) {
          s.capture_time = good.capture_time;
          s.center = good.center;
          s.normal = ball_v3_scale(good.normal, 2.0);
        }) == SampleResult::duplicate);
  // the same time and centre with another normal is not the same pose: not newer, so stale
  CHECK(with([&](RacketSampleIn &s) {
          s.capture_time = good.capture_time;
          s.center = good.center;
          s.normal = ball_v3(0, 0, 1);
        }) == SampleResult::stale);
  CHECK_EQ(ball_sim_hash(&g.match.sim()), hash);
  // a slot nobody holds
  Game h;
  h.join(0, A);
  RacketSampleIn s = h.parked_sample(0);
  s.player = 1;
  CHECK(h.match.on_sample(s, h.now) == SampleResult::not_joined);
  // well formed while waiting: only presence
  CHECK(h.match.on_sample(h.parked_sample(0), h.now) == SampleResult::idle);
}

// A player's racket stays a body on its own side: a sample implying more
// than max_racket_speed since the slot's previous one is too_fast, a centre
// beyond the player's half (plus the margin, 1 m over the net, 1 m under the
// floor) out_of_range, whatever else it says; the ball is never touched.
TEST(a_racket_stays_physical_and_on_its_side) {
  Game g = two_players();
  g.run(1.0);
  const Court &c = g.match.court();
  const MatchConfig &cfg = g.match.config();
  RacketSampleIn prev = g.parked_sample(0);
  CHECK(g.match.on_sample(prev, g.now) == SampleResult::accepted);
  uint64_t hash = ball_sim_hash(&g.match.sim());
  // moves of d metres 0.1 s later: 4.99 m is 49.9 m/s, 5.01 m 50.1 m/s (max_racket_speed 50)
  auto moved = [&](double dx, double dz, double dt) {
    RacketSampleIn s = prev;
    s.seq = ++g.seq[0];
    s.capture_time = prev.capture_time + dt;
    s.center.x += dx;
    s.center.z += dz;
    return s;
  };
  CHECK_NEAR(cfg.max_racket_speed, 50.0, 0.0);
  CHECK(g.match.on_sample(moved(5.01, 0.0, 0.1), g.now) == SampleResult::too_fast);
  CHECK(g.match.on_sample(moved(0.0, 12.0, 0.1), g.now) == SampleResult::too_fast);  // a jump across the court
  CHECK_EQ(ball_sim_hash(&g.match.sim()), hash);
  RacketSampleIn ok = moved(4.99, 0.0, 0.1);
  CHECK(g.match.on_sample(ok, g.now) == SampleResult::accepted);
  prev = ok;
  // the half of slot 0 (x < net_x) and its margin, over the net, under the floor
  auto at = [&](double x, double y, double z) {
    RacketSampleIn s = prev;
    s.seq = ++g.seq[0];
    s.capture_time = prev.capture_time + 10.0;  // slow enough for any move
    s.center = ball_v3(x, y, z);
    return g.match.on_sample(s, g.now);
  };
  double m = cfg.racket_margin;
  CHECK(at(c.net_x + 1.1, 1.0, c.z_mid()) == SampleResult::out_of_range);       // over the net by 1.1 m
  CHECK(at(c.x_lo - m - 0.1, 1.0, c.z_mid()) == SampleResult::out_of_range);    // behind the baseline
  CHECK(at(c.x_lo + 1.0, 1.0, c.z_hi + m + 0.1) == SampleResult::out_of_range); // off the sideline
  CHECK(at(c.x_lo + 1.0, c.floor - 1.1, c.z_mid()) == SampleResult::out_of_range);  // under the floor
  // slot 1 on the far side: the near side is out of its range, its own is not
  RacketSampleIn far = g.parked_sample(1);
  CHECK(g.match.on_sample(far, g.now) == SampleResult::accepted);
  RacketSampleIn near = g.parked_sample(1);
  near.capture_time = far.capture_time + 10.0;
  near.center.x = c.net_x - 1.1;
  CHECK(g.match.on_sample(near, g.now) == SampleResult::out_of_range);
}

// The speed limit holds across a pause: a sample captured before the slot's
// previous one (taken while paused, up to max_sample_lead ahead of the
// stopped sim clock), or at its time elsewhere, is a racket in two places,
// stale, not pushed on the track behind that sample's back; one at its time
// and place is that sample again. Over random moves: every sample that
// passed every check lies within max_racket_speed of every one before it.
TEST(a_capture_time_going_back_is_stale) {
  Game g = two_players();
  g.run(1.0);
  g.park[0] = false;  // slot 0's stream by hand from here
  const double vmax = g.match.config().max_racket_speed;
  RacketSampleIn a = g.parked_sample(0);
  a.center.x += 2.0;
  CHECK(g.match.on_sample(a, g.now) == SampleResult::accepted);
  CHECK(g.control(ControlKind::pause, g.owner[0]) == Reason::none);
  RacketSampleIn b = a;  // while paused: 15 m in 0.4 s is 37.5 m/s
  b.seq = ++g.seq[0];
  b.capture_time = a.capture_time + 0.4;
  b.center.z += 15.0;
  CHECK(g.match.on_sample(b, g.now) == SampleResult::idle);
  CHECK(g.control(ControlKind::resume, g.owner[0]) == Reason::none);
  uint64_t hash = ball_sim_hash(&g.match.sim());
  RacketSampleIn c = a;  // back at a's place 0.2 s after it, but 0.2 s before b
  c.seq = ++g.seq[0];
  c.capture_time = a.capture_time + 0.2;
  CHECK(g.match.on_sample(c, g.now) == SampleResult::stale);
  c.seq = ++g.seq[0];
  c.capture_time = b.capture_time;  // at b's time, elsewhere
  CHECK(g.match.on_sample(c, g.now) == SampleResult::stale);
  CHECK_EQ(ball_sim_hash(&g.match.sim()), hash);
  RacketSampleIn again = b;  // b once more, with a new seq: the same place at the same time
  again.seq = ++g.seq[0];
  CHECK(g.match.on_sample(again, g.now) == SampleResult::accepted);

  // random moves, forward and back in time: what is accepted stays a body
  const Court &court = g.match.court();
  std::vector<RacketSampleIn> kept{again};
  int refused = 0;
  for (uint64_t seed = 1; seed <= 8; ++seed) {
    seeded_rng rng = seeded_stream(seed, 12);
    for (int k = 0; k < 60; ++k) {
      RacketSampleIn s = kept.back();
      s.seq = ++g.seq[0];
      s.capture_time = kept.back().capture_time + seeded_uniform(&rng, -0.05, 0.1);
      while (s.capture_time > g.match.sim().time + 0.3) g.run(1.0 / 60.0);  // within max_sample_lead
      if (seeded_uniform(&rng, 0.0, 1.0) < 0.7)  // mostly near the newest accepted one
        s.center = ball_v3_add(s.center, ball_v3(seeded_uniform(&rng, -1.0, 1.0), seeded_uniform(&rng, -0.2, 0.2),
                                                 seeded_uniform(&rng, -1.0, 1.0)));
      else
        s.center = ball_v3(seeded_uniform(&rng, court.x_lo, court.net_x), seeded_uniform(&rng, 0.2, 2.0),
                           seeded_uniform(&rng, court.z_lo, court.z_hi));
      bool paused = seeded_below(&rng, 8) == 0;  // now and then the sample comes while paused
      if (paused) CHECK(g.control(ControlKind::pause, g.owner[0]) == Reason::none);
      SampleResult r = g.match.on_sample(s, g.now);
      if (paused) CHECK(g.control(ControlKind::resume, g.owner[0]) == Reason::none);
      if (r == SampleResult::accepted || r == SampleResult::idle)
        kept.push_back(s);
      else
        refused++;
    }
  }
  CHECK(kept.size() > 100);
  CHECK(refused > 100);
  for (size_t i = 1; i < kept.size(); ++i)
    for (size_t j = 0; j < i; ++j)
      CHECK(ball_v3_norm(ball_v3_sub(kept[i].center, kept[j].center)) <=
            vmax * (kept[i].capture_time - kept[j].capture_time) + 1e-9);
}

// Sequence numbers compare as serial numbers (RFC 1982): a stream at
// 2^32 - 1 goes on at 0 instead of locking; a holder's repeated JOIN starts
// its stream anew.
TEST(sample_seq_wraps_and_a_rejoin_restarts_the_stream) {
  Game g = two_players();
  g.run(1.0);
  g.park[0] = false;  // slot 0's stream by hand from here
  auto next = [&](uint32_t seq) {
    g.run(0.05);
    g.seq[0] = seq - 1;
    return g.match.on_sample(g.parked_sample(0), g.now);
  };
  // on across the wrap, never more than 1000 ahead at once
  CHECK(next(0xFFFFFFF0u) == SampleResult::out_of_order);  // a jump
  CHECK(g.control(ControlKind::join, A, 0) == Reason::none);  // a rejoin: the stream starts anew
  CHECK(next(0xFFFFFFF0u) == SampleResult::accepted);
  CHECK(next(0xFFFFFFFFu) == SampleResult::accepted);
  CHECK(next(0u) == SampleResult::accepted);
  CHECK(next(1u) == SampleResult::accepted);
  CHECK(next(0xFFFFFFF0u) == SampleResult::out_of_order);  // behind 1 by 17
  CHECK(next(1u) == SampleResult::duplicate);
  CHECK(next(1u + 1001u) == SampleResult::out_of_order);    // 1001 ahead: a forged seq, not the stream
  CHECK(next(1u + 1000u) == SampleResult::accepted);
  // the holder joins again (a restarted client): its seq 1 is new again
  CHECK(g.control(ControlKind::join, A, 0) == Reason::none);
  CHECK(next(1u) == SampleResult::accepted);
}

// `lost` is the holder's own seq gaps: over a random stream in which
// samples vanish, reach the match malformed, find the reader full
// (rejected) or come from a stranger, every seq the holder wrote up to the
// newest that arrived is counted once: arrived or lost.
TEST(lost_counts_each_skipped_seq_of_the_holder_once) {
  for (uint64_t seed = 1; seed <= 20; ++seed) {
    seeded_rng rng = seeded_stream(seed, 7);
    Game g = two_players();
    g.run(1.0);
    g.park[0] = false;
    CHECK(g.control(ControlKind::join, A, 0) == Reason::none);  // the stream starts anew
    g.seq[0] = 0xFFFFFF00u + static_cast<uint32_t>(seeded_below(&rng, 512));  // across the wrap
    uint64_t lost = 0, arrived = 0, stranger_lost = 0, rejected = 0;
    uint32_t first = 0, newest = 0;
    for (int i = 0; i < 400; ++i) {
      if (i % 8 == 0) g.run(0.02);
      RacketSampleIn s = g.parked_sample(0);
      s.capture_time -= (7 - i % 8) * 0.0025;  // captured 400 a second, each at its own time
      double u = seeded_uniform(&rng, 0.0, 1.0);
      if (u < 0.3 && arrived > 0) continue;  // never arrives
      if (arrived == 0) first = s.seq;
      newest = s.seq;
      arrived++;
      if (u < 0.4) {
        g.match.on_rejected(s, &lost);
        rejected++;
        continue;
      }
      if (u < 0.5) s.center.y = 1e4;  // out_of_range, still of the stream
      g.match.on_sample(s, g.now, &lost);
      // a stranger under the same key, at any seq: no stream of its own, nothing lost
      RacketSampleIn x = s;
      x.from = B;
      x.seq = s.seq + static_cast<uint32_t>(seeded_below(&rng, 5000));
      CHECK(g.match.on_sample(x, g.now, &stranger_lost) == SampleResult::not_owner);
      g.match.on_rejected(x, &stranger_lost);
      rejected++;
    }
    CHECK_EQ(stranger_lost, 0u);
    g.match.end_streams();  // the gaps still open for a late sample: lost
    lost += g.match.take_lost();
    CHECK_EQ(g.match.counters().rejected, rejected);  // the match's share of the server's rejected
    CHECK_MSG(lost + arrived == static_cast<uint64_t>(newest - first) + 1u,
              "seed %llu: %llu lost + %llu arrived, seqs %u..%u", static_cast<unsigned long long>(seed),
              static_cast<unsigned long long>(lost), static_cast<unsigned long long>(arrived), first, newest);
  }
  // one forged seq far ahead is out_of_order and counts no gap; the holder's next one counts its own
  Game g = two_players();
  g.run(1.0);
  g.park[0] = false;
  uint64_t lost = 0;
  RacketSampleIn s = g.parked_sample(0);
  s.seq += 0x7FFFFFFFu;
  g.seq[0]--;  // not the holder's own
  CHECK(g.match.on_sample(s, g.now, &lost) == SampleResult::out_of_order);
  CHECK_EQ(lost, 0u);
  g.run(0.02);
  g.seq[0] += 2;  // two lost
  CHECK(g.match.on_sample(g.parked_sample(0), g.now, &lost) == SampleResult::accepted);
  CHECK_EQ(lost, 0u);  // not yet: a late sample may fill them
  g.match.end_streams();
  CHECK_EQ(g.match.take_lost(), 2u);
}

// A holder cannot make `lost` grow faster than its capture times allow
// (kMaxStreamRate, 1000 a second): 300 samples 1/30 s apart, each 999 seqs
// past the one before (in reach of kMaxSeqJump), count no loss; a real
// stream at 30 a second that lost 9 in 10 counts each of them.
TEST(lost_grows_no_faster_than_capture_times_allow) {
  Game g = two_players();
  g.run(1.0);
  g.park[0] = false;
  CHECK(g.control(ControlKind::join, A, 0) == Reason::none);
  uint64_t forged = 0, real = 0;
  for (int i = 0; i < 300; ++i) {
    g.run(1.0 / 30.0);
    g.seq[0] += 998;  // (parked_sample adds the 999th)
    g.match.on_sample(g.parked_sample(0), g.now, &forged);
  }
  g.match.end_streams();
  forged += g.match.take_lost();
  CHECK(g.control(ControlKind::join, A, 0) == Reason::none);  // a new stream
  g.seq[0] = 0;
  for (int i = 0; i < 300; ++i) {
    g.run(1.0 / 30.0);
    if (i % 10 == 0) g.match.on_sample(g.parked_sample(0), g.now, &real);
    else g.seq[0]++;  // written, never arrived
  }
  g.match.end_streams();
  real += g.match.take_lost();
  check::note("300 jumps of 999 seqs 1/30 s apart: %llu lost; 270 of 300 never arrived: %llu lost",
       static_cast<unsigned long long>(forged), static_cast<unsigned long long>(real));
  CHECK_EQ(forged, 0u);
  CHECK_EQ(real, 261u);  // (the 9 after the last that arrived are not known to be)
}

// A stream with known gaps, late samples, a forged jump and a rejoin, by
// hand: a gap counts lost once the stream is 16 seqs past it (or ends)
// without it; a late sample that fills its gap before then counts where it
// is dropped (out_of_order), never lost; one later than that was counted
// lost already and counts out_of_order too (docs/protocol.md, `lost`).
TEST(lost_counts_a_gap_once_the_window_has_passed_it) {
  Game g = two_players();
  g.run(1.0);
  g.park[0] = false;
  CHECK(g.control(ControlKind::join, A, 0) == Reason::none);  // the stream starts anew
  uint64_t lost = 0;
  auto next = [&](uint32_t seq) {
    g.run(0.04);  // (time enough for the jumps below: kMaxStreamRate)
    g.seq[0] = seq - 1;
    return g.match.on_sample(g.parked_sample(0), g.now, &lost);
  };
  CHECK(next(1) == SampleResult::accepted);
  CHECK(next(2) == SampleResult::accepted);
  CHECK(next(5) == SampleResult::accepted);      // 3 and 4 skipped: gaps, not yet lost
  CHECK(next(4) == SampleResult::out_of_order);  // late: fills its gap
  CHECK(next(6) == SampleResult::accepted);
  CHECK_EQ(lost, 0u);
  CHECK(next(30) == SampleResult::accepted);     // 3 leaves the window; of 7..29, 7..13 at once
  CHECK_EQ(lost, 1u + 7u);
  CHECK(next(20) == SampleResult::out_of_order); // late, in the window: fills its gap
  CHECK(next(13) == SampleResult::out_of_order); // 17 behind: counted lost already
  CHECK(next(30 + 1001) == SampleResult::out_of_order);  // a forged jump: no gap, the stream stays
  CHECK_EQ(lost, 8u);
  CHECK(next(31) == SampleResult::accepted);     // 14 leaves the window
  CHECK_EQ(lost, 9u);
  CHECK_EQ(g.match.take_lost(), 0u);
  // a JOIN anew ends the stream: its open gaps, 15..29 but 20, are lost
  CHECK(g.control(ControlKind::join, A, 0) == Reason::none);
  CHECK_EQ(g.match.take_lost(), 14u);
  // of 1..31: 22 seqs never arrived, and 13 came too late: 23 in all
  CHECK(next(1) == SampleResult::accepted);      // the new stream
  CHECK(next(3) == SampleResult::accepted);
  CHECK(g.control(ControlKind::leave, A, 0) == Reason::none);  // a LEAVE ends it too: 2
  CHECK_EQ(g.match.take_lost(), 1u);
  CHECK_EQ(lost, 9u);
  CHECK_EQ(g.match.take_lost(), 0u);  // each gap once
}

TEST(vanished_player_pauses_and_resumes) {
  MatchConfig c = default_config();
  c.player_timeout = 0.5;
  Game g = two_players(c);
  g.run(2.0);
  CHECK(g.match.state() == MatchState::playing);
  g.park[1] = false;  // player 1 goes silent
  double silent_at = g.now;
  g.run(2.0);
  CHECK(g.match.state() == MatchState::paused);
  const EventOut *p = g.first(EventKind::pause);
  CHECK(p != nullptr);
  CHECK_EQ(p->index, 1);
  CHECK(p->reason == Reason::pause_vanished);
  // it paused within one timeout and one frame of the last sample (10 Hz: 0.1 s before)
  size_t k = 0;
  while (&g.events[k] != p) k++;
  double t_pause = p->time;
  double sim_frozen = g.match.sim().time;
  CHECK_NEAR(sim_frozen, t_pause, 0.0);
  (void)silent_at;
  g.run(1.0);
  CHECK_EQ(g.match.sim().time, sim_frozen);  // the sim clock stands still
  CHECK(g.states.back().sim_time <= sim_frozen);
  g.park[1] = true;  // back
  g.run(0.5);
  CHECK(g.match.state() == MatchState::playing);
  CHECK(g.first(EventKind::resume, k) != nullptr);
  CHECK(g.match.sim().time > sim_frozen);
  CHECK_EQ(g.match.counters().pauses, 1u);
}

TEST(pause_comes_within_one_timeout) {
  MatchConfig c = default_config();
  c.player_timeout = 0.5;
  Game g = two_players(c);
  g.run(1.0);
  g.park[0] = false;
  double last_sample = g.sent_at[0];
  double paused_at = -1.0;
  for (int k = 0; k < 120 && paused_at < 0; ++k) {
    g.run(1.0 / 60.0);
    if (g.match.state() == MatchState::paused) paused_at = g.now;
  }
  CHECK(paused_at > 0);
  CHECK(paused_at - last_sample <= 0.5 + 2.0 / 60.0);
  CHECK(paused_at - last_sample >= 0.5);
}

TEST(participant_lost_pauses_at_the_next_frame) {
  Game g = two_players();
  g.run(1.0);
  g.match.on_participant_lost(B);
  g.park[1] = false;
  g.run(1.0 / 60.0);
  CHECK(g.match.state() == MatchState::paused);
  // a new participant takes the vanished slot and the match goes on
  CHECK(g.join(1, C) == Reason::none);
  g.run(0.2);
  CHECK(g.match.state() == MatchState::playing);
  CHECK(g.match.info().slots[1].owner == C);
}

TEST(join_and_leave) {
  Game g;
  CHECK(g.join(0, A) == Reason::none);
  CHECK(g.join(0, A) == Reason::none);  // again: nothing changes
  CHECK_EQ(g.count(EventKind::join), 1);
  CHECK(g.join(0, B) == Reason::refused_slot_held);
  const EventOut *r = g.first(EventKind::refused);
  CHECK(r && r->reason == Reason::refused_slot_held && r->index == static_cast<int>(ControlKind::join));
  CHECK(g.join(7, B) == Reason::refused_bad_value);
  CHECK(g.control(ControlKind::join, B, -1) == Reason::none);  // any free slot: 1
  CHECK(g.match.info().slots[1].owner == B);
  g.owner[1] = B;
  g.park[1] = true;
  CHECK(g.control(ControlKind::join, C, -1) == Reason::refused_no_room);
  g.run(1.0);
  CHECK(g.match.state() == MatchState::playing);
  CHECK(g.control(ControlKind::leave, A, 1) == Reason::refused_not_player);
  CHECK(g.control(ControlKind::leave, B, 1) == Reason::none);
  g.park[1] = false;
  CHECK(g.match.state() == MatchState::waiting);
  const EventOut *p = g.first(EventKind::pause);
  CHECK(p && p->reason == Reason::pause_left);
  double t = g.match.sim().time;
  g.run(1.0);
  CHECK_EQ(g.match.sim().time, t);
  CHECK(g.join(1, C) == Reason::none);
  g.run(0.1);
  CHECK(g.match.state() == MatchState::playing);
  CHECK(g.first(EventKind::resume) != nullptr);
}

TEST(controls) {
  Game g = two_players();
  g.run(1.0);
  CHECK(g.control(ControlKind::time_base, C, -1, 0.5) == Reason::refused_not_player);
  CHECK(g.control(ControlKind::time_base, A, -1, 50.0) == Reason::refused_bad_value);
  // a time base needs every holder asking for the same value: one asking changes nothing
  CHECK(g.control(ControlKind::time_base, A, -1, 0.5) == Reason::none);
  double t = g.match.sim().time;
  g.run(1.0);
  CHECK_NEAR(g.match.sim().time - t, 1.0, 1e-9);
  CHECK(g.first(EventKind::time_base) == nullptr);
  CHECK(g.control(ControlKind::time_base, B, -1, 2.0) == Reason::none);  // another value: still none
  CHECK(g.control(ControlKind::time_base, B, -1, 0.5) == Reason::none);
  CHECK(g.first(EventKind::time_base) != nullptr);
  t = g.match.sim().time;
  g.run(1.0);
  CHECK_NEAR(g.match.sim().time - t, 0.5, 1e-9);  // slow motion: half a sim second per real second
  CHECK(g.control(ControlKind::time_base, A, -1, 2.0) == Reason::none);
  CHECK(g.control(ControlKind::time_base, B, -1, 2.0) == Reason::none);
  t = g.match.sim().time;
  g.run(1.0);
  CHECK_NEAR(g.match.sim().time - t, 2.0, 1e-9);
  uint64_t h = g.match.info().model_hash;
  CHECK(g.control(ControlKind::level, B, -1, 3) == Reason::none);
  CHECK(g.match.info().model_hash != h);
  CHECK_EQ(g.match.info().level, 3);
  CHECK(g.match.model().response == BALL_RESPONSE_PHYSICAL);
  // the states' sim hash is the sim's under the new model (the match keeps the model's hash)
  for (int k = 0, seen = 0; k < 60 && seen < 3; ++k) {
    size_t n = g.states.size();
    g.run(1.0 / g.match.config().frame_rate);
    if (g.states.size() == n) continue;
    seen++;
    CHECK_EQ(g.states.back().sim_hash, ball_sim_hash(&g.match.sim()));
    CHECK(g.states.back().sim_hash != ball_sim_hash_with(&g.match.sim(), h));
  }
  CHECK(g.control(ControlKind::level, B, -1, 9) == Reason::refused_bad_value);
  CHECK(g.control(ControlKind::pause, A) == Reason::none);
  CHECK(g.match.state() == MatchState::paused);
  t = g.match.sim().time;
  g.run(1.0);
  CHECK_EQ(g.match.sim().time, t);
  CHECK(g.control(ControlKind::pause, A) == Reason::refused_state);
  CHECK(g.control(ControlKind::resume, B) == Reason::none);
  CHECK(g.match.state() == MatchState::playing);
  // serve early: between points only
  CHECK(g.control(ControlKind::serve, A) == Reason::refused_state || g.match.counters().points > 0);
  CHECK(g.control(ControlKind::create, A) == Reason::refused_bad_value);
}

TEST(serve_on_request) {
  MatchConfig c = default_config();
  c.serve_delay = 30.0;
  Game g = two_players(c);
  g.run(6.0);
  CHECK_EQ(g.count(EventKind::point), 1);
  CHECK_EQ(g.count(EventKind::serve), 1);
  CHECK(g.control(ControlKind::serve, B) == Reason::none);
  g.run(0.1);
  CHECK_EQ(g.count(EventKind::serve), 2);
}

TEST(state_rate) {
  MatchConfig c = default_config();
  c.state_rate = 20.0;
  Game g = two_players(c);
  g.run(3.0);
  int playing_frames = static_cast<int>(g.match.counters().frames);
  CHECK_EQ(playing_frames, 180);  // both slots held from the start: 3 s at 60 Hz
  CHECK(std::abs(static_cast<int>(g.states.size()) - playing_frames / 3) <= 1);
  c.state_rate = 0.0;
  Game off = two_players(c);
  off.run(3.0);
  CHECK_EQ(off.states.size(), 0u);
  // each state lies on the segment it names
  for (const auto &s : g.states) {
    const SegmentOut *seg = nullptr;
    for (const auto &x : g.segments)
      if (x.seq == s.segment_seq) seg = &x;
    CHECK(seg != nullptr);
    if (!seg) continue;
    ball_state b;
    ball_segment_eval(&g.match.model(), &seg->segment, s.sim_time, &b);
    CHECK(ball_v3_max_diff(b.position, s.ball.position) <= 1e-12);
  }
}

TEST(deterministic) {
  Game a = two_players(), b = two_players();
  a.run(20.0);
  b.run(20.0);
  CHECK_EQ(ball_sim_hash(&a.match.sim()), ball_sim_hash(&b.match.sim()));
  CHECK_EQ(a.events.size(), b.events.size());
}

TEST(config_checks) {
  std::string err;
  MatchConfig c = default_config();
  CHECK(check_match_config(c, &err));
  c.players = 5;
  CHECK(!check_match_config(c, &err));
  CHECK(err.find("players") == 0);
  c = default_config();
  c.state_rate = 120.0;
  CHECK(!check_match_config(c, &err));
  CHECK(err.find("state_rate") == 0);
  c = default_config();
  c.time_base = std::nan("");
  CHECK(!check_match_config(c, &err));
  // a scene without a net cannot be played by these rules
  ball_scene scene;
  ball_scene_default(&scene);
  scene.model.has_net = 0;
  Match m;
  CHECK(!m.init(default_config(), scene, &err));
  CHECK(err.find("net") != std::string::npos);
}

TEST(host_routes_and_creates) {
  MatchConfig t = default_config();
  Host host(2, true, t);
  ball_scene scene;
  ball_scene_default(&scene);
  std::string err;
  CHECK(host.add_scene("tennis", scene, &err));
  CHECK(host.add_match(t, scene, &err));
  CHECK(!host.add_match(t, scene, &err));  // the same id twice
  RacketSampleIn s;
  s.match_id = 99;
  CHECK(host.on_sample(s, 0.0) == SampleResult::unknown_match);
  MatchOutput out;
  Match *m = nullptr;
  ControlIn c;
  c.kind = ControlKind::create;
  c.match_id = 1008;
  c.scene = "nowhere";
  CHECK(host.on_control(c, 0.0, &out, &m) == Reason::refused_bad_value);
  c.scene = "tennis";
  c.players = 2;
  c.level = 2;
  c.match_id = 4096;  // not an id CREATEs may name (by default 0 to 4095)
  CHECK(host.on_control(c, 0.0, &out, &m) == Reason::refused_bad_value);
  c.match_id = 0xFFFFFFFFu;
  CHECK(host.on_control(c, 0.0, &out, &m) == Reason::refused_bad_value);
  c.match_id = 1008;
  CHECK(host.on_control(c, 0.0, &out, &m) == Reason::none);
  CHECK(m != nullptr && m->id() == 1008 && m->config().level == BALL_LEVEL_MID);
  c.match_id = 1009;
  CHECK(host.on_control(c, 0.0, &out, &m) == Reason::refused_no_room);  // max_matches 2
  c.kind = ControlKind::join;
  c.match_id = 42;
  CHECK(host.on_control(c, 0.0, &out, &m) == Reason::refused_bad_value);
  CHECK(m == nullptr);
  Host closed(4, false, t);
  closed.add_scene("tennis", scene, &err);
  c.kind = ControlKind::create;
  CHECK(closed.on_control(c, 0.0, &out, &m) == Reason::refused_no_room);
  // one process's CREATEs have at most max_creates matches standing; another's are its own
  Host open(8, true, t);
  open.add_scene("tennis", scene, &err);
  open.set_create_shares(Host::Origin::process, 2, 100);
  c.from = participant(3);
  for (uint32_t id : {1020u, 1021u}) {
    c.match_id = id;
    CHECK(open.on_control(c, 0.0, &out, &m) == Reason::none);
  }
  c.match_id = 1022;
  CHECK(open.on_control(c, 0.0, &out, &m) == Reason::refused_no_room);
  c.from = participant(4);
  CHECK(open.on_control(c, 0.0, &out, &m) == Reason::none);
  CHECK(open.creator(1020) == participant(3) && open.creator(1022) == participant(4));
  open.remove(1020);  // one gone: the first may create again
  c.from = participant(3);
  c.match_id = 1023;
  CHECK(open.on_control(c, 0.0, &out, &m) == Reason::none);
}

// The shares of CREATEs (docs/protocol.md, "Control messages"), over
// random participants: however many participants a process has, its
// CREATEs have at most max_creates matches standing (5 participants of one
// process, 2 CREATEs each: 2 stand, the review's 8 of 9 places); on a
// secure domain those of one identity (the first 6 bytes of the GUID
// prefix), whatever its other bytes; and those from one host address at
// most max_creates_per_host, whatever process; an unknown host (zeros) has
// no host share. Every refusal is no_room and changes nothing.
TEST(creates_are_shared_by_process_identity_and_host) {
  MatchConfig t;
  ball_scene scene;
  ball_scene_default(&scene);
  std::mt19937 rng(40);
  auto random_prefix = [&rng]() {
    ParticipantId p;
    for (auto &b : p) b = static_cast<uint8_t>(rng());
    return p;
  };
  HostAddress home{}, other{};
  home[15] = 7;
  other[15] = 9;
  for (int round = 0; round < 50; ++round) {
    for (Host::Origin origin : {Host::Origin::process, Host::Origin::identity}) {
      const size_t same = origin == Host::Origin::process ? 8 : 6;
      Host host(40, true, t);
      std::string err;
      host.add_scene("tennis", scene, &err);
      host.set_create_shares(origin, 2, 5);
      MatchOutput out;
      Match *m = nullptr;
      ControlIn c;
      c.kind = ControlKind::create;
      c.scene = "tennis";
      uint32_t next_id = 1000;
      auto create = [&](const ParticipantId &from, const HostAddress &at) {
        c.from = from;
        c.host = at;
        c.match_id = next_id++;
        size_t before = host.matches().size();
        Reason r = host.on_control(c, 0.0, &out, &m);
        CHECK(r == Reason::none || (r == Reason::refused_no_room && host.matches().size() == before));
        return r == Reason::none;
      };
      // 5 participants of one origin (its bytes the same, the rest random), 2 CREATEs each
      ParticipantId base = random_prefix();
      int stood = 0;
      for (int k = 0; k < 5; ++k) {
        ParticipantId p = random_prefix();
        std::copy(base.begin(), base.begin() + same, p.begin());
        for (int j = 0; j < 2; ++j) stood += create(p, HostAddress{});
      }
      CHECK_EQ(stood, 2);
      CHECK(create(random_prefix(), HostAddress{}));  // another origin: its own share
      // from one host address: 5 stand, whatever their origins; another host's are its own
      Host by_host(40, true, t);
      by_host.add_scene("tennis", scene, &err);
      by_host.set_create_shares(origin, 2, 5);
      int from_home = 0;
      for (int k = 0; k < 8; ++k) {
        c.from = random_prefix();
        c.host = home;
        c.match_id = next_id++;
        from_home += by_host.on_control(c, 0.0, &out, &m) == Reason::none;
      }
      CHECK_EQ(from_home, 5);
      c.from = random_prefix();
      c.host = other;
      c.match_id = next_id++;
      CHECK(by_host.on_control(c, 0.0, &out, &m) == Reason::none);
      // one gone: its host may create again
      by_host.remove(by_host.matches().front()->id());
      c.from = random_prefix();
      c.host = home;
      c.match_id = next_id++;
      CHECK(by_host.on_control(c, 0.0, &out, &m) == Reason::none);
    }
  }
}

CHECK_MAIN

// Slots bound to identities (docs/security.md, "Slots bound to
// identities"): slot 0 is A's, slot 1 B's. B cannot JOIN slot 0 while it
// is free, nor when A vanished; a JOIN of "a free slot" finds only its
// own; a third participant finds no room in a match whose slots are all
// bound; A and B play.
TEST(a_slot_bound_to_an_identity_is_that_identity_s_alone) {
  Game g;
  g.match.set_slot_rule([](int slot, const ParticipantId &who) { return who == (slot == 0 ? A : B); });
  CHECK(g.control(ControlKind::join, B, 0) == Reason::refused_not_player);  // free, but A's
  CHECK(g.control(ControlKind::join, C, -1) == Reason::refused_not_player);  // none of them is C's
  CHECK(g.control(ControlKind::join, B, -1) == Reason::none);                // its own: slot 1
  CHECK(g.match.info().slots[1].held && g.match.info().slots[1].owner == B);
  CHECK(!g.match.info().slots[0].held);
  CHECK(g.control(ControlKind::join, A, 0) == Reason::none);
  g.run(3.0);  // A's samples stop coming (parked: g.park), it vanishes after the timeout
  g.park[0] = false;
  g.run(3.0);
  CHECK(g.control(ControlKind::join, B, 0) == Reason::refused_not_player);  // vanished, still A's
  CHECK(g.control(ControlKind::join, C, 0) == Reason::refused_not_player);
  CHECK(g.match.info().slots[0].owner == A);
  CHECK(g.control(ControlKind::join, A, 0) == Reason::none);  // A again
}
