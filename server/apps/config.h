// ball-server's configuration: defaults like ball_model_default, then a JSON
// file (docs/server.md, "Configuration"), then the command line. A bad file
// is reported as FILE:LINE: /json/pointer: what is wrong.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "match.h"

namespace ballsrv {
namespace app {

struct MatchEntry {
  MatchConfig config;
  std::string scene;  // a catalogue name, a libball scene name, a file, or "default"
};

struct ServerConfig {
  uint32_t server_id = 1;
  int domain = 0;
  std::string profile;                       // QoS profile file ("": find_profile)
  std::string participant = "loopback";      // its participant profile
  size_t max_matches = 0;                    // 0: the configured matches, plus 8 when CREATE is allowed
  bool allow_create = true;                  // clients may CREATE matches from the catalogue
  double status_interval = 1.0;              // s between status lines
  double startup_wait = 1.0;                 // s to listen for another server owning our matches
  std::map<std::string, std::string> catalogue = {{"tennis", "default"}};  // name -> scene
  MatchConfig defaults;                      // every match's settings unless it says otherwise
  std::vector<MatchEntry> matches;
};

// Reads a JSON config over *config (defaults first). Relative scene paths
// are taken from the file's directory. false with "FILE:LINE: /pointer: ..." in err.
bool load_config_file(const std::string &path, ServerConfig *config, std::string *err);
bool parse_config(const std::string &text, const std::string &name, const std::string &base_dir,
                  ServerConfig *config, std::string *err);

// The 1-based line where the value at a JSON pointer starts in text (or, if
// it is missing, where its nearest existing parent starts); 0 if unknown.
int json_pointer_line(const std::string &text, const std::string &pointer);

}  // namespace app
}  // namespace ballsrv
