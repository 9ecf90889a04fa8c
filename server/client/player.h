// One autonomous player of one match, free of DDS: what ball-bot runs once
// and ball-load runs for every slot of many matches. It plays through the
// client library's C API (ball/net.h), as a game does: the match's model,
// clock and the segment in effect from the client, planned with BotBrain,
// and its racket pose pushed at its rate; the client's simulated network
// (ball_net_config's link_*, from the bot's delay, jitter and loss) delays
// and loses them as a network would. No scene file: the match's model
// comes from the wire.
#pragma once

#include <string>
#include <vector>

#include "ball/net.h"
#include "bot.h"
#include "fields.h"
#include "types.h"

namespace ballsrv {

// A bot's settings; their ranges and meanings are player_fields() (the
// options of ball-bot, and those ball-demo and ball-load pass on).
struct PlayerParams {
  uint32_t match = 0;         // the match
  int player = -1;            // slot wanted, -1: any free one
  double rate = 30.0;         // samples per s
  double delay = 0.0;         // s added to each sample's trip
  double jitter = 0.0;        // s: up to this much later again, uniform
  double loss = 0.0;          // probability a sample is lost
  double noise = 0.0;         // m: Gaussian tracker noise on the centre
  double miss = 0.0;          // skill: probability of missing a ball
  double aim_error = 0.0;     // skill: m of Gaussian error on the planned contact
  double move_speed = 12.0;   // m/s the racket travels between strokes
  double lead = -1.0;         // s on the stroke line before contact; < 0: bot_lead(rate, delay, jitter, loss)
  uint64_t seed = 1;          // of every random draw
  std::string servers;        // the server ids it takes the server topics from, comma-separated ("": any)
};
const std::vector<Field<PlayerParams>> &player_fields();

// The simulated network of a client whose bots play with these settings
// (their delay, jitter, loss; the link's draws from their seed).
void set_link(const PlayerParams &params, ball_net_config *config);

struct PlayerCounters {
  uint64_t taken = 0;  // poses taken and pushed (the client writes them, or its simulated network loses them)
};

class BotPlayer {
 public:
  explicit BotPlayer(const PlayerParams &params);

  // Advances to `mono` of the client's clock on `client`, which follows the
  // bot's match; `held` the slots of the match the client holds (a bit
  // each, from its BALL_NET_EVENT_SLOT events): plays the segment in
  // effect and pushes its racket pose at its rate.
  void tick(ball_net_client *client, unsigned held, double mono);

  uint32_t match() const { return p_.match; }
  int wanted() const { return p_.player; }  // the slot it joins, -1: any
  bool joined() const { return joined_; }
  int slot() const { return slot_; }
  const PlayerCounters &counters() const { return counters_; }
  const BotCounters &brain_counters() const { return brain_.counters(); }

 private:
  PlayerParams p_;
  BotBrain brain_;
  Rng noise_;
  bool brain_ready_ = false, joined_ = false;
  int slot_ = -1;
  uint64_t model_hash_ = 0;  // the model the brain plays with
  bool any_segment_ = false;
  uint32_t segment_ = 0;     // the seq of the segment in effect handed to the brain
  double next_sample_ = -1.0;
  PlayerCounters counters_;
  void plan(ball_net_client *client, double mono, double sim);
};

}  // namespace ballsrv
