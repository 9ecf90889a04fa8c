#include "watch_feed.h"

namespace ballsrv {

void take_all(ClientPort &port, Watcher &w, RacketTracks *rackets, double real, std::vector<RacketSampleIn> *drawn) {
  // events are not kept for late joiners: what came before "ready" is not seen
  if (port.hears_server()) w.on_ready(real);
  MatchModelOut model;  // (before the infos: a view takes the model its info names at once)
  while (port.take(&model)) w.on_model(model);
  MatchInfoOut info;
  while (port.take(&info)) w.on_info(info, real);
  SegmentOut seg;
  while (port.take(&seg)) w.on_segment(seg, real);
  EventOut e;
  while (port.take(&e)) w.on_event(e, real);
  StateOut s;
  while (port.take(&s)) w.on_state(s, real);
  StatusOut so;
  while (port.take(&so)) w.on_status(so);
  w.check_states();
  drawn->clear();
  RacketSampleIn rs;
  while (rackets && port.take(&rs))
    if (rackets->take(rs, w)) drawn->push_back(rs);
}

}  // namespace ballsrv
