#include "config.h"

#include <yaml.h>

#include <cstdlib>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "common.h"

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

// The match settings that are plain numbers: the JSON key is the member's name.
double MatchConfig::*real_field(const std::string &key) {
  static const std::pair<const char *, double MatchConfig::*> fields[] = {
      {"frame_rate", &MatchConfig::frame_rate},
      {"time_base", &MatchConfig::time_base},
      {"state_rate", &MatchConfig::state_rate},
      {"serve_delay", &MatchConfig::serve_delay},
      {"max_rally_time", &MatchConfig::max_rally_time},
      {"extrapolation_time", &MatchConfig::extrapolation_time},
      {"stale_time", &MatchConfig::stale_time},
      {"max_sample_age", &MatchConfig::max_sample_age},
      {"max_sample_lead", &MatchConfig::max_sample_lead},
      {"serve_v_up", &MatchConfig::serve_v_up},
      {"court_x_lo", &MatchConfig::court_x_lo},
  };
  for (const auto &f : fields)
    if (key == f.first) return f.second;
  return nullptr;
}

// The settings of a match (or of the defaults) from a JSON object.
void match_settings(const json &obj, const std::string &ptr, bool is_match, const std::string &base_dir,
                    MatchConfig *c, std::string *scene) {
  if (!obj.is_object()) bad(ptr, "expected an object");
  for (auto it = obj.begin(); it != obj.end(); ++it) {
    const std::string &k = it.key();
    const json &v = it.value();
    std::string p = ptr + "/" + escape_key(k);
    if (k == "scene") {
      *scene = resolve(text(v, p), base_dir);
    } else if (k == "level") {
      if (!parse_level(text(v, p), &c->level)) bad(p, "expected easy, mid, advanced or custom");
    } else if (k == "players") {
      c->players = static_cast<int>(integer(v, p, 1, kMaxPlayers));
    } else if (k == "id" && is_match) {
      c->id = static_cast<uint32_t>(integer(v, p, 0, 0xffffffffLL));
    } else if (k == "seed") {
      c->seed = static_cast<uint64_t>(integer(v, p, 0, 0x7fffffffffffffffLL));
    } else if (double MatchConfig::*field = real_field(k)) {
      c->*field = number(v, p);
    } else {
      bad(p, "unknown key \"" + k + "\"");
    }
  }
  // a match's state rate follows its frame rate unless it says otherwise
  if (!obj.contains("state_rate") && c->state_rate > c->frame_rate) c->state_rate = c->frame_rate;
  std::string why;
  if (!check_match_config(*c, &why)) {
    size_t colon = why.find(':');
    std::string field = why.substr(0, colon);
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
    if (k == "defaults") continue;
    if (k == "server_id") c->server_id = static_cast<uint32_t>(integer(v, p, 0, 0xffffffffLL));
    else if (k == "domain") c->domain = static_cast<int>(integer(v, p, 0, 232));
    else if (k == "profile") c->profile = relative_to(text(v, p), base_dir);
    else if (k == "participant_profile") c->participant = text(v, p);
    else if (k == "max_matches") c->max_matches = static_cast<size_t>(integer(v, p, 1, 100000));
    else if (k == "allow_create") c->allow_create = boolean(v, p);
    else if (k == "status_interval") {
      c->status_interval = number(v, p);
      if (!(c->status_interval > 0.0)) bad(p, "must be > 0 s");
    } else if (k == "startup_wait") {
      c->startup_wait = number(v, p);
      if (!(c->startup_wait >= 0.0 && c->startup_wait <= 60.0)) bad(p, "must be in [0, 60] s");
    } else if (k == "catalogue") {
      if (!v.is_object()) bad(p, "expected an object of scene names and scenes");
      for (auto s = v.begin(); s != v.end(); ++s) {
        std::string sp = p + "/" + escape_key(s.key());
        if (s.key().empty() || s.key().size() >= static_cast<size_t>(kNameLen)) bad(sp, "a scene name has 1 to 31 bytes");
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
      bad(p, "unknown key \"" + k + "\"");
    }
  }
}

}  // namespace

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

}  // namespace app
}  // namespace ballsrv
