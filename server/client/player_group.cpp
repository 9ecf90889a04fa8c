#include "player_group.h"

#include <set>

namespace ballsrv {

namespace {
CoreSettings core_settings(const ServerChoice &servers) {
  CoreSettings s;
  s.servers = servers;
  return s;
}
}  // namespace

PlayerGroup::PlayerGroup(std::vector<BotPlayer> bots, const ParticipantId &me, const ServerChoice &servers)
    : bots_(std::move(bots)), me_(me), core_(core_settings(servers), me), begun_(bots_.size(), false) {}

void PlayerGroup::tick(ClientPort &port, double mono, double real,
                       const std::function<void(const SegmentOut &, double)> &on_segment) {
  core_.on_segment([&](const SegmentOut &s) {
    if (on_segment) on_segment(s, real);
  });
  core_.pump(port, mono, real);
  core_.events().clear();  // (the bots play from the views; the events are the watcher's)
  samples_.clear();
  std::string why;
  for (size_t i = 0; i < bots_.size(); ++i) {
    BotPlayer &b = bots_[i];
    if (!starts_.empty() && mono < starts_[i]) continue;
    if (!begun_[i]) {
      core_.join(b.match(), b.wanted(), port, mono, &why);
      begun_[i] = true;
    }
    b.tick(core_.view(b.match()), core_, mono, &samples_);
  }
  for (const auto &s : samples_) {
    if (port.write(s)) samples_written_++;
    else sample_failures_++;
  }
}

void PlayerGroup::start_at(std::vector<double> starts) {
  if (starts.size() == bots_.size()) starts_ = std::move(starts);
}

int PlayerGroup::leave(ClientPort &port) {
  int n = 0;
  std::string why;
  for (auto &b : bots_) {
    if (!b.joined()) continue;
    n += core_.leave(b.match(), b.slot(), port, &why) == BALL_OK;
  }
  return n;
}

bool PlayerGroup::all_joined() const {
  for (const auto &b : bots_)
    if (!b.joined()) return false;
  return true;
}

uint64_t PlayerGroup::write_failures() const {
  uint64_t n = sample_failures_;
  std::set<uint32_t> matches;
  for (const auto &b : bots_) matches.insert(b.match());
  for (uint32_t m : matches)
    if (const OwnCounters *own = core_.own(m)) n += own->write_failures;
  return n;
}

uint64_t PlayerGroup::refused() const {
  uint64_t n = 0;
  std::set<uint32_t> matches;
  for (const auto &b : bots_) matches.insert(b.match());
  for (uint32_t m : matches)
    if (const MatchView *v = core_.view(m)) n += v->counters().refused;
  return n;
}

uint64_t PlayerGroup::segments() const {
  uint64_t n = 0;
  std::set<uint32_t> matches;
  for (const auto &b : bots_) matches.insert(b.match());
  for (uint32_t m : matches)
    if (const MatchView *v = core_.view(m)) n += v->counters().segments;
  return n;
}

BotReport PlayerGroup::report(size_t i) const {
  const BotPlayer &b = bots_[i];
  BotReport r;
  r.match = b.match();
  r.slot = b.slot();
  r.samples = b.counters().taken;
  r.lost = b.counters().lost;
  r.written = b.counters().delivered;
  r.write_failures = write_failures();
  const MatchView *v = core_.view(b.match());
  r.segments = v ? v->counters().segments : 0;
  r.plans = b.brain_counters().plans;
  r.late = b.brain_counters().late;
  r.missed_on_purpose = b.brain_counters().missed_on_purpose;
  r.refused = v ? v->counters().refused : 0;
  r.participant = hex(me_);
  return r;
}

}  // namespace ballsrv
