// A client's side without a network: the sim clock estimate (docs/protocol.md,
// "Time"), the link that delays and loses samples, and a BotPlayer joining a
// match from what MatchInfo says.
#include <cmath>

#include "check.hpp"
#include "game.h"
#include "player.h"

using namespace test;

TEST(sim_clock_maps_by_the_smallest_offset) {
  SimClock c;
  CHECK(!c.valid());
  // the server's clock runs 100 s behind ours; latencies 5, 1 and 3 ms
  const double skew = 100.0;
  c.observe(10.0, 1000.0, 1.0, true, 1000.0 + skew + 0.005);
  c.observe(10.5, 1000.5, 1.0, true, 1000.5 + skew + 0.001);
  c.observe(11.0, 1001.0, 1.0, true, 1001.0 + skew + 0.003);
  CHECK(c.valid());
  CHECK_NEAR(c.offset(), skew + 0.001, 1e-12);
  // 0.25 s after the newest pair (local time), less the 1 ms the filter keeps
  CHECK_NEAR(c.sim_now(1001.25 + skew), 11.249, 1e-9);
  // slow motion: sim advances half as fast
  c.observe(11.0, 1001.0, 0.5, true, 1001.0 + skew + 0.003);
  CHECK_NEAR(c.sim_now(1002.0 + skew), 11.0 + 0.999 * 0.5, 1e-9);
  // paused: the sim clock stands still
  c.observe(11.2, 1001.4, 0.5, false, 1001.4 + skew + 0.002);
  CHECK_NEAR(c.sim_now(1010.0 + skew), 11.2, 0.0);
  // a pair that arrives late does not move the anchor back
  c.observe(10.9, 1000.9, 1.0, true, 1001.5 + skew);
  CHECK_NEAR(c.sim_now(1010.0 + skew), 11.2, 0.0);
}

TEST(link_delays_reorders_and_loses) {
  Link<int> clean({0.1, 0.0, 0.0}, 1);
  for (int i = 0; i < 10; ++i) clean.send(i, i * 0.01);
  std::vector<int> got;
  clean.deliver(0.1 + 0.045, [&](int v) { got.push_back(v); });
  CHECK_EQ(got.size(), 5u);  // sent at 0 .. 0.04, each 0.1 s late
  CHECK_EQ(clean.pending(), 5u);
  Link<int> lossy({0.0, 0.05, 0.2}, 7);
  int sent = 0, lost = 0;
  for (int i = 0; i < 10000; ++i, ++sent) lost += !lossy.send(i, i * 0.001);
  CHECK_NEAR(lost / static_cast<double>(sent), 0.2, 0.02);
  int last = -1, overtaken = 0;
  lossy.deliver(100.0, [&](int v) {
    overtaken += v < last;
    last = std::max(last, v);
  });
  CHECK(overtaken > 1000);  // 50 ms of jitter at 1 kHz: samples overtake each other
}

TEST(player_joins_then_sends) {
  Game g;
  ball_scene scene;
  ball_scene_default(&scene);
  ParticipantId me = participant(9);
  PlayerParams p;
  p.match = g.match.id();
  p.player = 1;
  p.rate = 20.0;
  BotPlayer bot(scene, me, p);
  std::vector<RacketSampleIn> samples;
  std::vector<ControlIn> controls;
  MatchInfoOut info = g.match.info();
  CHECK(bot.on_info(info, 0.0));
  CHECK_EQ(bot.model_hash(), info.model_hash);  // the bot builds the server's model
  bot.tick(0.0, 0.0, &samples, &controls);
  CHECK_EQ(controls.size(), 1u);
  CHECK(controls[0].kind == ControlKind::join && controls[0].player == 1);
  CHECK(samples.empty());  // nothing before the slot is its own
  bot.tick(0.2, 0.2, &samples, &controls);
  CHECK_EQ(controls.size(), 1u);  // resent every 0.5 s, not sooner
  bot.tick(0.6, 0.6, &samples, &controls);
  CHECK_EQ(controls.size(), 2u);
  g.control(ControlKind::join, me, 1);
  CHECK(bot.on_info(g.match.info(), 0.7));
  CHECK(bot.joined());
  CHECK_EQ(bot.slot(), 1);
  for (int k = 0; k < 20; ++k) bot.tick(0.7 + k * 0.05, 0.7 + k * 0.05, &samples, &controls);
  CHECK(samples.size() >= 19 && samples.size() <= 21);  // 20 Hz for 1 s
  CHECK_EQ(controls.size(), 2u);
  for (size_t i = 1; i < samples.size(); ++i) CHECK(samples[i].seq > samples[i - 1].seq);
  // what it sends, the server accepts
  for (const auto &s : samples) {
    RacketSampleIn in = s;
    in.from = me;
    CHECK(g.match.on_sample(in, g.now) == SampleResult::idle);  // the match waits for slot 0
  }
  ControlIn bye;
  CHECK(bot.leave(&bye));
  CHECK(bye.kind == ControlKind::leave && bye.player == 1);
}

CHECK_MAIN
