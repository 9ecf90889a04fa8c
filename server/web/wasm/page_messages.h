// The messages the spectator page's core takes and the answers it gives
// (page_core.cpp): for each kind, the JSON paths of its numbers and texts
// ("info.play.score.0") and what each sets of the record it is read into,
// as records.cpp writes the watcher's records. Included by page_core.cpp
// alone; its names are that file's.
#pragma once

#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "ball/ball.h"
#include "match_config.h"
#include "types.h"

namespace page_messages {

using namespace ballsrv;

// ---- numbers from JSON, never undefined behaviour --------------------------
// (a double out of an integer's range is not cast: the value then fails the
// trust rules, which is what a forged number deserves)
inline uint32_t u32(double v) { return v >= 0.0 && v <= 4294967295.0 ? static_cast<uint32_t>(v) : 0xFFFFFFFFu; }
inline int i32(double v) { return v >= -2147483648.0 && v <= 2147483647.0 ? static_cast<int>(v) : INT32_MIN; }
inline bool flag(double v) { return v == 1.0; }

template <class E>
void enum_of(const char *text, E *out) {
  if (!parse_name(text, out)) *out = static_cast<E>(-1);  // no value: refused by the trust rules
}

// What a message is read into.
struct InfoIn {
  uint32_t match = 0;
  double real = 0.0;  // the watcher's realtime when the MatchInfo came
  MatchInfoOut info;
};
struct SegmentIn {
  uint32_t match = 0;
  SegmentOut segment;
};
struct EventIn {
  uint32_t match = 0;
  EventOut event;
};

template <class T>
struct Number {
  const char *path;
  void (*set)(T &, double);
};
template <class T>
struct Text {
  const char *path;
  void (*set)(T &, const char *);
};

#define NUM(T, path, expr) \
  Number<T> { path, [](T &o, double v) { expr; } }
#define TEXT(T, path, expr) \
  Text<T> { path, [](T &o, const char *t) { expr; } }
#define VEC(T, path, field) NUM(T, path ".0", field.x = v), NUM(T, path ".1", field.y = v), NUM(T, path ".2", field.z = v)
#define PLAY(T, path, p)                                                                                      \
  NUM(T, path ".score.0", p.score[0] = i32(v)), NUM(T, path ".score.1", p.score[1] = i32(v)),                 \
      NUM(T, path ".serving_side", p.serving_side = i32(v)), NUM(T, path ".rally", p.rally = u32(v)),          \
      NUM(T, path ".live", p.live = flag(v)), NUM(T, path ".striker", p.striker = i32(v)),                     \
      NUM(T, path ".bounces", p.bounces = i32(v)), NUM(T, path ".bounce_side", p.bounce_side = i32(v)),        \
      NUM(T, path ".net", p.net = flag(v)), NUM(T, path ".rally_start", p.rally_start = v),                    \
      NUM(T, path ".serve_due", p.serve_due = flag(v)), NUM(T, path ".serve_at", p.serve_at = v),              \
      NUM(T, path ".event_seq", p.event_seq = u32(v))
#define FLIGHT(T, prefix, s)                                                                                  \
  NUM(T, prefix "t0", s.t0 = v), VEC(T, prefix "p0", s.p0), VEC(T, prefix "v0", s.v0), VEC(T, prefix "s0", s.s0), \
      NUM(T, prefix "grounded", s.grounded = flag(v) ? 1 : 0)
// who wrote a sample, and when: its match, server and server time
#define FROM(T, path, s)                                                                                      \
  NUM(T, path ".match", s.match_id = u32(v)), NUM(T, path ".server", s.server_id = u32(v)),                   \
      NUM(T, path ".term", s.term = u32(v)), NUM(T, path ".server_time", s.server_time = v)
#define SLOT(i)                                                                                               \
  NUM(InfoIn, "info.slots." #i ".held", o.info.slots[i].held = flag(v)),                                      \
      NUM(InfoIn, "info.slots." #i ".present", o.info.slots[i].present = flag(v)),                            \
      NUM(InfoIn, "info.slots." #i ".samples", o.info.slots[i].samples = u32(v)),                             \
      NUM(InfoIn, "info.slots." #i ".last_seq", o.info.slots[i].last_seq = u32(v)),                           \
      NUM(InfoIn, "info.slots." #i ".last_capture_time", o.info.slots[i].last_capture_time = v)
#define OWNER(i) TEXT(InfoIn, "info.slots." #i ".owner", if (!parse_hex(t, &o.info.slots[i].owner)) o.info.slots[i].owner = {})

// The info message (spectator.h, info_message): the MatchInfo as records.cpp writes it.
inline const Number<InfoIn> kInfoNumbers[] = {
    NUM(InfoIn, "match", o.match = u32(v)),
    NUM(InfoIn, "real", o.real = v),
    FROM(InfoIn, "info", o.info),
    NUM(InfoIn, "info.revision", o.info.revision = u32(v)),
    NUM(InfoIn, "info.level", o.info.level = i32(v)),
    NUM(InfoIn, "info.players", o.info.players = i32(v)),
    PLAY(InfoIn, "info.play", o.info.play),
    NUM(InfoIn, "info.pause_slot", o.info.pause_slot = i32(v)),
    NUM(InfoIn, "info.segment_seq", o.info.segment_seq = u32(v)),
    NUM(InfoIn, "info.segment_index", o.info.segment_cause_index = i32(v)),
    FLIGHT(InfoIn, "info.segment_", o.info.segment),
    NUM(InfoIn, "info.frame_time", o.info.frame_time = v),
    NUM(InfoIn, "info.sim_time", o.info.sim_time = v),
    NUM(InfoIn, "info.net_x", o.info.net_x = v),
    NUM(InfoIn, "info.court_x.0", o.info.court_x[0] = v),
    NUM(InfoIn, "info.court_x.1", o.info.court_x[1] = v),
    NUM(InfoIn, "info.court_z.0", o.info.court_z[0] = v),
    NUM(InfoIn, "info.court_z.1", o.info.court_z[1] = v),
    SLOT(0), SLOT(1), SLOT(2), SLOT(3),
#define BALL_SETTING_NUMBER(f) NUM(InfoIn, "info." #f, o.info.settings.f = static_cast<decltype(o.info.settings.f)>(v)),
    BALL_MATCH_WIRE_SETTINGS(BALL_SETTING_NUMBER)
#undef BALL_SETTING_NUMBER
#define BALL_FLIGHT_NUMBER(f) NUM(InfoIn, "info.model." #f, o.info.model.f = v),
    BALL_FLIGHT_FIELDS(BALL_FLIGHT_NUMBER)
#undef BALL_FLIGHT_NUMBER
};
inline const Text<InfoIn> kInfoTexts[] = {
    TEXT(InfoIn, "model_hash", o.info.model_hash = std::strtoull(t, nullptr, 16)),  // 64 bits in hex
    TEXT(InfoIn, "info.state", enum_of(t, &o.info.state)),
    TEXT(InfoIn, "info.pause_reason", enum_of(t, &o.info.pause_reason)),
    TEXT(InfoIn, "info.segment_cause", enum_of(t, &o.info.segment_cause)),
    TEXT(InfoIn, "info.scene", o.info.scene = t),
    OWNER(0), OWNER(1), OWNER(2), OWNER(3),
};

// The segment message: a Segment as records.cpp writes it.
inline const Number<SegmentIn> kSegmentNumbers[] = {
    NUM(SegmentIn, "match", o.match = u32(v)),
    FROM(SegmentIn, "segment", o.segment),
    NUM(SegmentIn, "segment.seq", o.segment.seq = u32(v)),
    NUM(SegmentIn, "segment.index", o.segment.cause_index = i32(v)),
    FLIGHT(SegmentIn, "segment.", o.segment.segment),
    NUM(SegmentIn, "segment.sound", o.segment.sound = flag(v)),
    NUM(SegmentIn, "segment.correction", o.segment.correction = flag(v)),
    PLAY(SegmentIn, "segment.play", o.segment.play),
};
inline const Text<SegmentIn> kSegmentTexts[] = {
    TEXT(SegmentIn, "segment.cause", enum_of(t, &o.segment.cause)),
};

// The event message: an Event as records.cpp writes it.
inline const Number<EventIn> kEventNumbers[] = {
    NUM(EventIn, "match", o.match = u32(v)),
    FROM(EventIn, "event", o.event),
    NUM(EventIn, "event.seq", o.event.seq = u32(v)),
    NUM(EventIn, "event.index", o.event.index = i32(v)),
    NUM(EventIn, "event.side", o.event.side = i32(v)),
    NUM(EventIn, "event.in_play", o.event.in_play = flag(v)),
    NUM(EventIn, "event.sound", o.event.sound = flag(v)),
    NUM(EventIn, "event.time", o.event.time = v),
    VEC(EventIn, "event.point", o.event.point),
    VEC(EventIn, "event.velocity_in", o.event.velocity_in),
    VEC(EventIn, "event.velocity_out", o.event.velocity_out),
    NUM(EventIn, "event.segment_seq", o.event.segment_seq = u32(v)),
    NUM(EventIn, "event.score.0", o.event.score[0] = i32(v)),
    NUM(EventIn, "event.score.1", o.event.score[1] = i32(v)),
    NUM(EventIn, "event.value", o.event.value = v),
};
inline const Text<EventIn> kEventTexts[] = {
    TEXT(EventIn, "event.kind", enum_of(t, &o.event.kind)),
    TEXT(EventIn, "event.reason", enum_of(t, &o.event.reason)),
};

// What the answers put in the number slots, in order.
inline const char *const kBallPaths[] = {"position.0", "position.1", "position.2", "velocity.0", "velocity.1", "velocity.2",
                                  "spin.0",     "spin.1",     "spin.2",     "seq",        "t0",         "live",
                                  "sound",      "correction"};
inline const char *const kPosePaths[] = {"center.0",   "center.1",   "center.2",   "normal.0", "normal.1",
                                  "normal.2",   "velocity.0", "velocity.1", "velocity.2"};
inline const char *const kCameraPaths[] = {"eye.0", "eye.1", "eye.2", "target.0", "target.1",
                                    "target.2", "up.0", "up.1", "up.2", "fov"};
inline const char *const kMarkerPaths[] = {"kind", "index", "point.0", "point.1", "point.2"};

template <class T, size_t N>
constexpr int count(const T (&)[N]) {
  return static_cast<int>(N);
}

#undef NUM
#undef TEXT
#undef VEC
#undef PLAY
#undef FLIGHT
#undef FROM
#undef SLOT
#undef OWNER

}  // namespace page_messages
