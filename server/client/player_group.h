// The bots of one process, free of DDS: ball-bot runs one, ball-load every
// slot of many matches. One client core (the client library's: client_core.h)
// holds every match the bots play, joins their slots and takes what the
// server says; each tick the bots play from their matches' views and the
// group writes their racket samples, counting refused writes.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "client_core.h"
#include "player.h"
#include "records.h"

namespace ballsrv {

class PlayerGroup {
 public:
  // bots: stable in place from here on; `me` the participant of the port
  // (a slot is the bots' when the server says it is its), `servers` whose
  // samples the group takes
  PlayerGroup(std::vector<BotPlayer> bots, const ParticipantId &me, const ServerChoice &servers);
  PlayerGroup(const PlayerGroup &) = delete;
  PlayerGroup &operator=(const PlayerGroup &) = delete;

  // One tick at local time (monotonic `mono`, realtime `real`); every
  // segment of the group's matches is shown to on_segment too (a meter's,
  // with `real`: its reception's time when DDS did not say it).
  void tick(ClientPort &port, double mono, double real,
            const std::function<void(const SegmentOut &, double)> &on_segment = {});
  // Each joined bot's LEAVE, written (a clean exit); how many.
  int leave(ClientPort &port);
  // Bot i begins (its JOIN, its first tick) at monotonic starts[i], not
  // before; the default: at the first tick. Sizes other than the bots' are ignored.
  void start_at(std::vector<double> starts);

  std::vector<BotPlayer> &bots() { return bots_; }
  const std::vector<BotPlayer> &bots() const { return bots_; }
  bool all_joined() const;
  uint64_t samples_written() const { return samples_written_; }  // racket samples written, all ticks
  uint64_t write_failures() const;                                 // writes refused, samples and controls
  uint64_t refused() const;    // server samples the core did not take, over the bots' matches
  uint64_t segments() const;   // segments the core took, over the bots' matches
  const ClientCore &core() const { return core_; }
  // A bot's counters as its --stats-json file has them.
  BotReport report(size_t bot) const;

 private:
  std::vector<BotPlayer> bots_;
  ParticipantId me_;
  ClientCore core_;
  std::vector<double> starts_;  // start_at's (empty: every bot at once)
  std::vector<bool> begun_;
  std::vector<RacketSampleIn> samples_;
  uint64_t samples_written_ = 0, sample_failures_ = 0;
};

}  // namespace ballsrv
