// IDL <-> server types, field for field, in one place (idl/ball.idl). What
// comes off the wire is converted as it is; ranges are the match's to check,
// except enums and strings, which are checked here (ControlIn::valid).
#pragma once

#include "ball_wire.h"  // generated from idl/ball.idl
#include "types.h"

namespace ballsrv {
namespace dds {

balldds::RacketSample to_idl(const RacketSampleIn &in);
balldds::MatchControl to_idl(const ControlIn &in);
balldds::Segment to_idl(const SegmentOut &in);
balldds::Event to_idl(const EventOut &in);
balldds::BallState to_idl(const StateOut &in);
balldds::MatchInfo to_idl(const MatchInfoOut &in);
balldds::ServerStatus to_idl(const StatusOut &in);
balldds::MatchModel to_idl(const MatchModelOut &in);

void from_idl(const balldds::RacketSample &in, RacketSampleIn *out);
void from_idl(const balldds::MatchControl &in, ControlIn *out);
void from_idl(const balldds::Segment &in, SegmentOut *out);
void from_idl(const balldds::Event &in, EventOut *out);
void from_idl(const balldds::BallState &in, StateOut *out);
void from_idl(const balldds::MatchInfo &in, MatchInfoOut *out);
void from_idl(const balldds::ServerStatus &in, StatusOut *out);
void from_idl(const balldds::MatchModel &in, MatchModelOut *out);

}  // namespace dds
}  // namespace ballsrv
