// What a client takes from and gives to the network, free of DDS: the
// client library's core (ClientCore), the bots (PlayerGroup), the load
// generator and the watcher are fed through it. server/dds implements it
// over DDS (dds::ClientEndpoints); the tests feed the same cores from a Match.
#pragma once

#include <cstdint>
#include <string>

#include "types.h"

namespace ballsrv {

// Bytes of one sample of each topic's type as written: its CDR encoding
// with the 4-byte encapsulation header (the types are fixed-size, so every
// sample of a type has the same size; dds::wire_sizes() gives them).
struct WireSizes {
  uint64_t sample = 0, control = 0, segment = 0, event = 0, state = 0, info = 0, status = 0, model = 0;
};

class ClientPort {
 public:
  virtual ~ClientPort() = default;
  // the server's samples, one at a time; false: none left (or not read by this client)
  virtual bool take(MatchInfoOut *info) = 0;
  virtual bool take(SegmentOut *segment) = 0;
  virtual bool take(StateOut *state) = 0;
  virtual bool take(EventOut *event) = 0;
  virtual bool take(StatusOut *status) = 0;
  virtual bool take(MatchModelOut *) { return false; }
  // the players' racket samples, read only (a watcher draws the rackets); `from` filled in
  virtual bool take(RacketSampleIn *) { return false; }
  // A client follows `match` from now on: a port that reads per match (the
  // players' rackets in a match's partition under DDS Security) begins to.
  // false with a sentence in *why: it cannot (the follow is refused).
  virtual bool follow(uint32_t /*match*/, std::string * /*why*/) { return true; }
  // The client follows `match` no more (a port that reads only the matches
  // followed stops reading it).
  virtual void unfollow(uint32_t /*match*/) {}
  // false: the write was refused (the caller counts it)
  [[nodiscard]] virtual bool write(const RacketSampleIn &sample) = 0;
  [[nodiscard]] virtual bool write(const ControlIn &control) = 0;
  // a server's segments, events and match info reach this client from now on
  virtual bool hears_server() const = 0;
  // some server's endpoint matched one of this client's: discovery goes on
  // (a server of many matches takes seconds to be found whole); false:
  // nothing of a server found at all, the client may start anew
  virtual bool meets_server() const { return hears_server(); }
  // the bytes of one sample of each type on this port (a client counts its traffic by them; zeros: uncounted)
  virtual WireSizes sizes() const { return {}; }
  // samples refused because they claimed a server id bound to a
  // certificate their writer does not hold (ServerChoice, trust.h)
  virtual uint64_t untrusted() const { return 0; }
};

}  // namespace ballsrv
