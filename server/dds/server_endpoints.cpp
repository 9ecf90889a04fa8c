#include "server_endpoints.h"

namespace ballsrv {
namespace dds {

std::unique_ptr<ServerEndpoints> ServerEndpoints::open(Domain &d, int matches, int players, std::string *err) {
  std::unique_ptr<ServerEndpoints> p(new ServerEndpoints(d));
  int match_room = matches;
  int sample_room = match_room * std::max(1, players) + 64;  // + room for junk keys
  constexpr int kInboxPerSlot = 64;  // samples a slot may have waiting between two frames, on average
  p->segments_ = d.writer<SegmentOut>(kSegmentTopic, kSegmentProfile, {match_room}, err);
  if (p->segments_.valid()) p->events_ = d.writer<EventOut>(kEventTopic, kEventProfile, {match_room}, err);
  if (p->events_.valid()) p->states_ = d.writer<StateOut>(kStateTopic, kStateProfile, {match_room}, err);
  if (p->states_.valid()) p->infos_ = d.writer<MatchInfoOut>(kInfoTopic, kInfoProfile, {match_room}, err);
  if (p->infos_.valid()) p->status_ = d.writer<StatusOut>(kStatusTopic, kStatusProfile, {1}, err);
  if (!p->status_.valid()) return nullptr;
  p->samples_ = d.reader<RacketSampleIn>(kRacketTopic, kRacketProfile, {sample_room, sample_room * kInboxPerSlot}, err);
  p->controls_ = d.reader<ControlIn>(kControlTopic, kControlProfile, {match_room + 64}, err);
  p->others_ = d.reader<MatchInfoOut>(kInfoTopic, kInfoProfile, {match_room + 64}, err);
  if (!p->samples_.valid() || !p->controls_.valid() || !p->others_.valid()) return nullptr;
  return p;
}

void ServerEndpoints::take_notes(std::vector<PortNote> *out) {
  notes_.clear();
  samples_.drain_status(&notes_);
  for (const auto &n : notes_) {
    switch (n.kind) {
      case StatusNote::writer_lost: out->push_back({PortNote::writer_lost, n.who, 1}); break;
      case StatusNote::deadline_missed:
        out->push_back({PortNote::deadline_missed, {}, static_cast<uint64_t>(n.count)});
        break;
      case StatusNote::rejected: out->push_back({PortNote::rejected, {}, static_cast<uint64_t>(n.count)}); break;
      case StatusNote::samples_lost: out->push_back({PortNote::lost, {}, static_cast<uint64_t>(n.count)}); break;
      case StatusNote::writer_matched: break;
    }
  }
}

bool ServerEndpoints::take_sample(RacketSampleIn *sample) {
  SampleMeta meta;
  if (!samples_.take(sample, &meta)) return false;
  sample->from = meta.from;
  sample->source_time = meta.source_time;
  return true;
}

bool ServerEndpoints::take_control(ControlIn *control) {
  SampleMeta meta;
  if (!controls_.take(control, &meta)) return false;
  control->from = meta.from;
  return true;
}

bool ServerEndpoints::take_other_info(MatchInfoOut *info, ParticipantId *from) {
  SampleMeta meta;
  while (others_.take(info, &meta))
    if (meta.from != domain_.id()) {
      *from = meta.from;
      return true;
    }
  return false;
}

}  // namespace dds
}  // namespace ballsrv
