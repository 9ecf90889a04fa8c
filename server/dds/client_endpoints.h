// A client's port over DDS (client/port.h): the readers and writers a bot,
// the load generator or a watcher needs on a Domain.
#pragma once

#include <memory>
#include <string>

#include "domain.h"
#include "load.h"
#include "port.h"

namespace ballsrv {
namespace dds {

struct ClientNeeds {
  int players = 0;            // slots it writes samples for (0: no writers)
  int controls = 1;           // matches it writes control messages for
  int matches = kClientRoom;  // matches its readers make room for
  bool events = false;    // reads ball/events
  bool status = false;    // reads ball/server_status
  std::string partition;  // its writers' DDS partition: under DDS Security its match's (match_partition)
};

// The size of one sample of every topic (load.h).
WireSizes wire_sizes();

class ClientEndpoints : public ClientPort {
 public:
  // nullptr with err when an endpoint cannot be made
  static std::unique_ptr<ClientEndpoints> open(Domain &domain, const ClientNeeds &needs, std::string *err);

  bool take(MatchInfoOut *info) override { return infos_.take(info, nullptr); }
  bool take(SegmentOut *segment) override { return segments_.take(segment, nullptr); }
  bool take(StateOut *state) override { return states_.take(state, nullptr); }
  bool take(EventOut *event) override { return events_.take(event, nullptr); }
  bool take(StatusOut *status) override { return status_.take(status, nullptr); }
  bool write(const RacketSampleIn &sample) override { return samples_.write(sample); }
  bool write(const ControlIn &control) override { return controls_.write(control); }
  bool hears_server() const override {
    return segments_.matched() > 0 && infos_.matched() > 0 && (!events_.valid() || events_.matched() > 0);
  }

 private:
  ClientEndpoints() = default;
  Writer<RacketSampleIn> samples_;
  Writer<ControlIn> controls_;
  Reader<SegmentOut> segments_;
  Reader<MatchInfoOut> infos_;
  Reader<StateOut> states_;
  Reader<EventOut> events_;
  Reader<StatusOut> status_;
};

}  // namespace dds
}  // namespace ballsrv
