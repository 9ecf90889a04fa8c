// A match's settings, with defaults like ball_model_default, and their
// field table (fields.h): JSON key, member, range, unit and meaning of each,
// stated here only (docs/server-reference.md, "Configuration keys", is printed from it).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "ball/ball.h"
#include "fields.h"

namespace ballsrv {

struct MatchConfig {
  uint32_t id = 0;
  std::string scene_name = "tennis";  // what MatchInfo calls it
  int players = 2;                    // slots
  ball_level level = BALL_LEVEL_EASY; // custom: the scene's own racket fields
  double frame_rate = 60.0;           // frames per real s
  double time_base = 1.0;             // sim s per real s
  double state_rate = 60.0;           // ball states per real s; 0: off
  double serve_delay = 1.5;           // sim s between a point and the next serve
  double max_rally_time = 60.0;       // sim s: a longer rally is a let
  double extrapolation_time = 0.25;   // s, eq 15's cap; < 0: the scene's
  double stale_time = -1.0;           // s; < 0: the scene's
  double player_timeout = 1.0;        // real s without a sample before a player has vanished
  double max_sample_age = 2.0;        // sim s: older samples are stale
  double max_sample_lead = 0.5;       // sim s: capture times further ahead are out of range
  double serve_v_up = 4.0;            // m/s: vertical launch speed of a serve
  double max_racket_speed = 50.0;     // m/s: a racket implied faster between two samples is refused
  double racket_margin = 8.0;         // m: how far beyond its own half (sidelines, baseline) a racket may be
  bool hit_instant = true;            // step to a racket hit's instant between frames (false: frame-locked)
  double hit_lead = 0.002;            // real s before a hit's instant that the loop steps to it and writes it
  double rewind_window = 0.25;        // sim s a late racket sample may take the match back; 0: off
  bool rewind_own_hit = false;        // a late sample may take the match back past its own racket's last hit
  double court_x_lo = 0.0;            // m: where the court starts (Court)
  uint64_t seed = 1;                  // serve placement
};

// The settings that travel in MatchInfo as they are (docs/protocol.md;
// idl/ball.idl MatchInfo), under their key's name: MatchInfoOut::settings holds them,
// and the IDL's MatchInfo, its conversions, the JSON records, the spectator
// page, Match::info and a standby's follow all take this one list. A new
// setting that travels is its member and row above, its name here and its
// IDL field.
#define BALL_MATCH_WIRE_SETTINGS(X)                                                                     \
  X(time_base) X(state_rate) X(player_timeout) X(max_sample_age) X(max_sample_lead) X(serve_delay)      \
  X(max_rally_time) X(serve_v_up) X(seed) X(max_racket_speed) X(racket_margin)

// Every setting of a match, in the order of docs/server-reference.md; `scene` and
// `id` are keys of a match in the config file that live beside its
// MatchConfig (their member is the reader's to fill).
const std::vector<Field<MatchConfig>> &match_fields();

// The rows of match_fields() of the settings that travel, in the order of
// BALL_MATCH_WIRE_SETTINGS, as a reader of MatchInfo checks them: an upper
// end that is another field's value is that field's own upper end
// (state_rate <= frame_rate's 1000 Hz: MatchInfo carries frame_time).
const std::vector<Field<MatchConfig>> &wire_setting_fields();

// Checks a config against its field table; false with
// "field: must be in RANGE" in err.
bool check_match_config(const MatchConfig &config, std::string *err);

// Checks the settings that travel against wire_setting_fields(); false
// with "field: must be in RANGE" in err.
bool check_wire_settings(const MatchConfig &config, std::string *err);

// A match's state rate follows its frame rate unless it was set: called
// when it was not, it lowers the state rate to the frame rate.
void follow_frame_rate(MatchConfig *config);

}  // namespace ballsrv
