// The spectator page's HTTP server (docs/bots-and-watchers.md, "The spectator page"):
// cpp-httplib on threads of its own, serving the page's files, three.js
// from Debian's libjs-three, and the Spectator's messages as a stream of
// server-sent events (/stream). The owner changes the Spectator through
// update(), under the server's lock, and the pages get the news at once.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <string>

#include "spectator.h"

namespace ballsrv {

// The page's bounds against hostile clients (docs/bots-and-watchers.md, "The page
// against hostile HTTP"); server/web/http_guard.h keeps them.
struct HttpLimits {
  int queue = 64;                   // accepted connections waiting for a thread; more are closed at once
  int per_address = 16;             // connections one client address holds at once; more are closed at once
  double head_seconds = 5.0;        // a request's head (line and headers) must be whole this long after it begins
  double idle_seconds = 1.0;        // a connection with no request begun this long is closed
  size_t head_bytes = 16384;        // a request's head and body, at most (more: the connection is closed)
  size_t headers = 64;              // header lines of a request, at most (more: 431)
  std::string proxy;                // a reverse proxy's address: no per-address share for it ("": none)
};

struct WebSettings {
  std::string address = "127.0.0.1";  // where it listens (another address only when asked)
  int port = 0;                       // 0: a free port, chosen by the system
  std::string page_dir;               // index.html, app.js, ballwasm.js, style.css
  std::string wasm_file;              // ball.wasm: libball and the client core for the page (page_core.cpp)
  std::string three_dir;              // three.js: build/three.min.js, examples/js/controls/OrbitControls.js
  int max_pages = 8;                  // pages streaming at once; more are told 503
  int pages_per_address = 2;          // pages one client address streams at once; more are told 503
  HttpLimits http;
};

class WebServer {
 public:
  // Binds and starts serving; nullptr with a sentence in err when a file is
  // missing or the address cannot be bound.
  static std::unique_ptr<WebServer> start(const WebSettings &settings, const SpectatorSettings &spectator,
                                          std::function<ball_model(const MatchInfoOut &)> court, std::string *err);
  ~WebServer();  // stops every page's stream and the server, joins its threads
  WebServer(const WebServer &) = delete;
  WebServer &operator=(const WebServer &) = delete;

  int port() const;
  std::string url() const;  // http://ADDRESS:PORT/
  // Changes the spectator under the lock; the pages then get what it sent.
  void update(const std::function<void(Spectator &)> &change);
  uint64_t pages_opened() const;  // streams started so far
  uint64_t pages_refused() const; // streams refused (max_pages)

 private:
  struct Impl;
  explicit WebServer(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace ballsrv
