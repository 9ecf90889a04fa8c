#include "bot.h"

#include <cmath>

#include "ball/vec3.h"

namespace ballsrv {

namespace {
constexpr double kPredictDt = 1.0 / 240.0;  // s between predicted states
constexpr double kHorizon = 3.5;            // s of flight looked at
constexpr double kJoinStep = 0.005;         // s: search step for joining a stroke line late
constexpr double kMissOffset = 0.8;         // m beside the ball when missing on purpose
}  // namespace

double bot_lead(double rate, double delay, double jitter, double loss) {
  double lead = 2.0 / rate + delay + jitter + (loss > 0.0 ? 1.0 / rate : 0.0) + 0.05;
  return std::fmin(1.0, std::fmax(0.25, lead));
}

void BotBrain::init(const ball_model &model, const Court &court, const BotParams &params) {
  model_ = model;
  court_ = court;
  params_ = params;
  rng_ = Rng(params.seed);
  rest_ = court.ready(params.slot, params.players);
  normal_ = ball_v3(Court::toward_net(side()), 0.0, 0.0);
  legs_.clear();
  states_.assign(static_cast<size_t>(std::ceil(kHorizon / kPredictDt)) + 2, ball_state{});
  events_.assign(32, ball_event{});
}

void BotBrain::pose(double t, ball_vec3 *center, ball_vec3 *normal) const {
  *normal = normal_;
  if (legs_.empty() || t <= legs_.front().t0) {
    *center = legs_.empty() ? rest_ : legs_.front().p0;
    return;
  }
  for (const Leg &leg : legs_) {
    if (t <= leg.t1) {
      *center = ball_v3_add(leg.p0, ball_v3_scale(leg.v, t - leg.t0));
      return;
    }
  }
  const Leg &last = legs_.back();
  *center = ball_v3_add(last.p0, ball_v3_scale(last.v, last.t1 - last.t0));
}

void BotBrain::go_to(ball_vec3 target, double now, ball_vec3 normal) {
  ball_vec3 here, n;
  pose(now, &here, &n);
  legs_.clear();
  rest_ = here;
  normal_ = normal;
  double d = ball_v3_dist(here, target);
  if (d <= 0.0) return;
  double dur = d / params_.move_speed;
  legs_.push_back(Leg{now, now + dur, here, ball_v3_scale(ball_v3_sub(target, here), 1.0 / dur)});
}

// The racket velocity and face normal that send a ball arriving at x with
// velocity v_in and spin s_in back to the other side, per the model's response.
void BotBrain::stroke_for(ball_vec3 x, ball_vec3 v_in, ball_vec3 s_in, ball_vec3 *v_racket, ball_vec3 *normal) {
  int s = side();
  double half_width = 0.5 * (court_.z_hi - court_.z_lo);
  ball_vec3 target = court_.spot(1 - s, 0.65, rng_.uniform(-0.25, 0.25) * half_width);
  ball_vec3 v_d;
  if (lob_velocity(model_, x, target, params_.v_up, &v_d) != BALL_OK)
    v_d = ball_v3(Court::toward_net(s) * 15.0, params_.v_up, 0.0);
  switch (model_.response) {
    case BALL_RESPONSE_AUTONOMOUS:
      // eq 8, 9: the ball flies to the partner whatever the stroke; a still
      // racket is what the sphere test finds most surely
      *v_racket = ball_v3(0.0, 0.0, 0.0);
      *normal = ball_v3_unit(ball_v3_scale(v_in, -1.0));
      break;
    case BALL_RESPONSE_MIXED: {
      // eq 10: the stroke has 1 - friendly_factor of the say; swing toward the aim
      double speed = std::fmin(ball_v3_norm(v_d), params_.swing_length / params_.lead);
      *normal = ball_v3_unit(v_d);
      *v_racket = ball_v3_scale(*normal, speed);
      break;
    }
    case BALL_RESPONSE_PHYSICAL: {
      // eq 11 with the racket moving along its normal (no racket spin, S_racket = 0):
      // V0 = V + (w - 2 n.V) n + S x n. For V0 = v_d: n is the direction of
      // v_d - V - S x n (a fixed point: S x n depends on n) and w follows.
      bool spin = (model_.effects & BALL_EFFECT_SPIN) != 0;
      ball_vec3 n = ball_v3_unit(ball_v3_sub(v_d, v_in));
      ball_vec3 need = ball_v3_sub(v_d, v_in);
      for (int it = 0; it < 8; ++it) {
        need = ball_v3_sub(ball_v3_sub(v_d, v_in), spin ? ball_v3_cross(s_in, n) : ball_v3(0, 0, 0));
        n = ball_v3_unit(need);
      }
      double w = ball_v3_dot(n, need) + 2.0 * ball_v3_dot(n, v_in);
      *normal = n;
      *v_racket = ball_v3_scale(n, w);
      break;
    }
    default:  // eq 7: the ball leaves along the racket velocity
      *normal = ball_v3_unit(v_d);
      *v_racket = v_d;
      break;
  }
}

// A segment that changes nothing (the bounce the plan foresaw) keeps the
// plan: the ball still passes the planned contact at the planned time.
bool BotBrain::keeps_plan(const ball_segment &seg, int n_events) const {
  ball_segment then = seg;
  for (int i = 0; i < n_events; ++i)
    if (events_[i].time <= raw_t_) then = events_[i].segment;
  ball_state at;
  return ball_segment_eval(&model_, &then, raw_t_, &at) == BALL_OK && ball_v3_dist(at.position, raw_p_) < 0.01;
}

// Of the predicted states from t_from, the reachable one nearest the bot's
// ready spot, so that it keeps its place on the court instead of being
// driven back stroke after stroke; none reachable: the one it misses by
// least; -1: none on its side it could ever meet.
int BotBrain::pick_contact(double now, double t_from, ball_vec3 here, int n_states) const {
  const int s = side();
  const double dir = Court::toward_net(s);
  ball_vec3 home = court_.ready(params_.slot, params_.players);
  int best = -1, best_late = -1;
  double best_home = 1e300, best_slack = -1e300;
  double depth_max = court_.side_length(s) + params_.max_behind;
  for (int k = 0; k < n_states; ++k) {
    double t = t_from + k * kPredictDt;
    const ball_state &b = states_[k];
    if (t < now + params_.reaction) continue;
    if (court_.side_of(b.position.x) != s || b.velocity.x * dir >= 0.0) continue;
    double depth = (court_.net_x - b.position.x) * dir;
    double h = b.position.y - court_.floor;
    if (depth < params_.min_depth || depth > depth_max || h < params_.reach_lo || h > params_.reach_hi) continue;
    double travel = ball_v3_dist(here, b.position);
    double slack = (t - now) - travel / params_.move_speed - params_.lead;
    double from_home = ball_v3_dist(home, b.position);
    if (slack >= 0.0 && from_home < best_home) {
      best = k;
      best_home = from_home;
    }
    if (slack > best_slack) {
      best_late = k;
      best_slack = slack;
    }
  }
  return best >= 0 ? best : best_late;
}

// The racket's way from `here` at `now` to the stroke through x at t_hit
// with velocity v_racket: it joins the stroke line p(t) = x + v_racket (t -
// t_hit) as early as it can get there, `lead` before contact at the
// earliest, and above the floor (a steep stroke's line starts under it: a
// racket there is no body, and the server drops its samples as out of
// range), then follows through.
void BotBrain::plan_stroke(double now, ball_vec3 here, double t_hit, ball_vec3 x, ball_vec3 v_racket, ball_vec3 normal) {
  double t_join = t_hit - params_.lead;
  ball_vec3 p_join = ball_v3_add(x, ball_v3_scale(v_racket, t_join - t_hit));
  while ((ball_v3_dist(here, p_join) > params_.move_speed * (t_join - now) || p_join.y < court_.floor) &&
         t_join < t_hit) {
    t_join += kJoinStep;
    p_join = ball_v3_add(x, ball_v3_scale(v_racket, t_join - t_hit));
  }
  double follow = params_.follow;  // (the follow-through ends at the floor too)
  if (v_racket.y < 0.0) follow = std::fmin(follow, std::fmax(0.0, (x.y - court_.floor) / -v_racket.y));
  if (t_join > t_hit - params_.lead + 1e-9) counters_.late++;
  counters_.plans++;

  legs_.clear();
  rest_ = here;
  normal_ = normal;
  double travel = ball_v3_dist(here, p_join);
  double t_arrive = now + travel / params_.move_speed;
  if (t_arrive > t_join) t_arrive = t_join;
  if (t_arrive > now)
    legs_.push_back(Leg{now, t_arrive, here, ball_v3_scale(ball_v3_sub(p_join, here), 1.0 / (t_arrive - now))});
  else
    legs_.push_back(Leg{now, now, here, ball_v3(0, 0, 0)});
  legs_.push_back(Leg{legs_.back().t1, t_join, p_join, ball_v3(0, 0, 0)});
  legs_.push_back(Leg{t_join, t_hit + follow, p_join, v_racket});
  has_contact_ = true;
  contact_t_ = t_hit;
  contact_p_ = x;
}

void BotBrain::on_segment(const ball_segment &seg, bool serve, int serving_slot, double now) {
  ball_vec3 here, n;
  pose(now, &here, &n);
  has_contact_ = false;
  bool had_plan = has_planned_ && raw_t_ > now;
  has_planned_ = false;
  if (serve && Court::side_of_slot(serving_slot) == side()) {
    // our side serves: back to the ready spot, out of the serve's way
    go_to(court_.ready(params_.slot, params_.players), now, ball_v3(Court::toward_net(side()), 0.0, 0.0));
    return;
  }
  double t_from = std::fmax(now, seg.t0);
  ball_prediction pr{};
  pr.states = states_.data();
  pr.cap_states = static_cast<int>(states_.size());
  pr.events = events_.data();
  pr.cap_events = static_cast<int>(events_.size());
  if (ball_predict(&model_, &seg, t_from, t_from + kHorizon, kPredictDt, &pr) != BALL_OK) {
    counters_.ignored++;
    return;
  }
  if (had_plan && keeps_plan(seg, pr.n_events)) {
    has_planned_ = true;
    has_contact_ = true;
    return;
  }
  int best = pick_contact(now, t_from, here, pr.n_states);
  if (best < 0) {
    counters_.ignored++;
    legs_.clear();
    rest_ = here;
    return;
  }
  double t_hit = t_from + best * kPredictDt;
  ball_vec3 x = states_[best].position;
  has_planned_ = true;
  raw_t_ = t_hit;
  raw_p_ = x;
  if (params_.miss_rate > 0.0 && rng_.chance(params_.miss_rate)) {
    x.z += (rng_.chance(0.5) ? 1.0 : -1.0) * kMissOffset;
    counters_.missed_on_purpose++;
  } else if (params_.aim_error > 0.0) {
    x.y += rng_.normal(params_.aim_error);
    x.z += rng_.normal(params_.aim_error);
  }
  ball_vec3 v_racket, normal;
  stroke_for(x, states_[best].velocity, states_[best].spin, &v_racket, &normal);
  plan_stroke(now, here, t_hit, x, v_racket, normal);
}

}  // namespace ballsrv
