#include "common.h"

#include "court.h"
#include "match_model.h"

#include <pthread.h>
#include <sched.h>
#include <cstring>

#include <unistd.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <fstream>

namespace ballsrv {
namespace app {

namespace {
volatile std::sig_atomic_t g_stop = 0;  // the one global: set by SIGINT/SIGTERM
void on_stop_signal(int) { g_stop = 1; }

double clock_seconds(clockid_t id) {
  timespec ts;
  clock_gettime(id, &ts);
  return static_cast<double>(ts.tv_sec) + static_cast<double>(ts.tv_nsec) * 1e-9;
}

bool readable(const std::string &path) { return std::ifstream(path).good(); }

}  // namespace

void install_stop_signals() {
  struct sigaction sa {};
  sa.sa_handler = on_stop_signal;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
}

bool stop_requested() { return g_stop != 0; }

std::string program_dir() {
  char buf[4096];
  ssize_t n = readlink("/proc/self/exe", buf, sizeof buf - 1);
  if (n <= 0) return ".";
  std::string p(buf, static_cast<size_t>(n));
  size_t slash = p.rfind('/');
  return slash == std::string::npos ? "." : p.substr(0, slash);
}

double realtime_now() { return clock_seconds(CLOCK_REALTIME); }
double mono_now() { return clock_seconds(CLOCK_MONOTONIC); }

void sleep_until(double t) {
  timespec ts;
  ts.tv_sec = static_cast<time_t>(t);
  ts.tv_nsec = static_cast<long>((t - static_cast<double>(ts.tv_sec)) * 1e9);
  if (ts.tv_nsec >= 1000000000L) {
    ts.tv_sec++;
    ts.tv_nsec -= 1000000000L;
  }
  while (!stop_requested() && clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, nullptr) == EINTR) {
  }
}

// Where the build tree's copies are when the build does not say (common.h).
#ifndef BALL_QOS_PROFILE_BUILD
#define BALL_QOS_PROFILE_BUILD "ball_qos.xml"
#endif
#ifndef BALL_SCENES_BUILD
#define BALL_SCENES_BUILD "scenes"
#endif
#ifndef BALL_WEB_BUILD
#define BALL_WEB_BUILD "web"
#endif
#ifndef BALL_WASM_BUILD
#define BALL_WASM_BUILD "ball.wasm"
#endif

// One of the project's data files or folders: $env, else the copy installed
// beside the programs (../share/libball/NAME, when PROBE in it, or NAME itself
// for "", can be read), else the build tree's.
static std::string find_data(const char *env, const std::string &name, const std::string &probe, const char *build) {
  if (const char *given = std::getenv(env)) return given;
  std::string installed = program_dir() + "/../share/libball/" + name;
  if (readable(probe.empty() ? installed : installed + "/" + probe)) return installed;
  return build;
}

std::string find_profile(const std::string &given) {
  return given.empty() ? find_data("BALL_QOS_PROFILE", "ball_qos.xml", "", BALL_QOS_PROFILE_BUILD) : given;
}

std::string scenes_dir() { return find_data("BALL_SCENES", "scenes", "tennis.yaml", BALL_SCENES_BUILD); }

std::string find_page_dir() { return find_data("BALL_WEB_DIR", "web", "index.html", BALL_WEB_BUILD); }

std::string find_page_wasm() { return find_data("BALL_WEB_WASM", "web/ball.wasm", "", BALL_WASM_BUILD); }

std::string find_three_dir() {
  if (const char *env = std::getenv("BALL_THREE_DIR")) return env;
  return "/usr/share/javascript/three";  // Debian's libjs-three (./run setup)
}

void add_dds_options(CLI::App &app, DdsOptions *o) {
  app.add_option("--domain", o->domain,
                 "DDS domain id, [0, " + std::to_string(kMaxDomain) + "] (default " + std::to_string(o->domain) + ")");
  app.add_option("--profile", o->profile,
                 "QoS profile file (default: $BALL_QOS_PROFILE, the installed one, the source tree's)");
  app.add_option("--participant-profile", o->participant,
                 "participant profile of that file: loopback (default), lan, discovery_client, tcp_server, tcp_client");
  app.add_option("--discovery-server", o->discovery_server,
                 "with discovery_client: the Discovery Server(s), HOST:PORT[;HOST:PORT...] as in ROS_DISCOVERY_SERVER "
                 "(default: the profile's, 127.0.0.1:11811)");
  app.add_option("--secure", o->security,
                 "DDS Security: the folder of ca.pem, governance.p7s, permissions.p7s and the identities "
                 "(docs/security.md; ./run certs makes test ones)");
  app.add_option("--identity", o->identity,
                 "with --secure or --tls: this participant's identity, NAME.pem and NAME.key");
  app.add_option("--tcp-peers", o->tcp_peers,
                 "with tcp_client or tcp_server: the servers to connect to, HOST:PORT[;HOST:PORT...] "
                 "(docs/deploy.md; default: tcp_client's 127.0.0.1:7400, none for tcp_server)");
  app.add_option("--tcp-listen", o->tcp_listen, "with tcp_server: the TCP port to listen on (default 7400)")
      ->check(CLI::Range(1, 65535));
  app.add_option("--tcp-public-address", o->tcp_public,
                 "with tcp_server behind a router that forwards its port: the router's IPv4 address");
  app.add_option("--tls", o->tls,
                 "with tcp_client or tcp_server: TLS, with ca.pem and the --identity's certificate in this folder; "
                 "a peer without a certificate of that CA is refused (docs/deploy.md)");
}

std::vector<std::string> dds_arguments(const DdsOptions &o) {
  std::vector<std::string> a = {"--domain", std::to_string(o.domain), "--participant-profile", o.participant};
  if (!o.profile.empty()) a.insert(a.end(), {"--profile", o.profile});
  if (!o.discovery_server.empty()) a.insert(a.end(), {"--discovery-server", o.discovery_server});
  if (!o.security.empty()) a.insert(a.end(), {"--secure", o.security});
  if (!o.identity.empty()) a.insert(a.end(), {"--identity", o.identity});
  if (!o.tcp_peers.empty()) a.insert(a.end(), {"--tcp-peers", o.tcp_peers});
  if (o.tcp_listen != 0) a.insert(a.end(), {"--tcp-listen", std::to_string(o.tcp_listen)});
  if (!o.tcp_public.empty()) a.insert(a.end(), {"--tcp-public-address", o.tcp_public});
  if (!o.tls.empty()) a.insert(a.end(), {"--tls", o.tls});
  return a;
}

bool parse_level(const std::string &text, ball_level *out) {
  for (int l = 0; l < BALL_LEVEL_COUNT; ++l)
    if (text == ball_level_name(static_cast<ball_level>(l))) {
      *out = static_cast<ball_level>(l);
      return true;
    }
  return false;
}

std::string level_names() {
  std::string s;
  for (int l = 1; l <= BALL_LEVEL_COUNT; ++l) {
    s += ball_level_name(static_cast<ball_level>(l % BALL_LEVEL_COUNT));
    s += l + 2 < BALL_LEVEL_COUNT + 1 ? ", " : l < BALL_LEVEL_COUNT ? " or " : "";
  }
  return s;
}

bool set_realtime_priority(int priority, std::string *err) {
  sched_param p{};
  p.sched_priority = priority;
  int rc = pthread_setschedparam(pthread_self(), SCHED_FIFO, &p);
  if (rc == 0) return true;
  *err = "realtime priority " + std::to_string(priority) + " (SCHED_FIFO): " + std::strerror(rc);
  return false;
}

ball_model court_model(const MatchInfoOut &info) {
  ball_scene scene;
  std::string err;
  if (!plain_scene_name(info.scene) || !load_scene(info.scene, &scene, &err)) ball_scene_default(&scene);
  ball_model model;
  Court court;
  if (!match_model_of(scene, info, &model, &court, &err)) model = scene.model;  // the scene's court at least
#define BALL_COURT_FLIGHT(f) model.f = info.model.f;
  BALL_FLIGHT_FIELDS(BALL_COURT_FLIGHT)
#undef BALL_COURT_FLIGHT
  return model;
}

bool load_scene(const std::string &what, ball_scene *scene, std::string *err) {
  if (what.empty() || what == "default") {
    ball_scene_default(scene);
    return true;
  }
  std::string path = what;
  if (what.find('/') == std::string::npos && what.find(".yaml") == std::string::npos)
    path = scenes_dir() + "/" + what + ".yaml";
  ball_scene_error e;
  if (ball_scene_load_file(path.c_str(), scene, &e) != BALL_OK) {
    char text[1024];
    ball_scene_error_format(&e, text, sizeof text);
    *err = text;
    return false;
  }
  return true;
}

bool write_file(const std::string &path, const std::string &text, std::string *err) {
  OutputFile f;
  if (f.open(path) && f.write_line(text) && f.close()) return true;
  *err = f.error();
  return false;
}

OutputFile::~OutputFile() {
  if (f_) std::fclose(f_);
}

bool OutputFile::failed() {
  error_ = "cannot write " + path_ + ": " + std::strerror(errno);
  return false;
}

bool OutputFile::open(const std::string &path) {
  path_ = path;
  f_ = std::fopen(path.c_str(), "w");
  return f_ ? true : failed();
}

bool OutputFile::write_line(const std::string &line) {
  if (!f_) return false;
  return std::fputs(line.c_str(), f_) >= 0 && std::fputc('\n', f_) != EOF ? true : failed();
}

bool OutputFile::flush() {
  if (!f_) return false;
  return std::fflush(f_) == 0 ? true : failed();
}

bool OutputFile::close() {
  if (!f_) return false;
  std::FILE *f = f_;
  f_ = nullptr;
  return std::fclose(f) == 0 ? true : failed();
}

int fail(const char *program, const std::string &message) {
  std::fprintf(stderr, "%s: %s\n", program, message.c_str());
  return 1;
}

}  // namespace app
}  // namespace ballsrv
