// The game of examples/c/rally.c in C++17 (docs/client.md): it lists the
// matches a ball server serves, joins one, moves its racket on a scripted
// path (onto the ball where the server's segments say it will be, on its
// own half), prints the rally as it happens and leaves.
//
//   rally_cpp [--domain D] [--match M] [--points N] [--hits H] [--seconds S] [--log 1] [--states 1]
//
// With --log 1 it also prints every event of the server as it comes:
// "event SEQ KIND server ID". With --states 1 it reads the server's ball
// states too (ball_net_config.ball_states).
// It returns H balls a rally (default 3), then lets the next one go, so
// that points are played. Exit status 0 when it played N points (default
// 3) with at least one hit of its own, 1 otherwise: rally.c's lines and
// status, so that either can stand for the other.
//
// What C++ adds is the wrapper below, the way a C++ game would hold the
// client library: an owning handle (ball_net_free when it goes), the
// game's std::chrono::steady_clock as the library's clock, and exceptions
// where a call really failed. Outcomes a game expects every frame (no
// clock or segment yet, a match not heard of) are std::optional or bool,
// not exceptions. No exception ever reaches the C side: the library calls
// back into this file only through the clock, which is noexcept.
#include <ball/net.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace ballnet {

using Clock = std::chrono::steady_clock;
using Time = Clock::time_point;

// A call the library refused: its status and its sentence (ball_net_message);
// what() says both.
class Error : public std::runtime_error {
 public:
  Error(ball_status status, const std::string &message)
      : std::runtime_error(std::string(ball_strerror(status)) + ": " + message), status_(status), message_(message) {}
  ball_status status() const noexcept { return status_; }
  const std::string &message() const noexcept { return message_; }

 private:
  ball_status status_;
  std::string message_;
};

// The library's clock is steady_clock, passed through ball_net_config.clock:
// libstdc++ reads CLOCK_MONOTONIC for it on Linux, the library's default, but
// naming it makes the game's times and the library's one clock on any
// standard library. Seconds since steady_clock's epoch.
inline double seconds(Time t) noexcept { return std::chrono::duration<double>(t.time_since_epoch()).count(); }
inline double steady_seconds(void *) noexcept { return seconds(Clock::now()); }

// One client of the library, owned: closed and freed when it goes.
class Client {
 public:
  // Opens a client on `config` (its clock replaced by steady_clock); Error on failure.
  explicit Client(ball_net_config config) {
    config.clock = steady_seconds;
    config.clock_user = nullptr;
    char why[256] = "";
    ball_net_client *c = nullptr;
    ball_status st = ball_net_open(&config, &c, why, sizeof why);
    if (st != BALL_OK) throw Error(st, why);
    client_.reset(c);
  }

  // The matches the domain's servers serve now.
  std::vector<ball_net_match> matches() {
    std::vector<ball_net_match> list(16);
    int n = 0;
    for (;;) {
      check(ball_net_matches(get(), list.data(), static_cast<int>(list.size()), &n));
      if (n <= static_cast<int>(list.size())) break;
      list.resize(static_cast<size_t>(n));  // more than there was room for: again, with room for all
    }
    list.resize(static_cast<size_t>(n));
    return list;
  }

  // One match; nullopt while no server serves it.
  std::optional<ball_net_match> match_info(uint32_t match) {
    ball_net_match m;
    ball_status st = ball_net_match_info(get(), match, &m);
    if (st == BALL_ENOMATCH) return std::nullopt;
    check(st);
    return m;
  }

  void join(uint32_t match, int slot = -1) { check(ball_net_join(get(), match, slot)); }
  void leave(uint32_t match, int slot = -1) { check(ball_net_leave(get(), match, slot)); }

  // The racket's pose at `t`; false while the match's clock is not known yet.
  bool push(uint32_t match, int slot, Time t, ball_vec3 center, ball_vec3 normal) {
    ball_status st = ball_net_push(get(), match, slot, seconds(t), center, normal);
    if (st == BALL_EAGAIN) return false;
    check(st);
    return true;
  }

  // The status of a match it follows; nullopt when it follows none of that id.
  std::optional<ball_net_status> status(uint32_t match) const {
    ball_net_status s;
    ball_status st = ball_net_status_of(get(), match, &s);
    if (st == BALL_ENOMATCH) return std::nullopt;
    check(st);
    return s;
  }

  // The ball at `t`; nullopt while the match has no clock or segment yet.
  std::optional<ball_net_ball> ball_at(uint32_t match, Time t) const {
    ball_net_ball b;
    ball_status st = ball_net_ball_at(get(), match, seconds(t), &b);
    if (st == BALL_EAGAIN) return std::nullopt;
    check(st);
    return b;
  }

  // Every event that came in, in order (and what was not answered, resent).
  std::vector<ball_net_event> poll() {
    std::vector<ball_net_event> events;
    ball_net_event batch[32];
    int n = 0;
    do {
      check(ball_net_poll(get(), batch, 32, &n));
      events.insert(events.end(), batch, batch + n);
    } while (n == 32);
    return events;
  }

  // Leaves every slot and closes; the destructor frees. Error when Fast DDS
  // did not finish (the client is closed all the same).
  void close() { check(ball_net_close(get())); }

 private:
  struct Free {
    void operator()(ball_net_client *c) const noexcept { ball_net_free(c); }
  };
  ball_net_client *get() const noexcept { return client_.get(); }
  void check(ball_status st) const {
    if (st != BALL_OK) throw Error(st, ball_net_message(get()));
  }
  std::unique_ptr<ball_net_client, Free> client_;
};

}  // namespace ballnet

namespace {

using ballnet::Time;
using std::chrono::duration;
using std::chrono::duration_cast;

Time::duration secs(double s) { return duration_cast<Time::duration>(duration<double>(s)); }

// Where the racket wants to be at `t`: onto the ball 0.05 s ahead while the
// ball is on this side of the net, coming in, and not yet 2 m past the
// baseline or a sideline (a racket far off the court is refused: the
// server's racket_margin), and this rally has not had its `hits` of ours yet; else
// waiting 1 m inside its baseline.
ball_vec3 target(const ballnet::Client &c, uint32_t match, const ball_net_match &m, int side, Time t, bool chase) {
  const double toward_net = side == 0 ? 1.0 : -1.0;  // the net is toward +x from side 0
  const ball_vec3 ready{side == 0 ? m.court_x[0] + 1.0 : m.court_x[1] - 1.0, 1.0, 0.5 * (m.court_z[0] + m.court_z[1])};
  if (!chase) return ready;
  std::optional<ball_net_ball> b = c.ball_at(match, t + secs(0.05));
  const double baseline = side == 0 ? m.court_x[0] : m.court_x[1];
  if (b && (b->state.position.x - m.net_x) * toward_net < 0.0 && b->state.velocity.x * toward_net < 0.0 &&
      (b->state.position.x - baseline) * toward_net > -2.0 && b->state.position.z > m.court_z[0] - 2.0 &&
      b->state.position.z < m.court_z[1] + 2.0 && b->state.position.y < 3.0)
    return b->state.position;
  return ready;
}

// A step from `at` toward `to`, at most `reach` long: a racket is a body (the
// server refuses one faster than its max_racket_speed, 50 m/s by default).
ball_vec3 toward(ball_vec3 at, ball_vec3 to, double reach) {
  const double dx = to.x - at.x, dy = to.y - at.y, dz = to.z - at.z;
  const double d = std::sqrt(dx * dx + dy * dy + dz * dz);
  if (d <= reach) return to;
  return {at.x + dx * reach / d, at.y + dy * reach / d, at.z + dz * reach / d};
}

struct Options {
  ball_net_config config;
  long match = -1;
  int points = 3, hits = 3;
  bool log = false;
  double seconds = 60.0;
};

Options parse(int argc, char **argv) {
  Options o;
  ball_net_config_default(&o.config);
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string flag = argv[i];
    const char *value = argv[i + 1];
    if (flag == "--domain") o.config.domain = std::atoi(value);
    else if (flag == "--match") o.match = std::atol(value);
    else if (flag == "--points") o.points = std::atoi(value);
    else if (flag == "--hits") o.hits = std::atoi(value);
    else if (flag == "--log") o.log = std::atoi(value) != 0;
    else if (flag == "--states") o.config.ball_states = std::atoi(value);
    else if (flag == "--seconds") o.seconds = std::atof(value);
  }
  return o;
}

// The match asked for, or the first with a free slot; nullopt after 10 s.
std::optional<ball_net_match> find_match(ballnet::Client &client, long asked, Time start) {
  const uint32_t none = UINT32_MAX;
  uint32_t match = asked >= 0 ? static_cast<uint32_t>(asked) : none;
  for (;;) {
    if (match != none)
      if (std::optional<ball_net_match> m = client.match_info(match)) return m;
    client.poll();  // (takes the MatchInfos in; nothing is followed yet)
    for (const ball_net_match &m : client.matches()) {
      int free_slots = 0;
      for (int k = 0; k < m.players; ++k) free_slots += !m.slots[k].held;
      if (match == none && free_slots > 0) match = m.id;
    }
    if (ballnet::Clock::now() - start > secs(10.0)) return std::nullopt;
    std::this_thread::sleep_for(secs(0.05));
  }
}

}  // namespace

int main(int argc, char **argv) try {
  std::setvbuf(stdout, nullptr, _IOLBF, 0);  // the rally as it happens, also into a file
  Options o = parse(argc, argv);
  ballnet::Client client(o.config);
  const Time start = ballnet::Clock::now();
  std::optional<ball_net_match> found = find_match(client, o.match, start);
  if (!found) {
    std::fprintf(stderr, "rally: no match with a free slot within 10 s\n");
    return 1;
  }
  ball_net_match m = *found;
  const uint32_t match = m.id;
  std::printf("rally: match %u, scene %s, %d players, score %d-%d\n", match, m.scene, m.players, m.score[0],
              m.score[1]);
  client.join(match);

  int played = 0, mine = 0, rally_hits = 0, slot = -1;
  std::optional<ball_vec3> racket;
  const Time::duration pose_period = secs(1.0 / 30.0), frame = secs(1.0 / 60.0);
  Time next_pose = ballnet::Clock::now();
  while (played < o.points && ballnet::Clock::now() - start < secs(o.seconds)) {
    const Time t = ballnet::Clock::now();
    std::vector<ball_net_event> events;
    try {
      events = client.poll();
    } catch (const ballnet::Error &e) {
      std::fprintf(stderr, "rally: %s\n", e.message().c_str());
      break;
    }
    for (const ball_net_event &e : events) {
      if (o.log && e.seq > 0)
        std::printf("rally: event %u %s server %u\n", e.seq, ball_net_event_kind_name(e.kind), e.server);
      switch (e.kind) {
        case BALL_NET_EVENT_SLOT:
          if (e.value > 0.0) slot = e.index;
          std::printf("rally: %s slot %d\n", e.value > 0.0 ? "holds" : "lost", e.index);
          break;
        case BALL_NET_EVENT_SERVE: std::printf("rally: serve by slot %d\n", e.index); break;
        case BALL_NET_EVENT_RACKET:
          if (e.in_play) {
            const bool me = e.index == slot;
            mine += me;
            rally_hits += me;
            std::printf("rally: hit by slot %d%s at (%.2f, %.2f, %.2f)\n", e.index, me ? " (me)" : "", e.point.x,
                        e.point.y, e.point.z);
          }
          break;
        case BALL_NET_EVENT_FLOOR:
          if (e.in_play) std::printf("rally: bounce at (%.2f, %.2f)\n", e.point.x, e.point.z);
          break;
        case BALL_NET_EVENT_POINT:
          played++;
          rally_hits = 0;
          std::printf("rally: point to side %d (%s), score %d-%d\n", e.side, ball_net_reason_name(e.reason), e.score[0],
                      e.score[1]);
          break;
        case BALL_NET_EVENT_SERVER: std::printf("rally: now served by server %u\n", e.server); break;
        default: break;
      }
    }
    client.ball_at(match, t);  // what a game draws every frame: the ball now
    // the racket's pose, 30 a second, at most 30 m/s
    std::optional<ball_net_match> now_m = slot >= 0 && t >= next_pose ? client.match_info(match) : std::nullopt;
    if (now_m) {
      m = *now_m;
      const ball_vec3 to = target(client, match, m, slot % 2, t, rally_hits < o.hits);
      racket = racket ? toward(*racket, to, 30.0 / 30.0) : to;
      const ball_vec3 normal{slot % 2 == 0 ? 1.0 : -1.0, 0.0, 0.0};
      try {
        client.push(match, slot, t, *racket, normal);  // (false: the match's clock not known yet)
      } catch (const ballnet::Error &e) {
        std::fprintf(stderr, "rally: push: %s\n", e.message().c_str());
      }
      next_pose += pose_period;
      if (next_pose < t) next_pose = t + pose_period;
    }
    std::this_thread::sleep_until(t + frame);
  }
  if (std::optional<ball_net_status> s = client.status(match))
    std::printf("rally: %.1f s: %lu poses, %lu segments, %lu events taken; bytes in %lu, out %lu; term %u\n",
                duration<double>(ballnet::Clock::now() - start).count(), static_cast<unsigned long>(s->samples),
                static_cast<unsigned long>(s->segments), static_cast<unsigned long>(s->events),
                static_cast<unsigned long>(s->bytes_in), static_cast<unsigned long>(s->bytes_out), s->term);
  std::printf("rally: %d points played, %d hits of mine; leaving\n", played, mine);
  std::fflush(stdout);
  client.leave(match);
  try {
    client.close();
  } catch (const ballnet::Error &e) {
    std::fprintf(stderr, "rally: close: %s\n", e.message().c_str());
  }
  return played >= o.points && mine > 0 ? 0 : 1;
} catch (const ballnet::Error &e) {
  std::fprintf(stderr, "rally: %s\n", e.what());
  return 1;
}
