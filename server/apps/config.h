// ball-server's configuration: defaults like ball_model_default, then a JSON
// file (docs/server.md, "Configuration"), then the command line. Both the
// file and the command line are read from the field tables (fields.h:
// server_fields here, match_fields in match_config.h). A bad file is
// reported as FILE:LINE: /json/pointer: what is wrong.
#pragma once

#include <deque>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "common.h"
#include "options.h"
#include "host.h"
#include "server_loop.h"
#include "match_config.h"

namespace ballsrv {
namespace app {

struct MatchEntry {
  MatchConfig config;
  std::string scene;  // a catalogue name, a libball scene name, a file, or "default"
};

// Matches a server makes room for beyond its configured ones when CREATE is
// allowed, and a standby for the other servers' matches it follows.
constexpr uint32_t kCreateRoom = 8;
constexpr uint32_t kFollowRoom = 64;

struct ServerConfig {
  uint32_t server_id = 1;
  int domain = 0;
  std::string profile;                       // QoS profile file ("": find_profile)
  std::string participant = "loopback";      // its participant profile
  std::string discovery_server;              // a client profile's Discovery Servers ("": the profile's)
  std::string security;                      // DDS Security's folder ("": an open domain)
  std::string identity;                      // the server's identity in it (and in tls)
  std::string tcp_peers;                     // a TCP profile's other servers ("": the profile's)
  int tcp_listen = 0;                        // a TCP profile's listening port (0: the profile's)
  std::string tcp_public;                    // its address as players reach it ("": its own)
  std::string tls;                           // TLS's folder for a TCP profile ("": plain TCP)
  // slots bound to identities on a secure domain (--slot-owner MATCH:SLOT=IDENTITY): that slot
  // is IDENTITY's alone (docs/security.md, "Slots bound to identities")
  struct SlotOwner {
    uint32_t match = 0;
    int slot = 0;
    std::string identity;
  };
  std::vector<SlotOwner> slot_owners;
  uint32_t max_matches = 0;                  // 0: the configured matches, plus kCreateRoom when CREATE is allowed,
                                             // plus kFollowRoom for a standby
  bool allow_create = true;                  // clients may CREATE matches from the catalogue
  uint32_t max_creates = 2;                  // matches one process's (secure: one identity's) CREATEs may have standing
  uint32_t max_creates_per_host = 8;         // matches the CREATEs from one host address may have standing
  uint32_t create_first = CreateIds{}.first; // the first match id a CREATE may name
  uint32_t create_ids = CreateIds{}.count;   // how many ids from it on (each an instance of the control reader)
  double create_timeout = 30.0;              // s a created match stands with nobody holding a slot
  bool standby = false;                      // follows other servers' matches, takes them over (--standby)
  uint32_t claim = 0;                        // claims up to this many unplaced or created matches; 0: none
  int realtime_priority = 0;                 // SCHED_FIFO priority of its loop thread, 1-99; 0: the normal scheduler
  double status_interval = 1.0;              // s between status lines
  double startup_wait = 1.0;                 // s to listen for another server owning our matches
  std::map<std::string, std::string> catalogue = {{"tennis", "default"}};  // name -> scene
  MatchConfig defaults;                      // every match's settings unless it says otherwise
  std::vector<MatchEntry> matches;
};

// The server's own settings, in the order of docs/server-reference.md.
const std::vector<Field<ServerConfig>> &server_fields();

// Reads a JSON config over *config (defaults first). Relative scene paths
// are taken from the file's directory. false with "FILE:LINE: /pointer: ..." in err.
bool load_config_file(const std::string &path, ServerConfig *config, std::string *err);
bool parse_config(const std::string &text, const std::string &name, const std::string &base_dir,
                  ServerConfig *config, std::string *err);

// The 1-based line where the value at a JSON pointer starts in text (or, if
// it is missing, where its nearest existing parent starts); 0 if unknown.
int json_pointer_line(const std::string &text, const std::string &pointer);

// ball-server's command line over its config: the options of both field
// tables, --matches N, --no-create, the DDS options.
class ServerOptions {
 public:
  void add(CLI::App &app);
  // Applies what was given over *config (the file's or the defaults): the
  // server's settings, every match's (a state rate follows its frame rate
  // unless set), N matches 0..N-1 on --scene with --matches or when none is
  // configured, then max_matches. false with err when it does not fit.
  bool apply(ServerConfig *config, std::string *err) const;

  std::string config_file;  // --config
  std::string keys;         // --keys server|match: print that table of docs/server-reference.md and exit

 private:
  FieldOptions<ServerConfig> server_;
  FieldOptions<MatchConfig> match_;
  DdsOptions dds_;
  CLI::Option *domain_ = nullptr, *profile_ = nullptr, *participant_ = nullptr, *discovery_server_ = nullptr,
              *security_ = nullptr, *identity_ = nullptr, *tcp_peers_ = nullptr, *tcp_listen_ = nullptr,
              *tcp_public_ = nullptr, *tls_ = nullptr;
  int matches_ = 0;
  bool no_create_ = false;
  std::vector<std::string> slot_owners_;  // --slot-owner MATCH:SLOT=IDENTITY
  bool standby_ = false;
};

// Every scene the config names, read before DDS is touched (a bad config fails fast).
struct ServerScenes {
  std::map<std::string, ball_scene> catalogue;  // by the name a CREATE gives
  std::vector<ball_scene> matches;              // one per configured match
};
bool load_scenes(const ServerConfig &config, ServerScenes *scenes, std::string *err);

// The host of the configured matches and catalogue. A player_timeout > 0
// (the liveliness lease the racket samples reader requests) replaces the
// configured one, in *config too. nullptr with err ("match 3 (x.yaml): ...").
std::unique_ptr<Host> make_host(ServerConfig *config, const ServerScenes &scenes, double player_timeout,
                                std::string *err);

// The server loop's settings from the config; `strength` is the ownership
// strength of its writers (the QoS file's, for its role).
LoopSettings loop_settings(const ServerConfig &config, uint32_t strength);

// The markdown table docs/server-reference.md shows for "server" or "match" keys ("" for another name).
std::string keys_table(const std::string &which);

}  // namespace app
}  // namespace ballsrv
