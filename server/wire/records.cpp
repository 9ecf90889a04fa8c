#include "records.h"

void to_json(nlohmann::json &j, const ball_vec3 &v) { j = nlohmann::json::array({v.x, v.y, v.z}); }
void from_json(const nlohmann::json &j, ball_vec3 &v) {
  v.x = j.at(0).get<double>();
  v.y = j.at(1).get<double>();
  v.z = j.at(2).get<double>();
}

namespace ballsrv {

#define BALL_JSON_ENUM(E)                                                                               \
  void to_json(json &j, const E &v) { j = name_of(v); }                                                 \
  void from_json(const json &j, E &v) {                                                                 \
    if (!parse_name(j.get<std::string>(), &v)) throw std::invalid_argument("not a " #E ": " + j.dump()); \
  }
BALL_JSON_ENUMS(BALL_JSON_ENUM)
#undef BALL_JSON_ENUM

// Each form below is one list of (key, field), written by BALL_PUT and read
// by BALL_GET: a key is stated once for both directions, and every key of
// a record must be there when it is read.
#define BALL_PUT(key, field) j[key] = (field);
#define BALL_GET(key, field) j.at(key).get_to(field);

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

#define BALL_SEGMENT_KEYS(X, s)                                                                        \
  X("match", s.match_id) X("server", s.server_id) X("term", s.term) X("seq", s.seq) X("cause", s.cause)                  \
  X("index", s.cause_index) X("t0", s.segment.t0) X("p0", s.segment.p0) X("v0", s.segment.v0)          \
  X("s0", s.segment.s0) X("sound", s.sound) X("correction", s.correction) X("server_time", s.server_time) X("model_hash", s.model_hash)                  \
  X("sample_seq", s.sample.seq) X("sample_source_time", s.sample.source_time)                          \
  X("sample_capture_time", s.sample.capture_time) X("play", s.play)

void to_json(json &j, const PlayState &p) {
  j = json::object();
#define BALL_PUT_PLAY(f) j[#f] = p.f;
  BALL_PLAY_FIELDS(BALL_PUT_PLAY)
#undef BALL_PUT_PLAY
}

void from_json(const json &j, PlayState &p) {
#define BALL_GET_PLAY(f) j.at(#f).get_to(p.f);
  BALL_PLAY_FIELDS(BALL_GET_PLAY)
#undef BALL_GET_PLAY
}

void to_json(json &j, const SegmentOut &s) {
  j = json::object();
  BALL_SEGMENT_KEYS(BALL_PUT, s)
  j["grounded"] = s.segment.grounded != 0;
}

void from_json(const json &j, SegmentOut &s) {
  BALL_SEGMENT_KEYS(BALL_GET, s)
  s.segment.grounded = j.at("grounded").get<bool>() ? 1 : 0;
  s.sample.valid = s.sample.source_time != 0.0;  // as on the wire
}

#define BALL_EVENT_KEYS(X, e)                                                                           \
  X("match", e.match_id) X("server", e.server_id) X("term", e.term) X("seq", e.seq) X("kind", e.kind) X("index", e.index) \
  X("side", e.side) X("in_play", e.in_play) X("sound", e.sound) X("time", e.time)                       \
  X("server_time", e.server_time) X("point", e.point) X("velocity_in", e.velocity_in)                   \
  X("velocity_out", e.velocity_out) X("segment_seq", e.segment_seq) X("reason", e.reason)               \
  X("score", e.score) X("value", e.value)

void to_json(json &j, const EventOut &e) {
  j = json::object();
  BALL_EVENT_KEYS(BALL_PUT, e)
}
void from_json(const json &j, EventOut &e) { BALL_EVENT_KEYS(BALL_GET, e) }

#define BALL_STATE_KEYS(X, s)                                                                           \
  X("match", s.match_id) X("server", s.server_id) X("term", s.term) X("frame", s.frame) X("sim_time", s.sim_time)         \
  X("server_time", s.server_time) X("state", s.state) X("segment_seq", s.segment_seq)                   \
  X("position", s.ball.position) X("velocity", s.ball.velocity) X("spin", s.ball.spin)                  \
  X("sim_hash", s.sim_hash)

void to_json(json &j, const StateOut &s) {
  j = json::object();
  BALL_STATE_KEYS(BALL_PUT, s)
}
void from_json(const json &j, StateOut &s) { BALL_STATE_KEYS(BALL_GET, s) }

#define BALL_SLOT_KEYS(X, s)                                                                            \
  X("held", s.held) X("present", s.present) X("samples", s.samples) X("last_seq", s.last_seq)           \
  X("last_capture_time", s.last_capture_time)

#define BALL_INFO_KEYS(X, i)                                                                            \
  X("match", i.match_id) X("server", i.server_id) X("term", i.term) X("server_time", i.server_time)                       \
  X("revision", i.revision) X("state", i.state) X("scene", i.scene) X("level", i.level)                 \
  X("players", i.players) X("play", i.play) X("pause_reason", i.pause_reason) X("pause_slot", i.pause_slot) \
  X("segment_seq", i.segment_seq) X("frame_time", i.frame_time) X("sim_time", i.sim_time)               \
  X("model_hash", i.model_hash) X("net_x", i.net_x) X("court_x", i.court_x) X("court_z", i.court_z)     \
  X("segment_cause", i.segment_cause) X("segment_index", i.segment_cause_index)                         \
  X("segment_t0", i.segment.t0) X("segment_p0", i.segment.p0) X("segment_v0", i.segment.v0)             \
  X("segment_s0", i.segment.s0)
// (and the settings that travel, under their keys)
#define BALL_INFO_SETTING(X, f) X(#f, i.settings.f)

void to_json(json &j, const SlotInfo &s) {
  j = json::object();
  BALL_SLOT_KEYS(BALL_PUT, s)
  j["owner"] = hex(s.owner);
}

void from_json(const json &j, SlotInfo &s) {
  BALL_SLOT_KEYS(BALL_GET, s)
  if (!parse_hex(j.at("owner").get<std::string>(), &s.owner)) throw std::invalid_argument("not an owner: " + j.dump());
}

void to_json(json &j, const MatchInfoOut &i) {
  j = json::object();
  BALL_INFO_KEYS(BALL_PUT, i)
#define BALL_PUT_SETTING(f) BALL_INFO_SETTING(BALL_PUT, f)
  BALL_MATCH_WIRE_SETTINGS(BALL_PUT_SETTING)
#undef BALL_PUT_SETTING
  j["segment_grounded"] = i.segment.grounded != 0;
  j["slots"] = i.slots;
  json &model = j["model"] = json::object();
#define BALL_PUT_MODEL(f) model[#f] = i.model.f;
  BALL_FLIGHT_FIELDS(BALL_PUT_MODEL)
#undef BALL_PUT_MODEL
}

void from_json(const json &j, MatchInfoOut &i) {
  BALL_INFO_KEYS(BALL_GET, i)
#define BALL_GET_SETTING(f) BALL_INFO_SETTING(BALL_GET, f)
  BALL_MATCH_WIRE_SETTINGS(BALL_GET_SETTING)
#undef BALL_GET_SETTING
  i.segment.grounded = j.at("segment_grounded").get<bool>() ? 1 : 0;
  j.at("slots").get_to(i.slots);
  ball_model_default(&i.model);  // as a receiver of MatchInfo has it: only the flight fields travel
  const json &model = j.at("model");
#define BALL_GET_MODEL(f) model.at(#f).get_to(i.model.f);
  BALL_FLIGHT_FIELDS(BALL_GET_MODEL)
#undef BALL_GET_MODEL
}

#define BALL_RACKET_KEYS(X, s)                                                                          \
  X("match", s.match_id) X("player", s.player) X("seq", s.seq) X("capture_time", s.capture_time)        \
  X("center", s.center) X("normal", s.normal) X("source_time", s.source_time) X("permitted", s.permitted)

void to_json(json &j, const RacketSampleIn &s) {
  j = json::object();
  BALL_RACKET_KEYS(BALL_PUT, s)
  j["from"] = hex(s.from);
}

void from_json(const json &j, RacketSampleIn &s) {
  BALL_RACKET_KEYS(BALL_GET, s)
  if (!parse_hex(j.at("from").get<std::string>(), &s.from)) throw std::invalid_argument("not a writer: " + j.dump());
}

// The counters of a status (its own form and the server's report share them).
#define BALL_STATUS_COUNTER_KEYS(X, s)                                                                  \
  X("server_id", s.server_id) X("uptime", s.uptime) X("samples_in", s.samples_in)                       \
  X("samples_ok", s.samples_ok) X("controls_in", s.controls_in) X("controls_refused", s.controls_refused) \
  X("states_out", s.states_out) X("segments_out", s.segments_out) X("events_out", s.events_out)         \
  X("frames", s.frames) X("overruns", s.overruns) X("samples_idle", s.samples_idle)                    \
  X("write_failures", s.write_failures) X("dds_lost", s.dds_lost)
#define BALL_STATUS_KEYS(X, s)                                                                          \
  X("server_time", s.server_time) X("matches", s.matches) X("playing", s.playing)                       \
  X("frame_p50", s.frame_p50) X("frame_p99", s.frame_p99) X("max_matches", s.max_matches)               \
  X("following", s.following) X("claim_room", s.claim_room) X("standby", s.standby) X("strength", s.strength) \
  X("latency_p50", s.latency_p50) X("latency_p99", s.latency_p99)

void to_json(json &j, const StatusOut &s) {
  j = json::object();
  BALL_STATUS_COUNTER_KEYS(BALL_PUT, s)
  BALL_STATUS_KEYS(BALL_PUT, s)
  j["drops"] = drops_json(s.drops);
}

void from_json(const json &j, StatusOut &s) {
  BALL_STATUS_COUNTER_KEYS(BALL_GET, s)
  BALL_STATUS_KEYS(BALL_GET, s)
  drops_from_json(j.at("drops"), &s.drops);
}

// ---- the watcher's own lines and summary -----------------------------------

#define BALL_FRAME_KEYS(X, f)                                                                           \
  X("real", f.real) X("match", f.match) X("sim_time", f.sim_time) X("segment_seq", f.segment_seq)       \
  X("position", f.position)

void to_json(json &j, const OwnFrame &f) {
  j = {{"type", "frame"}};
  BALL_FRAME_KEYS(BALL_PUT, f)
}
void from_json(const json &j, OwnFrame &f) { BALL_FRAME_KEYS(BALL_GET, f) }

#define BALL_SNAPSHOT_KEYS(X, s)                                                                        \
  X("real", s.real) X("match", s.match) X("sim_time", s.sim_time) X("file", s.file)                     \
  X("position", s.position) X("camera", s.camera) X("size", s.size) X("racket_drawn", s.racket_drawn)  \
  X("rackets", s.rackets)

void to_json(json &j, const SnapshotRecord &s) {
  j = {{"type", "snapshot"}};
  BALL_SNAPSHOT_KEYS(BALL_PUT, s)
}
void from_json(const json &j, SnapshotRecord &s) { BALL_SNAPSHOT_KEYS(BALL_GET, s) }

// ---- the server's report -------------------------------------------------------

#define BALL_MATCH_REPORT_KEYS(X, m)                                                                    \
  X("id", m.id) X("state", m.state) X("score", m.score) X("sim_time", m.sim_time) X("sim_hash", m.sim_hash) \
  X("since", m.since) X("taken_over", m.taken_over)

void to_json(json &j, const MatchReport &m) {
  j = json::object();
  BALL_MATCH_REPORT_KEYS(BALL_PUT, m)
#define BALL_PUT_COUNTER(name) j[#name] = m.counters.name;
  BALL_MATCH_COUNTERS(BALL_PUT_COUNTER)
#undef BALL_PUT_COUNTER
}

void from_json(const json &j, MatchReport &m) {
  BALL_MATCH_REPORT_KEYS(BALL_GET, m)
#define BALL_GET_COUNTER(name) j.at(#name).get_to(m.counters.name);
  BALL_MATCH_COUNTERS(BALL_GET_COUNTER)
#undef BALL_GET_COUNTER
}

// the absolute frame clock: how late frames start (each status period's p99, then its median and max)
#define BALL_REPORT_KEYS(X, r)                                                                          \
  X("infos_out", r.infos_out)                                                                           \
  X("skipped_frames", r.skipped_frames) X("late_p99_median", r.late_p99_median)                         \
  X("late_p99_max", r.late_p99_max) X("late_max", r.late_max) X("deadline_missed", r.deadline_missed)   \
  X("writers_lost", r.writers_lost) X("controls_at_door", r.controls_at_door) X("controls_no_room", r.controls_no_room) X("creates_elsewhere", r.creates_elsewhere) X("others_refused", r.others_refused) X("conflicts", r.conflicts) X("latency_p50", r.latency_p50)         \
  X("latency_p99", r.latency_p99) X("latency_count", r.latency_count) X("matches", r.matches)           \
  X("hit_wakes", r.hit_wakes) X("hit_late_p50", r.hit_late_p50) X("hit_late_p99", r.hit_late_p99)       \
  X("hit_known", r.hit_known) X("hit_wake_late_p99", r.hit_wake_late_p99)                               \
  X("hit_found_after", r.hit_found_after) X("hit_found_late_p50", r.hit_found_late_p50)                 \
  X("hit_found_late_p99", r.hit_found_late_p99)                                                         \
  X("takeovers", r.takeovers) X("yields", r.yields) X("claims", r.claims)                               \
  X("follow_failures", r.follow_failures) X("takeovers_waiting", r.takeovers_waiting) X("stale_terms", r.stale_terms) X("unknown_writers", r.unknown_writers) X("unheld_let_go", r.unheld_let_go) X("following", r.following) X("created_expired", r.created_expired)

void to_json(json &j, const ServerReport &r) {
  j = json::object();
  BALL_STATUS_COUNTER_KEYS(BALL_PUT, r.status)
  j["drops"] = drops_json(r.status.drops);
  BALL_REPORT_KEYS(BALL_PUT, r)
}

void from_json(const json &j, ServerReport &r) {
  BALL_STATUS_COUNTER_KEYS(BALL_GET, r.status)
  drops_from_json(j.at("drops"), &r.status.drops);
  BALL_REPORT_KEYS(BALL_GET, r)
  r.status.matches = static_cast<uint32_t>(r.matches.size());  // the list's
  r.status.playing = 0;
  for (const auto &m : r.matches) r.status.playing += m.state == MatchState::playing;
}

}  // namespace ballsrv
