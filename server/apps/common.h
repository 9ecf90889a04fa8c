// What the thin mains share: the stop flag (the one global), the system's
// clocks, finding the QoS profile file, command line pieces and printing.
#pragma once

#include <cmath>
#include <csignal>
#include <cstdio>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "ball/scene.h"
#include "frame_clock.h"
#include "types.h"

namespace CLI {
class App;
}

namespace ballsrv {
namespace app {

// SIGINT and SIGTERM set the stop flag; loops poll stop_requested().
void install_stop_signals();
bool stop_requested();

double realtime_now();  // CLOCK_REALTIME, s since 1970
double mono_now();      // CLOCK_MONOTONIC, s
// Sleeps until CLOCK_MONOTONIC reaches t (absolute: no drift); returns early on a signal.
void sleep_until(double t);

// Puts the calling thread (and threads it starts from then on) under
// SCHED_FIFO at `priority` (1-99): a frame loop that wakes on its deadline
// is not preempted by the other threads and programs of the host. Needs
// root or CAP_SYS_NICE; false with the system's reason in err.
bool set_realtime_priority(int priority, std::string *err);

// The system's clocks for the server loop (frame_clock.h).
class SystemClock : public Clock {
 public:
  double mono() override { return mono_now(); }
  double realtime() override { return realtime_now(); }
  void sleep_until(double t) override { app::sleep_until(t); }
};

// The QoS profile file: `given`, else $BALL_QOS_PROFILE, else the one
// installed beside the program (../share/libball/ball_qos.xml), else the
// build tree's server/qos/ball_qos.xml.
std::string find_profile(const std::string &given);
// libball's example scenes, for names like "rally_mid"
std::string scenes_dir();
// The directory of the running program (ball-demo finds ball-server beside it).
std::string program_dir();

// The DDS options every program has: domain, profile file, participant
// profile, the Discovery Servers of a client profile, a TCP profile's peers,
// port and address ("" and 0: the profile's), DDS Security and TLS.
struct DdsOptions {
  int domain = 0;
  std::string profile;
  std::string participant = "loopback";
  std::string discovery_server;
  std::string security;  // DDS Security's folder ("": an open domain; docs/security.md)
  std::string identity;  // the identity in it: NAME.pem and NAME.key
  std::string tcp_peers;   // a TCP profile's servers, HOST:PORT[;HOST:PORT...] ("": the profile's)
  int tcp_listen = 0;      // a TCP server profile's listening port (0: the profile's)
  std::string tcp_public;  // its address as players reach it, behind a router ("": its own)
  std::string tls;         // TLS's folder for a TCP profile: ca.pem and the identity ("": plain TCP)
};
void add_dds_options(CLI::App &app, DdsOptions *o);
// The same options as arguments, for a program this one starts ("--domain", "7", ...).
std::vector<std::string> dds_arguments(const DdsOptions &o);

bool parse_level(const std::string &text, ball_level *out);  // a name of ball_level_name
std::string level_names();  // "easy, mid, advanced or custom": the game levels, then the scene's own
// Loads a scene: "" or "default" is ball_scene_default, a name without a
// slash is libball's scenes/NAME.yaml, else a file. false with the loader's
// "file:line:column: field: message" in err.
bool load_scene(const std::string &what, ball_scene *scene, std::string *err);
// The model a watcher draws a match with: the court (net, walls, rackets) of
// the scene its MatchInfo names, when that is a plain name of a scene found
// here, else libball's default; the flight fields as the MatchInfo states them.
ball_model court_model(const MatchInfoOut &info);
// The spectator page's files: $BALL_WEB_DIR, else the copy installed beside
// the program (../share/libball/web), else the build tree's server/web/page.
std::string find_page_dir();
// The page's WebAssembly module (libball and the client core): $BALL_WEB_WASM,
// else the copy installed with the page (../share/libball/web/ball.wasm),
// else the build tree's server/web/ball.wasm.
std::string find_page_wasm();
// three.js for the page: $BALL_THREE_DIR, else Debian's libjs-three.
std::string find_three_dir();


// Output files, every write checked: a failure says "cannot write PATH:
// REASON" (the system's words) and makes the program's exit status 1.
bool write_file(const std::string &path, const std::string &text, std::string *err);
// A file written as it goes (a JSON Lines record): each line and each
// flush checked; after a failure, error() says what and where.
class OutputFile {
 public:
  OutputFile() = default;
  ~OutputFile();
  OutputFile(const OutputFile &) = delete;
  OutputFile &operator=(const OutputFile &) = delete;
  bool open(const std::string &path);  // truncates
  bool is_open() const { return f_ != nullptr; }
  bool write_line(const std::string &line);
  bool flush();
  bool close();  // also what is still buffered
  const std::string &error() const { return error_; }

 private:
  bool failed();
  std::string path_, error_;
  std::FILE *f_ = nullptr;
};

// "name: message" to stderr, and the exit status 1
int fail(const char *program, const std::string &message);

}  // namespace app
}  // namespace ballsrv
