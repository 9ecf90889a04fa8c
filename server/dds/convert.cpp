#include "convert.h"

#include <algorithm>
#include <cstring>
#include <type_traits>

namespace ballsrv {
namespace dds {

// The IDL's sizes, and every enumerator of the server's enums against its
// IDL constant, one by one (the lists are in types.h).
static_assert(balldds::MAX_PLAYERS == kMaxPlayers, "IDL MAX_PLAYERS");
static_assert(balldds::NAME_LEN == kNameLen, "IDL NAME_LEN");
static_assert(balldds::DROP_REASONS == kDropSlots && kDropReasons <= kDropSlots, "IDL DROP_REASONS");
#define BALL_CHECK_STATE(e, name, idl) \
  static_assert(static_cast<int>(MatchState::e) == static_cast<int>(balldds::idl), "MatchState::" #e " is IDL " #idl);
#define BALL_CHECK_CAUSE(e, name, idl) \
  static_assert(static_cast<int>(Cause::e) == static_cast<int>(balldds::idl), "Cause::" #e " is IDL " #idl);
#define BALL_CHECK_EVENT(e, name, idl) \
  static_assert(static_cast<int>(EventKind::e) == static_cast<int>(balldds::idl), "EventKind::" #e " is IDL " #idl);
#define BALL_CHECK_REASON(e, name, idl) \
  static_assert(static_cast<int>(Reason::e) == static_cast<int>(balldds::idl), "Reason::" #e " is IDL " #idl);
#define BALL_CHECK_CONTROL(e, name, idl) \
  static_assert(static_cast<int>(ControlKind::e) == static_cast<int>(balldds::idl), "ControlKind::" #e " is IDL " #idl);
BALL_MATCH_STATES(BALL_CHECK_STATE)
BALL_CAUSES(BALL_CHECK_CAUSE)
BALL_EVENT_KINDS(BALL_CHECK_EVENT)
BALL_REASONS(BALL_CHECK_REASON)
BALL_CONTROL_KINDS(BALL_CHECK_CONTROL)
#undef BALL_CHECK_STATE
#undef BALL_CHECK_CAUSE
#undef BALL_CHECK_EVENT
#undef BALL_CHECK_REASON
#undef BALL_CHECK_CONTROL

namespace {

// An enum from the wire as it came, or kEnumCount<E> for any value outside
// the IDL's: a value of E (a cast to it from one beyond int would not be)
// that a receiver refuses (usable_info, usable_segment).
template <class E, class W>
E wire_enum(W w) {
  return static_cast<E>(std::min(static_cast<uint32_t>(w), static_cast<uint32_t>(kEnumCount<E>)));
}

balldds::Vec3 v3(ball_vec3 v) {
  balldds::Vec3 o;
  o.x(v.x);
  o.y(v.y);
  o.z(v.z);
  return o;
}

ball_vec3 v3(const balldds::Vec3 &v) { return ball_vec3{v.x(), v.y(), v.z()}; }

template <size_t N>
void put_name(const std::string &s, std::array<char, N> *out) {
  out->fill('\0');
  std::memcpy(out->data(), s.data(), std::min(s.size(), N - 1));
}

// a name from the wire: false unless NUL-terminated within the array
template <size_t N>
bool get_name(const std::array<char, N> &in, std::string *out) {
  const char *end = static_cast<const char *>(std::memchr(in.data(), '\0', N));
  if (!end) return false;
  // printable ASCII only (docs/protocol.md, "The wire"): any other byte, an
  // invalid UTF-8 sequence among them, would reach the JSON records and the page
  for (const char *c = in.data(); c != end; ++c)
    if (*c < 0x20 || *c > 0x7e) return false;
  out->assign(in.data(), end);
  return true;
}

template <size_t N>
void put_pid(const ParticipantId &id, std::array<uint8_t, N> *out) {
  static_assert(N == sizeof(ParticipantId), "GUID prefix size");
  std::copy(id.begin(), id.end(), out->begin());
}

// A field between a server type and its IDL twin: a number cast, an array
// element by element.
template <class To>
struct Cast {
  template <class From>
  static To of(const From &v) {
    return static_cast<To>(v);
  }
};
template <class T, size_t N>
struct Cast<std::array<T, N>> {
  template <class F>
  static std::array<T, N> of(const std::array<F, N> &v) {
    std::array<T, N> o;
    for (size_t i = 0; i < N; ++i) o[i] = static_cast<T>(v[i]);
    return o;
  }
};

balldds::Play play_to_idl(const PlayState &p) {
  balldds::Play o;
#define BALL_PUT_PLAY(f) o.f(Cast<std::decay_t<decltype(o.f())>>::of(p.f));
  BALL_PLAY_FIELDS(BALL_PUT_PLAY)
#undef BALL_PUT_PLAY
  return o;
}

PlayState play_from_idl(const balldds::Play &in) {
  PlayState p;
#define BALL_GET_PLAY(f) p.f = Cast<std::decay_t<decltype(p.f)>>::of(in.f());
  BALL_PLAY_FIELDS(BALL_GET_PLAY)
#undef BALL_GET_PLAY
  return p;
}

// libball's ball_model, ball_plane and ball_racket_def against their IDL
// twins (Model, Plane, RacketDef), field for field in the order of
// ball.h; the arrays (net, walls, rackets, vectors) apart.
#define BALL_MODEL_NUMBERS(X)                                                                               \
  X(gravity) X(mass) X(air_friction) X(radius) X(spin_damping) X(floor_level) X(floor_damping)             \
  X(bounce_threshold) X(sound_threshold) X(spin_floor_damping) X(has_net) X(n_walls) X(n_rackets)           \
  X(collision_distance) X(v_min) X(v_max) X(v_up) X(friendly_factor) X(spin_rack_damping)                  \
  X(extrapolation_time) X(stale_time) X(sleep_frames) X(v_up_from_racket) X(history) X(effects)
// libball's enums, each with its count: a value outside [0, count] comes in as the count, which
// ball_model_check refuses (a cast of any other number to the enum would not be one of its values)
#define BALL_MODEL_ENUMS(X) \
  X(detect, BALL_DETECT_COUNT) X(normal_mode, BALL_NORMAL_COUNT) X(response, BALL_RESPONSE_COUNT) \
  X(scheme, BALL_SCHEME_COUNT) X(level, BALL_LEVEL_COUNT)
#define BALL_MODEL_VECTORS(X) X(initial_position) X(initial_velocity) X(initial_spin)
#define BALL_PLANE_NUMBERS(X) X(axis) X(position) X(lo) X(hi) X(bottom) X(top) X(damping)
#define BALL_RACKET_NUMBERS(X) X(radius) X(partner) X(goal_reach)
static_assert(balldds::MAX_WALLS == BALL_MAX_WALLS, "IDL MAX_WALLS");

balldds::Plane plane_to_idl(const ball_plane &p) {
  balldds::Plane o;
#define BALL_PUT(f) o.f(Cast<std::decay_t<decltype(o.f())>>::of(p.f));
  BALL_PLANE_NUMBERS(BALL_PUT)
#undef BALL_PUT
  return o;
}

ball_plane plane_from_idl(const balldds::Plane &in) {
  ball_plane p{};
#define BALL_GET(f) p.f = Cast<std::decay_t<decltype(p.f)>>::of(in.f());
  BALL_PLANE_NUMBERS(BALL_GET)
#undef BALL_GET
  return p;
}

}  // namespace

balldds::MatchModel to_idl(const MatchModelOut &in) {
  balldds::MatchModel o;
  o.match_id(in.match_id);
  o.server_id(in.server_id);
  o.model_hash(in.model_hash);
  balldds::Model &w = o.model();
  const ball_model &m = in.model;
#define BALL_PUT(f) w.f(Cast<std::decay_t<decltype(w.f())>>::of(m.f));
  BALL_MODEL_NUMBERS(BALL_PUT)
#undef BALL_PUT
#define BALL_PUT(f, count) w.f(static_cast<int32_t>(m.f));
  BALL_MODEL_ENUMS(BALL_PUT)
#undef BALL_PUT
#define BALL_PUT(f) w.f(v3(m.f));
  BALL_MODEL_VECTORS(BALL_PUT)
#undef BALL_PUT
  w.net(plane_to_idl(m.net));
  for (int i = 0; i < BALL_MAX_WALLS; ++i) w.walls()[i] = plane_to_idl(m.walls[i]);
  for (int i = 0; i < BALL_MAX_RACKETS; ++i) {
    balldds::RacketDef &r = w.rackets()[i];
#define BALL_PUT(f) r.f(Cast<std::decay_t<decltype(r.f())>>::of(m.rackets[i].f));
    BALL_RACKET_NUMBERS(BALL_PUT)
#undef BALL_PUT
    r.target(v3(m.rackets[i].target));
  }
  return o;
}

void from_idl(const balldds::MatchModel &in, MatchModelOut *o) {
  o->match_id = in.match_id();
  o->server_id = in.server_id();
  o->model_hash = in.model_hash();
  const balldds::Model &w = in.model();
  ball_model &m = o->model;
  m = ball_model{};
  // (numbers as they came: an enum or a count out of range is ball_model_check's to refuse, usable_model)
#define BALL_GET(f) m.f = Cast<std::decay_t<decltype(m.f)>>::of(w.f());
  BALL_MODEL_NUMBERS(BALL_GET)
#undef BALL_GET
#define BALL_GET(f, count) m.f = w.f() >= 0 && w.f() < (count) ? static_cast<decltype(m.f)>(w.f()) : (count);
  BALL_MODEL_ENUMS(BALL_GET)
#undef BALL_GET
#define BALL_GET(f) m.f = v3(w.f());
  BALL_MODEL_VECTORS(BALL_GET)
#undef BALL_GET
  m.net = plane_from_idl(w.net());
  for (int i = 0; i < BALL_MAX_WALLS; ++i) m.walls[i] = plane_from_idl(w.walls()[i]);
  for (int i = 0; i < BALL_MAX_RACKETS; ++i) {
    ball_racket_def &r = m.rackets[i];
#define BALL_GET(f) r.f = Cast<std::decay_t<decltype(r.f)>>::of(w.rackets()[i].f());
    BALL_RACKET_NUMBERS(BALL_GET)
#undef BALL_GET
    r.target = v3(w.rackets()[i].target());
  }
}

balldds::RacketSample to_idl(const RacketSampleIn &in) {
  balldds::RacketSample o;
  o.match_id(in.match_id);
  o.player(static_cast<uint16_t>(in.player));
  o.seq(in.seq);
  o.capture_time(in.capture_time);
  o.center(v3(in.center));
  o.normal(v3(in.normal));
  return o;
}

void from_idl(const balldds::RacketSample &in, RacketSampleIn *o) {
  o->match_id = in.match_id();
  o->player = in.player();
  o->seq = in.seq();
  o->capture_time = in.capture_time();
  o->center = v3(in.center());
  o->normal = v3(in.normal());
}

balldds::MatchControl to_idl(const ControlIn &in) {
  balldds::MatchControl o;
  o.match_id(in.match_id);
  o.seq(in.seq);
  o.kind(static_cast<balldds::ControlKind>(in.kind));
  o.player(static_cast<int16_t>(in.player));
  o.level(in.level);
  o.time_base(in.time_base);
  o.players(static_cast<uint16_t>(in.players));
  put_name(in.scene, &o.scene());
  return o;
}

void from_idl(const balldds::MatchControl &in, ControlIn *o) {
  o->match_id = in.match_id();
  o->seq = in.seq();
  uint32_t kind = static_cast<uint32_t>(in.kind());
  o->valid = kind < static_cast<uint32_t>(kEnumCount<ControlKind>) && get_name(in.scene(), &o->scene);
  o->kind = o->valid ? static_cast<ControlKind>(kind) : ControlKind::join;
  o->player = in.player();
  o->level = in.level();
  o->time_base = in.time_base();
  o->players = in.players();
}

balldds::Segment to_idl(const SegmentOut &in) {
  balldds::Segment o;
  o.match_id(in.match_id);
  o.server_id(in.server_id);
  o.term(in.term);
  o.seq(in.seq);
  o.cause(static_cast<balldds::Cause>(in.cause));
  o.cause_index(static_cast<int16_t>(in.cause_index));
  o.t0(in.segment.t0);
  o.p0(v3(in.segment.p0));
  o.v0(v3(in.segment.v0));
  o.s0(v3(in.segment.s0));
  o.grounded(in.segment.grounded != 0);
  o.sound(in.sound);
  o.correction(in.correction);
  o.server_time(in.server_time);
  o.model_hash(in.model_hash);
  o.sample_seq(in.sample.seq);
  o.sample_source_time(in.sample.valid ? in.sample.source_time : 0.0);
  o.sample_capture_time(in.sample.capture_time);
  o.play(play_to_idl(in.play));
  return o;
}

void from_idl(const balldds::Segment &in, SegmentOut *o) {
  o->match_id = in.match_id();
  o->server_id = in.server_id();
  o->term = in.term();
  o->seq = in.seq();
  o->cause = wire_enum<Cause>(in.cause());  // (usable_segment refuses one outside the IDL's)
  o->cause_index = in.cause_index();
  o->segment.t0 = in.t0();
  o->segment.p0 = v3(in.p0());
  o->segment.v0 = v3(in.v0());
  o->segment.s0 = v3(in.s0());
  o->segment.grounded = in.grounded() ? 1 : 0;
  o->sound = in.sound();
  o->correction = in.correction();
  o->server_time = in.server_time();
  o->model_hash = in.model_hash();
  o->sample.seq = in.sample_seq();
  o->sample.source_time = in.sample_source_time();
  o->sample.capture_time = in.sample_capture_time();
  o->sample.valid = in.sample_source_time() != 0.0;
  o->play = play_from_idl(in.play());
}

balldds::Event to_idl(const EventOut &in) {
  balldds::Event o;
  o.match_id(in.match_id);
  o.server_id(in.server_id);
  o.term(in.term);
  o.seq(in.seq);
  o.kind(static_cast<balldds::EventKind>(in.kind));
  o.index(static_cast<int16_t>(in.index));
  o.side(static_cast<int16_t>(in.side));
  o.in_play(in.in_play);
  o.sound(in.sound);
  o.time(in.time);
  o.server_time(in.server_time);
  o.point(v3(in.point));
  o.velocity_in(v3(in.velocity_in));
  o.velocity_out(v3(in.velocity_out));
  o.segment_seq(in.segment_seq);
  o.reason(static_cast<balldds::Reason>(in.reason));
  o.score({static_cast<uint16_t>(in.score[0]), static_cast<uint16_t>(in.score[1])});
  o.value(in.value);
  return o;
}

void from_idl(const balldds::Event &in, EventOut *o) {
  o->match_id = in.match_id();
  o->server_id = in.server_id();
  o->term = in.term();
  o->seq = in.seq();
  o->kind = static_cast<EventKind>(in.kind());
  o->index = in.index();
  o->side = in.side();
  o->in_play = in.in_play();
  o->sound = in.sound();
  o->time = in.time();
  o->server_time = in.server_time();
  o->point = v3(in.point());
  o->velocity_in = v3(in.velocity_in());
  o->velocity_out = v3(in.velocity_out());
  o->segment_seq = in.segment_seq();
  o->reason = static_cast<Reason>(in.reason());
  o->score = {in.score()[0], in.score()[1]};
  o->value = in.value();
}

balldds::BallState to_idl(const StateOut &in) {
  balldds::BallState o;
  o.match_id(in.match_id);
  o.server_id(in.server_id);
  o.term(in.term);
  o.frame(in.frame);
  o.sim_time(in.sim_time);
  o.server_time(in.server_time);
  o.state(static_cast<balldds::MatchState>(in.state));
  o.segment_seq(in.segment_seq);
  o.position(v3(in.ball.position));
  o.velocity(v3(in.ball.velocity));
  o.spin(v3(in.ball.spin));
  o.sim_hash(in.sim_hash);
  return o;
}

void from_idl(const balldds::BallState &in, StateOut *o) {
  o->match_id = in.match_id();
  o->server_id = in.server_id();
  o->term = in.term();
  o->frame = in.frame();
  o->sim_time = in.sim_time();
  o->server_time = in.server_time();
  o->state = wire_enum<MatchState>(in.state());
  o->segment_seq = in.segment_seq();
  o->ball.position = v3(in.position());
  o->ball.velocity = v3(in.velocity());
  o->ball.spin = v3(in.spin());
  o->sim_hash = in.sim_hash();
}

balldds::MatchInfo to_idl(const MatchInfoOut &in) {
  balldds::MatchInfo o;
  o.match_id(in.match_id);
  o.server_id(in.server_id);
  o.term(in.term);
  o.revision(in.revision);
  o.state(static_cast<balldds::MatchState>(in.state));
  put_name(in.scene, &o.scene());
  o.level(in.level);
  o.players(static_cast<uint16_t>(in.players));
  for (int i = 0; i < kMaxPlayers; ++i) {
    const SlotInfo &s = in.slots[i];
    balldds::Slot &w = o.slots()[i];
    w.held(s.held);
    w.present(s.present);
    put_pid(s.owner, &w.owner());
    w.samples(s.samples);
    w.last_seq(s.last_seq);
    w.last_capture_time(s.last_capture_time);
  }
  o.play(play_to_idl(in.play));
  o.pause_reason(static_cast<balldds::Reason>(in.pause_reason));
  o.pause_slot(static_cast<int16_t>(in.pause_slot));
  o.segment_seq(in.segment_seq);
  balldds::Flight f;
  f.cause(static_cast<balldds::Cause>(in.segment_cause));
  f.cause_index(static_cast<int16_t>(in.segment_cause_index));
  f.t0(in.segment.t0);
  f.p0(v3(in.segment.p0));
  f.v0(v3(in.segment.v0));
  f.s0(v3(in.segment.s0));
  f.grounded(in.segment.grounded != 0);
  o.segment(f);
  o.frame_time(in.frame_time);
  o.sim_time(in.sim_time);
  o.server_time(in.server_time);
  o.model_hash(in.model_hash);
#define BALL_PUT_SETTING(f) o.f(in.settings.f);
  BALL_MATCH_WIRE_SETTINGS(BALL_PUT_SETTING)
#undef BALL_PUT_SETTING
#define BALL_PUT(f) o.f(in.model.f);
  BALL_FLIGHT_FIELDS(BALL_PUT)
#undef BALL_PUT
  o.net_x(in.net_x);
  o.court_x({in.court_x[0], in.court_x[1]});
  o.court_z({in.court_z[0], in.court_z[1]});
  return o;
}

void from_idl(const balldds::MatchInfo &in, MatchInfoOut *o) {
  o->match_id = in.match_id();
  o->server_id = in.server_id();
  o->term = in.term();
  o->revision = in.revision();
  o->state = wire_enum<MatchState>(in.state());  // (usable_info refuses one outside the IDL's)
  if (!get_name(in.scene(), &o->scene)) o->scene.clear();
  o->level = in.level();
  o->players = std::min<int>(in.players(), kMaxPlayers);
  for (int i = 0; i < kMaxPlayers; ++i) {
    const balldds::Slot &w = in.slots()[i];
    SlotInfo &s = o->slots[i];
    s.held = w.held();
    s.present = w.present();
    std::copy(w.owner().begin(), w.owner().end(), s.owner.begin());
    s.samples = w.samples();
    s.last_seq = w.last_seq();
    s.last_capture_time = w.last_capture_time();
  }
  o->play = play_from_idl(in.play());
  uint32_t reason = static_cast<uint32_t>(in.pause_reason());
  o->pause_reason = reason < static_cast<uint32_t>(kEnumCount<Reason>) ? static_cast<Reason>(reason) : Reason::none;
  o->pause_slot = in.pause_slot();
  o->segment_seq = in.segment_seq();
  const balldds::Flight &f = in.segment();
  uint32_t cause = static_cast<uint32_t>(f.cause());
  o->segment_cause = cause < static_cast<uint32_t>(kEnumCount<Cause>) ? static_cast<Cause>(cause) : Cause::serve;
  o->segment_cause_index = f.cause_index();
  o->segment.t0 = f.t0();
  o->segment.p0 = v3(f.p0());
  o->segment.v0 = v3(f.v0());
  o->segment.s0 = v3(f.s0());
  o->segment.grounded = f.grounded() ? 1 : 0;
  o->frame_time = in.frame_time();
  o->sim_time = in.sim_time();
  o->server_time = in.server_time();
  o->model_hash = in.model_hash();
#define BALL_GET_SETTING(f) o->settings.f = in.f();
  BALL_MATCH_WIRE_SETTINGS(BALL_GET_SETTING)
#undef BALL_GET_SETTING
  ball_model_default(&o->model);
#define BALL_GET(f) o->model.f = in.f();
  BALL_FLIGHT_FIELDS(BALL_GET)
#undef BALL_GET
  o->net_x = in.net_x();
  o->court_x[0] = in.court_x()[0];
  o->court_x[1] = in.court_x()[1];
  o->court_z[0] = in.court_z()[0];
  o->court_z[1] = in.court_z()[1];
}

balldds::ServerStatus to_idl(const StatusOut &in) {
  balldds::ServerStatus o;
  o.server_id(in.server_id);
  o.server_time(in.server_time);
  o.uptime(in.uptime);
  o.matches(in.matches);
  o.playing(in.playing);
  o.samples_in(in.samples_in);
  o.samples_ok(in.samples_ok);
  std::array<uint64_t, kDropSlots> drops;
  std::copy(in.drops.begin(), in.drops.end(), drops.begin());
  o.drops(drops);
  o.controls_in(in.controls_in);
  o.controls_refused(in.controls_refused);
  o.states_out(in.states_out);
  o.segments_out(in.segments_out);
  o.events_out(in.events_out);
  o.frames(in.frames);
  o.overruns(in.overruns);
  o.frame_p50(in.frame_p50);
  o.frame_p99(in.frame_p99);
  o.max_matches(in.max_matches);
  o.following(in.following);
  o.claim_room(in.claim_room);
  o.standby(in.standby);
  o.strength(in.strength);
  o.samples_idle(in.samples_idle);
  o.write_failures(in.write_failures);
  o.dds_lost(in.dds_lost);
  o.latency_p50(in.latency_p50);
  o.latency_p99(in.latency_p99);
  return o;
}

void from_idl(const balldds::ServerStatus &in, StatusOut *o) {
  o->server_id = in.server_id();
  o->server_time = in.server_time();
  o->uptime = in.uptime();
  o->matches = in.matches();
  o->playing = in.playing();
  o->samples_in = in.samples_in();
  o->samples_ok = in.samples_ok();
  std::copy(in.drops().begin(), in.drops().end(), o->drops.begin());
  o->controls_in = in.controls_in();
  o->controls_refused = in.controls_refused();
  o->states_out = in.states_out();
  o->segments_out = in.segments_out();
  o->events_out = in.events_out();
  o->frames = in.frames();
  o->overruns = in.overruns();
  o->frame_p50 = in.frame_p50();
  o->frame_p99 = in.frame_p99();
  o->max_matches = in.max_matches();
  o->following = in.following();
  o->claim_room = in.claim_room();
  o->standby = in.standby();
  o->strength = in.strength();
  o->samples_idle = in.samples_idle();
  o->write_failures = in.write_failures();
  o->dds_lost = in.dds_lost();
  o->latency_p50 = in.latency_p50();
  o->latency_p99 = in.latency_p99();
}

}  // namespace dds
}  // namespace ballsrv
