// A program's client of the client library (ball/net.h) from the options
// every program has (common.h, DdsOptions): its domain, QoS profile file
// (as find_profile finds it), participant profile, Discovery Servers and
// DDS Security. Header only: the programs that play link libball-net, the
// app library does not.
#pragma once

#include <functional>
#include <string>

#include "ball/net.h"
#include "common.h"

namespace ballsrv {
namespace app {

// `servers` as ball_net_config has them ("" any); `more` sets the
// config's other fields, if given. nullptr with a sentence in err.
inline ball_net_client *open_client(const DdsOptions &o, const std::string &name, const std::string &servers,
                                    const std::function<void(ball_net_config *)> &more, std::string *err) {
  ball_net_config c;
  ball_net_config_default(&c);
  const std::string profile = find_profile(o.profile);
  c.domain = o.domain;
  c.participant = o.participant.c_str();
  c.discovery_servers = o.discovery_server.empty() ? nullptr : o.discovery_server.c_str();
  c.qos_file = profile.empty() ? nullptr : profile.c_str();
  c.security_dir = o.security.empty() ? nullptr : o.security.c_str();
  c.identity = o.security.empty() && o.tls.empty() ? nullptr : o.identity.c_str();
  c.tcp_peers = o.tcp_peers.empty() ? nullptr : o.tcp_peers.c_str();
  c.tls_dir = o.tls.empty() ? nullptr : o.tls.c_str();
  c.servers = servers.empty() ? nullptr : servers.c_str();
  c.name = name.c_str();
  if (more) more(&c);
  ball_net_client *client = nullptr;
  char why[512];
  if (ball_net_open(&c, &client, why, sizeof why) != BALL_OK) {
    *err = why;
    return nullptr;
  }
  return client;
}

}  // namespace app
}  // namespace ballsrv
