// Hosts of a networked case in network namespaces of their own
// (docs/server-tests.md, "Several hosts"): a switch namespace holding a
// bridge, and per host a namespace whose one link (eth0, 10.77.0.N/24, and
// the route for multicast) is a veth to that bridge; and, with add_home, a
// home router doing NAT with hosts behind it. Every link is made in
// its namespace: nothing outside them is touched or addressed. A host is cut
// off by setting its port on the bridge down, and healed by setting it up;
// two hosts are cut from each other only (each still reaching the others)
// by isolating both their ports (a bridge forwards nothing between two
// isolated ports), and joined again by ending that.
// The destructor removes every namespace (the veths go with them); a rig
// also removes those a killed earlier run left, named after its dead pid.
// Needs root (CAP_NET_ADMIN) and iproute2's ip (./run setup).
#pragma once

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "process.h"

namespace itest {

class Hosts {
 public:
  explicit Hosts(std::vector<std::string> names) : names_(std::move(names)) {
    remove_left_over();
    ok_ = ip({"netns", "add", ns("switch")}) && ip({"-n", ns("switch"), "link", "set", "lo", "up"}) &&
          ip({"-n", ns("switch"), "link", "add", "br0", "type", "bridge"}) &&
          ip({"-n", ns("switch"), "link", "set", "br0", "up"});
    for (size_t i = 0; ok_ && i < names_.size(); ++i)
      ok_ = attach(names_[i], "switch", "br0", "p" + std::to_string(i), address(names_[i])) &&
            ip({"-n", ns(names_[i]), "route", "add", "224.0.0.0/4", "dev", "eth0"});
  }
  // A home router on the switch (a host like the others, named `router`)
  // and hosts behind it on its own LAN, 192.168.N.0/24 (N = 7 for the first
  // router, 8 for the next...; a bridge in the router, its address .1),
  // whose only way out is the router's NAT (nftables masquerade on its
  // eth0); from outside it forwards nothing into the LAN but the replies of
  // connections made from inside, as home routers do, and, with `forward`
  // (a TCP port and a host of its LAN), the connections to that port, to
  // that host (dnat), as a data centre's router does. Needs nftables' nft
  // (./run setup).
  bool add_home(const std::string &router, const std::vector<std::string> &home, int forward = 0,
                const std::string &to = "") {
    names_.push_back(router);
    routers_.push_back(router);
    const std::string r = ns(router);
    const std::string lan = "192.168." + std::to_string(6 + routers_.size()) + ".";
    std::string rules =
        "add table ip home; "
        "add chain ip home nat { type nat hook postrouting priority srcnat; }; "
        "add rule ip home nat oifname eth0 masquerade; "
        "add chain ip home in { type filter hook forward priority filter; policy drop; }; "
        "add rule ip home in ct state established,related accept; "
        "add rule ip home in iifname br1 accept";
    for (size_t i = 0; i < home.size(); ++i) lans_[home[i]] = {routers_.size() - 1, i};
    if (forward)
      rules += "; add chain ip home pre { type nat hook prerouting priority dstnat; }; "
               "add rule ip home pre iifname eth0 tcp dport " + std::to_string(forward) + " dnat to " +
               address(to) + "; add rule ip home in iifname eth0 ct status dnat accept";
    ok_ = ok_ && attach(router, "switch", "br0", "p" + std::to_string(names_.size() - 1), address(router)) &&
          ip({"-n", r, "link", "add", "br1", "type", "bridge"}) && ip({"-n", r, "link", "set", "br1", "up"}) &&
          ip({"-n", r, "addr", "add", lan + "1/24", "dev", "br1"}) &&
          run(on(router, {"sysctl", "-q", "-w", "net.ipv4.ip_forward=1"})) && run(on(router, {nft_path(), rules}));
    for (const std::string &h : home) {
      names_.push_back(h);
      ok_ = ok_ && attach(h, router, "br1", port(h), address(h)) &&
            ip({"-n", ns(h), "route", "add", "default", "via", lan + "1"});
    }
    return ok_;
  }
  ~Hosts() {
    for (const std::string &h : names_) ip({"netns", "del", ns(h)});
    ip({"netns", "del", ns("switch")});
  }
  Hosts(const Hosts &) = delete;
  Hosts &operator=(const Hosts &) = delete;

  bool ok() const { return ok_; }
  const std::string &error() const { return error_; }
  // argv run on host h
  std::vector<std::string> on(const std::string &h, std::vector<std::string> argv) const {
    argv.insert(argv.begin(), {ip_path(), "netns", "exec", ns(h)});
    return argv;
  }
  // a host's address: 10.77.0.N on the switch, 192.168.7.N behind the first home router
  std::string address(const std::string &h) const {
    auto it = lans_.find(h);
    if (it != lans_.end())
      return "192.168." + std::to_string(7 + it->second.first) + "." + std::to_string(it->second.second + 2);
    return "10.77.0." + std::to_string(index(h) + 1);
  }
  // host h's link to its switch or home router down (cut) or up again (heal)
  bool cut(const std::string &h) { return ip({"-n", port_ns(h), "link", "set", port(h), "down"}); }
  bool heal(const std::string &h) { return ip({"-n", port_ns(h), "link", "set", port(h), "up"}); }
  bool split(const std::string &a, const std::string &b) { return isolate(a, "on") && isolate(b, "on"); }
  bool join(const std::string &a, const std::string &b) { return isolate(a, "off") && isolate(b, "off"); }

 private:
  static std::string prefix() { return "libball-itest-"; }
  std::string ns(const std::string &h) const { return prefix() + std::to_string(getpid()) + "-" + h; }
  size_t index(const std::string &h) const {
    size_t i = 0;
    while (i < names_.size() && names_[i] != h) ++i;
    return i;
  }
  std::string port(const std::string &h) const {
    auto it = lans_.find(h);
    return it == lans_.end() ? "p" + std::to_string(index(h)) : "h" + std::to_string(it->second.second + 1);
  }
  std::string port_ns(const std::string &h) const {
    auto it = lans_.find(h);
    return ns(it == lans_.end() ? "switch" : routers_[it->second.first]);
  }
  bool isolate(const std::string &h, const char *on) {
    return ip({"-n", ns("switch"), "link", "set", port(h), "type", "bridge_slave", "isolated", on});
  }
  // host h's link eth0, a veth whose other end `port` is on `bridge` in namespace `at`
  bool attach(const std::string &h, const std::string &at, const std::string &bridge, const std::string &port,
              const std::string &addr) {
    return ip({"netns", "add", ns(h)}) &&
           ip({"link", "add", "eth0", "netns", ns(h), "type", "veth", "peer", "name", port, "netns", ns(at)}) &&
           ip({"-n", ns(at), "link", "set", port, "master", bridge}) && ip({"-n", ns(at), "link", "set", port, "up"}) &&
           ip({"-n", ns(h), "link", "set", "lo", "up"}) && ip({"-n", ns(h), "addr", "add", addr + "/24", "dev", "eth0"}) &&
           ip({"-n", ns(h), "link", "set", "eth0", "up"});
  }
  static std::string nft_path() {
    for (const char *p : {"/usr/sbin/nft", "/sbin/nft"})
      if (access(p, X_OK) == 0) return p;
    return "/usr/sbin/nft";
  }
  static std::string ip_path() {
    for (const char *p : {"/usr/sbin/ip", "/sbin/ip", "/usr/bin/ip", "/bin/ip"})
      if (access(p, X_OK) == 0) return p;
    return "/usr/sbin/ip";
  }
  bool ip(std::vector<std::string> args) {
    args.insert(args.begin(), ip_path());
    return run(args);
  }
  bool run(const std::vector<std::string> &args) {
    ballsrv::app::Process p = ballsrv::app::Process::start(args, "/dev/null", "/dev/null");
    int rc = p.pid() > 0 ? p.wait(10.0) : -1;
    if (rc != 0 && error_.empty()) {
      for (const std::string &a : args) error_ += (error_.empty() ? "" : " ") + a;
      error_ += ": exit status " + std::to_string(rc) + " (root, iproute2 and nftables needed)";
    }
    return rc == 0;
  }
  // namespaces of this rig's kind whose run (the pid in the name) is dead
  void remove_left_over() {
    std::error_code ec;
    for (const auto &e : std::filesystem::directory_iterator("/var/run/netns", ec)) {
      std::string name = e.path().filename().string();
      if (name.rfind(prefix(), 0) != 0) continue;
      long pid = std::strtol(name.c_str() + prefix().size(), nullptr, 10);
      if (pid > 0 && kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH) ip({"netns", "del", name});
    }
    error_.clear();
  }

  std::vector<std::string> names_;
  std::vector<std::string> routers_;                            // the home routers, in order
  std::map<std::string, std::pair<size_t, size_t>> lans_;  // a LAN host: (its router, its place there)
  bool ok_ = false;
  std::string error_;
};

}  // namespace itest
