// ball_create: a client of the integration tests that asks the servers of a
// domain for a new match (CONTROL_CREATE, docs/protocol.md) every 0.5 s
// until a MatchInfo for it comes, then listens on, and writes as JSON which
// servers announced that match and when the first did. The first CREATE
// goes out once a server's control reader and MatchInfo writer matched its
// own (the control topic keeps nothing for a reader that comes late), and
// `first_after` and `creates` count from then, not from its discovery.
// With --participants N --each K it is one process of N participants, the
// p-th CREATEing matches --match + p*K to + p*K + K-1 (a greedy client: the
// servers' shares of CREATEs, docs/protocol.md), and `announced` counts
// those a server announced.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <set>

#include "common.h"
#include "domain.h"
#include "open_domain.h"

using namespace ballsrv;
using namespace ballsrv::app;

int main(int argc, char **argv) {
  CLI::App cli{"ball_create: CREATE a match until a server announces it; which servers did"};
  uint32_t match = 0;
  double duration = 10.0;
  std::string scene = "tennis", out_json;
  DdsOptions dds_opt;
  cli.add_option("--match", match, "the new match's id")->required();
  cli.add_option("--scene", scene, "a scene of the servers' catalogue");
  cli.add_option("--duration", duration, "s to run");
  cli.add_option("--out", out_json, "JSON file of what was heard");
  uint32_t participants = 1, each = 1;
  cli.add_option("--participants", participants, "participants of this process")->check(CLI::Range(1, 20));
  cli.add_option("--each", each, "matches each participant CREATEs")->check(CLI::Range(1, 20));
  add_dds_options(cli, &dds_opt);
  CLI11_PARSE(cli, argc, argv);

  std::string err;
  install_stop_signals();
  struct Asker {
    std::unique_ptr<dds::Domain> d;
    dds::Writer<ControlIn> controls;
  };
  std::vector<Asker> askers;
  dds::Reader<MatchInfoOut> infos;
  for (uint32_t p = 0; p < participants; ++p) {
    Asker a;
    a.d = open_domain(dds_opt, "ball_create", &err);
    if (a.d) a.controls = a.d->writer<ControlIn>(dds::kControlTopic, dds::kControlProfile, {static_cast<int>(each)}, &err);
    if (!a.controls.valid()) return fail("ball_create", err);
    askers.push_back(std::move(a));
  }
  infos = askers[0].d->reader<MatchInfoOut>(dds::kInfoTopic, dds::kInfoProfile, {dds::kClientRoom}, &err);
  if (!infos.valid()) return fail("ball_create", err);
  auto all_matched = [&] {
    bool all = infos.matched() >= 1;
    for (const Asker &a : askers) all = all && a.controls.matched() >= 1;
    return all;
  };
  std::set<uint32_t> servers, announced;
  uint32_t seq = 0;
  const double opened = mono_now();
  while (!stop_requested() && mono_now() - opened < duration && !all_matched()) sleep_until(mono_now() + 0.01);
  const double start = mono_now();
  double next = start, first = -1.0;
  long refused = 0;
  const uint32_t wanted = participants * each;
  while (!stop_requested() && mono_now() - opened < duration) {
    MatchInfoOut in;
    while (infos.take(&in, nullptr))
      if (in.match_id - match < wanted) {  // (unsigned: below --match wraps far above)
        announced.insert(in.match_id);
        if (in.match_id == match) servers.insert(in.server_id);
        if (first < 0.0 && in.match_id == match) first = mono_now() - start;
      }
    if (announced.size() < wanted && mono_now() >= next) {
      for (uint32_t k = 0; k < wanted; ++k) {
        if (announced.count(match + k)) continue;
        ControlIn c;
        c.match_id = match + k;
        c.seq = ++seq;
        c.kind = ControlKind::create;
        c.players = 2;
        c.level = 0;
        c.scene = scene;
        if (!askers[k / each].controls.write(c)) refused++;
      }
      next = mono_now() + 0.5;
    }
    sleep_until(mono_now() + 0.01);
  }
  nlohmann::json j = {{"servers", servers},   {"first_after", first}, {"creates", seq},
                      {"matched_after", start - opened}, {"refused", refused}, {"announced", announced.size()}};
  if (!out_json.empty() && !write_file(out_json, j.dump(1), &err)) return fail("ball_create", err);
  std::printf("ball_create: match %u announced by %zu server(s), first %.2f s after the start\n", match,
              servers.size(), first);
  return announced.empty() ? 1 : 0;
}
