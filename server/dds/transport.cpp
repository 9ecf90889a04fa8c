// The TCP transport of a participant (docs/deploy.md): a TCP profile's
// peers, listening port and public address from Reach, and TLS with the
// identity's certificate. Kept apart from domain.cpp, which opens the
// participant with them.
#include "domain.h"

#include "domain_impl.h"

namespace ballsrv {
namespace dds {

namespace {

// The profile's TCPv4 transports, copied so that they may be changed (the
// profile's own are shared with every participant made from it).
std::vector<std::shared_ptr<eprosima::fastdds::rtps::TCPv4TransportDescriptor>> own_tcp_transports(
    fdds::DomainParticipantQos *qos) {
  using Tcp = eprosima::fastdds::rtps::TCPv4TransportDescriptor;
  std::vector<std::shared_ptr<Tcp>> tcp;
  for (auto &t : qos->transport().user_transports)
    if (auto *d = dynamic_cast<Tcp *>(t.get())) {
      auto copy = std::make_shared<Tcp>(*d);
      t = copy;
      tcp.push_back(copy);
    }
  return tcp;
}

bool ipv4_address(const std::string &text) {
  in_addr a;
  return inet_pton(AF_INET, text.c_str(), &a) == 1;
}

// "HOST:PORT[;HOST:PORT...]" as TCPv4 initial peers (a name is resolved
// now), or false with err.
bool tcp_peers(const std::string &list, eprosima::fastrtps::rtps::LocatorList_t *out, std::string *err) {
  namespace rtps = eprosima::fastrtps::rtps;
  std::stringstream in(list);
  std::string entry;
  while (std::getline(in, entry, ';')) {
    size_t colon = entry.rfind(':');
    char *end = nullptr;
    long port = colon == std::string::npos ? 0 : std::strtol(entry.c_str() + colon + 1, &end, 10);
    if (colon == std::string::npos || colon == 0 || !end || *end || port < 1 || port > 65535) {
      *err = "TCP peers \"" + list + "\": \"" + entry + "\" is not HOST:PORT with a port in [1, 65535]";
      return false;
    }
    std::string host = entry.substr(0, colon);
    if (!ipv4_address(host)) {
      auto found = rtps::IPLocator::resolveNameDNS(host).first;
      if (found.empty()) {
        *err = "TCP peers \"" + list + "\": " + host + " has no IPv4 address";
        return false;
      }
      host = *found.begin();
    }
    rtps::Locator_t peer;
    peer.kind = LOCATOR_KIND_TCPv4;
    rtps::IPLocator::setIPv4(peer, host);
    rtps::IPLocator::setPhysicalPort(peer, static_cast<uint16_t>(port));
    out->push_back(peer);
  }
  if (out->empty()) {
    *err = "TCP peers \"" + list + "\": no HOST:PORT in it";
    return false;
  }
  return true;
}

}  // namespace

// The TCP fields of `reach` over the profile's (docs/deploy.md), or false
// with err.
bool tcp_client_only(const fdds::DomainParticipantQos &qos) {
  using Tcp = eprosima::fastdds::rtps::TCPv4TransportDescriptor;
  bool tcp = false;
  for (const auto &t : qos.transport().user_transports) {
    const auto *d = dynamic_cast<const Tcp *>(t.get());
    if (!d || !d->listening_ports.empty()) return false;
    tcp = true;
  }
  return tcp && !qos.transport().use_builtin_transports;
}

bool use_tcp(const Reach &reach, fdds::DomainParticipantQos *qos, std::string *err) {
  if (reach.tcp_peers.empty() && reach.tcp_port == 0 && reach.tcp_public.empty()) return true;
  auto tcp = own_tcp_transports(qos);
  if (tcp.empty()) {
    *err = "TCP peers, a listening port or a public address given, but the profile has no TCP transport";
    return false;
  }
  if (!reach.tcp_peers.empty()) {
    eprosima::fastrtps::rtps::LocatorList_t peers;
    if (!tcp_peers(reach.tcp_peers, &peers, err)) return false;
    qos->wire_protocol().builtin.initialPeersList = peers;
  }
  if (reach.tcp_port != 0 && (reach.tcp_port < 1 || reach.tcp_port > 65535)) {
    *err = "TCP listening port " + std::to_string(reach.tcp_port) + " is outside [1, 65535]";
    return false;
  }
  if (!reach.tcp_public.empty() && !ipv4_address(reach.tcp_public)) {
    *err = "TCP public address \"" + reach.tcp_public + "\" is not an IPv4 address";
    return false;
  }
  for (auto &t : tcp) {
    if (reach.tcp_port != 0) t->listening_ports = {static_cast<uint16_t>(reach.tcp_port)};
    if (!reach.tcp_public.empty()) t->set_WAN_address(reach.tcp_public);
    if (t->listening_ports.empty() && (reach.tcp_port != 0 || !reach.tcp_public.empty())) {
      *err = "a public address given for a TCP profile that listens on no port";
      return false;
    }
  }
  return true;
}

// TLS on the profile's TCP transports with the identity's certificate: both
// ends show a certificate signed by ca.pem, or the connection is refused
// (docs/deploy.md). false with err.
bool use_tls(const Security &sec, fdds::DomainParticipantQos *qos, std::string *err) {
  using Tls = eprosima::fastdds::rtps::TCPTransportDescriptor::TLSConfig;
  if (sec.identity.empty()) {
    *err = "--tls " + sec.tls_dir + " needs --identity NAME (NAME.pem and NAME.key in that folder)";
    return false;
  }
  std::string d = absolute(sec.tls_dir);
  for (const auto &f : {std::string("ca.pem"), sec.identity + ".pem", sec.identity + ".key"})
    if (!readable(d + "/" + f)) {
      *err = "TLS: " + d + "/" + f + ": " + std::strerror(errno) + " (./run certs makes test certificates)";
      return false;
    }
  auto tcp = own_tcp_transports(qos);
  if (tcp.empty()) {
    *err = "TLS given, but the profile has no TCP transport (tcp_server or tcp_client: docs/deploy.md)";
    return false;
  }
  for (auto &t : tcp) {
    t->apply_security = true;
    Tls &tls = t->tls_config;
    tls.verify_file = d + "/ca.pem";
    tls.cert_chain_file = d + "/" + sec.identity + ".pem";
    tls.private_key_file = d + "/" + sec.identity + ".key";
    tls.verify_mode = Tls::TLSVerifyMode::VERIFY_PEER | Tls::TLSVerifyMode::VERIFY_FAIL_IF_NO_PEER_CERT;
    tls.options = Tls::TLSOptions::DEFAULT_WORKAROUNDS | Tls::TLSOptions::NO_COMPRESSION | Tls::TLSOptions::NO_SSLV2 |
                  Tls::TLSOptions::NO_SSLV3 | Tls::TLSOptions::NO_TLSV1 | Tls::TLSOptions::NO_TLSV1_1;
    tls.handshake_role = Tls::TLSHandShakeRole::DEFAULT;
  }
  return true;
}
}  // namespace dds
}  // namespace ballsrv
