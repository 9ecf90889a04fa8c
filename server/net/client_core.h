// The client library's core (docs/client.md), free of DDS: the matches a
// client follows (a MatchView each), the matches the domain serves, and
// what the client asked for (JOIN, CREATE), sent again until the server
// answers, as docs/protocol.md says a client must. A ClientPort brings the
// server's samples and takes the client's; ball/net.h's C API is a thin
// shell over one, and the tests drive one from a Match.
#pragma once

#include <array>
#include <cstdint>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "link.h"
#include "match_rackets.h"
#include "match_view.h"
#include "port.h"
#include "records.h"

namespace ballsrv {

// The most matches a client lists and follows (ball_net_config's max_matches).
constexpr size_t kMaxClientMatches = 4096;

struct CoreSettings {
  ServerChoice servers;         // whose samples it takes
  double retry = 0.5;           // s between a JOIN or a CREATE and the next while the server has not answered
  double silence = 10.0;        // s a match goes unheard before it is not listed (docs/protocol.md, "Time")
  size_t max_matches = kMaxClientMatches;  // matches listed and followed at most (the readers' room)
  bool rackets = false;         // keeps the players' rackets of the matches followed (racket())
  LinkParams link;              // a simulated network for the racket poses (none by default)
  uint64_t link_seed = 0;       // its draws' seed (each slot's link its own stream from it)
};

// A match the domain serves: its newest usable MatchInfo.
struct Listed {
  MatchInfoOut info;
  double heard = 0.0;  // the caller's clock when it came
};

// What a followed match counts of the client's own traffic.
struct OwnCounters {
  uint64_t samples = 0;         // racket poses written
  uint64_t link_lost = 0;       // racket poses the simulated network lost (CoreSettings::link)
  uint64_t write_failures = 0;  // poses and controls DDS refused
  uint64_t bytes_in = 0;        // payload bytes of the match's samples taken (ClientPort::sizes)
  uint64_t bytes_out = 0;       // and of the samples and controls written for it
  uint64_t rackets = 0;         // the players' racket samples taken (CoreSettings::rackets)
  uint64_t rackets_refused = 0; // and not taken: not the slot's holder's, no such slot, not newer, no model yet
};

class ClientCore {
 public:
  ClientCore(const CoreSettings &settings, const ParticipantId &me);

  // Takes everything `port` holds to the matches; then writes the JOINs and
  // CREATEs due. `local` is the caller's clock now, `real` the realtime
  // clock now (DDS stamps a reception with it).
  void pump(ClientPort &port, double local, double real);

  // The client's requests; false with a sentence in *why (the status in
  // *status) when refused, and nothing changes.
  ball_status watch(uint32_t match, ClientPort &port, std::string *why);
  ball_status unwatch(uint32_t match, ClientPort &port, std::string *why);
  ball_status join(uint32_t match, int slot, ClientPort &port, double local, std::string *why);
  ball_status leave(uint32_t match, int slot, ClientPort &port, std::string *why);  // slot -1: every one
  ball_status create(uint32_t match, const std::string &scene, int players, int level, ClientPort &port,
                     double local, std::string *why);
  ball_status ask(uint32_t match, ControlKind kind, double value, ClientPort &port, std::string *why);
  // The pose of slot `slot`'s racket at `local`, mapped to the sim clock,
  // numbered and written: at once, or through the simulated network
  // (CoreSettings::link) when its trip ends (this call's or a later pump's).
  ball_status push(uint32_t match, int slot, double local, ball_vec3 center, ball_vec3 normal, ClientPort &port,
                   std::string *why);
  // Slot `slot`'s racket at `local` of the caller's clock, from the
  // holder's samples (docs/protocol.md, "The other players' rackets").
  // BALL_ENOMATCH: not followed; BALL_EAGAIN: no clock or model yet;
  // BALL_ERANGE: no such slot; else ball_racket_estimate's status.
  ball_status racket(uint32_t match, int slot, double local, ball_racket_pose *out) const;
  // The tap (ball_net_set_tap): every sample pump takes, of any match,
  // as a record line (records.h) stamped with the realtime s of its
  // reception ("recv") and, where DDS says it, of its writing ("sent"),
  // and the client's verdict ("taken"; "anew" on a MatchInfo that started
  // a followed match anew); a "ready" line once the port first hears a
  // server. Empty: none.
  void on_sample(std::function<void(const json &)> fn) { tap_ = std::move(fn); }
  // A LEAVE for every slot held (a client closing); how many were written.
  int leave_all(ClientPort &port);

  // Segments of a match not followed kept for when it is (a reader gets a match's newest segments
  // once, when it matches the server's writer): the newest of each match, at most max_matches matches.
  static constexpr size_t kKeptUnfollowed = 4;
  size_t kept_unfollowed() const;  // segments kept so

  const MatchView *view(uint32_t match) const;  // nullptr: not followed
  const OwnCounters *own(uint32_t match) const;
  std::vector<const Listed *> matches(double local) const;  // listed now (heard within `silence`), by id
  const Listed *listed(uint32_t match, double local) const;
  std::deque<ViewEvent> &events() { return events_; }  // of every followed match, in order, not taken yet

  // Starting anew (docs/deploy.md, "Limits": a TCP connection Fast DDS 2.9
  // left deaf). Called after each pump with whether the port meets a server
  // (some endpoint of one matched: ClientPort::meets_server) and hears one:
  // true when the client should make its participant anew, either because
  // no server has been met for `renew_wait` s since it opened (or last
  // started anew, or last met one), because a JOIN has had no answer
  // (the slot held, or a refusal in its match) for that long while a server
  // is heard, or because a followed match it heard has had no MatchInfo for
  // the silence (and that wait) while a server is heard (an owner lost, and
  // its successor deaf to this client). A server of many matches takes seconds to be found whole:
  // meeting it is enough to wait on. Each time it says so the wait doubles,
  // up to kRenewMost s; it is kRenewFirst again once a server is heard and
  // no JOIN waits. After a new participant, renewed() with its id: the
  // views take it as theirs, every JOIN and CREATE waiting is sent at once.
  static constexpr double kRenewFirst = 5.0, kRenewMost = 60.0;
  bool wants_renewal(bool meets, bool hears, double local);
  void renewed(const ParticipantId &me, double local);
  uint64_t renewals() const { return renewals_; }
  uint64_t refused() const { return refused_; }        // samples of matches it does not follow that were not usable
  uint64_t unlisted() const { return unlisted_; }
  double silence() const { return settings_.silence; }      // matches the list let go to make room (list_room)

 private:
  bool list_room(double local);
  struct Followed {
    std::unique_ptr<MatchView> view;
    bool any = false;                          // it wants a slot, any (JOIN -1) until leave
    std::array<bool, kMaxPlayers> want{};      // it wants these slots (JOIN k) until leave
    std::array<double, kMaxPlayers + 1> next_join{};  // the caller's clock of the next JOIN of each (the last: any)
    std::array<uint32_t, kMaxPlayers> sample_seq{};
    std::array<bool, kMaxPlayers> pushed{};
    std::array<double, kMaxPlayers> last_push{};  // the caller's clock of each slot's newest pose
    std::array<std::unique_ptr<Link<RacketSampleIn>>, kMaxPlayers> links;  // each slot's simulated network
    MatchRackets rackets;                      // the players' rackets (CoreSettings::rackets)
    OwnCounters own;
    double join_since = -1.0;  // the caller's clock of the first JOIN not answered yet (-1: none waits)
    double answered = -1.0;    // of the newest refusal in the match (an answer to someone's control)
    bool joining() const;
    bool wants(int k) const;      // slot k (kMaxPlayers: any) wanted and not held
    bool waits_for_slot() const;  // a slot wanted that it does not hold
  };
  struct Creating {
    ControlIn control;
    double next = 0.0;  // the caller's clock of the next CREATE
  };
  Followed *followed(uint32_t match);
  Followed *follow(uint32_t match, ClientPort &port, ball_status *st, std::string *why);
  bool take_racket(Followed *f, const RacketSampleIn &s);  // false: not taken
  struct Pump;  // one pump's clocks, byte counts and tap line
  void pump_models(ClientPort &port, const Pump &p);
  void pump_segments(ClientPort &port, const Pump &p);
  bool write(ClientPort &port, const ControlIn &c, Followed *f);
  bool write(ClientPort &port, const RacketSampleIn &s, Followed *f);
  ball_status number(uint32_t match, int slot, double local, ball_vec3 center, ball_vec3 normal, RacketSampleIn *out,
                     std::string *why);
  void deliver(ClientPort &port, Followed *f, double local);
  bool take_info(const MatchInfoOut &info, double local);  // false: neither listed nor taken by its match
  void send_due(ClientPort &port, double local);

  CoreSettings settings_;
  ParticipantId me_;
  std::map<uint32_t, Followed> followed_;
  std::map<uint32_t, Listed> listed_;
  // the newest MatchModel of every match heard (written once per model, transient local: a match
  // followed later starts from it); at most max_matches
  std::map<uint32_t, MatchModelOut> models_;
  // the newest segments of matches not followed, with the caller's clock and the realtime clock
  // at their reception
  struct Kept {
    SegmentOut segment;
    double local = 0.0, real = 0.0;
  };
  std::map<uint32_t, std::deque<Kept>> unfollowed_;
  std::map<uint32_t, Creating> creating_;
  std::deque<ViewEvent> events_;
  std::vector<ViewEvent> scratch_;
  uint32_t control_seq_ = 0;
  WireSizes sizes_;  // the port's, as the newest pump saw them
  std::function<void(const json &)> tap_;
  bool tapped_ready_ = false;  // the tap's "ready" line is out
  uint64_t refused_ = 0;
  uint64_t unlisted_ = 0;
  uint64_t lost_writes_ = 0;  // controls DDS refused outside a followed match (CREATE)
  double renewed_at_ = -1.0;  // the caller's clock when it opened or last started anew
  double heard_at_ = -1.0;    // and when it last heard a server (or renewed_at_)
  double renew_wait_ = kRenewFirst;
  uint64_t renewals_ = 0;
};

}  // namespace ballsrv
