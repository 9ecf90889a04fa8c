// One autonomous player of one match, free of DDS: what ball-bot runs once
// and ball-load runs for every slot of many matches. It plays from what the
// client library's core holds of its match (a MatchView: the trusted
// MatchInfo, the whole model from the wire, the sim clock, the segment in
// effect), plans with BotBrain, and says which racket samples to write and
// when, numbered by the core and sent through a link that delays and loses
// them as a network would; its group (PlayerGroup) joins its slot and
// writes them. No scene file: the match's model comes from the wire.
#pragma once

#include <string>
#include <vector>

#include "bot.h"
#include "client_core.h"
#include "fields.h"
#include "link.h"
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

struct PlayerCounters {
  uint64_t taken = 0;     // samples taken
  uint64_t lost = 0;      // of those, lost on the link
  uint64_t delivered = 0; // handed to the caller to write
};

class BotPlayer {
 public:
  explicit BotPlayer(const PlayerParams &params);

  // Advances to the monotonic clock's `mono` (the core's clock) with its
  // match's view (nullptr: not followed yet): plays the segment in effect,
  // takes a sample at its rate (numbered and mapped to the sim clock by
  // `core`) and appends those whose (simulated) network trip ends now.
  void tick(const MatchView *view, ClientCore &core, double mono, std::vector<RacketSampleIn> *samples);

  uint32_t match() const { return p_.match; }
  int wanted() const { return p_.player; }  // the slot it joins, -1: any
  bool joined() const { return joined_; }
  int slot() const { return slot_; }
  const PlayerCounters &counters() const { return counters_; }
  const BotCounters &brain_counters() const { return brain_.counters(); }

 private:
  PlayerParams p_;
  BotBrain brain_;
  Link<RacketSampleIn> link_;
  Rng noise_;
  bool brain_ready_ = false, joined_ = false;
  int slot_ = -1;
  uint64_t model_hash_ = 0;  // the model the brain plays with
  EffectFeed feed_;          // the segment in effect, handed to the brain
  double next_sample_ = -1.0;
  PlayerCounters counters_;
  void plan(const MatchView &view, double sim);
};

}  // namespace ballsrv
