// ball-watch: an observer (docs/bots-and-watchers.md, "Watchers"), a client of the
// client library (ball/net.h) and nothing else: a Watcher (watcher.h) over
// one client. It prints the rally as it happens,
// records everything it receives to JSON Lines on request, evaluates the
// ball from the segments at its own frame rate and checks that ball against
// the server's ball states (the desync check). With --snapshots it also
// draws PNG frames of each match (libball::render, headless OSMesa) every S
// sim seconds, as ballrender does for a scene, rackets included (placed by
// the library from their holders' samples). With --http it serves the spectator
// page (server/web): the loop feeds it, the HTTP server runs on threads of
// its own. One loop.
#include <sys/stat.h>

#include <CLI/CLI.hpp>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <map>
#include <memory>

#include "ball/render.h"
#include "common.h"
#include "open_client.h"
#include "watcher.h"
#include "web_server.h"

using namespace ballsrv;
using namespace ballsrv::app;

namespace {

const char *kProgram = "ball-watch";

// Draws the snapshots a Watcher says are due (docs/bots-and-watchers.md, "Snapshot frames").
struct Snapshots {
  std::string dir, camera = "side";
  std::vector<int> size{640, 480};  // pixels
  double every = 0.5;               // sim s
  ball_renderer *renderer = nullptr;
  std::map<uint32_t, ball_model> courts;  // by match
  ~Snapshots() { ball_renderer_destroy(renderer); }

  void add_options(CLI::App &cli) {
    std::vector<std::string> cameras;
    for (int i = 0; i < BALL_CAMERA_PRESET_COUNT; ++i) cameras.push_back(ball_camera_preset_name(static_cast<ball_camera_preset>(i)));
    cli.add_option("--snapshots", dir, "write PNG frames of each match to DIR (m<match>_t<sim time>.png)");
    cli.add_option("--snapshot-every", every, "with --snapshots: sim seconds between frames")->capture_default_str()->check(CLI::Range(0.01, 3600.0));
    cli.add_option("--camera", camera, "with --snapshots: the camera")->capture_default_str()->check(CLI::IsMember(cameras));
    cli.add_option("--size", size, "with --snapshots: WxH pixels (default 640x480)")->delimiter('x')->expected(2)
        ->check(CLI::Range(BALL_RENDER_MIN_SIZE, BALL_RENDER_MAX_SIZE));
  }
  // The folder, made if it is not there: "" or what went wrong.
  std::string make_dir() const {
    struct stat st {};
    if (dir.empty()) return "";
    if (::stat(dir.c_str(), &st) != 0 && ::mkdir(dir.c_str(), 0777) != 0)
      return "--snapshots: cannot create " + dir + ": " + std::strerror(errno);
    if (::stat(dir.c_str(), &st) != 0 || !S_ISDIR(st.st_mode)) return "--snapshots: " + dir + " is not a folder";
    return "";
  }

  // The frame into dir: "" and its path in *file, or what went wrong.
  std::string draw(const SnapshotDue &d, SnapshotRecord *drawn) {
    if (!renderer && ball_renderer_create(size[0], size[1], &renderer) != BALL_OK)
      return "cannot create an OSMesa renderer";
    auto it = courts.find(d.match);
    // the court the server judges: the match's model from the wire, else a scene of its name
    if (it == courts.end() || (d.has_model && ball_model_hash(&it->second) != ball_model_hash(&d.model)))
      it = courts.insert_or_assign(d.match, d.has_model ? d.model : court_model(d.info)).first;
    ball_camera cam;
    ball_camera_preset preset = BALL_CAMERA_SIDE;
    for (int i = 0; i < BALL_CAMERA_PRESET_COUNT; ++i)
      if (camera == ball_camera_preset_name(static_cast<ball_camera_preset>(i))) preset = static_cast<ball_camera_preset>(i);
    if (ball_camera_from_preset(&it->second, preset, static_cast<double>(size[0]) / size[1], &cam) != BALL_OK)
      return "no camera for match " + std::to_string(d.match);
    ball_frame f{};
    f.time = d.sim_time;
    f.ball = d.ball;
    f.n_rackets = std::min(it->second.n_rackets, d.info.players);
    for (int i = 0; i < f.n_rackets; ++i) {
      f.rackets[i].visible = drawn->racket_drawn[i] = d.racket_drawn[i];
      f.rackets[i].center = drawn->rackets[i] = d.rackets[i].center;
      f.rackets[i].normal = d.rackets[i].normal;
    }
    f.n_trail = static_cast<int>(d.trail.size());
    f.trail = d.trail.data();
    f.n_events = static_cast<int>(d.events.size());
    f.events = d.events.data();
    if (ball_render_draw(renderer, &it->second, &cam, &f) != BALL_OK) return "cannot draw match " + std::to_string(d.match);
    const unsigned char *rgb;
    int width, height;
    ball_render_pixels(renderer, &rgb, &width, &height);
    char name[64];
    std::snprintf(name, sizeof name, "/m%u_t%08.3f.png", d.match, d.sim_time);
    drawn->file = dir + name;
    drawn->camera = camera;
    drawn->size = {width, height};
    errno = 0;
    if (ball_png_write(drawn->file.c_str(), rgb, width, height) != BALL_OK)
      return "cannot write " + drawn->file + ": " + (errno ? std::strerror(errno) : "the PNG writer failed");
    return "";
  }
};

// --http: the spectator page (server/web).
struct Page {
  int port = -1;  // -1: none
  std::string address = WebSettings().address;
  std::string proxy;
  std::unique_ptr<WebServer> web;

  void add_options(CLI::App &cli) {
    cli.add_option("--http", port, "serve the spectator page on PORT (0: a free port; the URL is printed); "
                                   "docs/bots-and-watchers.md, \"The spectator page\"")->check(CLI::Range(0, 65535));
    cli.add_option("--http-address", address, "with --http: the address to listen on")->capture_default_str();
    cli.add_option("--http-proxy", proxy,
                   "with --http: the address of a reverse proxy in front of the page, whose connections have no "
                   "per-address share (docs/bots-and-watchers.md, \"The page against hostile HTTP\")");
  }
  // Serving, when asked for: "" or what went wrong.
  std::string start() {
    if (port < 0) return "";
    WebSettings o;
    o.address = address;
    o.port = port;
    o.http.proxy = proxy;
    o.page_dir = find_page_dir();
    o.wasm_file = find_page_wasm();
    o.three_dir = find_three_dir();
    std::string err;
    if (!(web = WebServer::start(o, SpectatorSettings(), court_model, &err))) return "--http: " + err;
    std::printf("%s: the spectator page is at %s\n", kProgram, web->url().c_str());
    std::fflush(stdout);
    return "";
  }
};

// Prints, records and draws what the watcher produced; "" or what went wrong.
std::string drain(Watcher &w, OutputFile &rec, Snapshots &snap, bool quiet, double start) {
  WatchOutput &out = w.output();
  for (const auto &l : out.log)
    if (!quiet) std::printf("[%6.2f s] match %u, t %7.3f: %s\n", mono_now() - start, l.match, l.sim_time, l.text.c_str());
  std::fflush(stdout);
  std::vector<SnapshotDue> due = std::move(out.snapshots);
  out.snapshots.clear();
  for (const auto &d : due) {
    SnapshotRecord drawn;
    std::string why = snap.draw(d, &drawn);
    if (!why.empty()) return why;
    w.snapshot_written(d, drawn, realtime_now());
  }
  for (const auto &r : out.records)  // a reader can follow the record as it grows
    if (rec.is_open() && !rec.write_line(r.dump())) return rec.error();
  std::string err = out.records.empty() || !rec.is_open() || rec.flush() ? "" : rec.error();
  out.clear();
  return err;
}

// How this run ends and what it writes.
struct Run {
  double duration = 0.0;    // real s (0: until SIGINT/SIGTERM)
  uint64_t until_hits = 0;  // racket hits in play (0: no limit)
  std::string record, summary_json;
  bool quiet = false, no_log = false;
};

// The watcher's turns, its own ball at its frame rate, the page and the
// record until the run ends: "" or why it failed.
std::string watch(Watcher &w, const WatcherSettings &ws, const Run &run, Page &page, Snapshots &snap,
                  OutputFile &rec, double start) {
  std::string err;
  for (double next_frame = start; !stop_requested(); sleep_until(std::min(next_frame, mono_now() + 0.002))) {
    double now = mono_now(), real = realtime_now();
    if ((run.duration > 0.0 && now - start >= run.duration) || (run.until_hits > 0 && w.hits() >= run.until_hits))
      break;
    if (!(err = w.turn(real)).empty()) return err;
    if (page.web) page.web->update([&](Spectator &sp) {
        for (const auto &r : w.output().rackets) sp.on_racket(r);
        sp.update(w, real);
      });
    if (now >= next_frame) {  // the watcher's own ball, at its own frame rate
      w.frame(real);
      next_frame += 1.0 / ws.fps;
      if (next_frame < now) next_frame = now + 1.0 / ws.fps;
    }
    if (!(err = drain(w, rec, snap, run.quiet, start)).empty()) return err;
  }
  return "";
}

// The summary printed, recorded and written: "" or why it could not be.
std::string finish(Watcher &w, const Run &run, Page &page, Snapshots &snap, OutputFile &rec, double start) {
  WatchSummary sum = w.summary(mono_now() - start);
  w.output().records.push_back({{"type", "summary"}, {"summary", sum}});
  if (!run.quiet)
    for (const auto &line : summary_lines(sum)) std::printf("%s\n", line.c_str());
  if (!run.quiet && page.web)
    std::printf("summary: the spectator page: %llu streams opened, %llu refused (too many at once)\n",
                static_cast<unsigned long long>(page.web->pages_opened()),
                static_cast<unsigned long long>(page.web->pages_refused()));
  std::string err = drain(w, rec, snap, true, start);
  if (!err.empty()) return err;
  if (rec.is_open() && !rec.close()) return rec.error();
  if (!run.summary_json.empty() && !write_file(run.summary_json, json(sum).dump(1), &err)) return err;
  return "";
}

}  // namespace

int main(int argc, char **argv) {
  CLI::App cli{"ball-watch: watch ball-server's matches: the rally log, a JSON Lines record, the ball\n"
               "evaluated from segments and checked against the server's ball states"};
  WatcherSettings ws;
  Run run;
  std::string err;
  Snapshots snap;
  Page page;
  DdsOptions dds_opt;
  std::string servers;
  cli.add_option("--match", ws.match, "watch this match only (default: all)");
  cli.add_option("--servers", servers, "use the server topics only from these server ids, comma-separated; "
                                       "ID=IDENTITY: only from the holder of that certificate (--secure) "
                                       "(default: any; the record keeps everything else received)");
  cli.add_option("--fps", ws.fps, "frames per second of the watcher's own ball")->capture_default_str()->check(CLI::Range(1.0, 1000.0));
  cli.add_option("--duration", run.duration, "stop after S real seconds (0: until SIGINT/SIGTERM)")->check(CLI::Range(0.0, 1e9));
  cli.add_option("--until-hits", run.until_hits, "stop once this many racket hits were seen in play")->check(CLI::Range(0, 1000000));
  cli.add_option("--record", run.record, "write everything received to FILE as JSON Lines (one object a line)");
  cli.add_flag("--record-frames", ws.record_frames, "with --record: also the watcher's own ball, every frame");
  cli.add_option("--summary-json", run.summary_json, "write the summary to FILE as JSON at exit");
  cli.add_flag("--no-log", run.no_log, "no rally log, only the summary");
  cli.add_flag("--quiet,-q", run.quiet, "print nothing but errors");
  snap.add_options(cli);
  page.add_options(cli);
  add_dds_options(cli, &dds_opt);
  CLI11_PARSE(cli, argc, argv);
  ws.log = !run.no_log && !run.quiet;
  ws.snapshot_every = snap.dir.empty() ? 0.0 : snap.every;
  if (!(err = snap.make_dir()).empty()) return fail(kProgram, err);

  install_stop_signals();
  ball_net_client *client = open_client(dds_opt, kProgram, servers, [&](ball_net_config *c) {
    c->clock = [](void *) { return realtime_now(); };  // (the watcher's times are the realtime clock's)
    c->ball_states = 1;  // (the desync check)
    c->server_status = 1;
    c->rackets = page.port >= 0 || !snap.dir.empty();  // (the rackets are drawn)
  }, &err);
  if (!client) return fail(kProgram, err);
  std::unique_ptr<ball_net_client, void (*)(ball_net_client *)> owned(client, ball_net_free);  // (outlives w)
  if (!(err = page.start()).empty()) return fail(kProgram, err);
  OutputFile rec;
  if (!run.record.empty() && !rec.open(run.record)) return fail(kProgram, rec.error());
  Watcher w(ws, client);
  const double start = mono_now();
  w.on_start(realtime_now());
  if (!(err = watch(w, ws, run, page, snap, rec, start)).empty()) return fail(kProgram, err);
  if (!(err = finish(w, run, page, snap, rec, start)).empty()) return fail(kProgram, err);
  return 0;
}
