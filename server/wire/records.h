// The JSON forms of the server's data, written and read here only (with
// nlohmann-json's to_json/from_json): the lines of `ball-watch --record`
// (JSON Lines, one sample a line with its "type" and "recv"), the watcher's
// summary, `ball-server --stats-json`, `ball-bot --stats-json`,
// `ball-load --json`; the integration tests read them back with the same
// functions. Enums are written by name (types.h), participant ids as hex,
// vectors as [x, y, z].
#pragma once

#include <array>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "types.h"

void to_json(nlohmann::json &j, const ball_vec3 &v);
void from_json(const nlohmann::json &j, ball_vec3 &v);

namespace ballsrv {

using json = nlohmann::json;

// the enums written by name
#define BALL_JSON_ENUMS(X) X(MatchState) X(Cause) X(EventKind) X(Reason) X(ControlKind)
#define BALL_JSON_ENUM(E)            \
  void to_json(json &j, const E &v); \
  void from_json(const json &j, E &v);
BALL_JSON_ENUMS(BALL_JSON_ENUM)
#undef BALL_JSON_ENUM

void to_json(json &j, const SegmentOut &s);
void from_json(const json &j, SegmentOut &s);
void to_json(json &j, const EventOut &e);
void from_json(const json &j, EventOut &e);
void to_json(json &j, const StateOut &s);
void from_json(const json &j, StateOut &s);
void to_json(json &j, const PlayState &p);
void from_json(const json &j, PlayState &p);
void to_json(json &j, const SlotInfo &s);
void from_json(const json &j, SlotInfo &s);
void to_json(json &j, const MatchInfoOut &i);
void from_json(const json &j, MatchInfoOut &i);
// a player's racket sample: its fields and its writer ("from", hex); the DDS layer's flags but `permitted` not
void to_json(json &j, const RacketSampleIn &s);
void from_json(const json &j, RacketSampleIn &s);
// drop counters by reason name, every reason ({"unknown_match": 0, ...})
json drops_json(const std::array<uint64_t, kDropSlots> &drops);
void drops_from_json(const json &j, std::array<uint64_t, kDropSlots> *drops);

// ---- ball-watch --record: one line per sample, with its type -------------

inline const char *record_type(const SegmentOut &) { return "segment"; }
inline const char *record_type(const EventOut &) { return "event"; }
inline const char *record_type(const StateOut &) { return "state"; }
inline const char *record_type(const MatchInfoOut &) { return "match_info"; }
inline const char *record_type(const RacketSampleIn &) { return "racket_sample"; }
inline const char *record_type(const StatusOut &) { return "server_status"; }

// A sample as a record line: its fields, "type", and "recv" (the
// watcher's realtime clock at reception, s).
template <class T>
json record_line(const T &sample, double recv) {
  json j = sample;
  j["type"] = record_type(sample);
  j["recv"] = recv;
  return j;
}
// The type of a record line ("" if it has none).
std::string record_type(const json &line);

// The watcher's own ball at one of its frames ("frame" lines, with --record-frames).
struct OwnFrame {
  double real = 0.0;           // watcher's realtime s
  uint32_t match = 0;
  double sim_time = 0.0;       // sim s, the watcher's estimate
  uint32_t segment_seq = 0;    // the segment evaluated
  ball_vec3 position{0, 0, 0}; // m
};
void to_json(json &j, const OwnFrame &f);
void from_json(const json &j, OwnFrame &f);

// A PNG frame written ("snapshot" lines).
struct SnapshotRecord {
  double real = 0.0;           // watcher's realtime s
  uint32_t match = 0;
  double sim_time = 0.0;       // sim s drawn
  std::string file;
  ball_vec3 position{0, 0, 0}; // m, the ball drawn
  std::string camera;
  std::array<int, 2> size{0, 0};  // pixels, width and height
  std::array<bool, kMaxPlayers> racket_drawn{};         // each slot's racket: drawn (it had a pose)
  std::array<ball_vec3, kMaxPlayers> rackets{};         // m, the centre drawn
};
void to_json(json &j, const SnapshotRecord &s);
void from_json(const json &j, SnapshotRecord &s);

// ---- the watcher's summary (the last record line, --summary-json) --------

struct WatchedMatchSummary {
  uint32_t match = 0;
  uint64_t hits = 0, dead_hits = 0, bounces = 0, nets = 0, walls = 0, sounds = 0, serves = 0, points = 0, lets = 0;
  std::array<int, 2> score{0, 0};
  uint64_t pauses = 0, resumes = 0, refused = 0;
  uint64_t events_missed = 0;     // gaps in the events' seq
  uint64_t states = 0;            // server ball states received
  uint64_t states_checked = 0;    // of those, evaluated from their segment
  uint64_t states_unmatched = 0;  // whose segment never came (or was too old)
  double max_error = 0.0;         // m: the desync, the largest |own - server| position component
  uint64_t frames = 0;            // own frames evaluated
  uint64_t snapshots = 0;
  uint32_t segments = 0;          // seq of the newest segment
  uint64_t not_taken = 0;         // server samples recorded but not used: another server's, numbers out of range,
                                  // a clock pair or a segment seq that does not fit (trust.h)
  uint64_t voided = 0;            // events a correction voided (docs/protocol.md, "Corrections"): off the counts
};
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(WatchedMatchSummary, match, hits, dead_hits, bounces, nets, walls, sounds, serves,
                                   points, lets, score, pauses, resumes, refused, events_missed, states,
                                   states_checked, states_unmatched, max_error, frames, snapshots, segments,
                                   not_taken, voided)

// A server's status line (ServerStatus): every field, drops by name.
void to_json(json &j, const StatusOut &s);
void from_json(const json &j, StatusOut &s);

struct WatchSummary {
  double seconds = 0.0;              // real s watched
  double first_segment_after = -1.0; // real s after the start; -1: none
  std::vector<WatchedMatchSummary> matches;
  std::vector<StatusOut> servers;  // each server's newest status
  // sample-to-segment latency (s): a hit's newest racket sample written ->
  // its segment received here / written by the server
  double latency_p50 = 0.0, latency_p99 = 0.0, latency_server_p50 = 0.0, latency_server_p99 = 0.0;
  uint64_t latency_count = 0;
  uint64_t untrusted = 0;  // server samples refused: their writer lacks the certificate bound to their server id
  // floor, net and wall contacts that happened (docs/protocol.md, "Segments
  // ahead of time"): their segment received before (ahead) or after (late)
  // the contact on this watcher's clock, and the lead (real s, contact time
  // minus reception) at its 1st percentile and median; superseded: received
  // and then superseded by a hit, never in effect
  uint64_t bounces_ahead = 0, bounces_late = 0, bounces_superseded = 0;
  double bounce_lead_p1 = 0.0, bounce_lead_p50 = 0.0;
};
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(WatchSummary, seconds, first_segment_after, matches, servers, latency_p50,
                                   latency_p99, latency_server_p50, latency_server_p99, latency_count, untrusted,
                                   bounces_ahead, bounces_late, bounces_superseded, bounce_lead_p1, bounce_lead_p50)

// ---- ball-server --stats-json ----------------------------------------------

struct MatchReport {  // written flat: id, state, each counter, score, sim_time, sim_hash, since, taken_over
  uint32_t id = 0;
  MatchState state = MatchState::waiting;
  MatchCounters counters;
  std::array<int, 2> score{0, 0};  // points of side 0 and side 1
  double sim_time = 0.0;           // sim s
  uint64_t sim_hash = 0;           // ball_sim_hash
  double since = 0.0;              // server s: when this server began to step it
  bool taken_over = false;         // from another server (a standby's take-over)
};
void to_json(json &j, const MatchReport &m);
void from_json(const json &j, MatchReport &m);

// The totals (its last status line) and what only the file has. Written
// flat: the status's fields (its match count and playing count are the
// list's), then the rest, then "matches", the list.
struct ServerReport {
  StatusOut status;
  uint64_t infos_out = 0;
  uint64_t skipped_frames = 0;  // frames skipped after a stall (more than 5 behind)
  double late_p99_median = 0.0, late_p99_max = 0.0, late_max = 0.0;  // s: frames' start after their deadline
  uint64_t deadline_missed = 0, writers_lost = 0, conflicts = 0;
  uint64_t controls_at_door = 0;  // of controls_refused, turned away at the control reader's door
  uint64_t controls_no_room = 0;  // of controls_refused, over their writer's share of the inbox (or DDS's room)
  uint64_t creates_elsewhere = 0; // of controls_refused, CREATEs left to another server (a standby, the claim rule)
  uint64_t others_refused = 0;    // other participants' MatchInfo and Segments no server writes (trust.h, kMaxClockGap)
  uint64_t takeovers = 0, yields = 0, claims = 0, follow_failures = 0;  // among the servers of a domain
  uint64_t takeovers_waiting = 0;  // take-overs held back until a player of the match was heard
  uint64_t stale_terms = 0;        // other servers' MatchInfo of an older owner than this one or the one followed
  uint64_t unknown_writers = 0;    // MatchInfos held back: their participant's ServerStatus not heard (yet)
  uint64_t unheld_let_go = 0;      // followed matches let go: their owner died with no slot held
  uint64_t created_expired = 0;  // created or taken-over matches removed: nobody held a slot for create_timeout
  uint32_t following = 0;       // matches followed at the end
  double latency_p50 = 0.0, latency_p99 = 0.0;  // s: a hit's newest sample written -> its segment written
  uint64_t latency_count = 0;
  uint64_t hit_wakes = 0;       // partial frames stepped to a racket hit's instant
  double hit_late_p50 = 0.0, hit_late_p99 = 0.0;  // s: such a step began after the hit's instant (negative: before)
  uint64_t hit_known = 0;         // of them, hits the loop knew before they were due (the instant less hit_lead)
  double hit_wake_late_p99 = 0.0;  // s: their step began after that
  uint64_t hit_found_after = 0;   // of them, hits first seen after their instant (samples that came after it)
  double hit_found_late_p50 = 0.0, hit_found_late_p99 = 0.0;  // s: their step began after the instant
  std::vector<MatchReport> matches;
};
void to_json(json &j, const ServerReport &r);
void from_json(const json &j, ServerReport &r);

// ---- ball-bot --stats-json, ball-load --json -------------------------------

struct BotReport {
  uint32_t match = 0;
  int slot = -1;
  uint64_t samples = 0;     // racket poses taken and pushed
  uint64_t lost = 0, written = 0, write_failures = 0, segments = 0;  // the client's (ball_net_status) in the match
  uint64_t plans = 0, late = 0, missed_on_purpose = 0;
  uint64_t refused = 0;     // server samples not taken (trust.h)
  uint64_t untrusted = 0;   // of them, from a writer without the certificate bound to their server id
};
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(BotReport, match, slot, samples, lost, written, write_failures, segments, plans,
                                   late, missed_on_purpose, refused, untrusted)

struct LoadRow {  // one point (match count, state rate) of one round of the load benchmark
  int matches = 0, bots = 0;
  double rate = 0.0;          // Hz, each bot's
  double state_rate = -1.0;   // Hz, the server's ball states (0: off); -1: not started by ball-load
  int bot_processes = 1;
  int server_priority = 0;    // the server's SCHED_FIFO priority (0: the normal scheduler)
  bool ready = false;         // every slot joined within the warm-up
  double seconds = 0.0;       // measured
  double samples_per_s = 0.0;
  uint64_t hits = 0, write_failures = 0;
  double latency_p50_ms = 0.0, latency_p99_ms = 0.0;          // a hit's newest sample written -> its segment received
  double hit_to_wire_p50_ms = 0.0, hit_to_wire_p99_ms = 0.0;  // the hit's sim time (as real) -> its segment received
  // hit-to-wire's two parts: the hit's sim time (as real) -> the server's write (DDS source timestamp), and that write ->
  // the reception (one host's clock: on several hosts their offset is in both)
  double hit_to_write_p50_ms = 0.0, hit_to_write_p99_ms = 0.0, delivery_p50_ms = 0.0, delivery_p99_ms = 0.0;
  uint64_t server_frames = 0, server_overruns = 0;
  double overrun_pct = 0.0;   // of the server's frames
  double frame_p50_ms = 0.0, frame_p99_ms_median = 0.0, frame_p99_ms_max = 0.0;
  uint32_t playing = 0;
  // per match (-1: not measured): CPU in % of one core, resident memory in
  // KiB, bytes per s: the payload of the server's samples and of the bots'
  // samples, and everything the loopback device carried (every process)
  double server_cpu_pct = -1.0, server_rss_kib = -1.0, bots_cpu_pct = -1.0, bots_rss_kib = -1.0;
  double server_bytes = -1.0, bots_bytes = -1.0, lo_bytes = -1.0, lo_packets = -1.0;
};
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(LoadRow, matches, bots, rate, state_rate, bot_processes, server_priority, ready, seconds,
                                   samples_per_s, hits, write_failures, latency_p50_ms, latency_p99_ms,
                                   hit_to_wire_p50_ms, hit_to_wire_p99_ms, hit_to_write_p50_ms, hit_to_write_p99_ms,
                                   delivery_p50_ms, delivery_p99_ms, server_frames, server_overruns,
                                   overrun_pct, frame_p50_ms, frame_p99_ms_median, frame_p99_ms_max, playing,
                                   server_cpu_pct, server_rss_kib, bots_cpu_pct, bots_rss_kib, server_bytes,
                                   bots_bytes, lo_bytes, lo_packets)

// What ball-load's client passed (load.h's LoadMeter): samples taken, by type, and written.
struct PortCounts {
  uint64_t infos = 0, segments = 0, states = 0, events = 0, statuses = 0;
  uint64_t samples_written = 0, controls_written = 0;  // writes accepted
};
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(PortCounts, infos, segments, states, events, statuses, samples_written,
                                   controls_written)

// What one bot process of ball-load measured over the window (--part-json).
struct LoadPart {
  LoadRow row;                         // its bots: matches, bots, ready, seconds, samples_per_s, write_failures
  std::vector<double> latency;         // s, each hit's: newest sample written -> segment received
  std::vector<double> hit_to_wire;     // s, each hit's: the hit's sim time (as real) -> segment received
  std::vector<double> hit_to_write, delivery;  // s, each hit's: its sim time (as real) -> written; written -> received
  std::vector<double> frame_p50, frame_p99;  // s, the server's, each status period's
  StatusOut first, last;               // the server's first and last status of the window
  PortCounts counts;                   // over the window
};
NLOHMANN_DEFINE_TYPE_NON_INTRUSIVE(LoadPart, row, latency, hit_to_wire, hit_to_write, delivery, frame_p50, frame_p99, first, last, counts)

}  // namespace ballsrv
