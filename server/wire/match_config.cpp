#include "match_config.h"

#include <cstdint>

#include "types.h"

namespace ballsrv {

namespace {

using F = Field<MatchConfig>;
using M = MatchConfig;

// the match, its clocks and its rackets' tracks
std::vector<F> match_and_clock_fields() {
  return {
      {"scene", std::monostate{}, {}, "",
       "`default` (libball's tennis court), a libball scene name (`rally_mid`), or a YAML file relative to the "
       "config file",
       "--scene", "`default`"},
      {"id", std::monostate{}, whole(0, UINT32_MAX), "", "the match's id (a match's key, not a default's)", nullptr,
       "its index"},
      {"level", &M::level, {}, "",
       "`easy`, `mid`, `advanced` (docs/game-levels.md), or `custom`: the scene's own racket fields", "--level"},
      {"players", &M::players, whole(1, kMaxPlayers), "",
       "player slots; slot i plays on side i % 2; the scene's rackets, and defaults for the slots it lacks",
       "--players"},
      {"frame_rate", &M::frame_rate, open_closed(0.0, 1000.0), "Hz",
       "frames per real s; every match's deadlines count from the server's start, so matches of one rate step "
       "together",
       "--frame-rate"},
      {"time_base", &M::time_base, closed(0.05, 20.0), "", "sim s per real s (slow motion, fast forward)",
       "--time-base"},
      {"state_rate", &M::state_rate, up_to_field(0.0, "frame_rate"), "Hz",
       "`BallState` samples per real s; 0: off (clients evaluate segments)", "--state-rate", "the frame rate"},
      {"serve_delay", &M::serve_delay, closed(0.0, 60.0), "s", "sim s between a point and the next serve",
       "--serve-delay"},
      {"max_rally_time", &M::max_rally_time, open_closed(0.0, 3600.0), "s", "sim s: a longer rally is a let",
       "--max-rally-time"},
      {"extrapolation_time", &M::extrapolation_time, closed(-1.0, 10.0), "s",
       "eq 15's cap on racket extrapolation (about a 6 Hz sample period plus 100 ms of delay); negative: the "
       "scene's",
       "--extrapolation-time,--extrapolation"},
      {"stale_time", &M::stale_time, closed(-1.0, 60.0), "s",
       "a racket silent this long does not collide; negative: the scene's", "--stale-time", "-1 (the scene's)"},
  };
}

// what it takes from its players, how it finds hits, its court and serves
std::vector<F> player_and_hit_fields() {
  return {
      {"player_timeout", &M::player_timeout, open_closed(0.0, 60.0), "s",
       "real s without a sample before a player has vanished: the racket_samples reader's liveliness lease", nullptr,
       nullptr, false},
      {"max_sample_age", &M::max_sample_age, open_closed(0.0, 60.0), "s", "older samples are dropped as stale",
       "--max-sample-age"},
      {"max_sample_lead", &M::max_sample_lead, closed(0.0, 10.0), "s",
       "capture times further ahead of the sim clock are out of range", "--max-sample-lead"},
      {"serve_v_up", &M::serve_v_up, open_closed(0.0, 30.0), "m/s", "the serve's vertical launch speed",
       "--serve-v-up"},
      {"max_racket_speed", &M::max_racket_speed, open_closed(0.0, 1000.0), "m/s",
       "a sample implying a faster racket since the slot's previous one is refused (`too_fast`)",
       "--max-racket-speed"},
      {"racket_margin", &M::racket_margin, closed(0.0, 100.0), "m",
       "a racket centre beyond its player's half (its baseline or sidelines) by more, over the net by more than "
       "1 m, or more than 1 m under the floor, is refused (`out_of_range`)",
       "--racket-margin"},
      {"hit_instant", &M::hit_instant, {}, "",
       "step the match to a racket hit's instant between frames, found from the rackets' tracks "
       "(docs/server-design.md, \"Hits at their instant\"); false: hits are found at frame ends only",
       "--hit-instant"},
      {"hit_lead", &M::hit_lead, closed(0.0, 0.02), "s",
       "real s before a racket hit's instant that the loop wakes, steps the match to the instant and writes the "
       "hit, so that it reaches clients before its `t0` (docs/server-design.md, \"Hits at their instant\"); 0: at the "
       "instant",
       "--hit-lead"},
      {"rewind_window", &M::rewind_window, closed(0.0, 2.0), "s",
       "lag compensation: how far back (sim s) a late racket sample is tested against the ball where it was, "
       "and a hit found so rewinds the match to it (docs/server-design.md, \"Lag compensation\"); 0: off",
       "--rewind-window"},
      {"rewind_own_hit", &M::rewind_own_hit, {}, "",
       "lag compensation: a late racket sample captured before its own racket's last hit may take the match back "
       "past that hit, to move it (never past another racket's hit, the serve or a decided point; "
       "docs/server-design.md, \"Lag compensation\"); false: a hit ends its racket's stroke and such samples are "
       "dropped (`before_hit`)",
       "--rewind-own-hit"},
      {"court_x_lo", &M::court_x_lo, closed(-BALL_MAX_COORD, BALL_MAX_COORD), "m",
       "where the court starts; it spans x in [court_x_lo, 2 net_x - court_x_lo], z over the net", "--court-x-lo"},
      {"seed", &M::seed, whole(0, INT64_MAX), "", "the serves' placement", "--seed", "1 (+ index with `--matches`)"},
      {"scene_name", &M::scene_name, whole(1, kNameLen - 1), "", "what MatchInfo calls the scene", nullptr, nullptr,
       false},
  };
}

}  // namespace

const std::vector<Field<MatchConfig>> &match_fields() {
  static const std::vector<F> table = [] {
    std::vector<F> t = match_and_clock_fields();
    std::vector<F> more = player_and_hit_fields();
    t.insert(t.end(), more.begin(), more.end());
    return t;
  }();
  return table;
}

const std::vector<Field<MatchConfig>> &wire_setting_fields() {
  static const std::vector<F> table = [] {
    std::vector<F> t;
#define BALL_SETTING_KEY(f) #f,
    for (const char *key : {BALL_MATCH_WIRE_SETTINGS(BALL_SETTING_KEY)})
#undef BALL_SETTING_KEY
      if (const F *f = find_field(match_fields(), key)) t.push_back(*f);
    // (MatchInfo carries frame_time, not frame_rate: an upper end that is
    // another field's value is that field's own upper end)
    for (F &f : t)
      if (const F *other = f.bounds.hi_field ? find_field(match_fields(), f.bounds.hi_field) : nullptr) {
        f.bounds.hi = other->bounds.hi;
        f.bounds.hi_open = other->bounds.hi_open;
        f.bounds.hi_field = nullptr;
      }
    return t;
  }();
  return table;
}

bool check_match_config(const MatchConfig &c, std::string *err) { return check_fields(match_fields(), c, err); }

bool check_wire_settings(const MatchConfig &c, std::string *err) { return check_fields(wire_setting_fields(), c, err); }

void follow_frame_rate(MatchConfig *c) {
  if (c->state_rate > c->frame_rate) c->state_rate = c->frame_rate;
}

}  // namespace ballsrv
