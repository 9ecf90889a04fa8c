#include "player_group.h"

namespace ballsrv {

PlayerGroup::PlayerGroup(std::vector<BotPlayer> bots) : bots_(std::move(bots)) {
  for (auto &b : bots_) by_match_[b.match()].push_back(&b);
}

template <class T>
void PlayerGroup::write(ClientPort &port, const std::vector<T> &items, uint64_t *written) {
  for (const auto &item : items) {
    if (port.write(item)) (*written)++;
    else write_failures_++;
  }
}

bool PlayerGroup::tick(ClientPort &port, double mono, double real,
                       const std::function<void(const SegmentOut &, double)> &on_segment) {
  MatchInfoOut info;
  while (port.take(&info)) {
    auto it = by_match_.find(info.match_id);
    if (it == by_match_.end()) continue;
    for (BotPlayer *b : it->second) b->on_info(info, real);
  }
  StateOut state;
  while (port.take(&state)) {
    auto it = by_match_.find(state.match_id);
    if (it != by_match_.end())
      for (BotPlayer *b : it->second) b->on_state(state, real);
  }
  SegmentOut seg;
  while (port.take(&seg)) {
    auto it = by_match_.find(seg.match_id);
    if (it == by_match_.end()) continue;
    for (BotPlayer *b : it->second) b->on_segment(seg, real);
    if (on_segment) on_segment(seg, real);
  }
  samples_.clear();
  controls_.clear();
  for (size_t i = 0; i < bots_.size(); ++i)
    if (starts_.empty() || mono >= starts_[i]) bots_[i].tick(mono, real, &samples_, &controls_);
  write(port, controls_, &controls_written_);
  write(port, samples_, &samples_written_);
  return true;
}

void PlayerGroup::start_at(std::vector<double> starts) {
  if (starts.size() == bots_.size()) starts_ = std::move(starts);
}

int PlayerGroup::leave(ClientPort &port) {
  int n = 0;
  for (auto &b : bots_) {
    ControlIn bye;
    if (!b.leave(&bye)) continue;
    if (port.write(bye)) n++;
    else write_failures_++;
  }
  return n;
}

bool PlayerGroup::all_joined() const {
  for (const auto &b : bots_)
    if (!b.joined()) return false;
  return true;
}

BotReport PlayerGroup::report(size_t i, const ParticipantId &me) const {
  const BotPlayer &b = bots_[i];
  BotReport r;
  r.match = b.match();
  r.slot = b.slot();
  r.samples = b.counters().taken;
  r.lost = b.counters().lost;
  r.written = b.counters().delivered;
  r.write_failures = write_failures_;
  r.segments = b.counters().segments;
  r.plans = b.brain_counters().plans;
  r.late = b.brain_counters().late;
  r.missed_on_purpose = b.brain_counters().missed_on_purpose;
  r.refused = b.counters().refused;
  r.participant = hex(me);
  return r;
}

}  // namespace ballsrv
