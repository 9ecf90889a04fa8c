// A client's side without a network: the sim clock estimate (docs/protocol.md,
// "Time"), the link that delays and loses samples (alone, and as a client's
// simulated network), a BotPlayer joining a match from what MatchInfo says,
// and a PlayerGroup playing its bots through one client of the client
// library (ball/net.h) and counting refused writes.
#include <cmath>
#include <cstring>

#include <deque>
#include <map>
#include <memory>
#include <set>

#include "check.hpp"
#include "fake_net_client.h"
#include "game.h"
#include "player_group.h"

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

// Pairs that do not fit move nothing (counted): a number that is not
// finite, a time base out of range, a forged pair from a clock 1e6 s away
// (three of them froze every bot for good before); ten in a row that agree
// with each other are a new clock (another server's host), adopted.
TEST(sim_clock_refuses_pairs_that_do_not_fit) {
  SimClock c;
  const double skew = 100.0;
  for (int i = 0; i < 5; ++i) CHECK(c.observe(10.0 + i, 1000.0 + i, 1.0, true, 1000.0 + i + skew + 0.001));
  double before = c.sim_now(1005.0 + skew);
  CHECK(!c.observe(std::nan(""), 1005.0, 1.0, true, 1005.0 + skew));
  CHECK(!c.observe(15.0, 1005.0, 50.0, true, 1005.0 + skew));
  CHECK(!c.observe(15.0, 1005.0, 0.0, true, 1005.0 + skew));
  for (int i = 0; i < 3; ++i) CHECK(!c.observe(1e9, 1e12, 1.0, true, 1005.0 + skew));
  CHECK(!c.observe(15.0, 1005.0 - 3.0, 1.0, true, 1005.0 + skew));  // 3 s above: a jump
  CHECK(!c.observe(15.0, 1005.0 + 6.0, 1.0, true, 1005.0 + skew));  // 6 s below: a jump
  CHECK_EQ(c.rejected(), 8ul);
  CHECK_NEAR(c.sim_now(1005.0 + skew), before, 0.0);
  // a real pair between forged ones breaks their run
  for (int i = 0; i < SimClock::kConfirm - 1; ++i) CHECK(!c.observe(50.0, 2000.0 + i, 1.0, true, 1005.0 + skew));
  CHECK(c.observe(15.0, 1005.0, 1.0, true, 1005.0 + skew + 0.001));
  CHECK(!c.observe(50.0, 2000.0, 1.0, true, 1005.0 + skew));
  // a new clock, 500 s off, kConfirm pairs in a row: adopted
  for (int i = 0; i < SimClock::kConfirm - 1; ++i) CHECK(!c.observe(20.0 + i, 500.0 + i, 1.0, true, 1006.0 + i + skew));
  CHECK(c.observe(20.0 + 9, 500.0 + 9, 1.0, true, 1006.0 + 9 + skew));
  CHECK_NEAR(c.sim_now(1016.0 + skew), 30.0, 1e-9);
}

// The first pair a late joiner gets is a transient-local MatchInfo, written
// up to 4 s before (docs/protocol.md, "Time"): its offset lies that much
// above the true one. The next, fresh pair is taken at once, whatever that
// age, and the clock is the fresh one's.
TEST(sim_clock_takes_a_fresh_pair_after_a_stale_first) {
  for (double age = 0.0; age <= 4.0; age += 0.25) {
    SimClock c;
    const double skew = 100.0;
    CHECK(c.observe(10.0, 1000.0, 1.0, true, 1000.0 + age + skew + 0.001));
    CHECK(c.observe(10.0 + age + 0.5, 1000.0 + age + 0.5, 1.0, true, 1000.0 + age + 0.5 + skew + 0.001));
    CHECK_NEAR(c.offset(), skew + 0.001, 1e-9);
    CHECK_NEAR(c.sim_now(1000.0 + age + 1.0 + skew), 10.0 + age + 0.999, 1e-9);
  }
}

// A pair of a fitting offset but a sim time that does not fit the clock
// (the server's time now, the sim 100 s ahead: every bot's clock moved
// before) moves nothing, whatever its count; neither does one 3 s behind.
// Pause, slow motion and a late pair fit; a new owner's first pair
// (rebase) may set the sim clock anywhere.
TEST(sim_clock_refuses_a_sim_time_that_does_not_fit) {
  SimClock c;
  const double skew = 100.0;
  for (int i = 0; i < 5; ++i) CHECK(c.observe(10.0 + i, 1000.0 + i, 1.0, true, 1000.0 + i + skew + 0.001));
  for (int i = 0; i < 3 * SimClock::kConfirm; ++i) {
    const double t = 1004.0 + 0.2 * i;
    CHECK(!c.observe(14.0 + 0.2 * i + 100.0, t, 1.0, true, t + skew + 0.001));
  }
  CHECK(!c.observe(20.0 - 3.0, 1010.0, 1.0, true, 1010.0 + skew + 0.001));
  CHECK_EQ(c.rejected(), static_cast<unsigned long>(3 * SimClock::kConfirm + 1));
  CHECK_NEAR(c.sim_now(1010.0 + skew), 20.0 - 0.001, 1e-9);
  CHECK(c.observe(20.0, 1010.0, 0.5, false, 1010.0 + skew + 0.002));   // paused, slow motion
  CHECK(c.observe(19.99, 1009.99, 1.0, true, 1010.5 + skew));          // a late pair
  CHECK(c.observe(20.0, 1011.0, 0.5, true, 1011.0 + skew + 0.001));   // resumed
  CHECK_NEAR(c.sim_now(1012.0 + skew), 20.0 + 0.999 * 0.5, 1e-9);
  c.rebase();
  CHECK(c.observe(500.0, 1012.0, 1.0, true, 1012.0 + skew + 0.001));
  CHECK_NEAR(c.sim_now(1013.0 + skew), 500.999, 1e-9);
  CHECK(!c.observe(900.0, 1013.0, 1.0, true, 1013.0 + skew + 0.001));  // once only
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

namespace {
// A game's MatchInfo and MatchModel, as its server writes them, to a client's port.
void server_says(Game &g, FakeClientPort &port, uint32_t server = 1) {
  MatchInfoOut i = g.match.info();
  i.server_id = server;
  i.server_time = g.now;
  port.infos.push_back(i);
  MatchModelOut m;
  m.match_id = g.match.id();
  m.server_id = server;
  m.model = g.match.model();
  m.model_hash = ball_model_hash(&m.model);
  port.models.push_back(m);
}
}  // namespace

// A client's simulated network (ball_net_config's link_*): each pose pushed
// is numbered at once and written no sooner than link_delay after its push
// nor later than link_delay + link_jitter (and a tick), some overtaking
// others; about link_loss of them are lost, counted, their numbers never
// written. Every pose pushed is written or lost.
TEST(a_clients_simulated_network_delays_reorders_and_loses_its_poses) {
  Game g;
  const ParticipantId me = participant(9);
  FakeNet net(me, [](ball_net_config *c) {
    c->link_delay = 0.1;
    c->link_jitter = 0.05;
    c->link_loss = 0.2;
    c->link_seed = 3;
  });
  const uint32_t match = g.match.id();
  g.control(ControlKind::join, me, 1);
  CHECK_EQ(ball_net_join(net.client, match, 1), BALL_OK);
  server_says(g, net.port);
  ball_net_event ev[16];
  int n = 0;
  CHECK_EQ(ball_net_poll(net.client, ev, 16, &n), BALL_OK);
  const int kPoses = 2000;
  const double dt = 0.001;
  std::vector<double> pushed(kPoses + 1, 0.0);  // by seq: the client's clock of its push
  size_t seen = 0;
  int early = 0, late = 0, overtaken = 0;
  uint32_t newest = 0;
  auto check_written = [&]() {
    for (; seen < net.port.samples.size(); ++seen) {
      const RacketSampleIn &s = net.port.samples[seen];
      CHECK(s.seq >= 1 && s.seq <= static_cast<uint32_t>(kPoses));
      double trip = net.now - pushed[s.seq];
      early += trip < 0.1 - 1e-9;
      late += trip > 0.15 + dt + 1e-9;
      overtaken += s.seq < newest;
      newest = std::max(newest, s.seq);
    }
  };
  for (int k = 0; k < kPoses; ++k) {
    net.now = 1.0 + k * dt;
    CHECK_EQ(ball_net_push(net.client, match, 1, net.now, {0.0, 1.0, 0.0}, {-1.0, 0.0, 0.0}), BALL_OK);
    pushed[static_cast<size_t>(k + 1)] = net.now;
    check_written();
  }
  for (int k = 1; k <= 200; ++k) {  // the last on their way, written by the polls
    net.now = 1.0 + kPoses * dt + k * dt;
    CHECK_EQ(ball_net_poll(net.client, ev, 16, &n), BALL_OK);
    check_written();
  }
  ball_net_status st;
  CHECK_EQ(ball_net_status_of(net.client, match, &st), BALL_OK);
  check::note("%d poses: %llu written, %llu lost; %d overtook another", kPoses,
              static_cast<unsigned long long>(st.samples), static_cast<unsigned long long>(st.link_lost), overtaken);
  CHECK_EQ(early, 0);
  CHECK_EQ(late, 0);
  CHECK_EQ(st.samples, net.port.samples.size());
  CHECK_EQ(st.samples + st.link_lost, static_cast<uint64_t>(kPoses));
  CHECK(st.link_lost >= 310 && st.link_lost <= 490);  // 400 expected, 5 standard deviations
  CHECK(overtaken > 100);                             // 50 ms of jitter at 1 kHz
  std::vector<bool> once(kPoses + 1, false);
  for (const auto &s : net.port.samples) {
    CHECK(!once[s.seq]);
    once[s.seq] = true;
  }
  // the same seed, the same network: the same poses lost
  FakeNet again(me, [](ball_net_config *c) {
    c->link_delay = 0.1;
    c->link_jitter = 0.05;
    c->link_loss = 0.2;
    c->link_seed = 3;
  });
  CHECK_EQ(ball_net_join(again.client, match, 1), BALL_OK);
  server_says(g, again.port);
  CHECK_EQ(ball_net_poll(again.client, ev, 16, &n), BALL_OK);
  for (int k = 0; k < kPoses; ++k) {
    again.now = 1.0 + k * dt;
    ball_net_push(again.client, match, 1, again.now, {0.0, 1.0, 0.0}, {-1.0, 0.0, 0.0});
  }
  again.now += 1.0;
  CHECK_EQ(ball_net_poll(again.client, ev, 16, &n), BALL_OK);
  std::vector<bool> twice(kPoses + 1, false);
  for (const auto &s : again.port.samples) twice[s.seq] = true;
  CHECK(once == twice);
}

// A bot's group joins its slot through the client core (JOIN now and every
// 0.5 s until the MatchInfo shows it), then plays with the model from the

// Bots in a PlayerGroup over a FakeNet: tick(t) sets the client's clock to
// t and ticks the group.
struct Players {
  Players(std::vector<BotPlayer> bots, const ParticipantId &me, void (*more)(ball_net_config *) = nullptr)
      : net(me, more), group(std::move(bots), net.client) {}
  void tick(double t) {
    net.now = t;
    group.tick(t);
  }
  FakeNet net;
  PlayerGroup group;
};

// Polls the client every 0.1 s of its clock until t.
void poll_every_tenth(FakeNet *net, double t) {
  ball_net_event ev[16];
  int n = 0;
  for (; net->now < t - 1e-9; net->now += 0.1) CHECK_EQ(ball_net_poll(net->client, ev, 16, &n), BALL_OK);
}

// A TCP client starts anew (docs/deploy.md, "Limits") when it hears no
// server for 5 s, and when a JOIN has no answer for that long while it
// hears one; each time it waits twice as long, and never while a refusal
// answers its JOIN or its slot is held. A transport that cannot start anew
// is never asked.
TEST(a_client_that_hears_no_answer_starts_anew) {
  Game g;
  const ParticipantId me = participant(9);
  FakeNet net(me);
  net.renewable = true;
  auto poll_until = [&](double t) { poll_every_tenth(&net, t); };
  net.port.heard = false;
  poll_until(4.9);
  CHECK_EQ(net.renewals, 0);
  poll_until(5.2);
  CHECK_EQ(net.renewals, 1);  // no server in 5 s
  poll_until(14.9);
  CHECK_EQ(net.renewals, 1);  // then 10 s
  poll_until(15.3);
  CHECK_EQ(net.renewals, 2);
  // a server heard: the wait is 5 s again once nothing waits
  net.port.heard = true;
  poll_until(16.0);
  const uint32_t match = g.match.id();
  CHECK_EQ(ball_net_join(net.client, match, 1), BALL_OK);
  size_t joins = net.port.controls.size();
  poll_until(20.9);
  CHECK_EQ(net.renewals, 2);
  CHECK(net.port.controls.size() > joins);  // (JOINs resent, unanswered)
  poll_until(21.3);
  CHECK_EQ(net.renewals, 3);  // a JOIN unanswered for 5 s while the server is heard
  // the new participant's JOIN goes out at once
  CHECK(net.port.controls.back().kind == ControlKind::join);
  // a refusal in the match is an answer: no renewal while they come
  ParticipantId renewed = me;
  renewed[11] += 3;
  ParticipantId other = participant(1);
  g.control(ControlKind::join, other, 1);
  server_says(g, net.port);
  for (double t = 21.3; t < 40.0; t += 1.0) {
    if (static_cast<int>(t) % 4 == 0) server_says(g, net.port);  // (its MatchInfo every 4 s)
    EventOut refused;
    refused.match_id = match;
    refused.server_id = 1;
    refused.kind = EventKind::refused;
    refused.seq = static_cast<uint32_t>(100 + t);
    net.port.events.push_back(refused);
    poll_until(t + 1.0);
  }
  CHECK_EQ(net.renewals, 3);
  // the slot given to the new participant: held, nothing waits
  g.control(ControlKind::leave, other, 1);
  CHECK(g.control(ControlKind::join, renewed, 1) == Reason::none);
  for (double t = 40.0; t < 80.0; t += 1.0) {  // (its server's MatchInfo once a second)
    server_says(g, net.port);
    poll_until(t + 1.0);
  }
  CHECK_EQ(net.renewals, 3);
  int slot = -1;
  CHECK_EQ(ball_net_slot_of(net.client, match, &slot), BALL_OK);
  CHECK_EQ(slot, 1);
  // a transport that cannot start anew is never asked
  FakeNet udp(me);
  udp.port.heard = false;
  poll_every_tenth(&udp, 30.0);
  CHECK_EQ(udp.renewals, 0);
}

// A TCP client that follows a match and hears its MatchInfo no more for
// the silence (10 s) while it hears a server starts anew (the owner lost,
// its successor deaf to this client); each time it waits twice as long,
// and not at all once the match's MatchInfo comes again.
TEST(a_client_whose_match_falls_silent_starts_anew) {
  Game g;
  FakeNet net(participant(9));
  net.renewable = true;
  auto poll_until = [&](double t) { poll_every_tenth(&net, t); };
  CHECK_EQ(ball_net_watch(net.client, g.match.id()), BALL_OK);
  for (double t = 0.0; t < 12.0; t += 4.0) {  // its owner's MatchInfo every 4 s
    server_says(g, net.port);
    poll_until(t + 4.0);
  }
  CHECK_EQ(net.renewals, 0);
  // the owner's last MatchInfo at 8 s, a server still heard (its successor)
  poll_until(17.9);
  CHECK_EQ(net.renewals, 0);
  poll_until(18.2);
  CHECK_EQ(net.renewals, 1);
  poll_until(27.8);
  CHECK_EQ(net.renewals, 1);  // the wait is 10 s, and the silence counts from the renewal
  poll_until(28.4);
  CHECK_EQ(net.renewals, 2);
  poll_until(47.8);
  CHECK_EQ(net.renewals, 2);  // then 20 s
  poll_until(48.6);
  CHECK_EQ(net.renewals, 3);
  for (double t = 48.6; t < 120.0; t += 4.0) {  // the successor heard: no more
    server_says(g, net.port, 2);
    poll_until(t + 4.0);
  }
  CHECK_EQ(net.renewals, 3);
}

// wire, no scene file, and sends at its rate what the server accepts.
// A server of many matches takes seconds to be found whole: a client that
// has met some of its endpoints waits on, however long, and its JOIN's
// silence does not count until it hears the server; once nothing of a
// server is met, it starts anew 5 s later.
TEST(a_client_that_meets_a_server_waits_for_the_rest) {
  Game g;
  FakeNet net(participant(9));
  net.renewable = true;
  auto poll_until = [&](double t) { poll_every_tenth(&net, t); };
  net.port.heard = false;
  net.port.met = true;
  CHECK_EQ(ball_net_join(net.client, g.match.id(), 1), BALL_OK);
  poll_until(30.0);
  CHECK_EQ(net.renewals, 0);
  CHECK(net.port.controls.size() > 10u);  // (JOINs resent, unanswered)
  net.port.met = false;
  poll_until(34.9);
  CHECK_EQ(net.renewals, 0);
  poll_until(35.2);
  CHECK_EQ(net.renewals, 1);
}

TEST(player_joins_then_sends) {
  Game g;
  ParticipantId me = participant(9);
  PlayerParams p;
  p.match = g.match.id();
  p.player = 1;
  p.rate = 20.0;
  Players players({BotPlayer(p)}, me);
  FakeClientPort &port = players.net.port;
  PlayerGroup &group = players.group;
  auto tick = [&](double t) { players.tick(t); };
  tick(0.0);
  CHECK_EQ(port.controls.size(), 1u);
  CHECK(port.controls[0].kind == ControlKind::join && port.controls[0].player == 1);
  CHECK(port.samples.empty());  // nothing before the slot is its own
  tick(0.2);
  CHECK_EQ(port.controls.size(), 1u);  // resent every 0.5 s, not sooner
  tick(0.6);
  CHECK_EQ(port.controls.size(), 2u);
  g.control(ControlKind::join, me, 1);
  server_says(g, port);
  tick(0.7);
  const BotPlayer &bot = group.bots()[0];
  CHECK(bot.joined());
  CHECK_EQ(bot.slot(), 1);
  for (int k = 1; k <= 20; ++k) tick(0.7 + k * 0.05);
  CHECK(port.samples.size() >= 19 && port.samples.size() <= 21);  // 20 Hz for 1 s
  CHECK_EQ(port.controls.size(), 2u);
  for (size_t i = 1; i < port.samples.size(); ++i) CHECK(port.samples[i].seq > port.samples[i - 1].seq);
  // what it sends, the server accepts
  for (const auto &s : port.samples) {
    RacketSampleIn in = s;
    in.from = me;
    CHECK(g.match.on_sample(in, g.now) == SampleResult::idle);  // the match waits for slot 0
  }
  CHECK_EQ(group.leave(), 1);
  CHECK(port.controls.back().kind == ControlKind::leave && port.controls.back().player == 1);
}

// Players sample on phases of their own (from their seeds), not in step: 60
// bots at 30 Hz in one process (30 matches, both slots, one participant),
// joined at the same instant, write their samples spread over the period,
// not 60 at once (a burst that held the server's and the bots' cores), and
// keep their phases after a wait.
TEST(players_sample_on_their_own_phases) {
  std::vector<std::unique_ptr<Game>> games;
  std::vector<BotPlayer> bots;
  for (int i = 0; i < 60; ++i) {
    PlayerParams p;
    p.match = static_cast<uint32_t>(100 + i / 2);
    p.player = i % 2;
    p.rate = 30.0;
    p.seed = static_cast<uint64_t>(i + 1);
    bots.emplace_back(p);
  }
  Players players(std::move(bots), participant(9));
  FakeClientPort &port = players.net.port;
  PlayerGroup &group = players.group;
  auto tick = [&](double t) { players.tick(t); };
  tick(0.0);
  for (uint32_t m = 0; m < 30; ++m) {
    MatchConfig c = default_config();
    c.id = 100 + m;
    games.push_back(std::make_unique<Game>(c));
    games.back()->control(ControlKind::join, participant(9), 0);
    games.back()->control(ControlKind::join, participant(9), 1);
    server_says(*games.back(), port);
  }
  tick(0.5);
  std::map<int, int> per_ms;  // samples written per millisecond tick
  for (int k = 1; k <= 200; ++k) {
    double t = 0.5 + k * 0.001;
    size_t before = port.samples.size();
    tick(t);
    if (port.samples.size() > before) per_ms[k] = static_cast<int>(port.samples.size() - before);
  }
  int most = 0, total = 0;
  for (const auto &m : per_ms) {
    most = std::max(most, m.second);
    total += m.second;
  }
  check::note("%d samples in 0.2 s over %zu ticks of 1 ms, at most %d in one", total, per_ms.size(), most);
  CHECK(group.all_joined());
  CHECK(total >= 60 * 6 - 60 && total <= 60 * 7);  // 30 Hz each
  CHECK(most <= 8);                                // (60 in the first tick and every 33 ms, in step)
  CHECK(per_ms.size() >= 100u);
}

// A bot's group takes only what fits (the client core's rules, test_net_core):
// a MatchInfo with level 99 or a NaN clock, another server's samples when it
// chose server 1, a segment seq 0xFFFFFFFF are counted refused; the real
// stream goes on.
TEST(a_bot_takes_nothing_that_does_not_fit) {
  Game g;
  g.join(0, participant(1));
  g.join(1, participant(9));
  g.run(2.0);  // serves
  PlayerParams p;
  p.match = g.match.id();
  p.player = 1;
  std::string err;
  FakeNet net(participant(9), [](ball_net_config *c) { c->servers = "1"; });
  FakeClientPort &port = net.port;
  PlayerGroup group({BotPlayer(p)}, net.client);
  auto tick = [&](double t) {
    net.now = t;
    group.tick(t);
  };
  server_says(g, port);
  tick(g.now);
  CHECK(group.bots()[0].joined());
  CHECK_EQ(group.refused(), 0u);
  MatchInfoOut info = port.infos.empty() ? g.match.info() : port.infos.front();
  info = g.match.info();
  info.server_id = 1;
  info.server_time = g.now;
  MatchInfoOut bad = info;
  bad.level = 99;
  port.infos.push_back(bad);
  bad = info;
  bad.sim_time = std::nan("");
  port.infos.push_back(bad);
  bad = info;
  bad.server_id = 2;  // not chosen
  port.infos.push_back(bad);
  tick(g.now + 0.1);
  CHECK_EQ(group.refused(), 3u);
  CHECK(!g.segments.empty());
  SegmentOut real = g.segments.back();
  real.server_id = 1;
  port.segments.push_back(real);
  tick(g.now + 0.15);
  uint64_t seen = group.segments();
  SegmentOut forged = real;
  forged.seq = real.seq + kMaxSeqAhead + 1;
  port.segments.push_back(forged);
  tick(g.now + 0.2);
  CHECK_EQ(group.refused(), 4u);
  real.seq += 1;  // the server's next segment still gets through
  port.segments.push_back(real);
  tick(g.now + 0.3);
  CHECK_EQ(group.segments(), seen + 1);
  CHECK(segment_is_news(5, 0xFFFFFFFEu, 0));  // across the wrap
  CHECK(!segment_is_news(3, 5, 0));
  CHECK(segment_is_news(3, 5, 3));            // a match started anew: the info says so
  ServerChoice any, two;
  CHECK(ServerChoice::parse("", &any, &err) && any.accepts(77));
  CHECK(ServerChoice::parse("1,2", &two, &err) && two.accepts(2) && !two.accepts(3));
  CHECK(!ServerChoice::parse("1,x", &two, &err) && err.find("server ids") != std::string::npos);
  // an id bound to a certificate's identity: a name, never a path
  ServerChoice bound;
  CHECK(ServerChoice::parse("1=server1,2,7=srv-7.b", &bound, &err) && bound.accepts(7) && bound.accepts(2));
  auto b = bound.bound();
  CHECK_EQ(b.size(), 2u);
  CHECK(b[0].first == 1u && b[0].second == "server1" && b[1].first == 7u && b[1].second == "srv-7.b");
  CHECK(two.bound().empty());
  for (const char *text : {"1=", "1=../ca", "1=a/b", "=server1", "1=.hidden", "1=server1=x"})
    CHECK_MSG(!ServerChoice::parse(text, &two, &err), "\"%s\" taken", text);
  CHECK(two.accepts(2) && !two.accepts(3));  // a refused text leaves the choice as it was
}

TEST(a_group_routes_by_match_and_counts_refused_writes) {
  Game g;  // match 7
  const ParticipantId me = participant(4);
  std::vector<BotPlayer> bots;
  for (int slot = 0; slot < 2; ++slot) {
    PlayerParams p;
    p.match = 7;
    p.player = slot;
    bots.emplace_back(p);
  }
  PlayerParams other;
  other.match = 8;
  bots.emplace_back(other);
  Players players(std::move(bots), me);
  FakeClientPort &port = players.net.port;
  PlayerGroup &group = players.group;
  auto tick = [&](double t) { players.tick(t); };
  tick(0.0);  // three JOINs
  CHECK(group.error().empty());
  CHECK_EQ(port.controls.size(), 3u);
  port.controls.clear();
  // both slots of match 7 taken by the group's participant; match 8 is not there
  g.control(ControlKind::join, me, 0);
  g.control(ControlKind::join, me, 1);
  server_says(g, port);
  tick(0.6);
  CHECK(group.bots()[0].joined() && group.bots()[1].joined());
  CHECK(!group.bots()[2].joined());
  CHECK(!group.all_joined());
  CHECK_EQ(port.controls.size(), 1u);  // only match 8's bot asks again
  CHECK_EQ(port.controls[0].match_id, 8u);
  // a segment of match 7 reaches its bots; one of match 9 no one
  g.run(0.2);  // the serve
  CHECK(!g.segments.empty());
  SegmentOut seg = g.segments.front(), stray = seg;
  stray.match_id = 9;
  port.segments = {seg, stray};
  tick(0.7);
  CHECK_EQ(group.report(0).segments, 1u);
  CHECK_EQ(group.report(2).segments, 0u);
  CHECK_EQ(group.segments(), 1u);
  // samples at 30 Hz from both joined bots over 1 s; the transport refuses
  // those of the first 0.2 s
  port.refuse = true;
  for (int k = 1; k <= 20; ++k) tick(0.7 + k * 0.01);
  port.refuse = false;
  for (int k = 21; k <= 100; ++k) tick(0.7 + k * 0.01);
  CHECK(port.samples.size() >= 46 && port.samples.size() <= 50);
  CHECK_EQ(group.samples_written(), port.samples.size());
  CHECK(group.write_failures() >= 10 && group.write_failures() <= 14);
  CHECK_EQ(group.leave(), 2);  // the two joined bots say LEAVE
  BotReport r = group.report(0);
  CHECK_EQ(r.match, 7u);
  CHECK_EQ(r.slot, 0);
  CHECK_EQ(r.write_failures, group.write_failures());  // (match 8 has none)
  // no simulated network: every pose the client took from the bots is written
  CHECK_EQ(group.bots()[0].counters().taken + group.bots()[1].counters().taken, group.samples_written());
  CHECK(group.error().empty());
}

// A JOIN the transport refuses (under DDS Security: a partition the
// identity is not granted) is the group's error, in the client's words;
// the match is not followed, and no bot asks again.
TEST(a_join_the_transport_refuses_is_the_groups_error) {
  PlayerParams p;
  p.match = 7;
  FakeNet net(participant(4));
  net.port.refuse = true;
  PlayerGroup group({BotPlayer(p)}, net.client);
  net.now = 0.0;
  group.tick(0.0);
  CHECK_MSG(group.error().find("the transport refused the join of match 7") != std::string::npos, "error: %s",
            group.error().c_str());
  ball_net_status st;
  CHECK_EQ(ball_net_status_of(net.client, 7, &st), BALL_ENOMATCH);  // not followed
  net.port.refuse = false;
  for (int k = 1; k <= 20; ++k) {
    net.now = k * 0.1;
    group.tick(net.now);
  }
  CHECK(net.port.controls.empty());
  CHECK(!group.bots()[0].joined());
}

// A bot given a later start says nothing before it (no JOIN, no sample);
// starts that are not one for every bot change nothing.
TEST(a_group_begins_each_bot_at_its_start) {
  std::vector<BotPlayer> bots;
  for (int slot = 0; slot < 2; ++slot) {
    PlayerParams p;
    p.match = 7;
    p.player = slot;
    bots.emplace_back(p);
  }
  Players players(std::move(bots), participant(4));
  FakeClientPort &port = players.net.port;
  PlayerGroup &group = players.group;
  auto tick = [&](double t) { players.tick(t); };
  group.start_at({0.0});  // one start for two bots: ignored
  group.start_at({0.0, 1.0});
  tick(0.0);
  tick(0.999);
  CHECK_EQ(port.controls.size(), 2u);  // bot 0's JOIN, and again 0.5 s on (unanswered)
  for (const ControlIn &c : port.controls) CHECK_EQ(c.player, 0);
  size_t before = port.controls.size();
  tick(1.0);
  CHECK_EQ(port.controls.size(), before + 1);
  CHECK_EQ(port.controls.back().player, 1);
}

CHECK_MAIN

namespace {

// what a tap was given, and what it did from inside
struct Tapped {
  std::vector<std::string> lines;
  ball_net_client *client = nullptr;
  bool poll_inside = false;   // it calls ball_net_poll (refused)
  bool watch_inside = false;  // it calls ball_net_watch (refused)
  ball_status inside = BALL_OK;
};

void keep_line(void *user, const char *line, size_t length) {
  auto *t = static_cast<Tapped *>(user);
  CHECK_EQ(std::strlen(line), length);
  t->lines.emplace_back(line, length);
  if (t->poll_inside) {
    int n = 0;
    t->inside = ball_net_poll(t->client, nullptr, 0, &n);
  }
  if (t->watch_inside) t->inside = ball_net_watch(t->client, 43);
}

}  // namespace

// The tap gives every sample the client takes, of any match and before the
// trust rules (another server's, a forged one, a match not followed), in
// the order taken, as record lines that read back bit for bit; "ready"
// once; none once it is removed; and calls that would end the poll are
// refused from inside it.
TEST(the_tap_gives_every_sample_as_it_came) {
  Game g;
  g.join(0, participant(1));
  g.join(1, participant(2));
  g.run(4.0);
  FakeNet net(participant(9), [](ball_net_config *c) {
    c->servers = "1";
    c->rackets = 1;
  });
  Tapped t;
  t.client = net.client;
  CHECK_EQ(ball_net_set_tap(nullptr, keep_line, &t), BALL_EINVAL);
  CHECK_EQ(ball_net_set_tap(net.client, keep_line, &t), BALL_OK);
  CHECK_EQ(ball_net_watch(net.client, g.match.id()), BALL_OK);
  uint64_t seed = 77;
  auto draw = [&seed](int n) {
    seed = seed * 6364136223846793005ull + 1442695040888963407ull;
    return static_cast<int>((seed >> 33) % static_cast<uint64_t>(n));
  };
  // a random mix of every kind, some of them not the chosen server's or not of the match followed
  std::map<std::string, size_t> fed;
  std::vector<json> verdicts;  // every line read back
  MatchInfoOut info = g.match.info();
  info.server_id = 1;
  int poll_rounds = 0;
  for (int round = 0; round < 40; ++round) {
    size_t before = t.lines.size();
    std::vector<std::pair<std::string, json>> round_fed;
    for (int k = draw(6); k >= 0; --k) {
      MatchInfoOut i = info;
      if (draw(3) == 0) i.server_id = 2;  // not chosen: refused, tapped all the same
      if (draw(4) == 0) i.match_id = 1000 + static_cast<uint32_t>(draw(5));  // not followed
      net.port.infos.push_back(i);
      round_fed.emplace_back("match_info", json(i));
    }
    for (int k = draw(4); k >= 0 && !g.segments.empty(); --k) {
      SegmentOut s = g.segments[static_cast<size_t>(draw(static_cast<int>(g.segments.size())))];
      s.server_id = draw(3) == 0 ? 2 : 1;
      net.port.segments.push_back(s);
      round_fed.emplace_back("segment", json(s));
    }
    for (int k = draw(4); k >= 0; --k) {
      EventOut e = g.events[static_cast<size_t>(draw(static_cast<int>(g.events.size())))];
      e.server_id = 1;
      net.port.events.push_back(e);
      round_fed.emplace_back("event", json(e));
    }
    for (int k = draw(3); k >= 0; --k) {
      StateOut s = g.states[static_cast<size_t>(draw(static_cast<int>(g.states.size())))];
      net.port.states.push_back(s);
      round_fed.emplace_back("state", json(s));
    }
    if (draw(2) == 0) {
      StatusOut s;
      s.server_id = 1 + static_cast<uint32_t>(draw(3));
      s.samples_in = static_cast<uint64_t>(draw(1000));
      net.port.statuses.push_back(s);
      round_fed.emplace_back("server_status", json(s));
    }
    if (draw(2) == 0) {
      RacketSampleIn r;
      r.match_id = g.match.id();
      r.player = draw(2);
      r.seq = static_cast<uint32_t>(round);
      r.from = participant(static_cast<uint8_t>(1 + draw(3)));  // the holder's, or a stranger's
      net.port.rackets.push_back(r);
      round_fed.emplace_back("racket_sample", json(r));
    }
    net.now += 0.05;
    int n = 0;
    ball_net_event ev[8];
    do CHECK_EQ(ball_net_poll(net.client, ev, 8, &n), BALL_OK);
    while (n == 8);
    poll_rounds++;
    // the ready line first of all, once
    if (round == 0) {
      CHECK(!t.lines.empty() && record_type(json::parse(t.lines[0])) == "ready");
      before = 1;
    }
    CHECK_EQ(t.lines.size() - before, round_fed.size());
    // every line read back is the sample fed, kind by kind in the order fed
    std::map<std::string, std::vector<json>> got, want;
    for (size_t i = before; i < t.lines.size(); ++i) {
      json line = json::parse(t.lines[i]);
      CHECK(line.at("recv").is_number());
      got[record_type(line)].push_back(line);
    }
    for (const auto &f : round_fed) want[f.first].push_back(f.second);
    for (const auto &kv : want) {
      fed[kv.first] += kv.second.size();
      CHECK_EQ(got[kv.first].size(), kv.second.size());
      for (size_t i = 0; i < kv.second.size() && i < got[kv.first].size(); ++i) {
        json j = got[kv.first][i];
        verdicts.push_back(j);
        for (const char *key : {"type", "recv", "trusted", "anew"}) j.erase(key);
        CHECK_MSG(j == kv.second[i], "%s line %zu is not the sample fed", kv.first.c_str(), i);
      }
    }
  }
  CHECK(fed["match_info"] > 40 && fed["segment"] > 40 && fed["event"] > 40 && fed["state"] > 40);
  // the client's verdict on each: never another server's, a racket sample only from its slot's
  // holder; and some of every kind the match takes
  std::map<std::string, size_t> trusted;
  for (const json &j : verdicts) {
    const std::string type = record_type(j);
    CHECK_MSG(j.at("trusted").is_boolean(), "%s line without a verdict", type.c_str());
    if (!j.at("trusted").get<bool>()) continue;
    trusted[type]++;
    if (type == "match_info" || type == "segment" || type == "event") CHECK(j.at("server").get<uint32_t>() == 1);
    if (type == "racket_sample") {
      RacketSampleIn r = j.get<RacketSampleIn>();
      CHECK(r.from == participant(static_cast<uint8_t>(1 + r.player)));
    }
  }
  CHECK(trusted["match_info"] > 10 && trusted["segment"] > 0 && trusted["event"] > 0 && trusted["server_status"] > 5);
  CHECK(trusted["match_info"] < fed["match_info"] && trusted["segment"] < fed["segment"]);
  // a model: its note line (the model itself: ball_net_model)
  MatchModelOut m;
  m.match_id = g.match.id();
  m.server_id = 1;
  ball_model_default(&m.model);
  m.model_hash = ball_model_hash(&m.model);
  net.port.models.push_back(m);
  int n = 0;
  size_t before = t.lines.size();
  CHECK_EQ(ball_net_poll(net.client, nullptr, 0, &n), BALL_OK);
  CHECK_EQ(t.lines.size(), before + 1);
  json note = json::parse(t.lines.back());
  CHECK(record_type(note) == "match_model" && note.at("model_hash").get<uint64_t>() == m.model_hash);
  // DDS's stamps: received as recv, written as sent
  SegmentOut stamped = g.segments.front();
  stamped.reception = Reception{1700000000.25, 1700000000.125};
  net.port.segments.push_back(stamped);
  CHECK_EQ(ball_net_poll(net.client, nullptr, 0, &n), BALL_OK);
  json line = json::parse(t.lines.back());
  CHECK_EQ(line.at("recv").get<double>(), 1700000000.25);
  CHECK_EQ(line.at("sent").get<double>(), 1700000000.125);
  CHECK(json::parse(t.lines[before]).count("sent") == 0);  // (none said: none given)
  before = t.lines.size() - 1;
  // a MatchInfo 2 s behind: the match started anew, and the line says so
  MatchInfoOut back = info;
  back.sim_time -= 2.0;
  back.server_time += 1.0;
  net.port.infos.push_back(back);
  CHECK_EQ(ball_net_poll(net.client, nullptr, 0, &n), BALL_OK);
  json again = json::parse(t.lines.back());
  CHECK_MSG(again.at("trusted").get<bool>() && again.value("anew", false), "%s", again.dump().c_str());
  CHECK(json::parse(t.lines[t.lines.size() - 2]).count("anew") == 0);
  before = t.lines.size() - 1;
  // from inside the tap: ball_net_poll refused, and the poll goes on
  t.poll_inside = true;
  net.port.events.push_back(g.events.front());
  net.port.events.push_back(g.events.back());
  CHECK_EQ(ball_net_poll(net.client, nullptr, 0, &n), BALL_OK);
  CHECK_EQ(t.inside, BALL_EINVAL);
  CHECK_EQ(t.lines.size(), before + 3);
  // segments of a match not followed come as they came (not trusted), and again, kept, when it is
  // followed: from within ball_net_watch, with that match's verdict
  t.poll_inside = false;
  MatchInfoOut other = info;
  other.match_id = 42;
  other.server_id = 1;
  net.port.infos.push_back(other);
  for (size_t i = 0; i < g.segments.size(); ++i) {
    SegmentOut s = g.segments[i];
    s.match_id = 42;
    s.server_id = 1;
    net.port.segments.push_back(s);
  }
  size_t mark = t.lines.size();
  CHECK_EQ(ball_net_poll(net.client, nullptr, 0, &n), BALL_OK);
  size_t untrusted = 0;
  for (size_t i = mark; i < t.lines.size(); ++i) {
    json j = json::parse(t.lines[i]);
    if (record_type(j) == "segment") untrusted += !j.at("trusted").get<bool>() && !j.contains("kept");
  }
  CHECK_EQ(untrusted, g.segments.size());
  mark = t.lines.size();
  CHECK_EQ(ball_net_watch(net.client, 42), BALL_OK);
  const size_t kept = t.lines.size() - mark;
  CHECK_EQ(kept, std::min<size_t>(g.segments.size(), 4));  // the newest 4 the client kept
  for (size_t i = mark; i < t.lines.size(); ++i) {
    json j = json::parse(t.lines[i]);
    CHECK(record_type(j) == "segment" && j.value("kept", false) && j.at("trusted").is_boolean());
    CHECK_EQ(j.at("seq").get<uint32_t>(), g.segments[g.segments.size() - kept + (i - mark)].seq);
  }
  // ball_net_watch from inside the tap: refused, nothing followed
  t.watch_inside = true;
  t.inside = BALL_OK;
  net.port.events.push_back(g.events.front());
  CHECK_EQ(ball_net_poll(net.client, nullptr, 0, &n), BALL_OK);
  CHECK_EQ(t.inside, BALL_EINVAL);
  ball_net_status st43;
  CHECK_EQ(ball_net_status_of(net.client, 43, &st43), BALL_ENOMATCH);
  t.watch_inside = false;
  // removed: nothing more
  mark = t.lines.size();
  CHECK_EQ(ball_net_set_tap(net.client, nullptr, nullptr), BALL_OK);
  net.port.events.push_back(g.events.front());
  CHECK_EQ(ball_net_poll(net.client, nullptr, 0, &n), BALL_OK);
  CHECK_EQ(t.lines.size(), mark);
  CHECK_EQ(ball_net_close(net.client), BALL_OK);
  CHECK_EQ(ball_net_set_tap(net.client, keep_line, &t), BALL_ECLOSED);
  CHECK(poll_rounds == 40);
}
