#include "client_endpoints.h"

namespace ballsrv {
namespace dds {

std::unique_ptr<ClientEndpoints> ClientEndpoints::open(Domain &d, const ClientNeeds &n, std::string *err) {
  std::unique_ptr<ClientEndpoints> p(new ClientEndpoints(d, n));
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
  if (!p->open_lens("", &p->lens_, err)) return nullptr;
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

bool ClientEndpoints::open_lens(const std::string &partition, Lens *l, std::string *err) {
  Domain &d = domain_;
  const ClientNeeds &n = needs_;
  l->segments = d.reader<SegmentOut>(kSegmentTopic, kSegmentProfile, {n.matches, 0, partition}, err);
  l->infos = d.reader<MatchInfoOut>(kInfoTopic, kInfoProfile, {n.matches, 0, partition}, err);
  if (n.states) l->states = d.reader<StateOut>(kStateTopic, kStateProfile, {n.matches, 0, partition}, err);
  l->models = d.reader<MatchModelOut>(kModelTopic, kModelProfile, {n.matches, 0, partition}, err);
  if (n.events) l->events = d.reader<EventOut>(kEventTopic, kEventProfile, {n.matches, 0, partition}, err);
  if (l->segments.valid() && l->infos.valid() && (!n.states || l->states.valid()) && l->models.valid() &&
      (!n.events || l->events.valid()))
    return true;
  remove(l);
  return false;
}

void ClientEndpoints::remove(Lens *l) {
  domain_.remove(&l->segments), domain_.remove(&l->infos), domain_.remove(&l->states);
  domain_.remove(&l->events), domain_.remove(&l->models);
}

bool ClientEndpoints::narrow(const std::set<uint32_t> &matches, std::string *err) {
  std::string partitions;  // Fast DDS's list of an endpoint's partitions: NAME;NAME...
  for (uint32_t m : matches) partitions += (partitions.empty() ? "" : ";") + match_partition(m);
  Lens fresh;
  if (!open_lens(partitions, &fresh, err)) return false;
  if (old_) remove(old_.get());  // (a narrow while the last one overlaps: the newer old readers stay)
  old_ = std::make_unique<Lens>(std::move(lens_));
  lens_ = std::move(fresh);
  narrowed_ = std::chrono::steady_clock::now();
  return true;
}

void ClientEndpoints::retire_old() {
  if (!old_) return;
  double since = std::chrono::duration<double>(std::chrono::steady_clock::now() - narrowed_).count();
  if (since < kOverlap || (!lens_.hears() && since < kOverlapMost)) return;
  remove(old_.get());
  old_.reset();
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
