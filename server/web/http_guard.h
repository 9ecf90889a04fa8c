// The spectator page's HTTP server, bounded against hostile clients
// (docs/bots-and-watchers.md, "The page against hostile HTTP"): cpp-httplib's
// Server, whose connections are served here instead of by its own loop, so
// that each request's head has a deadline and a byte budget, each client
// address a number of connections, and the queue of accepted connections a
// length. The HTTP itself (request line, headers, ranges, responses) is still
// cpp-httplib's.
#pragma once

#include <httplib.h>

#include <atomic>
#include <cstdint>
#include <map>
#include <memory>
#include <mutex>
#include <string>

#include "web_server.h"

namespace ballsrv {


// What the guard refused, by reason; each connection or request is counted once.
struct HttpRefusals {
  std::atomic<uint64_t> queue_full{0}, per_address{0}, head_late{0}, head_large{0}, too_many_headers{0};
};

class GuardedHttp : public httplib::Server {
 public:
  GuardedHttp(const HttpLimits &limits, int threads);  // threads: connections served at once
  // After a bind: the listening socket's backlog raised from cpp-httplib's 5.
  void widen_backlog();
  const HttpRefusals &refusals() const { return refusals_; }
  const HttpLimits &limits() const { return limits_; }

 private:
  bool process_and_close_socket(socket_t sock) override;
  bool admit(const std::string &address);
  void release(const std::string &address);

  HttpLimits limits_;
  HttpRefusals refusals_;
  std::mutex mutex_;
  std::map<std::string, int> open_;  // connections by client address (under mutex_)
};

}  // namespace ballsrv
