// The one check harness of the C++ tests (the server's offline tests and the
// networked integration tests): TEST(name) { ... } registers a case;
// CHECK(cond), CHECK_EQ(a, b), CHECK_NEAR(a, b, tol) and
// CHECK_MSG(cond, printf-format, ...) report the file, the line, the values
// or the message and mark the case failed. check::run runs every case (or
// those named) and returns 1 if a check failed or no case ran: a run that
// checks nothing is not a pass.
#pragma once

#include <cmath>
#include <cstdarg>
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
  std::fflush(stderr);
  failures()++;
}

inline std::string format(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
inline std::string format(const char *fmt, ...) {
  char buf[2048];
  va_list ap;
  va_start(ap, fmt);
  std::vsnprintf(buf, sizeof buf, fmt, ap);
  va_end(ap);
  return buf;
}

// A line of what a case measured, indented under its name (not a check).
inline void note(const char *fmt, ...) __attribute__((format(printf, 1, 2)));
inline void note(const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  std::printf("  ");
  std::vprintf(fmt, ap);
  std::printf("\n");
  va_end(ap);
  std::fflush(stdout);
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

// Runs the cases named (every case when names is empty); 0 when at least
// one ran and every check held.
inline int run(const std::vector<std::string> &names) {
  int ran = 0;
  for (const Case &c : cases()) {
    bool wanted = names.empty();
    for (const auto &n : names) wanted = wanted || n == c.name;
    if (!wanted) continue;
    int before = failures();
    c.fn();
    std::printf("%s %s\n", failures() == before ? "ok  " : "FAIL", c.name);
    std::fflush(stdout);
    ran++;
  }
  std::printf("%d cases, %d failed checks\n", ran, failures());
  if (ran == 0) std::printf("FAILED: no case ran\n");
  return failures() == 0 && ran > 0 ? 0 : 1;
}

inline int run(int argc, char **argv) { return run(std::vector<std::string>(argv + 1, argv + argc)); }

}  // namespace check

#define TEST(name)                                                  \
  static void test_##name();                                        \
  static check::Register register_##name(#name, test_##name);       \
  static void test_##name()

#define CHECK(cond) \
  do { if (!(cond)) check::fail(__FILE__, __LINE__, #cond); } while (0)

#define CHECK_MSG(cond, ...)                                                               \
  do {                                                                                     \
    if (!(cond)) check::fail(__FILE__, __LINE__, std::string(#cond) + ": " + check::format(__VA_ARGS__)); \
  } while (0)

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
