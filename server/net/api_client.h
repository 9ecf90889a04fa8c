// The client library's C API, inside (api.cpp, api_ball.cpp): the client
// behind a ball_net_client handle and the checks every call makes. Not
// installed: ball/net.h is the library's only public header.
#pragma once

#include <time.h>

#include <memory>
#include <new>
#include <string>

#include "ball/net.h"
#include "client_core.h"
#include "net_client.h"

namespace ballsrv {
namespace api {

inline double system_clock(clockid_t id) {
  struct timespec ts;
  clock_gettime(id, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

inline double monotonic(void *) { return system_clock(CLOCK_MONOTONIC); }

}  // namespace api
}  // namespace ballsrv

struct ball_net_client {
  ball_net_clock clock = ballsrv::api::monotonic;
  void *clock_user = nullptr;
  std::unique_ptr<ballsrv::Transport> transport;
  ballsrv::ClientPort *port = nullptr;  // the transport's
  std::unique_ptr<ballsrv::ClientCore> core;
  bool closed = false;
  bool rackets = false;  // ball_net_config.rackets
  ball_net_tap tap = nullptr;  // ball_net_set_tap's
  void *tap_user = nullptr;
  bool in_tap = false;         // a tap call is under way
  std::string message;
  // the view the newest ball query found, by match: a game asks for one match's ball every frame
  uint32_t hot_match = 0;
  const ballsrv::MatchView *hot_view = nullptr;

  double now() const { return clock(clock_user); }
  ball_status fail(ball_status st, const std::string &why) {
    message = why;
    return st;
  }
  ball_status ok() {
    if (!message.empty()) message.clear();
    return BALL_OK;
  }
};

namespace ballsrv {
namespace api {

// The client ready for a call; BALL_EINVAL for NULL, BALL_ECLOSED once closed.
inline ball_status usable(const ball_net_client *c) {
  if (!c) return BALL_EINVAL;
  if (c->closed) {
    const_cast<ball_net_client *>(c)->message = "the client is closed";
    return BALL_ECLOSED;
  }
  return BALL_OK;
}

// Runs a call's body: no exception leaves it (an allocation that fails is BALL_ENOMEM).
template <class F>
inline ball_status guarded(ball_net_client *c, F &&body) {
  try {
    return body();
  } catch (const std::bad_alloc &) {
    if (c) c->message = "out of memory";
    return BALL_ENOMEM;
  } catch (const std::exception &e) {
    if (c) c->message = std::string("unexpected: ") + e.what();
    return BALL_ENETWORK;
  } catch (...) {
    if (c) c->message = "unexpected failure";
    return BALL_ENETWORK;
  }
}

inline const MatchView *followed(const ball_net_client *c, uint32_t match) {
  const MatchView *v = c->core->view(match);
  if (!v) const_cast<ball_net_client *>(c)->message = "the client does not follow match " + std::to_string(match);
  return v;
}

// A call on a match the client follows: the client usable, the out-pointer
// not NULL, the match followed, then body(client, view).
template <class F>
inline ball_status on_view(const ball_net_client *cc, uint32_t match, const void *out, F &&body) {
  auto *c = const_cast<ball_net_client *>(cc);
  ball_status st = usable(c);
  if (st != BALL_OK) return st;
  if (!out) return c->fail(BALL_EINVAL, "the out-pointer must not be NULL");
  const MatchView *v = followed(c, match);
  if (!v) return BALL_ENOMATCH;
  return body(c, *v);
}

inline ball_status no_clock(ball_net_client *c, uint32_t match) {
  return c->fail(BALL_EAGAIN, "the clock of match " + std::to_string(match) + " is not known yet");
}

}  // namespace api
}  // namespace ballsrv
