// ball/net.h's calls on the ball of a followed match: where it is at a
// time of the caller's clock, a racket, the path ahead, the clocks and the
// model (docs/client.md). The checks are api_client.h's.
#include <cmath>
#include <string>

#include "api_client.h"

using namespace ballsrv;
using namespace ballsrv::api;

extern "C" {

namespace {
// ball_net_ball_at's refusals, out of its way (it runs every frame)
__attribute__((cold, noinline)) ball_status ball_refused(ball_net_client *c, uint32_t match, ball_status st) {
  if (!c) return BALL_EINVAL;
  if (st == BALL_EAGAIN) return c->fail(st, "match " + std::to_string(match) + " has no clock or segment yet");
  if (st == BALL_EINVAL) return c->fail(st, "out must not be NULL");
  if (st == BALL_ENONFINITE) return c->fail(st, "the time must be finite");
  if (st == BALL_ENOMATCH || st == BALL_ECLOSED) return st;  // (said by followed or usable)
  return c->fail(st, std::string("the ball at that time: ") + ball_strerror(st));
}
}  // namespace

// (the call a game makes every frame: docs/client.md, "What it costs", measures it against ball_segment_eval)
ball_status ball_net_ball_at(const ball_net_client *cc, uint32_t match, double time, ball_net_ball *out) {
  auto *c = const_cast<ball_net_client *>(cc);
  if (!c || c->closed) return ball_refused(c, match, usable(c));
  if (!out) return ball_refused(c, match, BALL_EINVAL);
  const MatchView *v = c->hot_view && c->hot_match == match ? c->hot_view : followed(c, match);
  if (!v) return ball_refused(c, match, BALL_ENOMATCH);
  c->hot_match = match;
  c->hot_view = v;
  if (!std::isfinite(time)) return ball_refused(c, match, BALL_ENONFINITE);
  double sim = 0.0;
  const KeptSegment *k = v->at(time, &sim);
  if (!k) return ball_refused(c, match, BALL_EAGAIN);
  ball_status st = ball_flight_eval(&k->flight, sim, &out->state);
  if (st != BALL_OK) return ball_refused(c, match, st);
  const SegmentOut &s = k->segment;
  out->sim_time = sim;
  out->segment = s.seq;
  out->cause = static_cast<ball_net_cause>(s.cause);
  out->cause_index = s.cause_index;
  out->sound = s.sound;
  out->flight = s.segment;
  return c->ok();
}

ball_status ball_net_racket(const ball_net_client *cc, uint32_t match, int slot, double time, ball_racket_pose *out) {
  return on_view(cc, match, out, [&](ball_net_client *c, const MatchView &) {
    if (!c->rackets) return c->fail(BALL_EINVAL, "the client reads no rackets: set ball_net_config.rackets");
    if (!std::isfinite(time)) return c->fail(BALL_ENONFINITE, "the time must be finite");
    ball_status st = c->core->racket(match, slot, time, out);
    if (st == BALL_OK) return c->ok();
    const std::string which = "slot " + std::to_string(slot) + " of match " + std::to_string(match);
    if (st == BALL_ERANGE) return c->fail(st, which + ": the match has no such slot");
    if (st == BALL_EAGAIN || st == BALL_ENOTFOUND)
      return c->fail(BALL_EAGAIN, which + ": no clock, model or racket sample of it yet");
    if (st == BALL_ESTALE) return c->fail(st, which + ": its newest sample is older than the model's stale_time");
    return c->fail(st, which + ": " + ball_strerror(st));
  });
}

ball_status ball_net_predict(const ball_net_client *cc, uint32_t match, double time, double horizon, double dt,
                             ball_prediction *out) {
  return on_view(cc, match, out, [&](ball_net_client *c, const MatchView &v) {
    ball_status st = v.predict(time, horizon, dt, out);
    if (st == BALL_EAGAIN)
      return c->fail(st, "match " + std::to_string(match) + ": its whole model, clock or segment has not come yet");
    if (st != BALL_OK) return c->fail(st, std::string("ball_predict: ") + ball_strerror(st));
    return c->ok();
  });
}

ball_status ball_net_sim_time(const ball_net_client *cc, uint32_t match, double time, double *sim) {
  return on_view(cc, match, sim, [&](ball_net_client *c, const MatchView &v) {
    if (!std::isfinite(time)) return c->fail(BALL_ENONFINITE, "the time must be finite");
    if (!v.clock().valid()) return no_clock(c, match);
    *sim = v.clock().sim_now(time);
    return c->ok();
  });
}

ball_status ball_net_local_time(const ball_net_client *cc, uint32_t match, double sim, double *time) {
  return on_view(cc, match, time, [&](ball_net_client *c, const MatchView &v) {
    if (!std::isfinite(sim)) return c->fail(BALL_ENONFINITE, "the sim time must be finite");
    if (!v.clock().valid()) return no_clock(c, match);
    *time = v.clock().local_at(sim, c->now());
    return c->ok();
  });
}

ball_status ball_net_model(const ball_net_client *cc, uint32_t match, ball_model *out) {
  return on_view(cc, match, out, [&](ball_net_client *c, const MatchView &v) {
    if (!v.model()) return c->fail(BALL_EAGAIN, "the model of match " + std::to_string(match) + " has not come yet");
    *out = *v.model();
    return c->ok();
  });
}

}  // extern "C"
