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
    open_over(std::make_unique<Over>(*this, me), c, &client, &why);
  }
  ~FakeNet() { ball_net_free(client); }
  FakeNet(const FakeNet &) = delete;
  FakeNet &operator=(const FakeNet &) = delete;

  FakeClientPort port;
  double now = 0.0;  // the client's clock
  ball_net_client *client = nullptr;
  // a transport that may start anew (a TCP client's): each renewal a new
  // participant, its id's last byte the previous one's plus one
  bool renewable = false;
  int renewals = 0;

 private:
  struct Over : Transport {
    Over(FakeNet &net, const ParticipantId &m) : net_(net), me_(m) {}
    ClientPort &port() override { return net_.port; }
    ParticipantId id() const override { return me_; }
    bool close(double) override { return true; }
    bool renewable() const override { return net_.renewable; }
    bool renew(std::string *) override {
      net_.renewals++;
      me_[11]++;
      return true;
    }
    FakeNet &net_;
    ParticipantId me_;
  };
};

}  // namespace test
