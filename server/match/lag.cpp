#include "lag.h"

#include <algorithm>

namespace ballsrv {

void aside(ball_sim *sim, Aside *a, double end) {
  for (int k = 0, n = std::min(ball_sim_model(sim)->n_rackets, kMaxPlayers); k < n; ++k) {
    ball_racket_track &t = sim->tracks[k];
    const size_t i = static_cast<size_t>(k);
    if (a->held[i] && a->track[i].samples[0].t <= end) {  // reached: back, after what came meanwhile (nothing)
      for (int j = 0; j < a->track[i].count; ++j) ball_racket_push(sim, k, &a->track[i].samples[j]);
      a->held[i] = false;
    } else if (!a->held[i] && t.count > 0 && t.samples[0].t > end) {
      a->track[i] = t;
      a->held[i] = true;
      ball_racket_clear(sim, k);
    }
  }
}

ball_status unended_track(ball_sim *sim, int k, const Slot &slot, const ball_racket_sample *extra) {
  ball_status st = ball_racket_clear(sim, k);
  for (int i = 0; i < slot.kept_n && st == BALL_OK; ++i) st = ball_racket_push(sim, k, &slot.kept[static_cast<size_t>(i)]);
  if (extra && st == BALL_OK) st = ball_racket_push(sim, k, extra);
  return st;
}

int sleep_left(double t_hit, double t, double frame, int sleep_frames) {
  double dt = frame;
  const int sleep = sleep_frames;
  double ends = dt > 0.0 ? std::ceil((t - t_hit) / dt - 1e-9) : 0.0;
  // clamped before the conversion: a hit far in the past (a sim time from
  // the wire) is as long past as sleep_frames + 1 frame ends; NaN: awake
  if (!(ends <= sleep + 1.0)) return 0;
  return std::max(0, sleep - std::max(0, static_cast<int>(ends) - 1));
}

namespace {

// Where a late sample's search begins: t_a (sim s), the segment in effect
// there, the racket hit whose sleep still holds there (nullptr: none), the
// t0 of the first of its own hits after t_a (+Inf: none).
struct LateStart {
  double t_a = 0.0;
  const SegmentOut *at = nullptr, *slept = nullptr;
  double passed = HUGE_VAL;
};

LateStart late_start(const ball_sim &sim, const std::vector<SegmentOut> &history, int slot, double from,
                     const LagParams &p) {
  LateStart w;
  const double now = sim.time;
  // back no further than the window, the sample before this one, the last
  // hit (with rewind_own_hit: another racket's) or the serve
  const bool own = p.rewind_own_hit;
  w.t_a = std::max(from, now - p.rewind_window);
  for (const SegmentOut &h : history)
    if (h.cause == Cause::serve || (h.cause == Cause::racket && !(own && h.cause_index == slot)))
      w.t_a = std::max(w.t_a, h.segment.t0);
  for (const SegmentOut &h : history) {
    if (h.segment.t0 <= w.t_a) {
      w.at = &h;
      if (h.cause == Cause::racket) w.slept = &h;
      if (h.cause == Cause::serve) w.slept = nullptr;  // (a serve's tests are awake)
    } else if (h.cause == Cause::racket) {
      w.passed = std::min(w.passed, h.segment.t0);
    }
  }
  return w;
}

// The frames from *then to now, slot's racket looked for in each: hit
// (*hit its sim s, *then the ball there), none, stopped (another racket, a
// contact past its own hit, a step refused), or again (a frame found it
// without having kept its start: walk again keeping every frame's).
enum class Walk { none, hit, stopped, again };

Walk walk_to_hit(ball_sim *then, double now, int slot, const LateStart &w, bool keep_all, const LagParams &p,
                 Aside *early, double *hit, std::vector<ball_event> *events) {
  const double dt = p.frame;
  ball_sim before;
  *hit = HUGE_VAL;
  early->held.fill(false);
  while (then->time < now) {
    double end = std::min(now, then->time + dt);
    aside(then, early, end);
    ball_racket_contact c{};
    int may = 1;
    // (a contact before the racket's first sample is not one: it was not there yet)
    if ((ball_racket_may_reach(then, slot, end, &may) != BALL_OK || may) &&
        ball_racket_first_contact(then, slot, end, &c) == BALL_OK && c.step_to <= end &&
        !(then->tracks[slot].count > 0 && then->tracks[slot].samples[0].t > c.step_to)) {
      *hit = c.step_to;
      return Walk::hit;
    }
    // (the exact scheme's next contact, when known, says whether the frame holds one)
    const bool keep = keep_all || !(then->next.valid && then->next.time > end);
    if (keep) before = *then;
    int n = 0;
    if (ball_step(then, end - then->time, events->data(), static_cast<int>(events->size()), &n) != BALL_OK)
      return Walk::stopped;
    bool racket = false;
    for (int k = 0; k < n && !racket; ++k) {
      if ((*events)[k].kind != BALL_EVENT_RACKET) {
        // past its own hit the ball flies where the match has no judged
        // segment of its own: a contact there is not gone back over
        if ((*events)[k].time > w.passed) return Walk::stopped;
        continue;
      }
      if ((*events)[k].index != slot) return Walk::stopped;  // another racket got there first
      racket = true;
    }
    if (racket && !keep) return Walk::again;
    if (racket) {  // after a bounce inside the frame: the step's own test found it at the frame's end
      *then = before;
      *hit = end;
      return Walk::hit;
    }
  }
  return Walk::none;
}

}  // namespace

LateHit find_late_hit(const ball_sim &sim, const std::vector<SegmentOut> &history, int slot, const Slot &kept,
                      double from, const LagParams &p, std::vector<ball_event> *events) {
  LateHit r;
  const double now = sim.time;
  const LateStart w = late_start(sim, history, slot, from, p);
  if (!w.at || !(w.t_a < now)) return r;
  r.outcome = LateHit::none;  // (tested: late_tested)
  ball_sim &then = r.then;
  // A frame whose step finds the racket (after a bounce inside it, where
  // the query stops) is stepped again from its start, so only a frame that
  // may hold a static contact keeps its start (a copy of the whole sim);
  // one that finds the racket without having kept it (the query gave up
  // early) walks again, keeping every frame's.
  for (int keep_all = 0; keep_all < 2; ++keep_all) {
    // the ball where it was at t_a, the tracks as they are now (the late sample
    // in them; past its own hit, the racket's as if no hit had ended its stroke)
    then = sim;
    if (ball_sim_set_segment(&then, &w.at->segment, w.t_a) != BALL_OK) return r;
    if (std::isfinite(w.passed) && unended_track(&then, slot, kept, nullptr) != BALL_OK) return r;
    for (int i = 0; i < ball_sim_model(&sim)->n_rackets; ++i) then.tracks[i].has_prev = 0;  // R_old: the track at t_a
    // most late samples meet nothing: when the ball stayed on one segment
    // since t_a (no contact took effect since, and the exact scheme steps
    // the same contacts on any frames) and the bound rules the racket out
    // of a step ending anywhere up to now (every frame's P_old, R_old and
    // ends lie in its boxes and spheres; asked awake), no frame can find it
    if (keep_all == 0 && !std::isfinite(w.passed) && w.at == &history.back() &&
        ball_sim_model(&sim)->scheme == BALL_SCHEME_EXACT) {
      int may = 1;
      if (ball_racket_may_reach(&then, slot, now, &may) == BALL_OK && !may) {
        r.outcome = LateHit::ruled_out;
        return r;
      }
    }
    // the racket tests slept after the last hit as they did in the match: else
    // the hitter's own next sample finds its racket still on the ball at the
    // hit's instant and hits it again
    // (ball_sim_set_segment woke them: a serve's, or one past no hit, stay awake)
    if (w.slept && ball_sim_set_sleep(&then, sleep_left(w.slept->segment.t0, w.t_a, p.frame, ball_sim_model(&sim)->sleep_frames)) != BALL_OK) return r;
    // frame by frame up to now: where the racket meets it first (a frame the
    // bound rules out costs no query; the query stops before a bounce, the
    // step goes through it)
    Walk walked = walk_to_hit(&then, now, slot, w, keep_all != 0, p, &r.early, &r.hit, events);
    if (walked == Walk::stopped) {
      r.hit = HUGE_VAL;
      return r;
    }
    if (walked != Walk::again) break;
  }
  if (std::isfinite(r.hit)) r.outcome = LateHit::found;
  r.passed = w.passed;
  r.at = w.at;
  return r;
}

}  // namespace ballsrv
