// ball-watch's feed (docs/server.md, "Watchers"), free of DDS: the lines of
// the client library's tap (ball_net_set_tap, docs/client.md "A tap"), each
// read back into its sample and handed to the watcher as it came; the
// players' racket samples go to the racket tracks, and those the tracks
// took come back for the page. A line that does not read as its type (a
// stranger's numbers no name fits) counts as not taken of its match.
#pragma once

#include <cstddef>
#include <cstdint>
#include <set>
#include <vector>

#include "racket_tracks.h"
#include "watcher.h"

namespace ballsrv {

class WatchFeed {
 public:
  // rackets may be null: racket samples are then passed over
  WatchFeed(Watcher &w, RacketTracks *rackets) : w_(w), rackets_(rackets) {}

  // One line of the tap.
  void line(const char *text, size_t length);
  // ball_net_tap's shape, `user` a WatchFeed
  static void tap(void *user, const char *text, size_t length) { static_cast<WatchFeed *>(user)->line(text, length); }

  std::vector<RacketSampleIn> drawn;  // the racket samples the tracks took (the caller clears it)
  std::set<uint32_t> models;          // matches a model line came for (the caller fetches the model and clears it)
  uint64_t unreadable() const { return unreadable_; }

 private:
  Watcher &w_;
  RacketTracks *rackets_;
  uint64_t unreadable_ = 0;
};

}  // namespace ballsrv
