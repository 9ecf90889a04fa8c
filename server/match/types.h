// The ball server's vocabulary, free of DDS: what comes in (racket samples,
// control messages), what goes out (segments, events, ball states, match
// info). server/dds/convert.cpp maps each type to its IDL twin in
// idl/ball.idl, field for field; docs/protocol.md describes them on the wire.
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include "ball/ball.h"

namespace ballsrv {

constexpr int kMaxPlayers = BALL_MAX_RACKETS;  // player slots per match (IDL MAX_PLAYERS)
constexpr int kNameLen = 32;                   // scene names on the wire, NUL included (IDL NAME_LEN)

// Who sent a sample or a control message: the DDS participant GUID prefix of
// the client (the DDS layer fills it in from the sample's writer GUID; under
// DDS Security it is the authenticated participant). All zeros: nobody.
using ParticipantId = std::array<uint8_t, 12>;

enum class MatchState { waiting, playing, paused };
enum class Cause { serve, floor, net, wall, racket };
enum class EventKind {
  floor, net, wall, racket, sound, serve, point, pause, resume, join, leave, level, time_base, refused
};
enum class Reason {
  none,
  point_double_bounce,
  point_out,
  point_net,
  point_own_side,
  point_not_returned,
  point_let,
  pause_vanished,
  pause_left,
  pause_requested,
  refused_slot_held,
  refused_not_player,
  refused_bad_value,
  refused_no_room,
  refused_state
};
enum class ControlKind { create, join, leave, serve, level, pause, resume, time_base };

// What became of a racket sample. Everything but accepted and idle is a drop,
// counted by reason (the order is the wire order of ServerStatus.drops).
enum class SampleResult : int {
  unknown_match = 0,  // no match with that id on this server
  bad_slot,           // player index outside the match's slots
  not_joined,         // nobody holds that slot
  not_owner,          // the slot is held by another participant
  nonfinite,          // NaN or Inf in the time, the centre or the normal
  zero_normal,        // |normal| < 1e-6
  out_of_range,       // centre outside the match's box, |normal| > 1e6, capture time too far ahead
  duplicate,          // the same seq again, or the same pose and time as a kept sample
  out_of_order,       // seq older than the newest accepted one (reordered by the network)
  stale,              // capture time older than the match's sample age limit, or not newer than the newest kept
  rejected,           // refused by DDS itself before the server saw it (resource limits); DDS layer only
  lost,               // never arrived: DDS saw a gap in a writer's sequence numbers; DDS layer only
  drop_count,         // (number of drop reasons)
  accepted = 100,     // fed to the racket track
  idle,               // well formed, but the match is not playing: refreshes presence only
};
constexpr int kDropReasons = static_cast<int>(SampleResult::drop_count);
constexpr int kDropSlots = 16;  // IDL DROP_REASONS: room on the wire for more reasons

const char *drop_name(SampleResult r);  // "unknown_match", ..., "accepted", "idle"
const char *state_name(MatchState s);
const char *cause_name(Cause c);
const char *event_name(EventKind k);
const char *reason_name(Reason r);
const char *control_name(ControlKind k);

struct RacketSampleIn {
  uint32_t match_id = 0;
  int player = 0;
  uint32_t seq = 0;
  double capture_time = 0.0;  // sim s
  ball_vec3 center{0, 0, 0};  // m
  ball_vec3 normal{1, 0, 0};
  ParticipantId from{};       // the sender
  double source_time = 0.0;   // the writer's timestamp, server-comparable realtime s (0: unknown)
};

struct ControlIn {
  uint32_t match_id = 0;
  uint32_t seq = 0;
  ControlKind kind = ControlKind::join;
  int player = -1;
  int level = 0;
  double time_base = 1.0;
  int players = 2;
  std::string scene;  // CREATE
  ParticipantId from{};
  bool valid = true;  // false: an enum out of range or a scene name without its NUL on the wire
};

// The newest sample of a racket when it hit the ball, for latency.
struct SampleRef {
  bool valid = false;
  uint32_t seq = 0;
  double source_time = 0.0;   // realtime s
  double capture_time = 0.0;  // sim s
};

// Server -> client samples carry the server's id and its realtime clock at
// publication (s since 1970); the DDS layer writes them as they are.
struct SegmentOut {
  uint32_t match_id = 0;
  uint32_t server_id = 0;
  double server_time = 0.0;
  uint32_t seq = 0;
  Cause cause = Cause::serve;
  int cause_index = -1;
  ball_segment segment{};
  uint64_t model_hash = 0;
  SampleRef sample;
};

struct EventOut {
  uint32_t match_id = 0;
  uint32_t server_id = 0;
  double server_time = 0.0;
  uint32_t seq = 0;
  EventKind kind = EventKind::floor;
  int index = -1;
  int side = -1;
  bool in_play = false;
  bool sound = false;
  double time = 0.0;  // sim s
  ball_vec3 point{0, 0, 0};
  ball_vec3 velocity_in{0, 0, 0};
  ball_vec3 velocity_out{0, 0, 0};
  uint32_t segment_seq = 0;
  Reason reason = Reason::none;
  std::array<int, 2> score{0, 0};
  double value = 0.0;
};

struct StateOut {
  uint32_t match_id = 0;
  uint32_t server_id = 0;
  double server_time = 0.0;  // the frame's deadline
  uint64_t frame = 0;
  double sim_time = 0.0;
  MatchState state = MatchState::playing;
  uint32_t segment_seq = 0;
  ball_state ball{};
  uint64_t sim_hash = 0;
};

struct SlotInfo {
  bool held = false;
  bool present = false;
  ParticipantId owner{};
  uint32_t samples = 0;
  uint32_t last_seq = 0;
  double last_capture_time = 0.0;
};

struct MatchInfoOut {
  uint32_t match_id = 0;
  uint32_t server_id = 0;
  double server_time = 0.0;  // the instant sim_time holds for
  uint32_t revision = 0;
  MatchState state = MatchState::waiting;
  std::string scene;
  int level = 0;
  int players = 0;
  std::array<SlotInfo, kMaxPlayers> slots{};
  std::array<int, 2> score{0, 0};
  int serving_side = 0;
  uint32_t rally = 0;
  uint32_t segment_seq = 0;
  double frame_time = 0.0;
  double time_base = 1.0;
  double sim_time = 0.0;
  double state_rate = 0.0;
  double player_timeout = 0.0;
  double max_sample_age = 0.0;
  double max_sample_lead = 0.0;
  uint64_t model_hash = 0;
  // the model; on the wire only its flight fields (gravity, mass,
  // air_friction, spin_damping, radius, floor_level, effects,
  // extrapolation_time, stale_time) travel, and a receiver gets them over
  // ball_model_default: enough for ball_segment_eval
  ball_model model{};
  double net_x = 0.0;
  double court_x[2] = {0, 0};
  double court_z[2] = {0, 0};
};

// The server's status line as data (ServerStatus on the wire).
struct StatusOut {
  uint32_t server_id = 0;
  double server_time = 0.0;
  double uptime = 0.0;
  uint32_t matches = 0;
  uint32_t playing = 0;
  uint64_t samples_in = 0;
  uint64_t samples_ok = 0;
  std::array<uint64_t, kDropSlots> drops{};
  uint64_t controls_in = 0;
  uint64_t controls_refused = 0;
  uint64_t states_out = 0;
  uint64_t segments_out = 0;
  uint64_t events_out = 0;
  uint64_t frames = 0;
  uint64_t overruns = 0;
  double frame_p50 = 0.0;  // s
  double frame_p99 = 0.0;  // s
};

}  // namespace ballsrv
