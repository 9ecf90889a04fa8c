// ball-server's configuration file: defaults, matches, catalogue, and errors
// that name the file, the line and the JSON pointer.
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
      {"{\n \"status_interval\": 0\n}", "t.json:2: /status_interval: must be > 0 s"},
      {"{\n  \"server_id\": 1,\n  \"domain\": 2,,\n}", "t.json:3:15: not valid JSON"},
  };
  for (const auto &k : cases) {
    ServerConfig c;
    std::string err;
    CHECK(!parse_config(k.text, "t.json", "", &c, &err));
    bool ok = err.find(k.expect) == 0;
    if (!ok) std::printf("  got: %s\n  expected: %s\n", err.c_str(), k.expect);
    CHECK(ok);
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

CHECK_MAIN
