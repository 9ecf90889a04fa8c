// The cases across the internet (docs/deploy.md): a server on a public
// address, its players and a watcher behind a home router doing NAT, over
// the TCP profiles (tcp_server, tcp_client), plain, under DDS Security and
// over TLS; the same layout on UDP does not connect; a stranger beside the
// players reaches nothing through TLS; a player's link cut for 3 s comes
// back by itself. Network namespaces the case makes and removes
// (itest_hosts.h): server host s (10.77.0.1), router r (10.77.0.2), behind
// it p and q (the players), w (a watcher) and x (a stranger).
#include <cstdlib>
#include <functional>

#include "itest_checks.h"
#include "itest_hosts.h"
#include "itest_kit.h"

using check::note;

namespace {

using namespace itest;

enum class Guard { none, dds_security, tls };

// The case's hosts and programs. The server (server 1) runs on `server_host`
// and a standby (server 2), if `standby_host` is set, on that host; the
// clients connect to `peers` (by default the server's address).
struct Wan {
  explicit Wan(const Env &env, std::vector<std::string> public_hosts = {"s"})
      : hosts(std::move(public_hosts)), port(std::to_string(20000 + env.domain)) {}
  Hosts hosts;
  std::string port;                    // the servers' TCP port
  std::string server_host = "s", standby_host;
  std::string peers;                   // the clients' --tcp-peers ("": the server's address)
  std::vector<std::string> server_extra;
  std::vector<std::string> security;   // a client's certificate options but --identity
  std::vector<std::string> watch_extra;
  std::string matches = "1";                 // the server's --matches
  std::vector<std::string> bot_extra[2];     // more options of each slot's bot
  std::string certs;
  std::function<void(Wan *)> before_clients;  // run once the servers are up
  int reconnects = 0;                         // clients started again (wan_rig)
  Process server, standby, w, p, q;
  std::unique_ptr<Tail> t;
};

// A program of the project on host h, its output to WHO.out and WHO.err.
Process on(const Env &env, const Wan &n, const char *h, const std::string &who, const std::string &exe,
           std::vector<std::string> args) {
  args.insert(args.begin(), {env.bin + "/" + exe, "--domain", env.dom()});
  return Process::start(n.hosts.on(h, args), path(env, who + ".out"), path(env, who + ".err"));
}

// A client's options on the TCP profile toward the server, as identity `who`.
std::vector<std::string> client(const Wan &n, const std::string &who, std::vector<std::string> more) {
  std::vector<std::string> a = {"--participant-profile", "tcp_client", "--tcp-peers",
                                n.peers.empty() ? n.hosts.address(n.server_host) + ":" + n.port : n.peers};
  a.insert(a.end(), n.security.begin(), n.security.end());
  if (!n.security.empty()) a.insert(a.end(), {"--identity", who});
  a.insert(a.end(), more.begin(), more.end());
  return a;
}

// The layout, the server of match 0 on s, a watcher on w and a bot on each
// of p and q; true once the match rallies (6 hits within 40 s).
bool wan_rig(const Env &env, Guard guard, Wan *n) {
  n->hosts.add_home("r", {"p", "q", "w", "x"});
  CHECK_MSG(n->hosts.ok(), "the hosts' namespaces: %s", n->hosts.error().c_str());
  if (!n->hosts.ok()) return false;
  if (guard != Guard::none) {
    n->certs = path(env, "certs");
    std::string err;
    CHECK_EQ(run_to_end(env, {"/bin/bash", env.source + "/server/security/certs.sh", n->certs, "1"}, "certs", &err), 0);
    n->security = {guard == Guard::tls ? "--tls" : "--secure", n->certs};
  }
  std::vector<std::string> s = {"--participant-profile", "tcp_server", "--tcp-listen", n->port, "--server-id", "1",
                                "--matches", n->matches, "--startup-wait", "0", "--duration", "120", "--state-rate", "10",
                                "--stats-json", path(env, "server.json")};
  s.insert(s.end(), n->server_extra.begin(), n->server_extra.end());
  s.insert(s.end(), n->security.begin(), n->security.end());
  if (!n->security.empty()) s.insert(s.end(), {"--identity", "server1"});
  n->server = on(env, *n, n->server_host.c_str(), "server", "ball-server", s);
  usleep(500000);
  if (!n->standby_host.empty()) {
    n->standby = on(env, *n, n->standby_host.c_str(), "standby", "ball-server",
                    {"--participant-profile", "tcp_server", "--tcp-listen", n->port, "--server-id", "2", "--standby",
                     "--startup-wait", "0.5", "--duration", "120", "--state-rate", "10", "--tcp-peers",
                     n->hosts.address(n->server_host) + ":" + n->port, "--stats-json", path(env, "standby.json")});
    usleep(1500000);
  }
  if (n->before_clients) n->before_clients(n);
  std::vector<std::string> watch = {"--no-log", "--duration", "120", "--record", path(env, "watch.jsonl")};
  watch.insert(watch.end(), n->watch_extra.begin(), n->watch_extra.end());
  // A client that heard nothing within 8 s is started again, up to twice, as
  // docs/deploy.md ("Limits") tells a client to: Fast DDS 2.9's race of
  // logical ports may leave a new connection deaf. Each restart is counted.
  bool ready = false;
  for (int attempt = 0; attempt < 3 && !ready; ++attempt) {
    if (attempt > 0) {
      n->w.stop(5.0);
      std::remove(path(env, "watch.jsonl").c_str());
      n->reconnects++;
    }
    n->w = on(env, *n, "w", "watch", "ball-watch", client(*n, "watch", watch));
    n->t = std::make_unique<Tail>(path(env, "watch.jsonl"));
    ready = !wait_for(*n->t, 8.0, [](const json &j) { return is_type(j, "ready"); }).is_null();
  }
  CHECK_MSG(ready, "the watcher behind the NAT did not match the server in 3 tries of 8 s");
  for (int slot = 0; slot < 2; ++slot) {
    const char *host = slot == 0 ? "p" : "q";
    std::vector<std::string> bot = client(*n, slot == 0 ? "m0-a" : "m0-b",
                                          {"--match", "0", "--player", std::to_string(slot), "--seed",
                                           std::to_string(slot + 1), "--duration", "100"});
    bot.insert(bot.end(), n->bot_extra[slot].begin(), n->bot_extra[slot].end());
    Process &b = slot == 0 ? n->p : n->q;
    bool joined = false;
    for (int attempt = 0; attempt < 3 && !joined; ++attempt) {
      if (attempt > 0) b.stop(5.0), n->reconnects++;
      b = on(env, *n, host, std::string("bot") + host, "ball-bot", bot);
      size_t from = 0;
      joined = !wait_for(*n->t, 8.0, [&](const json &j) {
                  return is_event(j, EventKind::join) && j.get<EventOut>().index == slot;
                }, &from).is_null();
    }
    CHECK_MSG(joined, "bot %d did not join in 3 tries of 8 s", slot);
  }
  if (n->reconnects) note("clients started again after hearing nothing for 8 s: %d", n->reconnects);
  bool rallying = rallies(*n->t, 1, 6, 40.0);
  if (!rallying) {
    Process ss = Process::start(n->hosts.on("s", {"ss", "-tn"}), path(env, "ss-failed.out"), "/dev/null");
    ss.wait(5.0);
  }
  CHECK_MSG(rallying, "match 0 had no 6 hits through the NAT within 40 s; the server's connections: %s",
            file_text(path(env, "ss-failed.out")).c_str());
  return rallying;
}

// The TCP connections the server's host has with its clients: the peers'
// addresses, one per connection (ss in its namespace).
std::vector<std::string> server_peers(const Env &env, const Wan &n) {
  Process ss = Process::start(n.hosts.on("s", {"ss", "-Htn", "state", "established"}), path(env, "ss.out"),
                              path(env, "ss.err"));
  ss.wait(5.0);
  std::vector<std::string> peers;
  std::istringstream in(file_text(path(env, "ss.out")));
  std::string line;
  while (std::getline(in, line)) {
    std::istringstream f(line);
    std::string recv_q, send_q, local, peer;
    if (!(f >> recv_q >> send_q >> local >> peer)) continue;
    if (local.substr(local.rfind(':') + 1) != n.port) continue;  // (the server's own outgoing ones)
    peers.push_back(peer.substr(0, peer.rfind(':')));
  }
  return peers;
}

// Stops the clients, then the server, and checks what the watcher saw.
void wan_end(Wan &n) {
  for (Process *c : {&n.p, &n.q, &n.w}) c->stop(5.0);
  n.t->poll();
  check_history(n.t->lines);
  for (Process *s : {&n.standby, &n.server})
    if (s->running()) {
      int rc = s->stop(5.0);
      CHECK_MSG(rc == 0, "a server's exit status on SIGTERM: %d", rc);
    }
}

// A match through the NAT: every connection the server has comes from the
// router's address (the players' own are private), and what the watcher
// saw breaks nothing.
void wan_plays(const Env &env, Guard guard) {
  Wan n(env);
  if (!wan_rig(env, guard, &n)) return;
  std::vector<std::string> peers = server_peers(env, n);
  size_t from_router = count_if(peers.begin(), peers.end(), [&](const std::string &a) { return a == n.hosts.address("r"); });
  note("through the NAT: the server has %zu client connections, %zu from the router's address %s", peers.size(),
       from_router, n.hosts.address("r").c_str());
  CHECK(peers.size() >= 3u);  // the watcher and two bots
  CHECK_EQ(from_router, peers.size());
  wan_end(n);
}

void case_wan_tcp(const Env &env) { wan_plays(env, Guard::none); }
void case_wan_secure(const Env &env) { wan_plays(env, Guard::dds_security); }

// Over TLS, a stranger on the players' LAN: a bot without a certificate, a
// bot with a certificate of another CA, and raw bytes (wan_stranger.py):
// none gets a slot or a byte of RTPS back, the server has no UDP port, and
// the rally goes on.
void case_wan_tls(const Env &env) {
  Wan n(env);
  if (!wan_rig(env, Guard::tls, &n)) return;
  std::string err;
  const std::string other = path(env, "other-ca");
  CHECK_EQ(run_to_end(env, {"/bin/bash", env.source + "/server/security/certs.sh", other, "1"}, "other-ca", &err), 0);
  const double from = realtime_now();
  std::vector<std::string> stranger = {"--participant-profile", "tcp_client", "--tcp-peers",
                                       n.hosts.address("s") + ":" + n.port, "--match", "0", "--player", "0",
                                       "--duration", "6"};
  Process none = on(env, n, "x", "stranger-plain", "ball-bot", stranger);
  usleep(1000000);
  stranger.insert(stranger.end(), {"--tls", other, "--identity", "m0-a"});
  Process foreign = on(env, n, "x", "stranger-other-ca", "ball-bot", stranger);
  Process raw = Process::start(n.hosts.on("x", {env.python, env.source + "/tests/server/wan_stranger.py",
                                                n.hosts.address("s"), n.port, env.dom()}),
                               path(env, "stranger-raw.out"), path(env, "stranger-raw.err"));
  CHECK_EQ(raw.wait(30.0), 0);
  none.wait(15.0);
  foreign.wait(15.0);
  json attack = json::parse(file_text(path(env, "stranger-raw.out")), nullptr, false);
  CHECK_MSG(attack.is_object(), "wan_stranger.py wrote no JSON: %s", file_text(path(env, "stranger-raw.err")).c_str());
  if (attack.is_object()) {
    note("the stranger's raw tries: %s", attack.dump().c_str());
    CHECK(!attack["plain"]["rtps_back"].get<bool>());
    CHECK(!attack["tls"]["rtps_back"].get<bool>());
  }
  for (const char *who : {"stranger-plain", "stranger-other-ca"}) {
    std::string out = file_text(path(env, std::string(who) + ".out")) + file_text(path(env, std::string(who) + ".err"));
    CHECK_MSG(out.find("holds match") == std::string::npos, "%s got a slot: %s", who, out.c_str());
  }
  double last = 0.0;
  int hits = hits_within(*n.t, from, 4, 20.0, &last);
  note("over TLS: %d hits in play after the stranger began", hits);
  CHECK(hits >= 4);
  // the server's host has no UDP socket at all (ss in its namespace)
  Process ss = Process::start(n.hosts.on("s", {"ss", "-Huan"}), path(env, "ss-udp.out"), path(env, "ss-udp.err"));
  ss.wait(5.0);
  CHECK_MSG(file_text(path(env, "ss-udp.out")).empty(), "UDP sockets on the server's host: %s",
            file_text(path(env, "ss-udp.out")).c_str());
  wan_end(n);
}

// The same layout on UDP (a Discovery Server on the server's host, the
// profile that needs no multicast): the clients' announcements give their
// private addresses, which the server cannot reach, so that the watcher
// never matches the server and no bot gets a slot.
void case_wan_udp(const Env &env) {
  Wan n(env);
  n.hosts.add_home("r", {"p", "q", "w", "x"});
  CHECK_MSG(n.hosts.ok(), "the hosts' namespaces: %s", n.hosts.error().c_str());
  if (!n.hosts.ok()) return;
  const std::string ds = n.hosts.address("s") + ":11811";
  DiscoveryServer discovery;
  discovery.p = Process::start(n.hosts.on("s", {env.fastdds, "discovery", "-x", "discovery_server@" + find_profile(""),
                                                "-l", n.hosts.address("s"), "-p", "11811"}),
                               path(env, "ds.out"), path(env, "ds.err"));
  const std::vector<std::string> udp = {"--participant-profile", "discovery_client", "--discovery-server", ds};
  auto with = [&](std::vector<std::string> a) {
    a.insert(a.begin() + 1, udp.begin(), udp.end());
    return a;
  };
  Server server(Process::start(
      n.hosts.on("s", with({env.bin + "/ball-server", "--domain", env.dom(), "--matches", "1", "--startup-wait", "0",
                            "--duration", "60"})),
      path(env, "server.out"), path(env, "server.err")));
  // (the server reaches the Discovery Server on its own host: a watcher there sees it)
  Process here = Process::start(
      n.hosts.on("s", with({env.bin + "/ball-watch", "--domain", env.dom(), "--no-log", "--duration", "60",
                            "--record", path(env, "here.jsonl")})),
      path(env, "here.out"), path(env, "here.err"));
  Process w = Process::start(
      n.hosts.on("w", with({env.bin + "/ball-watch", "--domain", env.dom(), "--no-log", "--duration", "60",
                            "--record", path(env, "watch.jsonl")})),
      path(env, "watch.out"), path(env, "watch.err"));
  Process bot = Process::start(
      n.hosts.on("p", with({env.bin + "/ball-bot", "--domain", env.dom(), "--match", "0", "--duration", "15"})),
      path(env, "bot.out"), path(env, "bot.err"));
  Tail t_here(path(env, "here.jsonl"));
  bool seen_here = !wait_for(t_here, 15.0, [](const json &j) { return is_type(j, "match_info"); }).is_null();
  bot.wait(25.0);
  Tail t(path(env, "watch.jsonl"));
  t.poll();
  size_t infos = count(t.lines, [](const json &j) { return is_type(j, "match_info"); });
  std::string bot_out = file_text(path(env, "bot.out")) + file_text(path(env, "bot.err"));
  note("UDP through the NAT: a watcher on the server's host saw the match: %s; behind the NAT: %zu MatchInfos, the "
       "bot %s a slot",
       seen_here ? "yes" : "no", infos, bot_out.find("holds match") != std::string::npos ? "got" : "got no");
  CHECK(seen_here);
  CHECK_EQ(infos, 0u);
  CHECK(bot_out.find("holds match") == std::string::npos);
  here.stop(5.0);
  w.stop(5.0);
}

// The link of a player (host p) cut for 3 s, then back: the player's
// connection comes back by itself; the match pauses (vanished) and resumes
// by its rules; a watcher on p's own host loses no segment or event and gets
// none twice (check_stream), and what the watcher on w saw breaks nothing.
void case_wan_link_cut(const Env &env) {
  Wan n(env);
  if (!wan_rig(env, Guard::none, &n)) return;
  Process wp = on(env, n, "p", "watch_p", "ball-watch",
                  client(n, "watch", {"--no-log", "--duration", "60", "--record", path(env, "watch_p.jsonl")}));
  Tail tp(path(env, "watch_p.jsonl"));
  CHECK(!wait_for(tp, 20.0, [](const json &j) { return is_type(j, "match_info"); }).is_null());
  usleep(2000000);
  const double cut = realtime_now();
  CHECK(n.hosts.cut("p"));
  usleep(3000000);
  CHECK(n.hosts.heal("p"));
  const double healed = realtime_now();
  size_t from = 0;
  json pause = wait_for(*n.t, 5.0, [&](const json &j) {
    return is_event(j, EventKind::pause) && j.get<EventOut>().reason == Reason::pause_vanished && recv(j) > cut;
  }, &from);
  CHECK_MSG(!pause.is_null(), "no PAUSE_VANISHED after the cut");
  json resume = wait_for(*n.t, 15.0, [](const json &j) { return is_event(j, EventKind::resume); }, &from);
  CHECK_MSG(!resume.is_null(), "no RESUME within 15 s of the pause");
  double last = 0.0;
  int hits = hits_within(*n.t, healed, 4, 25.0, &last);
  usleep(2000000);
  wp.stop(5.0);
  tp.poll();
  std::map<uint32_t, Seen> seen = by_match(tp.lines);
  int bounces = check_stream(0, seen[0]);
  check_history(tp.lines);
  size_t before = 0, after = 0;
  for (double r : seen[0].segment_recv) (r < cut ? before : after) += r < cut || r > healed;
  CHECK_MSG(before >= 3 && after >= 3, "the cut host's watcher got %zu segments before the cut, %zu after the heal",
            before, after);
  note("a player's link cut for 3 s: paused %.1f s after the cut, resumed %.1f s after the heal, %d hits after; the "
       "cut host's watcher got %zu segments and %zu events, %d bounces checked",
       pause.is_null() ? -1.0 : recv(pause) - cut, resume.is_null() ? -1.0 : recv(resume) - healed, hits,
       seen[0].segments.size(), seen[0].events.size(), bounces);
  CHECK(hits >= 4);
  wan_end(n);  // (the bots' output is whole once they ended)
  std::string bot = file_text(path(env, "botp.out")) + file_text(path(env, "botp.err"));
  size_t holds = 0;
  for (size_t at = bot.find("holds match"); at != std::string::npos; at = bot.find("holds match", at + 1)) holds++;
  CHECK_MSG(holds == 1u, "the player on p took a slot %zu times (it should have kept its one)", holds);
}

// A primary on host a and a standby on host b, both on public addresses,
// the clients behind the home router listing both: the primary killed
// (SIGKILL) mid-rally, the standby takes the match over and the rally goes
// on, over TCP as on UDP (docs/server.md, "Several servers and failover").
// A primary on host a and a standby on host b, the clients listing both;
// true once the match rallies (wan_rig).
bool two_servers_rig(const Env &env, Wan *n) {
  n->server_host = "a";
  n->standby_host = "b";
  n->peers = n->hosts.address("a") + ":" + n->port + ";" + n->hosts.address("b") + ":" + n->port;
  return wan_rig(env, Guard::none, n);
}

void case_wan_failover(const Env &env) {
  Wan n(env, {"a", "b"});
  if (!two_servers_rig(env, &n)) return;
  const double killed = realtime_now();
  n.server.signal(SIGKILL);
  n.server.wait(2.0);
  // (a player whose connection to the standby stayed deaf starts anew once the match is
  // silent for 10 s, and the standby takes the match over 2 s after it hears it: deploy.md, "Limits")
  json taken = wait_for(*n.t, 20.0, [&](const json &j) {
    return is_type(j, "match_info") && j.get<MatchInfoOut>().server_id == 2 && recv(j) > killed;
  });
  CHECK_MSG(!taken.is_null(), "no MatchInfo of the standby within 20 s of the kill");
  double last = 0.0;
  int hits = hits_within(*n.t, killed, 4, 30.0, &last);
  wan_end(n);
  ServerReport s = report(env, "standby");
  note("over TCP through the NAT: the standby's MatchInfo %.2f s after the kill, %d hits after, %llu take-overs",
       taken.is_null() ? -1.0 : recv(taken) - killed, hits, static_cast<unsigned long long>(s.takeovers));
  CHECK(hits >= 4);
  CHECK_EQ(s.takeovers, 1u);
}

// The same layout, the primary stopped (SIGSTOP) for 6 s and let go on:
// the standby takes the match over at the next term, the primary yields it
// on its return over its still open TCP connections, and from 1 s after
// the return the watcher gets nothing of the primary's; the rally goes on.
void case_wan_stall(const Env &env) {
  Wan n(env, {"a", "b"});
  if (!two_servers_rig(env, &n)) return;
  const double stopped = realtime_now();
  n.server.signal(SIGSTOP);
  json taken = wait_for(*n.t, 10.0, [&](const json &j) {
    return is_type(j, "match_info") && j.get<MatchInfoOut>().server_id == 2 && recv(j) > stopped;
  });
  CHECK_MSG(!taken.is_null(), "no MatchInfo of the standby within 10 s of the stop");
  sleep_until(mono_now() + std::max(0.0, stopped + 6.0 - realtime_now()));
  const double back = realtime_now();
  n.server.signal(SIGCONT);
  double last = 0.0;
  int hits = hits_within(*n.t, back, 4, 25.0, &last);
  n.t->poll();
  size_t of_old = count_if(n.t->lines.begin(), n.t->lines.end(), [&](const json &j) {
    return j.contains("server") && j.value("server", 0u) == 1u && recv(j) > back + 1.0 &&
           (is_type(j, "match_info") || is_type(j, "segment") || is_type(j, "event") || is_type(j, "state"));
  });
  wan_end(n);
  ServerReport primary = report(env, "server"), standby = report(env, "standby");
  note("over TCP through the NAT: the standby's MatchInfo %.2f s after the stop; after the return %d hits, %zu "
       "samples of the old owner, %llu take-overs, %llu yields",
       taken.is_null() ? -1.0 : recv(taken) - stopped, hits, of_old,
       static_cast<unsigned long long>(standby.takeovers), static_cast<unsigned long long>(primary.yields));
  CHECK(hits >= 4);
  CHECK_EQ(of_old, 0u);
  CHECK_EQ(standby.takeovers, 1u);
  CHECK_EQ(primary.yields, 1u);
}

// The server in a data centre whose router forwards the port to the
// server's private address (dnat): announcing the router's address
// (--tcp-public-address), the players behind their own router play;
// announcing its own, a watcher there never matches it (it is told to
// reach the server at an address it cannot reach).
void case_wan_public_address(const Env &env) {
  for (bool announce : {false, true}) {
    Wan n(env, {});
    n.hosts.add_home("dc", {"d"}, std::stoi(n.port), "d");
    n.server_host = "d";
    n.peers = n.hosts.address("dc") + ":" + n.port;
    if (announce) {
      n.server_extra = {"--tcp-public-address", n.hosts.address("dc")};
      if (wan_rig(env, Guard::none, &n)) note("announcing %s: the match rallies", n.hosts.address("dc").c_str());
      wan_end(n);
      continue;
    }
    n.hosts.add_home("r", {"p", "q", "w", "x"});
    CHECK_MSG(n.hosts.ok(), "the hosts' namespaces: %s", n.hosts.error().c_str());
    Server server(on(env, n, "d", "unannounced", "ball-server",
                     {"--participant-profile", "tcp_server", "--tcp-listen", n.port, "--matches", "1",
                      "--startup-wait", "0", "--duration", "60"}));
    Process w = on(env, n, "w", "unannounced-watch", "ball-watch",
                   client(n, "watch", {"--no-log", "--duration", "60", "--record", path(env, "unannounced.jsonl")}));
    Tail t(path(env, "unannounced.jsonl"));
    json ready = wait_for(t, 12.0, [](const json &j) { return is_type(j, "ready"); });
    note("announcing its own address %s: the watcher %s", n.hosts.address("d").c_str(),
         ready.is_null() ? "never matched the server in 12 s" : "matched it");
    CHECK(ready.is_null());
    w.stop(5.0);
  }
}

// One match through the test's relay (tests/support/delay_relay.py) on the
// home router, between the players' LAN and the server, delaying each
// direction by `delay` s one way with jitter of a fifth of that; the
// players' own connections to the server are dropped by the router, so
// that everything goes through it (the server announces the relay's
// address). Its figures as a JSON row, the hits in play of the 20 s from
// the first serve in *hits; null after a failed check.
json delay_run(const Env &env, double delay, std::vector<EventOut> *hits) {
  const double jitter = delay / 5.0;
  Wan n(env);
  const std::string relay_at = "192.168.7.1:" + n.port;  // the router's LAN address (itest_hosts.h)
  n.peers = relay_at;
  n.server_extra = {"--tcp-public-address", "192.168.7.1"};
  const std::string summary = path(env, "watch.json"), relay_stats = path(env, "relay.json");
  for (const std::string &f : {summary, relay_stats, path(env, "watch.jsonl"), path(env, "server.json")})
    std::remove(f.c_str());  // (the run before's)
  n.watch_extra = {"--summary-json", summary};
  Process relay;
  n.before_clients = [&](Wan *w) {
    Process drop = Process::start(
        w->hosts.on("r", {"/usr/sbin/nft", "insert rule ip home in iifname br1 tcp dport " + w->port + " drop"}),
        path(env, "nft.out"), path(env, "nft.err"));
    CHECK_EQ(drop.wait(5.0), 0);
    char d[32], j[32];
    std::snprintf(d, sizeof d, "%.4f", delay);
    std::snprintf(j, sizeof j, "%.4f", jitter);
    relay = Process::start(w->hosts.on("r", {env.python, env.source + "/tests/support/delay_relay.py", "--listen",
                                             relay_at, "--to", w->hosts.address("s") + ":" + w->port, "--delay", d,
                                             "--jitter", j, "--stats", relay_stats}),
                           path(env, "relay.out"), path(env, "relay.err"));
    double end = mono_now() + 10.0;
    while (file_text(path(env, "relay.out")).find("listening") == std::string::npos && mono_now() < end)
      usleep(50000);
  };
  if (!wan_rig(env, Guard::none, &n)) return json();
  // 20 s of rally from its first hit: a pause before it (a client started
  // anew after a deaf TCP connection: docs/deploy.md, "Limits") takes none of them
  double t0 = first_serve(*n.t), last = 0.0;
  json first = t0 >= 0.0 ? wait_for(*n.t, 30.0, is_hit) : json();
  t0 = first.is_null() ? -1.0 : recv(first) - 1e-6;
  if (t0 >= 0.0) hits_within(*n.t, t0, 1000, 20.0, &last);
  wan_end(n);
  CHECK_EQ(relay.stop(5.0), 0);
  for (const json &j : n.t->lines)
    if (is_hit(j) && recv(j) <= t0 + 20.0) hits->push_back(j.get<EventOut>());
  ServerReport r = report(env, "server");
  uint64_t rewinds = 0, tested = 0;
  for (const auto &m : r.matches) rewinds += m.counters.rewinds, tested += m.counters.late_tested;
  WatchSummary w;
  json rs = json::parse(file_text(relay_stats), nullptr, false);
  CHECK_MSG(rs.is_object(), "no relay stats: %s", file_text(path(env, "relay.err")).c_str());
  if (!read_summary(summary, &w) || !rs.is_object() || w.matches.empty()) return json();
  const double up = rs["up"]["delay_mean"].get<double>(), down = rs["down"]["delay_mean"].get<double>();
  note("%.0f ms one way (jitter %.0f ms; the relay's mean %.0f up, %.0f down): %zu hits in 20 s, %llu late samples "
       "tested, %llu rewinds, desync %.3g m; sample-to-segment p50 %.0f ms at the server, %.0f ms at the watcher; "
       "bounces %llu ahead, %llu late",
       delay * 1e3, jitter * 1e3, up * 1e3, down * 1e3, hits->size(), (unsigned long long)tested,
       (unsigned long long)rewinds, w.matches[0].max_error, w.latency_server_p50 * 1e3, w.latency_p50 * 1e3,
       (unsigned long long)w.bounces_ahead, (unsigned long long)w.bounces_late);
  CHECK(rs["connections"].get<int>() >= 3);
  CHECK(up >= delay && down >= delay);
  CHECK_MSG(hits->size() >= 6u, "%zu hits in 20 s", hits->size());
  CHECK(w.matches[0].max_error <= 1e-9);
  return {{"delay", delay},
          {"jitter", jitter},
          {"relay_up_mean", up},
          {"relay_down_mean", down},
          {"hits_20s", hits->size()},
          {"rewinds", rewinds},
          {"late_tested", tested},
          {"desync", w.matches[0].max_error},
          {"sample_to_segment_server_p50", w.latency_server_p50},
          {"sample_to_segment_server_p99", w.latency_server_p99},
          {"sample_to_segment_watcher_p50", w.latency_p50},
          {"sample_to_segment_watcher_p99", w.latency_p99},
          {"bounces_ahead", w.bounces_ahead},
          {"bounces_late", w.bounces_late},
          {"bounce_lead_p50", w.bounce_lead_p50}};
}

// Real delay ($BALL_WAN_DELAY s one way, default 0.15): the match behind
// it and the same match (the same bots, the same seeds) at 0 ms. It
// rallies, the watcher's ball is the server's (desync 0), and every hit is
// judged as at 0 ms: the same racket hits each ball, within one sample
// interval of the bots (1/30 s) and a frame of the same sim time, 0.25 m of
// the same point, 0.5 m/s of the same return. (Two runs at 0 ms differ by as
// much as a few ms and cm: the bots sample on their own clocks.) The row
// goes to wan_delay.json in the work folder (`./run bench-wan` gathers
// them).
void case_wan_delay(const Env &env) {
  const char *given = std::getenv("BALL_WAN_DELAY");
  const double delay = given ? std::atof(given) : 0.15;
  std::vector<EventOut> at0, behind;
  json base = delay_run(env, 0.0, &at0);
  json row = delay_run(env, delay, &behind);
  if (base.is_null() || row.is_null()) return;
  const size_t n = std::min(at0.size(), behind.size());
  size_t same_racket = 0;
  double dt = 0.0, dp = 0.0, dv = 0.0;
  for (size_t k = 0; k < n; ++k) {
    same_racket += at0[k].index == behind[k].index;
    dt = std::max(dt, std::fabs(at0[k].time - behind[k].time));
    dp = std::max(dp, ball_v3_norm(ball_v3_sub(at0[k].point, behind[k].point)));
    dv = std::max(dv, ball_v3_norm(ball_v3_sub(at0[k].velocity_out, behind[k].velocity_out)));
  }
  row["hits_compared"] = n;
  row["same_racket"] = same_racket;
  row["max_time_difference"] = dt;
  row["max_point_difference"] = dp;
  row["max_return_difference"] = dv;
  std::ofstream(path(env, "wan_delay.json")) << row.dump() << "\n";
  note("behind %.0f ms against 0 ms: %zu hits compared, %zu by the same racket; the largest difference %.3g s in "
       "time, %.3g m in the point, %.3g m/s in the return",
       delay * 1e3, n, same_racket, dt, dp, dv);
  CHECK(n >= 6u);
  CHECK(at0.size() <= behind.size() + 1 && behind.size() <= at0.size() + 1);
  CHECK_EQ(same_racket, n);
  CHECK(dt <= 1.0 / 30.0 + 1.0 / 60.0);
  CHECK(dp <= 0.25);
  CHECK(dv <= 0.5);
}

// What the TCP options refuse, before any participant is made: each with
// status 1 and a sentence naming what is wrong.
void case_wan_refused(const Env &env) {
  struct Refused {
    std::vector<std::string> args;
    const char *expect;
  } refused[] = {
      {{"--tcp-peers", "10.77.0.1:7400"}, "has no TCP transport"},
      {{"--participant-profile", "tcp_client", "--tcp-peers", "10.77.0.1"}, "is not HOST:PORT"},
      {{"--participant-profile", "tcp_client", "--tcp-peers", "10.77.0.1:70000"}, "is not HOST:PORT"},
      {{"--participant-profile", "tcp_client", "--tcp-peers", "no-such-host.invalid:7400"}, "has no IPv4 address"},
      {{"--participant-profile", "tcp_client", "--tls", path(env, "none"), "--identity", "m0-a"}, "ca.pem"},
      {{"--tls", env.source, "--identity", "m0-a"}, "ca.pem"},
      {{"--participant-profile", "tcp_client", "--tls", path(env, "none")}, "needs --identity"},
  };
  int k = 0;
  for (const Refused &r : refused) {
    std::vector<std::string> argv = {env.bin + "/ball-watch", "--domain", env.dom(), "--duration", "3"};
    argv.insert(argv.end(), r.args.begin(), r.args.end());
    std::string err;
    int rc = run_to_end(env, argv, "refused" + std::to_string(++k), &err);
    note("%s: status %d: %s", r.args.back().c_str(), rc, err.substr(0, err.find('\n')).c_str());
    CHECK_MSG(rc == 1 && err.find(r.expect) != std::string::npos, "status %d: %s", rc, err.c_str());
  }
}

}  // namespace

// Bytes host h's TCP connections have received (`key` "bytes_received:")
// or sent ("bytes_sent:") so far, by ss: the RTPS stream in its TCP framing,
// without TCP and IP headers, bare acknowledgements or resent segments.
double tcp_bytes(const Env &env, const Wan &n, const std::string &h, const std::string &key) {
  std::string out = path(env, "ss-" + h + ".out");
  Process::start(n.hosts.on(h, {"ss", "-tinH"}), out, "/dev/null").wait(5.0);
  std::string text = file_text(out);
  double sum = 0.0;
  for (size_t at = text.find(key); at != std::string::npos; at = text.find(key, at + 1))
    sum += std::atof(text.c_str() + at + key.size());
  return sum;
}

// Bytes a second over `seconds` s: received by hosts p and q, written by the server's host.
struct Rates {
  double p = 0, q = 0, server = 0;
};
Rates tcp_rates(const Env &env, const Wan &n, double seconds) {
  auto now = [&] {
    return Rates{tcp_bytes(env, n, "p", "bytes_received:"), tcp_bytes(env, n, "q", "bytes_received:"),
                 tcp_bytes(env, n, "s", "bytes_sent:")};
  };
  Rates a = now();
  usleep(static_cast<useconds_t>(seconds * 1e6));
  Rates b = now();
  return {(b.p - a.p) / seconds, (b.q - a.q) / seconds, (b.server - a.server) / seconds};
}

// What one player receives does not grow with the matches on its server
// (docs/protocol.md, "A match's own partition"): match 0's bot on p reads
// its match's partition, the other, on q, every match (--every-match). The
// hosts' TCP connections count their bytes while match 0 plays alone (the
// others idle), then while $BALL_WAN_OTHERS (default 24) more matches play
// beside it, ball-load's bots on host l (./run bench-server: 99 and 999).
void case_wan_bytes(const Env &env) {
  const char *given = std::getenv("BALL_WAN_OTHERS");
  const int others = given ? std::atoi(given) : 24;
  constexpr double kWindow = 10.0;
  Wan n(env, {"s", "l"});
  n.matches = std::to_string(1 + others);
  n.bot_extra[1] = {"--every-match"};
  if (!wan_rig(env, Guard::none, &n)) return;
  n.t->poll();
  int hits0 = hits_by_match(n.t->lines)[0];
  Rates alone = tcp_rates(env, n, kWindow);
  n.t->poll();
  int hits_alone = hits_by_match(n.t->lines)[0] - hits0;
  Process load;
  if (others > 0) {
    load = on(env, n, "l", "load", "ball-load",
              client(n, "load", {"--matches", std::to_string(others), "--first-match", "1", "--warmup", "3",
                                 "--duration", "1000", "--stagger", "2"}));
    bool all = rallies(*n.t, 1 + others, 1, 30.0 + others * 0.05);
    CHECK_MSG(all, "the %d other matches did not all play in time (%zu did)", others,
              hits_by_match(n.t->lines).size() - 1);
  }
  n.t->poll();
  hits0 = hits_by_match(n.t->lines)[0];
  Rates beside = tcp_rates(env, n, kWindow);
  n.t->poll();
  int hits_beside = hits_by_match(n.t->lines)[0] - hits0;
  if (load.running()) load.stop(5.0);
  json row = {{"matches", 1 + others}, {"player_alone", alone.p}, {"player", beside.p},
              {"every_match_alone", alone.q}, {"every_match", beside.q}, {"server_alone", alone.server},
              {"server", beside.server}, {"hits_alone", hits_alone}, {"hits", hits_beside}};
  std::ofstream(path(env, "wan_bytes.json")) << row.dump() << "\n";
  note("match 0's hits in the windows: %d alone, %d beside", hits_alone, hits_beside);
  note("bytes a second in, match 0 alone / beside %d more matches: its own partition (p) %.0f / %.0f (x%.3f); "
       "every match (q) %.0f / %.0f (x%.2f); written by the server's host %.0f / %.0f",
       others, alone.p, beside.p, beside.p / alone.p, alone.q, beside.q, beside.q / alone.q, alone.server,
       beside.server);
  CHECK(alone.p > 500.0);  // (match 0's ball states, segments and infos do reach p)
  CHECK(std::fabs(beside.p / alone.p - 1.0) <= 0.10);
  // (what the partition keeps away; alone, q already reads the idle matches' MatchInfos)
  if (others > 0) CHECK(beside.q / alone.q >= 2.0);
  wan_end(n);
}

// A TCP client that hears no server starts anew by itself (docs/deploy.md,
// "Limits"), on this host: a watcher and two bots connect to a port where
// no server listens yet; 5 s later each has made a new participant; the
// server starts at 7 s, and the match rallies with the new participants.
void case_wan_renew(const Env &env) {
  const std::string port = std::to_string(20000 + env.domain);
  auto tcp = [&](const std::string &exe, const std::string &who, std::vector<std::string> more) {
    std::vector<std::string> a = {env.bin + "/" + exe, "--domain", env.dom(), "--participant-profile", "tcp_client",
                                  "--tcp-peers", "127.0.0.1:" + port};
    a.insert(a.end(), more.begin(), more.end());
    return Process::start(a, path(env, who + ".out"), path(env, who + ".err"));
  };
  Process w = tcp("ball-watch", "watch", {"--no-log", "--duration", "60", "--record", path(env, "watch.jsonl")});
  Process p = tcp("ball-bot", "botp", {"--match", "0", "--player", "0", "--seed", "1", "--duration", "50"});
  Process q = tcp("ball-bot", "botq", {"--match", "0", "--player", "1", "--seed", "2", "--duration", "50"});
  usleep(7000000);
  Tail t(path(env, "watch.jsonl"));
  t.poll();
  size_t renewed = count_if(t.lines.begin(), t.lines.end(), [](const json &j) { return is_type(j, "renewed"); });
  CHECK_EQ(renewed, 1u);  // at 5 s (the next would be 10 s later)
  Process s = Process::start({env.bin + "/ball-server", "--domain", env.dom(), "--participant-profile", "tcp_server",
                              "--tcp-listen", port, "--matches", "1", "--startup-wait", "0", "--duration", "60",
                              "--state-rate", "10"},
                             path(env, "server.out"), path(env, "server.err"));
  CHECK_MSG(rallies(t, 1, 4, 30.0), "no rally within 30 s of the server's start");
  bool ready_after = false;
  for (const json &j : t.lines) ready_after = (ready_after || is_type(j, "ready"));
  CHECK(ready_after);
  note("the watcher started anew %zu time(s) before the server came; the match rallied", renewed);
  for (Process *c : {&p, &q, &w}) c->stop(5.0);
  t.poll();
  check_history(t.lines);
  CHECK_EQ(s.stop(5.0), 0);
}

TEST(wan_tcp) { itest::in_case(case_wan_tcp); }
TEST(wan_secure) { itest::in_case(case_wan_secure); }
TEST(wan_tls) { itest::in_case(case_wan_tls); }
TEST(wan_udp) { itest::in_case(case_wan_udp); }
TEST(wan_link_cut) { itest::in_case(case_wan_link_cut); }
TEST(wan_failover) { itest::in_case(case_wan_failover); }
TEST(wan_public_address) { itest::in_case(case_wan_public_address); }
TEST(wan_delay) { itest::in_case(case_wan_delay); }
TEST(wan_refused) { itest::in_case(case_wan_refused); }
TEST(wan_bytes) { itest::in_case(case_wan_bytes); }
TEST(wan_renew) { itest::in_case(case_wan_renew); }
TEST(wan_stall) { itest::in_case(case_wan_stall); }
