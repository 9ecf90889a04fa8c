// Hosts of a networked case in network namespaces of their own
// (docs/server-tests.md, "Several hosts"): a switch namespace holding a
// bridge, and per host a namespace whose one link (eth0, 10.77.0.N/24, and
// the route for multicast) is a veth to that bridge. Every link is made in
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

#include <cerrno>
#include <filesystem>
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
    for (size_t i = 0; ok_ && i < names_.size(); ++i) {
      const std::string &h = names_[i];
      const std::string port = "p" + std::to_string(i);
      ok_ = ip({"netns", "add", ns(h)}) &&
            ip({"link", "add", "eth0", "netns", ns(h), "type", "veth", "peer", "name", port, "netns", ns("switch")}) &&
            ip({"-n", ns("switch"), "link", "set", port, "master", "br0"}) &&
            ip({"-n", ns("switch"), "link", "set", port, "up"}) && ip({"-n", ns(h), "link", "set", "lo", "up"}) &&
            ip({"-n", ns(h), "addr", "add", address(h) + "/24", "dev", "eth0"}) &&
            ip({"-n", ns(h), "link", "set", "eth0", "up"}) &&
            ip({"-n", ns(h), "route", "add", "224.0.0.0/4", "dev", "eth0"});
    }
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
  std::string address(const std::string &h) const { return "10.77.0." + std::to_string(index(h) + 1); }
  bool cut(const std::string &h) { return ip({"-n", ns("switch"), "link", "set", port(h), "down"}); }
  bool heal(const std::string &h) { return ip({"-n", ns("switch"), "link", "set", port(h), "up"}); }
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
  std::string port(const std::string &h) const { return "p" + std::to_string(index(h)); }
  bool isolate(const std::string &h, const char *on) {
    return ip({"-n", ns("switch"), "link", "set", port(h), "type", "bridge_slave", "isolated", on});
  }
  static std::string ip_path() {
    for (const char *p : {"/usr/sbin/ip", "/sbin/ip", "/usr/bin/ip", "/bin/ip"})
      if (access(p, X_OK) == 0) return p;
    return "/usr/sbin/ip";
  }
  bool ip(std::vector<std::string> args) {
    args.insert(args.begin(), ip_path());
    ballsrv::app::Process p = ballsrv::app::Process::start(args, "/dev/null", "/dev/null");
    int rc = p.pid() > 0 ? p.wait(10.0) : -1;
    if (rc != 0 && error_.empty()) {
      error_ = "ip";
      for (size_t i = 1; i < args.size(); ++i) error_ += " " + args[i];
      error_ += ": exit status " + std::to_string(rc) + " (root and iproute2 needed)";
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
  bool ok_ = false;
  std::string error_;
};

}  // namespace itest
