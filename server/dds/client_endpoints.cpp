#include "client_endpoints.h"

namespace ballsrv {
namespace dds {

std::unique_ptr<ClientEndpoints> ClientEndpoints::open(Domain &d, const ClientNeeds &n, std::string *err) {
  std::unique_ptr<ClientEndpoints> p(new ClientEndpoints());
  for (const auto &b : n.server_certs) {
    SubjectKey key{};
    if (!d.subject_key(b.second, &key, err)) {
      *err = "server " + std::to_string(b.first) + "=" + b.second + ": " + *err;
      return nullptr;
    }
    p->bound_[b.first] = key;
  }
  if (n.players > 0) {
    p->samples_ = d.writer<RacketSampleIn>(kRacketTopic, kRacketProfile, {n.players, 0, n.partition}, err);
    p->controls_ = d.writer<ControlIn>(kControlTopic, kControlProfile, {n.controls, 0, n.partition}, err);
    if (!p->samples_.valid() || !p->controls_.valid()) return nullptr;
  }
  p->segments_ = d.reader<SegmentOut>(kSegmentTopic, kSegmentProfile, {n.matches}, err);
  p->infos_ = d.reader<MatchInfoOut>(kInfoTopic, kInfoProfile, {n.matches}, err);
  if (n.states) p->states_ = d.reader<StateOut>(kStateTopic, kStateProfile, {n.matches}, err);
  p->models_ = d.reader<MatchModelOut>(kModelTopic, kModelProfile, {n.matches}, err);
  if (!p->segments_.valid() || !p->infos_.valid() || (n.states && !p->states_.valid()) || !p->models_.valid())
    return nullptr;
  if (n.events) {
    p->events_ = d.reader<EventOut>(kEventTopic, kEventProfile, {n.matches}, err);
    if (!p->events_.valid()) return nullptr;
  }
  if (n.status) {
    p->status_ = d.reader<StatusOut>(kStatusTopic, kStatusProfile, {16}, err);
    if (!p->status_.valid()) return nullptr;
  }
  if (n.rackets) {
    // every player's samples, in every match's partition under DDS Security
    p->rackets_ = racket_reader(d, n.matches, d.secure() ? kAnyMatchPartition : "", err);
    if (!p->rackets_.valid()) return nullptr;
  }
  return p;
}

Reader<RacketSampleIn> racket_reader(Domain &d, int matches, const std::string &partition, std::string *err) {
  constexpr int kInboxPerSlot = 16;  // samples a slot may have waiting between two reads
  Sizing racket{matches * kMaxPlayers, 1024, partition};
  racket.inbox_per_key = kInboxPerSlot;
  return d.reader<RacketSampleIn>(kRacketTopic, kRacketProfile, racket, err);
}

bool take_racket(Reader<RacketSampleIn> &reader, RacketSampleIn *sample) {
  SampleMeta meta;
  if (!reader.valid() || !reader.take(sample, &meta)) return false;
  sample->from = meta.from;
  sample->source_time = meta.source_time;
  sample->rejected = meta.rejected;
  return true;
}

bool ClientEndpoints::take(RacketSampleIn *sample) { return take_racket(rackets_, sample); }

WireSizes wire_sizes() {
  WireSizes s;
  s.sample = serialized_size<RacketSampleIn>();
  s.control = serialized_size<ControlIn>();
  s.segment = serialized_size<SegmentOut>();
  s.event = serialized_size<EventOut>();
  s.state = serialized_size<StateOut>();
  s.info = serialized_size<MatchInfoOut>();
  s.status = serialized_size<StatusOut>();
  s.model = serialized_size<MatchModelOut>();
  return s;
}

}  // namespace dds
}  // namespace ballsrv
