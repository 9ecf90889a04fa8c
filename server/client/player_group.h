// The bots of one process, free of DDS: ball-bot runs one, ball-load every
// slot of many matches. One client of the client library (ball/net.h: the
// very calls a game makes) holds every match the bots play and joins their
// slots; each tick the group polls it, tells each bot the slots its client
// holds, and the bots play and push their racket poses through it.
#pragma once

#include <functional>
#include <map>
#include <string>
#include <vector>

#include "ball/net.h"
#include "player.h"
#include "records.h"

namespace ballsrv {

class PlayerGroup {
 public:
  // bots: stable in place from here on; `client`: open, the group's to
  // use (not to close), its clock the one tick() is given
  PlayerGroup(std::vector<BotPlayer> bots, ball_net_client *client);
  PlayerGroup(const PlayerGroup &) = delete;
  PlayerGroup &operator=(const PlayerGroup &) = delete;

  // One tick at `mono` of the client's clock: each bot begun (its JOIN) at
  // its start, the client polled (its events shown to on_event, if
  // given), then the bots played.
  void tick(double mono, const std::function<void(const ball_net_event &)> &on_event = {});
  // Each joined bot's LEAVE, written (a clean exit); how many.
  int leave();
  // Bot i begins (its JOIN, its first tick) at starts[i], not before; the
  // default: at the first tick. Sizes other than the bots' are ignored.
  void start_at(std::vector<double> starts);

  std::vector<BotPlayer> &bots() { return bots_; }
  const std::vector<BotPlayer> &bots() const { return bots_; }
  bool all_joined() const;
  // the client's words on the first JOIN it refused (e.g. a partition the
  // identity is not granted under DDS Security); empty while none was
  const std::string &error() const { return error_; }
  // the client's counts (ball_net_status) over the bots' matches
  uint64_t samples_written() const { return sum(&ball_net_status::samples); }
  uint64_t write_failures() const { return sum(&ball_net_status::write_failures); }
  uint64_t refused() const { return sum(&ball_net_status::refused); }
  uint64_t segments() const { return sum(&ball_net_status::segments); }
  uint64_t bytes_out() const { return sum(&ball_net_status::bytes_out); }
  // A bot's counters as its --stats-json file has them.
  BotReport report(size_t bot) const;

 private:
  uint64_t sum(uint64_t ball_net_status::*field) const;
  std::vector<BotPlayer> bots_;
  ball_net_client *client_;
  std::vector<double> starts_;  // start_at's (empty: every bot at once)
  std::vector<bool> begun_;
  std::map<uint32_t, unsigned> held_;  // by match, the slots the client holds (a bit each)
  std::vector<ball_net_event> events_;
  std::string error_;
};

}  // namespace ballsrv
