// The segment in effect on a client's sim clock, handed on once each time
// it changes (docs/protocol.md, "Evaluating the ball from segments"): a
// segment written ahead of its contact when its t0 has come, never one a
// racket hit superseded. What a bot's brain plays from.
#pragma once

#include <cstddef>
#include <cstdint>

#include "types.h"

namespace ballsrv {

class SegmentFeed {
 public:
  static constexpr size_t kKept = 8;  // the one in effect and those written ahead (the topic's depth)

  // A segment the client took (trust.h decides that): kept by seq, the
  // oldest beyond kKept forgotten; one not ahead of the newest means the
  // match started anew, and the older ones go.
  void add(const SegmentOut &s) {
    if (!segments_.empty() && static_cast<int32_t>(s.seq - segments_.rbegin()->first) <= 0) segments_.clear();
    segments_[s.seq] = s;
    while (segments_.size() > kKept) segments_.erase(segments_.begin());
  }
  // The segment in effect at sim_now if it was not handed on yet; nullptr otherwise.
  const SegmentOut *due(double sim_now) {
    const SegmentOut *s = segment_in_effect(segments_, sim_now);
    if (!s || (handed_any_ && s->seq == handed_)) return nullptr;
    handed_ = s->seq;
    handed_any_ = true;
    return s;
  }

 private:
  Segments segments_;
  uint32_t handed_ = 0;
  bool handed_any_ = false;
};

}  // namespace ballsrv
