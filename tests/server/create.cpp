// ball_create: a client of the integration tests that asks the servers of a
// domain for a new match (CONTROL_CREATE, docs/protocol.md) every 0.5 s
// until a MatchInfo for it comes, then listens on, and writes as JSON which
// servers announced that match and when the first did. The first CREATE
// goes out once a server's control reader and MatchInfo writer matched its
// own (the control topic keeps nothing for a reader that comes late), and
// `first_after` and `creates` count from then, not from its discovery.
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
  add_dds_options(cli, &dds_opt);
  CLI11_PARSE(cli, argc, argv);

  std::string err;
  install_stop_signals();
  auto d = open_domain(dds_opt, "ball_create", &err);
  if (!d) return fail("ball_create", err);
  auto controls = d->writer<ControlIn>(dds::kControlTopic, dds::kControlProfile, {1}, &err);
  auto infos = d->reader<MatchInfoOut>(dds::kInfoTopic, dds::kInfoProfile, {dds::kClientRoom}, &err);
  if (!controls.valid() || !infos.valid()) return fail("ball_create", err);
  std::set<uint32_t> servers;
  uint32_t seq = 0;
  const double opened = mono_now();
  while (!stop_requested() && mono_now() - opened < duration && (controls.matched() < 1 || infos.matched() < 1))
    sleep_until(mono_now() + 0.01);
  const double start = mono_now();
  double next = start, first = -1.0;
  long refused = 0;
  while (!stop_requested() && mono_now() - opened < duration) {
    MatchInfoOut in;
    while (infos.take(&in, nullptr))
      if (in.match_id == match) {
        servers.insert(in.server_id);
        if (first < 0.0) first = mono_now() - start;
      }
    if (first < 0.0 && mono_now() >= next) {
      ControlIn c;
      c.match_id = match;
      c.seq = ++seq;
      c.kind = ControlKind::create;
      c.players = 2;
      c.level = 0;
      c.scene = scene;
      if (!controls.write(c)) refused++;
      next = mono_now() + 0.5;
    }
    sleep_until(mono_now() + 0.01);
  }
  nlohmann::json j = {{"servers", servers},   {"first_after", first}, {"creates", seq},
                      {"matched_after", start - opened}, {"refused", refused}};
  if (!out_json.empty() && !write_file(out_json, j.dump(1), &err)) return fail("ball_create", err);
  std::printf("ball_create: match %u announced by %zu server(s), first %.2f s after the start\n", match,
              servers.size(), first);
  return first >= 0.0 ? 0 : 1;
}
