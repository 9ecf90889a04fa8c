// ball/net.h: the client library's C API, a thin shell over ClientCore
// (client_core.h) and a transport (net_client.h): a DDS participant
// (net_dds.cpp) or the offline tests' port. Every call checks its
// arguments, catches every exception, keeps its sentence in the client and
// returns a ball_status.
#include "ball/net.h"

#include <time.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>
#include <cstring>
#include <map>
#include <utility>
#include <memory>
#include <new>
#include <string>

#include "api_client.h"
#include "client_core.h"
#include "net_client.h"

using namespace ballsrv;
using namespace ballsrv::api;

// The C enums are the wire's, value for value (types.h lists the wire's once).
static_assert(static_cast<int>(MatchState::waiting) == BALL_NET_WAITING && static_cast<int>(MatchState::playing) == BALL_NET_PLAYING &&
                  static_cast<int>(MatchState::paused) == BALL_NET_PAUSED && kEnumCount<MatchState> == BALL_NET_STATE_COUNT,
              "ball_net_state is MatchState");
static_assert(static_cast<int>(Cause::serve) == BALL_NET_CAUSE_SERVE && static_cast<int>(Cause::racket) == BALL_NET_CAUSE_RACKET &&
                  kEnumCount<Cause> == BALL_NET_CAUSE_COUNT,
              "ball_net_cause is Cause");
static_assert(static_cast<int>(EventKind::floor) == BALL_NET_EVENT_FLOOR &&
                  static_cast<int>(EventKind::refused) == BALL_NET_EVENT_REFUSED &&
                  kEnumCount<EventKind> == BALL_NET_EVENT_SERVER,
              "ball_net_event_kind begins with EventKind");
static_assert(static_cast<int>(Reason::refused_state) == BALL_NET_REFUSED_STATE && kEnumCount<Reason> == BALL_NET_REASON_COUNT,
              "ball_net_reason is Reason");
static_assert(kMaxPlayers == BALL_NET_MAX_PLAYERS && kNameLen == BALL_NET_NAME_LEN, "ball/net.h's sizes are the wire's");

namespace {

constexpr double kLeaveGrace = 0.2;      // s a LEAVE is given to get out before the participant goes
constexpr double kTeardownLimit = 3.0;   // s the transport is given to delete what it made (dds::kTeardownLimit)
constexpr int kMaxMatches = static_cast<int>(kMaxClientMatches);

const char *or_empty(const char *s) { return s ? s : ""; }

// An enum the C caller passed, as the number it is: a binding may pass any
// int, and C++ must not read one outside the enum's values as the enum
// (undefined; UBSan's -fsanitize=enum stops there).
template <class E>
int number_of(const E &e) {
  static_assert(sizeof(E) == sizeof(int), "a C enum is an int here");
  int v;
  std::memcpy(&v, &e, sizeof v);
  return v;
}

void copy_text(const std::string &text, char *out, size_t size) {
  if (!out || size == 0) return;
  size_t n = std::min(text.size(), size - 1);
  std::memcpy(out, text.data(), n);
  out[n] = '\0';
}

ball_vec3 v3(const ball_vec3 &v) { return v; }

}  // namespace

namespace {

ball_status with_why(ball_net_client *c, ball_status st, const std::string &why) {
  return st == BALL_OK ? c->ok() : c->fail(st, why);
}

// a write the transport refused: its own words appended (e.g. the
// permissions of the identity under DDS Security)
ball_status with_transport(const ball_net_client *c, ball_status st, std::string *why) {
  if (st == BALL_ENETWORK && !c->transport->error().empty()) *why += ": " + c->transport->error();
  return st;
}

void to_c(const MatchInfoOut &i, double sim_now, ball_net_match *out, const ParticipantId &me) {
  std::memset(out, 0, sizeof *out);
  out->id = i.match_id;
  out->server = i.server_id;
  copy_text(i.scene, out->scene, sizeof out->scene);
  out->level = i.level;
  out->state = static_cast<ball_net_state>(i.state);
  out->players = i.players;
  for (int k = 0; k < BALL_NET_MAX_PLAYERS; ++k) {
    out->slots[k].held = i.slots[k].held;
    out->slots[k].present = i.slots[k].present;
    out->slots[k].mine = i.slots[k].held && i.slots[k].owner == me;
  }
  out->score[0] = i.play.score[0];
  out->score[1] = i.play.score[1];
  out->rally = i.play.rally;
  out->serving_side = i.play.serving_side;
  out->time_base = i.settings.time_base;
  out->sim_time = sim_now;
  out->net_x = i.net_x;
  out->court_x[0] = i.court_x[0];
  out->court_x[1] = i.court_x[1];
  out->court_z[0] = i.court_z[0];
  out->court_z[1] = i.court_z[1];
  out->model_hash = i.model_hash;
}

void to_c(const ViewEvent &v, const MatchView *view, double now, ball_net_event *out) {
  std::memset(out, 0, sizeof *out);
  const EventOut &e = v.event;
  out->match = e.match_id;
  out->seq = v.note == ViewNote::none ? e.seq : 0;
  switch (v.note) {
    case ViewNote::none: out->kind = static_cast<ball_net_event_kind>(e.kind); break;
    case ViewNote::server: out->kind = BALL_NET_EVENT_SERVER; break;
    case ViewNote::slot: out->kind = BALL_NET_EVENT_SLOT; break;
    case ViewNote::voided: out->kind = BALL_NET_EVENT_VOIDED; break;  // (the rest: the event taken back)
    case ViewNote::gap: out->kind = BALL_NET_EVENT_GAP; break;
  }
  out->index = e.index;
  out->side = e.side;
  out->in_play = e.in_play;
  out->sound = e.sound;
  out->time = e.time;
  out->local_time = view ? view->clock().local_at(e.time, now) : now;
  out->point = v3(e.point);
  out->velocity_in = v3(e.velocity_in);
  out->velocity_out = v3(e.velocity_out);
  out->reason = static_cast<ball_net_reason>(e.reason);
  out->score[0] = e.score[0];
  out->score[1] = e.score[1];
  out->value = v.note == ViewNote::voided ? e.seq : e.value;
  out->server = e.server_id;
}

}  // namespace

namespace {
// Every member of the public structs, by name (ball_net_offsetof).
#define BALL_NET_CONFIG_FIELDS(X)                                                                              \
  X(domain) X(participant) X(discovery_servers) X(qos_file) X(security_dir) X(identity) X(servers) X(name)     \
  X(max_matches) X(ball_states) X(clock) X(clock_user) X(link_delay) X(link_jitter) X(link_loss) X(link_seed)     \
  X(rackets) X(server_status) X(tcp_peers) X(tls_dir) X(followed_only)
#define BALL_NET_MATCH_FIELDS(X)                                                                               \
  X(id) X(server) X(scene) X(level) X(state) X(players) X(slots) X(score) X(rally) X(serving_side) X(time_base) \
  X(sim_time) X(net_x) X(court_x) X(court_z) X(model_hash)
#define BALL_NET_SLOT_FIELDS(X) X(held) X(present) X(mine)
#define BALL_NET_BALL_FIELDS(X) X(state) X(sim_time) X(segment) X(cause) X(cause_index) X(sound) X(flight)
#define BALL_NET_EVENT_FIELDS(X)                                                                               \
  X(match) X(seq) X(kind) X(index) X(side) X(in_play) X(sound) X(time) X(local_time) X(point) X(velocity_in)   \
  X(velocity_out) X(reason) X(score) X(value) X(server)
#define BALL_NET_STATUS_FIELDS(X)                                                                              \
  X(server) X(clock_known) X(clock_offset) X(clock_uncertainty) X(delay) X(segments) X(events) X(refused)      \
  X(lost) X(late) X(voided) X(samples) X(link_lost) X(write_failures) X(bytes_in) X(bytes_out) X(untrusted)   \
  X(rackets) X(rackets_refused)
#define BALL_NET_PREDICTION_FIELDS(X)                                                                          \
  X(states) X(cap_states) X(n_states) X(events) X(cap_events) X(n_events) X(events_missed) X(end)

using Fields = std::pair<const std::pair<const char *, size_t> *, size_t>;  // a struct's members and their count

Fields fields_of(int type) {
#define BALL_NET_FIELDS(LIST)                                                         \
  {                                                                                   \
    static const std::pair<const char *, size_t> fields[] = {LIST(BALL_NET_OFFSET)};  \
    return {fields, sizeof fields / sizeof fields[0]};                                \
  }
  switch (type) {
#define BALL_NET_OFFSET(f) {#f, offsetof(ball_net_config, f)},
    case BALL_NET_TYPE_CONFIG: BALL_NET_FIELDS(BALL_NET_CONFIG_FIELDS)
#undef BALL_NET_OFFSET
#define BALL_NET_OFFSET(f) {#f, offsetof(ball_net_match, f)},
    case BALL_NET_TYPE_MATCH: BALL_NET_FIELDS(BALL_NET_MATCH_FIELDS)
#undef BALL_NET_OFFSET
#define BALL_NET_OFFSET(f) {#f, offsetof(ball_net_slot, f)},
    case BALL_NET_TYPE_SLOT: BALL_NET_FIELDS(BALL_NET_SLOT_FIELDS)
#undef BALL_NET_OFFSET
#define BALL_NET_OFFSET(f) {#f, offsetof(ball_net_ball, f)},
    case BALL_NET_TYPE_BALL: BALL_NET_FIELDS(BALL_NET_BALL_FIELDS)
#undef BALL_NET_OFFSET
#define BALL_NET_OFFSET(f) {#f, offsetof(ball_net_event, f)},
    case BALL_NET_TYPE_EVENT: BALL_NET_FIELDS(BALL_NET_EVENT_FIELDS)
#undef BALL_NET_OFFSET
#define BALL_NET_OFFSET(f) {#f, offsetof(ball_net_status, f)},
    case BALL_NET_TYPE_STATUS: BALL_NET_FIELDS(BALL_NET_STATUS_FIELDS)
#undef BALL_NET_OFFSET
#define BALL_NET_OFFSET(f) {#f, offsetof(ball_prediction, f)},
    case BALL_NET_TYPE_PREDICTION: BALL_NET_FIELDS(BALL_NET_PREDICTION_FIELDS)
#undef BALL_NET_OFFSET
    case BALL_NET_TYPE_COUNT: break;
  }
#undef BALL_NET_FIELDS
  return {nullptr, 0};
}
}  // namespace

namespace ballsrv {

ball_status core_settings_of(const ball_net_config &config, CoreSettings *out, std::string *why) {
  auto refuse = [&](ball_status st, const std::string &text) {
    *why = text;
    return st;
  };
  if (config.max_matches < 0 || config.max_matches > kMaxMatches)
    return refuse(BALL_ERANGE, "max_matches " + std::to_string(config.max_matches) + " is not in [0, " +
                                   std::to_string(kMaxMatches) + "]");
  if (config.ball_states != 0 && config.ball_states != 1) return refuse(BALL_ERANGE, "ball_states must be 0 or 1");
  if (config.rackets != 0 && config.rackets != 1) return refuse(BALL_ERANGE, "rackets must be 0 or 1");
  if (config.server_status != 0 && config.server_status != 1)
    return refuse(BALL_ERANGE, "server_status must be 0 or 1");
  if (config.followed_only != 0 && config.followed_only != 1)
    return refuse(BALL_ERANGE, "followed_only must be 0 or 1");
  if (config.identity && !config.security_dir && !config.tls_dir)
    return refuse(BALL_EINVAL, "an identity needs security_dir or tls_dir");
  if (config.security_dir && !config.identity) return refuse(BALL_EINVAL, "security_dir needs an identity");
  if (config.tls_dir && !config.identity) return refuse(BALL_EINVAL, "tls_dir needs an identity");
  CoreSettings settings;
  if (!ServerChoice::parse(or_empty(config.servers), &settings.servers, why)) return BALL_ERANGE;
  if (!config.security_dir && !settings.servers.bound().empty())
    return refuse(BALL_EINVAL, "servers bound to certificates (ID=IDENTITY) need security_dir");
  settings.max_matches = static_cast<size_t>(config.max_matches ? config.max_matches : kMaxMatches);
  settings.link = {config.link_delay, config.link_jitter, config.link_loss};
  if (!settings.link.valid()) {
    char text[200];
    std::snprintf(text, sizeof text,
                  "a simulated network of link_delay %g s, link_jitter %g s, link_loss %g: not in [0, %g], [0, %g], "
                  "[0, %g]",
                  config.link_delay, config.link_jitter, config.link_loss, LinkParams::kMaxDelay,
                  LinkParams::kMaxJitter, LinkParams::kMaxLoss);
    return refuse(BALL_ERANGE, text);
  }
  settings.link_seed = config.link_seed;
  settings.rackets = config.rackets != 0;
  *out = settings;
  return BALL_OK;
}

ball_status open_over(std::unique_ptr<Transport> transport, const ball_net_config &config, ball_net_client **client,
                      std::string *why) {
  *client = nullptr;
  CoreSettings settings;
  ball_status st = core_settings_of(config, &settings, why);
  if (st != BALL_OK) return st;
  auto c = std::make_unique<ball_net_client>();
  if (config.clock) {
    c->clock = config.clock;
    c->clock_user = config.clock_user;
  }
  c->port = &transport->port();
  c->rackets = settings.rackets;
  c->core = std::make_unique<ClientCore>(settings, transport->id());
  c->transport = std::move(transport);
  *client = c.release();
  return BALL_OK;
}

}  // namespace ballsrv

extern "C" {

void ball_net_config_default(ball_net_config *config) {
  if (!config) return;
  std::memset(config, 0, sizeof *config);
  config->participant = "loopback";
}

ball_status ball_net_close(ball_net_client *c) {
  ball_status st = usable(c);
  if (st != BALL_OK) return st;
  if (c->in_tap) return c->fail(BALL_EINVAL, "ball_net_close called from the client's own tap");
  return guarded(c, [&] {
    if (c->core->leave_all(*c->port) > 0) usleep(static_cast<useconds_t>(kLeaveGrace * 1e6));
    c->closed = true;
    c->port = nullptr;
    bool done = c->transport->close(kTeardownLimit);
    c->transport.reset();
    return done ? c->ok()
                : c->fail(BALL_ENETWORK, "Fast DDS did not delete the client's entities within 3 s (left to it)");
  });
}

void ball_net_free(ball_net_client *c) {
  if (!c || c->in_tap) return;  // (from its own tap: nothing, as documented)
  if (!c->closed) ball_net_close(c);
  delete c;
}

const char *ball_net_message(const ball_net_client *c) { return c ? c->message.c_str() : ""; }

ball_status ball_net_matches(ball_net_client *c, ball_net_match *out, int cap, int *n) {
  ball_status st = usable(c);
  if (st != BALL_OK) return st;
  if (!n || cap < 0 || (cap > 0 && !out)) return c->fail(BALL_EINVAL, "n must not be NULL, out not NULL when cap > 0");
  return guarded(c, [&] {
    double now = c->now();
    std::vector<const Listed *> list = c->core->matches(now);
    *n = static_cast<int>(list.size());
    for (int k = 0; k < cap && k < *n; ++k) {
      const Listed &l = *list[static_cast<size_t>(k)];
      const MatchView *v = c->core->view(l.info.match_id);
      double sim = v && v->clock().valid() ? v->clock().sim_now(now)
                   : l.info.state == MatchState::playing ? l.info.sim_time + (now - l.heard) * l.info.settings.time_base
                                                         : l.info.sim_time;
      to_c(l.info, sim, &out[k], c->transport->id());
    }
    return c->ok();
  });
}

ball_status ball_net_match_info(ball_net_client *c, uint32_t match, ball_net_match *out) {
  ball_status st = usable(c);
  if (st != BALL_OK) return st;
  if (!out) return c->fail(BALL_EINVAL, "out must not be NULL");
  return guarded(c, [&] {
    double now = c->now();
    const Listed *l = c->core->listed(match, now);
    if (!l) return c->fail(BALL_ENOMATCH, "no server serves match " + std::to_string(match) + " (none heard within " +
                                               std::to_string(static_cast<int>(c->core->silence())) + " s)");
    const MatchView *v = c->core->view(match);
    double sim = v && v->clock().valid() ? v->clock().sim_now(now) : l->info.sim_time;
    to_c(l->info, sim, out, c->transport->id());
    return c->ok();
  });
}

ball_status ball_net_create(ball_net_client *c, uint32_t match, const char *scene, int players, ball_level level) {
  ball_status st = usable(c);
  if (st != BALL_OK) return st;
  if (!scene) return c->fail(BALL_EINVAL, "scene must not be NULL");
  return guarded(c, [&] {
    std::string why;
    return with_why(c, with_transport(c, c->core->create(match, scene, players, number_of(level), *c->port, c->now(), &why), &why), why);
  });
}

ball_status ball_net_join(ball_net_client *c, uint32_t match, int slot) {
  ball_status st = usable(c);
  if (st != BALL_OK) return st;
  if (c->in_tap) return c->fail(BALL_EINVAL, "ball_net_join called from the client's own tap");
  return guarded(c, [&] {
    std::string why;
    return with_why(c, with_transport(c, c->core->join(match, slot, *c->port, c->now(), &why), &why), why);
  });
}

ball_status ball_net_leave(ball_net_client *c, uint32_t match, int slot) {
  ball_status st = usable(c);
  if (st != BALL_OK) return st;
  return guarded(c, [&] {
    std::string why;
    return with_why(c, c->core->leave(match, slot, *c->port, &why), why);
  });
}

ball_status ball_net_slot_of(ball_net_client *c, uint32_t match, int *slot) {
  return on_view(c, match, slot, [&](ball_net_client *cl, const MatchView &v) {
    *slot = v.slot();
    return cl->ok();
  });
}

ball_status ball_net_watch(ball_net_client *c, uint32_t match) {
  ball_status st = usable(c);
  if (st != BALL_OK) return st;
  if (c->in_tap) return c->fail(BALL_EINVAL, "ball_net_watch called from the client's own tap");
  return guarded(c, [&] {
    std::string why;
    return with_why(c, with_transport(c, c->core->watch(match, *c->port, &why), &why), why);
  });
}

ball_status ball_net_unwatch(ball_net_client *c, uint32_t match) {
  ball_status st = usable(c);
  if (st != BALL_OK) return st;
  c->hot_view = nullptr;  // (the view may go)
  return guarded(c, [&] {
    std::string why;
    return with_why(c, c->core->unwatch(match, *c->port, &why), why);
  });
}

ball_status ball_net_ask(ball_net_client *c, uint32_t match, ball_net_request request, double value) {
  ball_status st = usable(c);
  if (st != BALL_OK) return st;
  static const ControlKind kinds[BALL_NET_REQUEST_COUNT] = {ControlKind::serve, ControlKind::level, ControlKind::pause,
                                                            ControlKind::resume, ControlKind::time_base};
  const int r = number_of(request);
  if (r < 0 || r >= BALL_NET_REQUEST_COUNT)
    return c->fail(BALL_EINVAL, "request " + std::to_string(r) + " is not a ball_net_request");
  if (!std::isfinite(value)) return c->fail(BALL_ENONFINITE, "a request's value must be finite");
  return guarded(c, [&] {
    std::string why;
    return with_why(c, c->core->ask(match, kinds[r], value, *c->port, &why), why);
  });
}

ball_status ball_net_push(ball_net_client *c, uint32_t match, int slot, double time, ball_vec3 center,
                          ball_vec3 normal) {
  ball_status st = usable(c);
  if (st != BALL_OK) return st;
  return guarded(c, [&] {
    std::string why;
    return with_why(c, with_transport(c, c->core->push(match, slot, time, center, normal, *c->port, &why), &why), why);
  });
}

ball_status ball_net_set_tap(ball_net_client *c, ball_net_tap tap, void *user) {
  ball_status st = usable(c);
  if (st != BALL_OK) return st;
  if (c->in_tap) return c->fail(BALL_EINVAL, "ball_net_set_tap called from the client's own tap");
  return guarded(c, [&] {
    c->tap = tap;
    c->tap_user = user;
    if (!tap) {
      c->core->on_sample(nullptr);
      return c->ok();
    }
    c->core->on_sample([c](const json &line) {
      // (bytes that are not UTF-8 in a stranger's strings become U+FFFD: the line stays JSON)
      const std::string text = line.dump(-1, ' ', false, json::error_handler_t::replace);
      c->in_tap = true;
      c->tap(c->tap_user, text.c_str(), text.size());
      c->in_tap = false;
    });
    return c->ok();
  });
}

ball_status ball_net_poll(ball_net_client *c, ball_net_event *out, int cap, int *n) {
  ball_status st = usable(c);
  if (st != BALL_OK) return st;
  if (c->in_tap) return c->fail(BALL_EINVAL, "ball_net_poll called from the client's own tap");
  if (!n || cap < 0 || (cap > 0 && !out)) return c->fail(BALL_EINVAL, "n must not be NULL, out not NULL when cap > 0");
  return guarded(c, [&] {
    double now = c->now();
    c->core->pump(*c->port, now, system_clock(CLOCK_REALTIME));
    // a TCP client that hears no server, or no answer to its JOIN, starts anew (docs/deploy.md, "Limits")
    std::string why;
    if (c->transport->renewable() && c->core->wants_renewal(c->port->meets_server(), c->port->hears_server(), now) &&
        c->transport->renew(&why)) {
      c->port = &c->transport->port();
      c->core->renewed(c->transport->id(), now);
    }
    std::deque<ViewEvent> &events = c->core->events();
    int k = 0;
    for (; k < cap && !events.empty(); ++k) {
      to_c(events.front(), c->core->view(events.front().event.match_id), now, &out[k]);
      events.pop_front();
    }
    *n = k;
    return c->ok();
  });
}

const char *ball_net_event_kind_name(ball_net_event_kind kind) {
  static const char *const own[] = {"server", "slot", "voided", "gap"};
  const int k = number_of(kind);
  if (k >= 0 && k < BALL_NET_EVENT_SERVER) return name_of(static_cast<EventKind>(k));
  if (k >= BALL_NET_EVENT_SERVER && k < BALL_NET_EVENT_KIND_COUNT) return own[k - BALL_NET_EVENT_SERVER];
  return "unknown";
}

const char *ball_net_reason_name(ball_net_reason reason) {
  const int r = number_of(reason);
  return r >= 0 && r < BALL_NET_REASON_COUNT ? name_of(static_cast<Reason>(r)) : "unknown";
}

const char *ball_net_state_name(ball_net_state state) {
  const int v = number_of(state);
  return v >= 0 && v < BALL_NET_STATE_COUNT ? name_of(static_cast<MatchState>(v)) : "unknown";
}

const char *ball_net_cause_name(ball_net_cause cause) {
  const int v = number_of(cause);
  return v >= 0 && v < BALL_NET_CAUSE_COUNT ? name_of(static_cast<Cause>(v)) : "unknown";
}

ball_status ball_net_status_of(const ball_net_client *cc, uint32_t match, ball_net_status *out) {
  return on_view(cc, match, out, [&](ball_net_client *c, const MatchView &v) {
    std::memset(out, 0, sizeof *out);
    out->server = v.info().server_id;
    out->clock_known = v.clock().valid();
    out->clock_offset = v.clock().offset();
    out->clock_uncertainty = v.clock().spread();
    out->delay = v.delay();
    const ViewCounters &k = v.counters();
    out->segments = k.segments;
    out->events = k.events;
    out->refused = k.refused;
    out->lost = k.lost;
    out->late = k.late;
    out->voided = k.voided;
    out->term = v.term();
    out->old_owner = k.old_owner;
    const OwnCounters *own = c->core->own(match);
    out->samples = own->samples;
    out->link_lost = own->link_lost;
    out->untrusted = c->port->untrusted();
    out->rackets = own->rackets;
    out->rackets_refused = own->rackets_refused;
    out->write_failures = own->write_failures;
    out->bytes_in = own->bytes_in;
    out->bytes_out = own->bytes_out;
    return c->ok();
  });
}

size_t ball_net_offsetof(ball_net_type type, const char *field) {
  Fields f = fields_of(number_of(type));
  for (size_t i = 0; field && i < f.second; ++i)
    if (std::strcmp(f.first[i].first, field) == 0) return f.first[i].second;
  return static_cast<size_t>(-1);
}

const char *ball_net_field(ball_net_type type, int index) {
  Fields f = fields_of(number_of(type));
  return index >= 0 && static_cast<size_t>(index) < f.second ? f.first[index].first : nullptr;
}

size_t ball_net_sizeof(ball_net_type type) {
  switch (number_of(type)) {
    case BALL_NET_TYPE_CONFIG: return sizeof(ball_net_config);
    case BALL_NET_TYPE_MATCH: return sizeof(ball_net_match);
    case BALL_NET_TYPE_BALL: return sizeof(ball_net_ball);
    case BALL_NET_TYPE_EVENT: return sizeof(ball_net_event);
    case BALL_NET_TYPE_STATUS: return sizeof(ball_net_status);
    case BALL_NET_TYPE_PREDICTION: return sizeof(ball_prediction);
    case BALL_NET_TYPE_SLOT: return sizeof(ball_net_slot);
    case BALL_NET_TYPE_COUNT: break;
  }
  return 0;
}

}  // extern "C"
