// Two bots playing a Match offline, through links with delay, jitter, loss
// and tracker noise: the bots' and the rules' test without a network.
#pragma once

#include "bot.h"
#include "game.h"
#include "client_feed.h"
#include "link.h"

namespace test {

struct Net {
  double rate = 15.0;   // samples per s
  double delay = 0.0;   // s
  double jitter = 0.0;  // s
  double loss = 0.0;
  double noise = 0.0;   // m
  // the bots' swing: ahead of the delay (bot_lead with it), or as people
  // swing, unaware of it: the stroke line's last kLateSwing s only
  bool plan_ahead = true;
};
constexpr double kLateSwing = 0.12;  // s: a late swinger's stroke (a person's swing lasts about 0.1 s)

struct RallyResult {
  uint64_t hits = 0, bounces = 0, points = 0, serves = 0;
  uint64_t accepted = 0, drops = 0;
  std::array<uint64_t, kDropSlots> drop_by{};  // the drops by reason
  uint64_t plans = 0, late = 0;
  int racket_segments_with_sample = 0, racket_segments = 0;
  // what the match wrote, each segment with the sim time of the frame that wrote it
  std::vector<SegmentOut> segments;
  std::vector<double> written_at;
  std::vector<EventOut> events;
  std::vector<StateOut> states;
  std::vector<size_t> segments_before;  // each state's: how many segments were written before it
  MatchCounters counters;
};

// Slot `slot`'s racket as its bot has it at sim time t, the slot's next
// sample from its holder.
inline RacketSampleIn bot_sample(Game &g, BotBrain &brain, int slot, double t) {
  RacketSampleIn s;
  s.match_id = g.match.id();
  s.player = slot;
  s.seq = ++g.seq[slot];
  s.capture_time = t;
  brain.pose(t, &s.center, &s.normal);
  s.from = g.owner[slot];
  s.source_time = g.now;
  return s;
}

inline RallyResult play(const MatchConfig &c, const Net &net, double seconds, uint64_t seed = 1,
                        double miss_rate = 0.0) {
  Game g(c);
  std::vector<size_t> segments_before;
  BotBrain brain[2];
  ClientFeed feed(g.match.id());  // the segment in effect, for the bots
  Link<RacketSampleIn> link[2] = {Link<RacketSampleIn>({net.delay, net.jitter, net.loss}, seed * 2 + 1),
                                  Link<RacketSampleIn>({net.delay, net.jitter, net.loss}, seed * 2 + 2)};
  Rng noise(seed * 7 + 3);
  double next_capture[2] = {0, 0};
  RallyResult r;
  for (int i = 0; i < 2; ++i) {
    g.join(i, participant(static_cast<uint8_t>(i + 1)));
    g.park[i] = false;
    BotParams p;
    p.slot = i;
    p.lead = net.plan_ahead ? bot_lead(net.rate, net.delay, net.jitter, net.loss) : kLateSwing;
    p.miss_rate = miss_rate;
    p.seed = seed * 11 + i;
    brain[i].init(g.match.model(), g.match.court(), p);
  }
  int frames = static_cast<int>(seconds * c.frame_rate);
  for (int k = 0; k < frames; ++k) {
    double sim = g.match.sim().time;
    for (int i = 0; i < 2; ++i) {
      // samples taken on the sim clock at the bot's rate, sent through its link
      while (next_capture[i] <= sim + 1e-12) {
        RacketSampleIn s = bot_sample(g, brain[i], i, next_capture[i]);
        s.center.x += noise.normal(net.noise);
        s.center.y += noise.normal(net.noise);
        s.center.z += noise.normal(net.noise);
        link[i].send(s, g.now);
        next_capture[i] += 1.0 / net.rate;
      }
      link[i].deliver(g.now, [&](const RacketSampleIn &s) {
        SampleResult res = g.match.on_sample(s, g.now);
        if (res == SampleResult::accepted) r.accepted++;
        else if (res != SampleResult::idle) {
          r.drops++;
          if (static_cast<int>(res) < kDropSlots) r.drop_by[static_cast<size_t>(res)]++;
        }
      });
    }
    // as the server loop does: late samples tested where the ball was, then a
    // racket hit's instant before the frame's end is stepped to first
    if (g.match.has_late()) {
      g.out.clear();
      g.match.compensate(&g.out);
      g.keep();
      r.written_at.insert(r.written_at.end(), g.out.segments.size(), g.match.sim().time);
      for (const SegmentOut &s : g.out.segments) feed.add(s);
    }
    if (g.match.hit_after() < g.match.frame_time()) {
      g.out.clear();
      g.match.step_to_hit(&g.out);
      g.keep();
      r.written_at.insert(r.written_at.end(), g.out.segments.size(), g.match.sim().time);
      for (const SegmentOut &s : g.out.segments) feed.add(s);
    }
    g.out.clear();
    g.match.frame(g.now, &g.out);
    g.keep();
    if (g.out.has_state) segments_before.push_back(g.segments.size());
    r.written_at.insert(r.written_at.end(), g.out.segments.size(), g.match.sim().time);
    for (const SegmentOut &s : g.out.segments) feed.add(s);
    if (const SegmentOut *s = feed.due(g.match.sim().time))
      for (int i = 0; i < 2; ++i)
        brain[i].on_segment(s->segment, s->cause == Cause::serve, s->cause_index, g.match.sim().time);
    g.now += g.match.frame_time();
  }
  for (const auto &s : g.segments) {
    if (s.cause != Cause::racket) continue;
    r.racket_segments++;
    r.racket_segments_with_sample += s.sample.valid;
  }
  r.hits = g.match.counters().hits;
  r.bounces = g.match.counters().bounces;
  r.points = g.match.counters().points;
  r.serves = g.match.counters().serves;
  r.segments = g.segments;
  r.events = g.events;
  r.states = g.states;
  r.segments_before = segments_before;
  r.counters = g.match.counters();
  for (int i = 0; i < 2; ++i) {
    r.plans += brain[i].counters().plans;
    r.late += brain[i].counters().late;
  }
  return r;
}

inline RallyResult play(ball_level level, const Net &net, double seconds, uint64_t seed = 1,
                        double miss_rate = 0.0, double extrapolation = 0.25) {
  MatchConfig c = default_config();
  c.level = level;
  c.extrapolation_time = extrapolation;
  return play(c, net, seconds, seed, miss_rate);
}

}  // namespace test
