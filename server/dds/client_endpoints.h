// A client's port over DDS (client/port.h): the readers and writers a bot,
// the load generator or a watcher needs on a Domain.
#pragma once

#include <type_traits>
#include <map>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "domain.h"
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
  // under DDS Security, server ids bound to the identity whose certificate
  // their server holds (ServerChoice::bound): their samples from any other
  // participant are refused and counted (untrusted)
  std::vector<std::pair<uint32_t, std::string>> server_certs;
  bool rackets = false;   // reads ball/racket_samples (a watcher that draws the rackets)
  bool states = true;     // reads ball/ball_state
};

// The size of one sample of every topic (load.h).
WireSizes wire_sizes();

// A reader of the players' racket samples of `matches` matches in
// `partition` (under DDS Security: a match's, or match/* for a spectator);
// invalid with err when it cannot be made.
Reader<RacketSampleIn> racket_reader(Domain &domain, int matches, const std::string &partition, std::string *err);
// One racket sample from such a reader, its writer (`from`), source time
// and rejection filled in; false: none left.
bool take_racket(Reader<RacketSampleIn> &reader, RacketSampleIn *sample);

class ClientEndpoints : public ClientPort {
 public:
  // nullptr with err when an endpoint cannot be made
  static std::unique_ptr<ClientEndpoints> open(Domain &domain, const ClientNeeds &needs, std::string *err);

  bool take(MatchInfoOut *info) override { return take_trusted(infos_, info); }
  bool take(SegmentOut *segment) override { return take_trusted(segments_, segment); }
  bool take(StateOut *state) override { return take_trusted(states_, state); }
  bool take(EventOut *event) override { return take_trusted(events_, event); }
  bool take(StatusOut *status) override { return take_trusted(status_, status); }
  bool take(MatchModelOut *model) override { return take_trusted(models_, model); }
  bool take(RacketSampleIn *sample) override;
  uint64_t untrusted() const override { return untrusted_; }
  bool write(const RacketSampleIn &sample) override { return samples_.write(sample); }
  bool write(const ControlIn &control) override { return controls_.write(control); }
  bool hears_server() const override {
    return segments_.matched() > 0 && infos_.matched() > 0 && (!events_.valid() || events_.matched() > 0);
  }

 private:
  ClientEndpoints() = default;
  // the next sample whose server id, if bound to a certificate, came from its holder
  template <class T>
  bool take_trusted(Reader<T> &r, T *out) {
    SampleMeta meta;
    while (r.take(out, &meta)) {
      auto it = bound_.find(out->server_id);
      if (it == bound_.end() || prefix_fits(meta.from, it->second)) {
        if constexpr (!std::is_same_v<T, StatusOut> && !std::is_same_v<T, MatchModelOut>) {
          out->reception.received = meta.reception_time;
          out->reception.written = meta.source_time;
        }
        return true;
      }
      untrusted_++;
    }
    return false;
  }
  std::map<uint32_t, SubjectKey> bound_;
  uint64_t untrusted_ = 0;
  Writer<RacketSampleIn> samples_;
  Writer<ControlIn> controls_;
  Reader<SegmentOut> segments_;
  Reader<MatchInfoOut> infos_;
  Reader<StateOut> states_;
  Reader<EventOut> events_;
  Reader<StatusOut> status_;
  Reader<MatchModelOut> models_;
  Reader<RacketSampleIn> rackets_;
};

}  // namespace dds
}  // namespace ballsrv
