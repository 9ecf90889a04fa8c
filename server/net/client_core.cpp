#include "client_core.h"

#include <algorithm>
#include <cmath>

namespace ballsrv {

namespace {

constexpr double kMinNormal = 1e-6;  // a racket normal shorter than this is none (the server's zero_normal)
constexpr double kMaxNormal = 1e6;   // longer: out of range

bool finite3(const ball_vec3 &v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }
double norm(const ball_vec3 &v) { return std::sqrt(v.x * v.x + v.y * v.y + v.z * v.z); }

ball_status refuse(ball_status st, const std::string &sentence, std::string *why) {
  *why = sentence;
  return st;
}

std::string match_name(uint32_t m) { return "match " + std::to_string(m); }

}  // namespace

ClientCore::ClientCore(const CoreSettings &settings, const ParticipantId &me) : settings_(settings), me_(me) {}

ClientCore::Followed *ClientCore::followed(uint32_t match) {
  auto it = followed_.find(match);
  return it == followed_.end() ? nullptr : &it->second;
}

const MatchView *ClientCore::view(uint32_t match) const {
  auto it = followed_.find(match);
  return it == followed_.end() ? nullptr : it->second.view.get();
}

const OwnCounters *ClientCore::own(uint32_t match) const {
  auto it = followed_.find(match);
  return it == followed_.end() ? nullptr : &it->second.own;
}

ClientCore::Followed *ClientCore::follow(uint32_t match, ClientPort &port, ball_status *st, std::string *why) {
  if (Followed *f = followed(match)) return f;
  if (followed_.size() >= settings_.max_matches) {
    *why = "the client follows " + std::to_string(followed_.size()) + " matches, its room (max_matches)";
    *st = BALL_ENOSPACE;
    return nullptr;
  }
  if (!port.follow(match, why)) {
    *why = "the transport cannot follow " + match_name(match) + ": " + *why;
    *st = BALL_ENETWORK;
    return nullptr;
  }
  Followed &f = followed_[match];
  f.view = std::make_unique<MatchView>(match, settings_.servers, me_);
  // what the client holds of it already: the view starts from it
  auto m = models_.find(match);
  if (m != models_.end()) f.view->on_model(m->second);
  auto l = listed_.find(match);
  scratch_.clear();
  if (l != listed_.end()) f.view->on_info(l->second.info, l->second.heard, &scratch_);
  auto u = unfollowed_.find(match);
  if (u != unfollowed_.end()) {
    for (const auto &k : u->second) {
      const bool trusted = f.view->on_segment(k.segment, k.local, &scratch_);
      if (!tap_) continue;
      // (the tap had it as not trusted when it came: now the match took it, from what the client kept)
      json line = record_line(k.segment, k.real);
      line["trusted"] = trusted;
      line["kept"] = true;
      tap_(line);
    }
    unfollowed_.erase(u);
  }
  events_.insert(events_.end(), scratch_.begin(), scratch_.end());
  return &f;
}

size_t ClientCore::kept_unfollowed() const {
  size_t n = 0;
  for (const auto &kv : unfollowed_) n += kv.second.size();
  return n;
}

bool ClientCore::take_info(const MatchInfoOut &info, double local) {
  bool listed = false;
  if (!settings_.servers.accepts(info.server_id) || !usable_info(info)) {
    if (!followed(info.match_id)) refused_++;
  } else if (listed_.count(info.match_id) || list_room(local)) {
    Listed &l = listed_[info.match_id];
    l.info = info;
    l.heard = local;
    listed = true;
  }
  if (Followed *f = followed(info.match_id)) return f->view->on_info(info, local, &scratch_);
  return listed;
}

// Room in the list for one more match. When it is full, what went unheard
// for the silence goes (a stranger's made-up ids are heard once, disposed
// or not; a followed match keeps its view); when nothing did, the match
// not followed heard longest ago (docs/client.md, "The matches a client lists").
bool ClientCore::list_room(double local) {
  if (listed_.size() < settings_.max_matches) return true;
  auto oldest = listed_.end();
  for (auto it = listed_.begin(); it != listed_.end();) {
    if (local - it->second.heard > settings_.silence) {  // (a view of it stays while followed)
      it = listed_.erase(it);
      unlisted_++;
    } else if (followed(it->first)) {
      ++it;
    } else {
      if (oldest == listed_.end() || it->second.heard < oldest->second.heard) oldest = it;
      ++it;
    }
  }
  if (listed_.size() < settings_.max_matches) return true;
  if (oldest == listed_.end()) return false;  // (every one followed)
  listed_.erase(oldest);
  unlisted_++;
  return true;
}

// One pump's clocks, byte counts and tap line (ClientCore::pump).
struct ClientCore::Pump {
  ClientCore &core;
  double local, real;  // now on the caller's clock and the realtime clock
  WireSizes size;
  // a sample's reception on the caller's clock (its DDS stamp, else now)
  double at(const Reception &r) const { return r.received > 0.0 ? r.received + (local - real) : local; }
  // the followed match a sample is of, its bytes counted; nullptr: not followed
  Followed *of(uint32_t match, uint64_t bytes) const {
    Followed *f = core.followed(match);
    if (f) f->own.bytes_in += bytes;
    return f;
  }
  static void delay(Followed *f, const Reception &r) {
    if (r.received > 0.0 && r.written > 0.0) f->view->on_delay(r.received - r.written);
  }
  // the tap's line of a sample: received at its DDS stamp, else now; sent at
  // its writer's; trusted when the client kept it
  template <class T>
  json tap(const T &sample, const Reception &r, bool taken) const {
    if (!core.tap_) return json();
    json line = record_line(sample, r.received > 0.0 ? r.received : real);
    if (r.written > 0.0) line["sent"] = r.written;
    line["trusted"] = taken;
    return line;
  }
  void put(const json &line) const {
    if (core.tap_) core.tap_(line);
  }
};

void ClientCore::pump(ClientPort &port, double local, double real) {
  const Pump p{*this, local, real, port.sizes()};
  if (tap_ && !tapped_ready_ && port.hears_server()) {
    tapped_ready_ = true;
    tap_(json{{"type", "ready"}, {"recv", real}});
  }
  scratch_.clear();
  pump_models(port, p);  // models before infos: a view takes the model its info names at once
  MatchInfoOut info;
  while (port.take(&info)) {
    Followed *f = p.of(info.match_id, p.size.info);
    const uint64_t anew = f ? f->view->counters().anew : 0;
    json line = p.tap(info, info.reception, take_info(info, p.at(info.reception)));
    if (f) {
      Pump::delay(f, info.reception);
      if (tap_ && f->view->counters().anew != anew) line["anew"] = true;
    }
    p.put(line);
  }
  StateOut state;
  while (port.take(&state)) {
    Followed *f = p.of(state.match_id, p.size.state);
    p.put(p.tap(state, state.reception, f && f->view->on_state(state, p.at(state.reception))));
  }
  pump_segments(port, p);
  EventOut ev;
  while (port.take(&ev)) {
    Followed *f = p.of(ev.match_id, p.size.event);
    if (f && ev.kind == EventKind::refused) f->answered = p.local;
    p.put(p.tap(ev, ev.reception, f && f->view->on_event(ev, p.at(ev.reception), &scratch_)));
  }
  StatusOut status;  // (read when the config asks for it: only the tap has it)
  while (port.take(&status)) p.put(p.tap(status, Reception{}, true));
  RacketSampleIn racket;
  while (settings_.rackets && port.take(&racket)) {
    Followed *f = p.of(racket.match_id, p.size.sample);
    p.put(p.tap(racket, Reception{}, f && take_racket(f, racket)));
  }
  events_.insert(events_.end(), scratch_.begin(), scratch_.end());
  sizes_ = p.size;
  send_due(port, local);
  for (auto &kv : followed_) deliver(port, &kv.second, local);
}

void ClientCore::pump_models(ClientPort &port, const Pump &p) {
  MatchModelOut model;
  while (port.take(&model)) {
    if (tap_)  // (the model itself: ball_net_model)
      tap_(json{{"type", "match_model"}, {"match", model.match_id}, {"server", model.server_id},
                {"model_hash", model.model_hash}, {"recv", p.real}});
    if (models_.count(model.match_id) || models_.size() < settings_.max_matches) models_[model.match_id] = model;
    if (Followed *f = p.of(model.match_id, p.size.model)) f->view->on_model(model);
  }
}

// Segments: a followed match's view takes them; the newest few of a match
// not followed are kept for a later follow (kKeptUnfollowed).
void ClientCore::pump_segments(ClientPort &port, const Pump &p) {
  SegmentOut seg;
  while (port.take(&seg)) {
    Followed *f = p.of(seg.match_id, p.size.segment);
    p.put(p.tap(seg, seg.reception, f && f->view->on_segment(seg, p.at(seg.reception), &scratch_)));
    if (f) {
      Pump::delay(f, seg.reception);
    } else if (unfollowed_.count(seg.match_id) || unfollowed_.size() < settings_.max_matches) {
      auto &kept = unfollowed_[seg.match_id];
      kept.push_back(Kept{seg, p.at(seg.reception), seg.reception.received > 0.0 ? seg.reception.received : p.real});
      if (kept.size() > kKeptUnfollowed) kept.pop_front();
    }
  }
}

// A player's racket sample, kept on its slot's track if the match's
// newest MatchInfo names its writer as the slot's holder
// (docs/protocol.md, "The other players' rackets").
bool ClientCore::take_racket(Followed *f, const RacketSampleIn &s) {
  const MatchView &v = *f->view;
  MatchRackets &m = f->rackets;
  const bool ok = v.has_info() && v.model() && m.follow(v.info(), *v.model()) && m.has(s.player) &&
                  v.info().slots[s.player].held && m.holder(s.player) == s.from && !s.rejected;
  const ball_racket_sample sample{s.capture_time, s.center, s.normal};
  if (ok && m.push(s.player, sample) == BALL_OK) {
    f->own.rackets++;
    return true;
  }
  f->own.rackets_refused++;
  return false;
}

ball_status ClientCore::racket(uint32_t match, int slot, double local, ball_racket_pose *out) const {
  auto it = followed_.find(match);
  if (it == followed_.end()) return BALL_ENOMATCH;
  const Followed &f = it->second;
  if (!f.view->clock().valid() || !f.view->model()) return BALL_EAGAIN;
  if (slot < 0 || slot >= kMaxPlayers || (f.view->has_info() && slot >= f.view->info().players)) return BALL_ERANGE;
  return f.rackets.pose(slot, f.view->clock().sim_now(local), out);
}

// The poses whose simulated trip has ended by `local`, written.
void ClientCore::deliver(ClientPort &port, Followed *f, double local) {
  for (auto &link : f->links)
    if (link) link->deliver(local, [&](const RacketSampleIn &s) { write(port, s, f); });
}

bool ClientCore::write(ClientPort &port, const RacketSampleIn &s, Followed *f) {
  if (!port.write(s)) {
    f->own.write_failures++;
    return false;
  }
  f->own.samples++;
  f->own.bytes_out += sizes_.sample;
  return true;
}

bool ClientCore::write(ClientPort &port, const ControlIn &c, Followed *f) {
  if (port.write(c)) {
    if (f) f->own.bytes_out += sizes_.control;
    return true;
  }
  if (f) f->own.write_failures++;
  else lost_writes_++;
  return false;
}

bool ClientCore::Followed::joining() const {
  bool w = any;
  for (bool x : want) w = w || x;
  return w;
}

bool ClientCore::Followed::wants(int k) const {
  return k < kMaxPlayers ? want[k] && !view->holds(k) : any && view->slot() < 0;
}

bool ClientCore::Followed::waits_for_slot() const {
  for (int k = 0; k <= kMaxPlayers; ++k)
    if (wants(k)) return true;
  return false;
}

bool ClientCore::wants_renewal(bool meets, bool hears, double local) {
  if (renewed_at_ < 0.0) renewed_at_ = heard_at_ = local;
  if (meets || hears) heard_at_ = local;
  bool stuck = !meets && !hears && local - heard_at_ >= renew_wait_;
  bool waiting = false;
  for (auto &kv : followed_) {
    Followed &f = kv.second;
    if (!f.waits_for_slot()) {
      f.join_since = -1.0;
      continue;
    }
    waiting = true;
    double since = std::max({f.join_since, f.answered, renewed_at_});
    stuck = stuck || (hears && f.join_since >= 0.0 && local - since >= renew_wait_);
  }
  // a followed match heard once, and no MatchInfo of it for the silence
  // (its owner writes one at least every kInfoEvery s, its successor takes it over in
  // seconds) while a server is heard: a connection to its new owner may be deaf
  for (auto &kv : followed_) {
    auto l = listed_.find(kv.first);
    if (l == listed_.end() || local - l->second.heard < settings_.silence) continue;
    waiting = true;
    double since = std::max(l->second.heard, renewed_at_);
    stuck = stuck || (hears && local - since >= std::max(settings_.silence, renew_wait_));
  }
  if (hears && !waiting && !stuck) renew_wait_ = kRenewFirst;
  if (!stuck) return false;
  renewed_at_ = heard_at_ = local;
  renew_wait_ = std::min(2.0 * renew_wait_, kRenewMost);
  return true;
}

void ClientCore::renewed(const ParticipantId &me, double local) {
  me_ = me;
  renewals_++;
  tapped_ready_ = false;  // (the new participant's "ready" when it hears a server)
  for (auto &kv : followed_) {
    Followed &f = kv.second;
    f.view->set_me(me);
    f.next_join.fill(local);
    if (f.join_since >= 0.0) f.join_since = local;
  }
  for (auto &kv : creating_) kv.second.next = local;
  if (tap_) tap_(json{{"type", "renewed"}, {"renewals", renewals_}});
}

void ClientCore::send_due(ClientPort &port, double local) {
  for (auto &kv : followed_) {
    Followed &f = kv.second;
    // each slot wanted and not held, and `any` while none is held
    for (int k = 0; k <= kMaxPlayers; ++k) {
      if (!f.wants(k) || local < f.next_join[k]) continue;
      ControlIn c;
      c.match_id = kv.first;
      c.seq = ++control_seq_;
      c.kind = ControlKind::join;
      c.player = k < kMaxPlayers ? k : -1;
      write(port, c, &f);
      f.next_join[k] = local + settings_.retry;
      if (f.join_since < 0.0) f.join_since = local;
    }
  }
  for (auto it = creating_.begin(); it != creating_.end();) {
    if (listed_.count(it->first)) {  // its MatchInfo came: created (by whomever)
      it = creating_.erase(it);
      continue;
    }
    if (local >= it->second.next) {
      it->second.control.seq = ++control_seq_;
      write(port, it->second.control, followed(it->first));
      it->second.next = local + settings_.retry;
    }
    ++it;
  }
}

ball_status ClientCore::watch(uint32_t match, ClientPort &port, std::string *why) {
  ball_status st = BALL_OK;
  return follow(match, port, &st, why) ? BALL_OK : st;
}

ball_status ClientCore::unwatch(uint32_t match, ClientPort &port, std::string *why) {
  Followed *f = followed(match);
  if (!f) return refuse(BALL_ENOMATCH, "the client does not follow " + match_name(match), why);
  if (f->view->slot() >= 0) leave(match, -1, port, why);
  followed_.erase(match);
  port.unfollow(match);
  return BALL_OK;
}

ball_status ClientCore::join(uint32_t match, int slot, ClientPort &port, double local, std::string *why) {
  if (slot < -1 || slot >= kMaxPlayers)
    return refuse(BALL_ERANGE, "slot " + std::to_string(slot) + " is not -1 (any) or in [0, " +
                                   std::to_string(kMaxPlayers - 1) + "]",
                  why);
  const bool was_followed = followed(match) != nullptr;
  ball_status st = BALL_OK;
  Followed *f = follow(match, port, &st, why);
  if (!f) return st;
  size_t k = slot < 0 ? kMaxPlayers : static_cast<size_t>(slot);
  const bool held = slot < 0 ? f->view->slot() >= 0 : f->view->holds(slot);
  if (!held) {  // the first JOIN now: a writer the transport refuses (a partition not granted) is said here
    ControlIn c;
    c.match_id = match;
    c.seq = ++control_seq_;
    c.kind = ControlKind::join;
    c.player = slot;
    if (!write(port, c, f)) {
      if (!was_followed) followed_.erase(match), port.unfollow(match);
      return refuse(BALL_ENETWORK, "the transport refused the join of " + match_name(match), why);
    }
    if (f->join_since < 0.0) f->join_since = local;
  }
  if (slot < 0) f->any = true;
  else f->want[k] = true;
  f->next_join[k] = local + settings_.retry;
  return BALL_OK;
}

ball_status ClientCore::leave(uint32_t match, int slot, ClientPort &port, std::string *why) {
  Followed *f = followed(match);
  if (slot < -1 || slot >= kMaxPlayers || !f || !(slot < 0 ? f->joining() || f->view->slot() >= 0
                                                             : f->want[static_cast<size_t>(slot)] || f->view->holds(slot)))
    return refuse(BALL_ENOMATCH, "the client has not joined " + (slot < 0 ? match_name(match) : "slot " +
                  std::to_string(slot) + " of " + match_name(match)), why);
  bool written = true;
  for (int k = 0; k < kMaxPlayers; ++k) {
    if (slot >= 0 && k != slot) continue;
    f->want[static_cast<size_t>(k)] = false;
    if (!f->view->holds(k)) continue;
    ControlIn c;
    c.match_id = match;
    c.seq = ++control_seq_;
    c.kind = ControlKind::leave;
    c.player = k;
    written = write(port, c, f) && written;
  }
  if (slot < 0) f->any = false;
  if (!written) return refuse(BALL_ENETWORK, "DDS refused a LEAVE of " + match_name(match), why);
  return BALL_OK;
}

int ClientCore::leave_all(ClientPort &port) {
  int n = 0;
  std::string why;
  for (auto &kv : followed_)
    for (int k = 0; k < kMaxPlayers; ++k) n += kv.second.view->holds(k);
  for (auto &kv : followed_)
    if (kv.second.view->slot() >= 0) leave(kv.first, -1, port, &why);
  return n;
}

ball_status ClientCore::create(uint32_t match, const std::string &scene, int players, int level, ClientPort &port,
                               double local, std::string *why) {
  if (players < 1 || players > kMaxPlayers)
    return refuse(BALL_ERANGE, "players " + std::to_string(players) + " is not in [1, " + std::to_string(kMaxPlayers) + "]",
                  why);
  if (level < BALL_LEVEL_CUSTOM || level > BALL_LEVEL_ADVANCED)
    return refuse(BALL_ERANGE, "level " + std::to_string(level) + " is not in [0, 3]", why);
  if (scene.empty() || scene.size() >= static_cast<size_t>(kNameLen) || !plain_scene_name(scene))
    return refuse(BALL_ERANGE, "scene \"" + scene + "\" is not a name of 1 to 31 letters, digits, '_' or '-'", why);
  Creating c;
  c.control.match_id = match;
  c.control.seq = ++control_seq_;
  c.control.kind = ControlKind::create;
  c.control.scene = scene;
  c.control.players = players;
  c.control.level = level;
  if (!write(port, c.control, followed(match)))
    return refuse(BALL_ENETWORK, "the transport refused the creation of " + match_name(match), why);
  c.next = local + settings_.retry;
  creating_[match] = c;
  return BALL_OK;
}

ball_status ClientCore::ask(uint32_t match, ControlKind kind, double value, ClientPort &port, std::string *why) {
  Followed *f = followed(match);
  if (!f || f->view->slot() < 0) return refuse(BALL_ENOMATCH, "the client holds no slot of " + match_name(match), why);
  ControlIn c;
  c.match_id = match;
  c.seq = ++control_seq_;
  c.kind = kind;
  c.player = f->view->slot();
  if (kind == ControlKind::level) {
    if (!(value >= BALL_LEVEL_EASY && value <= BALL_LEVEL_ADVANCED) || value != std::floor(value))
      return refuse(BALL_ERANGE, "level " + std::to_string(value) + " is not 1, 2 or 3", why);
    c.level = static_cast<int>(value);
  } else if (kind == ControlKind::time_base) {
    if (!(value >= 0.05 && value <= 20.0)) return refuse(BALL_ERANGE, "time base " + std::to_string(value) + " is not in [0.05, 20]", why);
    c.time_base = value;
  } else if (kind != ControlKind::serve && kind != ControlKind::pause && kind != ControlKind::resume) {
    return refuse(BALL_EINVAL, std::string("a player does not ask for ") + name_of(kind), why);
  }
  if (!write(port, c, f)) return refuse(BALL_ENETWORK, "DDS refused the request", why);
  return BALL_OK;
}

ball_status ClientCore::number(uint32_t match, int slot, double local, ball_vec3 center, ball_vec3 normal,
                               RacketSampleIn *out, std::string *why) {
  Followed *f = followed(match);
  if (!f || !f->view->holds(slot))
    return refuse(BALL_ENOMATCH, "the client holds no slot " + std::to_string(slot) + " of " + match_name(match), why);
  const size_t k = static_cast<size_t>(slot);
  if (!std::isfinite(local) || !finite3(center) || !finite3(normal))
    return refuse(BALL_ENONFINITE, "a racket pose with NaN or infinity in its time, centre or normal", why);
  double n = norm(normal);
  if (!(n >= kMinNormal && n <= kMaxNormal))
    return refuse(BALL_ERANGE, "a racket normal of length " + std::to_string(n) + ", not in [1e-6, 1e6]", why);
  if (std::fabs(center.x) > BALL_MAX_COORD || std::fabs(center.y) > BALL_MAX_COORD || std::fabs(center.z) > BALL_MAX_COORD)
    return refuse(BALL_ERANGE, "a racket centre beyond 1e9 m", why);
  const MatchView &v = *f->view;
  if (!v.clock().valid()) return refuse(BALL_EAGAIN, "the clock of " + match_name(match) + " is not known yet", why);
  if (f->pushed[k] && !(local > f->last_push[k]))
    return refuse(BALL_ESTALE, "a racket pose at " + std::to_string(local) + " s, not after the previous one's", why);
  RacketSampleIn s;
  s.match_id = match;
  s.player = slot;
  s.seq = f->sample_seq[k] + 1;
  s.capture_time = v.clock().sim_now(local);
  s.center = center;
  s.normal = normal;
  f->sample_seq[k] = s.seq;
  f->pushed[k] = true;
  f->last_push[k] = local;
  *out = s;
  return BALL_OK;
}

ball_status ClientCore::push(uint32_t match, int slot, double local, ball_vec3 center, ball_vec3 normal,
                             ClientPort &port, std::string *why) {
  RacketSampleIn s;
  ball_status st = number(match, slot, local, center, normal, &s, why);
  if (st != BALL_OK) return st;
  Followed *f = followed(match);
  const size_t k = static_cast<size_t>(slot);
  if (settings_.link.active()) {
    // its trip through the simulated network: numbered now, written when it ends (lost: a gap in the numbers)
    auto &link = f->links[k];
    if (!link)
      link = std::make_unique<Link<RacketSampleIn>>(
          settings_.link, settings_.link_seed * 0x9e3779b97f4a7c15ull + (static_cast<uint64_t>(match) << 2) + k + 7);
    if (!link->send(s, local)) f->own.link_lost++;
    deliver(port, f, local);
    return BALL_OK;
  }
  if (write(port, s, f)) return BALL_OK;
  f->sample_seq[k]--;  // not written: its number is the next one's
  return refuse(BALL_ENETWORK, "DDS refused the racket sample", why);
}

std::vector<const Listed *> ClientCore::matches(double local) const {
  std::vector<const Listed *> out;
  for (const auto &kv : listed_)
    if (local - kv.second.heard <= settings_.silence) out.push_back(&kv.second);
  return out;
}

const Listed *ClientCore::listed(uint32_t match, double local) const {
  auto it = listed_.find(match);
  if (it == listed_.end() || local - it->second.heard > settings_.silence) return nullptr;
  return &it->second;
}

}  // namespace ballsrv
