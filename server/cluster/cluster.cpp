#include "cluster.h"

#include "trust.h"

#include <algorithm>
#include <cmath>

namespace ballsrv {

// ---- what the network brought ------------------------------------------------

void Cluster::hear_status(const StatusOut &status, const ParticipantId &from) {
  if (peers_.size() >= kMaxPeers && !peers_.count(from)) {  // full: the one heard longest ago goes
    auto oldest = std::min_element(peers_.begin(), peers_.end(),
                                   [](const auto &a, const auto &b) { return a.second.heard < b.second.heard; });
    peers_.erase(oldest);
  }
  Peer &p = peers_[from];
  p.status = status;
  p.alive = true;
  p.heard = ++statuses_heard_;
}

void Cluster::hear_model(const MatchModelOut &model) {
  if (other_models_.size() >= kMaxPeers && !other_models_.count(model.match_id)) return;
  other_models_[model.match_id] = model;
}

// A MatchInfo no server could have written (numbers out of range, as a
// client judges them, or its segment and Play not fitting its sim time:
// usable_other_info) is not another server's: nobody yields to it, follows
// it, counts it an owner or is kept from starting by it; counted.
bool Cluster::server_wrote(const MatchInfoOut &info) {
  if (usable_other_info(info)) return true;
  stats_.others_refused++;
  return false;
}

Cluster::Heard Cluster::hear_info(const MatchInfoOut &info, const ParticipantId &from, bool hosted, bool ours,
                                  uint32_t our_term, double now) {
  if (!server_wrote(info)) return Heard::refused;
  // a server follows what it reads (a standby, and any after a yield), and
  // a take-over maps the owner's sim clock by the info's server_time: one
  // far from this server's clock is no server's (a forged one made the
  // catch-up endless)
  if (!(std::fabs(info.server_time - now) <= kMaxClockGap)) {
    stats_.others_refused++;
    return Heard::refused;
  }
  if (!knows(from)) {  // (a stranger's made-up matches, or a server whose status is still on its way)
    if (unknown_.size() >= kMaxPeers && !unknown_.count(info.match_id)) unknown_.clear();
    unknown_[info.match_id] = {info, from};
    stats_.unknown_writers++;
    return Heard::unknown;
  }
  // only a claimant's configured matches wait for their owners (claims_due;
  // before start they are still the host's): a bounded map, whatever ids come
  bool candidate = hosted;
  for (const auto &c : candidates_) candidate = candidate || c.id == info.match_id;
  if (settings_.claim > 0 && candidate) owners_[info.match_id] = {from, -1.0};
  if (terms_.size() < kMaxPeers || terms_.count(info.match_id))
    terms_[info.match_id] = std::max(terms_[info.match_id], info.term);
  if (!ours) return Heard::noted;
  if (info.term < our_term || (info.term == our_term && info.server_id > settings_.server_id)) {
    stats_.stale_terms++;
    return Heard::stale;
  }
  stats_.conflicts++;
  return Heard::conflict;
}

std::vector<std::pair<MatchInfoOut, ParticipantId>> Cluster::known_infos() {
  std::vector<std::pair<MatchInfoOut, ParticipantId>> out;
  for (auto it = unknown_.begin(); it != unknown_.end();) {
    if (knows(it->second.second)) {
      out.push_back(it->second);
      it = unknown_.erase(it);
    } else {
      ++it;
    }
  }
  return out;
}

uint32_t Cluster::heard_term(uint32_t match_id) const {
  auto it = terms_.find(match_id);
  return it == terms_.end() ? 0 : it->second;
}

uint32_t Cluster::stronger_than(const ParticipantId &from, uint32_t own) const {
  auto it = peers_.find(from);
  if (it == peers_.end()) return own + kTermStrength;
  return std::max(own, it->second.status.strength + 1);
}

Cluster::Follow Cluster::follow_plan(const MatchInfoOut &info, double t0, const ball_model **model) {
  *model = nullptr;
  auto f = followed_.find(info.match_id);
  if (!settings_.standby && f == followed_.end()) return Follow::none;  // (one it yielded it follows)
  if (f != followed_.end()) {
    // nothing of an older owner than the one followed while that one lives
    // (docs/protocol.md, "Terms")
    const MatchInfoOut &was = f->second.info;
    if (f->second.lost_at < 0.0 && owner_before(info.term, info.server_id, was.term, was.server_id)) {
      stats_.stale_terms++;
      return Follow::none;
    }
    return Follow::update;
  }
  if (model_waits_.size() > kMaxPeers) model_waits_.clear();  // (matches no model came for: forgotten)
  auto m = other_models_.find(info.match_id);
  if (m != other_models_.end() && usable_model(m->second, info.model_hash)) *model = &m->second.model;
  // the MatchModel may come after the MatchInfo (another topic): it is
  // waited for kModelWait before a scene of the info's name is looked for
  if (!*model) {
    auto first = model_waits_.emplace(info.match_id, t0).first;
    if (t0 - first->second < kModelWait) return Follow::none;
  }
  model_waits_.erase(info.match_id);
  return Follow::begin;
}

std::string Cluster::followed(const MatchInfoOut &info, const ParticipantId &from, Follow plan, bool ok,
                              const std::string &err, double t0) {
  if (plan == Follow::none) return "";
  std::string line;
  if (!ok) {
    bool say = stats_.follow_failures++ == 0 || stats_.follow_failures % 1000 == 0;
    if (plan == Follow::begin) {
      if (say)
        line = "cannot follow match " + std::to_string(info.match_id) + " of server " +
               std::to_string(info.server_id) + ": " + err;
      return line;
    }
  }
  Followed &f = followed_[info.match_id];
  if (f.owner != from || info.revision >= f.info.revision) f.info = info;
  if (f.owner != from) f.segments.clear();  // a new owner: its segments from now
  f.owner = from;
  f.lost_at = -1.0;
  f.heard_at = t0;
  return line;
}

void Cluster::yielded(uint32_t match_id, const MatchInfoOut &to, const ParticipantId &from, bool following,
                      double t0) {
  stats_.yields++;
  if (!following) return;
  Followed f;
  f.info = to;
  f.owner = from;
  f.heard_at = t0;
  followed_[match_id] = f;
}

void Cluster::hear_segment(const SegmentOut &seg, const ParticipantId &from, bool ours) {
  // another server steps one of ours, and DDS gave us its sample: its
  // MatchInfo will say who it is (the next one, within a second)
  if (ours) return;
  auto it = followed_.find(seg.match_id);
  if (it == followed_.end() || !(it->second.owner == from)) return;
  if (!usable_segment(seg)) {  // a take-over may go on from it: counted like a MatchInfo no server writes
    stats_.others_refused++;
    return;
  }
  Segments &kept = it->second.segments;
  kept[seg.seq] = seg;
  while (kept.size() > kFollowedSegments) kept.erase(kept.begin());
}

std::string Cluster::server_lost(const ParticipantId &who, double t0) {
  std::string line;
  auto p = peers_.find(who);
  if (p != peers_.end()) {
    line = "server " + std::to_string(p->second.status.server_id) + " (participant " + hex(who) +
           ") is gone: its writers lost their liveliness";
    peers_.erase(p);  // (forgotten: forged writers come and go without bound)
  }
  for (auto &f : followed_)
    if (f.second.owner == who && f.second.lost_at < 0.0) f.second.lost_at = t0;
  for (auto &o : owners_)
    if (o.second.first == who && o.second.second < 0.0) o.second.second = t0;
  return line;
}

// ---- take-overs ----------------------------------------------------------------

const SegmentOut *stepped_segment(const Segments &segments, const MatchInfoOut &info, double target) {
  for (auto it = segments.rbegin(); it != segments.rend(); ++it) {
    const SegmentOut &c = it->second;
    if (c.seq < info.segment_seq) break;  // the info's own is newer
    if (c.segment.t0 > target) continue;
    bool superseded = false, followed = false;
    for (auto later = it.base(); later != segments.end(); ++later) {
      superseded = superseded || later->second.segment.t0 <= c.segment.t0;
      followed = followed || later->second.segment.t0 > c.segment.t0;
    }
    if (superseded) continue;  // never in effect
    if (c.cause == Cause::serve || c.cause == Cause::racket || c.seq == info.segment_seq || followed) return &c;
  }
  return nullptr;
}

RestorePoint restore_point(const Followed &f, double first_real, double frame_time) {
  RestorePoint p;
  p.info = f.info;
  const MatchInfoOut &info = f.info;
  // a segment written after the info says the match played on (one
  // written ahead of its contact may come before a pause's info)
  bool plays = info.state == MatchState::playing;
  p.newest_seq = info.segment_seq;
  for (const auto &kv : f.segments) {
    plays = plays || (kv.first > info.segment_seq && kv.second.server_time > info.server_time);
    p.newest_seq = std::max(p.newest_seq, kv.first);
  }
  p.target = info.sim_time;
  if (plays) p.target += (first_real - frame_time - info.server_time) * info.settings.time_base;
  for (const auto &kv : f.segments)
    if (kv.second.cause == Cause::serve || kv.second.cause == Cause::racket)
      p.target = std::max(p.target, kv.second.segment.t0);
  if (info.segment_seq > 0) p.target = std::max(p.target, info.segment.t0);
  // the segment in effect at target (protocol.md: the highest seq whose t0
  // is not after it): a Segment sample, or the one the MatchInfo carries
  const SegmentOut *seg = stepped_segment(f.segments, info, p.target);
  if (seg) p.segment = *seg;
  else if (info.segment_seq > 0) p.segment = current_segment(info);
  p.has_segment = seg || info.segment_seq > 0;
  return p;
}

namespace {
// Mono s a followed match's owner was lost: its writers' liveliness, or
// kOwnerSilent after its newest MatchInfo (+Inf: it lives and writes).
double owner_lost_at(const Followed &f) {
  double silent = f.heard_at >= 0.0 ? f.heard_at + kOwnerSilent : HUGE_VAL;
  return f.lost_at >= 0.0 ? std::min(f.lost_at, silent) : silent;
}
}  // namespace

// Whether this server succeeds followed match f's owner (placement.h): when
// no standby lives, a server that yielded the match takes it back.
bool Cluster::succeeds(const Followed &f, std::vector<ServerView> *servers) const {
  if (servers->empty()) *servers = views();
  uint32_t next = 0;
  if (!successor(*servers, f.info.server_id, &next) && !settings_.standby) next = settings_.server_id;
  return next == settings_.server_id;
}

uint32_t Cluster::coming_term(double t0) const {
  uint32_t term = 0;
  std::vector<ServerView> servers;
  for (const auto &kv : followed_)
    if (t0 >= owner_lost_at(kv.second) && succeeds(kv.second, &servers))
      term = std::max(term, next_term(heard_term(kv.first), settings_.server_id));
  return term;
}

std::vector<uint32_t> Cluster::due_takeovers(double t0, const std::function<bool(uint32_t)> &hears_players) {
  std::vector<uint32_t> due;
  std::vector<ServerView> servers;
  for (auto &kv : followed_) {
    Followed &f = kv.second;
    if (t0 < owner_lost_at(f) + settings_.takeover_grace || !succeeds(f, &servers)) continue;
    // an owner cut off from this server but not from its players plays
    // on: a take-over here would be a second match nobody plays in
    if (!hears_players(kv.first)) {
      if (!f.waits_for_players) stats_.takeovers_waiting++;
      f.waits_for_players = true;
      f.players_back_at = -1.0;
      continue;
    }
    if (f.waits_for_players) {  // heard again: the owner may come back with them
      if (f.players_back_at < 0.0) f.players_back_at = t0;
      if (t0 < f.players_back_at + kPlayersSettle) continue;
    }
    f.waits_for_players = false;
    due.push_back(kv.first);
  }
  return due;
}

std::vector<uint32_t> Cluster::let_go_unheld(double t0) {
  std::vector<uint32_t> out;
  for (auto it = followed_.begin(); it != followed_.end();) {
    const Followed &f = it->second;
    bool held = false;
    for (int i = 0; i < f.info.players && i < kMaxPlayers; ++i) held = held || f.info.slots[i].held;
    if (t0 >= owner_lost_at(f) + settings_.takeover_grace && !held) {
      out.push_back(it->first);
      stats_.unheld_let_go++;
      it = followed_.erase(it);
    } else {
      ++it;
    }
  }
  return out;
}

const Followed *Cluster::followed(uint32_t match_id) const {
  auto it = followed_.find(match_id);
  return it == followed_.end() ? nullptr : &it->second;
}

void Cluster::taken_over(uint32_t match_id, bool ok) {
  if (ok) stats_.takeovers++;
  else stats_.follow_failures++;
  followed_.erase(match_id);
}

// ---- claims and creates ------------------------------------------------------------

std::vector<MatchConfig> Cluster::claims_due(double t0, const std::function<bool(uint32_t)> &placed) const {
  std::vector<uint32_t> unplaced;
  for (const auto &c : candidates_) {
    if (placed(c.id)) continue;
    auto o = owners_.find(c.id);
    // placed while its owner lives, and for orphan_wait after it was lost (a standby's to take over)
    if (o != owners_.end() && (o->second.second < 0.0 || t0 - o->second.second < settings_.orphan_wait)) continue;
    unplaced.push_back(c.id);
  }
  std::vector<MatchConfig> due;
  if (unplaced.empty()) return due;
  std::map<uint32_t, uint32_t> to = assign_claims(unplaced, views());
  for (const auto &c : candidates_) {
    auto w = to.find(c.id);
    if (w != to.end() && w->second == settings_.server_id) due.push_back(c);
  }
  return due;
}

void Cluster::claimed() {
  claimed_++;
  stats_.claims++;
}

bool Cluster::may_create(uint32_t match_id) {
  bool mine = false;
  if (settings_.claim == 0) {
    mine = !settings_.standby;  // it steps its configured matches, and creates, as before; a standby alone never
  } else if (claimed_ < settings_.claim) {
    std::map<uint32_t, uint32_t> to = assign_claims({match_id}, views());
    auto w = to.find(match_id);
    mine = w != to.end() && w->second == settings_.server_id;
  }
  if (!mine) stats_.creates_elsewhere++;
  return mine;
}

// ---- what it knows ------------------------------------------------------------------

ServerView Cluster::own_view() const {
  ServerView v;
  v.server_id = settings_.server_id;
  v.strength = settings_.strength;
  v.standby = settings_.standby;
  v.claim_room = settings_.claim > claimed_ ? settings_.claim - claimed_ : 0;
  return v;
}

std::vector<ServerView> Cluster::views() const {
  std::vector<ServerView> out{own_view()};
  for (const auto &p : peers_) {
    if (!p.second.alive || p.second.status.server_id == settings_.server_id) continue;
    ServerView v;
    v.server_id = p.second.status.server_id;
    v.strength = p.second.status.strength;
    v.standby = p.second.status.standby;
    v.claim_room = p.second.status.claim_room;
    out.push_back(v);
  }
  return out;
}

double Cluster::next_wake(double t0) const {
  // a standby takes its followed matches' samples, notes and data at least
  // every kFollowWake, and wakes for a take-over when its grace ends
  double wake = HUGE_VAL;
  if (!followed_.empty()) wake = t0 + kFollowWake;
  for (const auto &f : followed_) wake = std::min(wake, owner_lost_at(f.second) + settings_.takeover_grace);
  return wake;
}

}  // namespace ballsrv
