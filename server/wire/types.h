// The ball server's vocabulary, free of DDS: what comes in (racket samples,
// control messages), what goes out (segments, events, ball states, match
// info). server/dds/convert.cpp maps each type to its IDL twin in
// idl/ball.idl, field for field; docs/protocol.md describes them on the wire.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <string>

#include "ball/ball.h"
#include "match_config.h"

namespace ballsrv {

constexpr int kMaxPlayers = BALL_MAX_RACKETS;  // player slots per match (IDL MAX_PLAYERS)
constexpr int kNameLen = 32;                   // scene names on the wire, NUL included (IDL NAME_LEN)
constexpr int kMaxDomain = 232;                // DDS domain ids [0, 232]: RTPS maps domain d onto UDP ports
                                               // from 7400 + 250 d, which must stay below 65536

// Who sent a sample or a control message: the DDS participant GUID prefix of
// the client (the DDS layer fills it in from the sample's writer GUID; under
// DDS Security it is the authenticated participant). All zeros: nobody.
using ParticipantId = std::array<uint8_t, 12>;
// The address a participant announced in discovery (its first unicast
// IP locator's 16 bytes, IPv4 in the last 4): the host it says it is on.
// All zeros: none announced, or unknown.
using HostAddress = std::array<uint8_t, 16>;
std::string hex(const ParticipantId &id);                   // 24 hex digits
bool parse_hex(const std::string &text, ParticipantId *id);  // false unless 24 hex digits

// Every enum of the vocabulary is listed once, below, as an X-macro of
// (enumerator, name, IDL constant): the enum itself, its name and its
// parsing (types.cpp, name_of/parse_name) and the compile-time check that
// each enumerator equals its IDL twin (server/dds/convert.cpp) are all made
// from the one list. The names are those of the JSON records, the status
// line and docs/protocol.md.
#define BALL_MATCH_STATES(X)                                                          \
  X(waiting, "waiting", MATCH_WAITING) /* a slot is free or away: nothing moves */    \
  X(playing, "playing", MATCH_PLAYING) /* the sim runs */                             \
  X(paused, "paused", MATCH_PAUSED)    /* a player vanished or asked: the clock stands still */

#define BALL_CAUSES(X)                                                                \
  X(serve, "serve", CAUSE_SERVE)                                                      \
  X(floor, "floor", CAUSE_FLOOR)                                                      \
  X(net, "net", CAUSE_NET)                                                            \
  X(wall, "wall", CAUSE_WALL)       /* cause_index: the wall */                       \
  X(racket, "racket", CAUSE_RACKET) /* cause_index: the racket, which is the player slot */

#define BALL_EVENT_KINDS(X)                                                           \
  X(floor, "floor", EVENT_FLOOR)                                                      \
  X(net, "net", EVENT_NET)                                                            \
  X(wall, "wall", EVENT_WALL)                                                         \
  X(racket, "racket", EVENT_RACKET)                                                   \
  X(sound, "sound", EVENT_SOUND)                                                      \
  X(serve, "serve", EVENT_SERVE)                                                      \
  X(point, "point", EVENT_POINT)                                                      \
  X(pause, "pause", EVENT_PAUSE)                                                      \
  X(resume, "resume", EVENT_RESUME)                                                   \
  X(join, "join", EVENT_JOIN)                                                         \
  X(leave, "leave", EVENT_LEAVE)                                                      \
  X(level, "level", EVENT_LEVEL)                                                      \
  X(time_base, "time_base", EVENT_TIME_BASE)                                          \
  X(refused, "refused", EVENT_REFUSED)

#define BALL_REASONS(X)                                                               \
  X(none, "none", REASON_NONE)                                                        \
  X(point_double_bounce, "double_bounce", POINT_DOUBLE_BOUNCE)                        \
  X(point_out, "out", POINT_OUT)                                                      \
  X(point_net, "net", POINT_NET)                                                      \
  X(point_own_side, "own_side", POINT_OWN_SIDE)                                       \
  X(point_not_returned, "not_returned", POINT_NOT_RETURNED)                           \
  X(point_let, "let", POINT_LET)                                                      \
  X(pause_vanished, "vanished", PAUSE_VANISHED)                                       \
  X(pause_left, "left", PAUSE_LEFT)                                                   \
  X(pause_requested, "requested", PAUSE_REQUESTED)                                    \
  X(refused_slot_held, "slot_held", REFUSED_SLOT_HELD)                                \
  X(refused_not_player, "not_player", REFUSED_NOT_PLAYER)                             \
  X(refused_bad_value, "bad_value", REFUSED_BAD_VALUE)                                \
  X(refused_no_room, "no_room", REFUSED_NO_ROOM)                                      \
  X(refused_state, "state", REFUSED_STATE)

#define BALL_CONTROL_KINDS(X)                                                         \
  X(create, "create", CONTROL_CREATE)                                                 \
  X(join, "join", CONTROL_JOIN)                                                       \
  X(leave, "leave", CONTROL_LEAVE)                                                    \
  X(serve, "serve", CONTROL_SERVE)                                                    \
  X(level, "level", CONTROL_LEVEL)                                                    \
  X(pause, "pause", CONTROL_PAUSE)                                                    \
  X(resume, "resume", CONTROL_RESUME)                                                 \
  X(time_base, "time_base", CONTROL_TIME_BASE)

// What became of a racket sample. Everything but accepted and idle is a drop,
// counted by reason; the order is the index of ServerStatus.drops on the
// wire (docs/protocol.md, "What the server does with a racket sample").
// The third column is not an IDL constant: drops are indices, not an enum.
#define BALL_DROP_REASONS(X)                                                          \
  X(unknown_match, "unknown_match", 0) /* no match with that id on this server */     \
  X(bad_slot, "bad_slot", 1)           /* player index outside the match's slots */   \
  X(not_joined, "not_joined", 2)       /* nobody holds that slot */                   \
  X(not_owner, "not_owner", 3)         /* the slot is held by another participant */  \
  X(nonfinite, "nonfinite", 4)         /* NaN or Inf in the time, the centre or the normal */ \
  X(zero_normal, "zero_normal", 5)     /* |normal| < 1e-6 */                          \
  X(out_of_range, "out_of_range", 6)   /* outside the match's box, |normal| > 1e6, too far ahead */ \
  X(duplicate, "duplicate", 7)         /* the same seq again, or libball's BALL_EDUPLICATE */ \
  X(out_of_order, "out_of_order", 8)   /* seq older than the newest accepted one */   \
  X(stale, "stale", 9)                 /* too old, or libball's BALL_ESTALE */        \
  X(rejected, "rejected", 10)          /* refused by DDS itself (resource limits); DDS layer only */ \
  X(lost, "lost", 11)                  /* never arrived: a gap or a full history; DDS layer only */ \
  X(too_fast, "too_fast", 12)          /* implies a racket faster than max_racket_speed since the previous one */ \
  X(not_permitted, "not_permitted", 13) /* DDS Security: its writer's partition is not the match's */ \
  X(before_hit, "before_hit", 14)      /* captured before its racket's last hit */ \
  X(malformed, "malformed", 15)        /* not readable as a RacketSample (its encapsulation, cut short); DDS layer only */

#define BALL_ENUMERATOR(e, name, idl) e,
enum class MatchState { BALL_MATCH_STATES(BALL_ENUMERATOR) };
enum class Cause { BALL_CAUSES(BALL_ENUMERATOR) };
enum class EventKind { BALL_EVENT_KINDS(BALL_ENUMERATOR) };
enum class Reason { BALL_REASONS(BALL_ENUMERATOR) };
enum class ControlKind { BALL_CONTROL_KINDS(BALL_ENUMERATOR) };
enum class SampleResult : int {
  BALL_DROP_REASONS(BALL_ENUMERATOR)
  drop_count,      // (the number of drop reasons)
  accepted = 100,  // fed to the racket track
  idle,            // well formed, but the match is not playing: refreshes presence only
};
#undef BALL_ENUMERATOR

constexpr int kDropReasons = static_cast<int>(SampleResult::drop_count);
constexpr int kDropSlots = 16;  // IDL DROP_REASONS: room on the wire for more reasons

// A scene name from the wire that a program may look up: letters, digits,
// '_' and '-' only, never a path (a MatchInfo naming a FIFO once hung
// ball-watch).
bool plain_scene_name(const std::string &name);

// Drop counters as words: "12 (stale 10, duplicate 2)", or "0".
std::string drops_text(const std::array<uint64_t, kDropSlots> &drops);

// How many enumerators each enum has (drop reasons: without accepted and idle).
#define BALL_ONE(e, name, idl) +1
template <class E>
constexpr int kEnumCount = 0;
template <>
inline constexpr int kEnumCount<MatchState> = 0 BALL_MATCH_STATES(BALL_ONE);
template <>
inline constexpr int kEnumCount<Cause> = 0 BALL_CAUSES(BALL_ONE);
template <>
inline constexpr int kEnumCount<EventKind> = 0 BALL_EVENT_KINDS(BALL_ONE);
template <>
inline constexpr int kEnumCount<Reason> = 0 BALL_REASONS(BALL_ONE);
template <>
inline constexpr int kEnumCount<ControlKind> = 0 BALL_CONTROL_KINDS(BALL_ONE);
template <>
inline constexpr int kEnumCount<SampleResult> = kDropReasons;
#undef BALL_ONE
// A collision's kind: the ones whose event carries the paper's sound flag
// (docs/protocol.md, "Events")
inline bool is_collision(EventKind k) {
  return k == EventKind::floor || k == EventKind::net || k == EventKind::wall || k == EventKind::racket;
}
// The name of a value ("unknown" for a value outside the list); drop
// reasons also name accepted and idle.
const char *name_of(MatchState v);
const char *name_of(Cause v);
const char *name_of(EventKind v);
const char *name_of(Reason v);
const char *name_of(ControlKind v);
const char *name_of(SampleResult v);
// The value of a name; false (and *out unchanged) for a name not in the list.
template <class E>
bool parse_name(const std::string &name, E *out);


// The fields below carry their unit or meaning in a trailing comment, as
// libball's structs do: "sim s" is the match's sim clock, "server s" the
// server's realtime clock (s since 1970-01-01 UTC), "real s" a duration on
// a wall clock; counts and indices have none. docs/protocol.md, "Time".

// client -> server: one racket pose (RacketSample).
struct RacketSampleIn {
  uint32_t match_id = 0;      // the match
  int player = 0;             // the slot, [0, players)
  uint32_t seq = 0;           // per (match, player) stream: one more than the one written before
  double capture_time = 0.0;  // sim s: when the pose was taken, as the client maps its clock
  ball_vec3 center{0, 0, 0};  // m: the disc centre
  ball_vec3 normal{1, 0, 0};  // the disc normal, any length in [1e-6, 1e6] (normalised by libball)
  ParticipantId from{};       // the sender: its writer's participant GUID prefix (filled in by the DDS layer)
  double source_time = 0.0;   // server s: the writer's DDS source timestamp (0: unknown)
  bool permitted = true;      // false: under DDS Security, written outside the match's partition (DDS layer)
  bool rejected = false;      // true: the reader had no room for it; it counts only as `rejected` (DDS layer)
};

// client -> server: a control message (MatchControl).
// The match ids a CREATE may name: [first, first + count); count 0: none.
struct CreateIds {
  uint32_t first = 0;
  uint32_t count = 4096;  // by default the ids 0 to 4095, as many as a client's readers make room for
  bool has(uint32_t id) const { return id - first < count; }  // (unsigned: below first wraps far above)
  bool operator==(const CreateIds &o) const { return first == o.first && count == o.count; }
};

struct ControlIn {
  uint32_t match_id = 0;      // the match (CREATE: the new one's id)
  uint32_t seq = 0;           // per writer; echoed in a refusal
  ControlKind kind = ControlKind::join;
  int player = -1;            // JOIN: the slot wanted, -1 any; LEAVE: the slot
  int level = 0;              // LEVEL, CREATE: 1 easy, 2 mid, 3 advanced (CREATE: 0 the scene's)
  double time_base = 1.0;     // TIME_BASE: sim s per real s
  int players = 2;            // CREATE: slots
  std::string scene;          // CREATE: a scene name of the server's catalogue
  ParticipantId from{};       // the sender (filled in by the DDS layer)
  HostAddress host{};         // CREATE: the address the sender's participant announced (DDS layer)
  bool valid = true;          // false: an enum out of range or a scene name without its NUL on the wire
  bool permitted = true;      // false: under DDS Security, written outside the match's partition (DDS layer)
  bool rejected = false;      // true: the reader had no room for it; it counts only as `rejected` (DDS layer)
};

// The newest sample of a racket when it hit the ball, for latency.
struct SampleRef {
  bool valid = false;         // false: no sample (the segment is not a racket hit)
  uint32_t seq = 0;           // its seq
  double source_time = 0.0;   // server s: its DDS source timestamp (the player's realtime clock)
  double capture_time = 0.0;  // sim s: its capture time
};

// The rules' state of a match (Play on the wire: docs/protocol.md,
// "Segments") once a segment's collision is judged, or at a MatchInfo's sim
// time: what another server goes on from. Its fields are listed once, for
// the DDS layer and the records.
#define BALL_PLAY_FIELDS(X) \
  X(score) X(serving_side) X(rally) X(live) X(striker) X(bounces) X(bounce_side) X(net) X(rally_start) \
  X(serve_due) X(serve_at) X(event_seq)
struct PlayState {
  std::array<int, 2> score{0, 0};  // points of side 0 and side 1
  int serving_side = 0;            // the side that serves next
  uint32_t rally = 0;              // points played so far, lets included
  bool live = false;               // a rally is on: its point is not decided yet
  int striker = 0;                 // the side of the last stroke (the serve counts)
  int bounces = 0;                 // bounces since that stroke
  int bounce_side = 0;             // the side of the first of them
  bool net = false;                // the ball touched the net since that stroke
  double rally_start = 0.0;        // sim s: when the rally began
  bool serve_due = true;           // a serve is due at serve_at
  double serve_at = 0.0;           // sim s
  uint32_t event_seq = 0;          // seq of the match's newest event
};

inline bool operator==(const PlayState &a, const PlayState &b) {
  bool same = true;
#define BALL_SAME_PLAY(f) same = same && a.f == b.f;
  BALL_PLAY_FIELDS(BALL_SAME_PLAY)
#undef BALL_SAME_PLAY
  return same;
}

// When a reader's DDS took a server sample, for its clock and its delays:
// not on the wire.
struct Reception {
  double received = 0.0;  // realtime s its DDS reader received it (0: unknown)
  double written = 0.0;   // its DDS source timestamp, the writer's realtime s (0: unknown)
  ParticipantId from{};   // its writer's participant GUID prefix (zeros: unknown)
};

// server -> clients: a flight segment (Segment). Every server sample carries
// the server's id and the server s of its publication; the loop fills them in.
struct SegmentOut {
  uint32_t match_id = 0;      // the match
  uint32_t server_id = 0;     // the server that wrote it
  uint32_t term = 0;              // the owner's term of the match (docs/protocol.md, "Terms")
  double server_time = 0.0;   // server s: when it was published
  uint32_t seq = 0;           // 1, 2, ... per match
  Cause cause = Cause::serve; // what started it
  int cause_index = -1;       // WALL: the wall; RACKET: the racket (slot); SERVE: the serving slot; else -1
  ball_segment segment{};     // t0 sim s, p0 m, v0 m/s, s0 m/s, grounded (libball's ball_segment)
  bool sound = false;         // its collision makes the paper's sound
  bool correction = false;    // written by a rewind for a late racket sample (docs/protocol.md, "Corrections")
  uint64_t model_hash = 0;    // ball_model_hash of the model that made it
  SampleRef sample;           // RACKET: the hitting racket's newest sample
  PlayState play;             // the rules' state once its collision is judged
  Reception reception;        // a reader's, not on the wire
};

// server -> clients: a collision or a match event (Event).
struct EventOut {
  uint32_t match_id = 0;           // the match
  uint32_t server_id = 0;          // the server that wrote it
  uint32_t term = 0;              // the owner's term of the match (docs/protocol.md, "Terms")
  double server_time = 0.0;        // server s: when it was published
  uint32_t seq = 0;                // 1, 2, ... per match: a gap means events were lost
  EventKind kind = EventKind::floor;
  int index = -1;                  // by kind (docs/protocol.md, "Events"): wall, racket, slot or control kind
  int side = -1;                   // collisions: 0 x < net_x, 1 beyond; POINT: the winner, -1 a let
  bool in_play = false;            // collisions: during a rally, before its point was decided
  bool sound = false;              // collisions: loud enough for the paper's sound event
  double time = 0.0;               // sim s
  ball_vec3 point{0, 0, 0};        // m: the ball's centre at the collision
  ball_vec3 velocity_in{0, 0, 0};  // m/s
  ball_vec3 velocity_out{0, 0, 0}; // m/s
  uint32_t segment_seq = 0;        // the segment the collision starts (others: the current one)
  Reason reason = Reason::none;    // POINT, PAUSE, REFUSED: why
  std::array<int, 2> score{0, 0};  // points of side 0 and side 1 after the event
  double value = 0.0;              // LEVEL: the level; TIME_BASE: sim s per real s; REFUSED: the control's seq
  Reception reception;             // a reader's, not on the wire
};

// server -> clients: the ball after a frame (BallState).
struct StateOut {
  uint32_t match_id = 0;      // the match
  uint32_t server_id = 0;     // the server that wrote it
  uint32_t term = 0;              // the owner's term of the match (docs/protocol.md, "Terms")
  double server_time = 0.0;   // server s: the frame's deadline
  uint64_t frame = 0;         // sim steps taken
  double sim_time = 0.0;      // sim s
  MatchState state = MatchState::playing;
  uint32_t segment_seq = 0;   // the segment this state lies on
  ball_state ball{};          // position m, velocity m/s, spin m/s (libball's ball_state)
  uint64_t sim_hash = 0;      // ball_sim_hash after the step
  Reception reception;             // a reader's, not on the wire
};

// A player slot as MatchInfo shows it.
struct SlotInfo {
  bool held = false;               // a participant holds it
  bool present = false;            // its samples arrive within player_timeout and its writer lives
  ParticipantId owner{};           // the holder's participant GUID prefix; zeros when free
  uint32_t samples = 0;            // samples accepted from the holder
  uint32_t last_seq = 0;           // seq of the newest accepted one
  double last_capture_time = 0.0;  // sim s: its capture time
};

// The fields of a match's ball_model that MatchInfo carries (each in the
// model's own unit: ball.h), listed once for the DDS layer and the records.
#define BALL_FLIGHT_FIELDS(X) \
  X(gravity) X(mass) X(air_friction) X(spin_damping) X(radius) X(floor_level) X(effects) X(extrapolation_time) X(stale_time)

// real s: a match's owner writes its MatchInfo on every change and at
// least this often (docs/protocol.md, "Time")
constexpr double kInfoEvery = 4.0;

// server -> clients: a match's setup and state (MatchInfo).
struct MatchInfoOut {
  uint32_t match_id = 0;           // the match
  uint32_t server_id = 0;          // the server that wrote it
  uint32_t term = 0;              // the owner's term of the match (docs/protocol.md, "Terms")
  double server_time = 0.0;        // server s: the instant sim_time holds for (the newest frame's deadline)
  uint32_t revision = 0;           // increments with every MatchInfo the server writes for the match
  MatchState state = MatchState::waiting;
  std::string scene;               // the scene's name, at most 31 bytes
  int level = 0;                   // 0 the scene's own, 1 easy, 2 mid, 3 advanced
  int players = 0;                 // slots in use
  std::array<SlotInfo, kMaxPlayers> slots{};
  PlayState play;                  // the rules' state at sim_time: score, serving side, points played, rally
  Reason pause_reason = Reason::none;  // paused: pause_vanished or pause_requested
  int pause_slot = -1;             // pause_vanished: the slot that vanished
  uint32_t segment_seq = 0;        // the current segment (0: none yet)
  Cause segment_cause = Cause::serve;  // what started it
  int segment_cause_index = -1;    // as SegmentOut's cause_index
  ball_segment segment{};          // its flight: t0 sim s, p0 m, v0 m/s, s0 m/s, grounded
  double frame_time = 0.0;         // real s per frame
  double sim_time = 0.0;           // sim s at server_time
  uint64_t model_hash = 0;         // ball_model_hash of the model the server steps
  // the model; on the wire only its BALL_FLIGHT_FIELDS travel, and a
  // receiver gets them over ball_model_default: enough for ball_segment_eval
  ball_model model{};
  double net_x = 0.0;              // m: the net plane x = net_x
  double court_x[2] = {0, 0};      // m: the court's extent in x
  double court_z[2] = {0, 0};      // m: and in z
  // the match's settings that travel (BALL_MATCH_WIRE_SETTINGS); the
  // others are MatchConfig's defaults
  MatchConfig settings;
  Reception reception;             // a reader's, not on the wire
};

// server -> clients: the whole model a match is stepped with (MatchModel:
// docs/protocol.md, "The match's model").
struct MatchModelOut {
  uint32_t match_id = 0;      // the match
  uint32_t server_id = 0;     // the server that wrote it
  uint64_t model_hash = 0;    // ball_model_hash(&model), as its writer says
  ball_model model{};         // libball's model, every field
};

// A reader's segments of one match, by seq.
using Segments = std::map<uint32_t, SegmentOut>;

// The segment in effect at sim time t (docs/protocol.md, "Evaluating the
// ball from segments"): the highest seq whose t0 is not after t; nullptr:
// none. One written ahead of its contact that a later seq superseded (a
// hit before the contact) never is.
inline const SegmentOut *segment_in_effect(const Segments &segments, double t) {
  for (auto it = segments.rbegin(); it != segments.rend(); ++it)
    if (it->second.segment.t0 <= t) return &it->second;
  return nullptr;
}

// The current segment a MatchInfo carries, as a Segment (without its
// racket sample and its rules' state), for a reader that has not got it.
inline SegmentOut current_segment(const MatchInfoOut &i) {
  SegmentOut s;
  s.match_id = i.match_id;
  s.server_id = i.server_id;
  s.term = i.term;
  s.server_time = i.server_time;
  s.seq = i.segment_seq;
  s.cause = i.segment_cause;
  s.cause_index = i.segment_cause_index;
  s.segment = i.segment;
  s.model_hash = i.model_hash;
  s.play = i.play;
  return s;
}

// What a match counts (the server's --stats-json has them per match),
// listed once for the struct and its JSON form.
#define BALL_MATCH_COUNTERS(X)                                                    \
  X(frames)      /* sim steps */                                                  \
  X(hits)        /* racket hits in play */                                        \
  X(dead_hits)   /* racket hits after the point was decided */                    \
  X(bounces)     /* floor contacts in play */                                     \
  X(points)      /* points decided (not lets) */                                  \
  X(lets)        /* rallies replayed */                                           \
  X(serves)      /* serves */                                                     \
  X(pauses)      /* pauses, every reason */                                       \
  X(step_errors) /* frames ball_step refused (never seen; counted, not fatal) */  \
  X(rejected)    /* racket samples that found their share of the reader's inbox full */     \
  X(ahead)       /* segments of static contacts written before the contact */             \
  X(ahead_corrected) /* of those, written again when the contact was stepped */                \
  X(hit_steps)   /* partial frames stepped to a racket hit's instant */                  \
  X(hit_looks)   /* times the next hit was looked for (after frames, samples, hits) */   \
  X(hit_looks_spared) /* of those, answered by the bound a look before gave over two frames */ \
  X(hit_queries) /* of those, first-contact queries made (the rest: no racket within reach) */ \
  X(late_tested) /* late racket samples tested against the ball where it was (rewind_window) */ \
  X(late_ruled_out) /* of those, ruled out by libball's bound at once (one segment since, the racket out of reach) */ \
  X(rewinds)     /* of those, hits found late: the match went back to the hit and on again */ \
  X(rewinds_past_own_hit) /* of those, back past the racket's own last hit, to move it (rewind_own_hit) */
struct MatchCounters {
#define BALL_COUNTER(name) uint64_t name = 0;
  BALL_MATCH_COUNTERS(BALL_COUNTER)
#undef BALL_COUNTER
};

// The server's status line as data (ServerStatus on the wire): totals since
// the start, but for the frame times.
struct StatusOut {
  uint32_t server_id = 0;                    // the server
  double server_time = 0.0;                  // server s: when it was written
  double uptime = 0.0;                       // real s since the server started
  uint32_t matches = 0;                      // hosted
  uint32_t playing = 0;                      // of those, playing
  uint64_t samples_in = 0;                   // racket samples taken, plus those DDS counted as rejected or lost
  uint64_t samples_ok = 0;                   // of those, fed to a racket track
  std::array<uint64_t, kDropSlots> drops{};  // dropped, by reason (BALL_DROP_REASONS order)
  uint64_t controls_in = 0;                  // control messages taken
  uint64_t controls_refused = 0;             // of those, refused or malformed
  uint64_t states_out = 0;                   // BallState samples written
  uint64_t segments_out = 0;                 // Segment samples written
  uint64_t events_out = 0;                   // Event samples written
  uint64_t frames = 0;                       // frames stepped, every match's
  uint64_t overruns = 0;                     // frames that ended after the next deadline
  double frame_p50 = 0.0;                    // real s of work per wake-up, median of the last status period
  double frame_p99 = 0.0;                    // real s, its 99th percentile
  // its place among the servers of a domain (docs/protocol.md, "Several servers")
  uint32_t max_matches = 0;                  // room for matches
  uint32_t following = 0;                    // matches it follows as a standby
  uint32_t claim_room = 0;                   // matches it may still claim; 0: it claims none
  bool standby = false;                      // it follows other servers' matches and takes them over
  uint32_t strength = 0;                     // its match writers' ownership strength
  // the rest of the status line
  uint64_t samples_idle = 0;                 // well formed, their match not playing: presence only
  uint64_t write_failures = 0;               // samples of every topic the port refused to write (the status too)
  uint64_t dds_lost = 0;                     // DDS's own count of gaps in the racket writers' sequences (at most 1000 a note)
  double latency_p50 = 0.0;                  // real s, the status period: a hit's newest sample written -> its segment written
  double latency_p99 = 0.0;
};

}  // namespace ballsrv
