// Shared pieces of the validation programs.
#include <algorithm>
#include <cstdarg>
#include <cstdio>

#include "common.h"

namespace bv {

Stat stat_of(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  size_t n = v.size();
  if (n == 0) return Stat{};
  return Stat{v[0], n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2])};
}

std::string fmt(const char *format, ...) {
  va_list ap, ap2;
  va_start(ap, format);
  va_copy(ap2, ap);
  int n = std::vsnprintf(nullptr, 0, format, ap);
  va_end(ap);
  std::string s(n > 0 ? static_cast<size_t>(n) : 0, '\0');
  std::vsnprintf(&s[0], s.size() + 1, format, ap2);
  va_end(ap2);
  return s;
}

}  // namespace bv
