// The watcher without a network (watcher.h): its client of the client
// library fed from a Match (watch_rig.h): the tally,
// the desync check (and states whose segment comes later or never), missed
// events, its own ball at its estimate of the sim clock, the snapshot
// schedule, the record lines and the summary, with numbers.
#include <algorithm>
#include <cmath>
#include <map>

#include "check.hpp"
#include "game.h"
#include "rally.h"
#include "watch_rig.h"

using namespace test;

namespace {

// the match's info as the server writes it: its sim time holds from `server_time` on
MatchInfoOut info_at(const Game &g, double sim_time, double server_time, MatchState state) {
  MatchInfoOut i = g.match.info();
  i.server_id = g.server_id;  // as its server writes it
  i.term = g.term;
  i.sim_time = sim_time;
  i.server_time = server_time;
  i.state = state;
  return i;
}

size_t count_type(const WatchOutput &out, const std::string &type) {
  size_t n = 0;
  for (const auto &r : out.records) n += record_type(r) == type;
  return n;
}

}  // namespace

TEST(tally_and_desync_from_a_match) {
  Game g = played(12.0);
  WatchRig w(WatcherSettings{});
  w.on_start(1000.0);
  w.on_info(g.match.info(), 1000.0);
  // as they come: a state after the segments written up to it (one ahead of its bounce included)
  size_t given = 0;
  for (const auto &st : g.states) {
    for (; given < g.segments.size() && static_cast<int32_t>(g.segments[given].seq - st.segment_seq) <= 1; ++given)
      w.on_segment(g.segments[given], 1000.1);
    w.on_state(st, 1000.1);
    w.check_states();
  }
  for (const auto &e : g.events) w.on_event(e, 1000.1);
  WatchSummary sum = w.summary(12.0);
  CHECK_EQ(sum.matches.size(), 1u);
  const WatchedMatchSummary &m = sum.matches[0];
  CHECK_EQ(m.match, g.match.id());
  CHECK_EQ(m.serves, static_cast<uint64_t>(g.count(EventKind::serve)));
  CHECK_EQ(m.points, static_cast<uint64_t>(g.count(EventKind::point)));
  CHECK(m.points >= 2);  // nobody returns: a point a serve, 1.5 s apart
  uint64_t in_play_bounces = 0;
  for (const auto &e : g.events) in_play_bounces += e.kind == EventKind::floor && e.in_play;
  CHECK_EQ(m.bounces, in_play_bounces);
  CHECK_EQ(m.hits, 0u);
  uint64_t loud = 0;  // (the sound is its collision's flag: no EVENT_SOUND is written)
  for (const auto &e : g.events) loud += e.sound && is_collision(e.kind);
  CHECK_EQ(g.count(EventKind::sound), 0);
  CHECK(loud > 0);
  CHECK_EQ(m.sounds, loud);
  CHECK(m.score == g.match.score());
  CHECK_EQ(m.events_missed, 0u);
  // every state checked against its segment: the same closed form on the same numbers
  CHECK_EQ(m.states, g.states.size());
  CHECK_EQ(m.states_checked, g.states.size());
  CHECK_EQ(m.states_unmatched, 0u);
  CHECK(m.max_error <= 1e-12);
  CHECK_EQ(m.segments, g.segments.back().seq);
  // one record line per sample, after the start line
  WatchOutput &out = w.output();
  CHECK_EQ(record_type(out.records.front()), std::string("start"));
  CHECK_EQ(count_type(out, "ready"), 1u);
  CHECK_EQ(count_type(out, "segment"), g.segments.size());
  CHECK_EQ(count_type(out, "event"), g.events.size());
  CHECK_EQ(count_type(out, "state"), g.states.size());
  CHECK_EQ(count_type(out, "match_info"), 1u);
  CHECK_EQ(out.records.size(), 3 + g.segments.size() + g.events.size() + g.states.size());
  // the rally log: the state once, then a line per event worth one
  CHECK_EQ(out.log.front().text.find("match playing (tennis, level easy, 2 players"), 0u);
  size_t lines = 1;
  for (const auto &e : g.events) lines += !rally_line(e).empty();
  CHECK_EQ(out.log.size(), lines);
}

// A correction voids the events written before it for a later time
// (docs/protocol.md, "Corrections"): rallies behind 100 ms with lag
// compensation, rewind_own_hit off and on (moved hits, bounces the hits
// prevented), fed to a watcher as written, a wake-up's segments before its
// events and after them, and the events 0.3 s behind the segments (two
// topics: either may come first, and a correction before events it voids).
// Its tally of hits and bounces is the server's stats' in each order.
TEST(a_correction_voids_what_it_took_back) {
  int voided[2] = {0, 0}, runs = 0;
  for (int own = 0; own < 2; ++own)
    for (ball_level level : {BALL_LEVEL_MID, BALL_LEVEL_ADVANCED})
      for (uint64_t seed = 1; seed <= 4; ++seed) {
        MatchConfig c = default_config();
        c.level = level;
        c.seed = seed;
        c.rewind_own_hit = own == 1;
        Net net;
        net.delay = 0.1;
        net.noise = 0.002;
        net.plan_ahead = false;
        RallyResult r = play(c, net, 30.0, seed);
        Game g(c);
        for (int order = 0; order < 3; ++order) {
          WatchRig w(WatcherSettings{});
          w.on_start(1000.0);
          w.on_info(g.match.info(), 1000.0);
          // as written: each event with the segment in effect when it was (its
          // wake-up's), the segments of a wake-up before its events or after
          std::map<uint32_t, double> written;
          for (size_t i = 0; i < r.segments.size(); ++i) written[r.segments[i].seq] = r.written_at[i];
          std::vector<std::pair<double, long>> feed;  // (write time, segment i or -1 - event i)
          for (size_t i = 0; i < r.segments.size(); ++i) feed.push_back({r.written_at[i], static_cast<long>(i)});
          for (size_t i = 0; i < r.events.size(); ++i) {
            auto it = written.find(r.events[i].segment_seq);
            double late = order == 2 ? 0.3 : 0.0;  // (events held up: later corrections come first)
            feed.push_back({(it == written.end() ? 0.0 : it->second) + late, -1 - static_cast<long>(i)});
          }
          std::stable_sort(feed.begin(), feed.end(), [order](const auto &a, const auto &b) {
            if (a.first != b.first) return a.first < b.first;
            return order == 0 ? a.second >= 0 && b.second < 0 : a.second < 0 && b.second >= 0;
          });
          for (const auto &f : feed) {
            if (f.second >= 0)
              w.on_segment(r.segments[static_cast<size_t>(f.second)], 1000.1);
            else
              w.on_event(r.events[static_cast<size_t>(-1 - f.second)], 1000.1);
          }
          const WatchedMatchSummary m = w.summary(30.0).matches.at(0);
          CHECK_EQ(m.hits, r.counters.hits);
          CHECK_EQ(m.bounces, r.counters.bounces);
          voided[own] += static_cast<int>(m.voided);
        }
        runs++;
      }
  check::note("%d rallies behind 100 ms, each fed in three orders: %d events voided without "
       "rewind_own_hit, %d with it; the watcher's hits and bounces are the server's",
       runs, voided[0], voided[1]);
  CHECK(voided[1] >= 100);
}

TEST(a_state_waits_for_its_segment_or_is_counted_unmatched) {
  Game g = played(3.0);
  CHECK(g.segments.size() >= 3);
  WatchRig w(WatcherSettings{});
  w.on_info(g.match.info(), 0.0);
  // a state on segment 2 before segment 2 arrives: it waits
  const StateOut *on2 = nullptr;
  for (const auto &s : g.states)
    if (s.segment_seq == 2) on2 = &s;
  CHECK(on2 != nullptr);
  if (!on2) return;
  w.on_segment(g.segments[0], 0.0);
  w.on_state(*on2, 0.0);
  w.check_states();
  CHECK_EQ(w.summary(0).matches[0].states_checked, 0u);
  CHECK_EQ(w.summary(0).matches[0].states_unmatched, 0u);
  w.on_segment(g.segments[1], 0.0);
  w.check_states();
  CHECK_EQ(w.summary(0).matches[0].states_checked, 1u);
  // a state on segment 1 when the watcher only holds newer ones: too old, unmatched
  WatchRig late(WatcherSettings{});
  late.on_info(g.match.info(), 0.0);
  late.on_segment(g.segments[1], 0.0);
  late.on_segment(g.segments[2], 0.0);
  StateOut on1 = g.states.front();
  CHECK_EQ(on1.segment_seq, 1u);
  late.on_state(on1, 0.0);
  late.check_states();
  CHECK_EQ(late.summary(0).matches[0].states_unmatched, 1u);
  CHECK_EQ(late.summary(0).matches[0].states_checked, 0u);
}

TEST(gaps_in_the_event_sequence_are_missed_events) {
  Game g = played(1.0);
  WatchRig w(WatcherSettings{});
  MatchInfoOut info = g.match.info();
  info.match_id = 3;
  w.on_info(info, 0.0);
  EventOut e;
  e.match_id = 3;
  e.kind = EventKind::join;
  for (uint32_t seq : {1u, 2u, 5u, 6u, 10u}) {
    e.seq = seq;
    w.on_event(e, 0.0);
  }
  CHECK_EQ(w.summary(0).matches[0].events_missed, 2u + 3u);
}

TEST(own_ball_at_the_estimated_sim_clock) {
  Game g = played(2.0);
  WatcherSettings s;
  s.record_frames = true;
  WatchRig w(s);
  const double server = 5000.0, latency = 0.01;
  const SegmentOut &seg = g.segments.back();
  double t0 = seg.segment.t0;
  w.on_segment(seg, server + latency);
  // sim time t0 holds from server time 5000 (playing); received 10 ms later
  w.on_info(info_at(g, t0, server, MatchState::playing), server + latency);
  w.output().clear();
  w.frame(server + latency + 0.25);  // a quarter of a second later here: the sim clock 0.25 s on
  CHECK_EQ(w.output().records.size(), 1u);
  if (w.output().records.empty()) return;
  OwnFrame f = w.output().records[0].get<OwnFrame>();
  CHECK_NEAR(f.sim_time, t0 + 0.25, 1e-9);
  CHECK_EQ(f.segment_seq, seg.seq);
  ball_state b;
  CHECK_EQ(ball_segment_eval(&g.match.model(), &seg.segment, f.sim_time, &b), BALL_OK);
  CHECK_NEAR(f.position.y, b.position.y, 0.0);
  CHECK_EQ(w.summary(0).matches[0].frames, 1u);
  // before the segment starts there is nothing to draw
  WatchRig early(s);
  early.on_segment(seg, server);
  early.on_info(info_at(g, t0 - 1.0, server, MatchState::paused), server);
  early.frame(server + 1.0);
  CHECK_EQ(count_type(early.output(), "frame"), 0u);
}

TEST(snapshots_fall_due_on_multiples_of_their_period) {
  Game g = played(2.0);
  WatcherSettings s;
  s.snapshot_every = 0.5;
  WatchRig w(s);
  double t0 = g.segments[0].segment.t0;  // the serve, at sim time 0
  CHECK_EQ(t0, 0.0);
  w.on_info(info_at(g, 0.0, 0.5, MatchState::paused), 0.5);  // (the match followed from its first info)
  w.on_segment(g.segments[0], 0.5);
  EventOut bounce;
  bounce.match_id = g.match.id();
  bounce.server_id = g.server_id;
  bounce.term = g.term;
  bounce.kind = EventKind::floor;
  bounce.time = 0.4;
  bounce.seq = 1;
  w.on_event(bounce, 0.5);
  // the watcher's clock put at each sim time (a paused match: sim_now is sim_time)
  std::vector<double> due;
  double server = 1.0;
  for (double t : {0.1, 0.3, 0.55, 0.7, 1.02, 1.2, 1.49, 1.5}) {
    w.on_info(info_at(g, t, server, MatchState::paused), server);
    server += 1.0;
    w.frame(server);
    for (const auto &d : w.output().snapshots) due.push_back(d.sim_time);
    if (!w.output().snapshots.empty() && due.size() == 1) {
      const SnapshotDue &d = w.output().snapshots[0];
      CHECK_EQ(d.trail.size(), 3u);          // own frames at 0.1, 0.3 and 0.55: the last second
      CHECK_EQ(d.events.size(), 1u);         // the bounce at 0.4 s
      CHECK_EQ(d.events[0].kind, BALL_EVENT_FLOOR);
      SnapshotRecord drawn;
      drawn.file = "m7_t0000.550.png";
      drawn.camera = "top";
      drawn.size = {320, 240};
      drawn.racket_drawn[1] = true;
      drawn.rackets[1] = ball_v3(22.0, 1.0, 5.0);
      w.snapshot_written(d, drawn, server);
      // the record line: what was drawn, at the due frame's time and ball
      SnapshotRecord r = w.output().records.back().get<SnapshotRecord>();
      CHECK_EQ(r.file, drawn.file);
      CHECK_NEAR(r.sim_time, d.sim_time, 0.0);
      CHECK_NEAR(r.position.x, d.ball.x, 0.0);
      CHECK(!r.racket_drawn[0] && r.racket_drawn[1]);
      CHECK_NEAR(r.rackets[1].x, 22.0, 0.0);
    }
    w.output().snapshots.clear();
  }
  // the first own frame at or after 0.5, 1.0, 1.5
  CHECK_EQ(due.size(), 3u);
  if (due.size() == 3) {
    CHECK_NEAR(due[0], 0.55, 0.0);
    CHECK_NEAR(due[1], 1.02, 0.0);
    CHECK_NEAR(due[2], 1.5, 0.0);
  }
  CHECK_EQ(w.summary(0).matches[0].snapshots, 1u);
  CHECK_EQ(count_type(w.output(), "snapshot"), 1u);
}

TEST(one_match_only_and_ready_once) {
  Game g = played(1.0);
  WatcherSettings s;
  s.match = 3;  // not g's (7)
  WatchRig w(s);
  w.turn(1.0);  // (the client hears a server: the ready line, once)
  w.turn(2.0);
  w.on_info(g.match.info(), 1.0);
  for (const auto &x : g.segments) w.on_segment(x, 1.0);
  for (const auto &e : g.events) w.on_event(e, 1.0);
  CHECK_EQ(w.output().records.size(), 1u);  // the one ready line
  CHECK_EQ(record_type(w.output().records[0]), std::string("ready"));
  CHECK(w.summary(0).matches.empty());
  CHECK(w.output().log.empty());
}

// Every line of the client's tap reaches the watcher: a server's status
// (its summary's), and a sample whose numbers its type cannot hold (a
// cause no name fits), recorded as it came, counted, not used.
TEST(status_and_unreadable_lines) {
  Game g = played(2.0);
  WatchRig w(WatcherSettings{});
  w.on_info(g.match.info(), 1.0);
  StatusOut status;
  status.server_id = 4;
  status.samples_in = 17;
  w.on_status(status, 1.1);
  WatchSummary sum = w.summary(1.0);
  CHECK_EQ(sum.servers.size(), 1u);
  CHECK(!sum.servers.empty() && sum.servers[0].server_id == 4u && sum.servers[0].samples_in == 17u);
  size_t recorded = count_type(w.output(), "segment");
  SegmentOut odd = g.segments.back();
  odd.seq += 1;
  odd.cause = static_cast<Cause>(99);
  w.on_segment(odd, 1.2);
  CHECK_EQ(count_type(w.output(), "segment"), recorded + 1);
  CHECK_EQ(w.output().records.back().at("cause").get<std::string>(), std::string("unknown"));
  CHECK_EQ(w.w.unreadable(), 1u);
  CHECK_EQ(w.summary(1.0).matches.at(0).not_taken, 1u);
  CHECK_EQ(w.summary(1.0).matches.at(0).segments, g.match.info().segment_seq);  // (the info's): the odd one not used
}

TEST(summary_lines_say_the_numbers) {
  WatchSummary s;
  WatchedMatchSummary m;
  m.match = 2;
  m.hits = 10;
  m.states = 602;
  m.states_checked = 600;
  m.score = {3, 1};
  s.matches = {m};
  StatusOut o;
  o.server_id = 1;
  o.samples_in = 371;
  o.samples_ok = 365;
  o.samples_idle = 2;
  o.drops[static_cast<int>(SampleResult::stale)] = 4;
  o.write_failures = 1;
  s.servers = {o};
  s.latency_p50 = 0.0121;
  s.latency_count = 10;
  std::vector<std::string> lines = summary_lines(s);
  CHECK_EQ(lines.size(), 3u);
  CHECK_MSG(lines[0].find("match 2: 10 hits") != std::string::npos, "%s", lines[0].c_str());
  CHECK_MSG(lines[0].find("600 of 602 ball states checked") != std::string::npos, "%s", lines[0].c_str());
  CHECK_MSG(lines[1].find("371 racket samples in, 365 accepted, 2 idle, dropped 4 (stale 4), 1 writes refused") !=
                std::string::npos,
            "%s", lines[1].c_str());
  CHECK_MSG(lines[2].find("p50 12.1 ms") != std::string::npos, "%s", lines[2].c_str());
}

CHECK_MAIN

// What does not fit is recorded (it arrived) but not used, and counted: a
// segment 0xFFFFFFFF ahead, another server's samples when server 1 was
// chosen, a MatchInfo with level 99 or a clock 1e6 s away; the watcher's
// own ball stays on the real stream.
TEST(what_does_not_fit_is_recorded_not_used) {
  Game g = played(3.0);
  WatchRig w(WatcherSettings{}, [](ball_net_config *c) { c->servers = "1"; });
  MatchInfoOut info = info_at(g, g.match.sim().time, 1000.0, MatchState::playing);
  info.server_id = 1;
  w.on_info(info, 1000.0);
  for (SegmentOut s : g.segments) {
    s.server_id = 1;
    w.on_segment(s, 1000.0);
  }
  uint32_t newest = g.segments.back().seq;
  SegmentOut forged = g.segments.back();
  forged.server_id = 1;
  forged.seq = 0xFFFFFFFFu;
  w.on_segment(forged, 1000.0);
  forged.seq = newest + 1;
  forged.server_id = 2;  // not chosen
  w.on_segment(forged, 1000.0);
  forged.server_id = 1;
  forged.segment.p0.y = NAN;  // no evaluation can use it
  w.on_segment(forged, 1000.0);
  MatchInfoOut bad = info;
  bad.level = 99;
  w.on_info(bad, 1000.1);
  bad = info;
  bad.server_time = 1e6;  // a clock 1e6 s away
  w.on_info(bad, 1000.1);
  const WatchedMatchSummary m = w.summary(1).matches[0];
  CHECK_EQ(m.not_taken, 5u);
  CHECK_EQ(m.segments, newest);
  CHECK_EQ(count_type(w.output(), "segment"), g.segments.size() + 3);  // recorded all the same
  CHECK_EQ(count_type(w.output(), "match_info"), 3u);
}

// A stranger fills the client's room with made-up matches (each heard
// once, then disposed or never heard again): a real match that comes 10 s
// later is listed, followed and shown, its segments taken; what went is
// counted; while the made-up ones are still heard, the real one waits.
TEST(a_full_room_lets_go_of_silent_matches) {
  constexpr int kRoom = 8;
  Game g = played(3.0);
  WatchRig w(WatcherSettings{}, [](ball_net_config *c) { c->max_matches = kRoom; });
  for (uint32_t k = 0; k < 3 * kRoom; ++k) {  // three rooms' worth, in the first second
    MatchInfoOut fake = info_at(g, 1.0, 1000.0 + k * 0.01, MatchState::waiting);
    fake.match_id = 5000 + k;
    w.on_info(fake, 1000.0 + k * 0.01);
  }
  std::vector<uint32_t> ids = w.w.match_ids();
  CHECK_EQ(std::count_if(ids.begin(), ids.end(), [](uint32_t id) { return id >= 5000; }), kRoom);
  // the real match while they are heard: not followed yet
  MatchInfoOut real = info_at(g, g.match.sim().time, 1005.0, MatchState::playing);
  w.on_info(real, 1005.0);
  ball_net_status st;
  CHECK(ball_net_status_of(w.net.client, g.match.id(), &st) != BALL_OK);
  CHECK_EQ(w.w.let_go(), 0u);
  // 10 s after they were last heard
  real.server_time = 1011.0;
  w.on_info(real, 1011.0);
  for (const auto &s : g.segments) w.on_segment(s, 1011.0);
  CHECK_EQ(ball_net_status_of(w.net.client, g.match.id(), &st), BALL_OK);
  WatchedView v;
  CHECK(w.w.view(g.match.id(), &v));
  CHECK_EQ(v.segments->size(), g.segments.size());
  CHECK_EQ(w.w.let_go(), static_cast<uint64_t>(3 * kRoom));  // (every made-up one: none is served)
  ids = w.w.match_ids();
  CHECK_EQ(ids.size(), 1u);
}

// A stranger copies the server's id and term (an open domain): one event
// of its own, a point 999 seqs ahead with the score 0-99, and a ball state
// whose sim time lies 100 s ahead. The samples the server's participant
// wrote keep coming and are taken; the stranger's are refused: the score,
// the missed events and the clock stay the server's. A server restarted
// under its old term (another participant) is taken once the first has
// been silent for kOwnerWriter.
TEST(a_copy_of_the_owner_from_another_participant_is_refused) {
  Game g = played(12.0);
  const ParticipantId server = participant(7), stranger = participant(66);
  WatchRig w(WatcherSettings{});
  MatchInfoOut info = info_at(g, g.match.sim().time, 1000.0, MatchState::playing);
  info.reception.from = server;
  w.on_info(info, 1000.0);
  for (SegmentOut s : g.segments) {
    s.reception.from = server;
    w.on_segment(s, 1000.0);
  }
  const size_t half = g.events.size() / 2;
  for (size_t k = 0; k < half; ++k) {
    EventOut e = g.events[k];
    e.reception.from = server;
    w.on_event(e, 1000.0);
  }
  EventOut forged = g.events[half - 1];
  forged.reception.from = stranger;
  forged.kind = EventKind::point;
  forged.score = {0, 99};
  forged.seq += 999;
  w.on_event(forged, 1000.1);
  ball_net_match before;
  CHECK_EQ(ball_net_match_info(w.net.client, g.match.id(), &before), BALL_OK);
  StateOut st = g.states.back();
  st.reception.from = stranger;
  st.sim_time += 100.0;
  st.server_time = 1000.1;
  w.on_state(st, 1000.1);
  ball_net_match after;
  CHECK_EQ(ball_net_match_info(w.net.client, g.match.id(), &after), BALL_OK);
  CHECK(std::fabs(after.sim_time - before.sim_time) < 1.0);  // (the clock: not moved 100 s)
  for (size_t k = half; k < g.events.size(); ++k) {
    EventOut e = g.events[k];
    e.reception.from = server;
    w.on_event(e, 1000.2);
  }
  WatchedMatchSummary m = w.summary(12).matches[0];
  CHECK_EQ(m.events_missed, 0u);
  CHECK_EQ(m.points, static_cast<uint64_t>(g.count(EventKind::point)));
  CHECK_EQ(m.score[0], g.match.info().play.score[0]);
  CHECK_EQ(m.score[1], g.match.info().play.score[1]);
  ball_net_status status;
  CHECK_EQ(ball_net_status_of(w.net.client, g.match.id(), &status), BALL_OK);
  CHECK(status.refused >= 2u);
  // the server restarted under its old term, another participant: taken after kOwnerWriter
  MatchInfoOut again = info;
  again.reception.from = participant(8);
  again.server_time = 1003.0;
  again.sim_time = info.sim_time + 3.0;  // (its clock goes on)
  w.on_info(again, 1003.0);
  ball_net_status later;
  CHECK_EQ(ball_net_status_of(w.net.client, g.match.id(), &later), BALL_OK);
  CHECK_EQ(later.refused, status.refused + 1);
  again.server_time = 1005.3;
  again.sim_time = info.sim_time + 5.3;
  w.on_info(again, 1005.3);  // (5.1 s after the first participant's last)
  CHECK_EQ(ball_net_status_of(w.net.client, g.match.id(), &later), BALL_OK);
  CHECK_EQ(later.refused, status.refused + 1);
}
