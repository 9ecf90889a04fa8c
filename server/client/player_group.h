// The bots of one process, free of DDS: ball-bot runs one, ball-load every
// slot of many matches. Each tick takes what the server said (match info,
// ball states, segments) to the bots of its match, ticks them and writes
// their racket samples and control messages, counting refused writes.
#pragma once

#include <functional>
#include <map>
#include <string>
#include <vector>

#include "player.h"
#include "port.h"
#include "records.h"

namespace ballsrv {

class PlayerGroup {
 public:
  // bots: stable in place from here on (the group routes by pointer)
  explicit PlayerGroup(std::vector<BotPlayer> bots);
  PlayerGroup(const PlayerGroup &) = delete;
  PlayerGroup &operator=(const PlayerGroup &) = delete;

  // One tick at local time (monotonic `mono`, realtime `real`); every
  // segment of the group's matches is shown to on_segment too (a meter's,
  // with its reception time). false (with error()) when a bot cannot
  // build its match's model from its scene.
  bool tick(ClientPort &port, double mono, double real,
            const std::function<void(const SegmentOut &, double)> &on_segment = {});
  // Each joined bot's LEAVE, written (a clean exit); how many.
  int leave(ClientPort &port);
  // Bot i begins (its first tick, its JOIN) at monotonic starts[i], not
  // before; the default: at the first tick. Sizes other than the bots' are ignored.
  void start_at(std::vector<double> starts);

  std::vector<BotPlayer> &bots() { return bots_; }
  const std::vector<BotPlayer> &bots() const { return bots_; }
  bool all_joined() const;
  uint64_t samples_written() const { return samples_written_; }  // racket samples written, all ticks
  uint64_t write_failures() const { return write_failures_; }    // writes refused, samples and controls
  const std::string &error() const { return error_; }
  // A bot's counters as its --stats-json file has them.
  BotReport report(size_t bot, const ParticipantId &me) const;

 private:
  template <class T>
  void write(ClientPort &port, const std::vector<T> &items, uint64_t *written);

  std::vector<BotPlayer> bots_;
  std::vector<double> starts_;  // start_at's (empty: every bot at once)
  std::map<uint32_t, std::vector<BotPlayer *>> by_match_;
  std::vector<RacketSampleIn> samples_;
  std::vector<ControlIn> controls_;
  uint64_t samples_written_ = 0, controls_written_ = 0, write_failures_ = 0;
  std::string error_;
};

}  // namespace ballsrv
