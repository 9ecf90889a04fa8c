// Inside the client library: ball/net.h's client over a transport. The C
// API (api.cpp) is free of DDS; ball_net_open (net_dds.cpp) gives it a DDS
// participant, and the offline tests give it a port they feed from a Match
// (open_over), so that our bots play through the very calls a game makes.
#pragma once

#include <memory>
#include <string>

#include "ball/net.h"
#include "client_core.h"
#include "port.h"

namespace ballsrv {

// Where a client's samples come from and go to.
class Transport {
 public:
  virtual ~Transport() = default;
  virtual ClientPort &port() = 0;
  virtual ParticipantId id() const = 0;  // this client's participant
  // what the newest refused write said ("" nothing)
  virtual std::string error() const { return {}; }
  // Deletes what it made; false when that took longer than `limit` s (left to it).
  virtual bool close(double limit) = 0;
  // Whether starting anew may help a client that hears no server
  // (ClientCore::wants_renewal): a TCP client's connections are its own.
  virtual bool renewable() const { return false; }
  // Makes its participant and endpoints anew (the matches followed read
  // again), then deletes the old ones; port() and id() are the new ones'.
  // false with a sentence: the old ones are kept.
  virtual bool renew(std::string *why) {
    *why = "this transport cannot start anew";
    return false;
  }
};

// The settings a config asks for; BALL_OK, or a refusal with its sentence
// in *why. Checks every field but the transport's own (domain, profiles,
// certificates).
ball_status core_settings_of(const ball_net_config &config, CoreSettings *out, std::string *why);

// A client over `transport`, the config checked as ball_net_open checks it
// (the transport's own fields aside); *client NULL and *why said on refusal.
ball_status open_over(std::unique_ptr<Transport> transport, const ball_net_config &config, ball_net_client **client,
                      std::string *why);

}  // namespace ballsrv
