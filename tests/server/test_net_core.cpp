// The client library's core offline (docs/client.md): a MatchView and a
// ClientCore fed from a Match through a fake port, on a client clock 1000 s
// off the server's. The ball it answers is libball's evaluation of the
// segment in effect, to the bit; events come once and in order through a
// failover's replay, gaps and corrections; a match started anew drops what
// was held; the whole model is used only when the MatchInfo names it; JOIN
// and CREATE are sent again until the server answers; and every request
// with a bad argument is refused with nothing changed.
#include <cmath>
#include <map>
#include <random>

#include "check.hpp"
#include "client_core.h"
#include "fake_client_port.h"
#include "match_rackets.h"
#include "game.h"

using namespace test;
using check::note;

namespace {

constexpr double kSkew = 1000.0;     // the client's clock runs this far ahead of the server's
constexpr double kLatency = 0.001;   // s from a server's write to the client's reception

ParticipantId me() { return participant(9); }

// A game's MatchInfo as a server writes it at game time g.now.
MatchInfoOut info_of(Game &g, uint32_t server = 1, uint32_t term = 1) {
  static uint32_t revision = 0;
  MatchInfoOut i = g.match.info();
  i.server_id = server;
  i.term = term;
  i.server_time = g.now;
  i.revision = ++revision;
  return i;
}

MatchModelOut model_of(Game &g, uint32_t server = 1) {
  MatchModelOut m;
  m.match_id = g.match.id();
  m.server_id = server;
  m.model = g.match.model();
  m.model_hash = ball_model_hash(&m.model);
  return m;
}

bool same_bits(const ball_vec3 &a, const ball_vec3 &b) {
  return std::memcmp(&a.x, &b.x, sizeof a.x) == 0 && std::memcmp(&a.y, &b.y, sizeof a.y) == 0 &&
         std::memcmp(&a.z, &b.z, sizeof a.z) == 0;
}

EventOut event(uint32_t seq, EventKind kind = EventKind::floor, double time = 1.0, uint32_t server = 1,
               uint32_t term = 1) {
  EventOut e;
  e.match_id = 7;
  e.server_id = server;
  e.term = term;
  e.seq = seq;
  e.kind = kind;
  e.time = time;
  return e;
}

// What a view handed on: the server's events' seqs, and its notes; the
// library's sound events apart, each right after its loud collision
struct Handed {
  std::vector<uint32_t> seqs;
  std::map<ViewNote, int> notes;
  std::vector<ViewEvent> all;
  int sounds = 0, loud = 0, unpaired = 0;
  void take(std::vector<ViewEvent> &out) {
    for (size_t i = 0; i < out.size(); ++i) {
      const ViewEvent &v = out[i];
      all.push_back(v);
      if (v.note == ViewNote::none && v.event.kind == EventKind::sound) {
        sounds++;
        bool paired = i > 0 && out[i - 1].note == ViewNote::none && out[i - 1].event.seq == v.event.seq &&
                      out[i - 1].event.sound;
        unpaired += !paired;
      } else if (v.note == ViewNote::none) {
        seqs.push_back(v.event.seq);
        loud += is_collision(v.event.kind) && v.event.sound;
      } else {
        notes[v.note]++;
      }
    }
    out.clear();
  }
};

}  // namespace

// 20 s of a match (serves, bounces written ahead, points), every MatchInfo
// and segment given to a view as it is written; at 2000 random times the
// view's ball is ball_segment_eval of the segment in effect among every
// segment written, at the sim time the server's clock says, to the bit.
TEST(the_ball_is_libballs_evaluation_of_the_segment_in_effect) {
  Game g;
  CHECK(g.ok);
  g.join(0, participant(1));
  g.join(1, participant(2));
  MatchView v(7, ServerChoice{}, me());
  std::vector<ViewEvent> out;
  Segments all;
  size_t given = 0;
  std::mt19937_64 rng(7);
  int compared = 0, bits = 0, ahead_in_effect = 0;
  MatchInfoOut anchor;
  double worst_clock = 0.0;
  for (int k = 0; k < 20 * 60; ++k) {
    g.run(1.0 / 60.0);
    double local = g.now + kSkew + kLatency;
    if (k % 6 == 0) {
      anchor = info_of(g);
      CHECK(v.on_info(anchor, local, &out));
    }
    for (; given < g.segments.size(); ++given) {
      SegmentOut s = g.segments[given];
      s.server_id = 1;
      all[s.seq] = s;
      CHECK(v.on_segment(s, local, &out));
    }
    for (int r = 0; r < 2; ++r) {
      // a time within the next frame of the client's clock
      double at = g.now + kSkew + std::uniform_real_distribution<double>(0.0, 1.0 / 60.0)(rng);
      ViewBall b;
      if (v.ball(at, &b) != BALL_OK) continue;
      // the server's sim time then: the info's pair, less the client's kLatency (the min filter keeps it)
      // the newest pair's mapping (never before its sim time: the clock does not go back)
      double sim = anchor.state == MatchState::playing
                       ? anchor.sim_time + std::max(0.0, at - kSkew - kLatency - anchor.server_time) * anchor.settings.time_base
                       : anchor.sim_time;
      worst_clock = std::max(worst_clock, std::fabs(b.sim_time - sim));
      const SegmentOut *want = segment_in_effect(all, b.sim_time);
      CHECK(want && b.segment && want->seq == b.segment->seq);
      if (!want) continue;
      ball_state ref;
      CHECK_EQ(ball_segment_eval(&g.match.model(), &want->segment, b.sim_time, &ref), BALL_OK);
      bits += same_bits(ref.position, b.state.position) && same_bits(ref.velocity, b.state.velocity) &&
              same_bits(ref.spin, b.state.spin);
      ahead_in_effect += want->cause == Cause::floor || want->cause == Cause::net;
      compared++;
    }
  }
  note("%d balls compared, %d to the bit (%d on a segment written ahead of its bounce); sim clock within %.3g s",
       compared, bits, ahead_in_effect, worst_clock);
  CHECK(compared > 2000);
  CHECK_EQ(bits, compared);
  CHECK(ahead_in_effect > 100);
  CHECK(worst_clock < 1e-9);
  CHECK_EQ(v.counters().refused, 0u);
}

// A failover: the new owner (the next term) goes on from events the client
// has given already (seqs 15..20 again), then its own; a gap of 3 is one GAP
// note and 3 lost; a forged seq far ahead is refused and blinds nobody; the
// server's change is one SERVER note; the old owner back (its term older)
// changes nothing.
TEST(events_come_once_and_in_order) {
  Game g;
  MatchView v(7, ServerChoice{}, me());
  std::vector<ViewEvent> out;
  Handed h;
  CHECK(v.on_info(info_of(g, 1), kSkew, &out));
  for (uint32_t s = 1; s <= 20; ++s) v.on_event(event(s), kSkew, &out);
  h.take(out);
  CHECK(v.on_info(info_of(g, 2, 2), kSkew, &out));  // server 2 took it over
  for (uint32_t s = 15; s <= 30; ++s) v.on_event(event(s, EventKind::floor, 1.0, 2, 2), kSkew, &out);
  CHECK(!v.on_event(event(0xFFFFFFF0u, EventKind::point, 1.0, 2, 2), kSkew, &out));  // behind: given already
  CHECK(!v.on_event(event(30 + 5000, EventKind::point, 1.0, 2, 2), kSkew, &out));     // forged, far ahead
  CHECK(!v.on_info(info_of(g, 1, 1), kSkew, &out));                                   // the old owner back
  for (uint32_t s = 31; s <= 33; ++s) CHECK(!v.on_event(event(s), kSkew, &out));
  CHECK_EQ(v.counters().old_owner, 4u);
  for (uint32_t s = 34; s <= 36; ++s) v.on_event(event(s, EventKind::floor, 1.0, 2, 2), kSkew, &out);
  h.take(out);
  std::vector<uint32_t> want;
  for (uint32_t s = 1; s <= 30; ++s) want.push_back(s);
  for (uint32_t s = 34; s <= 36; ++s) want.push_back(s);
  CHECK(h.seqs == want);
  CHECK_EQ(h.notes[ViewNote::server], 1);
  CHECK_EQ(h.notes[ViewNote::gap], 1);
  CHECK_EQ(v.counters().lost, 3u);
  CHECK_EQ(v.counters().events, 33u);
  CHECK_EQ(v.counters().refused, 1u);
}

namespace {

// One sample as a client's transport hands it on, at the caller's clock.
struct Sample {
  int kind = 0;  // 0 info, 1 segment, 2 event, 3 state
  MatchInfoOut info;
  SegmentOut segment;
  EventOut event;
  StateOut state;
  double local = 0.0;
};

bool feed(MatchView &v, const Sample &s, std::vector<ViewEvent> *out) {
  switch (s.kind) {
    case 0: return v.on_info(s.info, s.local, out);
    case 1: return v.on_segment(s.segment, s.local, out);
    case 2: return v.on_event(s.event, s.local, out);
    default: return v.on_state(s.state, s.local);
  }
}

// What a game writes over `seconds`, as its server would: a MatchInfo every
// 6 frames, its segments, events and states; seqs moved on by `seq_from`
// and `event_from` (a take-over goes on from the old owner's).
std::vector<Sample> written(Game &g, double seconds, double skew, uint32_t seq_from = 0, uint32_t event_from = 0) {
  std::vector<Sample> out;
  auto add = [&](int kind, double local) -> Sample & {
    out.emplace_back();
    out.back().kind = kind;
    out.back().local = local;
    return out.back();
  };
  size_t segs = g.segments.size(), evs = g.events.size(), sts = g.states.size();
  for (int k = 0; k < static_cast<int>(seconds * 60.0); ++k) {
    g.run(1.0 / 60.0);
    double local = g.now + skew;
    if (k % 6 == 0) {
      Sample &i = add(0, local);
      i.info = info_of(g, g.server_id, g.term);
      i.info.segment_seq += seq_from;
    }
    for (; segs < g.segments.size(); ++segs) (add(1, local).segment = g.segments[segs]).seq += seq_from;
    for (; evs < g.events.size(); ++evs) (add(2, local).event = g.events[evs]).seq += event_from;
    for (; sts < g.states.size(); ++sts) add(3, local).state = g.states[sts];
  }
  return out;
}

}  // namespace

// docs/protocol.md, "Terms": once a client took a newer owner's sample (the
// next term, or of one term a lower server id), the older owner's samples
// change nothing, whenever they come. 40 random runs: an owner plays 3 s, a
// new one takes over and plays 3 s while the old one, back, plays on; a view
// fed both streams, shuffled together after the new owner's first info, and
// a view fed only the new owner's answer the same ball to the bit at 300
// random times, hand on the same events and notes, and the first counts
// every sample of the old owner's as an older owner's.
TEST(an_older_owners_samples_change_nothing) {
  int runs = 0, stale = 0, balls = 0, same = 0;
  for (uint32_t seed = 1; seed <= 40; ++seed) {
    std::mt19937_64 rng(seed);
    Game old;
    old.join(0, participant(1));
    old.join(1, participant(2));
    std::vector<Sample> before = written(old, 3.0, kSkew);
    Game nw;  // the new owner: the next term, or the same term from a lower server id
    bool same_term = seed % 3 == 0;
    old.server_id = same_term ? 5 : 1;
    for (auto &x : before) x.info.server_id = x.segment.server_id = x.event.server_id = x.state.server_id = old.server_id;
    nw.server_id = same_term ? 2 : 2 + static_cast<uint32_t>(rng() % 5);
    nw.term = same_term ? 1 : 2 + static_cast<uint32_t>(rng() % 3);
    nw.now = old.now;
    nw.join(0, participant(1));
    nw.join(1, participant(2));
    std::vector<Sample> back = written(old, 3.0, kSkew);
    std::vector<Sample> taken = written(nw, 3.0, kSkew, 1000, 1000);
    MatchView both(7, ServerChoice{}, me()), only(7, ServerChoice{}, me());
    std::vector<ViewEvent> out_both, out_only;
    Handed h_both, h_only;
    for (const auto &x : before) {
      feed(both, x, &out_both);
      feed(only, x, &out_only);
    }
    // the new owner's first info, then both streams shuffled, each in its own order
    feed(both, taken[0], &out_both);
    feed(only, taken[0], &out_only);
    size_t i = 0, j = 1;
    while (i < back.size() || j < taken.size()) {
      bool old_next = j == taken.size() || (i < back.size() && rng() % 2 == 0);
      if (old_next) {
        CHECK(!feed(both, back[i++], &out_both));
        stale++;
      } else {
        feed(both, taken[j], &out_both);
        feed(only, taken[j++], &out_only);
      }
    }
    h_both.take(out_both);
    h_only.take(out_only);
    CHECK(h_both.seqs == h_only.seqs && h_both.notes == h_only.notes);
    CHECK_EQ(both.counters().old_owner, back.size());
    CHECK_EQ(only.counters().old_owner, 0u);
    CHECK_EQ(both.term(), nw.term);
    double local = taken.back().local;
    for (int k = 0; k < 300; ++k) {
      double at = local + std::uniform_real_distribution<double>(-2.0, 0.5)(rng);
      ViewBall a, b;
      ball_status sa = both.ball(at, &a), sb = only.ball(at, &b);
      CHECK_EQ(sa, sb);
      if (sa != BALL_OK) continue;
      balls++;
      same += same_bits(a.state.position, b.state.position) && same_bits(a.state.velocity, b.state.velocity) &&
              same_bits(a.state.spin, b.state.spin) && a.segment->term == nw.term;
    }
    runs++;
  }
  note("%d runs: %d samples of the old owner refused, %d balls asked, %d the same to the bit on the new owner's",
       runs, stale, balls, same);
  CHECK(balls > 40 * 250);
  CHECK_EQ(same, balls);
}

// An owner of whom nothing came for kForgetOwner is forgotten: a match
// served anew by an older owner (its servers gone, one started again that
// knew none of its terms) is taken then, and started anew; before, not.
TEST(a_gone_owner_is_forgotten) {
  Game g;
  g.join(0, participant(1));
  g.join(1, participant(2));
  g.server_id = 2;
  g.term = 3;
  MatchView v(7, ServerChoice{}, me());
  std::vector<ViewEvent> out;
  std::vector<Sample> held = written(g, 2.0, kSkew);
  for (const auto &x : held) feed(v, x, &out);
  double last = held.back().local;
  MatchInfoOut forged = info_of(g, 2, 3 + kMaxTermAhead + 1);  // more than 1000 rounds ahead: refused
  const uint64_t refused = v.counters().refused;
  CHECK(!v.on_info(forged, last, &out));
  CHECK_EQ(v.counters().refused, refused + 1);
  CHECK(v.on_info(info_of(g, 2, 3 + kMaxTermAhead), last, &out));  // (as far as a match may go)
  Game again;
  again.join(0, participant(1));
  again.run(1.0);
  MatchInfoOut i = info_of(again, 1, 1);
  CHECK(!v.on_info(i, last + MatchView::kForgetOwner - 0.1, &out));
  CHECK_EQ(v.counters().old_owner, 1u);
  CHECK_EQ(v.term(), 3u + kMaxTermAhead);
  CHECK(v.on_info(i, last + MatchView::kForgetOwner + 0.1, &out));
  CHECK_EQ(v.term(), 1u);
  CHECK_EQ(v.counters().anew, 1u);
  CHECK(v.window().size() <= 1u);
}

// docs/protocol.md, "Terms": a newer owner writes again events of seqs the
// old one wrote; the same event is not given twice, another replaces the
// one given, which is voided (a VOIDED note naming it); an older owner's
// event of a seq given is never given.
TEST(a_newer_owners_other_event_replaces_the_one_given) {
  Game g;
  MatchView v(7, ServerChoice{}, me());
  std::vector<ViewEvent> out;
  Handed h;
  CHECK(v.on_info(info_of(g, 1, 1), kSkew, &out));
  for (uint32_t s = 1; s <= 6; ++s) v.on_event(event(s, EventKind::floor, 0.5 * s), kSkew, &out);
  h.take(out);
  CHECK(v.on_info(info_of(g, 2, 2), kSkew, &out));
  CHECK(!v.on_event(event(5, EventKind::floor, 2.5, 2, 2), kSkew, &out));  // the same: not again
  CHECK(v.on_event(event(6, EventKind::racket, 2.9, 2, 2), kSkew, &out));  // another: replaces it
  CHECK(!v.on_event(event(6, EventKind::racket, 2.9, 2, 2), kSkew, &out)); // (given now)
  CHECK(v.on_event(event(7, EventKind::floor, 3.5, 2, 2), kSkew, &out));
  h.take(out);
  CHECK((h.seqs == std::vector<uint32_t>{1, 2, 3, 4, 5, 6, 6, 7}));
  CHECK_EQ(h.notes[ViewNote::voided], 1);
  bool named = false;
  for (const auto &e : h.all)
    named = named || (e.note == ViewNote::voided && e.event.seq == 6 && e.event.kind == EventKind::floor &&
                      e.event.server_id == 1);
  CHECK(named);
  CHECK_EQ(v.counters().replaced, 1u);
  CHECK_EQ(v.counters().voided, 1u);
}

// A correction voids the collision and point events given for a later time
// (a VOIDED note each, with its seq) and those that come after it.
TEST(a_correction_voids_events_given_and_to_come) {
  Game g;
  MatchView v(7, ServerChoice{}, me());
  std::vector<ViewEvent> out;
  Handed h;
  CHECK(v.on_info(info_of(g), kSkew, &out));
  SegmentOut base;
  base.match_id = 7;
  base.server_id = 1;
  base.term = 1;
  base.seq = 5;
  base.segment.p0 = ball_v3(1, 1, 1);
  CHECK(v.on_segment(base, kSkew, &out));
  EventOut bounce = event(1, EventKind::floor, 2.0), point = event(2, EventKind::point, 2.5), serve = event(3, EventKind::serve, 2.6);
  bounce.segment_seq = point.segment_seq = serve.segment_seq = 5;
  v.on_event(bounce, kSkew, &out);
  v.on_event(point, kSkew, &out);
  v.on_event(serve, kSkew, &out);
  SegmentOut corr = base;
  corr.seq = 6;
  corr.segment.t0 = 1.5;
  corr.correction = true;
  CHECK(v.on_segment(corr, kSkew, &out));
  EventOut late = event(4, EventKind::net, 3.0);  // written before the correction, arriving after it
  late.segment_seq = 5;
  v.on_event(late, kSkew, &out);
  h.take(out);
  CHECK((h.seqs == std::vector<uint32_t>{1, 2, 3}));
  CHECK_EQ(h.notes[ViewNote::voided], 2);  // the bounce and the point, not the serve
  CHECK_EQ(v.counters().voided, 3u);        // and the net event that came after
}

// A MatchInfo more than a second behind the newest: the match started anew;
// its new stream's seqs and events are taken from 1 again.
TEST(a_match_started_anew_drops_what_was_held) {
  Game g;
  g.join(0, participant(1));
  g.join(1, participant(2));
  g.run(5.0);
  MatchView v(7, ServerChoice{}, me());
  std::vector<ViewEvent> out;
  Handed h;
  CHECK(v.on_info(info_of(g), g.now + kSkew, &out));
  for (const auto &s : g.segments) v.on_segment(s, g.now + kSkew, &out);
  for (const auto &e : g.events) v.on_event(e, g.now + kSkew, &out);
  size_t before = v.window().size();
  uint32_t newest = g.segments.back().seq;
  h.take(out);
  Game fresh;  // the same match id, started anew on another server (a claim: the next term)
  fresh.server_id = 3;
  fresh.term = 2;
  fresh.join(0, participant(1));
  fresh.join(1, participant(2));
  fresh.run(1.0);
  CHECK(v.on_info(info_of(fresh, 3, 2), g.now + kSkew, &out));
  for (const auto &s : fresh.segments) CHECK(v.on_segment(s, g.now + kSkew, &out));
  for (const auto &e : fresh.events) v.on_event(e, g.now + kSkew, &out);
  h.take(out);
  note("held %zu segments up to seq %u; started anew: %zu segments, newest %u", before, newest, v.window().size(),
       v.window().empty() ? 0u : v.window().back().segment.seq);
  CHECK_EQ(v.counters().anew, 1u);
  CHECK(!v.window().empty() && v.window().back().segment.seq == fresh.segments.back().seq);
  CHECK(v.window().back().segment.seq < newest);
  CHECK(h.seqs.size() == g.events.size() + fresh.events.size());
  // every loud collision given is followed by its sound, and only those
  CHECK(h.loud > 0);
  CHECK_EQ(h.sounds, h.loud);
  CHECK_EQ(h.unpaired, 0);
}

// What does not fit is refused, counted, and changes nothing: another
// server's samples (when one is chosen), a MatchInfo out of range, a
// segment with NaN or a seq 1000 past the newest, a clock pair 1e6 s away.
TEST(what_does_not_fit_is_refused) {
  Game g;
  g.join(0, participant(1));
  g.join(1, participant(2));
  g.run(3.0);
  ServerChoice one;
  std::string err;
  CHECK(ServerChoice::parse("1", &one, &err));
  MatchView v(7, one, me());
  std::vector<ViewEvent> out;
  CHECK(v.on_info(info_of(g), g.now + kSkew, &out));
  for (const auto &s : g.segments) v.on_segment(s, g.now + kSkew, &out);
  ViewBall before;
  CHECK_EQ(v.ball(g.now + kSkew, &before), BALL_OK);
  uint64_t refused = v.counters().refused;
  MatchInfoOut other = info_of(g, 5);
  CHECK(!v.on_info(other, g.now + kSkew, &out));
  MatchInfoOut bad = info_of(g);
  bad.players = 9;
  CHECK(!v.on_info(bad, g.now + kSkew, &out));
  MatchInfoOut far = info_of(g);
  far.server_time += 1e6;
  CHECK(!v.on_info(far, g.now + kSkew, &out));
  SegmentOut nan = g.segments.back();
  nan.seq += 1;
  nan.segment.v0.x = NAN;
  CHECK(!v.on_segment(nan, g.now + kSkew, &out));
  SegmentOut forged = g.segments.back();
  forged.seq += 1001;
  CHECK(!v.on_segment(forged, g.now + kSkew, &out));
  SegmentOut stranger = g.segments.back();
  stranger.seq += 1;
  stranger.server_id = 5;
  CHECK(!v.on_segment(stranger, g.now + kSkew, &out));
  CHECK_EQ(v.counters().refused, refused + 6);
  ViewBall after;
  CHECK_EQ(v.ball(g.now + kSkew, &after), BALL_OK);
  CHECK(same_bits(before.state.position, after.state.position) && before.segment->seq == after.segment->seq);
}

// The whole model is used only once a MatchInfo names it (its hash): one
// that came first waits for it; one under a hash not its own never counts.
// predict then gives ball_predict's path from the segment in effect.
TEST(the_whole_model_is_the_one_the_info_names) {
  Game g;
  g.join(0, participant(1));
  g.join(1, participant(2));
  g.run(2.0);
  MatchView v(7, ServerChoice{}, me());
  std::vector<ViewEvent> out;
  MatchModelOut m = model_of(g);
  MatchModelOut lying = m;
  lying.model.gravity = 3.0;
  CHECK(!v.on_model(lying));
  CHECK(v.on_model(m));  // before any MatchInfo: waits
  CHECK(v.model() == nullptr);
  double local = g.now + kSkew;
  ball_state states[32];
  ball_event events[8];
  ball_prediction pr{};
  pr.states = states;
  pr.cap_states = 32;
  pr.events = events;
  pr.cap_events = 8;
  CHECK_EQ(v.predict(local, 1.0, 0.05, &pr), BALL_EAGAIN);
  CHECK(v.on_info(info_of(g), local, &out));
  for (const auto &s : g.segments) v.on_segment(s, local, &out);
  CHECK(v.model() != nullptr);
  CHECK_EQ(v.predict(local, 1.0, 0.05, &pr), BALL_OK);
  ViewBall b;
  CHECK_EQ(v.ball(local, &b), BALL_OK);
  ball_state ref[32];
  ball_prediction want{};
  want.states = ref;
  want.cap_states = 32;
  CHECK_EQ(ball_predict(&g.match.model(), &b.segment->segment, b.sim_time, b.sim_time + 1.0, 0.05, &want), BALL_OK);
  CHECK_EQ(pr.n_states, want.n_states);
  bool same = pr.n_states > 0;
  for (int k = 0; k < pr.n_states; ++k) same = same && same_bits(states[k].position, ref[k].position);
  CHECK(same);
  // a new level: a new hash the held model is not; its model comes after the info
  CHECK(g.control(ControlKind::level, participant(1), -1, 3) == Reason::none);
  CHECK(v.on_info(info_of(g), local, &out));
  CHECK(v.model() == nullptr);
  CHECK(v.on_model(model_of(g)));
  CHECK(v.model() != nullptr && ball_model_hash(v.model()) == g.match.info().model_hash);
}

// ---- the core of many matches ------------------------------------------------

// JOIN goes out at once and every retry (0.5 s) until the MatchInfo shows
// the slot held by this client; a SLOT note then, and again when it is
// lost, and JOIN again. A pose before the slot or the clock, with NaN, a
// zero normal or a time not after the previous one is refused, nothing
// written; the poses written carry seqs 1, 2, ... and the sim time the
// clock maps their time to.
TEST(the_core_joins_until_the_server_answers_and_pushes_poses) {
  Game g;
  ClientCore core(CoreSettings{}, me());
  FakeClientPort port;
  std::string why;
  double t = kSkew;
  CHECK_EQ(core.push(7, 0, t, ball_v3(1, 1, 1), ball_v3(1, 0, 0), port, &why), BALL_ENOMATCH);
  CHECK_EQ(core.join(7, 5, port, t, &why), BALL_ERANGE);
  CHECK(port.controls.empty());
  CHECK_EQ(core.join(7, -1, port, t, &why), BALL_OK);
  CHECK_EQ(port.controls.size(), 1u);
  for (int k = 1; k <= 20; ++k) core.pump(port, t + 0.1 * k, t + 0.1 * k);  // 2 s unanswered
  note("JOINs in 2 s unanswered: %zu", port.controls.size());
  CHECK_EQ(port.controls.size(), 5u);  // at 0, 0.5, 1.0, 1.5, 2.0
  CHECK_EQ(core.push(7, 0, t + 2.0, ball_v3(1, 1, 1), ball_v3(1, 0, 0), port, &why), BALL_ENOMATCH);
  CHECK_EQ(g.join(0, me()), Reason::none);
  port.infos.push_back(info_of(g));
  port.infos.back().reception.received = g.now + 0.001;
  core.pump(port, g.now + kSkew + 0.001, g.now + 0.001);
  CHECK_EQ(core.view(7)->slot(), 0);
  int slot_notes = 0;
  for (const auto &e : core.events()) slot_notes += e.note == ViewNote::slot && e.event.index == 0 && e.event.value == 1;
  CHECK_EQ(slot_notes, 1);
  size_t joins = port.controls.size();
  core.pump(port, g.now + kSkew + 1.0, g.now + 1.0);
  CHECK_EQ(port.controls.size(), joins);  // answered: no more JOIN
  double at = g.now + kSkew + 0.5;
  CHECK_EQ(core.push(7, 0, at, ball_v3(NAN, 1, 1), ball_v3(1, 0, 0), port, &why), BALL_ENONFINITE);
  CHECK_EQ(core.push(7, 0, at, ball_v3(1, 1, 1), ball_v3(0, 1e-7, 0), port, &why), BALL_ERANGE);
  CHECK_EQ(core.push(7, 0, at, ball_v3(1, 1, 1), ball_v3(0, 2e6, 0), port, &why), BALL_ERANGE);
  CHECK(port.samples.empty());
  CHECK_EQ(core.push(7, 0, at, ball_v3(1, 1, 1), ball_v3(1, 0, 0), port, &why), BALL_OK);
  CHECK_EQ(core.push(7, 0, at, ball_v3(1, 1, 2), ball_v3(1, 0, 0), port, &why), BALL_ESTALE);
  CHECK_EQ(core.push(7, 0, at + 0.1, ball_v3(1, 1, 2), ball_v3(1, 0, 0), port, &why), BALL_OK);
  CHECK_EQ(port.samples.size(), 2u);
  CHECK(port.samples[0].seq == 1 && port.samples[1].seq == 2 && port.samples[0].player == 0);
  // waiting: the sim clock stands still, every time maps to the info's sim time
  CHECK_NEAR(port.samples[1].capture_time, g.match.info().sim_time, 0.0);
  port.refuse = true;
  CHECK_EQ(core.push(7, 0, at + 0.2, ball_v3(1, 1, 2), ball_v3(1, 0, 0), port, &why), BALL_ENETWORK);
  CHECK_EQ(core.own(7)->write_failures, 1u);
  port.refuse = false;
  // the slot taken by another: lost, and JOIN again
  CHECK_EQ(g.control(ControlKind::leave, me(), 0), Reason::none);
  CHECK_EQ(g.join(0, participant(3)), Reason::none);
  port.infos.push_back(info_of(g));
  core.pump(port, g.now + kSkew + 2.0, g.now + 2.0);
  CHECK_EQ(core.view(7)->slot(), -1);
  CHECK(port.controls.back().kind == ControlKind::join);
  // leave: a LEAVE for the slot held, none when none is held
  CHECK_EQ(core.leave(7, -1, port, &why), BALL_OK);
  CHECK_EQ(core.leave(7, -1, port, &why), BALL_ENOMATCH);
}

// Two players at one console: one client joins both slots by number, holds
// both (a SLOT note each), pushes each slot's stream with its own seqs, and
// gives one up without the other; the bytes of what it took and wrote are counted.
TEST(one_client_holds_two_slots) {
  Game g;
  ClientCore core(CoreSettings{}, me());
  FakeClientPort port;
  port.wire.sample = 40;
  port.wire.control = 60;
  port.wire.info = 1000;
  std::string why;
  core.pump(port, 0.0, 0.0);  // (the core learns the port's sizes)
  CHECK_EQ(core.join(7, 0, port, 0.0, &why), BALL_OK);
  CHECK_EQ(core.join(7, 1, port, 0.0, &why), BALL_OK);
  CHECK_EQ(port.controls.size(), 2u);
  CHECK(port.controls[0].player == 0 && port.controls[1].player == 1);
  CHECK_EQ(g.join(0, me()), Reason::none);
  CHECK_EQ(g.join(1, me()), Reason::none);
  port.infos.push_back(info_of(g));
  core.pump(port, 0.1, 0.1);
  CHECK(core.view(7)->holds(0) && core.view(7)->holds(1) && core.view(7)->slot() == 0);
  int taken = 0;
  for (const auto &e : core.events()) taken += e.note == ViewNote::slot && e.event.value == 1;
  CHECK_EQ(taken, 2);
  CHECK_EQ(core.push(7, 1, 0.2, ball_v3(20, 1, 5), ball_v3(-1, 0, 0), port, &why), BALL_OK);
  CHECK_EQ(core.push(7, 0, 0.2, ball_v3(2, 1, 5), ball_v3(1, 0, 0), port, &why), BALL_OK);
  CHECK_EQ(core.push(7, 1, 0.3, ball_v3(20, 1, 5), ball_v3(-1, 0, 0), port, &why), BALL_OK);
  CHECK_EQ(core.push(7, 2, 0.3, ball_v3(2, 1, 5), ball_v3(1, 0, 0), port, &why), BALL_ENOMATCH);
  CHECK_EQ(port.samples.size(), 3u);
  CHECK_EQ(core.own(7)->bytes_out, 3u * 40u + 2u * 60u);  // three poses, two JOINs
  CHECK_EQ(core.own(7)->bytes_in, 1000u);                 // one MatchInfo
  CHECK(port.samples[0].player == 1 && port.samples[0].seq == 1 && port.samples[1].player == 0 &&
        port.samples[1].seq == 1 && port.samples[2].seq == 2);
  size_t controls = port.controls.size();
  CHECK_EQ(core.leave(7, 1, port, &why), BALL_OK);
  CHECK_EQ(port.controls.size(), controls + 1);
  CHECK(port.controls.back().kind == ControlKind::leave && port.controls.back().player == 1);
  CHECK_EQ(core.leave(7, 1, port, &why), BALL_OK);  // (still held until the server says: a LEAVE again)
  CHECK_EQ(core.leave(7, 3, port, &why), BALL_ENOMATCH);
}

// A match's model is written once (transient local): one that came before
// the client followed the match is the view's as soon as it does (a game
// that lists and joins later, a bot that began late). It once never came:
// ball-load's bots never played with the primary that wrote it.
TEST(a_model_taken_before_the_match_is_followed_is_kept) {
  Game g;
  ClientCore core(CoreSettings{}, me());
  FakeClientPort port;
  port.models.push_back(model_of(g));
  port.infos.push_back(info_of(g));
  core.pump(port, 0.0, 0.0);
  CHECK(core.view(7) == nullptr);
  std::string why;
  CHECK_EQ(core.watch(7, port, &why), BALL_OK);
  CHECK(core.view(7)->model() != nullptr);
  CHECK_EQ(ball_model_hash(core.view(7)->model()), g.match.info().model_hash);
}

// A match followed after its segments came (a game lists, then joins; a
// reader that matched late gets a match's newest segments once, at
// matching) starts from them: the ball at once, from the segment in
// effect, even from segments that came before the MatchInfo; and what it
// keeps of matches it does not follow is bounded.
TEST(segments_taken_before_the_match_is_followed_are_kept) {
  Game g;
  g.join(0, participant(1));
  g.join(1, participant(2));
  g.run(3.0);
  CHECK(g.segments.size() >= 3);
  for (int segments_first = 0; segments_first < 2; ++segments_first) {
    ClientCore core(CoreSettings{}, me());
    FakeClientPort port;
    for (size_t i = 0; i < g.segments.size(); ++i) {
      SegmentOut s = g.segments[i];
      s.server_id = 1;
      port.segments.push_back(s);
    }
    if (!segments_first) core.pump(port, g.now, g.now);  // (the segments in this pump, the info in the next)
    port.infos.push_back(info_of(g));
    core.pump(port, g.now, g.now);
    CHECK(core.view(7) == nullptr);
    std::string why;
    CHECK_EQ(core.watch(7, port, &why), BALL_OK);
    const MatchView *v = core.view(7);
    CHECK(v && !v->window().empty());
    if (!v || v->window().empty()) continue;
    CHECK_EQ(v->window().back().segment.seq, g.segments.back().seq);  // the newest, ahead or in effect
    ViewBall b;
    CHECK_EQ(v->ball(g.now, &b), BALL_OK);
    CHECK(b.segment != nullptr);
    if (!b.segment) continue;
    ball_state want;
    CHECK_EQ(ball_segment_eval(&g.match.model(), &b.segment->segment, b.sim_time, &want), BALL_OK);
    CHECK_EQ(b.state.position.x, want.position.x);
    CHECK_EQ(b.state.position.y, want.position.y);
  }
  // a stranger's segments of many made-up matches: kept for at most max_matches of them
  CoreSettings few;
  few.max_matches = 8;
  ClientCore core(few, me());
  FakeClientPort port;
  for (uint32_t m = 100; m < 200; ++m) {
    SegmentOut s = g.segments.back();
    s.match_id = m;
    for (int k = 0; k < 10; ++k) {
      s.seq = static_cast<uint32_t>(k + 1);
      port.segments.push_back(s);
    }
  }
  core.pump(port, g.now, g.now);
  CHECK_EQ(core.kept_unfollowed(), 8u * ClientCore::kKeptUnfollowed);
}

// The rackets a client draws (the watcher's and the page's one rule): a
// slot's track starts anew with a new holder, every track with a new
// server; a new level keeps them; a slot the match has not is refused.
TEST(the_rackets_start_anew_with_a_holder_or_a_server) {
  Game g;
  g.join(0, participant(1));
  g.join(1, participant(2));
  MatchRackets r;
  ball_racket_pose p;
  CHECK_EQ(r.push(0, ball_racket_sample{1.0, ball_v3(1, 1, 5), ball_v3(1, 0, 0)}), BALL_EAGAIN);
  MatchInfoOut i = info_of(g);
  CHECK(r.follow(i, g.match.model()));
  CHECK_EQ(r.push(0, ball_racket_sample{1.0, ball_v3(1, 1, 5), ball_v3(1, 0, 0)}), BALL_OK);
  CHECK_EQ(r.push(1, ball_racket_sample{1.0, ball_v3(20, 1, 5), ball_v3(-1, 0, 0)}), BALL_OK);
  CHECK_EQ(r.push(2, ball_racket_sample{1.0, ball_v3(1, 1, 5), ball_v3(1, 0, 0)}), BALL_ERANGE);
  CHECK_EQ(r.pose(0, 1.0, &p), BALL_OK);
  CHECK(g.control(ControlKind::level, participant(1), -1, 3) == Reason::none);  // a new model: kept
  CHECK(r.follow(info_of(g), g.match.model()));
  CHECK_EQ(r.pose(0, 1.0, &p), BALL_OK);
  CHECK_EQ(g.control(ControlKind::leave, participant(1), 0), Reason::none);  // slot 0 changes hands
  CHECK_EQ(g.join(0, participant(3)), Reason::none);
  CHECK(r.follow(info_of(g), g.match.model()));
  CHECK_EQ(r.pose(0, 1.0, &p), BALL_ENOTFOUND);  // its track anew
  CHECK_EQ(r.pose(1, 1.0, &p), BALL_OK);         // the other's kept
  MatchInfoOut other = info_of(g, 2);            // another server: every track anew
  CHECK(r.follow(other, g.match.model()));
  CHECK_EQ(r.pose(1, 1.0, &p), BALL_ENOTFOUND);
}

// A client that reads the rackets (CoreSettings::rackets) keeps a slot's
// samples from its holder only (docs/protocol.md, "The other players'
// rackets"): a stranger's, a slot the match lacks, an older one and one
// come before the model are refused and counted; the racket between two
// samples is where libball's track puts it, on the caller's clock; a
// client that does not read them leaves them in the port.
TEST(a_clients_rackets_are_their_holders_samples) {
  Game g;
  g.join(0, participant(1));
  g.join(1, participant(2));
  CoreSettings settings;
  settings.rackets = true;
  ClientCore core(settings, me());
  FakeClientPort port;
  std::string why;
  CHECK_EQ(core.watch(7, port, &why), BALL_OK);
  auto sample = [&](const ParticipantId &from, int slot, double t, double z) {
    RacketSampleIn s;
    s.match_id = 7;
    s.player = slot;
    s.capture_time = t;
    s.center = ball_v3(20, 1, z);
    s.normal = ball_v3(-1, 0, 0);
    s.from = from;
    port.rackets.push_back(s);
  };
  const double local = g.now + kSkew;
  port.infos.push_back(info_of(g));
  sample(participant(2), 1, 0.0, 4.0);  // before the model: refused
  core.pump(port, local, g.now);
  CHECK_EQ(core.own(7)->rackets_refused, 1u);
  ball_racket_pose pose;
  CHECK_EQ(core.racket(7, 1, local, &pose), BALL_EAGAIN);  // no model yet
  port.models.push_back(model_of(g));
  port.infos.push_back(info_of(g));
  core.pump(port, local, g.now);
  const double sim = core.view(7)->clock().sim_now(local + 0.5);
  sample(participant(2), 1, sim - 0.05, 5.0);
  sample(participant(2), 1, sim + 0.05, 6.0);
  sample(participant(3), 1, sim + 0.06, 9.0);  // a stranger
  sample(participant(2), 2, sim + 0.07, 9.0);  // no slot 2 in a match of two
  sample(participant(2), 1, sim + 0.04, 9.0);  // older than the newest
  RacketSampleIn elsewhere;
  elsewhere.match_id = 8;  // a match not followed: not counted
  port.rackets.push_back(elsewhere);
  core.pump(port, local + 0.5, g.now + 0.5);
  CHECK_EQ(core.own(7)->rackets, 2u);
  CHECK_EQ(core.own(7)->rackets_refused, 4u);
  CHECK_EQ(core.racket(7, 1, local + 0.5, &pose), BALL_OK);
  // libball's own track of the same two samples, at the same sim time: the same bits
  ball_sim own;
  ball_model m = g.match.model();
  CHECK_EQ(ball_sim_init(&own, &m), BALL_OK);
  ball_racket_sample a{sim - 0.05, ball_v3(20, 1, 5.0), ball_v3(-1, 0, 0)}, b{sim + 0.05, ball_v3(20, 1, 6.0), ball_v3(-1, 0, 0)};
  CHECK_EQ(ball_racket_push(&own, 1, &a), BALL_OK);
  CHECK_EQ(ball_racket_push(&own, 1, &b), BALL_OK);
  ball_racket_pose want;
  CHECK_EQ(ball_racket_estimate(&own, 1, sim, &want), BALL_OK);
  CHECK(same_bits(pose.center, want.center) && same_bits(pose.normal, want.normal));
  CHECK_NEAR(pose.center.z, 5.5, 1e-9);
  CHECK_EQ(core.racket(7, 0, local + 0.5, &pose), BALL_ENOTFOUND);  // slot 0: no sample
  CHECK_EQ(core.racket(7, 2, local + 0.5, &pose), BALL_ERANGE);
  CHECK_EQ(core.racket(8, 1, local + 0.5, &pose), BALL_ENOMATCH);
  // a client that does not read the rackets leaves them where they are
  ClientCore plain(CoreSettings{}, me());
  CHECK_EQ(plain.watch(7, port, &why), BALL_OK);
  sample(participant(2), 1, sim + 0.1, 6.0);
  plain.pump(port, local + 0.6, g.now + 0.6);
  CHECK_EQ(port.rackets.size(), 1u);
  CHECK_EQ(plain.own(7)->rackets + plain.own(7)->rackets_refused, 0u);
}

// CREATE goes out until a MatchInfo of the match appears; the list holds
// what was heard within `silence` (10 s); a bad CREATE is refused, not sent.
TEST(the_core_creates_until_the_match_appears_and_lists_the_heard) {
  Game g;
  ClientCore core(CoreSettings{}, me());
  FakeClientPort port;
  std::string why;
  CHECK_EQ(core.create(7, "../etc", 2, 1, port, 0.0, &why), BALL_ERANGE);
  CHECK_EQ(core.create(7, "tennis", 5, 1, port, 0.0, &why), BALL_ERANGE);
  CHECK_EQ(core.create(7, "tennis", 2, 4, port, 0.0, &why), BALL_ERANGE);
  CHECK(port.controls.empty());
  CHECK_EQ(core.create(7, "tennis", 2, 1, port, 0.0, &why), BALL_OK);
  for (int k = 1; k <= 10; ++k) core.pump(port, 0.1 * k, 0.1 * k);
  CHECK_EQ(port.controls.size(), 3u);  // at 0, 0.5 and 1.0 s
  CHECK(port.controls[0].kind == ControlKind::create && port.controls[0].scene == "tennis" && port.controls[0].players == 2);
  MatchInfoOut i = info_of(g);
  i.reception.received = 1.05;
  port.infos.push_back(i);
  core.pump(port, 1.1, 1.1);
  for (int k = 1; k <= 10; ++k) core.pump(port, 1.1 + 0.1 * k, 1.1 + 0.1 * k);
  CHECK_EQ(port.controls.size(), 3u);
  CHECK_EQ(core.matches(2.0).size(), 1u);
  CHECK(core.listed(7, 11.0) != nullptr);
  CHECK(core.matches(11.1).empty());  // not heard for 10 s
}

CHECK_MAIN
