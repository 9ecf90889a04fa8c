#include "racket_tracks.h"

namespace ballsrv {

bool RacketTracks::take(const RacketSampleIn &s, const Watcher &w) {
  WatchedView v;
  if (!w.view(s.match_id, &v) || s.player < 0 || s.player >= std::min(v.info->players, kMaxPlayers) ||
      !v.info->slots[s.player].held || v.info->slots[s.player].owner != s.from || s.rejected) {
    dropped_++;
    return false;
  }
  Match &m = matches_[s.match_id];
  if (!m.sim || m.server != v.info->server_id) {  // a new match or server: its tracks start anew
    ball_model model = v.model ? *v.model : court_(*v.info);  // the wire's model, else a scene's
    auto sim = std::make_unique<ball_sim>();
    if (ball_sim_init(sim.get(), &model) != BALL_OK) {
      dropped_++;
      return false;
    }
    m.sim = std::move(sim);
    m.server = v.info->server_id;
    m.owners = {};
  }
  if (m.owners[s.player] != s.from) {  // a new holder, on its own clock
    ball_racket_clear(m.sim.get(), s.player);
    m.owners[s.player] = s.from;
  }
  ball_racket_sample rs{s.capture_time, s.center, s.normal};
  if (s.player >= ball_sim_model(m.sim.get())->n_rackets || ball_racket_push(m.sim.get(), s.player, &rs) != BALL_OK) {
    dropped_++;
    return false;
  }
  taken_++;
  return true;
}

bool RacketTracks::pose(uint32_t match, int slot, double t, ball_racket_pose *out) const {
  auto it = matches_.find(match);
  if (it == matches_.end() || !it->second.sim || slot < 0 || slot >= ball_sim_model(it->second.sim.get())->n_rackets)
    return false;
  return ball_racket_estimate(it->second.sim.get(), slot, t, out) == BALL_OK;
}

}  // namespace ballsrv
