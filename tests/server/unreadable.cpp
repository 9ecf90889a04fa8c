// ball_unreadable: a hostile participant of the integration tests that
// writes, on every topic a server or a client reads, samples that no IDL
// type writes (docs/protocol.md, "What the server does with a racket
// sample", reason `malformed`): the encapsulation of XCDR2, which Fast CDR
// 1.0 does not read; a first byte of the encapsulation other than 0; a
// sample cut short; a boolean byte of 2 (the types with booleans); and, on
// the racket topic, a sample of a made-up match in plain CDR with the
// parameter-list flag, which Fast CDR reads as plain CDR (the server's
// door must judge it as such: `unknown_match`). Each kind --count times,
// every --interval s, once a server's MatchInfo was heard and its writers
// matched the server's readers (with --clients, a client's readers of
// segments and events too). It writes what it sent, by topic (racket,
// control, info, segment, event, status) and kind, as JSON.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>

#include "ball/vec3.h"
#include "common.h"
#include "testing/raw.h"
#include "open_domain.h"

using namespace ballsrv;
using namespace ballsrv::app;

namespace {
const char *kProgram = "ball_unreadable";

using Bytes = std::vector<uint8_t>;

// The index of the one byte in which two encodings differ (a boolean's): -1 if not one.
long one_byte_apart(const Bytes &a, const Bytes &b) {
  long at = -1;
  if (a.size() != b.size()) return -1;
  for (size_t i = 0; i < a.size(); ++i)
    if (a[i] != b[i]) {
      if (at >= 0) return -1;
      at = static_cast<long>(i);
    }
  return at;
}

// The kinds of one topic's unreadable samples from one well-formed sample,
// and, where the type has a boolean, the same sample with it the other way.
std::map<std::string, Bytes> kinds_of(const Bytes &ok, const Bytes &flipped) {
  std::map<std::string, Bytes> k;
  Bytes b = ok;
  b[1] = 0x07;  // XCDR2, little endian
  k["xcdr2"] = b;
  b = ok;
  b[0] = 0x01;
  k["encapsulation"] = b;
  k["cut_short"] = Bytes(ok.begin(), ok.begin() + 10);
  long at = one_byte_apart(ok, flipped);
  if (at >= 0) {
    b = ok;
    b[static_cast<size_t>(at)] = 2;
    k["boolean_2"] = b;
  }
  return k;
}
}  // namespace

int main(int argc, char **argv) {
  CLI::App cli{"ball_unreadable: samples no IDL type writes, on every topic a server or client reads"};
  long count = 20;
  double interval = 0.02, duration = 10.0;
  std::string out_json;
  DdsOptions dds_opt;
  cli.add_option("--count", count, "samples of each kind on each topic")->check(CLI::Range(1L, 100000L));
  cli.add_option("--interval", interval, "s between two rounds of every kind");
  cli.add_option("--duration", duration, "s to run at most");
  cli.add_option("--out", out_json, "JSON file of what was sent");
  bool clients = false;
  cli.add_flag("--clients", clients, "wait for a client's readers of segments and events too");
  add_dds_options(cli, &dds_opt);
  CLI11_PARSE(cli, argc, argv);

  std::string err;
  install_stop_signals();
  // a participant that listens, and one whose topics carry raw payloads (one type per name)
  auto ear = open_domain(dds_opt, "unreadable ear", &err);
  auto raw = ear ? open_domain(dds_opt, "unreadable", &err) : nullptr;
  if (!ear || !raw) return fail(kProgram, err);
  auto infos = ear->reader<MatchInfoOut>(dds::kInfoTopic, dds::kInfoProfile, {dds::kClientRoom}, &err);
  if (!infos.valid()) return fail(kProgram, err);

  struct Topic {
    const char *name;  // in the JSON: racket, control, info, segment, event, status
    dds::RawWriter writer;
    std::map<std::string, Bytes> kinds;
  };
  std::vector<Topic> topics;
  auto add = [&](const char *name, dds::RawWriter w, const Bytes &ok, const Bytes &flipped) {
    if (!w.valid()) return false;
    topics.push_back(Topic{name, w, kinds_of(ok, flipped)});
    return true;
  };
  RacketSampleIn s;
  s.match_id = 999;  // made up: were one read, nothing would take it
  s.normal = ball_v3(1, 0, 0);
  ControlIn c;
  c.match_id = 999;
  c.kind = ControlKind::join;
  MatchInfoOut i, i2;
  i.match_id = i2.match_id = 999;
  i2.slots[0].held = true;
  SegmentOut g, g2;
  g.match_id = g2.match_id = 999;
  g2.segment.grounded = 1;
  EventOut e, e2;
  e.match_id = e2.match_id = 999;
  e2.in_play = true;
  StatusOut t, t2;
  t.server_id = t2.server_id = 999;
  t2.standby = true;
  bool ok =
      add("racket", dds::raw_writer<RacketSampleIn>(*raw, dds::kRacketTopic, dds::kRacketProfile, &err),
          dds::serialized(s), dds::serialized(s)) &&
      add("control", dds::raw_writer<ControlIn>(*raw, dds::kControlTopic, dds::kControlProfile, &err),
          dds::serialized(c), dds::serialized(c)) &&
      add("info", dds::raw_writer<MatchInfoOut>(*raw, dds::kInfoTopic, dds::kInfoProfile, &err),
          dds::serialized(i), dds::serialized(i2)) &&
      add("segment", dds::raw_writer<SegmentOut>(*raw, dds::kSegmentTopic, dds::kSegmentProfile, &err),
          dds::serialized(g), dds::serialized(g2)) &&
      add("event", dds::raw_writer<EventOut>(*raw, dds::kEventTopic, dds::kEventProfile, &err),
          dds::serialized(e), dds::serialized(e2)) &&
      add("status", dds::raw_writer<StatusOut>(*raw, dds::kStatusTopic, dds::kStatusProfile, &err),
          dds::serialized(t), dds::serialized(t2));
  if (!ok) return fail(kProgram, err);
  // the racket topic's readable one: plain CDR with the parameter-list flag, of a made-up match
  Bytes pl = dds::serialized(s);
  pl[1] |= 0x02;
  topics[0].kinds["parameter_list"] = pl;

  std::map<std::string, std::map<std::string, long>> sent;
  long rounds = 0, refused = 0;
  bool heard = false;
  const double start = mono_now();
  while (!stop_requested() && mono_now() - start < duration && rounds < count) {
    MatchInfoOut in;
    while (infos.take(&in, nullptr)) heard = true;
    bool matched = heard;  // (the server is there, its readers matched: what is written now reaches them)
    for (const Topic &tp : topics)
      if (clients || (tp.name != std::string("segment") && tp.name != std::string("event")))
        matched = matched && tp.writer.matched() > 0;
    if (matched) {
      for (Topic &tp : topics)
        for (const auto &k : tp.kinds) {
          if (tp.writer.write(k.second)) sent[tp.name][k.first]++;
          else refused++;
        }
      rounds++;
    }
    sleep_until(mono_now() + interval);
  }
  nlohmann::json j;
  j["sent"] = sent;
  j["rounds"] = rounds;
  j["write_failures"] = refused;
  if (!out_json.empty() && !write_file(out_json, j.dump(1), &err)) return fail(kProgram, err);
  std::printf("%s: %ld rounds of every kind on %zu topics, %ld writes refused\n", kProgram, rounds, topics.size(),
              refused);
  std::fflush(stdout);
  int status = rounds < count || refused ? 1 : 0;
  dds::set_exit_status_if_stuck(status);  // two participants in one process: the case of Fast-DDS#6193
  return status;
}
