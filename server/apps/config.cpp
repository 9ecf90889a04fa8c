#include "config.h"

#include <yaml.h>

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>

#include "certificate.h"
#include "common.h"
#include "options_impl.h"

namespace ballsrv {
namespace app {

using json = nlohmann::json;

namespace {

// A config error: where (a JSON pointer) and what.
struct Bad {
  std::string pointer;
  std::string message;
};

[[noreturn]] void bad(const std::string &pointer, const std::string &message) { throw Bad{pointer, message}; }

std::string escape_key(const std::string &key) {
  std::string out;
  for (char c : key) {
    if (c == '~') out += "~0";
    else if (c == '/') out += "~1";
    else out += c;
  }
  return out;
}

double number(const json &j, const std::string &p) {
  if (!j.is_number()) bad(p, "expected a number, got " + j.dump());
  double v = j.get<double>();
  if (!std::isfinite(v)) bad(p, "expected a finite number");
  return v;
}

long long integer(const json &j, const std::string &p, long long lo, long long hi) {
  if (!j.is_number_integer()) bad(p, "expected an integer, got " + j.dump());
  long long v = j.get<long long>();
  if (v < lo || v > hi) bad(p, "expected an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " + std::to_string(v));
  return v;
}

std::string text(const json &j, const std::string &p) {
  if (!j.is_string()) bad(p, "expected a string, got " + j.dump());
  return j.get<std::string>();
}

bool boolean(const json &j, const std::string &p) {
  if (!j.is_boolean()) bad(p, "expected true or false, got " + j.dump());
  return j.get<bool>();
}

// a file named relative to the config file
std::string relative_to(const std::string &file, const std::string &base_dir) {
  if (file.empty() || file[0] == '/' || base_dir.empty()) return file;
  return base_dir + "/" + file;
}

// a scene: names ("tennis", "rally_mid", "default") stay names, files are relative to the config file
std::string resolve(const std::string &scene, const std::string &base_dir) {
  if (scene.find('/') == std::string::npos && scene.find(".yaml") == std::string::npos) return scene;
  return relative_to(scene, base_dir);
}

// One field of a table from its JSON value (a monostate member is the
// caller's to read); the range of a number is the check's to report.
template <class S>
void read_field(const Field<S> &f, const json &v, const std::string &p, S *s) {
  std::visit(
      [&](auto m) {
        using M = decltype(m);
        if constexpr (std::is_same_v<M, double S::*>) {
          s->*m = number(v, p);
        } else if constexpr (std::is_same_v<M, int S::*> || std::is_same_v<M, uint32_t S::*> ||
                             std::is_same_v<M, uint64_t S::*>) {
          using T = std::remove_reference_t<decltype(s->*m)>;
          s->*m = static_cast<T>(integer(v, p, f.bounds.ilo, f.bounds.ihi));
        } else if constexpr (std::is_same_v<M, bool S::*>) {
          s->*m = boolean(v, p);
        } else if constexpr (std::is_same_v<M, std::string S::*>) {
          s->*m = text(v, p);
        } else if constexpr (std::is_same_v<M, ball_level S::*>) {
          if (!parse_level(text(v, p), &(s->*m))) bad(p, "expected " + level_names());
        }
      },
      f.member);
}

// The settings of a match (or of the defaults) from a JSON object.
void match_settings(const json &obj, const std::string &ptr, bool is_match, const std::string &base_dir,
                    MatchConfig *c, std::string *scene) {
  if (!obj.is_object()) bad(ptr, "expected an object");
  for (auto it = obj.begin(); it != obj.end(); ++it) {
    const std::string &k = it.key();
    const json &v = it.value();
    std::string p = ptr + "/" + escape_key(k);
    const Field<MatchConfig> *f = find_field(match_fields(), k);
    if (!f || !f->in_file || (k == "id" && !is_match)) bad(p, "unknown key \"" + k + "\"");
    if (k == "scene") *scene = resolve(text(v, p), base_dir);
    else if (k == "id") c->id = static_cast<uint32_t>(integer(v, p, f->bounds.ilo, f->bounds.ihi));
    else read_field(*f, v, p, c);
  }
  if (!obj.contains("state_rate")) follow_frame_rate(c);
  std::string why;
  if (!check_match_config(*c, &why)) {
    std::string field = why.substr(0, why.find(':'));
    bad(obj.contains(field) ? ptr + "/" + field : ptr, why);
  }
}

void parse_into(const json &root, const std::string &base_dir, ServerConfig *c) {
  if (!root.is_object()) bad("", "expected a JSON object");
  // the defaults first: every match starts from them
  if (root.contains("defaults")) {
    std::string scene;
    match_settings(root["defaults"], "/defaults", false, base_dir, &c->defaults, &scene);
    if (!scene.empty()) bad("/defaults/scene", "a scene belongs to a match, not to the defaults");
  }
  for (auto it = root.begin(); it != root.end(); ++it) {
    const std::string &k = it.key();
    const json &v = it.value();
    std::string p = "/" + escape_key(k);
    const Field<ServerConfig> *f = find_field(server_fields(), k);
    if (!f) bad(p, "unknown key \"" + k + "\"");
    if (k == "defaults") continue;
    if (k == "profile" || k == "security" || k == "tls") {
      (k == "profile" ? c->profile : k == "tls" ? c->tls : c->security) = relative_to(text(v, p), base_dir);
    } else if (k == "catalogue") {
      if (!v.is_object()) bad(p, "expected an object of scene names and scenes");
      const Field<MatchConfig> &name = *find_field(match_fields(), "scene_name");
      for (auto s = v.begin(); s != v.end(); ++s) {
        std::string sp = p + "/" + escape_key(s.key());
        long long n = static_cast<long long>(s.key().size());
        if (n < name.bounds.ilo || n > name.bounds.ihi) bad(sp, "a scene name has " + range_text(name));
        c->catalogue[s.key()] = resolve(text(s.value(), sp), base_dir);
      }
    } else if (k == "matches") {
      if (!v.is_array()) bad(p, "expected an array of matches");
      c->matches.clear();
      for (size_t i = 0; i < v.size(); ++i) {
        MatchEntry e;
        e.config = c->defaults;
        e.config.id = static_cast<uint32_t>(i);
        e.scene = "default";
        std::string mp = p + "/" + std::to_string(i);
        match_settings(v[i], mp, true, base_dir, &e.config, &e.scene);
        for (const auto &other : c->matches)
          if (other.config.id == e.config.id) bad(mp + "/id", "match id " + std::to_string(e.config.id) + " is used twice");
        c->matches.push_back(e);
      }
    } else {
      read_field(*f, v, p, c);
      std::string why;
      if (!check_fields(std::vector<Field<ServerConfig>>{*f}, *c, &why)) bad(p, why);
    }
  }
}

// The rows of the DDS settings: the domain, the profiles, Discovery
// Servers, the TCP transport and security (server_fields keeps their place).
std::vector<Field<ServerConfig>> dds_fields() {
  using C = ServerConfig;
  return {
      {"domain", &C::domain, whole(0, kMaxDomain), "", "DDS domain id (docs/server-reference.md, \"DDS domains\")"},
      {"profile", std::monostate{}, {}, "", "the QoS profile file, relative to the config file", nullptr,
       "found as above"},
      {"participant_profile", &C::participant, {}, "",
       "`loopback`, `lan`, `discovery_client`, `tcp_server` (docs/deploy.md)"},
      {"discovery_server", &C::discovery_server, {}, "",
       "with `discovery_client`: `HOST:PORT[;HOST:PORT...]` (docs/server.md, \"Without multicast: a Discovery "
       "Server\")", nullptr, "the profile's"},
      {"security", std::monostate{}, {}, "",
       "DDS Security: the folder of the CA, the signed documents and the identities, relative to the config "
       "file (docs/security.md)", nullptr, "an open domain"},
      {"identity", &C::identity, {}, "", "with `security` or `tls`: the server's identity (NAME.pem, NAME.key)"},
      {"tcp_peers", &C::tcp_peers, {}, "",
       "with `tcp_server`: the other servers to connect to, `HOST:PORT[;HOST:PORT...]` (docs/deploy.md)", nullptr,
       "none"},
      {"tcp_listen", &C::tcp_listen, whole(0, 65535), "", "with `tcp_server`: the TCP port it listens on; 0: the "
       "profile's", nullptr, "0 (7400)"},
      {"tcp_public_address", &C::tcp_public, {}, "",
       "with `tcp_server` behind a router that forwards its port: the router's IPv4 address", nullptr, "its own"},
      {"tls", std::monostate{}, {}, "",
       "with `tcp_server`: TLS, the folder of ca.pem and the identity, relative to the config file; a peer "
       "without a certificate of that CA is refused (docs/deploy.md)", nullptr, "plain TCP"},
  };
}

}  // namespace

const std::vector<Field<ServerConfig>> &server_fields() {
  using F = Field<ServerConfig>;
  using C = ServerConfig;
  static const std::string create_room = "configured + " + std::to_string(kCreateRoom) +
                                         " when CREATE is allowed, + " + std::to_string(kFollowRoom) + " for a standby";
  static const std::vector<F> rest = {
      {"max_matches", &C::max_matches, whole(1, 100000), "", "room for matches; sizes every DDS resource limit",
       "--max-matches", create_room.c_str()},
      {"allow_create", &C::allow_create, {}, "", "clients may CREATE matches from the catalogue (`--no-create`)"},
      {"max_creates", &C::max_creates, whole(0, 100000), "",
       "matches the CREATEs of one process (of one identity on a secure domain), however many participants it "
       "has, may have standing (the rest refused, `no_room`)", "--max-creates"},
      {"max_creates_per_host", &C::max_creates_per_host, whole(0, 100000), "",
       "matches the CREATEs from one host address (the one its participants announce) may have standing (the "
       "rest refused, `no_room`)", "--max-creates-per-host"},
      {"create_first", &C::create_first, whole(0, UINT32_MAX), "", "the first match id a CREATE may name"},
      {"create_ids", &C::create_ids, whole(1, 65536), "",
       "how many match ids a CREATE may name, from `create_first` on (the rest turned away at the control "
       "reader's door; each one an instance of that reader)"},
      {"create_timeout", &C::create_timeout, open_closed(0.0, 3600.0), "s",
       "a created match nobody holds a slot of for this long is removed (its MatchInfo disposed)",
       "--create-timeout"},
      {"standby", &C::standby, {}, "",
       "follow the other servers' matches and take one over when its server dies (`--standby`; docs/server.md, "
       "\"Several servers and failover\")"},
      {"claim", &C::claim, whole(0, 100000), "",
       "claim up to N of the configured or created matches that no server owns, by the claim rule; 0: serve the "
       "configured matches", "--claim"},
      {"realtime_priority", &C::realtime_priority, whole(0, 99), "",
       "SCHED_FIFO priority of the server's loop thread (root or CAP_SYS_NICE); 0: the normal scheduler "
       "(docs/server-reference.md, \"Load\")", "--realtime-priority"},
      {"status_interval", &C::status_interval, open_closed(0.0, 3600.0), "s", "between status lines",
       "--status-interval"},
      {"startup_wait", &C::startup_wait, closed(0.0, 60.0), "s",
       "listen for another server owning one of our matches before starting", "--startup-wait"},
      {"catalogue", std::monostate{}, {}, "", "scene names a CREATE may ask for", nullptr,
       "`{\"tennis\": \"default\"}`"},
      {"defaults", std::monostate{}, {}, "", "the match settings below, for every match", nullptr, ""},
      {"matches", std::monostate{}, {}, "", "a list of match settings, each with `id` (default: its index) and `scene`",
       nullptr, "one match on `default`"},
  };
  static const std::vector<F> table = [] {
    std::vector<F> t = {
        {"server_id", &C::server_id, whole(0, UINT32_MAX), "", "in every sample the server writes", "--server-id"}};
    for (const F &f : dds_fields()) t.push_back(f);
    t.insert(t.end(), rest.begin(), rest.end());
    return t;
  }();
  return table;
}

bool load_scenes(const ServerConfig &config, ServerScenes *scenes, std::string *err) {
  for (const auto &c : config.catalogue)
    if (!load_scene(c.second, &scenes->catalogue[c.first], err)) {
      *err = "catalogue \"" + c.first + "\": " + *err;
      return false;
    }
  scenes->matches.resize(config.matches.size());
  for (size_t i = 0; i < config.matches.size(); ++i)
    if (!load_scene(config.matches[i].scene, &scenes->matches[i], err)) return false;
  return true;
}

std::unique_ptr<Host> make_host(ServerConfig *config, const ServerScenes &scenes, double player_timeout,
                                std::string *err) {
  if (player_timeout > 0.0) config->defaults.player_timeout = player_timeout;
  auto host = std::make_unique<Host>(config->max_matches, config->allow_create, config->defaults);
  host->set_create_shares(config->security.empty() ? Host::Origin::process : Host::Origin::identity,
                          config->max_creates, config->max_creates_per_host);
  host->set_create_ids({config->create_first, config->create_ids});
  for (const auto &c : scenes.catalogue)
    if (!host->add_scene(c.first, c.second, err)) return nullptr;
  // another server's match may name a scene by libball's name (a standby
  // follows it); a name from the wire is never a path
  host->set_scene_source([](const std::string &name, ball_scene *scene, std::string *e) {
    return plain_scene_name(name) && load_scene(name, scene, e);
  });
  if (!config->slot_owners.empty()) {  // (docs/security.md, "Slots bound to identities")
    if (config->security.empty()) {
      *err = "--slot-owner needs a secure domain (--secure): on an open domain a participant is whoever it says";
      return nullptr;
    }
    std::map<std::pair<uint32_t, int>, SubjectKey> keys;
    for (const auto &o : config->slot_owners) {
      SubjectKey key;
      if (!subject_key_of(config->security + "/" + o.identity + ".pem", &key, err)) return nullptr;
      keys[{o.match, o.slot}] = key;
    }
    host->set_slot_rule([keys](uint32_t match, int slot, const ParticipantId &who) {
      auto it = keys.find({match, slot});
      return it == keys.end() || prefix_fits(who, it->second);
    });
  }
  for (size_t i = 0; i < config->matches.size(); ++i) {
    MatchEntry &e = config->matches[i];
    const ball_scene &sc = scenes.matches[i];
    if (player_timeout > 0.0) e.config.player_timeout = player_timeout;
    // what MatchInfo calls the scene: its own name, else the file's as given, else libball's court
    if (e.scene != "default" && !sc.name[0]) e.config.scene_name = e.scene.substr(0, kNameLen - 1);
    else e.config.scene_name = sc.name[0] ? sc.name : "tennis";
    if (!host->add_match(e.config, sc, err)) {
      *err = "match " + std::to_string(e.config.id) + " (" + e.scene + "): " + *err;
      return nullptr;
    }
  }
  return host;
}

LoopSettings loop_settings(const ServerConfig &config, uint32_t strength) {
  LoopSettings s;
  s.server_id = config.server_id;
  s.status_interval = config.status_interval;
  s.standby = config.standby;
  s.claim = config.claim;
  s.strength = strength;
  s.settle = config.startup_wait;  // a claim settles as long as the servers listen to each other at start
  s.create_timeout = config.create_timeout;
  return s;
}

std::string keys_table(const std::string &which) {
  if (which == "server") return doc_table(server_fields(), ServerConfig{});
  if (which == "match") return doc_table(match_fields(), MatchConfig{});
  return "";
}

// ---- the command line ------------------------------------------------------


void ServerOptions::add(CLI::App &app) {
  app.add_option("--config", config_file, "JSON config file (docs/server.md, \"Configuration\")");
  app.add_option("--keys", keys, "print the key table (server or match) of docs/server-reference.md and exit")
      ->check(CLI::IsMember({"server", "match"}));
  app.add_option("--matches", matches_, "host N matches, ids 0..N-1, replacing the config's list")
      ->check(CLI::Range(1, 100000));
  app.add_flag("--no-create", no_create_, "refuse CREATE requests (allow_create false)");
  app.add_flag("--standby", standby_, "a hot standby: follow the other servers' matches (standby true)");
  app.add_option("--slot-owner", slot_owners_,
                 "with --secure: slot SLOT of match MATCH may be held only by the holder of IDENTITY.pem in the "
                 "--secure folder (MATCH:SLOT=IDENTITY; repeated)");
  server_.add(app, server_fields(), ServerConfig{});
  match_.add(app, match_fields(), MatchConfig{});
  add_dds_options(app, &dds_);
  domain_ = app.get_option("--domain");
  profile_ = app.get_option("--profile");
  participant_ = app.get_option("--participant-profile");
  discovery_server_ = app.get_option("--discovery-server");
  security_ = app.get_option("--secure");
  identity_ = app.get_option("--identity");
  tcp_peers_ = app.get_option("--tcp-peers");
  tcp_listen_ = app.get_option("--tcp-listen");
  tcp_public_ = app.get_option("--tcp-public-address");
  tls_ = app.get_option("--tls");
}

bool ServerOptions::apply(ServerConfig *config, std::string *err) const {
  if (domain_->count()) config->domain = dds_.domain;
  if (profile_->count()) config->profile = dds_.profile;
  if (participant_->count()) config->participant = dds_.participant;
  if (discovery_server_->count()) config->discovery_server = dds_.discovery_server;
  if (security_->count()) config->security = dds_.security;
  if (identity_->count()) config->identity = dds_.identity;
  if (tcp_peers_->count()) config->tcp_peers = dds_.tcp_peers;
  if (tcp_listen_->count()) config->tcp_listen = dds_.tcp_listen;
  if (tcp_public_->count()) config->tcp_public = dds_.tcp_public;
  if (tls_->count()) config->tls = dds_.tls;
  server_.apply(config);
  if (no_create_) config->allow_create = false;
  for (const std::string &text : slot_owners_) {
    unsigned match = 0;
    int slot = -1, used = 0;
    size_t eq = text.find('=');
    if (eq == std::string::npos || std::sscanf(text.c_str(), "%u:%d%n", &match, &slot, &used) != 2 ||
        static_cast<size_t>(used) != eq || slot < 0 || slot >= kMaxPlayers || !plain_scene_name(text.substr(eq + 1))) {
      *err = "--slot-owner " + text + ": not MATCH:SLOT=IDENTITY (a slot in [0, " + std::to_string(kMaxPlayers - 1) +
             "], an identity's name)";
      return false;
    }
    config->slot_owners.push_back({match, slot, text.substr(eq + 1)});
  }
  if (standby_) config->standby = true;
  auto settle = [&](MatchConfig *c) {
    match_.apply(c);
    if (!match_.given("state_rate")) follow_frame_rate(c);
  };
  settle(&config->defaults);
  std::string scene = match_.text("scene");
  if (matches_ > 0 || config->matches.empty()) {
    config->matches.clear();
    for (int i = 0; i < (matches_ > 0 ? matches_ : 1); ++i) {
      MatchEntry e;
      e.config = config->defaults;
      e.config.id = static_cast<uint32_t>(i);
      e.config.seed = config->defaults.seed + static_cast<uint64_t>(i);
      e.scene = scene.empty() ? "default" : scene;
      config->matches.push_back(e);
    }
  } else {
    for (auto &e : config->matches) {
      settle(&e.config);
      if (!scene.empty()) e.scene = scene;
    }
  }
  if (config->max_matches == 0)
    config->max_matches = static_cast<uint32_t>(config->matches.size()) + (config->allow_create ? kCreateRoom : 0) +
                          (config->standby ? kFollowRoom : 0);
  if (config->max_matches < config->matches.size()) {
    *err = "max_matches " + std::to_string(config->max_matches) + " is less than the " +
           std::to_string(config->matches.size()) + " matches configured";
    return false;
  }
  return true;
}

bool parse_config(const std::string &text_in, const std::string &name, const std::string &base_dir,
                  ServerConfig *config, std::string *err) {
  json root;
  try {
    root = json::parse(text_in);
  } catch (const json::parse_error &e) {
    // the byte offset to a line and column of our own
    size_t byte = e.byte > 0 ? static_cast<size_t>(e.byte) - 1 : 0;
    int line = 1, col = 1;
    for (size_t i = 0; i < byte && i < text_in.size(); ++i) {
      if (text_in[i] == '\n') {
        line++;
        col = 1;
      } else {
        col++;
      }
    }
    std::string what = e.what();
    size_t colon = what.rfind(": ");
    *err = name + ":" + std::to_string(line) + ":" + std::to_string(col) + ": not valid JSON: " +
           (colon == std::string::npos ? what : what.substr(colon + 2));
    return false;
  }
  ServerConfig c = *config;
  try {
    parse_into(root, base_dir, &c);
  } catch (const Bad &b) {
    int line = json_pointer_line(text_in, b.pointer);
    *err = name + ":" + std::to_string(line) + ": " + (b.pointer.empty() ? "/" : b.pointer) + ": " + b.message;
    return false;
  }
  *config = c;
  return true;
}

bool load_config_file(const std::string &path, ServerConfig *config, std::string *err) {
  std::ifstream f(path);
  if (!f) {
    *err = path + ": cannot read the config file";
    return false;
  }
  std::stringstream ss;
  ss << f.rdbuf();
  size_t slash = path.rfind('/');
  return parse_config(ss.str(), path, slash == std::string::npos ? "" : path.substr(0, slash), config, err);
}

// ---- where a JSON pointer points in the text ------------------------------
// nlohmann-json 3.11 keeps no positions; libyaml (already the scene reader's)
// reads JSON as YAML's flow style and marks every node with its line.

namespace {

std::vector<std::string> pointer_tokens(const std::string &pointer) {
  std::vector<std::string> out;
  size_t i = 1;
  while (i <= pointer.size() && !pointer.empty()) {
    size_t j = pointer.find('/', i);
    std::string tok = pointer.substr(i, j == std::string::npos ? std::string::npos : j - i);
    std::string un;  // RFC 6901: ~1 is '/', ~0 is '~'
    for (size_t k = 0; k < tok.size(); ++k) {
      if (tok[k] == '~' && k + 1 < tok.size()) {
        un += tok[k + 1] == '1' ? '/' : '~';
        k++;
      } else {
        un += tok[k];
      }
    }
    out.push_back(un);
    if (j == std::string::npos) break;
    i = j + 1;
  }
  return out;
}

int line_of(const yaml_node_t *n) { return static_cast<int>(n->start_mark.line) + 1; }

}  // namespace

int json_pointer_line(const std::string &text_in, const std::string &pointer) {
  yaml_parser_t parser;
  yaml_document_t doc;
  if (!yaml_parser_initialize(&parser)) return 1;
  yaml_parser_set_input_string(&parser, reinterpret_cast<const unsigned char *>(text_in.data()), text_in.size());
  int best = 1;
  if (yaml_parser_load(&parser, &doc)) {
    yaml_node_t *n = yaml_document_get_root_node(&doc);
    if (n) best = line_of(n);
    for (const std::string &tok : pointer_tokens(pointer)) {
      yaml_node_t *child = nullptr;
      if (n && n->type == YAML_MAPPING_NODE) {
        for (yaml_node_pair_t *p = n->data.mapping.pairs.start; p < n->data.mapping.pairs.top && !child; ++p) {
          yaml_node_t *key = yaml_document_get_node(&doc, p->key);
          if (key && key->type == YAML_SCALAR_NODE &&
              tok == std::string(reinterpret_cast<const char *>(key->data.scalar.value), key->data.scalar.length))
            child = yaml_document_get_node(&doc, p->value);
        }
      } else if (n && n->type == YAML_SEQUENCE_NODE && !tok.empty() &&
                 tok.find_first_not_of("0123456789") == std::string::npos) {
        long idx = std::strtol(tok.c_str(), nullptr, 10);
        yaml_node_item_t *items = n->data.sequence.items.start;
        if (idx < n->data.sequence.items.top - items) child = yaml_document_get_node(&doc, items[idx]);
      }
      if (!child) break;  // the nearest parent
      n = child;
      best = line_of(n);
    }
    yaml_document_delete(&doc);
  }
  yaml_parser_delete(&parser);
  return best;
}

template class FieldOptions<ServerConfig>;

}  // namespace app
}  // namespace ballsrv
