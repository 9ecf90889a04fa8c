// What the WebAssembly module (cmake/BallWasm.cmake, server/web/page/ballwasm.js)
// holds besides libball's core, until the client core takes its place: C++17
// with libc++'s containers over libball's C API, so that the toolchain is
// shown to link and run them (tests/web/wasm_check.py).
//
//   wasm_probe_history(n)  n segments keyed by sequence number in a std::map,
//       inserted in a scrambled order, read back in key order into a
//       std::vector, the newest 64 kept in a std::deque, each evaluated with
//       ball_segment_eval at t0 + seq without drag (so its x is seq, exactly):
//       the sum of their x, 64 n - 2080; -1 when an order or a size is wrong.
//   wasm_probe_layout(i)   sizeof and offsetof on this target of what
//       ballwasm.js writes and reads in the module's memory (kLayout below;
//       -1 past the end): the test holds the glue's numbers to these.
#include <cstddef>
#include <cstdint>
#include <deque>
#include <map>
#include <vector>

#include "ball/ball.h"

namespace {

const long kLayout[] = {
    sizeof(ball_model),
    sizeof(ball_segment),
    offsetof(ball_segment, t0),
    offsetof(ball_segment, p0),
    offsetof(ball_segment, v0),
    offsetof(ball_segment, s0),
    offsetof(ball_segment, grounded),
    sizeof(ball_state),
    offsetof(ball_state, position),
    offsetof(ball_state, velocity),
    offsetof(ball_state, spin),
    sizeof(ball_field),
    offsetof(ball_field, name),
    offsetof(ball_field, type),
    offsetof(ball_field, offset),
    sizeof(ball_vec3),
};

}  // namespace

extern "C" {

__attribute__((visibility("default"))) long wasm_probe_layout(int i) {
  return i >= 0 && i < static_cast<int>(sizeof kLayout / sizeof kLayout[0]) ? kLayout[i] : -1;
}

__attribute__((visibility("default"))) double wasm_probe_history(int n) {
  const int keep = 64, stride = 7919;  // a prime: i * stride mod n visits every key once
  if (n < keep || n % stride == 0) return -1.0;
  ball_model model;
  ball_model_default(&model);
  model.effects &= ~static_cast<unsigned>(BALL_EFFECT_DRAG);
  std::map<std::uint32_t, ball_segment> by_seq;
  for (int i = 0; i < n; ++i) {
    std::uint32_t seq = static_cast<std::uint32_t>((static_cast<long long>(i) * stride) % n);
    ball_segment s = {};
    s.t0 = 0.5 * seq;
    s.v0.x = 1.0;
    by_seq[seq] = s;
  }
  std::vector<std::uint32_t> order;
  std::deque<const ball_segment *> newest;
  for (const auto &kv : by_seq) {
    order.push_back(kv.first);
    newest.push_back(&kv.second);
    if (static_cast<int>(newest.size()) > keep) newest.pop_front();
  }
  if (static_cast<int>(by_seq.size()) != n || static_cast<int>(order.size()) != n) return -1.0;
  for (int i = 0; i < n; ++i)
    if (order[i] != static_cast<std::uint32_t>(i)) return -1.0;
  double sum = 0.0;
  for (const ball_segment *s : newest) {
    ball_state out;
    // seq = 2 t0: at t0 + seq the ball has flown seq metres at 1 m/s
    if (ball_segment_eval(&model, s, s->t0 + 2.0 * s->t0, &out) != BALL_OK) return -1.0;
    sum += out.position.x;
  }
  return sum;
}

}  // extern "C"
