// The server loop's port over DDS (server_loop.h): the server's readers and
// writers on a Domain, sized for its matches and players.
#pragma once

#include <chrono>
#include <memory>
#include <string>
#include <unordered_map>

#include "domain.h"
#include "server_loop.h"

namespace ballsrv {
namespace dds {

class ServerEndpoints : public ServerPort {
 public:
  // Endpoints sized for `matches` x `players` and `create_ids` ids a CREATE
  // may name (Fast DDS allows 10 instances per topic by default), the match
  // writers with the ownership
  // strength of `role` (kPrimaryProfile, kStandbyProfile), and readers of
  // the other servers' segments and models when it follows their matches (a standby);
  // nullptr with err when one cannot be made.
  static std::unique_ptr<ServerEndpoints> open(Domain &domain, int matches, int players, uint32_t create_ids,
                                               const char *role, bool follows, std::string *err);

  void take_notes(std::vector<PortNote> *out) override;
  bool take_sample(RacketSampleIn *sample) override;
  bool take_control(ControlIn *control) override;
  void admit(const std::vector<std::pair<uint32_t, int>> &matches, CreateIds creates) override;
  bool take_other_info(MatchInfoOut *info, ParticipantId *from) override;
  bool take_other_segment(SegmentOut *segment, ParticipantId *from) override;
  bool take_other_status(StatusOut *status, ParticipantId *from) override;
  bool take_other_model(MatchModelOut *model, ParticipantId *from) override;
  // every match's writer, and the match's own in its partition (View)
  bool write(const SegmentOut &s) override { return segments_.write(s) & view(s.match_id).segments.write(s); }
  bool write(const EventOut &e) override { return events_.write(e) & volatile_write(view(e.match_id).events, e); }
  bool write(const StateOut &s) override { return states_.write(s) & volatile_write(view(s.match_id).states, s); }
  bool write(const MatchInfoOut &i) override { return infos_.write(i) & view(i.match_id).infos.write(i); }
  bool write(const StatusOut &s) override { return status_.write(s); }
  bool write(const MatchModelOut &m) override { return models_.write(m) & view(m.match_id).models.write(m); }
  bool assert_liveliness() override;
  bool dispose_match(uint32_t match_id) override;
  bool set_strength(uint32_t strength) override;

 private:
  explicit ServerEndpoints(Domain &domain, const char *role) : domain_(domain), role_(role) {}
  // A match's own writers of the five match topics, in its DDS partition
  // match/<id> (docs/protocol.md, "A match's own partition"): a reader there
  // gets that match's samples alone. Made at the match's first write, with
  // the writers' strength; kept 5 s after the match is disposed (its
  // readers take the disposal), then deleted.
  struct View {
    Writer<SegmentOut> segments;
    Writer<EventOut> events;
    Writer<StateOut> states;
    Writer<MatchInfoOut> infos;
    Writer<MatchModelOut> models;
    std::chrono::steady_clock::time_point retire{};  // disposed: deleted from then on
    bool set_strength(uint32_t s) {
      return segments.set_strength(s) & events.set_strength(s) & states.set_strength(s) & infos.set_strength(s) &
             models.set_strength(s);
    }
  };
  View &view(uint32_t match);
  void remove_retired();
  // a volatile topic's sample reaches no later reader: unwritten without one
  template <class W, class T>
  static bool volatile_write(W &w, const T &sample) {
    return w.valid() && (w.matched() == 0 || w.write(sample));
  }
  Domain &domain_;
  const char *role_;
  uint32_t strength_ = 0;  // set_strength's (0: the role's)
  std::unordered_map<uint32_t, View> views_;
  std::shared_ptr<class MatchDoor> sample_door_, control_door_;
  Writer<SegmentOut> segments_;
  Writer<EventOut> events_;
  Writer<StateOut> states_;
  Writer<MatchInfoOut> infos_;
  Writer<StatusOut> status_;
  Writer<MatchModelOut> models_;
  Reader<RacketSampleIn> samples_;
  Reader<ControlIn> controls_;
  Reader<MatchInfoOut> others_;
  Reader<SegmentOut> other_segments_;
  Reader<StatusOut> other_status_;
  Reader<MatchModelOut> other_models_;
  std::vector<StatusNote> notes_;
};

}  // namespace dds
}  // namespace ballsrv
