// ball-server's configuration file: defaults, matches, catalogue, and errors
// that name the file, the line and the JSON pointer.
#include <CLI/CLI.hpp>
#include <fstream>
#include <nlohmann/json.hpp>
#include <set>
#include <unistd.h>

#include "check.hpp"
#include "config.h"

using namespace ballsrv;
using namespace ballsrv::app;

TEST(a_full_config) {
  const char *text = R"({
  "server_id": 3,
  "domain": 17,
  "profile": "qos.xml",
  "max_matches": 12,
  "allow_create": false,
  "catalogue": {"mid": "rally_mid", "court": "scenes/court.yaml"},
  "defaults": {"level": "mid", "frame_rate": 50, "time_base": 0.5},
  "matches": [
    {"id": 4, "scene": "tennis.yaml", "players": 2},
    {"id": 9, "level": "advanced", "state_rate": 0, "seed": 77}
  ]
})";
  ServerConfig c;
  std::string err;
  CHECK(parse_config(text, "t.json", "/etc/ball", &c, &err));
  CHECK_EQ(err, std::string());
  CHECK_EQ(c.server_id, 3u);
  CHECK_EQ(c.domain, 17);
  CHECK_EQ(c.profile, std::string("/etc/ball/qos.xml"));  // relative to the file
  CHECK_EQ(c.max_matches, 12u);
  CHECK(!c.allow_create);
  CHECK_EQ(c.catalogue["mid"], std::string("rally_mid"));  // a name stays a name
  CHECK_EQ(c.catalogue["court"], std::string("/etc/ball/scenes/court.yaml"));
  CHECK_EQ(c.matches.size(), 2u);
  CHECK_EQ(c.matches[0].config.id, 4u);
  CHECK_EQ(c.matches[0].scene, std::string("/etc/ball/tennis.yaml"));
  CHECK_EQ(c.matches[0].config.level, BALL_LEVEL_MID);        // from the defaults
  CHECK_NEAR(c.matches[0].config.frame_rate, 50.0, 0.0);
  CHECK_NEAR(c.matches[0].config.state_rate, 50.0, 0.0);      // follows the frame rate
  CHECK_NEAR(c.matches[0].config.time_base, 0.5, 0.0);
  CHECK_EQ(c.matches[1].config.level, BALL_LEVEL_ADVANCED);   // its own
  CHECK_NEAR(c.matches[1].config.state_rate, 0.0, 0.0);
  CHECK_EQ(c.matches[1].config.seed, 77u);
  CHECK_EQ(c.matches[1].scene, std::string("default"));
}

TEST(errors_name_file_line_and_pointer) {
  struct {
    const char *text, *expect;
  } cases[] = {
      {"{\n \"matches\": [\n  {\"id\": 1},\n  {\"id\": 1}\n ]\n}", "t.json:4: /matches/1/id: match id 1 is used twice"},
      {"{\n \"defaults\": {\n  \"level\": \"hard\"\n }\n}", "t.json:3: /defaults/level: expected easy, mid, advanced or custom"},
      {"{\n \"domain\": 999\n}", "t.json:2: /domain: expected an integer in [0, 232], got 999"},
      {"{\n \"catalogue\": {\"a/b\": 3}\n}", "t.json:2: /catalogue/a~1b: expected a string, got 3"},
      {"[1, 2]", "t.json:1: /: expected a JSON object"},
      {"{\n \"defaults\": {\"time_base\": 100}\n}", "t.json:2: /defaults/time_base: time_base: must be in [0.05, 20]"},
      {"{\n \"matches\": [ {\"frame_rate\": 0} ]\n}", "t.json:2: /matches/0/frame_rate: frame_rate: must be in (0, 1000] Hz"},
      {"{\n \"status_interval\": 0\n}", "t.json:2: /status_interval: status_interval: must be in (0, 3600] s"},
      {"{\n  \"server_id\": 1,\n  \"domain\": 2,,\n}", "t.json:3:15: not valid JSON"},
  };
  for (const auto &k : cases) {
    ServerConfig c;
    std::string err;
    CHECK(!parse_config(k.text, "t.json", "", &c, &err));
    CHECK_MSG(err.find(k.expect) == 0, "got \"%s\", expected \"%s\"", err.c_str(), k.expect);
  }
  ServerConfig c;
  std::string err;
  CHECK(!load_config_file("/nonexistent/ball.json", &c, &err));
  CHECK(err.find("/nonexistent/ball.json: cannot read") == 0);
}

TEST(pointer_lines) {
  const char *text = "{\n  \"a\": {\n    \"b\": [10,\n      {\"c\": \"x,}]\"},\n      3]\n  },\n  \"d\": 1\n}\n";
  CHECK_EQ(json_pointer_line(text, ""), 1);
  CHECK_EQ(json_pointer_line(text, "/a"), 2);
  CHECK_EQ(json_pointer_line(text, "/a/b"), 3);
  CHECK_EQ(json_pointer_line(text, "/a/b/1"), 4);
  CHECK_EQ(json_pointer_line(text, "/a/b/1/c"), 4);
  CHECK_EQ(json_pointer_line(text, "/a/b/2"), 5);  // past a string holding ",}]"
  CHECK_EQ(json_pointer_line(text, "/d"), 7);
  CHECK_EQ(json_pointer_line(text, "/a/missing"), 2);  // the nearest parent
  // compact JSON (no space after a colon), escapes, a key with '/' and '~'
  const char *compact = "{\"x\":{\"a/b\":[1,\n2],\n\"m~n\":\"q\\\"\\/\"},\n\"y\":[{},\n{\"z\":true}]}";
  CHECK_EQ(json_pointer_line(compact, "/x/a~1b/1"), 2);
  CHECK_EQ(json_pointer_line(compact, "/x/m~0n"), 3);
  CHECK_EQ(json_pointer_line(compact, "/y/1/z"), 5);
  CHECK_EQ(json_pointer_line(compact, "/y/7"), 4);  // past the end: the list
  CHECK_EQ(json_pointer_line("not [ json", "/a"), 1);
}

// The field table's ranges as the check, the JSON reader and the command
// line apply them: at each end of every numeric range, one value inside and
// one outside, all three agree.
TEST(the_three_readers_agree_on_every_range) {
  int ends = 0;
  for (const auto &f : match_fields()) {
    if (!f.in_file || !std::holds_alternative<double MatchConfig::*>(f.member)) continue;
    const Bounds &b = f.bounds;
    double step = 1e-3;
    std::vector<std::pair<double, bool>> probes = {{b.lo, !b.lo_open}, {b.lo - step, false}};
    if (!b.hi_field) probes.push_back({b.hi, !b.hi_open}), probes.push_back({b.hi + step, false});
    for (auto [v, inside] : probes) {
      char value[64];
      std::snprintf(value, sizeof value, "%.17g", v);
      // the check
      MatchConfig c;
      c.state_rate = 0.0;  // below every frame rate
      c.*std::get<double MatchConfig::*>(f.member) = v;
      std::string err;
      bool by_check = check_match_config(c, &err);
      // the JSON reader (a state rate not given follows the frame rate down)
      ServerConfig sc;
      bool by_json = parse_config(std::string("{\"defaults\": {\"") + f.key + "\": " + value + "}}", "t.json", "",
                                  &sc, &err);
      // the command line's own check, as it parses
      CLI::App app;
      ServerOptions opt;
      opt.add(app);
      bool by_cli = true;
      try {
        std::string option = f.option;
        app.parse(option.substr(0, option.find(',')) + " " + value, false);
      } catch (const CLI::ParseError &) {
        by_cli = false;
      }
      CHECK_MSG(by_check == inside && by_json == inside && by_cli == inside,
                "%s = %s: inside %d, check %d, JSON %d, command line %d", f.key, value, inside, by_check, by_json,
                by_cli);
      ends++;
    }
  }
  CHECK_EQ(ends, 58);  // 15 numeric settings: 14 with two ends, state_rate with its lower end only
}

TEST(integer_ranges_and_names_agree) {
  // players, from the table: 4 is in, 5 is out, for the check, the file and the command line
  const Bounds &p = find_field(match_fields(), "players")->bounds;
  CHECK_EQ(p.ilo, 1);
  CHECK_EQ(p.ihi, kMaxPlayers);
  MatchConfig c;
  std::string err;
  c.players = kMaxPlayers + 1;
  CHECK(!check_match_config(c, &err));
  CHECK_EQ(err, std::string("players: must be in [1, 4]"));
  ServerConfig sc;
  CHECK(!parse_config("{\"defaults\": {\"players\": 5}}", "t.json", "", &sc, &err));
  CHECK_EQ(err, std::string("t.json:1: /defaults/players: expected an integer in [1, 4], got 5"));
  CHECK(parse_config("{\"defaults\": {\"players\": 4}}", "t.json", "", &sc, &err));
  CLI::App app;
  ServerOptions opt;
  opt.add(app);
  bool threw = false;
  try {
    app.parse("--players 5", false);
  } catch (const CLI::ParseError &) {
    threw = true;
  }
  CHECK(threw);
  // the old name of an option still works; a level by name
  CLI::App app2;
  ServerOptions opt2;
  opt2.add(app2);
  app2.parse("--extrapolation -1 --level mid --matches 3 --seed 5", false);
  ServerConfig cc;
  CHECK(opt2.apply(&cc, &err));
  CHECK_EQ(cc.matches.size(), 3u);
  CHECK_NEAR(cc.matches[2].config.extrapolation_time, -1.0, 0.0);
  CHECK_EQ(cc.matches[2].config.level, BALL_LEVEL_MID);
  CHECK_EQ(cc.matches[2].config.seed, 7u);  // the seed plus the index
  CHECK_EQ(cc.max_matches, 3u + kCreateRoom);
}

TEST(command_line_over_the_file) {
  ServerConfig c;
  std::string err;
  CHECK(parse_config(R"({"defaults": {"frame_rate": 30, "state_rate": 30},
                          "matches": [{"id": 5, "state_rate": 10}, {"id": 6}]})",
                     "t.json", "", &c, &err));
  CLI::App app;
  ServerOptions opt;
  opt.add(app);
  app.parse("--frame-rate 20 --serve-delay 2 --no-create --server-id 9", false);
  CHECK(opt.apply(&c, &err));
  CHECK_EQ(c.matches.size(), 2u);  // the file's matches, with the command line over them
  CHECK_NEAR(c.matches[0].config.frame_rate, 20.0, 0.0);
  CHECK_NEAR(c.matches[0].config.state_rate, 10.0, 0.0);   // its own, below the frame rate
  CHECK_NEAR(c.matches[1].config.state_rate, 20.0, 0.0);   // 30 follows the frame rate down
  CHECK_NEAR(c.matches[1].config.serve_delay, 2.0, 0.0);
  CHECK(!c.allow_create);
  CHECK_EQ(c.server_id, 9u);
  CHECK_EQ(c.max_matches, 2u);  // no CREATE: no room beyond the configured matches
}

// the DDS options a program hands to a ball-server it starts (ball-load
// --sweep) come back the same; the file has the Discovery Server key too
TEST(dds_options_pass_to_a_started_server) {
  DdsOptions o;
  o.domain = 7;
  o.profile = "q.xml";
  o.participant = "discovery_client";
  o.discovery_server = "10.0.0.5:11811;10.0.0.6:11811";
  o.security = "/etc/ball/certs";
  o.identity = "server2";
  std::vector<std::string> args = dds_arguments(o);
  CHECK_EQ(args.size(), 12u);
  CLI::App app;
  ServerOptions opt;
  opt.add(app);
  app.parse(std::vector<std::string>(args.rbegin(), args.rend()));  // CLI11 takes them last first
  ServerConfig c;
  std::string err;
  CHECK(opt.apply(&c, &err));
  CHECK_EQ(c.domain, 7);
  CHECK(c.profile == "q.xml" && c.participant == "discovery_client");
  CHECK(c.discovery_server == "10.0.0.5:11811;10.0.0.6:11811");
  CHECK(c.security == "/etc/ball/certs" && c.identity == "server2");
  CHECK_EQ(dds_arguments(DdsOptions{}).size(), 4u);  // no profile file, no servers: the programs' own defaults
  ServerConfig f;
  CHECK(parse_config(R"({"participant_profile": "discovery_client", "discovery_server": "ds:11811"})", "t.json", "",
                     &f, &err));
  CHECK(f.participant == "discovery_client" && f.discovery_server == "ds:11811");
  // DDS Security's folder is relative to the config file, as the profile is; "" stays an open domain
  ServerConfig g;
  CHECK(parse_config(R"({"security": "certs", "identity": "server1"})", "t.json", "/srv/ball", &g, &err));
  CHECK(g.security == "/srv/ball/certs" && g.identity == "server1");
  ServerConfig h;
  CHECK(parse_config(R"({"security": "", "identity": ""})", "t.json", "/srv/ball", &h, &err));
  CHECK(h.security.empty() && h.identity.empty());
}

// server/config/example.json uses every key of both tables, and reads
TEST(the_example_uses_every_key) {
  std::ifstream f(BALL_EXAMPLE_CONFIG);
  CHECK(f.good());
  nlohmann::json j = nlohmann::json::parse(f, nullptr, false);
  CHECK(j.is_object());
  std::set<std::string> used;
  for (auto &kv : j.items()) used.insert(kv.key());
  for (auto &kv : j["defaults"].items()) used.insert(kv.key());
  for (const auto &m : j["matches"])
    for (auto &kv : m.items()) used.insert(kv.key());
  int keys = 0;
  for (const auto &k : server_fields()) {
    CHECK_MSG(used.count(k.key), "server key %s is not in %s", k.key, BALL_EXAMPLE_CONFIG);
    keys++;
  }
  for (const auto &k : match_fields()) {
    if (!k.in_file) continue;
    CHECK_MSG(used.count(k.key), "match key %s is not in %s", k.key, BALL_EXAMPLE_CONFIG);
    keys++;
  }
  CHECK_EQ(keys, 26 + 22);
  ServerConfig c;
  std::string err;
  CHECK_MSG(load_config_file(BALL_EXAMPLE_CONFIG, &c, &err), "%s", err.c_str());
  CHECK_EQ(c.matches.size(), 4u);
  CHECK_NEAR(c.matches[3].config.time_base, 0.5, 0.0);
  CHECK_NEAR(c.defaults.state_rate, 30.0, 0.0);
}

// Output files say which file failed and why, at open, at a write or a flush.
TEST(output_files_say_what_failed) {
  std::string err;
  CHECK(!write_file("/nonexistent/dir/stats.json", "{}", &err));
  CHECK_EQ(err, std::string("cannot write /nonexistent/dir/stats.json: No such file or directory"));
  OutputFile full;  // a device that takes nothing: the buffered line fails at its flush
  CHECK(full.open("/dev/full"));
  CHECK(full.write_line("{\"type\": \"start\"}"));
  CHECK(!full.flush());
  CHECK_EQ(full.error(), std::string("cannot write /dev/full: No space left on device"));
  CHECK(!write_file("/dev/full", "{}", &err));
  CHECK_EQ(err, std::string("cannot write /dev/full: No space left on device"));
  char dir[] = "/tmp/test_config-XXXXXX";
  CHECK(mkdtemp(dir) != nullptr);
  std::string path = std::string(dir) + "/ok.json";
  CHECK(write_file(path, "{\"a\": 1}", &err));
  std::ifstream f(path);
  std::string text((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
  CHECK_EQ(text, std::string("{\"a\": 1}\n"));
  std::remove(path.c_str());
  rmdir(dir);
}

CHECK_MAIN
