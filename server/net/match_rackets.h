// The players' rackets of one match as a client draws them (the watcher's
// snapshots and the spectator page, natively and on WebAssembly): one
// libball track per slot, in a sim of the match's model, so that a racket
// is where ball_racket_estimate puts it (interpolated between samples,
// eq 15 past the newest, capped by extrapolation_time). The tracks start
// anew with a new server (another clock); a slot's track starts anew with a
// new holder (its own clock); a new model (a level) keeps them.
#pragma once

#include <array>
#include <cstdint>
#include <memory>

#include "ball/ball.h"
#include "types.h"

namespace ballsrv {

class MatchRackets {
 public:
  // The match as its newest MatchInfo has it, with the model to draw it
  // with; false when that model starts no sim (the tracks are as they were).
  bool follow(const MatchInfoOut &info, const ball_model &model) {
    if (!sim_ || info.server_id != server_) {
      auto sim = std::make_unique<ball_sim>();
      if (ball_sim_init(sim.get(), &model) != BALL_OK) return false;
      sim_ = std::move(sim);
      server_ = info.server_id;
      hash_ = ball_model_hash(&model);
      owners_ = {};
    } else if (ball_model_hash(&model) != hash_) {
      if (ball_sim_set_model(sim_.get(), &model) != BALL_OK) return false;
      hash_ = ball_model_hash(&model);
    }
    players_ = info.players < kMaxPlayers ? info.players : kMaxPlayers;
    for (int i = 0; i < kMaxPlayers; ++i)
      if (owners_[i] != info.slots[i].owner) {
        if (i < ball_sim_model(sim_.get())->n_rackets) ball_racket_clear(sim_.get(), i);
        owners_[i] = info.slots[i].owner;
      }
    return true;
  }
  // A sample of slot `slot`'s racket (BALL_EAGAIN: no match followed yet;
  // BALL_ERANGE: no such slot; else ball_racket_push's status).
  ball_status push(int slot, const ball_racket_sample &s) {
    if (!sim_) return BALL_EAGAIN;
    if (!has(slot)) return BALL_ERANGE;
    return ball_racket_push(sim_.get(), slot, &s);
  }
  // Slot `slot`'s racket at sim time t (ball_racket_estimate's status).
  ball_status pose(int slot, double t, ball_racket_pose *out) const {
    if (!sim_) return BALL_EAGAIN;
    if (!has(slot)) return BALL_ERANGE;
    return ball_racket_estimate(sim_.get(), slot, t, out);
  }
  // The slot's holder as the newest MatchInfo followed names it (zeros: none).
  const ParticipantId &holder(int slot) const { return owners_[static_cast<size_t>(slot)]; }
  bool has(int slot) const {
    return sim_ && slot >= 0 && slot < players_ && slot < ball_sim_model(sim_.get())->n_rackets;
  }

 private:
  std::unique_ptr<ball_sim> sim_;  // its model's rackets are the slots' tracks
  uint32_t server_ = 0;
  uint64_t hash_ = 0;
  int players_ = 0;
  std::array<ParticipantId, kMaxPlayers> owners_{};
};

}  // namespace ballsrv
