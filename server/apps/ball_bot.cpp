// ball-bot: an autonomous player (docs/server.md, "Bots"). It joins a slot,
// maps its clock to the match's sim clock, plans every ball from the
// server's segments with ball_predict (BotBrain), and sends its racket pose
// at its sample rate through a link with the chosen delay, jitter, loss and
// noise. One loop, one thread.
#include <CLI/CLI.hpp>
#include <cinttypes>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>

#include "common.h"
#include "domain.h"
#include "player.h"

using namespace ballsrv;
using namespace ballsrv::app;

namespace {
const char *kProgram = "ball-bot";
constexpr double kTick = 0.002;  // s: the loop's period (sampling, delivery, reading)
}  // namespace

int main(int argc, char **argv) {
  CLI::App cli{"ball-bot: an autonomous player for ball-server (docs/server.md, \"Bots\")"};
  long match_id = 0;
  int player = -1;
  double rate = 30.0, delay = 0.0, jitter = 0.0, loss = 0.0, noise = 0.0;
  double miss = 0.0, aim_error = 0.0, lead = -1.0, duration = 0.0, move_speed = 12.0;
  uint64_t seed = 1;
  std::string scene, stats_json;
  bool quiet = false, stay = false;
  DdsOptions dds_opt;
  cli.add_option("--match", match_id, "match id")->capture_default_str()->check(CLI::Range(0L, 4294967295L));
  cli.add_option("--player", player, "player slot, -1: any free one")->capture_default_str()->check(CLI::Range(-1, 3));
  cli.add_option("--rate", rate, "racket samples per second, [2, 120]")->capture_default_str()->check(CLI::Range(2.0, 120.0));
  cli.add_option("--delay", delay, "s added to every sample's trip")->capture_default_str()->check(CLI::Range(0.0, 10.0));
  cli.add_option("--jitter", jitter, "s: each sample is up to this much later again (uniform)")
      ->capture_default_str()->check(CLI::Range(0.0, 1.0));
  cli.add_option("--loss", loss, "probability a sample is lost, [0, 0.9]")->capture_default_str()->check(CLI::Range(0.0, 0.9));
  cli.add_option("--noise", noise, "m: Gaussian tracker noise on the racket centre")->capture_default_str()->check(CLI::Range(0.0, 1.0));
  cli.add_option("--miss", miss, "skill: probability of missing a ball, [0, 1]")->capture_default_str()->check(CLI::Range(0.0, 1.0));
  cli.add_option("--aim-error", aim_error, "skill: m of Gaussian error on the planned contact")
      ->capture_default_str()->check(CLI::Range(0.0, 2.0));
  cli.add_option("--move-speed", move_speed, "m/s the racket travels between strokes")->capture_default_str()->check(CLI::Range(0.5, 100.0));
  cli.add_option("--lead", lead, "s on the stroke line before contact (default: from rate, delay, jitter, loss)")
      ->check(CLI::Range(0.0, 2.0));
  cli.add_option("--seed", seed, "seed of every random draw")->capture_default_str();
  cli.add_option("--scene", scene, "the match's scene (for ball_predict): a file, a libball scene name, default");
  cli.add_option("--duration", duration, "stop after S real seconds (0: until SIGINT/SIGTERM)")->check(CLI::Range(0.0, 1e9));
  cli.add_flag("--stay", stay, "keep the slot on exit (no LEAVE): the match pauses as if the bot vanished");
  cli.add_option("--stats-json", stats_json, "write the bot's counters to FILE as JSON at exit");
  cli.add_flag("--quiet,-q", quiet, "print only errors");
  add_dds_options(cli, &dds_opt);
  CLI11_PARSE(cli, argc, argv);

  std::string err;
  ball_scene sc;
  if (!load_scene(scene, &sc, &err)) return fail(kProgram, err);
  install_stop_signals();
  auto domain = dds::Domain::open(dds_opt.domain, find_profile(dds_opt.profile), dds_opt.participant,
                                  "ball-bot", &err);
  if (!domain) return fail(kProgram, err);
  const ParticipantId me = domain->id();
  auto samples = domain->writer<RacketSampleIn>(dds::kRacketTopic, dds::kRacketProfile, {kMaxPlayers}, &err);
  auto controls = domain->writer<ControlIn>(dds::kControlTopic, dds::kControlProfile, {1}, &err);
  auto segments = domain->reader<SegmentOut>(dds::kSegmentTopic, dds::kSegmentProfile, {dds::kClientRoom}, &err);
  auto infos = domain->reader<MatchInfoOut>(dds::kInfoTopic, dds::kInfoProfile, {dds::kClientRoom}, &err);
  auto states = domain->reader<StateOut>(dds::kStateTopic, dds::kStateProfile, {dds::kClientRoom}, &err);
  if (!samples.valid() || !controls.valid() || !segments.valid() || !infos.valid() || !states.valid())
    return fail(kProgram, err);

  PlayerParams pp;
  pp.match = static_cast<uint32_t>(match_id);
  pp.player = player;
  pp.rate = rate;
  pp.delay = delay;
  pp.jitter = jitter;
  pp.loss = loss;
  pp.noise = noise;
  pp.miss = miss;
  pp.aim_error = aim_error;
  pp.move_speed = move_speed;
  pp.lead = lead;
  pp.seed = seed;
  BotPlayer bot(sc, me, pp);
  std::vector<RacketSampleIn> out_samples;
  std::vector<ControlIn> out_controls;
  bool was_joined = false, warned_hash = false;

  const double start = mono_now();
  double next_tick = start;
  while (!stop_requested()) {
    double now = mono_now();
    if (duration > 0.0 && now - start >= duration) break;
    double real = realtime_now();
    MatchInfoOut info;
    while (infos.take(&info, nullptr))
      if (!bot.on_info(info, real)) return fail(kProgram, "cannot build the match's model from the scene: " + bot.error());
    if (bot.joined() != was_joined && !quiet)
      std::printf("%s: %s match %u slot %d\n", kProgram, bot.joined() ? "holds" : "lost", pp.match, bot.slot());
    was_joined = bot.joined();
    if (bot.counters().hash_differs && !warned_hash) {
      std::fprintf(stderr, "%s: my model differs from the server's (hash %016" PRIx64 " vs %016" PRIx64
                           "): is --scene the match's scene?\n",
                   kProgram, bot.model_hash(), bot.server_hash());
      warned_hash = true;
    }
    StateOut state;
    while (states.take(&state, nullptr)) bot.on_state(state, real);
    SegmentOut seg;
    while (segments.take(&seg, nullptr)) bot.on_segment(seg, real);
    out_samples.clear();
    out_controls.clear();
    bot.tick(now, real, &out_samples, &out_controls);
    for (const auto &c : out_controls) controls.write(c);
    for (const auto &s : out_samples) samples.write(s);

    next_tick += kTick;
    if (next_tick < now) next_tick = now + kTick;
    sleep_until(next_tick);
  }
  ControlIn bye;
  bool left = !stay && bot.leave(&bye);
  if (left) controls.write(bye);
  const PlayerCounters &pc = bot.counters();
  const BotCounters &c = bot.brain_counters();
  if (!quiet)
    std::printf("%s: match %u slot %d: %" PRIu64 " samples taken, %" PRIu64 " lost on the link, %" PRIu64
                " written; %" PRIu64 " segments; %" PRIu64 " balls played (%" PRIu64 " late, %" PRIu64
                " missed on purpose)\n",
                kProgram, pp.match, bot.slot(), pc.taken, pc.lost, pc.delivered, pc.segments, c.plans, c.late,
                c.missed_on_purpose);
  if (!stats_json.empty()) {
    nlohmann::json j = {{"match", pp.match}, {"slot", bot.slot()}, {"samples", pc.taken}, {"lost", pc.lost},
                        {"written", pc.delivered}, {"segments", pc.segments}, {"plans", c.plans}, {"late", c.late},
                        {"missed_on_purpose", c.missed_on_purpose}, {"participant", hex(me)}};
    std::ofstream(stats_json) << j.dump(1) << "\n";
  }
  // a LEAVE written just now must get out before the participant goes
  if (left) sleep_until(mono_now() + 0.2);
  dds::set_exit_status_if_stuck(0);  // all is written: a stuck DDS teardown still ends well (domain.h)
  return 0;
}
