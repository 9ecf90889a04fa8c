// Racket hits at their instant (docs/server-design.md, "Hits at their instant"):
// between frames a match finds when a racket's track first meets the ball
// (ball_racket_first_contact_any) and the server steps it to that instant,
// so that the level's own test finds the hit then, not at the frame's end.
// Offline rallies of two bots, stepped as the server loop steps them.
#include <cmath>
#include <cstdio>

#include "ball/vec3.h"
#include "check.hpp"
#include "rally.h"
#include "rng.h"

using namespace ballsrv;
using namespace test;
using check::note;

namespace {

struct Hits {
  size_t segments = 0, on_boundary = 0, at_writing = 0, event_time = 0;
  uint64_t hits = 0, steps = 0, looks = 0, spared = 0, queries = 0;
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
      h.spared += r.counters.hit_looks_spared;
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
       "%llu looks for the next hit (%llu spared), %llu queries",
       off.segments, off.on_boundary, on.segments, (unsigned long long)on.steps, on.on_boundary, on.at_writing,
       on.event_time, (unsigned long long)on.looks, (unsigned long long)on.spared, (unsigned long long)on.queries);
  CHECK(off.segments >= 200);
  CHECK_EQ(off.on_boundary, off.segments);  // the test can tell
  CHECK_EQ(off.event_time, off.segments);
  CHECK(on.segments >= off.segments * 9 / 10);
  // a hit found at a frame's end happens only when a sample came after the last look:
  // never here, where every sample comes before the look (nor where a look was spared)
  CHECK(on.on_boundary * 20 <= on.segments);
  CHECK_EQ(on.steps, on.segments);
  CHECK(on.at_writing * 20 >= on.segments * 19);
  CHECK_EQ(on.event_time, on.segments);
  CHECK(on.steps >= on.segments * 9 / 10);
}

// libball's bound, as the server asks it before the query (any racket).
bool may_reach(const ball_sim &sim, double end) {
  int may = -1;
  CHECK_EQ(ball_racket_may_reach(&sim, -1, end, &may), BALL_OK);
  return may == 1;
}

// The bound that spares the query (ball_racket_may_reach) never hides a hit
// in the server's own model (the tennis court, the advanced level):
// 6000 random sims, each with a racket swinging through the ball's path
// near a random instant, at each detection test and normal mode, some
// stepped a frame since a sample moved the track; wherever the query finds
// a hit before the window's end, the bound said a racket may reach.
TEST(the_bound_never_hides_a_hit) {
  Rng r(20261203);
  int hits = 0, hidden = 0, spared = 0, asked = 0;
  const ball_detect detects[] = {BALL_DETECT_SPHERE, BALL_DETECT_DISC, BALL_DETECT_SWEPT};
  for (int n = 0; n < 6000; ++n) {
    MatchConfig c = default_config();
    c.level = BALL_LEVEL_ADVANCED;
    Game g(c);
    ball_model m = g.match.model();
    m.detect = detects[n % 3];
    m.normal_mode = (n / 3) % 2 ? BALL_NORMAL_REAL : BALL_NORMAL_VELOCITY;
    if (n % 4 == 1) m.radius = r.uniform(0.01, 0.12);  // balls with a radius too
    ball_sim sim;
    if (ball_sim_init(&sim, &m) != BALL_OK) continue;
    // a ball in flight over the court
    ball_segment seg{};
    seg.t0 = 0.0;
    seg.p0 = ball_v3(r.uniform(2.0, 22.0), r.uniform(0.5, 2.5), r.uniform(1.0, 10.0));
    seg.v0 = ball_v3(r.uniform(-25.0, 25.0), r.uniform(-3.0, 6.0), r.uniform(-4.0, 4.0));
    double now = r.uniform(0.0, 0.3);
    if (ball_sim_set_segment(&sim, &seg, now) != BALL_OK) continue;
    // racket 1's stroke through where the ball is at a random instant ahead
    double t_hit = now + r.uniform(0.0, 0.25);
    ball_state at;
    ball_segment_eval(&m, &seg, t_hit, &at);
    ball_vec3 v = ball_v3(r.uniform(-15.0, 15.0), r.uniform(-5.0, 5.0), r.uniform(-5.0, 5.0));
    ball_vec3 aim = ball_v3_add(at.position, ball_v3(r.uniform(-0.1, 0.1), r.uniform(-0.1, 0.1), r.uniform(-0.1, 0.1)));
    ball_vec3 normal = ball_v3(r.uniform(-1.0, 1.0), r.uniform(-1.0, 1.0), r.uniform(-1.0, 1.0));
    double period = r.uniform(1.0 / 30.0, 0.2);
    for (double t = now - 2 * period; t <= now + r.uniform(0.0, 0.1); t += period) {
      ball_racket_sample smp{t, ball_v3_add(aim, ball_v3_scale(v, t - t_hit)), normal};
      ball_racket_push(&sim, 1, &smp);
    }
    // sometimes a step first (R_old from it), then a sample that moves the track
    if (r.chance(0.5)) {
      int k = 0;
      ball_event ev[8];
      double dt = r.uniform(0.001, 0.02);
      if (ball_step(&sim, dt, ev, 8, &k) != BALL_OK || k > 0) continue;
      ball_racket_sample smp{sim.time + r.uniform(-0.01, 0.05),
                             ball_v3_add(aim, ball_v3(r.uniform(-0.2, 0.2), r.uniform(-0.2, 0.2), 0.0)), normal};
      ball_racket_push(&sim, 1, &smp);
    }
    double end = sim.time + r.uniform(0.005, 0.3);
    ball_racket_contact contact;
    bool found = ball_racket_first_contact_any(&sim, end, &contact) == BALL_OK && contact.step_to <= end;
    bool may = may_reach(sim, end);
    hits += found;
    hidden += found && !may;
    spared += !may;
    asked++;
  }
  note("%d sims: %d hits found by the query, %d of them where the bound said no; the bound spared %d queries",
       asked, hits, hidden, spared);
  CHECK(asked >= 5000);
  CHECK(hits >= 1000);
  CHECK_EQ(hidden, 0);
  CHECK(spared >= 500);  // it does spare some
}

// The disc test grows the disc by the ball radius within the ball radius of
// either face: a ball whose centre comes to the corner of that cylinder,
// sqrt((r + b)^2 + b^2) from the racket's centre, is hit. The bound must
// reach that far (it reached r + b only: a ball drifting into the rim's
// corner was found at the frame's end, not at its instant). (The swept
// test is exact at the rim: it finds no hit there.)
TEST(the_bound_reaches_the_disc_tests_rim) {
  MatchConfig c = default_config();
  c.level = BALL_LEVEL_ADVANCED;
  Game g(c);
  for (ball_detect detect : {BALL_DETECT_DISC}) {
    ball_model m = g.match.model();
    m.detect = detect;
    m.normal_mode = BALL_NORMAL_REAL;
    m.radius = 0.04;  // a ball with a radius (the levels' is the paper's point)
    ball_sim sim;
    CHECK_EQ(ball_sim_init(&sim, &m), BALL_OK);
    const double r = m.rackets[1].radius, b = m.radius, drift = 0.0005;
    ball_vec3 centre = ball_v3(12.0, 1.0, 4.0);
    for (int k = 0; k < 3; ++k) {  // a racket held still, its face along x
      ball_racket_sample smp{0.05 * k, centre, ball_v3(1.0, 0.0, 0.0)};
      CHECK_EQ(ball_racket_push(&sim, 1, &smp), BALL_OK);
    }
    // the ball just off the face's slab, just inside the grown rim, drifting onto the face
    ball_segment seg{};
    seg.t0 = 0.1;
    seg.p0 = ball_v3(centre.x + b + drift, centre.y, centre.z + r + b - 1e-4);
    seg.v0 = ball_v3(-0.1, 0.0, 0.0);
    CHECK_EQ(ball_sim_set_segment(&sim, &seg, 0.1), BALL_OK);
    double end = sim.time + 1.0 / 60.0;
    ball_racket_contact contact;
    bool found = ball_racket_first_contact_any(&sim, end, &contact) == BALL_OK && contact.step_to <= end;
    double dist = ball_v3_dist(seg.p0, centre), moves = 0.1 / 60.0 + 0.5 * m.gravity / 3600.0;
    note("%s: the ball %.4f m from the racket's centre (r + b = %.4f m), found %d at %.4f s", ball_detect_name(detect),
         dist, r + b, found, found ? contact.step_to : 0.0);
    CHECK(found);
    CHECK(dist - (r + b) > moves);  // (the old reach said no)
    CHECK(may_reach(sim, end));
  }
}

int main(int argc, char **argv) { return check::run(argc, argv); }

// A look the bound spared (its no over two frames, hit_looks_spared) is
// looked at again once a sample moves a track: a player's racket, parked
// off the court, is next sampled where the ball will be in the middle of
// the frame (its capture time ahead of the sim clock, within
// max_sample_lead, at a legal speed since its previous sample).
TEST(a_new_sample_ends_what_the_bound_spared) {
  int tried = 0, found = 0;
  for (int level = BALL_LEVEL_EASY; level <= BALL_LEVEL_ADVANCED; ++level) {
    MatchConfig c = default_config();
    c.level = static_cast<ball_level>(level);
    Game g(c);
    g.join(0, participant(1));
    g.join(1, participant(2));
    g.run(0.7);  // served, the ball in flight
    g.park[0] = g.park[1] = false;  // (their rackets may move 25 m in the next 0.5 s)
    g.run(0.5);
    // frames until one's look is spared: the bound a frame before covers this frame
    uint64_t spared = g.match.counters().hit_looks_spared;
    for (int k = 0; k < 30 && g.match.counters().hit_looks_spared == spared; ++k) g.run(1.0 / c.frame_rate);
    CHECK(g.match.counters().hit_looks_spared > spared);
    CHECK(g.match.hit_after() == HUGE_VAL);
    const ball_sim &sim = g.match.sim();
    double t = sim.time + 0.5 * g.match.frame_time() * c.time_base;
    ball_state at{};
    CHECK_EQ(ball_segment_eval(&g.match.model(), &sim.seg, t, &at), BALL_OK);
    int slot = g.match.court().side_of(at.position.x);  // the player on the ball's half (singles: slot = side)
    RacketSampleIn s = g.parked_sample(slot);
    s.capture_time = t;
    s.center = at.position;
    s.normal = ball_v3(1, 0, 0);
    tried++;
    SampleResult took = g.match.on_sample(s, g.now);
    CHECK_MSG(took == SampleResult::accepted, "sample: %s", name_of(took));
    double after = g.match.hit_after();
    note("level %d: the ball at %.2f s on side %d; a sample puts racket %d on it at %.4f s: hit after %.4f s", level,
         sim.time, slot, slot, t, after);
    found += after < g.match.frame_time();
  }
  CHECK_EQ(found, tried);
}
