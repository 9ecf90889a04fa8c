// The spectator page's core without a network or a browser (spectator.h),
// fed through a Watcher and its client from a Match (watch_rig.h): the page is given
// every match as the watcher took it (court, info, segments to the bit,
// events, clock), a match started anew resets it, a silent server freezes
// its clock, racket samples only from their slot's holder, and the message
// ring says when a reader fell behind. With numbers.
#include <cmath>
#include <cstdio>
#include <map>

#include "ball/render.h"
#include "check.hpp"
#include "court.h"
#include "game.h"
#include "records.h"
#include "spectator.h"
#include "watch_rig.h"
#include "match_model.h"

using namespace test;

namespace {

ball_model court_of(const MatchInfoOut &info) {
  ball_scene scene;
  ball_scene_default(&scene);
  ball_model m;
  Court c;
  std::string err;
  return match_model_of(scene, info, &m, &c, &err) ? m : scene.model;
}

// a watcher fed everything of game g, received at `real`: its info (the
// match then followed), then its segments and events
void feed(WatchRig &r, const Game &g, double real) {
  MatchInfoOut i = g.match.info();
  i.server_time = real;
  r.on_info(i, real);
  for (const auto &s : g.segments) r.net.port.segments.push_back(s);
  for (const auto &e : g.events) r.net.port.events.push_back(e);
  r.turn(real);
}

// a game played for `seconds`, a watcher fed all of it at real 1000 s, and the page's core updated then
struct Page {
  Game g;
  WatchRig r{WatcherSettings{}, [](ball_net_config *c) { c->rackets = 1; }};
  Watcher &w = r.w;
  SpectatorSettings ss;
  Spectator sp;
  Page(double seconds, const SpectatorSettings &settings) : g(played(seconds)), ss(settings), sp(settings, court_of) {
    feed(r, g, 1000.0);
    sp.update(w, 1000.0);
  }
};

std::vector<json> messages(const std::vector<std::string> &texts) {
  std::vector<json> out;
  for (const auto &t : texts) out.push_back(json::parse(t));
  return out;
}

// The court message's model read back by libball's field tables, as the
// page copies it into its module (ballwasm.js): over ball_model_default,
// the walls and rackets listed, "Infinity" for +Inf.
double real_of(const json &j) { return j.is_string() ? std::stod(j.get<std::string>()) : j.get<double>(); }

void fields_from(const json &j, const ball_field *fields, int count, unsigned char *base) {
  int nplane = 0, nracket = 0;
  const ball_field *plane = ball_plane_fields(&nplane), *racket = ball_racket_fields(&nracket);
  for (int i = 0; i < count; ++i) {
    const ball_field &f = fields[i];
    const json &v = j.at(f.name);
    unsigned char *at = base + f.offset;
    switch (f.type) {
      case BALL_FIELD_REAL: *reinterpret_cast<double *>(at) = real_of(v); break;
      case BALL_FIELD_INT:
      case BALL_FIELD_ENUM:
      case BALL_FIELD_AXIS: *reinterpret_cast<int *>(at) = v.get<int>(); break;
      case BALL_FIELD_BOOL: *reinterpret_cast<int *>(at) = v.get<bool>() ? 1 : 0; break;
      case BALL_FIELD_EFFECTS: *reinterpret_cast<unsigned *>(at) = v.get<unsigned>(); break;
      case BALL_FIELD_VEC3: *reinterpret_cast<ball_vec3 *>(at) = ball_v3(real_of(v[0]), real_of(v[1]), real_of(v[2])); break;
      case BALL_FIELD_PLANE: fields_from(v, plane, nplane, at); break;
      case BALL_FIELD_PLANES:
        for (size_t k = 0; k < v.size(); ++k) fields_from(v[k], plane, nplane, at + k * sizeof(ball_plane));
        break;
      case BALL_FIELD_RACKETS:
        for (size_t k = 0; k < v.size(); ++k) fields_from(v[k], racket, nracket, at + k * sizeof(ball_racket_def));
        break;
      case BALL_FIELD_TYPE_COUNT: break;
    }
  }
}

ball_model model_from(const json &j) {
  ball_model m;
  int count = 0;
  const ball_field *fields = ball_model_fields(&count);
  ball_model_default(&m);
  fields_from(j, fields, count, reinterpret_cast<unsigned char *>(&m));
  return m;
}

std::vector<json> of_type(const std::vector<json> &all, const std::string &type) {
  std::vector<json> out;
  for (const auto &m : all)
    if (m.at("type") == type) out.push_back(m);
  return out;
}

}  // namespace

TEST(the_page_is_given_what_the_watcher_took) {
  Page p(12.0, SpectatorSettings{});
  Game &g = p.g;
  Watcher &w = p.w;
  Spectator &sp = p.sp;
  const SpectatorSettings &ss = p.ss;
  std::vector<json> snap = messages(sp.snapshot());
  CHECK_EQ(snap.front().at("type"), "hello");
  CHECK_EQ(of_type(snap, "court").size(), 1u);
  CHECK_EQ(of_type(snap, "info").size(), 1u);
  CHECK_EQ(of_type(snap, "clock").size(), 1u);
  // the newest page_segments segments, each to the bit as the match wrote it
  std::vector<json> segs = of_type(snap, "segment");
  CHECK_EQ(segs.size(), std::min(ss.page_segments, g.segments.size()));
  std::map<uint32_t, SegmentOut> written;
  for (const auto &s : g.segments) written[s.seq] = s;
  for (const auto &m : segs) {
    SegmentOut s = m.at("segment").get<SegmentOut>();
    const SegmentOut &o = written.at(s.seq);
    CHECK(std::memcmp(&s.segment, &o.segment, sizeof s.segment) == 0);
  }
  CHECK_EQ(segs.back().at("segment").at("seq").get<uint32_t>(), g.segments.back().seq);
  std::vector<json> events = of_type(snap, "event");
  CHECK_EQ(events.size(), std::min(ss.page_events, g.events.size()));
  CHECK_EQ(events.back().at("event").at("seq").get<uint32_t>(), g.events.back().seq);
  CHECK(!events.back().at("text").get<std::string>().empty());
  // the court: libball's floor and presets, a radius per slot
  json court = of_type(snap, "court")[0];
  CHECK_EQ(court.at("floor").at("lines").size(), 7u);
  CHECK_EQ(court.at("cameras").size(), static_cast<size_t>(BALL_CAMERA_PRESET_COUNT));
  CHECK_EQ(court.at("rackets").size(), 2u);
  CHECK(!court.at("net").is_null());
  // ... around the court the rules judge, MatchInfo's court_x and court_z
  const MatchInfoOut &info = g.match.info();
  json want_court = {info.court_x[0], info.court_z[0], info.court_x[1], info.court_z[1]};
  CHECK_EQ(court.at("floor").at("court"), want_court);
  CHECK_EQ(court.at("judged"), want_court);
  // ... in libball's colours, and with the whole model, which reads back to the bit (its hash)
  ball_palette pal;
  ball_render_palette(&pal);
  CHECK_EQ(court.at("palette").at("ball"), json::array({pal.ball.r, pal.ball.g, pal.ball.b}));
  CHECK_EQ(court.at("palette").at("rackets").size(), static_cast<size_t>(BALL_MAX_RACKETS));
  CHECK_EQ(court.at("palette").at("markers").at("racket"),
           json::array({pal.markers[BALL_EVENT_RACKET].r, pal.markers[BALL_EVENT_RACKET].g, pal.markers[BALL_EVENT_RACKET].b}));
  ball_model back = model_from(court.at("model"));
  ball_model sent = court_of(info);
  char hash[17];
  std::snprintf(hash, sizeof hash, "%016llx", static_cast<unsigned long long>(ball_model_hash(&sent)));
  CHECK_EQ(court.at("model_hash").get<std::string>(), std::string(hash));
  CHECK_EQ(ball_model_hash(&back), ball_model_hash(&sent));
  CHECK_EQ(ball_model_check(&back, nullptr), BALL_OK);
  CHECK_EQ(back.n_rackets, sent.n_rackets);
  // the info: libball's level name, each side's name and slots, the hash in hex
  json inf = of_type(snap, "info")[0];
  CHECK_EQ(inf.at("level_name").get<std::string>(), std::string(ball_level_name(static_cast<ball_level>(info.level))));
  CHECK_EQ(inf.at("sides"), json::parse(R"([{"name":"near side","slots":[0]},{"name":"far side","slots":[1]}])"));
  std::snprintf(hash, sizeof hash, "%016llx", static_cast<unsigned long long>(info.model_hash));
  CHECK_EQ(inf.at("model_hash").get<std::string>(), std::string(hash));
  CHECK_EQ(inf.at("real").get<double>(), 1000.0);
  // the stream: every message numbered in order, nothing new without news
  std::vector<PageMessage> got;
  CHECK(sp.since(0, 100000, &got));
  CHECK_EQ(got.size(), static_cast<size_t>(sp.newest()));
  for (size_t i = 0; i < got.size(); ++i) CHECK_EQ(got[i].id, i + 1);
  uint64_t before = sp.newest();
  sp.update(w, 1000.05);  // within clock_every: nothing to say
  CHECK_EQ(sp.newest(), before);
  sp.update(w, 1000.2);  // a clock message
  CHECK_EQ(sp.newest(), before + 1);
  CHECK(sp.since(before, 10, &got));
  CHECK_EQ(got.size(), 1u);
  CHECK_EQ(json::parse(got[0].text).at("type"), "clock");
}

TEST(a_silent_server_freezes_the_clock_and_a_new_one_moves_it) {
  Page p(4.0, SpectatorSettings{});
  Game &g = p.g;
  Watcher &w = p.w;
  Spectator &sp = p.sp;
  const SpectatorSettings &ss = p.ss;
  double sim0 = g.match.info().sim_time;
  // no MatchInfo for longer than `silence`: gone, and still at the sim time of the info period after the last
  sp.update(w, 1000.0 + ss.silence + 0.1);
  std::vector<PageMessage> got;
  CHECK(sp.since(0, 100000, &got));
  json clock = json::parse(got.back().text);
  CHECK_EQ(clock.at("type"), "clock");
  CHECK_EQ(clock.at("live"), false);
  CHECK_EQ(clock.at("running"), false);
  CHECK_NEAR(clock.at("sim_time").get<double>(), sim0 + kInfoEvery, 1e-9);
  json info = of_type(messages(sp.snapshot()), "info")[0];
  CHECK_EQ(info.at("live"), false);
  sp.update(w, 1010.0);
  CHECK_NEAR(json::parse(sp.snapshot().back()).at("sim_time").get<double>(), sim0 + kInfoEvery, 1e-9);
  // a server that started the match anew: its seqs start over, the page is reset
  Game again = played(1.5);
  uint64_t before = sp.newest();
  feed(p.r, again, 1011.0);
  sp.update(w, 1011.0);
  CHECK(sp.since(before, 100000, &got));
  std::vector<json> fresh;
  for (const auto &m : got) fresh.push_back(json::parse(m.text));
  CHECK_EQ(of_type(fresh, "reset").size(), 1u);
  CHECK_EQ(of_type(fresh, "segment").size(), again.segments.size());
  std::vector<json> snap = messages(sp.snapshot());
  CHECK_EQ(of_type(snap, "segment").size(), again.segments.size());  // none of the old match's
  json live = of_type(snap, "clock")[0];
  CHECK_EQ(live.at("live"), true);
  CHECK(live.at("sim_time").get<double>() < 2.0);
}

TEST(rackets_only_from_their_holder) {
  Page page(2.0, SpectatorSettings{});
  Game &g = page.g;
  Watcher &w = page.w;
  Spectator &sp = page.sp;
  RacketSampleIn a = g.parked_sample(0), b = a;
  a.capture_time = 1.0;
  a.center = ball_v3(1.0, 1.0, 5.0);
  b.capture_time = 1.2;
  b.center = ball_v3(1.4, 1.2, 5.0);
  b.seq = a.seq + 1;
  RacketSampleIn stranger = b;
  stranger.from = participant(9);
  stranger.capture_time = 1.3;
  RacketSampleIn older = a;  // libball's track refuses a sample older than its newest
  older.capture_time = 0.5;
  RacketSampleIn bad = b;
  bad.capture_time = 1.5;
  bad.center.x = NAN;
  RacketSampleIn other = b;
  other.match_id = 99;  // a match nobody watches
  MatchModelOut model;  // (the client places rackets by the match's model from the wire)
  model.match_id = g.match.id();
  model.server_id = g.match.info().server_id;
  model.model = g.match.model();
  model.model_hash = ball_model_hash(&model.model);
  page.r.net.port.models.push_back(model);
  page.r.turn(1000.04);
  w.output().clear();
  page.r.net.port.rackets = {a, b, stranger, older, bad, other};
  page.r.turn(1000.05);
  // the watcher passes on what the client library trusted: the holder's, in order
  const std::vector<RacketSampleIn> &trusted = w.output().rackets;
  CHECK_EQ(trusted.size(), 2u);
  if (trusted.size() == 2) {
    CHECK_EQ(trusted[0].capture_time, 1.0);
    CHECK_EQ(trusted[1].capture_time, 1.2);
    CHECK(trusted[1].from == a.from);
  }
  // the page: passed on unless within 1/120 s of the slot's newest
  CHECK(sp.on_racket(a));
  RacketSampleIn close = a;
  close.capture_time = a.capture_time + 0.004;
  CHECK(!sp.on_racket(close));
  CHECK(sp.on_racket(b));
  CHECK_EQ(sp.racket_dropped(), 1u);
  // an event with a number that is not finite is never passed on (JSON has no NaN: the page would get null)
  EventOut e = g.events.back();
  e.seq += 1;
  e.time = NAN;
  page.r.on_event(e, 1000.1);
  uint64_t before = sp.newest();
  sp.update(w, 1000.1);
  std::vector<PageMessage> got;
  CHECK(sp.since(before, 100, &got));
  for (const auto &m : got) CHECK(json::parse(m.text).at("type") != "event");
  CHECK_EQ(sp.not_drawable(), 0u);  // (the client library never gave it: trust.h)
  std::vector<json> r = of_type(messages(sp.snapshot()), "racket");
  CHECK_EQ(r.size(), 2u);
  CHECK_EQ(r[1].at("t").get<double>(), 1.2);
  CHECK_EQ(r[1].at("center")[0].get<double>(), 1.4);
}

TEST(a_reader_that_fell_behind_is_told) {
  SpectatorSettings few;
  few.keep_messages = 8;
  Page p(8.0, few);
  Spectator &sp = p.sp;
  CHECK(sp.newest() > 8u);
  std::vector<PageMessage> got;
  CHECK(!sp.since(0, 100, &got));  // the first messages are gone: start over from a snapshot
  CHECK(sp.since(sp.newest() - 8, 100, &got));
  CHECK_EQ(got.size(), 8u);
  CHECK(sp.since(sp.newest() - 8, 3, &got));
  CHECK_EQ(got.size(), 3u);  // at most `max`
}

int main(int argc, char **argv) { return check::run(argc, argv); }
