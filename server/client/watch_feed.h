// One turn of a watcher's loop over its port (ball-watch; docs/server.md,
// "Watchers"), free of DDS: everything the port has is taken, in order
// (ready, MatchInfo, segments, events, states, server status, then the
// desync check), and the players' racket samples go to the racket tracks;
// the samples the tracks took come back for the page.
#pragma once

#include <vector>

#include "port.h"
#include "racket_tracks.h"
#include "watcher.h"

namespace ballsrv {

// `real`: the local realtime clock now, s. rackets may be null (the racket
// samples are then left to the port). *drawn gets the racket samples taken.
void take_all(ClientPort &port, Watcher &w, RacketTracks *rackets, double real, std::vector<RacketSampleIn> *drawn);

}  // namespace ballsrv
