#include "player.h"

#include <cmath>

#include "ball/vec3.h"
#include "court.h"
#include "rng.h"

namespace ballsrv {

BotPlayer::BotPlayer(const PlayerParams &params) : p_(params), noise_(params.seed * 31 + 5), slot_(params.player) {}

// The brain plays the segment in effect on the client's clock, handed on
// once each time it changes, with the match's model from the wire (a new
// one at a new level).
void BotPlayer::plan(ball_net_client *client, double mono, double sim) {
  ball_net_match m;
  if (ball_net_match_info(client, p_.match, &m) != BALL_OK) return;
  if (!brain_ready_ || m.model_hash != model_hash_) {
    ball_model model;
    if (ball_net_model(client, p_.match, &model) != BALL_OK) return;  // (its MatchModel has not come: the bot waits)
    if (!brain_ready_) {
      Court court;
      std::string err;
      if (!court_from_model(model, m.court_x[0], &court, &err)) return;
      BotParams b;
      b.slot = slot_;
      b.players = m.players;
      b.miss_rate = p_.miss;
      b.aim_error = p_.aim_error;
      b.move_speed = p_.move_speed;
      b.lead = p_.lead >= 0.0 ? p_.lead : bot_lead(p_.rate, p_.delay, p_.jitter, p_.loss);
      b.seed = p_.seed;
      brain_.init(model, court, b);
      brain_ready_ = true;
    } else {
      brain_.set_model(model);
    }
    model_hash_ = m.model_hash;
  }
  ball_net_ball ball;
  if (ball_net_ball_at(client, p_.match, mono, &ball) != BALL_OK) return;
  if (any_segment_ && ball.segment == segment_) return;
  any_segment_ = true;
  segment_ = ball.segment;
  brain_.on_segment(ball.flight, ball.cause == BALL_NET_CAUSE_SERVE, ball.cause_index, sim);
}

void BotPlayer::tick(ball_net_client *client, unsigned held, double mono) {
  // players sample on their own phases, not in step (a seeded fraction of a sample's period):
  // a process of many bots would write all their samples in one burst otherwise
  if (next_sample_ < 0.0) next_sample_ = mono + golden_phase(p_.seed) / p_.rate;
  int slot = -1;
  for (int k = 0; k < kMaxPlayers && slot < 0; ++k)
    if ((held >> k & 1u) && (p_.player < 0 || p_.player == k)) slot = k;
  joined_ = slot >= 0;
  if (joined_) {
    if (slot != slot_ && brain_ready_) brain_ready_ = false;  // another slot: another side of the court
    slot_ = slot;
  } else if (p_.player < 0) {
    slot_ = -1;  // taken from us: any free one again (the client asks)
  }
  double sim = 0.0;
  bool clock = ball_net_sim_time(client, p_.match, mono, &sim) == BALL_OK;
  if (joined_ && clock) plan(client, mono, sim);
  // after a wait (to join, for the clock) or a stall: on at the player's phase, no burst
  if (next_sample_ < mono - 1.0 / p_.rate) next_sample_ += std::ceil((mono - next_sample_) * p_.rate) / p_.rate;
  if (joined_ && brain_ready_ && clock && mono >= next_sample_) {
    ball_vec3 center, normal;
    brain_.pose(sim, &center, &normal);
    center.x += noise_.normal(p_.noise);
    center.y += noise_.normal(p_.noise);
    center.z += noise_.normal(p_.noise);
    if (ball_net_push(client, p_.match, slot_, mono, center, normal) == BALL_OK) counters_.taken++;
    next_sample_ += 1.0 / p_.rate;
  }
}

}  // namespace ballsrv
