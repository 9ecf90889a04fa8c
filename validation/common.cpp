// Shared pieces of the validation programs.
#include <cstdarg>
#include <cstdio>

#include "common.h"

namespace bv {

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
