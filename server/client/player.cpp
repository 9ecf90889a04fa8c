#include "player.h"

#include <cmath>

#include "ball/vec3.h"
#include "rng.h"

namespace ballsrv {

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

BotPlayer::BotPlayer(const PlayerParams &params)
    : p_(params),
      link_({params.delay, params.jitter, params.loss}, params.seed * 0x9e3779b97f4a7c15ull + 7),
      noise_(params.seed * 31 + 5),
      slot_(params.player) {}

// The brain plays the segment in effect on the bot's clock, handed on once
// each time it changes, with the match's model from the wire (a new one at a
// new level).
void BotPlayer::plan(const MatchView &view, double sim) {
  const ball_model *model = view.model();
  if (!model) return;  // (its MatchModel has not come: the bot waits for it)
  uint64_t hash = view.info().model_hash;
  if (!brain_ready_) {
    Court court;
    std::string err;
    if (!court_from_model(*model, view.info().court_x[0], &court, &err)) return;
    BotParams b;
    b.slot = slot_;
    b.players = view.info().players;
    b.miss_rate = p_.miss;
    b.aim_error = p_.aim_error;
    b.move_speed = p_.move_speed;
    b.lead = p_.lead >= 0.0 ? p_.lead : bot_lead(p_.rate, p_.delay, p_.jitter, p_.loss);
    b.seed = p_.seed;
    brain_.init(*model, court, b);
    brain_ready_ = true;
    model_hash_ = hash;
  } else if (hash != model_hash_) {
    brain_.set_model(*model);
    model_hash_ = hash;
  }
  if (const SegmentOut *s = feed_.due(view, sim)) brain_.on_segment(s->segment, s->cause == Cause::serve, s->cause_index, sim);
}

void BotPlayer::tick(const MatchView *view, ClientCore &core, double mono, std::vector<RacketSampleIn> *samples) {
  // players sample on their own phases, not in step (a seeded fraction of a sample's period):
  // a process of many bots would write all their samples in one burst otherwise
  if (next_sample_ < 0.0) next_sample_ = mono + golden_phase(p_.seed) / p_.rate;
  joined_ = view && (p_.player >= 0 ? view->holds(p_.player) : view->slot() >= 0);
  if (joined_) {
    int slot = p_.player >= 0 ? p_.player : view->slot();
    if (slot != slot_ && brain_ready_) brain_ready_ = false;  // another slot: another side of the court
    slot_ = slot;
  } else if (p_.player < 0) {
    slot_ = -1;  // taken from us: any free one again (the core asks)
  }
  bool clock = view && view->clock().valid();
  if (joined_ && clock) plan(*view, view->clock().sim_now(mono));
  // after a wait (to join, for the clock) or a stall: on at the player's phase, no burst
  if (next_sample_ < mono - 1.0 / p_.rate) next_sample_ += std::ceil((mono - next_sample_) * p_.rate) / p_.rate;
  if (joined_ && brain_ready_ && clock && mono >= next_sample_) {
    ball_vec3 center, normal;
    brain_.pose(view->clock().sim_now(mono), &center, &normal);
    center.x += noise_.normal(p_.noise);
    center.y += noise_.normal(p_.noise);
    center.z += noise_.normal(p_.noise);
    RacketSampleIn s;
    std::string why;
    if (core.sample(p_.match, slot_, mono, center, normal, &s, &why) == BALL_OK) {
      counters_.taken++;
      if (!link_.send(s, mono)) counters_.lost++;
    }
    next_sample_ += 1.0 / p_.rate;
  }
  link_.deliver(mono, [&](const RacketSampleIn &s) {
    samples->push_back(s);
    counters_.delivered++;
  });
}

}  // namespace ballsrv
