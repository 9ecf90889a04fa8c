// ball-bot: an autonomous player (docs/bots-and-watchers.md, "Bots"), a game on the
// client library (ball/net.h). One BotPlayer (player.h) in a PlayerGroup
// over one client: the library joins its slot and maps its clock to the
// match's sim clock; the bot plans every ball from the segment in effect
// with the match's model from the wire (no scene file) and pushes its
// racket pose at its sample rate, with the chosen noise, through the
// client's simulated network of the chosen delay, jitter and loss. One
// loop, one thread.
#include <CLI/CLI.hpp>
#include <cinttypes>
#include <cstdio>
#include <cstdlib>

#include "common.h"
#include "open_client.h"
#include "options.h"
#include "player_group.h"

using namespace ballsrv;
using namespace ballsrv::app;

namespace {
const char *kProgram = "ball-bot";
constexpr double kTick = 0.002;  // s: the loop's period (sampling, delivery, reading)

// The bot's ticks until the run ends (duration real s, 0: until a stop
// signal); its slot's changes printed unless quiet. *left: LEAVEs written
// (none with stay). "" or the error that ended it.
std::string play(ball_net_client *client, const PlayerParams &pp, double duration, bool quiet, bool stay,
                 BotReport *r, int *left) {
  std::string err;
  PlayerGroup group({BotPlayer(pp)}, client);
  const BotPlayer &bot = group.bots()[0];
  bool was_joined = false;
  const double start = mono_now();
  for (double next_tick = start; !stop_requested(); sleep_until(next_tick)) {
    double now = mono_now();
    if (duration > 0.0 && now - start >= duration) break;
    group.tick(now);
    if (!group.error().empty()) {
      err = group.error();
      break;
    }
    if (bot.joined() != was_joined && !quiet)
      std::printf("%s: %s match %u slot %d\n", kProgram, bot.joined() ? "holds" : "lost", pp.match, bot.slot());
    was_joined = bot.joined();
    next_tick += kTick;
    if (next_tick < now) next_tick = now + kTick;
  }
  *left = stay ? 0 : group.leave();
  *r = group.report(0);
  return err;
}
}  // namespace

int main(int argc, char **argv) {
  CLI::App cli{"ball-bot: an autonomous player for ball-server (docs/bots-and-watchers.md, \"Bots\")"};
  PlayerParams pp;
  double duration = 0.0;
  std::string stats_json;
  bool quiet = false, stay = false, every_match = false;
  DdsOptions dds_opt;
  FieldOptions<PlayerParams> player_opt;
  player_opt.add(cli, player_fields(), pp);
  cli.add_option("--duration", duration, "stop after S real seconds (0: until SIGINT/SIGTERM)")->check(CLI::Range(0.0, 1e9));
  cli.add_flag("--stay", stay, "keep the slot on exit: no LEAVE, it ends at once as if the bot vanished (the match pauses)");
  cli.add_option("--stats-json", stats_json, "write the bot's counters to FILE as JSON at exit");
  cli.add_flag("--quiet,-q", quiet, "print only errors");
  cli.add_flag("--every-match", every_match,
               "read every match on the domain, not its own alone (what the bot receives then grows with the "
               "matches: docs/client.md, \"What it costs\")");
  add_dds_options(cli, &dds_opt);
  CLI11_PARSE(cli, argc, argv);
  player_opt.apply(&pp);

  std::string err;
  install_stop_signals();
  ball_net_client *client =
      open_client(dds_opt, "ball-bot", pp.servers, [&](ball_net_config *c) {
        set_link(pp, c);
        c->followed_only = every_match ? 0 : 1;
      }, &err);
  if (!client) return fail(kProgram, err);
  int left = 0;
  BotReport r;
  err = play(client, pp, duration, quiet, stay, &r, &left);
  if (!quiet)
    std::printf("%s: match %u slot %d: %" PRIu64 " samples taken, %" PRIu64 " lost on the link, %" PRIu64
                " written, %" PRIu64 " writes refused; %" PRIu64 " segments; %" PRIu64 " balls played (%" PRIu64
                " late, %" PRIu64 " missed on purpose); %" PRIu64 " server samples refused\n",
                kProgram, r.match, r.slot, r.samples, r.lost, r.written, r.write_failures, r.segments, r.plans,
                r.late, r.missed_on_purpose, r.refused);
  int rc = err.empty() ? 0 : fail(kProgram, err);  // (a JOIN the client refused)
  if (!stats_json.empty() && !write_file(stats_json, json(r).dump(1), &err)) rc = fail(kProgram, err);
  if (stay) {  // vanish: the slot stays held until the server misses the bot (ball_net_close would LEAVE)
    std::fflush(nullptr);
    std::_Exit(rc);
  }
  // a LEAVE written just now must get out before the participant goes
  if (left) sleep_until(mono_now() + 0.2);
  ball_net_free(client);
  return rc;
}
