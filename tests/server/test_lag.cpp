// Lag compensation (docs/server-design.md, "Lag compensation"; docs/protocol.md,
// "Corrections"): a racket sample that arrives late is tested against the
// ball where it was at its time; a hit found so takes the match back to it
// and on again, and what that gives is written as corrections. Offline
// rallies of two bots behind a delay, with compensation on and off.
#include <cmath>
#include <cstdio>

#include "check.hpp"
#include "game.h"
#include "lag.h"
#include "rally.h"

using namespace ballsrv;
using namespace test;
using check::note;

namespace {

struct Lag {
  uint64_t hits = 0, rewinds = 0, tested = 0, ruled_out = 0, points = 0, past_own = 0;
  size_t corrections = 0, correction_hits = 0;
  int before_barrier = 0;   // corrections that start before the last hit or serve the client had
  int not_past = 0;         // correction hits not in the past when written
  int rehits = 0;           // correction hits by the racket that hit last, while its tests slept
  int again = 0;            // corrections that write a segment again (rewind_own_hit)
  // the stats' hits and bounces against those a client ends up with (the
  // segments in effect once each supersedes those with a later t0)
  long long hits_off = 0, bounces_off = 0;
  int twice = 0;  // of those, hits by the racket whose hit a client had last, within 0.3 s of it
  int states = 0, wrong = 0;  // states on the rule's segment from what was written before them
  double worst = 0.0;
};

Lag run(double delay, double window, int seeds, bool plan_ahead = true, ball_level level = BALL_LEVEL_MID,
        bool own_hit = false, double jitter = 0.0, double loss = 0.0, double noise = 0.002) {
  Lag l;
  for (int seed = 1; seed <= seeds; ++seed) {
    MatchConfig c = default_config();
    c.level = level;
    c.seed = static_cast<uint64_t>(seed);
    c.rewind_window = window;
    c.rewind_own_hit = own_hit;
    Net net;
    net.delay = delay;
    net.jitter = jitter;
    net.loss = loss;
    net.noise = noise;
    net.plan_ahead = plan_ahead;
    RallyResult r = play(c, net, 30.0, static_cast<uint64_t>(seed));
    l.hits += r.counters.hits;
    l.rewinds += r.counters.rewinds;
    l.tested += r.counters.late_tested;
    l.ruled_out += r.counters.late_ruled_out;
    l.points += r.counters.points;
    l.past_own += r.counters.rewinds_past_own_hit;
    Game g(c);
    // t0 of the newest serve or hit written before, not by racket k (with
    // rewind_own_hit, a racket's own hit is no barrier to its corrections)
    double last_barrier[kMaxPlayers];
    for (double &b : last_barrier) b = -1e300;
    const SegmentOut *last_hit = nullptr;
    const double slept = g.match.model().sleep_frames * c.time_base / c.frame_rate;  // sim s the tests sleep after a hit
    for (size_t i = 0; i < r.segments.size(); ++i) {
      const SegmentOut &s = r.segments[i];
      // a segment written again (in effect before a hit it moved): no new collision
      bool again = false;
      for (size_t k = 0; k < i && s.correction && !again; ++k)
        again = r.segments[k].segment.t0 == s.segment.t0 && r.segments[k].cause == s.cause &&
                r.segments[k].cause_index == s.cause_index;
      l.again += again;
      if (last_hit && s.segment.t0 < last_hit->segment.t0) last_hit = nullptr;  // superseded
      if (s.correction && !again) {
        l.corrections++;
        double barrier = last_barrier[0];  // (what no correction goes before: the barrier of every racket)
        for (double b : last_barrier) barrier = std::fmin(barrier, b);
        if (s.cause == Cause::racket && s.cause_index >= 0 && s.cause_index < kMaxPlayers)
          barrier = last_barrier[s.cause_index];
        if (s.segment.t0 < barrier) l.before_barrier++;
        if (s.cause == Cause::racket) {
          l.correction_hits++;
          if (!(s.segment.t0 <= r.written_at[i])) l.not_past++;
          if (last_hit && last_hit->cause_index == s.cause_index && s.segment.t0 - last_hit->segment.t0 < slept - 1e-9)
            l.rehits++;
        }
      }
      for (int k = 0; k < kMaxPlayers; ++k)
        if (s.cause == Cause::serve || (s.cause == Cause::racket && !(own_hit && s.cause_index == k)))
          last_barrier[k] = std::fmax(last_barrier[k], s.segment.t0);
      if (s.cause == Cause::serve) last_hit = nullptr;
      if (s.cause == Cause::racket && !again) last_hit = &s;
    }
    std::vector<const SegmentOut *> kept;
    for (const SegmentOut &s : r.segments) {
      while (!kept.empty() && kept.back()->segment.t0 > s.segment.t0) kept.pop_back();
      const SegmentOut *b = kept.empty() ? nullptr : kept.back();
      if (b && b->segment.t0 == s.segment.t0 && b->cause == s.cause && b->cause_index == s.cause_index) continue;
      kept.push_back(&s);
    }
    long long hits = 0, bounces = 0;
    const double end = r.states.empty() ? 0.0 : r.states.back().sim_time;  // (a contact written ahead is still to come)
    const SegmentOut *last_racket = nullptr;
    for (size_t k = 1; k < kept.size() && kept[k]->segment.t0 <= end; ++k) {  // (in play: live after the one before)
      if (kept[k]->cause == Cause::serve) last_racket = nullptr;
      if (kept[k]->cause == Cause::racket) {
        l.twice += last_racket && last_racket->cause_index == kept[k]->cause_index &&
                   kept[k]->segment.t0 - last_racket->segment.t0 < 0.3;
        last_racket = kept[k];
      }
      hits += kept[k]->cause == Cause::racket && kept[k - 1]->play.live;
      bounces += kept[k]->cause == Cause::floor && kept[k - 1]->play.live;
    }
    l.hits_off += std::llabs(hits - static_cast<long long>(r.counters.hits));
    l.bounces_off += std::llabs(bounces - static_cast<long long>(r.counters.bounces));
    for (size_t n = 0; n < r.states.size(); ++n) {
      Segments known;
      for (size_t k = 0; k < r.segments_before[n]; ++k) known[r.segments[k].seq] = r.segments[k];
      const StateOut &st = r.states[n];
      const SegmentOut *e = segment_in_effect(known, st.sim_time);
      l.states++;
      ball_state b;
      if (!e || ball_segment_eval(&g.match.model(), &e->segment, st.sim_time, &b) != BALL_OK) {
        l.wrong++;
        continue;
      }
      double d = ball_v3_dist(b.position, st.ball.position);
      // (a serve starts at the instant of the frame before: there the ball is on both)
      if (d > 0.0 && e->segment.t0 == st.sim_time) continue;
      l.worst = std::fmax(l.worst, d);
    }
  }
  return l;
}

// every rewind a correction hit in the past, none before the barrier, none
// by a racket asleep after its hit, and every state on the client's segment
void keeps_the_rules(const Lag &on) {
  CHECK_EQ(on.hits_off, 0);
  CHECK_EQ(on.bounces_off, 0);
  CHECK_EQ(on.correction_hits, on.rewinds);
  CHECK_EQ(on.rehits, 0);
  CHECK_EQ(on.before_barrier, 0);
  CHECK_EQ(on.not_past, 0);
  CHECK_EQ(on.wrong, 0);
  CHECK(on.worst == 0.0);
}

}  // namespace

// 100 ms of delay on every sample, bots that swing late (as people do,
// unaware of the delay): the late samples inside the window find
// hits where the ball was, each one a correction in the past that starts
// no earlier than the last hit or serve and never a hit by the racket that
// hit last while its tests slept (its own next sample finds it still on the
// ball), and a client that takes every segment as it comes has the server's
// ball at every state.
// The core alone (lag.h), on a ball in flight and a racket held still
// where the ball was at 0.15 s, sampled from 0.10 s to 0.20 s, asked at
// 0.30 s: the hit lies inside the samples' span, the ball at the start of
// the frame it comes in; asked
// again it gives the same to the bit; the sim it is given is not changed;
// a racket 4 m away or a window that ends after the samples find none.
TEST(the_late_hit_is_a_function_of_the_sim_the_history_and_the_parameters) {
  Game game;
  ball_model m = game.match.model();
  ball_sim sim;
  CHECK(ball_sim_init(&sim, &m) == BALL_OK);
  ball_segment seg{};
  seg.p0 = ball_v3(-3.0, 1.5, 0.0);
  seg.v0 = ball_v3(5.0, 2.0, 0.0);
  CHECK(ball_sim_set_segment(&sim, &seg, 0.0) == BALL_OK);
  SegmentOut serve;
  serve.cause = Cause::serve;
  serve.segment = seg;
  serve.play.live = true;
  std::vector<SegmentOut> history{serve};
  std::vector<ball_event> events(BALL_MAX_CONTACTS + BALL_MAX_RACKETS + 8);
  int n = 0;
  CHECK(ball_step(&sim, 0.3, events.data(), static_cast<int>(events.size()), &n) == BALL_OK && n == 0);
  auto with_racket = [&](ball_vec3 offset) {
    ball_sim s = sim;
    ball_state at;
    CHECK(ball_segment_eval(&m, &seg, 0.15, &at) == BALL_OK);
    for (int k = 0; k <= 5; ++k) {
      ball_racket_sample r;
      r.t = 0.10 + 0.02 * k;
      r.center = ball_v3_add(at.position, offset);
      r.normal = ball_v3(-1.0, 0.0, 0.0);
      CHECK(ball_racket_push(&s, 0, &r) == BALL_OK);
    }
    return s;
  };
  LagParams p{0.5, false, 1.0 / 60.0};
  Slot slot;
  ball_sim near = with_racket(ball_v3(0.0, 0.0, 0.0));
  uint64_t before = ball_sim_hash(&near);
  LateHit a = find_late_hit(near, history, 0, slot, 0.0, p, &events);
  LateHit b = find_late_hit(near, history, 0, slot, 0.0, p, &events);
  note("the late hit at sim s %.4f (samples 0.10 to 0.20)", a.hit);
  CHECK(a.outcome == LateHit::found);
  CHECK(a.hit >= 0.10 - 1e-9 && a.hit <= 0.20 + 1e-9);
  CHECK(a.at == &history[0] && !std::isfinite(a.passed));
  CHECK(a.hit == b.hit && ball_sim_hash(&a.then) == ball_sim_hash(&b.then));
  CHECK(a.then.time <= a.hit && a.hit - a.then.time <= p.frame + 1e-12);  // (the ball at the frame it hits in)
  CHECK_EQ(ball_sim_hash(&near), before);
  ball_sim far = with_racket(ball_v3(0.0, 0.0, 4.0));
  CHECK(find_late_hit(far, history, 0, slot, 0.0, p, &events).outcome != LateHit::found);
  LagParams short_window{0.05, false, 1.0 / 60.0};
  CHECK(find_late_hit(near, history, 0, slot, 0.0, short_window, &events).outcome != LateHit::found);
}

TEST(a_late_sample_inside_the_window_hits_where_the_ball_was) {
  Lag off = run(0.1, 0.0, 6, false), on = run(0.1, 0.25, 6, false);
  note("100 ms delay, mid, 6 rallies of 30 s: without compensation %llu hits %llu points; with it %llu hits %llu "
       "points, %llu late samples tested (%llu ruled out by the bound at once), %llu rewinds, %zu correction segments "
       "(%zu hits, %d by the last hitter asleep), %d before the last hit, %d not in the past; %d states within %.3g m, "
       "%d without a segment",
       (unsigned long long)off.hits, (unsigned long long)off.points, (unsigned long long)on.hits,
       (unsigned long long)on.points, (unsigned long long)on.tested, (unsigned long long)on.ruled_out,
       (unsigned long long)on.rewinds, on.corrections,
       on.correction_hits, on.rehits, on.before_barrier, on.not_past, on.states, on.worst, on.wrong);
  CHECK_EQ(off.rewinds, 0u);
  CHECK_EQ(off.corrections, 0u);
  CHECK(on.tested > 1000);
  CHECK(on.rewinds >= 10);
  // most late samples meet nothing, and the bound says so before any frame is stepped again
  // (what it spares would have found no hit: libball's the_bound_covers_every_walk_of_frames)
  CHECK(on.ruled_out * 2 >= on.tested);
  CHECK(on.ruled_out + on.rewinds <= on.tested);
  keeps_the_rules(on);
  CHECK(on.hits >= off.hits);
}

// With rewind_own_hit, a late sample captured before its own racket's last
// hit may take the match back past that hit and move it (docs/server-design.md,
// "Lag compensation"): rallies at the three levels behind 50, 100 and
// 150 ms, bots that swing late and ahead, the same rules (no correction
// before another racket's last hit or the serve, none by a racket asleep
// after its hit, each in the past), rewinds past the racket's own hit among
// them, and a client that takes every segment as it comes (the segment in
// effect before a moved hit, written again, supersedes it) has the
// server's ball at every state.
TEST(a_rewind_past_its_own_hit_keeps_every_client_on_the_servers_ball) {
  uint64_t past_own = 0;
  int again = 0;
  for (ball_level level : {BALL_LEVEL_EASY, BALL_LEVEL_MID, BALL_LEVEL_ADVANCED})
    for (double delay : {0.05, 0.1, 0.15})
      for (bool ahead : {false, true}) {
        Lag on = run(delay, 0.25, 8, ahead, level, true);
        note("rewind_own_hit, %3.0f ms, %-8s %-5s 8 rallies of 30 s: %4llu hits %3llu points, %4llu late samples "
             "tested, %3llu rewinds (%3llu past the own hit), %4zu corrections (%3zu hits, %d asleep, %2d written "
             "again), %d before the barrier, %d not in the past; %d states within %.3g m, %d without a segment",
             delay * 1e3, level == BALL_LEVEL_EASY ? "easy," : level == BALL_LEVEL_MID ? "mid," : "advanced,",
             ahead ? "ahead" : "late", (unsigned long long)on.hits, (unsigned long long)on.points,
             (unsigned long long)on.tested, (unsigned long long)on.rewinds, (unsigned long long)on.past_own,
             on.corrections, on.correction_hits, on.rehits, on.again, on.before_barrier, on.not_past, on.states,
             on.worst, on.wrong);
        CHECK(on.rewinds >= on.past_own);
        keeps_the_rules(on);
        past_own += on.past_own;
        again += on.again;
      }
  CHECK(past_own >= 500);
  CHECK(again >= 100);
}

// The same rules over a poor network (samples reordered by 80 ms of
// jitter, 20 % lost, 2 cm of noise), rewind_own_hit off and on: out-of-order
// and lost samples among the late ones change nothing of the above. Here a
// rewind's steps through the past once met tracks whose samples all came
// after the frame stepped: the racket stood at its first later sample, and
// a hit's follow-through met the ball again (one rewind, two hits: 28
// correction hits for 27 rewinds in one rally); such a track now waits
// until the steps reach its first sample.
TEST(rewinds_over_a_poor_network) {
  for (int own = 0; own < 2; ++own) {
    uint64_t past_own = 0, rewinds = 0;
    int twice = 0;
    for (ball_level level : {BALL_LEVEL_EASY, BALL_LEVEL_MID, BALL_LEVEL_ADVANCED})
      for (bool ahead : {false, true}) {
        Lag on = run(0.1, 0.25, 6, ahead, level, own == 1, 0.08, 0.2, 0.02);
        keeps_the_rules(on);
        past_own += on.past_own;
        rewinds += on.rewinds;
        twice += on.twice;
      }
    note("poor network, 36 rallies, rewind_own_hit %s: %llu rewinds, %llu past the own hit; %d hits within 0.3 s "
         "of the same racket's as a client has them",
         own ? "on" : "off", (unsigned long long)rewinds, (unsigned long long)past_own, twice);
    CHECK(rewinds >= 200);
    CHECK(own ? past_own >= 50 : past_own == 0);
    if (own) CHECK_EQ(twice, 0);
  }
}

// A window shorter than the delay: every sample is older than it, none is
// tested, nothing is rewound.
TEST(outside_the_window_nothing_is_rewound) {
  Lag l = run(0.1, 0.05, 3);
  note("100 ms delay, 50 ms window: %llu tested, %llu rewinds, %zu corrections", (unsigned long long)l.tested,
       (unsigned long long)l.rewinds, l.corrections);
  CHECK_EQ(l.tested, 0u);
  CHECK_EQ(l.rewinds, 0u);
  CHECK_EQ(l.corrections, 0u);
}

// A flood of late samples of one slot between two wake-ups costs one test
// of that slot, not one per sample (a hostile player cannot buy work).
TEST(a_flood_of_late_samples_is_tested_once_a_slot) {
  Game g;
  g.join(0, participant(1));
  g.join(1, participant(2));
  g.run(0.5);  // served: the rally is on
  CHECK(g.match.play().live);
  uint64_t before = g.match.counters().late_tested;
  double now = g.match.sim().time;
  int accepted = 0;
  for (int k = 0; k < 200; ++k) {
    RacketSampleIn s = g.parked_sample(1);
    s.capture_time = now - 0.09 + 0.0004 * k;  // in the past (after the newest parked one), inside the window
    accepted += g.match.on_sample(s, g.now) == SampleResult::accepted;
  }
  CHECK(g.match.has_late());
  MatchOutput out;
  g.match.compensate(&out);
  note("%d late samples accepted, %llu tested", accepted,
       (unsigned long long)(g.match.counters().late_tested - before));
  CHECK(accepted >= 100);
  CHECK_EQ(g.match.counters().late_tested - before, 1u);
  CHECK(!g.match.has_late());
}

int main(int argc, char **argv) { return check::run(argc, argv); }
