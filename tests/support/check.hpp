// A small test harness for the server's C++ tests: TEST(name) { ... }
// registers a case, CHECK(cond) / CHECK_NEAR(a, b, tol) / CHECK_EQ(a, b)
// report the file, line and values and mark the case failed; main() runs
// every case (or those named on the command line) and returns 1 on failure.
#pragma once

#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

namespace check {

struct Case {
  const char *name;
  std::function<void()> fn;
};

inline std::vector<Case> &cases() {
  static std::vector<Case> all;
  return all;
}
inline int &failures() {
  static int n = 0;
  return n;
}

struct Register {
  Register(const char *name, std::function<void()> fn) { cases().push_back(Case{name, std::move(fn)}); }
};

inline void fail(const char *file, int line, const std::string &what) {
  std::fprintf(stderr, "%s:%d: FAILED %s\n", file, line, what.c_str());
  failures()++;
}

// enums print as their number
template <class T>
auto printable(const T &v) {
  if constexpr (std::is_enum<T>::value) return static_cast<long long>(v);
  else return v;
}

template <class A, class B>
std::string pair_text(const char *ea, const char *eb, const A &a, const B &b) {
  std::ostringstream o;
  o.precision(17);
  o << ea << " == " << eb << " (" << printable(a) << " vs " << printable(b) << ")";
  return o.str();
}

inline int run(int argc, char **argv) {
  int ran = 0;
  for (const Case &c : cases()) {
    bool wanted = argc <= 1;
    for (int i = 1; i < argc; ++i) wanted = wanted || std::strcmp(argv[i], c.name) == 0;
    if (!wanted) continue;
    int before = failures();
    c.fn();
    std::printf("%s %s\n", failures() == before ? "ok  " : "FAIL", c.name);
    ran++;
  }
  std::printf("%d cases, %d failed checks\n", ran, failures());
  return failures() == 0 && ran > 0 ? 0 : 1;
}

}  // namespace check

#define TEST(name)                                                  \
  static void test_##name();                                        \
  static check::Register register_##name(#name, test_##name);       \
  static void test_##name()

#define CHECK(cond) \
  do { if (!(cond)) check::fail(__FILE__, __LINE__, #cond); } while (0)

#define CHECK_EQ(a, b)                                                              \
  do {                                                                              \
    auto check_a_ = (a);                                                            \
    auto check_b_ = (b);                                                            \
    if (!(check_a_ == check_b_)) check::fail(__FILE__, __LINE__, check::pair_text(#a, #b, check_a_, check_b_)); \
  } while (0)

#define CHECK_NEAR(a, b, tol)                                                       \
  do {                                                                              \
    double check_a_ = (a), check_b_ = (b);                                          \
    if (!(std::fabs(check_a_ - check_b_) <= (tol)))                                 \
      check::fail(__FILE__, __LINE__, check::pair_text(#a, #b, check_a_, check_b_) + " tol " #tol); \
  } while (0)

#define CHECK_MAIN \
  int main(int argc, char **argv) { return check::run(argc, argv); }
