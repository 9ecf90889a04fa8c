// Match::restore: a standby's match that follows another's and takes it
// over goes on as the owner does (docs/protocol.md, "Several servers on one
// domain"). Offline: the owner is a Match with two bots, the standby a
// second Match that gets the owner's MatchInfo and segments as a server
// publishes them (an info on every change and once a second, the segments
// as they come) and the same racket samples. At a random frame the owner
// "dies"; some frames later (the time DDS takes to notice) the standby
// restores from what it had and both step on: the standby's segments and
// events, the catch-up's included, must be the owner's.
#include <array>
#include <climits>
#include <cmath>
#include <cstdio>

#include "check.hpp"
#include "rally.h"
#include "server_loop.h"
#include "trust.h"

using namespace ballsrv;
using namespace test;
using check::note;

namespace {

struct Trial {
  ball_level level = BALL_LEVEL_EASY;
  double time_base = 1.0;
  uint64_t seed = 1;
  int death = 0;  // frame of the owner's last publication
  int gap = 0;    // frames until the standby takes over
  int after = 0;  // frames compared after that
};

struct Outcome {
  bool restored = false;
  std::string err;
  size_t compared_segments = 0, compared_events = 0, catch_up_segments = 0;
  int mismatches = 0;         // segments or events that differ
  double worst_p0 = 0.0;      // m, the largest p0 difference of a segment
  double worst_t0 = 0.0;      // s
  double worst_handover = 0.0;  // m: the first standby segment's distance from the ball, beyond eq 6's shift
  std::string first_mismatch; // what differed first
  int tracks_after_hit = 0;   // rackets restored after a hit of theirs (the segment's or the catch-up's)
  int samples_before_hit = 0; // samples on such a track captured before that hit
};

bool same_play(const PlayState &a, const PlayState &b) {
  return a.score == b.score && a.serving_side == b.serving_side && a.rally == b.rally && a.live == b.live &&
         a.striker == b.striker && a.bounces == b.bounces && a.net == b.net && a.serve_due == b.serve_due &&
         a.event_seq == b.event_seq && std::fabs(a.serve_at - b.serve_at) < 1e-9;
}

Outcome run(const Trial &tr) {
  Outcome o;
  MatchConfig c = default_config();
  c.level = tr.level;
  c.time_base = tr.time_base;
  c.seed = tr.seed;
  Game a(c);  // the owner
  Game b(c);  // the standby
  if (!a.ok || !b.ok) {
    o.err = "init: " + a.err + b.err;
    return o;
  }
  BotBrain brain[2];
  double next_capture[2] = {0, 0};
  const double rate = 15.0;
  for (int i = 0; i < 2; ++i) {
    a.join(i, participant(static_cast<uint8_t>(i + 1)));
    a.park[i] = false;
    BotParams p;
    p.slot = i;
    p.lead = bot_lead(rate, 0.0, 0.0, 0.0);
    p.seed = tr.seed * 11 + i;
    brain[i].init(a.match.model(), a.match.court(), p);
  }
  // what the standby holds: the newest info and the segments the owner
  // published (the newest may lie ahead of its contact)
  MatchInfoOut info = a.match.info();
  Segments published;
  SegmentOut seg;
  bool have_seg = false;
  ClientFeed feed(a.match.id());  // the segment in effect, for the bots
  uint32_t newest_published = 0;
  std::string err;
  CHECK_MSG(b.match.follow(info, &err), "follow: %s", err.c_str());
  int next_info = 0;
  size_t a_seg_seen = 0;
  std::vector<SegmentOut> b_segs;
  std::vector<EventOut> b_events;
  const int frames = tr.death + tr.gap + tr.after;
  for (int k = 0; k < frames; ++k) {
    double sim = a.match.sim().time;
    // the bots' samples, to both servers as they arrive (no delay)
    for (int i = 0; i < 2; ++i)
      while (next_capture[i] <= sim + 1e-12) {
        RacketSampleIn s = bot_sample(a, brain[i], i, next_capture[i]);
        a.match.on_sample(s, a.now);
        if (b.match.following()) b.match.follow_clock(a.match.sim().time);
        b.match.on_sample(s, a.now);
        next_capture[i] += 1.0 / rate;
      }
    if (k == tr.death + tr.gap) {
      // the take-over: from what the owner published up to its death, on to
      // the owner's sim time now (the end of its previous frame)
      MatchOutput out;
      const SegmentOut *stepped = stepped_segment(published, info, a.match.sim().time);
      have_seg = stepped != nullptr;
      if (have_seg) seg = *stepped;
      newest_published = published.empty() ? info.segment_seq : std::max(info.segment_seq, published.rbegin()->first);
      o.restored = b.match.restore(info, have_seg ? &seg : nullptr, newest_published, a.match.sim().time, &out,
                                   &o.err);
      if (!o.restored) return o;
      o.catch_up_segments = out.segments.size();
      // a hit ends its racket's stroke (docs/server-design.md, "Lag compensation"):
      // the racket's track holds no sample from before its newest hit
      double hit_at[2] = {-1e300, -1e300};
      if (have_seg && seg.cause == Cause::racket && seg.cause_index >= 0 && seg.cause_index < 2)
        hit_at[seg.cause_index] = seg.segment.t0;
      for (const SegmentOut &s : out.segments)
        if (s.cause == Cause::racket && s.cause_index >= 0 && s.cause_index < 2)
          hit_at[s.cause_index] = std::fmax(hit_at[s.cause_index], s.segment.t0);
      for (int i = 0; i < 2; ++i) {
        if (hit_at[i] <= -1e300) continue;
        const ball_racket_track &track = b.match.sim().tracks[i];
        o.tracks_after_hit++;
        for (int j = 0; j < track.count; ++j) o.samples_before_hit += track.samples[j].t < hit_at[i];
      }
      b_segs.insert(b_segs.end(), out.segments.begin(), out.segments.end());
      b_events.insert(b_events.end(), out.events.begin(), out.events.end());
    }
    a.out.clear();
    a.match.frame(a.now, &a.out);
    a.keep();
    if (!b.match.following()) {
      MatchOutput out;
      b.match.frame(a.now, &out);
      b_segs.insert(b_segs.end(), out.segments.begin(), out.segments.end());
      b_events.insert(b_events.end(), out.events.begin(), out.events.end());
    }
    // the bots play the segment in effect (protocol.md), as ball-bot does
    for (const SegmentOut &s : a.out.segments) feed.add(s);
    if (const SegmentOut *now = feed.due(a.match.sim().time)) {
      for (int i = 0; i < 2; ++i)
        brain[i].on_segment(now->segment, now->cause == Cause::serve, now->cause_index, a.match.sim().time);
    }
    // the owner publishes until it dies: segments, then an info on a change or once a second
    if (k <= tr.death) {
      for (; a_seg_seen < a.segments.size(); ++a_seg_seen) published[a.segments[a_seg_seen].seq] = a.segments[a_seg_seen];
      if (a.out.info_changed || k >= next_info) {
        info = a.match.info();
        info.server_time = a.now;
        next_info = k + 60;
        if (b.match.following()) CHECK_MSG(b.match.follow(info, &err), "follow: %s", err.c_str());
      }
    }
    a.now += a.match.frame_time();
  }
  // The standby knows every racket sample of the gap at once when it takes
  // over, where the owner knew each as it came: where a racket hit (its
  // estimate of a racket) is involved they may differ, as they would on the
  // wire. Up to the first racket segment of either, the streams are the same:
  // the standby's seqs go on from the newest the owner wrote, its segments
  // are the owner's from the one after the segment it restored from (the
  // owner's segment written ahead of its contact, written again).
  uint32_t last_known = newest_published;
  uint32_t restored_seq = have_seg ? seg.seq : info.segment_seq;
  while (a_seg_seen > 0 && a.segments[a_seg_seen - 1].seq > restored_seq) --a_seg_seen;
  uint32_t last_event = std::max(have_seg ? seg.play.event_seq : 0u, info.play.event_seq);
  for (size_t n = 0; n < b_segs.size(); ++n) {
    const SegmentOut &s = b_segs[n];
    if (s.seq != last_known + 1 + n) {
      o.first_mismatch = "standby segment " + std::to_string(s.seq) + " after " + std::to_string(last_known) +
                         " and " + std::to_string(n) + " more";
      o.mismatches++;
      break;
    }
    size_t i = a_seg_seen + n;
    if (i >= a.segments.size() || a.segments[i].cause == Cause::racket || s.cause == Cause::racket) break;
    const SegmentOut &r = a.segments[i];
    double dp = std::fmax(ball_v3_max_diff(r.segment.p0, s.segment.p0), ball_v3_max_diff(r.segment.v0, s.segment.v0));
    o.worst_p0 = std::fmax(o.worst_p0, dp);
    o.worst_t0 = std::fmax(o.worst_t0, std::fabs(r.segment.t0 - s.segment.t0));
    o.compared_segments++;
    if (r.cause != s.cause || r.cause_index != s.cause_index || dp > 1e-9 || !same_play(r.play, s.play)) {
      if (o.first_mismatch.empty())
        o.first_mismatch = "segment " + std::to_string(s.seq) + ": " + name_of(r.cause) + " / " + name_of(s.cause) +
                           ", p0/v0 off by " + std::to_string(dp);
      o.mismatches++;
    }
  }
  // The handover itself: the standby's first segment goes on from the
  // ball of the newest one it had: a floor or wall bounce where that ball
  // is then, a net hit one eq 6 shift (a tenth of a frame's flight) away.
  // (A racket hit restarts at the disc test's point, a serve elsewhere.)
  if (!b_segs.empty() && have_seg && b_segs.front().cause != Cause::racket && b_segs.front().cause != Cause::serve) {
    const SegmentOut &f = b_segs.front();
    ball_state there;
    ball_segment_eval(&b.match.model(), &seg.segment, f.segment.t0, &there);
    double shift = f.cause == Cause::net ? ball_v3_norm(f.segment.v0) * b.match.frame_time() * tr.time_base / 10.0
                                         : 0.0;
    double d = ball_v3_norm(ball_v3_sub(there.position, f.segment.p0));
    o.worst_handover = std::fmax(o.worst_handover, d - shift);
    if (d > shift + 1e-9) {
      if (o.first_mismatch.empty())
        o.first_mismatch = "first standby segment " + std::to_string(f.seq) + " (" + name_of(f.cause) + ") " +
                           std::to_string(d) + " m from the ball";
      o.mismatches++;
    }
  }
  // events go on from the newest the standby knew of, one by one; a serve
  // only after a point (no second serve), scores never go back
  int points_since_serve = 0;
  std::array<int, 2> score = have_seg && seg.seq > info.segment_seq ? seg.play.score : info.play.score;
  bool live = have_seg && seg.seq > info.segment_seq ? seg.play.live : info.play.live;
  points_since_serve = live ? 0 : 1;
  for (size_t n = 0; n < b_events.size(); ++n) {
    const EventOut &e = b_events[n];
    o.compared_events++;
    bool ok = e.seq == last_event + 1 + n && e.score[0] >= score[0] && e.score[1] >= score[1];
    if (e.kind == EventKind::point) points_since_serve++;
    if (e.kind == EventKind::serve) ok = ok && points_since_serve > 0, points_since_serve = 0;
    score = e.score;
    if (!ok) {
      if (o.first_mismatch.empty())
        o.first_mismatch = "standby event " + std::to_string(e.seq) + " (" + name_of(e.kind) + ") after " +
                           std::to_string(last_event);
      o.mismatches++;
      break;
    }
  }
  return o;
}

}  // namespace

// 300 take-overs at random frames, levels, time bases and detection gaps:
// the standby's stream is the owner's, segment for segment and event for event.
TEST(a_restored_match_goes_on_as_its_owner) {
  Rng r(20261202);
  int restored = 0, differing = 0, after_hit = 0, before_hit = 0;
  size_t segments = 0, events = 0, catch_up = 0;
  double worst_p0 = 0.0, worst_t0 = 0.0, worst_handover = 0.0;
  for (int n = 0; n < 300; ++n) {
    Trial t;
    t.level = static_cast<ball_level>(BALL_LEVEL_EASY + static_cast<int>(r.uniform(0.0, 3.0)));
    t.time_base = r.uniform(0.0, 1.0) < 0.25 ? r.uniform(0.5, 2.0) : 1.0;
    t.seed = 1 + static_cast<uint64_t>(n);
    t.death = 30 + static_cast<int>(r.uniform(0.0, 900.0));
    t.gap = static_cast<int>(r.uniform(0.0, 120.0));
    t.after = 120;
    Outcome o = run(t);
    CHECK_MSG(o.restored, "trial %d: not restored: %s", n, o.err.c_str());
    restored += o.restored;
    segments += o.compared_segments;
    events += o.compared_events;
    catch_up += o.catch_up_segments;
    worst_p0 = std::fmax(worst_p0, o.worst_p0);
    worst_t0 = std::fmax(worst_t0, o.worst_t0);
    worst_handover = std::fmax(worst_handover, o.worst_handover);
    after_hit += o.tracks_after_hit;
    before_hit += o.samples_before_hit;
    if (o.mismatches > 0) {
      differing++;
      note("trial %d (level %d, time base %.2f, death frame %d, gap %d): %s", n, static_cast<int>(t.level),
           t.time_base, t.death, t.gap, o.first_mismatch.c_str());
    }
  }
  note("%d of 300 restored; %zu standby segments came out of the catch-ups; %zu segments before the first racket "
       "hit compared with the owner's (p0/v0 within %.3g, t0 within %.3g s), %zu events checked; the first bounce "
       "within %.3g m of the ball; %d trials differ",
       restored, catch_up, segments, worst_p0, worst_t0, events, worst_handover, differing);
  note("%d rackets restored after a hit of theirs, %d samples from before that hit on their tracks", after_hit,
       before_hit);
  CHECK_EQ(restored, 300);
  CHECK(after_hit >= 50);
  CHECK_EQ(before_hit, 0);
  CHECK(segments > 100);
  CHECK(catch_up > 100);
  CHECK_EQ(differing, 0);
  CHECK(worst_p0 <= 1e-9);
  CHECK(worst_handover <= 1e-9);
}

// What does not fit is refused with a reason, and the standby's match stays
// as it was: another match's info, another slot count or model, a segment
// libball refuses (ball_sim_set_segment: under the floor, NaN, before t0).
TEST(what_does_not_fit_is_refused_and_changes_nothing) {
  Game a, b;
  CHECK(a.ok && b.ok);
  a.join(0, participant(1));
  a.join(1, participant(2));
  a.run(3.0);
  MatchInfoOut info = a.match.info();
  std::string err;
  CHECK(b.match.follow(info, &err));
  uint64_t before = ball_sim_hash(&b.match.sim());
  MatchInfoOut other = info;
  other.match_id = info.match_id + 1;
  CHECK(!b.match.follow(other, &err) && err.find("is not match") != std::string::npos);
  other = info;
  other.players = 3;
  CHECK(!b.match.follow(other, &err) && err.find("slots") != std::string::npos);
  other = info;
  other.model_hash ^= 1;
  err.clear();
  CHECK(!b.match.follow(other, &err) && err.find("model") != std::string::npos);
  other = info;
  other.level = 9;
  err.clear();
  CHECK(!b.match.follow(other, &err) && err.find("not a game level") != std::string::npos);
  CHECK(!a.segments.empty());
  SegmentOut bad = a.segments.back();
  MatchOutput out;
  for (int k = 0; k < 3; ++k) {
    SegmentOut s = bad;
    if (k == 0) s.segment.p0.y = -1.0;            // under the floor
    if (k == 1) s.segment.v0.x = std::nan("");     // not a number
    if (k == 2) s.segment.t0 = info.sim_time + 5;  // after the time it is restored at
    s.seq = info.segment_seq + 1;
    err.clear();
    CHECK_MSG(!b.match.restore(info, &s, s.seq, info.sim_time, &out, &err), "bad segment %d restored", k);
    CHECK_MSG(err.find("segment") != std::string::npos, "%s", err.c_str());
    CHECK(b.match.following());
    CHECK(out.segments.empty() && out.events.empty());
  }
  CHECK_EQ(ball_sim_hash(&b.match.sim()), before);
  // the one in effect is restored, and the match is the owner's
  Segments all;
  for (const SegmentOut &s : a.segments) all[s.seq] = s;
  CHECK(b.match.restore(info, stepped_segment(all, info, a.match.sim().time), all.rbegin()->first,
                        a.match.sim().time, &out, &err));
  CHECK(!b.match.following());
  CHECK(b.match.play().score == a.match.play().score);
}


namespace {

// A value a forger might write into a field of Play: mostly in range (1 in
// 8 outside it: just outside, far outside, or the ends of int; NaN, an
// infinity, a time far after `at`).
int wild_int(Rng &r, int lo, int hi) {
  if (!r.chance(0.125)) return lo + static_cast<int>(r.uniform(0.0, hi - lo + 1.0));
  switch (static_cast<int>(r.uniform(0.0, 4.0))) {
    case 0: return lo - 1;
    case 1: return hi + 1;
    case 2: return r.chance(0.5) ? static_cast<int>(r.uniform(hi + 2.0, 40000.0)) : static_cast<int>(r.uniform(-40000.0, lo - 2.0));
    default: return r.chance(0.5) ? INT_MIN : INT_MAX;
  }
}
double wild_time(Rng &r, double at) {
  if (!r.chance(0.125)) return at - r.uniform(0.0, 5.0);
  switch (static_cast<int>(r.uniform(0.0, 3.0))) {
    case 0: return std::nan("");
    case 1: return r.chance(0.5) ? HUGE_VAL : -HUGE_VAL;
    default: return at + r.uniform(61.0, 1e12);
  }
}

}  // namespace

// A Play from the wire names sides and counts the rules index arrays by
// (score[striker], the serve's slot): 2,000 random Plays, each field outside
// its range 1 time in 8, restored into a playing match: each one
// play_fits refuses is refused by restore with the match as it was, each
// one it takes plays 5 s on with the score and the sides in range (under
// the asan preset: no write past score[1]).
TEST(a_forged_play_is_refused_or_stays_in_range) {
  Game a = played(3.0);
  CHECK(a.ok);
  const MatchInfoOut info = a.match.info();
  CHECK(info.state == MatchState::playing);
  Rng r(20261204);
  int refused = 0, taken = 0, out_of_range = 0, serves = 0;
  for (int n = 0; n < 2000; ++n) {
    Game b;
    CHECK(b.ok);
    std::string err;
    CHECK(b.match.follow(info, &err));
    MatchInfoOut forged = info;
    PlayState &p = forged.play;
    p.score = {wild_int(r, 0, kMaxScore), wild_int(r, 0, kMaxScore)};
    p.serving_side = wild_int(r, 0, 1);
    p.striker = wild_int(r, 0, 1);
    p.bounces = wild_int(r, 0, 1);
    p.bounce_side = wild_int(r, 0, 1);
    p.live = r.chance(0.5);
    p.serve_due = r.chance(0.5);
    p.rally_start = wild_time(r, info.sim_time);
    p.serve_at = wild_time(r, info.sim_time);
    uint64_t before = ball_sim_hash(&b.match.sim());
    MatchOutput out;
    err.clear();
    const SegmentOut own = current_segment(forged);
    bool restored = b.match.restore(forged, &own, info.segment_seq, info.sim_time, &out, &err);
    if (!play_fits(p, info.sim_time)) {
      refused++;
      CHECK_MSG(!restored, "play %d restored: striker %d serving %d bounces %d", n, p.striker, p.serving_side,
                p.bounces);
      CHECK(b.match.following() && ball_sim_hash(&b.match.sim()) == before);
      CHECK(out.segments.empty() && out.events.empty());
      continue;
    }
    CHECK_MSG(restored, "play %d refused: %s", n, err.c_str());
    taken++;
    b.park[0] = b.park[1] = true;
    b.owner[0] = participant(1);
    b.owner[1] = participant(2);
    b.run(5.0);
    PlayState q = b.match.play();
    bool ok = q.score[0] >= p.score[0] && q.score[1] >= p.score[1] && q.score[0] <= kMaxScore + 10 &&
              q.score[1] <= kMaxScore + 10 && (q.serving_side == 0 || q.serving_side == 1) &&
              (q.striker == 0 || q.striker == 1);
    out_of_range += !ok;
    serves += b.count(EventKind::serve) > 0;
  }
  note("2000 forged plays: %d refused, %d taken (%d of them served within 5 s), %d out of range after", refused,
       taken, serves, out_of_range);
  CHECK(refused > 1000 && taken > 100);
  CHECK_EQ(out_of_range, 0);
  CHECK(serves > taken / 2);
}

// A restore steps from the segment to the present in frames: a present a
// forged clock puts far away (+Inf, 3e10 sim s) is refused at once, the match
// as it was; the longest catch-up taken is kMaxCatchUp of the owner's frames.
TEST(a_catch_up_beyond_its_bound_is_refused) {
  Game a = played(3.0);
  CHECK(a.ok);
  const MatchInfoOut info = a.match.info();
  CHECK(info.state == MatchState::playing);
  const double span = kMaxCatchUp * info.settings.time_base;  // sim s
  struct Case {
    double target;
    bool taken;
  } cases[] = {{HUGE_VAL, false},
               {info.sim_time + 3e10, false},
               {info.sim_time + span + 1.0, false},
               {std::nan(""), false},
               {info.sim_time + span - 1.0, true}};
  for (const Case &c : cases) {
    Game b;
    std::string err;
    CHECK(b.match.follow(info, &err));
    uint64_t before = ball_sim_hash(&b.match.sim());
    MatchOutput out;
    const SegmentOut own = current_segment(info);  // (the catch-up starts at the info's sim time)
    bool restored = b.match.restore(info, &own, info.segment_seq, c.target, &out, &err);
    note("present %.6g sim s (catch-up %.6g): %s %s", c.target, c.target - info.sim_time,
         restored ? "restored" : "refused:", restored ? "" : err.c_str());
    CHECK_EQ(restored, c.taken);
    if (restored) {
      CHECK_NEAR(b.match.sim().time, c.target, 1e-6);
      continue;
    }
    CHECK(b.match.following() && ball_sim_hash(&b.match.sim()) == before);
    CHECK(out.segments.empty() && out.events.empty());
  }
}

// The racket tests sleep after a hit for sleep_frames frames (section 3.1):
// restored on a racket hit's segment at a sim time a forged info puts far
// after it (1e3 to 1e300 s), they are awake, as after any hit long past;
// restored at the hit's instant they sleep the whole sleep_frames.
TEST(a_hit_long_past_leaves_the_rackets_awake) {
  Game a = played(3.0);
  CHECK(a.ok);
  MatchInfoOut info = a.match.info();
  SegmentOut hit = current_segment(info);
  hit.cause = Cause::racket;
  hit.cause_index = 0;
  hit.segment.grounded = 1;  // (a rolling ball: any sim time after t0 is on the court)
  hit.segment.p0.y = a.match.model().floor_level + a.match.model().radius;
  hit.segment.v0 = ball_v3(0.1, 0.0, 0.0);
  info.state = MatchState::waiting;  // nothing stepped: the sleep is the restore's own
  info.segment = hit.segment;
  const int sleep_frames = a.match.model().sleep_frames;
  CHECK(sleep_frames > 0);
  for (double after : {0.0, 1e3, 1e9, 1e12, 1e300}) {
    Game b;
    std::string err;
    CHECK(b.match.follow(info, &err));
    MatchInfoOut i = info;
    i.sim_time = hit.segment.t0 + after;
    MatchOutput out;
    bool restored = b.match.restore(i, &hit, hit.seq, i.sim_time, &out, &err);
    note("restored %.0e s after a hit: %s, sleep %d", after, restored ? "yes" : err.c_str(),
         restored ? b.match.sim().sleep : -1);
    if (!restored) continue;  // (libball may refuse a time that far: then nothing changed)
    CHECK_EQ(b.match.sim().sleep, after == 0.0 ? sleep_frames : 0);
  }
}

// A slot's newest seq from the owner's MatchInfo moves the standby's stream
// on as a sample would (serial-number arithmetic, at most 1000 ahead): a
// forged last_seq of the real one plus k (k random over the 2^32 circle)
// keeps the holder's next samples out for at most 1000 seqs.
TEST(a_forged_last_seq_holds_a_slot_back_no_further_than_a_sample_could) {
  Game a = played(3.0);
  CHECK(a.ok);
  MatchInfoOut info = a.match.info();
  info.state = MatchState::waiting;  // (the holder's samples only refresh its presence and seq)
  const uint32_t real = info.slots[0].last_seq;
  CHECK(info.slots[0].samples > 0);
  Rng r(20261205);
  int held_back = 0, worst = 0;
  for (int n = 0; n < 500; ++n) {
    Game b;
    std::string err;
    CHECK(b.match.follow(info, &err));
    MatchInfoOut forged = info;
    const uint32_t fixed[6] = {0x80000000u, 0x7fffffffu, 0xffffffffu, 5000u, 1000u, 500u};
    uint32_t k = n < 6 ? fixed[n] : static_cast<uint32_t>(r.next());
    forged.slots[0].last_seq = real + k;
    CHECK(b.match.follow(forged, &err));
    b.match.follow_clock(info.sim_time);
    // the holder goes on from its real seq: how many of its samples the standby refuses
    RacketSampleIn s = a.parked_sample(0);
    s.capture_time = info.sim_time;
    int out = 0;
    for (uint32_t j = 1; j <= 1001; ++j, ++out) {
      s.seq = real + j;
      SampleResult res = b.match.on_sample(s, a.now);
      if (res == SampleResult::idle || res == SampleResult::accepted) break;
    }
    worst = std::max(worst, out);
    if (out > 1000) {
      held_back++;
      if (held_back <= 3) note("forged last_seq %u + %u: the holder's next 1001 samples refused", real, k);
    }
  }
  note("500 forged last_seq: at most %d of the holder's samples refused after one; %d held it back for good", worst,
       held_back);
  CHECK_EQ(held_back, 0);
  CHECK_EQ(worst, 1000);  // (k = 1000: seqs 1 to 1000 behind or at the forged one)
}

int main(int argc, char **argv) { return check::run(argc, argv); }
