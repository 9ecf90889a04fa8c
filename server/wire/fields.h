// A settings struct described field by field: the one place where a
// setting's JSON key, member, range, unit and meaning are stated. The check
// of a struct (check_fields), the JSON reader and the command-line options
// (server/apps/config.cpp) and the tables of docs/server-reference.md (doc_table,
// printed by `ball-server --keys` and held to the page by a test) are all
// made from these tables, so they cannot disagree.
#pragma once

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <variant>
#include <vector>

#include "ball/ball.h"

namespace ballsrv {

// A setting's range. Reals: lo to hi, either end open; the upper end may be
// another field of the same struct instead (state_rate <= frame_rate).
// Integers: [ilo, ihi]. Text: its length in bytes in [ilo, ihi].
struct Bounds {
  double lo = -HUGE_VAL, hi = HUGE_VAL;
  bool lo_open = false, hi_open = false;
  const char *hi_field = nullptr;
  long long ilo = 0, ihi = 0;
  bool has_range() const { return lo > -HUGE_VAL || hi < HUGE_VAL || hi_field || ilo != 0 || ihi != 0; }
};
inline Bounds closed(double lo, double hi) {
  Bounds b;
  b.lo = lo;
  b.hi = hi;
  return b;
}
inline Bounds open_closed(double lo, double hi) {  // (lo, hi]
  Bounds b = closed(lo, hi);
  b.lo_open = true;
  return b;
}
inline Bounds up_to_field(double lo, const char *field) {  // [lo, that field's value]
  Bounds b;
  b.lo = lo;
  b.hi_field = field;
  return b;
}
inline Bounds whole(long long lo, long long hi) {  // integers, or a text's length
  Bounds b;
  b.ilo = lo;
  b.ihi = hi;
  return b;
}

template <class S>
using Member = std::variant<std::monostate, double S::*, int S::*, uint32_t S::*, uint64_t S::*, bool S::*,
                            std::string S::*, ball_level S::*>;

template <class S>
struct Field {
  const char *key;                     // the JSON key, and the setting's name in messages
  Member<S> member;                    // monostate: a key the reader handles itself (objects, lists, files)
  Bounds bounds;
  const char *unit;                    // "Hz", "s", "m/s", "m", or "" (a count, a ratio, a name)
  const char *doc;                     // what it means (docs/server-reference.md, --help)
  const char *option = nullptr;        // its command-line option(s), CLI11 style; nullptr: none
  const char *default_text = nullptr;  // the default in words; nullptr: the struct's value
  bool in_file = true;                 // false: set by the program, not a key; only checked
};

// "1000", "0.05", "1e9": a bound or a default as the docs write it.
inline std::string number_text(double v) {
  char buf[32];
  if (v == std::floor(v) && std::fabs(v) < 1e6) std::snprintf(buf, sizeof buf, "%.0f", v);
  else std::snprintf(buf, sizeof buf, "%g", v);
  std::string s = buf;
  size_t e = s.find("e+");
  if (e != std::string::npos) s.erase(e + 1, 1);  // 1e+09 -> 1e09
  e = s.find("e0");
  if (e != std::string::npos) s.erase(e + 1, 1);  // 1e09 -> 1e9
  e = s.find("e-0");
  if (e != std::string::npos) s.erase(e + 2, 1);  // 1e-06 -> 1e-6
  return s;
}

// "[1, 4]", "(0, 1000] Hz", "[0, frame_rate] Hz", "1 to 31 bytes"; "" for no range.
template <class S>
std::string range_text(const Field<S> &f) {
  const Bounds &b = f.bounds;
  std::string unit = *f.unit ? std::string(" ") + f.unit : "";
  if (std::holds_alternative<std::string S::*>(f.member) && b.ihi > 0)
    return std::to_string(b.ilo) + " to " + std::to_string(b.ihi) + " bytes";
  if (b.ilo != 0 || b.ihi != 0) return "[" + std::to_string(b.ilo) + ", " + std::to_string(b.ihi) + "]";
  if (!b.has_range()) return "";
  std::string hi = b.hi_field ? b.hi_field : number_text(b.hi);
  return std::string(b.lo_open ? "(" : "[") + number_text(b.lo) + ", " + hi + (b.hi_open ? ")" : "]") + unit;
}

// Whether a real is inside a field's bounds (NaN never is); `field_hi` is
// the other field's value when the upper end is one.
inline bool in_bounds(const Bounds &b, double v, double field_hi = HUGE_VAL) {
  double hi = b.hi_field ? field_hi : b.hi;
  bool lo_ok = b.lo_open ? v > b.lo : v >= b.lo;
  bool hi_ok = b.hi_open ? v < hi : v <= hi;
  return lo_ok && hi_ok;
}

template <class S>
const Field<S> *find_field(const std::vector<Field<S>> &table, const std::string &key) {
  for (const auto &f : table)
    if (key == f.key) return &f;
  return nullptr;
}

// The value of a field of s as a real (numbers only).
template <class S>
bool real_value(const Field<S> &f, const S &s, double *out) {
  return std::visit(
      [&](auto m) {
        using M = decltype(m);
        if constexpr (std::is_same_v<M, double S::*> || std::is_same_v<M, int S::*> ||
                      std::is_same_v<M, uint32_t S::*> || std::is_same_v<M, uint64_t S::*>) {
          *out = static_cast<double>(s.*m);
          return true;
        } else {
          return false;
        }
      },
      f.member);
}

// Checks every field of s against its bounds; false with
// "key: must be in RANGE" in err for the first that is outside.
template <class S>
bool check_fields(const std::vector<Field<S>> &table, const S &s, std::string *err) {
  for (const auto &f : table) {
    bool ok = std::visit(
        [&](auto m) {
          using M = decltype(m);
          const Bounds &b = f.bounds;
          if constexpr (std::is_same_v<M, double S::*>) {
            double hi = HUGE_VAL;
            if (b.hi_field) {
              const Field<S> *other = find_field(table, b.hi_field);
              if (other) real_value(*other, s, &hi);
            }
            return in_bounds(b, s.*m, hi);
          } else if constexpr (std::is_same_v<M, int S::*> || std::is_same_v<M, uint32_t S::*> ||
                               std::is_same_v<M, uint64_t S::*>) {
            long double v = static_cast<long double>(s.*m);
            return (b.ilo == 0 && b.ihi == 0) || (v >= b.ilo && v <= b.ihi);
          } else if constexpr (std::is_same_v<M, std::string S::*>) {
            long long n = static_cast<long long>((s.*m).size());
            return b.ihi == 0 || (n >= b.ilo && n <= b.ihi);
          } else {
            return true;
          }
        },
        f.member);
    if (!ok) {
      *err = std::string(f.key) + ": must be " + (std::holds_alternative<std::string S::*>(f.member) ? "" : "in ") +
             range_text(f);
      return false;
    }
  }
  return true;
}

// The value of a field of s in words: "60 Hz", "easy", "true".
template <class S>
std::string value_text(const Field<S> &f, const S &s) {
  return std::visit(
      [&](auto m) -> std::string {
        using M = decltype(m);
        std::string unit = *f.unit ? std::string(" ") + f.unit : "";
        if constexpr (std::is_same_v<M, std::monostate>) {
          return "";
        } else if constexpr (std::is_same_v<M, double S::*>) {
          return number_text(s.*m) + unit;
        } else if constexpr (std::is_same_v<M, bool S::*>) {
          return s.*m ? "true" : "false";
        } else if constexpr (std::is_same_v<M, std::string S::*>) {
          return "`" + s.*m + "`";
        } else if constexpr (std::is_same_v<M, ball_level S::*>) {
          return std::string("`") + ball_level_name(s.*m) + "`";
        } else {
          return std::to_string(s.*m) + unit;
        }
      },
      f.member);
}

// The markdown table of docs/server-reference.md for the keys of a table, with the
// defaults of `defaults`: | key | default | range | meaning |.
template <class S>
std::string doc_table(const std::vector<Field<S>> &table, const S &defaults) {
  std::string out = "| key | default | range | meaning |\n|---|---|---|---|\n";
  for (const auto &f : table) {
    if (!f.in_file) continue;
    std::string def = f.default_text ? f.default_text : value_text(f, defaults);
    out += std::string("| `") + f.key + "` | " + def + " | " + range_text(f) + " | " + f.doc + " |\n";
  }
  return out;
}

}  // namespace ballsrv
