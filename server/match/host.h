// The matches of one server and the scenes it may start new ones from, free
// of DDS: routes samples and control messages to their match, creates
// matches on request. The server app owns one and drives it from its loop.
#pragma once

#include <functional>
#include <cstdint>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "match.h"

namespace ballsrv {

class Host {
 public:
  // `max_matches` bounds matches created on request (and sizes DDS); the
  // template gives every setting of such a match but id, scene, players and level.
  Host(size_t max_matches, bool allow_create, MatchConfig create_template);
  // Whose a CREATE is beyond its participant (docs/protocol.md, "Control
  // messages"): its process (the first 8 bytes of its GUID prefix: vendor,
  // host and process id in Fast DDS's layout, the same for every
  // participant of a process), or on a secure domain its identity (the
  // first 48 bits: PKI-DH's flag and 47 bits of its subject, certificate.h).
  enum class Origin { process, identity };
  // The CREATEs of one origin may have at most `per_origin` matches
  // standing, those of one host address (ControlIn::host, when known) at
  // most `per_host`: a stranger's CREATEs, from however many participants,
  // must not fill max_matches for good.
  void set_create_shares(Origin origin, uint32_t per_origin, uint32_t per_host) {
    origin_ = origin;
    max_creates_ = per_origin;
    max_creates_per_host_ = per_host;
  }
  // Which participant may hold which slot of which match (Match::set_slot_rule): every match's, those to come too.
  void set_slot_rule(std::function<bool(uint32_t match, int slot, const ParticipantId &who)> rule);
  bool allows_create() const { return allow_create_; }
  // The match ids a CREATE may name (the rest refused, `bad_value`): a
  // bounded key space, so that made-up CREATE ids cannot fill the control
  // reader's instances (docs/protocol.md, "Control messages").
  void set_create_ids(CreateIds ids) { create_ids_ = ids; }
  CreateIds create_ids() const { return allow_create_ ? create_ids_ : CreateIds{create_ids_.first, 0}; }
  // The participant that created match `id` (zeros: configured, or unknown).
  ParticipantId creator(uint32_t id) const;

  // A scene a CREATE may name (at most 31 bytes).
  bool add_scene(const std::string &name, const ball_scene &scene, std::string *err);
  bool add_match(const MatchConfig &config, const ball_scene &scene, std::string *err);

  // Where scenes come from that neither the catalogue nor a configured match
  // names (MatchInfo of another server may name any): false with err.
  using SceneSource = std::function<bool(const std::string &name, ball_scene *scene, std::string *err)>;
  void set_scene_source(SceneSource source) { source_ = std::move(source); }
  // A scene by the name MatchInfo gives it: the catalogue's, then the
  // configured matches', then the scene source's (kept for the next time).
  const ball_scene *scene(const std::string &name, std::string *err);

  // Another server's match, followed (Match::follow) from its MatchInfo:
  // its settings, and its model from the wire (`model`, the MatchModel the
  // info names: usable_model) or else from the scene the info names;
  // nullptr with err when there is no room, no model nor such scene, or it
  // does not fit.
  Match *follow(const MatchInfoOut &info, const ball_model *model, std::string *err);
  // A match this server neither steps nor follows any more.
  void remove(uint32_t id);

  // Routes a racket sample (followed matches take them too, to stay warm).
  SampleResult on_sample(const RacketSampleIn &sample, double now, uint64_t *lost = nullptr);  // Match::on_sample
  void on_rejected(const RacketSampleIn &sample, uint64_t *lost);                            // Match::on_rejected
  // The gaps of the streams that ended since the last call, over the
  // matches (removed ones included): Match::take_lost. end_streams() ends
  // every stream (the server stops).
  uint64_t take_lost();
  void end_streams();
  // Routes one control message; *match gets the match it concerned (nullptr
  // when none: an unknown match, or a CREATE refused; those are only counted;
  // a followed match's controls are its owner's: nullptr, Reason::none).
  Reason on_control(const ControlIn &control, double now, MatchOutput *out, Match **match);
  void on_participant_lost(const ParticipantId &who);

  Match *find(uint32_t id);
  const std::vector<std::unique_ptr<Match>> &matches() const { return matches_; }
  size_t max_matches() const { return max_matches_; }
  int max_players() const;  // over the matches and what CREATE allows

 private:
  bool insert_match(const MatchConfig &config, const ball_scene &scene, std::string *err);  // add_match's, no catalogue
  size_t max_matches_;
  bool allow_create_;
  MatchConfig template_;
  std::map<std::string, ball_scene> scenes_;
  SceneSource source_;
  std::vector<std::unique_ptr<Match>> matches_;
  std::map<uint32_t, Match *> by_id_;
  std::function<bool(uint32_t, int, const ParticipantId &)> slot_rule_;
  void apply_slot_rule(Match &m) const;  // the match's own view of slot_rule_
  struct Creator {
    ParticipantId from{};
    HostAddress host{};
  };
  std::map<uint32_t, Creator> creators_;  // the matches created on request, by whom
  Origin origin_ = Origin::process;
  uint32_t max_creates_ = UINT32_MAX, max_creates_per_host_ = UINT32_MAX;
  bool share_taken(const ControlIn &create) const;  // its origin's or its host's
  CreateIds create_ids_;
  uint64_t removed_lost_ = 0;  // the gaps of removed matches' streams, until take_lost
};

}  // namespace ballsrv
