// ball_flood: a hostile client for the integration tests. Participant A
// joins both slots of match 0 and keeps its rackets parked off the court
// with well-formed samples at 10 Hz; once the match plays it sends, with
// --per-kind N, N samples of every malformed kind the server must drop
// (interleaved, about 1250 a second), some from a second participant B that
// holds nothing. With --burst M it then writes M more out_of_range samples
// in one go, faster than the server's reader keeps them (its history holds
// 64 a slot between two frames): DDS must count what it refuses. It writes
// what it sent, by kind, as JSON. With --key-flood N, B writes N samples
// every 10 ms under A's own keys (slot 0 and 1 of match 0) while the match
// plays, evenly, in chunks between which the loop sleeps: a stranger's flood
// must not make A's slots vanish. (Written 4000 at a time with A's sample
// right behind each burst, A's samples met the server's socket full, burst
// after burst: a phase no other process could keep, and a pause in a run of
// several.)
#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>

#include "ball/vec3.h"
#include "common.h"
#include "domain.h"
#include "open_domain.h"
#include "sim_clock.h"

using namespace ballsrv;
using namespace ballsrv::app;

namespace {
const char *kProgram = "ball_flood";
// each kind lands on the drop reason of the same name
const SampleResult kKinds[] = {SampleResult::unknown_match, SampleResult::bad_slot, SampleResult::not_joined,
                               SampleResult::not_owner,     SampleResult::nonfinite, SampleResult::zero_normal,
                               SampleResult::out_of_range,  SampleResult::duplicate, SampleResult::out_of_order,
                               SampleResult::stale};
}  // namespace

int main(int argc, char **argv) {
  CLI::App cli{"ball_flood: well-formed parked rackets on match 0, then malformed samples of every kind"};
  long per_kind = 0, burst = 0, key_flood = 0;
  double duration = 12.0, interval = 0.0008, rate = 10.0;
  std::string out_json;
  DdsOptions dds_opt;
  cli.add_option("--per-kind", per_kind, "malformed samples of each kind (0: only the parked rackets)");
  cli.add_option("--duration", duration, "s to run");
  cli.add_option("--interval", interval, "s between malformed samples");
  cli.add_option("--burst", burst, "then this many out_of_range samples at once");
  cli.add_option("--rate", rate, "A's parked samples per second and slot")->check(CLI::Range(2.0, 120.0));
  cli.add_option("--key-flood", key_flood, "B writes this many samples every 10 ms under A's keys once the match plays");
  cli.add_option("--out", out_json, "JSON file of what was sent");
  add_dds_options(cli, &dds_opt);
  CLI11_PARSE(cli, argc, argv);

  std::string err;
  install_stop_signals();
  auto a = open_domain(dds_opt, "flood A", &err);
  auto b = a ? open_domain(dds_opt, "flood B", &err) : nullptr;
  if (!a || !b) return fail(kProgram, err);
  auto a_samples = a->writer<RacketSampleIn>(dds::kRacketTopic, dds::kRacketProfile, {16}, &err);
  auto a_controls = a->writer<ControlIn>(dds::kControlTopic, dds::kControlProfile, {1}, &err);
  auto a_infos = a->reader<MatchInfoOut>(dds::kInfoTopic, dds::kInfoProfile, {dds::kClientRoom}, &err);
  auto a_states = a->reader<StateOut>(dds::kStateTopic, dds::kStateProfile, {dds::kClientRoom}, &err);
  auto b_samples = b->writer<RacketSampleIn>(dds::kRacketTopic, dds::kRacketProfile, {16}, &err);
  if (!a_samples.valid() || !a_controls.valid() || !a_infos.valid() || !a_states.valid() || !b_samples.valid())
    return fail(kProgram, err);

  SimClock clock;
  MatchInfoOut info;
  bool have_info = false;
  uint32_t seq[2] = {0, 0}, control_seq = 0;
  RacketSampleIn last_valid[2];
  std::map<std::string, long> sent;
  long valid = 0, flood_index = 0, burst_sent = 0, write_failures = 0;
  auto put = [&](auto &writer, const auto &sample) {  // every write checked: a refused one fails the run
    if (!writer.write(sample)) write_failures++;
  };
  const double start = mono_now();
  double next_valid = start, next_join = start, next_bad = start, flood_started = -1.0, first_valid = -1.0;
  double key_flood_from = -1.0;
  long key_flood_sent = 0;
  constexpr long kKeyFloodChunk = 200;  // samples written at once (1 ms at 200,000 a second)
  bool playing = false;

  auto parked = [&](int slot, double t) {
    RacketSampleIn s;
    s.match_id = 0;
    s.player = slot;
    s.seq = ++seq[slot];
    s.capture_time = t;
    // behind its own baseline, off the side: inside the racket margin (docs/protocol.md)
    s.center = ball_v3(slot == 0 ? info.court_x[0] - 4.0 : info.court_x[1] + 4.0, 1.0, info.court_z[0] - 4.0 - slot);
    s.normal = ball_v3(1, 0, 0);
    return s;
  };

  while (!stop_requested() && mono_now() - start < duration) {
    double now = mono_now(), real = realtime_now();
    MatchInfoOut in;
    while (a_infos.take(&in, nullptr))
      if (in.match_id == 0) {
        info = in;
        have_info = true;
        clock.observe(in.sim_time, in.server_time, in.settings.time_base, in.state == MatchState::playing, real);
      }
    StateOut st;
    while (a_states.take(&st, nullptr))
      if (st.match_id == 0) {
        clock.observe(st.sim_time, st.server_time, info.settings.time_base, st.state == MatchState::playing, real);
        playing = st.state == MatchState::playing;
      }
    if (!have_info) {
      sleep_until(now + 0.005);
      continue;
    }
    bool mine = info.slots[0].held && info.slots[0].owner == a->id() && info.slots[1].held &&
                info.slots[1].owner == a->id();
    if (!mine && now >= next_join) {
      for (int slot = 0; slot < 2; ++slot) {
        ControlIn c;
        c.match_id = 0;
        c.seq = ++control_seq;
        c.kind = ControlKind::join;
        c.player = slot;
        put(a_controls, c);
      }
      next_join = now + 0.5;
    }
    double sim = clock.sim_now(real);
    if (mine && now >= next_valid) {
      for (int slot = 0; slot < 2; ++slot) {
        last_valid[slot] = parked(slot, sim);
        put(a_samples, last_valid[slot]);
        valid++;
      }
      // no catching up: a burst would repeat one capture time (a duplicate)
      next_valid = now + 1.0 / rate;
    }
    // the match plays and has taken the parked rackets for a while (the
    // duplicate kind repeats an accepted sample)
    if (info.state == MatchState::playing) playing = true;
    if (mine && playing && first_valid < 0.0 && valid > 0) first_valid = now;
    bool ready = mine && playing && first_valid > 0.0 && now - first_valid > 0.5;
    if (ready && flood_started < 0.0) flood_started = now;
    // the flood, once the match plays and both parked rackets are accepted
    while (per_kind > 0 && ready && flood_index < per_kind * 10 && now >= next_bad) {
      SampleResult kind = kKinds[flood_index % 10];
      RacketSampleIn s = parked(0, sim);
      bool from_b = false;
      // a sample that is not of A's slot-0 stream leaves that stream's seq as it was (a skipped
      // seq is a sample lost on the way, docs/protocol.md)
      switch (kind) {
        case SampleResult::unknown_match: s.match_id = 999; seq[0]--; break;
        case SampleResult::bad_slot: s.player = 7; seq[0]--; break;
        case SampleResult::not_joined: s.match_id = 1; seq[0]--; break;
        case SampleResult::not_owner: from_b = true; seq[0]--; break;
        case SampleResult::nonfinite: s.center.x = std::nan(""); break;
        case SampleResult::zero_normal: s.normal = ball_v3(0, 0, 0); break;
        case SampleResult::out_of_range: s.center.y = 1e4; break;
        case SampleResult::duplicate: s = last_valid[0]; seq[0]--; break;  // the very same sample again
        case SampleResult::out_of_order: s.seq = 1; seq[0]--; break;
        case SampleResult::stale: s.capture_time = sim - 10.0; break;
        default: break;
      }
      put(from_b ? b_samples : a_samples, s);
      sent[name_of(kind)]++;
      flood_index++;
      next_bad += interval;
    }
    if (!ready) next_bad = now;
    // the burst, once the flood is out and the server had 0.5 s for it
    if (ready && burst_sent == 0 && burst > 0 && flood_index >= per_kind * 10 && now >= next_bad + 0.5) {
      for (; burst_sent < burst; ++burst_sent) {
        RacketSampleIn s = parked(0, sim);
        s.center.y = 1e4;  // out_of_range
        put(a_samples, s);
      }
    }
    // the key flood: B under A's keys, key_flood per 10 ms (as far as this process keeps up)
    if (key_flood > 0 && ready) {
      if (key_flood_from < 0.0) key_flood_from = now;
      long owed = static_cast<long>((now - key_flood_from) * 100.0 * static_cast<double>(key_flood)) - key_flood_sent;
      for (long i = 0; i < std::min(owed, kKeyFloodChunk); ++i, ++key_flood_sent) {
        int slot = static_cast<int>(key_flood_sent % 2);
        RacketSampleIn s = parked(slot, sim);
        seq[slot]--;  // A's own stream goes on as it was
        s.seq = static_cast<uint32_t>(key_flood_sent);
        put(b_samples, s);
      }
      sent["key_flood"] = key_flood_sent;
    }
    // a pause after the work, whatever it took (the server drains its socket meanwhile)
    sleep_until(std::min(next_valid, mono_now() + 0.0002));
  }
  nlohmann::json j;
  j["valid"] = valid;
  j["flood_started"] = flood_started < 0 ? -1.0 : flood_started - start;
  j["sent"] = sent;
  j["malformed"] = flood_index;
  j["burst"] = burst_sent;
  j["write_failures"] = write_failures;
  // what it last heard, to tell why a flood did not start
  j["last_info"] = {{"have", have_info},
                    {"state", name_of(info.state)},
                    {"held", {info.slots[0].held, info.slots[1].held}},
                    {"samples", {info.slots[0].samples, info.slots[1].samples}},
                    {"revision", info.revision}};
  if (!out_json.empty() && !write_file(out_json, j.dump(1), &err)) return fail(kProgram, err);
  std::printf("%s: %ld parked samples, %ld malformed, %ld writes refused\n", kProgram, valid, flood_index,
              write_failures);
  std::fflush(stdout);
  int status = (per_kind > 0 && flood_index < per_kind * 10) || burst_sent < burst || write_failures ? 1 : 0;
  dds::set_exit_status_if_stuck(status);  // two participants in one process: the case of Fast-DDS#6193
  return status;
}
