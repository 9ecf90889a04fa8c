// The segment in effect as a client of the match has it, for the tests'
// bots: the client library's own view of a match (MatchView) fed with the
// segments the match writes, and the one in effect handed on once each time
// it changes (EffectFeed).
#pragma once

#include <vector>

#include "match_view.h"

namespace test {

using namespace ballsrv;

struct ClientFeed {
  explicit ClientFeed(uint32_t match) : view(match, ServerChoice{}, ParticipantId{}) {}
  void add(const SegmentOut &s) {
    view.on_segment(s, 0.0, &notes);
    notes.clear();
  }
  const SegmentOut *due(double sim) { return feed.due(view, sim); }
  MatchView view;
  EffectFeed feed;
  std::vector<ViewEvent> notes;
};

}  // namespace test
