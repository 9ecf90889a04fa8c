#include "types.h"

namespace ballsrv {

const char *drop_name(SampleResult r) {
  switch (r) {
    case SampleResult::unknown_match: return "unknown_match";
    case SampleResult::bad_slot: return "bad_slot";
    case SampleResult::not_joined: return "not_joined";
    case SampleResult::not_owner: return "not_owner";
    case SampleResult::nonfinite: return "nonfinite";
    case SampleResult::zero_normal: return "zero_normal";
    case SampleResult::out_of_range: return "out_of_range";
    case SampleResult::duplicate: return "duplicate";
    case SampleResult::out_of_order: return "out_of_order";
    case SampleResult::stale: return "stale";
    case SampleResult::rejected: return "rejected";
    case SampleResult::lost: return "lost";
    case SampleResult::drop_count: break;
    case SampleResult::accepted: return "accepted";
    case SampleResult::idle: return "idle";
  }
  return "unknown";
}

const char *state_name(MatchState s) {
  switch (s) {
    case MatchState::waiting: return "waiting";
    case MatchState::playing: return "playing";
    case MatchState::paused: return "paused";
  }
  return "unknown";
}

const char *cause_name(Cause c) {
  switch (c) {
    case Cause::serve: return "serve";
    case Cause::floor: return "floor";
    case Cause::net: return "net";
    case Cause::wall: return "wall";
    case Cause::racket: return "racket";
  }
  return "unknown";
}

const char *event_name(EventKind k) {
  switch (k) {
    case EventKind::floor: return "floor";
    case EventKind::net: return "net";
    case EventKind::wall: return "wall";
    case EventKind::racket: return "racket";
    case EventKind::sound: return "sound";
    case EventKind::serve: return "serve";
    case EventKind::point: return "point";
    case EventKind::pause: return "pause";
    case EventKind::resume: return "resume";
    case EventKind::join: return "join";
    case EventKind::leave: return "leave";
    case EventKind::level: return "level";
    case EventKind::time_base: return "time_base";
    case EventKind::refused: return "refused";
  }
  return "unknown";
}

const char *reason_name(Reason r) {
  switch (r) {
    case Reason::none: return "none";
    case Reason::point_double_bounce: return "double_bounce";
    case Reason::point_out: return "out";
    case Reason::point_net: return "net";
    case Reason::point_own_side: return "own_side";
    case Reason::point_not_returned: return "not_returned";
    case Reason::point_let: return "let";
    case Reason::pause_vanished: return "vanished";
    case Reason::pause_left: return "left";
    case Reason::pause_requested: return "requested";
    case Reason::refused_slot_held: return "slot_held";
    case Reason::refused_not_player: return "not_player";
    case Reason::refused_bad_value: return "bad_value";
    case Reason::refused_no_room: return "no_room";
    case Reason::refused_state: return "state";
  }
  return "unknown";
}

const char *control_name(ControlKind k) {
  switch (k) {
    case ControlKind::create: return "create";
    case ControlKind::join: return "join";
    case ControlKind::leave: return "leave";
    case ControlKind::serve: return "serve";
    case ControlKind::level: return "level";
    case ControlKind::pause: return "pause";
    case ControlKind::resume: return "resume";
    case ControlKind::time_base: return "time_base";
  }
  return "unknown";
}

}  // namespace ballsrv
