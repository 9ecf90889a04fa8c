// One autonomous player of one match, free of DDS: what ball-bot runs once
// and ball-load runs for every slot of many matches. It reads what the
// server says (match info, ball states, segments), holds its slot (JOIN
// until the match info shows it), maps its clock to the sim clock, plans
// with BotBrain, and says which racket samples and control messages to
// write and when; the caller writes them.
#pragma once

#include <string>
#include <vector>

#include "ball/scene.h"
#include "bot.h"
#include "fields.h"
#include "link.h"
#include "segment_feed.h"
#include "sim_clock.h"
#include "trust.h"
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
  uint64_t segments = 0;  // newer segments seen
  uint64_t refused = 0;   // server samples not taken: another server, numbers out of range, a clock pair or
                          // a segment seq that does not fit (trust.h)
  bool hash_differs = false;  // its model is not the server's (another scene?)
};

class BotPlayer {
 public:
  BotPlayer(const ball_scene &scene, const ParticipantId &me, const PlayerParams &params);

  // What the server said; `real` is the local realtime clock at reception.
  // What does not fit (trust.h) is refused and counted; a MatchInfo whose
  // model cannot be built from the scene leaves the bot as it was, with
  // error() saying why. Nothing from the wire ends the bot.
  void on_info(const MatchInfoOut &info, double real);
  void on_state(const StateOut &state, double real);
  void on_segment(const SegmentOut &segment, double real);

  // Advances to local time (monotonic `mono`, realtime `real`): appends the
  // samples whose (simulated) network trip ends now and the control
  // messages due.
  void tick(double mono, double real, std::vector<RacketSampleIn> *samples, std::vector<ControlIn> *controls);

  // The LEAVE to send on a clean exit; false when not joined.
  bool leave(ControlIn *out);

  uint32_t match() const { return p_.match; }
  bool joined() const { return joined_; }
  int slot() const { return slot_; }
  const std::string &error() const { return error_; }
  const PlayerCounters &counters() const { return counters_; }
  const BotCounters &brain_counters() const { return brain_.counters(); }
  uint64_t model_hash() const { return model_hash_; }
  uint64_t server_hash() const { return server_hash_; }

 private:
  ball_scene scene_;
  ParticipantId me_;
  PlayerParams p_;
  SimClock clock_;
  ServerChoice servers_;
  BotBrain brain_;
  Link<RacketSampleIn> link_;
  Rng noise_;
  MatchInfoOut info_;
  bool have_info_ = false, model_ready_ = false, brain_ready_ = false, joined_ = false;
  int slot_ = -1;
  ball_model model_{};
  Court court_;
  uint64_t model_hash_ = 0, server_hash_ = 0;
  int level_ = -1, players_ = 0;
  double extrapolation_ = -1.0, stale_ = -1.0;
  SegmentFeed feed_;
  uint32_t newest_seq_ = 0, sample_seq_ = 0, control_seq_ = 0;
  void hand_over(double real);
  double next_sample_ = -1.0, next_join_ = -1.0;
  std::string error_;
  PlayerCounters counters_;
};

}  // namespace ballsrv
