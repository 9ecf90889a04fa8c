// A client of the client library (ball/net.h) without a network: the very
// calls a game makes, over a FakeClientPort the test feeds, on a clock the
// test sets (test_client's player groups).
#pragma once

#include <memory>
#include <string>

#include "fake_client_port.h"
#include "net_client.h"

namespace test {

using namespace ballsrv;

class FakeNet {
 public:
  // `more` sets config fields beyond the clock (servers, the simulated network)
  explicit FakeNet(const ParticipantId &me, void (*more)(ball_net_config *) = nullptr) {
    ball_net_config c;
    ball_net_config_default(&c);
    c.clock = [](void *user) { return *static_cast<double *>(user); };
    c.clock_user = &now;
    if (more) more(&c);
    std::string why;
    open_over(std::make_unique<Over>(port, me), c, &client, &why);
  }
  ~FakeNet() { ball_net_free(client); }
  FakeNet(const FakeNet &) = delete;
  FakeNet &operator=(const FakeNet &) = delete;

  FakeClientPort port;
  double now = 0.0;  // the client's clock
  ball_net_client *client = nullptr;

 private:
  struct Over : Transport {
    Over(FakeClientPort &p, const ParticipantId &m) : port_(p), me_(m) {}
    ClientPort &port() override { return port_; }
    ParticipantId id() const override { return me_; }
    bool close(double) override { return true; }
    FakeClientPort &port_;
    ParticipantId me_;
  };
};

}  // namespace test
