// A program's DDS participant from the options every program has
// (common.h, DdsOptions): its domain, QoS profile file (as find_profile
// finds it), participant profile, Discovery Servers and DDS Security.
// Header only: the programs link ball_dds, the app library does not.
#pragma once

#include <memory>
#include <string>

#include "common.h"
#include "domain.h"

namespace ballsrv {
namespace app {

// nullptr with a sentence in err (dds::Domain::open)
inline std::unique_ptr<dds::Domain> open_domain(const DdsOptions &o, const std::string &name, std::string *err) {
  return dds::Domain::open(o.domain, find_profile(o.profile), o.participant,
                           dds::Reach{o.discovery_server, o.tcp_peers, o.tcp_listen, o.tcp_public}, name, err,
                           dds::Security{o.security, o.identity, o.tls});
}

}  // namespace app
}  // namespace ballsrv
