// Which server steps which match (placement.h, docs/protocol.md "Several
// servers on one domain"): the claim rule and the successor rule over random
// servers heard in random orders, then the server loop offline (a fake port
// and clock) as a standby that takes a match over and as a claimant.
#include <algorithm>
#include <cinttypes>
#include <cmath>
#include <functional>
#include <random>

#include "check.hpp"
#include "fake_port.h"
#include "game.h"
#include "placement.h"
#include "rng.h"

using namespace test;
using check::note;

namespace {

std::vector<ServerView> random_servers(std::mt19937_64 &g, int n) {
  std::vector<ServerView> v;
  std::vector<uint32_t> ids;
  while (static_cast<int>(ids.size()) < n) {
    uint32_t id = static_cast<uint32_t>(g() % 50);
    if (std::find(ids.begin(), ids.end(), id) == ids.end()) ids.push_back(id);
  }
  for (uint32_t id : ids) {
    ServerView s;
    s.server_id = id;
    s.strength = g() % 2 ? 20 : 10;
    s.standby = g() % 2;
    s.claim_room = static_cast<uint32_t>(g() % 4 == 0 ? 0 : g() % 40);
    s.alive = g() % 6 != 0;
    v.push_back(s);
  }
  return v;
}

}  // namespace

// 2,000 random domains, each heard in 5 orders: the same claims every time,
// each match once, to a live claimant with room, no claimant over its room,
// and as many matches placed as there is room.
TEST(the_claim_rule_does_not_depend_on_the_order_heard) {
  std::mt19937_64 g(20261202);
  int placed = 0;
  for (int n = 0; n < 2000; ++n) {
    std::vector<ServerView> servers = random_servers(g, 1 + static_cast<int>(g() % 6));
    std::vector<uint32_t> matches;
    for (int k = static_cast<int>(g() % 80); k > 0; --k) matches.push_back(static_cast<uint32_t>(g() % 500));
    std::map<uint32_t, uint32_t> first = assign_claims(matches, servers);
    for (int o = 0; o < 5; ++o) {
      std::shuffle(servers.begin(), servers.end(), g);
      std::shuffle(matches.begin(), matches.end(), g);
      CHECK(assign_claims(matches, servers) == first);
    }
    std::map<uint32_t, uint32_t> got;
    uint64_t room = 0;
    for (const auto &kv : first) got[kv.second]++;
    for (const auto &s : servers) {
      if (s.alive) room += s.claim_room;
      CHECK_MSG(got[s.server_id] <= (s.alive ? s.claim_room : 0), "server %u: %u claims, room %u", s.server_id,
                got[s.server_id], s.claim_room);
    }
    std::vector<uint32_t> distinct = matches;
    std::sort(distinct.begin(), distinct.end());
    distinct.erase(std::unique(distinct.begin(), distinct.end()), distinct.end());
    CHECK_EQ(first.size(), std::min<size_t>(distinct.size(), room));
    placed += static_cast<int>(first.size());
  }
  note("%d matches placed over 2000 domains, each the same in 5 orders", placed);
  CHECK(placed > 20000);
}

// With room enough, the matches spread evenly (rendezvous hashing), and a
// newcomer takes only matches for itself: no match moves between the others.
TEST(claims_spread_and_a_newcomer_moves_only_its_share) {
  std::vector<ServerView> three;
  for (uint32_t id : {1u, 2u, 3u}) {
    ServerView s;
    s.server_id = id;
    s.claim_room = 100000;
    three.push_back(s);
  }
  std::vector<uint32_t> matches(3000);
  for (uint32_t k = 0; k < 3000; ++k) matches[k] = k;
  std::map<uint32_t, uint32_t> a = assign_claims(matches, three);
  std::map<uint32_t, int> share;
  for (const auto &kv : a) share[kv.second]++;
  note("3000 matches on 3 claimants: %d, %d, %d", share[1], share[2], share[3]);
  for (uint32_t id : {1u, 2u, 3u}) CHECK(share[id] > 900 && share[id] < 1100);
  std::vector<ServerView> four = three;
  four.push_back(three[0]);
  four.back().server_id = 4;
  std::map<uint32_t, uint32_t> b = assign_claims(matches, four);
  int moved = 0, to_new = 0;
  for (uint32_t k = 0; k < 3000; ++k)
    if (a[k] != b[k]) moved++, to_new += b[k] == 4;
  note("a fourth claimant: %d matches move, all %d to it", moved, to_new);
  CHECK_EQ(moved, to_new);
  CHECK(to_new > 600 && to_new < 900);
}

// The successor of a lost owner: the strongest live standby, then the
// lowest id, never the owner itself; against a brute force over random domains.
TEST(the_successor_is_the_strongest_live_standby) {
  std::mt19937_64 g(7);
  int found = 0;
  for (int n = 0; n < 5000; ++n) {
    std::vector<ServerView> servers = random_servers(g, 1 + static_cast<int>(g() % 6));
    uint32_t owner = servers[g() % servers.size()].server_id;
    const ServerView *best = nullptr;
    for (const auto &s : servers)
      if (s.alive && s.standby && s.server_id != owner &&
          (!best || std::make_pair(-static_cast<int>(s.strength), s.server_id) <
                        std::make_pair(-static_cast<int>(best->strength), best->server_id)))
        best = &s;
    uint32_t who = 12345;
    bool any = successor(servers, owner, &who);
    CHECK_EQ(any, best != nullptr);
    if (best) CHECK_EQ(who, best->server_id);
    std::shuffle(servers.begin(), servers.end(), g);
    uint32_t again = 12345;
    successor(servers, owner, &again);
    CHECK_EQ(again, who);
    found += any;
  }
  CHECK(found > 2000);
}

// ---- the loop ----------------------------------------------------------------

namespace {

ParticipantId owner_participant() { return participant(77); }

// A standby's loop over a fake port, and an owner's match playing offline
// whose MatchInfo and segments the port hands it, as DDS would.
struct StandbyRig {
  Host host{16, true, default_config()};
  FakeClock clock;
  FakePort port;
  std::unique_ptr<ServerLoop> loop;
  Game owner;
  size_t segments_given = 0;
  bool give_model = false;  // the owner's MatchModel to the standby's port with every info
  uint32_t revision = 0;    // the owner's MatchInfo revision
  // with_scene: the standby has the owner's scene itself, by its name
  explicit StandbyRig(bool with_scene = true) {
    ball_scene scene;
    ball_scene_default(&scene);
    std::string err;
    if (with_scene) host.add_scene("tennis", scene, &err);
    port.clock = &clock;
    LoopSettings s;
    s.server_id = 2;
    s.standby = true;
    s.strength = 10;
    loop = std::make_unique<ServerLoop>(host, port, clock, s);
    StatusOut st;
    st.server_id = 1;
    st.strength = 20;
    port.other_status.push_back({st, owner_participant()});
    owner.join(0, participant(1));
    owner.join(1, participant(2));
    loop->start();
  }
  // the players' parked rackets, to the standby's port as to the owner
  void feed(double capture_time) {
    for (int i = 0; i < 2; ++i) {
      RacketSampleIn s = owner.parked_sample(i);
      s.capture_time = capture_time;
      port.samples.push_back(s);
    }
  }
  // the owner plays on and publishes, the standby's loop wakes alongside
  void play(double seconds) {
    int n = static_cast<int>(seconds * 60.0);
    for (int k = 0; k < n; ++k) {
      if (k % 6 == 0) feed(owner.match.sim().time);
      owner.run(1.0 / 60.0);
      for (; segments_given < owner.segments.size(); ++segments_given) {
        SegmentOut s = owner.segments[segments_given];
        s.server_id = 1;
        port.other_segments.push_back({s, owner_participant()});
      }
      MatchInfoOut i = owner.match.info();
      i.server_id = 1;
      i.server_time = clock.realtime();
      i.revision = ++revision;
      if (give_model) {
        MatchModelOut m;
        m.match_id = i.match_id;
        m.server_id = 1;
        m.model = owner.match.model();
        m.model_hash = ball_model_hash(&m.model);
        port.other_models.push_back({m, owner_participant()});
      }
      port.others.push_back({i, owner_participant()});
      clock.now += 1.0 / 60.0;
      loop->wake();
    }
  }
};

// A host with the tennis scene and `configured` matches (ids 0, 1, ...),
// with a fake port and clock, for a loop.
struct HostRig {
  Host host{16, true, default_config()};
  FakeClock clock;
  FakePort port;
  explicit HostRig(uint32_t configured) {
    port.clock = &clock;
    ball_scene scene;
    ball_scene_default(&scene);
    std::string err;
    host.add_scene("tennis", scene, &err);
    for (uint32_t k = 0; k < configured; ++k) {
      MatchConfig c = default_config();
      c.id = k;
      host.add_match(c, scene, &err);
    }
  }
};

// A claimant's view of itself (server 3) and of server 4, a claimant heard of.
std::vector<ServerView> three_and_four(uint32_t room3, uint32_t room4) {
  ServerView me, them;
  me.server_id = 3;
  me.claim_room = room3;
  them.server_id = 4;
  them.claim_room = room4;
  return {me, them};
}

// Starts a loop that heard server 4, a claimant with room `room4`, first.
void start_after_hearing_four(ServerLoop &loop, FakePort &port, uint32_t room4) {
  StatusOut other;
  other.server_id = 4;
  other.claim_room = room4;
  port.other_status.push_back({other, participant(40)});
  loop.listen(0.2, [] { return false; });
  loop.start();
}

}  // namespace

// A standby follows the owner's match, writes nothing, and takes it over
// a grace (takeover_grace) after the owner's writers are lost: its segments go on from the
// owner's newest seq (one written ahead included), its MatchInfo from the owner's revision, on the owner's clock.
TEST(a_standby_takes_a_match_over_when_its_owner_is_lost) {
  StandbyRig r;
  r.play(4.0);
  CHECK_EQ(r.loop->status_now().following, 1u);
  CHECK_EQ(r.loop->status_now().matches, 0u);
  CHECK(r.port.segments.empty() && r.port.events.empty() && r.port.infos.empty());
  CHECK(r.host.find(7) && r.host.find(7)->following());
  CHECK(!r.owner.segments.empty());
  uint32_t last_seq = r.owner.segments.back().seq;
  MatchInfoOut last = r.owner.match.info();
  double lost = r.clock.now;
  r.port.notes.push_back({PortNote::server_lost, owner_participant(), 1});
  // the owner stops; the standby wakes on its own
  const double grace = LoopSettings{}.takeover_grace;
  while (r.loop->cluster().stats().takeovers == 0 && r.clock.now < lost + 2.0) r.loop->step();
  // the first wake-up at or after the grace's end (the note is taken at the first one after `lost`)
  CHECK_EQ(r.loop->cluster().stats().takeovers, 1u);
  CHECK(r.clock.now >= lost + grace - 1e-9 && r.clock.now <= lost + grace + kFollowWake + 1e-9);
  CHECK_EQ(r.loop->status_now().following, 0u);
  CHECK(!r.host.find(7)->following());
  CHECK(!r.port.infos.empty());
  const MatchInfoOut &first = r.port.infos.front();
  note("taken over %.3f s after the owner was lost; first MatchInfo revision %u, segment %u (the owner's %u)",
       r.clock.now - lost, first.revision, first.segment_seq, last_seq);
  CHECK_EQ(first.server_id, 2u);
  CHECK(first.revision > 240u);  // the owner's went up to 240
  // the segment in effect when the owner went (the owner's newest may lie ahead of its contact)
  CHECK(first.segment_seq >= last.segment_seq);
  CHECK(first.play.score == last.play.score || first.play.rally > last.play.rally);
  // on the owner's clock: sim time at the info's instant as the owner's info maps it
  double mapped = last.sim_time + (first.server_time - (lost - 1.0 / 60.0 + kRealOffset)) * last.settings.time_base;
  CHECK_NEAR(first.sim_time, mapped, 1.0 / 60.0 + 1e-6);
  // the players go on with the standby: its segments go on from the owner's seq
  while (r.clock.now < lost + 4.0) {
    r.loop->step();
    if (r.loop->stats().totals.frames % 6 == 0) r.feed(r.host.find(7)->sim().time);
  }
  note("%zu segments from the standby in 4 s", r.port.segments.size());
  CHECK(r.port.segments.size() >= 2u);
  for (size_t k = 0; k < r.port.segments.size(); ++k)
    CHECK_EQ(r.port.segments[k].seq, last_seq + 1 + static_cast<uint32_t>(k));
  ServerReport rep = r.loop->report();
  CHECK(rep.matches.size() == 1u && rep.matches[0].taken_over);
}

// A standby with no scene of the match's name follows the match from the
// owner's MatchModel alone (docs/protocol.md, "The match's model"), through
// a level change, and takes it over; without the model it waits kModelWait
// for it, then cannot follow it, and a model whose hash is not the info's is
// not taken.
TEST(a_standby_without_the_scene_follows_from_the_wire_model) {
  {
    StandbyRig r(false);
    r.play(kModelWait - 0.2);  // the model may still come: nothing tried yet
    CHECK_EQ(r.loop->cluster().stats().follow_failures, 0u);
    r.play(1.0);
    note("no scene, no model: %llu follow failures", (unsigned long long)r.loop->cluster().stats().follow_failures);
    CHECK(r.loop->cluster().stats().follow_failures > 0u);
    CHECK_EQ(r.loop->status_now().following, 0u);
  }
  {
    StandbyRig r(false);
    MatchModelOut forged;
    forged.match_id = 7;
    forged.model = r.owner.match.model();
    forged.model.gravity = 3.7;  // not the owner's, under its hash
    forged.model_hash = r.owner.match.info().model_hash;
    r.port.other_models.push_back({forged, participant(99)});
    r.play(kModelWait + 0.5);
    CHECK(r.loop->cluster().stats().follow_failures > 0u);
    CHECK_EQ(r.loop->status_now().following, 0u);
  }
  StandbyRig r(false);
  r.give_model = true;
  r.play(2.0);
  CHECK_EQ(r.loop->cluster().stats().follow_failures, 0u);
  CHECK_EQ(r.loop->status_now().following, 1u);
  uint64_t easy = r.owner.match.info().model_hash;
  CHECK_EQ(r.host.find(7)->info().model_hash, easy);
  // the owner's players go to the advanced level: a new model, followed
  CHECK(r.owner.control(ControlKind::level, participant(1), -1, 3) == Reason::none);
  r.play(1.0);
  uint64_t advanced = r.owner.match.info().model_hash;
  CHECK(advanced != easy);
  CHECK_EQ(r.host.find(7)->info().model_hash, advanced);
  r.port.notes.push_back({PortNote::server_lost, owner_participant(), 1});
  double lost = r.clock.now;
  while (r.loop->cluster().stats().takeovers == 0 && r.clock.now < lost + 2.0) r.loop->step();
  CHECK_EQ(r.loop->cluster().stats().takeovers, 1u);
  // the new owner writes the model it steps, once
  while (r.clock.now < lost + 3.0) r.loop->step();
  CHECK_EQ(r.port.models.size(), 1u);
  if (!r.port.models.empty()) {
    CHECK_EQ(r.port.models[0].server_id, 2u);
    CHECK_EQ(r.port.models[0].model_hash, advanced);
    CHECK_EQ(ball_model_hash(&r.port.models[0].model), advanced);
  }
  CHECK(!r.port.infos.empty() && r.port.infos.back().model_hash == advanced);
}

// A stranger writes one forged MatchInfo (or Segment) of the followed match
// after the owner's last and leaves with the owner: the standby refuses what
// no server writes (counted as others_refused), takes the match over from
// the owner's own newest, on the owner's clock, within its grace, and the
// match plays on with its rules in range. Each forgery once hung the
// standby (a clock far away), wrote past score[1], or froze the match.
TEST(a_strangers_forged_info_never_takes_a_match_over) {
  struct Forgery {
    const char *what;
    std::function<void(MatchInfoOut &)> info;  // a forged MatchInfo
    std::function<void(SegmentOut &)> seg;     // or a forged Segment after a true copy of the info
  };
  const std::vector<Forgery> forgeries = {
      {"server_time -1e308", [](MatchInfoOut &i) { i.server_time = -1e308; }, nullptr},
      {"server_time 0", [](MatchInfoOut &i) { i.server_time = 0.0; }, nullptr},
      {"server_time an hour ago", [](MatchInfoOut &i) { i.server_time -= 3600.0; }, nullptr},
      {"sim_time 1e300", [](MatchInfoOut &i) { i.sim_time = 1e300; }, nullptr},
      {"striker 30000", [](MatchInfoOut &i) { i.play.striker = 30000; }, nullptr},
      {"serving_side -1", [](MatchInfoOut &i) { i.play.serving_side = -1; }, nullptr},
      {"serve_at NaN", [](MatchInfoOut &i) { i.play.serve_at = std::nan(""); }, nullptr},
      {"score INT_MAX", [](MatchInfoOut &i) { i.play.score[1] = 2147483647; }, nullptr},
      {"state 7", [](MatchInfoOut &i) { i.state = static_cast<MatchState>(7); }, nullptr},
      {"pause_reason 99", [](MatchInfoOut &i) { i.pause_reason = static_cast<Reason>(99); }, nullptr},
      {"info segment_cause 9", [](MatchInfoOut &i) { i.segment_cause = static_cast<Cause>(9); }, nullptr},
      {"segment striker 30000", nullptr, [](SegmentOut &s) { s.play.striker = 30000; }},
      {"segment cause 9", nullptr, [](SegmentOut &s) { s.cause = static_cast<Cause>(9); }},
      {"segment t0 1e300", nullptr, [](SegmentOut &s) { s.segment.t0 = 1e300; }},
  };
  const ParticipantId stranger = participant(99);
  for (const Forgery &f : forgeries) {
    StandbyRig r;
    r.play(4.0);
    MatchInfoOut last = r.owner.match.info();
    last.server_id = 1;
    last.server_time = r.clock.realtime() - 1.0 / 60.0;
    MatchInfoOut forged = last;
    forged.revision = 100000;
    if (f.info) f.info(forged);
    r.port.others.push_back({forged, stranger});
    if (f.seg) {
      SegmentOut s = current_segment(last);
      s.seq = last.segment_seq + 1;
      s.cause = Cause::floor;
      s.segment.t0 = last.sim_time;
      s.play = last.play;
      f.seg(s);
      r.port.other_segments.push_back({s, stranger});
    }
    uint64_t refused = r.loop->cluster().stats().others_refused + r.loop->cluster().stats().unknown_writers;
    r.loop->wake();
    r.port.notes.push_back({PortNote::server_lost, owner_participant(), 1});
    r.port.notes.push_back({PortNote::server_lost, stranger, 1});
    double lost = r.clock.now;
    int wakes = 0;
    while (r.loop->cluster().stats().takeovers == 0 && r.clock.now < lost + 2.0 && wakes++ < 1000) r.loop->step();
    const Match *m = r.host.find(7);
    // refused as no server's, or held back as no server heard alive (its segment then nobody's)
    CHECK_MSG(r.loop->cluster().stats().others_refused + r.loop->cluster().stats().unknown_writers > refused,
              "%s: not refused", f.what);
    CHECK_MSG(r.loop->cluster().stats().takeovers == 1u && m && !m->following(), "%s: not taken over (%" PRIu64 " failures)",
              f.what, r.loop->cluster().stats().follow_failures);
    if (!m || m->following()) continue;
    // on the owner's clock, from its own newest info
    double mapped = last.sim_time + (r.port.infos.front().server_time - last.server_time) * last.settings.time_base;
    CHECK_MSG(std::fabs(r.port.infos.front().sim_time - mapped) <= 1.0 / 60.0 + 1e-6, "%s: sim time %.3f, the owner's %.3f",
              f.what, r.port.infos.front().sim_time, mapped);
    double sim0 = m->sim().time;
    while (r.clock.now < lost + 6.0) {
      r.loop->step();
      if (r.loop->stats().totals.frames % 6 == 0) r.feed(m->sim().time);
    }
    PlayState p = m->play();
    bool in_range = (p.serving_side == 0 || p.serving_side == 1) && (p.striker == 0 || p.striker == 1) &&
                    p.score[0] >= last.play.score[0] && p.score[1] >= last.play.score[1] &&
                    p.score[0] < last.play.score[0] + 10 && p.score[1] < last.play.score[1] + 10;
    note("%s: refused, taken over; %.2f sim s played on, score %d:%d, %s", f.what, m->sim().time - sim0, p.score[0],
         p.score[1], name_of(m->state()));
    CHECK_MSG(in_range, "%s: rules out of range after the take-over", f.what);
    CHECK_MSG(m->state() == MatchState::playing && m->sim().time - sim0 > 3.0, "%s: the match did not play on", f.what);
  }
}

// Every control a loop takes is counted once: in controls_in, and in
// controls_refused unless it took effect here. A standby creates nothing and
// a claimant creates only the matches the claim rule gives it: the CREATEs
// they leave to another server took no effect here, so they are refused.
TEST(a_create_left_to_another_server_is_counted_refused) {
  for (int claimant = 0; claimant < 2; ++claimant) {
    HostRig h(0);
    FakePort &port = h.port;
    LoopSettings s;
    s.server_id = 3;
    s.standby = !claimant;
    s.claim = claimant ? 10 : 0;
    ServerLoop loop(h.host, port, h.clock, s);
    start_after_hearing_four(loop, port, 1000);
    const std::vector<ServerView> views = three_and_four(10, 1000);
    Rng r(20261206 + static_cast<uint64_t>(claimant));
    int sent = 0, ours = 0;
    for (int n = 0; n < 200; ++n) {
      ControlIn c;
      c.kind = ControlKind::create;
      c.match_id = static_cast<uint32_t>(r.uniform(0.0, 4096.0));
      c.scene = "tennis";
      c.from = participant(static_cast<uint8_t>(1 + n % 200));
      if (claimant && assign_claims({c.match_id}, views)[c.match_id] == 3) {
        if (ours >= 2) continue;  // (a few of its own: those take effect)
        ours++;
      }
      port.controls.push_back(c);
      sent++;
    }
    h.clock.now += 0.01;
    loop.wake();
    const StatusOut st = loop.status_now();
    note("%s: %d CREATEs, %d of them its own: %" PRIu64 " in, %" PRIu64 " refused, %u matches", claimant ? "claimant" : "standby",
         sent, ours, st.controls_in, st.controls_refused, st.matches);
    CHECK_EQ(st.controls_in, static_cast<uint64_t>(sent));
    CHECK_EQ(st.matches, static_cast<uint32_t>(ours));
    CHECK_EQ(st.controls_refused, static_cast<uint64_t>(sent - ours));
    CHECK_EQ(loop.report().creates_elsewhere, static_cast<uint64_t>(sent - ours));
  }
}

// What a loop keeps of the others (ServerStatus writers, match owners
// heard of) stays bounded however many forged writers and match ids come
// and go: 20,000 forged ServerStatus and MatchInfo, each from a writer of
// its own under a random match id, half of the writers lost soon after.
TEST(what_a_loop_keeps_of_strangers_is_bounded) {
  HostRig h(8);
  CHECK_EQ(h.host.matches().size(), 8u);
  FakeClock &clock = h.clock;
  FakePort &port = h.port;
  LoopSettings s;
  s.server_id = 3;
  s.claim = 4;
  ServerLoop loop(h.host, port, clock, s);
  loop.start();
  Game owner;  // a usable MatchInfo to forge from
  Rng r(20261207);
  size_t most_peers = 0, most_owners = 0;
  for (int n = 0; n < 20000; ++n) {
    ParticipantId w{};
    for (auto &b : w) b = static_cast<uint8_t>(r.next());
    StatusOut st;
    st.server_id = static_cast<uint32_t>(r.next());
    port.other_status.push_back({st, w});
    MatchInfoOut i = owner.match.info();
    i.match_id = static_cast<uint32_t>(r.next());
    i.server_id = st.server_id;
    i.server_time = clock.realtime();
    port.others.push_back({i, w});
    if (n % 2 == 0) port.notes.push_back({PortNote::server_lost, w, 1});
    if (n % 100 == 99) {
      clock.now += 0.01;
      loop.wake();
      most_peers = std::max(most_peers, loop.cluster().peers_known());
      most_owners = std::max(most_owners, loop.cluster().owners_known());
    }
  }
  note("20000 forged writers and match ids: at most %zu peers kept (cap %zu), %zu owners (of 8 candidates)",
       most_peers, kMaxPeers, most_owners);
  CHECK(most_peers <= kMaxPeers);
  CHECK(most_owners <= 8u);
  // the owners of its configured matches it still keeps (a server heard alive)
  StatusOut alive;
  alive.server_id = 50;
  port.other_status.push_back({alive, participant(50)});
  for (uint32_t k = 0; k < 8; ++k) {
    MatchInfoOut i = owner.match.info();
    i.match_id = k;
    i.server_time = clock.realtime();
    port.others.push_back({i, participant(50)});
  }
  clock.now += 0.01;
  loop.wake();
  note("then the owner of each of its 8 configured matches: %zu owners kept", loop.cluster().owners_known());
  CHECK_EQ(loop.cluster().owners_known(), 8u);
}

// Of 8 configured matches, a claimant that hears another claimant takes the
// ones the claim rule gives it, and steps them only after it settled.
TEST(a_claimant_takes_its_share_after_settling) {
  Host host{16, true, default_config()};
  FakeClock clock;
  FakePort port;
  port.clock = &clock;
  ball_scene scene;
  ball_scene_default(&scene);
  std::string err;
  host.add_scene("tennis", scene, &err);
  std::vector<uint32_t> ids;
  for (uint32_t k = 0; k < 8; ++k) {
    MatchConfig c = default_config();
    c.id = k;
    CHECK(host.add_match(c, scene, &err));
    ids.push_back(k);
  }
  LoopSettings s;
  s.server_id = 3;
  s.claim = 10;
  s.settle = 1.0;
  ServerLoop loop(host, port, clock, s);
  start_after_hearing_four(loop, port, 10);
  std::map<uint32_t, uint32_t> rule = assign_claims(ids, three_and_four(10, 10));
  std::vector<uint32_t> mine;
  for (const auto &kv : rule)
    if (kv.second == 3) mine.push_back(kv.first);
  note("the rule gives server 3 %zu of 8 matches", mine.size());
  CHECK(!mine.empty() && mine.size() < 8);
  CHECK_EQ(loop.status_now().matches, static_cast<uint32_t>(mine.size()));
  CHECK_EQ(loop.cluster().stats().claims, mine.size());
  CHECK_EQ(loop.status_now().claim_room, 10u - static_cast<uint32_t>(mine.size()));
  for (uint32_t id : ids) CHECK_EQ(host.find(id) != nullptr, rule[id] == 3);
  double start = clock.now;
  while (clock.now < start + 0.9) loop.step();
  CHECK_EQ(loop.stats().totals.frames, 0u);  // settling: nothing moves
  while (clock.now < start + 1.5) loop.step();
  CHECK(loop.stats().totals.frames > 0u);
}

CHECK_MAIN
