#include "match_view.h"

#include <algorithm>
#include <cmath>

namespace ballsrv {

namespace {

constexpr size_t kModelsKept = 4;  // models not yet named by a MatchInfo (a level change's may come first)
constexpr size_t kDelays = 32;     // one-way delays kept for their median
constexpr size_t kGivenKept = 64;  // voidable events kept, at most

bool seq_before(uint32_t a, uint32_t b) { return static_cast<int32_t>(a - b) < 0; }

bool same_owner(const SegmentOut &a, const SegmentOut &b) { return a.term == b.term && a.server_id == b.server_id; }

// whether segment a comes after b: by owner, then by seq (docs/protocol.md, "Terms")
bool later(const SegmentOut &a, const SegmentOut &b) {
  if (!same_owner(a, b)) return owner_before(b.term, b.server_id, a.term, a.server_id);
  return seq_before(b.seq, a.seq);
}

bool voidable(const EventOut &e) { return is_collision(e.kind) || e.kind == EventKind::point; }

// A note to the caller; a collision whose sound flag is set is followed by
// the library's sound event, its twin of the same seq (docs/client.md,
// "Events"; the server writes no EVENT_SOUND: docs/protocol.md, "Events").
// Voiding the collision voids its twin with it.
void put(const ViewEvent &v, std::vector<ViewEvent> *out) {
  out->push_back(v);
  if (v.note != ViewNote::none || !is_collision(v.event.kind) || !v.event.sound) return;
  out->push_back(v);
  out->back().event.kind = EventKind::sound;
}

bool finite3(const ball_vec3 &v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// an event a caller can be given: its numbers finite, its enums the IDL's
// (EVENT_SOUND is none of them: the library makes its own, put above)
bool usable_event(const EventOut &e) {
  return e.kind != EventKind::sound && std::isfinite(e.time) && finite3(e.point) && finite3(e.velocity_in) && finite3(e.velocity_out) &&
         std::isfinite(e.value) && static_cast<unsigned>(e.kind) < static_cast<unsigned>(kEnumCount<EventKind>) &&
         static_cast<unsigned>(e.reason) < static_cast<unsigned>(kEnumCount<Reason>);
}

}  // namespace

bool same_event(const EventOut &a, const EventOut &b) {
  return a.kind == b.kind && a.index == b.index && a.side == b.side && a.in_play == b.in_play && a.time == b.time &&
         a.reason == b.reason && a.score == b.score;
}

bool voids(uint32_t correction_seq, double t0, const EventOut &e) {
  return voidable(e) && e.time > t0 && seq_before(e.segment_seq, correction_seq);
}

MatchView::MatchView(uint32_t id, const ServerChoice &servers, const ParticipantId &me)
    : id_(id), servers_(servers), me_(me) {
  ball_model_default(&info_.model);
}

ViewEvent MatchView::note(ViewNote n, double time) const {
  ViewEvent v;
  v.note = n;
  v.event.match_id = id_;
  v.event.server_id = info_.server_id;
  v.event.time = time;
  v.event.score = info_.play.score;
  v.event.seq = 0;
  return v;
}

// A match started anew (docs/protocol.md, "Clients that trust no one"):
// nothing held of the old one applies, its seqs start over.
void MatchView::start_anew() {
  window_.clear();
  any_event_ = false;
  last_event_ = 0;
  given_.clear();
  recent_.clear();
  corrections_.clear();
  clock_ = SimClock();
  counters_.anew++;
}

bool MatchView::owner_fits(uint32_t term, uint32_t server, const ParticipantId &from, double local) {
  if (!has_owner_ || local - owner_local_ > kForgetOwner) return true;
  if (term == term_ && server == owner_ && from != ParticipantId{} && owner_from_ != ParticipantId{} &&
      from != owner_from_ && local - owner_local_ <= kOwnerWriter) {
    counters_.refused++;  // its server's id and term, another participant's writer: a copy
    return false;
  }
  if (owner_before(term, server, term_, owner_)) {
    counters_.old_owner++;
    return false;
  }
  if (term - term_ > kMaxTermAhead) {
    counters_.refused++;  // no match goes through that many rounds: forged
    return false;
  }
  return true;
}

// An older owner than the one held is taken only once that one is
// forgotten: its match is served anew, nothing held of it applies.
bool MatchView::take_owner(uint32_t term, uint32_t server, const ParticipantId &from, double local) {
  bool older = has_owner_ && owner_before(term, server, term_, owner_);
  if (older) start_anew();
  if (!has_owner_ || older || owner_before(term_, owner_, term, server)) {
    if (has_owner_ && !older) clock_.rebase();  // a newer owner: its sim clock may be another (two claimants)
    term_ = term;
    owner_ = server;
    has_owner_ = true;
  }
  if (from != ParticipantId{}) owner_from_ = from;
  owner_local_ = local;
  return older;
}

bool MatchView::on_info(const MatchInfoOut &in, double local, std::vector<ViewEvent> *out) {
  if (in.match_id != id_ || !servers_.accepts(in.server_id) || !usable_info(in)) {
    counters_.refused++;
    return false;
  }
  if (!owner_fits(in.term, in.server_id, in.reception.from, local)) return false;
  bool anew = take_owner(in.term, in.server_id, in.reception.from, local);
  if (!anew && has_info_ && in.sim_time + kAnew < info_.sim_time) start_anew();
  if (!clock_.observe(in.sim_time, in.server_time, in.settings.time_base, in.state == MatchState::playing, local)) {
    counters_.refused++;
    return false;
  }
  bool server_changed = has_info_ && in.server_id != info_.server_id;
  info_ = in;
  info_local_ = local;
  has_info_ = true;
  if (server_changed) {
    ViewEvent v = note(ViewNote::server, in.sim_time);
    v.event.server_id = in.server_id;
    out->push_back(v);
  }
  // this client's slots
  unsigned mine = 0;
  for (int i = 0; i < in.players && i < kMaxPlayers; ++i)
    if (in.slots[i].held && in.slots[i].owner == me_) mine |= 1u << i;
  for (int i = 0; i < kMaxPlayers; ++i)
    if ((mine ^ mine_) >> i & 1u) {
      ViewEvent v = note(ViewNote::slot, in.sim_time);
      v.event.index = i;
      v.event.value = mine >> i & 1u;
      out->push_back(v);
    }
  mine_ = mine;
  // the whole model it names, if it came first; else the one held may no longer be it
  if (!has_model_ || model_.model_hash != in.model_hash) {
    has_model_ = false;
    for (const auto &m : models_)
      if (usable_model(m, in.model_hash)) {
        model_ = m;
        has_model_ = true;
      }
  }
  if (flight_hash_ != in.model_hash) {  // a new flight model (a level turns spin on or off): prepared anew
    flight_hash_ = in.model_hash;
    for (auto &k : window_) prepare(&k);
  }
  // the segment in effect, for a client that has not got it (one that joined after a failover)
  if (in.segment_seq > 0) {
    bool held = false;
    for (const auto &k : window_) held = held || k.segment.seq == in.segment_seq;
    if (!held) keep(current_segment(in));
  }
  return true;
}

bool MatchView::on_model(const MatchModelOut &m) {
  if (m.match_id != id_ || !servers_.accepts(m.server_id) || ball_model_check(&m.model, nullptr) != BALL_OK ||
      ball_model_hash(&m.model) != m.model_hash) {
    counters_.refused++;
    return false;
  }
  if (has_info_ && m.model_hash == info_.model_hash) {
    model_ = m;
    has_model_ = true;
    return true;
  }
  models_.push_back(m);
  if (models_.size() > kModelsKept) models_.erase(models_.begin());
  return true;
}

void MatchView::prepare(KeptSegment *k) const {
  k->ready = ball_flight_init(&flight_model(), &k->segment.segment, &k->flight) == BALL_OK;
}

bool MatchView::keep(const SegmentOut &s) {
  for (auto &k : window_)
    if (k.segment.seq == s.seq && same_owner(k.segment, s)) return false;  // (the same segment again)
  KeptSegment k;
  k.segment = s;
  prepare(&k);
  auto at = std::find_if(window_.begin(), window_.end(), [&](const KeptSegment &w) { return later(w.segment, s); });
  window_.insert(at, k);
  if (window_.size() > kWindow) window_.erase(window_.begin());
  return true;
}

bool MatchView::on_segment(const SegmentOut &s, double local, std::vector<ViewEvent> *out) {
  if (s.match_id != id_) return false;
  // a new owner's seqs are checked against its own stream (a claim begins anew)
  const SegmentOut *last = window_.empty() ? nullptr : &window_.back().segment;
  uint32_t base = last && same_owner(*last, s) ? last->seq : 0;
  if (!servers_.accepts(s.server_id) || !finite_segment(s.segment) ||
      static_cast<unsigned>(s.cause) >= static_cast<unsigned>(kEnumCount<Cause>) ||
      !segment_fits(s.seq, base, info_.segment_seq)) {
    counters_.refused++;
    return false;
  }
  if (!owner_fits(s.term, s.server_id, s.reception.from, local)) return false;
  take_owner(s.term, s.server_id, s.reception.from, local);
  bool news = window_.empty() || later(s, window_.back().segment);
  if (!keep(s)) return true;  // held already
  counters_.segments++;
  if (news && clock_.valid() && s.segment.t0 < clock_.sim_now(local)) counters_.late++;
  if (s.correction) void_given(s, out);
  return true;
}

void MatchView::void_given(const SegmentOut &c, std::vector<ViewEvent> *out) {
  corrections_.push_back({c.seq, c.segment.t0});
  if (corrections_.size() > kCorrections) corrections_.pop_front();
  for (auto it = given_.begin(); it != given_.end();) {
    if (voids(c.seq, c.segment.t0, *it)) {
      ViewEvent v;
      v.note = ViewNote::voided;
      v.event = *it;
      out->push_back(v);
      counters_.voided++;
      it = given_.erase(it);
    } else {
      ++it;
    }
  }
}

bool MatchView::voided_before(const EventOut &e) const {
  for (const auto &c : corrections_)
    if (voids(c.first, c.second, e)) return true;
  return false;
}

bool MatchView::on_event(const EventOut &e, double local, std::vector<ViewEvent> *out) {
  if (e.match_id != id_) return false;
  if (!servers_.accepts(e.server_id) || !usable_event(e)) {
    counters_.refused++;
    return false;
  }
  if (!owner_fits(e.term, e.server_id, e.reception.from, local)) return false;
  take_owner(e.term, e.server_id, e.reception.from, local);
  int32_t ahead = static_cast<int32_t>(e.seq - last_event_);
  if (any_event_ && ahead <= 0) return replace_given(e, out);  // given already, unless a newer owner's other
  if (any_event_ && static_cast<uint32_t>(ahead) > kMaxSeqAhead) {
    counters_.refused++;  // no stream goes that far: a forged seq must not blind the client
    return false;
  }
  if (any_event_ && ahead > 1) {
    ViewEvent gap = note(ViewNote::gap, e.time);
    gap.event.value = ahead - 1;
    out->push_back(gap);
    counters_.lost += static_cast<uint64_t>(ahead - 1);
  }
  any_event_ = true;
  last_event_ = e.seq;
  if (voided_before(e)) {  // a correction that came first took it back
    counters_.voided++;
    return true;
  }
  give(e, out);
  return true;
}

void MatchView::give(const EventOut &e, std::vector<ViewEvent> *out) {
  ViewEvent v;
  v.event = e;
  put(v, out);
  counters_.events++;
  recent_.push_back(e);
  if (recent_.size() > kGivenKept) recent_.pop_front();
  if (voidable(e)) {
    given_.push_back(e);
    while (!given_.empty() && (given_.size() > kGivenKept || given_.front().time < e.time - kVoidableFor))
      given_.pop_front();
  }
}

// docs/protocol.md, "Terms": a newer owner goes on from the event seq it
// restored, and writes again events the old owner wrote: the same event is
// not given twice; another one (the new owner judged the time since
// otherwise) replaces the one given, which is voided.
bool MatchView::replace_given(const EventOut &e, std::vector<ViewEvent> *out) {
  auto was = std::find_if(recent_.begin(), recent_.end(), [&](const EventOut &r) { return r.seq == e.seq; });
  if (was == recent_.end() || !owner_before(was->term, was->server_id, e.term, e.server_id)) return false;
  if (same_event(*was, e)) {
    was->term = e.term;  // (now the newer owner's)
    was->server_id = e.server_id;
    return false;
  }
  for (auto it = given_.begin(); it != given_.end(); ++it)
    if (it->seq == was->seq && it->term == was->term && it->server_id == was->server_id) {
      ViewEvent v;
      v.note = ViewNote::voided;
      v.event = *it;
      out->push_back(v);
      counters_.voided++;
      given_.erase(it);
      break;
    }
  recent_.erase(was);
  counters_.replaced++;
  give(e, out);
  return true;
}

bool MatchView::on_state(const StateOut &s, double local) {
  if (s.match_id != id_) return false;
  if (has_info_ && servers_.accepts(s.server_id) && !owner_fits(s.term, s.server_id, s.reception.from, local))
    return false;
  if (has_info_ && servers_.accepts(s.server_id)) take_owner(s.term, s.server_id, s.reception.from, local);
  if (!has_info_ || !servers_.accepts(s.server_id) ||
      !clock_.observe(s.sim_time, s.server_time, info_.settings.time_base, s.state == MatchState::playing, local)) {
    counters_.refused++;
    return false;
  }
  return true;
}

void MatchView::on_delay(double seconds) {
  if (!std::isfinite(seconds)) return;
  if (delays_.size() < kDelays) {
    delays_.push_back(seconds);
  } else {
    delays_[next_delay_] = seconds;
    next_delay_ = (next_delay_ + 1) % kDelays;
  }
}

double MatchView::delay() const {
  if (delays_.empty()) return 0.0;
  std::vector<double> d = delays_;
  std::nth_element(d.begin(), d.begin() + static_cast<long>(d.size() / 2), d.end());
  return d[d.size() / 2];
}

int MatchView::slot() const {
  for (int i = 0; i < kMaxPlayers; ++i)
    if (holds(i)) return i;
  return -1;
}

ball_status MatchView::ball(double local, ViewBall *out) const {
  if (!std::isfinite(local)) return BALL_ENONFINITE;
  double sim = 0.0;
  const KeptSegment *k = at(local, &sim);
  if (!k) return BALL_EAGAIN;
  ball_status st = ball_flight_eval(&k->flight, sim, &out->state);
  if (st != BALL_OK) return st;
  out->sim_time = sim;
  out->segment = &k->segment;
  return BALL_OK;
}

ball_status MatchView::predict(double local, double horizon, double dt, ball_prediction *out) const {
  if (!std::isfinite(local) || !std::isfinite(horizon) || !std::isfinite(dt)) return BALL_ENONFINITE;
  if (!has_model_ || !clock_.valid()) return BALL_EAGAIN;
  double sim = clock_.sim_now(local);
  const KeptSegment *k = in_effect(sim);
  if (!k) return BALL_EAGAIN;
  return ball_predict(&model_.model, &k->segment.segment, sim, sim + horizon, dt, out);
}

}  // namespace ballsrv
