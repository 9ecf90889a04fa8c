// What a network does to a stream a client sends: every item is delayed by
// `delay` plus a uniform draw in [0, jitter] (so items can overtake each
// other), some are lost; the draws come from a seed. The client library
// puts a client's racket poses through one when its config asks for a
// simulated network (ball_net_config's link_*: ball-bot's --delay, --jitter,
// --loss); the offline tests put both players of a rally through one.
#pragma once

#include <algorithm>
#include <deque>

#include "rng.h"

namespace ballsrv {

struct LinkParams {
  double delay = 0.0;   // s added to every item's trip, [0, kMaxDelay]
  double jitter = 0.0;  // s: up to this much later again (uniform), [0, kMaxJitter]
  double loss = 0.0;    // probability an item is lost, [0, kMaxLoss]
  static constexpr double kMaxDelay = 10.0, kMaxJitter = 1.0, kMaxLoss = 0.9;
  bool active() const { return delay > 0.0 || jitter > 0.0 || loss > 0.0; }
  bool valid() const {
    return delay >= 0.0 && delay <= kMaxDelay && jitter >= 0.0 && jitter <= kMaxJitter && loss >= 0.0 && loss <= kMaxLoss;
  }
};

template <class T>
class Link {
 public:
  Link(LinkParams p, uint64_t seed) : p_(p), rng_(seed) {}

  // Sends an item at time now; false if the network loses it.
  bool send(const T &item, double now) {
    if (p_.loss > 0.0 && rng_.chance(p_.loss)) return false;
    double arrival = now + p_.delay + (p_.jitter > 0.0 ? rng_.uniform(0.0, p_.jitter) : 0.0);
    Item it{arrival, item};
    auto pos = std::upper_bound(queue_.begin(), queue_.end(), arrival,
                                [](double a, const Item &b) { return a < b.arrival; });
    queue_.insert(pos, it);
    return true;
  }

  // Hands every item that has arrived by `now` to f, in arrival order.
  template <class F>
  void deliver(double now, F &&f) {
    while (!queue_.empty() && queue_.front().arrival <= now) {
      Item it = queue_.front();
      queue_.pop_front();
      f(it.item);
    }
  }

  size_t pending() const { return queue_.size(); }
  // when the next item arrives (+inf: none)
  double next_arrival() const { return queue_.empty() ? 1e300 : queue_.front().arrival; }

 private:
  struct Item {
    double arrival;
    T item;
  };
  LinkParams p_;
  Rng rng_;
  std::deque<Item> queue_;
};

}  // namespace ballsrv
