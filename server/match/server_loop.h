// The server's loop, free of DDS (docs/server.md, "The status line", "Frame
// clock"). One loop on one thread owns every match of a Host; at each
// wake-up it runs its phases in order:
//
//   take notes     what the DDS threads noticed: writers lost, deadlines
//                  missed, samples DDS rejected or lost (counted as drops)
//   take samples   every racket sample that came in, to its match
//   take controls  every control message, to its match; a CREATE schedules
//                  the new match
//   run due frames each match whose deadline has come steps one frame and
//                  publishes what it produced; a match more than
//                  max_behind frames late (the machine stalled) skips to
//                  the present and counts the skipped frames
//   status         once a status interval: the status written, conflicts
//                  (another server announcing one of our matches) reported
//
// Deadlines are absolute (FrameClock), so errors do not add up. The network
// is reached through a ServerPort (server/dds implements it over DDS), the
// time through a Clock: the tests drive the loop with fakes of both.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "frame_clock.h"
#include "host.h"
#include "records.h"

namespace ballsrv {

// What the network side noticed about the racket samples' writers.
struct PortNote {
  enum Kind { writer_lost, deadline_missed, rejected, lost } kind;
  ParticipantId who{};  // writer_lost: the participant; zeros otherwise
  uint64_t count = 1;   // samples or deadlines
};

class ServerPort {
 public:
  virtual ~ServerPort() = default;
  virtual void take_notes(std::vector<PortNote> *out) = 0;  // appends what was noticed since the last call
  virtual bool take_sample(RacketSampleIn *sample) = 0;     // false: none left; from and source_time filled in
  virtual bool take_control(ControlIn *control) = 0;        // false: none left; from filled in
  // MatchInfo written by other servers (our own is skipped); false: none left
  virtual bool take_other_info(MatchInfoOut *info, ParticipantId *from) = 0;
  // false: the write was refused (counted as a write failure)
  [[nodiscard]] virtual bool write(const SegmentOut &s) = 0;
  [[nodiscard]] virtual bool write(const EventOut &e) = 0;
  [[nodiscard]] virtual bool write(const StateOut &s) = 0;
  [[nodiscard]] virtual bool write(const MatchInfoOut &i) = 0;
  [[nodiscard]] virtual bool write(const StatusOut &s) = 0;
};

struct LoopSettings {
  uint32_t server_id = 1;        // in every sample written
  double status_interval = 1.0;  // real s between status writes
  double info_interval = 1.0;    // real s between a match's periodic MatchInfo
  double max_behind = 5.0;       // frames: a match further behind its deadline skips to the present
};

// The loop's counters: the status line, ServerStatus, the stats file.
struct LoopStats {
  StatusOut totals;             // the counters ServerStatus carries: samples, drops, controls, writes, frames, overruns
  uint64_t samples_idle = 0;    // well formed, but their match was not playing
  uint64_t infos_out = 0, statuses_out = 0;  // MatchInfo and ServerStatus written
  uint64_t write_failures = 0;  // writes the port refused (every kind, the status too)
  uint64_t skipped = 0;         // frames skipped after a stall
  uint64_t deadline_missed = 0, writers_lost = 0;
  uint64_t conflicts = 0;       // MatchInfo of one of our matches from another server
  Percentiles frame_time;       // real s of work per wake-up, this status period
  Percentiles late;             // real s a frame started after its deadline, this status period
  Percentiles late_p99;         // each period's p99 of that, over the run
  double late_max = 0.0;        // real s, over the run
  Percentiles latency;          // real s from a hit's newest racket sample's write to its segment's, this period
  Percentiles latency_all;      // the same over the run
  double period_latency_p50 = 0.0, period_latency_p99 = 0.0;  // real s, of the last status period closed
};

class ServerLoop {
 public:
  ServerLoop(Host &host, ServerPort &port, Clock &clock, const LoopSettings &settings);

  // Listens up to `seconds` for another server announcing one of our
  // matches: true with its MatchInfo (the domain is busy).
  bool find_owner(double seconds, const std::function<bool()> &stop, MatchInfoOut *other);

  // Schedules every match (their frames count from now: matches of one
  // rate step together) and publishes their MatchInfo.
  void start();

  // Runs the phases now; true when a status period ended (status() has
  // the new status, already written). step() sleeps to next_wake() first.
  bool wake();
  bool step();
  // Steps until stop() or `duration` real s (0: no limit); calls on_status
  // with each status written, on_conflict with each MatchInfo of another
  // server for one of our matches.
  void run(double duration, const std::function<bool()> &stop,
           const std::function<void(const StatusOut &)> &on_status,
           const std::function<void(const MatchInfoOut &, const ParticipantId &)> &on_conflict);
  // The last status, written once more at the end.
  StatusOut finish();

  // The phases, in the order step runs them (t0: mono s of the wake-up,
  // now: server s).
  void take_notes();
  void take_samples(double now);
  void take_controls(double now);
  void run_due_frames(double t0, double now);

  double next_wake() const;  // mono s
  StatusOut status_now() const;
  const StatusOut &status() const { return status_; }
  const LoopStats &stats() const { return stats_; }
  ServerReport report() const;
  double uptime() const;  // real s since start

 private:
  struct Scheduled {
    Match *match;
    FrameClock clock;
    uint64_t k = 0;                // next frame index
    double last_frame_real = 0.0;  // server s of the newest frame's deadline
    double next_info = 0.0;        // mono s of the next periodic MatchInfo
    uint32_t revision = 0;
  };
  Scheduled schedule(Match *m);
  void publish(const MatchOutput &out, Scheduled &s, double now);
  void publish_info(Scheduled &s);
  void check_conflicts(const std::function<void(const MatchInfoOut &, const ParticipantId &)> &on_conflict);
  void close_period();  // the status written, the period's latency kept for the line
  template <class T>
  void write(const T &sample, uint64_t *written);

  Host &host_;
  ServerPort &port_;
  Clock &clock_;
  LoopSettings settings_;
  FrameClock origin_{1.0, 0.0, 0.0};
  std::vector<Scheduled> sched_;
  double start_ = 0.0, next_status_ = 0.0;
  LoopStats stats_;
  StatusOut status_;
  MatchOutput out_;
  std::vector<PortNote> notes_;
  std::function<void(const MatchInfoOut &, const ParticipantId &)> on_conflict_;
};

// The status line: "ball-server 1: 12 s, matches 1 (1 playing), samples in ...".
std::string status_line(const StatusOut &status, const LoopStats &stats);

}  // namespace ballsrv
