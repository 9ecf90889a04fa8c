// The model a match is played with, built from its scene as the server
// builds it (and so with the same ball_model_hash): the server's match, and
// a tool that builds a match's model from a scene of its own.
#pragma once

#include <string>

#include "ball/ball.h"
#include "ball/scene.h"
#include "court.h"
#include "types.h"

namespace ballsrv {

// What a match changes in its scene's model.
struct ModelSetup {
  int players = 2;                  // [1, kMaxPlayers]
  ball_level level = BALL_LEVEL_CUSTOM;  // custom: the scene's own racket fields
  double extrapolation_time = -1.0; // s; < 0: the scene's
  double stale_time = -1.0;         // s; < 0: the scene's
};

// The scene's model with the match's level and network settings, and with
// rackets added for players the scene has none for: default radius, the
// partner the racket on the other side, the other side's ready spot as
// target. Checked with ball_model_check; err names the field.
bool build_match_model(const ball_scene &scene, const Court &court, const ModelSetup &setup,
                       ball_model *out, std::string *err);

// The model and court a MatchInfo's match is played with, from its scene
// (the level, players, extrapolation and stale times and the court's x_lo
// as the info states them): what a client builds to step or draw the
// match as its server does (ball_model_hash then agrees).
bool match_model_of(const ball_scene &scene, const MatchInfoOut &info, ball_model *model, Court *court,
                    std::string *err);

}  // namespace ballsrv
