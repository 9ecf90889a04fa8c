// Lag compensation's core (docs/server-design.md, "Lag compensation"; docs/design.md,
// "Rooms by state"): a late racket sample's hit, if any, as a function of
// the sim now, the history of the segments in effect over the rewind
// window, the slot's kept samples and the parameters. It changes nothing:
// the match applies what it finds (Match::rewind).
#pragma once

#include <array>
#include <cmath>
#include <vector>

#include "ball/ball.h"
#include "roster.h"
#include "types.h"

namespace ballsrv {

struct LagParams {
  double rewind_window = 0.0;   // sim s back at most (the match setting rewind_window)
  bool rewind_own_hit = false;  // back past the slot's own racket hit (match setting)
  double frame = 0.0;           // sim s of a frame (frame_time times the time base)
};

// A rewind steps the past with the tracks of now: a track whose samples
// all come after a frame's end would hold its racket at the first of them
// (libball: before its first sample a track is at it), where the racket
// had not been yet. Before each frame, such a track waits aside (its
// racket meets nothing) until the steps reach its first sample.
struct Aside {
  std::array<ball_racket_track, kMaxPlayers> track;  // (only the held ones are read)
  std::array<bool, kMaxPlayers> held{};
};
// Sets aside the tracks that begin after `end`, and gives back those that
// begin by then.
void aside(ball_sim *sim, Aside *a, double end);

// sim's track k from slot.kept (and `extra`, newer, if given): the track it
// would hold had no hit ended its stroke; libball's status.
ball_status unended_track(ball_sim *sim, int k, const Slot &slot, const ball_racket_sample *extra);

// The racket tests sleep after a hit (section 3.1) for sleep_frames steps:
// what is left at sim s t of a hit at t_hit, the frame ends since it
// counted as the match's frames of `frame` sim s (the hit's own frame end
// included in the sleep it began).
int sleep_left(double t_hit, double t, double frame, int sleep_frames);

// What find_late_hit found.
struct LateHit {
  enum Outcome { untested, none, ruled_out, found } outcome = untested;
  double hit = HUGE_VAL;           // sim s of the hit found
  double passed = HUGE_VAL;        // t0 of the first of its own hits the search went back past
  const SegmentOut *at = nullptr;  // the segment in effect where the search began (in the history)
  ball_sim then{};                 // the ball and the tracks at the hit
  Aside early;                     // the tracks still set aside there
};

// The late hit of slot k's racket since sim s `from` (the capture time of
// the sample before its first late one): back no further than the window,
// the serve or the last hit (with rewind_own_hit: another racket's), frame
// by frame up to sim.time, the first frame where the racket meets the ball
// before anything else does. events: room for a step's events.
LateHit find_late_hit(const ball_sim &sim, const std::vector<SegmentOut> &history, int k, const Slot &slot,
                      double from, const LagParams &p, std::vector<ball_event> *events);

}  // namespace ballsrv
