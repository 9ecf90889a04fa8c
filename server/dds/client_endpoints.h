// A client's port over DDS (client/port.h): the readers and writers a bot,
// the load generator or a watcher needs on a Domain.
#pragma once

#include <chrono>
#include <set>
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

  bool take(MatchInfoOut *info) override { return take_lens(&Lens::infos, info); }
  bool take(SegmentOut *segment) override { return take_lens(&Lens::segments, segment); }
  bool take(StateOut *state) override { return take_lens(&Lens::states, state); }
  bool take(EventOut *event) override { return take_lens(&Lens::events, event); }
  bool take(StatusOut *status) override { return take_trusted(status_, status); }
  bool take(MatchModelOut *model) override {
    retire_old();
    return take_lens(&Lens::models, model);
  }
  bool take(RacketSampleIn *sample) override;
  uint64_t untrusted() const override { return untrusted_; }
  bool write(const RacketSampleIn &sample) override { return samples_.write(sample); }
  bool write(const ControlIn &control) override { return controls_.write(control); }
  bool hears_server() const override { return lens_.hears(); }
  bool meets_server() const override {
    return lens_.meets() || (old_ && old_->meets()) || (controls_.valid() && controls_.matched() > 0) ||
           (status_.valid() && status_.matched() > 0);
  }
  // Reads the five match topics in the partitions of `matches` alone from
  // now on (docs/protocol.md, "A match's own partition"; {}: the default
  // partition, every match). New readers are made; the old ones are taken
  // from too until the new ones hear a server and kOverlap s have passed
  // (or kOverlapMost), so that nothing written meanwhile is lost (what
  // comes twice, the news rules drop). false with err: a reader refused.
  bool narrow(const std::set<uint32_t> &matches, std::string *err);
  static constexpr double kOverlap = 2.0, kOverlapMost = 10.0;

 private:
  ClientEndpoints(Domain &domain, const ClientNeeds &needs) : domain_(domain), needs_(needs) {}
  // the readers of the five match topics in one set of partitions
  struct Lens {
    Reader<SegmentOut> segments;
    Reader<MatchInfoOut> infos;
    Reader<StateOut> states;
    Reader<EventOut> events;
    Reader<MatchModelOut> models;
    bool hears() const {
      return segments.matched() > 0 && infos.matched() > 0 && (!events.valid() || events.matched() > 0);
    }
    bool meets() const { return segments.matched() > 0 || infos.matched() > 0 || models.matched() > 0; }
  };
  bool open_lens(const std::string &partition, Lens *out, std::string *err);
  void remove(Lens *l);
  void retire_old();
  template <class T>
  bool take_lens(Reader<T> Lens::*which, T *out) {
    if (take_trusted(lens_.*which, out)) return true;
    return old_ && take_trusted((*old_).*which, out);
  }
  // the next sample whose server id, if bound to a certificate, came from its holder
  template <class T>
  bool take_trusted(Reader<T> &r, T *out) {
    SampleMeta meta;
    while (r.valid() && r.take(out, &meta)) {
      auto it = bound_.find(out->server_id);
      if (it == bound_.end() || prefix_fits(meta.from, it->second)) {
        if constexpr (!std::is_same_v<T, StatusOut> && !std::is_same_v<T, MatchModelOut>) {
          out->reception.received = meta.reception_time;
          out->reception.written = meta.source_time;
          out->reception.from = meta.from;
        }
        return true;
      }
      untrusted_++;
    }
    return false;
  }
  Domain &domain_;
  ClientNeeds needs_;
  std::map<uint32_t, SubjectKey> bound_;
  uint64_t untrusted_ = 0;
  Writer<RacketSampleIn> samples_;
  Writer<ControlIn> controls_;
  Lens lens_;
  std::unique_ptr<Lens> old_;  // the readers before the last narrow, while they overlap
  std::chrono::steady_clock::time_point narrowed_{};
  Reader<StatusOut> status_;
  Reader<RacketSampleIn> rackets_;
};

}  // namespace dds
}  // namespace ballsrv
