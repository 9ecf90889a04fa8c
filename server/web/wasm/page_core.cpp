// The spectator page's core in the browser (docs/bots-and-watchers.md, "The spectator
// page"): compiled to WebAssembly with libball and the client library's
// core (cmake/BallWasm.cmake), called by server/web/page/ballwasm.js. No
// rule of the protocol is written again here: each match the page follows
// is the client library's MatchView (the trust rules, the window of
// segments, the segment in effect, corrections and the events they void),
// its clock is the client library's SimClock over the watcher's (sim time,
// realtime) pairs, the ball is libball's ball_flight_eval of the segment in
// effect, the rackets are libball's tracks (MatchRackets, match_rackets.h:
// ball_racket_push, ball_racket_estimate, as the client library keeps them
// for every client: ball_net_racket) and the cameras libball's presets.
//
// A C ABI of scalars and the core's own buffers: the glue copies a
// message's numbers and names from the browser's JSON.parse into the slots
// page_core_numbers and page_core_texts, at the places the message kind's
// paths say (page_core_path, page_core_text_path: "info.play.score.0"),
// and calls page_core_take; an answer (the ball, a racket's pose, a camera)
// comes back in the number slots at the places its kind's paths say, and a
// list (a trail, markers) in page_core_out. Each match is keyed by its id.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "ball/ball.h"
#include "ball/render.h"
#include "ball/vec3.h"
#include "match_rackets.h"
#include "match_view.h"
#include "page_messages.h"
#include "sim_clock.h"

namespace {

using namespace ballsrv;
using namespace page_messages;

constexpr int kSlots = 160;        // number slots
constexpr int kTexts = 12;         // text slots
constexpr int kTextLen = 48;       // bytes a text slot holds, its NUL included
constexpr int kOut = 3 * 1024;     // doubles of the list buffer
constexpr size_t kKeptEvents = 64; // events kept per match for the markers
constexpr double kKeptFor = 5.0;   // sim s they are kept

enum Kind { kInfo, kSegment, kEvent, kBall, kPose, kCamera, kMarker, kKinds };
const char *const kKindNames[kKinds] = {"info", "segment", "event", "ball", "pose", "camera", "marker"};

static_assert(count(kInfoNumbers) <= kSlots && count(kSegmentNumbers) <= kSlots && count(kEventNumbers) <= kSlots,
              "the number slots hold every message");
static_assert(count(kInfoTexts) <= kTexts, "the text slots hold every message");

// An event given, kept for the markers, and whether a correction took it back.
struct Kept {
  EventOut event;
  bool void_ = false;
};

// One match as the page follows it.
struct PageMatch {
  explicit PageMatch(uint32_t match) : view(fresh_view(match)) {}
  static std::unique_ptr<MatchView> fresh_view(uint32_t match) {
    return std::make_unique<MatchView>(match, ServerChoice{}, ParticipantId{});  // any server; no slot of its own
  }
  std::unique_ptr<MatchView> view;  // the client library's view, fed as the watcher's was (its realtime)
  SimClock clock;              // the page's: the watcher's (sim time, realtime) pairs at the page's clock
  bool has_info = false;       // the newest MatchInfo the view took, for a match started anew
  MatchInfoOut info;
  double info_real = 0.0;
  bool has_court = false;      // the match's whole model (the court message)
  ball_model court{};
  MatchRackets rackets;        // its rackets: one libball track per slot (the watcher's rules)
  std::vector<Kept> events;  // oldest first

  // The segment in effect at sim time `sim`, prepared; nullptr: none.
  const KeptSegment *at(double sim) const {
    const KeptSegment *k = view->in_effect(sim);
    return k && k->ready ? k : nullptr;
  }
  // The watcher's realtime now, as the page's clock maps it: the view's `local`.
  double watcher_now(double local) const { return clock.valid() ? clock.server_now(local) : info_real; }
  void mark_void(uint32_t seq) {
    for (auto &k : events)
      if (k.event.seq == seq) k.void_ = true;
  }
  void keep(const EventOut &e, bool void_) {
    events.push_back(Kept{e, void_});
    size_t old = 0;
    while (old < events.size() && (events.size() - old > kKeptEvents || events[old].event.time < e.time - kKeptFor)) ++old;
    events.erase(events.begin(), events.begin() + static_cast<long>(old));
  }
  // The rackets as the newest MatchInfo has the match, with its court's model
  void follow_rackets() {
    if (has_info && has_court) rackets.follow(info, court);
  }
};

}  // namespace

// The page's core: its matches and the slots messages pass through.
struct page_core {
  std::map<uint32_t, std::unique_ptr<PageMatch>> matches;
  double numbers[kSlots] = {0};
  char texts[kTexts][kTextLen] = {{0}};
  double out[kOut] = {0};
  std::vector<uint32_t> voided;  // the events the last segment taken voided

  PageMatch &match(uint32_t id) {
    auto &m = matches[id];
    if (!m) m = std::make_unique<PageMatch>(id);
    return *m;
  }
  PageMatch *find(uint32_t id) {
    auto it = matches.find(id);
    return it == matches.end() ? nullptr : it->second.get();
  }
  const char *text(int i) {
    texts[i][kTextLen - 1] = '\0';
    return texts[i];
  }
  template <class T, size_t N, size_t M>
  void read(T *into, const Number<T> (&nums)[N], const Text<T> (&txts)[M]) {
    for (size_t i = 0; i < N; ++i) nums[i].set(*into, numbers[i]);
    for (size_t i = 0; i < M; ++i) txts[i].set(*into, text(static_cast<int>(i)));
  }
};

namespace {

int take_info(page_core *core) {
  InfoIn in;
  core->read(&in, kInfoNumbers, kInfoTexts);
  PageMatch &m = core->match(in.match);
  std::vector<ViewEvent> notes;
  if (!m.view->on_info(in.info, in.real, &notes)) return 0;
  m.info = in.info;
  m.info_real = in.real;
  m.has_info = true;
  m.follow_rackets();
  return 1;
}

int take_segment(page_core *core, double local) {
  SegmentIn in;
  core->read(&in, kSegmentNumbers, kSegmentTexts);
  PageMatch &m = core->match(in.match);
  std::vector<ViewEvent> notes;
  core->voided.clear();
  if (!m.view->on_segment(in.segment, m.watcher_now(local), &notes)) return -1;
  for (const auto &n : notes)
    if (n.note == ViewNote::voided) {
      core->voided.push_back(n.event.seq);
      m.mark_void(n.event.seq);
    }
  return static_cast<int>(core->voided.size());
}

int take_event(page_core *core, double local) {
  EventIn in;
  core->read(&in, kEventNumbers, kEventTexts);
  PageMatch &m = core->match(in.match);
  std::vector<ViewEvent> notes;
  uint64_t voided = m.view->counters().voided;
  if (!m.view->on_event(in.event, m.watcher_now(local), &notes)) return 0;
  for (const auto &n : notes)
    if (n.note == ViewNote::none) {
      m.keep(n.event, false);
      return 1;
    }
  if (m.view->counters().voided > voided) {  // a correction that came first took it back
    m.keep(in.event, true);
    return 2;
  }
  return 0;
}

ball_status put_ball(page_core *core, const KeptSegment &k, double sim) {
  ball_state st;
  ball_status s = ball_flight_eval(&k.flight, sim, &st);
  if (s != BALL_OK) return s;
  const SegmentOut &seg = k.segment;
  const double v[] = {st.position.x, st.position.y, st.position.z, st.velocity.x, st.velocity.y,
                      st.velocity.z, st.spin.x,     st.spin.y,     st.spin.z,     static_cast<double>(seg.seq),
                      seg.segment.t0, seg.play.live ? 1.0 : 0.0, seg.sound ? 1.0 : 0.0, seg.correction ? 1.0 : 0.0};
  static_assert(sizeof v / sizeof v[0] == count(kBallPaths), "one value per path");
  std::memcpy(core->numbers, v, sizeof v);
  return BALL_OK;
}

}  // namespace

#define PAGE_API extern "C" __attribute__((visibility("default")))

namespace {
// The sizes and offsets on this target of what the glue writes and reads in
// the module's memory, in the order of ballwasm.js's layout (its test,
// tests/web/wasm_check.py, holds the glue's numbers to these).
const long kLayout[] = {
    sizeof(ball_model),
    sizeof(ball_segment),
    offsetof(ball_segment, t0),
    offsetof(ball_segment, p0),
    offsetof(ball_segment, v0),
    offsetof(ball_segment, s0),
    offsetof(ball_segment, grounded),
    sizeof(ball_state),
    offsetof(ball_state, position),
    offsetof(ball_state, velocity),
    offsetof(ball_state, spin),
    sizeof(ball_field),
    offsetof(ball_field, name),
    offsetof(ball_field, type),
    offsetof(ball_field, offset),
    sizeof(ball_vec3),
    sizeof(ball_plane),
    sizeof(ball_racket_def),
};
}  // namespace

// kLayout[i]; -1 past the end.
PAGE_API long page_core_layout(int i) { return i >= 0 && i < count(kLayout) ? kLayout[i] : -1; }

// A core of no match; NULL: out of memory (the module has no exceptions:
// libc++ aborts the module on a failed allocation, which the glue reports).
PAGE_API page_core *page_core_open(void) { return new page_core(); }
PAGE_API void page_core_close(page_core *core) { delete core; }

// The slots: kSlots numbers, kTexts texts of kTextLen bytes (NUL included).
PAGE_API double *page_core_numbers(page_core *core) { return core->numbers; }
PAGE_API char *page_core_texts(page_core *core) { return &core->texts[0][0]; }
PAGE_API double *page_core_out(page_core *core) { return core->out; }
PAGE_API int page_core_size(int what) {
  const int sizes[] = {kSlots, kTexts, kTextLen, kOut};
  return what >= 0 && what < 4 ? sizes[what] : -1;
}

// The kinds, by name ("info", ... NULL past the last), and the JSON path
// of a kind's number slot i and text slot i (NULL past the last).
PAGE_API const char *page_core_kind_name(int kind) { return kind >= 0 && kind < kKinds ? kKindNames[kind] : nullptr; }
PAGE_API const char *page_core_path(int kind, int i) {
  auto pick = [i](const auto &table) -> const char * { return i >= 0 && i < count(table) ? table[i].path : nullptr; };
  auto name = [i](const auto &table) -> const char * { return i >= 0 && i < count(table) ? table[i] : nullptr; };
  switch (kind) {
    case kInfo: return pick(kInfoNumbers);
    case kSegment: return pick(kSegmentNumbers);
    case kEvent: return pick(kEventNumbers);
    case kBall: return name(kBallPaths);
    case kPose: return name(kPosePaths);
    case kCamera: return name(kCameraPaths);
    case kMarker: return name(kMarkerPaths);
    default: return nullptr;
  }
}
PAGE_API const char *page_core_text_path(int kind, int i) {
  auto pick = [i](const auto &table) -> const char * { return i >= 0 && i < count(table) ? table[i].path : nullptr; };
  switch (kind) {
    case kInfo: return pick(kInfoTexts);
    case kSegment: return pick(kSegmentTexts);
    case kEvent: return pick(kEventTexts);
    default: return nullptr;
  }
}

// Takes the message in the slots, of kind info, segment or event, at the
// page's clock `local` (s). info: 1 taken, 0 refused (the trust rules).
// segment: the events it voided (page_core_voided), -1 refused or held
// already. event: 1 given, 2 taken back before it came (a correction came
// first), 0 refused or given already.
PAGE_API int page_core_take(page_core *core, int kind, double local) {
  switch (kind) {
    case kInfo: return take_info(core);
    case kSegment: return take_segment(core, local);
    case kEvent: return take_event(core, local);
    default: return -1;
  }
}
// The seq of the i-th event the last segment taken voided (-1 past the last).
PAGE_API double page_core_voided(page_core *core, int i) {
  return i >= 0 && i < static_cast<int>(core->voided.size()) ? core->voided[i] : -1.0;
}

// A clock message: the watcher's sim time of the match at its realtime
// `real`, received at the page's clock `local`. 1 taken (SimClock::observe).
// Its sim time is the watcher's, which applied the client's rules to the
// server's pairs: taken wherever it is (the clock frozen where a gone
// server left it, a new server's).
PAGE_API int page_core_clock(page_core *core, uint32_t match, double sim_time, double real, double time_base,
                             int running, double local) {
  SimClock &clock = core->match(match).clock;
  clock.rebase();
  return clock.observe(sim_time, real, time_base, running != 0, local) ? 1 : 0;
}
// The match's sim time at the page's clock `local`; NaN without a clock.
PAGE_API double page_core_sim_now(page_core *core, uint32_t match, double local) {
  PageMatch *m = core->find(match);
  return m && m->clock.valid() ? m->clock.sim_now(local) : NAN;
}

// The court message's model (written into the module's memory through
// libball's field tables by the glue) and its ball_model_hash in hex: 1
// taken, 0 refused (a hash that differs: the copy is not the model; a model
// ball_model_check refuses). The view takes it too when its MatchInfo names it.
PAGE_API int page_core_court(page_core *core, uint32_t match, const ball_model *model, const char *hash) {
  if (!model || !hash || ball_model_check(model, nullptr) != BALL_OK ||
      ball_model_hash(model) != std::strtoull(hash, nullptr, 16))
    return 0;
  PageMatch &m = core->match(match);
  m.court = *model;
  m.has_court = true;
  MatchModelOut wire;
  wire.match_id = match;
  wire.server_id = m.info.server_id;
  wire.model_hash = ball_model_hash(model);
  wire.model = *model;
  m.view->on_model(wire);
  m.follow_rackets();
  return 1;
}

// A racket sample of slot `player` at sim time t: a ball_status
// (BALL_EAGAIN: no court or MatchInfo yet; BALL_ERANGE: no such slot;
// ball_racket_push's otherwise).
PAGE_API int page_core_racket(page_core *core, uint32_t match, int player, double t, double cx, double cy, double cz,
                              double nx, double ny, double nz) {
  PageMatch *m = core->find(match);
  if (!m) return BALL_EAGAIN;
  ball_racket_sample s{t, ball_v3(cx, cy, cz), ball_v3(nx, ny, nz)};
  return m->rackets.push(player, s);
}
// Slot `slot`'s racket at sim time t into the number slots (kind pose): a
// ball_status (ball_racket_estimate's; BALL_EAGAIN without tracks).
PAGE_API int page_core_pose(page_core *core, uint32_t match, int slot, double t) {
  PageMatch *m = core->find(match);
  if (!m) return BALL_EAGAIN;
  ball_racket_pose p;
  ball_status st = m->rackets.pose(slot, t, &p);
  if (st != BALL_OK) return st;
  const double v[] = {p.center.x, p.center.y, p.center.z, p.normal.x, p.normal.y, p.normal.z,
                      p.velocity.x, p.velocity.y, p.velocity.z};
  std::memcpy(core->numbers, v, sizeof v);
  return BALL_OK;
}

// The ball at sim time `sim` from the segment in effect then (the client
// library's rule), by libball's ball_flight_eval, into the number slots
// (kind ball: the state, the segment's seq and t0, whether a rally is on
// once its collision is judged (its play.live: 0 is a dead ball), its sound
// and correction flags): a ball_status, BALL_EAGAIN without a segment.
PAGE_API int page_core_ball(page_core *core, uint32_t match, double sim) {
  PageMatch *m = core->find(match);
  if (!std::isfinite(sim)) return BALL_ENONFINITE;
  const KeptSegment *k = m ? m->at(sim) : nullptr;
  return k ? put_ball(core, *k, sim) : BALL_EAGAIN;
}

// The ball's path over the `seconds` before `sim`, evaluated from the
// segments in effect (at most `cap` points, the segments' starts among
// them so the bounces are corners), from the serve in effect on (a serve
// puts the ball in the server's hand: nothing flew from where it was),
// oldest first, x y z each, in page_core_out: how many points.
PAGE_API int page_core_trail(page_core *core, uint32_t match, double sim, double seconds, int cap) {
  PageMatch *m = core->find(match);
  if (!m || !std::isfinite(sim) || !(seconds > 0.0) || !std::isfinite(seconds)) return 0;
  cap = std::min(cap, kOut / 3);
  int uniform = cap - static_cast<int>(MatchView::kWindow) - 1;
  if (uniform < 2) return 0;
  double from = sim - seconds;
  for (double t = sim;;) {  // the newest serve in effect by sim
    const KeptSegment *k = m->view->in_effect(t);
    if (!k || k->segment.segment.t0 <= from) break;
    if (k->segment.cause == Cause::serve) {
      from = k->segment.segment.t0;
      break;
    }
    t = std::nextafter(k->segment.segment.t0, -HUGE_VAL);
  }
  std::vector<double> times;
  for (int i = 0; i < uniform; ++i) times.push_back(from + (sim - from) * i / (uniform - 1));
  for (const auto &k : m->view->window()) {
    double t0 = k.segment.segment.t0;
    if (t0 > from && t0 < sim) times.insert(std::lower_bound(times.begin(), times.end(), t0), t0);
  }
  int n = 0;
  for (double t : times) {
    const KeptSegment *k = m->at(t);
    ball_state st;
    if (!k || ball_flight_eval(&k->flight, t, &st) != BALL_OK) continue;
    core->out[3 * n] = st.position.x;
    core->out[3 * n + 1] = st.position.y;
    core->out[3 * n + 2] = st.position.z;
    ++n;
  }
  return n;
}

// The collisions of the `seconds` before `sim` to mark (floor, net, wall,
// racket hits; none a correction voided), at most `cap`, in page_core_out,
// each as kind marker says (its ball_event_kind, index, point): how many.
PAGE_API int page_core_markers(page_core *core, uint32_t match, double sim, double seconds, int cap) {
  PageMatch *m = core->find(match);
  if (!m || !std::isfinite(sim) || !std::isfinite(seconds)) return 0;
  cap = std::min(cap, kOut / count(kMarkerPaths));
  int n = 0;
  for (const auto &k : m->events) {
    const EventOut &e = k.event;
    ball_event_kind kind;
    switch (e.kind) {
      case EventKind::floor: kind = BALL_EVENT_FLOOR; break;
      case EventKind::net: kind = BALL_EVENT_NET; break;
      case EventKind::wall: kind = BALL_EVENT_WALL; break;
      case EventKind::racket: kind = BALL_EVENT_RACKET; break;
      default: continue;
    }
    if (k.void_ || e.time > sim || e.time < sim - seconds || n >= cap) continue;
    double *o = core->out + count(kMarkerPaths) * n++;
    o[0] = kind;
    o[1] = e.index;
    o[2] = e.point.x;
    o[3] = e.point.y;
    o[4] = e.point.z;
  }
  return n;
}

// Camera preset `preset` (ball_camera_preset) of the match for an image of
// aspect width / height, framing the court its rules judge (MatchInfo's
// court_x and court_z: ball_camera_from_preset_court, as the court
// message's floor is laid out), into the number slots (kind camera): a
// ball_status, BALL_EAGAIN before the court message.
PAGE_API int page_core_camera(page_core *core, uint32_t match, int preset, double aspect) {
  PageMatch *m = core->find(match);
  if (!m || !m->has_court) return BALL_EAGAIN;
  const double judged[4] = {m->info.court_x[0], m->info.court_z[0], m->info.court_x[1], m->info.court_z[1]};
  ball_camera c;
  auto p = static_cast<ball_camera_preset>(preset);
  ball_status st = m->has_info ? ball_camera_from_preset_court(&m->court, judged, p, aspect, &c) : BALL_EAGAIN;
  if (st != BALL_OK && st != BALL_EINVAL) st = ball_camera_from_preset(&m->court, p, aspect, &c);
  if (st != BALL_OK) return st;
  const double v[] = {c.eye.x, c.eye.y, c.eye.z, c.target.x, c.target.y, c.target.z, c.up.x, c.up.y, c.up.z, c.fov};
  std::memcpy(core->numbers, v, sizeof v);
  return BALL_OK;
}

// The name of a marker's kind (ball_event_kind_name); NULL past the last.
PAGE_API const char *page_core_marker_kind(int kind) {
  return kind >= 0 && kind < BALL_EVENT_KIND_COUNT ? ball_event_kind_name(static_cast<ball_event_kind>(kind)) : nullptr;
}

// A match started anew (the reset message): the view starts over from the
// newest MatchInfo it took; the court, the clock and the rackets stay.
PAGE_API void page_core_reset(page_core *core, uint32_t match) {
  PageMatch *m = core->find(match);
  if (!m) return;
  std::unique_ptr<MatchView> fresh = PageMatch::fresh_view(match);
  std::vector<ViewEvent> notes;
  if (m->has_info) fresh->on_info(m->info, m->info_real, &notes);
  if (m->has_court) {
    MatchModelOut wire;
    wire.match_id = match;
    wire.server_id = m->info.server_id;
    wire.model_hash = ball_model_hash(&m->court);
    wire.model = m->court;
    fresh->on_model(wire);
  }
  m->view = std::move(fresh);
  m->events.clear();
}
// Forgets a match; every match (a stream started anew: hello).
PAGE_API void page_core_forget(page_core *core, uint32_t match) { core->matches.erase(match); }
PAGE_API void page_core_clear(page_core *core) { core->matches.clear(); }
