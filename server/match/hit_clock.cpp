#include "hit_clock.h"

namespace ballsrv {

void HitClock::look(const ball_sim &sim, int rackets, uint64_t model_hash, double end, double frame,
                    MatchCounters *counters) {
  none();
  counters->hit_looks++;
  if (!(end > sim.time)) return;
  if (clear_holds(sim, rackets, model_hash, end)) {
    counters->hit_looks_spared++;
    return;
  }
  // the bound over this frame and the next first: its no spares the look
  // after this frame's end too, while nothing it rests on changes
  int may = 1;  // (a sim the bound refuses goes to the query, which says why)
  if (ball_racket_may_reach(&sim, -1, end + frame, &may) == BALL_OK && !may) {
    keep_clear(sim, rackets, model_hash, end + frame);
    return;
  }
  near_ = true;
  if (ball_racket_may_reach(&sim, -1, end, &may) == BALL_OK && !may) return;
  counters->hit_queries++;
  ball_racket_contact c;
  if (ball_racket_first_contact_any(&sim, end, &c) == BALL_OK && c.racket >= 0 && c.step_to < end) next_ = c.step_to;
}

// What a bound over (sim time, until] said no to stays so for a later sim
// time before `until` while the ball is on the same segment (a step without
// a contact moves it along it: its path since is part of the path then),
// the tracks have no new sample (R_old and R lie on the same track), the
// model is the same and the tests are awake (asleep, the bound says no
// without looking, and sleep ends at a step). A new segment has a new start
// or a new velocity (a contact at the very instant another began changes
// the velocity).
bool HitClock::clear_holds(const ball_sim &sim, int rackets, uint64_t model_hash, double end) const {
  if (!(end <= clear_.until) || sim.sleep > 0 || sim.seg.t0 != clear_.t0 || sim.seg.v0.x != clear_.v0.x ||
      sim.seg.v0.y != clear_.v0.y || sim.seg.v0.z != clear_.v0.z || model_hash != clear_.model_hash)
    return false;
  for (int i = 0; i < rackets; ++i) {
    const ball_racket_track &t = sim.tracks[i];
    if (t.count != clear_.count[i] || (t.count > 0 && t.samples[t.count - 1].t != clear_.newest[i])) return false;
  }
  return true;
}

void HitClock::keep_clear(const ball_sim &sim, int rackets, uint64_t model_hash, double until) {
  clear_.until = sim.sleep > 0 ? -HUGE_VAL : until;  // (asleep, the bound did not look)
  clear_.t0 = sim.seg.t0;
  clear_.v0 = sim.seg.v0;
  clear_.model_hash = model_hash;
  for (int i = 0; i < rackets; ++i) {
    const ball_racket_track &t = sim.tracks[i];
    clear_.count[i] = t.count;
    clear_.newest[i] = t.count > 0 ? t.samples[t.count - 1].t : 0.0;
  }
}

}  // namespace ballsrv
