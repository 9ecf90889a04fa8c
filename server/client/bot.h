// An autonomous player's mind, free of DDS: from the ball's segments it
// plans where its racket disc meets the ball (ball_predict) and how it
// swings, and says where the disc is at any sim time. ball-bot samples that
// pose at its rate and sends it; the offline tests feed it to a Match.
//
// The plan is a path of straight legs: move to the start of the stroke line
// at move_speed, wait, then travel the stroke line at constant racket
// velocity through the contact point at the contact time, `lead` seconds
// before to `follow` after. A straight stroke of that length is what the
// server's eq 15 extrapolation carries over the samples' network delay
// (docs/bots-and-watchers.md, "Bots").
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "ball/ball.h"
#include "court.h"
#include "rng.h"

namespace ballsrv {

struct BotParams {
  int slot = 0;
  int players = 2;
  double miss_rate = 0.0;      // probability of missing a ball on purpose, [0, 1]
  double aim_error = 0.0;      // m: Gaussian sigma on the planned contact point (y and z)
  double move_speed = 12.0;    // m/s the racket travels between strokes
  double lead = 0.3;           // s on the stroke line before contact
  double follow = 0.2;         // s on it after contact
  double swing_length = 2.0;   // m: the most the racket travels during `lead` (mid level)
  double v_up = 4.0;           // m/s: vertical speed of the bot's returns (mid, advanced)
  double reach_lo = 0.3;       // m above the floor: lowest contact
  double reach_hi = 2.0;       // m above the floor: highest contact
  double min_depth = 1.5;      // m from the net: closest contact
  double max_behind = 4.0;     // m behind its baseline: farthest contact
  double reaction = 0.05;      // s: nothing closer in time than this is planned
  uint64_t seed = 1;
};

struct BotCounters {
  uint64_t plans = 0;         // balls it went for
  uint64_t late = 0;          // of those, too far to be on the stroke line in time
  uint64_t missed_on_purpose = 0;
  uint64_t ignored = 0;       // segments with no ball to play
};

// How long a bot should be on its stroke line before contact so that the
// server sees the straight stroke through samples taken at `rate` Hz that
// arrive `delay` + up to `jitter` late, one in a while lost: two sample
// periods (eq 15 extrapolates from the two newest samples), one more when
// samples get lost, the delay, the jitter and 50 ms; within [0.25, 1] s.
double bot_lead(double rate, double delay, double jitter, double loss);

class BotBrain {
 public:
  void init(const ball_model &model, const Court &court, const BotParams &params);
  void set_model(const ball_model &model) { model_ = model; }

  // A segment from the server (its newest); `serve` when a serve started it.
  // Replans from the racket's pose at sim time `now`.
  void on_segment(const ball_segment &seg, bool serve, int serving_slot, double now);

  // Where the disc is at sim time t: centre and unit normal.
  void pose(double t, ball_vec3 *center, ball_vec3 *normal) const;

  int side() const { return Court::side_of_slot(params_.slot); }
  const BotCounters &counters() const { return counters_; }
  bool planned() const { return has_contact_; }
  double contact_time() const { return contact_t_; }
  ball_vec3 contact_point() const { return contact_p_; }

 private:
  struct Leg {
    double t0, t1;  // sim s
    ball_vec3 p0;   // at t0, m
    ball_vec3 v;    // m/s
  };
  void go_to(ball_vec3 target, double now, ball_vec3 normal);
  void stroke_for(ball_vec3 x, ball_vec3 v_in, ball_vec3 s_in, ball_vec3 *v_racket, ball_vec3 *normal);
  bool keeps_plan(const ball_segment &seg, int n_events) const;  // the ball still passes the planned contact
  int pick_contact(double now, double t_from, ball_vec3 here, int n_states) const;  // index into states_; -1: none
  void plan_stroke(double now, ball_vec3 here, double t_hit, ball_vec3 x, ball_vec3 v_racket, ball_vec3 normal);

  ball_model model_{};
  Court court_;
  BotParams params_;
  Rng rng_{1};
  std::vector<Leg> legs_;   // in time order; before the first and after the last: held
  ball_vec3 rest_{0, 0, 0}; // where it is when no leg applies yet
  ball_vec3 normal_{1, 0, 0};
  bool has_contact_ = false;
  bool has_planned_ = false;  // raw_* hold the predicted contact the current plan is for
  double raw_t_ = 0.0;
  ball_vec3 raw_p_{0, 0, 0};
  double contact_t_ = 0.0;
  ball_vec3 contact_p_{0, 0, 0};
  BotCounters counters_;
  std::vector<ball_state> states_;
  std::vector<ball_event> events_;
};

}  // namespace ballsrv
