#include "web_server.h"

#include "http_guard.h"

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <fstream>
#include <map>
#include <mutex>
#include <sstream>
#include <thread>
#include <utility>
#include <vector>

namespace ballsrv {

namespace {

constexpr size_t kBatch = 256;        // messages one write of a stream carries at most
constexpr auto kKeepAlive = std::chrono::seconds(1);  // a comment line this often when nothing happens

struct File {
  std::string type, body;
};

// The files the page needs: URL path -> (where, name, content type).
enum class From { page, three, wasm };
struct Served {
  const char *path;
  From from;         // the page's folder, three.js's, or the WebAssembly module itself
  const char *name;  // in that folder ("": the module's file)
  const char *type;
};
const Served kFiles[] = {
    {"/", From::page, "index.html", "text/html; charset=utf-8"},
    {"/index.html", From::page, "index.html", "text/html; charset=utf-8"},
    {"/style.css", From::page, "style.css", "text/css; charset=utf-8"},
    {"/ballwasm.js", From::page, "ballwasm.js", "text/javascript; charset=utf-8"},
    {"/app.js", From::page, "app.js", "text/javascript; charset=utf-8"},
    {"/ball.wasm", From::wasm, "", "application/wasm"},
    {"/lib/three.min.js", From::three, "build/three.min.js", "text/javascript; charset=utf-8"},
    {"/lib/OrbitControls.js", From::three, "examples/js/controls/OrbitControls.js", "text/javascript; charset=utf-8"},
};

bool read_all(const std::string &path, std::string *out) {
  std::ifstream f(path, std::ios::binary);
  if (!f) return false;
  std::ostringstream s;
  s << f.rdbuf();
  *out = s.str();
  return static_cast<bool>(f) || f.eof();
}

std::string event_text(const std::string &json_text) { return "data: " + json_text + "\n\n"; }

}  // namespace

struct WebServer::Impl {
  WebSettings settings;
  std::map<std::string, File> files;
  GuardedHttp http;
  std::thread thread;
  int port = 0;
  std::mutex mutex;
  std::condition_variable news;
  Spectator spectator;
  bool stopping = false;  // under mutex
  std::atomic<int> streaming{0};
  std::atomic<uint64_t> opened{0}, refused{0};
  std::map<std::string, int> streaming_from;  // pages streaming, by client address (under mutex)

  // pages stream on threads of their own, beside an address's share of others
  Impl(const WebSettings &s, const SpectatorSettings &ss, std::function<ball_model(const MatchInfoOut &)> court)
      : settings(s), http(s.http, s.max_pages + 2 * s.http.per_address), spectator(ss, std::move(court)) {}

  // The next batch of a page's stream: the snapshot first, then what came
  // after its cursor (waiting for it up to kKeepAlive); a page that fell
  // too far behind starts over. false: the server stops.
  bool next(bool *first, uint64_t *cursor, std::string *out) {
    std::unique_lock<std::mutex> lock(mutex);
    out->clear();
    if (!*first) news.wait_for(lock, kKeepAlive, [&] { return stopping || spectator.newest() > *cursor; });
    if (stopping) return false;
    std::vector<PageMessage> batch;
    if (!*first && !spectator.since(*cursor, kBatch, &batch)) {
      *out += event_text("{\"type\":\"restart\"}");
      *first = true;
    }
    if (*first) {
      for (const auto &text : spectator.snapshot()) *out += event_text(text);
      *cursor = spectator.newest();
      *first = false;
      return true;
    }
    for (const auto &m : batch) {
      *out += event_text(m.text);
      *cursor = m.id;
    }
    if (out->empty()) *out = ": keep-alive\n\n";
    return true;
  }

  // A page's place: within max_pages and its address's share.
  bool take_place(const std::string &address) {
    std::lock_guard<std::mutex> lock(mutex);
    int &mine = streaming_from[address];
    bool shared = settings.http.proxy.empty() || address != settings.http.proxy;
    if (streaming >= settings.max_pages || (shared && mine >= settings.pages_per_address)) {
      if (mine == 0) streaming_from.erase(address);
      return false;
    }
    mine++;
    streaming++;
    return true;
  }
  void leave_place(const std::string &address) {
    std::lock_guard<std::mutex> lock(mutex);
    auto it = streaming_from.find(address);
    if (it != streaming_from.end() && --it->second <= 0) streaming_from.erase(it);
    streaming--;
  }

  void stream(const httplib::Request &req, httplib::Response &res) {
    if (!take_place(req.remote_addr)) {
      refused++;
      res.status = 503;
      res.set_content("too many pages are open\n", "text/plain");
      return;
    }
    opened++;
    auto first = std::make_shared<bool>(true);
    auto cursor = std::make_shared<uint64_t>(0);
    res.set_header("Cache-Control", "no-cache");
    res.set_chunked_content_provider(
        "text/event-stream",
        [this, first, cursor](size_t, httplib::DataSink &sink) {
          std::string text;
          if (!next(first.get(), cursor.get(), &text)) {
            sink.done();
            return false;
          }
          return sink.write(text.data(), text.size());
        },
        [this, address = req.remote_addr](bool) { leave_place(address); });
  }
};

WebServer::WebServer(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}

std::unique_ptr<WebServer> WebServer::start(const WebSettings &settings, const SpectatorSettings &spectator,
                                            std::function<ball_model(const MatchInfoOut &)> court,
                                            std::string *err) {
  auto impl = std::make_unique<Impl>(settings, spectator, std::move(court));
  for (const auto &f : kFiles) {
    std::string path = f.from == From::wasm    ? settings.wasm_file
                       : f.from == From::three ? settings.three_dir + "/" + f.name
                                               : settings.page_dir + "/" + f.name;
    File file{f.type, ""};
    if (!read_all(path, &file.body)) {
      *err = "cannot read " + path +
             (f.from == From::three  ? " (three.js: Debian's libjs-three, which ./run setup installs)"
              : f.from == From::wasm ? " (the page's WebAssembly module: the build's ball_wasm target)"
                                     : " (the page's files)");
      return nullptr;
    }
    impl->files[f.path] = std::move(file);
  }
  Impl *p = impl.get();
  for (const auto &kv : p->files) {
    const File *file = &kv.second;
    p->http.Get(kv.first, [file](const httplib::Request &, httplib::Response &res) {
      res.set_content(file->body, file->type.c_str());
    });
  }
  p->http.Get("/stream", [p](const httplib::Request &req, httplib::Response &res) { p->stream(req, res); });
  p->http.Get("/snapshot", [p](const httplib::Request &, httplib::Response &res) {
    std::string body = "[";
    {
      std::lock_guard<std::mutex> lock(p->mutex);
      for (const auto &text : p->spectator.snapshot()) body += (body.size() > 1 ? "," : "") + text;
    }
    res.set_content(body + "]", "application/json");
  });
  if (settings.port == 0) p->port = p->http.bind_to_any_port(settings.address);
  else p->port = p->http.bind_to_port(settings.address, settings.port) ? settings.port : -1;
  if (p->port <= 0) {
    *err = "cannot listen on " + settings.address + ":" + std::to_string(settings.port);
    return nullptr;
  }
  p->http.widen_backlog();
  p->thread = std::thread([p] { p->http.listen_after_bind(); });
  // serving before start returns: a stop() before the listening loop runs would not end it
  for (int i = 0; i < 2000 && !p->http.is_running(); ++i) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  return std::unique_ptr<WebServer>(new WebServer(std::move(impl)));
}

WebServer::~WebServer() {
  {
    std::lock_guard<std::mutex> lock(impl_->mutex);
    impl_->stopping = true;
  }
  impl_->news.notify_all();
  impl_->http.stop();
  if (impl_->thread.joinable()) impl_->thread.join();
}

int WebServer::port() const { return impl_->port; }

std::string WebServer::url() const {
  const std::string &a = impl_->settings.address;
  std::string host = a.find(':') != std::string::npos ? "[" + a + "]" : a;
  return "http://" + host + ":" + std::to_string(impl_->port) + "/";
}

void WebServer::update(const std::function<void(Spectator &)> &change) {
  {
    std::lock_guard<std::mutex> lock(impl_->mutex);
    change(impl_->spectator);
  }
  impl_->news.notify_all();
}

uint64_t WebServer::pages_opened() const { return impl_->opened; }
uint64_t WebServer::pages_refused() const { return impl_->refused; }

}  // namespace ballsrv
