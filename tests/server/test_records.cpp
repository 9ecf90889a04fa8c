// The JSON records (records.h): what a match produces, and reports with a
// value in every field, written, printed as text, parsed and read back,
// give every field again, bit for bit; a line names its type.
#include <cmath>

#include "check.hpp"
#include "game.h"
#include "records.h"

using namespace test;

namespace {

// through text and back, as a record file does it
template <class T>
T round_trip(const T &x) {
  std::string text = json(x).dump();
  return json::parse(text).get<T>();
}

// every field again: the two serialise to the same JSON (doubles compared exactly)
template <class T>
bool same(const T &a, const T &b) {
  return json(a) == json(b);
}

// reading `j` as a T is an error, not a silent default
template <class T>
bool unreadable_as(const json &j) {
  try {
    j.get<T>();
  } catch (const std::exception &) {
    return true;
  }
  return false;
}

// a game with both slots joined, 6 s of play: serves, bounces, points, states
Game played() {
  Game g;
  g.join(0, participant(1));
  g.join(1, participant(2));
  g.run(6.0);
  return g;
}

}  // namespace

TEST(samples_of_a_match_come_back_bit_for_bit) {
  Game g = played();
  CHECK(g.segments.size() >= 4);
  CHECK(g.events.size() >= 8);
  CHECK(g.states.size() >= 300);
  int n = 0;
  for (const auto &s : g.segments) {
    SegmentOut back = round_trip(s);
    CHECK(same(back, s));
    CHECK_EQ(back.segment.p0.y, s.segment.p0.y);
    CHECK_EQ(back.segment.v0.x, s.segment.v0.x);
    CHECK_EQ(back.cause, s.cause);
    n++;
  }
  for (const auto &e : g.events) {
    EventOut back = round_trip(e);
    CHECK(same(back, e));
    CHECK_EQ(back.kind, e.kind);
    CHECK_EQ(back.reason, e.reason);
    CHECK_EQ(back.point.x, e.point.x);
    n++;
  }
  for (const auto &s : g.states) {
    StateOut back = round_trip(s);
    CHECK(same(back, s));
    CHECK_EQ(back.ball.position.y, s.ball.position.y);
    CHECK_EQ(back.sim_hash, s.sim_hash);
    n++;
  }
  CHECK_EQ(n, static_cast<int>(g.segments.size() + g.events.size() + g.states.size()));
}

TEST(match_info_comes_back_with_the_flight_model) {
  Game g = played();
  MatchInfoOut i = g.match.info();
  i.server_id = 3;
  i.server_time = 1.7e9 + 0.123456789;
  i.revision = 11;
  MatchInfoOut back = round_trip(i);
  CHECK(same(back, i));
  CHECK(back.slots[1].owner == participant(2));
  CHECK_EQ(back.slots[0].samples, i.slots[0].samples);
  CHECK_EQ(back.model_hash, i.model_hash);
  CHECK_EQ(back.model.gravity, i.model.gravity);
  CHECK_EQ(back.model.effects, i.model.effects);
  CHECK_EQ(back.court_x[1], i.court_x[1]);
  // like MatchInfo on the wire: the model's other fields are libball's defaults
  ball_model def;
  ball_model_default(&def);
  CHECK_EQ(back.model.n_rackets, def.n_rackets);
  // the flight model is enough to evaluate a segment exactly
  ball_state a, b;
  const ball_segment &seg = g.segments.back().segment;
  CHECK_EQ(ball_segment_eval(&i.model, &seg, seg.t0 + 0.37, &a), BALL_OK);
  CHECK_EQ(ball_segment_eval(&back.model, &seg, seg.t0 + 0.37, &b), BALL_OK);
  CHECK_EQ(a.position.x, b.position.x);
  CHECK_EQ(a.position.y, b.position.y);
}

TEST(a_record_line_names_its_type) {
  Game g = played();
  json line = record_line(g.segments.front(), 1234.5);
  CHECK_EQ(record_type(line), std::string("segment"));
  CHECK_EQ(line["recv"].get<double>(), 1234.5);
  CHECK_EQ(line["cause"].get<std::string>(), std::string("serve"));
  CHECK_EQ(line.get<SegmentOut>().seq, 1u);
  CHECK_EQ(record_type(record_line(g.events.front(), 0.0)), std::string("event"));
  CHECK_EQ(record_type(record_line(g.states.front(), 0.0)), std::string("state"));
  CHECK_EQ(record_type(record_line(g.match.info(), 0.0)), std::string("match_info"));
  CHECK_EQ(record_type(record_line(StatusOut{}, 0.0)), std::string("server_status"));
  CHECK_EQ(record_type(json{{"kind", "x"}}), std::string());
  // an unknown enum name is an error, not a silent default
  json bad = line;
  bad["cause"] = "volley";
  CHECK(unreadable_as<SegmentOut>(bad));
}

TEST(racket_samples_come_back_with_their_writer) {
  uint64_t seed = 0x5eed;
  for (int k = 0; k < 200; ++k) {  // random values in every field
    auto draw = [&seed] {
      seed = seed * 6364136223846793005ull + 1442695040888963407ull;
      return static_cast<double>(seed >> 11) * 0x1.0p-53 * 20.0 - 10.0;
    };
    RacketSampleIn s;
    s.match_id = static_cast<uint32_t>(k * 7919);
    s.player = k % 4;
    s.seq = static_cast<uint32_t>(k) * 2654435761u;
    s.capture_time = draw() * 1e3;
    s.center = ball_v3(draw(), draw(), draw());
    s.normal = ball_v3(draw(), draw(), draw());
    s.source_time = 1.7e9 + draw();
    s.permitted = k % 3 != 0;
    s.from = participant(k + 1);
    json line = record_line(s, 5.0);
    CHECK_EQ(record_type(line), std::string("racket_sample"));
    RacketSampleIn back = json::parse(line.dump()).get<RacketSampleIn>();
    CHECK(same(back, s));
    CHECK(back.from == s.from);
    CHECK_EQ(back.center.z, s.center.z);
    CHECK_EQ(back.capture_time, s.capture_time);
  }
  json bad = json(RacketSampleIn{});
  bad["from"] = "xyz";
  CHECK(unreadable_as<RacketSampleIn>(bad));
}

TEST(reports_come_back) {
  ServerReport r;
  r.status.server_id = 4;
  r.status.uptime = 12.25;
  r.status.samples_in = 371;
  r.status.samples_ok = 365;
  r.status.drops[static_cast<int>(SampleResult::stale)] = 3;
  r.status.drops[static_cast<int>(SampleResult::lost)] = 1;
  r.status.frames = 720;
  r.status.overruns = 2;
  r.status.samples_idle = 2;
  r.status.write_failures = 5;
  r.status.latency_p50 = 0.0121;  // (the status period's: in the status's own form, not the report's)
  r.skipped_frames = 7;
  r.late_max = 0.081;
  r.latency_p99 = 0.0309;
  r.latency_count = 48;
  r.status.dds_lost = 6;
  r.controls_at_door = 11;
  r.creates_elsewhere = 13;
  MatchReport m;
  m.id = 9;
  m.state = MatchState::playing;
  m.counters.hits = 10;
  m.score = {3, 1};
  m.sim_time = 11.983333333333333;
  m.sim_hash = 0xfedcba9876543210ull;
  r.matches = {m, MatchReport{}};
  ServerReport back = round_trip(r);
  CHECK(same(back, r));
  CHECK_EQ(back.status.drops[static_cast<int>(SampleResult::stale)], 3u);
  CHECK_EQ(back.matches[0].sim_hash, 0xfedcba9876543210ull);
  CHECK_EQ(back.status.dds_lost, 6u);
  CHECK_EQ(back.status.samples_idle, 2u);
  CHECK_EQ(back.status.write_failures, 5u);
  CHECK_EQ(back.controls_at_door, 11u);
  CHECK_EQ(back.creates_elsewhere, 13u);
  CHECK_EQ(back.status.matches, 2u);  // the list's
  CHECK_EQ(back.status.playing, 1u);
  // the books a test checks: drops by every reason's name
  json j = r;
  CHECK_EQ(j["drops"].size(), static_cast<size_t>(kDropReasons));
  CHECK_EQ(j["drops"]["stale"].get<int>(), 3);

  WatchSummary w;
  w.seconds = 20.5;
  w.first_segment_after = 0.08;
  WatchedMatchSummary wm;
  wm.match = 2;
  wm.states_checked = 602;
  wm.max_error = 1e-300;
  w.matches = {wm};
  w.servers = {r.status};
  w.untrusted = 12;
  WatchSummary wb = round_trip(w);
  CHECK(same(wb, w));
  CHECK_EQ(wb.matches[0].max_error, 1e-300);
  CHECK_EQ(wb.servers[0].samples_in, 371u);
  CHECK_EQ(wb.servers[0].samples_idle, 2u);  // a status carries the whole books
  CHECK_EQ(wb.servers[0].latency_p50, 0.0121);
  CHECK_EQ(wb.untrusted, 12u);

  BotReport b{2, 1, 300, 60, 240, 1, 55, 8, 1, 0, 3, 2};
  CHECK(same(round_trip(b), b));
  LoadRow l;
  l.matches = 100;
  l.frame_p99_ms_max = 5.544;
  CHECK(same(round_trip(l), l));
  OwnFrame f{1.5, 3, 2.25, 17, ball_v3(0.1, 0.2, 0.3)};
  CHECK(same(round_trip(f), f));
  SnapshotRecord s{1.5, 3, 2.5, "frames/m3_t0002.500.png", ball_v3(1, 2, 3), "top", {480, 320}};
  CHECK(same(round_trip(s), s));
  CHECK_EQ(round_trip(s).file, s.file);
}

CHECK_MAIN
