#include "racket_tracks.h"

namespace ballsrv {

bool RacketTracks::take(const RacketSampleIn &s, const Watcher &w) {
  WatchedView v;
  MatchRackets &m = matches_[s.match_id];
  // the tracks as the newest MatchInfo has the match: its model (the wire's, else a scene's), server and holders
  bool ok = w.view(s.match_id, &v) && m.follow(*v.info, v.model ? *v.model : court_(*v.info)) && m.has(s.player) &&
            v.info->slots[s.player].held && m.holder(s.player) == s.from && !s.rejected;
  ball_racket_sample rs{s.capture_time, s.center, s.normal};
  if (!ok || m.push(s.player, rs) != BALL_OK) {
    dropped_++;
    return false;
  }
  taken_++;
  return true;
}

bool RacketTracks::pose(uint32_t match, int slot, double t, ball_racket_pose *out) const {
  auto it = matches_.find(match);
  return it != matches_.end() && it->second.pose(slot, t, out) == BALL_OK;
}

}  // namespace ballsrv
