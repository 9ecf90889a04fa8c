#include "records.h"

void to_json(nlohmann::json &j, const ball_vec3 &v) { j = nlohmann::json::array({v.x, v.y, v.z}); }
void from_json(const nlohmann::json &j, ball_vec3 &v) {
  v.x = j.at(0).get<double>();
  v.y = j.at(1).get<double>();
  v.z = j.at(2).get<double>();
}

namespace ballsrv {

#define BALL_JSON_ENUM(E)                                                                   \
  void to_json(json &j, const E &v) { j = name_of(v); }                                     \
  void from_json(const json &j, E &v) {                                                     \
    if (!parse_name(j.get<std::string>(), &v)) throw std::invalid_argument("not a " #E ": " + j.dump()); \
  }
BALL_JSON_ENUM(MatchState)
BALL_JSON_ENUM(Cause)
BALL_JSON_ENUM(EventKind)
BALL_JSON_ENUM(Reason)
BALL_JSON_ENUM(ControlKind)
#undef BALL_JSON_ENUM

namespace {

// reads a key into a value of its type: every key of a record must be there
template <class T>
void get(const json &j, const char *key, T *v) {
  j.at(key).get_to(*v);
}

}  // namespace

json drops_json(const std::array<uint64_t, kDropSlots> &drops) {
  json j = json::object();
  for (int i = 0; i < kDropReasons; ++i) j[name_of(static_cast<SampleResult>(i))] = drops[i];
  return j;
}

void drops_from_json(const json &j, std::array<uint64_t, kDropSlots> *drops) {
  drops->fill(0);
  for (auto &kv : j.items()) {
    SampleResult r;
    if (!parse_name(kv.key(), &r) || static_cast<int>(r) >= kDropReasons)
      throw std::invalid_argument("not a drop reason: " + kv.key());
    (*drops)[static_cast<int>(r)] = kv.value().get<uint64_t>();
  }
}

std::string record_type(const json &line) {
  auto it = line.find("type");
  return it != line.end() && it->is_string() ? it->get<std::string>() : "";
}

// ---- the samples -------------------------------------------------------------

void to_json(json &j, const SegmentOut &s) {
  j = {{"match", s.match_id}, {"server", s.server_id}, {"seq", s.seq}, {"cause", s.cause},
       {"index", s.cause_index}, {"t0", s.segment.t0}, {"p0", s.segment.p0}, {"v0", s.segment.v0},
       {"s0", s.segment.s0}, {"grounded", s.segment.grounded != 0}, {"server_time", s.server_time},
       {"model_hash", s.model_hash}, {"sample_seq", s.sample.seq}, {"sample_source_time", s.sample.source_time},
       {"sample_capture_time", s.sample.capture_time}};
}

void from_json(const json &j, SegmentOut &s) {
  get(j, "match", &s.match_id);
  get(j, "server", &s.server_id);
  get(j, "seq", &s.seq);
  get(j, "cause", &s.cause);
  get(j, "index", &s.cause_index);
  get(j, "t0", &s.segment.t0);
  get(j, "p0", &s.segment.p0);
  get(j, "v0", &s.segment.v0);
  get(j, "s0", &s.segment.s0);
  s.segment.grounded = j.at("grounded").get<bool>() ? 1 : 0;
  get(j, "server_time", &s.server_time);
  get(j, "model_hash", &s.model_hash);
  get(j, "sample_seq", &s.sample.seq);
  get(j, "sample_source_time", &s.sample.source_time);
  get(j, "sample_capture_time", &s.sample.capture_time);
  s.sample.valid = s.sample.source_time != 0.0;  // as on the wire
}

void to_json(json &j, const EventOut &e) {
  j = {{"match", e.match_id},      {"server", e.server_id},       {"seq", e.seq},
       {"kind", e.kind},           {"index", e.index},            {"side", e.side},
       {"in_play", e.in_play},     {"sound", e.sound},            {"time", e.time},
       {"server_time", e.server_time}, {"point", e.point},        {"velocity_in", e.velocity_in},
       {"velocity_out", e.velocity_out}, {"segment_seq", e.segment_seq}, {"reason", e.reason},
       {"score", e.score},         {"value", e.value}};
}

void from_json(const json &j, EventOut &e) {
  get(j, "match", &e.match_id);
  get(j, "server", &e.server_id);
  get(j, "seq", &e.seq);
  get(j, "kind", &e.kind);
  get(j, "index", &e.index);
  get(j, "side", &e.side);
  get(j, "in_play", &e.in_play);
  get(j, "sound", &e.sound);
  get(j, "time", &e.time);
  get(j, "server_time", &e.server_time);
  get(j, "point", &e.point);
  get(j, "velocity_in", &e.velocity_in);
  get(j, "velocity_out", &e.velocity_out);
  get(j, "segment_seq", &e.segment_seq);
  get(j, "reason", &e.reason);
  get(j, "score", &e.score);
  get(j, "value", &e.value);
}

void to_json(json &j, const StateOut &s) {
  j = {{"match", s.match_id},  {"server", s.server_id},         {"frame", s.frame},
       {"sim_time", s.sim_time}, {"server_time", s.server_time}, {"state", s.state},
       {"segment_seq", s.segment_seq}, {"position", s.ball.position}, {"velocity", s.ball.velocity},
       {"spin", s.ball.spin},  {"sim_hash", s.sim_hash}};
}

void from_json(const json &j, StateOut &s) {
  get(j, "match", &s.match_id);
  get(j, "server", &s.server_id);
  get(j, "frame", &s.frame);
  get(j, "sim_time", &s.sim_time);
  get(j, "server_time", &s.server_time);
  get(j, "state", &s.state);
  get(j, "segment_seq", &s.segment_seq);
  get(j, "position", &s.ball.position);
  get(j, "velocity", &s.ball.velocity);
  get(j, "spin", &s.ball.spin);
  get(j, "sim_hash", &s.sim_hash);
}

void to_json(json &j, const MatchInfoOut &i) {
  json slots = json::array();
  for (int k = 0; k < kMaxPlayers; ++k) {
    const SlotInfo &s = i.slots[k];
    slots.push_back({{"held", s.held}, {"present", s.present}, {"owner", hex(s.owner)}, {"samples", s.samples},
                     {"last_seq", s.last_seq}, {"last_capture_time", s.last_capture_time}});
  }
  json model = json::object();
#define BALL_PUT(f) model[#f] = i.model.f;
  BALL_FLIGHT_FIELDS(BALL_PUT)
#undef BALL_PUT
  j = {{"match", i.match_id},         {"server", i.server_id},
       {"server_time", i.server_time}, {"revision", i.revision},
       {"state", i.state},            {"scene", i.scene},
       {"level", i.level},            {"players", i.players},
       {"slots", slots},              {"score", i.score},
       {"serving_side", i.serving_side}, {"rally", i.rally},
       {"segment_seq", i.segment_seq}, {"frame_time", i.frame_time},
       {"time_base", i.time_base},    {"sim_time", i.sim_time},
       {"state_rate", i.state_rate},  {"player_timeout", i.player_timeout},
       {"max_sample_age", i.max_sample_age}, {"max_sample_lead", i.max_sample_lead},
       {"model_hash", i.model_hash},  {"model", model},
       {"net_x", i.net_x},            {"court_x", {i.court_x[0], i.court_x[1]}},
       {"court_z", {i.court_z[0], i.court_z[1]}}};
}

void from_json(const json &j, MatchInfoOut &i) {
  get(j, "match", &i.match_id);
  get(j, "server", &i.server_id);
  get(j, "server_time", &i.server_time);
  get(j, "revision", &i.revision);
  get(j, "state", &i.state);
  get(j, "scene", &i.scene);
  get(j, "level", &i.level);
  get(j, "players", &i.players);
  const json &slots = j.at("slots");
  for (int k = 0; k < kMaxPlayers; ++k) {
    const json &s = slots.at(static_cast<size_t>(k));
    SlotInfo &o = i.slots[k];
    get(s, "held", &o.held);
    get(s, "present", &o.present);
    if (!parse_hex(s.at("owner").get<std::string>(), &o.owner)) throw std::invalid_argument("not an owner: " + s.dump());
    get(s, "samples", &o.samples);
    get(s, "last_seq", &o.last_seq);
    get(s, "last_capture_time", &o.last_capture_time);
  }
  get(j, "score", &i.score);
  get(j, "serving_side", &i.serving_side);
  get(j, "rally", &i.rally);
  get(j, "segment_seq", &i.segment_seq);
  get(j, "frame_time", &i.frame_time);
  get(j, "time_base", &i.time_base);
  get(j, "sim_time", &i.sim_time);
  get(j, "state_rate", &i.state_rate);
  get(j, "player_timeout", &i.player_timeout);
  get(j, "max_sample_age", &i.max_sample_age);
  get(j, "max_sample_lead", &i.max_sample_lead);
  get(j, "model_hash", &i.model_hash);
  ball_model_default(&i.model);  // as a receiver of MatchInfo has it
  const json &model = j.at("model");
#define BALL_GET(f) get(model, #f, &i.model.f);
  BALL_FLIGHT_FIELDS(BALL_GET)
#undef BALL_GET
  get(j, "net_x", &i.net_x);
  i.court_x[0] = j.at("court_x").at(0).get<double>();
  i.court_x[1] = j.at("court_x").at(1).get<double>();
  i.court_z[0] = j.at("court_z").at(0).get<double>();
  i.court_z[1] = j.at("court_z").at(1).get<double>();
}

// The counters of a status, shared by its own form and the server's report.
namespace {

void put_counters(json &j, const StatusOut &s) {
  j["server_id"] = s.server_id;
  j["uptime"] = s.uptime;
  j["samples_in"] = s.samples_in;
  j["samples_ok"] = s.samples_ok;
  j["drops"] = drops_json(s.drops);
  j["controls_in"] = s.controls_in;
  j["controls_refused"] = s.controls_refused;
  j["states_out"] = s.states_out;
  j["segments_out"] = s.segments_out;
  j["events_out"] = s.events_out;
  j["frames"] = s.frames;
  j["overruns"] = s.overruns;
}

void get_counters(const json &j, StatusOut &s) {
  get(j, "server_id", &s.server_id);
  get(j, "uptime", &s.uptime);
  get(j, "samples_in", &s.samples_in);
  get(j, "samples_ok", &s.samples_ok);
  drops_from_json(j.at("drops"), &s.drops);
  get(j, "controls_in", &s.controls_in);
  get(j, "controls_refused", &s.controls_refused);
  get(j, "states_out", &s.states_out);
  get(j, "segments_out", &s.segments_out);
  get(j, "events_out", &s.events_out);
  get(j, "frames", &s.frames);
  get(j, "overruns", &s.overruns);
}

}  // namespace

void to_json(json &j, const StatusOut &s) {
  j = json::object();
  put_counters(j, s);
  j["server_time"] = s.server_time;
  j["matches"] = s.matches;
  j["playing"] = s.playing;
  j["frame_p50"] = s.frame_p50;
  j["frame_p99"] = s.frame_p99;
}

void from_json(const json &j, StatusOut &s) {
  get_counters(j, s);
  get(j, "server_time", &s.server_time);
  get(j, "matches", &s.matches);
  get(j, "playing", &s.playing);
  get(j, "frame_p50", &s.frame_p50);
  get(j, "frame_p99", &s.frame_p99);
}

// ---- the watcher's own lines and summary -----------------------------------

void to_json(json &j, const OwnFrame &f) {
  j = {{"type", "frame"}, {"real", f.real}, {"match", f.match}, {"sim_time", f.sim_time},
       {"segment_seq", f.segment_seq}, {"position", f.position}};
}
void from_json(const json &j, OwnFrame &f) {
  get(j, "real", &f.real);
  get(j, "match", &f.match);
  get(j, "sim_time", &f.sim_time);
  get(j, "segment_seq", &f.segment_seq);
  get(j, "position", &f.position);
}

void to_json(json &j, const SnapshotRecord &s) {
  j = {{"type", "snapshot"}, {"real", s.real},         {"match", s.match},   {"sim_time", s.sim_time},
       {"file", s.file},     {"position", s.position}, {"camera", s.camera}, {"size", s.size}};
}
void from_json(const json &j, SnapshotRecord &s) {
  get(j, "real", &s.real);
  get(j, "match", &s.match);
  get(j, "sim_time", &s.sim_time);
  get(j, "file", &s.file);
  get(j, "position", &s.position);
  get(j, "camera", &s.camera);
  get(j, "size", &s.size);
}


// ---- the server's report -------------------------------------------------------


void to_json(json &j, const ServerReport &r) {
  j = json::object();
  put_counters(j, r.status);
  j["samples_idle"] = r.samples_idle;
  j["infos_out"] = r.infos_out;
  j["write_failures"] = r.write_failures;
  j["skipped_frames"] = r.skipped_frames;
  // the absolute frame clock: how late frames start (each status period's p99, then its median and max)
  j["late_p99_median"] = r.late_p99_median;
  j["late_p99_max"] = r.late_p99_max;
  j["late_max"] = r.late_max;
  j["deadline_missed"] = r.deadline_missed;
  j["writers_lost"] = r.writers_lost;
  j["conflicts"] = r.conflicts;
  j["latency_p50"] = r.latency_p50;
  j["latency_p99"] = r.latency_p99;
  j["latency_count"] = r.latency_count;
  j["matches"] = r.matches;
}

void from_json(const json &j, ServerReport &r) {
  get_counters(j, r.status);
  get(j, "samples_idle", &r.samples_idle);
  get(j, "infos_out", &r.infos_out);
  get(j, "write_failures", &r.write_failures);
  get(j, "skipped_frames", &r.skipped_frames);
  get(j, "late_p99_median", &r.late_p99_median);
  get(j, "late_p99_max", &r.late_p99_max);
  get(j, "late_max", &r.late_max);
  get(j, "deadline_missed", &r.deadline_missed);
  get(j, "writers_lost", &r.writers_lost);
  get(j, "conflicts", &r.conflicts);
  get(j, "latency_p50", &r.latency_p50);
  get(j, "latency_p99", &r.latency_p99);
  get(j, "latency_count", &r.latency_count);
  get(j, "matches", &r.matches);
  r.status.matches = static_cast<uint32_t>(r.matches.size());
  r.status.playing = 0;
  for (const auto &m : r.matches) r.status.playing += m.state == MatchState::playing;
}


}  // namespace ballsrv
