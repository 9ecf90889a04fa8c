#include "server_endpoints.h"

#include <algorithm>
#include <atomic>
#include <mutex>
#include <unordered_map>

#include "convert.h"

namespace ballsrv {
namespace dds {

// The door of the racket and control readers (domain.h): only the samples
// of the matches the server has, and their slots, become instances of the
// readers; a control for another match only if it is a CREATE of an id
// CREATEs may name (Host::create_ids). Made-up match ids then cannot fill
// the readers' instances and starve the real ones (docs/protocol.md, "What
// the server does with a racket sample"): the control reader has an
// instance for each of those ids (open). (Fast DDS 2.9 does not tell a
// filter the writer, its FilterSampleInfo is empty on a reader, and a
// live writer's instances stay in the reader until it goes: no bound by
// writer or by rate would keep a flood from filling it.) What the door
// turns away is counted here and handed on as door notes.
class MatchDoor : public Door {
 public:
  explicit MatchDoor(bool controls) : controls_(controls) {}
  bool admit(const uint8_t *body, size_t size, bool le) const override {
    // RacketSample: match_id u32 at 0, player u16 at 4; MatchControl: match_id u32 at 0, kind at 8
    if (size < 12) return true;  // (never: it read as its type, malformed() otherwise)
    uint32_t id = u32(body, le);
    std::shared_ptr<const Admitted> in = admitted();
    if (!in) return true;  // nothing said yet
    auto it = in->find(id);
    if (controls_) {
      if (it != in->end() || (u32(body + 8, le) == static_cast<uint32_t>(balldds::CONTROL_CREATE) && creates().has(id)))
        return true;
      turned_away_[0]++;
      return false;
    }
    if (it == in->end()) {
      turned_away_[0]++;
      return false;
    }
    uint16_t player = static_cast<uint16_t>(le ? body[4] | body[5] << 8 : body[4] << 8 | body[5]);
    if (player < it->second) return true;
    turned_away_[1]++;
    return false;
  }
  void malformed() const override { turned_away_[2]++; }
  void set(const std::vector<std::pair<uint32_t, int>> &matches, CreateIds creates) {
    auto in = std::make_shared<Admitted>(matches.begin(), matches.end());
    std::lock_guard<std::mutex> lock(mutex_);
    admitted_ = std::move(in);
    creates_ = creates;
  }
  // turned away since the last call: [0] unknown match (controls: all but
  // the malformed), [1] bad slot, [2] not readable as the type
  void take(uint64_t out[3]) {
    for (int i = 0; i < 3; ++i) out[i] = turned_away_[i].exchange(0);
  }

 private:
  using Admitted = std::unordered_map<uint32_t, int>;
  static uint32_t u32(const uint8_t *b, bool le) {
    return le ? uint32_t(b[0]) | uint32_t(b[1]) << 8 | uint32_t(b[2]) << 16 | uint32_t(b[3]) << 24
              : uint32_t(b[3]) | uint32_t(b[2]) << 8 | uint32_t(b[1]) << 16 | uint32_t(b[0]) << 24;
  }
  std::shared_ptr<const Admitted> admitted() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return admitted_;
  }
  CreateIds creates() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return creates_;
  }
  bool controls_;
  mutable std::mutex mutex_;
  std::shared_ptr<const Admitted> admitted_;
  CreateIds creates_;
  mutable std::atomic<uint64_t> turned_away_[3] = {{0}, {0}, {0}};
};

void ServerEndpoints::admit(const std::vector<std::pair<uint32_t, int>> &matches, CreateIds creates) {
  sample_door_->set(matches, creates);
  control_door_->set(matches, creates);
}

std::unique_ptr<ServerEndpoints> ServerEndpoints::open(Domain &d, int matches, int players, uint32_t create_ids,
                                                       const char *role, bool follows, std::string *err) {
  std::unique_ptr<ServerEndpoints> p(new ServerEndpoints(d, role));
  int match_room = matches;
  int sample_room = match_room * std::max(1, players) + 64;  // + room for junk keys
  constexpr int kInboxPerSlot = 64;  // samples a slot may have waiting between two frames, on average
  constexpr int kServerRoom = 64;    // other servers' status instances
  p->segments_ = d.writer<SegmentOut>(kSegmentTopic, kSegmentProfile, {match_room}, err, role);
  if (p->segments_.valid()) p->events_ = d.writer<EventOut>(kEventTopic, kEventProfile, {match_room}, err, role);
  if (p->events_.valid()) p->states_ = d.writer<StateOut>(kStateTopic, kStateProfile, {match_room}, err, role);
  if (p->states_.valid()) p->infos_ = d.writer<MatchInfoOut>(kInfoTopic, kInfoProfile, {match_room}, err, role);
  if (p->infos_.valid()) p->models_ = d.writer<MatchModelOut>(kModelTopic, kModelProfile, {match_room}, err, role);
  if (p->models_.valid()) p->status_ = d.writer<StatusOut>(kStatusTopic, kStatusProfile, {1}, err);
  if (!p->status_.valid()) return nullptr;
  // under DDS Security players write in their match's partition (docs/security.md)
  std::string from_players = d.secure() ? kAnyMatchPartition : "";
  p->sample_door_ = std::make_shared<MatchDoor>(false);
  p->control_door_ = std::make_shared<MatchDoor>(true);
  Sizing racket{sample_room, sample_room * kInboxPerSlot, from_players, p->sample_door_};
  racket.inbox_per_key = kInboxPerSlot;  // one writer's burst in a slot takes its own share only
  p->samples_ = d.reader<RacketSampleIn>(kRacketTopic, kRacketProfile, racket, err);
  // an instance for every match and every id a CREATE may name: made-up ids
  // cannot fill it; an inbox with a share per writer: one writer's flood
  // cannot push another's JOIN out, nor take more than its share of a turn
  constexpr int kControlsPerWriter = 8;  // controls a writer may have waiting between two turns
  const int control_room = match_room + static_cast<int>(create_ids) + 64;
  Sizing control{control_room, control_room * kControlsPerWriter, from_players, p->control_door_};
  control.inbox_per_key = kControlsPerWriter;
  p->controls_ = d.reader<ControlIn>(kControlTopic, kControlProfile, control, err);
  p->others_ = d.reader<MatchInfoOut>(kInfoTopic, kInfoProfile, {match_room + 64}, err);
  // (only a standby reads segments: every other server would take its own back)
  if (follows) p->other_segments_ = d.reader<SegmentOut>(kSegmentTopic, kSegmentProfile, {match_room + 64}, err);
  if (follows) p->other_models_ = d.reader<MatchModelOut>(kModelTopic, kModelProfile, {match_room + 64}, err);
  p->other_status_ = d.reader<StatusOut>(kStatusTopic, kStatusProfile, {kServerRoom}, err);
  if (!p->samples_.valid() || !p->controls_.valid() || !p->others_.valid() ||
      (follows && (!p->other_segments_.valid() || !p->other_models_.valid())) || !p->other_status_.valid())
    return nullptr;
  return p;
}

ServerEndpoints::View &ServerEndpoints::view(uint32_t match) {
  auto it = views_.find(match);
  if (it != views_.end()) {
    it->second.retire = {};  // (a match served again before its view went)
    return it->second;
  }
  View &v = views_[match];
  // (a writer the domain refuses stays invalid: each write to it is then refused, and counted)
  std::string err;
  Sizing own{1, 0, match_partition(match)};
  v.segments = domain_.writer<SegmentOut>(kSegmentTopic, kSegmentProfile, own, &err, role_);
  v.events = domain_.writer<EventOut>(kEventTopic, kEventProfile, own, &err, role_);
  v.states = domain_.writer<StateOut>(kStateTopic, kStateProfile, own, &err, role_);
  v.infos = domain_.writer<MatchInfoOut>(kInfoTopic, kInfoProfile, own, &err, role_);
  v.models = domain_.writer<MatchModelOut>(kModelTopic, kModelProfile, own, &err, role_);
  if (strength_) v.set_strength(strength_);
  return v;
}

void ServerEndpoints::remove_retired() {
  const auto now = std::chrono::steady_clock::now();
  for (auto it = views_.begin(); it != views_.end();) {
    View &v = it->second;
    if (v.retire == std::chrono::steady_clock::time_point{} || now < v.retire) {
      ++it;
      continue;
    }
    domain_.remove(&v.segments), domain_.remove(&v.events), domain_.remove(&v.states);
    domain_.remove(&v.infos), domain_.remove(&v.models);
    it = views_.erase(it);
  }
}

bool ServerEndpoints::assert_liveliness() {
  // the best-effort ball states assert theirs by being written (Fast DDS sends
  // no heartbeat for them); a standby's writers that never wrote harm nobody
  bool ok = segments_.assert_liveliness();
  ok = events_.assert_liveliness() && ok;
  ok = infos_.assert_liveliness() && ok;
  ok = models_.assert_liveliness() && ok;
  ok = status_.assert_liveliness() && ok;
  states_.assert_liveliness();
  // a view's writers only while a reader has them (one that matches later
  // has them asserted within a quarter of its lease)
  for (auto &kv : views_) {
    View &v = kv.second;
    if (v.segments.matched() > 0) ok = v.segments.assert_liveliness() && ok;
    if (v.events.matched() > 0) ok = v.events.assert_liveliness() && ok;
    if (v.infos.matched() > 0) ok = v.infos.assert_liveliness() && ok;
    if (v.models.matched() > 0) ok = v.models.assert_liveliness() && ok;
  }
  return ok;
}

bool ServerEndpoints::set_strength(uint32_t strength) {
  strength_ = strength;
  bool ok = segments_.set_strength(strength) && events_.set_strength(strength) && states_.set_strength(strength) &&
            infos_.set_strength(strength) && models_.set_strength(strength);
  for (auto &kv : views_) ok = kv.second.set_strength(strength) && ok;
  return ok;
}

bool ServerEndpoints::dispose_match(uint32_t match_id) {
  constexpr auto kViewKept = std::chrono::seconds(5);  // for the view's readers to take the disposal
  MatchInfoOut key;
  key.match_id = match_id;
  MatchModelOut model_key;
  model_key.match_id = match_id;
  bool ok = infos_.dispose(key);
  ok = models_.dispose(model_key) && ok;
  auto it = views_.find(match_id);
  if (it == views_.end()) return ok;
  View &v = it->second;
  ok = v.infos.dispose(key) && ok;
  ok = v.models.dispose(model_key) && ok;
  v.retire = std::chrono::steady_clock::now() + kViewKept;
  return ok;
}

void ServerEndpoints::take_notes(std::vector<PortNote> *out) {
  remove_retired();
  // another server's writers gone (liveliness lost, or unmatched with its participant)
  notes_.clear();
  others_.drain_status(&notes_);
  other_segments_.drain_status(&notes_);
  other_status_.drain_status(&notes_);
  other_models_.drain_status(&notes_);
  for (const auto &n : notes_)
    if (n.kind == StatusNote::writer_lost && n.who != domain_.id()) out->push_back({PortNote::server_lost, n.who, 1});
  // the controls DDS refused or lost (drained, never left to pile up)
  notes_.clear();
  controls_.drain_status(&notes_);
  for (const auto &n : notes_) {
    if (n.kind == StatusNote::rejected) out->push_back({PortNote::control_rejected, {}, static_cast<uint64_t>(n.count)});
    if (n.kind == StatusNote::samples_lost) out->push_back({PortNote::control_lost, {}, static_cast<uint64_t>(n.count)});
  }
  uint64_t away[3];
  control_door_->take(away);
  if (away[0] + away[2]) out->push_back({PortNote::door_control, {}, away[0] + away[2]});
  sample_door_->take(away);
  if (away[0]) out->push_back({PortNote::door_unknown_match, {}, away[0]});
  if (away[1]) out->push_back({PortNote::door_bad_slot, {}, away[1]});
  if (away[2]) out->push_back({PortNote::door_malformed, {}, away[2]});
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
  sample->rejected = meta.rejected;
  sample->permitted = !domain_.secure() || domain_.writes_in(meta.writer, match_partition(sample->match_id));
  return true;
}

bool ServerEndpoints::take_control(ControlIn *control) {
  SampleMeta meta;
  if (!controls_.take(control, &meta)) return false;
  control->from = meta.from;
  if (control->kind == ControlKind::create) control->host = domain_.host_of(meta.from);  // (its share: Host)
  control->rejected = meta.rejected;
  control->permitted = !domain_.secure() || domain_.writes_in(meta.writer, match_partition(control->match_id));
  return true;
}

namespace {
// the next sample another participant wrote (our own writers' are skipped)
template <class T>
bool take_others(Reader<T> &reader, const ParticipantId &self, T *sample, ParticipantId *from) {
  SampleMeta meta;
  while (reader.take(sample, &meta))
    if (meta.from != self) {
      *from = meta.from;
      return true;
    }
  return false;
}
}  // namespace

bool ServerEndpoints::take_other_info(MatchInfoOut *info, ParticipantId *from) {
  return take_others(others_, domain_.id(), info, from);
}
bool ServerEndpoints::take_other_segment(SegmentOut *segment, ParticipantId *from) {
  return take_others(other_segments_, domain_.id(), segment, from);
}
bool ServerEndpoints::take_other_status(StatusOut *status, ParticipantId *from) {
  return take_others(other_status_, domain_.id(), status, from);
}
bool ServerEndpoints::take_other_model(MatchModelOut *model, ParticipantId *from) {
  return other_models_.valid() && take_others(other_models_, domain_.id(), model, from);
}

}  // namespace dds
}  // namespace ballsrv
