// A match's controls (match.h, Match::on_control; docs/protocol.md, "Control messages").
#include "match.h"

#include <algorithm>
#include <cmath>

namespace ballsrv {

// ---- control --------------------------------------------------------------

Reason Match::refuse(const ControlIn &c, Reason why, MatchOutput *out) {
  emit(out, EventKind::refused, static_cast<int>(c.kind), sim_.time, why, static_cast<double>(c.seq));
  return why;
}

Reason Match::on_control(const ControlIn &c, double now, MatchOutput *out) {
  switch (c.kind) {
    case ControlKind::join: return on_join(c, now, out);
    case ControlKind::leave: return on_leave(c, out);
    case ControlKind::create: return refuse(c, Reason::refused_bad_value, out);  // the match exists already
    default: break;
  }
  // the rest is for the match's players
  if (!roster_.holds(c.from)) return refuse(c, Reason::refused_not_player, out);
  return on_player_control(c, out);
}

Reason Match::on_join(const ControlIn &c, double now, MatchOutput *out) {
  // the slots it may hold: on a secure domain a slot bound to an identity is that identity's alone
  unsigned allowed = 0;
  for (int k = 0; k < config_.players; ++k) allowed |= (!slot_rule_ || slot_rule_(k, c.from)) ? 1u << k : 0u;
  int slot = c.player == -1 ? roster_.free_slot(c.from, now, config_.player_timeout, allowed) : c.player;
  if (c.player == -1 && slot < 0) return refuse(c, allowed ? Reason::refused_no_room : Reason::refused_not_player, out);
  if (slot < 0 || slot >= config_.players) return refuse(c, Reason::refused_bad_value, out);
  if (!(allowed >> slot & 1u)) return refuse(c, Reason::refused_not_player, out);  // another identity's, free or not
  switch (roster_.join(slot, c.from, now, config_.player_timeout)) {
    case Roster::Join::again: return Reason::none;
    case Roster::Join::refused: return refuse(c, Reason::refused_slot_held, out);
    case Roster::Join::taken: break;
  }
  // the racket of a new holder starts without the old one's history
  ball_racket_clear(&sim_, slot);
  emit(out, EventKind::join, slot, sim_.time);
  out->info_changed = true;
  return Reason::none;
}

Reason Match::on_leave(const ControlIn &c, MatchOutput *out) {
  int slot = c.player;
  if (slot < 0 || slot >= config_.players) return refuse(c, Reason::refused_bad_value, out);
  if (!roster_.leave(slot, c.from)) return refuse(c, Reason::refused_not_player, out);
  ball_racket_clear(&sim_, slot);
  emit(out, EventKind::leave, slot, sim_.time);
  if (state_ != MatchState::waiting) {
    set_state(MatchState::waiting, out);
    left_mid_match_ = true;
    emit(out, EventKind::pause, slot, sim_.time, Reason::pause_left);
    counters_.pauses++;
  }
  out->info_changed = true;
  return Reason::none;
}

Reason Match::on_player_control(const ControlIn &c, MatchOutput *out) {
  switch (c.kind) {
    case ControlKind::serve:
      if (state_ != MatchState::playing || !rules().serve_due) return refuse(c, Reason::refused_state, out);
      rules().serve_at = sim_.time;
      return Reason::none;
    case ControlKind::level: {
      if (c.level < BALL_LEVEL_EASY || c.level > BALL_LEVEL_ADVANCED) return refuse(c, Reason::refused_bad_value, out);
      std::string err;
      set_level(static_cast<ball_level>(c.level), &err);
      if (!err.empty()) return refuse(c, Reason::refused_bad_value, out);
      emit(out, EventKind::level, -1, sim_.time, Reason::none, c.level);
      out->info_changed = true;
      return Reason::none;
    }
    case ControlKind::pause:
      if (state_ != MatchState::playing) return refuse(c, Reason::refused_state, out);
      set_state(MatchState::paused, out);
      pause_reason_ = Reason::pause_requested;
      pause_slot_ = -1;
      counters_.pauses++;
      emit(out, EventKind::pause, -1, sim_.time, Reason::pause_requested);
      return Reason::none;
    case ControlKind::resume:
      if (state_ != MatchState::paused || !roster_.all_present()) return refuse(c, Reason::refused_state, out);
      set_state(MatchState::playing, out);
      pause_reason_ = Reason::none;
      emit(out, EventKind::resume, -1, sim_.time);
      return Reason::none;
    case ControlKind::time_base: {
      if (!in_bounds(find_field(match_fields(), "time_base")->bounds, c.time_base))
        return refuse(c, Reason::refused_bad_value, out);
      // it changes every player's clock: it takes every holder asking for the same value
      if (!roster_.ask_time_base(c.from, c.time_base)) return Reason::none;  // asked: it waits for the others
      config_.time_base = c.time_base;
      emit(out, EventKind::time_base, -1, sim_.time, Reason::none, c.time_base);
      out->info_changed = true;
      return Reason::none;
    }
    default:
      return refuse(c, Reason::refused_bad_value, out);
  }
}

}  // namespace ballsrv
