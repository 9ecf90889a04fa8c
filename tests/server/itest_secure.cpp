// The networked case of DDS Security (docs/security.md, "What the tests
// show"): the same rally first on an open domain, then on a secure one, each
// under a loopback capture (tcpdump). On the open domain the capture holds
// the ball's positions in plaintext and a datagram forged from a captured
// racket sample reaches the server, as a LEAVE forged from a player's JOIN
// frees its slot; on the secure one the capture holds none of them, the same
// forgeries under a real player's GUID prefix are dropped, a
// participant without a certificate hears nothing and reaches no match, and a
// player certified for match 1 cannot write into match 0 (refused by DDS in
// the partition match/0, counted `not_permitted` from its own). A
// certified server claiming another's server id reaches a client that chose
// by id only, never one that bound the id to that server's certificate.
#include <dirent.h>
#include <unistd.h>

#include <set>

#include "itest_kit.h"

using check::note;

namespace {

using namespace itest;

// A named program of the case, logging NAME.out and NAME.err in the work folder.
Process program(const Env &env, const std::string &name, std::vector<std::string> argv) {
  return Process::start(argv, path(env, name + ".out"), path(env, name + ".err"));
}

// tcpdump on the loopback (as root: -Z keeps it so, to write into the work
// folder), every UDP datagram sent to a port of the case's domain, until
// stopped (by destination only: another domain's participant may send from an
// ephemeral port that falls in this range, and a deterministic rally of its
// own carries the same ball positions);
// the capture has begun when it returns (or a failed check says why not)
Process capture(const Env &env, const std::string &name) {
  int base = 7400 + 250 * env.domain;  // RTPS: the domain's 250 ports
  Process p = program(env, name, {env.tcpdump, "-i", "lo", "-U", "-Z", "root", "-w", path(env, name + ".pcap"), "udp", "and", "dst", "portrange",
                                  std::to_string(base) + "-" + std::to_string(base + 249)});
  double end = mono_now() + 10.0;
  while (file_text(path(env, name + ".err")).find("listening on") == std::string::npos && mono_now() < end &&
         p.wait(0.05) == -1) {
  }
  CHECK_MSG(file_text(path(env, name + ".err")).find("listening on") != std::string::npos,
            "tcpdump did not start (root, or CAP_NET_RAW, and ./run setup's tcpdump): %s",
            file_text(path(env, name + ".err")).c_str());
  return p;
}

// tests/server/wire_check.py's answer (an empty object on failure, with a failed check)
json wire_check(const Env &env, const std::string &name, std::vector<std::string> args) {
  args.insert(args.begin(), {env.python, env.source + "/tests/server/wire_check.py"});
  std::string err;
  int rc = run_to_end(env, args, name, &err);
  CHECK_MSG(rc == 0, "wire_check.py %s: status %d: %s", args[2].c_str(), rc, err.c_str());
  json j = json::parse(file_text(path(env, name + ".out")), nullptr, false);
  CHECK_MSG(!j.is_discarded(), "wire_check.py %s printed no JSON", args[2].c_str());
  return j.is_discarded() || !j.is_object() ? json::object() : j;
}

// the server's report at its end (a failed check when unreadable)
uint64_t drops(const ServerReport &r, SampleResult why) { return r.status.drops[static_cast<int>(why)]; }

// A server, a ready watcher and two bots at 15 Hz, each with its DDS
// arguments (none: the open domain); the watcher records to TAG.jsonl.
struct Rally {
  Server server;
  Process w, b0, b1;
  Tail t{""};
};

Rally rally(Case &c, const std::string &tag, const std::vector<std::string> &server_dds,
            const std::vector<std::string> &watch_dds, const std::vector<std::string> &bot0_dds,
            const std::vector<std::string> &bot1_dds) {
  std::string rec = path(c.env, tag + ".jsonl");
  auto bot = [&](int slot, std::vector<std::string> extra) {
    extra.insert(extra.end(), {"--rate", "15"});
    return c.bot(slot, extra);
  };
  Rally r{Server(c.server(server_dds)), ready_watcher(c, rec, watch_dds), bot(0, bot0_dds), bot(1, bot1_dds), Tail(rec)};
  return r;
}

// slot 0's holder (its GUID prefix, hex) as the server announces it ("" and a failed check: none)
std::string slot0_holder(Tail &t) {
  json info = wait_for(t, 5.0, [](const json &j) {
    return is_type(j, "match_info") && j.at("slots").at(0).at("held").get<bool>();
  });
  std::string owner = info.is_null() ? "" : info.at("slots").at(0).at("owner").get<std::string>();
  CHECK_MSG(owner.size() == 24, "no holder of slot 0 announced");
  return owner;
}

// Stops the rally's programs, the server last (its report in *rep), then the
// capture TAG.pcap; what wire_check.py finds of TAG.jsonl's positions in it.
json end_rally(const Env &env, Rally &r, Process &cap, const std::string &tag, ServerReport *rep) {
  r.b0.stop();
  r.b1.stop();
  r.w.stop();
  *rep = stop_server(r.server, path(env, "server.json"));
  cap.stop();
  return wire_check(env, tag + "_scan", {"scan", path(env, tag + ".pcap"), path(env, tag + ".jsonl")});
}

void case_secure(const Env &env) {
  Case c{env};
  std::string err, certs = path(env, "certs");
  int rc = run_to_end(env, {"/bin/bash", env.source + "/server/security/certs.sh", certs, "2"}, "certs", &err);
  CHECK_MSG(rc == 0, "certs.sh: status %d: %s", rc, err.c_str());
  if (rc != 0) return;

  // a server id bound to a certificate means nothing on an open domain: refused at start
  rc = run_to_end(env, {env.bin + "/ball-watch", "--domain", env.dom(), "--duration", "2", "--servers", "1=server1"},
                  "bound_open", &err);
  CHECK_MSG(rc == 1 && err.find("bound to certificates (ID=IDENTITY) need security_dir") != std::string::npos,
            "--servers 1=server1 open: %d: %s", rc, err.c_str());

  // ---- the open domain: what an eavesdropper and a forger get there ----
  {
    Process cap = capture(env, "open");
    Rally r = rally(c, "open", {}, {}, {}, {});
    int hits = hits_after_serve_within(r.t, 3, 20.0);
    CHECK_MSG(hits >= 3, "open: %d hits", hits);
    json forged = wire_check(env, "open_forge", {"forge", path(env, "open.pcap"), env.dom()});
    // a LEAVE of slot 0 forged from its holder's own JOIN frees the slot (the match pauses)
    std::string holder = slot0_holder(r.t);
    size_t from = r.t.lines.size();
    wire_check(env, "open_leave", {"forge", path(env, "open.pcap"), env.dom(), "--leave", "--sender", holder});
    bool paused = !wait_for(r.t, 3.0, [](const json &j) { return is_event(j, EventKind::pause); }, &from).is_null();
    usleep(500000);
    ServerReport rep;
    json scan = end_rally(env, r, cap, "open", &rep);
    note("open: %d hits; %s of %s positions in plaintext; forged racket samples counted unknown_match: %llu; "
         "a forged LEAVE %s",
         hits,
         scan.value("positions_found", json(0)).dump().c_str(), scan.value("positions", json(0)).dump().c_str(),
         static_cast<unsigned long long>(drops(rep, SampleResult::unknown_match)), paused ? "paused it" : "did nothing");
    // the checks below can fail: in the open, positions and forgeries get through
    CHECK(scan.value("positions", 0) >= 50);
    CHECK(scan.value("positions_found", 0) >= scan.value("positions", 0) * 9 / 10);
    CHECK(forged.value("forged", 0) >= 1);
    CHECK(drops(rep, SampleResult::unknown_match) >= 1);
    CHECK_MSG(paused, "open: a forged LEAVE under the holder's prefix did not pause the match");
  }

  // ---- the secure domain ----
  auto sec = [&](const char *who) { return std::vector<std::string>{"--secure", certs, "--identity", who}; };
  Process cap = capture(env, "secure");
  // the clients take the server topics only from server 1 holding server1's certificate
  auto bound = [&](const char *who) {
    std::vector<std::string> a = sec(who);
    a.insert(a.end(), {"--servers", "1=server1"});
    return a;
  };
  Rally r = rally(c, "secure", sec("server1"), bound("watch"), bound("m0-a"), bound("m0-b"));
  int hits = hits_after_serve_within(r.t, 3, 20.0);
  CHECK_MSG(hits >= 3, "secure: %d hits", hits);
  std::string owner = slot0_holder(r.t);

  // a stranger without a certificate, and a player of match 1, both writing into match 0
  auto intruder = [&](const std::string &name, std::vector<std::string> extra) {
    std::vector<std::string> a = {env.bin + "/ball_intrude", "--domain", env.dom(), "--match", "0", "--duration", "5",
                                  "--out", path(env, name + ".json")};
    a.insert(a.end(), extra.begin(), extra.end());
    return program(env, name, a);
  };
  Process stranger = intruder("stranger", {});
  std::vector<std::string> cross = sec("m1-a");
  cross.insert(cross.end(), {"--partition", "match/1", "--wait-match"});
  Process player1 = intruder("player1", cross);
  // a certified server (server3) claiming server id 1 for a match 7 of its own, and two watchers:
  // one that takes server id 1 from anyone certified, one that bound it to server1's certificate
  std::vector<std::string> hostile = sec("server3");
  hostile.insert(hostile.end(), {"--as-server", "1", "--match", "7"});
  std::vector<std::string> h = {env.bin + "/ball_intrude", "--domain", env.dom(), "--duration", "5", "--out",
                                path(env, "hostile.json")};
  h.insert(h.end(), hostile.begin(), hostile.end());
  Process hostile_server = program(env, "hostile", h);
  auto watch = [&](const std::string &name, std::vector<std::string> who) {
    std::vector<std::string> a = {env.bin + "/ball-watch", "--domain", env.dom(), "--duration", "6", "--quiet",
                                  "--summary-json", path(env, name + ".json")};
    a.insert(a.end(), who.begin(), who.end());
    return program(env, name, a);
  };
  std::vector<std::string> by_id = sec("watch");
  by_id.insert(by_id.end(), {"--servers", "1"});
  Process watch_id = watch("watch_by_id", by_id), watch_cert = watch("watch_by_cert", bound("watch"));
  // the player of match 1 cannot even make a writer in match 0's partition
  std::vector<std::string> into0 = sec("m1-a");
  into0.insert(into0.end(), {"--partition", "match/0", "--duration", "1"});
  into0.insert(into0.begin(), {env.bin + "/ball_intrude", "--domain", env.dom(), "--match", "0"});
  rc = run_to_end(env, into0, "player1_in_match0", &err);
  CHECK_MSG(rc == 1 && err.find("permissions do not grant it in partition match/0") != std::string::npos,
            "a writer of m1-a in match/0: status %d: %s", rc, err.c_str());
  json forged = wire_check(env, "secure_forge", {"forge", path(env, "open.pcap"), env.dom(), "--prefix", owner});
  size_t leave_from = r.t.lines.size();
  wire_check(env, "secure_leave", {"forge", path(env, "open.pcap"), env.dom(), "--leave", "--prefix", owner});
  CHECK_EQ(stranger.wait(15.0), 0);
  CHECK_EQ(player1.wait(15.0), 0);
  CHECK_EQ(hostile_server.wait(15.0), 0);
  CHECK_EQ(watch_id.wait(15.0), 0);
  CHECK_EQ(watch_cert.wait(15.0), 0);
  {
    json hs = json::parse(file_text(path(env, "hostile.json")), nullptr, false);
    json wi = json::parse(file_text(path(env, "watch_by_id.json")), nullptr, false);
    json wc = json::parse(file_text(path(env, "watch_by_cert.json")), nullptr, false);
    auto matches = [](const json &w) {
      std::set<uint32_t> ids;
      if (w.is_object())
        for (const auto &m : w.value("matches", json::array())) ids.insert(m.value("match", 0u));
      return ids;
    };
    std::set<uint32_t> by_id_seen = matches(wi), by_cert_seen = matches(wc);
    long forged_infos = hs.is_object() ? hs.value("infos", 0L) : 0L;
    uint64_t untrusted = wc.is_object() ? wc.value("untrusted", uint64_t{0}) : 0;
    note("a certified server3 claiming server 1 sent %ld MatchInfo for match 7: the watcher by id saw matches %s, "
         "the watcher bound to server1's certificate %s and refused %llu samples",
         forged_infos, json(by_id_seen).dump().c_str(), json(by_cert_seen).dump().c_str(),
         static_cast<unsigned long long>(untrusted));
    CHECK(forged_infos >= 10);
    // the attack is real for a client that chose by id only ...
    CHECK(by_id_seen.count(7) == 1 && by_id_seen.count(0) == 1);
    CHECK_EQ(wi.value("untrusted", uint64_t{1}), 0u);
    // ... and refused, every copy it received, by one that bound the id to the certificate
    CHECK(by_cert_seen.count(7) == 0 && by_cert_seen.count(0) == 1);
    CHECK(untrusted >= 1 && untrusted <= static_cast<uint64_t>(forged_infos));
  }
  // the rally went on through it all, never paused by the forged LEAVE
  size_t from = r.t.lines.size();
  int later = 0;
  while (later < 2 && !wait_for(r.t, 10.0, is_hit, &from).is_null()) later++;
  CHECK_MSG(later >= 2, "%d hits after the intruders", later);
  r.t.poll();
  size_t pauses = 0;
  for (size_t i = leave_from; i < r.t.lines.size(); ++i) pauses += is_event(r.t.lines[i], EventKind::pause);
  CHECK_MSG(pauses == 0, "secure: %zu pauses after the forged LEAVE", pauses);
  ServerReport rep;
  json scan = end_rally(env, r, cap, "secure", &rep);
  json st = json::parse(file_text(path(env, "stranger.json")), nullptr, false);
  json p1 = json::parse(file_text(path(env, "player1.json")), nullptr, false);
  if (st.is_discarded() || p1.is_discarded()) {
    CHECK_MSG(false, "the intruders wrote no report");
    return;
  }
  long p1_samples = p1.value("samples", 0L), p1_controls = p1.value("controls", 0L);
  note("secure: %d hits, %d after the intruders; %s of %s positions in plaintext; the stranger heard %s infos and "
       "%s states; %llu of match 1's player's %ld samples not_permitted, %llu controls refused of its %ld; "
       "forged samples counted: %llu",
       hits, later, scan.value("positions_found", json(0)).dump().c_str(),
       scan.value("positions", json(0)).dump().c_str(), st.value("heard_infos", json(0)).dump().c_str(),
       st.value("heard_states", json(0)).dump().c_str(),
       static_cast<unsigned long long>(drops(rep, SampleResult::not_permitted)), p1_samples,
       static_cast<unsigned long long>(rep.status.controls_refused), p1_controls,
       static_cast<unsigned long long>(drops(rep, SampleResult::unknown_match)));
  // no plaintext ball on the wire
  CHECK(scan.value("positions", 0) >= 50);
  CHECK_EQ(scan.value("positions_found", -1), 0);
  // the stranger hears nothing and reaches nobody: its samples for slot 0 would be not_owner
  CHECK(st.value("samples", 0) >= 100);
  CHECK_EQ(st.value("heard_infos", -1), 0);
  CHECK_EQ(st.value("heard_states", -1), 0);
  CHECK_EQ(drops(rep, SampleResult::not_owner), 0u);
  // the forgery under the real player's prefix is dropped before any match sees it
  CHECK(forged.value("forged", 0) >= 1);
  CHECK_EQ(drops(rep, SampleResult::unknown_match), 0u);
  // match 1's player reaches the server and is refused by its own partition, every sample once
  // (a stranger's sample that got through would be not_permitted as well, from a writer nobody granted)
  CHECK(p1_samples >= 100);
  CHECK(drops(rep, SampleResult::not_permitted) <= static_cast<uint64_t>(p1_samples));
  // (a server loaded beside other work takes fewer of them: those DDS dropped for want of room
  // are counted as rejected or lost, writer unknown)
  uint64_t unseen = drops(rep, SampleResult::rejected) + drops(rep, SampleResult::lost);
  note("secure: %llu samples DDS rejected or lost (every writer's)", static_cast<unsigned long long>(unseen));
  CHECK(drops(rep, SampleResult::not_permitted) + unseen >= static_cast<uint64_t>(p1_samples) * 9 / 10);
  CHECK(drops(rep, SampleResult::not_permitted) >= static_cast<uint64_t>(p1_samples) / 2);
  // (and a bot's control the match refuses: a JOIN repeated, a LEAVE at the end)
  CHECK(rep.status.controls_refused <= static_cast<uint64_t>(p1_controls) + 2u);
  CHECK(rep.status.controls_refused >= static_cast<uint64_t>(p1_controls) * 8 / 10);
}

// ball-load under DDS Security: its one participant, as `load` (granted
// every match/*), writes in the partitions of every match it plays, and a
// sweep starts its server as server1; a player's identity cannot do it.
void case_load_secure(const Env &env) {
  std::string err, certs = path(env, "certs");
  int rc = run_to_end(env, {"/bin/bash", env.source + "/server/security/certs.sh", certs, "1"}, "certs", &err);
  CHECK_MSG(rc == 0, "certs.sh: status %d: %s", rc, err.c_str());
  if (rc != 0) return;
  std::string out = path(env, "load.json");
  auto load = [&](const char *identity, const std::string &json_out) {
    std::vector<std::string> a = {env.bin + "/ball-load", "--domain", env.dom(), "--sweep", "3", "--warmup", "5",
                                  "--duration", "4", "--secure", certs, "--identity", identity};
    if (!json_out.empty()) a.insert(a.end(), {"--json", json_out});
    return a;
  };
  rc = run_to_end(env, load("load", out), "load", &err);
  CHECK_MSG(rc == 0, "ball-load --secure as load: status %d: %s", rc, err.c_str());
  json j = json::parse(file_text(out), nullptr, false);
  CHECK_MSG(j.is_object() && j.value("rows", json::array()).size() == 1, "no row in %s", out.c_str());
  if (!j.is_object() || j.value("rows", json::array()).size() != 1) return;
  LoadRow row = j.at("rows").at(0).get<LoadRow>();
  note("ball-load under DDS Security, 3 matches: ready %s, %.1f samples/s, %llu hits, %llu write failures",
       row.ready ? "yes" : "no", row.samples_per_s, static_cast<unsigned long long>(row.hits),
       static_cast<unsigned long long>(row.write_failures));
  CHECK(row.ready);  // every slot joined: the server took its controls from all three partitions
  CHECK(row.hits >= 3);
  CHECK_EQ(row.write_failures, 0u);
  // a player's identity is granted its own match only
  rc = run_to_end(env, load("m0-a", ""), "load_as_player", &err);
  CHECK_MSG(rc == 1 && err.find("the transport refused the join of match 1: cannot create a writer on ball/racket_samples") != std::string::npos &&
                           err.find("permissions do not grant it in partition match/1") !=
                           std::string::npos,
            "ball-load as m0-a: status %d: %s", rc, err.c_str());
}

#ifdef __SANITIZE_ADDRESS__
constexpr bool kSanitized = true;  // built for ./run asan, as the programs it runs
#else
constexpr bool kSanitized = false;
#endif

// the resident memory of process `pid` (kB; 0: unknown)
long rss_kb(pid_t pid) {
  std::string status = file_text("/proc/" + std::to_string(pid) + "/status");
  size_t at = status.find("VmRSS:");
  return at == std::string::npos ? 0 : std::strtol(status.c_str() + at + 6, nullptr, 10);
}

// A flood of made-up participant announcements (docs/server-reference.md, "Discovery,
// bounded"), replayed from a captured one under 3000 fresh GUID prefixes in
// 3 s, at a server whose profile keeps at most 64 remote participants: its
// memory grows by a bounded amount, the rally in play goes on, and once the
// made-up leases (3 s) have run out a new watcher finds the server.
void case_discovery_flood(const Env &env) {
  Case c{env};
  std::string qos = path(env, "small_qos.xml"), text = file_text(env.source + "/server/qos/ball_qos.xml");
  const std::string room = "<maximum>4096</maximum>";
  size_t at = text.find(room);  // the first profile's, loopback's
  CHECK_MSG(at != std::string::npos && text.rfind("profile_name=\"loopback\"", at) != std::string::npos,
            "no participant maximum in the loopback profile");
  if (at == std::string::npos) return;
  text.replace(at, room.size(), "<maximum>64</maximum>");
  std::string err;
  CHECK(write_file(qos, text, &err));
  Process cap = capture(env, "discovery");
  Server server(c.server({"--profile", qos}));
  std::string rec = path(env, "watch.jsonl");
  Process w = ready_watcher(c, rec, {});
  Process b0 = c.bot(0, {"--rate", "15"}), b1 = c.bot(1, {"--rate", "15"});
  Tail t(rec);
  int hits = hits_after_serve_within(t, 2, 20.0);
  CHECK_MSG(hits >= 2, "%d hits before the flood", hits);
  cap.stop();
  long before = rss_kb(server.p.pid());
  size_t from = t.lines.size();
  double flood_start = mono_now();
  json flood = wire_check(env, "spdp", {"spdp", path(env, "discovery.pcap"), env.dom(), "--count", "3000", "--lease",
                                        "3", "--rate", "1000"});
  long after = rss_kb(server.p.pid());
  int during = 0;
  while (during < 1 && !wait_for(t, 5.0, is_hit, &from).is_null()) during++;
  usleep(4000000);  // the made-up leases run out
  double found_from = mono_now();
  Process late = ready_watcher(c, path(env, "late.jsonl"), {});
  double found = mono_now() - found_from;
  note("3000 made-up participants in %.1f s: server %ld -> %ld kB; %d hit(s) during and after; a new watcher found "
       "the server %.1f s after the leases ran out (%.1f s after the flood began)",
       flood.value("seconds", 0.0), before, after, during, found, mono_now() - flood_start);
  CHECK_EQ(flood.value("sent", 0), 3000);
  CHECK(before > 0 && after > 0);
  // (64 places cost about 1 MB; with the 4096 of the shipped profile the same flood grew it by 13 MB;
  // under AddressSanitizer freed memory waits in its quarantine and is not reused: 21 MB)
  if (!kSanitized) CHECK_MSG(after - before < 6 * 1024, "the server grew by %ld kB", after - before);
  CHECK_MSG(during >= 1, "no hit after the flood began");
  CHECK_MSG(late.running(), "the late watcher ended");
  late.stop();
  b0.stop();
  b1.stop();
  w.stop();
}

// The secure UDP domain's documented limit (docs/security.md, "Which
// profile holds against whom"): one plaintext datagram from a host without
// any certificate, a participant disposal in the name of slot 0's holder
// (its GUID prefix, plaintext in every announcement), removes the player:
// the match pauses (PAUSE_VANISHED) and does not resume, though the bot
// plays on. This checks the limit the page states; when Debian's Fast DDS
// takes the fix of CVE-2023-50257 it fails, and the page must change.
// The DDS options of identity `who` of the test certificates in `certs`
std::vector<std::string> secure_as(const std::string &certs, const char *who) {
  return {"--secure", certs, "--identity", who};
}

// test certificates for one match (certs.sh) and a rally on the secure UDP
// domain: the server, a watcher and match 0's two bots, each its identity
Rally secure_rally(Case &c, const std::string &tag, std::string *certs) {
  std::string err;
  *certs = path(c.env, "certs");
  CHECK_EQ(run_to_end(c.env, {"/bin/bash", c.env.source + "/server/security/certs.sh", *certs, "1"}, "certs", &err), 0);
  return rally(c, tag, secure_as(*certs, "server1"), secure_as(*certs, "watch"), secure_as(*certs, "m0-a"),
               secure_as(*certs, "m0-b"));
}

void case_secure_udp_disposal(const Env &env) {
  Case c{env};
  std::string err, certs;
  Rally r = secure_rally(c, "disposal", &certs);
  int hits = hits_after_serve_within(r.t, 3, 20.0);
  CHECK_MSG(hits >= 3, "%d hits before the datagram", hits);
  std::string holder = slot0_holder(r.t);
  size_t from = r.t.lines.size();
  const double sent = realtime_now();
  CHECK_EQ(run_to_end(env, {env.python, env.source + "/tests/server/udp_disposal.py", "127.0.0.1", env.dom(), holder},
                      "disposal", &err),
           0);
  json paused = wait_for(r.t, 3.0, [](const json &j) {
    return is_event(j, EventKind::pause) && j.get<EventOut>().index == 0;
  }, &from);
  bool resumed = !wait_for(r.t, 8.0, [](const json &j) { return is_event(j, EventKind::resume); }, &from).is_null();
  const bool bot_on = r.b0.running();
  note("one plaintext disposal datagram in slot 0's holder's name: %s %.2f s after it, %s within 8 s; the bot %s",
       paused.is_null() ? "no pause" : "paused", paused.is_null() ? -1.0 : recv(paused) - sent,
       resumed ? "resumed" : "not resumed", bot_on ? "still running" : "ended");
  CHECK_MSG(!paused.is_null(), "the documented limit did not reproduce: no pause within 3 s (security.md must change)");
  CHECK(!resumed);
  CHECK(bot_on);
  for (Process *p : {&r.b0, &r.b1, &r.w}) p->stop();
}

// The secure UDP domain's second reported attack (docs/benchmarks.md,
// "Attacks on the secure UDP domain"): a participant announcement captured
// on the domain (plaintext, as the protocol has it) sent again 300 times in
// 3 s, each under a fresh GUID prefix, from a host without certificates,
// then a normal certified join. What it does here: the server lives, the
// rally goes on, and the new watcher finds the server.
void case_secure_udp_replay(const Env &env) {
  Case c{env};
  Process cap = capture(env, "replay");
  std::string certs;
  Rally r = secure_rally(c, "replay", &certs);
  int hits = hits_after_serve_within(r.t, 2, 20.0);
  CHECK_MSG(hits >= 2, "%d hits before the replays", hits);
  cap.stop();
  size_t from = r.t.lines.size();
  json replays = wire_check(env, "spdp", {"spdp", path(env, "replay.pcap"), env.dom(), "--count", "300", "--lease",
                                          "10", "--rate", "100"});
  double join_from = mono_now();
  Process late = ready_watcher(c, path(env, "late.jsonl"), secure_as(certs, "watch"));
  double joined = mono_now() - join_from;
  int after = 0;
  while (after < 2 && !wait_for(r.t, 5.0, is_hit, &from).is_null()) after++;
  const bool server_on = r.server.p.running();
  note("%d replayed announcements in %.1f s, then a certified watcher: ready %.1f s after; %d hit(s) after; the "
       "server %s",
       replays.value("sent", 0), replays.value("seconds", 0.0), joined, after, server_on ? "still running" : "ended");
  CHECK_EQ(replays.value("sent", 0), 300);
  CHECK_MSG(server_on, "the server ended after the replays (docs/security.md and benchmarks.md must change)");
  CHECK_MSG(late.running(), "the late watcher ended");
  CHECK_MSG(after >= 2, "%d hits after the replays", after);
  for (Process *p : {&late, &r.b0, &r.b1, &r.w}) p->stop();
}

// Test certificates for one match (certs.sh) in the case's folder
// (*certs), and a secure server with match 0's slot 0 bound to m0-a and
// slot 1 to m0-b (--slot-owner).
Server slot_bound_server(Case &c, const Env &env, std::string *certs) {
  std::string err;
  *certs = path(env, "certs");
  CHECK_EQ(run_to_end(env, {"/bin/bash", env.source + "/server/security/certs.sh", *certs, "1"}, "certs", &err), 0);
  std::vector<std::string> sd = secure_as(*certs, "server1");
  sd.insert(sd.end(), {"--slot-owner", "0:0=m0-a", "--slot-owner", "0:1=m0-b"});
  return Server(c.server(sd));
}

// Slots bound to identities (docs/security.md): the server binds match 0's
// slot 0 to m0-a and slot 1 to m0-b (--slot-owner). A participant of m0-a,
// certified for match 0, JOINs slot 1 twice a second from before the bots
// start: every JOIN is refused (not_player), m0-b's bot takes its slot and
// the two rally.
void case_secure_slots(const Env &env) {
  Case c{env};
  std::string certs;
  Server server = slot_bound_server(c, env, &certs);
  std::vector<std::string> sq = {env.bin + "/ball_intrude", "--domain", env.dom(), "--match", "0", "--join", "1",
                                 "--rate", "2", "--duration", "14", "--partition", "match/0", "--wait-match",
                                 "--out", path(env, "squatter.json")};
  for (const auto &a : secure_as(certs, "m0-a")) sq.push_back(a);
  Process squatter = program(env, "squatter", sq);
  usleep(2000000);
  std::string rec = path(env, "slots.jsonl");
  Process w = ready_watcher(c, rec, secure_as(certs, "watch"));
  auto bot = [&](int slot, const char *who) {
    std::vector<std::string> a = secure_as(certs, who);
    a.insert(a.end(), {"--rate", "15", "--stats-json", path(env, std::string(who) + ".json")});
    return c.bot(slot, a);
  };
  Process b0 = bot(0, "m0-a"), b1 = bot(1, "m0-b");
  Tail t(rec);
  int hits = hits_after_serve_within(t, 3, 25.0);
  CHECK_EQ(squatter.wait(20.0), 0);
  ServerReport r = stop_all(server, {&b0, &b1, &w}, path(env, "server.json"));
  size_t refused = count(t.lines, [](const json &j) {
    return is_type(j, "event") && j.at("kind") == "refused" && j.at("reason") == "not_player";
  });
  json sent = json::parse(file_text(path(env, "squatter.json")), nullptr, false);
  long joins = sent.is_object() ? sent.value("controls", 0L) : 0L;
  note("m0-a's %ld JOINs of m0-b's slot: %zu refused not_player as the watcher saw them; %d hits", joins, refused, hits);
  CHECK(joins >= 10);
  CHECK(refused >= 5u);
  CHECK_MSG(hits >= 3, "%d hits with m0-b in its slot", hits);
  CHECK(r.status.controls_refused >= static_cast<uint64_t>(joins) / 2);
}

// Real s of CPU process `pid` has used (user and system), from /proc.
double cpu_seconds(pid_t pid) {
  std::istringstream in(file_text("/proc/" + std::to_string(pid) + "/stat"));
  std::string field;
  double ticks = 0.0;
  for (int k = 1; in >> field && k <= 15; ++k)
    if (k == 14 || k == 15) ticks += std::atof(field.c_str());  // utime, stime
  return ticks / static_cast<double>(sysconf(_SC_CLK_TCK));
}

// The UDP sockets process `pid` holds, from /proc/PID/net/udp (matched to
// the process's sockets by inode): the datagrams the kernel dropped on them
// (a full receive buffer) and the bytes waiting in them, not read yet.
struct UdpSockets {
  uint64_t drops = 0, queued = 0;
};
UdpSockets kernel_udp(pid_t pid) {
  std::set<std::string> inodes;
  std::string fds = "/proc/" + std::to_string(pid) + "/fd";
  if (DIR *d = opendir(fds.c_str())) {
    while (dirent *e = readdir(d)) {
      char link[128];
      ssize_t n = readlink((fds + "/" + e->d_name).c_str(), link, sizeof link - 1);
      if (n <= 0) continue;
      std::string l(link, static_cast<size_t>(n));
      if (l.rfind("socket:[", 0) == 0) inodes.insert(l.substr(8, l.size() - 9));
    }
    closedir(d);
  }
  UdpSockets u;
  std::istringstream table(file_text("/proc/" + std::to_string(pid) + "/net/udp"));
  std::string line;
  std::getline(table, line);  // the header
  while (std::getline(table, line)) {
    std::istringstream row(line);
    std::vector<std::string> f;
    for (std::string w; row >> w;) f.push_back(w);
    if (f.size() < 13 || !inodes.count(f[9])) continue;
    u.drops += std::strtoull(f[12].c_str(), nullptr, 10);
    u.queued += std::strtoull(f[4].substr(f[4].find(':') + 1).c_str(), nullptr, 16);  // tx_queue:rx_queue
  }
  return u;
}

// A certified player floods its own slot (the review's finding): m0-a
// holds slot 0 of match 0 and, once the server took one of its samples,
// writes 20,000 samples a second into it (as fast as it goes) for about
// 10 s while m0-b's bot holds slot 1. The partner never vanishes, and the
// books balance: samples_in = ok + idle + drops, no more than were sent
// (nothing counted twice); with what the kernel dropped from the server's
// full socket buffers, at least three quarters of the flood (what Fast
// DDS's receive path loses without a note when the server is short of CPU
// is the rest). The server's CPU over the flood is noted: it is Fast DDS's
// receive path, which no reader can refuse a writer's datagrams before
// (docs/security.md, "What it costs").
void case_secure_own_flood(const Env &env) {
  Case c{env};
  std::string certs;
  Server server = slot_bound_server(c, env, &certs);
  std::string rec = path(env, "flood.jsonl");
  Process w = ready_watcher(c, rec, secure_as(certs, "watch"));
  std::vector<std::string> pa = secure_as(certs, "m0-b");
  pa.insert(pa.end(), {"--rate", "15", "--stats-json", path(env, "m0-b.json")});
  Process partner = c.bot(1, pa);
  Tail t(rec);
  wait_for(t, 15.0, [](const json &j) {
    return is_type(j, "match_info") && j.at("match") == 0 && j.at("slots").at(1).at("held").get<bool>();
  });
  std::vector<std::string> fa = {env.bin + "/ball_intrude", "--domain", env.dom(), "--match", "0", "--join", "0",
                                 "--rate", "20000", "--duration", "14", "--partition", "match/0", "--wait-held",
                                 "--out", path(env, "flooder.json")};
  for (const auto &a : secure_as(certs, "m0-a")) fa.push_back(a);
  double cpu0 = cpu_seconds(server.p.pid()), began = mono_now();
  uint64_t kdrops0 = kernel_udp(server.p.pid()).drops;
  Process flooder = program(env, "flooder", fa);
  CHECK_EQ(flooder.wait(30.0), 0);
  double cpu = cpu_seconds(server.p.pid()) - cpu0, span = mono_now() - began;
  // what the flood left in the server's socket buffers is read (the partner's few come and go)
  for (double until = mono_now() + 15.0; kernel_udp(server.p.pid()).queued > 4096 && mono_now() < until;)
    usleep(50000);
  usleep(500000);
  uint64_t kdrops = kernel_udp(server.p.pid()).drops - kdrops0;
  double ended = realtime_now();
  usleep(1000000);
  ServerReport r = stop_all(server, {&partner, &w}, path(env, "server.json"));
  t.poll();
  size_t vanished = count(t.lines, [&](const json &j) {
    if (!is_event(j, EventKind::pause) || recv(j) > ended) return false;
    EventOut e = j.get<EventOut>();
    return e.reason == Reason::pause_vanished && e.index == 1;
  });
  json sent = json::parse(file_text(path(env, "flooder.json")), nullptr, false);
  uint64_t flooded = sent.is_object() ? sent.value("samples", uint64_t{0}) : 0;
  note("the flood began %.2f s after the start, once the server took a sample of m0-a's (%ld at 30 Hz before)",
       sent.is_object() ? sent.value("held_after", -1.0) : -1.0, sent.is_object() ? sent.value("samples_before_held", 0L) : 0L);
  uint64_t drops = 0;
  for (int i = 0; i < kDropReasons; ++i) drops += r.status.drops[i];
  note("m0-a wrote %llu samples into its own slot in %.1f s: the server took %llu in (%llu ok, %llu rejected, %llu "
       "stale), DDS counted %llu lost, the kernel dropped %llu datagrams of its full socket buffers; the partner "
       "vanished %zu times; the server used %.0f %% of a core",
       static_cast<unsigned long long>(flooded), span, static_cast<unsigned long long>(r.status.samples_in),
       static_cast<unsigned long long>(r.status.samples_ok),
       static_cast<unsigned long long>(r.status.drops[static_cast<int>(SampleResult::rejected)]),
       static_cast<unsigned long long>(r.status.drops[static_cast<int>(SampleResult::stale)]),
       static_cast<unsigned long long>(r.status.dds_lost), static_cast<unsigned long long>(kdrops), vanished,
       100.0 * cpu / span);
  CHECK(flooded >= 30000u);
  CHECK_EQ(vanished, 0u);
  CHECK_EQ(r.status.samples_in, r.status.samples_ok + r.status.samples_idle + drops);
  CHECK(r.status.samples_in <= flooded + 1000u);  // (the partner's few besides): nothing counted twice
  // what the kernel did not drop reached the server and was counted, but for what Fast DDS's
  // receive path loses without a note when the server is short of CPU: 2 % of a flood on an
  // idle machine, 10 % beside two busy loops on 2 cores (docs/benchmarks.md)
  CHECK_MSG(r.status.samples_in + kdrops >= flooded * 3 / 4, "%llu of %llu accounted for",
            static_cast<unsigned long long>(r.status.samples_in + kdrops), static_cast<unsigned long long>(flooded));
}

}  // namespace

TEST(secure) { itest::in_case(case_secure); }
TEST(secure_own_flood) { itest::in_case(case_secure_own_flood); }
TEST(secure_slots) { itest::in_case(case_secure_slots); }
TEST(secure_udp_disposal) { itest::in_case(case_secure_udp_disposal); }
TEST(secure_udp_replay) { itest::in_case(case_secure_udp_replay); }
TEST(discovery_flood) { itest::in_case(case_discovery_flood); }
TEST(load_secure) { itest::in_case(case_load_secure); }
