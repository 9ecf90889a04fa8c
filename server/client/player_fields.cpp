// A bot's settings (player.h): their table, apart from the bot, so that a
// program that only passes them on (ball-demo) links no client.
#include "link.h"
#include "player.h"

namespace ballsrv {

const std::vector<Field<PlayerParams>> &player_fields() {
  using P = PlayerParams;
  static const std::vector<Field<P>> table = {
      {"match", &P::match, whole(0, UINT32_MAX), "", "match id", "--match"},
      {"player", &P::player, whole(-1, kMaxPlayers - 1), "", "player slot, -1: any free one", "--player"},
      {"rate", &P::rate, closed(2.0, 120.0), "Hz", "racket samples per second", "--rate"},
      {"delay", &P::delay, closed(0.0, LinkParams::kMaxDelay), "s", "added to every sample's trip", "--delay"},
      {"jitter", &P::jitter, closed(0.0, LinkParams::kMaxJitter), "s", "each sample is up to this much later again (uniform)",
       "--jitter"},
      {"loss", &P::loss, closed(0.0, LinkParams::kMaxLoss), "", "probability a sample is lost", "--loss"},
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

void set_link(const PlayerParams &p, ball_net_config *config) {
  config->link_delay = p.delay;
  config->link_jitter = p.jitter;
  config->link_loss = p.loss;
  config->link_seed = p.seed * 0x9e3779b97f4a7c15ull + 7;
}

}  // namespace ballsrv
