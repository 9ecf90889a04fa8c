#include "types.h"

#include <iterator>

namespace ballsrv {

namespace {

#define BALL_NAME(e, name, idl) name,
constexpr const char *kStates[] = {BALL_MATCH_STATES(BALL_NAME)};
constexpr const char *kCauses[] = {BALL_CAUSES(BALL_NAME)};
constexpr const char *kEventKinds[] = {BALL_EVENT_KINDS(BALL_NAME)};
constexpr const char *kReasons[] = {BALL_REASONS(BALL_NAME)};
constexpr const char *kControlKinds[] = {BALL_CONTROL_KINDS(BALL_NAME)};
constexpr const char *kDrops[] = {BALL_DROP_REASONS(BALL_NAME)};
#undef BALL_NAME

template <size_t N>
const char *lookup(const char *const (&names)[N], int i) {
  return i >= 0 && i < static_cast<int>(N) ? names[i] : "unknown";
}

template <class E, size_t N>
bool find(const char *const (&names)[N], const std::string &name, E *out) {
  for (size_t i = 0; i < N; ++i)
    if (name == names[i]) {
      *out = static_cast<E>(i);
      return true;
    }
  return false;
}

// a drop reason's third column is its index in ServerStatus.drops
#define BALL_CHECK_INDEX(e, name, index) \
  static_assert(static_cast<int>(SampleResult::e) == index, "drop reason " #e " is index " #index);
BALL_DROP_REASONS(BALL_CHECK_INDEX)
#undef BALL_CHECK_INDEX

}  // namespace

std::string hex(const ParticipantId &id) {
  static const char *digits = "0123456789abcdef";
  std::string s;
  for (uint8_t b : id) {
    s += digits[b >> 4];
    s += digits[b & 15];
  }
  return s;
}

bool parse_hex(const std::string &text, ParticipantId *id) {
  if (text.size() != 2 * id->size() || text.find_first_not_of("0123456789abcdef") != std::string::npos) return false;
  // (digit by digit: std::stoul would bring the C library's printf into the page's WebAssembly module)
  auto digit = [](char c) { return static_cast<uint8_t>(c <= '9' ? c - '0' : c - 'a' + 10); };
  for (size_t i = 0; i < id->size(); ++i) (*id)[i] = static_cast<uint8_t>(digit(text[2 * i]) << 4 | digit(text[2 * i + 1]));
  return true;
}

std::string drops_text(const std::array<uint64_t, kDropSlots> &drops) {
  uint64_t total = 0;
  std::string reasons;
  for (int i = 0; i < kDropReasons; ++i) {
    total += drops[i];
    if (drops[i])
      reasons += std::string(reasons.empty() ? "" : ", ") + name_of(static_cast<SampleResult>(i)) + " " +
                 std::to_string(drops[i]);
  }
  return std::to_string(total) + (reasons.empty() ? "" : " (" + reasons + ")");
}

const char *name_of(MatchState v) { return lookup(kStates, static_cast<int>(v)); }
const char *name_of(Cause v) { return lookup(kCauses, static_cast<int>(v)); }
const char *name_of(EventKind v) { return lookup(kEventKinds, static_cast<int>(v)); }
const char *name_of(Reason v) { return lookup(kReasons, static_cast<int>(v)); }
const char *name_of(ControlKind v) { return lookup(kControlKinds, static_cast<int>(v)); }
const char *name_of(SampleResult v) {
  if (v == SampleResult::accepted) return "accepted";
  if (v == SampleResult::idle) return "idle";
  return lookup(kDrops, static_cast<int>(v));
}

template <>
bool parse_name(const std::string &n, MatchState *out) { return find(kStates, n, out); }
template <>
bool parse_name(const std::string &n, Cause *out) { return find(kCauses, n, out); }
template <>
bool parse_name(const std::string &n, EventKind *out) { return find(kEventKinds, n, out); }
template <>
bool parse_name(const std::string &n, Reason *out) { return find(kReasons, n, out); }
template <>
bool parse_name(const std::string &n, ControlKind *out) { return find(kControlKinds, n, out); }
template <>
bool parse_name(const std::string &n, SampleResult *out) {
  if (n == "accepted") *out = SampleResult::accepted;
  else if (n == "idle") *out = SampleResult::idle;
  else return find(kDrops, n, out);
  return true;
}

bool plain_scene_name(const std::string &name) {
  return !name.empty() && name.size() < static_cast<size_t>(kNameLen) &&
         name.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-") == std::string::npos;
}

}  // namespace ballsrv
