// The server loop without a network or a clock (server_loop.h): a fake
// clock that sleeps exactly (and stalls on request), a fake port that
// takes queued input, records every write and makes each wake-up's work
// take a chosen time. Due frames, the frame clock's lateness, overruns,
// skips after a stall, the percentiles of the status line, the books of
// the samples, refused writes, CREATE, a busy domain and conflicts, all
// checked with numbers worked out by hand; and a rally of two bots through
// the loop, whose clock pairs must lie on one line.
#include <algorithm>
#include <cmath>
#include <deque>
#include <functional>
#include <map>

#include "bot.h"
#include "check.hpp"
#include "game.h"
#include "rally.h"
#include "rng.h"
#include "fake_port.h"
#include "client_feed.h"
#include "server_loop.h"

using namespace test;
using check::note;

namespace {

// A host of matches at the given frame rates (ids 0, 1, ...), a fake clock
// and port, a loop started at kStart.
struct Rig {
  Host host{16, true, default_config()};
  FakeClock clock;
  FakePort port;
  LoopSettings settings;
  std::unique_ptr<ServerLoop> loop;
  // (state_rate: every match's ball states per s; 0: its frame rate)
  explicit Rig(std::vector<double> rates, double status_interval = 1.0, double state_rate = 0.0,
               const MatchConfig &base = default_config()) {
    ball_scene scene;
    ball_scene_default(&scene);
    std::string err;
    host.add_scene("tennis", scene, &err);
    for (size_t i = 0; i < rates.size(); ++i) {
      MatchConfig c = base;
      c.id = static_cast<uint32_t>(i);
      c.frame_rate = rates[i];
      c.state_rate = state_rate > 0.0 ? state_rate : rates[i];
      host.add_match(c, scene, &err);
    }
    port.clock = &clock;
    settings.server_id = 5;
    settings.status_interval = status_interval;
    loop = std::make_unique<ServerLoop>(host, port, clock, settings);
    loop->start();
  }
  // wake-ups until the next one would be at or after mono t
  int run_until(double t) {
    int n = 0;
    while (loop->next_wake() < t - 1e-9) {
      loop->step();
      n++;
    }
    return n;
  }
};

ControlIn join(uint32_t match, int slot, ParticipantId who) {
  ControlIn c;
  c.match_id = match;
  c.kind = ControlKind::join;
  c.player = slot;
  c.from = who;
  return c;
}

}  // namespace

// Where a LoopRally plays: by default alone, with samples 50 to 100 ms late
// from bots that swing late, as people do (hits at their instant and
// rewinds); or after `others` idle matches (the rally is the last), with
// samples `trip` late from bots that plan ahead of it.
struct Crowd {
  int others = 0;
  double trip = 0.1;  // s, the most a sample takes (each takes 0.5 to 1 times it)
  bool plan_ahead = false;
  double per_read = 0.0;  // s each reading of the clock takes (FakeClock::per_read)
};

// Two bots play a MID-level match of 20 s through the loop, their samples
// at 15 Hz on the clock the states give them, arriving 50 to 100 ms late:
// hits stepped at their instant and rewinds for late samples both come.
struct LoopRally {
  Rig r;
  MatchConfig c;
  uint32_t id;  // the rally's match
  // (each_wake: called after every wake-up, to give the loop more input)
  LoopRally(uint64_t seed, double hit_lead, const std::function<void(Rig &)> &each_wake = nullptr,
            bool own_hit = false, Crowd crowd = {})
      : r(std::vector<double>(static_cast<size_t>(crowd.others) + 1, 60.0), 1.0, 0.0, base(seed, hit_lead, own_hit)),
        c(r.host.find(static_cast<uint32_t>(crowd.others))->config()),
        id(static_cast<uint32_t>(crowd.others)) {
    const double trip = crowd.trip;
    const ParticipantId who[2] = {participant(1), participant(2)};
    r.port.controls = {join(id, 0, who[0]), join(id, 1, who[1])};
    BotBrain brain[2];
    for (int i = 0; i < 2; ++i) {
      BotParams p;
      p.slot = i;
      p.seed = seed * 11 + static_cast<uint64_t>(i);
      // (unaware of the trip, their hits come late, and rewind the match)
      p.lead = crowd.plan_ahead ? bot_lead(15.0, trip, 0.0, 0.0) : kLateSwing;
      p.aim_error = 0.02;
      brain[i].init(r.host.find(id)->model(), r.host.find(id)->court(), p);
    }
    ClientFeed feed(id);
    size_t given = 0, looked = 0;
    size_t st = SIZE_MAX;  // the rally's newest ball state
    uint32_t seq[2] = {0, 0};
    double next_sample = kStart;
    std::deque<std::pair<double, RacketSampleIn>> on_the_way;  // (mono s of arrival, sample)
    Rng jitter(seed);
    r.clock.per_read = crowd.per_read;
    while (r.clock.now < kStart + 20.0) {
      r.loop->step();
      if (each_wake) each_wake(r);
      while (!on_the_way.empty() && on_the_way.front().first <= r.clock.now) {
        r.port.samples.push_back(on_the_way.front().second);
        on_the_way.pop_front();
      }
      for (; looked < r.port.states.size(); ++looked)
        if (r.port.states[looked].match_id == id) st = looked;
      if (st == SIZE_MAX) continue;
      // the bots' clock: the newest state's pair
      const StateOut &newest = r.port.states[st];
      double sim_now = newest.sim_time + (r.clock.realtime() - newest.server_time) * c.time_base;
      for (; given < r.port.segments.size(); ++given)
        if (r.port.segments[given].match_id == id) feed.add(r.port.segments[given]);
      if (const SegmentOut *s = feed.due(sim_now))
        for (int i = 0; i < 2; ++i) brain[i].on_segment(s->segment, s->cause == Cause::serve, s->cause_index, sim_now);
      if (r.clock.now < next_sample) continue;
      next_sample += 1.0 / 15.0;
      for (int i = 0; i < 2; ++i) {
        RacketSampleIn s;
        s.match_id = id;
        s.player = i;
        s.seq = ++seq[i];
        s.capture_time = sim_now;
        brain[i].pose(sim_now, &s.center, &s.normal);
        s.from = who[i];
        s.source_time = r.clock.realtime();
        on_the_way.push_back({r.clock.now + trip * jitter.uniform(0.5, 1.0), s});
      }
    }
    r.loop->finish();
  }
  static MatchConfig base(uint64_t seed, double hit_lead, bool own_hit) {
    MatchConfig b = default_config();
    b.level = BALL_LEVEL_MID;
    b.seed = seed;
    b.hit_lead = hit_lead;
    b.rewind_own_hit = own_hit;
    return b;
  }
  // the (sim_time, server_time) pairs of the playing match: its ball states first
  std::vector<std::pair<double, double>> pairs(size_t *states) const {
    std::vector<std::pair<double, double>> out;
    for (const StateOut &s : r.port.states)
      if (s.match_id == id && s.state == MatchState::playing) out.push_back({s.sim_time, s.server_time});
    *states = out.size();
    for (const MatchInfoOut &i : r.port.infos)
      if (i.match_id == id && i.state == MatchState::playing) out.push_back({i.sim_time, i.server_time});
    return out;
  }
};

// Every (sim_time, server_time) pair a playing match writes, in its
// MatchInfo and its ball states, says where its sim clock is: they all lie
// on one line sim = sim_0 + (server - server_0) * time_base
// (docs/protocol.md, "Time"), also those written after a hit stepped the
// match between frames (hit_lead before its instant) or a late sample
// rewound it (a rewind writes a MatchInfo at once).
TEST(every_clock_pair_of_a_playing_match_lies_on_one_line) {
  uint64_t steps = 0, rewinds = 0;
  for (uint64_t seed = 1; seed <= 6; ++seed) {
    LoopRally g(seed, default_config().hit_lead);
    size_t states = 0;
    std::vector<std::pair<double, double>> pairs = g.pairs(&states);
    CHECK(states > 1000u);
    double worst = 0.0;
    for (const auto &p : pairs)
      worst = std::max(worst, std::fabs(p.first - (pairs[0].first + (p.second - pairs[0].second) * g.c.time_base)));
    const MatchCounters &k = g.r.host.find(0)->counters();
    note("seed %llu: %zu states and %zu infos while playing, %llu hits (%llu stepped at their instant, "
         "%llu rewinds): largest distance from the line %.3g s",
         static_cast<unsigned long long>(seed), states, pairs.size() - states, static_cast<unsigned long long>(k.hits),
         static_cast<unsigned long long>(k.hit_steps), static_cast<unsigned long long>(k.rewinds), worst);
    steps += k.hit_steps;
    rewinds += k.rewinds;
    CHECK(worst <= 1e-6);  // (server times near 1.7e9 s are doubles 2.4e-7 s apart)
  }
  CHECK(steps >= 10u && rewinds >= 10u);  // both ways of stepping between frames were taken
}

// A MatchInfo due between a hit's partial step and the next frame (a
// LEVEL control comes then: the loop takes controls before it steps
// frames) waits for that frame: every MatchInfo's pair is a frame's, on the
// line and with a server_time not after its write (the clients' minimum
// filter, docs/protocol.md "Time"), and none is lost.
TEST(a_match_info_due_after_a_hit_step_waits_for_the_frame) {
  size_t asked = 0, answered = 0, checked = 0;
  for (uint64_t seed = 1; seed <= 8; ++seed) {
    uint64_t wakes = 0;
    std::vector<double> asked_at;  // mono s
    LoopRally g(seed, default_config().hit_lead, [&](Rig &r) {
      if (r.loop->stats().hit_wakes == wakes) return;
      wakes = r.loop->stats().hit_wakes;
      ControlIn c = join(0, 0, participant(1));  // the holder of slot 0 asks for the level it has
      c.kind = ControlKind::level;
      c.level = BALL_LEVEL_MID;
      r.port.controls.push_back(c);
      asked_at.push_back(r.clock.now);
    });
    size_t states = 0;
    std::vector<std::pair<double, double>> pairs = g.pairs(&states);
    CHECK(states > 1000u);
    if (pairs.empty()) continue;
    const double frame = 1.0 / g.c.frame_rate;
    const std::vector<MatchInfoOut> &infos = g.r.port.infos;
    for (size_t k = 0; k < infos.size(); ++k) {
      const MatchInfoOut &i = infos[k];
      if (i.state != MatchState::playing) continue;
      checked++;
      double off = i.sim_time - (pairs[0].first + (i.server_time - pairs[0].second) * g.c.time_base);
      double into = std::fmod(i.sim_time - pairs[0].first, frame);
      CHECK_MSG(std::fabs(off) <= 1e-6 && (into <= 1e-6 || frame - into <= 1e-6),
                "a MatchInfo %.4g s off the line, its sim_time %.4g s into a frame", off, into);
      CHECK_MSG(i.server_time <= g.r.port.info_mono[k] + kRealOffset + 1e-6, "a MatchInfo stamped %.4g s ahead",
                i.server_time - g.r.port.info_mono[k] - kRealOffset);
    }
    // each LEVEL asked after a hit's step is answered with the next frame
    for (double t : asked_at) {
      asked++;
      for (double w : g.r.port.info_mono)
        if (w >= t && w <= t + frame + 1e-6) {
          answered++;
          break;
        }
    }
  }
  note("%zu LEVELs asked after a hit's step, %zu answered by a MatchInfo within a frame; %zu playing MatchInfos on "
       "the line",
       asked, answered, checked);
  CHECK(asked >= 10u);
  CHECK_EQ(answered, asked);
}

// A hit stepped between frames is written hit_lead before its instant: the
// loop wakes then (the fake clock wakes exactly), steps the match to the
// instant and writes the segment, whose t0 maps to the loop's clock by the
// states' line. A hit that a frame's look finds less than hit_lead ahead is
// stepped at once, at that frame's deadline; one that a frame's own step
// finds (a sample came after the look) is written at the frame's deadline,
// after its instant. No racket segment is written more than hit_lead early.
TEST(a_hit_is_written_hit_lead_before_its_instant) {
  for (double lead : {0.0, 0.002, 0.005}) {
    size_t on_lead = 0, early = 0, racket = 0;
    for (uint64_t seed = 1; seed <= 8; ++seed) {
      LoopRally g(seed, lead);
      size_t states = 0;
      std::vector<std::pair<double, double>> pairs = g.pairs(&states);
      CHECK(!pairs.empty());
      if (pairs.empty()) continue;
      const double frame = 1.0 / g.c.frame_rate;
      for (size_t i = 0; i < g.r.port.segments.size(); ++i) {
        const SegmentOut &s = g.r.port.segments[i];
        if (s.cause != Cause::racket || s.correction) continue;
        racket++;
        // the instant on the loop's clock: the states' line, back from sim to real time
        double instant = pairs[0].second - kRealOffset + (s.segment.t0 - pairs[0].first) / g.c.time_base;
        double ahead = instant - g.r.port.segment_mono[i];
        double into_frame = std::fmod(g.r.port.segment_mono[i] - kStart, frame);
        bool on_deadline = into_frame <= 1e-6 || frame - into_frame <= 1e-6;
        CHECK_MSG(ahead <= lead + 1e-6, "lead %g: a racket segment written %.4g s before its instant", lead, ahead);
        if (std::fabs(ahead - lead) <= 1e-6 && !on_deadline) {
          on_lead++;
        } else {
          CHECK_MSG(on_deadline, "lead %g: a racket segment written %.4g s before its instant, %.4g s into a frame",
                    lead, ahead, into_frame);
        }
        if (ahead > 1e-6) early++;
      }
    }
    note("hit_lead %g s: %zu racket segments, %zu written hit_lead before their instant between frames, %zu before "
         "it at all",
         lead, racket, on_lead, early);
    CHECK(on_lead >= 3u);
    CHECK(lead > 0.0 ? early >= on_lead : early == 0u);
  }
}

// Why a hit's step was late (the stats file's hit_known, hit_wake_late_p99,
// hit_found_after; docs/server-design.md, "Hits at their instant"): every hit
// stepped between frames is one the loop knew before it was due (its
// instant less hit_lead), one it first saw within the lead, or one it first
// saw after its instant (a sample that came after it). The fake clock
// wakes exactly, or `over` late at every sleep: a known hit's step begins
// that much after its due time, never more (its wake-up may be a frame's,
// less late for the hit). A hit first seen after its instant is written
// after it. (Here the samples come 50 to 100 ms late: most hits are
// rewinds', and of those stepped between frames many were first seen late.)
TEST(a_hit_steps_lateness_is_the_wake_ups_or_its_samples) {
  for (double over : {0.0, 0.0007}) {
    uint64_t wakes = 0, known = 0, after = 0;
    size_t written_after = 0;
    double worst = 0.0, median = 0.0, found_late = 0.0;
    for (uint64_t seed = 1; seed <= 8; ++seed) {
      LoopRally g(seed, default_config().hit_lead, [&](Rig &r) {
        if (over > 0.0) r.clock.oversleep[r.clock.sleeps] = over;
      });
      const ServerReport rep = g.r.loop->report();
      const LoopStats &st = g.r.loop->stats();
      CHECK_EQ(rep.hit_known, static_cast<uint64_t>(st.hit_wake_late.size()));
      CHECK(rep.hit_known + rep.hit_found_after <= rep.hit_wakes);
      wakes += rep.hit_wakes;
      known += rep.hit_known;
      after += rep.hit_found_after;
      CHECK_EQ(rep.hit_found_after, static_cast<uint64_t>(st.hit_found_late.size()));
      // (first seen after the instant, stepped no earlier than that)
      CHECK(st.hit_found_late.size() == 0 || st.hit_found_late.quantile(0.0) > 0.0);
      CHECK(rep.hit_found_late_p50 <= rep.hit_found_late_p99);
      found_late = std::max(found_late, st.hit_found_late.max());
      worst = std::max(worst, st.hit_wake_late.max());
      median = std::max(median, st.hit_wake_late.quantile(0.5));
      size_t states = 0;
      std::vector<std::pair<double, double>> pairs = g.pairs(&states);
      if (pairs.empty()) continue;
      for (size_t i = 0; i < g.r.port.segments.size(); ++i) {
        const SegmentOut &s = g.r.port.segments[i];
        if (s.cause != Cause::racket || s.correction) continue;
        double instant = pairs[0].second - kRealOffset + (s.segment.t0 - pairs[0].first) / g.c.time_base;
        if (g.r.port.segment_mono[i] > instant + 1e-6) written_after++;
      }
    }
    note("every sleep %g s late: %llu hits stepped between frames, %llu known before due (their steps at most %.3g s "
         "after it, median %.3g s), %llu first seen after their instant (stepped up to %.3g s after it); %zu racket "
         "segments written after it",
         over, static_cast<unsigned long long>(wakes), static_cast<unsigned long long>(known), worst, median,
         static_cast<unsigned long long>(after), found_late, written_after);
    CHECK(known >= 3u && after >= 3u && known + after <= wakes);
    CHECK(worst <= over + 1e-9);
    CHECK(over == 0.0 ? worst >= 0.0 : median >= over - 1e-9);  // a known hit wakes for itself
    CHECK(after <= written_after);
  }
}

// A hit early in a frame while many matches share its deadline: the loop
// runs first the frames of the matches a racket may hit before the next
// frame's end (Match::near_hit), so that such a hit is found as soon as the
// deadline's wake-up begins rather than after every other match's frame.
// The rally comes after 15 idle matches and every reading of the clock
// takes 0.25 ms (in the matches' order its frame ends 4 ms after the
// deadline); the samples take 0.5 to 1 ms, the bots plan ahead of that.
// Alone on a free clock no racket segment comes after its instant; in the
// crowd the late ones are those whose instant fell within the wake-up's and
// the frame's two readings, written at most those 0.5 ms after it (in the
// matches' order: 18 of 64 late, by up to 4.2 ms).
TEST(a_match_near_a_hit_has_its_frame_first) {
  const double per_read = 2.5e-4;
  size_t racket[2] = {0, 0}, late[2] = {0, 0};
  double worst[2] = {0.0, 0.0};
  for (uint64_t seed = 1; seed <= 4; ++seed)
    for (int crowded = 0; crowded < 2; ++crowded) {
      Crowd crowd;
      crowd.others = crowded ? 15 : 0;
      crowd.trip = 0.001;
      crowd.plan_ahead = true;
      crowd.per_read = crowded ? per_read : 0.0;
      LoopRally g(seed, default_config().hit_lead, nullptr, false, crowd);
      size_t states = 0;
      std::vector<std::pair<double, double>> pairs = g.pairs(&states);
      CHECK(states > 100u);
      if (pairs.empty()) continue;
      for (size_t i = 0; i < g.r.port.segments.size(); ++i) {
        const SegmentOut &s = g.r.port.segments[i];
        if (s.match_id != g.id || s.cause != Cause::racket || s.correction) continue;
        double instant = pairs[0].second - kRealOffset + (s.segment.t0 - pairs[0].first) / g.c.time_base;
        double after = g.r.port.segment_mono[i] - instant;
        racket[crowded]++;
        if (after > 1e-6) late[crowded]++;
        worst[crowded] = std::max(worst[crowded], after);
      }
    }
  note("racket segments written after their instant: alone %zu of %zu (at most %.3g s after), after 15 matches' "
       "frames %zu of %zu (at most %.3g s)",
       late[0], racket[0], worst[0], late[1], racket[1], worst[1]);
  CHECK(racket[0] >= 40u && racket[1] >= 40u);
  CHECK_EQ(late[0], 0u);
  CHECK(worst[1] <= 2.0 * per_read + 1e-9);
}

// A hit ends its racket's stroke (docs/server-design.md, "Lag compensation"):
// with samples 50 to 100 ms late, the samples of the stroke that arrive
// after the hit are dropped as before_hit, so that at every wake-up a
// racket's track holds only samples captured at or after its last hit, and
// no racket hits again on what was known before its last hit (each racket
// hit's newest sample is captured at or after the same racket's hit before
// it). Without the rule, 24 of the 203 racket segments of these rallies
// were such second hits: the stroke carried on past the hit by eq 15 found
// the ball again once the racket tests woke, three frames on.
TEST(a_hit_ends_its_rackets_stroke) {
  int hits = 0, again = 0, on_old_news = 0, wakes = 0, old_on_track = 0;
  uint64_t before_hit = 0;
  for (uint64_t seed = 1; seed <= 10; ++seed) {
    double last_hit[2] = {-1e300, -1e300};
    size_t seen = 0;
    LoopRally g(seed, default_config().hit_lead, [&](Rig &r) {
      for (; seen < r.port.segments.size(); ++seen) {
        const SegmentOut &s = r.port.segments[seen];
        if (s.cause == Cause::racket && s.cause_index >= 0 && s.cause_index < 2)
          last_hit[s.cause_index] = std::fmax(last_hit[s.cause_index], s.segment.t0);
      }
      const ball_sim &sim = r.host.find(0)->sim();
      for (int k = 0; k < 2; ++k)
        for (int i = 0; i < sim.tracks[k].count; ++i) old_on_track += sim.tracks[k].samples[i].t < last_hit[k];
      wakes++;
    });
    before_hit += g.r.loop->status_now().drops[static_cast<int>(SampleResult::before_hit)];
    const SegmentOut *prev[2] = {nullptr, nullptr};
    for (const SegmentOut &s : g.r.port.segments) {
      if (s.cause != Cause::racket || s.cause_index < 0 || s.cause_index > 1) continue;
      hits++;
      const SegmentOut *p = prev[s.cause_index];
      if (p && s.segment.t0 - p->segment.t0 < 0.3) again++;
      if (p && s.sample.capture_time < p->segment.t0) on_old_news++;
      prev[s.cause_index] = &s;
    }
  }
  note("10 rallies: %d racket segments, %d of them within 0.3 s of the same racket's hit before, %d on samples "
       "from before it; %llu samples before_hit; %d wake-ups, %d samples from before a racket's last hit on its track",
       hits, again, on_old_news, (unsigned long long)before_hit, wakes, old_on_track);
  CHECK(hits >= 150);
  CHECK(before_hit >= 25);
  CHECK_EQ(on_old_news, 0);
  CHECK_EQ(old_on_track, 0);
}

// With rewind_own_hit (docs/server-design.md, "Lag compensation") the samples a
// hit's stroke sends after it may move the hit, earlier or later: the same
// rallies as above, taken as a client takes them (a segment supersedes
// those written before it with a later t0), have no racket hitting again
// within 0.3 s of its own hit, where a hit that ends its stroke leaves a
// few (a hit found early on an extrapolated track stands, and the racket's
// true path meets the ball again on its way back); the stroke's samples
// that come after the hit inside the window are kept, not dropped.
TEST(a_rewind_past_its_own_hit_leaves_no_second_hit) {
  int hits[2] = {0, 0}, again[2] = {0, 0};
  uint64_t moved = 0, before_hit[2] = {0, 0};
  std::vector<double> shift_t, shift_v;  // how far moved hits moved: s, m/s of the outgoing velocity
  for (int own = 0; own < 2; ++own)
    for (uint64_t seed = 1; seed <= 10; ++seed) {
      LoopRally g(seed, default_config().hit_lead, nullptr, own == 1);
      std::vector<SegmentOut> seen;  // in effect, as a client has them
      for (const SegmentOut &s : g.r.port.segments) {
        while (!seen.empty() && seen.back().segment.t0 > s.segment.t0) seen.pop_back();
        seen.push_back(s);
      }
      const SegmentOut *prev[2] = {nullptr, nullptr};
      for (const SegmentOut &s : seen) {
        if (s.cause != Cause::racket || s.cause_index < 0 || s.cause_index > 1) continue;
        const SegmentOut *p = prev[s.cause_index];
        if (p && p->segment.t0 == s.segment.t0) continue;  // written again
        hits[own]++;
        if (p && s.segment.t0 - p->segment.t0 < 0.3) again[own]++;
        prev[s.cause_index] = &s;
      }
      // each moved hit against the one it moved: the same racket's hit written last, within 0.3 s
      const SegmentOut *last[2] = {nullptr, nullptr};
      for (const SegmentOut &s : g.r.port.segments) {
        if (s.cause != Cause::racket || s.cause_index < 0 || s.cause_index > 1) continue;
        const SegmentOut *p = last[s.cause_index];
        if (own && s.correction && p && p->segment.t0 != s.segment.t0 && std::fabs(s.segment.t0 - p->segment.t0) < 0.3) {
          shift_t.push_back(std::fabs(s.segment.t0 - p->segment.t0));
          shift_v.push_back(ball_v3_dist(s.segment.v0, p->segment.v0));
        }
        last[s.cause_index] = &s;
      }
      if (own) moved += g.r.host.find(0)->counters().rewinds_past_own_hit;
      before_hit[own] += g.r.loop->status_now().drops[static_cast<int>(SampleResult::before_hit)];
    }
  note("10 rallies: a hit ends its stroke: %d racket hits, %d within 0.3 s of the same racket's; rewind_own_hit: %d "
       "hits, %d within 0.3 s, %llu rewinds past the racket's own hit; samples before_hit %llu and %llu",
       hits[0], again[0], hits[1], again[1], (unsigned long long)moved, (unsigned long long)before_hit[0],
       (unsigned long long)before_hit[1]);
  std::sort(shift_t.begin(), shift_t.end());
  std::sort(shift_v.begin(), shift_v.end());
  if (!shift_t.empty())
    note("%zu hits moved: by %.4f s (median) and %.4f s (most), their outgoing velocity by %.3f and %.3f m/s",
         shift_t.size(), shift_t[shift_t.size() / 2], shift_t.back(), shift_v[shift_v.size() / 2], shift_v.back());
  CHECK(hits[0] >= 150);
  CHECK(hits[1] >= 150);
  CHECK(moved >= 20);
  CHECK_EQ(again[1], 0);
  // (the samples of the stroke inside the window are kept, not dropped)
  CHECK(before_hit[1] * 2 < before_hit[0]);
}

TEST(frames_come_at_their_deadlines) {
  Rig r({60.0, 30.0});
  CHECK_EQ(r.port.infos.size(), 2u);  // every match announced at the start
  int wakes = r.run_until(kStart + 1.0);
  // deadlines kStart + k/60 and kStart + k/30 in [kStart, kStart + 1): the
  // 30 Hz ones fall on 60 Hz wake-ups
  CHECK_EQ(wakes, 60);
  CHECK_EQ(r.loop->stats().totals.frames, 90u);
  CHECK_EQ(r.loop->stats().totals.overruns, 0u);
  CHECK_EQ(r.loop->stats().skipped, 0u);
  CHECK_EQ(r.loop->stats().late_max, 0.0);  // the fake clock wakes exactly on time
  CHECK_NEAR(r.clock.now, kStart + 59.0 / 60.0, 1e-9);
  // and match 0's MatchInfo once more at its first frame: the periodic ones
  // come 4 s apart, spread over the interval by id (match 1's at kStart + 2.47)
  CHECK_EQ(r.port.infos.size(), 3u);
  CHECK_EQ(r.port.infos[2].revision, 2u);
  CHECK_EQ(r.port.infos[0].server_id, 5u);
  CHECK_EQ(r.port.statuses.size(), 0u);
}

// Matches write their ball states on frames of their own (a phase from the
// id), not all on the same frame: 12 matches at 60 Hz with states at 10 Hz
// write 2 states a frame, not 12 every sixth frame. And a wake-up writes its
// states after its frames: the frames' segments and hits go out first.
TEST(matches_write_their_states_on_different_frames) {
  Rig r(std::vector<double>(12, 60.0), 1.0, 10.0);
  for (uint32_t m = 0; m < 12; ++m)
    for (int slot = 0; slot < 2; ++slot)
      r.port.controls.push_back(join(m, slot, participant(static_cast<uint8_t>(2 * m + slot + 1))));
  r.run_until(kStart + 0.5);  // every match playing
  for (uint32_t m = 0; m < 12; ++m) CHECK(r.host.find(m)->state() == MatchState::playing);
  size_t before = r.port.states.size(), worst = 0;
  int segments_too = 0;
  for (int k = 0; k < 60; ++k) {
    size_t b = r.port.states.size();
    r.port.written.clear();
    r.loop->step();
    worst = std::max(worst, r.port.states.size() - b);
    // the wake-up's segments and events were written before its states
    size_t first_state = r.port.written.find('b');
    if (first_state != std::string::npos) CHECK_EQ(r.port.written.find_first_of("se", first_state), std::string::npos);
    segments_too += first_state != std::string::npos && first_state > 0;
  }
  CHECK(segments_too >= 1);  // (a wake-up with both, at least)
  check::note("%zu states in 60 frames, at most %zu in one; %d wake-ups wrote segments or events and states",
              r.port.states.size() - before, worst, segments_too);
  CHECK(r.port.states.size() - before >= 60u);  // 12 matches x 10 Hz while they play (half a second at least)
  CHECK(worst <= 3);                               // (12 in one frame, none in the next five, before)
}

TEST(the_status_comes_once_an_interval) {
  Rig r({60.0, 30.0});
  r.run_until(kStart + 1.0);
  CHECK(r.loop->step());  // the wake-up at kStart + 1: two frames, then the status
  CHECK_EQ(r.port.statuses.size(), 1u);
  const StatusOut &s = r.port.statuses[0];
  CHECK_EQ(s.frames, 92u);
  CHECK_EQ(s.matches, 2u);
  CHECK_EQ(s.playing, 0u);
  CHECK_EQ(s.server_id, 5u);
  CHECK_NEAR(s.uptime, 1.0, 1e-9);
  CHECK_NEAR(s.server_time, kStart + 1.0 + kRealOffset, 1e-6);
  // and each match's periodic MatchInfo, 4 s apart and spread over them by id
  // (the golden ratio): match 0's at kStart, match 1's at kStart + 2.47
  CHECK_EQ(r.port.infos.size(), 3u);
  r.run_until(kStart + 2.0);
  CHECK(r.loop->step());
  CHECK_EQ(r.port.statuses.size(), 2u);
  CHECK_EQ(r.port.statuses[1].frames, 182u);
  std::string line = status_line(r.loop->status());
  CHECK_MSG(line.find("ball-server 5: 2 s, matches 2 (0 playing)") == 0, "%s", line.c_str());
  CHECK_MSG(line.find("failed writes 0, overruns 0") != std::string::npos, "%s", line.c_str());
  r.run_until(kStart + 2.55);
  CHECK_EQ(r.port.infos.size(), 4u);  // match 1's, at its first frame after kStart + 2.47
  r.run_until(kStart + 4.05);
  CHECK_EQ(r.port.infos.size(), 5u);  // match 0's, 4 s after its first
}

TEST(percentiles_of_the_work_per_wake_up) {
  Rig r({10.0});
  // wake-ups at 0, 0.1, ..., 1.0 s (the last one closes the period):
  // 1, 2, ..., 11 ms of work
  for (int i = 0; i <= 10; ++i) r.port.work[i] = (i + 1) * 1e-3;
  r.run_until(kStart + 1.0);
  CHECK(r.loop->step());
  const StatusOut &s = r.port.statuses.at(0);
  // 11 values: p50 is the one of rank round(0.5 * 10) = 5 (6 ms), p99 of rank round(9.9) = 10 (11 ms)
  CHECK_NEAR(s.frame_p50, 6e-3, 1e-9);
  CHECK_NEAR(s.frame_p99, 11e-3, 1e-9);
  CHECK_EQ(s.overruns, 0u);
  CHECK_EQ(r.loop->stats().late_max, 0.0);
  // the next period starts afresh
  r.run_until(kStart + 2.0);
  CHECK(r.loop->step());
  CHECK_NEAR(r.port.statuses.at(1).frame_p99, 0.0, 1e-9);
}

TEST(a_frame_done_after_the_next_deadline_is_an_overrun) {
  Rig r({10.0});
  r.port.work[3] = 0.15;  // the frame at 0.3 s ends at 0.45 s, after the deadline at 0.4 s
  r.run_until(kStart + 1.0);
  const LoopStats &st = r.loop->stats();
  CHECK_EQ(st.totals.overruns, 1u);
  CHECK_NEAR(st.late_max, 0.05, 1e-9);  // the frame of 0.4 s starts at 0.45 s
  CHECK_EQ(st.skipped, 0u);
  CHECK_EQ(st.totals.frames, 10u);  // no frame lost: 0, 0.1, ..., 0.9 s
}

TEST(a_stall_of_more_than_five_frames_skips_to_the_present) {
  Rig r({10.0});
  r.clock.oversleep[3] = 0.63;  // the wake-up for 0.3 s comes at 0.93 s: 6.3 frames behind
  r.run_until(kStart + 1.0);
  const LoopStats &st = r.loop->stats();
  CHECK_EQ(st.skipped, 6u);         // frames 3 to 8
  CHECK_EQ(st.totals.frames, 4u);          // 0, 0.1, 0.2, then 0.9 s at 0.93 s
  CHECK_NEAR(st.late_max, 0.03, 1e-9);
  CHECK_EQ(st.totals.overruns, 0u);
  // a stall of 4.3 frames is caught up, one frame a wake-up
  Rig q({10.0});
  q.clock.oversleep[3] = 0.43;
  q.run_until(kStart + 1.0);
  CHECK_EQ(q.loop->stats().skipped, 0u);
  CHECK_EQ(q.loop->stats().totals.frames, 10u);
  CHECK_NEAR(q.loop->stats().late_max, 0.43, 1e-9);
  CHECK_EQ(q.loop->stats().totals.overruns, 4u);  // the frames of 0.3 to 0.6 s end after their next deadline
}

TEST(samples_and_notes_balance_the_books) {
  Rig r({60.0});
  const ParticipantId A = participant(1), B = participant(2), C = participant(3);
  r.port.controls = {join(0, 0, A), join(0, 1, B)};
  r.loop->step();  // the controls, then the frame: both present, the match serves
  CHECK_EQ(r.loop->stats().totals.controls_in, 2u);
  CHECK_EQ(r.port.events.size(), 3u);
  CHECK(r.port.events[0].kind == EventKind::join && r.port.events[1].kind == EventKind::join);
  CHECK(r.port.events[2].kind == EventKind::serve);
  CHECK_EQ(r.port.events[0].server_id, 5u);
  r.run_until(kStart + 0.5);
  CHECK(r.host.find(0)->state() == MatchState::playing);
  CHECK(!r.port.segments.empty());  // the serve
  CHECK_EQ(r.port.segments[0].cause, Cause::serve);
  CHECK_EQ(r.port.segments[0].server_id, 5u);
  // a state's server time is its frame's deadline on the realtime clock
  const StateOut &st = r.port.states.at(3);
  CHECK_EQ(st.frame, 4u);  // the fourth frame stepped, at the deadline of frame index 3
  CHECK_NEAR(st.server_time - kRealOffset - kStart, 3.0 / 60.0, 1e-6);
  Game shape;  // a parked sample, as the tests' players send them
  RacketSampleIn good = shape.parked_sample(0);
  good.match_id = 0;
  good.capture_time = r.host.find(0)->sim().time;
  good.from = A;
  RacketSampleIn stranger = good, nowhere = good, second = good, third = good, full = good;
  stranger.from = C;
  nowhere.match_id = 99;
  second.seq = good.seq + 1;
  second.capture_time += 0.001;
  third.seq = good.seq + 4;  // two of the holder's seqs skipped: gaps, lost unless they come late
  third.capture_time += 0.002;
  full.seq = good.seq + 5;   // found the reader full: rejected, and not lost as well
  full.rejected = true;
  r.port.samples = {good, stranger, nowhere, good, second, third, full};
  // DDS's own gap count is kept apart (the stream's seqs count `lost`)
  r.port.notes = {{PortNote::rejected, {}, 3}, {PortNote::lost, {}, 2}, {PortNote::deadline_missed, {}, 1}};
  r.loop->step();
  const LoopStats &s = r.loop->stats();
  CHECK_EQ(s.totals.samples_in, 7u + 3u);
  CHECK_EQ(s.totals.samples_ok, 3u);
  CHECK_EQ(s.totals.drops[static_cast<int>(SampleResult::not_owner)], 1u);
  CHECK_EQ(s.totals.drops[static_cast<int>(SampleResult::unknown_match)], 1u);
  CHECK_EQ(s.totals.drops[static_cast<int>(SampleResult::duplicate)], 1u);
  CHECK_EQ(s.totals.drops[static_cast<int>(SampleResult::rejected)], 3u + 1u);
  CHECK_EQ(s.totals.drops[static_cast<int>(SampleResult::lost)], 0u);  // the gaps wait for late samples
  CHECK_EQ(s.totals.dds_lost, 2u);
  CHECK_EQ(s.deadline_missed, 1u);
  auto balanced = [&] {
    uint64_t dropped = 0;
    for (int i = 0; i < kDropReasons; ++i) dropped += s.totals.drops[i];
    return s.totals.samples_in == s.totals.samples_ok + s.totals.samples_idle + dropped;
  };
  CHECK(balanced());
  // the holder's next one after the rejected: no gap; one of the two skipped comes late
  RacketSampleIn next = full, late = good;
  next.rejected = false;
  next.seq = full.seq + 1;
  next.capture_time = third.capture_time + 0.001;
  late.seq = good.seq + 2;
  late.capture_time = second.capture_time + 0.0005;
  r.port.samples = {next, late};
  r.port.notes.clear();
  r.loop->step();
  CHECK_EQ(s.totals.drops[static_cast<int>(SampleResult::lost)], 0u);
  CHECK_EQ(s.totals.drops[static_cast<int>(SampleResult::out_of_order)], 1u);  // the late one, once
  CHECK_EQ(s.totals.samples_ok, 4u);
  CHECK(balanced());
  // the server stops: the gap still open is lost, the late one's is not
  r.loop->finish();
  CHECK_EQ(s.totals.drops[static_cast<int>(SampleResult::lost)], 1u);
  CHECK_EQ(s.totals.samples_in, 7u + 3u + 2u + 1u);
  CHECK(balanced());
  // a writer lost: its slot vanishes, the match pauses at the next frame
  r.port.notes = {{PortNote::writer_lost, B, 1}};
  r.loop->step();
  r.loop->step();
  CHECK_EQ(r.loop->stats().writers_lost, 1u);
  CHECK(r.host.find(0)->state() == MatchState::paused);
}

// Counters that do not lie: a gap DDS reports in one writer's sequence
// numbers is kept apart from the drops and counts at most kMaxLostPerNote
// (one forged datagram made it 2^31 - 1), controls DDS refused or lost are
// in and refused, and the books still balance.
TEST(dds_notes_count_what_they_can_mean) {
  Rig r({60.0});
  r.port.notes = {{PortNote::lost, {}, 2147483647ull}, {PortNote::rejected, {}, 5},
                  {PortNote::control_rejected, {}, 73}, {PortNote::control_lost, {}, 1ull << 40}};
  r.loop->step();
  const LoopStats &s = r.loop->stats();
  CHECK_EQ(s.totals.dds_lost, kMaxLostPerNote);
  CHECK_EQ(s.totals.drops[static_cast<int>(SampleResult::lost)], 0u);
  CHECK_EQ(s.totals.drops[static_cast<int>(SampleResult::rejected)], 5u);
  CHECK_EQ(s.totals.samples_in, 5u);
  CHECK_EQ(s.totals.controls_in, 73u + kMaxLostPerNote);
  CHECK_EQ(s.totals.controls_refused, 73u + kMaxLostPerNote);
  // what the readers' door turned away: a sample's first two checks, and refused controls
  r.port.notes = {{PortNote::door_unknown_match, {}, 7}, {PortNote::door_bad_slot, {}, 4},
                  {PortNote::door_control, {}, 9}};
  r.loop->step();
  CHECK_EQ(s.totals.drops[static_cast<int>(SampleResult::unknown_match)], 7u);
  CHECK_EQ(s.totals.drops[static_cast<int>(SampleResult::bad_slot)], 4u);
  CHECK_EQ(s.totals.samples_in, 5u + 7 + 4);
  CHECK_EQ(s.totals.controls_in, 73u + kMaxLostPerNote + 9);
  CHECK_EQ(s.totals.controls_refused, 73u + kMaxLostPerNote + 9);
  CHECK_EQ(s.controls_at_door, 9u);
}

// Percentiles keep at most kCap values, a uniform sample of all: a day of
// latencies costs no more memory than a second's worth, and the quantiles hold.
TEST(percentiles_are_bounded) {
  Percentiles p;
  const size_t n = 3 * Percentiles::kCap;
  for (size_t i = 0; i < n; ++i) p.add(static_cast<double>(i));
  CHECK_EQ(p.size(), n);
  CHECK_NEAR(p.quantile(0.5), 0.5 * n, 0.01 * n);
  CHECK_NEAR(p.quantile(0.99), 0.99 * n, 0.01 * n);
  CHECK(p.max() <= static_cast<double>(n - 1));
  p.clear();
  CHECK_EQ(p.size(), 0u);
}

// A created match nobody holds a slot of for create_timeout goes, its
// MatchInfo disposed; one a player joined stays.
TEST(a_created_match_nobody_joins_goes) {
  FakeClock clock;
  FakePort port;
  port.clock = &clock;
  Host host(8, true, default_config());
  ball_scene scene;
  ball_scene_default(&scene);
  std::string err;
  host.add_scene("tennis", scene, &err);
  LoopSettings s;
  s.create_timeout = 2.0;
  ServerLoop loop(host, port, clock, s);
  loop.start();
  ControlIn c;
  c.kind = ControlKind::create;
  c.scene = "tennis";
  c.players = 2;
  c.from = participant(5);
  c.match_id = 1030;
  port.controls.push_back(c);
  c.match_id = 1031;
  port.controls.push_back(c);
  loop.step();
  CHECK_EQ(host.matches().size(), 2u);
  port.controls.push_back(join(1031, 0, participant(6)));
  while (clock.now < kStart + 1.9) loop.step();
  CHECK_EQ(host.matches().size(), 2u);
  while (clock.now < kStart + 3.1) loop.step();  // the status at kStart + 3 looks
  CHECK(host.find(1030) == nullptr);
  CHECK(host.find(1031) != nullptr);
  CHECK(port.disposed == std::vector<uint32_t>{1030});
  CHECK_EQ(loop.report().created_expired, 1u);
  CHECK_EQ(loop.status_now().matches, 1u);
}

TEST(refused_writes_are_counted) {
  FakeClock clock;
  FakePort port;
  port.clock = &clock;
  port.refuse = true;
  Host host(4, false, default_config());
  ball_scene scene;
  ball_scene_default(&scene);
  std::string err;
  CHECK(host.add_match(default_config(), scene, &err));
  LoopSettings ls;
  ls.info_interval = 1.0;
  ServerLoop loop(host, port, clock, ls);
  loop.start();  // one MatchInfo and its MatchModel
  while (!loop.step()) {
  }  // its periodic MatchInfo at 0.326 s (id 7: 7 x 0.618 mod 1 of the interval) and the model again, then the status
  CHECK_EQ(loop.stats().totals.write_failures, 5u);
  CHECK_EQ(loop.stats().models_out, 0u);
  CHECK_EQ(port.models.size(), 0u);
  CHECK_EQ(loop.stats().infos_out, 0u);
  CHECK_EQ(port.infos.size(), 0u);
  port.refuse = false;
  loop.finish();
  CHECK_EQ(port.statuses.size(), 1u);
  CHECK_EQ(loop.report().status.write_failures, 5u);
}

TEST(a_create_schedules_the_new_match) {
  Rig r({60.0});
  ControlIn c;
  c.kind = ControlKind::create;
  c.match_id = 1008;
  c.scene = "tennis";
  c.players = 2;
  c.level = 1;
  r.port.controls = {c};
  r.run_until(kStart + 0.5);  // 30 wake-ups at 60 Hz
  CHECK_EQ(r.host.matches().size(), 2u);
  // created in the first wake-up's controls, before its frames: its first frame is due at once
  CHECK_EQ(r.loop->stats().totals.frames, 30u + 30u);
  CHECK_EQ(r.loop->stats().totals.controls_refused, 0u);
  c.match_id = 1009;
  c.scene = "nowhere";
  r.port.controls = {c};
  r.loop->step();
  CHECK_EQ(r.loop->stats().totals.controls_refused, 1u);
  CHECK_EQ(r.host.matches().size(), 2u);
  // the port's door: told the configured match at the first wake-up, the
  // created one with it after, and only when they change
  CHECK_EQ(r.port.admitted.size(), 2u);
  CHECK(r.port.admitted.front() == (std::vector<std::pair<uint32_t, int>>{{0, 2}}));
  CHECK(r.port.admitted.back() == (std::vector<std::pair<uint32_t, int>>{{0, 2}, {1008, 2}}));
  CHECK(r.port.admitted_creates.back() == (CreateIds{0, 4096}));  // the ids CREATEs may name
}

TEST(another_server_for_our_match) {
  Rig r({60.0});
  MatchInfoOut theirs = r.host.find(0)->info();  // a MatchInfo a server writes
  theirs.match_id = 99;  // not ours: no conflict
  theirs.server_id = 2;
  theirs.server_time = r.clock.realtime();  // (a server's clock is in step with ours)
  r.port.others.push_back({theirs, participant(9)});
  MatchInfoOut other;
  double t0 = r.clock.now;
  CHECK(!r.loop->find_owner(0.5, [] { return false; }, &other));
  CHECK(r.clock.now >= t0 + 0.5);  // it listened the whole wait
  theirs.match_id = 0;
  MatchInfoOut busy = theirs;  // numbers no server writes: nobody's, the match is not busy
  busy.players = 0;
  r.port.others.push_back({busy, participant(9)});
  CHECK(!r.loop->find_owner(0.2, [] { return false; }, &other));
  CHECK_EQ(r.loop->cluster().stats().others_refused, 1u);
  r.port.others.push_back({theirs, participant(9)});
  CHECK(r.loop->find_owner(0.5, [] { return false; }, &other));
  CHECK_EQ(other.server_id, 2u);
  // numbers no server writes (level 99): nobody's MatchInfo, however strong its writer
  MatchInfoOut forged = theirs;
  forged.level = 99;
  r.port.others.push_back({forged, participant(8)});
  r.loop->step();
  CHECK_EQ(r.loop->cluster().stats().others_refused, 2u);
  CHECK_EQ(r.loop->cluster().stats().yields, 0u);
  CHECK(r.host.find(0) != nullptr);
  // a MatchInfo of a participant whose ServerStatus was not heard: no server's yet, held back
  r.port.others.push_back({theirs, participant(9)});
  r.loop->step();
  CHECK_EQ(r.loop->cluster().stats().unknown_writers, 1u);
  CHECK_EQ(r.loop->cluster().stats().stale_terms, 0u);
  StatusOut st;
  st.server_id = 2;
  st.strength = 20;
  r.port.other_status.push_back({st, participant(9)});
  // an older term's owner (ours is round 1's, next_term(0, 1)): stale, nothing yielded
  r.port.others.push_back({theirs, participant(9)});
  r.loop->step();
  CHECK_EQ(r.loop->cluster().stats().stale_terms, 2u);  // (the one held back, heard again, and this one)
  CHECK(r.host.find(0) != nullptr);
  // a newer term's of a match this one is not (another model): nobody's, the match kept
  theirs.term = next_term(next_term(0, 1), 2);
  MatchInfoOut other_model = theirs;
  other_model.model_hash ^= 1;
  r.port.others.push_back({other_model, participant(9)});
  r.loop->step();
  CHECK_EQ(r.loop->cluster().stats().others_refused, 3u);
  CHECK_EQ(r.loop->cluster().stats().yields, 0u);
  CHECK(r.host.find(0) != nullptr && !r.host.find(0)->following());
  // while running, a newer term's (the next round): reported at the status, with the participant
  r.port.others.push_back({theirs, participant(9)});
  int seen = 0;
  ParticipantId who{};
  double end = r.clock.now + 1.5;
  r.loop->run(0.0, [&] { return r.clock.now > end; }, nullptr,
              [&](const MatchInfoOut &i, const ParticipantId &from) {
                seen += i.match_id == 0;
                who = from;
              });
  CHECK_EQ(seen, 1);
  CHECK(who == participant(9));
  CHECK_EQ(r.loop->cluster().stats().conflicts, 2u);  // (the other model's, refused, and this one)
  // a newer term owns the match (docs/protocol.md, "Terms"): we yield,
  // and follow it (to take it back if that owner is lost or goes silent)
  CHECK_EQ(r.loop->cluster().stats().yields, 1u);
  CHECK(r.host.find(0) != nullptr && r.host.find(0)->following());
  CHECK_EQ(r.loop->status_now().matches, 0u);
  CHECK_EQ(r.loop->status_now().following, 1u);
}

CHECK_MAIN
