#include "roster.h"

#include <algorithm>
#include <bitset>
#include <cmath>

#include "ball/vec3.h"

namespace ballsrv {

namespace {

constexpr double kMinNormal = 1e-6;   // |normal| below: zero_normal
constexpr double kMaxNormal = 1e6;    // above: out_of_range
constexpr double kBoxHeight = 30.0;   // m above the floor a racket may be
constexpr double kUnderFloor = 1.0;   // m under it: a swing's straight line through a low contact, a tracker's error
constexpr double kOverNet = 1.0;      // m beyond the net a racket may reach
constexpr int32_t kMaxSeqJump = 1000; // a holder's seq goes at most this far ahead of its previous (33 s at 30 Hz)
constexpr int32_t kLateWindow = 16;   // seqs behind a stream's newest arrival a late sample may fill its gap (< 64)
// samples a holder's stream may capture a second: seqs skipped beyond what
// the capture times allow (the newest's since the one before it) are no
// loss (a stream started over, or a writer inflating `lost`), however far
// within kMaxSeqJump; a capture time cannot run ahead of the match's clock
// (max_sample_lead), so `lost` grows at most this much a second a slot
constexpr double kMaxStreamRate = 1000.0;

bool in_range(double v, double lo, double hi) { return v >= lo && v <= hi; }

// the holder's sample `seq` arrived: the seqs the stream's window left
// behind that never arrived (lost), or, late, it fills its own gap
uint64_t stream_gap(Slot &slot, uint32_t seq, double capture) {
  if (!slot.has_seen) {
    slot.has_seen = true;
    slot.seen_seq = seq;
    slot.seen_at = capture;
    slot.missing = 0;
    return 0;
  }
  // serial-number arithmetic: behind, the same, or further than a stream goes: no gap
  int32_t ahead = static_cast<int32_t>(seq - slot.seen_seq);
  if (ahead < 0 && ahead >= -kLateWindow) {  // late: it fills its gap, never counted lost
    slot.missing &= ~(uint64_t{1} << (-ahead - 1));
    return 0;
  }
  if (ahead <= 0 || ahead > kMaxSeqJump) return 0;
  // (a skip of one or two is always a gap: a capture time earlier than the one before is no forgery of `lost`)
  if (ahead > 3 && !(ahead - 1 <= (capture - slot.seen_at) * kMaxStreamRate + 2.0)) {  // more than it could have captured
    uint64_t lost = std::bitset<64>(slot.missing).count();  // (its gaps until now were real)
    slot.seen_seq = seq;
    slot.seen_at = capture;
    slot.missing = 0;
    return lost;
  }
  slot.seen_seq = seq;
  slot.seen_at = capture;
  // the window moves on by `ahead`: the gaps it leaves behind are lost, and
  // the seqs skipped now are its new gaps (those beyond its end lost at once)
  const uint64_t window = (uint64_t{1} << kLateWindow) - 1;
  uint64_t skipped = static_cast<uint64_t>(ahead - 1), lost = 0;
  if (ahead >= kLateWindow) {
    lost = std::bitset<64>(slot.missing).count();
    slot.missing = 0;
  } else {
    lost = std::bitset<64>(slot.missing >> (kLateWindow - ahead)).count();
    slot.missing = (slot.missing << ahead) & window;
  }
  if (skipped >= static_cast<uint64_t>(kLateWindow)) {
    lost += skipped - kLateWindow;
    slot.missing = window;
  } else {
    slot.missing |= (uint64_t{1} << skipped) - 1;
  }
  return lost;
}

}  // namespace

void Slot::keep(const ball_racket_sample &s) {
  if (kept_n == BALL_MAX_HISTORY) {
    std::copy(kept.begin() + 1, kept.end(), kept.begin());
    kept_n--;
  }
  kept[static_cast<size_t>(kept_n++)] = s;
}

// ---- presence ---------------------------------------------------------------------

bool Roster::all_present() const {
  for (int i = 0; i < players_; ++i)
    if (!(*this)[i].held || !(*this)[i].present) return false;
  return true;
}

bool Roster::held() const {
  for (int i = 0; i < players_; ++i)
    if ((*this)[i].held) return true;
  return false;
}

bool Roster::holds(const ParticipantId &who) const {
  for (int i = 0; i < players_; ++i)
    if ((*this)[i].held && (*this)[i].owner == who) return true;
  return false;
}

void Roster::participant_lost(const ParticipantId &who) {
  for (int i = 0; i < players_; ++i)
    if ((*this)[i].held && (*this)[i].owner == who) (*this)[i].alive = false;
}

bool Roster::update_presence(double now, double timeout, int *missing) {
  bool changed = false;
  *missing = -1;
  for (int i = 0; i < players_; ++i) {
    Slot &s = (*this)[i];
    bool present = s.held && s.alive && now - s.last_seen <= timeout;
    changed = changed || present != s.present;
    s.present = present;
    if (s.held && !present && *missing < 0) *missing = i;
  }
  return changed;
}

bool Roster::hears_players(double now, double timeout) const {
  bool held = false;
  for (int i = 0; i < players_; ++i) {
    const Slot &s = (*this)[i];
    held = held || s.held;
    if (s.held && now - s.last_seen <= timeout) return true;
  }
  return !held;
}

// ---- JOIN and LEAVE ---------------------------------------------------------------

int Roster::free_slot(const ParticipantId &who, double now, double timeout, unsigned allowed) const {
  auto may = [allowed](int i) { return (allowed >> i & 1u) != 0; };
  for (int i = 0; i < players_; ++i)
    if ((*this)[i].held && (*this)[i].owner == who) return i;  // already its
  for (int i = 0; i < players_; ++i)
    if (may(i) && !(*this)[i].held) return i;
  for (int i = 0; i < players_; ++i)
    if (may(i) && (!(*this)[i].alive || now - (*this)[i].last_seen > timeout)) return i;  // vanished
  return -1;
}

Roster::Join Roster::join(int slot, const ParticipantId &who, double now, double timeout) {
  Slot &s = (*this)[slot];
  if (s.held && s.owner == who) {  // a repeated join: the holder's stream starts anew
    s.alive = true;
    s.has_seq = false;
    end_stream(s);
    s.has_prev = false;
    return Join::again;
  }
  if (s.held && s.alive && now - s.last_seen <= timeout) return Join::refused;
  end_stream(s);
  s = Slot{};
  s.held = true;
  s.owner = who;
  s.last_seen = now;  // joining counts as being there until the timeout runs out
  return Join::taken;
}

bool Roster::leave(int slot, const ParticipantId &who) {
  Slot &s = (*this)[slot];
  if (!s.held || s.owner != who) return false;
  end_stream(s);
  s = Slot{};
  return true;
}

unsigned Roster::follow(const MatchInfoOut &info) {
  unsigned cleared = 0;
  for (int k = 0; k < players_; ++k) {
    const SlotInfo &in = info.slots[k];
    Slot &sl = (*this)[k];
    if (!in.held) {
      end_stream(sl);
      sl = Slot{};
      continue;
    }
    if (!sl.held || sl.owner != in.owner) {  // a new holder: its own history
      double seen = sl.owner == in.owner ? sl.last_seen : -1e300;
      end_stream(sl);
      sl = Slot{};
      sl.last_seen = seen;
      cleared |= 1u << k;
    }
    sl.held = true;
    sl.owner = in.owner;
    sl.samples = std::max(sl.samples, in.samples);
    // the owner's newest seq moves the stream on as one of the holder's
    // samples would (check): ahead in serial-number arithmetic, by at most
    // kMaxSeqJump, so that a forged last_seq holds the holder back no
    // further than a forged sample could (docs/protocol.md, "Several servers")
    int32_t ahead = static_cast<int32_t>(in.last_seq - sl.last_seq);
    if (!sl.has_seq || (ahead > 0 && ahead <= kMaxSeqJump)) {
      sl.has_seq = in.samples > 0;
      sl.last_seq = in.last_seq;
    }
  }
  return cleared;
}

bool Roster::ask_time_base(const ParticipantId &who, double tb) {
  bool all = true;
  for (int i = 0; i < players_; ++i) {
    Slot &s = (*this)[i];
    if (s.held && s.owner == who) s.asked_time_base = tb;
    all = all && s.held && s.asked_time_base == tb;
  }
  if (all)
    for (int i = 0; i < players_; ++i) (*this)[i].asked_time_base = 0.0;
  return all;
}

void Roster::fill(MatchInfoOut *info) const {
  for (int k = 0; k < players_; ++k) {
    const Slot &s = (*this)[k];
    info->slots[k].held = s.held;
    info->slots[k].present = s.present;
    info->slots[k].owner = s.owner;
    info->slots[k].samples = s.samples;
    info->slots[k].last_seq = s.last_seq;
    info->slots[k].last_capture_time = s.ref.capture_time;
  }
}

// ---- the holders' streams -------------------------------------------------------------

uint64_t Roster::arrived(int k, uint32_t seq, double capture) { return stream_gap((*this)[k], seq, capture); }

void Roster::end_stream(Slot &slot) {
  ended_lost_ += std::bitset<64>(slot.missing).count();
  slot.missing = 0;
  slot.has_seen = false;
}

void Roster::end_streams() {
  for (auto &s : slots_) end_stream(s);
}

uint64_t Roster::take_lost() {
  uint64_t n = ended_lost_;
  ended_lost_ = 0;
  return n;
}

uint64_t Roster::rejected(const RacketSampleIn &s) {
  if (s.player < 0 || s.player >= players_) return 0;
  Slot &slot = (*this)[s.player];
  if (!slot.held || slot.owner != s.from) return 0;
  return stream_gap(slot, s.seq, s.capture_time);
}

// ---- a racket sample's checks ----------------------------------------------------------

SampleResult Roster::check(const RacketSampleIn &s, double now, double sim_now, const MatchConfig &config,
                           const Court &court, uint64_t *lost) {
  if (s.player < 0 || s.player >= players_) return SampleResult::bad_slot;
  Slot &slot = (*this)[s.player];
  if (!slot.held) return SampleResult::not_joined;
  if (slot.owner != s.from) return SampleResult::not_owner;
  // the holder's stream: seqs it skipped are samples lost on the way
  uint64_t gap = stream_gap(slot, s.seq, s.capture_time);
  if (lost) *lost += gap;
  if (!std::isfinite(s.capture_time) || !ball_v3_finite(s.center) || !ball_v3_finite(s.normal))
    return SampleResult::nonfinite;
  double n = ball_v3_norm(s.normal);
  if (!(n >= kMinNormal)) return SampleResult::zero_normal;
  if (n > kMaxNormal) return SampleResult::out_of_range;
  // the player's own half, a margin beyond its baseline and sidelines, a
  // reach over the net, about above the floor
  double m = config.racket_margin;
  bool near_side = Court::side_of_slot(s.player) == 0;
  double x_lo = near_side ? court.x_lo - m : court.net_x - kOverNet;
  double x_hi = near_side ? court.net_x + kOverNet : court.x_hi + m;
  if (!in_range(s.center.x, x_lo, x_hi) || !in_range(s.center.z, court.z_lo - m, court.z_hi + m) ||
      !in_range(s.center.y, court.floor - kUnderFloor, court.floor + kBoxHeight))
    return SampleResult::out_of_range;
  if (s.capture_time > sim_now + config.max_sample_lead) return SampleResult::out_of_range;
  // well formed and from the holder: the player is there
  slot.last_seen = now;
  slot.alive = true;
  if (slot.has_seq) {
    // serial number arithmetic (RFC 1982): a stream wraps around instead of locking at 2^32 - 1
    int32_t ahead = static_cast<int32_t>(s.seq - slot.last_seq);
    if (ahead == 0) return SampleResult::duplicate;
    // behind, or further ahead than a stream goes between two samples (a
    // forged seq must not put the holder's own stream behind it)
    if (ahead < 0 || ahead > kMaxSeqJump) return SampleResult::out_of_order;
  }
  if (s.capture_time < sim_now - config.max_sample_age) return SampleResult::stale;
  if (slot.has_prev) {
    double moved = ball_v3_norm(ball_v3_sub(s.center, slot.prev_center));
    // not newer than its previous sample (which may be one taken while
    // paused, not on the track: libball's order check does not see it):
    // the racket would be in two places
    if (s.capture_time < slot.prev_time || (s.capture_time == slot.prev_time && moved > 0.0))
      return SampleResult::stale;
    // a racket is a body: no faster than max_racket_speed since its previous sample, no jump
    if (moved > config.max_racket_speed * (s.capture_time - slot.prev_time)) return SampleResult::too_fast;
  }
  return SampleResult::accepted;
}

}  // namespace ballsrv
