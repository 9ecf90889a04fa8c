// ball_intrude: a hostile participant of the DDS Security tests
// (docs/security.md). One participant, with or without a certificate, that
// writes into match --match from the DDS partition --partition: a JOIN for
// slot 0 every 0.5 s and a well-formed racket sample for slot 0 at --rate Hz,
// on the court and slow, so that only who writes it can refuse it (with
// --wait-match only once the server's readers matched its writers; with
// --wait-held, at 30 Hz until the server took one of its samples for its
// slot, so that a flood begins once the server hears it). It
// listens to the server topics and writes as JSON what it sent and what it
// heard: a stranger hears nothing, a player of another match is refused by
// the server as `not_permitted`. With --junk N it cycles through N made-up
// match ids from --match on, a JOIN and a sample for each: they must not
// fill the server's readers (with --create its controls are CREATEs: a
// server takes max_creates of them, the rest take their writer's share; with --leave SLOT they are LEAVEs
// of that slot, a player's that the stranger is not). With --as-server ID --forge it
// forges the server topics of match --match itself instead (the review's
// findings, from writers as strong as --strength PROFILE of the QoS file
// says): a MatchInfo with level 99, a segment with seq 0xFFFFFFFF and ball
// states whose clock pairs are 10,000 s ahead, every 0.2 s; and, with
// --decoy ID, a well-formed copy of the match's MatchInfo as match ID
// whose scene is --scene-name (a path), and as match ID + 1 one whose scene
// is no name at all (bytes that are not UTF-8). With --as-server ID it is a server instead
// (under DDS Security one certified as a server, but not as server ID): it
// writes no samples, and every 0.2 s writes a copy of the newest MatchInfo
// it heard, as match --match of server ID (with --junk N, as the N match
// ids from --match on: made-up matches); a client that bound ID to
// another certificate must refuse every copy. With --status it is also a
// server heard alive (a ServerStatus as ID every 0.2 s, asserting its
// writers' liveliness), with --newer-term its copies claim the next
// round's term (the match's owner yields to them), and with --copies-for S
// it writes copies for S s only and then goes quiet, alive, to --duration.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "ball/vec3.h"
#include "cluster.h"
#include "common.h"
#include "domain.h"
#include "open_domain.h"

using namespace ballsrv;
using namespace ballsrv::app;

namespace {
const char *kProgram = "ball_intrude";
}

int main(int argc, char **argv) {
  CLI::App cli{"ball_intrude: JOIN and racket samples into a match from a chosen partition; what it heard"};
  uint32_t match = 0;
  double duration = 8.0, rate = 100.0;
  std::string partition, out_json;
  DdsOptions dds_opt;
  cli.add_option("--match", match, "the match written into");
  cli.add_option("--partition", partition, "the DDS partition of the writers (\"\": the default one)");
  cli.add_option("--rate", rate, "racket samples per s")->check(CLI::Range(1.0, 20000.0));
  cli.add_option("--duration", duration, "s to run");
  cli.add_option("--out", out_json, "JSON file of what was sent and heard");
  bool wait_match = false;
  uint32_t junk = 0;
  cli.add_option("--junk", junk, "write under this many match ids from --match on, in turn (made-up ids)");
  long as_server = -1;
  cli.add_option("--as-server", as_server, "write MatchInfo copies as this server id instead of samples")
      ->check(CLI::Range(0L, static_cast<long>(UINT32_MAX)));
  bool forge = false;
  std::string strength, scene_name;
  long decoy = -1;
  cli.add_flag("--forge", forge, "with --as-server: forge match --match's own server topics");
  cli.add_option("--strength", strength, "with --forge: the data_writer profile of the writers' ownership strength");
  cli.add_option("--decoy", decoy, "with --forge: also a well-formed MatchInfo copy as this match id")
      ->check(CLI::Range(0L, static_cast<long>(UINT32_MAX)));
  cli.add_option("--scene-name", scene_name, "with --decoy: the scene it names");
  bool status = false, newer_term = false;
  double copies_for = HUGE_VAL;
  cli.add_flag("--status", status, "with --as-server: also a ServerStatus as that server, every 0.2 s");
  cli.add_flag("--newer-term", newer_term, "with --as-server: the copies claim the next round's term");
  cli.add_option("--copies-for", copies_for, "with --as-server: s of copies, then quiet (alive) to --duration");
  bool create = false;
  cli.add_flag("--create", create, "its controls are CREATEs (scene tennis) instead of JOINs");
  long leave = -1, join_slot = 0;
  cli.add_option("--leave", leave, "its controls are LEAVEs of this slot instead of JOINs (another's: refused)");
  cli.add_option("--join", join_slot, "the slot its JOINs name")->check(CLI::Range(-1, 3));
  cli.add_flag("--wait-match", wait_match, "send only once a reader matched both writers");
  bool wait_held = false;
  cli.add_flag("--wait-held", wait_held,
               "samples at 30 Hz at most until a MatchInfo shows slot --join held by this participant with one of "
               "its samples taken (the server's readers matched both writers), --rate after");
  add_dds_options(cli, &dds_opt);
  CLI11_PARSE(cli, argc, argv);

  std::string err;
  install_stop_signals();
  auto d = open_domain(dds_opt, kProgram, &err);
  if (!d) return fail(kProgram, err);
  int keys = static_cast<int>(std::max<uint32_t>(1, junk));
  dds::Writer<RacketSampleIn> samples;
  dds::Writer<ControlIn> controls;
  dds::Writer<MatchInfoOut> forged;
  dds::Writer<StatusOut> forged_status;
  dds::Writer<SegmentOut> forged_segments;
  dds::Writer<StateOut> forged_states;
  // and the same in the match's own partition (docs/protocol.md, "A match's own partition")
  dds::Writer<MatchInfoOut> forged_here;
  dds::Writer<SegmentOut> forged_segments_here;
  dds::Writer<StateOut> forged_states_here;
  const char *by = strength.empty() ? nullptr : strength.c_str();
  if (as_server >= 0) {
    forged = d->writer<MatchInfoOut>(dds::kInfoTopic, dds::kInfoProfile, {std::max(16, static_cast<int>(junk))}, &err, by);
    if (forged.valid() && forge)
      forged_segments = d->writer<SegmentOut>(dds::kSegmentTopic, dds::kSegmentProfile, {16}, &err, by);
    if (forged_segments.valid())
      forged_states = d->writer<StateOut>(dds::kStateTopic, dds::kStateProfile, {16}, &err, by);
    if (forged.valid() && status)
      forged_status = d->writer<StatusOut>(dds::kStatusTopic, dds::kStatusProfile, {1}, &err, by);
    if (!forged.valid() || (forge && !forged_states.valid()) || (status && !forged_status.valid()))
      return fail(kProgram, err);
    if (forge) {
      dds::Sizing here{16, 0, dds::match_partition(static_cast<uint32_t>(match))};
      forged_here = d->writer<MatchInfoOut>(dds::kInfoTopic, dds::kInfoProfile, here, &err, by);
      forged_segments_here = d->writer<SegmentOut>(dds::kSegmentTopic, dds::kSegmentProfile, here, &err, by);
      forged_states_here = d->writer<StateOut>(dds::kStateTopic, dds::kStateProfile, here, &err, by);
      if (!forged_here.valid() || !forged_segments_here.valid() || !forged_states_here.valid())
        return fail(kProgram, err);
    }
  } else {
    samples = d->writer<RacketSampleIn>(dds::kRacketTopic, dds::kRacketProfile, {keys, 0, partition}, &err);
    if (samples.valid())
      controls = d->writer<ControlIn>(dds::kControlTopic, dds::kControlProfile, {keys, 0, partition}, &err);
    if (!samples.valid() || !controls.valid()) return fail(kProgram, err);
  }
  auto infos = d->reader<MatchInfoOut>(dds::kInfoTopic, dds::kInfoProfile, {dds::kClientRoom}, &err);
  auto states = d->reader<StateOut>(dds::kStateTopic, dds::kStateProfile, {dds::kClientRoom}, &err);
  if (!infos.valid() || !states.valid()) return fail(kProgram, err);

  long sent_samples = 0, sent_controls = 0, sent_infos = 0, refused = 0, heard_infos = 0, heard_states = 0;
  MatchInfoOut newest;  // the newest MatchInfo heard
  bool heard_info = false;
  uint32_t claimed_term = 0;  // --newer-term: the round above the first MatchInfo heard (0: none yet)
  uint32_t seq = 0, control_seq = 0;
  bool held = !wait_held;           // --wait-held: the server took one of our samples for slot --join
  long samples_before_held = 0;
  double held_after = -1.0;         // s from the start (-1: never)
  double sim = 0.0;  // the newest sim time heard (0: none)
  const double start = mono_now();
  double next_sample = start, next_join = start;
  while (!stop_requested() && mono_now() - start < duration) {
    double now = mono_now();
    MatchInfoOut in;
    while (infos.take(&in, nullptr)) {
      heard_infos++;
      if (!held && in.match_id == match && join_slot >= 0) {
        const SlotInfo &slot = in.slots[static_cast<size_t>(join_slot)];
        if (slot.held && slot.owner == d->id() && slot.samples > 0) held = true, held_after = now - start;
      }
      // --forge: the match's own, from its server (never our own forgeries back)
      // (else any but its own copies: another match's, or match --match's of another server)
      if (forge ? in.match_id == match && in.server_id != static_cast<uint32_t>(as_server)
                : in.match_id != match || in.server_id != static_cast<uint32_t>(as_server))
        newest = in, heard_info = true;
    }
    StateOut st;
    while (states.take(&st, nullptr)) {
      heard_states++;
      if (st.match_id == match && st.server_id != static_cast<uint32_t>(as_server)) sim = st.sim_time;
    }
    if (forge) {  // the match's own topics, forged
      if (heard_info) {
        MatchInfoOut f = newest;
        f.server_id = static_cast<uint32_t>(as_server);
        f.level = 99;
        bool ok = forged.write(f) & forged_here.write(f);
        if (decoy >= 0) {
          MatchInfoOut g = newest;
          g.match_id = static_cast<uint32_t>(decoy);
          g.server_id = static_cast<uint32_t>(as_server);
          g.scene = scene_name;
          ok = forged.write(g) && ok;
          MatchInfoOut h = g;  // and the next one's scene is not a name at all (not UTF-8)
          h.match_id = static_cast<uint32_t>(decoy + 1);
          h.scene = "\xff\xfe\x80<b>";
          ok = forged.write(h) && ok;
        }
        SegmentOut seg;
        seg.match_id = match;
        seg.server_id = static_cast<uint32_t>(as_server);
        seg.seq = 0xFFFFFFFFu;
        seg.segment.t0 = sim;
        seg.segment.p0 = ball_v3(0.0, 5.0, 0.0);
        ok = forged_segments.write(seg) && forged_segments_here.write(seg) && ok;
        StateOut far;
        far.match_id = match;
        far.server_id = static_cast<uint32_t>(as_server);
        far.sim_time = sim + 10000.0;
        far.server_time = realtime_now();
        far.segment_seq = 0xFFFFFFFFu;
        ok = forged_states.write(far) && forged_states_here.write(far) && ok;
        if (ok) sent_infos++;
        else refused++;
      }
      sleep_until(now + 0.2);
      continue;
    }
    if (forged.valid()) {  // a server: copies of what it heard, as --as-server's match --match (and on, --junk)
      const uint32_t id = static_cast<uint32_t>(as_server);
      if (status) {
        StatusOut alive;
        alive.server_id = id;
        alive.server_time = realtime_now();
        alive.uptime = now - start;
        if (!forged_status.write(alive)) refused++;
      }
      if (!claimed_term && heard_info) claimed_term = next_term(newest.term, id);  // (never 0)
      for (uint32_t k = 0; heard_info && now - start < copies_for && k < std::max(1u, junk); ++k) {
        MatchInfoOut f = newest;
        f.match_id = match + k;
        f.server_id = id;
        if (newer_term) f.term = claimed_term;
        if (forged.write(f)) sent_infos++;
        else refused++;
      }
      sleep_until(now + 0.2);
      continue;
    }
    if (wait_match && (samples.matched() < 1 || controls.matched() < 1)) {
      next_sample = next_join = now + 0.01;
      sleep_until(next_sample);
      continue;
    }
    uint32_t id = junk ? match + static_cast<uint32_t>(sent_samples % junk) : match;
    if (now >= next_join || (junk && now >= next_sample)) {  // made-up ids: a JOIN with every sample
      ControlIn c;
      c.match_id = id;
      c.seq = ++control_seq;
      c.kind = create ? ControlKind::create : leave >= 0 ? ControlKind::leave : ControlKind::join;
      c.player = static_cast<int>(leave >= 0 ? leave : join_slot);
      c.scene = "tennis";
      if (controls.write(c)) sent_controls++;
      else refused++;
      next_join = now + 0.5;
    }
    if (now >= next_sample) {
      RacketSampleIn s;
      s.match_id = id;
      s.player = 0;
      s.seq = ++seq;
      s.capture_time = sim + (now - start) * 1e-3;  // moves on, never ahead of the server's clock by much
      s.center = ball_v3(2.0, 1.0, 4.0);             // on slot 0's side of the default court
      s.normal = ball_v3(1, 0, 0);
      if (samples.write(s)) sent_samples++, samples_before_held += held ? 0 : 1;
      else refused++;
      next_sample += held ? 1.0 / rate : std::max(1.0 / rate, 1.0 / 30.0);
    }
    sleep_until(std::min(next_sample, next_join));
  }
  nlohmann::json j = {{"samples", sent_samples}, {"controls", sent_controls}, {"infos", sent_infos},
                      {"write_failures", refused},
                      {"samples_before_held", samples_before_held}, {"held_after", held_after},
                      {"heard_infos", heard_infos}, {"heard_states", heard_states},
                      {"participant", hex(d->id())}};
  if (!out_json.empty() && !write_file(out_json, j.dump(1), &err)) return fail(kProgram, err);
  std::printf("%s: %ld samples, %ld controls sent, %ld refused; heard %ld infos, %ld states\n", kProgram,
              sent_samples, sent_controls, refused, heard_infos, heard_states);
  std::fflush(stdout);
  return refused ? 1 : 0;
}
