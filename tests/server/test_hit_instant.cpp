// Racket hits at their instant (docs/server.md, "Hits at their instant"):
// between frames a match finds when a racket's track first meets the ball
// (ball_racket_first_contact_any) and the server steps it to that instant,
// so that the level's own test finds the hit then, not at the frame's end.
// Offline rallies of two bots, stepped as the server loop steps them.
#include <cmath>
#include <cstdio>

#include "check.hpp"
#include "rally.h"

using namespace ballsrv;
using namespace test;
using check::note;

namespace {

struct Hits {
  size_t segments = 0, on_boundary = 0, at_writing = 0, event_time = 0;
  uint64_t hits = 0, steps = 0, looks = 0, queries = 0;
};

Hits rally_hits(bool instant) {
  Hits h;
  for (int level = BALL_LEVEL_EASY; level <= BALL_LEVEL_ADVANCED; ++level)
    for (uint64_t seed = 1; seed <= 4; ++seed) {
      MatchConfig c = default_config();
      c.level = static_cast<ball_level>(level);
      c.seed = seed;
      c.hit_instant = instant;
      c.rewind_window = 0.0;  // (late samples' hits: test_lag)
      Net net;
      net.noise = 0.002;
      RallyResult r = play(c, net, 30.0, seed);
      h.hits += r.counters.hits;
      h.steps += r.counters.hit_steps;
      h.looks += r.counters.hit_looks;
      h.queries += r.counters.hit_queries;
      for (size_t i = 0; i < r.segments.size(); ++i) {
        const SegmentOut &s = r.segments[i];
        if (s.cause != Cause::racket) continue;
        h.segments++;
        double frames = s.segment.t0 * c.frame_rate;  // the sim clock runs at time base 1 from 0
        h.on_boundary += std::fabs(frames - std::round(frames)) < 1e-6;
        h.at_writing += r.written_at[i] == s.segment.t0;
        for (const EventOut &e : r.events)
          if (e.kind == EventKind::racket && e.segment_seq == s.seq) h.event_time += e.time == s.segment.t0;
      }
    }
  return h;
}

}  // namespace

// 12 rallies of 30 s at the three levels (sphere, disc with the velocity
// normal, disc with the real normal), frame-locked and at the instant.
TEST(racket_segments_start_at_the_hits_instant) {
  Hits off = rally_hits(false), on = rally_hits(true);
  note("frame-locked: %zu racket segments, %zu on a frame boundary; at the instant: %zu racket segments (%llu "
       "partial steps), %zu on a frame boundary, %zu written at their t0, %zu events at their segment's t0; "
       "%llu looks for the next hit, %llu queries",
       off.segments, off.on_boundary, on.segments, (unsigned long long)on.steps, on.on_boundary, on.at_writing,
       on.event_time, (unsigned long long)on.looks, (unsigned long long)on.queries);
  CHECK(off.segments >= 200);
  CHECK_EQ(off.on_boundary, off.segments);  // the test can tell
  CHECK_EQ(off.event_time, off.segments);
  CHECK(on.segments >= off.segments * 9 / 10);
  // a hit found at a frame's end happens only when a sample came after the last look
  CHECK(on.on_boundary * 20 <= on.segments);
  CHECK(on.at_writing * 20 >= on.segments * 19);
  CHECK_EQ(on.event_time, on.segments);
  CHECK(on.steps >= on.segments * 9 / 10);
}

int main(int argc, char **argv) { return check::run(argc, argv); }
