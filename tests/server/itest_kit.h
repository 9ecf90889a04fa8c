// What the networked integration tests share (itest.cpp, itest_failover.cpp):
// the case's environment, a record followed as it grows, the programs
// started and stopped by their owners, and the questions asked of a
// watcher's record.
#pragma once

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <initializer_list>
#include <string>
#include <vector>

#include "check.hpp"
#include "common.h"
#include "process.h"
#include "records.h"

namespace itest {

using namespace ballsrv;
using namespace ballsrv::app;


struct Env {
  std::string bin, work, fastdds;
  std::string source, python, tcpdump;  // the source tree, Debian's python3, tcpdump (the secure case)
  int domain = 0;
  std::string dom() const { return std::to_string(domain); }
};
inline Env g_env;  // the case's, from the command line

// Follows a JSON Lines file as it grows.
class Tail {
 public:
  explicit Tail(std::string path) : path_(std::move(path)) {}
  // reads the complete lines added since the last call
  void poll() {
    std::ifstream f(path_);
    if (!f) return;
    f.seekg(static_cast<std::streamoff>(offset_));
    std::string line;
    while (std::getline(f, line)) {
      if (f.eof()) break;  // no newline yet: a line being written
      offset_ += line.size() + 1;
      json j = json::parse(line, nullptr, false);
      if (!j.is_discarded()) lines.push_back(j);
    }
  }
  std::vector<json> lines;

 private:
  std::string path_;
  size_t offset_ = 0;
};

// A server that must end cleanly when it is told to: status 0 on SIGTERM.
// Declared first in a case, it is stopped last, after its clients.
struct Server {
  Process p;
  Server() = default;
  explicit Server(Process process) : p(std::move(process)) {}
  Server(Server &&) = default;
  Server &operator=(Server &&) = default;
  ~Server() {
    if (p.pid() <= 0 && p.status() == -1) return;  // moved from
    int rc = p.stop(5.0);
    CHECK_MSG(rc == 0, "the server's exit status on SIGTERM: %d", rc);
  }
};

// Processes of one case: started here, stopped by their owners.
struct Case {
  Env env;
  Server server(std::vector<std::string> extra = {}) {
    std::vector<std::string> a = {env.bin + "/ball-server", "--domain", env.dom(), "--startup-wait", "0",
                                  "--duration", "120", "--stats-json", env.work + "/server.json"};
    a.insert(a.end(), extra.begin(), extra.end());
    return Server(Process::start(a, env.work + "/server.out", env.work + "/server.err"));
  }
  Process bot(int slot, std::vector<std::string> extra = {}) {
    std::vector<std::string> a = {env.bin + "/ball-bot", "--domain", env.dom(), "--player", std::to_string(slot),
                                  "--duration", "120"};
    if (std::find(extra.begin(), extra.end(), "--seed") == extra.end()) extra.push_back("--seed"), extra.push_back(std::to_string(slot + 1));
    a.insert(a.end(), extra.begin(), extra.end());
    std::string log = env.work + "/bot" + std::to_string(slot) + "." + std::to_string(++bots_);
    return Process::start(a, log + ".out", log + ".err");
  }
  Process watcher(const std::string &record, std::vector<std::string> extra = {}) {
    std::vector<std::string> a = {env.bin + "/ball-watch", "--domain", env.dom(), "--no-log", "--duration", "120",
                                  "--record", record};
    a.insert(a.end(), extra.begin(), extra.end());
    return Process::start(a, record + ".out", record + ".err");
  }
  int bots_ = 0;
};

inline std::string path(const Env &e, const std::string &name) { return e.work + "/" + name; }

// a file's text ("" if it cannot be read)
inline std::string file_text(const std::string &file) {
  std::ifstream f(file);
  return std::string(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
}

// A watcher's --summary-json file: false (and a failed check) when it cannot be read.
// The project's QoS file with the primary's ownership strength raised to 4e9,
// written to the case's work folder: a forger's writers above any server's.
inline std::string strong_qos(const Env &env) {
  std::string qos = env.work + "/strong_qos.xml", text = file_text(env.source + "/server/qos/ball_qos.xml");
  const std::string primary = "<ownershipStrength><value>20</value></ownershipStrength>";
  size_t at = text.find(primary);
  CHECK_MSG(at != std::string::npos, "no primary strength in the QoS file");
  if (at != std::string::npos)
    text.replace(at, primary.size(), "<ownershipStrength><value>4000000000</value></ownershipStrength>");
  std::string err;
  CHECK(write_file(qos, text, &err));
  return qos;
}

inline bool read_summary(const std::string &file, WatchSummary *out) {
  try {
    *out = json::parse(file_text(file)).get<WatchSummary>();
    return true;
  } catch (const std::exception &e) {
    CHECK_MSG(false, "no summary in %s: %s", file.c_str(), e.what());
    return false;
  }
}

// Runs a program that should end by itself (logs NAME.out and NAME.err in
// the work folder): its exit status (-1: stopped after 20 s), its stderr in *err.
inline int run_to_end(const Env &env, const std::vector<std::string> &argv, const std::string &name, std::string *err) {
  Process p = Process::start(argv, path(env, name + ".out"), path(env, name + ".err"));
  int rc = p.wait(20.0);
  *err = file_text(path(env, name + ".err"));
  return rc;
}

// Polls a record until pred holds for one of its new lines or timeout s pass;
// the line, or null.
inline json wait_for(Tail &t, double timeout, const std::function<bool(const json &)> &pred, size_t *from = nullptr) {
  double end = mono_now() + timeout;
  size_t i = from ? *from : 0;
  while (true) {
    t.poll();
    for (; i < t.lines.size(); ++i)
      if (pred(t.lines[i])) {
        if (from) *from = i + 1;
        return t.lines[i];
      }
    if (mono_now() >= end) break;
    usleep(50000);
  }
  if (from) *from = i;
  return json();
}

// the record's lines, read with records.h
inline double recv(const json &line) { return line.at("recv").get<double>(); }
inline bool is_event(const json &j, EventKind kind) { return record_type(j) == "event" && j.get<EventOut>().kind == kind; }
inline bool is_hit(const json &j) { return is_event(j, EventKind::racket) && j.get<EventOut>().in_play; }
inline bool is_type(const json &j, const char *type) { return record_type(j) == type; }

inline size_t count(const std::vector<json> &lines, const std::function<bool(const json &)> &pred) {
  size_t n = 0;
  for (const auto &j : lines) n += pred(j);
  return n;
}

// A watcher that hears the server already: events are not kept for late
// joiners, so the bots start (and the match serves) only once it is ready.
inline Process ready_watcher(Case &c, const std::string &record, const std::vector<std::string> &extra) {
  Process w = c.watcher(record, extra);
  Tail t(record);
  json r = wait_for(t, 15.0, [](const json &j) { return is_type(j, "ready"); });
  CHECK_MSG(!r.is_null(), "the watcher did not match the server within 15 s");
  return w;
}

// Stops the server (SIGTERM, status 0) and reads its --stats-json `stats`
// (a failed check and an empty report when it cannot).
inline ServerReport stop_server(Server &server, const std::string &stats) {
  int rc = server.p.stop(5.0);
  server.p = Process();
  CHECK_MSG(rc == 0, "the server's exit status %d", rc);
  ServerReport r;
  try {
    std::ifstream f(stats);
    r = json::parse(f).get<ServerReport>();
  } catch (const std::exception &e) {
    CHECK_MSG(false, "the server's report %s: %s", stats.c_str(), e.what());
  }
  return r;
}

// The clients stopped, each with status 0 within 5 s, then the server: its report.
inline ServerReport stop_all(Server &server, std::initializer_list<Process *> clients, const std::string &stats) {
  for (Process *p : clients) {
    int rc = p->stop(5.0);
    CHECK_MSG(rc == 0, "a client's exit status %d", rc);
  }
  return stop_server(server, stats);
}

// A server, a watcher recording to `record` and two bots with the same
// options, started in that order (a braced list is evaluated left to right);
// the server, declared first, is stopped last.
struct Play {
  Server server;
  Process w, b0, b1;
  Tail t;
};

inline Play play(Case &c, const std::vector<std::string> &bot_args, const std::string &record,
          const std::vector<std::string> &watch_extra = {}) {
  return Play{c.server(), ready_watcher(c, record, watch_extra), c.bot(0, bot_args), c.bot(1, bot_args),
              Tail(record)};
}

// the first serve's reception time, or a failed check and -1
inline double first_serve(Tail &t) {
  json serve = wait_for(t, 15.0, [](const json &j) { return is_event(j, EventKind::serve); });
  CHECK_MSG(!serve.is_null(), "no serve within 15 s");
  return serve.is_null() ? -1.0 : recv(serve);
}

// racket hits in play received within `seconds` of t0, up to `want`; *last: when the last came
inline int hits_within(Tail &t, double t0, int want, double seconds, double *last) {
  size_t from = 0;
  int hits = 0;
  *last = t0;
  while (hits < want) {
    json h = wait_for(t, t0 + seconds - realtime_now(), is_hit, &from);
    if (h.is_null()) break;
    hits++;
    *last = recv(h);
  }
  return hits;
}

// racket hits in play within `seconds` of the first serve, up to `want` (0: no serve)
inline int hits_after_serve_within(Tail &t, int want, double seconds) {
  double t0 = first_serve(t), last = 0.0;
  return t0 < 0.0 ? 0 : hits_within(t, t0, want, seconds, &last);
}

// A case, then no Fast DDS file left behind; every Process of the case is
// stopped when it returns.
inline void in_case(void (*fn)(const Env &)) {
  std::vector<std::string> shm_before = dds_shm_files();
  fn(g_env);
  std::vector<std::string> shm_after = dds_shm_files();
  CHECK_MSG(shm_after.size() <= shm_before.size(), "%zu Fast DDS files left in /dev/shm",
            shm_after.size() - shm_before.size());
}

// `fastdds discovery` is a Python launcher that runs fast-discovery-server
// as its child and ends with it. Signals go to that child (SIGINT: a clean
// stop, as by Ctrl-C; SIGKILL: a crash) so that the launcher reaps it: a
// signal to the whole group would leave the server to init as an orphan.
// Declared after its clients, it is stopped first, and Process stops the
// group if that did not end it.
struct DiscoveryServer {
  Process p;
  DiscoveryServer() = default;
  DiscoveryServer(DiscoveryServer &&) = default;
  DiscoveryServer &operator=(DiscoveryServer &&) = default;
  ~DiscoveryServer() { end(SIGINT); }
  void end(int sig) {
    if (!p.running()) return;
    std::ifstream children("/proc/" + std::to_string(p.pid()) + "/task/" + std::to_string(p.pid()) + "/children");
    pid_t child = -1;
    if (children >> child) kill(child, sig);
    else p.signal(sig);
    p.wait(5.0);
  }
};

}  // namespace itest
