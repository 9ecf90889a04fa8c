#include "player_group.h"

#include <set>

namespace ballsrv {

namespace {
constexpr int kEventBatch = 64;  // events taken per ball_net_poll
}  // namespace

PlayerGroup::PlayerGroup(std::vector<BotPlayer> bots, ball_net_client *client)
    : bots_(std::move(bots)), client_(client), begun_(bots_.size(), false), events_(kEventBatch) {}

void PlayerGroup::tick(double mono, const std::function<void(const ball_net_event &)> &on_event) {
  auto due = [&](size_t i) { return starts_.empty() || mono >= starts_[i]; };
  for (size_t i = 0; i < bots_.size(); ++i)
    if (!begun_[i] && due(i)) {
      if (ball_net_join(client_, bots_[i].match(), bots_[i].wanted()) != BALL_OK && error_.empty())
        error_ = ball_net_message(client_);
      begun_[i] = true;
    }
  int n = kEventBatch;
  while (n == kEventBatch && ball_net_poll(client_, events_.data(), kEventBatch, &n) == BALL_OK)
    for (int i = 0; i < n; ++i) {
      const ball_net_event &e = events_[static_cast<size_t>(i)];
      if (e.kind == BALL_NET_EVENT_SLOT && e.index >= 0 && e.index < kMaxPlayers) {
        unsigned bit = 1u << e.index;
        held_[e.match] = e.value != 0.0 ? held_[e.match] | bit : held_[e.match] & ~bit;
      }
      if (on_event) on_event(e);
    }
  for (size_t i = 0; i < bots_.size(); ++i) {
    if (!due(i)) continue;
    auto h = held_.find(bots_[i].match());
    bots_[i].tick(client_, h == held_.end() ? 0u : h->second, mono);
  }
}

void PlayerGroup::start_at(std::vector<double> starts) {
  if (starts.size() == bots_.size()) starts_ = std::move(starts);
}

int PlayerGroup::leave() {
  int n = 0;
  for (auto &b : bots_)
    if (b.joined()) n += ball_net_leave(client_, b.match(), b.slot()) == BALL_OK;
  return n;
}

bool PlayerGroup::all_joined() const {
  for (const auto &b : bots_)
    if (!b.joined()) return false;
  return true;
}

uint64_t PlayerGroup::sum(uint64_t ball_net_status::*field) const {
  std::set<uint32_t> matches;
  for (const auto &b : bots_) matches.insert(b.match());
  uint64_t n = 0;
  ball_net_status s;
  for (uint32_t m : matches)
    if (ball_net_status_of(client_, m, &s) == BALL_OK) n += s.*field;
  return n;
}

BotReport PlayerGroup::report(size_t i) const {
  const BotPlayer &b = bots_[i];
  BotReport r;
  r.match = b.match();
  r.slot = b.slot();
  r.samples = b.counters().taken;
  ball_net_status s{};
  if (ball_net_status_of(client_, b.match(), &s) == BALL_OK) {
    r.lost = s.link_lost;
    r.written = s.samples;
    r.segments = s.segments;
    r.refused = s.refused + s.untrusted;
    r.untrusted = s.untrusted;
  }
  r.write_failures = write_failures();
  r.plans = b.brain_counters().plans;
  r.late = b.brain_counters().late;
  r.missed_on_purpose = b.brain_counters().missed_on_purpose;
  return r;
}

}  // namespace ballsrv
