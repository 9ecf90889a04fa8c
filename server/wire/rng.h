// A small seeded generator with the same stream on every machine and
// standard library (std::normal_distribution is not specified bit for bit):
// splitmix64, uniform doubles from its top 53 bits, Gaussians by Box-Muller.
#pragma once

#include <cmath>
#include <cstdint>

namespace ballsrv {

// A phase in [0, 1) for item n, the fractional part of n / golden ratio:
// any run of items spreads evenly over the period (ball states over
// frames, a bot's samples over their period), none shares another's.
inline double golden_phase(uint64_t n) {
  return std::fmod(static_cast<double>(n % 1000003) * 0.6180339887498949, 1.0);
}

class Rng {
 public:
  explicit Rng(uint64_t seed = 1) : state_(seed) {}
  uint64_t next() {
    uint64_t z = (state_ += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
  }
  double uniform() { return static_cast<double>(next() >> 11) * (1.0 / 9007199254740992.0); }  // [0, 1)
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  bool chance(double p) { return uniform() < p; }
  double normal(double sigma) {
    if (sigma == 0.0) return 0.0;
    double u1 = uniform(), u2 = uniform();
    if (u1 < 1e-300) u1 = 1e-300;
    return sigma * std::sqrt(-2.0 * std::log(u1)) * std::cos(6.283185307179586 * u2);
  }

 private:
  uint64_t state_;
};

}  // namespace ballsrv
