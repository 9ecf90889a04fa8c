#include "watch_feed.h"

#include <string>

namespace ballsrv {

void WatchFeed::line(const char *text, size_t length) {
  json j = json::parse(text, text + length, nullptr, false);
  if (!j.is_object()) {
    unreadable_++;
    return;
  }
  const std::string type = record_type(j);
  const double recv = j.value("recv", 0.0);
  try {
    if (type == "ready") {
      w_.on_ready(recv);
    } else if (type == "match_info") {
      w_.on_info(j.get<MatchInfoOut>(), recv);
    } else if (type == "segment") {
      w_.on_segment(j.get<SegmentOut>(), recv);
    } else if (type == "event") {
      w_.on_event(j.get<EventOut>(), recv);
    } else if (type == "state") {
      w_.on_state(j.get<StateOut>(), recv);
    } else if (type == "server_status") {
      w_.on_status(j.get<StatusOut>());
    } else if (type == "match_model") {
      models.insert(j.at("match").get<uint32_t>());
    } else if (type == "racket_sample") {
      RacketSampleIn s = j.get<RacketSampleIn>();
      if (rackets_ && rackets_->take(s, w_)) drawn.push_back(s);
    }
  } catch (const std::exception &) {
    unreadable_++;
    auto m = j.find("match");
    if (m != j.end() && m->is_number_unsigned()) w_.not_taken(m->get<uint32_t>());
  }
}

}  // namespace ballsrv
