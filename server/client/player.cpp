#include "player.h"

#include <cmath>

#include "ball/vec3.h"
#include "rng.h"

namespace ballsrv {

namespace {
constexpr double kJoinRetry = 0.5;  // s between JOIN requests until the slot is ours
}

const std::vector<Field<PlayerParams>> &player_fields() {
  using P = PlayerParams;
  static const std::vector<Field<P>> table = {
      {"match", &P::match, whole(0, UINT32_MAX), "", "match id", "--match"},
      {"player", &P::player, whole(-1, kMaxPlayers - 1), "", "player slot, -1: any free one", "--player"},
      {"rate", &P::rate, closed(2.0, 120.0), "Hz", "racket samples per second", "--rate"},
      {"delay", &P::delay, closed(0.0, 10.0), "s", "added to every sample's trip", "--delay"},
      {"jitter", &P::jitter, closed(0.0, 1.0), "s", "each sample is up to this much later again (uniform)",
       "--jitter"},
      {"loss", &P::loss, closed(0.0, 0.9), "", "probability a sample is lost", "--loss"},
      {"noise", &P::noise, closed(0.0, 1.0), "m", "Gaussian tracker noise on the racket centre", "--noise"},
      {"miss", &P::miss, closed(0.0, 1.0), "", "skill: probability of missing a ball", "--miss"},
      {"aim_error", &P::aim_error, closed(0.0, 2.0), "m", "skill: Gaussian error on the planned contact",
       "--aim-error"},
      {"move_speed", &P::move_speed, closed(0.5, 100.0), "m/s", "the racket's speed between strokes",
       "--move-speed"},
      {"lead", &P::lead, closed(0.0, 2.0), "s", "on the stroke line before contact", "--lead",
       "from rate, delay, jitter, loss"},
      {"seed", &P::seed, whole(0, INT64_MAX), "", "seed of every random draw", "--seed"},
      {"servers", &P::servers, {}, "",
       "take the server topics only from these server ids, comma-separated; ID=IDENTITY: only from the holder of "
       "that certificate (--secure)",
       "--servers", "any"},
  };
  return table;
}

BotPlayer::BotPlayer(const ball_scene &scene, const ParticipantId &me, const PlayerParams &params)
    : scene_(scene),
      me_(me),
      p_(params),
      link_({params.delay, params.jitter, params.loss}, params.seed * 0x9e3779b97f4a7c15ull + 7),
      noise_(params.seed * 31 + 5),
      slot_(params.player) {
  std::string err;
  ServerChoice::parse(params.servers, &servers_, &err);  // checked by the program before
}

void BotPlayer::on_info(const MatchInfoOut &in, double real) {
  if (in.match_id != p_.match) return;
  if (!servers_.accepts(in.server_id) || !usable_info(in)) {
    counters_.refused++;
    return;
  }
  if (!clock_.observe(in.sim_time, in.server_time, in.time_base, in.state == MatchState::playing, real)) {
    counters_.refused++;
    return;
  }
  info_ = in;
  have_info_ = true;
  if (!joined_) {
    for (int i = 0; i < in.players; ++i)
      if (in.slots[i].held && in.slots[i].owner == me_ && (p_.player < 0 || p_.player == i)) slot_ = i;
  }
  joined_ = slot_ >= 0 && slot_ < in.players && in.slots[slot_].held && in.slots[slot_].owner == me_;
  if (!joined_ && p_.player < 0) slot_ = -1;  // taken from us: look for any free one again
  // the model the server steps, rebuilt when the match's setup changes
  if (in.level != level_ || in.players != players_ || in.model.extrapolation_time != extrapolation_ ||
      in.model.stale_time != stale_) {
    Court court;
    ball_model model;
    if (!match_model_of(scene_, in, &model, &court, &error_)) {
      counters_.refused++;
      return;
    }
    model_ = model;
    court_ = court;
    model_hash_ = ball_model_hash(&model_);
    server_hash_ = in.model_hash;
    counters_.hash_differs = model_hash_ != server_hash_;
    if (brain_ready_) brain_.set_model(model_);
    model_ready_ = true;
    level_ = in.level;
    players_ = in.players;
    extrapolation_ = in.model.extrapolation_time;
    stale_ = in.model.stale_time;
  }
  if (joined_ && model_ready_ && !brain_ready_) {
    BotParams b;
    b.slot = slot_;
    b.players = players_;
    b.miss_rate = p_.miss;
    b.aim_error = p_.aim_error;
    b.move_speed = p_.move_speed;
    b.lead = p_.lead >= 0.0 ? p_.lead : bot_lead(p_.rate, p_.delay, p_.jitter, p_.loss);
    b.seed = p_.seed;
    brain_.init(model_, court_, b);
    brain_ready_ = true;
  }
  // the segment in effect, for a bot that has not got it (one that joined
  // after a failover, whose new server has written no segment yet)
  if (in.segment_seq > 0 && segment_is_news(in.segment_seq, newest_seq_, in.segment_seq))
    on_segment(current_segment(in), real);
}

void BotPlayer::on_state(const StateOut &s, double real) {
  if (s.match_id != p_.match) return;
  if (!servers_.accepts(s.server_id) ||
      !clock_.observe(s.sim_time, s.server_time, info_.time_base, s.state == MatchState::playing, real))
    counters_.refused++;
}

void BotPlayer::on_segment(const SegmentOut &seg, double real) {
  if (seg.match_id != p_.match) return;
  if (!servers_.accepts(seg.server_id) || !segment_is_news(seg.seq, newest_seq_, info_.segment_seq) ||
      !finite_segment(seg.segment)) {
    if (seg.seq != newest_seq_) counters_.refused++;  // (the same segment again is no news, not a refusal)
    return;
  }
  newest_seq_ = seg.seq;
  counters_.segments++;
  feed_.add(seg);
  hand_over(real);
}

// The brain plays the segment in effect on the bot's clock (SegmentFeed).
void BotPlayer::hand_over(double real) {
  if (!brain_ready_ || !clock_.valid()) return;
  double now = clock_.sim_now(real);
  if (const SegmentOut *s = feed_.due(now)) brain_.on_segment(s->segment, s->cause == Cause::serve, s->cause_index, now);
}

void BotPlayer::tick(double mono, double real, std::vector<RacketSampleIn> *samples,
                     std::vector<ControlIn> *controls) {
  // players sample on their own phases, not in step (a seeded fraction of a sample's period):
  // a process of many bots would write all their samples in one burst otherwise
  if (next_sample_ < 0.0) {
    next_join_ = mono;
    next_sample_ = mono + golden_phase(p_.seed) / p_.rate;
  }
  hand_over(real);
  if (!joined_ && mono >= next_join_) {
    ControlIn c;
    c.match_id = p_.match;
    c.seq = ++control_seq_;
    c.kind = ControlKind::join;
    c.player = p_.player;
    controls->push_back(c);
    next_join_ = mono + kJoinRetry;
  }
  // after a wait (to join, for the clock) or a stall: on at the player's phase, no burst
  if (next_sample_ < mono - 1.0 / p_.rate) next_sample_ += std::ceil((mono - next_sample_) * p_.rate) / p_.rate;
  if (joined_ && brain_ready_ && clock_.valid() && mono >= next_sample_) {
    RacketSampleIn s;
    s.match_id = p_.match;
    s.player = slot_;
    s.seq = ++sample_seq_;
    s.capture_time = clock_.sim_now(real);
    brain_.pose(s.capture_time, &s.center, &s.normal);
    s.center.x += noise_.normal(p_.noise);
    s.center.y += noise_.normal(p_.noise);
    s.center.z += noise_.normal(p_.noise);
    counters_.taken++;
    if (!link_.send(s, mono)) counters_.lost++;
    next_sample_ += 1.0 / p_.rate;
  }
  link_.deliver(mono, [&](const RacketSampleIn &s) {
    samples->push_back(s);
    counters_.delivered++;
  });
}

bool BotPlayer::leave(ControlIn *out) {
  if (!joined_) return false;
  out->match_id = p_.match;
  out->seq = ++control_seq_;
  out->kind = ControlKind::leave;
  out->player = slot_;
  return true;
}

}  // namespace ballsrv
