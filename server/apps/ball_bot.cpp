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

#include "bot.h"
#include "common.h"
#include "domain.h"
#include "link.h"
#include "sim_clock.h"

using namespace ballsrv;
using namespace ballsrv::app;

namespace {
const char *kProgram = "ball-bot";
constexpr double kTick = 0.002;        // s: the loop's period (sampling, delivery, reading)
constexpr double kJoinRetry = 0.5;     // s between JOIN requests until the slot is ours
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
  auto segments = domain->reader<SegmentOut>(dds::kSegmentTopic, dds::kSegmentProfile, {64}, &err);
  auto infos = domain->reader<MatchInfoOut>(dds::kInfoTopic, dds::kInfoProfile, {64}, &err);
  auto states = domain->reader<StateOut>(dds::kStateTopic, dds::kStateProfile, {64}, &err);
  if (!samples.valid() || !controls.valid() || !segments.valid() || !infos.valid() || !states.valid())
    return fail(kProgram, err);

  const uint32_t mid = static_cast<uint32_t>(match_id);
  SimClock clock;
  BotBrain brain;
  bool have_model = false, model_ready = false, joined = false, warned_hash = false;
  ball_model match_model{};
  Court match_court;
  int slot = player;
  int level = -1, players = 0;
  double extrapolation = -1.0, stale = -1.0;
  uint32_t newest_seq = 0, control_seq = 0;
  uint64_t sent = 0, lost = 0, written = 0, segments_seen = 0;
  Link<RacketSampleIn> link({delay, jitter, loss}, seed * 0x9e3779b97f4a7c15ull + 7);
  Rng noise_rng(seed * 31 + 5);
  MatchInfoOut info;

  auto send_control = [&](ControlKind kind, int p) {
    ControlIn c;
    c.match_id = mid;
    c.seq = ++control_seq;
    c.kind = kind;
    c.player = p;
    controls.write(c);
  };

  const double start = mono_now();
  double next_tick = start, next_sample = start, next_join = start;
  while (!stop_requested()) {
    double now = mono_now();
    if (duration > 0.0 && now - start >= duration) break;
    double real = realtime_now();

    // the match: who holds which slot, the clock, the model
    MatchInfoOut in;
    while (infos.take(&in, nullptr)) {
      if (in.match_id != mid) continue;
      info = in;
      clock.observe(in.sim_time, in.server_time, in.time_base, in.state == MatchState::playing, real);
      if (slot < 0 || !joined) {
        for (int i = 0; i < in.players; ++i)
          if (in.slots[i].held && in.slots[i].owner == me && (player < 0 || player == i)) slot = i;
      }
      bool mine = slot >= 0 && slot < in.players && in.slots[slot].held && in.slots[slot].owner == me;
      if (mine != joined && !quiet)
        std::printf("%s: %s match %u slot %d\n", kProgram, mine ? "holds" : "lost", mid, slot);
      joined = mine;
      if (!mine && player < 0 && slot >= 0 && !(in.slots[slot].held && in.slots[slot].owner == me)) slot = -1;
      // (re)build the model when the match's setup changes: the same one the server steps
      if (in.level != level || in.players != players || in.model.extrapolation_time != extrapolation ||
          in.model.stale_time != stale) {
        Court court;
        ball_model model;
        ModelSetup setup;
        setup.players = in.players;
        setup.level = static_cast<ball_level>(in.level);
        setup.extrapolation_time = in.model.extrapolation_time;
        setup.stale_time = in.model.stale_time;
        if (!court_from_model(sc.model, in.court_x[0], &court, &err) ||
            !build_match_model(sc, court, setup, &model, &err))
          return fail(kProgram, "cannot build the match's model from the scene: " + err);
        if (ball_model_hash(&model) != in.model_hash && !warned_hash) {
          std::fprintf(stderr, "%s: my model differs from the server's (hash %016" PRIx64 " vs %016" PRIx64
                               "): is --scene the match's scene?\n",
                       kProgram, ball_model_hash(&model), in.model_hash);
          warned_hash = true;
        }
        if (have_model) brain.set_model(model);
        match_model = model;
        match_court = court;
        model_ready = true;
        level = in.level;
        players = in.players;
        extrapolation = in.model.extrapolation_time;
        stale = in.model.stale_time;
      }
    }
    if (joined && model_ready && !have_model) {
      BotParams p;
      p.slot = slot;
      p.players = players;
      p.miss_rate = miss;
      p.aim_error = aim_error;
      p.move_speed = move_speed;
      p.lead = lead >= 0.0 ? lead : bot_lead(rate, delay, jitter, loss);
      p.seed = seed;
      brain.init(match_model, match_court, p);
      have_model = true;
    }
    StateOut state;
    while (states.take(&state, nullptr))
      if (state.match_id == mid)
        clock.observe(state.sim_time, state.server_time, info.time_base, state.state == MatchState::playing, real);

    if (!joined && now >= next_join) {
      send_control(ControlKind::join, player);
      next_join = now + kJoinRetry;
    }

    // the ball: replan on every newer segment
    SegmentOut seg;
    while (segments.take(&seg, nullptr)) {
      if (seg.match_id != mid || seg.seq <= newest_seq) continue;
      newest_seq = seg.seq;
      segments_seen++;
      if (have_model && clock.valid())
        brain.on_segment(seg.segment, seg.cause == Cause::serve, seg.cause_index, clock.sim_now(real));
    }

    // the racket, sampled at the bot's rate on its own clock
    if (joined && have_model && clock.valid() && now >= next_sample) {
      RacketSampleIn s;
      s.match_id = mid;
      s.player = slot;
      s.seq = static_cast<uint32_t>(++sent);
      s.capture_time = clock.sim_now(real);
      brain.pose(s.capture_time, &s.center, &s.normal);
      s.center.x += noise_rng.normal(noise);
      s.center.y += noise_rng.normal(noise);
      s.center.z += noise_rng.normal(noise);
      if (!link.send(s, now)) lost++;
      next_sample += 1.0 / rate;
      if (next_sample < now) next_sample = now + 1.0 / rate;  // after a stall: no burst
    }
    link.deliver(now, [&](const RacketSampleIn &s) {
      samples.write(s);
      written++;
    });

    next_tick += kTick;
    if (next_tick < now) next_tick = now + kTick;
    sleep_until(next_tick);
  }
  if (joined && !stay) send_control(ControlKind::leave, slot);
  const BotCounters &c = brain.counters();
  if (!quiet)
    std::printf("%s: match %u slot %d: %" PRIu64 " samples taken, %" PRIu64 " lost on the link, %" PRIu64
                " written; %" PRIu64 " segments; %" PRIu64 " balls played (%" PRIu64 " late, %" PRIu64
                " missed on purpose)\n",
                kProgram, mid, slot, sent, lost, written, segments_seen, c.plans, c.late, c.missed_on_purpose);
  if (!stats_json.empty()) {
    nlohmann::json j = {{"match", mid}, {"slot", slot}, {"samples", sent}, {"lost", lost}, {"written", written},
                        {"segments", segments_seen}, {"plans", c.plans}, {"late", c.late},
                        {"missed_on_purpose", c.missed_on_purpose}, {"participant", hex(me)}};
    std::ofstream(stats_json) << j.dump(1) << "\n";
  }
  // a LEAVE written just now must get out before the participant goes
  if (joined && !stay) sleep_until(mono_now() + 0.2);
  return 0;
}
